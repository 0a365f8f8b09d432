//! Closed time intervals inside the shutter [0, 1]: the conservative temporal overlap
//! t̂ = [t_lo, t_hi] that every tile test returns (Munkberg 2011, §4, Eq. 2 and 9).

use num_traits::Float;

/// A closed interval `[lo, hi]` of shutter time; empty when `lo > hi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeInterval<F> {
    /// Start of the interval.
    pub lo: F,
    /// End of the interval.
    pub hi: F,
}

impl<F: Float> TimeInterval<F> {
    /// The whole shutter `[0, 1]`.
    #[inline]
    pub fn full() -> Self {
        TimeInterval {
            lo: F::zero(),
            hi: F::one(),
        }
    }

    /// The empty interval (`lo = 1 > hi = 0`).
    #[inline]
    pub fn empty() -> Self {
        TimeInterval {
            lo: F::one(),
            hi: F::zero(),
        }
    }

    /// `[lo, hi]` as given (may be empty).
    #[inline]
    pub fn new(lo: F, hi: F) -> Self {
        TimeInterval { lo, hi }
    }

    /// True when no time lies in the interval (also when a bound is NaN).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.lo
            .partial_cmp(&self.hi)
            .is_none_or(|o| o == core::cmp::Ordering::Greater)
    }

    /// The intersection (the paper's t̂_box ∩ t̂_edges, §4.2).
    #[inline]
    pub fn intersect(self, other: Self) -> Self {
        TimeInterval {
            lo: self.lo.max(other.lo),
            hi: self.hi.min(other.hi),
        }
    }

    /// The smallest interval containing both (an empty operand is ignored).
    #[inline]
    pub fn hull(self, other: Self) -> Self {
        if self.is_empty() {
            other
        } else if other.is_empty() {
            self
        } else {
            TimeInterval {
                lo: self.lo.min(other.lo),
                hi: self.hi.max(other.hi),
            }
        }
    }

    /// True when `t` lies in the interval.
    #[inline]
    pub fn contains(&self, t: F) -> bool {
        self.lo <= t && t <= self.hi
    }

    /// The interval widened by `pad` on both sides and clipped to `[0, 1]` (absorbs the
    /// rounding of the divisions in Eq. 1 and 8); empty stays empty.
    #[inline]
    pub fn widened(self, pad: F) -> Self {
        if self.is_empty() {
            return Self::empty();
        }
        TimeInterval {
            lo: (self.lo - pad).max(F::zero()),
            hi: (self.hi + pad).min(F::one()),
        }
    }

    /// Length `hi - lo`, zero when empty.
    #[inline]
    pub fn len(&self) -> F {
        if self.is_empty() {
            F::zero()
        } else {
            self.hi - self.lo
        }
    }
}

/// The time interval in which a linear function `d(t) = (1 - t) d0 + t d1` is `<= 0`,
/// clipped to `[0, 1]` (Munkberg 2011, Eq. 1-2 with d0, d1 the plane distances of the
/// moving n-vertex at open and close; "outside" is `d > 0`).
#[inline]
pub fn linear_nonpositive<F: Float>(d0: F, d1: F) -> TimeInterval<F> {
    let z = F::zero();
    match (d0 > z, d1 > z) {
        (true, true) => TimeInterval::empty(),
        (true, false) => TimeInterval::new((d0 / (d0 - d1)).max(z), F::one()),
        (false, true) => TimeInterval::new(z, (d0 / (d0 - d1)).min(F::one())),
        (false, false) => TimeInterval::full(),
    }
}

/// Converts an `f64` constant to `F` (exact for the small constants used here).
#[inline]
pub(crate) fn lit<F: Float>(v: f64) -> F {
    F::from(v).unwrap_or_else(F::zero)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_nonpositive_matches_dense_sampling() {
        let cases = [
            (1.0, -1.0),
            (-1.0, 1.0),
            (2.0, 3.0),
            (-2.0, -3.0),
            (0.0, 1.0),
            (3.0, -1.0),
        ];
        for (d0, d1) in cases {
            let iv = linear_nonpositive::<f64>(d0, d1);
            for i in 0..=1000 {
                let t = f64::from(i) / 1000.0;
                let d = (1.0 - t) * d0 + t * d1;
                if d <= 0.0 {
                    assert!(iv.contains(t), "{d0} {d1} t={t} iv={iv:?}");
                }
            }
        }
    }

    #[test]
    fn hull_and_intersect() {
        let a = TimeInterval::new(0.1f32, 0.4);
        let b = TimeInterval::new(0.3f32, 0.9);
        assert_eq!(a.intersect(b), TimeInterval::new(0.3, 0.4));
        assert_eq!(a.hull(b), TimeInterval::new(0.1, 0.9));
        assert_eq!(a.hull(TimeInterval::empty()), a);
        assert!(a.intersect(TimeInterval::new(0.5, 0.6)).is_empty());
        assert_eq!(
            TimeInterval::new(0.0f64, 1.0).widened(0.1),
            TimeInterval::full()
        );
    }
}
