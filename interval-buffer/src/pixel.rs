//! One pixel of the bounded buffer: insertion sort by ts, the opaque `LESS_EQUAL`
//! optimisations of Gribel 2010 Fig. 7, and oracle compression on overflow (§5.2).

use num_traits::Float;

use crate::{
    CompressionTrace, Error, InsertOutcome, Interval, MergeStep, Oracle, Payload, TraceEvent,
};

/// How intervals are inserted into a bounded pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Insertion<F> {
    /// The oracle used on overflow.
    pub oracle: Oracle<F>,
    /// The caller's promise that the content is opaque: enables the `LESS_EQUAL`
    /// optimisations of Gribel 2010, Fig. 7 (bottom two). Even then an interval only
    /// occludes others when its payload [`Payload::is_opaque`].
    pub opaque: bool,
}

impl<F: Float> Insertion<F> {
    /// The paper's settings for the content: [`Oracle::paper_for`] and the opaque flag.
    pub fn paper(opaque: bool) -> Self {
        Insertion {
            oracle: Oracle::paper_for(opaque),
            opaque,
        }
    }
}

/// Mutable view of one pixel of a bounded buffer: `capacity` slots, of which the first
/// `len` hold intervals sorted by ts.
#[derive(Debug)]
pub struct PixelMut<'a, F, P> {
    pub(crate) slots: &'a mut [Interval<F, P>],
    pub(crate) len: &'a mut u32,
    pub(crate) trace: Option<&'a mut CompressionTrace<F, P>>,
}

/// `true` when `e` is strictly nearer than `n` over the common span `[t0, t1]` (both
/// linear, so checking both ends suffices): `n` fails the `LESS_EQUAL` test there.
fn occludes<F: Float, P: Payload<F>>(e: &Interval<F, P>, n: &Interval<F, P>, t0: F, t1: F) -> bool {
    e.payload.is_opaque() && e.depth_at(t0) < n.depth_at(t0) && e.depth_at(t1) < n.depth_at(t1)
}

/// Clips `n` against opaque intervals in `list` that occlude one end of it, and reports
/// `None` when it is fully occluded. Never splits `n` into two.
fn clip_occluded<F: Float, P: Payload<F>>(
    list: &[Interval<F, P>],
    mut n: Interval<F, P>,
) -> (Option<Interval<F, P>>, bool) {
    let mut clipped = false;
    for _ in 0..=list.len() {
        let mut changed = false;
        for e in list {
            if e.te < n.ts || e.ts > n.te || e.duration() <= F::zero() {
                continue;
            }
            if e.ts <= n.ts && n.te <= e.te {
                if occludes(e, &n, n.ts, n.te) {
                    return (None, clipped);
                }
            } else if e.ts <= n.ts && e.te > n.ts && e.te < n.te {
                if occludes(e, &n, n.ts, e.te) {
                    n = n.clipped(e.te, n.te);
                    changed = true;
                }
            } else if e.ts > n.ts && e.ts < n.te && n.te <= e.te && occludes(e, &n, e.ts, n.te) {
                n = n.clipped(n.ts, e.ts);
                changed = true;
            }
        }
        clipped |= changed;
        if !changed {
            break;
        }
    }
    if n.duration() <= F::zero() {
        (None, clipped)
    } else {
        (Some(n), clipped)
    }
}

impl<'a, F: Float, P: Payload<F>> PixelMut<'a, F, P> {
    /// The pixel's intervals, sorted by ts.
    pub fn intervals(&self) -> &[Interval<F, P>] {
        let n = (*self.len as usize).min(self.slots.len());
        &self.slots[..n]
    }

    /// The pixel's capacity K.
    pub fn capacity(&self) -> usize {
        self.slots.len()
    }

    fn set(&mut self, q: usize, iv: Interval<F, P>) {
        if let Some(s) = self.slots.get_mut(q) {
            *s = iv;
        }
    }

    /// Inserts `iv` keeping the list sorted by ts (insertion sort; equal ts go after the
    /// existing ones), applying the opaque optimisations when `how.opaque`, and merging the
    /// oracle's best pair when the list would exceed the capacity (Gribel 2010 §5, §5.2).
    ///
    /// With `how.opaque`: a zero-length interval (it covers no time) or one fully occluded
    /// by an opaque interval is dropped; one whose start or end is occluded is clipped when
    /// that leaves one interval; existing intervals that the new opaque one covers and is
    /// nearer-or-equal to (`LESS_EQUAL`) over their whole span are removed.
    ///
    /// # Errors
    /// [`Error::InvalidInterval`] for a non-finite parameter or `ts > te`.
    pub fn insert(
        &mut self,
        iv: Interval<F, P>,
        how: &Insertion<F>,
    ) -> Result<InsertOutcome<F>, Error> {
        if !iv.is_valid() {
            return Err(Error::InvalidInterval);
        }
        let before = self.trace.as_ref().map(|_| self.intervals().to_vec());
        let outcome = self.insert_inner(iv, how);
        if let (Some(trace), Some(before)) = (self.trace.as_deref_mut(), before) {
            let n = (*self.len as usize).min(self.slots.len());
            trace.events.push(TraceEvent {
                inserted: iv,
                before,
                after: self.slots[..n].to_vec(),
                outcome,
            });
        }
        Ok(outcome)
    }

    fn insert_inner(&mut self, iv: Interval<F, P>, how: &Insertion<F>) -> InsertOutcome<F> {
        let cap = self.slots.len();
        let mut len = (*self.len as usize).min(cap);
        let mut outcome = InsertOutcome {
            stored: false,
            clipped: false,
            removed: 0,
            merged: None,
        };
        let mut n = iv;
        if how.opaque {
            let (kept, clipped) = clip_occluded(&self.slots[..len], n);
            outcome.clipped = clipped;
            match kept {
                Some(k) => n = k,
                None => return outcome,
            }
            if n.payload.is_opaque() {
                // Remove existing intervals hidden by n over their whole span (n wins ties).
                let mut w = 0;
                for r in 0..len {
                    let e = self.slots[r];
                    let hidden = n.ts <= e.ts
                        && e.te <= n.te
                        && n.depth_at(e.ts) <= e.z
                        && n.depth_at(e.te) <= e.end_depth();
                    if hidden {
                        outcome.removed += 1;
                    } else {
                        if w != r {
                            self.set(w, e);
                        }
                        w += 1;
                    }
                }
                len = w;
            }
        }
        outcome.stored = true;
        // Upper bound: first slot with ts > n.ts.
        let p = self.slots[..len].partition_point(|e| e.ts <= n.ts);
        if len < cap {
            self.slots.copy_within(p..len, p + 1);
            self.set(p, n);
            *self.len = (len + 1) as u32;
            return outcome;
        }
        // Overflow: the virtual list of cap + 1 intervals is slots with n at position p.
        let slots = &*self.slots;
        let virt = |q: usize| -> &Interval<F, P> {
            match q.cmp(&p) {
                core::cmp::Ordering::Less => &slots[q],
                core::cmp::Ordering::Equal => &n,
                core::cmp::Ordering::Greater => &slots[q - 1],
            }
        };
        let Some((i, j, cost)) = how.oracle.best_pair(cap + 1, virt) else {
            return outcome;
        };
        let merged = how.oracle.merge_in_list(cap + 1, virt, i, j);
        outcome.merged = Some(MergeStep { i, j, cost });
        if j == p {
            // n merged into an earlier slot.
            self.set(i, merged);
        } else if i == p {
            // n merged with slot j - 1, which leaves; the merged interval takes position p.
            self.slots.copy_within(p..j - 1, p + 1);
            self.set(p, merged);
        } else {
            // Two stored intervals merge; n takes the freed slot at its sorted position.
            let si = if i < p { i } else { i - 1 };
            let sj = if j < p { j } else { j - 1 };
            self.set(si, merged);
            self.slots.copy_within(sj + 1..cap, sj);
            let pn = if j < p { p - 1 } else { p };
            self.slots.copy_within(pn..cap - 1, pn + 1);
            self.set(pn, n);
        }
        *self.len = cap as u32;
        outcome
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rgba;

    fn iv(ts: f64, te: f64, z: f64, r: f64) -> Interval<f64, Rgba<f64>> {
        Interval::new(ts, te, z, 0.0, Rgba::opaque(r, 0.0, 0.0))
    }

    fn pixel<'a>(
        slots: &'a mut [Interval<f64, Rgba<f64>>],
        len: &'a mut u32,
    ) -> PixelMut<'a, f64, Rgba<f64>> {
        PixelMut {
            slots,
            len,
            trace: None,
        }
    }

    #[test]
    fn fig7_occluded_new_interval_is_clipped_then_dropped() {
        let mut slots = [iv(0.0, 0.0, 0.0, 0.0); 4];
        let mut len = 0;
        let mut px = pixel(&mut slots, &mut len);
        let how = Insertion::paper(true);
        px.insert(iv(0.0, 0.5, 1.0, 1.0), &how).ok();
        // Behind red over [0.25, 0.5]: clipped to [0.5, 0.75].
        let o = px.insert(iv(0.25, 0.75, 2.0, 0.5), &how).ok();
        assert!(o.is_some_and(|o| o.clipped && o.stored));
        assert_eq!(px.intervals()[1].ts, 0.5);
        // Fully behind: dropped.
        let o = px.insert(iv(0.1, 0.4, 3.0, 0.5), &how).ok();
        assert!(o.is_some_and(|o| !o.stored));
        assert_eq!(px.intervals().len(), 2);
        // In front over the whole of the first: removes it (LESS_EQUAL, equal depth wins).
        let o = px.insert(iv(0.0, 0.5, 1.0, 0.2), &how).ok();
        assert!(o.is_some_and(|o| o.removed == 1));
        assert_eq!(px.intervals()[0].payload.r, 0.2);
    }

    #[test]
    fn transparent_mode_keeps_everything_until_full() {
        let mut slots = [iv(0.0, 0.0, 0.0, 0.0); 2];
        let mut len = 0;
        let mut px = pixel(&mut slots, &mut len);
        let how = Insertion::paper(false);
        px.insert(iv(0.0, 1.0, 1.0, 1.0), &how).ok();
        px.insert(iv(0.2, 0.4, 5.0, 0.5), &how).ok();
        assert_eq!(px.intervals().len(), 2);
        let o = px.insert(iv(0.1, 0.3, 5.0, 0.5), &how).ok();
        assert!(o.is_some_and(|o| o.merged.is_some()));
        assert_eq!(px.intervals().len(), 2);
        assert!(px.intervals()[0].ts <= px.intervals()[1].ts);
    }
}
