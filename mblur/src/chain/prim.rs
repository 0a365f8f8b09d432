//! The chain's primitives: what each triangle of the scene becomes before it leaves
//! intervals in pixels.
//!
//! - A static triangle (no motion in 2DH) is set up once by the static rasteriser
//!   ([`crate::static_path::raster`], near-plane clipping) and covers its pixels over its
//!   whole time span: one interval `[t0, t1]` (`[0, 1]` unless it is a segment of a curved
//!   path) of constant depth (`Prim::Fixed`).
//! - Moving triangles are swept in time local to their span; a segment of a curved path
//!   ([`crate::motion`]) has its intervals' times mapped into its span, so one pixel's list
//!   holds the intervals of every segment.
//! - A moving triangle whose six corners all lie in front of the near plane
//!   (`crate::corners::in_front`) is swept exactly over the pixels of the convex hull of
//!   its six projected corners ([`raster_hier::SweptHull`], row by row): with edge-eqn
//!   (`Prim::Moving`, Gribel 2010 Eq. 3-9) or as a space-time prism with bilinear-patch
//!   (`Prim::Prism`, Rønnow 2021 §3-4.1), in coordinates local to a block of pixels
//!   ([`ORIGIN_BLOCK`]).
//! - A moving triangle touching or crossing the near plane cannot be swept (edge-eqn
//!   reports crossings behind the eye and does not clip): the shutter is cut into
//!   [`NEAR_SLICES`] equal slices, each rasterised by the static rasteriser (with clipping)
//!   at its midpoint into intervals spanning the slice — accum-style, exact in the limit of
//!   many slices, and only for those triangles.

use glam::DVec2;
use raster_hier::{HullRows, SweptHull};
use rayon::prelude::*;

use edge_eqn::{MovingTriangle, TriangleSetup};

use super::{Real, cf};
use crate::bands::Bins;
use crate::camera::Vertex2dh;
use crate::corners::{in_front, xyw};
use crate::cull::{Culling, Motion};
use crate::prepared::{PreparedScene, PreparedTriangle};
use crate::static_path::{PixelBounds, ScreenTriangle, Target, pixel_bounds, setup};

/// Number of shutter slices a moving triangle that touches the near plane is rasterised in.
pub const NEAR_SLICES: u32 = 64;

/// Side of the blocks whose corners are the origins of moving primitives' local
/// coordinates (`local_centre`).
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
pub const ORIGIN_BLOCK: u32 = 16;

/// The centre of the pixel `offset` pixels right of (or below) the origin of a moving
/// primitive, in its local coordinates: `offset + 0.5`, exact in f32 below 2^23 pixels.
///
/// Moving primitives keep their 2DH vertices relative to the corner of the
/// [`ORIGIN_BLOCK`]-pixel block holding the corner of their bounds. Edge functions are
/// products of coordinates, so in absolute coordinates f32 loses precision in proportion
/// to the position in the image: on clothball-ronnow at 512x512 a silhouette edge grazing a
/// pixel centre (a tangent root pair of Gribel 2010, Eq. 7) covered it for 0.035 of the
/// shutter too long. The shift is exact algebra (a translation with determinant 1 leaves
/// the edge functions, barycentrics and depth at the shifted sample unchanged); only the
/// rounding improves.
#[inline]
pub(crate) fn local_centre<F: Real>(offset: u32) -> F {
    cf(f64::from(offset) + 0.5)
}

/// Which exact sweep moving triangles in front of the near plane take.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Sweep {
    /// edge-eqn (Gribel 2010): exact in 2DH, rational depth fitted linearly per span.
    EdgeEqn,
    /// bilinear-patch prism (Rønnow 2021): screen-space vertices moving linearly.
    Prism,
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
    /// A moving triangle swept exactly by edge-eqn.
    Moving {
        setup: Box<TriangleSetup<F>>,
        swept: Swept,
    },
    /// A moving triangle swept by ray-vs-prism intersection (bilinear-patch, Rønnow 2021
    /// §4.1).
    Prism {
        prism: Box<bilinear_patch::Prism<F>>,
        swept: Swept,
    },
}

/// Where a swept primitive is evaluated: pixel bounds, row by row inside its hull.
#[derive(Debug, Clone)]
pub(crate) struct Swept {
    /// The pixel whose corner is the origin of the primitive's coordinates
    /// (`local_centre`).
    pub origin: [u32; 2],
    /// The convex hull of the six projected corners, set up for row queries.
    pub hull: Box<HullRows>,
    /// Index of the triangle in [`PreparedScene::triangles`].
    pub tri: u32,
    /// The pixel centres inside the bounding box of the six projected corners.
    pub bounds: PixelBounds,
    /// The triangle's time span ([`PreparedTriangle::span`]): the sweep runs in local
    /// time u ∈ \[0, 1\], emitted intervals are mapped to `t0 + u (t1 - t0)`.
    pub span: [f64; 2],
    /// The times in local u at which the triangle may face the eye, when back-face
    /// culling clips it to part of its span ([`crate::cull`]): coverage intervals are
    /// clipped to them before they get depth and payload. `None`: the whole span.
    pub facing: Option<Box<[[f64; 2]]>>,
}

impl<F> Prim<F> {
    /// The first and last image row it may leave intervals in.
    pub(crate) fn rows(&self) -> (u32, u32) {
        match self {
            Prim::Fixed { st, .. } => (st.y0, st.y1),
            Prim::Moving { swept, .. } | Prim::Prism { swept, .. } => {
                (swept.bounds.y0, swept.bounds.y1)
            }
        }
    }

    /// Index of the triangle it comes from.
    pub(crate) fn triangle(&self) -> u32 {
        match self {
            Prim::Fixed { st, .. } => st.order,
            Prim::Moving { swept, .. } | Prim::Prism { swept, .. } => swept.tri,
        }
    }
}

/// The primitives of every triangle of a scene.
pub(crate) struct Primitives<F> {
    /// In triangle order (a triangle's slices in time order).
    pub prims: Vec<Prim<F>>,
    /// Triangles removed by back-face culling (turned away during their whole span).
    pub culled: u64,
    /// Triangles whose intervals back-face culling clips to part of their span.
    pub clipped: u64,
}

impl<F: Real> Primitives<F> {
    /// Builds the primitives of every triangle of `scene`, moving ones in front of the near
    /// plane swept by `sweep`, culling (`cull`) or keeping the back faces of opaque closed
    /// meshes ([`crate::cull`]): a triangle turned away during its whole span has no
    /// primitive, one turned away during part of it keeps its facing windows.
    pub(crate) fn build(scene: &PreparedScene, sweep: Sweep, cull: bool) -> Self {
        let target = Target::of(scene);
        let culling = cull.then(|| Culling::of(scene));
        let motion = match sweep {
            Sweep::EdgeEqn => Motion::Homogeneous,
            Sweep::Prism => Motion::Screen,
        };
        let (prims, culled, clipped) = (0..scene.triangles.len() as u32)
            .into_par_iter()
            .with_min_len(256)
            .fold(
                || (Vec::new(), 0, 0),
                |(mut out, culled, mut clipped), i| {
                    let tri = &scene.triangles[i as usize];
                    let windows = culling
                        .as_ref()
                        .map(|c| c.windows(scene, i as usize, motion));
                    let facing = match &windows {
                        Some(w) if w.is_empty() => return (out, culled + 1, clipped),
                        Some(w) if !w.is_all() => {
                            clipped += 1;
                            Some(Box::from(w.as_slice()))
                        }
                        _ => None,
                    };
                    if !tri.is_moving() {
                        let whole = Slice {
                            t: 0.0,
                            t0: tri.span[0],
                            t1: tri.span[1],
                        };
                        fixed_prims(scene, &target, i, whole, &mut out);
                    } else if in_front(tri, scene.near) {
                        out.extend(moving_prim(scene, tri, i, sweep, facing));
                    } else {
                        let n = NEAR_SLICES;
                        for k in 0..n {
                            let (a, b) =
                                (f64::from(k) / f64::from(n), f64::from(k + 1) / f64::from(n));
                            let slice = Slice {
                                t: 0.5 * (a + b),
                                t0: tri.global_time(a),
                                t1: tri.global_time(b),
                            };
                            fixed_prims(scene, &target, i, slice, &mut out);
                        }
                    }
                    (out, culled, clipped)
                },
            )
            .reduce(
                || (Vec::new(), 0, 0),
                |(mut a, ca, pa), (mut b, cb, pb)| {
                    a.append(&mut b);
                    (a, ca + cb, pa + pb)
                },
            );
        Primitives {
            prims,
            culled,
            clipped,
        }
    }

    /// The primitives' indices per band of `rows` image rows.
    pub(crate) fn bins(&self, height: u32, rows: u32) -> Bins {
        Bins::new(height, rows, self.prims.iter().map(Prim::rows))
    }
}

/// A static rasterisation of a triangle: placed at time `t` local to its span, covering
/// the shutter times `[t0, t1]`.
#[derive(Debug, Clone, Copy)]
struct Slice {
    t: f64,
    t0: f64,
    t1: f64,
}

/// Static rasteriser primitives for triangle `i` at `slice`.
fn fixed_prims<F: Real>(
    scene: &PreparedScene,
    target: &Target,
    i: u32,
    slice: Slice,
    out: &mut Vec<Prim<F>>,
) {
    let Some(tri) = scene.triangles.get(i as usize) else {
        debug_assert!(false, "triangle {i} out of range");
        return;
    };
    let mut sts = Vec::new();
    setup(
        tri,
        slice.t,
        i,
        scene.is_opaque(tri.material),
        target,
        &mut sts,
    );
    out.extend(sts.into_iter().map(|st| Prim::Fixed {
        st: Box::new(st),
        t0: cf(slice.t0),
        t1: cf(slice.t1),
    }));
}

/// The swept primitive of a moving triangle in front of the near plane, or `None` when it
/// misses the image or its setup is degenerate.
fn moving_prim<F: Real>(
    scene: &PreparedScene,
    tri: &PreparedTriangle,
    i: u32,
    sweep: Sweep,
    facing: Option<Box<[[f64; 2]]>>,
) -> Option<Prim<F>> {
    let z = |a: &[Vertex2dh; 3]| a.map(|p| cf::<F>(p.depth));
    let hull = SweptHull::project(&xyw(&tri.open), &xyw(&tri.close));
    let (lo, hi) = hull.points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(DVec2::from(p)), hi.max(DVec2::from(p))),
    );
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let bounds = pixel_bounds(lo, hi, scene.width, scene.height)?;
    // Local coordinates (see `local_centre`): the origin is the corner of the
    // ORIGIN_BLOCK-pixel block holding (x0, y0). The shift is done in f64 before rounding
    // to F, so f32 keeps its precision for the small offsets instead of spending it on the
    // position in the image.
    let origin = [bounds.x0, bounds.y0].map(|v| v - v % ORIGIN_BLOCK);
    let (ox, oy) = (f64::from(origin[0]), f64::from(origin[1]));
    let swept = Swept {
        origin,
        hull: Box::new(hull.rows()),
        tri: i,
        bounds,
        span: tri.span,
        facing,
    };
    match sweep {
        Sweep::EdgeEqn => {
            let v = |a: &[Vertex2dh; 3]| {
                a.map(|p| [cf::<F>(p.x - ox * p.w), cf(p.y - oy * p.w), cf(p.w)])
            };
            let setup = MovingTriangle::new(v(&tri.open), v(&tri.close))
                .with_depth(z(&tri.open), z(&tri.close))
                .setup();
            setup.is_valid().then(|| Prim::Moving {
                setup: Box::new(setup),
                swept,
            })
        }
        Sweep::Prism => {
            let sv = |a: &[Vertex2dh; 3]| {
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
                swept,
            })
        }
    }
}
