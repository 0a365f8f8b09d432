//! Depth order of linear depth functions "just after" a time, and when two of them swap.
//!
//! Each active interval is reduced to its depth line d(t) = c + k t with the intercept
//! c = z - k ts (Gribel 2010, Eq. 16). The order just after time t compares the *exact*
//! depths c + k t of the two float lines (a filtered predicate: a floating-point estimate,
//! and an exact expansion sum when the estimate is within its rounding bound), then the
//! slopes (the flatter line is nearer right after an exact tie), then the list position.
//! Being exact, the order is a strict total order at every t, so sorting, taking the
//! minimum and pruning by it are sound even when many lines cross at one time.
//!
//! The time at which a nearer line is overtaken is the crossing τ = (c_b - c_a)/(k_a - k_b),
//! nudged up by a few ulps when rounding put it before the exact crossing, so that the
//! sweep, stopping there, finds the pair swapped (Rønnow 2021, Algorithm 1 swaps one pair
//! at an intersection; we re-sort by this order instead, which handles any number of
//! crossings at one time).
//!
//! Exact ties (same slope and same intercept: equal depth over a whole span) are broken by
//! position in the pixel's list: the later interval is nearer. Lists are sorted by `ts` and
//! the interval buffer appends later insertions after earlier ones at equal `ts`, so this is
//! the `LESS_EQUAL` rule "the later-inserted surface wins" (Gribel 2010, §5, Fig. 7).

use std::cmp::Ordering;

use num_traits::Float;

/// An active interval as the sweep sees it: depth line, clamped end time, list position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Line<F> {
    /// Depth at t = 0 of the interval's line, z - k ts.
    pub c: F,
    /// Depth slope dz/dt.
    pub k: F,
    /// End time clamped to the shutter, min(te, 1).
    pub te: F,
    /// Position of the interval in the pixel's list (the tie-breaker).
    pub index: usize,
}

impl<F: Float> Line<F> {
    /// Sign of depth(self) - depth(other) at time `t`, exactly for the float inputs.
    pub fn compare_depth(&self, other: &Self, t: F) -> Ordering {
        let dc = self.c - other.c;
        let dk = self.k - other.k;
        let p = dk * t;
        let d = dc + p;
        let eps = F::epsilon();
        let four = F::from(4.0).unwrap_or_else(F::one);
        let bound = four * eps * (dc.abs() + p.abs()) + F::min_positive_value();
        if d > bound {
            Ordering::Greater
        } else if d < -bound {
            Ordering::Less
        } else {
            exact_sign(self.c, other.c, self.k, other.k, t)
        }
    }

    /// Whether `self` is nearer than `other` on an open span just after time `t`
    /// (exact depth at t, then the smaller slope, then the later list position).
    pub fn nearer_after(&self, other: &Self, t: F) -> bool {
        match self.compare_depth(other, t) {
            Ordering::Less => true,
            Ordering::Greater => false,
            Ordering::Equal => {
                if self.k != other.k {
                    self.k < other.k
                } else {
                    self.index > other.index
                }
            }
        }
    }

    /// For `self` nearer than `behind`: the computed crossing time of their depth lines,
    /// `None` if `behind` never overtakes (it is not flatter). Rounding may put it a few
    /// ulps before the exact crossing; [`Line::nudge_past_crossing`] corrects that.
    pub fn crossing_estimate(&self, behind: &Self) -> Option<F> {
        if self.k <= behind.k {
            return None;
        }
        let tau = (behind.c - self.c) / (self.k - behind.k);
        tau.is_finite().then_some(tau)
    }

    /// For `self` nearer than `behind` now: the time from which `behind` is nearer, i.e.
    /// the first float time at or after the exact crossing (up to a nudge of a few ulps).
    /// `None` if `behind` never overtakes (it is not flatter).
    #[cfg(test)]
    pub fn overtaken_at(&self, behind: &Self) -> Option<F> {
        self.crossing_estimate(behind)
            .map(|tau| self.nudge_past_crossing(behind, tau))
    }

    /// Moves an estimate of the crossing with `behind` up until the exact order has
    /// flipped there (steps doubling from one ulp-ish; the result overshoots the exact
    /// crossing by at most about twice the estimate's error).
    pub fn nudge_past_crossing(&self, behind: &Self, estimate: F) -> F {
        let mut tau = estimate;
        let mut step = F::epsilon() * (tau.abs() + F::one());
        for _ in 0..64 {
            // Swapped once behind is at least as near (ties go to the flatter, `behind`).
            if self.compare_depth(behind, tau) != Ordering::Less {
                return tau;
            }
            tau = tau + step;
            step = step + step;
        }
        tau
    }
}

/// Error-free sum: a + b = s + e exactly.
fn two_sum<F: Float>(a: F, b: F) -> (F, F) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Error-free product: a b = p + e exactly (fused multiply-add).
fn two_prod<F: Float>(a: F, b: F) -> (F, F) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Exact sign of (ca - cb) + (ka - kb) t, by expansion arithmetic (Shewchuk's
/// grow-expansion): the terms are summed into a non-overlapping expansion whose largest
/// non-zero component carries the sign.
fn exact_sign<F: Float>(ca: F, cb: F, ka: F, kb: F, t: F) -> Ordering {
    let (s1, e1) = two_sum(ca, -cb);
    let (s2, e2) = two_sum(ka, -kb);
    let (p1, q1) = two_prod(s2, t);
    let (p2, q2) = two_prod(e2, t);
    let mut expansion = [F::zero(); 6];
    let mut len = 0;
    for x in [e1, q2, q1, p2, p1, s1] {
        let mut q = x;
        let mut out = 0;
        for i in 0..len {
            let (s, e) = two_sum(q, expansion[i]);
            q = s;
            if e != F::zero() {
                expansion[out] = e;
                out += 1;
            }
        }
        if q != F::zero() && out < expansion.len() {
            expansion[out] = q;
            out += 1;
        }
        len = out;
    }
    match expansion[..len].last() {
        Some(&top) if top > F::zero() => Ordering::Greater,
        Some(&top) if top < F::zero() => Ordering::Less,
        _ => Ordering::Equal,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(c: f64, k: f64, index: usize) -> Line<f64> {
        Line {
            c,
            k,
            te: 1.0,
            index,
        }
    }

    #[test]
    fn overtaking_time_is_where_the_order_flips() {
        let a = line(0.1, 1.0, 0); // 0.1 + t
        let b = line(0.9, -1.0, 1); // 0.9 - t, crosses a at 0.4
        let tau = a.overtaken_at(&b).unwrap();
        assert!((tau - 0.4).abs() < 1e-15);
        assert_eq!(b.overtaken_at(&a), None);
        assert!(a.nearer_after(&b, 0.0) && !b.nearer_after(&a, 0.0));
        assert!(b.nearer_after(&a, tau) && !a.nearer_after(&b, tau));
    }

    #[test]
    fn parallel_ties_go_to_the_later_interval() {
        let a = line(0.5, 0.25, 3);
        let b = line(0.5, 0.25, 7);
        assert!(b.nearer_after(&a, 0.3) && !a.nearer_after(&b, 0.3));
        assert_eq!(a.overtaken_at(&b), None);
    }

    #[test]
    fn equal_depth_now_breaks_by_slope() {
        // Both at depth 1 at t = 0.5; the falling one is nearer just after.
        let rising = line(0.5, 1.0, 0);
        let falling = line(1.5, -1.0, 1);
        assert!(falling.nearer_after(&rising, 0.5));
        assert!(rising.nearer_after(&falling, 0.49));
    }

    #[test]
    fn exact_sign_sees_what_rounding_hides() {
        // (1 + 2^-52) - 1 + (2^-60 - 0) * 1: floating point loses nothing here, but with
        // t chosen so that dk * t rounds, the exact sign must still be right.
        let ca = 1.0 + f64::EPSILON;
        let t = 1.0 / 3.0;
        // ka - kb = -3 eps exactly; (-3 eps) * (1/3 rounded) vs +eps.
        let kb = 3.0 * f64::EPSILON;
        let exact = {
            // Evaluate in i128 units of 2^-110 to get the true sign.
            let third = t; // the float nearest 1/3
            let (m, e) = frexp(third);
            // ca - 1 = 2^-52; dk * t = -3 * 2^-52 * m * 2^(e - 53)
            let lhs = 1i128 << 58; // 2^-52 in units of 2^-110
            let rhs = 3 * (m as i128) * (1i128 << (58 + e - 53));
            (lhs - rhs).signum()
        };
        let got = exact_sign(ca, 1.0, 0.0, kb, t);
        assert_eq!(got, exact.cmp(&0));
    }

    /// Mantissa (as an integer) and exponent with x = m 2^(e - 53).
    fn frexp(x: f64) -> (u64, i32) {
        let bits = x.to_bits();
        let e = ((bits >> 52) & 0x7ff) as i32 - 1022;
        let m = (bits & ((1u64 << 52) - 1)) | (1u64 << 52);
        (m, e)
    }

    #[test]
    fn three_lines_through_one_point_order_transitively() {
        let t0 = 0.5344681740460552;
        let d0 = 1.6456250935981604;
        let lines = [0.0, 1.0, -1.3059026726981948].map(|k| line(d0 - k * t0, k, 0));
        for t in [0.0, 0.534468174046055, t0, 0.5344681740460553, 1.0] {
            for a in &lines {
                for b in &lines {
                    for c in &lines {
                        let ab = a.nearer_after(b, t);
                        let bc = b.nearer_after(c, t);
                        let ac = a.nearer_after(c, t);
                        assert!(!(ab && bc) || ac || a == c, "intransitive at {t}");
                    }
                }
            }
        }
    }
}
