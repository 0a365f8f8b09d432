//! The prism method (bilinear-patch -> exact lists -> resolve) against independent
//! references: accum at a high time count, and the analytic method where the prism's
//! screen-space linear motion is exact (w constant: orthographic camera, or motion parallel
//! to the image plane).

use integration_tests::rmse;
use mblur::{Image, Method, NoProgress, RenderOptions};
use mblur_scene::Scene;

fn builtin(name: &str) -> mblur::PreparedScene {
    integration_tests::builtin(name, 64, 36)
}

fn render(p: &mblur::PreparedScene, method: Method, times: Option<u32>) -> Image {
    mblur::render(
        p,
        &RenderOptions {
            method,
            times,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap()
    .image
}

fn compare(label: &str, p: &mblur::PreparedScene) -> (f64, f64) {
    let pr = render(p, Method::Prism, None);
    assert!(pr.pixels.iter().flatten().all(|v| v.is_finite()));
    let acc = render(p, Method::Accum, Some(512));
    let an = render(p, Method::Analytic, None);
    let (ea, en) = (rmse(&pr, &acc), rmse(&pr, &an));
    eprintln!("{label}: prism vs accum 512 {ea:.5}, vs analytic {en:.5}");
    (ea, en)
}

/// Two quads sliding parallel to the image plane under perspective (w constant per vertex)
/// over a static wall.
const PARALLEL: &str = r#"{
  "camera": { "width": 48, "height": 32,
    "projection": { "perspective": { "fov_y_deg": 50 } },
    "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
  "background": [0.1, 0.1, 0.1],
  "objects": [
    { "name": "wall", "mesh": { "quad": { "size": [20, 20] } },
      "material": { "color": [0.2, 0.5, 0.3, 1] }, "transform": { "translate": [0, 0, -2] } },
    { "name": "a", "mesh": { "quad": { "size": [1.2, 1.2] } },
      "material": { "color": [0.9, 0.2, 0.1, 1] },
      "motion": { "open": { "translate": [-1.5, 0.2, 0] }, "close": { "translate": [1.5, -0.2, 0] } } },
    { "name": "b", "mesh": { "quad": { "size": [1.0, 1.0] } },
      "material": { "color": [0.1, 0.3, 0.9, 0.5] },
      "motion": { "open": { "translate": [1.0, 0.8, 0.5] }, "close": { "translate": [-1.0, -0.8, 0.5] } } }
  ]
}"#;

/// A spinning quad and a quad moving in depth, seen through an orthographic camera (w = 1).
const ORTHO: &str = r#"{
  "camera": { "width": 48, "height": 32,
    "projection": { "orthographic": { "height": 4 } },
    "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
  "background": [0.1, 0.1, 0.1],
  "objects": [
    { "name": "spinner", "mesh": { "quad": { "size": [2, 0.6] } },
      "material": { "color": [0.9, 0.8, 0.1, 1] },
      "motion": { "open": { "rotate": { "axis": [0, 1, 1], "degrees": -40 } },
                  "close": { "rotate": { "axis": [0, 1, 1], "degrees": 50 }, "translate": [0.5, 0, 0] } } },
    { "name": "red", "mesh": { "quad": { "size": [1.5, 1.5] } },
      "material": { "color": [1, 0, 0, 1] },
      "motion": { "open": { "translate": [0, 0, -1] }, "close": { "translate": [0, 0, 1] } } }
  ]
}"#;

#[test]
fn prism_equals_analytic_when_w_is_constant_under_perspective() {
    let p = Scene::from_json(PARALLEL, "parallel", ".")
        .unwrap()
        .prepare()
        .unwrap();
    let (ea, en) = compare("parallel", &p);
    assert!(ea < 5e-3 && en < 1e-3, "{ea} {en}");
}

#[test]
fn prism_equals_analytic_under_an_orthographic_camera() {
    let p = Scene::from_json(ORTHO, "ortho", ".")
        .unwrap()
        .prepare()
        .unwrap();
    let (ea, en) = compare("ortho", &p);
    assert!(ea < 5e-3 && en < 1e-3, "{ea} {en}");
}

#[test]
fn prism_matches_accum_on_builtin_scenes() {
    // Perspective scenes with depth motion: the prism's screen-linear motion is Rønnow's
    // approximation, so the bound is looser than for analytic.
    for (name, bound) in [
        ("billiards", 1e-2),
        ("crossing-quads", 1e-2),
        ("transparent-cubes", 1e-2),
        ("pills", 1e-2),
        ("fence", 1e-2),
        ("textured-quad", 2e-2),
    ] {
        let (ea, _) = compare(name, &builtin(name));
        assert!(ea < bound, "{name}: {ea}");
    }
}

#[test]
fn prism_static_scene_is_the_static_path() {
    let p = builtin("static");
    assert_eq!(
        render(&p, Method::Prism, None).pixels,
        mblur::accum::render_static(&p, 0.0).pixels
    );
}
