//! # edge-eqn
//!
//! Exact time coverage and depth of a linearly moving triangle at one sample point, after
//! Gribel, Doggett and Akenine-Möller 2010, "Analytical Motion Blur Rasterization with
//! Compression", §3-§5. A triangle given in 2DH at shutter open and close
//! ([`MovingTriangle::new`]) is set up once ([`MovingTriangle::setup`]) into three
//! time-dependent edge equations whose coefficients are quadratics in t (Eq. 3-5,
//! [`MovingEdge`]). At a sample each edge becomes e(t) = α t² + β t + γ (Eq. 7,
//! [`EdgeQuadratic`]), whose sign changes come from a robust, public quadratic solver
//! ([`quadratic::real_roots`]); the three inside functions combine into at most four covered
//! spans (Eq. 8-9, [`TriangleSetup::coverage`] returning [`Coverage`] of [`Span`]s). Along a
//! span the crate gives the perspective-correct barycentrics (Eq. 11-12), the exact rational
//! depth (Eq. 13-15, [`RationalDepth`]) and its linear approximation with the fit's maximum
//! error (Eq. 16, [`LinearDepth`]), all from one [`SampleEquations`]
//! ([`TriangleSetup::sample`]). The per-sample inside test at one time
//! ([`TriangleSetup::inside_at`]) is what stochastic rasterisers (Munkberg 2011, §4.2) call;
//! [`TriangleSetup::inside_depth_at`] returns the exact depth of a covered sample from the
//! same edge values in one pass.
//!
//! Everything is generic over [`num_traits::Float`]; f32 is the fast default, f64 the
//! accuracy knob (span ends agree to about 1e-5 in t; see the workspace's `docs/BENCHMARKS.md`). The second knob
//! is exact depth ([`SampleEquations::depth_at`], Eq. 15) versus the linear depth stored in
//! intervals ([`SampleEquations::linear_depth`], Eq. 16), whose `max_error` reports what the
//! approximation costs on each span.
//!
//! The inside rule accepts both windings (see [`TriangleSetup`] for the orientation rule and
//! the documented result for vertices behind the eye); a static triangle (q = r) is one
//! ordinary inside test with no quadratic solved.
//!
//! ```
//! use edge_eqn::MovingTriangle;
//! let q = [[10.0, 10.0, 1.0], [30.0, 10.0, 1.0], [10.0, 30.0, 1.0]];
//! let r = q.map(|[x, y, w]| [x + 20.0, y, w]);
//! let setup = MovingTriangle::<f32>::new(q, r).setup();
//! let cov = setup.coverage(35.5, 12.5);
//! assert_eq!(cov.len(), 1);
//! assert!(setup.inside_at(35.5, 12.5, cov[0].mid()));
//! ```

pub mod depth;
pub mod edge;
pub mod quadratic;
pub mod sample;
pub mod span;
pub mod triangle;

pub use depth::{LinearDepth, RationalDepth};
pub use edge::{EdgeQuadratic, MovingEdge};
pub use sample::SampleEquations;
pub use span::{Coverage, MAX_SPANS, Span};
pub use triangle::{MovingTriangle, TriangleSetup};
