//! A moving triangle's equations at one sample point: coverage, depth and barycentrics
//! (Gribel 2010, §4).

use num_traits::Float;

use crate::depth::{LinearDepth, RationalDepth};
use crate::edge::EdgeQuadratic;
use crate::quadratic::lit;
use crate::span::{Coverage, Span};
use crate::triangle::TriangleSetup;

/// The three edge functions of a moving triangle at a fixed sample (x₀, y₀), each a
/// quadratic in t (Gribel 2010, Eq. 7), with the vertex depths. Built by
/// [`TriangleSetup::sample`]; every per-sample query is one call on it:
///
/// ```
/// use edge_eqn::MovingTriangle;
/// let q = [[0.0, 0.0, 1.0], [8.0, 0.0, 2.0], [0.0, 8.0, 2.0]];
/// let r = q.map(|[x, y, w]| [x + 4.0, y, w]);
/// let s = MovingTriangle::<f64>::new(q, r).setup().sample(3.5, 0.5);
/// for span in s.coverage().iter() {
///     let fit = s.linear_depth(*span);            // Eq. 16: z, k and the fit's max error
///     let d = s.depth_at(span.mid());             // Eq. 15: exact depth
///     let [l0, l1, l2] = s.barycentrics(span.mid()); // Eq. 11: weights of vertices 0, 1, 2
///     assert!(fit.max_error >= 0.0 && d > 0.0);
///     assert!((l0 + l1 + l2 - 1.0).abs() < 1e-12);
/// }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleEquations<F> {
    edges: [EdgeQuadratic<F>; 3],
    zq: [F; 3],
    zr: [F; 3],
    is_static: bool,
    valid: bool,
}

/// True when the nine coefficients are finite (non-finite x or y always makes one of them
/// NaN or infinite). Evaluated without short-circuit so it compiles to independent compares.
#[inline(always)]
pub(crate) fn all_finite<F: Float>(e: &[EdgeQuadratic<F>; 3]) -> bool {
    let f = |q: &EdgeQuadratic<F>| q.alpha.is_finite() & q.beta.is_finite() & q.gamma.is_finite();
    f(&e[0]) & f(&e[1]) & f(&e[2])
}

#[inline]
fn covered(s: [i8; 3]) -> bool {
    (s[0] <= 0 && s[1] <= 0 && s[2] <= 0) || (s[0] >= 0 && s[1] >= 0 && s[2] >= 0)
}

/// Coverage of a moving triangle from its three edge quadratics (Gribel 2010, Eq. 9).
///
/// Each edge's sign changes come from [`EdgeQuadratic::crossings`] (a test without square
/// root or division settles edges that keep their sign on (0, 1); the others go to the
/// robust solver). Two edges that never change sign and disagree rule out coverage before
/// the third is looked at; otherwise the covered set is swept through the sorted crossing
/// times: covered when every edge is <= 0 or every edge is >= 0.
#[inline]
pub(crate) fn moving_coverage<F: Float>(edges: &[EdgeQuadratic<F>; 3]) -> Coverage<F> {
    let c0 = edges[0].crossings();
    let c1 = edges[1].crossings();
    if c0.times.is_empty() && c1.times.is_empty() && c0.sign0 * c1.sign0 < 0 {
        return Coverage::empty();
    }
    let cr = [c0, c1, edges[2].crossings()];
    let mut signs = [cr[0].sign0, cr[1].sign0, cr[2].sign0];
    // At most six crossing times in (0, 1); insertion-sort them with their edge index.
    let mut ev_t = [F::zero(); 6];
    let mut ev_k = [0usize; 6];
    let mut n = 0;
    for (k, c) in cr.iter().enumerate() {
        for &t in c.times.as_slice() {
            let mut i = n;
            while i > 0 && ev_t[i - 1] > t {
                ev_t[i] = ev_t[i - 1];
                ev_k[i] = ev_k[i - 1];
                i -= 1;
            }
            ev_t[i] = t;
            ev_k[i] = k;
            n += 1;
        }
    }
    let mut out = Coverage::empty();
    let mut start = if covered(signs) {
        Some(F::zero())
    } else {
        None
    };
    for (&t, &k) in ev_t.iter().zip(ev_k.iter()).take(n) {
        signs[k] = -signs[k];
        match (start, covered(signs)) {
            (Some(t0), false) => {
                out.append(t0, t);
                start = None;
            }
            (None, true) => start = Some(t),
            _ => {}
        }
    }
    if let Some(t0) = start {
        out.append(t0, F::one());
    }
    out
}

impl<F: Float> SampleEquations<F> {
    pub(crate) fn new(setup: &TriangleSetup<F>, x: F, y: F) -> Self {
        let e = &setup.edges;
        let edges = if setup.is_static {
            // Static fast path: f = g = 0, only γ = h · s is needed.
            let g = |k: usize| EdgeQuadratic {
                alpha: F::zero(),
                beta: F::zero(),
                gamma: e[k].h[0] * x + e[k].h[1] * y + e[k].h[2],
            };
            [g(0), g(1), g(2)]
        } else {
            [
                e[0].at_sample(x, y),
                e[1].at_sample(x, y),
                e[2].at_sample(x, y),
            ]
        };
        let valid = setup.valid && all_finite(&edges);
        SampleEquations {
            edges,
            zq: setup.zq,
            zr: setup.zr,
            is_static: setup.is_static,
            valid,
        }
    }

    /// The three edge quadratics e_k(t) = α_k t² + β_k t + γ_k (Gribel 2010, Eq. 7).
    pub fn edges(&self) -> &[EdgeQuadratic<F>; 3] {
        &self.edges
    }

    /// False when the setup or the sample point was non-finite or overflowed: then coverage
    /// is empty and depth and barycentric queries return zeros.
    pub fn is_valid(&self) -> bool {
        self.valid
    }

    /// Inside test at time t (the rule documented on [`TriangleSetup`]).
    #[inline]
    pub fn inside_at(&self, t: F) -> bool {
        if !self.valid {
            return false;
        }
        let z = F::zero();
        let [e0, e1, e2] = self.edges.map(|e| e.eval(t));
        (e0 <= z && e1 <= z && e2 <= z) || (e0 >= z && e1 >= z && e2 >= z)
    }

    /// The covered spans of [0, 1] (Gribel 2010, Eq. 9), sorted, disjoint, of positive
    /// length, at most four.
    ///
    /// Each edge's sign changes come from the robust quadratic solver (near-linear edges are
    /// solved as lines, see [`EdgeQuadratic::is_near_linear`]); the sign of each edge just
    /// after t = 0 is exact (the sign of γ, or of β, α when γ = 0), and the covered set is
    /// swept through the sorted crossing times. A static triangle takes one inside test.
    pub fn coverage(&self) -> Coverage<F> {
        if !self.valid {
            return Coverage::empty();
        }
        if self.is_static {
            let g = self.edges.map(|e| e.gamma);
            let z = F::zero();
            let inside =
                (g[0] <= z && g[1] <= z && g[2] <= z) || (g[0] >= z && g[1] >= z && g[2] >= z);
            return if inside {
                Coverage::full()
            } else {
                Coverage::empty()
            };
        }
        moving_coverage(&self.edges)
    }

    /// Perspective-correct barycentrics (λ₀, λ₁, λ₂) = (1 - u - v, u, v) at time t, with
    /// λ_k = e_k / (e₀ + e₁ + e₂) (Gribel 2010, Eq. 11-12). Interpolate any per-vertex
    /// attribute a_k(t) as Σ λ_k a_k(t).
    ///
    /// At covered times every λ_k is in [0, 1]. Where e₀ + e₁ + e₂ = 0 (a triangle of zero
    /// area at t) or the ratio overflows, (1/3, 1/3, 1/3) is returned; an invalid sample
    /// returns zeros.
    pub fn barycentrics(&self, t: F) -> [F; 3] {
        if !self.valid {
            return [F::zero(); 3];
        }
        let e = self.edges.map(|q| q.eval(t));
        let sum = e[0] + e[1] + e[2];
        let l = e.map(|v| v / sum);
        if sum != F::zero() && l.iter().all(|v| v.is_finite()) {
            l
        } else {
            [lit(1.0 / 3.0); 3]
        }
    }

    /// The exact depth as a rational function of time (Gribel 2010, Eq. 15).
    pub fn depth(&self) -> RationalDepth<F> {
        let e = self.edges.map(|q| [q.alpha, q.beta, q.gamma]);
        if self.valid {
            RationalDepth::new(e, self.zq, self.zr)
        } else {
            RationalDepth::new([[F::zero(); 3]; 3], [F::zero(); 3], [F::zero(); 3])
        }
    }

    /// Exact depth d(t) (Gribel 2010, Eq. 15); see [`RationalDepth::eval`].
    pub fn depth_at(&self, t: F) -> F {
        self.depth().eval(t)
    }

    /// Linear depth over a span (z at t0, slope k; Gribel 2010, Eq. 16) with the maximum
    /// error of that line against the exact depth over the span.
    pub fn linear_depth(&self, span: Span<F>) -> LinearDepth<F> {
        self.depth().linear_fit(span)
    }
}
