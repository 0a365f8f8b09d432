//! A moving triangle's equations at one sample point: coverage, depth and barycentrics
//! (Gribel 2010, §4).

use num_traits::Float;

use crate::depth::{LinearDepth, RationalDepth};
use crate::edge::EdgeQuadratic;
use crate::quadratic::lit;
use crate::span::{Coverage, MAX_SPANS, Span};
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
    /// The setup's depth clamp range (`zlo`, `zhi`).
    zrange: [F; 2],
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

/// Coverage of a moving triangle from its three edge quadratics (Gribel 2010, Eq. 9).
///
/// Each edge's sign changes come from [`EdgeQuadratic::crossings`] (a test without square
/// root or division settles edges that keep their sign on (0, 1); the others go to the
/// robust solver). Two edges that never change sign and disagree rule out coverage before
/// the third is looked at; otherwise the covered set is swept through the sorted crossing
/// times: covered when every edge is <= 0 or every edge is >= 0.
///
/// Written for the per-pixel hot loop (measured in `BENCHMARKS.md`): always inlined into
/// its two callers (a separate function cost a call and a second copy of the result), the
/// sign state is a bit mask in a register instead of an array in memory, and the spans stay
/// in registers until the result is built once (a `Coverage` built in memory and then
/// copied out stalled on store-to-load forwarding).
#[inline(always)]
pub(crate) fn moving_coverage<F: Float>(edges: &[EdgeQuadratic<F>; 3]) -> Coverage<F> {
    let c0 = edges[0].crossings();
    let c1 = edges[1].crossings();
    if c0.times.is_empty() && c1.times.is_empty() && c0.sign0 * c1.sign0 < 0 {
        return Coverage::empty();
    }
    let cr = [c0, c1, edges[2].crossings()];
    // Edges positive / negative just after 0 (bit k for edge k); an edge with crossings is
    // never identically zero. With f the set of edges that have flipped sign since 0, all
    // edges are <= 0 when f = pos and all are >= 0 when f = neg.
    let bits = |test: fn(i8) -> bool| {
        u8::from(test(cr[0].sign0))
            | u8::from(test(cr[1].sign0)) << 1
            | u8::from(test(cr[2].sign0)) << 2
    };
    let pos = bits(|s| s > 0);
    let neg = bits(|s| s < 0);
    let covered = |f: u8| f == pos || f == neg;
    // At most six crossing times in (0, 1); insertion-sort them with their edge bit.
    let mut ev_t = [F::zero(); 6];
    let mut ev_m = [0u8; 6];
    let mut n = 0;
    for (k, c) in cr.iter().enumerate() {
        for &t in c.times.as_slice() {
            let mut i = n;
            while i > 0 && ev_t[i - 1] > t {
                ev_t[i] = ev_t[i - 1];
                ev_m[i] = ev_m[i - 1];
                i -= 1;
            }
            ev_t[i] = t;
            ev_m[i] = 1 << k;
            n += 1;
        }
    }
    let mut out = SpanBuf::new();
    let mut f = 0u8;
    let mut start = if covered(f) { Some(F::zero()) } else { None };
    for (&t, &m) in ev_t.iter().zip(ev_m.iter()).take(n) {
        f ^= m;
        match (start, covered(f)) {
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
    out.finish()
}

/// The spans of one coverage while they are being swept, kept where the compiler can hold
/// them in registers (constant indices only), then written out once: building the
/// [`Coverage`] in memory and copying it costs a store-to-load forwarding stall.
struct SpanBuf<F> {
    s: [F; MAX_SPANS],
    e: [F; MAX_SPANS],
    n: usize,
}

impl<F: Float> SpanBuf<F> {
    #[inline(always)]
    fn new() -> Self {
        SpanBuf {
            s: [F::zero(); MAX_SPANS],
            e: [F::zero(); MAX_SPANS],
            n: 0,
        }
    }

    /// Appends [t0, t1] with the merge rules of `Coverage::append`: an empty span is
    /// dropped, one that touches the last span is merged into it.
    #[inline(always)]
    fn append(&mut self, t0: F, t1: F) {
        if t1 <= t0 {
            return;
        }
        let last = match self.n {
            0 => None,
            1 => Some(&mut self.e[0]),
            2 => Some(&mut self.e[1]),
            3 => Some(&mut self.e[2]),
            _ => Some(&mut self.e[3]),
        };
        if let Some(l) = last
            && *l >= t0
        {
            *l = l.max(t1);
            return;
        }
        match self.n {
            0 => (self.s[0], self.e[0]) = (t0, t1),
            1 => (self.s[1], self.e[1]) = (t0, t1),
            2 => (self.s[2], self.e[2]) = (t0, t1),
            3 => (self.s[3], self.e[3]) = (t0, t1),
            // Unreachable by the counting argument in MAX_SPANS; stay total rather than panic.
            _ => self.e[3] = t1,
        }
        self.n = (self.n + 1).min(MAX_SPANS);
    }

    #[inline(always)]
    fn finish(self) -> Coverage<F> {
        Coverage::from_starts_ends(self.s, self.e, self.n)
    }
}

impl<F: Float> SampleEquations<F> {
    #[inline]
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
            zrange: [setup.zlo, setup.zhi],
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
    #[inline]
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
    #[inline]
    pub fn depth(&self) -> RationalDepth<F> {
        let e = self.edges.map(|q| [q.alpha, q.beta, q.gamma]);
        if self.valid {
            RationalDepth::with_range(e, self.zq, self.zr, self.zrange)
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The sweep as it was before the register sweep (per-edge signs in an array, spans
    /// appended to a `Coverage` with its merge rules): the reference the register sweep
    /// must reproduce bit for bit.
    fn reference_sweep<F: Float>(edges: &[EdgeQuadratic<F>; 3]) -> Coverage<F> {
        let covered = |s: [i8; 3]| {
            (s[0] <= 0 && s[1] <= 0 && s[2] <= 0) || (s[0] >= 0 && s[1] >= 0 && s[2] >= 0)
        };
        let cr = edges.map(|e| e.crossings());
        let mut signs = cr.map(|c| c.sign0);
        let mut ev: Vec<(F, usize)> = Vec::new();
        for (k, c) in cr.iter().enumerate() {
            for &t in c.times.as_slice() {
                ev.push((t, k));
            }
        }
        // Stable sort by time, as the insertion sort.
        ev.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(core::cmp::Ordering::Equal));
        let mut out = Coverage::empty();
        let mut start = covered(signs).then_some(F::zero());
        for (t, k) in ev {
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

    fn bits<F: Float>(c: &Coverage<F>) -> Vec<(F, F)> {
        c.iter().map(|s| (s.t0, s.t1)).collect()
    }

    /// One edge quadratic, from a family chosen to hit the sweep's and the solver's special
    /// cases: random coefficients of mixed magnitude, s (t - r₁)(t - r₂) with roots drawn
    /// from a few dyadic values (exact coefficients, so edges share crossing times exactly:
    /// ties), exact double roots (tangency), near-linear (α = β 2^-k), γ = 0, constant, and
    /// coefficients near 2^±600 (the solver's scaled path).
    fn edge() -> impl Strategy<Value = EdgeQuadratic<f64>> {
        let root = prop_oneof![
            Just(0.25),
            Just(0.5),
            Just(0.75),
            Just(0.0),
            Just(1.0),
            -0.5..1.5_f64
        ];
        let scale = (-8i32..8, any::<bool>())
            .prop_map(|(e, neg)| 2f64.powi(e) * if neg { -1.0 } else { 1.0 });
        let q = |a: f64, b: f64, c: f64| EdgeQuadratic {
            alpha: a,
            beta: b,
            gamma: c,
        };
        prop_oneof![
            (-4.0..4.0_f64, -4.0..4.0_f64, -4.0..4.0_f64).prop_map(move |(a, b, c)| q(a, b, c)),
            (scale.clone(), root.clone(), root.clone()).prop_map(move |(s, r1, r2)| q(
                s,
                -s * (r1 + r2),
                s * r1 * r2
            )),
            (scale.clone(), root.clone()).prop_map(move |(s, r)| q(s, -2.0 * s * r, s * r * r)),
            (scale.clone(), 20i32..80, root.clone()).prop_map(move |(s, k, r)| q(
                s * 2f64.powi(-k),
                s,
                -s * r
            )),
            (-4.0..4.0_f64, -4.0..4.0_f64).prop_map(move |(a, b)| q(a, b, 0.0)),
            (-4.0..4.0_f64).prop_map(move |c| q(0.0, 0.0, c)),
            (
                scale,
                root.clone(),
                root,
                prop_oneof![Just(600), Just(-600)]
            )
                .prop_map(move |(s, r1, r2, e)| {
                    let s = s * 2f64.powi(e);
                    q(s, -s * (r1 + r2), s * r1 * r2)
                }),
        ]
    }

    proptest! {
        /// The register sweep (bit masks, spans held in registers) gives exactly the spans of
        /// the reference sweep, in f64 and in f32, on the hard edge families above.
        #[test]
        fn register_sweep_matches_reference_sweep(e in [edge(), edge(), edge()]) {
            let got = moving_coverage(&e);
            let want = reference_sweep(&e);
            prop_assert_eq!(bits(&got), bits(&want), "{:?}", e);
            let e32 = e.map(|q| EdgeQuadratic {
                alpha: q.alpha as f32,
                beta: q.beta as f32,
                gamma: q.gamma as f32,
            });
            prop_assert_eq!(bits(&moving_coverage(&e32)), bits(&reference_sweep(&e32)), "{:?}", e32);
        }
    }

    /// Ties by construction: edges crossing at the same instant, so that the order of the
    /// tied events decides whether a span is left and re-entered at that instant (merged into
    /// one span) or entered and left (a zero-length span, dropped).
    #[test]
    fn register_sweep_ties_merge_and_drop() {
        let q = |a: f64, b: f64, c: f64| EdgeQuadratic {
            alpha: a,
            beta: b,
            gamma: c,
        };
        let half = q(0.0, 1.0, -0.5); // t - 1/2: negative, then positive
        let cases = [
            // All three flip at 1/2 (the triangle collapses through the sample and turns
            // over): covered before and after, one merged span [0, 1].
            ([half, half, half], vec![(0.0, 1.0)]),
            // Two flip together, the third never: covered until 1/2 only.
            ([half, half, q(0.0, 0.0, -1.0)], vec![(0.0, 0.5)]),
            // A quadratic edge (t - 1/4)(t - 3/4) and a line crossing with it at 1/4.
            (
                [q(1.0, -1.0, 0.1875), q(0.0, -1.0, 0.25), q(0.0, 0.0, 1.0)],
                vec![(0.0, 0.25)],
            ),
            (
                [q(1.0, -1.0, 0.1875), q(0.0, 1.0, -0.25), q(0.0, -1.0, 0.75)],
                vec![],
            ),
            // Two edges that are each other's negation: never on one side together.
            ([q(1.0, -1.0, 0.1875), q(-1.0, 1.0, -0.1875), half], vec![]),
        ];
        for (e, want) in cases {
            let got = bits(&moving_coverage(&e));
            assert_eq!(got, bits(&reference_sweep(&e)), "{e:?}");
            assert_eq!(got, want, "{e:?}");
        }
        // Enter and leave at 1/2 from different edges: a zero-length span, dropped.
        let e = [q(0.0, -1.0, 0.5), q(0.0, 1.0, -0.5), q(0.0, 0.0, 1.0)];
        assert!(moving_coverage(&e).is_empty());
        assert!(reference_sweep(&e).is_empty());
    }
}
