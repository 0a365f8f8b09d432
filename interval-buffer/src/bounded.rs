//! The bounded strategy: a W x H buffer holding at most K intervals per pixel in one flat
//! allocation, compressed with the oracle on overflow (Gribel 2010 §5, §5.2).

use num_traits::Float;
use rayon::prelude::*;

use crate::{CompressionTrace, Error, InsertOutcome, Insertion, Interval, Payload, PixelMut};

/// A W x H image of per-pixel interval lists, each at most `capacity` (K) long.
///
/// Storage is `W * H * K` interval slots plus a `u32` length per pixel, allocated once:
/// memory never grows,
/// however many intervals a pixel receives.
///
/// No background interval is stored: Gribel 2010 §5 starts every pixel with a far-plane
/// background interval, but that would take one of the K slots; the resolve shows the
/// background colour wherever no interval covers the time.
#[derive(Clone, Debug)]
pub struct BoundedBuffer<F, P> {
    width: usize,
    height: usize,
    capacity: usize,
    how: Insertion<F>,
    slots: Vec<Interval<F, P>>,
    lens: Vec<u32>,
    traced: Option<usize>,
    traces: Vec<Option<CompressionTrace<F, P>>>,
}

/// Mutable view of one row of a [`BoundedBuffer`], disjoint from every other row, so rows
/// can be filled in parallel without locks (see [`BoundedBuffer::par_rows_mut`]).
#[derive(Debug)]
pub struct RowMut<'a, F, P> {
    y: usize,
    width: usize,
    capacity: usize,
    how: &'a Insertion<F>,
    slots: &'a mut [Interval<F, P>],
    lens: &'a mut [u32],
    traced_x: Option<usize>,
    trace: &'a mut Option<CompressionTrace<F, P>>,
}

fn empty_interval<F: Float, P: Default>() -> Interval<F, P> {
    Interval::new(F::zero(), F::zero(), F::zero(), F::zero(), P::default())
}

impl<F: Float + Send + Sync, P: Payload<F> + Default + Send + Sync> BoundedBuffer<F, P> {
    /// An empty `width` x `height` buffer with `capacity` (K) slots per pixel.
    ///
    /// # Errors
    /// [`Error::InvalidCapacity`] when K is 0 or above `u32::MAX`; [`Error::TooLarge`] when
    /// the slot count overflows.
    pub fn new(
        width: usize,
        height: usize,
        capacity: usize,
        how: Insertion<F>,
    ) -> Result<Self, Error> {
        if capacity == 0 || u32::try_from(capacity).is_err() {
            return Err(Error::InvalidCapacity(capacity));
        }
        let pixels = width.checked_mul(height).ok_or(Error::TooLarge)?;
        let n = pixels.checked_mul(capacity).ok_or(Error::TooLarge)?;
        Ok(BoundedBuffer {
            width,
            height,
            capacity,
            how,
            slots: vec![empty_interval(); n],
            lens: vec![0; pixels],
            traced: None,
            traces: (0..height).map(|_| None).collect(),
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

    /// Slots per pixel, K.
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// The insertion settings (oracle, opaque flag).
    pub fn insertion(&self) -> &Insertion<F> {
        &self.how
    }

    /// Bytes of interval storage per pixel: K slots and the length.
    pub fn bytes_per_pixel(&self) -> usize {
        self.capacity * size_of::<Interval<F, P>>() + size_of::<u32>()
    }

    /// The intervals of pixel index `i = y * width + x`, sorted by ts; empty out of range.
    pub fn pixel_index(&self, i: usize) -> &[Interval<F, P>] {
        let len = self.lens.get(i).copied().unwrap_or(0) as usize;
        let start = i.saturating_mul(self.capacity);
        self.slots
            .get(start..start.saturating_add(len))
            .unwrap_or(&[])
    }

    /// The intervals of pixel (x, y), sorted by ts; empty out of range.
    pub fn pixel(&self, x: usize, y: usize) -> &[Interval<F, P>] {
        if x >= self.width || y >= self.height {
            return &[];
        }
        self.pixel_index(y * self.width + x)
    }

    /// Mutable view of pixel (x, y), e.g. to insert a batch with [`PixelMut::insert`]
    /// (pass [`BoundedBuffer::insertion`]); `None` out of range.
    pub fn pixel_mut(&mut self, x: usize, y: usize) -> Option<PixelMut<'_, F, P>> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = y * self.width + x;
        let k = self.capacity;
        let trace = if self.traced == Some(i) {
            self.traces.get_mut(y).and_then(|t| t.as_mut())
        } else {
            None
        };
        Some(PixelMut {
            slots: self.slots.get_mut(i * k..(i + 1) * k)?,
            len: self.lens.get_mut(i)?,
            trace,
        })
    }

    /// Inserts `iv` into pixel (x, y) (see [`PixelMut::insert`]).
    ///
    /// # Errors
    /// [`Error::PixelOutOfRange`] or [`Error::InvalidInterval`].
    pub fn insert(
        &mut self,
        x: usize,
        y: usize,
        iv: Interval<F, P>,
    ) -> Result<InsertOutcome<F>, Error> {
        let pixels = self.lens.len();
        let how = self.how;
        match self.pixel_mut(x, y) {
            Some(mut px) => px.insert(iv, &how),
            None => Err(Error::PixelOutOfRange {
                pixel: y.saturating_mul(self.width).saturating_add(x),
                pixels,
            }),
        }
    }

    /// Empties every pixel (keeps the allocation and the traced pixel, clears its trace).
    pub fn clear(&mut self) {
        self.lens.iter_mut().for_each(|l| *l = 0);
        if let Some(i) = self.traced {
            self.trace_pixel_index(i);
        }
    }

    /// Starts recording a [`CompressionTrace`] for pixel index `i` (replacing any earlier
    /// trace). Out-of-range indices record nothing.
    pub fn trace_pixel_index(&mut self, i: usize) {
        self.traces.iter_mut().for_each(|t| *t = None);
        self.traced = None;
        if self.width > 0 && i < self.lens.len() {
            self.traced = Some(i);
            if let Some(t) = self.traces.get_mut(i / self.width) {
                *t = Some(CompressionTrace::new(i));
            }
        }
    }

    /// The trace of the traced pixel, if one was requested.
    pub fn trace(&self) -> Option<&CompressionTrace<F, P>> {
        let i = self.traced?;
        self.traces.get(i / self.width.max(1))?.as_ref()
    }

    /// Takes the trace out and stops tracing.
    pub fn take_trace(&mut self) -> Option<CompressionTrace<F, P>> {
        let i = self.traced.take()?;
        self.traces.get_mut(i / self.width.max(1))?.take()
    }

    /// Disjoint mutable rows, for filling the buffer with rayon without locks:
    /// `buf.par_rows_mut().for_each(|mut row| { row.insert(x, iv); })`.
    pub fn par_rows_mut(&mut self) -> impl IndexedParallelIterator<Item = RowMut<'_, F, P>> + '_ {
        let w = self.width;
        let k = self.capacity;
        let chunk = (w * k).max(1);
        let how = &self.how;
        let traced = self.traced;
        self.slots
            .par_chunks_mut(chunk)
            .zip(self.lens.par_chunks_mut(w.max(1)))
            .zip(self.traces.par_iter_mut())
            .enumerate()
            .map(move |(y, ((slots, lens), trace))| RowMut {
                y,
                width: w,
                capacity: k,
                how,
                slots,
                lens,
                traced_x: traced.and_then(|i| (i / w.max(1) == y).then(|| i % w.max(1))),
                trace,
            })
    }
}

impl<'a, F: Float, P: Payload<F>> RowMut<'a, F, P> {
    /// The row's index y.
    pub fn y(&self) -> usize {
        self.y
    }

    /// The intervals of pixel x of this row, sorted by ts; empty out of range.
    pub fn pixel(&self, x: usize) -> &[Interval<F, P>] {
        let len = self.lens.get(x).copied().unwrap_or(0) as usize;
        let start = x.saturating_mul(self.capacity);
        self.slots
            .get(start..start.saturating_add(len))
            .unwrap_or(&[])
    }

    /// Inserts `iv` into pixel x of this row (see [`PixelMut::insert`]).
    ///
    /// # Errors
    /// [`Error::PixelOutOfRange`] or [`Error::InvalidInterval`].
    pub fn insert(&mut self, x: usize, iv: Interval<F, P>) -> Result<InsertOutcome<F>, Error> {
        if x >= self.width {
            return Err(Error::PixelOutOfRange {
                pixel: self.y.saturating_mul(self.width).saturating_add(x),
                pixels: self.width,
            });
        }
        let k = self.capacity;
        let trace = if self.traced_x == Some(x) {
            self.trace.as_mut()
        } else {
            None
        };
        let mut px = PixelMut {
            slots: &mut self.slots[x * k..(x + 1) * k],
            len: &mut self.lens[x],
            trace,
        };
        px.insert(iv, self.how)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rgba;

    #[test]
    fn rows_in_parallel_match_sequential_inserts() {
        let how = Insertion::paper(false);
        let mut a = BoundedBuffer::<f64, Rgba<f64>>::new(5, 4, 3, how).expect("buffer");
        let mut b = a.clone();
        let make = |x: usize, y: usize, s: usize| {
            let t = ((x * 7 + y * 3 + s * 5) % 11) as f64 / 11.0;
            Interval::new(
                t,
                (t + 0.2).min(1.0),
                1.0 + s as f64,
                0.0,
                Rgba::opaque(t, 0.0, 0.0),
            )
        };
        for y in 0..4 {
            for x in 0..5 {
                for s in 0..6 {
                    a.insert(x, y, make(x, y, s)).expect("insert");
                }
            }
        }
        b.par_rows_mut().for_each(|mut row| {
            for x in 0..5 {
                for s in 0..6 {
                    row.insert(x, make(x, row.y(), s)).expect("insert");
                }
            }
        });
        for i in 0..20 {
            assert_eq!(a.pixel_index(i), b.pixel_index(i));
            assert_eq!(a.pixel_index(i).len(), 3);
        }
        assert!(a.pixel(5, 0).is_empty() && a.insert(5, 0, make(0, 0, 0)).is_err());
    }
}
