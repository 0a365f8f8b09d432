//! A bilinear patch laid out for repeated ray tests (a BVH leaf), and the fast path of the
//! watertight ray/patch test that [`Patch::intersect_ray`] also runs.
//!
//! What is prepared per patch is the corner layout: the coordinates are stored by axis
//! (`axes[k][i]` = coordinate k of corner i), so the move into ray space (Woop, Benthin and
//! Wald 2013: translate, permute, shear) of all four corners is four-wide arithmetic on
//! whole rows, with no per-corner gather through the ray's axis permutation. What is
//! prepared per ray is the [`Ray`] itself (one per ray, shared by every face it meets).
//!
//! The common case (both u-edges proper, a clearly positive or clearly negative
//! discriminant, well separated roots, no root of f within √ε of u = 0 or u = 1, and a root
//! count of the parity the exact end signs require) runs inline; every other case goes to
//! the general path `patch::intersect_in_ray_space` (the algorithm of [`Patch`] that handles
//! all of them), so both give the same hits bit for bit (unit test
//! `fast_path_matches_general_path_bit_for_bit`). The v-decisions compare the numerator of
//! v with its denominator, so the division is paid only for a hit (Reshetov 2019, ch. 8,
//! delays it the same way).
//!
//! Two things were measured and left out:
//! - a branch-free variant (both roots evaluated, every outcome folded into masks, hits
//!   selected without branches): a third of the mispredictions in cachegrind's model, but
//!   about 40 % more instructions, and about 25 % slower on the benchmark CPU (f32);
//! - precomputing Reshetov's world-space quantities (the edge cross product
//!   q_n = (q10 - q00) × (q01 - q11) giving the u² coefficient): the watertight test needs
//!   f(0), f(1) as exact-sign edge functions of the ray-space corners anyway (so that
//!   neighbouring faces decide identically), and with those in hand the remaining
//!   coefficient costs three operations in ray space, no more than a dot product with a
//!   stored q_n. (The non-watertight [`crate::FastPatch`] stores q_n for Reshetov's
//!   world-space algorithm, and the bilinear basis for the same quadratic in ray space
//!   without exact signs: 1.5x and 1.65x faster, at the price of leaks on shared edges.)

use num_traits::Float;

use crate::orient::{cross2, edge_sign};
use crate::patch::{Hits, Patch, intersect_in_ray_space, root_hit, small};
use crate::ray::Ray;

/// A bilinear patch with its corners stored by axis for fast repeated ray tests. Gives the
/// same hits as [`Patch::intersect_ray`] (same decisions, same values; see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreparedPatch<F> {
    /// `axes[k][i]`: coordinate k of corner i, corners in the order q00, q10, q11, q01; a
    /// fourth row of zeros makes indexing by `k & 3` free of bounds checks.
    axes: [[F; 4]; 4],
}

impl<F: Float> From<Patch<F>> for PreparedPatch<F> {
    fn from(p: Patch<F>) -> Self {
        PreparedPatch::new(p.corners())
    }
}

impl<F: Float> PreparedPatch<F> {
    /// Prepares the patch with corners `[q00, q10, q11, q01]` (Reshetov 2019 naming).
    pub fn new(corners: [[F; 3]; 4]) -> Self {
        let axis = |k: usize| corners.map(|c| c[k]);
        PreparedPatch {
            axes: [axis(0), axis(1), axis(2), [F::zero(); 4]],
        }
    }

    /// The patch back in corner form.
    pub fn patch(&self) -> Patch<F> {
        let [x, y, z, _] = self.axes;
        Patch::new([0, 1, 2, 3].map(|i| [x[i], y[i], z[i]]))
    }

    /// As [`Patch::intersect`]: all hits of the ray `origin + t * dir` with
    /// `t_min <= t <= t_max`, sorted by `t`; empty for non-finite input or NaN bounds.
    pub fn intersect(&self, origin: [F; 3], dir: [F; 3], t_min: F, t_max: F) -> Hits<F> {
        match Ray::new(origin, dir) {
            Some(ray) => self.intersect_ray(&ray, t_min, t_max),
            None => Hits::default(),
        }
    }

    /// As [`Patch::intersect_ray`], for a prepared [`Ray`] shared with the neighbouring
    /// faces (watertight on shared edges and corners, also with [`Patch`] and
    /// [`crate::Triangle`] faces tested against the same ray).
    #[inline]
    pub fn intersect_ray(&self, ray: &Ray<F>, t_min: F, t_max: F) -> Hits<F> {
        if t_min.is_nan() || t_max.is_nan() {
            return Hits::default();
        }
        let [kx, ky, kz] = ray.k;
        let [sx, sy, sz] = ray.s;
        let [ox, oy, oz] = ray.origin_k;
        // k < 3 always; `& 3` into four entries lets the compiler drop the bounds checks.
        let (xs, ys, zs) = (&self.axes[kx & 3], &self.axes[ky & 3], &self.axes[kz & 3]);
        // The same operations as `Ray::transform`, four corners at a time.
        let mut x = [F::zero(); 4];
        let mut y = [F::zero(); 4];
        let mut z = [F::zero(); 4];
        for i in 0..4 {
            let az = zs[i] - oz;
            x[i] = (xs[i] - ox) - sx * az;
            y[i] = (ys[i] - oy) - sy * az;
            z[i] = sz * az;
        }
        let corners = [0, 1, 2, 3].map(|i| [x[i], y[i], z[i]]);
        let general = || intersect_in_ray_space(corners, t_min, t_max);

        // Convex-hull rejection as in the general path.
        let zero = F::zero();
        let one = F::one();
        let all = |v: [F; 4], f: fn(F, F) -> bool| {
            f(v[0], zero) & f(v[1], zero) & f(v[2], zero) & f(v[3], zero)
        };
        let gt = |a: F, b: F| a > b;
        let lt = |a: F, b: F| a < b;
        if all(x, gt) | all(x, lt) | all(y, gt) | all(y, lt) {
            return Hits::default();
        }

        // f(u) = a + b u + c u² (see `patch`), with exact end signs s0 = sign f(0),
        // s1 = sign f(1).
        let (a, s0) = edge_sign([x[0], y[0]], [x[3], y[3]]);
        let (f1, s1) = edge_sign([x[1], y[1]], [x[2], y[2]]);
        let e10 = [x[1] - x[0], y[1] - y[0]];
        let d1 = [x[2] - x[3], y[2] - y[3]];
        let c = cross2(e10, d1);
        let b = f1 - a - c;
        if (s0 == 0) | (s1 == 0) | (c == zero) {
            return general();
        }
        let ac4 = small::<F>(4) * a * c;
        let bb = b * b;
        let disc = bb - ac4;
        let crossing = s0 != s1;
        if disc < zero || disc.is_nan() {
            // No real root: a miss when the end signs agree, unless the discriminant is
            // within rounding of zero (or NaN).
            let none = disc < -small::<F>(8) * F::epsilon() * (bb + ac4.abs());
            return if none && !crossing {
                Hits::default()
            } else {
                general()
            };
        }
        let close = disc * small::<F>(64) < bb;
        let root = disc.sqrt();
        let q = -(b + if b < zero { -root } else { root }) / (one + one);
        let (r0, r1) = (q / c, a / q);
        let (lo, hi) = if r0 <= r1 { (r0, r1) } else { (r1, r0) };
        let near = F::epsilon().sqrt();
        let at_end = |u: F| (u.abs() <= near) | ((u - one).abs() <= near);
        let (in_lo, in_hi) = ((lo > zero) & (lo < one), (hi > zero) & (hi < one));
        // The common case ends here: a double root at 0 (q = 0), close roots or an
        // ill-conditioned root (a Newton step follows), a root within √ε of u = 0 or 1, or a
        // root count of the wrong parity go to the general path.
        let (pa, p1, pc) = (
            crate::patch::cross_size([x[0], y[0]], [x[3], y[3]]),
            crate::patch::cross_size([x[1], y[1]], [x[2], y[2]]),
            crate::patch::cross_size(e10, d1),
        );
        let ill = |u: F, inside: bool| inside && crate::patch::ill_conditioned(pa, p1, pc, b, c, u);
        if (q == zero)
            | close
            | at_end(lo)
            | at_end(hi)
            | ((in_lo != in_hi) != crossing)
            | ill(lo, in_lo)
            | ill(hi, in_hi)
        {
            return general();
        }
        let mut out = Hits::default();
        if !(in_lo | in_hi) {
            return out;
        }
        // max |x|, |y| over the corners (as the general path), as a tree: no serial chain.
        let mx = |v: [F; 4]| (v[0].abs().max(v[1].abs())).max(v[2].abs().max(v[3].abs()));
        let m = mx(x).max(mx(y)).max(zero);
        let rung_tol = small::<F>(4) * F::epsilon() * m;
        for (u, keep) in [(lo, in_lo), (hi, in_hi)] {
            if keep && let Some(h) = root_hit(&corners, e10, d1, u, false, rung_tol, t_min, t_max) {
                out.push(h);
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
    fn round_trips_the_corners() {
        let c = [
            [0.0f64, 0.1, 0.2],
            [1.0, 0.3, 0.4],
            [1.1, 1.2, 0.5],
            [0.1, 0.9, 0.6],
        ];
        assert_eq!(PreparedPatch::new(c).patch().corners(), c);
        assert_eq!(PreparedPatch::from(Patch::new(c)), PreparedPatch::new(c));
    }

    /// The fast path against the general path (the pre-existing algorithm, which handles
    /// every case) on the same ray-space corners: identical hits, bit for bit. Patches are
    /// random, near-planar, or with a collapsed edge; rays are aimed at random points, at
    /// corners and along edges, at magnitudes 1e-6, 1 and 1e6; f32 and f64.
    fn fast_matches_general<F: Float + core::fmt::Debug>(
        cast: fn(f64) -> F,
        count: usize,
    ) -> usize {
        let mut r = crate::fixtures::uniform(0x5eed_0fc0_01da_7a00);
        let mut fast_only = 0;
        for k in 0..count {
            let m = [1e-6, 1.0, 1e6][k % 3];
            let flat = [1.0, 1e-4, 0.0][(k / 3) % 3];
            let mut c = [[0.0; 3]; 4];
            let base = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
            for (q, b) in c.iter_mut().zip(base) {
                *q = [b[0] + 0.3 * r(), b[1] + 0.3 * r(), flat * r()];
            }
            if k % 7 == 0 {
                c[3] = c[0]; // collapsed u = 0 edge (a triangle)
            }
            let (u, v) = match k % 5 {
                0 => (0.0, 0.0),             // a corner
                1 => (0.5 * r() + 0.5, 0.0), // the v = 0 edge
                2 => (1.0, 0.5 * r() + 0.5), // the u = 1 edge
                _ => (0.7 * r() + 0.5, 0.7 * r() + 0.5),
            };
            let lerp =
                |a: [f64; 3], b: [f64; 3], s: f64| [0, 1, 2].map(|i| a[i] + s * (b[i] - a[i]));
            let target = lerp(lerp(c[0], c[1], u), lerp(c[3], c[2], u), v);
            let dir = [0.4 * r(), 0.4 * r(), -1.0];
            let origin = [0, 1, 2].map(|i| (target[i] - 2.0 * dir[i]) * m);
            let corners = c.map(|q| q.map(|x| cast(x * m)));
            let Some(ray) = Ray::new(origin.map(cast), dir.map(|x| cast(x * m))) else {
                continue;
            };
            for (lo, hi) in [(F::neg_infinity(), F::infinity()), (F::zero(), cast(3.0))] {
                let fast = PreparedPatch::new(corners).intersect_ray(&ray, lo, hi);
                let general = intersect_in_ray_space(corners.map(|q| ray.transform(q)), lo, hi);
                assert_eq!(fast, general, "case {k}: {corners:?} {ray:?}");
                fast_only += usize::from(!fast.is_empty());
            }
        }
        fast_only
    }

    #[test]
    fn fast_path_matches_general_path_bit_for_bit() {
        // Many of the 6000 queries hit (about 2750: every ray is aimed at the patch, half of
        // them at its boundary, where the symbolic tie-break may put them outside), so the
        // comparison is not vacuous.
        assert!(fast_matches_general::<f64>(|x| x, 3000) > 2000);
        assert!(fast_matches_general::<f32>(|x| x as f32, 3000) > 2000);
    }

    #[test]
    fn same_hits_as_the_patch_on_a_saddle() {
        let c = crate::fixtures::SADDLE;
        let (o, d) = ([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0]);
        let p = PreparedPatch::new(c).intersect(o, d, 0.0, f64::INFINITY);
        assert_eq!(p.len(), 2);
        assert_eq!(p, Patch::new(c).intersect(o, d, 0.0, f64::INFINITY));
    }
}
