//! Effects analysis end to end: each scene runs only the stages it calls for, and the
//! shortcuts give the same image as the general path.
//! - the static scene allocates no interval storage and every method that applies renders it
//!   bit for bit as the static rasteriser does (one static render, `accum::render_static`);
//! - opaque scenes take the opaque resolve, transparent scenes the transparent resolve
//!   (the `Rendered` description and the pipeline say so), and on opaque content the two
//!   resolves agree;
//! - intersection handling is on exactly where the analysis finds overlapping swept bounds.

use integration_tests::{accum, builtin, render, rmse, triangle_scenes};
use mblur::{Effects, Method, MethodOptions, NoProgress};

fn described(p: &mblur::PreparedScene, method: Method) -> String {
    render(p, &MethodOptions::defaults(method)).description
}

/// The static scene, at 64x36 and at 48x27: the pipeline has no interval storage, motion
/// or intersection handling; every method that applies to it renders it bit for bit as the
/// static rasteriser does at one instant (any instant: nothing moves); analytic and prism
/// say "no interval storage", accum "1 sub-frame", and `auto` picks analytic (see
/// `mblur/tests/auto.rs`) and says it takes the static path. Accum with 64 sub-frames
/// averages to the same image within 1 f32 ulp.
#[test]
fn static_scene_needs_no_interval_storage_and_equals_the_static_path() {
    for (w, h) in [(64, 36), (48, 27)] {
        let p = builtin("static", w, h);
        let effects = Effects::analyse(&p);
        let pipeline = effects.pipeline();
        assert!(!pipeline.interval_storage && !pipeline.motion && !pipeline.intersection);
        assert!(pipeline.static_path && !pipeline.transparency);
        assert!(
            effects.to_string().contains("interval storage: none"),
            "{effects}"
        );

        let still = mblur::accum::render_static(&p, 0.0);
        // Nothing moves: any instant is the same image.
        for t in [0.5, 1.0] {
            assert!(
                mblur::accum::render_static(&p, t).pixels == still.pixels,
                "t = {t}"
            );
        }
        for method in [Method::Auto, Method::Accum, Method::Analytic, Method::Prism] {
            // At the pixel centre (auto's default sample positions are checked in
            // mblur/tests/auto.rs).
            let centre = MethodOptions::defaults(method)
                .with_antialiasing(mblur::aa::Antialiasing::default());
            let out = render(&p, &centre);
            assert!(
                out.image.pixels == still.pixels,
                "{w}x{h} {method}: differs from the static path"
            );
            let d = &out.description;
            match method {
                Method::Accum => assert!(d.contains("1 sub-frame"), "{d}"),
                _ => assert!(d.contains("no interval storage"), "{method}: {d}"),
            }
            if method == Method::Auto {
                let note = out.note.unwrap_or_default();
                assert!(note.contains("static path"), "{note}");
            }
        }
        // Many sub-frames of a static scene average to the same image, to 1 ulp of f32 (the
        // f64 sum of 64 weighted copies may round in its last bits).
        let many = accum(&p, 64);
        for (a, b) in many
            .pixels
            .iter()
            .flatten()
            .zip(still.pixels.iter().flatten())
        {
            assert!((a - b).abs() <= f32::EPSILON * b.abs(), "{a} vs {b}");
        }
    }
}

/// For every triangle scene the pipeline takes the transparent resolve exactly when some
/// object is transparent, and analytic and prism say which resolve they run. (Which scenes
/// the stochastic method, with one surface per sample, takes and refuses is checked with
/// every other method in `finite.rs`.)
#[test]
fn opaque_scenes_take_the_opaque_resolve_transparent_ones_the_transparent_resolve() {
    let mut seen = (0, 0);
    for name in triangle_scenes() {
        let p = builtin(name, 32, 18);
        let effects = Effects::analyse(&p);
        let pipeline = effects.pipeline();
        let transparent = effects.transparent() > 0;
        assert_eq!(pipeline.transparency, transparent, "{name}");
        if !pipeline.interval_storage {
            continue; // the static scene: no resolve at all (test above)
        }
        for method in [Method::Analytic, Method::Prism] {
            let d = described(&p, method);
            if transparent {
                assert!(d.contains("transparent resolve"), "{name} {method}: {d}");
            } else {
                assert!(
                    d.contains("opaque resolve") && !d.contains("transparent"),
                    "{name} {method}: {d}"
                );
            }
        }
        if transparent {
            seen.1 += 1;
        } else {
            seen.0 += 1;
        }
    }
    assert!(
        seen.0 >= 3 && seen.1 >= 2,
        "opaque/transparent scenes seen: {seen:?}"
    );
}

/// The opaque resolve is a shortcut: forcing the transparent resolve on an opaque scene
/// (every alpha 1) gives the same image up to f32 rounding.
#[test]
fn opaque_resolve_equals_transparent_resolve_on_opaque_scenes() {
    for name in ["billiards", "crossing-quads", "fence"] {
        let p = builtin(name, 48, 27);
        let pipeline = Effects::analyse(&p).pipeline();
        assert!(!pipeline.transparency);
        let mut forced = pipeline;
        forced.transparency = true;
        let opts = mblur::AnalyticOptions::default();
        let opaque = mblur::analytic::render(&p, &pipeline, &opts, &NoProgress).unwrap();
        let general = mblur::analytic::render(&p, &forced, &opts, &NoProgress).unwrap();
        let e = rmse(&opaque, &general);
        eprintln!("{name}: opaque vs transparent resolve rmse {e:.2e}");
        assert!(e < 1e-5, "{name}: {e}");
    }
}

/// Intersection handling follows the analysis: on for scenes with a moving object whose
/// swept bounds overlap another's, off otherwise, and the description says which.
#[test]
fn intersection_handling_only_where_swept_bounds_overlap() {
    for (name, expect) in [
        ("crossing-quads", true),
        ("transparent-cubes", true),
        ("fence", false),
        ("static", false),
    ] {
        let p = builtin(name, 32, 18);
        let effects = Effects::analyse(&p);
        assert_eq!(effects.pipeline().intersection, expect, "{name}: {effects}");
        assert_eq!(!effects.overlapping_pairs.is_empty(), expect, "{name}");
        if effects.pipeline().interval_storage {
            let d = described(&p, Method::Analytic);
            assert_eq!(d.contains("intersection handling"), expect, "{name}: {d}");
        }
    }
}

/// Static objects in a moving scene go through the static rasteriser, not the motion path:
/// the description's counts match the analysis. (That the image still matches accum is
/// billiards' test in `versus_accum.rs`, RMSE < 2e-4 at 64x36.)
#[test]
fn static_objects_of_moving_scenes_take_the_static_rasteriser() {
    let p = builtin("billiards", 48, 27);
    let moving = p.triangles.iter().filter(|t| t.is_moving()).count();
    let fixed = p.triangles.len() - moving;
    assert!(moving > 0 && fixed > 0);
    let d = described(&p, Method::Analytic);
    assert!(
        d.contains(&format!("{moving} moving triangles"))
            && d.contains(&format!("{fixed} static via the static rasteriser")),
        "{d}"
    );
}
