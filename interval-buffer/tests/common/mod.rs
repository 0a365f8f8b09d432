//! Shared test/bench helpers: a brute-force reference resolve and seeded workloads.
//!
//! The reference is a test oracle, not production code: it samples N evenly spaced times and
//! takes, at each, the nearest alive opaque interval (later in the list wins an exact tie),
//! or the background.
#![allow(dead_code)]

use interval_buffer::{Interval, Rgba};
use rand::{Rng, RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// An interval with an f64 flat colour.
pub type Iv = Interval<f64, Rgba<f64>>;

/// Brute-force opaque resolve over `n` midpoint samples of [0, 1].
pub fn resolve_opaque<F: num_traits::Float>(
    list: &[Interval<F, Rgba<F>>],
    bg: [f64; 3],
    n: usize,
) -> [f64; 3] {
    let f = |v: F| v.to_f64().unwrap_or(f64::NAN);
    let mut acc = [0.0; 3];
    for s in 0..n {
        let t = (s as f64 + 0.5) / n as f64;
        let mut best: Option<(f64, [f64; 3])> = None;
        for iv in list {
            if f(iv.ts) <= t && t <= f(iv.te) {
                let d = f(iv.z) + f(iv.k) * (t - f(iv.ts));
                if best.is_none_or(|(bd, _)| d <= bd) {
                    best = Some((d, [f(iv.payload.r), f(iv.payload.g), f(iv.payload.b)]));
                }
            }
        }
        let c = best.map_or(bg, |(_, c)| c);
        for k in 0..3 {
            acc[k] += c[k];
        }
    }
    acc.map(|a| a / n as f64)
}

/// Brute-force blending resolve over `n` midpoint samples: at each time the alive intervals
/// are composited back to front with straight-alpha "over" onto the background (equal depth:
/// later in the list is nearer). Equals [`resolve_opaque`] for opaque lists.
pub fn resolve_blend<F: num_traits::Float>(
    list: &[Interval<F, Rgba<F>>],
    bg: [f64; 3],
    n: usize,
) -> [f64; 3] {
    let f = |v: F| v.to_f64().unwrap_or(f64::NAN);
    let mut acc = [0.0; 3];
    let mut alive: Vec<(f64, usize)> = Vec::new();
    for s in 0..n {
        let t = (s as f64 + 0.5) / n as f64;
        alive.clear();
        for (i, iv) in list.iter().enumerate() {
            if f(iv.ts) <= t && t <= f(iv.te) {
                alive.push((f(iv.z) + f(iv.k) * (t - f(iv.ts)), i));
            }
        }
        // Far first; for equal depth the earlier list entry is drawn first.
        alive.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let mut c = bg;
        for &(_, i) in &alive {
            let p = list[i].payload;
            let a = f(p.a).clamp(0.0, 1.0);
            let col = [f(p.r), f(p.g), f(p.b)];
            for k in 0..3 {
                c[k] = c[k] * (1.0 - a) + col[k] * a;
            }
        }
        for k in 0..3 {
            acc[k] += c[k];
        }
    }
    acc.map(|a| a / n as f64)
}

/// Mean absolute RGB difference.
pub fn colour_error(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).sum::<f64>() / 3.0
}

/// Seeded generator.
pub fn rng(seed: u64) -> Pcg64 {
    Pcg64::seed_from_u64(seed)
}

fn colour<R: Rng>(r: &mut R) -> Rgba<f64> {
    Rgba::opaque(r.random::<f64>(), r.random::<f64>(), r.random::<f64>())
}

/// Independent random intervals (uncorrelated small triangles): random ts, lengths in
/// [0.01, 0.25], depth in [1, 10], slope in [-2, 2], random colour.
pub fn random_intervals<R: Rng>(r: &mut R, n: usize) -> Vec<Iv> {
    (0..n)
        .map(|_| {
            let ts = r.random::<f64>() * 0.95;
            let te = (ts + r.random_range(0.01..0.25)).min(1.0);
            Interval::new(
                ts,
                te,
                r.random_range(1.0..10.0),
                r.random_range(-2.0..2.0),
                colour(r),
            )
        })
        .collect()
}

/// Moving meshes of small triangles crossing a pixel: 2-5 objects, each crossing during a
/// random span tiled by 5-30 consecutive intervals that lie on the object's depth line
/// (plus a small per-triangle offset) with colours jittered around the object's colour.
/// Triangles of one object arrive in mesh order, unrelated to time order.
pub fn moving_meshes<R: Rng>(r: &mut R) -> Vec<Iv> {
    let mut out = Vec::new();
    let objects = r.random_range(2..=5);
    for _ in 0..objects {
        let a = r.random::<f64>() * 0.7;
        let b = (a + r.random_range(0.1..0.6)).min(1.0);
        let z0 = r.random_range(1.0..10.0);
        let k = r.random_range(-3.0..3.0);
        let base = colour(r);
        let m = r.random_range(5..=30);
        let mut cuts: Vec<f64> = (0..m - 1).map(|_| r.random_range(a..b)).collect();
        cuts.push(a);
        cuts.push(b);
        cuts.sort_by(|p, q| p.total_cmp(q));
        let mut pieces: Vec<Iv> = cuts
            .windows(2)
            .map(|w| {
                let dz = r.random_range(-0.02..0.02);
                let j = |c: f64, r: &mut R| (c + r.random_range(-0.1..0.1)).clamp(0.0, 1.0);
                let c = Rgba::opaque(j(base.r, r), j(base.g, r), j(base.b, r));
                Interval::new(w[0], w[1], z0 + k * w[0] + dz, k, c)
            })
            .collect();
        // Mesh order: a random permutation.
        for i in (1..pieces.len()).rev() {
            let j = r.random_range(0..=i);
            pieces.swap(i, j);
        }
        out.extend(pieces);
    }
    out
}

/// The fence pattern (Gribel 2010, Fig. 11): a static background interval over [0, 1] at
/// depth 10, then `periods` white foreground intervals of half a period each at depth 1,
/// a square wave of foreground and background over time.
pub fn fence(periods: usize, bg: Rgba<f64>) -> Vec<Iv> {
    let mut out = vec![Interval::new(0.0, 1.0, 10.0, 0.0, bg)];
    let p = periods.max(1) as f64;
    for i in 0..periods {
        let ts = i as f64 / p;
        out.push(Interval::new(
            ts,
            ts + 0.5 / p,
            1.0,
            0.0,
            Rgba::opaque(1.0, 1.0, 1.0),
        ));
    }
    out
}
