//! Triangle-level culling before traversal (Munkberg 2011, §3): conservative back-face
//! culling of a moving triangle and temporal view-frustum culling in 2DH.

use num_traits::Float;

use crate::interval::{TimeInterval, linear_nonpositive, lit};

/// Which windings a moving triangle can show during the shutter, from the sign of its 2DH
/// determinant det[p₀(t); p₁(t); p₂(t)] (edge-eqn's `orientation_at`: positive is
/// front-facing).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facing {
    /// det(t) > 0 for every t in [0, 1] (with a rounding margin): front-facing throughout.
    Front,
    /// det(t) < 0 for every t in [0, 1] (with a rounding margin): back-facing throughout.
    Back,
    /// The sign may change, or the triangle is (nearly) degenerate.
    Mixed,
}

impl Facing {
    /// The edge-function signs σ that a covered sample in front of the eye can have:
    /// `[σ = +1 (all e ≤ 0), σ = −1 (all e ≥ 0)]`.
    #[inline]
    pub fn windings(self) -> [bool; 2] {
        match self {
            Facing::Front => [true, false],
            Facing::Back => [false, true],
            Facing::Mixed => [true, true],
        }
    }
}

fn det3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> (f64, f64) {
    // a · (b × c) and the sum of the absolute values of its six products.
    let t = [
        a[0] * b[1] * c[2],
        -a[0] * b[2] * c[1],
        a[1] * b[2] * c[0],
        -a[1] * b[0] * c[2],
        a[2] * b[0] * c[1],
        -a[2] * b[1] * c[0],
    ];
    (t.iter().sum(), t.iter().map(|v| v.abs()).sum())
}

/// The Bernstein coefficients (times 3 for the middle two) of the cubic
/// det[p₀(t); p₁(t); p₂(t)] with p_i(t) = (1 − t) q_i + t r_i, and a rounding margin for
/// each. The determinant is trilinear in the three vertices, so its blossom gives
/// b_k = (Σ over vertex sets S with |S| = k of det with r for i ∈ S and q otherwise) / C(3, k)
/// (Munkberg and Akenine-Möller 2011, back-face culling of motion-blurred triangles).
/// Computed in f64 from the `F` input.
pub fn orientation_bernstein<F: Float>(q: &[[F; 3]; 3], r: &[[F; 3]; 3]) -> ([f64; 4], [f64; 4]) {
    let cv = |v: &[F; 3]| v.map(|c| c.to_f64().unwrap_or(f64::NAN));
    let (q, r) = (q.each_ref().map(cv), r.each_ref().map(cv));
    let mut b = [0.0; 4];
    let mut m = [0.0; 4];
    for mask in 0u32..8 {
        let pick = |i: usize| if mask >> i & 1 == 1 { r[i] } else { q[i] };
        let (d, a) = det3(pick(0), pick(1), pick(2));
        let k = mask.count_ones() as usize;
        b[k] += d;
        m[k] += a;
    }
    (b, m)
}

/// Conservative facing of a moving triangle: `Front` (`Back`) only when every Bernstein
/// coefficient of the orientation cubic is positive (negative) by more than a rounding
/// margin of `256 ε_F` times the magnitude of its terms. By the convex-hull property of the
/// Bernstein basis the cubic then has that sign on all of [0, 1]. Non-finite input is `Mixed`.
pub fn facing<F: Float>(q: &[[F; 3]; 3], r: &[[F; 3]; 3]) -> Facing {
    facing_with_margin(q, r, facing_margin::<F>())
}

/// The relative rounding margin of [`facing`] for input of type `F`: `256 ε_F`.
#[inline]
pub(crate) fn facing_margin<F: Float>() -> f64 {
    F::epsilon().to_f64().unwrap_or(1e-7) * 256.0
}

/// [`facing`] with the relative margin `eps` instead of `F`'s.
pub(crate) fn facing_with_margin<F: Float>(q: &[[F; 3]; 3], r: &[[F; 3]; 3], eps: f64) -> Facing {
    let (b, m) = orientation_bernstein(q, r);
    if b.iter().chain(m.iter()).any(|v| !v.is_finite()) {
        return Facing::Mixed;
    }
    if b.iter().zip(&m).all(|(b, m)| *b > eps * m) {
        Facing::Front
    } else if b.iter().zip(&m).all(|(b, m)| *b < -eps * m) {
        Facing::Back
    } else {
        Facing::Mixed
    }
}

/// True when the triangle is back-facing for the whole shutter and may be culled
/// (Munkberg 2011, §3: reject only triangles back-facing during all of [0, 1]).
#[inline]
pub fn is_backfacing<F: Float>(q: &[[F; 3]; 3], r: &[[F; 3]; 3]) -> bool {
    facing(q, r) == Facing::Back
}

/// Rounding margin for a plane distance n · p computed in `F`.
#[inline]
pub(crate) fn plane_margin<F: Float>(n: [F; 3], p: [F; 3]) -> F {
    let s = n[0].abs() * p[0].abs() + n[1].abs() * p[1].abs() + n[2].abs() * p[2].abs();
    s * F::epsilon() * lit(64.0)
}

/// The five planes n · (x, y, w) ≤ 0 of the view frustum of a `width` x `height` pixel
/// screen: x ≥ 0, x ≤ width·w, y ≥ 0, y ≤ height·w, and w ≥ 0 (the eye plane).
pub fn frustum_planes<F: Float>(width: F, height: F) -> [[F; 3]; 5] {
    let (o, z) = (F::one(), F::zero());
    [
        [-o, z, z],
        [o, z, -width],
        [z, -o, z],
        [z, o, -height],
        [z, z, -o],
    ]
}

/// Temporal view-frustum culling (Munkberg 2011, §3): the time interval `[t_s, t_e]` in
/// which the moving triangle may be inside the view frustum of a `width` x `height` screen.
/// Each vertex moves on a line in 2DH; for each frustum plane the triangle can only be inside
/// while at least one vertex is, so the result is ∩_planes hull_vertices {t : n · p_i(t) ≤ 0},
/// evaluated with a rounding margin and widened by a few ulps. Empty means "cull".
pub fn frustum_interval<F: Float>(
    q: &[[F; 3]; 3],
    r: &[[F; 3]; 3],
    width: F,
    height: F,
) -> TimeInterval<F> {
    let mut iv = TimeInterval::full();
    for n in frustum_planes(width, height) {
        let mut plane = TimeInterval::empty();
        for i in 0..3 {
            let d = |p: [F; 3]| n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - plane_margin(n, p);
            plane = plane.hull(linear_nonpositive(d(q[i]), d(r[i])));
        }
        iv = iv.intersect(plane);
        if iv.is_empty() {
            return TimeInterval::empty();
        }
    }
    iv.widened(F::epsilon() * lit(8.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn static_ccw_is_front_and_reversed_is_back() {
        let p = [[0.0f64, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 4.0, 1.0]];
        assert_eq!(facing(&p, &p), Facing::Front);
        let rev = [p[0], p[2], p[1]];
        assert_eq!(facing(&rev, &rev), Facing::Back);
        // Flipping during the shutter is mixed.
        assert_eq!(facing(&p, &rev), Facing::Mixed);
    }

    #[test]
    fn triangle_behind_the_eye_is_frustum_culled() {
        let q = [[1.0f32, 1.0, -1.0], [5.0, 1.0, -1.0], [1.0, 5.0, -2.0]];
        assert!(frustum_interval(&q, &q, 64.0, 64.0).is_empty());
    }
}
