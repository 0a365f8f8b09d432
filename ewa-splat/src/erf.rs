//! The error function as an accuracy knob (Heinzle 2010, §4.2 and §5.3).
//!
//! The closed-form line integral (Eq. 19) needs `erf` and, in the tails, the scaled
//! complementary function `erfcx(x) = exp(x²) erfc(x)` so that differences never cancel.
//! Three evaluations are offered:
//!
//! - [`ErfMethod::Full`]: `libm` `erf`/`erfc` (about 1-2 ulp in f64), with an asymptotic
//!   series for `erfcx` where `erfc` underflows.
//! - [`ErfMethod::Polynomial`]: the Chebyshev fit `erfcc` of Press et al. (Numerical
//!   Recipes, §6.2), fractional error below 1.2e-7 for every x >= 0, plus the Taylor series of
//!   erf near zero. One `exp` per call.
//! - [`ErfMethod::Table`]: a linearly interpolated look-up table of erf on [0, 6] with
//!   step 1/64, like the paper's GPU texture (absolute error about 3e-5; the tails are only
//!   as good as `1 - erf`).

use num_traits::Float;
use std::sync::OnceLock;

/// Which erf evaluation the line integral uses (the crate's main accuracy knob).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ErfMethod {
    /// Look-up table with linear interpolation, as in the paper's GPU version (§5.3).
    Table,
    /// Chebyshev fit (Numerical Recipes `erfcc`), relative error < 1.2e-7 in erfc.
    Polynomial,
    /// Full precision from the `libm` crate (default).
    #[default]
    Full,
}

/// Scalar type usable by the line integral: `f32` or `f64` with libm's erf and erfc.
pub trait Real: Float + core::fmt::Debug + Send + Sync + 'static {
    /// erf(x) from libm.
    fn libm_erf(self) -> Self;
    /// erfc(x) from libm.
    fn libm_erfc(self) -> Self;
    /// Convert from an f64 constant (rounds for f32).
    fn c(v: f64) -> Self;
    /// Largest argument for which `exp(x²)·erfc(x)` is computed directly (beyond it erfc
    /// underflows and the asymptotic series takes over).
    const ERFCX_DIRECT_MAX: f64;
    /// Exponents up to this are safe in `exp(-q)` (0.9 ln MAX).
    const Q_MAX: f64;
    /// Squares above this and below [`Real::SAFE_MAX`] are computed without scaling.
    const SAFE_MIN: f64;
    /// Upper end of the unscaled range.
    const SAFE_MAX: f64;
}

impl Real for f64 {
    #[inline]
    fn libm_erf(self) -> Self {
        libm::erf(self)
    }
    #[inline]
    fn libm_erfc(self) -> Self {
        libm::erfc(self)
    }
    #[inline]
    fn c(v: f64) -> Self {
        v
    }
    const ERFCX_DIRECT_MAX: f64 = 25.0;
    const Q_MAX: f64 = 638.0;
    const SAFE_MIN: f64 = 1e-150;
    const SAFE_MAX: f64 = 1e150;
}

impl Real for f32 {
    #[inline]
    fn libm_erf(self) -> Self {
        libm::erff(self)
    }
    #[inline]
    fn libm_erfc(self) -> Self {
        libm::erfcf(self)
    }
    #[inline]
    fn c(v: f64) -> Self {
        v as f32
    }
    const ERFCX_DIRECT_MAX: f64 = 8.0;
    const Q_MAX: f64 = 79.0;
    const SAFE_MIN: f64 = 1e-18;
    const SAFE_MAX: f64 = 1e18;
}

/// 1/sqrt(pi).
const FRAC_1_SQRT_PI: f64 = 0.564_189_583_547_756_3;

/// Asymptotic series of erfcx for large x (Abramowitz-Stegun 7.1.23):
/// `erfcx(x) ≈ 1/(x sqrt(pi)) Σ (-1)^k (2k-1)!! / (2x²)^k`. Eight terms; at x >= 8 (f32) or
/// x >= 25 (f64) the first omitted term is below the format's epsilon.
fn erfcx_asymptotic<T: Real>(x: T) -> T {
    let inv2x2 = T::one() / (T::c(2.0) * x * x);
    let mut term = T::one();
    let mut sum = T::one();
    for k in 1..8 {
        term = -term * T::c((2 * k - 1) as f64) * inv2x2;
        sum = sum + term;
    }
    sum * T::c(FRAC_1_SQRT_PI) / x
}

/// Table resolution: entries per unit argument.
const TABLE_STEPS_PER_UNIT: usize = 64;
/// Table range [0, TABLE_MAX]; erf(6) = 1 - 2.2e-17.
const TABLE_MAX: usize = 6;

fn erf_table() -> &'static [f64] {
    static TABLE: OnceLock<Vec<f64>> = OnceLock::new();
    TABLE.get_or_init(|| {
        (0..=TABLE_MAX * TABLE_STEPS_PER_UNIT)
            .map(|i| libm::erf(i as f64 / TABLE_STEPS_PER_UNIT as f64))
            .collect()
    })
}

/// Look-up table erf for x >= 0 (linear interpolation, saturating at 1).
fn erf_table_pos<T: Real>(x: T) -> T {
    let table = erf_table();
    let pos = x * T::c(TABLE_STEPS_PER_UNIT as f64);
    let last = table.len() - 1;
    if pos.is_nan() || pos >= T::c(last as f64) {
        // NaN cannot reach here from the line integral; treat it like the saturated end.
        return T::one();
    }
    let i = pos.floor().to_usize().unwrap_or(0).min(last - 1);
    let frac = pos - T::c(i as f64);
    let (a, b) = match (table.get(i), table.get(i + 1)) {
        (Some(&a), Some(&b)) => (a, b),
        _ => return T::one(),
    };
    T::c(a) + frac * T::c(b - a)
}

/// Numerical Recipes `erfcc` exponent polynomial: erfc(x) = t exp(-x² + poly(t)), t = 1/(1+x/2).
fn nr_poly<T: Real>(t: T) -> T {
    const C: [f64; 10] = [
        -1.265_512_23,
        1.000_023_68,
        0.374_091_96,
        0.096_784_18,
        -0.186_288_06,
        0.278_868_07,
        -1.135_203_98,
        1.488_515_87,
        -0.822_152_23,
        0.170_872_77,
    ];
    let mut acc = T::c(C[9]);
    for &c in C[..9].iter().rev() {
        acc = acc * t + T::c(c);
    }
    acc
}

/// `2/sqrt(pi) (-1)^n / (n! (2n+1))`, n = 0..6: the Taylor coefficients of erf(x)/x in x².
const ERF_TAYLOR: [f64; 7] = [
    2.0 * FRAC_1_SQRT_PI,
    -2.0 * FRAC_1_SQRT_PI / 3.0,
    2.0 * FRAC_1_SQRT_PI / 10.0,
    -2.0 * FRAC_1_SQRT_PI / 42.0,
    2.0 * FRAC_1_SQRT_PI / 216.0,
    -2.0 * FRAC_1_SQRT_PI / 1320.0,
    2.0 * FRAC_1_SQRT_PI / 9360.0,
];

/// erf(x) by the chosen method (odd in x).
pub fn erf<T: Real>(method: ErfMethod, x: T) -> T {
    let ax = x.abs();
    let v = match method {
        ErfMethod::Full => return x.libm_erf(),
        ErfMethod::Table => erf_table_pos(ax),
        ErfMethod::Polynomial => {
            if ax < T::c(0.5) {
                // Taylor series 2/sqrt(pi) Σ (-1)^n x^(2n+1) / (n! (2n+1)), 7 terms, in
                // Horner form with the coefficients precomputed.
                let x2 = ax * ax;
                let mut acc = T::c(ERF_TAYLOR[6]);
                for &c in ERF_TAYLOR[..6].iter().rev() {
                    acc = acc * x2 + T::c(c);
                }
                ax * acc
            } else {
                T::one() - erfc_pos_poly(ax)
            }
        }
    };
    if x < T::zero() { -v } else { v }
}

fn erfc_pos_poly<T: Real>(x: T) -> T {
    erfc_pos_poly_exp(x, T::zero())
}

/// `erfc(x) exp(-q)` for x >= 0 with the Chebyshev fit, the factor folded into its single
/// exp (one exp instead of two; the caller keeps `q` in the normal exponent range).
pub(crate) fn erfc_pos_poly_exp<T: Real>(x: T, q: T) -> T {
    let t = T::one() / (T::one() + T::c(0.5) * x);
    t * (nr_poly(t) - x * x - q).exp()
}

/// erfc(x) by the chosen method.
pub fn erfc<T: Real>(method: ErfMethod, x: T) -> T {
    match method {
        ErfMethod::Full => x.libm_erfc(),
        ErfMethod::Polynomial => {
            if x >= T::zero() {
                erfc_pos_poly(x)
            } else {
                T::c(2.0) - erfc_pos_poly(-x)
            }
        }
        ErfMethod::Table => T::one() - erf(method, x),
    }
}

/// Scaled complementary error function `erfcx(x) = exp(x²) erfc(x)` for x >= 0 (clamped to
/// x >= 0), finite for every finite argument: the factor that keeps Eq. 19 free of
/// cancellation and underflow in the tails.
pub fn erfcx_pos<T: Real>(method: ErfMethod, x: T) -> T {
    let x = x.max(T::zero());
    match method {
        ErfMethod::Full => {
            if x < T::c(T::ERFCX_DIRECT_MAX) {
                (x * x).exp() * x.libm_erfc()
            } else {
                erfcx_asymptotic(x)
            }
        }
        ErfMethod::Polynomial => {
            let t = T::one() / (T::one() + T::c(0.5) * x);
            t * nr_poly(t).exp()
        }
        ErfMethod::Table => {
            // The table only knows erf; its tails are 1 - erf, as on the GPU. Beyond the
            // table range the value is 0 (the table saturates), so exp(x²) never overflows
            // into a product with a non-zero factor.
            let e = T::one() - erf_table_pos(x);
            if e > T::zero() {
                (x * x).exp() * e
            } else {
                T::zero()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn asymptotic_matches_direct_at_switch_point() {
        let x = 25.0f64;
        let direct = (x * x).exp() * libm::erfc(x);
        let asym = erfcx_asymptotic(x);
        assert!(((direct - asym) / direct).abs() < 1e-13, "{direct} {asym}");
        let x = 8.0f32;
        let direct = ((x as f64) * (x as f64)).exp() * libm::erfc(x as f64);
        assert!(((direct - erfcx_asymptotic(x) as f64) / direct).abs() < 1e-6);
    }

    #[test]
    fn methods_are_odd() {
        for m in [ErfMethod::Table, ErfMethod::Polynomial, ErfMethod::Full] {
            for x in [0.1f64, 0.7, 2.5, 5.9, 7.0] {
                assert_eq!(erf(m, -x), -erf(m, x));
            }
        }
    }
}
