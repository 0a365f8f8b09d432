//! Rønnow 2021, Fig. 11 and §4.3: two quads pass through each other, a red one from back to
//! front and a green one from front to back, so their depth order flips at mid-shutter in
//! every pixel they share. Averaged over the shutter those pixels are half red, half green:
//! yellow. Without intersection handling (Algorithm 1 without the red-marked lines) one quad
//! keeps the front for the whole shutter. Two versions: the built-in `crossing-quads`
//! (orthographic camera, the quads also sliding sideways) and the figure's own set-up under a
//! perspective camera (both quads centred on the view axis, moving in depth only, so w
//! changes over the shutter).
//!
//! The region both quads cover for the whole shutter is found from the scene's 2DH vertices:
//! the intersection of the quads' screen rectangles at open and at close. Under the
//! orthographic camera the quads are axis-aligned and move linearly on screen, so a point in
//! both end rectangles is in every one between; under the perspective camera each centred
//! square's screen size changes monotonically, so the smaller end square is covered
//! throughout.

use integration_tests::{accum, assert_finite, builtin, from_json, rmse};
use mblur::{Effects, Image, NoProgress, PreparedScene};

/// Rønnow 2021, Fig. 11 under a perspective camera: the quads swap depth order at
/// mid-shutter at every pixel they share.
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

/// Pixel-centre bounds (x0, y0, x1, y1) covered by every quad at open and at close, shrunk
/// by one pixel.
fn shared_region(p: &PreparedScene) -> (f64, f64, f64, f64) {
    let mut r = (f64::MIN, f64::MIN, f64::MAX, f64::MAX);
    for o in &p.objects {
        for close in [false, true] {
            let tris = &p.triangles[o.range.clone()];
            let v = tris
                .iter()
                .flat_map(|t| if close { t.close } else { t.open })
                .map(|v| (v.x / v.w, v.y / v.w));
            let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
            for (x, y) in v {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
            r = (r.0.max(x0), r.1.max(y0), r.2.min(x1), r.3.min(y1));
        }
    }
    (r.0 + 1.0, r.1 + 1.0, r.2 - 1.0, r.3 - 1.0)
}

/// The pixels of `img` whose centres lie in the shared region.
fn shared_pixels(p: &PreparedScene, img: &Image) -> Vec<[f32; 3]> {
    let (x0, y0, x1, y1) = shared_region(p);
    let mut out = Vec::new();
    for y in 0..img.height {
        for x in 0..img.width {
            let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            if cx >= x0 && cx <= x1 && cy >= y0 && cy <= y1 {
                out.extend(img.get(x, y));
            }
        }
    }
    out
}

/// Yellow: red and green both within 0.02 of one half and within 0.03 of each other, no
/// blue at all (only the red and the green quad are seen there).
fn is_yellow(c: [f32; 3]) -> bool {
    (c[0] - 0.5).abs() < 0.02
        && (c[1] - 0.5).abs() < 0.02
        && (c[0] - c[1]).abs() < 0.03
        && c[2] == 0.0
}

/// The built-in scene at 64x48 (orthographic; shared region 56 pixels). Without
/// intersection handling every shared pixel has |R - G| > 0.3: where a quad's diagonal
/// splits its coverage into two intervals the order is re-taken at the split, so a few
/// pixels are a 1/3 : 2/3 mix (measured 0.57), still far from yellow.
#[test]
fn crossing_quads_is_yellow_with_intersection_handling_and_not_without() {
    let p = builtin("crossing-quads", 64, 48);
    check_fig11("crossing-quads", &p, 40, 1e-2, 0.3);
}

/// The figure's set-up under a perspective camera at 32x24 (shared region 36 pixels). The
/// quads move in depth, where the prism's screen-linear motion is Rønnow's approximation:
/// with handling its RMSE against accum is 0.012 (analytic 1e-4), so its bound is 2.4e-2.
/// Without handling one colour holds every shared pixel for the whole shutter
/// (|R - G| > 0.9; measured 1).
#[test]
fn perspective_crossing_quads_are_yellow_with_intersection_handling_and_not_without() {
    check_fig11("fig11 perspective", &from_json(FIG11), 16, 2.4e-2, 0.9);
}

/// The effects analysis turns intersection handling on; in the region both quads cover all
/// shutter (at least `min_pixels` pixels) accum at 512 sub-frames, and analytic and prism
/// with handling, are yellow in every pixel (measured within 4e-7 of one half), analytic
/// within RMSE 1e-2 of accum and prism within `prism_bound`; with
/// `Pipeline::intersection = false` neither method is yellow anywhere there (every pixel's
/// |R - G| above `min_split`, the mean's above 0.9), and its RMSE against accum is above
/// 0.05 and more than 10x the error with handling for analytic, 5x for prism (measured
/// 9.97x for prism under perspective, 600x elsewhere).
fn check_fig11(name: &str, p: &PreparedScene, min_pixels: usize, prism_bound: f64, min_split: f32) {
    let pipeline = Effects::analyse(p).pipeline();
    assert!(
        pipeline.intersection,
        "{name}: effects analysis must turn intersection handling on"
    );
    assert!(!pipeline.transparency);
    let mut off = pipeline;
    off.intersection = false;

    // The ground truth (independent of the interval resolve) is yellow there.
    let truth = accum(p, 512);
    let region = shared_pixels(p, &truth);
    assert!(
        region.len() >= min_pixels,
        "{name}: shared region has only {} pixels",
        region.len()
    );
    assert!(
        region.iter().all(|&c| is_yellow(c)),
        "{name}: accum: {region:?}"
    );

    let opts = mblur::AnalyticOptions::default();
    let analytic = |pipeline| mblur::analytic::render(p, pipeline, &opts, &NoProgress);
    let prism = |pipeline| mblur::prism::render(p, pipeline, &NoProgress);
    // (method, RMSE bound with handling, least ratio of the RMSE without to with)
    for (method, bound, ratio, with, without) in [
        ("analytic", 1e-2, 10.0, analytic(&pipeline), analytic(&off)),
        ("prism", prism_bound, 5.0, prism(&pipeline), prism(&off)),
    ] {
        let (with, without) = (with.unwrap(), without.unwrap());
        let (e_with, e_without) = (rmse(&with, &truth), rmse(&without, &truth));
        for (handling, img, e) in [(true, &with, e_with), (false, &without, e_without)] {
            assert_finite(img, method);
            let px = shared_pixels(p, img);
            let mean = px
                .iter()
                .fold([0.0f32; 3], |a, c| [a[0] + c[0], a[1] + c[1], a[2] + c[2]])
                .map(|v| v / px.len() as f32);
            let worst = px.iter().fold([0.0f32; 3], |w, c| {
                [
                    w[0].max((c[0] - 0.5).abs()),
                    w[1].max((c[1] - 0.5).abs()),
                    w[2].max(c[2]),
                ]
            });
            let least_rg = px
                .iter()
                .map(|c| (c[0] - c[1]).abs())
                .fold(f32::MAX, f32::min);
            eprintln!(
                "{name}, {method}, intersection handling {handling}: shared region ({} px) mean {mean:?}, max |R-1/2|, |G-1/2|, B {worst:?}, min |R-G| {least_rg}, rmse vs accum {e:.5}",
                px.len()
            );
            if handling {
                assert!(px.iter().all(|&c| is_yellow(c)), "{name}, {method}: {px:?}");
                assert!(e < bound, "{name}, {method}: rmse {e}");
            } else {
                // One quad stays in front for (almost) the whole shutter: no pixel is
                // yellow, and on average red and green differ by most of the full range.
                assert!(
                    px.iter().all(|c| (c[0] - c[1]).abs() > min_split),
                    "{name}, {method} without intersection handling: {px:?}"
                );
                assert!(
                    (mean[0] - mean[1]).abs() > 0.9,
                    "{name}, {method}: mean {mean:?}"
                );
                assert!(e > 0.05, "{name}, {method}: rmse {e}");
            }
        }
        assert!(
            e_without > ratio * e_with,
            "{name}, {method}: rmse without handling {e_without}, with {e_with}"
        );
    }
}
