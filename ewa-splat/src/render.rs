//! The renderer-facing entry point: splats in, a linear RGBA image and counters out
//! (Heinzle 2010, §4 and §5).

use crate::abuffer::{self, Scratch};
use crate::approx::{self, Passes};
use crate::bound::{Aabb2, ellipse_aabb, octagon, polygon_row_span};
use crate::camera::{Camera, CameraSetup};
use crate::erf::ErfMethod;
use crate::fragment::Fragment;
use crate::kernel::{Kernel, KernelParams, low_pass};
use crate::shutter::Shutter;
use crate::splat::Splat;
use crate::surface::SurfaceLists;
use arrayvec::ArrayVec;
use glam::{DVec2, DVec3};

/// How visibility between kernels is resolved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Visibility {
    /// The A-buffer of §4.4 (Heinzle 2010): per pixel the exposure is cut at every fragment
    /// end and wherever the visible surface changes (a fragment crossing the nearest one or
    /// its depth tolerance, a depth swap with a surface interval; closed form, depths are
    /// linear in time), so which surface is visible is exact at every instant; each piece
    /// is normalised by its kernel weights (§5.4). The reference of the two modes.
    #[default]
    ABuffer,
    /// The GPU passes of §5.1-§5.4: start/end depth buffers and [t_min, t_max] coverage.
    Approximate,
}

/// Which screen-space bound limits the pixels a kernel is evaluated at (§4.3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Bounding {
    /// Convex hull of the two ellipse boxes (Fig. 5).
    #[default]
    Octagon,
    /// The single combined box of \[SWBG06\].
    Box,
}

/// Settings of one frame; every field is an accuracy or speed knob.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Kernel construction (δ, α, safeguards, low-pass).
    pub kernel: KernelParams,
    /// Number of equidistant subframes the exposure is split into (§5.5), at least 1.
    pub subframes: u32,
    /// A-buffer or GPU-style approximate visibility.
    pub visibility: Visibility,
    /// Shutter response a(t).
    pub shutter: Shutter,
    /// erf evaluation of the line integrals.
    pub erf: ErfMethod,
    /// Screen bound of a kernel.
    pub bounding: Bounding,
    /// Ternary depth-test tolerance as a multiple of the splat's longer tangent axis.
    pub depth_epsilon: f64,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            kernel: KernelParams::default(),
            subframes: 1,
            visibility: Visibility::ABuffer,
            shutter: Shutter::Box,
            erf: ErfMethod::Full,
            bounding: Bounding::Octagon,
            depth_epsilon: 1.0,
        }
    }
}

/// Counters of one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Splats given.
    pub splats: u64,
    /// Kernels built (splats × subframes, minus degenerate ones).
    pub kernels: u64,
    /// Kernels skipped: degenerate axes or entirely behind the eye.
    pub kernels_culled: u64,
    /// Pixels tested against a kernel's cylinder (inside its screen bound).
    pub pixels_tested: u64,
    /// Kernel-pixel fragments with a non-empty time span.
    pub fragments: u64,
    /// Largest fragment count of one pixel.
    pub max_fragments_per_pixel: u64,
    /// Line integrals evaluated (Eq. 19).
    pub line_integrals: u64,
}

/// A rendered frame: linear RGBA with straight alpha, row-major, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixels, `width * height` of them.
    pub pixels: Vec<[f32; 4]>,
    /// Counters.
    pub stats: FrameStats,
}

/// Why a frame could not be rendered.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RenderError {
    /// The view-projection matrix is not finite or not invertible, or the viewport is empty.
    Camera,
    /// The viewport has more than 2²⁴ pixels.
    TooLarge,
    /// A splat (by index) has no keys, a non-finite value or a span outside \[0, 1\] or
    /// empty.
    Splat(usize),
    /// The background colour or a setting is not finite or out of range.
    Settings,
    /// A surface interval (by entry index) is outside the viewport, not finite, has its
    /// ends out of order or alpha outside [0, 1] ([`SurfaceLists::new`]).
    Surface(usize),
    /// Surface lists were given for another viewport size, or with
    /// [`Visibility::Approximate`] (only the A-buffer takes surface intervals).
    Surfaces,
}

impl core::fmt::Display for RenderError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::Camera => write!(
                f,
                "camera matrix is singular or not finite, or the viewport is empty"
            ),
            RenderError::TooLarge => write!(f, "viewport larger than 2^24 pixels"),
            RenderError::Splat(i) => {
                write!(f, "splat {i} has no keys, a non-finite value or a bad span")
            }
            RenderError::Settings => write!(f, "background or settings not finite or out of range"),
            RenderError::Surface(i) => write!(
                f,
                "surface interval {i} is outside the viewport, not finite, has t0 > t1 or alpha outside [0, 1]"
            ),
            RenderError::Surfaces => write!(
                f,
                "surface intervals need A-buffer visibility and lists of the viewport's size"
            ),
        }
    }
}

impl std::error::Error for RenderError {}

fn premultiply(c: [f32; 4]) -> [f64; 4] {
    let a = c[3].clamp(0.0, 1.0) as f64;
    [c[0] as f64 * a, c[1] as f64 * a, c[2] as f64 * a, a]
}

/// Renders motion-blurred EWA splats (Heinzle 2010, §4-§5): builds one 3D kernel per splat
/// and subframe (Eq. 12-14), bounds it on screen (§4.3), integrates it along every covered
/// pixel ray (Eq. 15-20), resolves visibility with the A-buffer (§4.4; cut wherever one
/// splat surface passes through another) or the GPU passes (§5), normalises (§5.4) and
/// blends with `background` (straight-alpha linear RGBA).
///
/// ```
/// use ewa_splat::{Camera, RenderSettings, Splat, render};
/// use glam::DVec3;
/// let camera = Camera::look_at_perspective(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y,
///                                          0.6, 0.1, 100.0, 32, 32);
/// let splat = Splat::moving_disc(DVec3::new(-0.5, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0),
///                                DVec3::Z, 0.3, [1.0, 0.5, 0.2, 1.0]);
/// let frame = render(&camera, &[splat], [0.0, 0.0, 0.0, 1.0], &RenderSettings::default())
///     .unwrap();
/// assert_eq!(frame.pixels.len(), 32 * 32);
/// assert!(frame.pixels[16 * 32 + 16][0] > 0.1); // the blurred streak covers the centre
/// ```
pub fn render(
    camera: &Camera,
    splats: &[Splat],
    background: [f32; 4],
    settings: &RenderSettings,
) -> Result<Frame, RenderError> {
    let none = SurfaceLists::empty(camera.width, camera.height);
    render_with_surfaces(camera, splats, background, settings, &none)
}

/// [`render`] with external surfaces (triangles of a mesh renderer) in the A-buffer
/// (Heinzle 2010, §4.4, extended): each pixel is resolved from its splat fragments and its
/// [`SurfaceInterval`](crate::SurfaceInterval)s together, the exposure cut at every
/// fragment and interval end, at every depth swap between an interval and a fragment or
/// another interval, and wherever the visible splat surface changes (as in [`render`]);
/// per piece the splat surface and the intervals are composited front to
/// back by depth (an opaque interval in front hides the splats; the splat surface covers
/// what is behind it by its normalised alpha), then the background fills the rest. Pixels
/// without intervals are exactly those of [`render`].
///
/// Requires [`Visibility::ABuffer`] and `surfaces` of the camera's viewport size
/// ([`RenderError::Surfaces`] otherwise); with empty lists it is [`render`].
///
/// ```
/// use ewa_splat::{Camera, RenderSettings, Splat, SurfaceInterval, SurfaceLists,
///                 render_with_surfaces};
/// use glam::DVec3;
/// let camera = Camera::look_at_perspective(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y,
///                                          0.6, 0.1, 100.0, 8, 8);
/// let splat = Splat::moving_disc(DVec3::ZERO, DVec3::ZERO, DVec3::Z, 0.5,
///                                [1.0, 0.0, 0.0, 1.0]);
/// // An opaque green triangle 1 unit in front of the splat covers pixel (4, 4) for the
/// // first half of the exposure (depth along the ray: the ray starts on the near plane).
/// let (o, d) = camera.pixel_ray(4.5, 4.5).unwrap();
/// let depth = (DVec3::new(0.0, 0.0, 1.0) - o).dot(d);
/// let green = SurfaceInterval { t0: 0.0, t1: 0.5, depth, depth_slope: 0.0,
///                               colour: [0.0, 1.0, 0.0, 1.0] };
/// let surfaces = SurfaceLists::new(8, 8, &[(4, 4, green)]).unwrap();
/// let frame = render_with_surfaces(&camera, &[splat], [0.0, 0.0, 0.0, 1.0],
///                                  &RenderSettings::default(), &surfaces).unwrap();
/// let p = frame.pixels[4 * 8 + 4];
/// assert!((p[0] - 0.5).abs() < 1e-6 && (p[1] - 0.5).abs() < 1e-6);
/// ```
pub fn render_with_surfaces(
    camera: &Camera,
    splats: &[Splat],
    background: [f32; 4],
    settings: &RenderSettings,
    surfaces: &SurfaceLists,
) -> Result<Frame, RenderError> {
    if surfaces.width() != camera.width
        || surfaces.height() != camera.height
        || (!surfaces.is_empty() && settings.visibility != Visibility::ABuffer)
    {
        return Err(RenderError::Surfaces);
    }
    let cam = CameraSetup::new(camera).ok_or(RenderError::Camera)?;
    let n_pix = camera.width as u64 * camera.height as u64;
    if n_pix > 1 << 24 {
        return Err(RenderError::TooLarge);
    }
    let k = &settings.kernel;
    let settings_ok = background.iter().all(|v| v.is_finite())
        && k.delta.is_finite()
        && k.delta > 0.0
        && k.alpha.is_finite()
        && k.alpha > 0.0
        && k.min_a3_rel.is_finite()
        && k.min_angle.is_finite()
        && k.low_pass_radius.is_finite()
        && settings.depth_epsilon.is_finite()
        && settings.depth_epsilon >= 0.0
        && settings.subframes >= 1
        && settings.subframes <= 4096;
    if !settings_ok {
        return Err(RenderError::Settings);
    }
    for (i, s) in splats.iter().enumerate() {
        if s.keys.is_empty()
            || !s.span_is_valid()
            || !s.keys.iter().all(|k| k.is_finite())
            || !s.colour.iter().all(|c| c.is_finite())
        {
            return Err(RenderError::Splat(i));
        }
    }
    let n_pix = n_pix as usize;
    let (w, h) = (camera.width as usize, camera.height as usize);
    let mut rays = Vec::with_capacity(n_pix);
    for j in 0..h {
        for i in 0..w {
            rays.push(cam.ray(i as f64 + 0.5, j as f64 + 0.5));
        }
    }
    let colours: Vec<[f64; 4]> = splats.iter().map(|s| premultiply(s.colour)).collect();
    let bg = premultiply(background);
    let mut stats = FrameStats {
        splats: splats.len() as u64,
        ..FrameStats::default()
    };
    let nsub = settings.subframes;

    let mut frags: Vec<Fragment> = Vec::new();
    for sub in 0..nsub {
        for (si, splat) in splats.iter().enumerate() {
            emit_kernel(
                &cam, &rays, splat, si as u32, sub, nsub, settings, &mut frags, &mut stats,
            );
        }
    }
    stats.fragments = frags.len() as u64;
    // Group by pixel (and by subframe for the approximate passes).
    frags.sort_by_key(|f| (f.pixel, f.subframe));

    let mut out = vec![bg; n_pix];
    let mut integrals = 0u64;
    match settings.visibility {
        Visibility::ABuffer => {
            let mut scratch = Scratch::default();
            let mut chunks = frags.chunk_by(|a, b| a.pixel == b.pixel).peekable();
            for (p, slot) in out.iter_mut().enumerate() {
                let chunk = match chunks.peek() {
                    Some(c) if c.first().is_some_and(|f| f.pixel as usize == p) => {
                        chunks.next().unwrap_or(&[])
                    }
                    _ => &[],
                };
                let lists = surfaces.pixel(p);
                if chunk.is_empty() && lists.is_empty() {
                    continue;
                }
                stats.max_fragments_per_pixel =
                    stats.max_fragments_per_pixel.max(chunk.len() as u64);
                *slot = abuffer::resolve(
                    chunk,
                    lists,
                    &colours,
                    bg,
                    k.delta,
                    settings.erf,
                    settings.shutter,
                    &mut scratch,
                    &mut integrals,
                );
            }
        }
        Visibility::Approximate => {
            let total = settings.shutter.integral(0.0, 1.0);
            let mut acc = vec![[0.0f64; 4]; n_pix];
            let mut passes = Passes::new(n_pix);
            let mut by_sub: Vec<Vec<&Fragment>> = vec![Vec::new(); nsub as usize];
            for f in &frags {
                if let Some(v) = by_sub.get_mut(f.subframe as usize) {
                    v.push(f);
                }
            }
            for chunk in frags.chunk_by(|a, b| a.pixel == b.pixel) {
                stats.max_fragments_per_pixel =
                    stats.max_fragments_per_pixel.max(chunk.len() as u64);
            }
            for sub in 0..nsub {
                let t0 = sub as f64 / nsub as f64;
                let t1 = (sub + 1) as f64 / nsub as f64;
                let weight = settings.shutter.integral(t0, t1) / total;
                passes.reset();
                let list = by_sub
                    .get(sub as usize)
                    .map(|v| v.as_slice())
                    .unwrap_or(&[]);
                for f in list {
                    passes.splat_depths(f);
                }
                // Pixels without fragments in this subframe show the background.
                for a in acc.iter_mut() {
                    for c in 0..4 {
                        a[c] += weight * bg[c];
                    }
                }
                let sub_frags: Vec<Fragment> = list.iter().map(|f| **f).collect();
                for chunk in sub_frags.chunk_by(|a, b| a.pixel == b.pixel) {
                    let Some(first) = chunk.first() else { continue };
                    let p = first.pixel as usize;
                    let (ds, de) = (
                        passes.depth_start.get(p).copied().unwrap_or(f64::INFINITY),
                        passes.depth_end.get(p).copied().unwrap_or(f64::INFINITY),
                    );
                    let px = approx::resolve_subframe(
                        chunk,
                        ds,
                        de,
                        t0,
                        t1,
                        &colours,
                        bg,
                        k.delta,
                        settings.erf,
                        settings.shutter,
                        &mut integrals,
                    );
                    if let Some(a) = acc.get_mut(p) {
                        for c in 0..4 {
                            a[c] += weight * (px[c] - bg[c]);
                        }
                    }
                }
            }
            out = acc;
        }
    }
    stats.line_integrals = integrals;
    let pixels = out
        .iter()
        .map(|p| {
            let a = p[3].clamp(0.0, 1.0);
            if a > 0.0 {
                [
                    (p[0] / a) as f32,
                    (p[1] / a) as f32,
                    (p[2] / a) as f32,
                    a as f32,
                ]
            } else {
                [0.0; 4]
            }
        })
        .collect();
    Ok(Frame {
        width: camera.width,
        height: camera.height,
        pixels,
        stats,
    })
}

/// Builds the kernel of one splat in one subframe and appends its fragments.
#[allow(clippy::too_many_arguments)]
fn emit_kernel(
    cam: &CameraSetup,
    rays: &[Option<(DVec3, DVec3)>],
    splat: &Splat,
    si: u32,
    sub: u32,
    nsub: u32,
    settings: &RenderSettings,
    frags: &mut Vec<Fragment>,
    stats: &mut FrameStats,
) {
    let params = &settings.kernel;
    // The subframe, cut to the splat's span (a splat on part of the exposure has no
    // kernel in the subframes outside it).
    let [s0, s1] = splat.span;
    let t0 = (sub as f64 / nsub as f64).max(s0);
    let t1 = ((sub + 1) as f64 / nsub as f64).min(s1);
    if t0 >= t1 {
        return;
    }
    let (Some(k0), Some(k1)) = (splat.key_at(t0), splat.key_at(t1)) else {
        stats.kernels_culled += 1;
        return;
    };
    let centre = 0.5 * (k0.centre + k1.centre);
    let motion = k1.centre - k0.centre;
    let mut a1 = 0.5 * (k0.axis_u + k1.axis_u);
    let mut a2 = 0.5 * (k0.axis_v + k1.axis_v);
    if let Some(jac) = cam.jacobian(centre) {
        a1 = low_pass(a1, jac, params.low_pass_radius);
        a2 = low_pass(a2, jac, params.low_pass_radius);
    }
    let a3 = 0.5 * params.alpha * motion;
    let time_mid = 0.5 * (t0 + t1);
    let time_half = 0.5 * params.alpha * (t1 - t0);
    let Some(kernel) = Kernel::new(centre, a1, a2, a3, time_mid, time_half, params) else {
        stats.kernels_culled += 1;
        return;
    };
    stats.kernels += 1;
    let a3 = kernel.axes[2];
    let eps = settings.depth_epsilon * a1.length().max(a2.length());

    // Screen bound: the two cut-off ellipses (§4.3); unbounded when one crosses the eye plane.
    let (w, h) = (cam.width as f64, cam.height as f64);
    let full = Aabb2 {
        min: DVec2::ZERO,
        max: DVec2::new(w, h),
    };
    let e0 = ellipse_aabb(&cam.screen, centre - a3, a1, a2);
    let e1 = ellipse_aabb(&cam.screen, centre + a3, a1, a2);
    let poly: ArrayVec<DVec2, 8> = match (e0, e1, settings.bounding) {
        (Some(p), Some(q), Bounding::Octagon) => octagon(&p, &q),
        (Some(p), Some(q), Bounding::Box) => {
            let u = p.union(&q);
            octagon(&u, &u)
        }
        _ => octagon(&full, &full),
    };
    let (mut ymin, mut ymax) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in &poly {
        ymin = ymin.min(v.y);
        ymax = ymax.max(v.y);
    }
    let row0 = (ymin - 0.5).ceil().max(0.0);
    let row1 = (ymax - 0.5).floor().min(h - 1.0);
    if row0.is_nan() || row1.is_nan() || row0 > row1 {
        return;
    }
    for j in row0 as usize..=row1 as usize {
        let y = j as f64 + 0.5;
        let Some((xl, xr)) = polygon_row_span(&poly, y) else {
            continue;
        };
        let c0 = (xl - 0.5).ceil().max(0.0);
        let c1 = (xr - 0.5).floor().min(w - 1.0);
        if c0.is_nan() || c1.is_nan() || c0 > c1 {
            continue;
        }
        for i in c0 as usize..=c1 as usize {
            let p = j * cam.width as usize + i;
            stats.pixels_tested += 1;
            let Some(Some((o, d))) = rays.get(p) else {
                continue;
            };
            let Some(line) = kernel.ray_line(*o, *d) else {
                continue;
            };
            let Some(span) = Kernel::cylinder_span(&line) else {
                continue;
            };
            if let Some(f) = Fragment::new(p as u32, si, sub, &kernel, line, span, eps, splat.span)
            {
                frags.push(f);
            }
        }
    }
}
