//! The brute-force ground truth the sweep is tested and benchmarked against.

use interval_buffer::{Interval, Rgba};
use num_traits::Float;

use crate::bilinear::unpremultiply;
use crate::{Blend, Settings, Shader};

/// The pixel colour by dense point sampling of the shutter: at `samples` evenly spaced times
/// t_i = (i + ½) / samples, sort the intervals alive at t_i (ts <= t_i < te) by their depth
/// z + k (t_i - ts), composite them front to back (no early termination), and average with
/// the shutter weights w(t_i).
///
/// Independent of the sweep: no events, no crossing times, no partitions. Opaque blending
/// shows the nearest interval at full opacity, like [`Blend::Opaque`]. Exact depth ties go
/// to the later list position (the sweep's `LESS_EQUAL` rule). The error against the exact
/// Eq. 17 is at most about (number of colour changes over time) / `samples` for colours in
/// [0, 1], so tolerances shrink with the sample count.
pub fn brute_force<F: Float, P, S: Shader<F, P>>(
    intervals: &[Interval<F, P>],
    shader: &S,
    settings: &Settings<F>,
    samples: usize,
) -> Rgba<F> {
    let (zero, one) = (F::zero(), F::one());
    let half = one / (one + one);
    let n = F::from(samples.max(1)).unwrap_or_else(F::one);
    let background = settings.background.premultiplied();
    let mut alive: Vec<(F, usize)> = Vec::new();
    let mut sum = [zero; 4];
    let mut weights = zero;
    for i in 0..samples.max(1) {
        let t = (F::from(i).unwrap_or_else(F::zero) + half) / n;
        let w = settings.shutter.weight(t);
        if w <= zero {
            continue;
        }
        alive.clear();
        for (index, iv) in intervals.iter().enumerate() {
            if iv.ts <= t && t < iv.te {
                alive.push((iv.depth_at(t), index));
            }
        }
        alive.sort_by(|a, b| {
            a.0.partial_cmp(&b.0)
                .unwrap_or(std::cmp::Ordering::Equal)
                .then(b.1.cmp(&a.1))
        });
        let mut colour = [zero; 4];
        let mut transmittance = one;
        for &(_, index) in &alive {
            let Some(iv) = intervals.get(index) else {
                continue;
            };
            let c = shader.shade_at(iv, t);
            if let Blend::Opaque = settings.blend {
                colour = if c[3] > zero {
                    [c[0] / c[3], c[1] / c[3], c[2] / c[3], one]
                } else {
                    [zero, zero, zero, one]
                };
                transmittance = zero;
                break;
            }
            for (acc, c) in colour.iter_mut().zip(c) {
                *acc = *acc + transmittance * c;
            }
            transmittance = transmittance * (one - c[3].max(zero).min(one));
        }
        for (acc, b) in colour.iter_mut().zip(background) {
            *acc = *acc + transmittance * b;
        }
        for (acc, c) in sum.iter_mut().zip(colour) {
            *acc = *acc + w * c;
        }
        weights = weights + w;
    }
    if weights > zero {
        unpremultiply([
            sum[0] / weights,
            sum[1] / weights,
            sum[2] / weights,
            sum[3] / weights,
        ])
    } else {
        settings.background
    }
}
