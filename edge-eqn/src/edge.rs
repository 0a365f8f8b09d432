//! Time-dependent edge equations (Gribel 2010, Eq. 1-8).

use arrayvec::ArrayVec;
use num_traits::Float;

use crate::quadratic::{Times, lit, unit_crossings};
use crate::span::Span;

/// Cross product of two 2DH points.
#[inline]
pub(crate) fn cross<F: Float>(u: [F; 3], v: [F; 3]) -> [F; 3] {
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

#[inline]
fn add<F: Float>(u: [F; 3], v: [F; 3]) -> [F; 3] {
    [u[0] + v[0], u[1] + v[1], u[2] + v[2]]
}

#[inline]
fn sub<F: Float>(u: [F; 3], v: [F; 3]) -> [F; 3] {
    [u[0] - v[0], u[1] - v[1], u[2] - v[2]]
}

/// (v · (x, y, 1)).
#[inline]
fn dot_s<F: Float>(v: [F; 3], x: F, y: F) -> F {
    v[0] * x + v[1] * y + v[2]
}

/// The edge from vertex `a` to vertex `b` of a linearly moving triangle:
/// (a(t), b(t), c(t)) = t² f + t g + h (Gribel 2010, Eq. 3-4), so that
/// e(x, y, t) = (f t² + g t + h) · (x, y, 1) (Eq. 5).
///
/// The coefficient vectors are the ones of Eq. 4, computed in a form that keeps exact zeros
/// exact: with Δ = r - q, f = Δ_b × Δ_a (zero for a pure translation with constant w) and
/// g = q_b × Δ_a + Δ_b × q_a (zero for a static edge); h = q_b × q_a and k = g + 2h as in
/// Eq. 4.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MovingEdge<F> {
    /// h = q̂_b × q̂_a: the static edge at shutter open (Eq. 4).
    pub h: [F; 3],
    /// k = q̂_b × r̂_a + r̂_b × q̂_a (Eq. 4).
    pub k: [F; 3],
    /// f = h - k + r̂_b × r̂_a: the t² coefficient (Eq. 4).
    pub f: [F; 3],
    /// g = -2h + k: the t coefficient (Eq. 4).
    pub g: [F; 3],
}

impl<F: Float> MovingEdge<F> {
    /// The edge from vertex a (at open `qa`, at close `ra`) to vertex b (`qb`, `rb`), all in
    /// 2DH (x, y, w). A point is inside this edge when e <= 0 (Gribel 2010, Eq. 1).
    pub fn new(qa: [F; 3], ra: [F; 3], qb: [F; 3], rb: [F; 3]) -> Self {
        let da = sub(ra, qa);
        let db = sub(rb, qb);
        let h = cross(qb, qa);
        let f = cross(db, da);
        let g = add(cross(qb, da), cross(db, qa));
        let k = add(g, add(h, h));
        MovingEdge { h, k, f, g }
    }

    /// The edge coefficients (a(t), b(t), c(t)) at time t (Gribel 2010, Eq. 3).
    pub fn coefficients_at(&self, t: F) -> [F; 3] {
        let c = |i: usize| (self.f[i] * t + self.g[i]) * t + self.h[i];
        [c(0), c(1), c(2)]
    }

    /// The edge function at a fixed sample point as a quadratic in t (Gribel 2010, Eq. 7):
    /// α = f · s, β = g · s, γ = h · s with s = (x, y, 1).
    pub fn at_sample(&self, x: F, y: F) -> EdgeQuadratic<F> {
        EdgeQuadratic {
            alpha: dot_s(self.f, x, y),
            beta: dot_s(self.g, x, y),
            gamma: dot_s(self.h, x, y),
        }
    }

    /// e(x, y, t) (Gribel 2010, Eq. 5).
    pub fn eval(&self, x: F, y: F, t: F) -> F {
        self.at_sample(x, y).eval(t)
    }

    /// True when every coefficient is finite.
    pub(crate) fn is_finite(&self) -> bool {
        [self.h, self.k, self.f, self.g]
            .iter()
            .all(|v| v.iter().all(|c| c.is_finite()))
    }
}

/// e(t) = α t² + β t + γ: one edge function at a fixed sample (Gribel 2010, Eq. 7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeQuadratic<F> {
    /// α, the t² coefficient.
    pub alpha: F,
    /// β, the t coefficient.
    pub beta: F,
    /// γ, the constant term (e at t = 0).
    pub gamma: F,
}

/// Where one edge function changes sign on (0, 1): its sign just after t = 0 and the simple
/// roots strictly inside (0, 1), ascending.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Crossings<F> {
    /// Sign of e on (0, first root): -1, +1, or 0 when e is identically zero.
    pub sign0: i8,
    /// Times in (0, 1) where e changes sign.
    pub times: Times<F>,
}

#[inline]
fn sign<F: Float>(v: F) -> i8 {
    i8::from(v > F::zero()) - i8::from(v < F::zero())
}

impl<F: Float> EdgeQuadratic<F> {
    /// e(t), evaluated with Horner's rule.
    #[inline]
    pub fn eval(&self, t: F) -> F {
        (self.alpha * t + self.beta) * t + self.gamma
    }

    /// True when the t² term is negligible on [0, 1]: |α| <= ε/2 · (|β| + |γ|), i.e. below
    /// the rounding error of evaluating β t + γ, so the edge is solved as a line. The far
    /// root of the quadratic then lies outside [0, 1] and the near root moves by about one
    /// ulp of t (Munkberg 2011, §4.2, on why near-linear motion must not divide by α).
    pub fn is_near_linear(&self) -> bool {
        self.alpha.abs() <= F::epsilon() * lit(0.5) * (self.beta.abs() + self.gamma.abs())
    }

    /// Sign structure of e on (0, 1), from the robust solver.
    #[inline(always)]
    pub(crate) fn crossings(&self) -> Crossings<F> {
        let (sign0, settled) = self.quick();
        let times = if settled {
            Times::new()
        } else {
            self.solve_crossings()
        };
        Crossings { sign0, times }
    }

    /// The sign of e just after t = 0 and whether a test without square root or division
    /// proves that e keeps that sign on (0, 1) (then there is nothing to solve).
    ///
    /// Settled when e is constant in t (α = β = 0), or when e(0) and e(1) share a sign and e
    /// has no extremum in (0, 1) that points towards zero (the derivative 2αt + β keeps its
    /// sign on [0, 1], or the extremum is a maximum above positive ends / a minimum below
    /// negative ends).
    #[inline(always)]
    pub(crate) fn quick(&self) -> (i8, bool) {
        let (a, b, c) = (self.alpha, self.beta, self.gamma);
        let zero = F::zero();
        let sign0 = if c != zero {
            sign(c)
        } else if b != zero {
            sign(b)
        } else {
            sign(a)
        };
        if a == zero && b == zero {
            return (sign0, true);
        }
        let e1 = a + b + c;
        if c != zero && e1 != zero && (c > zero) == (e1 > zero) {
            let d1 = a + a + b;
            let monotonic = !((b > zero && d1 < zero) || (b < zero && d1 > zero));
            if monotonic || (a > zero) != (c > zero) {
                return (sign0, true);
            }
        }
        (sign0, false)
    }

    /// The simple roots in (0, 1), ascending, from the robust solver (near-linear edges as
    /// lines, [`EdgeQuadratic::is_near_linear`]). Callers skip this when [`Self::quick`]
    /// settles the edge.
    #[inline(always)]
    pub(crate) fn solve_crossings(&self) -> Times<F> {
        let (a, b, c) = (self.alpha, self.beta, self.gamma);
        let (zero, one) = (F::zero(), F::one());
        if self.is_near_linear() {
            let mut times = Times::new();
            if b != zero {
                let t = -c / b;
                if t > zero && t < one {
                    times.push(t);
                }
            }
            times
        } else {
            unit_crossings(a, b, c)
        }
    }

    /// The spans of [0, 1] where the sample is inside this edge, e(t) <= 0 (Gribel 2010,
    /// Eq. 8): zero, one or two spans, ascending. Isolated touching instants (a double root
    /// of a quadratic that is otherwise positive) are not reported.
    pub fn inside_spans(&self) -> ArrayVec<Span<F>, 2> {
        let cr = self.crossings();
        let mut out: ArrayVec<Span<F>, 2> = ArrayVec::new();
        let mut s = cr.sign0;
        let mut start = if s <= 0 { Some(F::zero()) } else { None };
        for &t in cr.times.as_slice() {
            s = -s;
            match (start, s <= 0) {
                (Some(t0), false) => {
                    if t > t0 {
                        let _ = out.try_push(Span::new(t0, t));
                    }
                    start = None;
                }
                (None, true) => start = Some(t),
                _ => {}
            }
        }
        if let Some(t0) = start
            && F::one() > t0
        {
            let _ = out.try_push(Span::new(t0, F::one()));
        }
        out
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    #[test]
    fn eq4_matches_expansion() {
        // Compare the Eq. 4 coefficients with a direct cross product at several times.
        let qa = [1.0_f64, 2.0, 1.0];
        let ra = [3.0, -1.0, 2.0];
        let qb = [-2.0, 0.5, 1.5];
        let rb = [0.0, 4.0, 0.5];
        let e = MovingEdge::new(qa, ra, qb, rb);
        for i in 0..=10 {
            let t = f64::from(i) / 10.0;
            let lerp = |p: [f64; 3], r: [f64; 3]| [0, 1, 2].map(|j| (1.0 - t) * p[j] + t * r[j]);
            let direct = cross(lerp(qb, rb), lerp(qa, ra));
            let got = e.coefficients_at(t);
            for j in 0..3 {
                assert!((direct[j] - got[j]).abs() < 1e-12, "{direct:?} {got:?}");
            }
            // f = h - k + rb × ra, g = -2h + k.
            let rr = cross(rb, ra);
            for j in 0..3 {
                assert!((e.f[j] - (e.h[j] - e.k[j] + rr[j])).abs() < 1e-12);
                assert!((e.g[j] - (e.k[j] - 2.0 * e.h[j])).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn inside_spans_shapes() {
        // (t - 0.25)(t - 0.75): negative between the roots.
        let e = EdgeQuadratic {
            alpha: 1.0_f64,
            beta: -1.0,
            gamma: 0.1875,
        };
        assert_eq!(e.inside_spans().as_slice(), &[Span::new(0.25, 0.75)]);
        // Negated: inside outside the roots, two spans.
        let e = EdgeQuadratic {
            alpha: -1.0_f64,
            beta: 1.0,
            gamma: -0.1875,
        };
        assert_eq!(
            e.inside_spans().as_slice(),
            &[Span::new(0.0, 0.25), Span::new(0.75, 1.0)]
        );
        // Tangent from above: never inside for positive time.
        let e = EdgeQuadratic {
            alpha: 4.0_f64,
            beta: -4.0,
            gamma: 1.0,
        };
        assert!(e.inside_spans().is_empty());
        // Identically zero: on the edge all the time counts as inside.
        let e = EdgeQuadratic {
            alpha: 0.0_f64,
            beta: 0.0,
            gamma: 0.0,
        };
        assert_eq!(e.inside_spans().as_slice(), &[Span::new(0.0, 1.0)]);
        // Linear, root at 0: e = t, inside only at t = 0 (dropped).
        let e = EdgeQuadratic {
            alpha: 0.0_f64,
            beta: 1.0,
            gamma: 0.0,
        };
        assert!(e.inside_spans().is_empty());
    }
}
