//! The interval methods against the ground truth: `analytic` (unbounded interval lists,
//! Gribel 2010) and `prism` (Rønnow 2021) against `accum` at 512 sub-frames on every
//! built-in triangle scene at 64x36, with a per-scene RMSE bound; and `analytic` against
//! `prism` on the scenes where w is constant over the shutter (orthographic cameras, or
//! motion parallel to the image plane), where the prism's screen-linear motion is exact and
//! the two must agree. Curved motion is compared on the segments the methods are given
//! (`chord_accum`: accum on the segments' chords), so these bounds measure the methods'
//! exactness, including across segment boundaries; the chords' distance to the true arc is
//! measured in `curved_motion.rs`.
//!
//! Each bound is the RMSE measured when the test was written (listed in the crate README)
//! times 2, rounded up to two significant digits: a change that doubles a method's error
//! fails. All three methods sample pixel centres, so what is left is the accum reference's
//! own time quantisation (512 strata) and, for `prism` under perspective with depth motion,
//! Rønnow's screen-linear approximation (up to 100x the analytic error on the rotating
//! textured quad). The static scene must match exactly (bound 1e-6: no time dependence).

use integration_tests::{builtin, chord_accum as accum, from_json, render_with, rmse};
use mblur::Method;

const W: u32 = 64;
const H: u32 = 36;
const TIMES: u32 = 512;

/// RMSE of analytic and of prism against accum with [`TIMES`] sub-frames.
fn errors(name: &str) -> (f64, f64) {
    let p = builtin(name, W, H);
    let reference = accum(&p, TIMES);
    let a = rmse(&render_with(&p, Method::Analytic), &reference);
    let r = rmse(&render_with(&p, Method::Prism), &reference);
    eprintln!("{name} {W}x{H}: analytic {a:.3e}, prism {r:.3e} (vs accum {TIMES})");
    (a, r)
}

fn check(name: &str, analytic_bound: f64, prism_bound: f64) {
    let (a, r) = errors(name);
    assert!(
        a < analytic_bound,
        "{name}: analytic rmse {a} >= {analytic_bound}"
    );
    assert!(r < prism_bound, "{name}: prism rmse {r} >= {prism_bound}");
}

#[test]
fn billiards_analytic_and_prism_match_accum() {
    check("billiards", 2.0e-4, 2.2e-3);
}

#[test]
fn fence_analytic_and_prism_match_accum() {
    check("fence", 6.3e-4, 6.3e-4);
}

#[test]
fn transparent_cubes_analytic_and_prism_match_accum() {
    check("transparent-cubes", 4.2e-4, 3.7e-3);
}

#[test]
fn crossing_quads_analytic_and_prism_match_accum() {
    check("crossing-quads", 3.2e-4, 3.2e-4);
}

#[test]
fn pills_analytic_and_prism_match_accum() {
    check("pills", 2.2e-4, 6.2e-4);
}

#[test]
fn clothball_analytic_and_prism_match_accum() {
    check("clothball", 3.9e-4, 8.4e-3);
}

#[test]
fn clothball_ronnow_analytic_and_prism_match_accum() {
    check("clothball-ronnow", 1.6e-4, 2.1e-4);
}

#[test]
fn textured_quad_analytic_and_prism_match_accum() {
    check("textured-quad", 2.6e-4, 2.7e-2);
}

#[test]
fn spinning_wheel_analytic_and_prism_match_accum() {
    check("spinning-wheel", 4.0e-4, 4.0e-4);
}

#[test]
fn static_analytic_and_prism_match_accum() {
    check("static", 1e-6, 1e-6);
}

/// Every triangle scene has a test above (a new built-in scene must get one).
#[test]
fn every_triangle_scene_is_covered() {
    let covered = [
        "billiards",
        "fence",
        "transparent-cubes",
        "crossing-quads",
        "pills",
        "clothball",
        "clothball-ronnow",
        "textured-quad",
        "spinning-wheel",
        "static",
        // Compared in `lighting.rs`.
        "spinning-lit-ball",
    ];
    for name in integration_tests::triangle_scenes() {
        assert!(covered.contains(&name), "no accum comparison for {name}");
    }
}

/// Two quads sliding parallel to the image plane under perspective (w constant per vertex,
/// different between vertices; one quad half transparent) over a static wall.
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

/// Where w is constant over the shutter the prism's screen-linear vertex motion is exact, so
/// prism and analytic compute the same coverage intervals by different means
/// (ray/bilinear-patch vs time-dependent edge equations) and the images agree to f32
/// rounding: RMSE < 1e-6 (100x below either method's distance to accum) on the orthographic
/// built-in scenes crossing-quads and fence (64x36; measured 1.5e-8, 8.5e-8), on two quads
/// sliding parallel to the image plane under perspective, one of them transparent (48x32;
/// 9.8e-8), and on a spinning quad with a quad moving in depth under an orthographic camera
/// (48x32; 4.1e-8). w constant is checked on every vertex. The two hand-made scenes have no
/// per-scene test above, so there both methods are also held to accum at 512 sub-frames:
/// RMSE < 2.5e-4 (measured 1.2e-4) and < 5e-3 (measured 3.3e-3).
#[test]
fn analytic_and_prism_agree_where_w_is_constant() {
    // (name, scene, bound on each method's RMSE against accum where no test above has one)
    let scenes = [
        ("crossing-quads", builtin("crossing-quads", W, H), None),
        ("fence", builtin("fence", W, H), None),
        ("parallel", from_json(PARALLEL), Some(2.5e-4)),
        ("ortho", from_json(ORTHO), Some(5e-3)),
    ];
    for (name, p, accum_bound) in scenes {
        assert!(
            p.triangles
                .iter()
                .all(|t| (0..3).all(|i| t.open[i].w == t.close[i].w)),
            "{name}: w changes over the shutter"
        );
        let (a, r) = (
            render_with(&p, Method::Analytic),
            render_with(&p, Method::Prism),
        );
        let e = rmse(&a, &r);
        eprintln!("{name} {}x{}: analytic vs prism {e:.2e}", p.width, p.height);
        assert!(e < 1e-6, "{name}: analytic vs prism rmse {e}");
        if let Some(bound) = accum_bound {
            let reference = accum(&p, TIMES);
            let (ea, er) = (rmse(&a, &reference), rmse(&r, &reference));
            eprintln!("{name}: vs accum {TIMES}: analytic {ea:.2e}, prism {er:.2e}");
            assert!(
                ea < bound && er < bound,
                "{name}: analytic {ea}, prism {er}"
            );
        }
    }
}

/// analytic with 16 sample positions per pixel against accum with the same positions (each
/// a render of the shifted scene, [`mblur::aa`]): the same bound as at the pixel centre, so
/// "exact in time" stays checkable with spatial antialiasing.
#[test]
fn analytic_with_sample_positions_matches_accum_with_the_same_positions() {
    use mblur::aa::{Antialiasing, Filter};
    use mblur::{AccumOptions, AnalyticOptions, MethodOptions};
    for (name, bound) in [("billiards", 2.0e-4), ("textured-quad", 2.6e-4)] {
        let p = integration_tests::chords(&builtin(name, W, H));
        let aa = Antialiasing {
            samples: 16,
            filter: Filter::Tent,
            radius: None,
        };
        let accum_aa = MethodOptions::Accum(AccumOptions {
            times: Some(TIMES),
            jitter: None,
            aa,
        });
        let analytic_aa = MethodOptions::Analytic(AnalyticOptions {
            aa,
            ..AnalyticOptions::default()
        });
        let reference = integration_tests::render(&p, &accum_aa).image;
        let a = rmse(
            &integration_tests::render(&p, &analytic_aa).image,
            &reference,
        );
        eprintln!("{name} {W}x{H} --aa 16 tent: analytic {a:.3e} (vs accum {TIMES})");
        assert!(a < bound, "{name}: analytic --aa 16 rmse {a} >= {bound}");
        // The positions matter: against the pixel-centre reference the error is larger.
        let centre = rmse(
            &integration_tests::render(&p, &analytic_aa).image,
            &accum(&p, TIMES),
        );
        assert!(centre > 4.0 * a, "{name}: {centre} vs {a}");
    }
}
