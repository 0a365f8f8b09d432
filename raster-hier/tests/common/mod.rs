//! Shared helpers for the integration tests: triangle generators and the brute-force
//! reference (every sample of the image against every triangle, no tiles, no culling).
#![allow(dead_code)]

use edge_eqn::MovingTriangle;
use num_traits::Float;
use raster_hier::{
    EdgeTest, Footprint, NO_HIT, RasterConfig, RasterTriangle, SampleBuffer, Traversal, covered,
    rasterise,
};

/// Every traversal the crate offers.
pub const ALL: [Traversal; 11] = [
    Traversal::Bbox,
    Traversal::Convex,
    Traversal::Interleave,
    Traversal::Our(EdgeTest::LinearisedSetup),
    Traversal::Our(EdgeTest::LinearisedPerTile),
    Traversal::Our(EdgeTest::Exact),
    Traversal::Our(EdgeTest::LinearisedPerLevel),
    Traversal::Our(EdgeTest::ExactFinest),
    Traversal::OurFallback(EdgeTest::LinearisedSetup),
    Traversal::OurFallback(EdgeTest::LinearisedPerTile),
    Traversal::OurFallback(EdgeTest::Exact),
];

/// Traversal levels every traversal is checked with (bin 16, 4x4 pattern tiles): the
/// paper's 16 → 8 → 4, and levels below the pattern tile (2x2 quads, single pixels).
pub const LEVELS: [&[u32]; 3] = [&[16, 8, 4], &[16, 8, 4, 2], &[16, 8, 4, 2, 1]];

/// The reference: for each sample in storage order, (depth, id) after drawing all
/// triangles in order with LESS_EQUAL, testing every sample against every triangle whose
/// span holds the sample's time (in the triangle's whole-shutter form,
/// `RasterTriangle::over_shutter`, which is the triangle itself for a whole-shutter span).
pub fn brute_force<F: Float>(buf: &SampleBuffer<F>, tris: &[RasterTriangle<F>]) -> Vec<(F, u32)> {
    let setups: Vec<_> = tris
        .iter()
        .filter_map(|t| {
            let tri = t.triangle;
            let all_w = tri.q.iter().chain(tri.r.iter()).all(|v| v[2] > F::zero());
            Some((t.over_shutter()?.setup(), all_w, t.id, t.span))
        })
        .collect();
    let mut out = Vec::new();
    buf.for_each_sample(|_, _, x, y, t, _, _| {
        let mut best = (F::infinity(), NO_HIT);
        for (s, all_w, id, span) in &setups {
            if span.contains(t) && s.is_valid() && covered(s, *all_w, x, y, t) {
                // The depth function the rasteriser writes (edge-eqn's combined call; edge-eqn
                // tests it against `depth_at` and an f64 screen-space reference).
                let Some(d) = s.inside_depth_at(x, y, t) else {
                    continue;
                };
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
    render_levels(
        w,
        h,
        spp,
        tris,
        traversal,
        cull_backfaces,
        LEVELS[0],
        Footprint::Area,
    )
}

/// [`render`] with the given traversal levels (bin 16, 4x4 pattern tiles) and footprint.
#[allow(clippy::too_many_arguments)]
pub fn render_levels<F: Float + Send + Sync>(
    w: u32,
    h: u32,
    spp: u32,
    tris: &[RasterTriangle<F>],
    traversal: Traversal,
    cull_backfaces: bool,
    levels: &[u32],
    footprint: Footprint,
) -> (SampleBuffer<F>, raster_hier::Counters) {
    let mut buf = SampleBuffer::<F>::new(w, h, spp, 4, 16, 4, 11)
        .expect("valid buffer")
        .with_footprint(footprint);
    let mut cfg = RasterConfig::new(traversal);
    cfg.cull_backfaces = cull_backfaces;
    cfg.levels = levels.to_vec();
    let c = rasterise(&mut buf, tris, &cfg).expect("valid config");
    (buf, c)
}

/// Checks every traversal at every level configuration of [`LEVELS`] against the
/// brute-force reference, bit for bit; returns the counters per traversal at the paper's
/// levels 16 → 8 → 4.
pub fn check_all<F: Float + Send + Sync + core::fmt::Debug>(
    w: u32,
    h: u32,
    spp: u32,
    tris: &[RasterTriangle<F>],
) -> Vec<(Traversal, raster_hier::Counters)> {
    let mut all = check_levels(w, h, spp, tris);
    all.retain(|(levels, _, _)| levels.as_slice() == LEVELS[0]);
    all.into_iter().map(|(_, tr, c)| (tr, c)).collect()
}

/// Checks every traversal at every level configuration of [`LEVELS`] against the
/// brute-force reference, bit for bit; returns the counters per (levels, traversal).
pub fn check_levels<F: Float + Send + Sync + core::fmt::Debug>(
    w: u32,
    h: u32,
    spp: u32,
    tris: &[RasterTriangle<F>],
) -> Vec<(Vec<u32>, Traversal, raster_hier::Counters)> {
    check_levels_in(w, h, spp, tris, &LEVELS, Footprint::Area)
}

/// Checks every traversal at each of `configs` (levels) against the brute-force reference,
/// bit for bit, with samples placed by `footprint`; returns the counters per (levels,
/// traversal).
pub fn check_levels_in<F: Float + Send + Sync + core::fmt::Debug>(
    w: u32,
    h: u32,
    spp: u32,
    tris: &[RasterTriangle<F>],
    configs: &[&[u32]],
    footprint: Footprint,
) -> Vec<(Vec<u32>, Traversal, raster_hier::Counters)> {
    let probe = SampleBuffer::<F>::new(w, h, spp, 4, 16, 4, 11)
        .expect("valid buffer")
        .with_footprint(footprint);
    let reference = brute_force(&probe, tris);
    let mut out = Vec::new();
    for &levels in configs {
        for tr in ALL {
            let (buf, c) = render_levels(w, h, spp, tris, tr, false, levels, footprint);
            let got = contents(&buf);
            assert_eq!(got.len(), reference.len());
            for (i, (g, r)) in got.iter().zip(&reference).enumerate() {
                assert!(
                    g.1 == r.1 && (g.0 == r.0 || (g.0.is_nan() && r.0.is_nan())),
                    "{tr:?} {levels:?}: sample {i} got {g:?} want {r:?}"
                );
                assert!(!g.0.is_nan(), "NaN depth at sample {i}");
            }
            out.push((levels.to_vec(), tr, c));
        }
    }
    out
}

/// A triangle from f64 data, in F.
pub fn tri<F: Float>(q: [[f64; 3]; 3], r: [[f64; 3]; 3], id: u32) -> RasterTriangle<F> {
    let c = |v: [[f64; 3]; 3]| v.map(|p| p.map(|x| F::from(x).unwrap_or_else(F::zero)));
    RasterTriangle::whole(MovingTriangle::new(c(q), c(r)), id)
}

/// A random moving triangle of one of several kinds (general, crossing w = 0, sliver,
/// static, small and fast, pure translation, large, collapsing: vertex 2 ends mirrored
/// across the line of vertices 0 and 1, so the triangle degenerates to a segment and flips
/// during the shutter), in f64, for a `size` x `size` screen.
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
        7 => {
            // Collapsing: mirror vertex 2's close position (in screen space) across the line
            // of vertices 0 and 1 at close; det(t) then has a root inside the shutter.
            let (a, b, c) = (r[0], r[1], r[2]);
            let pr = |p: [f64; 3]| [p[0] / p[2], p[1] / p[2]];
            let (a, b, c, w) = (pr(a), pr(b), pr(c), c[2]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let len2 = d[0] * d[0] + d[1] * d[1];
            if len2 > 0.0 {
                let s = ((c[0] - a[0]) * d[0] + (c[1] - a[1]) * d[1]) / len2;
                let foot = [a[0] + s * d[0], a[1] + s * d[1]];
                let m = [2.0 * foot[0] - c[0], 2.0 * foot[1] - c[1]];
                r[2] = [m[0] * w, m[1] * w, w];
            }
        }
        _ => {}
    }
    (q, r)
}

/// What an f64 evaluation with a forward error bound says about one (sample, time) pair of
/// a moving triangle: the independent reference for "is this sample covered".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Certainty {
    /// Every edge function has the same sign by more than its error bound (and, when some
    /// w <= 0, the hit point is in front of the eye by more than the bound).
    Covered,
    /// Two edges have opposite signs by more than their error bounds, or the hit point is
    /// certainly behind the eye: no rounding of any inside test at this point is real
    /// coverage.
    NotCovered,
    /// Within the error bounds.
    Uncertain,
    /// The triangle is degenerate at t (its 2DH determinant is zero within its error bound)
    /// and the point is not provably outside: the inside rule (all e ≤ 0 or all e ≥ 0) then
    /// holds on the whole line through the collapsed triangle, also far outside it — an
    /// instant of zero area, not coverage that a tile bound must contain.
    Degenerate,
}

/// The coverage of (x, y) at time t by the triangle with 2DH vertices `q` (open) and `r`
/// (close), evaluated in f64 directly from the vertices (not from any crate's edge setup):
/// p_i(t) = q_i + t (r_i − q_i), e_k = (p_{k+2} × p_{k+1}) · (x, y, 1), with a forward error
/// bound of 64 ε₆₄ times the sum of the magnitudes of the products (|q_i| + |r_i| bound
/// |p_i(t)|). Pass the vertices, point and time as the rasteriser sees them (e.g. the f32
/// values widened to f64), so the reference is the triangle actually rasterised.
pub fn certainty_f64(q: [[f64; 3]; 3], r: [[f64; 3]; 3], x: f64, y: f64, t: f64) -> Certainty {
    let p: [[f64; 3]; 3] =
        core::array::from_fn(|i| core::array::from_fn(|c| q[i][c] + t * (r[i][c] - q[i][c])));
    let m: [[f64; 3]; 3] =
        core::array::from_fn(|i| core::array::from_fn(|c| q[i][c].abs() + r[i][c].abs()));
    let s = [x, y, 1.0];
    let sa = [x.abs(), y.abs(), 1.0];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let cross_mag = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] + a[2] * b[1],
            a[2] * b[0] + a[0] * b[2],
            a[0] * b[1] + a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let tol = 64.0 * f64::EPSILON;
    // Sign of each edge: +1 / -1 when certain, 0 when within the bound.
    let sign = |v: f64, bound: f64| {
        if v > bound {
            1i8
        } else if v < -bound {
            -1
        } else {
            0
        }
    };
    let mut e = [0.0; 3];
    let mut sg = [0i8; 3];
    for k in 0..3 {
        let (a, b) = (p[(k + 2) % 3], p[(k + 1) % 3]);
        e[k] = dot(cross(a, b), s);
        sg[k] = sign(
            e[k],
            tol * dot(cross_mag(m[(k + 2) % 3], m[(k + 1) % 3]), sa),
        );
    }
    if sg.contains(&1) && sg.contains(&-1) {
        return Certainty::NotCovered;
    }
    let det = dot(p[0], cross(p[1], p[2]));
    let det_bound = tol * dot(m[0], cross_mag(m[1], m[2]));
    if det.abs() <= det_bound {
        return Certainty::Degenerate;
    }
    let all_w = q.iter().chain(r.iter()).all(|v| v[2] > 0.0);
    if !all_w {
        // In front when det and the edge sum have opposite signs (μ = −det / Σe > 0).
        let sum_bound: f64 = (0..3)
            .map(|k| tol * dot(cross_mag(m[(k + 2) % 3], m[(k + 1) % 3]), sa))
            .sum();
        let (sd, ss) = (sign(det, det_bound), sign(e.iter().sum(), sum_bound));
        if sd != 0 && ss != 0 && sd == ss {
            return Certainty::NotCovered;
        }
        if sd == 0 || ss == 0 {
            return Certainty::Uncertain;
        }
    }
    if sg.contains(&0) {
        Certainty::Uncertain
    } else {
        Certainty::Covered
    }
}

/// The 2DH orientation det[p₀(t); p₁(t); p₂(t)] of the triangle moving linearly from `q`
/// (t = 0) to `r` (t = 1), evaluated independently of raster-hier's Bernstein form: the
/// vertices interpolated at t in f64 and the determinant by the rule of Sarrus. Returns the
/// value and the permanent of the interpolated magnitudes (the size of its terms); the
/// rounding of both steps is within `16 ε` times that permanent.
pub fn orientation_at(q: &[[f64; 3]; 3], r: &[[f64; 3]; 3], t: f64) -> (f64, f64) {
    let p = [0, 1, 2].map(|i| [0, 1, 2].map(|k| (1.0 - t) * q[i][k] + t * r[i][k]));
    let a = [0, 1, 2]
        .map(|i| [0, 1, 2].map(|k| (1.0 - t).abs() * q[i][k].abs() + t.abs() * r[i][k].abs()));
    let sarrus = |p: &[[f64; 3]; 3], s: f64| {
        p[0][0] * p[1][1] * p[2][2]
            + p[0][1] * p[1][2] * p[2][0]
            + p[0][2] * p[1][0] * p[2][1]
            + s * (p[0][2] * p[1][1] * p[2][0]
                + p[0][0] * p[1][2] * p[2][1]
                + p[0][1] * p[1][0] * p[2][2])
    };
    (sarrus(&p, -1.0), sarrus(&a, 1.0))
}

/// What [`check_facing_windows`] found at the sampled instants.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WindowCheck {
    /// Instants at which the reference proves the triangle shows a winding other than the
    /// hidden one but which no window holds (must be zero).
    pub misses: u32,
    /// Instants proved hidden by more than 10⁻³ of the size of the terms.
    pub clearly_hidden: u32,
    /// Of those, the ones a window keeps.
    pub kept: u32,
    /// Largest distance from a kept clearly hidden instant to the nearest instant that is
    /// not clearly hidden (0 when none is kept).
    pub kept_reach: f64,
}

/// [`raster_hier::facing_windows`] for input type `F` against [`orientation_at`] at `n + 1`
/// equally spaced instants of [0, 1], on the triangle exactly as `F` holds it.
pub fn check_facing_windows<F: Float>(
    q: [[f64; 3]; 3],
    r: [[f64; 3]; 3],
    hidden: raster_hier::Facing,
    n: u32,
) -> WindowCheck {
    let f = |v: f64| F::from(v).unwrap_or_else(F::zero);
    let (qf, rf) = (q.map(|p| p.map(f)), r.map(|p| p.map(f)));
    let w = |v: F| v.to_f64().unwrap_or(f64::NAN);
    let (q, r) = (qf.map(|p| p.map(w)), rf.map(|p| p.map(w)));
    let windows = raster_hier::facing_windows(&qf, &rf, hidden);
    let sign = match hidden {
        raster_hier::Facing::Front => 1.0,
        raster_hier::Facing::Back => -1.0,
        raster_hier::Facing::Mixed => 0.0,
    };
    let mut c = WindowCheck::default();
    let ts: Vec<f64> = (0..=n).map(|i| f64::from(i) / f64::from(n)).collect();
    let clear: Vec<bool> = ts
        .iter()
        .map(|&t| {
            let (d, m) = orientation_at(&q, &r, t);
            sign * d > 1e-3 * m
        })
        .collect();
    let others: Vec<f64> = ts
        .iter()
        .zip(&clear)
        .filter(|(_, c)| !**c)
        .map(|(t, _)| *t)
        .collect();
    for (&t, &is_clear) in ts.iter().zip(&clear) {
        let (d, m) = orientation_at(&q, &r, t);
        let shown = sign == 0.0 || sign * d < -16.0 * f64::EPSILON * m;
        if shown && !windows.contains(t) {
            c.misses += 1;
        }
        if is_clear {
            c.clearly_hidden += 1;
            if windows.contains(t) {
                c.kept += 1;
                let reach = others
                    .iter()
                    .map(|o| (o - t).abs())
                    .fold(f64::INFINITY, f64::min);
                c.kept_reach = c.kept_reach.max(reach);
            }
        }
    }
    c
}
