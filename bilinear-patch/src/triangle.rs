//! Ray vs triangle: the watertight test of Woop, Benthin and Wald 2013 (used for the prism
//! caps), and the Möller-Trumbore test (1997) as the classic non-watertight baseline.

use num_traits::Float;

use crate::orient::edge_sign;
use crate::ray::Ray;

/// A ray/triangle hit: ray parameter `t` and barycentrics `(u, v)` with the hit point
/// `(1 - u - v) p0 + u p1 + v p2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit<F> {
    /// Ray parameter of the hit.
    pub t: F,
    /// Barycentric weight of `p1`.
    pub u: F,
    /// Barycentric weight of `p2`.
    pub v: F,
}

/// A triangle `[p0, p1, p2]` for the watertight ray test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle<F> {
    vertices: [[F; 3]; 3],
}

impl<F: Float> Triangle<F> {
    /// Triangle with vertices `[p0, p1, p2]`.
    pub fn new(vertices: [[F; 3]; 3]) -> Self {
        Triangle { vertices }
    }

    /// The vertices `[p0, p1, p2]`.
    pub fn vertices(&self) -> [[F; 3]; 3] {
        self.vertices
    }

    /// Watertight hit of the ray `origin + t * dir` with `t_min <= t <= t_max`
    /// (Woop, Benthin and Wald 2013). Non-finite input gives `None`.
    pub fn intersect(
        &self,
        origin: [F; 3],
        dir: [F; 3],
        t_min: F,
        t_max: F,
    ) -> Option<TriangleHit<F>> {
        self.intersect_ray(&Ray::new(origin, dir)?, t_min, t_max)
    }

    /// As [`Triangle::intersect`] for a prepared [`Ray`].
    ///
    /// Woop et al. 2013: the vertices are moved into ray space, where the three edge
    /// functions at the origin are the unnormalised barycentrics. Their signs are exact and a
    /// zero is broken by a symbolic perturbation of the ray (see the crate doc), so a ray
    /// through an edge or vertex shared by several faces of a closed mesh is counted by
    /// exactly the faces it crosses: no leak and no double count. Faces of both orientations
    /// are hit; a face seen edge-on or with a zero-length edge is never hit.
    pub fn intersect_ray(&self, ray: &Ray<F>, t_min: F, t_max: F) -> Option<TriangleHit<F>> {
        let [a, b, c] = self.vertices.map(|p| ray.transform(p));
        let (e0, s0) = edge_sign([b[0], b[1]], [c[0], c[1]]);
        let (e1, s1) = edge_sign([c[0], c[1]], [a[0], a[1]]);
        let (e2, s2) = edge_sign([a[0], a[1]], [b[0], b[1]]);
        if s0 == 0 || s0 != s1 || s1 != s2 {
            return None;
        }
        let det = e0 + e1 + e2;
        if det == F::zero() {
            return None;
        }
        let inv = det.recip();
        let clamp = |x: F| x.max(F::zero()).min(F::one());
        let (w0, w1, w2) = (clamp(e0 * inv), clamp(e1 * inv), clamp(e2 * inv));
        let t = (e0 * a[2] + e1 * b[2] + e2 * c[2]) * inv;
        (t.is_finite() && t >= t_min && t <= t_max && (w0 + w1 + w2).is_finite())
            .then_some(TriangleHit { t, u: w1, v: w2 })
    }
}

/// Möller and Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection": the classic
/// test, kept as the baseline the patch test is benchmarked against. It is not watertight: a
/// ray through a shared edge may hit both faces or neither. Same as
/// [`MollerTrumbore::new`]`(*tri).intersect(..)`.
pub fn moller_trumbore<F: Float>(
    tri: &[[F; 3]; 3],
    origin: [F; 3],
    dir: [F; 3],
    t_min: F,
    t_max: F,
) -> Option<TriangleHit<F>> {
    MollerTrumbore::new(*tri).intersect(origin, dir, t_min, t_max)
}

/// A triangle prepared for the Möller-Trumbore test: the vertex p0 and the edges
/// e1 = p1 - p0, e2 = p2 - p0 precomputed (the "prepared" baseline of the benchmark, as a
/// BVH leaf would store it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MollerTrumbore<F> {
    p0: [F; 3],
    e1: [F; 3],
    e2: [F; 3],
}

#[inline]
fn sub3<F: Float>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
fn cross3<F: Float>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
fn dot3<F: Float>(a: [F; 3], b: [F; 3]) -> F {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl<F: Float> MollerTrumbore<F> {
    /// Prepares the triangle `[p0, p1, p2]`.
    pub fn new(tri: [[F; 3]; 3]) -> Self {
        let [p0, p1, p2] = tri;
        MollerTrumbore {
            p0,
            e1: sub3(p1, p0),
            e2: sub3(p2, p0),
        }
    }

    /// Hit of the ray `origin + t * dir` with `t_min <= t <= t_max` (Möller and Trumbore
    /// 1997); `(u, v)` are the barycentric weights of p1 and p2. Not watertight.
    #[inline]
    pub fn intersect(
        &self,
        origin: [F; 3],
        dir: [F; 3],
        t_min: F,
        t_max: F,
    ) -> Option<TriangleHit<F>> {
        let (e1, e2) = (self.e1, self.e2);
        let pv = cross3(dir, e2);
        let det = dot3(e1, pv);
        if det == F::zero() {
            return None;
        }
        let inv = det.recip();
        let tv = sub3(origin, self.p0);
        let u = dot3(tv, pv) * inv;
        if !(u >= F::zero() && u <= F::one()) {
            return None;
        }
        let qv = cross3(tv, e1);
        let v = dot3(dir, qv) * inv;
        if !(v >= F::zero() && u + v <= F::one()) {
            return None;
        }
        let t = dot3(e2, qv) * inv;
        (t.is_finite() && t >= t_min && t <= t_max).then_some(TriangleHit { t, u, v })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_tests_agree_on_a_plain_hit() {
        let tri = [[0.0f64, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let o = [0.25, 0.5, 1.0];
        let d = [0.0, 0.0, -2.0];
        let w = Triangle::new(tri).intersect(o, d, 0.0, 10.0).expect("hit");
        let m = moller_trumbore(&tri, o, d, 0.0, 10.0).expect("hit");
        assert_eq!(
            w,
            TriangleHit {
                t: 0.5,
                u: 0.25,
                v: 0.5
            }
        );
        assert_eq!(m, w);
    }

    #[test]
    fn misses_outside_and_behind() {
        let tri = Triangle::new([[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert!(
            tri.intersect([0.75, 0.75, 1.0], [0.0, 0.0, -1.0], 0.0, 10.0)
                .is_none()
        );
        assert!(
            tri.intersect([0.25, 0.25, 1.0], [0.0, 0.0, 1.0], 0.0, 10.0)
                .is_none()
        );
    }
}
