//! The exact time-dependent depth at a sample (Gribel 2010, Eq. 13-15) and its linear
//! approximation over a span (Eq. 16).

use num_traits::Float;

use crate::quadratic::lit;
use crate::span::Span;

/// Depth at a fixed sample as a function of time, d(t) = N(t) / D(t) with a cubic numerator
/// and a quadratic denominator (Gribel 2010, Eq. 15, with d = interpolated depth attribute).
///
/// With edge functions e_k(t) = α_k t² + β_k t + γ_k and per-vertex depth
/// z_k(t) = zq_k + t (zr_k - zq_k), the perspective-correct barycentrics are
/// λ_k = e_k / Σ e_j (Eq. 11-12), so d(t) = Σ e_k z_k / Σ e_k.
///
/// Evaluation is clamped to the range of the six vertex depths, which contains every exact
/// value at covered times (d is then a convex combination); where D(t) = 0 (a triangle with
/// zero area at that instant) the mean of the three vertex depths is returned. So the result
/// is always finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RationalDepth<F> {
    /// Numerator coefficients [m0, m1, m2, m3] of m3 t³ + m2 t² + m1 t + m0.
    pub m: [F; 4],
    /// Denominator coefficients [n0, n1, n2] of n2 t² + n1 t + n0.
    pub n: [F; 3],
    /// Depths of the three vertices at shutter open.
    pub zq: [F; 3],
    /// Depths of the three vertices at shutter close.
    pub zr: [F; 3],
    lo: F,
    hi: F,
}

/// The linear depth stored with an interval (Gribel 2010, Eq. 16): z at the span start and
/// slope k, z(t) = z + k (t - t0), here the chord through the exact depth at both span ends,
/// plus the maximum deviation from the exact depth over the span.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearDepth<F> {
    /// Span start t_s.
    pub t0: F,
    /// Span end t_e.
    pub t1: F,
    /// Depth at t0 (z_i of Eq. 16).
    pub z: F,
    /// Slope (k_i of Eq. 16), per unit of normalised time.
    pub k: F,
    /// max over [t0, t1] of |d(t) - (z + k (t - t0))|: what the approximation costs
    /// (saturates at `F::max_value()` for depths near the top of the range of `F`).
    pub max_error: F,
}

impl<F: Float> LinearDepth<F> {
    /// The approximated depth z + k (t - t0).
    #[inline]
    pub fn eval(&self, t: F) -> F {
        self.z + self.k * (t - self.t0)
    }

    /// Depth at the span end.
    pub fn z_end(&self) -> F {
        self.eval(self.t1)
    }
}

#[inline]
fn horner3<F: Float>(c: &[F; 4], t: F) -> F {
    ((c[3] * t + c[2]) * t + c[1]) * t + c[0]
}

#[inline]
fn horner2<F: Float>(c: &[F; 3], t: F) -> F {
    (c[2] * t + c[1]) * t + c[0]
}

/// Grid cells used to bracket the extrema of the fit error.
const FIT_CELLS: usize = 16;
/// Bisection steps per bracketed extremum (the error is flat there, so its value converges
/// quadratically in the bracket width).
const FIT_BISECTIONS: usize = 26;

impl<F: Float> RationalDepth<F> {
    /// Builds d(t) from the three edge quadratics (α_k, β_k, γ_k) and the vertex depths at
    /// open and close (Gribel 2010, Eq. 13-15).
    pub fn new(edges: [[F; 3]; 3], zq: [F; 3], zr: [F; 3]) -> Self {
        // Written out (a loop over the chained arrays was not unrolled and cost as much as
        // the rest of the setup); `min` / `max` skip a NaN as the loop did.
        let lo = zq[0].min(zq[1]).min(zq[2]).min(zr[0]).min(zr[1]).min(zr[2]);
        let hi = zq[0].max(zq[1]).max(zq[2]).max(zr[0]).max(zr[1]).max(zr[2]);
        Self::with_range(edges, zq, zr, [lo, hi])
    }

    /// [`RationalDepth::new`] with the clamp range `[lo, hi]` (the smallest and largest of
    /// the six vertex depths) given: a per-triangle constant that the setup computes once
    /// instead of every sample.
    #[inline]
    pub(crate) fn with_range(edges: [[F; 3]; 3], zq: [F; 3], zr: [F; 3], [lo, hi]: [F; 2]) -> Self {
        let mut m = [F::zero(); 4];
        let mut n = [F::zero(); 3];
        for k in 0..3 {
            let [a, b, c] = edges[k];
            let z0 = zq[k];
            let dz = zr[k] - zq[k];
            m[3] = m[3] + a * dz;
            m[2] = m[2] + a * z0 + b * dz;
            m[1] = m[1] + b * z0 + c * dz;
            m[0] = m[0] + c * z0;
            n[2] = n[2] + a;
            n[1] = n[1] + b;
            n[0] = n[0] + c;
        }
        RationalDepth {
            m,
            n,
            zq,
            zr,
            lo,
            hi,
        }
    }

    /// The exact depth d(t) = N(t) / D(t) (Gribel 2010, Eq. 15), clamped as documented on
    /// the type.
    #[inline]
    pub fn eval(&self, t: F) -> F {
        let num = horner3(&self.m, t);
        let den = horner2(&self.n, t);
        let (lo, hi) = (self.lo, self.hi);
        let d = num / den;
        if d.is_finite() {
            d.max(lo).min(hi)
        } else {
            let third: F = lit(1.0 / 3.0);
            let z = (0..3).fold(F::zero(), |acc, k| {
                acc + self.zq[k] + t * (self.zr[k] - self.zq[k])
            });
            (z * third).max(lo).min(hi)
        }
    }

    /// Sign-carrying numerator of d'(t) - k: N'D - ND' - k D².
    fn slope_gap(&self, t: F, k: F) -> F {
        let (two, three): (F, F) = (lit(2.0), lit(3.0));
        let num = horner3(&self.m, t);
        let dnum = (three * self.m[3] * t + two * self.m[2]) * t + self.m[1];
        let den = horner2(&self.n, t);
        let dden = two * self.n[2] * t + self.n[1];
        dnum * den - num * dden - k * den * den
    }

    /// The linear depth of Eq. 16 over `span`: the chord through d(t0) and d(t1), and the
    /// maximum error of that chord against d(t) over the span.
    ///
    /// The maximum is found by locating the extrema of d(t) - chord(t) (the sign changes of
    /// N'D - ND' - kD², a quartic) on a 16-cell grid and bisecting each bracket; it is exact
    /// up to rounding whenever no grid cell holds two extrema.
    pub fn linear_fit(&self, span: Span<F>) -> LinearDepth<F> {
        let (t0, t1) = (span.t0, span.t1);
        let z0 = self.eval(t0);
        let z1 = self.eval(t1);
        let width = t1 - t0;
        let mut k = if width > F::zero() {
            (z1 - z0) / width
        } else {
            F::zero()
        };
        if !k.is_finite() {
            k = F::zero();
        }
        let mut fit = LinearDepth {
            t0,
            t1,
            z: z0,
            k,
            max_error: F::zero(),
        };
        let err = |t: F| (self.eval(t) - fit.eval(t)).abs();
        let mut worst = err(t1);
        if width > F::zero() {
            let cells: F = lit(FIT_CELLS as f64);
            let at = |i: usize| {
                if i == FIT_CELLS {
                    t1
                } else {
                    t0 + width * lit::<F>(i as f64) / cells
                }
            };
            let mut ta = t0;
            let mut ga = self.slope_gap(ta, k);
            for i in 1..=FIT_CELLS {
                let tb = at(i);
                let gb = self.slope_gap(tb, k);
                worst = worst.max(err(tb));
                if (ga < F::zero()) != (gb < F::zero()) {
                    let (mut lo, mut hi) = (ta, tb);
                    let lo_neg = ga < F::zero();
                    for _ in 0..FIT_BISECTIONS {
                        let mid = (lo + hi) * lit(0.5);
                        if (self.slope_gap(mid, k) < F::zero()) == lo_neg {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    worst = worst.max(err(lo)).max(err(hi));
                }
                ta = tb;
                ga = gb;
            }
        }
        // Saturate instead of returning infinity when the depth values are near F::MAX.
        fit.max_error = if worst.is_nan() {
            F::max_value()
        } else {
            worst.min(F::max_value())
        };
        fit
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_depth_is_exactly_linear() {
        // Equal depths everywhere: d(t) = z, zero fit error.
        let e = [[0.1, -0.3, 0.2], [0.0, 0.4, 0.5], [-0.2, 0.1, 0.3]];
        let d = RationalDepth::new(e, [2.0_f64; 3], [2.0; 3]);
        let fit = d.linear_fit(Span::new(0.0, 1.0));
        assert!((fit.z - 2.0).abs() < 1e-14 && fit.k.abs() < 1e-13);
        assert!(fit.max_error < 1e-13);
    }

    #[test]
    fn fit_error_matches_dense_scan() {
        let e = [[1.0, -0.5, 0.3], [0.5, 0.2, 0.4], [-0.3, 0.1, 0.5]];
        let d = RationalDepth::new(e, [1.0_f64, 3.0, 2.0], [4.0, 1.0, 2.5]);
        let fit = d.linear_fit(Span::new(0.1, 0.9));
        let dense = (0..=20000)
            .map(|i| 0.1 + 0.8 * f64::from(i) / 20000.0)
            .map(|t| (d.eval(t) - fit.eval(t)).abs())
            .fold(0.0, f64::max);
        assert!(
            fit.max_error >= dense - 1e-12,
            "{} {}",
            fit.max_error,
            dense
        );
        assert!(fit.max_error <= dense * (1.0 + 1e-6) + 1e-12);
        assert!(dense > 1e-3);
    }
}
