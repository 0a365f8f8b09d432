//! The `analytic` method (Gribel, Doggett and Akenine-Möller 2010): per pixel centre, the
//! exact time spans during which each moving triangle covers it (edge-eqn, Eq. 3-9), stored
//! as intervals with linear depth (Eq. 16) in an interval buffer (exact unbounded lists, or
//! at most K per pixel with oracle compression, §5.2), then resolved by a sweep over time
//! against the shutter response (resolve, §5.1, Eq. 17).
//!
//! What runs depends on the [`Pipeline`]:
//! - a fully static opaque scene allocates no interval storage: it is rendered by the
//!   static path exactly ([`accum::render`] with one time);
//! - static triangles (no motion in 2DH) go through the static rasteriser
//!   ([`crate::raster`], coverage at pixel centres, near-plane clipping) and become one
//!   interval `[0, 1]` of constant depth;
//! - moving triangles whose six vertices all lie in front of the near plane (view depth >=
//!   near and w > 0 at open and close, hence throughout the shutter) are swept exactly with
//!   edge-eqn over the bounding box of their six projected vertices (the projection of a
//!   2DH segment with w > 0 is a screen segment, so the box is conservative);
//! - moving triangles that touch or cross the near plane during the shutter cannot be fed
//!   to edge-eqn (it reports crossings behind the eye and does not clip): the shutter is cut
//!   into [`NEAR_SLICES`] equal slices and each slice is rasterised by the static rasteriser
//!   (with clipping) at its midpoint into intervals spanning the slice — accum-style, exact
//!   in the limit of many slices, and only for those triangles;
//! - flat materials carry an [`Rgba`] payload (straight alpha), textured materials a
//!   [`Textured`] payload (UV at the interval ends from perspective-correct barycentrics,
//!   Eq. 11-12) shaded by [`PreparedScene::shade`] through a tap filter;
//! - opaque scenes use the opaque insertion (bounded buffers) and opaque resolve;
//!   intersection handling in the resolve only when the pipeline says objects may
//!   interpenetrate.
//!
//! Far clipping is approximate for moving intervals: a span is dropped when its depth is
//! beyond the far plane at both ends. Splats are not supported (use `ewa` or `accum`).
//!
//! Arithmetic of the whole chain (edge-eqn, interval-buffer, resolve) is f32 or f64
//! ([`Precision`], `--precision`); scene preparation is f64 either way.
//!
//! Cost control, none of which changes what is covered:
//! - opaque closed meshes lose the triangles that face away from the eye for the whole
//!   shutter ([`crate::cull`], Rønnow 2021 §4.4 made conservative);
//! - a moving triangle is evaluated only at pixel centres inside the convex hull of its six
//!   projected vertices, row by row ([`crate::hull`]), not over its whole bounding box;
//! - per pixel the span depth is the chord through the exact depth at both span ends
//!   (Eq. 16 as edge-eqn's `linear_depth` defines it, without its error estimate);
//! - rows are independent: each row's intervals are emitted once, placed into that row's
//!   exact lists ([`interval_buffer::PixelLists`]: count, scan, place, sort; Rønnow 2021
//!   §4.1-4.2) or bounded buffer, and resolved at once, in parallel over rows, so the
//!   interval storage is one row per thread, reused from row to row.

use std::fmt;
use std::str::FromStr;
use std::sync::{Arc, Mutex};

use glam::DVec2;
use interval_buffer::{
    BoundedBuffer, Insertion, Interval, IntervalCounts, Oracle, Payload, PixelLists, Rgba, Textured,
};
use num_traits::Float;
use rayon::prelude::*;
use resolve::{Flat, Scratch, Settings, Shader, TapFilter};

use edge_eqn::{MovingTriangle, TriangleSetup};

use crate::accum;
use crate::effects::Pipeline;
use crate::error::{Error, Result};
use crate::hull::SweptHull;
use crate::image::Image;
use crate::prepared::{PreparedScene, PreparedTriangle};
use crate::progress::Progress;
use crate::raster::{ScreenTriangle, Target, setup as raster_setup};

/// Rows per bin when distributing primitives over the image.
const BAND_ROWS: u32 = 8;

/// Number of shutter slices a moving triangle that touches the near plane is rasterised in.
pub const NEAR_SLICES: u32 = 64;

/// Texture taps per texel of a partition's UV segment: a textured span's filter takes this
/// many taps per texel its UV segment crosses.
pub const TAPS_PER_TEXEL: f64 = 16.0;

/// Most texture taps per partition for textured payloads (the cap on the per-texel count).
pub const TEXTURE_TAPS: usize = 256;

/// Textured moving spans are cut into at most this many pieces per shutter length, each
/// with its own UVs at both ends: the resolve interpolates UV linearly over an interval
/// (Rønnow 2021 Fig. 6), while the true UV path at a pixel under rotation or perspective is
/// curved. How many pieces a span actually gets is decided by [`TEXTURE_TOLERANCE`].
pub const TEXTURE_PIECES: u32 = 32;

/// Texels the linear UV of a piece may stray from the true UV path at the pixel: a
/// textured span is cut into n equal pieces with n the smallest count whose estimated
/// deviation (the span's deviation from its chord at 1/4, 1/2 and 3/4, divided by n²)
/// is at most this, capped by [`TEXTURE_PIECES`]. A span whose UV path is straight (pure
/// translation parallel to the image plane, or a static pixel) stays one interval.
///
/// The colour error is at most the texture's colour step per texel times this. On the
/// rotating `textured-quad` (a hard-edged checker, 8 texels per square) at 64x36 the RMSE
/// against accum at 512 times is 1.39e-3 with 1/16 texel, 3.96e-4 with 1/64, 1.55e-4 with
/// 1/256, against 1.26e-4 when every span takes the full [`TEXTURE_PIECES`] cut; a nearly
/// static textured clothball at 1024² keeps 0.6 M of its 16.5 M intervals, and one
/// translating by 0.06 of its radius 6.0 M of 19.5 M.
pub const TEXTURE_TOLERANCE: f64 = 1.0 / 256.0;

/// Largest accepted `--intervals`.
pub const MAX_INTERVALS: u32 = 1024;

/// Floating-point type of the interval chain (edge-eqn sweep, interval buffer, resolve).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Precision {
    /// Single precision (the default; what the papers' GPU implementations use).
    #[default]
    F32,
    /// Double precision.
    F64,
}

impl Precision {
    /// Both precisions.
    pub const ALL: [Precision; 2] = [Precision::F32, Precision::F64];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}

impl fmt::Display for Precision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Precision {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        crate::method::parse_by_name(s, &Precision::ALL, Precision::name, "precision")
    }
}

/// The float types the interval chain runs in.
pub(crate) trait Real: Float + Default + Send + Sync + fmt::Debug + 'static {}

impl Real for f32 {}
impl Real for f64 {}

/// `v` in `F` (f64 -> f32 rounds; never fails for the float types used here).
#[inline]
pub(crate) fn cf<F: Real>(v: f64) -> F {
    F::from(v).unwrap_or_else(F::zero)
}

/// End of piece `j` of `n` equal pieces of [t0, t1] (`j = n` gives `t1` exactly): how a
/// covered span is split so that each textured piece carries its own UV and depth chord.
#[inline]
pub(crate) fn piece_end<F: Real>(t0: F, t1: F, j: u32, n: u32) -> F {
    if j == n {
        t1
    } else if j == 0 {
        // The general formula's value without its division: (t1 - t0) * 0 is +0 for the
        // t1 >= t0 of a span.
        t0 + F::zero()
    } else {
        t0 + (t1 - t0) * (cf::<F>(f64::from(j)) / cf::<F>(f64::from(n)))
    }
}

/// Number of equal pieces the textured span [t0, t1] is cut into (see
/// [`TEXTURE_TOLERANCE`]): `uv(t)` is the true texture coordinate at the pixel at time t,
/// `texels` the texture's size (texels per unit of UV). The UV path is a ratio of
/// quadratics in t (Gribel 2010, Eq. 11-12); over a short piece it is close to a parabola,
/// whose deviation from its chord falls as 1/n² with n pieces. One piece when the old
/// cap allows only one (no extra work for short spans); the cap when the estimate is not
/// finite.
fn texture_pieces<F: Real>(t0: F, t1: F, texels: DVec2, uv: impl Fn(F) -> DVec2) -> u32 {
    let len = (t1 - t0).to_f64().unwrap_or(0.0);
    let cap = (len * f64::from(TEXTURE_PIECES)).ceil();
    // Also one piece for a NaN length.
    if cap.is_nan() || cap <= 1.0 {
        return 1;
    }
    let cap = cap.min(f64::from(TEXTURE_PIECES)) as u32;
    let (a, b) = (uv(t0), uv(t1));
    let mut dev: f64 = 0.0;
    for s in [0.25, 0.5, 0.75] {
        let p = uv(t0 + (t1 - t0) * cf::<F>(s));
        let d = ((p - a.lerp(b, s)) * texels).length();
        dev = if d.is_finite() {
            dev.max(d)
        } else {
            f64::INFINITY
        };
    }
    if !dev.is_finite() {
        return cap;
    }
    ((dev / TEXTURE_TOLERANCE).sqrt().ceil() as u32).clamp(1, cap)
}

/// Depth slope of the chord from (ta, za) to (tb, zb); zero for an empty or non-finite chord.
#[inline]
fn chord_slope<F: Real>(ta: F, tb: F, za: F, zb: F) -> F {
    let k = if tb > ta {
        (zb - za) / (tb - ta)
    } else {
        F::zero()
    };
    if k.is_finite() { k } else { F::zero() }
}

/// Options of the analytic method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AnalyticOptions {
    /// Intervals per pixel: 0 = exact unbounded lists (Rønnow 2021 §4.1-4.2), K > 0 = at
    /// most K per pixel with the paper's oracle compression (Gribel 2010 §5.2).
    pub intervals: u32,
    /// Arithmetic of the interval chain.
    pub precision: Precision,
    /// Keep the back-facing triangles of opaque closed meshes (turns off the conservative
    /// culling of [`crate::cull`]; for checking it).
    pub keep_backfaces: bool,
}

/// What the last render stored, per pixel (printed by `mblur render`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IntervalStats {
    /// Intervals emitted into the buffers (before any compression).
    pub total: u64,
    /// Largest number emitted into one pixel.
    pub max: u32,
    /// Pixels that received at least one interval.
    pub covered: u64,
    /// Pixels in the image.
    pub pixels: u64,
    /// Triangles removed by the conservative back-face culling.
    pub culled: u64,
}

impl IntervalStats {
    /// Mean intervals per covered pixel.
    pub fn mean(&self) -> f64 {
        if self.covered == 0 {
            0.0
        } else {
            self.total as f64 / self.covered as f64
        }
    }
}

impl fmt::Display for IntervalStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "intervals: {} total, {:.1} mean / {} max per covered pixel ({} of {} pixels covered); {} back-facing triangles culled",
            self.total,
            self.mean(),
            self.max,
            self.covered,
            self.pixels,
            self.culled
        )
    }
}

/// The `analytic` renderer.
#[derive(Debug, Clone, Default)]
pub struct AnalyticRenderer {
    /// Its options.
    pub options: AnalyticOptions,
    /// Statistics of the last render.
    last: Arc<Mutex<Option<IntervalStats>>>,
}

impl AnalyticRenderer {
    /// A renderer with these options.
    pub fn new(options: AnalyticOptions) -> Self {
        AnalyticRenderer {
            options,
            last: Arc::default(),
        }
    }

    /// Statistics of the last render through this renderer.
    pub fn last_stats(&self) -> Option<IntervalStats> {
        self.last.lock().ok().and_then(|l| *l)
    }
}

/// One primitive that leaves intervals in pixels.
#[derive(Debug, Clone)]
pub(crate) enum Prim<F = f32> {
    /// A static (or time-sliced) screen triangle covering time `[t0, t1]`.
    Fixed {
        st: Box<ScreenTriangle>,
        t0: F,
        t1: F,
    },
    /// A moving triangle swept exactly by edge-eqn over pixel bounds `x0..=x1`, `y0..=y1`,
    /// row by row inside `hull`.
    Moving {
        setup: Box<TriangleSetup<F>>,
        /// The pixel whose corner is the origin of `setup`'s coordinates ([`local_centre`]).
        origin: [u32; 2],
        hull: Box<SweptHull>,
        tri: u32,
        x0: u32,
        x1: u32,
        y0: u32,
        y1: u32,
    },
    /// A moving triangle swept by ray-vs-prism intersection (bilinear-patch, Rønnow 2021
    /// §4.1) over pixel bounds `x0..=x1`, `y0..=y1`, row by row inside `hull`.
    Prism {
        prism: Box<bilinear_patch::Prism<F>>,
        /// The pixel whose corner is the origin of `prism`'s coordinates ([`local_centre`]).
        origin: [u32; 2],
        hull: Box<SweptHull>,
        tri: u32,
        x0: u32,
        x1: u32,
        y0: u32,
        y1: u32,
    },
}

/// Which exact sweep moving triangles in front of the near plane take.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Sweep {
    /// edge-eqn (Gribel 2010): exact in 2DH, rational depth fitted linearly per span.
    EdgeEqn,
    /// bilinear-patch prism (Rønnow 2021): screen-space vertices moving linearly.
    Prism,
}

impl<F> Prim<F> {
    pub(crate) fn rows(&self) -> (u32, u32) {
        match self {
            Prim::Fixed { st, .. } => (st.y0, st.y1),
            Prim::Moving { y0, y1, .. } | Prim::Prism { y0, y1, .. } => (*y0, *y1),
        }
    }
}

/// The pixel bounds (pixel centres inside `[lo, hi]`) clamped to the image, or `None`.
pub(crate) fn pixel_bounds(
    lo: DVec2,
    hi: DVec2,
    width: u32,
    height: u32,
) -> Option<(u32, u32, u32, u32)> {
    let first = |v: f64, n: u32| (v - 0.5).ceil().clamp(0.0, f64::from(n)) as u32;
    let last = |v: f64, n: u32| (v - 0.5).floor().clamp(-1.0, f64::from(n) - 1.0) as i64;
    let (x0, y0) = (first(lo.x, width), first(lo.y, height));
    let (x1, y1) = (last(hi.x, width), last(hi.y, height));
    if x1 < i64::from(x0) || y1 < i64::from(y0) {
        None
    } else {
        Some((x0, x1 as u32, y0, y1 as u32))
    }
}

/// True when all six vertices are strictly in front of the eye and at or beyond the near
/// plane, so linear motion keeps the whole triangle there for the whole shutter.
pub(crate) fn in_front(tri: &PreparedTriangle, near: f64) -> bool {
    tri.open
        .iter()
        .chain(&tri.close)
        .all(|v| v.w > 0.0 && v.depth >= near)
}

/// Static rasteriser primitives for triangle `i` at time `t`, covering `[t0, t1]`.
fn fixed_prims<F: Real>(
    scene: &PreparedScene,
    target: &Target,
    i: u32,
    (t, t0, t1): (f64, f64, f64),
    out: &mut Vec<Prim<F>>,
) {
    let Some(tri) = scene.triangles.get(i as usize) else {
        return;
    };
    let mut sts = Vec::new();
    raster_setup(tri, t, i, scene.is_opaque(tri.material), target, &mut sts);
    out.extend(sts.into_iter().map(|st| Prim::Fixed {
        st: Box::new(st),
        t0: cf(t0),
        t1: cf(t1),
    }));
}

/// The swept primitive of a moving triangle in front of the near plane, or `None` when it
/// misses the image or its setup is degenerate.
fn moving_prim<F: Real>(
    scene: &PreparedScene,
    tri: &PreparedTriangle,
    i: u32,
    sweep: Sweep,
) -> Option<Prim<F>> {
    type V = crate::camera::Vertex2dh;
    let z = |a: &[V; 3]| a.map(|p| cf::<F>(p.depth));
    let mut points = [DVec2::ZERO; 6];
    for (q, p) in points.iter_mut().zip(tri.open.iter().chain(&tri.close)) {
        let (x, y) = p.screen();
        *q = DVec2::new(x, y);
    }
    let (lo, hi) = points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let (x0, x1, y0, y1) = pixel_bounds(lo, hi, scene.width, scene.height)?;
    let hull = Box::new(SweptHull { points });
    // Local coordinates (see `local_centre`): the origin is the corner of the
    // ORIGIN_BLOCK-pixel block holding (x0, y0). The shift is done in f64 before rounding
    // to F, so f32 keeps its precision for the small offsets instead of spending it on the
    // position in the image.
    let origin = [x0, y0].map(|v| v - v % ORIGIN_BLOCK);
    let (ox, oy) = (f64::from(origin[0]), f64::from(origin[1]));
    match sweep {
        Sweep::EdgeEqn => {
            let v = |a: &[V; 3]| a.map(|p| [cf::<F>(p.x - ox * p.w), cf(p.y - oy * p.w), cf(p.w)]);
            let setup = MovingTriangle::new(v(&tri.open), v(&tri.close))
                .with_depth(z(&tri.open), z(&tri.close))
                .setup();
            setup.is_valid().then(|| Prim::Moving {
                setup: Box::new(setup),
                origin,
                hull,
                tri: i,
                x0,
                x1,
                y0,
                y1,
            })
        }
        Sweep::Prism => {
            let sv = |a: &[V; 3]| {
                a.map(|p| {
                    let (x, y) = p.screen();
                    bilinear_patch::ScreenVertex {
                        x: cf::<F>(x - ox),
                        y: cf(y - oy),
                        depth: cf(p.depth),
                    }
                })
            };
            let prism = bilinear_patch::Prism::new(sv(&tri.open), sv(&tri.close));
            Some(Prim::Prism {
                prism: Box::new(prism),
                origin,
                hull,
                tri: i,
                x0,
                x1,
                y0,
                y1,
            })
        }
    }
}

/// Builds the primitives of every triangle, with the conservative back-face culling of
/// [`crate::cull`], in f32 (the entry point for tools that look at single pixels).
#[allow(dead_code)]
pub(crate) fn build_prims(scene: &PreparedScene, sweep: Sweep) -> Vec<Prim<f32>> {
    build_prims_with(scene, sweep, true).0
}

/// Builds the primitives of every triangle, culling (`cull`) or keeping the back faces of
/// opaque closed meshes; also returns how many triangles were culled.
pub(crate) fn build_prims_with<F: Real>(
    scene: &PreparedScene,
    sweep: Sweep,
    cull: bool,
) -> (Vec<Prim<F>>, u64) {
    let target = Target {
        width: scene.width,
        height: scene.height,
        near: scene.near,
    };
    let culled = if cull {
        crate::cull::backface_mask(scene)
    } else {
        Vec::new()
    };
    let prims = (0..scene.triangles.len() as u32)
        .into_par_iter()
        .with_min_len(256)
        .fold(Vec::new, |mut out, i| {
            let tri = &scene.triangles[i as usize];
            if culled.get(i as usize).copied().unwrap_or(false) {
                return out;
            }
            if !tri.is_moving() {
                fixed_prims(scene, &target, i, (0.0, 0.0, 1.0), &mut out);
            } else if in_front(tri, scene.near) {
                out.extend(moving_prim(scene, tri, i, sweep));
            } else {
                let n = NEAR_SLICES;
                for k in 0..n {
                    let (a, b) = (f64::from(k) / f64::from(n), f64::from(k + 1) / f64::from(n));
                    fixed_prims(scene, &target, i, (0.5 * (a + b), a, b), &mut out);
                }
            }
            out
        })
        .reduce(Vec::new, |mut a, mut b| {
            a.append(&mut b);
            a
        });
    (prims, culled.iter().filter(|&&c| c).count() as u64)
}

/// Primitive indices per band of [`BAND_ROWS`] rows.
pub(crate) fn bin<F>(prims: &[Prim<F>], height: u32) -> Vec<Vec<u32>> {
    let mut bins = vec![Vec::new(); height.div_ceil(BAND_ROWS) as usize];
    for (i, p) in prims.iter().enumerate() {
        let (y0, y1) = p.rows();
        for b in y0 / BAND_ROWS..=y1 / BAND_ROWS {
            if let Some(bin) = bins.get_mut(b as usize) {
                bin.push(i as u32);
            }
        }
    }
    bins
}

/// Makes payloads from (material, uv at span start, uv at span end).
pub(crate) trait MakePayload<F: Real = f32>: Sync {
    /// The payload type.
    type P: Payload<F> + Copy + Default + Send + Sync;
    /// Texels per unit of UV of `material`'s texture, or `None` when its payload carries
    /// no UV (then moving spans are never cut into pieces; see [`texture_pieces`]).
    fn texels(&self, material: u32) -> Option<DVec2> {
        let _ = material;
        None
    }
    fn make(&self, material: u32, uv0: DVec2, uv1: DVec2) -> Self::P;
}

/// Flat payloads: the material's straight-alpha colour.
pub(crate) struct FlatPayload<F = f32>(pub Vec<Rgba<F>>);

impl<F: Real> MakePayload<F> for FlatPayload<F> {
    type P = Rgba<F>;
    fn make(&self, material: u32, _: DVec2, _: DVec2) -> Rgba<F> {
        self.0.get(material as usize).copied().unwrap_or_default()
    }
}

/// Textured payloads: UVs at the ends and the material's alpha; per material the size of
/// its texture in texels, if it has one (only those spans are cut into pieces).
pub(crate) struct TexPayload<F = f32>(pub Vec<F>, pub Vec<Option<DVec2>>);

impl<F: Real> MakePayload<F> for TexPayload<F> {
    type P = Textured<F>;
    fn texels(&self, material: u32) -> Option<DVec2> {
        self.1.get(material as usize).copied().flatten()
    }
    fn make(&self, material: u32, uv0: DVec2, uv1: DVec2) -> Textured<F> {
        Textured {
            uv_start: [cf(uv0.x), cf(uv0.y)],
            uv_end: [cf(uv1.x), cf(uv1.y)],
            material,
            normal: [F::zero(); 3],
            alpha: self
                .0
                .get(material as usize)
                .copied()
                .unwrap_or_else(F::zero),
        }
    }
}

/// Straight-alpha colour from premultiplied `p`, alpha divided by `material_alpha`.
fn straight<F: Real>(p: [f64; 4], material_alpha: f64) -> Rgba<F> {
    if p[3] <= 0.0 || material_alpha <= 0.0 {
        return Rgba::default();
    }
    let a = p[3];
    // An opaque texel of an opaque material: the divisions below are by one (exact), so
    // skip them; the same bits, four divisions fewer per texture tap.
    if a == 1.0 && material_alpha == 1.0 {
        return Rgba::new(cf(p[0]), cf(p[1]), cf(p[2]), F::one());
    }
    Rgba::new(
        cf(p[0] / a),
        cf(p[1] / a),
        cf(p[2] / a),
        cf((a / material_alpha).min(1.0)),
    )
}

/// Side of the blocks whose corners are the origins of moving primitives' local
/// coordinates ([`local_centre`]).
///
/// Triangles in one block share the origin, so an edge they share gives them exactly
/// negated edge functions and bit-identical crossing times, as in absolute coordinates.
/// With an origin per triangle (its own corner pixel) the two sides of a shared edge
/// rounded differently: tiny gaps and overlaps between neighbours' intervals that the
/// resolve paid for as extra partitions. Measured with cachegrind (clothball 160x160, one
/// thread): absolute coordinates 6.18 G instructions; an origin per triangle 6.36 G
/// (resolve and shading +25 %); blocks of 8 / 16 / 32 px 6.27 / 6.24 / 6.22 G. The largest
/// f32 vs f64 difference on clothball-ronnow (512x512) is 0.0004 with an origin per
/// triangle, 0.0007 / 0.0009 / 0.0045 with blocks of 8 / 16 / 32 px, 0.022 in absolute
/// coordinates.
const ORIGIN_BLOCK: u32 = 16;

/// The centre of the pixel `offset` pixels right of (or below) the origin of a moving
/// primitive, in its local coordinates: `offset + 0.5`, exact in f32 below 2^23 pixels.
///
/// Moving primitives keep their 2DH vertices relative to the corner of the
/// [`ORIGIN_BLOCK`]-pixel block holding the corner of their bounds ([`moving_prim`]).
/// Edge functions are products of coordinates, so in absolute coordinates f32 loses
/// precision in proportion to the position in the image: on clothball-ronnow at 512x512 a
/// silhouette edge grazing a pixel centre (a tangent root pair of Gribel 2010, Eq. 7)
/// covered it for 0.035 of the shutter too long. The shift is exact algebra
/// (a translation with determinant 1 leaves the edge functions, barycentrics and depth at
/// the shifted sample unchanged); only the rounding improves.
#[inline]
fn local_centre<F: Real>(offset: u32) -> F {
    cf(f64::from(offset) + 0.5)
}

/// Calls `f(x, iv)` for every interval primitive `prim` leaves in row `y`, columns
/// `xs..xe`.
pub(crate) fn emit<F: Real, M: MakePayload<F>>(
    scene: &PreparedScene,
    prim: &Prim<F>,
    (y, xs, xe): (u32, u32, u32),
    mk: &M,
    mut f: impl FnMut(usize, Interval<F, M::P>) -> Result<()>,
) -> Result<()> {
    let far: F = cf(scene.far);
    let zero = F::zero();
    // The columns of row y to evaluate: inside the bounds, the hull's row span and xs..xe.
    let columns = |hull: &SweptHull, x0: u32, x1: u32, y0: u32, y1: u32| {
        if y < y0 || y > y1 || xe == 0 {
            return None;
        }
        hull.pixels(y, x0.max(xs), x1.min(xe - 1))
    };
    match prim {
        Prim::Fixed { st, t0, t1 } => {
            let mut res = Ok(());
            st.rasterise(y, y + 1, |x, _, frag| {
                if res.is_err() || frag.depth > scene.far || x < xs || x >= xe {
                    return;
                }
                let p = mk.make(st.material, frag.uv, frag.uv);
                res = f(x as usize, Interval::new(*t0, *t1, cf(frag.depth), zero, p));
            });
            res
        }
        Prim::Moving {
            setup,
            origin: [ox, oy],
            hull,
            tri,
            x0,
            x1,
            y0,
            y1,
        } => {
            let Some((cx0, cx1)) = columns(hull, *x0, *x1, *y0, *y1) else {
                return Ok(());
            };
            let Some(t) = scene.triangles.get(*tri as usize) else {
                return Ok(());
            };
            let sy = local_centre(y - *oy);
            let texels = mk.texels(t.material);
            for x in cx0..=cx1 {
                let s = setup.sample(local_centre(x - *ox), sy);
                let cov = s.coverage();
                if cov.iter().next().is_none() {
                    continue;
                }
                // Eq. 16 as edge-eqn's `linear_depth` defines it: the chord through the
                // exact depth (Eq. 15) at the span ends (its error estimate is not needed).
                let depth = s.depth();
                for whole in cov.iter() {
                    if whole.t1.partial_cmp(&whole.t0).is_none_or(|o| o.is_lt()) {
                        continue;
                    }
                    let uv = |tt: F| {
                        let bc = s.barycentrics(tt).map(|v| v.to_f64().unwrap_or(0.0));
                        t.uv[0] * bc[0] + t.uv[1] * bc[1] + t.uv[2] * bc[2]
                    };
                    let n = texels.map_or(1, |tx| texture_pieces(whole.t0, whole.t1, tx, uv));
                    for j in 0..n {
                        let a = piece_end(whole.t0, whole.t1, j, n);
                        let b = piece_end(whole.t0, whole.t1, j + 1, n).max(a);
                        let (za, zb) = (depth.eval(a), depth.eval(b));
                        let k = chord_slope(a, b, za, zb);
                        if !za.is_finite() || (za > far && zb > far) {
                            continue;
                        }
                        let p = mk.make(t.material, uv(a), uv(b));
                        f(x as usize, Interval::new(a, b, za, k, p))?;
                    }
                }
            }
            Ok(())
        }
        Prim::Prism {
            prism,
            origin: [ox, oy],
            hull,
            tri,
            x0,
            x1,
            y0,
            y1,
        } => {
            let Some((cx0, cx1)) = columns(hull, *x0, *x1, *y0, *y1) else {
                return Ok(());
            };
            let Some(t) = scene.triangles.get(*tri as usize) else {
                return Ok(());
            };
            let sy = local_centre(y - *oy);
            let uv = |b: [F; 2]| {
                let (b1, b2) = (b[0].to_f64().unwrap_or(0.0), b[1].to_f64().unwrap_or(0.0));
                t.uv[0] * (1.0 - b1 - b2) + t.uv[1] * b1 + t.uv[2] * b2
            };
            let texels = mk.texels(t.material);
            for x in cx0..=cx1 {
                let (px, py) = (local_centre::<F>(x - *ox), sy);
                for span in prism.coverage(px, py).iter() {
                    let len = span.t1 - span.t0;
                    let k = if len > zero {
                        (span.depth1 - span.depth0) / len
                    } else {
                        zero
                    };
                    let ok = len >= zero && span.depth0.is_finite() && k.is_finite();
                    if !ok || (span.depth0 > far && span.depth1 > far) {
                        continue;
                    }
                    // Textured spans may be cut into pieces with their own UV and depth at
                    // the ends, from the screen-space barycentrics of the triangle at that
                    // time (the prism's own model of the motion).
                    let at = |tt: F| -> ([F; 2], F) {
                        let v = prism.at(tt);
                        let (ax, ay) = (v[1].x - v[0].x, v[1].y - v[0].y);
                        let (bx, by) = (v[2].x - v[0].x, v[2].y - v[0].y);
                        let (cx, cy) = (px - v[0].x, py - v[0].y);
                        let d = ax * by - ay * bx;
                        let (b1, b2) = ((cx * by - cy * bx) / d, (ax * cy - ay * cx) / d);
                        let z =
                            (F::one() - b1 - b2) * v[0].depth + b1 * v[1].depth + b2 * v[2].depth;
                        if b1.is_finite() && b2.is_finite() && z.is_finite() {
                            ([b1, b2], z)
                        } else {
                            let s = (tt - span.t0) / len;
                            let l = |a: F, b: F| a + (b - a) * s;
                            (
                                [l(span.uv0[0], span.uv1[0]), l(span.uv0[1], span.uv1[1])],
                                l(span.depth0, span.depth1),
                            )
                        }
                    };
                    let n = texels.map_or(1, |tx| {
                        texture_pieces(span.t0, span.t1, tx, |tt| uv(at(tt).0))
                    });
                    if n == 1 {
                        let p = mk.make(t.material, uv(span.uv0), uv(span.uv1));
                        f(
                            x as usize,
                            Interval::new(span.t0, span.t1, span.depth0, k, p),
                        )?;
                        continue;
                    }
                    let mut prev = (span.t0, span.uv0, span.depth0);
                    for j in 1..=n {
                        let (tb, bb, zb) = if j == n {
                            (span.t1, span.uv1, span.depth1)
                        } else {
                            let tb = piece_end(span.t0, span.t1, j, n);
                            let (bb, zb) = at(tb);
                            (tb, bb, zb)
                        };
                        let (ta, ba, za) = prev;
                        let kk = chord_slope(ta, tb, za, zb);
                        let p = mk.make(t.material, uv(ba), uv(bb));
                        f(x as usize, Interval::new(ta, tb.max(ta), za, kk, p))?;
                        prev = (tb, bb, zb);
                    }
                }
            }
            Ok(())
        }
    }
}

/// Calls `f(triangle, interval)` for every interval `sweep` leaves in pixel (x, y), in
/// the order the interval buffers receive them (the same primitives and [`emit`] as a full
/// render; used by the temporal pixel visualiser, [`crate::inspect`]).
pub(crate) fn pixel_intervals<M: MakePayload>(
    scene: &PreparedScene,
    sweep: Sweep,
    mk: &M,
    (x, y): (u32, u32),
    mut f: impl FnMut(u32, Interval<f32, M::P>),
) -> Result<()> {
    for prim in &build_prims(scene, sweep) {
        let tri = match prim {
            Prim::Fixed { st, .. } => st.order,
            Prim::Moving { tri, .. } | Prim::Prism { tri, .. } => *tri,
        };
        emit(scene, prim, (y, x, x.saturating_add(1)), mk, |_, iv| {
            f(tri, iv);
            Ok(())
        })?;
    }
    Ok(())
}

fn buffer_error(e: interval_buffer::Error) -> Error {
    Error::MethodNotApplicable {
        method: "analytic".into(),
        reason: format!("interval buffer: {e}"),
    }
}

/// Resolve settings for the scene and pipeline (Gribel 2010 §5.1, Eq. 17).
pub(crate) fn settings_of<F: Real>(
    scene: &PreparedScene,
    pipeline: &Pipeline,
) -> Result<Settings<F>> {
    let base = if pipeline.transparency {
        Settings::transparent()
    } else {
        Settings::opaque()
    };
    let points: Vec<(F, F)> = scene
        .shutter
        .points
        .iter()
        .map(|&(t, w)| (cf(t), cf(w)))
        .collect();
    let shutter =
        resolve::Shutter::from_points(&points).map_err(|e| Error::MethodNotApplicable {
            method: "analytic".into(),
            reason: format!("shutter response: {e}"),
        })?;
    let [r, g, b] = scene.background.map(cf::<F>);
    Ok(base
        .with_intersections(pipeline.intersection)
        .with_shutter(shutter)
        .with_background(Rgba::opaque(r, g, b)))
}

/// The texture lookup handed to the resolve: [`PreparedScene::shade`] as straight alpha,
/// divided by the material alpha the payload already carries.
pub(crate) fn texture_fn_of<F: Real>(
    scene: &PreparedScene,
) -> impl Fn(u32, [F; 2]) -> Rgba<F> + Sync {
    move |m: u32, uv: [F; 2]| {
        let a = scene.materials.get(m as usize).map_or(0.0, |m| m.color[3]);
        let [u, v] = uv.map(|c| c.to_f64().unwrap_or(0.0));
        straight(scene.shade(m, DVec2::new(u, v)), a)
    }
}

/// Textured shading with the number of taps adapted to the partition: the tap filter of
/// the resolve crate ([`TapFilter`], midpoint rule along the partition's UV segment, each
/// tap weighted by the shutter response) with `clamp(ceil(TAPS_PER_TEXEL L), 1,
/// TEXTURE_TAPS)` taps, where L is the segment's length in texels, so taps stay at most
/// 1/16 texel apart. Inside one bilinear cell the texture is a quadratic in the step, which
/// the midpoint rule integrates with error below 1/24 of its second difference; where the
/// segment crosses a cell border the bilinear texture has a kink, and the midpoint rule's
/// error there grows with the square of the spacing (two taps per texel left an RMSE of
/// 1.3e-3 on the scrolling checker backdrop of `pills` once its spans stopped being cut
/// into 1/32-shutter pieces; 16 per texel, 8e-5). A moving mesh whose spans each cover a
/// small fraction of a texel (clothball) still costs one lookup per partition.
pub(crate) struct AdaptiveTaps<'a, T: ?Sized> {
    texture: &'a T,
    /// Per material: the larger texture dimension in texels (0 for untextured).
    texels: Vec<f64>,
}

impl<'a, T: ?Sized> AdaptiveTaps<'a, T> {
    pub(crate) fn new(texture: &'a T, scene: &PreparedScene) -> Self {
        let texels = scene
            .materials
            .iter()
            .map(|m| {
                m.texture
                    .and_then(|t| scene.textures.get(t as usize))
                    .map_or(0.0, |t| f64::from(t.width.max(t.height)))
            })
            .collect();
        AdaptiveTaps { texture, texels }
    }

    fn taps<F: Real>(&self, material: u32, du: F, dv: F) -> usize {
        let n = self.texels.get(material as usize).copied().unwrap_or(0.0);
        let len = du.abs().max(dv.abs()).to_f64().unwrap_or(f64::INFINITY) * n;
        if len.is_finite() {
            ((TAPS_PER_TEXEL * len).ceil() as usize).clamp(1, TEXTURE_TAPS)
        } else {
            TEXTURE_TAPS
        }
    }
}

impl<F: Real, T: resolve::Texture<F> + ?Sized> Shader<F, Textured<F>> for AdaptiveTaps<'_, T> {
    fn shade(&self, iv: &Interval<F, Textured<F>>, t0: F, t1: F, w0: F, w1: F) -> [F; 4] {
        let (uv0, uv1) = (resolve::uv_at(iv, t0), resolve::uv_at(iv, t1));
        let p = &iv.payload;
        let taps = self.taps(p.material, uv1[0] - uv0[0], uv1[1] - uv0[1]);
        // The UV ends computed once for the tap count and the filter (what
        // `TapFilter::shade` would compute again from the interval).
        TapFilter::new(self.texture, taps).shade_segment((p.material, p.alpha), uv0, uv1, w0, w1)
    }

    fn shade_at(&self, iv: &Interval<F, Textured<F>>, t: F) -> [F; 4] {
        TapFilter::new(self.texture, 1).shade_at(iv, t)
    }
}

/// One row's output: linear RGB per pixel and what its buffers held.
type Row = (Vec<[f32; 3]>, IntervalStats);

/// Per-thread working memory of [`render_row`], reused from row to row: the resolve's
/// scratch, the row's emitted `(x, interval)` pairs and its exact lists.
type RowScratch<F, P> = (Scratch<F>, Vec<(u32, Interval<F, P>)>, PixelLists<F, P>);

/// Emits, buffers and resolves row `y`: every primitive of the row's band emits its
/// intervals once into `emitted`, in primitive order; they go into the row's exact lists
/// (`k == 0`: count, scan, place, per-pixel sort by ts, in memory kept from the previous
/// row; Rønnow 2021 §4.1-4.2) or its bounded buffer (K per pixel, the paper's oracle), and
/// each pixel is resolved from its sorted list.
#[allow(clippy::too_many_arguments)]
fn render_row<F: Real, M: MakePayload<F>, S: Shader<F, M::P> + Sync>(
    scene: &PreparedScene,
    prims: &[Prim<F>],
    band: &[u32],
    (y, k, opaque): (u32, u32, bool),
    mk: &M,
    shader: &S,
    settings: &Settings<F>,
    (scratch, emitted, lists): &mut RowScratch<F, M::P>,
) -> Result<Row> {
    let w = scene.width as usize;
    emitted.clear();
    for &i in band {
        if let Some(prim) = prims.get(i as usize) {
            emit(scene, prim, (y, 0, scene.width), mk, |x, iv| {
                emitted.push((x as u32, iv));
                Ok(())
            })?;
        }
    }
    let mut stats = IntervalStats {
        total: emitted.len() as u64,
        pixels: w as u64,
        ..IntervalStats::default()
    };
    let mut pixels = Vec::with_capacity(w);
    let mut resolve_px = |x: usize, list: &[Interval<F, M::P>]| -> Result<()> {
        let c = resolve::resolve_with(scratch, list, shader, settings, |_| {}).map_err(|e| {
            Error::MethodNotApplicable {
                method: "analytic".into(),
                reason: format!("resolve at pixel ({x}, {y}): {e}"),
            }
        })?;
        pixels.push([c.r, c.g, c.b].map(|v| v.to_f32().filter(|v| v.is_finite()).unwrap_or(0.0)));
        Ok(())
    };
    if k == 0 {
        lists.rebuild(w, emitted).map_err(buffer_error)?;
        for x in 0..w {
            let c = lists.count(x);
            stats.max = stats.max.max(c);
            stats.covered += u64::from(c > 0);
        }
        for x in 0..w {
            resolve_px(x, lists.pixel(x))?;
        }
    } else {
        let how = Insertion {
            oracle: Oracle::paper_for(opaque),
            opaque,
        };
        let mut counts = IntervalCounts::new(w, 1).map_err(buffer_error)?;
        for &(x, _) in emitted.iter() {
            counts.count(x as usize).map_err(buffer_error)?;
        }
        for &c in counts.counts() {
            stats.max = stats.max.max(c);
            stats.covered += u64::from(c > 0);
        }
        let mut buf = BoundedBuffer::new(w, 1, k as usize, how).map_err(buffer_error)?;
        for (x, iv) in emitted.drain(..) {
            buf.insert(x as usize, 0, iv).map_err(buffer_error)?;
        }
        for x in 0..w {
            resolve_px(x, buf.pixel_index(x))?;
        }
    }
    Ok((pixels, stats))
}

/// The interval chain for one payload type and one float type, rows in parallel.
#[allow(clippy::too_many_arguments)]
fn run<F: Real, M: MakePayload<F>, S: Shader<F, M::P> + Sync>(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    (k, sweep, cull): (u32, Sweep, bool),
    mk: &M,
    shader: &S,
    progress: &dyn Progress,
) -> Result<(Image, IntervalStats)> {
    let (prims, culled) = build_prims_with::<F>(scene, sweep, cull);
    let bins = bin(&prims, scene.height);
    let settings = settings_of::<F>(scene, pipeline)?;
    let opaque = !pipeline.transparency;
    let rows: Vec<Row> = (0..scene.height)
        .into_par_iter()
        .map_init(
            || (Scratch::new(), Vec::new(), PixelLists::new()),
            |buf, y| {
                let band = bins
                    .get((y / BAND_ROWS) as usize)
                    .map_or(&[][..], |b| b.as_slice());
                let row = render_row(
                    scene,
                    &prims,
                    band,
                    (y, k, opaque),
                    mk,
                    shader,
                    &settings,
                    buf,
                );
                progress.advance(1);
                row
            },
        )
        .collect::<Result<_>>()?;
    let mut stats = IntervalStats {
        culled,
        ..IntervalStats::default()
    };
    let mut pixels = Vec::with_capacity(scene.width as usize * scene.height as usize);
    for (row, s) in rows {
        pixels.extend(row);
        stats.total += s.total;
        stats.max = stats.max.max(s.max);
        stats.covered += s.covered;
        stats.pixels += s.pixels;
    }
    Ok((
        Image {
            width: scene.width,
            height: scene.height,
            pixels,
        },
        stats,
    ))
}

/// Checks the scene has no feature the interval methods lack.
pub(crate) fn check_supported(method: &str, scene: &PreparedScene) -> Result<()> {
    if !scene.splats.is_empty() {
        return Err(Error::MethodNotApplicable {
            method: method.into(),
            reason: "the scene has splats (use --method ewa or accum)".into(),
        });
    }
    Ok(())
}

/// Flat payload table: each material's straight-alpha colour.
pub(crate) fn flat_payloads_of<F: Real>(scene: &PreparedScene) -> FlatPayload<F> {
    FlatPayload(
        scene
            .materials
            .iter()
            .map(|m| {
                let c = m.color.map(cf::<F>);
                Rgba::new(c[0], c[1], c[2], c[3].max(F::zero()).min(F::one()))
            })
            .collect(),
    )
}

/// Material alphas and texture sizes for textured payloads.
pub(crate) fn tex_payloads_of<F: Real>(scene: &PreparedScene) -> TexPayload<F> {
    TexPayload(
        scene
            .materials
            .iter()
            .map(|m| cf(m.color[3].clamp(0.0, 1.0)))
            .collect(),
        scene
            .materials
            .iter()
            .map(|m| {
                let t = scene.textures.get(m.texture? as usize)?;
                Some(DVec2::new(f64::from(t.width), f64::from(t.height)))
            })
            .collect(),
    )
}

/// Renders with the analytic method.
pub fn render(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    options: &AnalyticOptions,
    progress: &dyn Progress,
) -> Result<Image> {
    render_stats(scene, pipeline, options, progress).map(|(image, _)| image)
}

/// Renders with the analytic method and says what the interval buffers held (`None` for a
/// static opaque scene, which takes the static path).
pub fn render_stats(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    options: &AnalyticOptions,
    progress: &dyn Progress,
) -> Result<(Image, Option<IntervalStats>)> {
    check_supported("analytic", scene)?;
    if options.intervals > MAX_INTERVALS {
        return Err(Error::Option {
            option: "--intervals".into(),
            message: format!("must be at most {MAX_INTERVALS}, got {}", options.intervals),
        });
    }
    render_sweep(
        scene,
        pipeline,
        SweepOptions {
            intervals: options.intervals,
            sweep: Sweep::EdgeEqn,
            precision: options.precision,
            cull: !options.keep_backfaces,
        },
        progress,
    )
}

/// How [`render_sweep`] runs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SweepOptions {
    /// 0 = exact lists, K > 0 = bounded buffer.
    pub intervals: u32,
    /// The exact sweep of moving triangles.
    pub sweep: Sweep,
    /// Arithmetic of the chain.
    pub precision: Precision,
    /// Conservative back-face culling of opaque closed meshes.
    pub cull: bool,
}

fn render_typed<F: Real>(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    o: SweepOptions,
    progress: &dyn Progress,
) -> Result<(Image, IntervalStats)> {
    let how = (o.intervals, o.sweep, o.cull);
    if pipeline.textures {
        let tex = texture_fn_of::<F>(scene);
        run(
            scene,
            pipeline,
            how,
            &tex_payloads_of::<F>(scene),
            &AdaptiveTaps::new(&tex, scene),
            progress,
        )
    } else {
        run(
            scene,
            pipeline,
            how,
            &flat_payloads_of::<F>(scene),
            &Flat,
            progress,
        )
    }
}

/// The shared interval pipeline: primitives -> interval buffer (exact when `intervals ==
/// 0`) -> resolve, row by row; a fully static opaque scene takes the static path with no
/// interval storage.
pub(crate) fn render_sweep(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    o: SweepOptions,
    progress: &dyn Progress,
) -> Result<(Image, Option<IntervalStats>)> {
    if !pipeline.interval_storage {
        // A fully static opaque scene: exactly the static path, no interval storage.
        return Ok((accum::static_path(scene, progress)?, None));
    }
    progress.start(u64::from(scene.height));
    let (image, stats) = match o.precision {
        Precision::F32 => render_typed::<f32>(scene, pipeline, o, progress),
        Precision::F64 => render_typed::<f64>(scene, pipeline, o, progress),
    }?;
    progress.finish();
    Ok((image, Some(stats)))
}

/// The `describe` line shared by the interval methods (`analytic`, `prism`): what goes
/// through the motion path (`via`), the culling, the near-plane slicing, the static path,
/// the buffer (`lists`), the resolve the pipeline enables and the arithmetic.
pub(crate) fn describe_sweep(
    method: &str,
    via: &str,
    lists: &str,
    (scene, p): (&PreparedScene, &Pipeline),
    (precision, cull): (Precision, bool),
) -> String {
    if !p.interval_storage {
        return format!("{method}: static opaque scene, static path (no interval storage)");
    }
    let moving = scene.triangles.iter().filter(|t| t.is_moving()).count();
    let near = scene
        .triangles
        .iter()
        .filter(|t| t.is_moving() && !in_front(t, scene.near))
        .count();
    let culled = if cull {
        format!(
            "{} back-facing triangles of opaque closed meshes culled",
            crate::cull::backface_count(scene)
        )
    } else {
        "no back-face culling".to_string()
    };
    format!(
        "{method}: {moving} moving triangle{} via {via} ({near} near-plane crossing{} in {NEAR_SLICES} slices), {} static via the static rasteriser; {culled}; {lists}; {} resolve{}{}; {precision} arithmetic",
        if moving == 1 { "" } else { "s" },
        if near == 1 { "" } else { "s" },
        scene.triangles.len() - moving,
        if p.transparency {
            "transparent"
        } else {
            "opaque"
        },
        if p.intersection {
            ", intersection handling"
        } else {
            ""
        },
        if p.textures { ", textured" } else { "" },
    )
}

/// Stores `stats` as the renderer's last statistics.
pub(crate) fn remember(last: &Mutex<Option<IntervalStats>>, stats: Option<IntervalStats>) {
    if let Ok(mut l) = last.lock() {
        *l = stats;
    }
}

impl crate::method::Renderer for AnalyticRenderer {
    fn name(&self) -> &'static str {
        "analytic"
    }

    fn describe(&self, scene: &PreparedScene, p: &Pipeline) -> String {
        let lists = if self.options.intervals == 0 {
            "exact interval lists".to_string()
        } else {
            format!("at most {} intervals per pixel", self.options.intervals)
        };
        describe_sweep(
            "analytic",
            "edge-eqn",
            &lists,
            (scene, p),
            (self.options.precision, !self.options.keep_backfaces),
        )
    }

    fn render(
        &self,
        scene: &PreparedScene,
        pipeline: &Pipeline,
        progress: &dyn Progress,
    ) -> Result<Image> {
        let (image, stats) = render_stats(scene, pipeline, &self.options, progress)?;
        remember(&self.last, stats);
        Ok(image)
    }

    fn statistics(&self) -> Option<String> {
        self.last_stats().map(|s| s.to_string())
    }
}

/// [`settings_of`] in f32 (the default precision; used by tools that inspect single pixels).
#[allow(dead_code)]
pub(crate) fn settings(scene: &PreparedScene, pipeline: &Pipeline) -> Result<Settings<f32>> {
    settings_of(scene, pipeline)
}

/// [`texture_fn_of`] in f32.
#[allow(dead_code)]
pub(crate) fn texture_fn(scene: &PreparedScene) -> impl Fn(u32, [f32; 2]) -> Rgba<f32> + Sync {
    texture_fn_of::<f32>(scene)
}

/// [`flat_payloads_of`] in f32.
#[allow(dead_code)]
pub(crate) fn flat_payloads(scene: &PreparedScene) -> FlatPayload<f32> {
    flat_payloads_of(scene)
}

/// [`tex_payloads_of`] in f32.
#[allow(dead_code)]
pub(crate) fn tex_payloads(scene: &PreparedScene) -> TexPayload<f32> {
    tex_payloads_of(scene)
}
