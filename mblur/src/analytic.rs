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
//! Arithmetic is f32 (the edge-eqn default).

use glam::DVec2;
use interval_buffer::{
    BoundedBuffer, ExactBuffer, Insertion, Interval, IntervalCounts, Oracle, Payload, Rgba,
    Textured,
};
use rayon::prelude::*;
use resolve::{Flat, Settings, Shader, TapFilter};

use edge_eqn::{MovingTriangle, TriangleSetup};

use crate::accum::{self, AccumOptions};
use crate::effects::Pipeline;
use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepare::{PreparedScene, PreparedTriangle};
use crate::progress::Progress;
use crate::raster::{ScreenTriangle, Target, setup as raster_setup};

/// Rows per bin when distributing primitives over the image.
const BAND_ROWS: u32 = 8;

/// Pixels per exact-list segment: each run of up to this many pixels of one row gets its own
/// count / fill / sort (the exact strategy of Rønnow 2021 §4.1-4.2 per segment). Segmenting
/// works around `IntervalCounts::finish` in interval-buffer, whose overflow error value is
/// built eagerly (`ok_or(.. self.total() ..)`) and so costs O(pixels²) per call.
const SEGMENT: u32 = 256;

/// Number of shutter slices a moving triangle that touches the near plane is rasterised in.
pub const NEAR_SLICES: u32 = 64;

/// Texture taps per partition for textured payloads.
pub const TEXTURE_TAPS: usize = 8;

/// Textured moving spans are cut into pieces no longer than 1 / this of the shutter, each
/// with its own UVs at both ends: the resolve interpolates UV linearly over an interval
/// (Rønnow 2021 Fig. 6), while the true UV path at a pixel under rotation or perspective is
/// curved.
pub const TEXTURE_PIECES: u32 = 32;

/// Largest accepted `--intervals`.
pub const MAX_INTERVALS: u32 = 1024;

/// Options of the analytic method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AnalyticOptions {
    /// Intervals per pixel: 0 = exact unbounded lists (Rønnow 2021 §4.1-4.2), K > 0 = at
    /// most K per pixel with the paper's oracle compression (Gribel 2010 §5.2).
    pub intervals: u32,
}

/// The `analytic` renderer.
#[derive(Debug, Clone, Copy, Default)]
pub struct AnalyticRenderer {
    /// Its options.
    pub options: AnalyticOptions,
}

/// One primitive that leaves intervals in pixels.
#[derive(Debug, Clone)]
pub(crate) enum Prim {
    /// A static (or time-sliced) screen triangle covering time `[t0, t1]`.
    Fixed {
        st: Box<ScreenTriangle>,
        t0: f32,
        t1: f32,
    },
    /// A moving triangle swept exactly by edge-eqn over pixel bounds `x0..=x1`, `y0..=y1`.
    Moving {
        setup: Box<TriangleSetup<f32>>,
        tri: u32,
        x0: u32,
        x1: u32,
        y0: u32,
        y1: u32,
    },
    /// A moving triangle swept by ray-vs-prism intersection (bilinear-patch, Rønnow 2021
    /// §4.1) over pixel bounds `x0..=x1`, `y0..=y1`.
    Prism {
        prism: Box<bilinear_patch::Prism<f32>>,
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

impl Prim {
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
fn fixed_prims(
    scene: &PreparedScene,
    target: &Target,
    i: u32,
    (t, t0, t1): (f64, f32, f32),
    out: &mut Vec<Prim>,
) {
    let Some(tri) = scene.triangles.get(i as usize) else {
        return;
    };
    let mut sts = Vec::new();
    raster_setup(tri, t, i, scene.is_opaque(tri.material), target, &mut sts);
    out.extend(sts.into_iter().map(|st| Prim::Fixed {
        st: Box::new(st),
        t0,
        t1,
    }));
}

/// Builds the primitives of every triangle.
pub(crate) fn build_prims(scene: &PreparedScene, sweep: Sweep) -> Vec<Prim> {
    let target = Target {
        width: scene.width,
        height: scene.height,
        near: scene.near,
    };
    (0..scene.triangles.len() as u32)
        .into_par_iter()
        .fold(Vec::new, |mut out, i| {
            let tri = &scene.triangles[i as usize];
            if !tri.is_moving() {
                fixed_prims(scene, &target, i, (0.0, 0.0, 1.0), &mut out);
            } else if in_front(tri, scene.near) {
                let v = |a: &[crate::camera::Vertex2dh; 3]| {
                    a.map(|p| [p.x as f32, p.y as f32, p.w as f32])
                };
                let z = |a: &[crate::camera::Vertex2dh; 3]| a.map(|p| p.depth as f32);
                let setup = MovingTriangle::new(v(&tri.open), v(&tri.close))
                    .with_depth(z(&tri.open), z(&tri.close))
                    .setup();
                let pts = tri.open.iter().chain(&tri.close).map(|p| {
                    let (x, y) = p.screen();
                    DVec2::new(x, y)
                });
                let (lo, hi) = pts.fold(
                    (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                    |(lo, hi), p| (lo.min(p), hi.max(p)),
                );
                if setup.is_valid()
                    && lo.is_finite()
                    && hi.is_finite()
                    && let Some((x0, x1, y0, y1)) = pixel_bounds(lo, hi, scene.width, scene.height)
                {
                    match sweep {
                        Sweep::EdgeEqn => out.push(Prim::Moving {
                            setup: Box::new(setup),
                            tri: i,
                            x0,
                            x1,
                            y0,
                            y1,
                        }),
                        Sweep::Prism => {
                            let sv = |a: &[crate::camera::Vertex2dh; 3]| {
                                a.map(|p| {
                                    let (x, y) = p.screen();
                                    bilinear_patch::ScreenVertex {
                                        x: x as f32,
                                        y: y as f32,
                                        depth: p.depth as f32,
                                    }
                                })
                            };
                            let prism = bilinear_patch::Prism::new(sv(&tri.open), sv(&tri.close));
                            out.push(Prim::Prism {
                                prism: Box::new(prism),
                                tri: i,
                                x0,
                                x1,
                                y0,
                                y1,
                            });
                        }
                    }
                }
            } else {
                let n = NEAR_SLICES;
                for k in 0..n {
                    let (a, b) = (f64::from(k) / f64::from(n), f64::from(k + 1) / f64::from(n));
                    fixed_prims(
                        scene,
                        &target,
                        i,
                        (0.5 * (a + b), a as f32, b as f32),
                        &mut out,
                    );
                }
            }
            out
        })
        .reduce(Vec::new, |mut a, mut b| {
            a.append(&mut b);
            a
        })
}

/// Primitive indices per band of [`BAND_ROWS`] rows.
pub(crate) fn bin(prims: &[Prim], height: u32) -> Vec<Vec<u32>> {
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
pub(crate) trait MakePayload: Sync {
    /// The payload type.
    type P: Payload<f32> + Copy + Default + Send + Sync;
    /// Moving spans are cut into pieces no longer than `1 / max_pieces` of the shutter
    /// (textured payloads: the UV path at a pixel is curved, the payload's UV is linear).
    fn max_pieces(&self, material: u32) -> u32 {
        let _ = material;
        1
    }
    fn make(&self, material: u32, uv0: DVec2, uv1: DVec2) -> Self::P;
}

/// Flat payloads: the material's straight-alpha colour.
pub(crate) struct FlatPayload(pub Vec<Rgba<f32>>);

impl MakePayload for FlatPayload {
    type P = Rgba<f32>;
    fn make(&self, material: u32, _: DVec2, _: DVec2) -> Rgba<f32> {
        self.0.get(material as usize).copied().unwrap_or_default()
    }
}

/// Textured payloads: UVs at the ends and the material's alpha; per material whether it
/// has a texture (only those spans are cut into pieces).
pub(crate) struct TexPayload(pub Vec<f32>, pub Vec<bool>);

impl MakePayload for TexPayload {
    type P = Textured<f32>;
    fn max_pieces(&self, material: u32) -> u32 {
        if self.1.get(material as usize).copied().unwrap_or(false) {
            TEXTURE_PIECES
        } else {
            1
        }
    }
    fn make(&self, material: u32, uv0: DVec2, uv1: DVec2) -> Textured<f32> {
        Textured {
            uv_start: [uv0.x as f32, uv0.y as f32],
            uv_end: [uv1.x as f32, uv1.y as f32],
            material,
            normal: [0.0; 3],
            alpha: self.0.get(material as usize).copied().unwrap_or(0.0),
        }
    }
}

/// Straight-alpha colour from premultiplied `p`, alpha divided by `material_alpha`.
fn straight(p: [f64; 4], material_alpha: f64) -> Rgba<f32> {
    if p[3] <= 0.0 || material_alpha <= 0.0 {
        return Rgba::default();
    }
    let a = p[3];
    Rgba::new(
        (p[0] / a) as f32,
        (p[1] / a) as f32,
        (p[2] / a) as f32,
        ((a / material_alpha).min(1.0)) as f32,
    )
}

/// Calls `f(x, iv)` for every interval primitive `prim` leaves in row `y`.
pub(crate) fn emit<M: MakePayload>(
    scene: &PreparedScene,
    prim: &Prim,
    (y, xs, xe): (u32, u32, u32),
    mk: &M,
    mut f: impl FnMut(usize, Interval<f32, M::P>) -> Result<()>,
) -> Result<()> {
    let far = scene.far as f32;
    match prim {
        Prim::Fixed { st, t0, t1 } => {
            let mut res = Ok(());
            st.rasterise(y, y + 1, |x, _, frag| {
                if res.is_err() || frag.depth > scene.far || x < xs || x >= xe {
                    return;
                }
                let p = mk.make(st.material, frag.uv, frag.uv);
                res = f(
                    x as usize,
                    Interval::new(*t0, *t1, frag.depth as f32, 0.0, p),
                );
            });
            res
        }
        Prim::Moving {
            setup,
            tri,
            x0,
            x1,
            y0,
            y1,
        } => {
            if y < *y0 || y > *y1 {
                return Ok(());
            }
            let Some(t) = scene.triangles.get(*tri as usize) else {
                return Ok(());
            };
            let sy = y as f32 + 0.5;
            let pieces = mk.max_pieces(t.material).max(1) as f32;
            for x in (*x0).max(xs)..=(*x1).min(xe.saturating_sub(1)) {
                let s = setup.sample(x as f32 + 0.5, sy);
                for whole in s.coverage().iter() {
                    if whole.t1.partial_cmp(&whole.t0).is_none_or(|o| o.is_lt()) {
                        continue;
                    }
                    let n = ((whole.len() * pieces).ceil() as u32).max(1);
                    for j in 0..n {
                        let a = whole.t0 + whole.len() * (j as f32 / n as f32);
                        let b = if j + 1 == n {
                            whole.t1
                        } else {
                            whole.t0 + whole.len() * ((j + 1) as f32 / n as f32)
                        };
                        let span = &edge_eqn::Span::new(a, b.max(a));
                        let d = s.linear_depth(*span);
                        let (z, k) = (d.z, d.k);
                        if !(z.is_finite() && k.is_finite()) || (z > far && d.z_end() > far) {
                            continue;
                        }
                        let uv = |tt: f32| {
                            let b = s.barycentrics(tt);
                            t.uv[0] * f64::from(b[0])
                                + t.uv[1] * f64::from(b[1])
                                + t.uv[2] * f64::from(b[2])
                        };
                        let p = mk.make(t.material, uv(span.t0), uv(span.t1));
                        f(x as usize, Interval::new(span.t0, span.t1, z, k, p))?;
                    }
                }
            }
            Ok(())
        }
        Prim::Prism {
            prism,
            tri,
            x0,
            x1,
            y0,
            y1,
        } => {
            if y < *y0 || y > *y1 {
                return Ok(());
            }
            let Some(t) = scene.triangles.get(*tri as usize) else {
                return Ok(());
            };
            let sy = y as f32 + 0.5;
            let uv = |b: [f32; 2]| {
                let (b1, b2) = (f64::from(b[0]), f64::from(b[1]));
                t.uv[0] * (1.0 - b1 - b2) + t.uv[1] * b1 + t.uv[2] * b2
            };
            for x in (*x0).max(xs)..=(*x1).min(xe.saturating_sub(1)) {
                for span in prism.coverage(x as f32 + 0.5, sy).iter() {
                    let len = span.t1 - span.t0;
                    let k = if len > 0.0 {
                        (span.depth1 - span.depth0) / len
                    } else {
                        0.0
                    };
                    let ok = len >= 0.0 && span.depth0.is_finite() && k.is_finite();
                    if !ok || (span.depth0 > far && span.depth1 > far) {
                        continue;
                    }
                    let n = ((len * mk.max_pieces(t.material).max(1) as f32).ceil() as u32).max(1);
                    if n == 1 {
                        let p = mk.make(t.material, uv(span.uv0), uv(span.uv1));
                        f(
                            x as usize,
                            Interval::new(span.t0, span.t1, span.depth0, k, p),
                        )?;
                        continue;
                    }
                    // Textured: pieces with their own UV and depth at the ends, from the
                    // screen-space barycentrics of the triangle at that time (the prism's
                    // own model of the motion).
                    let (px, py) = (x as f32 + 0.5, sy);
                    let at = |tt: f32| -> ([f32; 2], f32) {
                        let v = prism.at(tt);
                        let (ax, ay) = (v[1].x - v[0].x, v[1].y - v[0].y);
                        let (bx, by) = (v[2].x - v[0].x, v[2].y - v[0].y);
                        let (cx, cy) = (px - v[0].x, py - v[0].y);
                        let d = ax * by - ay * bx;
                        let (b1, b2) = ((cx * by - cy * bx) / d, (ax * cy - ay * cx) / d);
                        let z = (1.0 - b1 - b2) * v[0].depth + b1 * v[1].depth + b2 * v[2].depth;
                        if b1.is_finite() && b2.is_finite() && z.is_finite() {
                            ([b1, b2], z)
                        } else {
                            let s = (tt - span.t0) / len;
                            let l = |a: f32, b: f32| a + (b - a) * s;
                            (
                                [l(span.uv0[0], span.uv1[0]), l(span.uv0[1], span.uv1[1])],
                                l(span.depth0, span.depth1),
                            )
                        }
                    };
                    let mut prev = (span.t0, span.uv0, span.depth0);
                    for j in 1..=n {
                        let (tb, bb, zb) = if j == n {
                            (span.t1, span.uv1, span.depth1)
                        } else {
                            let tb = span.t0 + len * (j as f32 / n as f32);
                            let (bb, zb) = at(tb);
                            (tb, bb, zb)
                        };
                        let (ta, ba, za) = prev;
                        let kk = if tb > ta { (zb - za) / (tb - ta) } else { 0.0 };
                        let kk = if kk.is_finite() { kk } else { 0.0 };
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

/// Exact unbounded lists: count pass, scan, fill pass, per-pixel sort.
pub(crate) fn exact_lists<M: MakePayload>(
    scene: &PreparedScene,
    prims: &[Prim],
    bins: &[Vec<u32>],
    mk: &M,
) -> Result<Vec<ExactBuffer<f32, M::P>>> {
    let w = scene.width;
    let segments = w.div_ceil(SEGMENT);
    (0..scene.height * segments)
        .into_par_iter()
        .map(|s| {
            let (y, xs) = (s / segments, (s % segments) * SEGMENT);
            let xe = (xs + SEGMENT).min(w);
            let band = bins
                .get((y / BAND_ROWS) as usize)
                .map_or(&[][..], |b| b.as_slice());
            let n = (xe - xs) as usize;
            let mut counts = IntervalCounts::new(n, 1).map_err(buffer_error)?;
            for &i in band {
                emit(scene, &prims[i as usize], (y, xs, xe), mk, |x, _| {
                    counts.count(x - xs as usize).map_err(buffer_error)
                })?;
            }
            let mut fill = counts.finish::<f32, M::P>().map_err(buffer_error)?;
            for &i in band {
                emit(scene, &prims[i as usize], (y, xs, xe), mk, |x, iv| {
                    fill.push(x - xs as usize, iv).map_err(buffer_error)
                })?;
            }
            fill.finish().map_err(buffer_error)
        })
        .collect()
}

/// Bounded buffer with K intervals per pixel and the paper's oracle.
fn bounded<M: MakePayload>(
    scene: &PreparedScene,
    prims: &[Prim],
    bins: &[Vec<u32>],
    mk: &M,
    k: u32,
    opaque: bool,
) -> Result<BoundedBuffer<f32, M::P>> {
    let (w, h) = (scene.width as usize, scene.height as usize);
    let band = |y: usize| {
        bins.get(y / BAND_ROWS as usize)
            .map_or(&[][..], |b| b.as_slice())
    };
    let mut buf = BoundedBuffer::new(
        w,
        h,
        k as usize,
        Insertion {
            oracle: Oracle::paper_for(opaque),
            opaque,
        },
    )
    .map_err(buffer_error)?;
    buf.par_rows_mut().try_for_each(|mut row| {
        let y = row.y();
        for &i in band(y) {
            emit(
                scene,
                &prims[i as usize],
                (y as u32, 0, scene.width),
                mk,
                |x, iv| row.insert(x, iv).map(|_| ()).map_err(buffer_error),
            )?;
        }
        Ok::<(), Error>(())
    })?;
    Ok(buf)
}

/// Resolve settings for the scene and pipeline (Gribel 2010 §5.1, Eq. 17).
pub(crate) fn settings(scene: &PreparedScene, pipeline: &Pipeline) -> Result<Settings<f32>> {
    let base = if pipeline.transparency {
        Settings::transparent()
    } else {
        Settings::opaque()
    };
    let points: Vec<(f32, f32)> = scene
        .shutter
        .points
        .iter()
        .map(|&(t, w)| (t as f32, w as f32))
        .collect();
    let shutter =
        resolve::Shutter::from_points(&points).map_err(|e| Error::MethodNotApplicable {
            method: "analytic".into(),
            reason: format!("shutter response: {e}"),
        })?;
    let [r, g, b] = scene.background.map(|c| c as f32);
    Ok(base
        .with_intersections(pipeline.intersection)
        .with_shutter(shutter)
        .with_background(Rgba::opaque(r, g, b)))
}

/// Resolves a frame from per-pixel lists into an image.
pub(crate) fn resolve_image<'a, P: Sync + 'a, S: Shader<f32, P> + Sync>(
    scene: &PreparedScene,
    pixel: impl Fn(usize) -> &'a [Interval<f32, P>] + Sync,
    shader: &S,
    settings: &Settings<f32>,
) -> Result<Image> {
    let (w, h) = (scene.width as usize, scene.height as usize);
    let mut out = vec![Rgba::default(); w * h];
    resolve::resolve_frame(w, h, pixel, shader, settings, &mut out).map_err(|e| {
        Error::MethodNotApplicable {
            method: "analytic".into(),
            reason: format!("resolve: {e}"),
        }
    })?;
    Ok(Image {
        width: scene.width,
        height: scene.height,
        pixels: out
            .iter()
            .map(|c| [c.r, c.g, c.b].map(|v| if v.is_finite() { v } else { 0.0 }))
            .collect(),
    })
}

/// The texture lookup handed to the resolve: [`PreparedScene::shade`] as straight alpha,
/// divided by the material alpha the payload already carries.
pub(crate) fn texture_fn(scene: &PreparedScene) -> impl Fn(u32, [f32; 2]) -> Rgba<f32> + Sync {
    move |m: u32, uv: [f32; 2]| {
        let a = scene.materials.get(m as usize).map_or(0.0, |m| m.color[3]);
        straight(
            scene.shade(m, DVec2::new(f64::from(uv[0]), f64::from(uv[1]))),
            a,
        )
    }
}

fn run<M: MakePayload, S: Shader<f32, M::P> + Sync>(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    (k, sweep): (u32, Sweep),
    mk: &M,
    shader: &S,
) -> Result<Image> {
    let prims = build_prims(scene, sweep);
    let bins = bin(&prims, scene.height);
    let settings = settings(scene, pipeline)?;
    if k == 0 {
        let segs = exact_lists(scene, &prims, &bins, mk)?;
        let w = scene.width as usize;
        let per_row = w.div_ceil(SEGMENT as usize);
        let seg = SEGMENT as usize;
        resolve_image(
            scene,
            |i| {
                let (y, x) = (i / w, i % w);
                segs.get(y * per_row + x / seg)
                    .map_or(&[][..], |b| b.pixel_index(x % seg))
            },
            shader,
            &settings,
        )
    } else {
        let buf = bounded(scene, &prims, &bins, mk, k, !pipeline.transparency)?;
        resolve_image(scene, |i| buf.pixel_index(i), shader, &settings)
    }
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
pub(crate) fn flat_payloads(scene: &PreparedScene) -> FlatPayload {
    FlatPayload(
        scene
            .materials
            .iter()
            .map(|m| {
                let c = m.color.map(|v| v as f32);
                Rgba::new(c[0], c[1], c[2], c[3].clamp(0.0, 1.0))
            })
            .collect(),
    )
}

/// Material alphas for textured payloads.
pub(crate) fn tex_payloads(scene: &PreparedScene) -> TexPayload {
    TexPayload(
        scene
            .materials
            .iter()
            .map(|m| m.color[3].clamp(0.0, 1.0) as f32)
            .collect(),
        scene
            .materials
            .iter()
            .map(|m| m.texture.is_some())
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
        (options.intervals, Sweep::EdgeEqn),
        progress,
    )
}

/// The shared interval pipeline: primitives -> interval buffer (exact when `k == 0`) ->
/// resolve; a fully static opaque scene takes the static path with no interval storage.
pub(crate) fn render_sweep(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    (k, sweep): (u32, Sweep),
    progress: &dyn Progress,
) -> Result<Image> {
    if !pipeline.interval_storage {
        // A fully static opaque scene: exactly the static path, no interval storage.
        return accum::render(
            scene,
            &AccumOptions {
                times: Some(1),
                jitter: None,
            },
            progress,
        );
    }
    progress.start(1);
    let image = if pipeline.textures {
        let tex = texture_fn(scene);
        run(
            scene,
            pipeline,
            (k, sweep),
            &tex_payloads(scene),
            &TapFilter::new(&tex, TEXTURE_TAPS),
        )
    } else {
        run(scene, pipeline, (k, sweep), &flat_payloads(scene), &Flat)
    }?;
    progress.advance(1);
    progress.finish();
    Ok(image)
}

/// The `describe` line shared by the interval methods (`analytic`, `prism`): what goes
/// through the motion path (`via`), the near-plane slicing, the static path, the buffer
/// (`lists`) and the resolve the pipeline enables.
pub(crate) fn describe_sweep(
    method: &str,
    via: &str,
    lists: &str,
    scene: &PreparedScene,
    p: &Pipeline,
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
    format!(
        "{method}: {moving} moving triangle{} via {via} ({near} near-plane crossing{} in {NEAR_SLICES} slices), {} static via the static rasteriser; {lists}; {} resolve{}{}",
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
        describe_sweep("analytic", "edge-eqn", &lists, scene, p)
    }

    fn render(
        &self,
        scene: &PreparedScene,
        pipeline: &Pipeline,
        progress: &dyn Progress,
    ) -> Result<Image> {
        render(scene, pipeline, &self.options, progress)
    }
}
