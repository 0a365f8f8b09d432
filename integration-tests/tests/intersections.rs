//! Rønnow 2021, Fig. 11 and §4.3: in the built-in `crossing-quads` scene a red quad moves
//! from back to front and a green one from front to back (both sliding sideways), so
//! their depth order flips at mid-shutter in every pixel they share. Averaged over the
//! shutter those pixels are half red, half green: yellow. Without intersection handling
//! (Algorithm 1 without the red-marked lines) one quad keeps the front for the whole shutter.
//!
//! The region both quads cover for the whole shutter is found from the scene's 2DH vertices
//! (orthographic camera: w = 1, axis-aligned quads moving linearly, so the intersection of
//! the four screen rectangles at open and close is covered throughout).

use integration_tests::{accum, assert_finite, builtin, rmse};
use mblur::{Effects, Image, NoProgress, PreparedScene};

const W: u32 = 64;
const H: u32 = 48;

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

/// Yellow: red and green both near one half, within 0.03 of each other, blue near zero.
fn is_yellow(c: [f32; 3]) -> bool {
    c[0] > 0.45 && c[1] > 0.45 && (c[0] - c[1]).abs() < 0.03 && c[2] < 0.02
}

#[test]
fn crossing_quads_is_yellow_with_intersection_handling_and_not_without() {
    let p = builtin("crossing-quads", W, H);
    let pipeline = Effects::analyse(&p).pipeline();
    assert!(
        pipeline.intersection,
        "effects analysis must turn intersection handling on"
    );
    assert!(!pipeline.transparency);
    let mut off = pipeline;
    off.intersection = false;

    // The ground truth (independent of the interval resolve) is yellow there.
    let truth = accum(&p, 512);
    let region = shared_pixels(&p, &truth);
    assert!(
        region.len() >= 40,
        "shared region has only {} pixels",
        region.len()
    );
    assert!(region.iter().all(|&c| is_yellow(c)), "accum: {region:?}");

    let opts = mblur::AnalyticOptions::default();
    let renders = [
        (
            "analytic",
            true,
            mblur::analytic::render(&p, &pipeline, &opts, &NoProgress),
        ),
        (
            "analytic",
            false,
            mblur::analytic::render(&p, &off, &opts, &NoProgress),
        ),
        (
            "prism",
            true,
            mblur::prism::render(&p, &pipeline, &NoProgress),
        ),
        ("prism", false, mblur::prism::render(&p, &off, &NoProgress)),
    ];
    for (method, handling, img) in renders {
        let img = img.unwrap();
        assert_finite(&img, method);
        let px = shared_pixels(&p, &img);
        let e = rmse(&img, &truth);
        let mean = px
            .iter()
            .fold([0.0f32; 3], |a, c| [a[0] + c[0], a[1] + c[1], a[2] + c[2]])
            .map(|v| v / px.len() as f32);
        eprintln!(
            "{method}, intersection handling {handling}: shared region mean {mean:?}, rmse vs accum {e:.5}"
        );
        if handling {
            assert!(px.iter().all(|&c| is_yellow(c)), "{method}: {px:?}");
            assert!(e < 1e-2, "{method}: rmse {e}");
        } else {
            // One quad stays in front for (almost) the whole shutter: no pixel is yellow, and
            // on average red and green differ by most of the full range. (Where a quad's
            // diagonal splits its coverage into two intervals, the order is re-taken at the
            // split, so a few pixels are a 1/3 : 2/3 mix; still far from yellow.)
            assert!(
                px.iter().all(|c| (c[0] - c[1]).abs() > 0.3),
                "{method} without intersection handling: {px:?}"
            );
            assert!((mean[0] - mean[1]).abs() > 0.9, "{method}: mean {mean:?}");
            assert!(e > 0.05, "{method}: rmse {e}");
        }
    }
}
