//! # ewa-splat
//!
//! Motion-blurred EWA surface splatting with 3D spatio-temporal Gaussian kernels.
//!
//! Implements Heinzle, Wolf, Kanamori, Weyrich, Nishita and Gross 2010, "Motion Blur for EWA
//! Surface Splatting", §3-§5: kernels extended along the motion vector (Eq. 12-14), the ray to
//! parameter space mapping and integration line (Eq. 15-17), the closed-form erf line integral
//! (Eq. 18-20), cylinder and octagon bounds (§4.3), A-buffer visibility (§4.4) and motion-path
//! subframes (§5.5).
//!
//! **Status: not implemented yet** (issue 8 builds it). The planned entry point is
//! `line_integral(b, f, delta, ta, tb)`.
