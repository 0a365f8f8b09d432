//! Tile layout and the tile sampler: a W x H pixel tile with S samples per pixel uses one
//! net of 2^m = W·H·S points whose x, y integers are fixed point — pixel index in the top
//! bits, sub-pixel position below (Munkberg 2011, §5: 4x4 pixels at 16 spp is m = 8, 2.6
//! fixed point).

use core::ops::Range;

use num_traits::Float;

use crate::error::Error;
use crate::ordered::TimeOrderedNet;
use crate::scramble::Scramble;
use crate::time_range::time_index_range;

/// A W x H pixel tile with S samples per pixel, all powers of two, `2 <= W·H·S <= 2^31`.
///
/// With `W = 2^a`, `H = 2^b`: of the m bits of x the top a are the pixel column and the
/// low `m - a` the sub-pixel position; likewise y with b. A pixel is an elementary interval
/// of volume 1/(W·H), so it holds exactly `2^(m-a-b) = S` points of a (0,m,3)-net, and
/// those form a (0, log2 S, 2)-net inside the pixel. Non-square tiles are allowed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TileLayout {
    width: u32,
    height: u32,
    spp: u32,
    m: u32,
    /// Fractional bits of x and y (`m - log2 W`, `m - log2 H`), kept so that
    /// [`TileLayout::split`], once per sample, does no bit counting.
    sub_bits: [u32; 2],
}

/// Where a sample falls in its tile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubPixel<F> {
    /// Pixel column and row within the tile, `[0, W) x [0, H)`.
    pub pixel: [u32; 2],
    /// Position inside the pixel, each in `[0, 1)` (pixel centre at 0.5).
    pub offset: [F; 2],
}

impl TileLayout {
    /// A tile of `width x height` pixels with `spp` samples per pixel. Errors with
    /// [`Error::NotPowerOfTwo`] for zero or non-power-of-two sizes and with
    /// [`Error::TileTooLarge`] unless `2 <= width·height·spp <= 2^31`.
    pub fn new(width: u32, height: u32, spp: u32) -> Result<Self, Error> {
        for (what, value) in [
            ("width", width),
            ("height", height),
            ("samples per pixel", spp),
        ] {
            if !value.is_power_of_two() {
                return Err(Error::NotPowerOfTwo { what, value });
            }
        }
        let m = width.trailing_zeros() + height.trailing_zeros() + spp.trailing_zeros();
        if !(1..=crate::MAX_M).contains(&m) {
            return Err(Error::TileTooLarge { log2_samples: m });
        }
        Ok(Self {
            width,
            height,
            spp,
            m,
            sub_bits: [m - width.trailing_zeros(), m - height.trailing_zeros()],
        })
    }

    /// Tile width W in pixels.
    #[inline]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Tile height H in pixels.
    #[inline]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Samples per pixel S.
    #[inline]
    pub fn spp(&self) -> u32 {
        self.spp
    }

    /// The net size exponent `m = log2(W·H·S)`.
    #[inline]
    pub fn m(&self) -> u32 {
        self.m
    }

    /// The number of samples in the tile, 2^m.
    #[inline]
    pub fn samples(&self) -> u32 {
        1 << self.m
    }

    /// Fractional bits of x: `m - log2 W`.
    #[inline]
    pub fn sub_bits_x(&self) -> u32 {
        self.sub_bits[0]
    }

    /// Fractional bits of y: `m - log2 H`.
    #[inline]
    pub fn sub_bits_y(&self) -> u32 {
        self.sub_bits[1]
    }

    /// Integer split of fixed-point `(x, y)`: `([pixel_x, pixel_y], [sub_x, sub_y])` with
    /// `sub_x` in `[0, 2^sub_bits_x)`. Bits of x, y at or above m are ignored.
    #[inline]
    pub fn split(&self, x: u32, y: u32) -> ([u32; 2], [u32; 2]) {
        let [bx, by] = self.sub_bits;
        // m <= MAX_M = 31 and bx, by <= m, so every shift is in range: no branch.
        let (x, y) = (x & ((1 << self.m) - 1), y & ((1 << self.m) - 1));
        (
            [x >> bx, y >> by],
            [x & ((1 << bx) - 1), y & ((1 << by) - 1)],
        )
    }

    /// Pixel and sub-pixel offset in `[0, 1)` of fixed-point `(x, y)`. The offset is the
    /// fixed-point fraction rounded to `F`, kept strictly below 1 (relevant only for f32
    /// with more than 24 fractional bits).
    pub fn sub_pixel<F: Float>(&self, x: u32, y: u32) -> Result<SubPixel<F>, Error> {
        let scale = self.scales::<F>()?;
        Ok(self.sub_pixel_with(x, y, &scale))
    }

    #[inline]
    fn sub_pixel_with<F: Float>(&self, x: u32, y: u32, s: &Scales<F>) -> SubPixel<F> {
        let (pixel, sub) = self.split(x, y);
        SubPixel {
            pixel,
            offset: [
                fraction(sub[0], s.sub_x, s.below_one),
                fraction(sub[1], s.sub_y, s.below_one),
            ],
        }
    }

    fn scales<F: Float>(&self) -> Result<Scales<F>, Error> {
        let pow = |bits: u32| F::from(f64::from(1u32 << bits).recip()).ok_or(Error::Conversion);
        let two = F::one() + F::one();
        Ok(Scales {
            sub_x: pow(self.sub_bits_x())?,
            sub_y: pow(self.sub_bits_y())?,
            time: pow(self.m)?,
            below_one: F::one() - F::epsilon() / two,
        })
    }
}

/// Precomputed powers of two in `F` for converting fixed point to floats.
#[derive(Clone, Copy, Debug)]
struct Scales<F> {
    sub_x: F,
    sub_y: F,
    time: F,
    below_one: F,
}

/// `v * scale` in F, clamped below 1. `v` is converted through f64 (exact for u32).
#[inline]
fn fraction<F: Float>(v: u32, scale: F, below_one: F) -> F {
    // NumCast from f64 succeeds for every float type; zero is an unreachable fallback.
    let f = F::from(f64::from(v)).unwrap_or_else(F::zero) * scale;
    if f < below_one { f } else { below_one }
}

/// One sample of a tile: index, fixed-point coordinates, pixel, sub-pixel offset and time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileSample<F> {
    /// Index j in the tile's net (the time index).
    pub index: u32,
    /// Scrambled fixed-point x in `[0, 2^m)`.
    pub x: u32,
    /// Scrambled fixed-point y in `[0, 2^m)`.
    pub y: u32,
    /// Pixel column and row within the tile.
    pub pixel: [u32; 2],
    /// Position inside the pixel, each in `[0, 1)`.
    pub offset: [F; 2],
    /// Time `j / 2^m` in [0, 1), rounded to `F` (exact for f64; for f32 exact up to m = 24,
    /// beyond that consecutive times may round to equal values or to 1).
    pub t: F,
}

impl<F: Float> TileSample<F> {
    /// Position in tile pixel units, `pixel + offset` (add the tile's origin for screen
    /// coordinates; pixel centres are at `i + 0.5`). Exact, and so equal to
    /// `x / 2^sub_bits_x`, whenever the fixed-point value fits `F`'s mantissa (always for
    /// f64; for f32 when m <= 24).
    #[inline]
    pub fn position(&self) -> [F; 2] {
        let px = |p: u32| F::from(f64::from(p)).unwrap_or_else(F::zero);
        [
            px(self.pixel[0]) + self.offset[0],
            px(self.pixel[1]) + self.offset[1],
        ]
    }
}

/// The samples of one tile: the time-ordered net of the tile's layout, scrambled with the
/// tile's hash (Munkberg 2011, §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileSampler {
    layout: TileLayout,
    net: TimeOrderedNet,
    scramble: Scramble,
}

impl TileSampler {
    /// The paper's sampler for the tile at `(tile_x, tile_y)`: the permuted net (Eq. 12)
    /// with random digit scrambling from `Scramble::for_tile(tile_x, tile_y, seed)`.
    pub fn new(layout: TileLayout, tile_x: u32, tile_y: u32, seed: u64) -> Result<Self, Error> {
        Self::with_net(
            layout,
            TimeOrderedNet::permuted(layout.m())?,
            Scramble::for_tile(tile_x, tile_y, seed),
        )
    }

    /// A sampler with an explicit net (e.g. [`TimeOrderedNet::original`]) and scramble
    /// ([`Scramble::NONE`] for the raw net). Errors if the net's m differs from the layout's.
    pub fn with_net(
        layout: TileLayout,
        net: TimeOrderedNet,
        scramble: Scramble,
    ) -> Result<Self, Error> {
        if net.m() != layout.m() {
            return Err(Error::SizeMismatch {
                expected: layout.m(),
                found: net.m(),
            });
        }
        Ok(Self {
            layout,
            net,
            scramble: scramble.truncated(layout.m()),
        })
    }

    /// The tile layout.
    #[inline]
    pub fn layout(&self) -> &TileLayout {
        &self.layout
    }

    /// The scramble (masks already cut to m bits).
    #[inline]
    pub fn scramble(&self) -> Scramble {
        self.scramble
    }

    /// The underlying unscrambled net.
    #[inline]
    pub fn net(&self) -> &TimeOrderedNet {
        &self.net
    }

    /// Sample `j` of the tile; errors if `j >= 2^m` or `F` cannot hold the scale factors.
    pub fn sample<F: Float>(&self, j: u32) -> Result<TileSample<F>, Error> {
        let (x, y) = self.net.xy(j)?;
        let scales = self.layout.scales::<F>()?;
        Ok(self.make(j, x, y, &scales))
    }

    /// All samples whose time `j / 2^m` lies in `[t0, t1]`, in time order, without touching
    /// the others: the index range from [`time_index_range`] (O(1)), then one XOR per
    /// coordinate per sample. Empty for `t0 > t1` or an interval between two sample times;
    /// errors for non-finite bounds.
    ///
    /// ```
    /// use tmsnet::{TileLayout, TileSampler};
    /// let tile = TileSampler::new(TileLayout::new(4, 4, 16)?, 3, 7, 42)?;
    /// let mut n = 0;
    /// for s in tile.samples_in(0.25f32, 0.5)? {
    ///     assert!(s.t >= 0.25 && s.t <= 0.5 && s.pixel[0] < 4 && s.offset[1] < 1.0);
    ///     n += 1;
    /// }
    /// assert_eq!(n, 65); // j = 64..=128 of 256
    /// # Ok::<(), tmsnet::Error>(())
    /// ```
    pub fn samples_in<F: Float>(&self, t0: F, t1: F) -> Result<TileSamples<'_, F>, Error> {
        let range = time_index_range(t0, t1, self.layout.m())?;
        self.samples_in_indices(range)
    }

    /// The samples with index in `range` (clipped to `0..2^m`), in order.
    pub fn samples_in_indices<F: Float>(
        &self,
        range: Range<u32>,
    ) -> Result<TileSamples<'_, F>, Error> {
        let scales = self.layout.scales::<F>()?;
        Ok(TileSamples {
            sampler: self,
            inner: self.net.iter_range(range),
            scales,
        })
    }

    #[inline]
    fn make<F: Float>(&self, j: u32, x: u32, y: u32, s: &Scales<F>) -> TileSample<F> {
        let (x, y) = (x ^ self.scramble.x, y ^ self.scramble.y);
        let sp = self.layout.sub_pixel_with(x, y, s);
        let t = F::from(f64::from(j)).unwrap_or_else(F::zero) * s.time;
        TileSample {
            index: j,
            x,
            y,
            pixel: sp.pixel,
            offset: sp.offset,
            t,
        }
    }
}

/// Iterator over a tile's samples in an index (time) range; see
/// [`TileSampler::samples_in`].
#[derive(Clone, Debug)]
pub struct TileSamples<'a, F> {
    sampler: &'a TileSampler,
    inner: crate::ordered::XyIter<'a>,
    scales: Scales<F>,
}

impl<F: Float> Iterator for TileSamples<'_, F> {
    type Item = TileSample<F>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let (j, x, y) = self.inner.next()?;
        Some(self.sampler.make(j, x, y, &self.scales))
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        self.inner.size_hint()
    }
}

impl<F: Float> ExactSizeIterator for TileSamples<'_, F> {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_validation() {
        assert_eq!(TileLayout::new(4, 4, 16).unwrap().m(), 8);
        assert_eq!(TileLayout::new(8, 2, 4).unwrap().sub_bits_x(), 3);
        assert_eq!(
            TileLayout::new(3, 4, 16),
            Err(Error::NotPowerOfTwo {
                what: "width",
                value: 3
            })
        );
        assert!(TileLayout::new(4, 0, 16).is_err());
        assert_eq!(
            TileLayout::new(1, 1, 1),
            Err(Error::TileTooLarge { log2_samples: 0 })
        );
        assert_eq!(
            TileLayout::new(1 << 16, 1 << 16, 1),
            Err(Error::TileTooLarge { log2_samples: 32 })
        );
        assert!(TileLayout::new(1 << 16, 1 << 15, 1).is_ok());
    }

    #[test]
    fn split_of_paper_example() {
        // 4x4 pixels, 16 spp, m = 8: x = 0b10_110011 is pixel 2, sub-pixel 51/64.
        let l = TileLayout::new(4, 4, 16).unwrap();
        assert_eq!(l.split(0b1011_0011, 0b0100_0000), ([2, 1], [51, 0]));
        let s = l.sub_pixel::<f64>(0b1011_0011, 0).unwrap();
        assert_eq!(s.offset, [51.0 / 64.0, 0.0]);
    }

    #[test]
    fn f32_offset_stays_below_one() {
        let l = TileLayout::new(1, 1, 1 << 31).unwrap();
        let s = l.sub_pixel::<f32>(u32::MAX >> 1, u32::MAX >> 1).unwrap();
        assert!(s.offset[0] < 1.0 && s.offset[1] < 1.0);
    }

    #[test]
    fn sampler_net_size_must_match() {
        let l = TileLayout::new(4, 4, 16).unwrap();
        let net = TimeOrderedNet::permuted(7).unwrap();
        assert!(TileSampler::with_net(l, net, Scramble::NONE).is_err());
    }
}
