//! The non-watertight ray/patch test: Reshetov's original "Cool Patches" algorithm in world
//! space (Reshetov 2019, Ray Tracing Gems ch. 8), with the per-patch quantities precomputed
//! as a BVH leaf would store them. It is the like-for-like counterpart of Möller-Trumbore
//! with stored edges ([`crate::MollerTrumbore`]): no ray-space transform, no exact signs.
//!
//! Geometry (own derivation; the names are Reshetov's). The patch is
//! Q(u, v) = lerp(lerp(q00, q10, u), lerp(q01, q11, u), v): for fixed u the points Q(u, ·)
//! form the rung from P(u) = q00 + u e10 to P(u) + R(u), with e10 = q10 - q00,
//! e00 = q01 - q00, e11 = q11 - q10 and R(u) = lerp(e00, e11, u). The ray o + t d meets the
//! line of the rung exactly when the two lines are coplanar:
//!
//! f(u) = det[P(u) - o, d, R(u)] = (P(u) - o) × d · R(u) = a + b u + c u²,
//!
//! with a = f(0) = (q00 - o) × d · e00, a + b + c = f(1) = (q10 - o) × d · e11, and
//! c = e10 × d · (e11 - e00) = d · ((e11 - e00) × e10) = d · q_n, because
//! e11 - e00 = -(q01 - q11) - e10, so (e11 - e00) × e10 = e10 × (q01 - q11) = q_n, Reshetov's
//! normal-like vector (zero for a parallelogram).
//! When f(0) and f(1) have one sign and f is monotone on [0, 1] (its vertex -b / 2c
//! outside, or c = 0) there is no root in [0, 1]: a miss before the square root. For each
//! root u in [0, 1], the ray and the rung's line are coplanar, and v is the parameter of
//! their crossing on the rung: with n = d × R(u),
//!
//! v |n|² = (n × (P(u) - o)) · d = n · ((P(u) - o) × d),
//!
//! where (P(u) - o) × d = lerp((q00 - o) × d, (q10 - o) × d, u) reuses the two cross
//! products of a and f(1). The hit is kept when 0 <= v |n|² <= |n|² (so the division is
//! paid only for a hit); t is the hit point Q(u, v) projected on the ray,
//! t = ((P(u) - o) · d + v R(u) · d) / (d · d) (equal to the closest-point formula at a
//! root, one cross product cheaper), kept when t_min <= t <= t_max.
//!
//! What it gives up against [`crate::Patch`] / [`crate::PreparedPatch`]:
//! - **Not watertight.** Boundary decisions are plain floating-point comparisons of u and v
//!   computed independently per patch, so a ray through an edge or corner shared by two
//!   patches may hit neither (a leak) or both (a double hit). On the random height-field
//!   grids the watertight test is checked on, about 10 % of rays through a shared edge or
//!   vertex leak and 24 % are counted twice
//!   (`tests/properties.rs::fast_patch_leak_rate_on_shared_edges_is_measured`).
//! - **Less robust near tangency.** A discriminant that rounds below zero is a miss, so a
//!   ray grazing the surface may lose both hits of the (near-)double root, and close roots
//!   carry the square-root error (no refinement step, unlike the watertight test).
//! - **A narrower range of magnitudes.** a, b, c are products of three coordinate
//!   differences and |n|² of four (the discriminant, of six, is rescaled when it would
//!   underflow or overflow), so in f32 the coordinates (patch size, ray direction,
//!   distance to the origin) should lie between about 1e-9 and 1e9 (f64: 1e-75 and 1e75);
//!   far outside, the intermediates overflow or underflow and the result is a miss (unit
//!   test `f32_magnitude_range`). The watertight test has no such limit.
//! - **Degenerate cases give a miss, never NaN.** A rung parallel to the ray (|n|² = 0,
//!   e.g. the collapsed edge of a triangle-shaped patch, at its apex), f ≡ 0 (the ray in the
//!   plane of a planar patch, or a patch collapsed to a segment) and any non-finite
//!   intermediate report no hit for that root. When c = 0 (a planar parallelogram, or
//!   d ⟂ q_n) f is linear and its one root u = -a/b is used. Every returned hit has finite
//!   t and u, v in [0, 1].

use num_traits::Float;

use crate::patch::{Hit, Hits, Patch};

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

/// A bilinear patch prepared for Reshetov's world-space ray test (Reshetov 2019, ch. 8):
/// about 1.5x faster than [`crate::PreparedPatch`], but **not watertight**. What it gives
/// up:
/// - rays through an edge or corner shared by adjacent patches may hit neither or both
///   (about 10 % leaks and 24 % double hits on the watertight grid test of
///   `tests/properties.rs`);
/// - a ray grazing the surface may lose both hits of the near-double root, and close roots
///   carry the square root's error (no refinement step);
/// - in f32 the coordinates should lie between about 1e-9 and 1e9 in magnitude (f64: 1e-75
///   and 1e75); far outside, intermediates overflow or underflow and the result is a miss;
/// - degenerate configurations (a rung parallel to the ray, e.g. at the apex of a
///   triangle-shaped patch; the ray in the plane of a planar patch; a patch collapsed to a
///   segment) give no hit. Never NaN: every hit has finite t and u, v in [0, 1].
///
/// Stores q00, the edges e10 = q10 - q00, e00 = q01 - q00, e11 = q11 - q10 and
/// q_n = (q10 - q00) × (q01 - q11), as [`crate::MollerTrumbore`] stores p0 and two edges.
/// Use it where a renderer would use Möller-Trumbore; use [`crate::PreparedPatch`] where
/// rays through shared edges must be counted exactly once.
///
/// ```
/// use bilinear_patch::FastPatch;
///
/// // The saddle z = u + v - 2uv over the unit square, crossed twice along the diagonal.
/// let c = [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0]];
/// let hits = FastPatch::<f64>::new(c).intersect([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0], 0.0, 10.0);
/// assert_eq!(hits.len(), 2);
/// assert!(hits[0].t < hits[1].t && (hits[0].u - hits[0].v).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FastPatch<F> {
    q00: [F; 3],
    e10: [F; 3],
    e00: [F; 3],
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
        let e10 = sub3(q10, q00);
        FastPatch {
            q00,
            e10,
            e00: sub3(q01, q00),
            e11: sub3(q11, q10),
            qn: cross3(e10, sub3(q01, q11)),
        }
    }

    /// Hits of the ray `origin + t * dir` with `t_min <= t <= t_max`, sorted by `t`, by
    /// Reshetov's world-space algorithm (Reshetov 2019, ch. 8; see the module doc).
    ///
    /// Not watertight: a ray through a shared edge or corner of adjacent patches may hit
    /// neither or both. Near-tangent rays may miss. Non-finite input, a zero direction or
    /// NaN bounds give an empty result; degenerate configurations give no hit, never NaN.
    #[inline(always)]
    pub fn intersect(&self, origin: [F; 3], dir: [F; 3], t_min: F, t_max: F) -> Hits<F> {
        let mut out = Hits::default();
        let zero = F::zero();
        let one = F::one();
        let finite = |p: [F; 3]| p[0].is_finite() & p[1].is_finite() & p[2].is_finite();
        if !(finite(origin) & finite(dir)) | t_min.is_nan() | t_max.is_nan() {
            return out;
        }
        let d = dir;
        let p00 = sub3(self.q00, origin);
        let p10 = [
            p00[0] + self.e10[0],
            p00[1] + self.e10[1],
            p00[2] + self.e10[2],
        ];
        // f(u) = a + b u + c u²: f(0) = a, f(1) = a + b + c, c = d · q_n, from the
        // (P(0) - o) × d and (P(1) - o) × d that v reuses below.
        let ad = cross3(p00, d);
        let bd = cross3(p10, d);
        let a = dot3(ad, self.e00);
        let f1 = dot3(bd, self.e11);
        let c = dot3(self.qn, d);
        let b = f1 - a - c;
        let two = one + one;
        // f(0), f(1) of one sign and f monotone on [0, 1]: no root there (see module doc).
        // An underflowing product only skips the early exit, except b c = 0 with
        // a f(1) > 0: but two roots in [0, 1] around a vertex ε = -b / 2c near 0 give
        // 0 < a f(1) < |b c| ε / 2, so a f(1) underflows as well.
        let same_sign = a * f1 > zero;
        let vertex_inside = (b * c < zero) & (b.abs() < two * c.abs());
        if same_sign & !vertex_inside {
            return out;
        }
        // The discriminant is of degree six in the coordinates: when b², 4ac would underflow
        // (losing relative precision) or overflow, the coefficients are first divided by
        // the largest of them (roots unchanged; rare: well-predicted branch).
        let (mut a, mut b, mut c) = (a, b, c);
        let (mut bb, mut ac4) = (b * b, two * two * a * c);
        let big = bb + ac4.abs();
        if !((big > F::min_positive_value() / F::epsilon()) & (big <= F::max_value())) {
            let k = a.abs().max(b.abs()).max(c.abs());
            if !((k > zero) & k.is_finite()) {
                return out; // a = b = c = 0 (f ≡ 0) or an overflow
            }
            (a, b, c) = (a / k, b / k, c / k);
            (bb, ac4) = (b * b, two * two * a * c);
        }
        let disc = bb - ac4;
        // Also false for NaN: no hit.
        if disc.is_nan() || disc < zero {
            return out;
        }
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
            let pb = lerp3(self.e00, self.e11, u);
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
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let fast = FastPatch::new(c).intersect(o, d, 0.0, f64::INFINITY);
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
            let h = p.intersect(o.map(|x| x * m), d.map(|x| x * m), 0.0, f32::INFINITY);
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
    }
}
