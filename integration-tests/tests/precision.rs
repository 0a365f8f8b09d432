//! `--precision f32|f64` for the interval methods, end to end against an independent
//! reference: the accum method (static f64 rasteriser, N renders averaged) at a high time
//! count.
//!
//! - Far-away z-fight: two moving quads 1000 units from the eye, 2e-5 units apart in depth
//!   (2e-8 relative, below f32's 6e-8 resolution, far above f64's). The f64 chain keeps the
//!   near (red) quad in front like accum; in f32 the two depths round to the same value, the
//!   tie goes to the later object (the far, blue quad) and blue shows wherever both cover.
//!   Measured at 48x32 against accum with 256 times: RMSE analytic f32 0.3298 vs f64 0.0003,
//!   prism f32 0.2757 vs f64 0.0003; with a 2e-2 gap f32 is fine (0.0003). The tests print
//!   the figures.
//! - Where f32 suffices (billiards, crossing-quads): f32 and f64 agree with each other, and
//!   f64 is within the bound `versus_accum.rs` holds the (f32) analytic method to against
//!   accum (measured: billiards f32 vs f64 RMSE 9.3e-6, crossing-quads 1.2e-8; both 1e-4 to
//!   2e-4 against accum). At these small
//!   sizes the coordinates are small anyway; `mblur/BENCHMARKS.md` has f32 vs f64 at the
//!   scenes' default sizes, where the local coordinates of moving primitives matter. Before
//!   them the far pair's f32 result depended on rounding noise (the quad listed first won).

use integration_tests::{accum, builtin, from_json, render, rmse};
use mblur::{
    AnalyticOptions, Image, Method, MethodOptions, Precision, PreparedScene, PrismOptions,
};

/// `method` in `precision` through the library entry point, every pixel checked finite.
fn render_in(p: &PreparedScene, method: Method, precision: Precision) -> Image {
    render(
        p,
        &match method {
            Method::Prism => MethodOptions::Prism(PrismOptions {
                precision,
                ..Default::default()
            }),
            _ => MethodOptions::Analytic(AnalyticOptions {
                precision,
                ..Default::default()
            }),
        },
    )
    .image
}

/// Two quads moving sideways 1000 units away; `gap` units of depth between them. The far
/// (blue) one is listed last, so an exact depth tie (which goes to the later object) shows
/// blue.
fn far_pair(gap: f64) -> PreparedScene {
    from_json(&format!(
        r#"{{
  "camera": {{ "width": 48, "height": 32,
    "projection": {{ "perspective": {{ "fov_y_deg": 30 }} }},
    "eye": [0, 0, 0], "target": [0, 0, -1], "near": 1, "far": 5000 }},
  "background": [0, 0, 0],
  "objects": [
    {{ "name": "red-near", "mesh": {{ "quad": {{ "size": [300, 300] }} }},
      "material": {{ "color": [1, 0, 0, 1] }},
      "motion": {{ "open": {{ "translate": [-100, 0, -1000] }}, "close": {{ "translate": [100, 0, -1000] }} }} }},
    {{ "name": "blue-far", "mesh": {{ "quad": {{ "size": [300, 300] }} }},
      "material": {{ "color": [0, 0, 1, 1] }},
      "motion": {{ "open": {{ "translate": [-100, 0, {zb}] }}, "close": {{ "translate": [100, 0, {zb}] }} }} }}
  ]
}}"#,
        zb = -1000.0 - gap
    ))
}

#[test]
fn far_away_z_fight_needs_f64() {
    let p = far_pair(2e-5);
    let reference = accum(&p, 256);
    for method in [Method::Analytic, Method::Prism] {
        let e32 = rmse(&render_in(&p, method, Precision::F32), &reference);
        let e64 = rmse(&render_in(&p, method, Precision::F64), &reference);
        eprintln!("far pair, {method}: rmse vs accum f32 {e32:.4}, f64 {e64:.4}");
        assert!(e64 < 2e-2, "{method} f64 {e64}");
        assert!(
            e32 > 0.1 && e32 > 10.0 * e64,
            "{method} f32 {e32} vs f64 {e64}"
        );
    }
}

#[test]
fn a_resolvable_gap_is_fine_in_f32() {
    // 2e-2 units at 1000 (2e-5 relative): far above f32's resolution.
    let p = far_pair(2e-2);
    let reference = accum(&p, 256);
    let e32 = rmse(&render_in(&p, Method::Analytic, Precision::F32), &reference);
    eprintln!("far pair, resolvable gap: rmse vs accum f32 {e32:.4}");
    assert!(e32 < 2e-2, "{e32}");
}

/// Billiards and crossing-quads at 64x36: analytic in f64 is within the bound
/// `versus_accum.rs` holds analytic (f32, the default) to against accum at 512 sub-frames
/// (2.0e-4 and 3.2e-4), and f32 and f64 agree (RMSE < 1e-3).
#[test]
fn f32_suffices_on_builtin_scenes() {
    for (name, bound) in [("billiards", 2.0e-4), ("crossing-quads", 3.2e-4)] {
        let p = builtin(name, 64, 36);
        let reference = integration_tests::chord_accum(&p, 512);
        let a32 = render_in(&p, Method::Analytic, Precision::F32);
        let a64 = render_in(&p, Method::Analytic, Precision::F64);
        let (e32, e64, d) = (
            rmse(&a32, &reference),
            rmse(&a64, &reference),
            rmse(&a32, &a64),
        );
        eprintln!("{name}: rmse vs accum f32 {e32:.5}, f64 {e64:.5}; f32 vs f64 {d:.2e}");
        assert!(e64 < bound, "{name}: f64 rmse vs accum {e64}");
        assert!(d < 1e-3, "{name}: f32 and f64 differ by {d}");
    }
}
