//! The interval methods against the ground truth: `analytic` (unbounded interval lists,
//! Gribel 2010) and `prism` (Rønnow 2021) against `accum` at 512 sub-frames on every
//! built-in triangle scene at 64x36, with a per-scene RMSE bound; and `analytic` against
//! `prism` on the scenes where w is constant over the shutter (orthographic cameras), where
//! the prism's screen-linear motion is exact and the two must agree.
//!
//! Each bound is the RMSE measured when the test was written (listed in the crate README)
//! times 2, rounded up to two significant digits: a change that doubles a method's error
//! fails. All three methods sample pixel centres, so what is left is the accum reference's
//! own time quantisation (512 strata) and, for `prism` under perspective with depth motion,
//! Rønnow's screen-linear approximation (up to 100x the analytic error on the rotating
//! textured quad). The static scene must match exactly (bound 1e-6: no time dependence).

use integration_tests::{accum, builtin, render_with, rmse};
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
        "static",
    ];
    for name in integration_tests::triangle_scenes() {
        assert!(covered.contains(&name), "no accum comparison for {name}");
    }
}

/// Where w is constant over the shutter (orthographic camera: fence, crossing-quads) the
/// prism's screen-linear vertex motion is exact, so prism and analytic compute the same
/// coverage intervals by different means (ray/bilinear-patch vs time-dependent edge
/// equations) and the images agree to f32 rounding (measured 1.5e-8 and 8.5e-8; bound 1e-6,
/// still 100x below either method's distance to accum).
#[test]
fn analytic_and_prism_agree_where_w_is_constant() {
    for (name, bound) in [("crossing-quads", 1e-6), ("fence", 1e-6)] {
        let p = builtin(name, W, H);
        assert!(
            p.triangles
                .iter()
                .all(|t| (0..3).all(|i| t.open[i].w == t.close[i].w)),
            "{name}: w changes over the shutter"
        );
        let e = rmse(
            &render_with(&p, Method::Analytic),
            &render_with(&p, Method::Prism),
        );
        eprintln!("{name} {W}x{H}: analytic vs prism {e:.2e}");
        assert!(e < bound, "{name}: analytic vs prism rmse {e} >= {bound}");
    }
}
