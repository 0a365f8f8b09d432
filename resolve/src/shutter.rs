//! The shutter response w(t): a piecewise-linear weight over the normalised shutter time.

use num_traits::Float;

use crate::ResolveError;

/// A piecewise-linear shutter response w(t) on [0, 1] (Gribel 2010, Eq. 17).
///
/// Stored as knots `(t, w)` with non-decreasing `t` in [0, 1]; w is linear between
/// consecutive knots, may jump where two knots share a time, and is zero outside
/// [first knot, last knot]. The resolve adds every knot time as a sweep event, so w is linear
/// inside each partition and Eq. 17 is integrated exactly (trapezoid rule on a linear
/// function). The pixel colour is divided by [`Shutter::total`] = ∫₀¹ w, so a constant colour
/// covering the whole shutter resolves to itself whatever the response.
#[derive(Clone, Debug, PartialEq)]
pub struct Shutter<F> {
    knots: Vec<(F, F)>,
    total: F,
}

impl<F: Float> Shutter<F> {
    /// The box response w(t) = 1 (the default; Gribel 2010, §5.1: "colors … weighted by
    /// their duration in time").
    pub fn box_filter() -> Self {
        Self::from_valid(vec![(F::zero(), F::one()), (F::one(), F::one())])
    }

    /// The tent response: 0 at t = 0 and t = 1, peak 1 at t = 0.5.
    pub fn tent() -> Self {
        let half = F::one() / (F::one() + F::one());
        Self::from_valid(vec![
            (F::zero(), F::zero()),
            (half, F::one()),
            (F::one(), F::zero()),
        ])
    }

    /// A trapezoid: the shutter opens linearly over `[0, open]`, stays fully open and
    /// closes linearly over `[1 - close, 1]`. `open = close = 0` is the box.
    ///
    /// Errors with [`ResolveError::InvalidShutter`] unless `open, close >= 0` and
    /// `open + close <= 1`.
    pub fn trapezoid(open: F, close: F) -> Result<Self, ResolveError> {
        if !(open >= F::zero() && close >= F::zero() && open + close <= F::one()) {
            return Err(ResolveError::InvalidShutter);
        }
        let mut knots = Vec::with_capacity(4);
        if open > F::zero() {
            knots.push((F::zero(), F::zero()));
        }
        knots.push((open, F::one()));
        knots.push((F::one() - close, F::one()));
        if close > F::zero() {
            knots.push((F::one(), F::zero()));
        }
        Self::from_points(&knots)
    }

    /// A response through explicit knots `(t, w)`.
    ///
    /// Knot times must be finite, inside [0, 1] and non-decreasing (two knots at one time
    /// make a jump); weights finite and non-negative; the integral positive. Otherwise
    /// [`ResolveError::InvalidShutter`].
    pub fn from_points(points: &[(F, F)]) -> Result<Self, ResolveError> {
        let mut previous = F::zero();
        for &(t, w) in points {
            let ok = t.is_finite() && w.is_finite() && t >= previous && t <= F::one();
            if !ok || w < F::zero() {
                return Err(ResolveError::InvalidShutter);
            }
            previous = t;
        }
        let shutter = Self::from_valid(points.to_vec());
        if shutter.total > F::zero() && shutter.total.is_finite() {
            Ok(shutter)
        } else {
            Err(ResolveError::InvalidShutter)
        }
    }

    fn from_valid(knots: Vec<(F, F)>) -> Self {
        let total = knots
            .windows(2)
            .fold(F::zero(), |acc, p| acc + trapezoid_area(p[0], p[1]));
        Self { knots, total }
    }

    /// The knots `(t, w)` in time order.
    pub fn knots(&self) -> &[(F, F)] {
        &self.knots
    }

    /// ∫₀¹ w(t) dt, the normalisation of Eq. 17 (always positive).
    pub fn total(&self) -> F {
        self.total
    }

    /// Whether this is the box response (every knot weighs the same).
    pub fn is_box(&self) -> bool {
        self.knots.len() == 2
            && self.knots[0] == (F::zero(), F::one())
            && self.knots[1] == (F::one(), F::one())
    }

    /// w(t) (right-continuous at jumps; zero outside the knots).
    pub fn weight(&self, t: F) -> F {
        let mut cursor = 0;
        self.advance(&mut cursor, t);
        self.right_value(cursor, t)
    }

    /// ∫_a^b w(t) dt, exact for the piecewise-linear response (`a <= b` assumed;
    /// returns 0 otherwise).
    pub fn integral(&self, a: F, b: F) -> F {
        if a.is_nan() || b.is_nan() || a >= b {
            return F::zero();
        }
        let mut sum = F::zero();
        for p in self.knots.windows(2) {
            let (t0, t1) = (p[0].0.max(a), p[1].0.min(b));
            if t0 < t1 {
                let w0 = lerp_knots(p[0], p[1], t0);
                let w1 = lerp_knots(p[0], p[1], t1);
                sum = sum + (t1 - t0) * (w0 + w1) * half::<F>();
            }
        }
        sum
    }

    /// Moves `cursor` to the first knot strictly after `t` (the sweep is monotone, so one
    /// cursor per pixel visits each knot once).
    pub(crate) fn advance(&self, cursor: &mut usize, t: F) {
        while let Some(&(kt, _)) = self.knots.get(*cursor) {
            if kt > t {
                break;
            }
            *cursor += 1;
        }
    }

    /// Time of the knot at `cursor`, the next shutter event after the current time.
    pub(crate) fn next_knot(&self, cursor: usize) -> Option<F> {
        self.knots.get(cursor).map(|k| k.0)
    }

    /// w(t) on the linear piece that starts at or before the current time, for `t` in
    /// [current time, next knot]: the weights at a partition's two ends.
    pub(crate) fn right_value(&self, cursor: usize, t: F) -> F {
        match (
            cursor.checked_sub(1).and_then(|i| self.knots.get(i)),
            self.knots.get(cursor),
        ) {
            (Some(&k0), Some(&k1)) => lerp_knots(k0, k1, t),
            _ => F::zero(),
        }
    }
}

impl<F: Float> Default for Shutter<F> {
    fn default() -> Self {
        Self::box_filter()
    }
}

fn half<F: Float>() -> F {
    F::one() / (F::one() + F::one())
}

fn trapezoid_area<F: Float>(k0: (F, F), k1: (F, F)) -> F {
    (k1.0 - k0.0) * (k0.1 + k1.1) * half::<F>()
}

/// Linear interpolation of the weight between two knots (the left value at a jump).
fn lerp_knots<F: Float>(k0: (F, F), k1: (F, F), t: F) -> F {
    let span = k1.0 - k0.0;
    if span > F::zero() {
        let s = ((t - k0.0) / span).max(F::zero()).min(F::one());
        k0.1 + (k1.1 - k0.1) * s
    } else {
        k1.1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn totals_of_named_responses() {
        assert_eq!(Shutter::<f64>::box_filter().total(), 1.0);
        assert_eq!(Shutter::<f64>::tent().total(), 0.5);
        let trap = Shutter::<f64>::trapezoid(0.25, 0.25).unwrap();
        assert_eq!(trap.total(), 0.75);
        assert!(Shutter::<f64>::trapezoid(0.0, 0.0).unwrap().is_box());
    }

    #[test]
    fn integral_matches_dense_midpoint_rule() {
        let s = Shutter::from_points(&[(0.1, 0.0), (0.3, 2.0), (0.3, 0.5), (0.9, 1.0)]).unwrap();
        let n = 200_000;
        let (a, b) = (0.05, 0.7);
        let h = (b - a) / n as f64;
        let dense: f64 = (0..n).map(|i| s.weight(a + (i as f64 + 0.5) * h) * h).sum();
        assert!(
            (s.integral(a, b) - dense).abs() < 1e-4,
            "{} vs {dense}",
            s.integral(a, b)
        );
        assert!((s.integral(0.0, 1.0) - s.total()).abs() < 1e-15);
    }

    #[test]
    fn invalid_responses_are_rejected() {
        assert!(Shutter::<f64>::from_points(&[(0.0, 0.0), (1.0, 0.0)]).is_err());
        assert!(Shutter::<f64>::from_points(&[(0.5, 1.0), (0.2, 1.0)]).is_err());
        assert!(Shutter::<f64>::from_points(&[(0.0, -1.0), (1.0, 1.0)]).is_err());
        assert!(Shutter::<f64>::from_points(&[(0.0, 1.0), (1.5, 1.0)]).is_err());
        assert!(Shutter::<f64>::from_points(&[(0.0, f64::NAN), (1.0, 1.0)]).is_err());
        assert!(Shutter::<f64>::trapezoid(0.6, 0.6).is_err());
    }

    #[test]
    fn weight_is_zero_outside_the_knots_and_right_continuous_at_jumps() {
        let s = Shutter::from_points(&[(0.2, 1.0), (0.5, 1.0), (0.5, 3.0), (0.8, 3.0)]).unwrap();
        assert_eq!(s.weight(0.1), 0.0);
        assert_eq!(s.weight(0.3), 1.0);
        assert_eq!(s.weight(0.5), 3.0);
        assert_eq!(s.weight(0.9), 0.0);
    }
}
