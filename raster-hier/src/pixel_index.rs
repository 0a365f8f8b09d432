//! The samples of one pixel of a sample-pattern tile in time order: what traversal levels
//! finer than the tmsnet tile (2x2 quads, single pixels) need to test only their own
//! pixels' samples inside a time interval.
//!
//! tmsnet's time-range iterator walks a whole tile's net in time order; a sub-tile would
//! have to step over the samples of every other pixel. The tile's scramble is an XOR of the
//! fixed-point x and y (Munkberg 2011, §5), which maps pixel column `c` of the unscrambled
//! net to column `c ^ (mask_x >> sub_bits_x)` (likewise rows) and leaves the time index
//! alone. So one table of the **unscrambled** net, bucketed by pixel and sorted by index,
//! serves every tile: the samples of scrambled pixel p are the bucket of p XOR the tile's
//! pixel mask, a time range is a binary search in it, and each sample is rebuilt from
//! tmsnet's own `TileLayout::sub_pixel` (tabulated once per fixed-point fraction) and its
//! time from tmsnet's sampler, so positions and times are bit-identical to the tile
//! iterator's (unit test below).

use core::ops::Range;

use num_traits::Float;
use tmsnet::{Scramble, TileLayout, TileSample, TileSampler, TimeOrderedNet};

/// One sample of the unscrambled net: index, fixed-point x and y, time.
#[derive(Clone, Copy, Debug)]
struct Entry<F> {
    j: u32,
    x: u32,
    y: u32,
    t: F,
}

/// Per pixel of the pattern tile, its samples of the unscrambled time-ordered net, sorted
/// by time index.
#[derive(Clone, Debug)]
pub(crate) struct PixelIndex<F> {
    layout: TileLayout,
    /// `starts[p] .. starts[p + 1]` are the entries of unscrambled pixel p (row-major).
    starts: Vec<u32>,
    entries: Vec<Entry<F>>,
    /// tmsnet's sub-pixel offset of every fixed-point fraction `0 .. 2^sub_bits` in x and
    /// in y (from `TileLayout::sub_pixel`, so bit-identical), when those tables are small.
    fractions: Option<(Vec<F>, Vec<F>)>,
}

/// Largest number of fractional bits for which the offsets are tabulated.
const MAX_TABLE_BITS: u32 = 12;

impl<F: Float> PixelIndex<F> {
    /// The index of `net` (with the tile layout `layout`); O(2^m) time and memory, once per
    /// frame. `None` if the net does not match the layout.
    pub(crate) fn new(layout: TileLayout, net: TimeOrderedNet) -> Option<Self> {
        let raw = TileSampler::with_net(layout, net, Scramble::NONE).ok()?;
        let n = layout.samples();
        let (w, h) = (layout.width(), layout.height());
        let pixels = (w * h) as usize;
        let pixel_of = |x: u32, y: u32| {
            let (p, _) = layout.split(x, y);
            (p[1] * w + p[0]) as usize
        };
        let mut count = vec![0u32; pixels + 1];
        for (_, x, y) in net.iter_range(0..n) {
            if let Some(c) = count.get_mut(pixel_of(x, y) + 1) {
                *c += 1;
            }
        }
        for p in 0..pixels {
            count[p + 1] += count[p];
        }
        let starts = count.clone();
        let mut fill = count;
        let mut entries = vec![
            Entry {
                j: 0,
                x: 0,
                y: 0,
                t: F::zero()
            };
            n as usize
        ];
        // The index walk is in time order, so every bucket ends up sorted by j.
        for s in raw.samples_in_indices::<F>(0..n).ok()? {
            let p = pixel_of(s.x, s.y);
            let slot = fill.get_mut(p)?;
            *entries.get_mut(*slot as usize)? = Entry {
                j: s.index,
                x: s.x,
                y: s.y,
                t: s.t,
            };
            *slot += 1;
        }
        let (bx, by) = (layout.sub_bits_x(), layout.sub_bits_y());
        let fractions = if bx <= MAX_TABLE_BITS && by <= MAX_TABLE_BITS {
            let xs = (0..1u32 << bx)
                .map(|v| layout.sub_pixel::<F>(v, 0).map(|s| s.offset[0]))
                .collect::<Result<Vec<F>, _>>()
                .ok()?;
            let ys = (0..1u32 << by)
                .map(|v| layout.sub_pixel::<F>(0, v).map(|s| s.offset[1]))
                .collect::<Result<Vec<F>, _>>()
                .ok()?;
            Some((xs, ys))
        } else {
            None
        };
        Some(PixelIndex {
            layout,
            starts,
            entries,
            fractions,
        })
    }

    /// The samples of the pixels `xs` × `ys` (within the tile, row by row) of the tile
    /// scrambled with `scramble` whose index lies in `range`, each pixel's in time order,
    /// the same `TileSample`s that `TileSampler::samples_in_indices` yields for them.
    #[inline]
    pub(crate) fn samples_in_rect(
        &self,
        scramble: Scramble,
        xs: Range<u32>,
        ys: Range<u32>,
        range: Range<u32>,
    ) -> PixelSamples<'_, F> {
        PixelSamples {
            index: self,
            scramble: scramble.truncated(self.layout.m()),
            px: xs.start,
            py: ys.start,
            xs,
            ys_end: ys.end,
            range,
            pixel: [0, 0],
            hits: [].iter(),
        }
    }

    /// The entries of pixel `(px, py)` of the tile scrambled with `s` (already truncated)
    /// from the first with index ≥ `start` on.
    #[inline]
    fn pixel_from(&self, s: Scramble, px: u32, py: u32, start: u32) -> &[Entry<F>] {
        let (ux, uy) = (
            px ^ (s.x >> self.layout.sub_bits_x()),
            py ^ (s.y >> self.layout.sub_bits_y()),
        );
        let p = (uy * self.layout.width() + ux) as usize;
        let (Some(&a), Some(&b)) = (self.starts.get(p), self.starts.get(p + 1)) else {
            return &[];
        };
        let Some(bucket) = self.entries.get(a as usize..b as usize) else {
            return &[];
        };
        let lo = bucket.partition_point(|e| e.j < start);
        bucket.get(lo..).unwrap_or(&[])
    }

    /// The sample of entry `e` of pixel `pixel` of the tile scrambled with `s`.
    #[inline]
    fn sample(&self, s: Scramble, pixel: [u32; 2], e: &Entry<F>) -> Option<TileSample<F>> {
        let (x, y) = (e.x ^ s.x, e.y ^ s.y);
        let offset = match &self.fractions {
            Some((fx, fy)) => {
                let lx = x & ((1u32 << self.layout.sub_bits_x()) - 1);
                let ly = y & ((1u32 << self.layout.sub_bits_y()) - 1);
                match (fx.get(lx as usize), fy.get(ly as usize)) {
                    (Some(&ox), Some(&oy)) => [ox, oy],
                    _ => return None,
                }
            }
            None => self.layout.sub_pixel::<F>(x, y).ok()?.offset,
        };
        Some(TileSample {
            index: e.j,
            x,
            y,
            pixel,
            offset,
            t: e.t,
        })
    }
}

/// Iterator over the samples of a rectangle of pixels of one tile in an index (time)
/// range; see [`PixelIndex::samples_in_rect`].
#[derive(Clone, Debug)]
pub(crate) struct PixelSamples<'a, F> {
    index: &'a PixelIndex<F>,
    scramble: Scramble,
    xs: Range<u32>,
    ys_end: u32,
    /// The next pixel to open.
    px: u32,
    py: u32,
    range: Range<u32>,
    /// The open pixel and its remaining entries from the range start on.
    pixel: [u32; 2],
    hits: core::slice::Iter<'a, Entry<F>>,
}

impl<F: Float> Iterator for PixelSamples<'_, F> {
    type Item = TileSample<F>;

    #[inline]
    fn next(&mut self) -> Option<TileSample<F>> {
        loop {
            if let Some(e) = self.hits.next() {
                if e.j >= self.range.end {
                    self.hits = [].iter();
                    continue;
                }
                match self.index.sample(self.scramble, self.pixel, e) {
                    Some(s) => return Some(s),
                    None => continue,
                }
            }
            if !self.open_next_pixel() {
                return None;
            }
        }
    }
}

impl<F: Float> PixelSamples<'_, F> {
    /// Opens the next pixel (its entries from the range start on); false after the last.
    /// Kept out of line so that the per-sample step inlined into the caller's sample loop
    /// stays small.
    #[inline(never)]
    fn open_next_pixel(&mut self) -> bool {
        if self.py >= self.ys_end || self.xs.is_empty() {
            return false;
        }
        self.pixel = [self.px, self.py];
        self.hits = self
            .index
            .pixel_from(self.scramble, self.px, self.py, self.range.start)
            .iter();
        self.px += 1;
        if self.px >= self.xs.end {
            self.px = self.xs.start;
            self.py += 1;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against tmsnet's tile iterator: for scrambled tiles, every pixel and time range, the
    /// index yields exactly the iterator's samples of that pixel, bit for bit, in order.
    #[test]
    fn matches_the_tile_iterator_per_pixel() {
        for (w, h, spp) in [(4u32, 4u32, 16u32), (4, 4, 4), (8, 8, 2), (2, 2, 8)] {
            let layout = TileLayout::new(w, h, spp).expect("layout");
            let net = TimeOrderedNet::permuted(layout.m()).expect("net");
            let index = PixelIndex::<f32>::new(layout, net).expect("index");
            let index64 = PixelIndex::<f64>::new(layout, net).expect("index");
            let n = layout.samples();
            for (tx, ty) in [(0u32, 0u32), (3, 7), (101, 5)] {
                let scramble = Scramble::for_tile(tx, ty, 9);
                let sampler = TileSampler::with_net(layout, net, scramble).expect("sampler");
                for range in [0..n, 0..1, n / 3..n / 2 + 1, n - 1..n, 5..5] {
                    let all: Vec<_> = sampler
                        .samples_in_indices::<f32>(range.clone())
                        .expect("iter")
                        .collect();
                    let mut total = 0;
                    for py in 0..h {
                        for px in 0..w {
                            let want: Vec<_> = all
                                .iter()
                                .filter(|s| s.pixel == [px, py])
                                .copied()
                                .collect();
                            let got = index
                                .samples_in_rect(scramble, px..px + 1, py..py + 1, range.clone())
                                .collect::<Vec<_>>();
                            assert_eq!(got, want, "{w}x{h}x{spp} tile ({tx},{ty}) {range:?}");
                            total += got.len();
                            let want64: Vec<_> = sampler
                                .samples_in_indices::<f64>(range.clone())
                                .expect("iter")
                                .filter(|s| s.pixel == [px, py])
                                .collect();
                            let got64 = index64
                                .samples_in_rect(scramble, px..px + 1, py..py + 1, range.clone())
                                .collect::<Vec<_>>();
                            assert_eq!(got64, want64);
                        }
                    }
                    assert_eq!(total, all.len());
                }
            }
        }
    }

    /// A rectangle of pixels yields its pixels' samples row by row, each pixel's as
    /// tmsnet's tile iterator gives them (in time order); empty rectangles yield nothing.
    #[test]
    fn rect_is_its_pixels_row_by_row() {
        let layout = TileLayout::new(4, 4, 16).expect("layout");
        let net = TimeOrderedNet::permuted(layout.m()).expect("net");
        let index = PixelIndex::<f32>::new(layout, net).expect("index");
        let n = layout.samples();
        let scramble = Scramble::for_tile(2, 9, 5);
        let sampler = TileSampler::with_net(layout, net, scramble).expect("sampler");
        for range in [0..n, n / 4..n / 2, 7..8, 3..3] {
            let all: Vec<_> = sampler
                .samples_in_indices::<f32>(range.clone())
                .expect("iter")
                .collect();
            for (xs, ys) in [
                (0..2, 2..4),
                (1..4, 0..3),
                (3..4, 3..4),
                (0..4, 0..4),
                (2..2, 0..4),
            ] {
                let want: Vec<_> = ys
                    .clone()
                    .flat_map(|py| xs.clone().map(move |px| [px, py]))
                    .flat_map(|pixel| all.iter().filter(move |s| s.pixel == pixel).copied())
                    .collect();
                let got: Vec<_> = index
                    .samples_in_rect(scramble, xs.clone(), ys.clone(), range.clone())
                    .collect();
                assert_eq!(got, want, "{xs:?} x {ys:?} in {range:?}");
            }
        }
    }
}
