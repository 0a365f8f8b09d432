//! # edge-eqn
//!
//! Exact time coverage and depth of a linearly moving triangle at one sample point.
//!
//! Implements Gribel, Doggett and Akenine-Möller 2010, "Analytical Motion Blur Rasterization
//! with Compression", §3-§4: time-dependent edge equations whose coefficients are quadratics
//! in t (Eq. 3-5), the per-sample quadratic e(t) = α t² + β t + γ (Eq. 7), the inside and
//! visibility functions (Eq. 8-9), perspective-correct barycentrics and the cubic rational
//! depth (Eq. 11-15), and the linear depth approximation stored in intervals (Eq. 16).
//!
//! **Status: not implemented yet** (issue 3 builds it). The planned entry points are
//! `MovingTriangle::new(q, r)`, `MovingTriangle::setup()`, `TriangleSetup::coverage(x, y)` and
//! the public robust solver `quadratic::real_roots(a, b, c)`.
