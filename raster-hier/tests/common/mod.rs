//! Shared helpers for the integration tests: triangle generators and the brute-force
//! reference (every sample of the image against every triangle, no tiles, no culling).
#![allow(dead_code)]

use edge_eqn::MovingTriangle;
use num_traits::Float;
use raster_hier::{
    EdgeTest, NO_HIT, RasterConfig, RasterTriangle, SampleBuffer, Traversal, covered, rasterise,
};

/// Every traversal the crate offers.
pub const ALL: [Traversal; 9] = [
    Traversal::Bbox,
    Traversal::Convex,
    Traversal::Interleave,
    Traversal::Our(EdgeTest::LinearisedSetup),
    Traversal::Our(EdgeTest::LinearisedPerTile),
    Traversal::Our(EdgeTest::Exact),
    Traversal::OurFallback(EdgeTest::LinearisedSetup),
    Traversal::OurFallback(EdgeTest::LinearisedPerTile),
    Traversal::OurFallback(EdgeTest::Exact),
];

/// The reference: for each sample in storage order, (depth, id) after drawing all
/// triangles in order with LESS_EQUAL, testing every sample against every triangle.
pub fn brute_force<F: Float>(buf: &SampleBuffer<F>, tris: &[RasterTriangle<F>]) -> Vec<(F, u32)> {
    let setups: Vec<_> = tris
        .iter()
        .map(|t| {
            let tri = t.triangle;
            let all_w = tri.q.iter().chain(tri.r.iter()).all(|v| v[2] > F::zero());
            (tri.setup(), all_w, t.id)
        })
        .collect();
    let mut out = Vec::new();
    buf.for_each_sample(|_, _, x, y, t, _, _| {
        let mut best = (F::infinity(), NO_HIT);
        for (s, all_w, id) in &setups {
            if s.is_valid() && covered(s, *all_w, x, y, t) {
                let d = s.depth_at(x, y, t);
                if d <= best.0 {
                    best = (d, *id);
                }
            }
        }
        out.push(best);
    });
    out
}

/// The buffer's samples in the same order as `brute_force`.
pub fn contents<F: Float>(buf: &SampleBuffer<F>) -> Vec<(F, u32)> {
    let mut out = Vec::new();
    buf.for_each_sample(|_, _, _, _, _, d, id| out.push((d, id)));
    out
}

/// Rasterises with `traversal` into a fresh buffer (16/8/4 levels) and returns it with the counters.
pub fn render<F: Float + Send + Sync>(
    w: u32,
    h: u32,
    spp: u32,
    tris: &[RasterTriangle<F>],
    traversal: Traversal,
    cull_backfaces: bool,
) -> (SampleBuffer<F>, raster_hier::Counters) {
    let mut buf = SampleBuffer::<F>::new(w, h, spp, 4, 16, 4, 11).expect("valid buffer");
    let mut cfg = RasterConfig::new(traversal);
    cfg.cull_backfaces = cull_backfaces;
    let c = rasterise(&mut buf, tris, &cfg).expect("valid config");
    (buf, c)
}

/// Checks every traversal against the brute-force reference, bit for bit; returns the
/// counters per traversal.
pub fn check_all<F: Float + Send + Sync + core::fmt::Debug>(
    w: u32,
    h: u32,
    spp: u32,
    tris: &[RasterTriangle<F>],
) -> Vec<(Traversal, raster_hier::Counters)> {
    let probe = SampleBuffer::<F>::new(w, h, spp, 4, 16, 4, 11).expect("valid buffer");
    let reference = brute_force(&probe, tris);
    let mut out = Vec::new();
    for tr in ALL {
        let (buf, c) = render(w, h, spp, tris, tr, false);
        let got = contents(&buf);
        assert_eq!(got.len(), reference.len());
        for (i, (g, r)) in got.iter().zip(&reference).enumerate() {
            assert!(
                g.1 == r.1 && (g.0 == r.0 || (g.0.is_nan() && r.0.is_nan())),
                "{tr:?}: sample {i} got {g:?} want {r:?}"
            );
            assert!(!g.0.is_nan(), "NaN depth at sample {i}");
        }
        out.push((tr, c));
    }
    out
}

/// A triangle from f64 data, in F.
pub fn tri<F: Float>(q: [[f64; 3]; 3], r: [[f64; 3]; 3], id: u32) -> RasterTriangle<F> {
    let c = |v: [[f64; 3]; 3]| v.map(|p| p.map(|x| F::from(x).unwrap_or_else(F::zero)));
    RasterTriangle {
        triangle: MovingTriangle::new(c(q), c(r)),
        id,
    }
}

/// A random moving triangle of one of several kinds (general, crossing w = 0, sliver,
/// static, small and fast, pure translation, large), in f64, for a `size` x `size` screen.
/// Vertices are given in 2DH, (X w, Y w, w) for screen position (X, Y).
pub fn random_triangle<R: rand::RngExt>(rng: &mut R, size: f64) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    let kind = rng.random_range(0..8u32);
    let m = size * 0.75;
    let mut q = [[0.0; 3]; 3];
    let mut r = [[0.0; 3]; 3];
    let (spread, motion) = match kind {
        4 => (1.5, size * 2.0),        // small and fast
        6 => (size * 1.5, size * 0.3), // large
        _ => (size * 0.4, m),
    };
    let cx = rng.random_range(-0.2 * size..1.2 * size);
    let cy = rng.random_range(-0.2 * size..1.2 * size);
    let shift = [
        rng.random_range(-motion..motion),
        rng.random_range(-motion..motion),
    ];
    for i in 0..3 {
        let (x, y) = (
            cx + rng.random_range(-spread..spread),
            cy + rng.random_range(-spread..spread),
        );
        let w0 = rng.random_range(0.5..2.0);
        let (x1, y1) = match kind {
            5 => (x + shift[0], y + shift[1]),
            _ => (
                x + shift[0] + rng.random_range(-motion..motion) * 0.3,
                y + shift[1] + rng.random_range(-motion..motion) * 0.3,
            ),
        };
        let w1 = if kind == 5 {
            w0
        } else {
            rng.random_range(0.5..2.0)
        };
        q[i] = [x * w0, y * w0, w0];
        r[i] = [x1 * w1, y1 * w1, w1];
    }
    match kind {
        1 => {
            // Crossing w = 0: one or two vertices get a w of the other sign at one end.
            let k = rng.random_range(0..3usize);
            let w = rng.random_range(-1.5..-0.05);
            if rng.random_bool(0.5) {
                r[k][2] = w
            } else {
                q[k][2] = w
            }
            if rng.random_bool(0.3) {
                let j = (k + 1) % 3;
                r[j][2] = rng.random_range(-1.0..0.3);
            }
        }
        2 => {
            // Sliver: vertex 2 within 0.05 px of the segment 0-1 (in screen space).
            for p in [&mut q, &mut r] {
                let s = rng.random_range(0.0..1.0);
                let (a, b) = (p[0], p[1]);
                let (ax, ay, bx, by) = (a[0] / a[2], a[1] / a[2], b[0] / b[2], b[1] / b[2]);
                let w = p[2][2];
                let x = ax + s * (bx - ax) + rng.random_range(-0.05..0.05);
                let y = ay + s * (by - ay) + rng.random_range(-0.05..0.05);
                p[2] = [x * w, y * w, w];
            }
        }
        3 => r = q,
        _ => {}
    }
    (q, r)
}
