//! No NaN, infinity or negative value in any pixel: every method on every built-in scene at
//! a small size either renders a finite image or refuses with an error naming the feature it
//! does not support (never a silent fallback, never a panic).

use integration_tests::{assert_finite, builtin};
use mblur::{Effects, Method, NoProgress, RenderOptions};

#[test]
fn every_method_on_every_builtin_scene_is_finite_or_a_clear_error() {
    for (name, _, _) in mblur_scene::builtin::SCENES {
        let p = builtin(name, 32, 18);
        let e = Effects::analyse(&p);
        let splats = e.splat_objects() > 0;
        let transparent = e.transparent() > 0;
        for method in Method::ALL {
            if splats && method == Method::Auto {
                // `auto` is `ewa` for a scene with (opaque) splats, with or without
                // triangles (the render's note says so); the explicit `ewa` run below
                // covers it at half the cost.
                continue;
            }
            let opts = RenderOptions {
                method,
                times: Some(32),
                spp: Some(1),
                ..Default::default()
            };
            let applies = match method {
                Method::Auto | Method::Accum => true,
                Method::Analytic | Method::Prism => !splats,
                Method::Stochastic => !transparent,
                Method::Ewa => splats,
            };
            let start = std::time::Instant::now();
            let result = mblur::render(&p, &opts, &NoProgress);
            eprintln!("{name} {method}: {:.3} s", start.elapsed().as_secs_f64());
            match result {
                Ok(out) => {
                    assert!(applies, "{name}: {method} should refuse");
                    assert_finite(&out.image, &format!("{name} {method}"));
                    assert_eq!(out.image.pixels.len(), 32 * 18);
                }
                Err(err) => {
                    assert!(!applies, "{name}: {method} failed: {err}");
                    let msg = err.to_string();
                    assert!(
                        ["splat", "transparen", "triangle"]
                            .iter()
                            .any(|f| msg.contains(f)),
                        "{name}: {method} error does not name the feature: {msg}"
                    );
                }
            }
        }
    }
}
