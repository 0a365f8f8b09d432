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
