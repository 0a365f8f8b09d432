//! The per-bin traversals of a frame (Munkberg 2011, §4, §7): the bin's state ([`Bin`]), the
//! frame constants its bins share ([`Frame`]), and the tile walks of every [`Traversal`] —
//! OUR's hierarchical tile tests with temporal bounds (§4), including the quads / pixels
//! below the pattern tile, CONVEX's hull test, BBOX, and INTERLEAVE's static triangle per
//! sample time (§7). The finest tiles' samples are tested in `samples`.

use num_traits::Float;
use tmsnet::{TileSampler, sample_time, time_index_range};

use super::samples::SubTiles;
use super::{Prepared, RasterConfig, Traversal};
use crate::bound::{Rect, projected_bound, vertices_at};
use crate::buffer::{Footprint, SampleBuffer};
use crate::counters::{Counters, cost};
use crate::error::Error;
use crate::interval::{TimeInterval, lit};
use crate::pixel_index::PixelIndex;
use crate::tile_test::{EdgeTest, EdgeWindow, Linearised, aabb3, static_tile_overlap};

/// The per-bin state: the bin's slices of the buffer and the constants of the frame.
pub(super) struct Bin<'a, F> {
    pub(super) buf: &'a Frame<F>,
    pub(super) bx: u32,
    pub(super) by: u32,
    pub(super) depth: &'a mut [F],
    pub(super) id: &'a mut [u32],
    pub(super) zmax: &'a mut [F],
    pub(super) c: Counters,
}

/// Frame constants shared by all bins (read-only).
pub(super) struct Frame<F> {
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) tile: u32,
    pub(super) bin: u32,
    pub(super) footprint: Footprint,
    pub(super) m: u32,
    pub(super) n: u32,
    pub(super) zslices: u32,
    pub(super) levels: Vec<u32>,
    pub(super) cfg: RasterConfig,
    pub(super) samplers: SamplerSource<F>,
}

impl<F: Float> Frame<F> {
    /// The constants of a frame of `buf` with the traversal of `cfg` over tile sizes
    /// `levels` (checked by the caller); builds the per-pixel index when the finest level
    /// is below the pattern tile.
    pub(super) fn new(
        buf: &SampleBuffer<F>,
        cfg: &RasterConfig,
        levels: Vec<u32>,
    ) -> Result<Self, Error> {
        let levels_finest = levels.last().copied().unwrap_or(buf.tile);
        Ok(Frame {
            width: buf.width,
            height: buf.height,
            tile: buf.tile,
            bin: buf.bin,
            footprint: buf.footprint,
            m: buf.layout.m(),
            n: buf.layout.samples(),
            zslices: buf.zslices,
            levels,
            cfg: cfg.clone(),
            samplers: SamplerSource {
                layout: buf.layout,
                net: buf.net,
                seed: buf.seed,
                pixels: if levels_finest < buf.tile {
                    Some(
                        PixelIndex::new(buf.layout, buf.net).ok_or(Error::InvalidConfig(
                            "the sample pattern's net does not match its layout",
                        ))?,
                    )
                } else {
                    None
                },
            },
        })
    }
}

/// Where a pattern tile's samples come from: the buffer's tmsnet layout, net and seed (the
/// tile's scramble), and the per-pixel index for levels below the pattern tile.
pub(super) struct SamplerSource<F> {
    layout: tmsnet::TileLayout,
    net: tmsnet::TimeOrderedNet,
    pub(super) seed: u64,
    /// Per-pixel time-sorted samples, built when the finest level is below the tile.
    pub(super) pixels: Option<PixelIndex<F>>,
}

impl<F> SamplerSource<F> {
    /// The sampler of pattern tile (tx, ty).
    pub(super) fn get(&self, tx: u32, ty: u32) -> Option<TileSampler> {
        TileSampler::with_net(
            self.layout,
            self.net,
            tmsnet::Scramble::for_tile(tx, ty, self.seed),
        )
        .ok()
    }
}

impl<F: Float> Bin<'_, F> {
    fn rect(&self, x: u32, y: u32, size: u32) -> Rect<F> {
        let f = |v: u32| lit::<F>(f64::from(v));
        Rect::new(f(x), f(y), f(x + size), f(y + size))
    }

    pub(super) fn run(&mut self, p: &Prepared<F>) {
        let (x, y) = (self.bx * self.buf.bin, self.by * self.buf.bin);
        match self.buf.cfg.traversal {
            Traversal::Bbox => self.bbox(p),
            Traversal::Convex => self.visit_convex(p, 0, x, y),
            Traversal::Interleave => self.interleave(p),
            Traversal::Our(m) | Traversal::OurFallback(m) => {
                if p.interleave {
                    self.interleave(p)
                } else {
                    self.visit_our(p, m, 0, x, y, p.tester.frustum, &p.tester.setup)
                }
            }
        }
    }

    /// The part of tile (x, y, size) inside the image and the triangle's bound, or None.
    fn clip(&self, p: &Prepared<F>, x: u32, y: u32, size: u32) -> Option<Rect<F>> {
        if x >= self.buf.width || y >= self.buf.height {
            return None;
        }
        let rect = self.rect(x, y, size);
        (!rect.intersect(&p.bound).is_empty()).then_some(rect)
    }

    #[allow(clippy::too_many_arguments)]
    fn visit_our(
        &mut self,
        p: &Prepared<F>,
        method: EdgeTest,
        level: usize,
        x: u32,
        y: u32,
        parent: TimeInterval<F>,
        lin: &Linearised<F>,
    ) {
        let size = self.buf.levels[level];
        let Some(rect) = self.clip(p, x, y, size) else {
            return;
        };
        let local;
        let lin = if level == 0 && method == EdgeTest::LinearisedPerTile {
            self.c.arithmetic += cost::LINEARISE;
            local = p.tester.linearise(rect.intersect(&p.bound));
            &local
        } else {
            lin
        };
        let windings = p.tester.windings.iter().filter(|w| **w).count() as u64;
        let finest = level + 1 == self.buf.levels.len();
        self.c.tile_tests += 1;
        self.c.arithmetic += cost::BOX_TEST
            + 3 * match method {
                EdgeTest::Exact => windings * 4 * cost::EXACT_EDGE_CORNER,
                EdgeTest::ExactFinest if finest => windings * 4 * cost::EXACT_EDGE_CORNER,
                EdgeTest::LinearisedPerLevel | EdgeTest::ExactFinest => {
                    cost::WINDOW_EDGE_SETUP + windings * cost::WINDOW_EDGE
                }
                EdgeTest::LinearisedSetup | EdgeTest::LinearisedPerTile => {
                    windings * cost::LINEAR_EDGE
                }
            };
        let iv = match method {
            EdgeTest::LinearisedPerLevel | EdgeTest::ExactFinest => p
                .tester
                .test_window(&rect, method, lin, parent, finest)
                .intersect(parent),
            _ => p.tester.test(&rect, method, lin).intersect(parent),
        };
        if iv.is_empty() {
            return;
        }
        if level + 1 == self.buf.levels.len() {
            self.shade_tile(p, x, y, size, iv);
            return;
        }
        if size == self.buf.tile && self.buf.cfg.sub_tile_min_samples > 0 {
            // Too short an interval to pay for the sub-tile tests: test the tile's samples.
            let Ok(range) = time_index_range(iv.lo, iv.hi, self.buf.m) else {
                return;
            };
            let min = u64::from(self.buf.cfg.sub_tile_min_samples) * u64::from(size * size);
            if (range.len() as u64) < min {
                self.shade_range(p, x, y, size, range, iv);
                return;
            }
        }
        if method == EdgeTest::LinearisedPerLevel && size == self.buf.tile {
            // Levels below the pattern tile: one z-max query for the pattern tile, then
            // quads / pixels tested against this tile's linearisation around its interval.
            let Ok(range) = time_index_range(iv.lo, iv.hi, self.buf.m) else {
                return;
            };
            if range.is_empty() || self.zmax_culled(p, x / size, y / size, &range, iv) {
                return;
            }
            self.c.arithmetic += 3 * cost::WINDOW_EDGE_SETUP;
            let ew = p.tester.edge_window(&rect, iv);
            let (tx, ty) = (x / size, y / size);
            let lt = self.local_tile(tx, ty);
            let mut ctx = SubTiles {
                tx,
                ty,
                base: lt * self.buf.n as usize,
                per_slice: self.buf.n / self.buf.zslices,
                scramble: tmsnet::Scramble::for_tile(tx, ty, self.buf.samplers.seed),
                dirty: 0,
            };
            let child = self.buf.levels[level + 1];
            for cy in (y..y + size).step_by(child as usize) {
                for cx in (x..x + size).step_by(child as usize) {
                    self.visit_sub(p, &ew, &mut ctx, level + 1, cx, cy, iv);
                }
            }
            self.update_zmax(lt, ctx.base, ctx.per_slice, ctx.dirty);
            return;
        }
        let child = self.buf.levels[level + 1];
        for cy in (y..y + size).step_by(child as usize) {
            for cx in (x..x + size).step_by(child as usize) {
                self.visit_our(p, method, level + 1, cx, cy, iv, lin);
            }
        }
    }

    /// A quad or pixel (x, y, `levels[level]`) of a pattern tile whose window
    /// linearisation is `ew`: the edge bound on the sub-tile (no box test, no z-max query),
    /// then its children or, at the finest level, its pixels' samples in the interval.
    #[allow(clippy::too_many_arguments)]
    fn visit_sub(
        &mut self,
        p: &Prepared<F>,
        ew: &EdgeWindow<F>,
        ctx: &mut SubTiles,
        level: usize,
        x: u32,
        y: u32,
        parent: TimeInterval<F>,
    ) {
        let frame = self.buf;
        let size = frame.levels[level];
        // The image and the triangle's screen bound (which the edge bounds alone do not
        // imply near the vertices), then the edges.
        let Some(rect) = self.clip(p, x, y, size) else {
            return;
        };
        let windings = p.tester.windings.iter().filter(|w| **w).count() as u64;
        self.c.tile_tests += 1;
        self.c.arithmetic += 3 * windings * cost::WINDOW_EDGE;
        // The widening for the division may reach past the span's ends: clip to them.
        let iv = p
            .tester
            .sub_tile_interval(ew, &rect, parent)
            .intersect(p.span);
        if iv.is_empty() {
            return;
        }
        if level + 1 < frame.levels.len() {
            let child = frame.levels[level + 1];
            for cy in (y..y + size).step_by(child as usize) {
                for cx in (x..x + size).step_by(child as usize) {
                    self.visit_sub(p, ew, ctx, level + 1, cx, cy, iv);
                }
            }
            return;
        }
        let (Ok(range), Some(index)) = (
            time_index_range(iv.lo, iv.hi, frame.m),
            &frame.samplers.pixels,
        ) else {
            return;
        };
        if range.is_empty() {
            return;
        }
        let samples = self.pixel_samples(index, ctx, x, y, size, range);
        self.test_samples(p, ctx, samples);
    }

    fn visit_convex(&mut self, p: &Prepared<F>, level: usize, x: u32, y: u32) {
        let size = self.buf.levels[level];
        if self.clip(p, x, y, size).is_none() {
            return;
        }
        if let Some(h) = &p.hull {
            self.c.tile_tests += 1;
            self.c.arithmetic += cost::HULL_EDGE * h.len() as u64;
            let f = f64::from;
            if !h.overlaps(f(x), f(y), f(x + size), f(y + size)) {
                return;
            }
        }
        if level + 1 == self.buf.levels.len() {
            self.shade_tile(p, x, y, size, p.tester.frustum);
            return;
        }
        let child = self.buf.levels[level + 1];
        for cy in (y..y + size).step_by(child as usize) {
            for cx in (x..x + size).step_by(child as usize) {
                self.visit_convex(p, level + 1, cx, cy);
            }
        }
    }

    fn bbox(&mut self, p: &Prepared<F>) {
        let t = self.buf.tile;
        let per = self.buf.bin / t;
        for ly in 0..per {
            for lx in 0..per {
                let (tx, ty) = (self.bx * per + lx, self.by * per + ly);
                if self.clip(p, tx * t, ty * t, t).is_some() {
                    self.shade_tile(p, tx * t, ty * t, t, p.tester.frustum);
                }
            }
        }
    }

    fn interleave(&mut self, p: &Prepared<F>) {
        let Ok(range) = time_index_range(p.tester.frustum.lo, p.tester.frustum.hi, self.buf.m)
        else {
            return;
        };
        let (x, y) = (self.bx * self.buf.bin, self.by * self.buf.bin);
        for j in range {
            let Ok(t) = sample_time::<F>(j, self.buf.m) else {
                continue;
            };
            self.c.arithmetic += cost::TIME_SETUP;
            let v = vertices_at(&p.q, &p.r, t);
            let bound = match projected_bound(&v) {
                Some(b) => b.intersect(&p.bound),
                None => p.bound,
            };
            if bound.is_empty() {
                continue;
            }
            let coeffs = p.setup.edges().map(|e| e.coefficients_at(t));
            let frame = TimeSlice {
                bound,
                aabb: aabb3(&v),
                coeffs,
                j,
                t,
            };
            self.visit_time(p, &frame, 0, x, y);
        }
    }

    fn visit_time(&mut self, p: &Prepared<F>, s: &TimeSlice<F>, level: usize, x: u32, y: u32) {
        let size = self.buf.levels[level];
        if x >= self.buf.width || y >= self.buf.height {
            return;
        }
        let rect = self.rect(x, y, size);
        if rect.intersect(&s.bound).is_empty() {
            return;
        }
        self.c.tile_tests += 1;
        self.c.arithmetic += cost::STATIC_TILE;
        if !static_tile_overlap(&rect, &s.aabb, &s.coeffs, p.tester.windings) {
            return;
        }
        // One sample time has one sample per pattern tile: levels below it cannot prune more.
        if level + 1 == self.buf.levels.len() || size <= self.buf.tile {
            let iv = TimeInterval::new(s.t, s.t);
            self.shade_range(p, x, y, size, s.j..s.j + 1, iv);
            return;
        }
        let child = self.buf.levels[level + 1];
        for cy in (y..y + size).step_by(child as usize) {
            for cx in (x..x + size).step_by(child as usize) {
                self.visit_time(p, s, level + 1, cx, cy);
            }
        }
    }
}

/// One sample time of the INTERLEAVE traversal: the static triangle at t.
struct TimeSlice<F> {
    bound: Rect<F>,
    aabb: [[F; 3]; 2],
    coeffs: [[F; 3]; 3],
    j: u32,
    t: F,
}
