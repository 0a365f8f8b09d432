//! The shutter response w(t) over normalised time t in [0, 1], as piecewise-linear points,
//! with exact integrals (the weights `accum` gives its sub-frames).

/// Shutter interval and piecewise-linear response.
#[derive(Debug, Clone, PartialEq)]
pub struct Shutter {
    /// Open time in seconds (informational).
    pub open: f64,
    /// Close time in seconds (informational).
    pub close: f64,
    /// Response points `(t, w)`, t strictly increasing from 0 to 1, w >= 0.
    pub points: Vec<(f64, f64)>,
}

impl Shutter {
    /// True for the box response (w constant).
    pub fn is_box(&self) -> bool {
        self.points.windows(2).all(|p| p[0].1 == p[1].1)
    }

    /// w(t), 0 outside [0, 1].
    pub fn weight(&self, t: f64) -> f64 {
        for p in self.points.windows(2) {
            let ((t0, w0), (t1, w1)) = (p[0], p[1]);
            if t >= t0 && t <= t1 {
                return w0 + (w1 - w0) * (t - t0) / (t1 - t0);
            }
        }
        0.0
    }

    /// Exact integral of w over [a, b] (clamped to [0, 1]).
    pub fn integral(&self, a: f64, b: f64) -> f64 {
        let mut sum = 0.0;
        for p in self.points.windows(2) {
            let (lo, hi) = (a.max(p[0].0), b.min(p[1].0));
            if hi > lo {
                // Trapezoid of the linear segment over [lo, hi] is exact.
                sum += 0.5 * (self.weight(lo) + self.weight(hi)) * (hi - lo);
            }
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tent_integrals_against_dense_midpoint_sum() {
        let s = Shutter {
            open: 0.0,
            close: 1.0,
            points: vec![(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)],
        };
        assert!((s.integral(0.0, 1.0) - 0.5).abs() < 1e-15);
        let n = 200_000;
        let (a, b) = (0.1, 0.7);
        let h = (b - a) / f64::from(n);
        let dense: f64 = (0..n)
            .map(|k| s.weight(a + (f64::from(k) + 0.5) * h) * h)
            .sum();
        assert!((s.integral(a, b) - dense).abs() < 1e-9);
    }
}
