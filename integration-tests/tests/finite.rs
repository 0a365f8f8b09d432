//! No NaN, infinity or negative value in any pixel: every method on every built-in scene at
//! a small size either renders a finite image that shows the scene, or refuses with an error
//! naming the feature it does not support (never a silent fallback, never a panic).

use integration_tests::{assert_finite, builtin};
use mblur::{AccumOptions, Effects, Method, MethodOptions, NoProgress, StochasticOptions};

/// Every method on every built-in scene at 32x18 (accum 32 sub-frames, stochastic at 1 and
/// at 16 samples per pixel): a finite, non-negative image of the right size in which some
/// pixel differs from the background, or exactly where the method does not apply an error
/// naming the feature: "splats" for analytic and prism on the splat scenes, "transparency"
/// for stochastic (one surface per sample) on the transparent ones, "no splats" for ewa on
/// the triangle-only ones.
#[test]
fn every_method_on_every_builtin_scene_is_finite_or_a_clear_error() {
    let (w, h) = (32, 18);
    for (name, _, _) in mblur_scene::builtin::SCENES {
        let p = builtin(name, w, h);
        let bg = p.background.map(|c| c as f32);
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
            // What the method refuses, if it does: the feature its error must name.
            let refusal = match method {
                Method::Auto | Method::Accum => None,
                Method::Analytic | Method::Prism => splats.then_some("splats"),
                Method::Stochastic => transparent.then_some("transparency"),
                Method::Ewa => (!splats).then_some("no splats"),
            };
            let spps: &[u32] = if method == Method::Stochastic {
                &[1, 16]
            } else {
                &[1]
            };
            for &spp in spps {
                let opts = match MethodOptions::defaults(method) {
                    MethodOptions::Accum(o) => MethodOptions::Accum(AccumOptions {
                        times: Some(32),
                        ..o
                    }),
                    MethodOptions::Stochastic(o) => MethodOptions::Stochastic(StochasticOptions {
                        spp: Some(spp),
                        ..o
                    }),
                    other => other,
                };
                let what = format!("{name} {method} (spp {spp})");
                let start = std::time::Instant::now();
                let result = mblur::render(&p, &opts, &NoProgress);
                eprintln!("{what}: {:.3} s", start.elapsed().as_secs_f64());
                match (result, refusal) {
                    (Ok(out), None) => {
                        assert_finite(&out.image, &what);
                        assert_eq!(out.image.pixels.len(), (w * h) as usize, "{what}");
                        assert!(
                            out.image.pixels.iter().any(|px| *px != bg),
                            "{what}: nothing drawn"
                        );
                    }
                    (Ok(_), Some(feature)) => panic!("{what}: rendered despite {feature}"),
                    (Err(err), None) => panic!("{what} failed: {err}"),
                    (Err(err), Some(feature)) => {
                        let msg = err.to_string();
                        assert!(
                            msg.contains(feature),
                            "{what}: error does not name `{feature}`: {msg}"
                        );
                    }
                }
            }
        }
    }
}
