//! The shutter response a(t) of Heinzle 2010, Eq. 1, and its integral over a time interval
//! (used for the covered-time background blend, §5.4, and the subframe weights, §5.5).

/// Shutter response over the exposure t in [0, 1].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shutter {
    /// Box: every instant weighs the same (the workspace convention).
    #[default]
    Box,
    /// The paper's Gaussian `exp(-t'²)` with t' = 2t - 1 in [-1, 1] (§5.4, §5.5).
    Gaussian,
}

impl Shutter {
    /// `∫_{t0}^{t1} a(t) dt` with both ends clamped to [0, 1].
    pub fn integral(self, t0: f64, t1: f64) -> f64 {
        let (t0, t1) = (t0.clamp(0.0, 1.0), t1.clamp(0.0, 1.0));
        match self {
            Shutter::Box => t1 - t0,
            Shutter::Gaussian => {
                0.25 * std::f64::consts::PI.sqrt()
                    * (libm::erf(2.0 * t1 - 1.0) - libm::erf(2.0 * t0 - 1.0))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_integral_matches_simpson() {
        let n = 2000;
        let h = 0.6 / n as f64;
        let g = |t: f64| (-(2.0 * t - 1.0f64).powi(2)).exp();
        let mut s = g(0.1) + g(0.7);
        for i in 1..n {
            s += g(0.1 + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        let simpson = s * h / 3.0;
        assert!((Shutter::Gaussian.integral(0.1, 0.7) - simpson).abs() < 1e-12);
        assert_eq!(Shutter::Box.integral(-1.0, 0.25), 0.25);
    }
}
