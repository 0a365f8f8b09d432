//! Exact time-dependent back-face culling of a moving triangle (Munkberg and
//! Akenine-Möller 2011, "Backface culling for motion blur and depth of field"): the times in
//! [0, 1] at which the triangle may face the camera, instead of one verdict for the whole
//! shutter ([`facing`](crate::cull::facing)).
//!
//! The 2DH orientation det[p₀(t); p₁(t); p₂(t)] of a triangle whose vertices move linearly
//! is a cubic in t ([`orientation_bernstein`]). Its real roots in (0, 1) cut the shutter into
//! pieces of constant sign; a piece is removed only when the Bernstein bound with a rounding
//! margin proves the hidden sign on it ([`facing`](crate::cull::facing) applied to the motion restricted to the
//! piece, which is again linear). So the windows are a superset of the times the triangle
//! faces the camera, the removed time never holds an instant where it may:
//!
//! 1. [`facing`](crate::cull::facing) on [0, 1] decides most triangles with no root solving.
//! 2. Otherwise the critical points of the cubic (the roots of its derivative, a quadratic
//!    solved by edge-eqn's [`edge_eqn::quadratic::real_roots`], which handles a vanishing
//!    leading coefficient) cut [0, 1] into monotone pieces; each piece whose ends have
//!    opposite signs holds one simple root, found by bisection on the Bernstein form
//!    (de Casteljau, stable on [0, 1]). A critical point where the cubic is within
//!    [`TANGENT`] of zero (relative to the magnitude of its terms) is a tangent root and
//!    cuts too.
//! 3. Each piece whose middle has the hidden sign is certified: first shrunk by [`SHRINK`]
//!    at its root ends, then, if the bound is not conclusive (near a root the cubic is
//!    smaller than the margin; the Bernstein hull of a long piece is loose), halved
//!    recursively down to [`DEPTH`] levels. Certified parts are removed.
//!
//! A degenerate triangle (orientation identically zero) or non-finite input keeps all of
//! [0, 1].

use arrayvec::ArrayVec;
use num_traits::Float;

use crate::cull::{Facing, facing_margin, facing_with_margin, orientation_bernstein};

/// Most windows a [`FacingWindows`] holds: the cubic has at most three roots and two
/// tangent points, and each removed piece may leave one window between it and the next.
pub const MAX_WINDOWS: usize = 8;

/// A critical point of the orientation cubic where |det| is at most this times the sum of
/// the magnitudes of its terms is treated as a (tangent) root.
pub const TANGENT: f64 = 1.0 / 1_048_576.0;

/// Time a removed piece is first shrunk by at each root end (2⁻²⁰ of the span), so the
/// Bernstein bound meets the cubic away from zero there.
pub const SHRINK: f64 = 1.0 / 1_048_576.0;

/// Levels of halving a hidden piece whose Bernstein bound is not conclusive; near a root
/// at most 2⁻¹⁰ of the piece is kept beyond the root.
pub const DEPTH: u32 = 10;

/// Most Bernstein tests per hidden piece (halving stops when they are spent; what is not
/// certified is kept).
const BUDGET: u32 = 64;

/// The times in [0, 1] at which a moving triangle may face the camera: sorted, disjoint,
/// closed windows (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct FacingWindows(ArrayVec<[f64; 2], MAX_WINDOWS>);

impl FacingWindows {
    /// All of [0, 1].
    pub fn all() -> Self {
        let mut w = ArrayVec::new();
        w.push([0.0, 1.0]);
        FacingWindows(w)
    }

    /// No time: the triangle faces away during all of [0, 1].
    pub fn none() -> Self {
        FacingWindows(ArrayVec::new())
    }

    /// True when the windows are all of [0, 1].
    pub fn is_all(&self) -> bool {
        self.0.as_slice() == [[0.0, 1.0]]
    }

    /// True when there is no window (the triangle may be culled whole).
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The windows `[t0, t1]`, sorted and disjoint.
    pub fn as_slice(&self) -> &[[f64; 2]] {
        &self.0
    }

    /// True when `t` lies in a window.
    pub fn contains(&self, t: f64) -> bool {
        self.0.iter().any(|&[a, b]| a <= t && t <= b)
    }

    /// Total length of the windows.
    pub fn len(&self) -> f64 {
        self.0.iter().map(|[a, b]| b - a).sum()
    }

    /// [0, 1] without the sorted, disjoint `removed` pieces.
    fn complement(removed: &[[f64; 2]]) -> Self {
        let mut w = ArrayVec::new();
        let mut from = 0.0;
        for &[a, b] in removed {
            if a > from && w.try_push([from, a]).is_err() {
                return FacingWindows::all();
            }
            from = from.max(b);
        }
        if from < 1.0 && w.try_push([from, 1.0]).is_err() {
            return FacingWindows::all();
        }
        FacingWindows(w)
    }
}

/// The times in [0, 1] at which the moving triangle with 2DH vertices `q` at t = 0 and `r`
/// at t = 1 may show a winding other than `hidden` (Munkberg and Akenine-Möller 2011):
/// outside the windows det[p₀(t); p₁(t); p₂(t)] provably has the sign of `hidden`
/// (positive for [`Facing::Front`], negative for [`Facing::Back`]) by more than the
/// rounding margin of [`facing`](crate::cull::facing) for `F`. `hidden == Facing::Mixed` gives all of [0, 1].
/// See the module documentation for the method.
pub fn facing_windows<F: Float>(q: &[[F; 3]; 3], r: &[[F; 3]; 3], hidden: Facing) -> FacingWindows {
    let sign = match hidden {
        Facing::Front => 1.0,
        Facing::Back => -1.0,
        Facing::Mixed => return FacingWindows::all(),
    };
    let eps = facing_margin::<F>();
    let cv = |v: &[F; 3]| v.map(|c| c.to_f64().unwrap_or(f64::NAN));
    let (q, r) = (q.each_ref().map(cv), r.each_ref().map(cv));
    match facing_with_margin(&q, &r, eps) {
        Facing::Mixed => {}
        f if f == hidden => return FacingWindows::none(),
        _ => return FacingWindows::all(),
    }
    let (b, m) = orientation_bernstein(&q, &r);
    let cubic = Cubic::from_bernstein(b);
    let scale: f64 = m.iter().sum();
    if !scale.is_finite() || scale == 0.0 {
        return FacingWindows::all();
    }
    let mut knots: ArrayVec<f64, 8> = ArrayVec::new();
    knots.push(0.0);
    knots.extend(cubic.roots(TANGENT * scale));
    knots.push(1.0);
    let piece = Piece {
        q: &q,
        r: &r,
        hidden,
        eps,
    };
    let mut removed: ArrayVec<[f64; 2], 16> = ArrayVec::new();
    for k in knots.windows(2) {
        let (a, c) = (k[0], k[1]);
        if c > a && sign * cubic.eval(0.5 * (a + c)) > 0.0 {
            piece.certify(a, c, &mut removed);
        }
    }
    FacingWindows::complement(&removed)
}

/// The orientation cubic in Bernstein form on [0, 1].
#[derive(Clone, Copy, Debug)]
struct Cubic {
    /// Bernstein coefficients β₀..β₃.
    beta: [f64; 4],
}

impl Cubic {
    /// From [`orientation_bernstein`]'s coefficients (the middle two times 3).
    fn from_bernstein(b: [f64; 4]) -> Self {
        Cubic {
            beta: [b[0], b[1] / 3.0, b[2] / 3.0, b[3]],
        }
    }

    /// The value at `t` (de Casteljau).
    fn eval(&self, t: f64) -> f64 {
        let s = 1.0 - t;
        let mut b = self.beta;
        for n in (1..4).rev() {
            for i in 0..n {
                b[i] = s * b[i] + t * b[i + 1];
            }
        }
        b[0]
    }

    /// Coefficients c₀..c₃ of c₀ + c₁ t + c₂ t² + c₃ t³.
    fn power(&self) -> [f64; 4] {
        let [b0, b1, b2, b3] = self.beta;
        [
            b0,
            3.0 * (b1 - b0),
            3.0 * (b0 - 2.0 * b1 + b2),
            b3 - b0 + 3.0 * (b1 - b2),
        ]
    }

    /// The roots in (0, 1), ascending: the sign changes (one per monotone piece between
    /// the critical points) and the critical points where |value| ≤ `tangent`.
    fn roots(&self, tangent: f64) -> ArrayVec<f64, 6> {
        let c = self.power();
        let mut knots: ArrayVec<f64, 4> = ArrayVec::new();
        knots.push(0.0);
        let crit = edge_eqn::quadratic::real_roots(3.0 * c[3], 2.0 * c[2], c[1]);
        knots.extend(crit.into_iter().filter(|&x| x > 0.0 && x < 1.0));
        knots.push(1.0);
        let mut out = ArrayVec::new();
        for (i, k) in knots.windows(2).enumerate() {
            if i > 0 && self.eval(k[0]).abs() <= tangent {
                out.push(k[0]);
            }
            let (fa, fb) = (self.eval(k[0]), self.eval(k[1]));
            if fa * fb < 0.0 {
                out.push(self.bisect(k[0], k[1], fa));
            }
        }
        out
    }

    /// The sign change in (a, b) where the value at `a` is `fa` (the value at `b` has the
    /// other sign), to the last bit.
    fn bisect(&self, mut a: f64, mut b: f64, fa: f64) -> f64 {
        for _ in 0..80 {
            let mid = 0.5 * (a + b);
            if mid <= a || mid >= b {
                break;
            }
            let fm = self.eval(mid);
            if fm == 0.0 {
                return mid;
            }
            if (fm < 0.0) == (fa < 0.0) {
                a = mid;
            } else {
                b = mid;
            }
        }
        0.5 * (a + b)
    }
}

/// The motion of one triangle, for certifying that it faces `hidden` on part of [0, 1].
struct Piece<'a> {
    q: &'a [[f64; 3]; 3],
    r: &'a [[f64; 3]; 3],
    hidden: Facing,
    eps: f64,
}

impl Piece<'_> {
    /// True when the Bernstein bound proves the `hidden` sign on [a, b]: the motion
    /// restricted to [a, b] is linear between the vertices at a and at b.
    fn proves(&self, a: f64, b: f64) -> bool {
        let at = |t: f64| {
            [0, 1, 2].map(|i| [0, 1, 2].map(|k| (1.0 - t) * self.q[i][k] + t * self.r[i][k]))
        };
        facing_with_margin(&at(a), &at(b), self.eps) == self.hidden
    }

    /// Appends the parts of the hidden piece [a, c] (its interior ends are roots) that are
    /// proved to face `hidden`, sorted and merged where they touch. Halving is breadth
    /// first, so the budget goes to the large parts before the small ones near a root.
    fn certify(&self, a: f64, c: f64, out: &mut ArrayVec<[f64; 2], 16>) {
        let lo = if a > 0.0 { a + SHRINK } else { a };
        let hi = if c < 1.0 { c - SHRINK } else { c };
        if hi <= lo {
            return;
        }
        let mut proved: ArrayVec<[f64; 2], { BUDGET as usize }> = ArrayVec::new();
        let mut level: ArrayVec<[f64; 2], { BUDGET as usize }> = ArrayVec::new();
        level.push([lo, hi]);
        let mut budget = BUDGET;
        for depth in 0..=DEPTH {
            let mut next: ArrayVec<[f64; 2], { BUDGET as usize }> = ArrayVec::new();
            for &[a, b] in &level {
                if budget == 0 {
                    break;
                }
                budget -= 1;
                if self.proves(a, b) {
                    proved.push([a, b]);
                    continue;
                }
                let mid = 0.5 * (a + b);
                if depth < DEPTH && mid > a && mid < b && next.remaining_capacity() >= 2 {
                    next.push([a, mid]);
                    next.push([mid, b]);
                }
            }
            if next.is_empty() || budget == 0 {
                break;
            }
            level = next;
        }
        proved.sort_by(|x, y| x[0].total_cmp(&y[0]));
        for [a, b] in proved {
            match out.last_mut() {
                Some(last) if last[1] >= a => last[1] = last[1].max(b),
                // Past the capacity, later parts are kept (never wrong, only less culled).
                _ => {
                    let _ = out.try_push([a, b]);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_power_form_matches_de_casteljau() {
        let c = Cubic {
            beta: [1.0, -2.0, 0.5, 3.0],
        };
        let p = c.power();
        for i in 0..=10 {
            let t = f64::from(i) / 10.0;
            let v = p[0] + t * (p[1] + t * (p[2] + t * p[3]));
            assert!((v - c.eval(t)).abs() < 1e-12, "{t}");
        }
    }

    #[test]
    fn a_triangle_flipping_once_keeps_the_front_part() {
        // Vertex 2 moves through the edge v0 v1: det ∝ (1 - 2t).
        let q = [[0.0f64, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 4.0, 1.0]];
        let r = [[0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, -4.0, 1.0]];
        let w = facing_windows(&q, &r, Facing::Back);
        assert_eq!(w.as_slice().len(), 1);
        let [a, b] = w.as_slice()[0];
        assert_eq!(a, 0.0);
        assert!((0.5..0.5 + 1e-3).contains(&b), "{b}");
    }
}
