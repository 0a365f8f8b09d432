//! # ewa-splat
//!
//! Motion-blurred EWA surface splatting with 3D spatio-temporal Gaussian kernels, after
//! Heinzle, Wolf, Kanamori, Weyrich, Nishita and Gross 2010, "Motion Blur for EWA Surface
//! Splatting", §3-§5. Each surface splat (centre, tangent axes a1, a2) moving by m over a
//! subframe becomes an ellipsoidal Gaussian with temporal axis a3 = (α/2) m, kept
//! well-conditioned by a minimum length and a minimum angle to the splat plane (Eq. 12-14,
//! [`Kernel`]); a pixel ray is mapped to the kernel's parameter space and re-parametrised by
//! time (Eq. 15-17, [`RayLine`]); the Gaussian is integrated along it in closed form with erf
//! (Eq. 18-20, [`line_integral`]), robustly in the tails and for near-static kernels, with the
//! erf evaluation as an accuracy knob ([`ErfMethod`]). Kernels are bounded by their cylinder
//! (Eq. 21) and on screen by the octagon hull of two boxes (§4.3, [`octagon`]); visibility is
//! resolved by the A-buffer of §4.4 (cut wherever the visible surface changes, so that one
//! splat surface passing through another switches at the exact crossing) or by the paper's
//! approximate GPU passes (§5), followed by normalisation (§5.4) and motion-path subframes
//! (§5.5). The README lists what is exact and what is approximated, with measured errors.
//!
//! Entry points: [`line_integral`] (f64) / [`line_integral_f32`] / [`line_integral_with`]
//! for the integral alone, and [`render()`] for a whole frame (a [`Camera`], [`Splat`]s, a
//! background colour and [`RenderSettings`] in; a [`Frame`] of linear RGBA and
//! [`FrameStats`] out). [`render_with_surfaces`] resolves the splats together with external
//! surfaces — per-pixel time intervals of triangles with depth linear in time along
//! [`Camera::pixel_ray`] and a premultiplied colour ([`SurfaceInterval`], [`SurfaceLists`])
//! — in the same A-buffer (§4.4), so a mesh renderer composites motion-blurred splats with
//! its motion-blurred triangles. The crate does no I/O.

mod abuffer;
mod approx;
pub mod bound;
mod camera;
pub mod erf;
mod fragment;
mod integral;
mod kernel;
mod render;
mod shutter;
mod splat;
mod split;
mod surface;

pub use bound::{Aabb2, ellipse_aabb, octagon, polygon_contains};
pub use camera::Camera;
pub use erf::{ErfMethod, Real};
pub use integral::{line_integral, line_integral_f32, line_integral_with};
pub use kernel::{Kernel, KernelParams, RayLine, low_pass};
pub use render::{
    Bounding, Frame, FrameStats, RenderError, RenderSettings, Visibility, render,
    render_with_surfaces,
};
pub use shutter::Shutter;
pub use splat::{Splat, SplatKey};
pub use surface::{SurfaceInterval, SurfaceLists};
