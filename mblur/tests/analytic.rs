//! The analytic method (edge-eqn -> interval-buffer -> resolve) against an independent
//! reference: the accum method (N static renders averaged) at a high time count, on small
//! versions of the built-in scenes, plus named hard cases.

use integration_tests::{assert_finite, builtin, rmse};
use mblur::{Image, Method, NoProgress, RenderOptions};
use mblur_scene::Scene;

fn render(p: &mblur::PreparedScene, method: Method, times: Option<u32>, intervals: u32) -> Image {
    mblur::render(
        p,
        &RenderOptions {
            method,
            times,
            intervals,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap()
    .image
}

/// RMSE of analytic with `k` intervals against accum at `times` sub-frames.
fn versus_accum(name: &str, w: u32, h: u32, times: u32, k: u32) -> f64 {
    let p = builtin(name, w, h);
    let a = render(&p, Method::Analytic, None, k);
    assert_finite(&a, name);
    let r = render(&p, Method::Accum, Some(times), 0);
    let e = rmse(&a, &r);
    eprintln!("{name} {w}x{h} K={k} vs accum {times}: rmse {e:.5}");
    e
}

#[test]
fn billiards_matches_accum() {
    assert!(versus_accum("billiards", 64, 36, 512, 0) < 1.5e-2);
}

#[test]
fn crossing_quads_matches_accum() {
    assert!(versus_accum("crossing-quads", 64, 36, 512, 0) < 1e-2);
}

#[test]
fn transparent_cubes_match_accum() {
    assert!(versus_accum("transparent-cubes", 64, 36, 512, 0) < 1.5e-2);
}

#[test]
fn pills_match_accum() {
    assert!(versus_accum("pills", 64, 36, 512, 0) < 1.5e-2);
}

#[test]
fn textured_quad_matches_accum() {
    assert!(versus_accum("textured-quad", 64, 36, 512, 0) < 1.5e-2);
}

#[test]
fn fence_matches_accum() {
    assert!(versus_accum("fence", 64, 36, 512, 0) < 1.5e-2);
}

#[test]
fn static_scene_is_identical_to_the_static_path() {
    let p = builtin("static", 64, 36);
    let a = render(&p, Method::Analytic, None, 0);
    let s = mblur::accum::render_static(&p, 0.0);
    assert_eq!(a.pixels, s.pixels);
    let desc = mblur::render(
        &p,
        &RenderOptions {
            method: Method::Analytic,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap()
    .description;
    assert!(desc.contains("no interval storage"), "{desc}");
}

/// Rønnow 2021, Fig. 11: a red quad moves from back to front while a green one moves from
/// front to back through it; they swap depth order at mid-shutter at every pixel they share.
const FIG11: &str = r#"{
  "camera": { "width": 32, "height": 24,
    "projection": { "perspective": { "fov_y_deg": 40 } },
    "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
  "background": [0, 0, 0],
  "objects": [
    { "name": "red", "mesh": { "quad": { "size": [1.5, 1.5] } },
      "material": { "color": [1, 0, 0, 1] },
      "motion": { "open": { "translate": [0, 0, -1] }, "close": { "translate": [0, 0, 1] } } },
    { "name": "green", "mesh": { "quad": { "size": [1.5, 1.5] } },
      "material": { "color": [0, 1, 0, 1] },
      "motion": { "open": { "translate": [0, 0, 1] }, "close": { "translate": [0, 0, -1] } } }
  ]
}"#;

#[test]
fn crossing_quads_turn_yellow_with_intersection_handling() {
    let p = Scene::from_json(FIG11, "fig11", ".")
        .unwrap()
        .prepare()
        .unwrap();
    let pipeline = mblur::Effects::analyse(&p).pipeline();
    assert!(pipeline.intersection);
    let opts = mblur::AnalyticOptions::default();
    let with = mblur::analytic::render(&p, &pipeline, &opts, &NoProgress).unwrap();
    let mut off = pipeline;
    off.intersection = false;
    let without = mblur::analytic::render(&p, &off, &opts, &NoProgress).unwrap();
    let centre = (12 * 32 + 16) as usize;
    let (c, n) = (with.pixels[centre], without.pixels[centre]);
    // Half the shutter red in front, half green: yellow-ish.
    assert!(
        (c[0] - 0.5).abs() < 2e-2 && (c[1] - 0.5).abs() < 2e-2 && c[2] == 0.0,
        "{c:?}"
    );
    // Without intersection handling one colour keeps the front for the whole shutter.
    assert!((n[0] - n[1]).abs() > 0.9, "{n:?}");
    let r = render(&p, Method::Accum, Some(512), 0);
    let (e_with, e_without) = (rmse(&with, &r), rmse(&without, &r));
    eprintln!("fig11 quads: rmse with intersections {e_with:.5}, without {e_without:.5}");
    assert!(
        e_with < 1e-2 && e_without > 10.0 * e_with,
        "{e_with} {e_without}"
    );
}

#[test]
fn compressed_buffers_are_worse_than_exact_but_bounded() {
    // The fence is the paper's own failure case for the oracle (Gribel 2010, Fig. 11):
    // many thin slats per pixel merge into wrong colours at small K.
    for (name, b16, b4) in [
        ("billiards", 2e-3, 2e-2),
        ("transparent-cubes", 2e-3, 3e-2),
        ("fence", 5e-2, 0.2),
    ] {
        let exact = versus_accum(name, 64, 36, 512, 0);
        let k16 = versus_accum(name, 64, 36, 512, 16);
        let k4 = versus_accum(name, 64, 36, 512, 4);
        assert!(k4 >= exact && k16 >= exact, "{name}: {exact} {k16} {k4}");
        assert!(k16 < b16 && k4 < b4, "{name}: {k16} {k4}");
    }
}

#[test]
fn quad_moving_through_the_near_plane_matches_accum() {
    // The quad starts at depth 6 and ends behind the near plane (depth 0.2 < 0.5): its
    // triangles cannot go to edge-eqn and are rendered in time slices with clipping.
    let json = r#"{
      "camera": { "width": 48, "height": 32,
        "projection": { "perspective": { "fov_y_deg": 60 } },
        "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
      "background": [0.2, 0.2, 0.2],
      "objects": [
        { "name": "wall", "mesh": { "quad": { "size": [20, 20] } },
          "material": { "color": [0.1, 0.6, 0.2, 1] },
          "transform": { "translate": [0, 0, -3] } },
        { "name": "flyer", "mesh": { "quad": { "size": [1.0, 1.0] } },
          "material": { "color": [0.9, 0.8, 0.1, 1] },
          "motion": { "open": { "translate": [0.3, 0, 0] }, "close": { "translate": [0, 0, 5.8] } } }
      ]
    }"#;
    let p = Scene::from_json(json, "near", ".")
        .unwrap()
        .prepare()
        .unwrap();
    let d = mblur::render(
        &p,
        &RenderOptions {
            method: Method::Analytic,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap()
    .description;
    assert!(d.contains("2 near-plane crossings"), "{d}");
    let a = render(&p, Method::Analytic, None, 0);
    assert_finite(&a, "near-plane crossing");
    let r = render(&p, Method::Accum, Some(1024), 0);
    let e = rmse(&a, &r);
    eprintln!("near-plane flyer: rmse {e:.5}");
    assert!(e < 2e-2, "{e}");
}

#[test]
fn too_many_intervals_is_an_option_error() {
    let p = builtin("billiards", 16, 9);
    let e = mblur::render(
        &p,
        &RenderOptions {
            method: Method::Analytic,
            intervals: mblur::analytic::MAX_INTERVALS + 1,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap_err();
    assert!(e.to_string().contains("--intervals"), "{e}");
}

#[test]
fn splat_scenes_are_refused_by_name() {
    let p = builtin("splat-ball", 16, 9);
    let e = mblur::render(
        &p,
        &RenderOptions {
            method: Method::Analytic,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap_err();
    assert!(e.to_string().contains("splats"), "{e}");
}
