//! # bilinear-patch
//!
//! Ray vs bilinear patch, watertight ray vs triangle, and the space-time prism of a moving
//! triangle, whose hits sorted by time and paired give the time spans during which the
//! triangle covers a pixel centre. This implements Rønnow, Assarsson, Sintorn and
//! Fratarcangeli 2021, "Fast Analytical Motion Blur with Transparency", §3-§4.1 (the prism of
//! Fig. 3, the up to eight hits paired into intervals of Fig. 5, the interval contents of
//! Fig. 6). The ray/patch test follows the geometry of Reshetov 2019, "Cool Patches: A
//! Geometric Approach to Ray/Bilinear Patch Intersections" (Ray Tracing Gems, ch. 8): a
//! quadratic in u for the distance from the ray to the u-isolines, then v and t. The
//! triangle test is the watertight test of Woop, Benthin and Wald 2013.
//!
//! Entry points: [`Patch::new`]`([q00, q10, q11, q01])` and [`Patch::intersect`]`(origin,
//! dir, t_min, t_max) -> `[`Hits`] (up to two [`Hit`]`{ t, u, v }` sorted by t);
//! [`PreparedPatch`] (corners laid out by axis, as a BVH leaf would store them) with
//! [`PreparedPatch::intersect_ray`] for a [`Ray`] prepared once and shared by every face it
//! meets (same hits, bit for bit); [`FastPatch`] (the non-watertight counterpart of
//! Möller-Trumbore, faster, but rays through shared edges may leak or double-hit):
//! [`FastPatch::intersect_ray`] solves Reshetov's quadratic in the space of a shared
//! prepared [`Ray`], [`FastPatch::intersect`] does the same for a one-off (origin,
//! direction) and [`FastPatch::intersect_world`] is Reshetov's original world-space test;
//! [`Triangle::intersect`] (watertight) and
//! [`moller_trumbore`] / [`MollerTrumbore`] (the non-watertight baseline, raw and with
//! stored edges);
//! [`Prism::new`] / [`Prism::from_homogeneous`], [`Prism::hits`] and [`Prism::coverage`]
//! (up to four [`Span`]s with time, depth and barycentrics at both ends). All numeric code
//! is generic over [`num_traits::Float`]; f32 vs f64 is the accuracy knob.
//!
//! ```
//! use bilinear_patch::{Patch, Prism};
//!
//! // A saddle: z = u + v - 2uv over the unit square; a ray along the diagonal hits it twice.
//! let patch = Patch::<f64>::new([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0]]);
//! let hits = patch.intersect([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0], 0.0, f64::INFINITY);
//! assert_eq!(hits.len(), 2);
//! assert!(hits[0].t < hits[1].t && (hits[0].u - hits[0].v).abs() < 1e-12);
//!
//! // A triangle moving 10 px right; (x, y, depth) at shutter open and close.
//! let open: [[f64; 3]; 3] = [[0.0, 0.0, 1.0], [2.0, 0.0, 1.0], [0.0, 10.0, 1.0]];
//! let close = open.map(|[x, y, d]| [x + 10.0, y, d + 2.0]);
//! let cov = Prism::from_arrays(open, close).coverage(5.5, 0.5);
//! assert_eq!(cov.len(), 1); // covered while the slanted edge has passed and the left has not
//! assert!((cov[0].t0 - 0.36).abs() < 1e-12 && (cov[0].t1 - 0.55).abs() < 1e-12);
//! ```
//!
//! ## Watertightness
//!
//! Every face tested against one [`Ray`] is first moved into the same ray space (Woop et al.
//! 2013), where a face's boundary decisions are signs of 2D edge functions of its edges.
//! Those signs are computed exactly (a floating-point filter, then Kahan's FMA difference of
//! products), so faces sharing an edge decide identically; an exact zero (the ray through an
//! edge or vertex) is broken by Simulation of Simplicity, as if the ray were moved by
//! (ε, ε²). The patch test keeps its boundary decisions in that form: the parity of the
//! number of u-roots in [0, 1] follows from the exact signs of the u = 0 and u = 1 edge
//! functions, and decisions within √ε of v = 0 or v = 1 from the exact signs of the v = 0
//! and v = 1 edge functions, through the identities cross(q00', q10') = v · cross(q10' -
//! q00', B(u)) and cross(q01', q11') = (v - 1) · cross(q11' - q01', B(u)) that hold at a hit
//! (q' the ray-space corners, B(u) the rung from (u, 0) to (u, 1)). So a ray through a
//! shared edge or corner of adjacent patches and triangles is counted exactly once when it
//! crosses the surface there, and zero or two times when it only touches it. The symbolic
//! tie-break cannot resolve a few doubly degenerate configurations (a pixel centre exactly
//! on a vertex that does not move, or touched tangentially in time by an edge exactly at
//! t = 0 or 1); [`Prism::coverage`] detects them by an odd hit count and recasts from a
//! centre moved by a few ulps.
//!
//! ## Why the prism is built in (x, y, t)
//!
//! Rønnow et al. build the prism in clip space and cast the pixel's ray along z, carrying
//! time as an interpolated surface attribute. Here the prism is built in screen space and
//! time: caps at t = 0 and t = 1, sides swept by the edges with the patch parameter v equal
//! to the time. The ray of a pixel centre (px, py) is the line {(px, py, t)}: its parameter
//! *is* the time, the horizontal slice of the prism at t is exactly the triangle at time t,
//! and the entry/exit hits alternate in time order by construction, so pairing sorted hits
//! gives exactly the set of times the centre is inside the triangle; the crossing time of a
//! side is read directly from the patch parameter, not interpolated. Depth and the
//! triangle's barycentrics are carried as attributes and interpolated linearly along each
//! vertex path, as Rønnow et al. do (§3, §5.1).
//!
//! ## What it approximates
//!
//! The renderer's vertices move linearly in 2DH, (x, y, w)(t) = (1 - t) q + t r, so the
//! projected position (x / w, y / w) is a rational function of t; edge-eqn's time-dependent
//! edge functions (Gribel et al. 2010, Eq. 3-7) are exact for that motion. The prism instead
//! moves the projected vertices linearly from their positions at open to those at close. The
//! two agree exactly when w is constant over the shutter (pure screen-space motion, and in
//! particular every orthographic camera); when w changes, the prism's vertex paths are the
//! chords of the true projected paths and the coverage times are off by up to the time the
//! true path needs to cross the gap between path and chord. Rønnow et al. accept the same
//! linearisation (§5.1).
#![forbid(unsafe_code)]

mod fast;
mod orient;
mod patch;
mod prepared;
mod prism;
mod ray;
mod triangle;

pub use fast::FastPatch;
pub use patch::{Hit, Hits, Patch};
pub use prepared::PreparedPatch;
pub use prism::{Coverage, Face, Prism, PrismHit, PrismHits, ScreenVertex, Span};
pub use ray::Ray;
pub use triangle::{MollerTrumbore, Triangle, TriangleHit, moller_trumbore};

/// Corner sets shared by the unit tests beside the code.
#[cfg(test)]
pub(crate) mod fixtures {
    /// The unit square in z = 0, a planar parallelogram (q_n = 0).
    pub(crate) const UNIT_SQUARE: [[f64; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    /// z = u + v - 2 u v: the ray (-0.1, -0.1, 0.3) + t (1, 1, 0) crosses it twice.
    pub(crate) const SADDLE: [[f64; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
    ];
    /// The corners in f32.
    pub(crate) fn f32(c: [[f64; 3]; 4]) -> [[f32; 3]; 4] {
        c.map(|p| p.map(|x| x as f32))
    }
    /// A seeded generator of values uniform in [-1, 1) (a 64-bit LCG, top 53 bits).
    pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed;
        move || {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }
    /// The 2D cross product a.x b.y - a.y b.x.
    pub(crate) fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
        a[0] * b[1] - a[1] * b[0]
    }
}
