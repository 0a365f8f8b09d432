//! A linearly moving triangle in 2DH and its per-triangle setup (Gribel 2010, §3).

use glam::{DVec3, Vec3};
use num_traits::Float;

use crate::depth::LinearDepth;
use crate::edge::MovingEdge;
use crate::quadratic::lit;
use crate::sample::{SampleEquations, all_finite, moving_coverage};
use crate::span::{Coverage, Span};

/// A triangle whose vertices move linearly during the shutter, p_k(t) = (1 - t) q_k + t r_k
/// (Gribel 2010, Eq. 2), given in 2DH: (x, y, w) with x and y in pixel units before the
/// division by w.
///
/// The depth attribute defaults to w, which for a perspective camera is the view-space
/// distance, interpolated perspective-correctly (Eq. 11-15). For an orthographic camera
/// (w constant) give explicit per-vertex depths with [`MovingTriangle::with_depth`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MovingTriangle<F> {
    /// Vertices at shutter open (t = 0), each (x, y, w).
    pub q: [[F; 3]; 3],
    /// Vertices at shutter close (t = 1), each (x, y, w).
    pub r: [[F; 3]; 3],
    /// Per-vertex depth at open and close; `None` means depth = w.
    pub depth: Option<([F; 3], [F; 3])>,
}

impl<F: Float> MovingTriangle<F> {
    /// Vertices (x, y, w) at shutter open `q` and close `r`; depth = w.
    pub fn new(q: [[F; 3]; 3], r: [[F; 3]; 3]) -> Self {
        MovingTriangle { q, r, depth: None }
    }

    /// A triangle that does not move (q = r): its setup takes the static fast path.
    pub fn fixed(p: [[F; 3]; 3]) -> Self {
        Self::new(p, p)
    }

    /// The same triangle with an explicit depth attribute per vertex at open (`zq`) and close
    /// (`zr`), interpolated perspective-correctly (Gribel 2010, Eq. 13-15). Smaller is nearer.
    pub fn with_depth(self, zq: [F; 3], zr: [F; 3]) -> Self {
        MovingTriangle {
            depth: Some((zq, zr)),
            ..self
        }
    }

    /// The per-triangle setup: the coefficient vectors h, k, f, g of the three edges
    /// (Gribel 2010, Eq. 4).
    ///
    /// Edge k is the edge opposite vertex k, from vertex k+1 to vertex k+2, with
    /// e_k = (p̂_{k+2} × p̂_{k+1}) · (x, y, 1) (Eq. 1 with p̂⁰ = p_{k+1}, p̂¹ = p_{k+2}), so that
    /// e_k / Σ e_j is the perspective-correct barycentric of vertex k (Eq. 11).
    ///
    /// Non-finite input, or input so large that the edge coefficients overflow `F`, gives a
    /// setup that covers nothing (every query returns empty coverage, `false`, or zeros).
    pub fn setup(&self) -> TriangleSetup<F> {
        let (zq, zr) = self.depth.unwrap_or_else(|| {
            (
                [self.q[0][2], self.q[1][2], self.q[2][2]],
                [self.r[0][2], self.r[1][2], self.r[2][2]],
            )
        });
        let edge = |k: usize| {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            MovingEdge::new(self.q[a], self.r[a], self.q[b], self.r[b])
        };
        let edges = [edge(0), edge(1), edge(2)];
        let finite_in = self
            .q
            .iter()
            .chain(self.r.iter())
            .flatten()
            .chain(zq.iter())
            .chain(zr.iter())
            .all(|v| v.is_finite());
        let valid = finite_in && edges.iter().all(MovingEdge::is_finite);
        let (mut zlo, mut zhi) = (zq[0], zq[0]);
        for &z in zq.iter().chain(zr.iter()) {
            zlo = zlo.min(z);
            zhi = zhi.max(z);
        }
        TriangleSetup {
            edges,
            zq,
            zr,
            zlo,
            zhi,
            is_static: self.q == self.r,
            valid,
            p0: [self.q[0], self.r[0]],
        }
    }
}

impl MovingTriangle<f32> {
    /// From glam vectors (x, y, w) at open and close.
    pub fn from_vec3(q: [Vec3; 3], r: [Vec3; 3]) -> Self {
        Self::new(q.map(|v| v.to_array()), r.map(|v| v.to_array()))
    }
}

impl MovingTriangle<f64> {
    /// From glam vectors (x, y, w) at open and close.
    pub fn from_dvec3(q: [DVec3; 3], r: [DVec3; 3]) -> Self {
        Self::new(q.map(|v| v.to_array()), r.map(|v| v.to_array()))
    }
}

/// Everything about a moving triangle that does not depend on the sample point: the three
/// time-dependent edge equations (Gribel 2010, Eq. 3-5) and the vertex depths.
///
/// # Inside rule and orientation
///
/// A sample is covered at time t when the three edge functions e_k(t) are all <= 0 **or**
/// all >= 0: the line through the eye and the sample crosses the triangle, whichever way
/// the triangle faces at that instant. For a front-facing triangle (det[p₀; p₁; p₂] > 0,
/// counter-clockwise with y up) this is Gribel's e <= 0 (Eq. 8-9); a triangle whose signed
/// area changes sign during the shutter (its 2DH determinant, a cubic in t, has a root in
/// (0, 1)) keeps being covered through the flip. This is exactly what a static inside test
/// that accepts both windings gives at every instant.
///
/// # Vertices behind the eye
///
/// Nothing divides by w, so w near zero or negative never produces NaN or infinity. With
/// some w <= 0 the rule above still returns the times at which the line through the eye and
/// the sample crosses the triangle, **including crossings behind the eye**; the default depth
/// (w) at such a crossing is <= 0. Callers clip or cull triangles against the near plane
/// first (the renderer does).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleSetup<F> {
    pub(crate) edges: [MovingEdge<F>; 3],
    pub(crate) zq: [F; 3],
    pub(crate) zr: [F; 3],
    /// Smallest and largest of the six vertex depths (the clamp range of exact depth).
    pub(crate) zlo: F,
    pub(crate) zhi: F,
    pub(crate) is_static: bool,
    pub(crate) valid: bool,
    /// Vertex 0 at open and close (for the orientation polynomial).
    pub(crate) p0: [[F; 3]; 2],
}

impl<F: Float> TriangleSetup<F> {
    /// The three moving edges; edge k is opposite vertex k (Gribel 2010, Eq. 4).
    pub fn edges(&self) -> &[MovingEdge<F>; 3] {
        &self.edges
    }

    /// True when q = r: coverage is one static inside test, no quadratic is solved.
    pub fn is_static(&self) -> bool {
        self.is_static
    }

    /// False when the input was non-finite or overflowed; such a setup covers nothing.
    pub fn is_valid(&self) -> bool {
        self.valid
    }

    /// Vertex depths at open and close (w unless given with `with_depth`).
    pub fn depths(&self) -> ([F; 3], [F; 3]) {
        (self.zq, self.zr)
    }

    /// The triangle's equations at the sample (x, y): the three quadratics of Gribel 2010,
    /// Eq. 7, from which coverage, depth and barycentrics of that sample follow.
    #[inline]
    pub fn sample(&self, x: F, y: F) -> SampleEquations<F> {
        SampleEquations::new(self, x, y)
    }

    /// The times during the shutter when the sample (x, y) is inside the triangle
    /// (Gribel 2010, Eq. 9): at most four disjoint spans, sorted.
    ///
    /// ```
    /// use edge_eqn::MovingTriangle;
    /// // A triangle sliding 8 px to the right: the sample (6.5, 1) is covered from when the
    /// // hypotenuse reaches it (t = 3.5/8) until the left edge passes it (t = 6.5/8).
    /// let q = [[0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 4.0, 1.0]];
    /// let r = q.map(|[x, y, w]| [x + 8.0, y, w]);
    /// let setup = MovingTriangle::<f64>::new(q, r).setup();
    /// let cov = setup.coverage(6.5, 1.0);
    /// assert_eq!(cov.len(), 1);
    /// assert!((cov[0].t0 - 0.4375).abs() < 1e-12 && (cov[0].t1 - 0.8125).abs() < 1e-12);
    /// ```
    #[inline]
    pub fn coverage(&self, x: F, y: F) -> Coverage<F> {
        if !self.valid {
            return Coverage::empty();
        }
        if self.is_static {
            return self.sample(x, y).coverage();
        }
        // Only the three quadratics are needed (no depth data): Eq. 7, then Eq. 9.
        let e = &self.edges;
        let q = [
            e[0].at_sample(x, y),
            e[1].at_sample(x, y),
            e[2].at_sample(x, y),
        ];
        if !all_finite(&q) {
            return Coverage::empty();
        }
        moving_coverage(&q)
    }

    /// The three edge functions e_k(x, y, t) evaluated the way the inside test does:
    /// coefficients (a, b, c)(t) by Horner in t (Eq. 3), then the dot with (x, y, 1).
    #[inline(always)]
    fn edge_values(&self, x: F, y: F, t: F) -> [F; 3] {
        let e = |k: usize| {
            let c = self.edges[k].coefficients_at(t);
            c[0] * x + c[1] * y + c[2]
        };
        [e(0), e(1), e(2)]
    }

    /// Time-dependent inside test of the sample (x, y) at one time t (the rule on the type).
    #[inline]
    pub fn inside_at(&self, x: F, y: F, t: F) -> bool {
        if !self.valid {
            return false;
        }
        let [e0, e1, e2] = self.edge_values(x, y, t);
        let z = F::zero();
        (e0 <= z && e1 <= z && e2 <= z) || (e0 >= z && e1 >= z && e2 >= z)
    }

    /// The inside test and the exact depth of the sample (x, y) at time t in one pass:
    /// `None` exactly when [`TriangleSetup::inside_at`] is false, otherwise the depth
    /// d = Σ e_k z_k(t) / Σ e_k (Gribel 2010, Eq. 11-15, with the perspective-correct
    /// barycentrics λ_k = e_k / Σ e_j of Eq. 11) from the same three edge values the inside
    /// test computed — what a stochastic rasteriser needs per sample (Munkberg 2011, §4.2),
    /// without rebuilding the sample's quadratics and the rational depth.
    ///
    /// At a covered time the e_k share a sign, so d is a convex combination of the vertex
    /// depths (no cancellation; it agrees with [`TriangleSetup::depth_at`] to a few ulps
    /// relative). The result is clamped to the range of the six vertex depths; where
    /// Σ e_k = 0 (the triangle has zero area at t) the mean of the three vertex depths at t
    /// is returned, as [`RationalDepth::eval`](crate::RationalDepth::eval) does. Always finite.
    ///
    /// ```
    /// use edge_eqn::MovingTriangle;
    /// let q = [[0.0, 0.0, 1.0], [8.0, 0.0, 2.0], [0.0, 8.0, 2.0]];
    /// let r = q.map(|[x, y, w]| [x + 4.0, y, w]);
    /// let setup = MovingTriangle::<f64>::new(q, r).setup();
    /// let d = setup.inside_depth_at(3.5, 0.5, 0.5).expect("covered");
    /// assert!((d - setup.depth_at(3.5, 0.5, 0.5)).abs() < 1e-12);
    /// assert_eq!(setup.inside_depth_at(30.0, 30.0, 0.5), None);
    /// ```
    #[inline]
    pub fn inside_depth_at(&self, x: F, y: F, t: F) -> Option<F> {
        if !self.valid {
            return None;
        }
        let [e0, e1, e2] = self.edge_values(x, y, t);
        let z = F::zero();
        if !((e0 <= z && e1 <= z && e2 <= z) || (e0 >= z && e1 >= z && e2 >= z)) {
            return None;
        }
        let (zq, zr) = (&self.zq, &self.zr);
        let zt = |k: usize| zq[k] + t * (zr[k] - zq[k]);
        let (z0, z1, z2) = (zt(0), zt(1), zt(2));
        let d = (e0 * z0 + e1 * z1 + e2 * z2) / (e0 + e1 + e2);
        let d = if d.is_finite() {
            d
        } else {
            (z0 + z1 + z2) * lit(1.0 / 3.0)
        };
        Some(d.max(self.zlo).min(self.zhi))
    }

    /// Exact depth at (x, y) and time t (Gribel 2010, Eq. 15).
    pub fn depth_at(&self, x: F, y: F, t: F) -> F {
        self.sample(x, y).depth_at(t)
    }

    /// Perspective-correct barycentrics (λ₀, λ₁, λ₂) = (1 - u - v, u, v) at (x, y) and time t
    /// (Gribel 2010, Eq. 11-12).
    pub fn barycentrics_at(&self, x: F, y: F, t: F) -> [F; 3] {
        self.sample(x, y).barycentrics(t)
    }

    /// Linear depth over a span at (x, y) with its maximum error (Gribel 2010, Eq. 16).
    pub fn linear_depth(&self, x: F, y: F, span: Span<F>) -> LinearDepth<F> {
        self.sample(x, y).linear_depth(span)
    }

    /// The 2DH determinant det[p₀(t); p₁(t); p₂(t)] (a cubic in t): positive when the triangle
    /// is front-facing at t (all e_k <= 0 inside), zero when it is degenerate at t. A value
    /// beyond the range of `F` saturates at ±`F::max_value()`; an invalid setup returns 0.
    pub fn orientation_at(&self, t: F) -> F {
        if !self.valid {
            return F::zero();
        }
        // e_0 = (p₂ × p₁) · s, so det = p₀ · (p₁ × p₂) = -(coefficients of e_0) · p₀.
        let c = self.edges[0].coefficients_at(t);
        let (a, b) = (self.p0[0], self.p0[1]);
        let p0 = [0, 1, 2].map(|i| a[i] + t * (b[i] - a[i]));
        let det = -(c[0] * p0[0] + c[1] * p0[1] + c[2] * p0[2]);
        if det.is_nan() {
            F::zero()
        } else {
            det.max(-F::max_value()).min(F::max_value())
        }
    }
}
