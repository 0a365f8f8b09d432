//! Shared generators and helpers for the resolve integration tests.
#![allow(dead_code)]

use interval_buffer::{Interval, Rgba};
use proptest::prelude::*;
use resolve::Shutter;

pub type Flat64 = Interval<f64, Rgba<f64>>;

/// A flat interval from its parameters and a straight-alpha colour.
pub fn flat(ts: f64, te: f64, z: f64, k: f64, c: [f64; 4]) -> Flat64 {
    Interval::new(ts, te, z, k, Rgba::new(c[0], c[1], c[2], c[3]))
}

/// A time that is often on a coarse grid (coincident starts, ends and crossings).
pub fn time() -> impl Strategy<Value = f64> {
    prop_oneof![0.0..=1.0_f64, (0..=8u32).prop_map(|i| f64::from(i) / 8.0)]
}

/// A depth slope that is often zero or on a grid (parallel lines, exact ties).
pub fn slope() -> impl Strategy<Value = f64> {
    prop_oneof![-2.0..2.0_f64, (-4..=4i32).prop_map(|i| f64::from(i) / 2.0)]
}

/// A colour channel, sometimes exactly 0 or 1.
pub fn channel() -> impl Strategy<Value = f64> {
    prop_oneof![0.0..=1.0_f64, Just(0.0), Just(1.0)]
}

/// One interval with the hard-input generators above.
pub fn interval() -> impl Strategy<Value = Flat64> {
    (
        time(),
        time(),
        prop_oneof![0.0..4.0_f64, (0..=8u32).prop_map(|i| f64::from(i) / 2.0)],
        slope(),
        [channel(), channel(), channel(), channel()],
    )
        .prop_map(|(a, b, z, k, c)| flat(a.min(b), a.max(b), z, k, c))
}

/// Up to `n` intervals sorted by start time.
pub fn intervals(n: usize) -> impl Strategy<Value = Vec<Flat64>> {
    prop::collection::vec(interval(), 0..=n).prop_map(|mut v| {
        v.sort_by(|a, b| a.ts.total_cmp(&b.ts));
        v
    })
}

/// One of the named shutter responses.
pub fn shutter() -> impl Strategy<Value = Shutter<f64>> {
    prop_oneof![
        Just(Shutter::box_filter()),
        Just(Shutter::tent()),
        (0.0..0.5_f64, 0.0..0.5_f64).prop_map(|(o, c)| Shutter::trapezoid(o, c).unwrap()),
        Just(Shutter::from_points(&[(0.0, 1.0), (0.5, 1.0), (0.5, 0.0), (1.0, 0.0)]).unwrap()),
    ]
}

/// Largest channel difference.
pub fn max_diff(a: Rgba<f64>, b: Rgba<f64>) -> f64 {
    (a.r - b.r)
        .abs()
        .max((a.g - b.g).abs())
        .max((a.b - b.b).abs())
        .max((a.a - b.a).abs())
}

/// Bound on the number of colour changes over the shutter: starts, ends, every pair's
/// crossing and the shutter knots.
pub fn events(n: usize, shutter: &Shutter<f64>) -> f64 {
    (2 * n + n * n.saturating_sub(1) / 2 + shutter.knots().len() + 2) as f64
}

/// Tolerance of the dense-sampling reference with `samples` samples: each colour change
/// misplaces at most half a sample spacing, times max w / mean w.
pub fn sampling_tolerance(n: usize, shutter: &Shutter<f64>, samples: usize) -> f64 {
    let wmax = shutter.knots().iter().fold(0.0_f64, |m, k| m.max(k.1));
    events(n, shutter) * wmax / shutter.total() / samples as f64 + 1e-12
}

/// Exact reference for flat colours by exhaustive events: every start, end, shutter knot
/// and the crossing time of *every* pair of depth lines are cut points; between two cut
/// points nothing changes order, so the colour at the midpoint (alive intervals sorted by
/// depth c + k t with c = z - k ts — exact ties to the later list position — composited
/// front to back with the same early-termination rule, `threshold`, as the sweep) times
/// ∫ w over the piece is exact up to rounding. No sweep, no active list, no kinetic
/// structure: O(n²) pieces, O(n log n) each. `opaque`: the nearest at full opacity.
pub fn exhaustive_events(
    ivs: &[Flat64],
    shutter: &Shutter<f64>,
    background: Rgba<f64>,
    opaque: bool,
    threshold: f64,
) -> Rgba<f64> {
    let clamp = |t: f64| t.clamp(0.0, 1.0);
    let lines: Vec<(f64, f64)> = ivs.iter().map(|iv| (iv.z - iv.k * iv.ts, iv.k)).collect();
    let mut cuts: Vec<f64> = vec![0.0, 1.0];
    cuts.extend(shutter.knots().iter().map(|k| k.0));
    for iv in ivs {
        cuts.push(clamp(iv.ts));
        cuts.push(clamp(iv.te));
    }
    for (i, a) in lines.iter().enumerate() {
        for b in &lines[i + 1..] {
            if a.1 != b.1 {
                let tau = (b.0 - a.0) / (a.1 - b.1);
                if tau > 0.0 && tau < 1.0 {
                    cuts.push(tau);
                }
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let bg = background.premultiplied();
    let mut sum = [0.0; 4];
    let mut alive: Vec<(f64, usize)> = Vec::new();
    for piece in cuts.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        let w = shutter.integral(a, b);
        if w <= 0.0 {
            continue;
        }
        let t = 0.5 * (a + b);
        alive.clear();
        for (i, iv) in ivs.iter().enumerate() {
            if clamp(iv.ts) <= t && t < clamp(iv.te) {
                alive.push((lines[i].0 + lines[i].1 * t, i));
            }
        }
        alive.sort_by(|x, y| x.0.total_cmp(&y.0).then(y.1.cmp(&x.1)));
        let mut c = [0.0; 4];
        let mut transmittance = 1.0;
        for &(_, i) in &alive {
            let p = ivs[i].payload;
            let alpha = p.a.clamp(0.0, 1.0);
            if opaque {
                c = if alpha > 0.0 {
                    [p.r, p.g, p.b, 1.0]
                } else {
                    [0.0, 0.0, 0.0, 1.0]
                };
                transmittance = 0.0;
                break;
            }
            let layer = [alpha * p.r, alpha * p.g, alpha * p.b, alpha];
            for k in 0..4 {
                c[k] += transmittance * layer[k];
            }
            transmittance *= 1.0 - alpha;
            if transmittance <= threshold {
                break;
            }
        }
        if transmittance > threshold {
            for k in 0..4 {
                c[k] += transmittance * bg[k];
            }
        }
        for k in 0..4 {
            sum[k] += w * c[k];
        }
    }
    let total = shutter.total();
    let s = sum.map(|x| x / total);
    if s[3] > 0.0 {
        Rgba::new(s[0] / s[3], s[1] / s[3], s[2] / s[3], s[3])
    } else {
        Rgba::new(0.0, 0.0, 0.0, 0.0)
    }
}

/// `n_min..=n_max` intervals that all overlap the middle of the shutter ([0.4, 0.6] at
/// least), with grid-valued starts, ends, depths and slopes mixed in (simultaneous
/// crossings, coincident ends, exact ties), sorted by start.
pub fn dense_intervals(n_min: usize, n_max: usize) -> impl Strategy<Value = Vec<Flat64>> {
    let one = (
        prop_oneof![0.0..0.4_f64, (0..=3u32).prop_map(|i| f64::from(i) / 8.0)],
        prop_oneof![0.6..=1.0_f64, (5..=8u32).prop_map(|i| f64::from(i) / 8.0)],
        prop_oneof![0.0..4.0_f64, (0..=8u32).prop_map(|i| f64::from(i) / 2.0)],
        slope(),
        [channel(), channel(), channel(), channel()],
    )
        .prop_map(|(ts, te, z, k, c)| flat(ts, te, z, k, c));
    prop::collection::vec(one, n_min..=n_max).prop_map(|mut v| {
        v.sort_by(|a, b| a.ts.total_cmp(&b.ts));
        v
    })
}

/// The three sweep implementations.
pub const SWEEPS: [resolve::Sweep; 3] = [
    resolve::Sweep::Auto,
    resolve::Sweep::Kinetic,
    resolve::Sweep::ActiveList,
];
