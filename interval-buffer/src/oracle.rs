//! The compression oracle of Gribel 2010 §5.2 (Eq. 18-19) and the interval merge (Eq. 20).

use num_traits::Float;

use crate::{Interval, Payload};

/// The oracle `O(Δi, Δj)` (Gribel 2010, Eq. 18-19) with its constants and search window.
///
/// Lower values mean "more appropriate to merge". The pair with the lowest value among
/// `j in i+1..=i+window` is merged on overflow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Oracle<F> {
    /// Weight of the time gap `max(t_j^s - t_i^e, 0)` (Eq. 19, first term).
    pub h1: F,
    /// Weight of the depth jump `|z̄_i - z_j|` (Eq. 19, second term).
    pub h2: F,
    /// Weight of the slope difference `|k_i - k_j|` (Eq. 19, third term).
    pub h3: F,
    /// Weight of the summed durations (Eq. 19, fourth term).
    pub h4: F,
    /// Weight of the payload distance, L1 over RGB for colours (Eq. 19, fifth term).
    pub h5: F,
    /// Search window: `j` ranges over `i+1..=i+window` (Gribel 2010 §5.2: 3, or 10 for
    /// transparent content). At least 1 is used.
    pub window: usize,
    /// Coverage-preserving merge (our extension, not in the paper): the merged interval's
    /// coverage opacity ([`Payload::coverage`]) is set so that its coverage mass
    /// `alpha x duration` equals the inputs' `alpha_i len_i + alpha_j len_j` (plus the gap
    /// time that counts as covered, see [`Oracle::merge_in_list`]), capped at the larger
    /// input alpha. Across a gap the merged surface then contributes as much as the two
    /// inputs did instead of also covering the gap; a later interval that fills the gap
    /// raises the alpha back. Results can be partly transparent and need the blending
    /// resolve. Off in the paper's oracle.
    pub keep_coverage: bool,
}

impl<F: Float> Oracle<F> {
    /// The paper's oracle for opaque content: h1..h5 = 1000, 100, 1, 100, 1 (Gribel 2010, §6),
    /// window 3, Eq. 20 merge, no coverage scaling.
    pub fn paper() -> Self {
        let c = |v: f64| F::from(v).unwrap_or_else(F::one);
        Oracle {
            h1: c(1000.0),
            h2: c(100.0),
            h3: F::one(),
            h4: c(100.0),
            h5: F::one(),
            window: 3,
            keep_coverage: false,
        }
    }

    /// The paper's oracle for transparent content: window 10 (Gribel 2010, §5.2).
    pub fn paper_transparent() -> Self {
        Oracle {
            window: 10,
            ..Self::paper()
        }
    }

    /// The paper's oracle with the window chosen for the content: 3 if opaque, else 10.
    pub fn paper_for(opaque: bool) -> Self {
        if opaque {
            Self::paper()
        } else {
            Self::paper_transparent()
        }
    }

    /// The same oracle with another search window.
    pub fn with_window(self, window: usize) -> Self {
        Oracle { window, ..self }
    }

    /// The same oracle with the coverage-preserving merge on or off.
    pub fn with_keep_coverage(self, keep_coverage: bool) -> Self {
        Oracle {
            keep_coverage,
            ..self
        }
    }

    /// The oracle value `O(Δi, Δj)` for `i < j` (so `a.ts <= b.ts`), Gribel 2010, Eq. 19.
    ///
    /// Returns `+inf` instead of NaN when the terms overflow.
    pub fn cost<P: Payload<F>>(&self, a: &Interval<F, P>, b: &Interval<F, P>) -> F {
        let gap = (b.ts - a.te).max(F::zero());
        let o = self.h1 * gap
            + self.h2 * (a.end_depth() - b.z).abs()
            + self.h3 * (a.k - b.k).abs()
            + self.h4 * (a.duration() + b.duration())
            + self.h5 * a.payload.distance(&b.payload);
        if o.is_nan() { F::infinity() } else { o }
    }

    /// Merges `a` and `b` (`a` first in ts order), Gribel 2010 Eq. 20.
    ///
    /// Eq. 20 keeps `ts = a.ts` and `te = max(a.te, b.te)` exactly. If the merged depth would
    /// not be finite (extreme magnitudes), the depth and payload of the longer interval are
    /// kept instead, so no NaN or infinity escapes. With [`Oracle::keep_coverage`] and no
    /// list context, the whole gap between `a` and `b` counts as uncovered; see
    /// [`Oracle::merge_in_list`].
    pub fn merge<P: Payload<F>>(&self, a: &Interval<F, P>, b: &Interval<F, P>) -> Interval<F, P> {
        self.merge_with_hidden_gap(a, b, |_| F::zero())
    }

    /// Merges items `i < j` of a ts-sorted list of `n` intervals given by `get(index)`.
    ///
    /// Like [`Oracle::merge`]. With [`Oracle::keep_coverage`], only the part of the gap
    /// between the two where the merged surface would newly show something constant lowers
    /// its coverage: gap time where another opaque interval of the list is nearer (the
    /// merged surface is hidden there anyway) or where another interval that does not span
    /// the whole merged time is alive (what shows through would change over the span) counts
    /// as covered. What remains is gap time in front of a backdrop spanning the whole merge,
    /// or of nothing (the background); there the scaled, partly transparent interval gives
    /// exactly the time-averaged colour.
    pub fn merge_in_list<'a, P: Payload<F> + 'a>(
        &self,
        n: usize,
        get: impl Fn(usize) -> &'a Interval<F, P>,
        i: usize,
        j: usize,
    ) -> Interval<F, P>
    where
        F: 'a,
    {
        self.merge_with_hidden_gap(get(i), get(j), |m: &Interval<F, P>| {
            let (a, b) = (get(i), get(j));
            let (g0, g1) = (a.te, b.ts);
            // Union of the counted-as-covered parts of the gap: a sweep in ts order.
            let mut hidden = F::zero();
            let mut reach = g0;
            for q in (0..n).filter(|&q| q != i && q != j) {
                let e = get(q);
                let (u0, u1) = (e.ts.max(reach), e.te.min(g1));
                if u1 <= u0 {
                    continue;
                }
                let backdrop = e.ts <= m.ts && m.te <= e.te;
                let nearer = e.payload.is_opaque()
                    && e.depth_at(u0) < m.depth_at(u0)
                    && e.depth_at(u1) < m.depth_at(u1);
                if nearer || !backdrop {
                    hidden = hidden + (u1 - u0);
                    reach = u1;
                }
            }
            hidden
        })
    }

    fn merge_with_hidden_gap<P: Payload<F>>(
        &self,
        a: &Interval<F, P>,
        b: &Interval<F, P>,
        hidden: impl Fn(&Interval<F, P>) -> F,
    ) -> Interval<F, P> {
        let m = merge_eq20(a, b);
        if m.is_valid() {
            let span = m.duration();
            if self.keep_coverage && span > F::zero() {
                let (ca, cb) = (a.payload.coverage(), b.payload.coverage());
                let mass = ca * a.duration() + cb * b.duration();
                let alpha = (mass + hidden(&m) * m.payload.coverage()) / span;
                let alpha = alpha.min(ca.max(cb)).max(F::zero());
                if alpha.is_finite() {
                    return Interval {
                        payload: m.payload.with_coverage(alpha),
                        ..m
                    };
                }
            }
            return m;
        }
        let keep = if b.duration() > a.duration() { b } else { a };
        let z = keep.depth_at(a.ts);
        Interval {
            ts: a.ts,
            te: a.te.max(b.te),
            z: if z.is_finite() { z } else { a.z },
            k: if z.is_finite() { keep.k } else { a.k },
            payload: keep.payload,
        }
    }

    /// Index pair `(i, j)` with the lowest oracle value among `j in i+1..=i+window` over a
    /// list of `n` intervals given by `get(index)`, with its value. `None` when `n < 2`. Ties keep the first pair found (lowest `i`, then `j`).
    pub fn best_pair<'a, P: Payload<F> + 'a>(
        &self,
        n: usize,
        get: impl Fn(usize) -> &'a Interval<F, P>,
    ) -> Option<(usize, usize, F)>
    where
        F: 'a,
    {
        let w = self.window.max(1);
        let mut best: Option<(usize, usize, F)> = None;
        for i in 0..n {
            let a = get(i);
            for j in (i + 1)..n.min(i.saturating_add(w).saturating_add(1)) {
                let b = get(j);
                let o = self.cost(a, b);
                if best.is_none_or(|(_, _, bo)| o < bo) {
                    best = Some((i, j, o));
                }
            }
        }
        best
    }
}

impl<F: Float> Default for Oracle<F> {
    /// [`Oracle::paper`].
    fn default() -> Self {
        Self::paper()
    }
}

/// The blend weight of `b` in a merge: `len_b / (len_a + len_b)`, or 1/2 when both
/// intervals have zero length.
///
/// Gribel 2010, Eq. 20 prints `alpha = (t_j^e - t_i^s) / (len_i + len_j)`, which exceeds 1
/// for any two disjoint intervals (the numerator spans both lengths plus the gap) and would
/// extrapolate instead of blend. The text says alpha "is used to linearly blend parameters
/// depending on the lengths (in time) of the intervals", so we read the numerator as
/// `t_j^e - t_j^s`: each interval weighs by its duration, alpha stays in [0, 1], and equal
/// lengths give 1/2.
pub fn merge_alpha<F: Float, P>(a: &Interval<F, P>, b: &Interval<F, P>) -> F {
    let la = a.duration().max(F::zero());
    let lb = b.duration().max(F::zero());
    let total = la + lb;
    if total > F::zero() {
        (lb / total).min(F::one())
    } else {
        F::one() / (F::one() + F::one())
    }
}

/// Gribel 2010, Eq. 20: `ts' = t_a^s`, `te' = max(t_a^e, t_b^e)`, slope, depth at `t_a^s`
/// and payload blended by [`merge_alpha`].
pub fn merge_eq20<F: Float, P: Payload<F>>(
    a: &Interval<F, P>,
    b: &Interval<F, P>,
) -> Interval<F, P> {
    let alpha = merge_alpha(a, b);
    let one = F::one();
    Interval {
        ts: a.ts,
        te: a.te.max(b.te),
        z: (one - alpha) * a.z + alpha * b.depth_at(a.ts),
        k: (one - alpha) * a.k + alpha * b.k,
        payload: a.payload.blend(&b.payload, alpha),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rgba;

    fn iv(ts: f64, te: f64, z: f64, k: f64, r: f64) -> Interval<f64, Rgba<f64>> {
        Interval::new(ts, te, z, k, Rgba::opaque(r, 0.0, 0.0))
    }

    #[test]
    fn eq19_terms_add_up_by_hand() {
        let o = Oracle::<f64>::paper();
        let a = iv(0.0, 0.25, 1.0, 2.0, 0.5);
        let b = iv(0.5, 0.75, 2.0, -1.0, 0.25);
        // gap 0.25, z̄a = 1.5, |1.5 - 2| = 0.5, |2 - -1| = 3, lengths 0.5, colour 0.25.
        let expect = 1000.0 * 0.25 + 100.0 * 0.5 + 3.0 + 100.0 * 0.5 + 0.25;
        assert!((o.cost(&a, &b) - expect).abs() < 1e-12);
    }

    #[test]
    fn alpha_weighs_by_duration() {
        let a = iv(0.0, 0.25, 1.0, 0.0, 0.0);
        let b = iv(0.5, 0.75, 1.0, 0.0, 0.0);
        assert_eq!(merge_alpha(&a, &b), 0.5);
        let c = iv(0.5, 1.0, 1.0, 0.0, 0.0);
        assert!((merge_alpha(&a, &c) - 2.0 / 3.0).abs() < 1e-15);
        let z = iv(0.5, 0.5, 1.0, 0.0, 0.0);
        assert_eq!(merge_alpha(&z, &z), 0.5);
        assert_eq!(merge_alpha(&z, &c), 1.0);
    }

    #[test]
    fn eq20_blends_depth_at_first_start() {
        let a = iv(0.0, 0.5, 1.0, 0.0, 1.0);
        let b = iv(0.5, 1.0, 3.0, 2.0, 0.0);
        let m = merge_eq20(&a, &b);
        // b's depth at t = 0 is 3 - 2 * 0.5 = 2; alpha = 0.5.
        assert_eq!((m.ts, m.te, m.z, m.k), (0.0, 1.0, 1.5, 1.0));
        assert_eq!(m.payload.r, 0.5);
    }

    #[test]
    fn coverage_merge_scales_only_the_visible_constant_gap() {
        let o = Oracle::<f64>::paper().with_keep_coverage(true);
        let a = iv(0.0, 0.25, 1.0, 0.0, 1.0);
        let b = iv(0.5, 0.75, 1.0, 0.0, 1.0);
        // Nothing else: half of [0, 0.75] is gap -> alpha 0.5 / 0.75.
        let m = o.merge(&a, &b);
        assert!((m.payload.a - 0.5 / 0.75).abs() < 1e-15);
        // A backdrop spanning the whole merge behind the gap: still scaled.
        let back = iv(0.0, 1.0, 5.0, 0.0, 0.0);
        let l = [back, a, b];
        let m = o.merge_in_list(3, |q| &l[q], 1, 2);
        assert!((m.payload.a - 0.5 / 0.75).abs() < 1e-15);
        // A nearer opaque interval hides the gap: no scaling.
        let l = [a, iv(0.25, 0.5, 0.5, 0.0, 0.0), b];
        assert_eq!(o.merge_in_list(3, |q| &l[q], 0, 2).payload.a, 1.0);
        // A farther interval only in the gap (not a backdrop): no scaling either.
        let l = [a, iv(0.25, 0.5, 5.0, 0.0, 0.0), b];
        assert_eq!(o.merge_in_list(3, |q| &l[q], 0, 2).payload.a, 1.0);
        // A later piece filling the gap restores the coverage mass: alpha back to 1.
        let m = o.merge(&a, &b);
        let fill = iv(0.25, 0.5, 1.0, 0.0, 1.0);
        let r = o.merge(&m, &fill);
        assert!((r.payload.a - 1.0).abs() < 1e-15);
        // The paper's merge never scales.
        assert_eq!(Oracle::<f64>::paper().merge(&a, &b).payload.a, 1.0);
    }

    #[test]
    fn best_pair_respects_window() {
        let o = Oracle::<f64>::paper().with_window(1);
        let list = [
            iv(0.0, 0.1, 1.0, 0.0, 0.0),
            iv(0.3, 0.4, 9.0, 0.0, 1.0),
            iv(0.4, 0.5, 1.0, 0.0, 0.0),
        ];
        let (i, j, _) = o.best_pair(3, |k| &list[k]).unwrap_or((9, 9, 0.0));
        assert_eq!(j, i + 1);
        let (i, j, _) = Oracle::<f64>::paper()
            .best_pair(3, |k| &list[k])
            .unwrap_or((9, 9, 0.0));
        assert_eq!((i, j), (0, 2));
    }
}
