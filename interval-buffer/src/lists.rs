//! Exact per-pixel lists built from one batch of `(pixel, interval)` pairs, with memory
//! reused from batch to batch (Rønnow 2021 §4.1-4.2: count, exclusive scan, place,
//! segmented sort by ts).
//!
//! The lists are those of [`crate::IntervalCounts`] → [`crate::ExactFill`] →
//! [`crate::ExactBuffer`] fed the same pairs in the same order (each pixel sorted by ts,
//! equal ts in insertion order), built for a caller that has a whole region's intervals
//! at hand (a renderer emitting one image row at a time): only a 16-byte key per interval
//! (8 bytes for f32 times) is placed and sorted, each interval is copied once, from the
//! batch straight to its sorted place, and the storage of the previous batch is reused (no
//! per-batch allocation or zero fill).

use num_traits::Float;

use crate::{Error, Interval};

/// Per-pixel interval lists sorted by ts, rebuilt from a batch of pairs by
/// [`PixelLists::rebuild`]; the storage grows to the largest batch and is reused.
///
/// ```
/// use interval_buffer::{Interval, PixelLists, Rgba};
/// let red = Rgba::opaque(1.0_f32, 0.0, 0.0);
/// let batch = [
///     (1, Interval::new(0.5, 0.75, 2.0, 0.0, red)),
///     (0, Interval::new(0.0, 1.0, 3.0, 0.0, red)),
///     (1, Interval::new(0.25, 0.5, 1.0, 0.0, red)),
/// ];
/// let mut lists = PixelLists::new();
/// lists.rebuild(2, &batch)?;
/// let ts: Vec<f32> = lists.pixel(1).iter().map(|iv| iv.ts).collect();
/// assert_eq!(ts, [0.25, 0.5]);
/// assert_eq!(lists.count(0), 1);
/// # Ok::<(), interval_buffer::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct PixelLists<F, P> {
    /// Start of each pixel's list in `data`, then the total.
    offsets: Vec<u32>,
    /// Next free key slot of each pixel while placing.
    cursors: Vec<u32>,
    /// Pixel by pixel: each interval's time key and its index in the batch.
    keys: Vec<(u64, u32)>,
    /// The same packed into one word where the times are f32 ([`narrow_key`]).
    narrow: Vec<u64>,
    /// The intervals in pixel order, each pixel's sorted by ts.
    data: Vec<Interval<F, P>>,
}

/// Order-preserving integer key of a finite time: `a < b` exactly when `key(a) < key(b)`,
/// and `key(-0) == key(+0)` (those times compare equal, so they keep batch order). The
/// time is widened to f64 exactly (f32 and f64 both are) and its bits mapped to an
/// unsigned order: sign bit set → all bits flipped, else the sign bit set.
fn ts_key<F: Float>(t: F) -> u64 {
    let bits = (t.to_f64().unwrap_or(0.0) + 0.0).to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | (1 << 63)
    }
}

/// Bits of a [`ts_key`] that carry no order when the time is an f32: widened to f64, its
/// low 29 mantissa bits are zero, which the key maps to all zeros (positive times) or all
/// ones (negative times).
const NARROW_BITS: u32 = 29;

/// The low [`NARROW_BITS`] bits.
const NARROW_MASK: u64 = (1 << NARROW_BITS) - 1;

/// `key` (a [`ts_key`]) with batch index `i` in its low [`NARROW_BITS`] bits, when those
/// bits carry no order (the time was an f32) and `i` fits: one word that orders like
/// `(key, i)`. `None` otherwise.
#[inline]
fn narrow_key(key: u64, i: usize) -> Option<u64> {
    let low = key & NARROW_MASK;
    let i = u64::try_from(i).ok().filter(|&i| i <= NARROW_MASK)?;
    (low == 0 || low == NARROW_MASK).then_some((key & !NARROW_MASK) | i)
}

/// Places the key `key(i, iv)` of every pair of `batch` in its pixel's segment of `keys`
/// (segments from the counted `offsets`, pairs in batch order), sorts each segment, and
/// gathers the intervals into `data` in key order, `index` giving a key's batch index: the
/// place, sort and gather steps of [`PixelLists::rebuild`] for one key type. False, with
/// nothing gathered, when `key` gives `None`.
fn place_sorted<K: Ord + Copy + Default, F: Copy, P: Copy>(
    offsets: &[u32],
    cursors: &mut Vec<u32>,
    keys: &mut Vec<K>,
    data: &mut Vec<Interval<F, P>>,
    batch: &[(u32, Interval<F, P>)],
    key: impl Fn(usize, &Interval<F, P>) -> Option<K>,
    index: impl Fn(K) -> usize,
) -> bool {
    cursors.clear();
    cursors.extend_from_slice(offsets.split_last().map_or(&[][..], |(_, starts)| starts));
    // Every slot is written below (each pair once, at its pixel's next slot), so the kept
    // slots of a longer previous batch need no zero fill.
    keys.resize(batch.len(), K::default());
    for (i, (p, iv)) in batch.iter().enumerate() {
        let Some(k) = key(i, iv) else {
            return false;
        };
        if let Some(c) = cursors.get_mut(*p as usize)
            && let Some(slot) = keys.get_mut(*c as usize)
        {
            *slot = k;
            *c += 1;
        }
    }
    // Sort each segment by its keys: the stable order by ts (ties by batch index).
    for w in offsets.windows(2) {
        if let Some(seg) = keys.get_mut(w[0] as usize..w[1] as usize)
            && !seg.is_sorted()
        {
            seg.sort_unstable();
        }
    }
    data.reserve(batch.len());
    data.extend(
        keys.iter()
            .filter_map(|&k| batch.get(index(k)).map(|(_, iv)| *iv)),
    );
    true
}

impl<F: Float, P: Copy> PixelLists<F, P> {
    /// Bytes the lists hold per interval of a batch, beyond the batch itself: its sort key
    /// and its place in the sorted copy (for memory budgets; the offsets add 8 bytes per
    /// pixel).
    pub const BYTES_PER_INTERVAL: usize =
        std::mem::size_of::<(u64, u32)>() + std::mem::size_of::<Interval<F, P>>();

    /// No pixels.
    pub fn new() -> Self {
        Self {
            offsets: Vec::new(),
            cursors: Vec::new(),
            keys: Vec::new(),
            narrow: Vec::new(),
            data: Vec::new(),
        }
    }

    /// Replaces the lists by those of `pixels` pixels receiving `batch`: pair `(p, iv)`
    /// appends `iv` to pixel `p`'s list, and each list is then sorted by ts, stably (equal
    /// ts keep their batch order: the `LESS_EQUAL` rule "the later-inserted surface wins"
    /// that the resolve relies on). On error the lists are left empty.
    ///
    /// # Errors
    /// [`Error::PixelOutOfRange`] for a pixel index `>= pixels`, [`Error::InvalidInterval`]
    /// for an interval with a non-finite parameter or `ts > te`, and
    /// [`Error::TooManyIntervals`] for a batch of more than `u32::MAX` intervals.
    pub fn rebuild(&mut self, pixels: usize, batch: &[(u32, Interval<F, P>)]) -> Result<(), Error> {
        self.offsets.clear();
        self.data.clear();
        let result = self.place(pixels, batch);
        if result.is_err() {
            self.offsets.clear();
            self.keys.clear();
            self.narrow.clear();
        }
        result
    }

    /// Count, scan, place the keys, sort each pixel's keys, gather the intervals.
    fn place(&mut self, pixels: usize, batch: &[(u32, Interval<F, P>)]) -> Result<(), Error> {
        if u32::try_from(batch.len()).is_err() {
            return Err(Error::TooManyIntervals {
                total: batch.len() as u64,
            });
        }
        // Count into offsets[p + 1], validating.
        self.offsets.resize(pixels + 1, 0);
        for (p, iv) in batch {
            let p = *p as usize;
            let out = Error::PixelOutOfRange { pixel: p, pixels };
            if p >= pixels {
                return Err(out);
            }
            let slot = self.offsets.get_mut(p + 1).ok_or(out)?;
            if !iv.is_valid() {
                return Err(Error::InvalidInterval);
            }
            *slot += 1;
        }
        // Inclusive scan of the shifted counts = exclusive scan (the total fits in u32).
        let mut sum = 0u32;
        for o in self.offsets.iter_mut() {
            sum += *o;
            *o = sum;
        }
        // f32 times: one-word keys, which sort faster (the same order); else, or where a
        // time or index does not fit one, the pair (time key, batch index).
        let (offsets, cursors, data) = (&self.offsets, &mut self.cursors, &mut self.data);
        if std::mem::size_of::<F>() <= 4
            && place_sorted(
                offsets,
                cursors,
                &mut self.narrow,
                data,
                batch,
                |i, iv| narrow_key(ts_key(iv.ts), i),
                |k| (k & NARROW_MASK) as usize,
            )
        {
            return Ok(());
        }
        place_sorted(
            offsets,
            cursors,
            &mut self.keys,
            data,
            batch,
            |i, iv| Some((ts_key(iv.ts), i as u32)),
            |(_, i)| i as usize,
        );
        Ok(())
    }

    /// Number of pixels of the last [`PixelLists::rebuild`] (0 after an error).
    pub fn pixels(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Total number of intervals held.
    pub fn len(&self) -> usize {
        self.data.len()
    }

    /// True when no pixel holds an interval.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// The intervals of pixel index `i`, sorted by ts; empty out of range.
    pub fn pixel(&self, i: usize) -> &[Interval<F, P>] {
        match (self.offsets.get(i), self.offsets.get(i.wrapping_add(1))) {
            (Some(&a), Some(&b)) => self.data.get(a as usize..b as usize).unwrap_or(&[]),
            _ => &[],
        }
    }

    /// Number of intervals in pixel index `i` (0 out of range).
    pub fn count(&self, i: usize) -> u32 {
        match (self.offsets.get(i), self.offsets.get(i.wrapping_add(1))) {
            (Some(&a), Some(&b)) => b.saturating_sub(a),
            _ => 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{IntervalCounts, Rgba};

    fn iv(ts: f64, te: f64, tag: f64) -> Interval<f64, Rgba<f64>> {
        Interval::new(ts, te, 1.0, 0.0, Rgba::opaque(tag, 0.0, 0.0))
    }

    #[test]
    fn keys_order_like_the_times() {
        let times = [
            -1.0,
            -f64::MIN_POSITIVE,
            -0.0,
            0.0,
            f64::MIN_POSITIVE,
            0.25,
            1.0 - f64::EPSILON,
            1.0,
            2.0,
        ];
        for &a in &times {
            for &b in &times {
                let want = a.partial_cmp(&b).unwrap();
                assert_eq!(ts_key(a).cmp(&ts_key(b)), want, "{a} {b}");
            }
        }
        for &a in &times {
            let a32 = a as f32;
            assert_eq!(ts_key(a32), ts_key(f64::from(a32)));
        }
    }

    #[test]
    fn narrow_keys_order_like_time_then_index() {
        // f32 times of both signs, both zeros and neighbours one ulp apart: every pair of
        // (time, index) orders as its packed key does.
        let times = [
            -1.0_f32,
            -0.5,
            -f32::MIN_POSITIVE,
            -0.0,
            0.0,
            f32::MIN_POSITIVE,
            0.25,
            0.25 + f32::EPSILON / 4.0,
            1.0 - f32::EPSILON,
            1.0,
            3.5,
        ];
        let indices = [0, 1, 7, NARROW_MASK as usize];
        for &a in &times {
            for &b in &times {
                for &i in &indices {
                    for &j in &indices {
                        let want = (ts_key(a), i).cmp(&(ts_key(b), j));
                        let (ka, kb) = (narrow_key(ts_key(a), i), narrow_key(ts_key(b), j));
                        assert_eq!(ka.unwrap().cmp(&kb.unwrap()), want, "{a} {i} {b} {j}");
                    }
                }
            }
        }
        // An index past the low bits, or a time only f64 holds, does not fit.
        assert_eq!(narrow_key(ts_key(0.5_f32), NARROW_MASK as usize + 1), None);
        assert_eq!(narrow_key(ts_key(0.1_f64), 0), None);
        assert_eq!(narrow_key(ts_key(-0.1_f64), 0), None);
    }

    #[test]
    fn matches_count_fill_finish_with_ties_in_batch_order() {
        // Three pixels; ties at 0.5 (and -0 vs +0) must keep batch order.
        let batch = [
            (2, iv(0.5, 0.6, 1.0)),
            (0, iv(0.7, 0.8, 2.0)),
            (2, iv(0.5, 0.9, 3.0)),
            (0, iv(0.0, 0.1, 4.0)),
            (2, iv(0.1, 0.2, 5.0)),
            (0, iv(-0.0, 0.3, 6.0)),
            (2, iv(0.5, 0.5, 7.0)),
        ];
        let mut counts = IntervalCounts::new(3, 1).unwrap();
        for &(p, _) in &batch {
            counts.count(p as usize).unwrap();
        }
        let mut fill = counts.finish::<f64, Rgba<f64>>().unwrap();
        for &(p, iv) in &batch {
            fill.push(p as usize, iv).unwrap();
        }
        let exact = fill.finish().unwrap();
        let mut lists = PixelLists::new();
        lists.rebuild(3, &batch).unwrap();
        for p in 0..3 {
            assert_eq!(lists.pixel(p), exact.pixel_index(p), "pixel {p}");
            assert_eq!(lists.count(p) as usize, exact.pixel_index(p).len());
        }
        let tags: Vec<f64> = lists.pixel(2).iter().map(|iv| iv.payload.r).collect();
        assert_eq!(tags, [5.0, 1.0, 3.0, 7.0]);
        assert_eq!((lists.pixels(), lists.len()), (3, batch.len()));
    }

    #[test]
    fn reuse_forgets_the_previous_batch() {
        let mut lists = PixelLists::new();
        let first = [(1, iv(0.5, 1.0, 1.0)), (1, iv(0.0, 1.0, 1.0))];
        lists.rebuild(2, &first).unwrap();
        lists.rebuild(3, &[(0, iv(0.2, 0.3, 2.0))]).unwrap();
        assert_eq!(lists.pixel(0).len(), 1);
        assert!(lists.pixel(1).is_empty() && lists.pixel(2).is_empty());
        assert!(lists.pixel(3).is_empty() && lists.pixel(usize::MAX).is_empty());
        lists.rebuild(0, &[]).unwrap();
        assert!(lists.is_empty() && lists.pixels() == 0);
    }

    #[test]
    fn bad_pairs_are_errors_and_leave_nothing() {
        let mut lists = PixelLists::new();
        let good = iv(0.0, 1.0, 1.0);
        assert_eq!(
            lists.rebuild(2, &[(0, good), (2, good)]),
            Err(Error::PixelOutOfRange {
                pixel: 2,
                pixels: 2
            })
        );
        assert!(lists.is_empty() && lists.pixel(0).is_empty() && lists.pixels() == 0);
        let reversed = iv(0.6, 0.5, 1.0);
        assert_eq!(
            lists.rebuild(2, &[(0, reversed)]),
            Err(Error::InvalidInterval)
        );
        let nan = iv(f64::NAN, 0.5, 1.0);
        assert_eq!(lists.rebuild(2, &[(0, nan)]), Err(Error::InvalidInterval));
        assert!(lists.is_empty());
    }
}
