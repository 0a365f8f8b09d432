//! The `ewa` method: motion-blurred EWA surface splatting of the scene's splats with the
//! `ewa-splat` crate (Heinzle, Wolf, Kanamori, Weyrich, Nishita and Gross 2010, §4-§5).
//!
//! Every [`PreparedSplat`] becomes an [`ewa_splat::Splat`]: a circular disc (tangent axes of
//! the splat's radius, reaching the kernel's cut-off) with one key when it does not move
//! (the static kernel, no temporal axis to speak of) or two keys, shutter open and close,
//! when it does (the 3D spatio-temporal kernel of Eq. 12-14, integrated along each pixel ray
//! in closed form, Eq. 15-20). Visibility is the A-buffer of §4.4 or the approximate GPU
//! passes of §5 (`--visibility`), the exposure may be cut into subframes (§5.5,
//! `--subframes`) and the erf evaluation is a knob (`--erf`).
//!
//! **Camera.** The ewa camera is mblur's shutter-open camera: `view_proj = clip_from_view *
//! view`, and ewa-splat's viewport (x = (ndc_x + 1) W / 2, y = (1 - ndc_y) H / 2, pixel
//! centres at i + 0.5, row 0 at the top) is exactly mblur's `pixel_from_clip`. **Camera
//! motion** is expressed as splat motion in the open camera's frame: the close key is
//! carried through `M = view_open⁻¹ · view_close`, so the open camera sees it where the
//! close camera sees the original. Both views are rigid and the projection does not change,
//! so `M` is affine, linear interpolation commutes with it and the 2DH path of every splat
//! centre is exactly mblur's (Gribel 2010, Eq. 2).
//!
//! **Parallelism.** The image is cut into bands of rows; each band is rendered by ewa-splat
//! with a cropped camera (the clip-space y row rescaled so that the band fills the
//! viewport), which gives the same pixel rays, Jacobians and fragments as the full frame.
//!
//! **Triangles** (scenes mixing meshes and splats): the triangles go through the analytic
//! chain's per-pixel emission (edge-eqn coverage spans with linear depth for moving
//! triangles, one `[0, 1]` interval from the static rasteriser for static ones, time slices
//! for near-plane crossings, time-dependent back-face culling; Gribel 2010) in f64, band by
//! band, and enter ewa-splat's A-buffer as surface intervals with their depth converted to
//! the ray parameter and a shaded premultiplied colour (see `surfaces.rs`):
//! [`ewa_splat::render_with_surfaces`] composites them with the splat surface per piece of
//! the exposure, cut at every interval end and depth swap (Heinzle 2010, §4.4, extended).
//! Opaque triangles in front hide the splats, splats in front cover the triangles by their
//! normalised alpha, transparent triangles composite front to back. This needs the
//! A-buffer: `--visibility approx` on a scene with triangles is an error.
//!
//! **Not supported** (a clear [`Error::MethodNotApplicable`], never a silent substitute):
//! scenes without splats (use `analytic`), transparent splats (ewa-splat composites a splat
//! surface by its alpha over what is behind it but does not order several splat surfaces),
//! the approximate visibility with triangles, and shutter responses other than the box
//! (ewa-splat integrates a box or the paper's Gaussian response, not mblur's
//! piecewise-linear ones).

use std::fmt;
use std::str::FromStr;

use glam::{DAffine3, DMat4, DQuat, DVec3, DVec4};
use rayon::prelude::*;

use ewa_splat::{Camera, RenderSettings, Splat, SplatKey, SurfaceLists};
pub use ewa_splat::{ErfMethod, Visibility};

use crate::chain::{Routes, plural};
use crate::effects::Pipeline;
use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepared::{PreparedScene, PreparedSplat};
use crate::progress::Progress;
use crate::surfaces::{Band, Triangles};

/// Rows per parallel band.
const BAND_ROWS: u32 = 16;
/// Largest accepted `--subframes` (ewa-splat's own limit).
pub const MAX_SUBFRAMES: u32 = 4096;

/// Options of the `ewa` method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EwaOptions {
    /// Equidistant subframes of the motion path (Heinzle 2010, §5.5), 1..=4096.
    pub subframes: u32,
    /// A-buffer (§4.4: which surface is in front is exact at every instant; kernels fixed
    /// per subframe) or the approximate GPU passes (§5).
    pub visibility: Visibility,
    /// erf evaluation of the line integrals (Eq. 19).
    pub erf: ErfMethod,
}

impl Default for EwaOptions {
    fn default() -> Self {
        EwaOptions {
            subframes: 1,
            visibility: Visibility::ABuffer,
            erf: ErfMethod::Full,
        }
    }
}

/// `--visibility` values: `abuffer` or `approx`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VisibilityArg(pub Visibility);

impl FromStr for VisibilityArg {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        let all = [Visibility::ABuffer, Visibility::Approximate];
        crate::names::parse_by_name(s, &all, visibility_name, "visibility").map(VisibilityArg)
    }
}

impl fmt::Display for VisibilityArg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(visibility_name(self.0))
    }
}

/// `--erf` values: `full`, `poly` or `table`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ErfArg(pub ErfMethod);

impl FromStr for ErfArg {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        let all = [ErfMethod::Full, ErfMethod::Polynomial, ErfMethod::Table];
        crate::names::parse_by_name(s, &all, erf_name, "erf method").map(ErfArg)
    }
}

impl fmt::Display for ErfArg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(erf_name(self.0))
    }
}

fn visibility_name(v: Visibility) -> &'static str {
    match v {
        Visibility::ABuffer => "abuffer",
        Visibility::Approximate => "approx",
    }
}

fn erf_name(e: ErfMethod) -> &'static str {
    match e {
        ErfMethod::Full => "full",
        ErfMethod::Polynomial => "poly",
        ErfMethod::Table => "table",
    }
}

fn not_applicable(reason: String) -> Error {
    Error::MethodNotApplicable {
        method: "ewa".into(),
        reason,
    }
}

fn name_list(names: &[&str]) -> String {
    match names.len() {
        0..=4 => names.join(", "),
        n => format!("{}, ... {} more", names[..3].join(", "), n - 3),
    }
}

/// Checks that the scene is something `ewa` renders: splats (all opaque), with or without
/// triangles, box shutter.
pub fn check_scene(scene: &PreparedScene) -> Result<()> {
    if scene.splats.is_empty() {
        return Err(not_applicable(
            "ewa renders splat-only scenes and splats mixed with triangles; the scene has no \
             splats (use analytic for a triangle-only scene)"
                .into(),
        ));
    }
    let transparent: Vec<&str> = scene
        .splat_objects
        .iter()
        .filter(|o| {
            scene
                .splats
                .get(o.range.clone())
                .is_some_and(|s| s.iter().any(|s| s.color[3] < 1.0))
        })
        .map(|o| o.name.as_str())
        .collect();
    if !transparent.is_empty() {
        return Err(not_applicable(format!(
            "transparent splats (alpha < 1) in {} are not supported: ewa-splat composites \
             splat alpha over the background only, not between surfaces",
            name_list(&transparent)
        )));
    }
    if !scene.shutter.is_box() {
        return Err(not_applicable(
            "only the box shutter response is supported (ewa-splat integrates a box or \
             Gaussian response, not tent or piecewise-linear ones)"
                .into(),
        ));
    }
    Ok(())
}

/// True for a splat-only scene (splats and no triangles; `compare` takes the ewa A-buffer
/// as its reference for those).
pub fn applies(scene: &PreparedScene) -> bool {
    scene.triangles.is_empty() && !scene.splats.is_empty()
}

/// True when `auto` picks `ewa`: the scene has splats, with or without triangles, and
/// nothing [`check_scene`] refuses.
pub fn accepts(scene: &PreparedScene) -> bool {
    check_scene(scene).is_ok()
}

/// The ewa-splat camera of the whole image: mblur's shutter-open camera (world to OpenGL
/// clip space; ewa-splat applies the same viewport as mblur's `pixel_from_clip`).
pub fn camera(scene: &PreparedScene) -> Camera {
    let c = &scene.camera_open;
    Camera {
        view_proj: c.clip_from_view * c.view,
        width: scene.width,
        height: scene.height,
    }
}

/// The camera of rows `y0..y0 + rows` of `full`: clip y is remapped so that the band fills
/// the viewport, y' = a y + b w with a = H / h and b = 1 - (H - 2 y0) / h, leaving every
/// pixel's ray and the pixel-unit Jacobian unchanged.
pub fn band_camera(full: &Camera, y0: u32, rows: u32) -> Camera {
    let (hh, h, y0) = (f64::from(full.height), f64::from(rows), f64::from(y0));
    let a = hh / h;
    let b = 1.0 - (hh - 2.0 * y0) / h;
    let crop = DMat4::from_cols(
        DVec4::new(1.0, 0.0, 0.0, 0.0),
        DVec4::new(0.0, a, 0.0, 0.0),
        DVec4::new(0.0, 0.0, 1.0, 0.0),
        DVec4::new(0.0, b, 0.0, 1.0),
    );
    Camera {
        view_proj: crop * full.view_proj,
        width: full.width,
        height: rows,
    }
}

/// World (shutter-close) to the open camera's frame: `view_open⁻¹ · view_close`. Identity
/// when the camera does not move.
pub fn close_to_open(scene: &PreparedScene) -> DAffine3 {
    if !scene.camera_moves() {
        return DAffine3::IDENTITY;
    }
    let m = scene.camera_open.view.inverse() * scene.camera_close.view;
    DAffine3::from_mat4(m)
}

/// World at normalised time `t` to the open camera's frame: `view_open⁻¹ · V(t)` with
/// `V(t)` the blend `(1 - u) view_a + u view_b` of the camera's poses around `t` (its keys,
/// or open and close). mblur's 2DH position of a point at `t` is the same blend of its
/// projections, and the projection is linear, so the open camera sees the carried point
/// exactly there; `V(t)` is affine (a blend of rigid maps), not rigid.
pub fn camera_carry(scene: &PreparedScene, t: f64) -> DAffine3 {
    if !scene.camera_moves() || t <= 0.0 {
        return DAffine3::IDENTITY;
    }
    let keys = &scene.camera_keys;
    let (a, b, u) = if keys.is_empty() {
        if t >= 1.0 {
            return close_to_open(scene);
        }
        (&scene.camera_open, &scene.camera_close, t)
    } else {
        let (i, u) = crate::motion::key_pair(keys, |k| k.t, t);
        match (keys.get(i), keys.get(i + 1)) {
            (Some(a), Some(b)) => (&a.frame, &b.frame, u),
            _ => (&scene.camera_open, &scene.camera_open, 0.0),
        }
    };
    let view = if u <= 0.0 {
        a.view
    } else if u >= 1.0 {
        b.view
    } else {
        a.view * (1.0 - u) + b.view * u
    };
    DAffine3::from_mat4(scene.camera_open.view.inverse() * view)
}

/// A splat's disc key: axes of length `radius` spanning the plane normal to `normal`.
fn key(centre: DVec3, u: DVec3, v: DVec3, radius: f64) -> SplatKey {
    SplatKey {
        centre,
        axis_u: u * radius,
        axis_v: v * radius,
    }
}

/// `k` carried into the open camera's frame by `m`.
fn carried(k: SplatKey, m: &DAffine3) -> SplatKey {
    SplatKey {
        centre: m.transform_point3(k.centre),
        axis_u: m.transform_vector3(k.axis_u),
        axis_v: m.transform_vector3(k.axis_v),
    }
}

/// The ewa-splat splat of one prepared splat over the whole shutter: one key when it does
/// not move (`moving`: [`PreparedScene::splat_moves`]), else keys at shutter open and close
/// (the close key carried into the open camera's frame by `m`). The close tangent frame is
/// the open one rotated by the shortest arc between the normals, so the axes interpolate
/// without twisting.
pub fn to_ewa_splat(s: &PreparedSplat, m: &DAffine3, moving: bool) -> Splat {
    to_ewa_splat_coloured(s, s.color, m, moving)
}

/// Instants at which a lit splat is shaded; its kernel takes their mean colour.
pub const SPLAT_SHADING_SAMPLES: u32 = 16;

/// The straight-alpha colour of splat `s` for its kernel: its own colour when its object is
/// unlit, else the mean over [`SPLAT_SHADING_SAMPLES`] instants (midpoints of equal strata
/// of its span; ewa renders box shutters only) of [`PreparedScene::shade_point`] at its
/// centre with its normal, both interpolated linearly over the span (a splat kernel has
/// one colour).
pub fn splat_colour(scene: &PreparedScene, s: &PreparedSplat) -> [f64; 4] {
    let Some(m) = scene.splat_material(s) else {
        return s.color;
    };
    let n = SPLAT_SHADING_SAMPLES;
    let [t0, t1] = s.span;
    let mut sum = [0.0; 4];
    for k in 0..n {
        let u = (f64::from(k) + 0.5) / f64::from(n);
        let t = (1.0 - u) * t0 + u * t1;
        let centre = s.centre_open.lerp(s.centre_close, u);
        let normal = s.normal_open.lerp(s.normal_close, u).normalize_or_zero();
        let c = scene.shade_point(m, s.color, centre, normal, t);
        for (a, c) in sum.iter_mut().zip(c) {
            *a += c / f64::from(n);
        }
    }
    let a = sum[3];
    if a > 0.0 {
        [sum[0] / a, sum[1] / a, sum[2] / a, a]
    } else {
        [0.0; 4]
    }
}

/// [`to_ewa_splat`] with the kernel colour `color` (straight alpha).
pub fn to_ewa_splat_coloured(
    s: &PreparedSplat,
    color: [f64; 4],
    m: &DAffine3,
    moving: bool,
) -> Splat {
    let colour = color.map(|c| c as f32);
    let (open, close) = world_keys(s);
    if !moving {
        return Splat::fixed(open, colour);
    }
    Splat::linear(open, carried(close, m), colour)
}

/// The world keys of `s` at the ends of its span from its prepared centres, normals and
/// radii: the open tangent frame any orthonormal pair of its normal, the close one that
/// frame rotated by the shortest arc between the normals.
fn world_keys(s: &PreparedSplat) -> (SplatKey, SplatKey) {
    let n0 = s.normal_open.normalize_or(DVec3::Z);
    let (u0, v0) = n0.any_orthonormal_pair();
    let n1 = s.normal_close.normalize_or(DVec3::Z);
    let q = DQuat::from_rotation_arc(n0, n1);
    (
        key(s.centre_open, u0, v0, s.radius_open),
        key(s.centre_close, q * u0, q * v0, s.radius_close),
    )
}

/// The ewa-splat splat of `s` with kernel colour `color`. A splat over the whole shutter
/// is [`to_ewa_splat_coloured`]; a segment (a piece of a curved path or of the camera's
/// keys) is a splat over its span with keys at the span's ends, each carried into the
/// open camera's frame by [`camera_carry`] at its instant. On a curved path the keys are
/// the object-space disc moved by the path ([`PreparedScene::splat_disc_at`]): ends on the
/// true path, tangent axes turning with it.
pub fn ewa_splat(scene: &PreparedScene, s: &PreparedSplat, color: [f64; 4]) -> Splat {
    let moving = scene.splat_moves(s);
    if s.span == [0.0, 1.0] && s.local.is_none() {
        return to_ewa_splat_coloured(s, color, &close_to_open(scene), moving);
    }
    let [t0, t1] = s.span;
    let disc = |t: f64| {
        scene.splat_disc_at(s, t).map(|[c, u, v]| SplatKey {
            centre: c,
            axis_u: u,
            axis_v: v,
        })
    };
    let (open, close) = match (disc(t0), disc(t1)) {
        (Some(a), Some(b)) => (a, b),
        _ => world_keys(s),
    };
    let colour = color.map(|c| c as f32);
    Splat::linear(
        carried(open, &camera_carry(scene, t0)),
        carried(close, &camera_carry(scene, t1)),
        colour,
    )
    .over(s.span)
}

/// All of the scene's splats for ewa-splat.
pub fn ewa_splats(scene: &PreparedScene) -> Vec<Splat> {
    scene
        .splats
        .iter()
        .map(|s| ewa_splat(scene, s, splat_colour(scene, s)))
        .collect()
}

impl EwaOptions {
    fn settings(&self, pipeline: &Pipeline) -> RenderSettings {
        RenderSettings {
            // A static scene has no motion path to subdivide.
            subframes: if pipeline.motion { self.subframes } else { 1 },
            visibility: self.visibility,
            erf: self.erf,
            ..RenderSettings::default()
        }
    }
}

/// The triangle part of `describe`: empty for a splat-only scene.
fn describe_triangles(scene: &PreparedScene, p: &Pipeline) -> String {
    if scene.triangles.is_empty() {
        return String::new();
    }
    let n = scene.triangles.len();
    let r = Routes::of(scene);
    let culled = crate::cull::Culling::of(scene).counts(scene, crate::cull::Motion::Homogeneous);
    format!(
        "; {n} triangle{} composited in the A-buffer as surface intervals: {} (one [0, 1] \
         interval); {} back-facing triangles of opaque closed meshes culled, {} clipped to the \
         times they face the eye; {}{}f64 arithmetic",
        plural(n),
        r.summary("edge-eqn"),
        culled.culled,
        culled.clipped,
        if p.transparency {
            "transparent surfaces composited front to back; "
        } else {
            "opaque; "
        },
        if p.textures {
            "textured intervals shaded by the tap filter; "
        } else {
            ""
        },
    )
}

impl EwaOptions {
    /// Checks the options: `subframes` in 1..=[`MAX_SUBFRAMES`].
    pub fn validate(&self) -> Result<()> {
        let n = self.subframes;
        if n == 0 || n > MAX_SUBFRAMES {
            return Err(Error::Setting {
                method: "ewa",
                setting: "subframes",
                message: format!("must be between 1 and {MAX_SUBFRAMES}, got {n}"),
            });
        }
        Ok(())
    }

    /// One line saying what the method will do for this pipeline.
    pub fn describe(&self, scene: &PreparedScene, pipeline: &Pipeline) -> String {
        let moving = ewa_splats(scene)
            .iter()
            .filter(|s| s.keys.len() > 1)
            .count();
        let s = self.settings(pipeline);
        let motion = if pipeline.motion {
            format!(
                "{moving} moving (3D spatio-temporal kernels{}), {} static",
                if scene.camera_moves() {
                    ", camera motion as splat motion"
                } else {
                    ""
                },
                scene.splats.len() - moving
            )
        } else {
            "all static (2D kernels, no motion path)".into()
        };
        format!(
            "ewa: {} splats, {motion}; {} subframe{}, visibility {}, erf {}{}",
            scene.splats.len(),
            s.subframes,
            if s.subframes == 1 { "" } else { "s" },
            visibility_name(s.visibility),
            erf_name(s.erf),
            describe_triangles(scene, pipeline)
        )
    }

    /// Renders the scene's splats, and its triangles as A-buffer surfaces.
    pub fn render(
        &self,
        scene: &PreparedScene,
        pipeline: &Pipeline,
        progress: &dyn Progress,
    ) -> Result<Image> {
        self.validate()?;
        check_scene(scene)?;
        let settings = self.settings(pipeline);
        let triangles = if scene.triangles.is_empty() {
            None
        } else {
            if settings.visibility != Visibility::ABuffer {
                return Err(not_applicable(
                    "the approximate visibility (--visibility approx, Heinzle 2010 §5) cannot \
                     take triangle intervals; a scene with triangles needs --visibility abuffer"
                        .into(),
                ));
            }
            Some(Triangles::new(scene, BAND_ROWS))
        };
        let splats = ewa_splats(scene);
        let full = camera(scene);
        let bg = scene.background;
        let background = [bg[0] as f32, bg[1] as f32, bg[2] as f32, 1.0];
        let view = scene.camera_open.view;
        let bands: Vec<u32> = (0..scene.height.div_ceil(BAND_ROWS)).collect();
        progress.start(bands.len() as u64, "bands of 16 rows");
        let parts: Vec<Result<ewa_splat::Frame>> = bands
            .par_iter()
            .map(|&b| {
                let y0 = b * BAND_ROWS;
                let rows = BAND_ROWS.min(scene.height - y0);
                let cam = band_camera(&full, y0, rows);
                let lists = match &triangles {
                    Some(t) => {
                        let band = Band {
                            camera: &cam,
                            view: &view,
                            y0,
                        };
                        t.band(scene, pipeline, band)?
                    }
                    None => SurfaceLists::empty(cam.width, cam.height),
                };
                let r =
                    ewa_splat::render_with_surfaces(&cam, &splats, background, &settings, &lists)
                        .map_err(|e| not_applicable(format!("ewa-splat: {e}")));
                progress.advance(1);
                r
            })
            .collect();
        progress.finish();
        let mut pixels = Vec::with_capacity(scene.width as usize * scene.height as usize);
        for part in parts {
            let frame = part?;
            // Opaque background: the frame's alpha is 1 and its colour is final.
            pixels.extend(
                frame.pixels.iter().map(|p| {
                    [p[0], p[1], p[2]].map(|c| if c.is_finite() { c.max(0.0) } else { 0.0 })
                }),
            );
        }
        Ok(Image {
            width: scene.width,
            height: scene.height,
            pixels,
        })
    }
}
