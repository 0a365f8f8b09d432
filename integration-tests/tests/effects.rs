//! Effects analysis end to end: each scene runs only the stages it calls for, and the
//! shortcuts give the same image as the general path.
//! - the static scene allocates no interval storage and every method that applies renders it
//!   bit for bit as the static rasteriser does (one static render, `accum::render_static`);
//! - opaque scenes take the opaque resolve, transparent scenes the transparent resolve
//!   (the `Rendered` description and the pipeline say so), and on opaque content the two
//!   resolves agree;
//! - intersection handling is on exactly where the analysis finds overlapping swept bounds.

use integration_tests::{accum, builtin, render, render_with, rmse, triangle_scenes};
use mblur::{Effects, Method, NoProgress, RenderOptions};

fn described(p: &mblur::PreparedScene, method: Method) -> String {
    render(
        p,
        &RenderOptions {
            method,
            ..Default::default()
        },
    )
    .description
}

#[test]
fn static_scene_needs_no_interval_storage_and_equals_the_static_path() {
    let p = builtin("static", 64, 36);
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
    assert!(mblur::accum::render_static(&p, 1.0).pixels == still.pixels);
    for method in [Method::Auto, Method::Accum, Method::Analytic, Method::Prism] {
        let out = render(
            &p,
            &RenderOptions {
                method,
                ..Default::default()
            },
        );
        assert!(
            out.image.pixels == still.pixels,
            "{method}: differs from the static path"
        );
        if matches!(method, Method::Analytic | Method::Prism) {
            assert!(
                out.description.contains("no interval storage"),
                "{method}: {}",
                out.description
            );
        }
        if method == Method::Accum {
            assert!(
                out.description.contains("1 sub-frame"),
                "{}",
                out.description
            );
        }
        if method == Method::Auto {
            // `auto` resolves to analytic (or accum) for a triangle scene; either way no
            // motion machinery runs.
            let d = &out.description;
            assert!(
                d.contains("1 sub-frame") || d.contains("no interval storage"),
                "{d}"
            );
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
        // The stochastic sample buffer keeps one surface per sample: it takes every opaque
        // scene and refuses every transparent one by name.
        let s = mblur::render(
            &p,
            &RenderOptions {
                method: Method::Stochastic,
                spp: Some(1),
                ..Default::default()
            },
            &NoProgress,
        );
        match (transparent, s) {
            (false, Ok(_)) => {}
            (true, Err(e)) => assert!(e.to_string().contains("transparen"), "{name}: {e}"),
            (t, r) => panic!(
                "{name}: transparent {t}, stochastic gave {:?}",
                r.map(|r| r.description)
            ),
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
/// the description's counts match the analysis, and the image still matches accum.
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
    let e = rmse(&render_with(&p, Method::Analytic), &accum(&p, 512));
    assert!(e < 2e-2, "{e}");
}
