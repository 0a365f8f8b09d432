//! The exact strategy: unbounded per-pixel lists in one flat array, built in two passes
//! (Rønnow 2021 §4.1: count, exclusive scan, fill; §4.2: segmented sort by ts).

use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

use num_traits::Float;
use rayon::prelude::*;

use crate::{Error, Interval};

/// Pass 1 of the exact strategy: the number of intervals each pixel will receive.
///
/// Counts from several threads are combined either by giving each thread its own
/// `IntervalCounts` and summing with [`IntervalCounts::add`], by filling disjoint rows with
/// [`IntervalCounts::par_rows_mut`], or with [`AtomicIntervalCounts`].
///
/// ```
/// use interval_buffer::{Interval, IntervalCounts, Rgba};
/// let white = Rgba::opaque(1.0_f32, 1.0, 1.0);
/// let emitted = [(3, Interval::new(0.5, 0.9, 1.0, 0.0, white)), (3, Interval::new(0.1, 0.2, 2.0, 0.0, white))];
/// let mut counts = IntervalCounts::new(2, 2)?; // pass 1: count
/// for (pixel, _) in &emitted {
///     counts.count(*pixel)?;
/// }
/// let mut fill = counts.finish()?; // exclusive scan, one allocation
/// for (pixel, iv) in emitted {
///     fill.push(pixel, iv)?; // pass 2: fill
/// }
/// let buf = fill.finish()?; // segmented sort by ts
/// assert_eq!(buf.pixel(1, 1)[0].ts, 0.1);
/// # Ok::<(), interval_buffer::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IntervalCounts {
    width: usize,
    height: usize,
    counts: Vec<u32>,
}

/// Mutable view of one row of an [`IntervalCounts`].
#[derive(Debug)]
pub struct CountRowMut<'a> {
    y: usize,
    counts: &'a mut [u32],
}

impl CountRowMut<'_> {
    /// The row's index y.
    pub fn y(&self) -> usize {
        self.y
    }

    /// Counts `n` more intervals for pixel x of this row.
    ///
    /// # Errors
    /// [`Error::PixelOutOfRange`], or [`Error::TooManyIntervals`] when the pixel's count
    /// would pass `u32::MAX` (the count is left unchanged).
    pub fn count_n(&mut self, x: usize, n: u32) -> Result<(), Error> {
        let pixels = self.counts.len();
        let c = self
            .counts
            .get_mut(x)
            .ok_or(Error::PixelOutOfRange { pixel: x, pixels })?;
        *c = c.checked_add(n).ok_or(Error::TooManyIntervals {
            total: u64::from(*c) + u64::from(n),
        })?;
        Ok(())
    }

    /// Counts one more interval for pixel x of this row.
    ///
    /// # Errors
    /// As [`CountRowMut::count_n`].
    pub fn count(&mut self, x: usize) -> Result<(), Error> {
        self.count_n(x, 1)
    }
}

fn pixels_of(width: usize, height: usize) -> Result<usize, Error> {
    width.checked_mul(height).ok_or(Error::TooLarge)
}

impl IntervalCounts {
    /// All-zero counts for a `width` x `height` image.
    ///
    /// # Errors
    /// [`Error::TooLarge`] when `width * height` overflows.
    pub fn new(width: usize, height: usize) -> Result<Self, Error> {
        Ok(IntervalCounts {
            width,
            height,
            counts: vec![0; pixels_of(width, height)?],
        })
    }

    /// Image width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The per-pixel counts, row-major.
    pub fn counts(&self) -> &[u32] {
        &self.counts
    }

    /// Counts `n` more intervals for pixel index `pixel`.
    ///
    /// # Errors
    /// [`Error::PixelOutOfRange`], or [`Error::TooManyIntervals`] when the pixel's count
    /// would pass `u32::MAX` (the count is left unchanged).
    pub fn count_n(&mut self, pixel: usize, n: u32) -> Result<(), Error> {
        let pixels = self.counts.len();
        let c = self
            .counts
            .get_mut(pixel)
            .ok_or(Error::PixelOutOfRange { pixel, pixels })?;
        *c = c.checked_add(n).ok_or(Error::TooManyIntervals {
            total: u64::from(*c) + u64::from(n),
        })?;
        Ok(())
    }

    /// Counts one more interval for pixel index `pixel`.
    ///
    /// # Errors
    /// As [`IntervalCounts::count_n`].
    pub fn count(&mut self, pixel: usize) -> Result<(), Error> {
        self.count_n(pixel, 1)
    }

    /// Adds another thread's counts for the same image (per-thread counting, then merge).
    ///
    /// # Errors
    /// [`Error::TooLarge`] for a different image size; [`Error::TooManyIntervals`] when a
    /// pixel's sum passes `u32::MAX` (counts are then unspecified but finite).
    pub fn add(&mut self, other: &IntervalCounts) -> Result<(), Error> {
        if other.counts.len() != self.counts.len() {
            return Err(Error::TooLarge);
        }
        let mut overflow = None;
        for (a, &b) in self.counts.iter_mut().zip(&other.counts) {
            match a.checked_add(b) {
                Some(s) => *a = s,
                None => {
                    overflow = Some(u64::from(*a) + u64::from(b));
                    *a = u32::MAX;
                }
            }
        }
        match overflow {
            Some(total) => Err(Error::TooManyIntervals { total }),
            None => Ok(()),
        }
    }

    /// Disjoint mutable rows, for counting in parallel without locks.
    pub fn par_rows_mut(&mut self) -> impl IndexedParallelIterator<Item = CountRowMut<'_>> + '_ {
        self.counts
            .par_chunks_mut(self.width.max(1))
            .enumerate()
            .map(|(y, counts)| CountRowMut { y, counts })
    }

    /// Sum of all counts, in `u64`.
    pub fn total(&self) -> u64 {
        self.counts.iter().map(|&c| u64::from(c)).sum()
    }

    /// Ends pass 1: exclusive scan of the counts into `u32` offsets (Rønnow 2021 §4.1, 2b)
    /// and one allocation for all intervals (2c).
    ///
    /// # Errors
    /// [`Error::TooManyIntervals`] when the total exceeds `u32::MAX` (checked before any
    /// allocation); [`Error::TooLarge`] when the allocation fails.
    pub fn finish<F: Float, P: Copy + Default>(self) -> Result<ExactFill<F, P>, Error> {
        let mut offsets = Vec::with_capacity(self.counts.len() + 1);
        let mut sum: u32 = 0;
        offsets.push(0);
        for &c in &self.counts {
            // `ok_or_else`: the error sums every count, so it must only be built on overflow
            // (built eagerly it made `finish` quadratic in the pixel count).
            sum = sum.checked_add(c).ok_or_else(|| Error::TooManyIntervals {
                total: self.total(),
            })?;
            offsets.push(sum);
        }
        let mut data = Vec::new();
        data.try_reserve_exact(sum as usize)
            .map_err(|_| Error::TooLarge)?;
        data.resize(
            sum as usize,
            Interval::new(F::zero(), F::zero(), F::zero(), F::zero(), P::default()),
        );
        Ok(ExactFill {
            width: self.width,
            height: self.height,
            cursors: vec![0; self.counts.len()],
            counts: self.counts,
            offsets,
            data,
        })
    }
}

/// Pass-1 counts shared between threads through atomic counters (`&self` access).
#[derive(Debug)]
pub struct AtomicIntervalCounts {
    width: usize,
    height: usize,
    counts: Vec<AtomicU32>,
    overflow: AtomicBool,
}

impl AtomicIntervalCounts {
    /// All-zero counts for a `width` x `height` image.
    ///
    /// # Errors
    /// [`Error::TooLarge`] when `width * height` overflows.
    pub fn new(width: usize, height: usize) -> Result<Self, Error> {
        Ok(AtomicIntervalCounts {
            width,
            height,
            counts: (0..pixels_of(width, height)?)
                .map(|_| AtomicU32::new(0))
                .collect(),
            overflow: AtomicBool::new(false),
        })
    }

    /// Counts one more interval for pixel index `pixel` (relaxed atomic increment).
    ///
    /// # Errors
    /// [`Error::PixelOutOfRange`]. A pixel passing `u32::MAX` is reported by
    /// [`AtomicIntervalCounts::into_counts`].
    pub fn count(&self, pixel: usize) -> Result<(), Error> {
        let pixels = self.counts.len();
        let c = self
            .counts
            .get(pixel)
            .ok_or(Error::PixelOutOfRange { pixel, pixels })?;
        if c.fetch_add(1, Ordering::Relaxed) == u32::MAX {
            self.overflow.store(true, Ordering::Relaxed);
        }
        Ok(())
    }

    /// The plain counts, ready for [`IntervalCounts::finish`].
    ///
    /// # Errors
    /// [`Error::TooManyIntervals`] when some pixel's counter wrapped past `u32::MAX`.
    pub fn into_counts(self) -> Result<IntervalCounts, Error> {
        if self.overflow.into_inner() {
            return Err(Error::TooManyIntervals {
                total: u64::from(u32::MAX) + 1,
            });
        }
        Ok(IntervalCounts {
            width: self.width,
            height: self.height,
            counts: self.counts.into_iter().map(AtomicU32::into_inner).collect(),
        })
    }
}

/// Pass 2 of the exact strategy: intervals written at their pixel's offset (Rønnow 2021
/// §4.1, 2d), then sorted per pixel by [`ExactFill::finish`].
#[derive(Clone, Debug)]
pub struct ExactFill<F, P> {
    width: usize,
    height: usize,
    counts: Vec<u32>,
    offsets: Vec<u32>,
    cursors: Vec<u32>,
    data: Vec<Interval<F, P>>,
}

/// Mutable view of one row of an [`ExactFill`], disjoint from every other row.
#[derive(Debug)]
pub struct FillRowMut<'a, F, P> {
    y: usize,
    counts: &'a [u32],
    offsets: &'a [u32],
    cursors: &'a mut [u32],
    data: &'a mut [Interval<F, P>],
}

impl<F: Float, P> FillRowMut<'_, F, P> {
    /// Writes `iv` at local pixel `local` (reported as `global` in errors).
    fn push_local(&mut self, local: usize, global: usize, iv: Interval<F, P>) -> Result<(), Error> {
        if !iv.is_valid() {
            return Err(Error::InvalidInterval);
        }
        let out = Error::PixelOutOfRange {
            pixel: global,
            pixels: self.counts.len(),
        };
        let base = self.offsets.first().copied().unwrap_or(0);
        let (Some(&counted), Some(&off), Some(cur)) = (
            self.counts.get(local),
            self.offsets.get(local),
            self.cursors.get_mut(local),
        ) else {
            return Err(out);
        };
        let over = Error::PushOverCount {
            pixel: global,
            counted,
        };
        if *cur >= counted {
            return Err(over);
        }
        let slot = self
            .data
            .get_mut((off - base + *cur) as usize)
            .ok_or(over)?;
        *slot = iv;
        *cur += 1;
        Ok(())
    }
}

/// Sorts each pixel segment of one row by ts, stably. Short segments use the standard
/// stable sort (insertion sort below 20 elements); longer ones sort `(ts, index)` keys
/// unstably (unique keys, so the order is the stable one) and permute through a scratch
/// copy, which moves each 32-byte interval twice instead of once per comparison.
fn sort_segments<F: Float, P: Copy>(offsets: &[u32], base: u32, data: &mut [Interval<F, P>]) {
    let by_ts = |p: &Interval<F, P>, q: &Interval<F, P>| {
        p.ts.partial_cmp(&q.ts)
            .unwrap_or(core::cmp::Ordering::Equal)
    };
    let mut keys: Vec<(F, u32)> = Vec::new();
    let mut scratch: Vec<Interval<F, P>> = Vec::new();
    for w in offsets.windows(2) {
        let (a, b) = ((w[0] - base) as usize, (w[1] - base) as usize);
        let Some(seg) = data.get_mut(a..b) else {
            continue;
        };
        if seg.windows(2).all(|x| x[0].ts <= x[1].ts) {
            continue;
        }
        if seg.len() <= KEY_SORT_MIN {
            seg.sort_by(by_ts);
            continue;
        }
        keys.clear();
        keys.extend(seg.iter().enumerate().map(|(i, iv)| (iv.ts, i as u32)));
        keys.sort_unstable_by(|p, q| {
            p.0.partial_cmp(&q.0)
                .unwrap_or(core::cmp::Ordering::Equal)
                .then(p.1.cmp(&q.1))
        });
        scratch.clear();
        scratch.extend_from_slice(seg);
        for (dst, &(_, i)) in seg.iter_mut().zip(&keys) {
            if let Some(src) = scratch.get(i as usize) {
                *dst = *src;
            }
        }
    }
}

/// Segments longer than this use the key sort in [`sort_segments`].
const KEY_SORT_MIN: usize = 24;

/// Splits `data` into the per-row chunks given by the row starts in `offsets`.
fn split_rows<'a, T>(
    mut data: &'a mut [T],
    offsets: &[u32],
    width: usize,
    height: usize,
) -> Vec<&'a mut [T]> {
    let mut rows = Vec::with_capacity(height);
    for y in 0..height {
        let a = offsets.get(y * width).copied().unwrap_or(0);
        let b = offsets.get((y + 1) * width).copied().unwrap_or(a);
        let n = (b.saturating_sub(a) as usize).min(data.len());
        let (row, rest) = std::mem::take(&mut data).split_at_mut(n);
        rows.push(row);
        data = rest;
    }
    rows
}

impl<F: Float + Send + Sync, P: Copy + Send + Sync> ExactFill<F, P> {
    /// Writes `iv` into pixel index `pixel` (pass 2).
    ///
    /// # Errors
    /// [`Error::InvalidInterval`], [`Error::PixelOutOfRange`], or [`Error::PushOverCount`]
    /// when the pixel already received all the intervals counted for it.
    pub fn push(&mut self, pixel: usize, iv: Interval<F, P>) -> Result<(), Error> {
        FillRowMut {
            y: 0,
            counts: &self.counts,
            offsets: &self.offsets,
            cursors: &mut self.cursors,
            data: &mut self.data,
        }
        .push_local(pixel, pixel, iv)
    }

    /// Disjoint mutable rows, for filling in parallel without locks or atomics.
    pub fn par_rows_mut(
        &mut self,
    ) -> impl IndexedParallelIterator<Item = FillRowMut<'_, F, P>> + '_ {
        let w = self.width;
        let rows = split_rows(&mut self.data, &self.offsets, w, self.height);
        let offsets = &self.offsets;
        let counts = &self.counts;
        rows.into_par_iter()
            .zip(self.cursors.par_chunks_mut(w.max(1)))
            .enumerate()
            .map(move |(y, (data, cursors))| FillRowMut {
                y,
                counts: counts.get(y * w..(y + 1) * w).unwrap_or(&[]),
                offsets: offsets.get(y * w..(y + 1) * w + 1).unwrap_or(&[]),
                cursors,
                data,
            })
    }

    /// Ends pass 2: checks that every pixel received exactly its count, then sorts each
    /// pixel's segment by ts (stable; Rønnow 2021 §4.2), rows in parallel.
    ///
    /// # Errors
    /// [`Error::CountMismatch`] for the first pixel that received fewer than counted.
    pub fn finish(mut self) -> Result<ExactBuffer<F, P>, Error> {
        if let Some((pixel, (&counted, &pushed))) = self
            .counts
            .iter()
            .zip(&self.cursors)
            .enumerate()
            .find(|(_, (c, p))| c != p)
        {
            return Err(Error::CountMismatch {
                pixel,
                counted,
                pushed,
            });
        }
        let w = self.width;
        let offsets = &self.offsets;
        split_rows(&mut self.data, offsets, w, self.height)
            .into_par_iter()
            .enumerate()
            .for_each(|(y, row)| {
                if let Some(o) = offsets.get(y * w..(y + 1) * w + 1) {
                    sort_segments(o, o[0], row);
                }
            });
        Ok(ExactBuffer {
            width: self.width,
            height: self.height,
            offsets: self.offsets,
            data: self.data,
        })
    }
}

impl<F: Float, P> FillRowMut<'_, F, P> {
    /// The row's index y.
    pub fn y(&self) -> usize {
        self.y
    }

    /// Writes `iv` into pixel x of this row.
    ///
    /// # Errors
    /// As [`ExactFill::push`].
    pub fn push(&mut self, x: usize, iv: Interval<F, P>) -> Result<(), Error> {
        let global = self.y.saturating_mul(self.counts.len()).saturating_add(x);
        self.push_local(x, global, iv)
    }
}

/// The finished exact buffer: every pixel's intervals, sorted by ts, in one flat array
/// indexed by `u32` offsets.
#[derive(Clone, Debug)]
pub struct ExactBuffer<F, P> {
    width: usize,
    height: usize,
    offsets: Vec<u32>,
    data: Vec<Interval<F, P>>,
}

impl<F, P> ExactBuffer<F, P> {
    /// Image width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The intervals of pixel index `i = y * width + x`, sorted by ts; empty out of range.
    pub fn pixel_index(&self, i: usize) -> &[Interval<F, P>] {
        match (
            self.offsets.get(i),
            i.checked_add(1).and_then(|j| self.offsets.get(j)),
        ) {
            (Some(&a), Some(&b)) => self.data.get(a as usize..b as usize).unwrap_or(&[]),
            _ => &[],
        }
    }

    /// The intervals of pixel (x, y), sorted by ts; empty out of range.
    pub fn pixel(&self, x: usize, y: usize) -> &[Interval<F, P>] {
        if x >= self.width || y >= self.height {
            return &[];
        }
        self.pixel_index(y * self.width + x)
    }

    /// The exclusive-scan offsets, one per pixel plus the total at the end.
    pub fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// All intervals, pixel after pixel.
    pub fn intervals(&self) -> &[Interval<F, P>] {
        &self.data
    }

    /// Bytes of storage: intervals plus offsets.
    pub fn bytes(&self) -> usize {
        self.data.len() * size_of::<Interval<F, P>>() + self.offsets.len() * size_of::<u32>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_scan_fill_sort_by_hand() {
        let mut c = IntervalCounts::new(2, 1).expect("counts");
        c.count(1).and(c.count(1)).and(c.count(0)).expect("count");
        let mut f = c.finish::<f64, ()>().expect("scan");
        f.push(1, Interval::new(0.5, 0.6, 1.0, 0.0, ()))
            .expect("push");
        f.push(1, Interval::new(0.1, 0.2, 1.0, 0.0, ()))
            .expect("push");
        assert!(f.clone().finish().is_err());
        f.push(0, Interval::new(0.3, 0.4, 1.0, 0.0, ()))
            .expect("push");
        assert!(matches!(
            f.push(0, Interval::new(0.3, 0.4, 1.0, 0.0, ())),
            Err(Error::PushOverCount { .. })
        ));
        let b = f.finish().expect("finish");
        assert_eq!(b.offsets(), &[0, 1, 3]);
        assert_eq!(
            b.pixel(1, 0).iter().map(|i| i.ts).collect::<Vec<_>>(),
            vec![0.1, 0.5]
        );
        assert_eq!(b.pixel(0, 0)[0].ts, 0.3);
    }

    #[test]
    fn scan_past_u32_is_an_error_before_allocating() {
        let mut c = IntervalCounts::new(2, 1).expect("counts");
        c.count_n(0, 3_000_000_000)
            .and(c.count_n(1, 3_000_000_000))
            .expect("count");
        assert_eq!(
            c.finish::<f32, ()>().err(),
            Some(Error::TooManyIntervals {
                total: 6_000_000_000
            })
        );
        let mut d = IntervalCounts::new(1, 1).expect("counts");
        d.count_n(0, u32::MAX).expect("count");
        assert!(matches!(d.count(0), Err(Error::TooManyIntervals { .. })));
    }
}
