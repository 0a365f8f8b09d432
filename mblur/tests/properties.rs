//! Property tests of the static rasteriser, the accumulation method and the exact texture
//! segment average against independent references (integer orientation tests,
//! hand-derived coverage fractions, Simpson's rule piece by piece on point samples).

use glam::{DVec2, DVec3};
use mblur::accum::{self, AccumOptions};
use mblur::static_path::{ScreenTriangle, Target, setup};
use mblur::texture::Texture;
use mblur::{NoProgress, PreparedTriangle, Vertex2dh};
use mblur_scene::Scene;
use proptest::prelude::*;

/// A triangle with fixed screen positions (w = 1, depth 1) at both shutter ends.
fn tri(p: [DVec2; 3]) -> PreparedTriangle {
    let v = p.map(|q| Vertex2dh {
        x: q.x,
        y: q.y,
        w: 1.0,
        depth: 1.0,
    });
    PreparedTriangle {
        object: 0,
        material: 0,
        world_open: [DVec3::ZERO; 3],
        world_close: [DVec3::ZERO; 3],
        open: v,
        close: v,
        uv: [DVec2::ZERO; 3],
        normal_open: [DVec3::Z; 3],
        normal_close: [DVec3::Z; 3],
        span: [0.0, 1.0],
        local: None,
    }
}

fn coverage(p: [DVec2; 3], w: u32, h: u32) -> Vec<u32> {
    let mut out = Vec::new();
    setup(
        &tri(p),
        0.0,
        0,
        true,
        &Target {
            width: w,
            height: h,
            near: 0.5,
        },
        &mut out,
    );
    let mut count = vec![0u32; (w * h) as usize];
    for st in &out {
        ScreenTriangle::rasterise(st, 0, h, |x, y, _| count[(y * w + x) as usize] += 1);
    }
    count
}

/// Independent reference in integers: coordinates are multiples of 1/256 (scaled by 256),
/// pixel centres multiples of 1/2. Inside when strictly inside every edge, or exactly on an
/// edge whose inward normal (a, b) has a > 0 or a = 0 and b > 0.
fn reference_inside(p: [(i64, i64); 3], s: (i64, i64)) -> bool {
    let orient = |a: (i64, i64), b: (i64, i64), c: (i64, i64)| {
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
    };
    let area = orient(p[0], p[1], p[2]);
    if area == 0 {
        return false;
    }
    let sign = area.signum();
    for k in 0..3 {
        let (a, b) = (p[(k + 1) % 3], p[(k + 2) % 3]);
        let e = orient(a, b, s) * sign;
        let normal = ((a.1 - b.1) * sign, (b.0 - a.0) * sign);
        if e < 0 || (e == 0 && !(normal.0 > 0 || (normal.0 == 0 && normal.1 > 0))) {
            return false;
        }
    }
    true
}

fn coord() -> impl Strategy<Value = i64> {
    // Mostly on a coarse grid (so vertices and edges hit pixel centres exactly), sometimes fine.
    prop_oneof![(0i64..=32).prop_map(|k| k * 128), -256i64..=8448]
}

/// The weighted mean of `t` along `uv0` -> `uv1` (weight linear from `w0` to `w1`, both
/// positive), independent of the texture's own stepping: every parameter where the
/// texel-space segment meets an integer column or row is enumerated, and each piece
/// between two of them (inside one bilinear cell, where the weighted blend is a cubic)
/// takes Simpson's rule on point samples ([`Texture::sample`]).
fn piecewise_simpson(t: &Texture, uv0: DVec2, uv1: DVec2, w0: f64, w1: f64) -> [f64; 4] {
    let (w, h) = (f64::from(t.width()), f64::from(t.height()));
    let texel = |uv: DVec2| [uv.x * w - 0.5, (1.0 - uv.y) * h - 0.5];
    let (a, b) = (texel(uv0), texel(uv1));
    let mut cuts = vec![0.0, 1.0];
    for k in 0..2 {
        let (lo, hi) = (a[k].min(b[k]), a[k].max(b[k]));
        let mut border = lo.floor() + 1.0;
        while border < hi {
            cuts.push((border - a[k]) / (b[k] - a[k]));
            border += 1.0;
        }
    }
    cuts.sort_by(f64::total_cmp);
    let weight = |s: f64| w0 + (w1 - w0) * s;
    let mut sum = [0.0; 4];
    for pair in cuts.windows(2) {
        let (sa, sb) = (pair[0], pair[1]);
        let step = (sb - sa) / 6.0;
        for (s, f) in [(sa, step), (0.5 * (sa + sb), 4.0 * step), (sb, step)] {
            let c = t.sample(uv0 + (uv1 - uv0) * s);
            for (acc, c) in sum.iter_mut().zip(c) {
                *acc += f * weight(s) * c;
            }
        }
    }
    sum.map(|v| v / (0.5 * (w0 + w1)))
}

/// A texture of `w` x `h` texels in blocks of `bx` x `by` texels, each block one of three
/// colours exact in f32 (picked by `picks`): flat regions of several sizes and colours.
fn blocky_texture(w: u32, h: u32, (bx, by): (u32, u32), picks: &[u8]) -> Texture {
    let palette = [
        [0.5, 0.25, 0.75, 1.0],
        [0.125, 0.625, 0.375, 0.5],
        [1.0, 0.0, 0.25, 1.0],
    ];
    let texels = (0..w * h)
        .map(|i| {
            let block = ((i / w) / by) * w.div_ceil(bx) + (i % w) / bx;
            palette[usize::from(picks[block as usize % picks.len()]) % 3]
        })
        .collect();
    Texture::from_straight(w, h, texels)
}

proptest! {
    /// The exact segment average, which crosses flat regions of decoded textures in one
    /// step per flat box, against [`piecewise_simpson`]; segments of any direction and up
    /// to ~100 cells long, some running exactly along a texel row's border.
    #[test]
    fn segment_average_matches_piecewise_simpson(
        size in (1u32..48, 1u32..48),
        blocks in (1u32..12, 1u32..12),
        picks in prop::collection::vec(0u8..3, 1..40),
        uv0 in (-2.0f64..2.0, -2.0f64..2.0),
        d in (-1.5f64..1.5, -1.5f64..1.5),
        on_row in prop::option::of(-60i32..60),
        weights in (0.1f64..2.0, 0.1f64..2.0),
    ) {
        let t = blocky_texture(size.0, size.1, blocks, &picks);
        let (mut uv0, mut uv1) = (DVec2::new(uv0.0, uv0.1), DVec2::new(uv0.0 + d.0, uv0.1 + d.1));
        if let Some(k) = on_row {
            // Texel-space y = k exactly: along the border between two texel rows.
            let v = 1.0 - (f64::from(k) + 0.5) / f64::from(size.1);
            (uv0.y, uv1.y) = (v, v);
        }
        let got = t.segment_average(uv0, uv1, weights.0, weights.1);
        let want = piecewise_simpson(&t, uv0, uv1, weights.0, weights.1);
        for k in 0..4 {
            prop_assert!((got[k] - want[k]).abs() <= 1e-9, "{:?} vs {:?}", got, want);
        }
    }

    #[test]
    fn coverage_matches_integer_reference(pts in prop::array::uniform3((coord(), coord()))) {
        let (w, h) = (32u32, 32u32);
        let p = pts.map(|(x, y)| DVec2::new(x as f64 / 256.0, y as f64 / 256.0));
        let got = coverage(p, w, h);
        for y in 0..h {
            for x in 0..w {
                let s = (i64::from(x) * 256 + 128, i64::from(y) * 256 + 128);
                let expect = u32::from(reference_inside(pts, s));
                prop_assert_eq!(got[(y * w + x) as usize], expect, "pixel ({}, {})", x, y);
            }
        }
    }

    #[test]
    fn triangulated_polygon_fan_covers_each_centre_once(
        centre in (coord(), coord()),
        ring in prop::collection::vec((1u32..=12, 0u32..64), 5..12),
    ) {
        // A star-shaped polygon around `centre`, fanned from the centre: every pixel centre
        // strictly inside the polygon's interior triangles must be covered exactly once, and
        // pixel centres on shared spokes must not be covered twice.
        let (w, h) = (32u32, 32u32);
        let c = DVec2::new(centre.0 as f64 / 256.0, centre.1 as f64 / 256.0);
        let n = ring.len();
        let pts: Vec<DVec2> = ring
            .iter()
            .enumerate()
            .map(|(k, &(r, jitter))| {
                let a = std::f64::consts::TAU * (k as f64 + jitter as f64 / 128.0) / n as f64;
                (c + DVec2::new(a.cos(), a.sin()) * f64::from(r) * 2.0).round()
            })
            .collect();
        // Rounding the ring to whole pixels can fold the fan (two spokes swap their angular
        // order, or a triangle collapses); then its triangles overlap and a centre may be
        // covered twice legitimately. Keep only fans whose triangles all turn one way and
        // wind around the centre once.
        let turns: Vec<f64> = (0..n)
            .map(|k| {
                let (a, b) = (pts[k] - c, pts[(k + 1) % n] - c);
                a.perp_dot(b).atan2(a.dot(b))
            })
            .collect();
        let winds_once = (turns.iter().sum::<f64>() - std::f64::consts::TAU).abs() < 1e-6;
        prop_assume!(turns.iter().all(|&t| t > 0.0) && winds_once);
        let mut total = vec![0u32; (w * h) as usize];
        for k in 0..n {
            let cov = coverage([c, pts[k], pts[(k + 1) % n]], w, h);
            for (t, v) in total.iter_mut().zip(cov) {
                *t += v;
            }
        }
        prop_assert!(total.iter().all(|&v| v <= 1), "a centre covered twice");
    }

    #[test]
    fn accum_moving_edge_within_one_stratum_of_exact(x0 in -4.0f64..4.0, dx in 0.5f64..12.0, n in 8u32..64) {
        // A white slab whose right edge moves from x0 to x0 + dx (pixel units from the image
        // centre) over a box shutter: exact value 1 - (c - x0) / dx clamped to [0, 1].
        let json = format!(
            r#"{{ "camera": {{ "width": 24, "height": 1, "projection": {{ "orthographic": {{ "height": 1 }} }},
                "eye": [0, 0, 10], "target": [0, 0, 0], "near": 1, "far": 100 }},
              "objects": [{{ "name": "s",
                "mesh": {{ "triangles": [[[-100, -5, 0], [0, -5, 0], [0, 5, 0]], [[-100, -5, 0], [0, 5, 0], [-100, 5, 0]]] }},
                "motion": {{ "open": {{ "translate": [{x0}, 0, 0] }}, "close": {{ "translate": [{}, 0, 0] }} }} }}] }}"#,
            x0 + dx
        );
        let s = Scene::from_json(&json, "p.json", ".").unwrap();
        let img = accum::render(&s.prepare().unwrap(), &AccumOptions { times: Some(n), jitter: None, ..Default::default() }, &NoProgress).unwrap();
        for i in 0..24u32 {
            let c = f64::from(i) + 0.5 - 12.0;
            let exact = (1.0 - (c - x0) / dx).clamp(0.0, 1.0);
            let got = f64::from(img.get(i, 0).unwrap()[0]);
            prop_assert!((got - exact).abs() <= 1.0 / f64::from(n) + 1e-6, "pixel {}: {} vs {}", i, got, exact);
        }
    }

    #[test]
    fn shutter_integral_is_additive(a in 0.0f64..1.0, b in 0.0f64..1.0, k in 0.0f64..1.0) {
        let (lo, hi) = (a.min(b), a.max(b));
        let mid = lo + (hi - lo) * k;
        let s = mblur::shutter::Shutter { open: 0.0, close: 1.0, points: vec![(0.0, 0.2), (0.3, 1.0), (0.8, 0.5), (1.0, 0.0)] };
        let whole = s.integral(lo, hi);
        let parts = s.integral(lo, mid) + s.integral(mid, hi);
        prop_assert!((whole - parts).abs() <= 1e-12 * whole.abs().max(1e-3));
    }
}
