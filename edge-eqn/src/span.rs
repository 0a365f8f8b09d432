//! Time spans and the fixed-capacity coverage of one sample.

use arrayvec::ArrayVec;
use core::ops::Deref;
use num_traits::Float;

/// Most disjoint spans the coverage of one sample can have (Gribel 2010, §4.3: each of the
/// three inside functions has at most two parts; with at most six crossings in (0, 1) the
/// covered set has at most four components).
pub const MAX_SPANS: usize = 4;

/// A closed time span [t0, t1] inside the shutter interval [0, 1] (Gribel 2010, Eq. 16:
/// t_s = t0, t_e = t1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span<F> {
    /// Start time, in [0, 1].
    pub t0: F,
    /// End time, in [t0, 1].
    pub t1: F,
}

impl<F: Float> Span<F> {
    /// The span [t0, t1] (no checks; the crate only builds spans with 0 <= t0 <= t1 <= 1).
    pub fn new(t0: F, t1: F) -> Self {
        Span { t0, t1 }
    }

    /// Length t1 - t0.
    pub fn len(&self) -> F {
        self.t1 - self.t0
    }

    /// True when the span has zero length.
    pub fn is_empty(&self) -> bool {
        self.t1 <= self.t0
    }

    /// True when t0 <= t <= t1.
    pub fn contains(&self, t: F) -> bool {
        self.t0 <= t && t <= self.t1
    }

    /// The time halfway through the span.
    pub fn mid(&self) -> F {
        (self.t0 + self.t1) * crate::quadratic::lit(0.5)
    }
}

/// The times during the shutter at which a sample is inside a moving triangle (Gribel 2010,
/// Eq. 9: where v(t) = i₀(t) i₁(t) i₂(t) = 1): at most [`MAX_SPANS`] disjoint spans of
/// positive length, sorted by time, stored without heap allocation. Dereferences to
/// `&[Span<F>]`.
///
/// Instants of zero length (a sample touching an edge at one time, a tangent double root)
/// are not reported: they cover no time.
#[derive(Clone, Debug, PartialEq)]
pub struct Coverage<F> {
    spans: ArrayVec<Span<F>, MAX_SPANS>,
}

impl<F: Float> Coverage<F> {
    /// No coverage.
    pub fn empty() -> Self {
        Coverage {
            spans: ArrayVec::new(),
        }
    }

    /// Coverage of the whole shutter interval [0, 1].
    pub fn full() -> Self {
        let mut c = Self::empty();
        c.spans.push(Span::new(F::zero(), F::one()));
        c
    }

    /// Total covered time (sum of the span lengths), in [0, 1].
    pub fn total(&self) -> F {
        self.spans.iter().fold(F::zero(), |acc, s| acc + s.len())
    }

    /// True when t lies in one of the spans.
    pub fn contains(&self, t: F) -> bool {
        self.spans.iter().any(|s| s.contains(t))
    }

    /// The first `n` of the spans [s_k, e_k] (n <= MAX_SPANS), sorted, disjoint and of
    /// positive length, built in one go.
    #[inline(always)]
    pub(crate) fn from_starts_ends(s: [F; MAX_SPANS], e: [F; MAX_SPANS], n: usize) -> Self {
        let mut spans = ArrayVec::from([0, 1, 2, 3].map(|k| Span::new(s[k], e[k])));
        spans.truncate(n);
        Coverage { spans }
    }

    /// Appends [t0, t1], merging it with the previous span when they touch. Zero-length
    /// spans are dropped. Callers append in increasing time. (The coverage sweep keeps its
    /// spans in registers with the same rules; this is the reference its tests compare to.)
    #[cfg(test)]
    pub(crate) fn append(&mut self, t0: F, t1: F) {
        if t1 <= t0 {
            return;
        }
        if let Some(last) = self.spans.last_mut()
            && last.t1 >= t0
        {
            last.t1 = last.t1.max(t1);
            return;
        }
        if let Err(e) = self.spans.try_push(Span::new(t0, t1)) {
            // Unreachable by the counting argument in MAX_SPANS; stay total rather than panic.
            if let Some(last) = self.spans.last_mut() {
                last.t1 = e.element().t1;
            }
        }
    }
}

impl<F> Deref for Coverage<F> {
    type Target = [Span<F>];
    fn deref(&self) -> &[Span<F>] {
        &self.spans
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn append_merges_and_drops_empty() {
        let mut c = Coverage::<f64>::empty();
        c.append(0.1, 0.2);
        c.append(0.2, 0.3);
        c.append(0.4, 0.4);
        c.append(0.5, 0.6);
        assert_eq!(&c[..], &[Span::new(0.1, 0.3), Span::new(0.5, 0.6)]);
        assert!((c.total() - 0.3).abs() < 1e-15);
        assert!(c.contains(0.25) && !c.contains(0.45));
    }
}
