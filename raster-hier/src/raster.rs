//! Hierarchical stochastic motion-blur rasterisation of a frame (Munkberg 2011, §3, §7):
//! culling and setup per triangle, binning to coarsest tiles, and per bin (in parallel) the
//! selected traversal — OUR (tile tests with temporal bounds), BBOX, CONVEX, INTERLEAVE, or
//! OUR with the §7 fallback to INTERLEAVE — feeding tmsnet samples to edge-eqn's inside test
//! and a LESS_EQUAL depth test.

use edge_eqn::{MovingTriangle, TriangleSetup};
use num_traits::Float;
use rayon::prelude::*;
use tmsnet::{TileSampler, sample_time, time_index_range};

use crate::bound::{Rect, projected_bound, screen_bound, vertices_at};
use crate::buffer::{Footprint, SampleBuffer, sample_xy};
use crate::convex::ConvexHull;
use crate::counters::{Counters, cost};
use crate::cull::{Facing, facing, frustum_interval};
use crate::error::Error;
use crate::interval::{TimeInterval, lit};
use crate::pixel_index::{PixelIndex, PixelSamples};
use crate::tile_test::{EdgeTest, EdgeWindow, Linearised, TileTester, aabb3, static_tile_overlap};

/// One triangle of a frame: its motion in 2DH (with optional per-vertex depth), the part
/// of the shutter it exists in and the payload id written to the samples it wins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterTriangle<F> {
    /// The moving triangle (edge-eqn): its vertices `q` at the start of `span` and `r` at
    /// its end, moving linearly in between.
    pub triangle: MovingTriangle<F>,
    /// Payload id (e.g. an index into a colour table); must not be [`crate::NO_HIT`].
    pub id: u32,
    /// The part `[t0, t1]` of the shutter the triangle exists in ([`TimeInterval::full`]
    /// for the whole shutter). Only samples with time in the span are tested; a sample at
    /// time t sees the triangle at local time (t - t0) / (t1 - t0) of its motion. One
    /// piece of a piecewise-linear (curved) path per triangle: consecutive pieces share
    /// their end time, so a sample exactly there is tested against both (they agree there)
    /// and no instant is left out. An empty span, or one outside \[0, 1\] or not finite,
    /// culls the triangle.
    pub span: TimeInterval<F>,
}

impl<F: Float> RasterTriangle<F> {
    /// A triangle over the whole shutter.
    pub fn whole(triangle: MovingTriangle<F>, id: u32) -> Self {
        RasterTriangle {
            triangle,
            id,
            span: TimeInterval::full(),
        }
    }

    /// The triangle's motion extended linearly over the whole shutter, p(t) = q + (t - t0)
    /// / (t1 - t0) (r - q), with vertices at t = 0 and t = 1 — the form every tile test and
    /// sample test takes (so they work in shutter time throughout, restricted to the span;
    /// within it the motion is the given one, up to the rounding of the extension, which
    /// grows with 1 / (t1 - t0)). The triangle itself for the whole-shutter span; `None`
    /// for an unusable span or a non-finite extension.
    pub fn over_shutter(&self) -> Option<MovingTriangle<F>> {
        let TimeInterval { lo, hi } = self.span;
        let (zero, one) = (F::zero(), F::one());
        if lo == zero && hi == one {
            return Some(self.triangle);
        }
        if !(lo >= zero && hi <= one && lo < hi) {
            return None;
        }
        let len = hi - lo;
        // a + (b - a) (t - t0) / len at t = 0 and t = 1.
        let at = |a: F, b: F, t: F| a + (b - a) * ((t - lo) / len);
        let ends = |a: &[F; 3], b: &[F; 3], t: F| -> [F; 3] {
            core::array::from_fn(|c| at(a[c], b[c], t))
        };
        let m = &self.triangle;
        let side = |t: F| -> [[F; 3]; 3] { core::array::from_fn(|k| ends(&m.q[k], &m.r[k], t)) };
        let depth = m
            .depth
            .map(|(zq, zr)| (ends(&zq, &zr, zero), ends(&zq, &zr, one)));
        let out = MovingTriangle {
            q: side(zero),
            r: side(one),
            depth,
        };
        let finite = out.q.iter().chain(&out.r).flatten().all(|v| v.is_finite());
        finite.then_some(out)
    }
}

/// The traversal algorithm (Munkberg 2011, Table 1). All use the same samples and the same
/// inside test, so they produce bit-identical sample buffers; only their cost differs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Traversal {
    /// Swept bounding box: every sample of every finest tile in the screen bound.
    Bbox,
    /// Tiles against the convex hull of the six projected vertices, all times (McGuire et
    /// al. 2010 as in §7).
    Convex,
    /// HIERARCHICAL INTERLEAVE: outer loop over the unique sample times, the static triangle
    /// at each time traversed hierarchically, one sample per finest tile (levels below the
    /// pattern tile are not descended: a time has one sample per pattern tile).
    Interleave,
    /// OUR: hierarchical tile tests with temporal bounds (§4) with the given edge test.
    Our(EdgeTest),
    /// OUR with the §7 fallback to INTERLEAVE for small, fast triangles:
    /// min(w₀, w₁) < w_s / N or min(h₀, h₁) < h_s / N.
    OurFallback(EdgeTest),
}

/// Frame settings.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RasterConfig {
    /// The traversal.
    pub traversal: Traversal,
    /// Tile sizes from coarsest to finest, e.g. `[16, 8, 4]`: powers of two, each dividing
    /// the previous; the first must equal the buffer's bin, the last must be at most its
    /// (sample-pattern) tile. Levels finer than the pattern tile (e.g. `[16, 8, 4, 2, 1]`
    /// with 4x4 pattern tiles, see [`RasterConfig::fine`]) give each 2x2 quad or pixel its
    /// own tile test and time interval; only that sub-tile's samples in its interval are
    /// tested. The sample pattern, and so the image, does not depend on the levels.
    pub levels: Vec<u32>,
    /// Cull triangles back-facing for the whole shutter (off: both windings are drawn, as
    /// edge-eqn's inside rule does).
    pub cull_backfaces: bool,
    /// Time-dependent z-max occlusion culling of finest tiles.
    pub zmax_culling: bool,
    /// Levels below the pattern tile: a pattern tile is split into its quads / pixels only
    /// when its time interval holds at least this many samples per pixel on average
    /// (index range ≥ value · tile²); otherwise its samples in the interval are tested
    /// directly, since the sub-tile tests would cost more than the few samples they could
    /// save. 0 = always split. No effect on the image.
    pub sub_tile_min_samples: u32,
}

impl RasterConfig {
    /// The paper's configuration: 16 → 8 → 4 pixel tiles, z-max culling on, no back-face
    /// culling.
    pub fn new(traversal: Traversal) -> Self {
        RasterConfig {
            traversal,
            levels: vec![16, 8, 4],
            cull_backfaces: false,
            zmax_culling: true,
            sub_tile_min_samples: 0,
        }
    }

    /// Fewest sample tests: OUR with [`EdgeTest::LinearisedPerLevel`] and levels
    /// 16 → 8 → 4 → 2 → 1, for a buffer with 16 px bins and 4x4 pattern tiles (the
    /// benchmarks' buffer). Below the pattern tile every 2x2 quad and every pixel gets its
    /// own interval from the 4x4 tile's linearisation, so only a pixel's own samples in its
    /// own interval are tested: 0.23 of CONVEX's sample tests at 1x motion on the Table 2
    /// scene (0.45 with [`RasterConfig::new`]'s 16 → 8 → 4), at the price of ~10x the tile
    /// tests: less time than CONVEX at every motion level measured (0.25x-4x), faster than
    /// `LinearisedPerLevel` at 16 → 8 → 4 at 0.25x but slower from 1x up at 16 spp — see
    /// BENCHMARKS.md. Same image as every other configuration.
    ///
    /// ```
    /// use raster_hier::{RasterConfig, SampleBuffer, benchmark_scene, rasterise};
    /// let tris = benchmark_scene::<f32>(20, 12.0, 1.0, 48, 32, 3);
    /// let mut a = SampleBuffer::<f32>::new(48, 32, 16, 4, 16, 4, 1)?;
    /// let mut b = a.clone();
    /// let fine = rasterise(&mut a, &tris, &RasterConfig::fine())?;
    /// let coarse = rasterise(&mut b, &tris, &RasterConfig::new(RasterConfig::fine().traversal))?;
    /// assert_eq!(a.ids(), b.ids());
    /// assert!(fine.sample_tests < coarse.sample_tests && fine.tile_tests > coarse.tile_tests);
    /// # Ok::<(), raster_hier::Error>(())
    /// ```
    pub fn fine() -> Self {
        RasterConfig {
            levels: vec![16, 8, 4, 2, 1],
            ..RasterConfig::new(Traversal::Our(EdgeTest::LinearisedPerLevel))
        }
    }
}

/// The rasteriser's coverage rule for a sample (x, y) at time t: edge-eqn's inside test
/// (either winding) **and** the hit point in front of the eye. The hit point on the ray
/// μ (x, y, 1) has μ = −det(t) / Σ_k e_k, so it is in front (μ > 0) when the edge sum and
/// the 2DH determinant have opposite signs. For triangles with w > 0 at every vertex the
/// second condition follows from the first and is skipped.
#[inline]
pub fn covered<F: Float>(setup: &TriangleSetup<F>, all_w_positive: bool, x: F, y: F, t: F) -> bool {
    if !setup.inside_at(x, y, t) {
        return false;
    }
    all_w_positive || hit_in_front(setup, x, y, t)
}

/// The second condition of [`covered`]: the hit point μ (x, y, 1) with
/// μ = −det(t) / Σ_k e_k lies in front of the eye (μ > 0).
#[inline]
fn hit_in_front<F: Float>(setup: &TriangleSetup<F>, x: F, y: F, t: F) -> bool {
    let det = setup.orientation_at(t);
    let sum = setup
        .edges()
        .iter()
        .fold(F::zero(), |a, e| a + e.eval(x, y, t));
    let z = F::zero();
    (det > z && sum < z) || (det < z && sum > z)
}

/// [`covered`] and, for a covered sample, its exact depth (edge-eqn's
/// `TriangleSetup::inside_depth_at`, Gribel 2010, Eq. 11-15) from the edge values of the
/// same inside test: one pass per sample instead of an inside test followed by a rebuild of
/// the sample's quadratics and rational depth. Always inlined into the one sample loop
/// (`Bin::test_samples`).
#[inline(always)]
pub fn covered_depth<F: Float>(
    setup: &TriangleSetup<F>,
    all_w_positive: bool,
    x: F,
    y: F,
    t: F,
) -> Option<F> {
    let d = setup.inside_depth_at(x, y, t)?;
    (all_w_positive || hit_in_front(setup, x, y, t)).then_some(d)
}

/// A triangle after culling and setup.
#[derive(Clone, Debug)]
struct Prepared<F> {
    setup: TriangleSetup<F>,
    id: u32,
    /// The triangle's span (every time interval of its traversal lies inside it).
    span: TimeInterval<F>,
    q: [[F; 3]; 3],
    r: [[F; 3]; 3],
    zq: [F; 3],
    zr: [F; 3],
    all_front: bool,
    tester: TileTester<F>,
    bound: Rect<F>,
    hull: Option<ConvexHull>,
    interleave: bool,
}

impl<F: Float> Prepared<F> {
    /// Lower bound of the triangle's depth over `iv`: the perspective-correct depth is a
    /// convex combination of the vertex depths, each linear in t. Lowered by a rounding margin.
    fn zmin(&self, iv: TimeInterval<F>) -> F {
        let mut m = F::infinity();
        for k in 0..3 {
            for t in [iv.lo, iv.hi] {
                m = m.min(self.zq[k] + t * (self.zr[k] - self.zq[k]));
            }
        }
        m - m.abs() * F::epsilon() * lit(16.0)
    }
}

fn prepare<F: Float>(
    tri: &RasterTriangle<F>,
    width: F,
    height: F,
    cfg: &RasterConfig,
    unique_times: u32,
    c: &mut Counters,
) -> Option<Prepared<F>> {
    c.triangles_in += 1;
    let Some(whole) = tri.over_shutter() else {
        c.frustum_culled += 1;
        return None;
    };
    let (q, r) = (whole.q, whole.r);
    let setup = whole.setup();
    c.arithmetic += cost::SETUP;
    let frustum = frustum_interval(&q, &r, width, height).intersect(tri.span);
    if !setup.is_valid() || frustum.is_empty() {
        c.frustum_culled += 1;
        return None;
    }
    // Over the span, which is the whole motion given (its orientation outside the span
    // does not matter).
    let face = facing(&tri.triangle.q, &tri.triangle.r);
    if cfg.cull_backfaces && face == Facing::Back {
        c.backface_culled += 1;
        return None;
    }
    let bound = screen_bound(&q, &r, frustum, width, height);
    if bound.rect.is_empty() {
        c.frustum_culled += 1;
        return None;
    }
    c.triangles_set_up += 1;
    c.arithmetic += cost::LINEARISE;
    // w is linear in t: positive at the span's ends, positive over it.
    let (given_q, given_r) = (tri.triangle.q, tri.triangle.r);
    let all_front = given_q
        .iter()
        .chain(given_r.iter())
        .all(|v| v[2] > F::zero());
    let tester = TileTester::new(&q, &r, *setup.edges(), face, frustum, bound.rect);
    let (a, b) = (
        vertices_at(&q, &r, frustum.lo),
        vertices_at(&q, &r, frustum.hi),
    );
    let (ba, bb) = (projected_bound(&a), projected_bound(&b));
    let hull = match (cfg.traversal, bound.projected) {
        (Traversal::Convex, true) => {
            let f = |v: F| v.to_f64().unwrap_or(0.0);
            let pts: [[f64; 2]; 6] = core::array::from_fn(|i| {
                let p = if i < 3 { a[i] } else { b[i - 3] };
                [f(p[0] / p[2]), f(p[1] / p[2])]
            });
            let mag = pts.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
            let eps = F::epsilon().to_f64().unwrap_or(1e-7);
            Some(ConvexHull::new(&pts, 1e-6 + 256.0 * eps * mag))
        }
        _ => None,
    };
    let interleave = match cfg.traversal {
        Traversal::Interleave => true,
        Traversal::OurFallback(_) => match (ba, bb) {
            (Some(ba), Some(bb)) => {
                let n: F = lit(f64::from(unique_times));
                let (w0, h0) = (ba.x1 - ba.x0, ba.y1 - ba.y0);
                let (w1, h1) = (bb.x1 - bb.x0, bb.y1 - bb.y0);
                let (ws, hs) = (
                    ba.x1.max(bb.x1) - ba.x0.min(bb.x0),
                    ba.y1.max(bb.y1) - ba.y0.min(bb.y0),
                );
                w0.min(w1) < ws / n || h0.min(h1) < hs / n
            }
            _ => false,
        },
        _ => false,
    };
    if interleave && cfg.traversal != Traversal::Interleave {
        c.fallbacks += 1;
    }
    let (zq, zr) = setup.depths();
    Some(Prepared {
        setup,
        id: tri.id,
        span: tri.span,
        q,
        r,
        zq,
        zr,
        all_front,
        tester,
        bound: bound.rect,
        hull,
        interleave,
    })
}

/// The per-bin state: the bin's slices of the buffer and the constants of the frame.
struct Bin<'a, F> {
    buf: &'a Frame<F>,
    bx: u32,
    by: u32,
    depth: &'a mut [F],
    id: &'a mut [u32],
    zmax: &'a mut [F],
    c: Counters,
}

/// Frame constants shared by all bins (read-only).
struct Frame<F> {
    width: u32,
    height: u32,
    tile: u32,
    bin: u32,
    footprint: Footprint,
    m: u32,
    n: u32,
    zslices: u32,
    levels: Vec<u32>,
    cfg: RasterConfig,
    samplers: SamplerSource<F>,
}

struct SamplerSource<F> {
    layout: tmsnet::TileLayout,
    net: tmsnet::TimeOrderedNet,
    seed: u64,
    /// Per-pixel time-sorted samples, built when the finest level is below the tile.
    pixels: Option<PixelIndex<F>>,
}

impl<F> SamplerSource<F> {
    fn get(&self, tx: u32, ty: u32) -> Option<TileSampler> {
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

    fn run(&mut self, p: &Prepared<F>) {
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

    /// The samples in `range` of the pixels of the quad / pixel (x, y, `size`) of pattern
    /// tile `ctx` that lie in the image, from the per-pixel index; counts the per-pixel
    /// range look-ups.
    fn pixel_samples<'a>(
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
    fn test_samples(&mut self, p: &Prepared<F>, ctx: &mut SubTiles, samples: Samples<'_, F>) {
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
    fn update_zmax(&mut self, lt: usize, base: usize, per_slice: u32, mut dirty: u64) {
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

    /// Finest tile (x, y, size) (pixels; the pattern tile or a sub-tile of it) over time
    /// interval `iv`: z-max query, then the samples.
    fn shade_tile(&mut self, p: &Prepared<F>, x: u32, y: u32, size: u32, iv: TimeInterval<F>) {
        let Ok(range) = time_index_range(iv.lo, iv.hi, self.buf.m) else {
            return;
        };
        self.shade_range(p, x, y, size, range, iv);
    }

    fn local_tile(&self, tx: u32, ty: u32) -> usize {
        let per = self.buf.bin / self.buf.tile;
        ((ty % per) * per + (tx % per)) as usize
    }

    /// The samples with time index in `range` of the finest tile at pixel (x, y) of side
    /// `size` (a whole pattern tile, or a 2x2 quad / pixel inside one): the z-max query of
    /// the pattern tile, then inside and depth tests.
    fn shade_range(
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
    fn zmax_culled(
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
struct SubTiles {
    tx: u32,
    ty: u32,
    base: usize,
    per_slice: u32,
    scramble: tmsnet::Scramble,
    dirty: u64,
}

/// The samples one finest tile tests: a pattern tile's in a time-index range (tmsnet's
/// iterator), or those of a quad / pixel of it (the per-pixel index). One type, so that
/// [`Bin::test_samples`] has one copy of the per-sample test.
enum Samples<'a, F> {
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

/// One sample time of the INTERLEAVE traversal: the static triangle at t.
struct TimeSlice<F> {
    bound: Rect<F>,
    aabb: [[F; 3]; 2],
    coeffs: [[F; 3]; 3],
    j: u32,
    t: F,
}

/// Rasterises `triangles` (in order: later ones win exact depth ties, LESS_EQUAL) into
/// `buf` with the traversal of `cfg`, and returns the frame's cost counters.
///
/// Triangles are culled and set up in parallel, binned to the coarsest tiles, and the bins
/// are processed in parallel on the current rayon pool, each owning its slice of the buffer.
/// The result does not depend on the number of threads.
///
/// ```
/// use edge_eqn::MovingTriangle;
/// use raster_hier::{EdgeTest, RasterConfig, RasterTriangle, SampleBuffer, Traversal, rasterise};
/// let q = [[4.0, 4.0, 1.0], [20.0, 4.0, 1.0], [4.0, 20.0, 1.0]];
/// let r = q.map(|[x, y, w]| [x + 8.0, y, w]);
/// let tri = RasterTriangle::whole(MovingTriangle::<f32>::new(q, r), 7);
/// let mut buf = SampleBuffer::<f32>::new(32, 32, 16, 4, 16, 4, 1)?;
/// let cfg = RasterConfig::new(Traversal::Our(EdgeTest::LinearisedSetup));
/// let stats = rasterise(&mut buf, &[tri], &cfg)?;
/// assert!(stats.samples_written > 0 && stats.sample_tests >= stats.depth_tests);
/// let image = buf.resolve(|_| [1.0, 0.0, 0.0, 1.0], [0.0; 4]);
/// assert_eq!(image.len(), 32 * 32);
/// # Ok::<(), raster_hier::Error>(())
/// ```
pub fn rasterise<F: Float + Send + Sync>(
    buf: &mut SampleBuffer<F>,
    triangles: &[RasterTriangle<F>],
    cfg: &RasterConfig,
) -> Result<Counters, Error> {
    let levels = cfg.levels.clone();
    if levels.first() != Some(&buf.bin) || levels.last().is_none_or(|&l| l > buf.tile) {
        return Err(Error::InvalidConfig(
            "levels must start at the buffer's bin and end at or below its tile",
        ));
    }
    if levels.windows(2).any(|w| w[1] >= w[0] || w[0] % w[1] != 0)
        || levels.iter().any(|l| !l.is_power_of_two())
    {
        return Err(Error::InvalidConfig(
            "levels must be decreasing powers of two",
        ));
    }
    if buf.zslices > 64 {
        return Err(Error::InvalidConfig("at most 64 z-max slices per tile"));
    }
    let (width, height) = (
        lit::<F>(f64::from(buf.width)),
        lit::<F>(f64::from(buf.height)),
    );
    let n = buf.layout.samples();
    let levels_finest = levels.last().copied().unwrap_or(buf.tile);
    if levels_finest < buf.tile && n > 1 << 24 {
        // The per-pixel index holds one entry per sample of the pattern tile.
        return Err(Error::InvalidConfig(
            "levels below the pattern tile need tile² · spp <= 2^24",
        ));
    }
    let prepared: Vec<(Option<Prepared<F>>, Counters)> = triangles
        .par_iter()
        .map(|t| {
            let mut c = Counters::default();
            let p = prepare(t, width, height, cfg, n, &mut c);
            (p, c)
        })
        .collect();
    let mut total = Counters::default();
    let nbins = (buf.bins_x * buf.bins_y) as usize;
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); nbins];
    let binf = lit::<F>(f64::from(buf.bin));
    for (i, (p, c)) in prepared.iter().enumerate() {
        total += *c;
        let Some(p) = p else { continue };
        let cell = |v: F, max: u32| v.div(binf).floor().to_u32().unwrap_or(0).min(max - 1);
        let (bx0, bx1) = (cell(p.bound.x0, buf.bins_x), cell(p.bound.x1, buf.bins_x));
        let (by0, by1) = (cell(p.bound.y0, buf.bins_y), cell(p.bound.y1, buf.bins_y));
        for by in by0..=by1 {
            for bx in bx0..=bx1 {
                if let Some(list) = bins.get_mut((by * buf.bins_x + bx) as usize) {
                    list.push(i as u32);
                }
            }
        }
    }
    let frame = Frame::<F> {
        width: buf.width,
        height: buf.height,
        tile: buf.tile,
        bin: buf.bin,
        footprint: buf.footprint,
        m: buf.layout.m(),
        n,
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
    };
    let per_tile = (buf.bin / buf.tile) * (buf.bin / buf.tile);
    let per_bin = (per_tile * n) as usize;
    let zper_bin = (per_tile * buf.zslices) as usize;
    let bins_x = buf.bins_x;
    let counters = buf
        .depth
        .par_chunks_mut(per_bin)
        .zip(buf.id.par_chunks_mut(per_bin))
        .zip(buf.zmax.par_chunks_mut(zper_bin))
        .zip(bins.par_iter())
        .enumerate()
        .map(|(b, (((depth, id), zmax), list))| {
            let mut bin = Bin {
                buf: &frame,
                bx: b as u32 % bins_x,
                by: b as u32 / bins_x,
                depth,
                id,
                zmax,
                c: Counters::default(),
            };
            for &i in list {
                if let Some((Some(p), _)) = prepared.get(i as usize) {
                    bin.run(p);
                }
            }
            bin.c
        })
        .reduce(Counters::default, |mut a, b| {
            a += b;
            a
        });
    total += counters;
    Ok(total)
}
