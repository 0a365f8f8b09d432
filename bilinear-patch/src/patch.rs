//! Ray vs bilinear patch (Reshetov 2019, "Cool Patches", Ray Tracing Gems ch. 8), made
//! watertight along the four boundary edges.
//!
//! The patch is Q(u, v) = lerp(lerp(q00, q10, u), lerp(q01, q11, u), v). In ray space (see
//! [`Ray`]) the ray is the z axis, and the hit condition is that the projected patch point
//! P(u, v) is the origin. For fixed u the points P(u, ·) form the straight "rung" from
//! P(u, 0) to P(u, 1); the ray meets that rung's line exactly when the 2D edge function
//!
//! f(u) = cross(P(u, 0), P(u, 1))
//!
//! vanishes (Reshetov 2019: the distance from the ray to the u-isoline). f is a quadratic
//! in u, and f(0), f(1) are the edge functions of the patch edges u = 0 and u = 1. Those two
//! signs are computed exactly (see `orient`), so the parity of the number of roots in [0, 1]
//! is decided exactly: that is what makes neighbouring patches agree about a ray through a
//! shared u-edge. The v-boundary is decided the same way through the identities
//!
//! cross(q00', q10') = v · cross(q10' - q00', B(u)),
//! cross(q01', q11') = (v - 1) · cross(q11' - q01', B(u)),
//!
//! which hold at a hit (u, v) with q' the ray-space corners and B(u) = P(u, 1) - P(u, 0).
//! Within √ε of v = 0 (v = 1) the sign of v (of v - 1) is taken as the exact sign of the
//! edge function of that edge times the sign of the factor, which there vanishes only where
//! the projected patch folds over at the edge; farther away the computed v decides (the
//! factor may vanish there together with the edge function, when the ray meets the line of
//! the edge outside the patch).

use arrayvec::ArrayVec;
use core::ops::Deref;
use num_traits::Float;

use crate::orient::{cross2, edge_sign, sign};
use crate::prepared::PreparedPatch;
use crate::ray::Ray;

/// One intersection of a ray with a patch: ray parameter `t` and patch parameters `(u, v)`
/// in [0, 1]², with the hit point `origin + t * dir = Q(u, v)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit<F> {
    /// Ray parameter of the hit.
    pub t: F,
    /// Patch parameter along q00 → q10 (and q01 → q11).
    pub u: F,
    /// Patch parameter along q00 → q01 (and q10 → q11).
    pub v: F,
}

/// Up to two hits of a ray with a bilinear patch, sorted by `t` (Reshetov 2019: a ray meets
/// a non-planar bilinear patch at most twice). Dereferences to `&[Hit<F>]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Hits<F>(ArrayVec<Hit<F>, 2>);

impl<F> Default for Hits<F> {
    fn default() -> Self {
        Hits(ArrayVec::new())
    }
}

impl<F> Deref for Hits<F> {
    type Target = [Hit<F>];
    fn deref(&self) -> &[Hit<F>] {
        &self.0
    }
}

impl<F> Hits<F> {
    /// The hits as a fixed-capacity vector.
    pub fn into_inner(self) -> ArrayVec<Hit<F>, 2> {
        self.0
    }
}

/// A bilinear patch given by its corners q00, q10, q11, q01 (in that order: around the
/// boundary). Any four points are allowed: non-planar, planar, or degenerate with coincident
/// corners (a triangle or a segment).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch<F> {
    corners: [[F; 3]; 4],
}

impl Patch<f32> {
    /// Patch from glam corners `[q00, q10, q11, q01]`.
    pub fn from_vec3(c: [glam::Vec3; 4]) -> Self {
        Patch::new(c.map(|p| p.to_array()))
    }
}

impl Patch<f64> {
    /// Patch from glam corners `[q00, q10, q11, q01]`.
    pub fn from_dvec3(c: [glam::DVec3; 4]) -> Self {
        Patch::new(c.map(|p| p.to_array()))
    }
}

#[inline]
pub(crate) fn lerp<F: Float>(a: F, b: F, s: F) -> F {
    a + s * (b - a)
}

#[inline]
pub(crate) fn lerp3<F: Float>(a: [F; 3], b: [F; 3], s: F) -> [F; 3] {
    [
        lerp(a[0], b[0], s),
        lerp(a[1], b[1], s),
        lerp(a[2], b[2], s),
    ]
}

#[inline]
pub(crate) fn xy<F: Copy>(p: [F; 3]) -> [F; 2] {
    [p[0], p[1]]
}

#[inline]
pub(crate) fn sub2<F: Float>(a: [F; 3], b: [F; 3]) -> [F; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

#[inline]
pub(crate) fn small<F: Float>(n: u8) -> F {
    F::from(n).unwrap_or_else(F::one)
}

impl<F: Float> Patch<F> {
    /// Patch with corners `[q00, q10, q11, q01]` (Reshetov 2019 naming).
    pub fn new(corners: [[F; 3]; 4]) -> Self {
        Patch { corners }
    }

    /// The corners `[q00, q10, q11, q01]`.
    pub fn corners(&self) -> [[F; 3]; 4] {
        self.corners
    }

    /// The surface point Q(u, v) = lerp(lerp(q00, q10, u), lerp(q01, q11, u), v).
    pub fn point(&self, u: F, v: F) -> [F; 3] {
        let [q00, q10, q11, q01] = self.corners;
        lerp3(lerp3(q00, q10, u), lerp3(q01, q11, u), v)
    }

    /// All hits of the ray `origin + t * dir` with `t_min <= t <= t_max`, sorted by `t`.
    ///
    /// A ray tangent to the surface gives a double hit (two equal entries). Rays that meet
    /// the patch in a whole segment (lying in a planar patch, or along a degenerate edge)
    /// report no hit. Non-finite input, a zero direction or NaN bounds give an empty result;
    /// the bounds may be infinite.
    pub fn intersect(&self, origin: [F; 3], dir: [F; 3], t_min: F, t_max: F) -> Hits<F> {
        match Ray::new(origin, dir) {
            Some(ray) => self.intersect_ray(&ray, t_min, t_max),
            None => Hits::default(),
        }
    }

    /// As [`Patch::intersect`], for a prepared [`Ray`] (share it across the faces of a mesh to
    /// get watertight decisions on shared edges).
    pub fn intersect_ray(&self, ray: &Ray<F>, t_min: F, t_max: F) -> Hits<F> {
        // The corners are laid out by axis on the fly (a dozen moves); the common case then
        // runs branch-light and the rest falls back to `intersect_in_ray_space`.
        PreparedPatch::new(self.corners).intersect_ray(ray, t_min, t_max)
    }
}

/// The ray/patch test on the corners `[p00, p10, p11, p01]` already moved into ray space
/// (the ray is the +z axis from the origin; z is the ray parameter). This is the general
/// path that handles every case; [`crate::PreparedPatch`] runs a branch-light version of the
/// common case and falls back to it (hence cold: 4 of 1024 random rays distributed as in `benches/ray_patch.rs` take it).
#[cold]
#[inline(never)]
pub(crate) fn intersect_in_ray_space<F: Float>(
    corners: [[F; 3]; 4],
    t_min: F,
    t_max: F,
) -> Hits<F> {
    let mut out = Hits::default();
    let [p00, p10, p11, p01] = corners;
    // The projected patch lies in the convex hull of its corners: reject when all four
    // lie strictly on one side of an axis through the origin (exact comparisons, so
    // the symbolic perturbation cannot change the outcome).
    let z = F::zero();
    let ps = corners;
    if ps.iter().all(|p| p[0] > z)
        || ps.iter().all(|p| p[0] < z)
        || ps.iter().all(|p| p[1] > z)
        || ps.iter().all(|p| p[1] < z)
    {
        return out;
    }

    // f(u) = a + b u + c u^2 = cross(P(u,0), P(u,1)); f(0) and f(1) are the edge
    // functions of edges u = 0 and u = 1, with exact signs s0, s1.
    let (a, s0) = edge_sign(xy(p00), xy(p01));
    let (f1, s1) = edge_sign(xy(p10), xy(p11));
    let e10 = sub2(p10, p00);
    let d1 = sub2(p11, p01);
    let c = cross2(e10, d1);
    let b = f1 - a - c;
    let (roots, close) = solve_quadratic(a, b, c);
    let (pa, p1, pc) = (
        cross_size(xy(p00), xy(p01)),
        cross_size(xy(p10), xy(p11)),
        cross_size(e10, d1),
    );
    // Width of the band around the parameter bounds where exact rules decide; computed
    // parameters are far more accurate than this unless the hit is nearly tangent.
    let near = F::epsilon().sqrt();
    let us = match clear_roots(&roots, s0, s1, near) {
        Some(us) => us,
        None => select_roots(roots, s0, s1, a, b, c),
    };
    if us.is_empty() {
        return out;
    }

    let m = ps
        .iter()
        .fold(F::zero(), |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let rung_tol = small::<F>(4) * F::epsilon() * m;
    for u in us {
        let close = close || ill_conditioned(pa, p1, pc, b, c, u);
        if let Some(h) = root_hit(&corners, e10, d1, u, close, rung_tol, t_min, t_max) {
            out.0.push(h);
        }
    }
    out.sort();
    out
}

impl<F: Float> Hits<F> {
    /// Puts two hits in order of `t` (the second first only when its `t` is smaller).
    #[inline]
    pub(crate) fn sort(&mut self) {
        if let [h0, h1] = self.0.as_mut_slice()
            && h1.t < h0.t
        {
            core::mem::swap(h0, h1);
        }
    }

    /// Appends a hit (callers push at most one per root of the quadratic, so at most two).
    #[inline]
    pub(crate) fn push(&mut self, h: Hit<F>) {
        let _ = self.0.try_push(h);
    }
}

/// The hit of the ray with the rung at the root `u` of f, if the crossing lies on the patch
/// (v in [0, 1]) and in [t_min, t_max]. `e10 = p10 - p00`, `d1 = p11 - p01` (ray-space xy),
/// `close` says the roots are close (a nearly tangent ray, where one Newton step restores
/// accuracy), `rung_tol` is the length below which a rung counts as parallel to the ray.
///
/// The decisions v >= 0 and v <= 1 are made on the numerator and denominator of v, so the
/// division is paid only for an actual hit (Reshetov 2019 delays it the same way). Within
/// √ε of v = 0 (v = 1) the sign of v (of v - 1) is the exact sign of the edge function of
/// that edge times the sign of the factor of the identity (see the module doc); away from
/// it the factor may vanish with the edge function (the origin on the line of that edge),
/// and the computed v decides.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn root_hit<F: Float>(
    corners: &[[F; 3]; 4],
    e10: [F; 2],
    d1: [F; 2],
    u: F,
    close: bool,
    rung_tol: F,
    t_min: F,
    t_max: F,
) -> Option<Hit<F>> {
    let [p00, p10, p11, p01] = *corners;
    let pa = lerp3(p00, p10, u);
    let pb = lerp3(p01, p11, u);
    let bv = [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]];
    let bb = bv[0] * bv[0] + bv[1] * bv[1];
    // A rung parallel to the ray has no isolated crossing (spurious root of f). Also false
    // for NaN.
    if bb.partial_cmp(&(rung_tol * rung_tol)) != Some(core::cmp::Ordering::Greater) {
        return None;
    }
    // v = n / bb with bb > 0.
    let n = -(pa[0] * bv[0] + pa[1] * bv[1]);
    let near = F::epsilon().sqrt();
    let band = near * bb;
    let ge0 = if n.abs() > band {
        n > F::zero()
    } else {
        edge_decision(xy(p00), xy(p10), e10, xy(bv), n / bb >= F::zero(), 1)
    };
    let le1 = if (n - bb).abs() > band {
        n < bb
    } else {
        edge_decision(xy(p01), xy(p11), d1, xy(bv), n / bb <= F::one(), -1)
    };
    if !(ge0 && le1) {
        return None;
    }
    let v_num = n / bb;
    let (u, v, t) = if close {
        let (u, v) = refine(p00, p10, p11, p01, u, v_num);
        let (za, zb) = (lerp(p00[2], p10[2], u), lerp(p01[2], p11[2], u));
        (u, v, za + v * (zb - za))
    } else {
        let v = v_num.max(F::zero()).min(F::one());
        (u, v, pa[2] + v * bv[2])
    };
    (t >= t_min && t <= t_max && t.is_finite() && u.is_finite() && v.is_finite()).then_some(Hit {
        t,
        u,
        v,
    })
}

/// Decision for a hit within `near` of the patch edge a → b (v = 0 with `want` = 1, or
/// v = 1 with `want` = -1): the exact sign of the edge function times the sign of the factor
/// cross(e, B(u)) of the identity, unless the factor is within rounding of zero (a fold of
/// the projected patch at the edge) or the edge is degenerate, where `numeric` decides.
#[cold]
#[inline(never)]
pub(crate) fn edge_decision<F: Float>(
    a: [F; 2],
    b: [F; 2],
    e: [F; 2],
    bv: [F; 2],
    numeric: bool,
    want: i8,
) -> bool {
    let (_, se) = edge_sign(a, b);
    let l = cross2(e, bv);
    let tol = small::<F>(4) * F::epsilon() * ((e[0] * bv[1]).abs() + (e[1] * bv[0]).abs());
    if se != 0 && l.abs() > tol {
        se * sign(l) == want
    } else {
        numeric
    }
}

/// The common case of root selection: both u-edges proper (s0, s1 != 0), no root within
/// `near` of 0 or 1, and the count in [0, 1] of the parity the end signs require. `None`
/// sends the roots to [`select_roots`].
#[inline]
pub(crate) fn clear_roots<F: Float>(
    roots: &ArrayVec<F, 2>,
    s0: i8,
    s1: i8,
    near: F,
) -> Option<ArrayVec<F, 2>> {
    if s0 == 0 || s1 == 0 {
        return None;
    }
    let mut out = ArrayVec::new();
    for &u in roots {
        if u.abs() <= near || (u - F::one()).abs() <= near {
            return None;
        }
        if u > F::zero() && u < F::one() {
            out.push(u);
        }
    }
    ((out.len() % 2 == 1) == (s0 != s1)).then_some(out)
}

/// Whether the root `u` of f(u) = a + b u + c u² is ill-conditioned: the rounding error of
/// f at u, bounded from the magnitudes of the products the coefficients were computed from
/// (`pa` for a = f(0), `p1` for f(1), `pc` for c; b = f(1) - a - c inherits all three), is
/// more than 64 ulps' worth of |f'(u)|: u may then carry more than ~64 ulps of error and v
/// (which can depend steeply on u) needs the Newton step of [`refine`].
#[inline]
pub(crate) fn ill_conditioned<F: Float>(pa: F, p1: F, pc: F, b: F, c: F, u: F) -> bool {
    let u = u.abs();
    let size = pa + u * (pa + p1 + pc) + pc * u * u;
    let slope = (b + (c + c) * u).abs();
    // NaN counts as ill-conditioned (the Newton step guards itself).
    !matches!(
        size.partial_cmp(&(small::<F>(64) * slope)),
        Some(core::cmp::Ordering::Less | core::cmp::Ordering::Equal)
    )
}

/// Sum of the absolute products of the 2D cross product of `p` and `q` (its rounding scale).
#[inline]
pub(crate) fn cross_size<F: Float>(p: [F; 2], q: [F; 2]) -> F {
    (p[0] * q[1]).abs() + (p[1] * q[0]).abs()
}

/// One Newton step on the 2D system P(u, v) = 0 in ray space, then clamping to [0, 1]².
/// The quadratic's root u loses accuracy when the two roots are close (a nearly tangent
/// ray) even where the 2D system itself is well conditioned; one step restores it, so it is
/// taken only for close roots. The step
/// is skipped where the Jacobian is nearly singular or the step exceeds ε^(1/4).
#[inline]
pub(crate) fn refine<F: Float>(
    p00: [F; 3],
    p10: [F; 3],
    p11: [F; 3],
    p01: [F; 3],
    u: F,
    v: F,
) -> (F, F) {
    let pa = [lerp(p00[0], p10[0], u), lerp(p00[1], p10[1], u)];
    let pb = [lerp(p01[0], p11[0], u), lerp(p01[1], p11[1], u)];
    let pv = [pb[0] - pa[0], pb[1] - pa[1]];
    let p = [pa[0] + v * pv[0], pa[1] + v * pv[1]];
    let bottom = [p10[0] - p00[0], p10[1] - p00[1]];
    let top = [p11[0] - p01[0], p11[1] - p01[1]];
    let pu = [lerp(bottom[0], top[0], v), lerp(bottom[1], top[1], v)];
    let det = cross2(pu, pv);
    let du = -cross2(p, pv) / det;
    let dv = -cross2(pu, p) / det;
    // Only a small step from a well-conditioned Jacobian: near a tangent ray (a double
    // root) the quadratic's solution is as good as it gets.
    let limit = F::epsilon().sqrt().sqrt();
    let size = (pu[0].abs() + pu[1].abs()) * (pv[0].abs() + pv[1].abs());
    let good = det.abs() > limit * size && du.abs() < limit && dv.abs() < limit;
    let (u, v) = if good { (u + du, v + dv) } else { (u, v) };
    let clamp = |x: F| x.max(F::zero()).min(F::one());
    (clamp(u), clamp(v))
}

/// Real roots of a + b u + c u² in ascending order, numerically stable; a discriminant within
/// rounding error of zero gives a double root (a tangent ray). The flag
/// tells whether the roots are close (discriminant below b²/64), where they lose accuracy.
pub(crate) fn solve_quadratic<F: Float>(a: F, b: F, c: F) -> (ArrayVec<F, 2>, bool) {
    let mut r = ArrayVec::new();
    if c == F::zero() {
        if b != F::zero() {
            r.push(-a / b);
        }
        return (r, false);
    }
    let four = small::<F>(4);
    let ac4 = four * a * c;
    let bb = b * b;
    let mut disc = bb - ac4;
    if disc < F::zero() {
        if disc < -small::<F>(8) * F::epsilon() * (bb + ac4.abs()) {
            return (r, false);
        }
        disc = F::zero();
    }
    let close = disc * small::<F>(64) < bb;
    let root = disc.sqrt();
    let q = -(b + if b < F::zero() { -root } else { root }) / (F::one() + F::one());
    if q == F::zero() {
        // b = 0 and disc = 0, so a = 0: double root at 0.
        r.push(F::zero());
        r.push(F::zero());
        return (r, true);
    }
    let (x, y) = (q / c, a / q);
    if x <= y {
        r.push(x);
        r.push(y);
    } else {
        r.push(y);
        r.push(x);
    }
    (r, close)
}

/// Root of the (deflated) polynomial from its coefficients (a, b, c), the rare fallback.
type Secant<F> = fn(F, F, F) -> F;

/// Chooses the roots u in [0, 1] of f(u) = a + b u + c u², enforcing the parity that the
/// exact end signs s0 = sign f(0), s1 = sign f(1) imply. A degenerate end (s = 0: the rung
/// there has length zero in ray space) carries a spurious root of f, which is divided out
/// first: with s0 = 0, f = u (b + c u); with s1 = 0, f = (u - 1)(c u - a). The parity then
/// comes from the sign change of the remaining linear factor over [0, 1].
#[cold]
#[inline(never)]
fn select_roots<F: Float>(
    mut roots: ArrayVec<F, 2>,
    s0: i8,
    s1: i8,
    a: F,
    b: F,
    c: F,
) -> ArrayVec<F, 2> {
    let one = F::one();
    let remove_nearest = |target: F, roots: &mut ArrayVec<F, 2>| {
        let mut best: Option<(usize, F)> = None;
        for (i, &u) in roots.iter().enumerate() {
            let d = (u - target).abs();
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        if let Some((i, _)) = best {
            roots.remove(i);
        }
    };
    // Signs of the (deflated) polynomial g at u = 0 and u = 1, the coefficients of its
    // derivative g'(u) = d0 + d1 u, and its root as a fallback.
    let two = one + one;
    let (g0, g1, d0, d1, fallback): (i8, i8, F, F, Secant<F>) = match (s0, s1) {
        (0, 0) => return ArrayVec::new(),
        (0, _) => {
            remove_nearest(F::zero(), &mut roots);
            // b = 0 leaves g = c u, whose only root is the degenerate end again.
            let sb = if b == F::zero() { s1 } else { sign(b) };
            (sb, s1, c, F::zero(), |_, b, c| -b / c)
        }
        (_, 0) => {
            remove_nearest(one, &mut roots);
            (-s0, sign(c - a), c, F::zero(), |a, _, c| a / c)
        }
        _ => (s0, s1, b, two * c, |a, b, c| -a / (b + c)),
    };
    let want_odd = g0 != g1;
    let near = F::epsilon().sqrt();
    let four = two + two;
    // A root within `near` of an end is inside iff g changes sign between that end and the
    // root in the right direction: g(0) ~ -g'(r) r, g(1) ~ g'(r) (1 - r), decided with the
    // exact end sign whenever g' dominates the curvature there.
    let inside = |u: F| {
        let d = d0 + d1 * u;
        if u.abs() <= near && d.abs() > four * c.abs() * u.abs() {
            g0 == -sign(d)
        } else if (u - one).abs() <= near && d.abs() > four * c.abs() * (u - one).abs() {
            g1 == sign(d)
        } else {
            u >= F::zero() && u <= one
        }
    };
    let mut keep = [false; 2];
    for (k, &u) in keep.iter_mut().zip(roots.iter()) {
        *k = inside(u);
    }
    let count = keep.iter().take(roots.len()).filter(|&&k| k).count();
    if (count % 2 == 1) != want_odd {
        // A root within rounding distance of u = 0 or u = 1 landed on the wrong side: flip
        // the one nearest to the boundary.
        let mut best: Option<(usize, F)> = None;
        for (i, &u) in roots.iter().enumerate() {
            let d = if keep.get(i) == Some(&true) {
                u.min(one - u)
            } else {
                (-u).max(u - one)
            };
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        match best {
            Some((i, _)) => {
                if let Some(k) = keep.get_mut(i) {
                    *k = !*k;
                }
            }
            None => {
                // The root was lost to rounding although the sign changes on [0, 1] (but not
                // when f vanishes identically: a patch seen edge-on, whose rungs all lie on
                // one line through the ray; the perturbed ray misses it).
                if a != F::zero() || b != F::zero() || c != F::zero() {
                    roots.push(fallback(a, b, c).max(F::zero()).min(one));
                    keep[0] = true;
                }
            }
        }
    }
    let mut out = ArrayVec::new();
    for (&u, &k) in roots.iter().zip(keep.iter()) {
        if k {
            out.push(u.max(F::zero()).min(one));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::cross2 as cross;

    #[test]
    fn boundary_identities_hold() {
        // The identities the v-decision relies on, checked at random points of random 2D
        // bilinear maps (origin moved to P(u, v)).
        let mut rnd = crate::fixtures::uniform(0x1234_5678);
        for _ in 0..200 {
            let c: Vec<[f64; 2]> = (0..4).map(|_| [rnd(), rnd()]).collect();
            let (u, v) = (rnd(), rnd());
            let l = |a: [f64; 2], b: [f64; 2], s: f64| {
                [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
            };
            let o = l(l(c[0], c[1], u), l(c[3], c[2], u), v);
            let sh = |p: [f64; 2]| [p[0] - o[0], p[1] - o[1]];
            let (p00, p10, p11, p01) = (sh(c[0]), sh(c[1]), sh(c[2]), sh(c[3]));
            let pa = l(p00, p10, u);
            let pb = l(p01, p11, u);
            let bv = [pb[0] - pa[0], pb[1] - pa[1]];
            let e10 = [p10[0] - p00[0], p10[1] - p00[1]];
            let d1 = [p11[0] - p01[0], p11[1] - p01[1]];
            assert!((cross(p00, p10) - v * cross(e10, bv)).abs() < 1e-12);
            assert!((cross(p01, p11) - (v - 1.0) * cross(d1, bv)).abs() < 1e-12);
            // f(u) = cross(P(u,0), P(u,1)) vanishes at the root.
            assert!(cross(pa, pb).abs() < 1e-12);
        }
    }

    #[test]
    fn quadratic_roots_sorted_and_stable() {
        let (r, close) = solve_quadratic(2.0f64, -3.0, 1.0); // (u - 1)(u - 2)
        assert_eq!((r.as_slice(), close), (&[1.0, 2.0][..], false));
        let (r, _) = solve_quadratic(1e-20f64, 1.0, 1.0); // roots ~ -1e-20 and ~ -1
        assert!((r[1] + 1e-20).abs() < 1e-34);
        assert!(solve_quadratic(1.0f64, 0.0, 1.0).0.is_empty());
        let (r, close) = solve_quadratic(0.25f64, -1.0, 1.0);
        assert_eq!((r.as_slice(), close), (&[0.5, 0.5][..], true));
    }

    #[test]
    fn unit_square_hit_in_the_middle() {
        let p = Patch::new([
            [0.0f64, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]);
        let h = p.intersect([0.25, 0.75, 2.0], [0.0, 0.0, -1.0], 0.0, f64::INFINITY);
        assert_eq!(h.len(), 1);
        assert_eq!(
            h[0],
            Hit {
                t: 2.0,
                u: 0.25,
                v: 0.75
            }
        );
    }
}
