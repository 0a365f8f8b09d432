//! The non-watertight ray/patch test, [`FastPatch`]: Reshetov's quadratic in u (Reshetov
//! 2019, "Cool Patches", Ray Tracing Gems ch. 8) with the per-patch quantities precomputed
//! as a BVH leaf would store them. It is the like-for-like counterpart of Möller-Trumbore
//! with stored edges ([`crate::MollerTrumbore`]): no exact signs, no fallback paths. Two
//! algorithms (measured in `BENCHMARKS.md`):
//!
//! - [`FastPatch::intersect_ray`], for a [`Ray`] prepared once per ray (a BVH traversal):
//!   the quadratic solved in the ray's space, with an early exit in u and one in v, u and v
//!   from their own quadratics sharing one square root. [`FastPatch::intersect`] runs it
//!   for a one-off (origin, direction), `Ray::new` included. On the benchmark rays it
//!   takes 0.62x (f32) / 0.58x (f64) the time of the world-space algorithm with a shared
//!   ray, 0.86x / 0.76x with `Ray::new` per call.
//! - [`FastPatch::intersect_world`]: Reshetov's original world-space algorithm, which needs
//!   no prepared ray: the reference formulation, kept for comparison.
//!
//! Both hit the same points up to rounding; both cost more than two Möller-Trumbore tests
//! with stored edges (prepared, f32 / f64: `intersect_ray` 1.34x / 1.46x, `intersect_world`
//! 2.2x / 2.5x), which the issue's goal asked them not to exceed. For `intersect_ray` a miss
//! costs less than the pair (0.85x / 1.0x) and a hit more (1.65x / 1.75x). The transform, the
//! cross products and the two exits alone cost 0.85x the pair on the benchmark's rays, and
//! the rest of a hit costs more than the remaining 0.15x even without its square root and
//! divisions (1.16x with both taken out; `BENCHMARKS.md`, "Why the like-for-like pairing stays at
//! 1.34x").
//!
//! ## In the ray's space (own derivation)
//!
//! Write the patch in its bilinear basis,
//!
//! Q(u, v) = q00 + u e10 + v e00 + u v g, e10 = q10 - q00, e00 = q01 - q00,
//! g = q11 - q10 - q01 + q00,
//!
//! and move it into the space of the prepared [`Ray`] (Woop, Benthin and Wald 2013:
//! translate by the origin, permute the axes so that the direction's largest component is
//! z, shear): x' = a_x - s_x a_z, y' = a_y - s_y a_z, z' = s_z a_z for a = p - o. The map
//! is affine, so the patch stays bilinear, Q'(u, v) = p + u e + v f + u v g with
//! p = (q00 - o)' and e, f, g the mapped e10, e00, g (the vector f, not the function f(u)
//! below); only p pays the translation (about
//! 20 operations per ray in all). The ray is the z' axis, and z' of a point on it is its
//! ray parameter. So the ray meets the patch at (u, v) exactly when the 2D part vanishes,
//!
//! A(u) + v B(u) = 0, A(u) = p + u e, B(u) = f + u g (xy components),
//!
//! and then t = z' of Q'(u, v). For fixed u, A(u) + v B(u) runs along the projected rung
//! from Q(u, 0) to Q(u, 1); the origin lies on its line exactly when A(u) and B(u) are
//! parallel:
//!
//! f(u) = cross(A(u), B(u)) = k0 + k1 u + k2 u², k0 = cross(p, f),
//! k1 = cross(p, g) + cross(e, f), k2 = cross(e, g)
//!
//! (Reshetov's quadratic, the distance from the ray to the u-isoline, here in 2D; the same
//! f as the watertight test's cross(P(u, 0), P(u, 1)) in [`crate::Patch`], since
//! cross(A, A + B) = cross(A, B)). When f(0) = k0 and f(1) = k0 + k1 + k2 have one sign and
//! f is monotone on [0, 1] (its vertex -k1 / 2k2 outside, or k2 = 0) there is no root in
//! [0, 1]: a miss before the square root. The same holds in v, Q' = C(v) + u D(v) with
//! C = p + v f, D = e + v g: the v of a hit is a root of h(v) = cross(C(v), D(v)) =
//! m0 + m1 v + m2 v², m0 = cross(p, e), m1 = cross(p, g) - cross(e, f), m2 = cross(f, g)
//! (two cross products more; m1 reuses those of k1), and h without a root in [0, 1] is a
//! miss too. The two exits are independent short chains; on the benchmark rays (48 %
//! misses) they stop 47 % of the rays before the square root (the u exit alone 27 %).
//! The roots are taken in the stable form
//! u = 2k0 / q and u = q / 2k2 with q = -(k1 + sign(k1) √disc).
//!
//! **One square root for u and v.** f and h have the same discriminant:
//! k1² - m1² = 4 cross(p, g) cross(e, f), and k0 k2 - m0 m2 = cross(p, f) cross(e, g) -
//! cross(p, e) cross(f, g) = cross(p, g) cross(e, f) by the 2D identity
//! cross(a, b) cross(c, d) - cross(a, c) cross(b, d) + cross(a, d) cross(b, c) = 0, so
//! k1² - 4 k0 k2 = m1² - 4 m0 m2. The roots pair crosswise: the hit with
//! u₊ = (-k1 + √disc) / 2k2 has v₋ = (-m1 - √disc) / 2m2, and u₋ has v₊ (checked on random
//! input by the unit test `u_and_v_roots_share_the_discriminant_and_pair_crosswise`). So v
//! comes from h's stable roots, 2m0 / q_m (that is v with the sign of m1) or q_m / 2m2,
//! with q_m = -(m1 + sign(m1) √disc): the root u = 2k0 / q is u with the sign of k1, and its
//! v is 2m0 / q_m when k1 and m1 differ in sign, else q_m / 2m2. The two divisions are
//! independent (before, v = -A·B / |B|² at u waited for the division giving u); t =
//! z'(u, v) = p_z + u e_z + v (f_z + u g_z). The signs are taken by `copysign`, not by a
//! branch on them (random on random rays: half of them mispredicted).
//!
//! **The second root only when inside.** For a patch that is not strongly curved, q / 2k2
//! (or its v) lies far outside [0, 1]; whether n / d lies in [0, 1] is decided without
//! dividing (n d >= 0 and |n| <= |d|), and the second root is evaluated only then. The
//! first root is evaluated without branches and kept when u, v lie in [0, 1] and t in
//! [t_min, t_max].
//!
//! Per ray that reaches the square root: about 20 operations for the transform, 20 for
//! the coefficients of f and h, 16 for the two exits, 10 for the discriminant, one square
//! root, 10 for the selection of the roots, then about 12 operations and two independent
//! divisions (u and v) for the first root. Two Möller-Trumbore tests: about 60 operations
//! and two divisions.
//!
//! ## In world space (Reshetov's original)
//!
//! For fixed u the points Q(u, ·) form the rung from P(u) = q00 + u e10 to P(u) + R(u),
//! with e11 = q11 - q10 and R(u) = lerp(e00, e11, u). The ray o + t d meets the line of the
//! rung exactly when the two lines are coplanar:
//!
//! f(u) = det[P(u) - o, d, R(u)] = (P(u) - o) × d · R(u) = a + b u + c u²,
//!
//! with a = f(0) = (q00 - o) × d · e00, a + b + c = f(1) = (q10 - o) × d · e11, and
//! c = e10 × d · (e11 - e00) = d · ((e11 - e00) × e10) = d · q_n, because
//! e11 - e00 = -(q01 - q11) - e10, so (e11 - e00) × e10 = e10 × (q01 - q11) = q_n, Reshetov's
//! normal-like vector (zero for a parallelogram). The same early exit and stable roots as
//! above. For each root u in [0, 1], the ray and the rung's line are coplanar, and v is the
//! parameter of their crossing on the rung: with n = d × R(u),
//!
//! v |n|² = (n × (P(u) - o)) · d = n · ((P(u) - o) × d),
//!
//! where (P(u) - o) × d = lerp((q00 - o) × d, (q10 - o) × d, u) reuses the two cross
//! products of a and f(1). The hit is kept when 0 <= v |n|² <= |n|² (so the division is
//! paid only for a hit); t is the hit point Q(u, v) projected on the ray,
//! t = ((P(u) - o) · d + v R(u) · d) / (d · d), kept when t_min <= t <= t_max. It is one
//! long dependent chain: three cross products and three dot products, the square root, the
//! division for u, the rung's cross product and |n|², the divisions for v and t.
//!
//! ## What both give up against [`crate::Patch`] / [`crate::PreparedPatch`]
//!
//! - **Not watertight.** Boundary decisions are plain floating-point comparisons of u and v
//!   computed independently per patch, so a ray through an edge or corner shared by two
//!   patches may hit neither (a leak) or both (a double hit). On the random height-field
//!   grids the watertight test is checked on, about 10 % (world space) and 18 % (ray
//!   space) of rays through a shared edge or vertex leak and 24 % / 21 % are counted twice
//!   (`tests/properties.rs::fast_patch_leak_rate_on_shared_edges_is_measured`).
//! - **Less robust near tangency.** A discriminant that rounds below zero is a miss, so a
//!   ray grazing the surface may lose both hits of the (near-)double root, and close roots
//!   carry the square-root error (no refinement step, unlike the watertight test).
//! - **A narrower range of magnitudes.** In world space a, b, c are products of three
//!   coordinate differences and |n|² of four; in ray space k0, k1, k2 and |B|² are
//!   products of two. The discriminant (degree six, resp. four) is rescaled when it would
//!   underflow or overflow. So in f32 the coordinates (patch size, ray direction, distance
//!   to the origin) should lie between about 1e-9 and 1e9 for
//!   [`FastPatch::intersect_world`] (f64: 1e-75 and 1e75) and between about 1e-18 and 1e18
//!   for [`FastPatch::intersect_ray`] and [`FastPatch::intersect`] (f64: 1e-140 and
//!   1e140); far outside, the intermediates
//!   overflow or underflow and the result is a miss (unit tests `f32_magnitude_range*`).
//!   The watertight test has no such limit.
//! - **Degenerate cases give a miss, never NaN.** A rung parallel to the ray (|n|² = 0,
//!   resp. B(u) = 0: e.g. the collapsed edge of a triangle-shaped patch, at its apex),
//!   f ≡ 0 (the ray in the plane of a planar patch, or a patch collapsed to a segment) and
//!   any non-finite intermediate report no hit for that root. When the u² coefficient is
//!   0 (a planar parallelogram, or a ray direction that makes it vanish) f is linear and
//!   its one root is used. Every returned hit has finite t and u, v in [0, 1].

use num_traits::Float;

use crate::patch::{Hit, Hits, Patch};
use crate::ray::Ray;

#[inline(always)]
fn sub3<F: Float>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn cross3<F: Float>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
fn dot3<F: Float>(a: [F; 3], b: [F; 3]) -> F {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn lerp3<F: Float>(a: [F; 3], b: [F; 3], s: F) -> [F; 3] {
    [
        a[0] + s * (b[0] - a[0]),
        a[1] + s * (b[1] - a[1]),
        a[2] + s * (b[2] - a[2]),
    ]
}

/// A bilinear patch prepared for the non-watertight ray tests (Reshetov 2019, ch. 8; see
/// the module doc): [`FastPatch::intersect_ray`] (in the space of a shared prepared
/// [`Ray`]) is about 2.2-2.5x as fast as [`crate::PreparedPatch::intersect_ray`],
/// [`FastPatch::intersect`] (the same with `Ray::new` per call) about 2.9x (f32) to 3.4x
/// (f64) as fast as [`Patch::intersect`]; but they are **not watertight**. What they give
/// up:
/// - rays through an edge or corner shared by adjacent patches may hit neither or both
///   (about 10-18 % leaks and 21-24 % double hits on the watertight grid test of
///   `tests/properties.rs`);
/// - a ray grazing the surface may lose both hits of the near-double root, and close roots
///   carry the square root's error (no refinement step);
/// - in f32 the coordinates should lie between about 1e-18 and 1e18 in magnitude for
///   `intersect` and `intersect_ray`, 1e-9 and 1e9 for `intersect_world`; far outside,
///   intermediates overflow or underflow and the result is a miss;
/// - degenerate configurations (a rung parallel to the ray, e.g. at the apex of a
///   triangle-shaped patch; the ray in the plane of a planar patch; a patch collapsed to a
///   segment) give no hit. Never NaN: every hit has finite t and u, v in [0, 1].
///
/// Stores q00 and the bilinear basis e10 = q10 - q00, e00 = q01 - q00,
/// g = q11 - q10 - q01 + q00 (for `intersect_ray`), and e11 = q11 - q10 and
/// q_n = (q10 - q00) × (q01 - q11) (for `intersect_world`), as [`crate::MollerTrumbore`] stores
/// p0 and two edges. Use it where a renderer would use Möller-Trumbore; use
/// [`crate::PreparedPatch`] where rays through shared edges must be counted exactly once.
///
/// ```
/// use bilinear_patch::{FastPatch, Ray};
///
/// // The saddle z = u + v - 2uv over the unit square, crossed twice along the diagonal.
/// let c = [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0]];
/// let patch = FastPatch::<f64>::new(c);
/// let hits = patch.intersect([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0], 0.0, 10.0);
/// assert_eq!(hits.len(), 2);
/// assert!(hits[0].t < hits[1].t && (hits[0].u - hits[0].v).abs() < 1e-12);
/// // The same with a ray prepared once and shared by every face it meets, and by
/// // Reshetov's world-space algorithm.
/// let ray = Ray::new([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0]).unwrap();
/// let same = patch.intersect_ray(&ray, 0.0, 10.0);
/// let world = patch.intersect_world([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0], 0.0, 10.0);
/// assert!(same.iter().zip(hits.iter()).all(|(a, b)| (a.t - b.t).abs() < 1e-12));
/// assert!(world.iter().zip(hits.iter()).all(|(a, b)| (a.t - b.t).abs() < 1e-12));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastPatch<F> {
    /// q00, e10, e00, g, each padded with a zero so that indexing by the ray's axis
    /// permutation (`k & 3`) is free of bounds checks. (Stored by axis instead, a row per
    /// axis, the prepared test is no faster, and a patch built just before the test, as in
    /// the `raw` benchmark, is 1.8x slower: the row loads wait for the scalar stores.)
    basis: [[F; 4]; 4],
    /// e11 = q11 - q10 and q_n = (q10 - q00) × (q01 - q11), for the world-space algorithm.
    e11: [F; 3],
    qn: [F; 3],
}

impl<F: Float> From<Patch<F>> for FastPatch<F> {
    fn from(p: Patch<F>) -> Self {
        FastPatch::new(p.corners())
    }
}

impl<F: Float> FastPatch<F> {
    /// Prepares the patch with corners `[q00, q10, q11, q01]` (Reshetov 2019 naming).
    pub fn new(corners: [[F; 3]; 4]) -> Self {
        let [q00, q10, q11, q01] = corners;
        let zero = F::zero();
        let e10 = [q10[0] - q00[0], q10[1] - q00[1], q10[2] - q00[2], zero];
        let e00 = [q01[0] - q00[0], q01[1] - q00[1], q01[2] - q00[2], zero];
        let g = [
            (q11[0] - q10[0]) - e00[0],
            (q11[1] - q10[1]) - e00[1],
            (q11[2] - q10[2]) - e00[2],
            zero,
        ];
        let e11 = sub3(q11, q10);
        FastPatch {
            basis: [[q00[0], q00[1], q00[2], zero], e10, e00, g],
            e11,
            qn: cross3([e10[0], e10[1], e10[2]], sub3(q01, q11)),
        }
    }

    /// Hits of the ray `origin + t * dir` with `t_min <= t <= t_max`, sorted by `t`, for a
    /// one-off query: prepares the [`Ray`] and runs [`FastPatch::intersect_ray`] (faster,
    /// `Ray::new` included, than Reshetov's world-space algorithm
    /// [`FastPatch::intersect_world`] on the benchmark rays: `BENCHMARKS.md`).
    ///
    /// Not watertight: a ray through a shared edge or corner of adjacent patches may hit
    /// neither or both. Near-tangent rays may miss. Non-finite input, a zero direction or
    /// NaN bounds give an empty result; degenerate configurations give no hit, never NaN.
    #[inline(always)]
    pub fn intersect(&self, origin: [F; 3], dir: [F; 3], t_min: F, t_max: F) -> Hits<F> {
        match Ray::new(origin, dir) {
            Some(ray) => self.intersect_ray(&ray, t_min, t_max),
            None => Hits::default(),
        }
    }

    /// As [`FastPatch::intersect`], by Reshetov's original world-space algorithm
    /// (Reshetov 2019, ch. 8; see the module doc), which needs no prepared [`Ray`]: the
    /// reference formulation, kept for comparison (its f32 range is narrower, about 1e-9 to
    /// 1e9, and on the benchmark rays it is slower even against `Ray::new` +
    /// [`FastPatch::intersect_ray`]).
    ///
    /// Not watertight: a ray through a shared edge or corner of adjacent patches may hit
    /// neither or both. Near-tangent rays may miss. Non-finite input, a zero direction or
    /// NaN bounds give an empty result; degenerate configurations give no hit, never NaN.
    #[inline(always)]
    pub fn intersect_world(&self, origin: [F; 3], dir: [F; 3], t_min: F, t_max: F) -> Hits<F> {
        let mut out = Hits::default();
        let zero = F::zero();
        let one = F::one();
        let finite = |p: [F; 3]| p[0].is_finite() & p[1].is_finite() & p[2].is_finite();
        if !(finite(origin) & finite(dir)) | t_min.is_nan() | t_max.is_nan() {
            return out;
        }
        let d = dir;
        let [q00, e10, e00, _] = self.basis;
        let (e10, e00) = ([e10[0], e10[1], e10[2]], [e00[0], e00[1], e00[2]]);
        let p00 = sub3([q00[0], q00[1], q00[2]], origin);
        let p10 = [p00[0] + e10[0], p00[1] + e10[1], p00[2] + e10[2]];
        // f(u) = a + b u + c u²: f(0) = a, f(1) = a + b + c, c = d · q_n, from the
        // (P(0) - o) × d and (P(1) - o) × d that v reuses below.
        let ad = cross3(p00, d);
        let bd = cross3(p10, d);
        let a = dot3(ad, e00);
        let f1 = dot3(bd, self.e11);
        let c = dot3(self.qn, d);
        let b = f1 - a - c;
        // f(0), f(1) of one sign and f monotone on [0, 1]: no root there (see module doc).
        // An underflowing product only skips the early exit, except b c = 0 with
        // a f(1) > 0: but two roots in [0, 1] around a vertex ε = -b / 2c near 0 give
        // 0 < a f(1) < |b c| ε / 2, so a f(1) underflows as well.
        if no_root_in_unit(a, f1, b, c) {
            return out;
        }
        // The discriminant is of degree six in the coordinates here.
        let Some((a, b, c, disc, _)) = scaled_discriminant(a, b, c) else {
            return out;
        };
        // Stable roots: q = -(b + sign(b) √disc) / 2, u = q / c and u = a / q.
        let root = disc.sqrt();
        let q = -(b + if b < zero { -root } else { root }) / (one + one);
        let (u0, u1) = if q != zero {
            // c = 0: f is linear, its one root is a / q = -a / b.
            (a / q, if c != zero { q / c } else { F::nan() })
        } else if c != zero {
            // b = 0 and disc = 0, so a c = 0 with c != 0: the double root u = 0.
            (zero, zero)
        } else {
            // f ≡ 0 (or a = b = c = 0 up to rounding): every rung meets the ray's line.
            return out;
        };
        for u in [u0, u1] {
            // False for NaN (no second root).
            if !((u >= zero) & (u <= one)) {
                continue;
            }
            // The rung R(u) and the normal of the plane of rung and ray, n = d × R(u).
            let pb = lerp3(e00, self.e11, u);
            let n = cross3(d, pb);
            let det = dot3(n, n);
            if !((det > zero) & det.is_finite()) {
                continue; // the rung is parallel to the ray (or collapsed), or overflow
            }
            // v |n|² = (n × (P(u) - o)) · d = n · ((P(u) - o) × d), the latter linear in u.
            let vn = dot3(n, lerp3(ad, bd, u));
            if !((vn >= zero) & (vn <= det)) {
                continue;
            }
            let v = vn / det;
            // t of the hit point P(u) + v R(u) projected on the ray (the closest-point formula
            // at a root, one cross product cheaper).
            let pa = lerp3(p00, p10, u);
            let dd = dot3(d, d);
            let t = (dot3(pa, d) + v * dot3(pb, d)) / dd;
            // An overflowing |d|² would give t = 0: no hit.
            if (t >= t_min) & (t <= t_max) & t.is_finite() & dd.is_finite() {
                out.push(Hit { t, u, v });
            }
        }
        out.sort();
        out
    }

    /// As [`FastPatch::intersect`] for a [`Ray`] prepared once and shared by every face it
    /// meets (Reshetov's quadratic in the ray's space, see the module doc). NaN bounds give
    /// an empty result; every hit has finite t and u, v in [0, 1]. Not watertight.
    #[inline(always)]
    pub fn intersect_ray(&self, ray: &Ray<F>, t_min: F, t_max: F) -> Hits<F> {
        let zero = F::zero();
        let two = F::one() + F::one();
        let mut out = Hits::default();
        let [kx, ky, kz] = ray.k;
        let [sx, sy, sz] = ray.s;
        let [ox, oy, oz] = ray.origin_k;
        // k < 3 always; `& 3` into four entries lets the compiler drop the bounds checks.
        let (kx, ky, kz) = (kx & 3, ky & 3, kz & 3);
        let [q, e, f, g] = &self.basis;
        let xs = [q[kx], e[kx], f[kx], g[kx]];
        let ys = [q[ky], e[ky], f[ky], g[ky]];
        let zs = [q[kz], e[kz], f[kz], g[kz]];
        // Into ray space (as `Ray::transform`); only q00 is translated.
        let az = zs[0] - oz;
        let px = (xs[0] - ox) - sx * az;
        let py = (ys[0] - oy) - sy * az;
        let pz = sz * az;
        let (ex, ey, ez) = (xs[1] - sx * zs[1], ys[1] - sy * zs[1], sz * zs[1]);
        let (fx, fy, fz) = (xs[2] - sx * zs[2], ys[2] - sy * zs[2], sz * zs[2]);
        let (gx, gy, gz) = (xs[3] - sx * zs[3], ys[3] - sy * zs[3], sz * zs[3]);
        let cross = |ax: F, ay: F, bx: F, by: F| ax * by - ay * bx;
        // f(u) = cross(A(u), B(u)) = k0 + k1 u + k2 u² with A = p + u e, B = f + u g.
        let k0 = cross(px, py, fx, fy);
        let (cpg, cef) = (cross(px, py, gx, gy), cross(ex, ey, fx, fy));
        let k1 = cpg + cef;
        let k2 = cross(ex, ey, gx, gy);
        // The same in v: Q' = C(v) + u D(v) with C = p + v f, D = e + v g, so the v of a hit
        // is a root of h(v) = cross(C(v), D(v)) = m0 + m1 v + m2 v² (m1 reuses the cross
        // products of k1). A second, independent chain: short, so the branch below
        // resolves early.
        let m0 = cross(px, py, ex, ey);
        let m1 = cpg - cef;
        let m2 = cross(fx, fy, gx, gy);
        let h1 = m0 + m1 + m2;
        // f (resp. h) of one sign at 0 and 1 and monotone on [0, 1]: no root there, a miss.
        // An underflowing product only skips the exit, except k1 k2 = 0 with k0 f(1) > 0:
        // but two roots in [0, 1] around a vertex ε = -k1 / 2k2 near 0 give
        // 0 < k0 f(1) < |k1 k2| ε / 2, so k0 f(1) underflows as well (the same for h).
        let f1 = k0 + k1 + k2;
        if no_root_in_unit(k0, f1, k1, k2) | no_root_in_unit(m0, h1, m1, m2) {
            return out;
        }
        // The discriminant is of degree four in the coordinates here; h has the same one
        // (module doc), so one square root serves both.
        let Some((a, b, c, disc, scale)) = scaled_discriminant(k0, k1, k2) else {
            return out;
        };
        let (m0, m1, m2) = if scale != F::one() {
            (m0 / scale, m1 / scale, m2 / scale)
        } else {
            (m0, m1, m2)
        };
        // Stable roots: q = -(b + sign(b) √disc) (twice Reshetov's), u = 2a / q, u = q / 2c
        // (c = 0: f is linear, its one root is 2a / q = -a / b; the other is a miss).
        let root = disc.sqrt();
        // Sign by the sign bit, branch-free (the sign of b is random: a branch on it would
        // be mispredicted half the time).
        let q = -(b + root.copysign(b));
        let (u0, u1) = if q != zero {
            ((two * a, q), (q, two * c))
        } else if c != zero {
            // b = 0 and disc = 0, so a c = 0 with c != 0: the double root u = 0.
            ((zero, c), (zero, c))
        } else {
            return out; // f ≡ 0 (or a = b = c = 0 up to rounding)
        };
        // The same for h. u0 = 2a / q is the root (-b ± √disc) / 2c with ± the sign of b
        // (its sign bit: copysign above), and its hit has the v of the other sign (module
        // doc); 2 m0 / q_m is the v with the sign of m1, q_m / 2 m2 the other.
        let qm = -(m1 + root.copysign(m1));
        let flip = b.is_sign_negative() != m1.is_sign_negative();
        let pick = |x: F, y: F| if flip { x } else { y };
        let (m0, m2) = (two * m0, two * m2);
        let (v0, v1) = ((pick(m0, qm), pick(qm, m2)), (pick(qm, m0), pick(m2, qm)));
        let rs = RaySpace {
            z: [pz, ez, fz, gz],
        };
        // Finite bounds (NaN stays NaN: no hit), so a kept t is finite by comparison.
        let max = F::max_value();
        let lo = if t_min < -max { -max } else { t_min };
        let hi = if t_max > max { max } else { t_max };
        let (ok0, h0) = rs.root_hit(u0, v0, lo, hi);
        if ok0 {
            out.push(h0);
        }
        // The second root is rarely inside the patch: test u1, v1 in [0, 1] without
        // dividing, and only then evaluate it.
        let unit = |(n, d): (F, F)| (n * d >= zero) & (n.abs() <= d.abs());
        if unit(u1) & unit(v1) {
            let (ok1, h1) = rs.root_hit(u1, v1, lo, hi);
            if ok1 {
                out.push(h1);
            }
            out.sort();
        }
        out
    }
}

/// True when f(u) = a + b u + c u² (with f(1) = `f1`) has no root in [0, 1]: f(0) and f(1)
/// of one sign and f monotone on [0, 1] (its vertex -b / 2c outside, or c = 0). Both
/// algorithms' exit before the square root.
#[inline(always)]
fn no_root_in_unit<F: Float>(a: F, f1: F, b: F, c: F) -> bool {
    let (zero, two) = (F::zero(), F::one() + F::one());
    (a * f1 > zero) & !((b * c < zero) & (b.abs() < two * c.abs()))
}

/// The discriminant b² - 4ac of a + b u + c u² and the coefficients it was computed from:
/// when b², 4ac would underflow (losing relative precision) or overflow, the coefficients
/// are first divided by the largest of them (roots unchanged; rare: a well-predicted
/// branch). `None` for a negative or NaN discriminant, for a = b = c = 0 (f ≡ 0) and on
/// overflow.
#[inline(always)]
fn scaled_discriminant<F: Float>(a: F, b: F, c: F) -> Option<(F, F, F, F, F)> {
    let (zero, two) = (F::zero(), F::one() + F::one());
    let (mut a, mut b, mut c) = (a, b, c);
    let (mut bb, mut ac4) = (b * b, two * two * a * c);
    let mut scale = F::one();
    let big = bb + ac4.abs();
    if !((big > F::min_positive_value() / F::epsilon()) & (big <= F::max_value())) {
        let k = a.abs().max(b.abs()).max(c.abs());
        if !((k > zero) & k.is_finite()) {
            return None;
        }
        (a, b, c) = (a / k, b / k, c / k);
        (bb, ac4) = (b * b, two * two * a * c);
        scale = k;
    }
    let disc = bb - ac4;
    // False for NaN as well.
    (disc >= zero).then_some((a, b, c, disc, scale))
}

/// The depth part of the patch in ray space, z'(u, v) = p_z + u e_z + v f_z + u v g_z,
/// scaled to the ray parameter.
struct RaySpace<F> {
    z: [F; 4],
}

impl<F: Float> RaySpace<F> {
    /// The hit at u = un / ud, v = vn / vd (a pair of roots of f and h), and whether it is
    /// kept (u, v in [0, 1], lo <= t <= hi). Branch-free; the two divisions are
    /// independent.
    #[inline(always)]
    fn root_hit(&self, (un, ud): (F, F), (vn, vd): (F, F), lo: F, hi: F) -> (bool, Hit<F>) {
        let (zero, one) = (F::zero(), F::one());
        let [pz, ez, fz, gz] = self.z;
        let u = un / ud;
        // NaN or an infinity (a root at infinity, 0 / 0): no hit.
        let v = vn / vd;
        let t = pz + u * ez + v * (fz + u * gz);
        let ok = (u >= zero) & (u <= one) & (v >= zero) & (v <= one) & (t >= lo) & (t <= hi);
        (ok, Hit { t, u, v })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The module doc's claims about f(u) and h(v) in ray space, on random 2D p, e, f, g:
    /// one discriminant, and the hit with u₊ has v₋ (the residual of the 2D bilinear
    /// equation vanishes there and not for the other pairing).
    #[test]
    fn u_and_v_roots_share_the_discriminant_and_pair_crosswise() {
        let mut next = crate::fixtures::uniform(0x9e37_79b9_7f4a_7c15);
        let cross = crate::fixtures::cross2;
        let (mut paired, mut crossed_wins) = (0, 0);
        for _ in 0..10_000 {
            let [p, e, f, g] = [0; 4].map(|_| [next(), next()]);
            let (k0, k2, m0, m2) = (cross(p, f), cross(e, g), cross(p, e), cross(f, g));
            let (cpg, cef) = (cross(p, g), cross(e, f));
            let (k1, m1) = (cpg + cef, cpg - cef);
            let (dk, dm) = (k1 * k1 - 4.0 * k0 * k2, m1 * m1 - 4.0 * m0 * m2);
            let size = k1 * k1 + (4.0 * k0 * k2).abs() + m1 * m1 + (4.0 * m0 * m2).abs();
            assert!((dk - dm).abs() <= 1e-14 * size, "{dk} vs {dm}");
            if dk <= 1e-6 || k2.abs() < 1e-3 || m2.abs() < 1e-3 {
                continue;
            }
            let r = dk.sqrt();
            let residual = |u: f64, v: f64| {
                let x = p[0] + u * e[0] + v * f[0] + u * v * g[0];
                let y = p[1] + u * e[1] + v * f[1] + u * v * g[1];
                x.hypot(y)
            };
            let (up, um) = ((-k1 + r) / (2.0 * k2), (-k1 - r) / (2.0 * k2));
            let (vp, vm) = ((-m1 + r) / (2.0 * m2), (-m1 - r) / (2.0 * m2));
            let scale = 1.0 + up.abs().max(um.abs()).max(vp.abs()).max(vm.abs()).powi(2);
            assert!(
                residual(up, vm) <= 1e-9 * scale,
                "u+ v-: {}",
                residual(up, vm)
            );
            assert!(
                residual(um, vp) <= 1e-9 * scale,
                "u- v+: {}",
                residual(um, vp)
            );
            paired += 1;
            crossed_wins += usize::from(residual(up, vp) > 1e-6 * scale);
        }
        assert!(paired > 1000, "{paired} cases checked");
        // The other pairing is not a solution (except where u₊ = u₋ or v₊ = v₋ nearly).
        assert!(
            crossed_wins * 100 > paired * 95,
            "{crossed_wins} of {paired}"
        );
    }

    #[test]
    fn plain_hit_matches_the_patch_on_a_unit_square() {
        let c = crate::fixtures::UNIT_SQUARE;
        let h = FastPatch::new(c).intersect([0.25, 0.75, 2.0], [0.0, 0.0, -1.0], 0.0, 10.0);
        assert_eq!(
            &*h,
            &[Hit {
                t: 2.0,
                u: 0.25,
                v: 0.75
            }]
        );
    }

    #[test]
    fn saddle_gives_two_sorted_hits() {
        let c = crate::fixtures::SADDLE;
        let (o, d) = ([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0]);
        let fast = FastPatch::new(c).intersect_world(o, d, 0.0, f64::INFINITY);
        let exact = Patch::new(c).intersect(o, d, 0.0, f64::INFINITY);
        assert_eq!(fast.len(), 2);
        assert!(fast[0].t < fast[1].t);
        for (f, e) in fast.iter().zip(exact.iter()) {
            assert!((f.t - e.t).abs() < 1e-12 && (f.u - e.u).abs() < 1e-12);
            assert!((f.v - e.v).abs() < 1e-12);
        }
    }

    /// The documented f32 range: hits found at scales 1e-8 and 1e8; far outside (1e-20,
    /// 1e20) the intermediates underflow or overflow and the result is a miss, not NaN.
    #[test]
    fn f32_magnitude_range() {
        let c = crate::fixtures::f32(crate::fixtures::SADDLE);
        let (o, d) = ([-0.1f32, -0.1, 0.3], [1.0f32, 1.0, 0.0]);
        for (m, expect) in [(1e-8f32, 2), (1e8, 2), (1e-20, 0), (1e20, 0)] {
            let p = FastPatch::new(c.map(|q| q.map(|x| x * m)));
            let h = p.intersect_world(o.map(|x| x * m), d.map(|x| x * m), 0.0, f32::INFINITY);
            assert_eq!(h.len(), expect, "scale {m}: {h:?}");
            // 2s - 2s² = 0.3 on the diagonal u = v = s, at t = s + 0.1.
            let r = (0.4f32).sqrt();
            for (x, s) in h.iter().zip([(1.0 - r) / 2.0, (1.0 + r) / 2.0]) {
                assert!(
                    (x.u - s).abs() < 1e-5 && (x.v - s).abs() < 1e-5,
                    "{m}: {x:?}"
                );
                assert!((x.t - (s + 0.1)).abs() < 1e-5, "{m}: {x:?}");
            }
        }
    }

    /// Both algorithms agree on plain hits (the world-space one through `intersect_world`,
    /// the ray-space one through `intersect_ray`), within rounding.
    #[test]
    fn world_and_ray_space_agree() {
        let c = crate::fixtures::SADDLE;
        let p = FastPatch::new(c);
        for (o, d) in [
            ([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0]),
            ([0.3, 0.6, 2.0], [0.1, -0.2, -1.0]),
            ([2.0, 0.4, 0.5], [-1.0, 0.05, 0.02]),
        ] {
            let world = p.intersect_world(o, d, 0.0, f64::INFINITY);
            let ray = p.intersect_ray(&Ray::new(o, d).expect("finite ray"), 0.0, f64::INFINITY);
            assert_eq!(world.len(), ray.len());
            assert!(!world.is_empty());
            for (a, b) in world.iter().zip(ray.iter()) {
                assert!((a.t - b.t).abs() < 1e-14 && (a.u - b.u).abs() < 1e-14);
                assert!((a.v - b.v).abs() < 1e-14, "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn t_range_and_bad_input() {
        let c = crate::fixtures::f32(crate::fixtures::UNIT_SQUARE);
        let p = FastPatch::new(c);
        let (o, d) = ([0.5, 0.5, 1.0], [0.0, 0.0, -1.0]);
        assert_eq!(p.intersect(o, d, 0.0, 2.0).len(), 1);
        assert!(p.intersect(o, d, 1.5, 2.0).is_empty());
        assert!(p.intersect(o, d, f32::NAN, 2.0).is_empty());
        assert!(p.intersect(o, [0.0; 3], 0.0, 2.0).is_empty());
        assert!(p.intersect([f32::NAN, 0.0, 0.0], d, 0.0, 2.0).is_empty());
        let ray = Ray::new(o, d).expect("finite ray");
        assert_eq!(p.intersect_ray(&ray, 0.0, 2.0).len(), 1);
        assert!(p.intersect_ray(&ray, 1.5, 2.0).is_empty());
        assert!(p.intersect_ray(&ray, f32::NAN, 2.0).is_empty());
        assert!(p.intersect_ray(&ray, 0.0, f32::NAN).is_empty());
        // A corner with an infinity: no hit, no NaN.
        let mut inf = c;
        inf[2][2] = f32::INFINITY;
        for h in FastPatch::new(inf)
            .intersect_ray(&ray, 0.0, f32::INFINITY)
            .iter()
        {
            assert!(h.t.is_finite() && (0.0..=1.0).contains(&h.u) && (0.0..=1.0).contains(&h.v));
        }
    }
}
