//! The samples of a finest tile (Munkberg 2011, §3, §7): the time-dependent z-max query of
//! its pattern tile, edge-eqn's inside and depth test of the tmsnet samples in its time
//! interval ([`covered_depth`]), the LESS_EQUAL write, and the z-max update of the slices
//! written — for a whole pattern tile or, below it, a quad / pixel of one.

use num_traits::Float;
use tmsnet::time_index_range;

use super::traversal::Bin;
use super::{Prepared, covered_depth};
use crate::buffer::sample_xy;
use crate::counters::cost;
use crate::interval::TimeInterval;
use crate::pixel_index::{PixelIndex, PixelSamples};

impl<F: Float> Bin<'_, F> {
    /// The samples in `range` of the pixels of the quad / pixel (x, y, `size`) of pattern
    /// tile `ctx` that lie in the image, from the per-pixel index; counts the per-pixel
    /// range look-ups.
    pub(super) fn pixel_samples<'a>(
        &mut self,
        index: &'a PixelIndex<F>,
        ctx: &SubTiles,
        x: u32,
        y: u32,
        size: u32,
        range: core::ops::Range<u32>,
    ) -> Samples<'a, F> {
        let frame = self.buf;
        let tile = frame.tile;
        let (x1, y1) = ((x + size).min(frame.width), (y + size).min(frame.height));
        let pixels = u64::from(x1.saturating_sub(x)) * u64::from(y1.saturating_sub(y));
        self.c.arithmetic += pixels * cost::PIXEL_RANGE;
        let (lx, ly) = (x % tile, y % tile);
        Samples::Pixels(index.samples_in_rect(
            ctx.scramble,
            lx..lx + (x1.saturating_sub(x)),
            ly..ly + (y1.saturating_sub(y)),
            range,
        ))
    }

    /// Inside, depth and write of every sample of `samples` (of pattern tile `ctx`) that
    /// lies in the image. The only caller of [`Bin::sample`], and never inlined: one copy
    /// of the per-sample test serves the pattern tiles and the quads / pixels below them.
    /// With a copy per sample source LLVM stops inlining the inside/depth test
    /// (`covered_depth`, `inside_depth_at`) into the loop: +45-52 % instructions on the
    /// default 16 → 8 → 4 path (callgrind).
    #[inline(never)]
    pub(super) fn test_samples(
        &mut self,
        p: &Prepared<F>,
        ctx: &mut SubTiles,
        samples: Samples<'_, F>,
    ) {
        let frame = self.buf;
        let tile = frame.tile;
        let (x0, y0) = (ctx.tx * tile, ctx.ty * tile);
        for s in samples {
            if x0 + s.pixel[0] >= frame.width || y0 + s.pixel[1] >= frame.height {
                continue;
            }
            self.sample(
                p,
                ctx.tx,
                ctx.ty,
                ctx.base,
                ctx.per_slice,
                &s,
                &mut ctx.dirty,
            );
        }
    }

    /// Recomputes the z-max of the slices flagged in `dirty` of the tile at local index
    /// `lt` (sample base `base`).
    pub(super) fn update_zmax(&mut self, lt: usize, base: usize, per_slice: u32, mut dirty: u64) {
        let zbase = lt * self.buf.zslices as usize;
        while dirty != 0 {
            let k = dirty.trailing_zeros();
            dirty &= dirty - 1;
            let lo = base + (k * per_slice) as usize;
            let hi = lo + per_slice as usize;
            if let (Some(ds), Some(z)) = (
                self.depth.get(lo..hi),
                self.zmax.get_mut(zbase + k as usize),
            ) {
                *z = ds.iter().fold(F::neg_infinity(), |m, &d| m.max(d));
            }
        }
    }

    /// Finest tile (x, y, size) (pixels; the pattern tile or a sub-tile of it) over time
    /// interval `iv`: z-max query, then the samples.
    pub(super) fn shade_tile(
        &mut self,
        p: &Prepared<F>,
        x: u32,
        y: u32,
        size: u32,
        iv: TimeInterval<F>,
    ) {
        let Ok(range) = time_index_range(iv.lo, iv.hi, self.buf.m) else {
            return;
        };
        self.shade_range(p, x, y, size, range, iv);
    }

    pub(super) fn local_tile(&self, tx: u32, ty: u32) -> usize {
        let per = self.buf.bin / self.buf.tile;
        ((ty % per) * per + (tx % per)) as usize
    }

    /// The samples with time index in `range` of the finest tile at pixel (x, y) of side
    /// `size` (a whole pattern tile, or a 2x2 quad / pixel inside one): the z-max query of
    /// the pattern tile, then inside and depth tests.
    pub(super) fn shade_range(
        &mut self,
        p: &Prepared<F>,
        x: u32,
        y: u32,
        size: u32,
        range: core::ops::Range<u32>,
        iv: TimeInterval<F>,
    ) {
        let tile = self.buf.tile;
        if range.is_empty() || self.zmax_culled(p, x / tile, y / tile, &range, iv) {
            return;
        }
        self.shade_samples(p, x, y, size, range);
    }

    /// The time-dependent z-max test of pattern tile (tx, ty) (Munkberg 2011, §7): true
    /// (and counted) when the triangle's nearest depth over `iv` is behind every written
    /// sample of the z-max slices that `range` touches. `range` must not be empty.
    pub(super) fn zmax_culled(
        &mut self,
        p: &Prepared<F>,
        tx: u32,
        ty: u32,
        range: &core::ops::Range<u32>,
        iv: TimeInterval<F>,
    ) -> bool {
        if !self.buf.cfg.zmax_culling {
            return false;
        }
        let per_slice = self.buf.n / self.buf.zslices;
        let zbase = self.local_tile(tx, ty) * self.buf.zslices as usize;
        self.c.arithmetic += cost::ZMAX_QUERY;
        let (s0, s1) = (
            range.start / per_slice,
            range.end.saturating_sub(1) / per_slice,
        );
        let zm = (s0..=s1).fold(F::neg_infinity(), |m, s| {
            m.max(
                self.zmax
                    .get(zbase + s as usize)
                    .copied()
                    .unwrap_or(F::infinity()),
            )
        });
        if p.zmin(iv) > zm {
            self.c.zmax_culls += 1;
            return true;
        }
        false
    }

    /// Inside and depth tests of the samples with time index in `range` of the finest
    /// tile at pixel (x, y) of side `size` (a pattern tile, or a quad / pixel of one), then
    /// the z-max update of the slices written.
    fn shade_samples(
        &mut self,
        p: &Prepared<F>,
        x: u32,
        y: u32,
        size: u32,
        range: core::ops::Range<u32>,
    ) {
        if range.is_empty() {
            return;
        }
        let tile = self.buf.tile;
        let (tx, ty) = (x / tile, y / tile);
        let lt = self.local_tile(tx, ty);
        let per_slice = self.buf.n / self.buf.zslices;
        let base = lt * self.buf.n as usize;
        let frame = self.buf;
        let mut ctx = SubTiles {
            tx,
            ty,
            base,
            per_slice,
            scramble: tmsnet::Scramble::for_tile(tx, ty, frame.samplers.seed),
            dirty: 0,
        };
        match &frame.samplers.pixels {
            Some(index) if size < tile => {
                // A quad or pixel of the pattern tile: its pixels' samples in the range.
                let samples = self.pixel_samples(index, &ctx, x, y, size, range);
                self.test_samples(p, &mut ctx, samples);
            }
            _ => {
                let Some(sampler) = frame.samplers.get(tx, ty) else {
                    return;
                };
                let Ok(iter) = sampler.samples_in_indices::<F>(range) else {
                    return;
                };
                self.test_samples(p, &mut ctx, Samples::Tile(iter));
            }
        }
        self.update_zmax(lt, base, per_slice, ctx.dirty);
    }

    /// One sample (inside the image) of pattern tile (tx, ty): inside test, depth test,
    /// write; marks its z-max slice dirty.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sample(
        &mut self,
        p: &Prepared<F>,
        tx: u32,
        ty: u32,
        base: usize,
        per_slice: u32,
        s: &tmsnet::TileSample<F>,
        dirty: &mut u64,
    ) {
        self.c.sample_tests += 1;
        self.c.arithmetic += cost::SAMPLE_TEST;
        let (x, y) = sample_xy(tx, ty, self.buf.tile, self.buf.footprint, s);
        let Some(d) = covered_depth(&p.setup, p.all_front, x, y, s.t) else {
            return;
        };
        self.c.depth_tests += 1;
        self.c.arithmetic += cost::DEPTH_TEST;
        let o = base + s.index as usize;
        if let (Some(slot), Some(id)) = (self.depth.get_mut(o), self.id.get_mut(o))
            && d <= *slot
        {
            *slot = d;
            *id = p.id;
            self.c.samples_written += 1;
            *dirty |= 1u64 << (s.index / per_slice).min(63);
        }
    }
}

/// The pattern tile whose samples (or quads / pixels, in [`Bin::visit_sub`]) are being
/// tested: its position, storage, scramble, and the z-max slices written so far.
pub(super) struct SubTiles {
    pub(super) tx: u32,
    pub(super) ty: u32,
    pub(super) base: usize,
    pub(super) per_slice: u32,
    pub(super) scramble: tmsnet::Scramble,
    pub(super) dirty: u64,
}

/// The samples one finest tile tests: a pattern tile's in a time-index range (tmsnet's
/// iterator), or those of a quad / pixel of it (the per-pixel index). One type, so that
/// [`Bin::test_samples`] has one copy of the per-sample test.
pub(super) enum Samples<'a, F> {
    Tile(tmsnet::TileSamples<'a, F>),
    Pixels(PixelSamples<'a, F>),
}

impl<F: Float> Iterator for Samples<'_, F> {
    type Item = tmsnet::TileSample<F>;

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        match self {
            Samples::Tile(it) => it.next(),
            Samples::Pixels(it) => it.next(),
        }
    }
}
