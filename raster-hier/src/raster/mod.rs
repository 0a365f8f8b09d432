//! Hierarchical stochastic motion-blur rasterisation of a frame (Munkberg 2011, §3, §7):
//! culling and setup per triangle, binning to coarsest tiles, and per bin (in parallel) the
//! selected traversal — OUR (tile tests with temporal bounds), BBOX, CONVEX, INTERLEAVE, or
//! OUR with the §7 fallback to INTERLEAVE — feeding tmsnet samples to edge-eqn's inside test
//! and a LESS_EQUAL depth test.
//!
//! This module holds the public types ([`RasterTriangle`], [`Traversal`],
//! [`RasterConfig`]), the coverage rule ([`covered`], [`covered_depth`]) and the entry point
//! [`rasterise`] with its binning; `prepare` culls and sets up a triangle, `traversal` walks
//! one bin's tiles, and `samples` tests a finest tile's samples.

mod prepare;
mod samples;
mod traversal;

use edge_eqn::{MovingTriangle, TriangleSetup};
use num_traits::Float;
use rayon::prelude::*;

use crate::buffer::SampleBuffer;
use crate::counters::Counters;
use crate::error::Error;
use crate::interval::{TimeInterval, lit};
use crate::tile_test::EdgeTest;
use prepare::{Prepared, prepare};
use traversal::{Bin, Frame};

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
    check_config(buf, &levels)?;
    let (width, height) = (
        lit::<F>(f64::from(buf.width)),
        lit::<F>(f64::from(buf.height)),
    );
    let n = buf.layout.samples();
    let prepared: Vec<(Option<Prepared<F>>, Counters)> = triangles
        .par_iter()
        .map(|t| {
            let mut c = Counters::default();
            let p = prepare(t, width, height, cfg, n, &mut c);
            (p, c)
        })
        .collect();
    let (bins, mut total) = bin_triangles(buf, &prepared);
    let frame = Frame::new(buf, cfg, levels)?;
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

/// Checks the tile sizes `levels` ([`RasterConfig::levels`]) and the z-max slices of `buf`
/// against what [`rasterise`] supports.
fn check_config<F>(buf: &SampleBuffer<F>, levels: &[u32]) -> Result<(), Error> {
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
    let n = buf.layout.samples();
    let levels_finest = levels.last().copied().unwrap_or(buf.tile);
    if levels_finest < buf.tile && n > 1 << 24 {
        // The per-pixel index holds one entry per sample of the pattern tile.
        return Err(Error::InvalidConfig(
            "levels below the pattern tile need tile² · spp <= 2^24",
        ));
    }
    Ok(())
}

/// Bins the prepared triangles to the coarsest tiles of `buf`: per bin (row-major), the
/// indices, in order, of the triangles whose screen bound touches it; and the sum of the
/// triangles' culling and setup counters.
fn bin_triangles<F: Float>(
    buf: &SampleBuffer<F>,
    prepared: &[(Option<Prepared<F>>, Counters)],
) -> (Vec<Vec<u32>>, Counters) {
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
    (bins, total)
}
