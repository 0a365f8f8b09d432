//! The prepared scene: world-space triangles at shutter open and close, per-vertex 2DH
//! positions and view depths for both camera poses, materials and textures — the input
//! contract every rendering method consumes (`mblur-scene` builds it from a scene file).
//!
//! A triangle moves linearly in 2DH over its time span (Gribel 2010, Eq. 2); camera motion is
//! folded in by projecting the positions at the span's start with the camera there and the
//! positions at its end with the camera there. Straight motion is one span, the whole
//! shutter; curved motion ([`crate::motion`]) is several consecutive spans per source
//! triangle, each a chord whose ends lie on the true path.

use glam::{DAffine3, DVec2, DVec3};

use crate::camera::{CameraFrame, Vertex2dh};
use crate::lighting::{Light, ShadingModel};
use crate::motion::{CameraKey, MotionPath, project_at};
use crate::shutter::Shutter;
use crate::texture::Texture;

/// A surface material: straight-alpha linear colour times an optional texture (the
/// albedo), lit by the scene's lights according to its [`ShadingModel`]
/// ([`crate::lighting`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Linear RGBA, straight alpha.
    pub color: [f64; 4],
    /// Index into [`PreparedScene::textures`].
    pub texture: Option<u32>,
    /// How it responds to light; [`ShadingModel::Unlit`] ignores the lights.
    pub shading: ShadingModel,
    /// Specular colour (linear RGB) of the Blinn-Phong lobe.
    pub specular: [f64; 3],
    /// Blinn-Phong exponent (`>= 0`).
    pub shininess: f64,
    /// Emitted radiance (linear RGB), added to lit materials whatever the lights.
    pub emissive: [f64; 3],
}

impl Material {
    /// An unlit material: `color` (straight RGBA) times the optional texture.
    pub fn unlit(color: [f64; 4], texture: Option<u32>) -> Self {
        Material {
            color,
            texture,
            shading: ShadingModel::Unlit,
            specular: [0.0; 3],
            shininess: 0.0,
            emissive: [0.0; 3],
        }
    }

    /// True when the lights shade it (any model but [`ShadingModel::Unlit`]).
    pub fn is_lit(&self) -> bool {
        self.shading != ShadingModel::Unlit
    }
}

/// One triangle ready to render: world positions, 2DH vertices and depth at the start
/// ("open") and end ("close") of its time span, UVs and normals.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedTriangle {
    /// Index into [`PreparedScene::objects`].
    pub object: u32,
    /// Index into [`PreparedScene::materials`].
    pub material: u32,
    /// World-space corners at shutter open.
    pub world_open: [DVec3; 3],
    /// World-space corners at shutter close.
    pub world_close: [DVec3; 3],
    /// 2DH corners (pixel units, before division by w) and view depth at shutter open (q).
    pub open: [Vertex2dh; 3],
    /// 2DH corners and view depth at shutter close (r).
    pub close: [Vertex2dh; 3],
    /// Texture coordinates per corner.
    pub uv: [DVec2; 3],
    /// World-space unit normals at open.
    pub normal_open: [DVec3; 3],
    /// World-space unit normals at close.
    pub normal_close: [DVec3; 3],
    /// The part `[t0, t1]` of the normalised shutter the triangle exists in: `[0, 1]` for
    /// straight motion, one segment of a curved path otherwise (`open` is at `t0`, `close`
    /// at `t1`).
    pub span: [f64; 2],
    /// Corner positions in the object's space (before placement and motion) when the
    /// object's path is curved ([`ObjectInfo::path`]); `None` for straight motion.
    pub local: Option<[DVec3; 3]>,
}

/// The local time u ∈ \[0, 1\] of shutter time `t` in the span `[t0, t1]` (0 for an empty
/// span).
pub(crate) fn span_local_time([t0, t1]: [f64; 2], t: f64) -> f64 {
    if t1 > t0 {
        ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

impl PreparedTriangle {
    /// The corners at time u ∈ \[0, 1\] local to the span: p(u) = (1 - u) q + u r (Gribel
    /// 2010, Eq. 2).
    pub fn at(&self, u: f64) -> [Vertex2dh; 3] {
        [0, 1, 2].map(|k| self.open[k].lerp(self.close[k], u))
    }

    /// True when the triangle exists at normalised shutter time `t`: `t` in `[t0, t1)`, or
    /// `t = t1` for the span ending at shutter close, so consecutive spans take every
    /// instant exactly once.
    pub fn exists_at(&self, t: f64) -> bool {
        let [t0, t1] = self.span;
        t0 <= t && (t < t1 || (t1 >= 1.0 && t <= t1))
    }

    /// The local time u ∈ \[0, 1\] of shutter time `t` in the span.
    pub fn local_time(&self, t: f64) -> f64 {
        span_local_time(self.span, t)
    }

    /// The shutter time of local time `u` in the span, exact at both ends.
    pub fn global_time(&self, u: f64) -> f64 {
        let [t0, t1] = self.span;
        (1.0 - u) * t0 + u * t1
    }

    /// The texture coordinate at barycentric weights `bary` of the three corners.
    pub fn uv_at(&self, bary: [f64; 3]) -> DVec2 {
        self.uv[0] * bary[0] + self.uv[1] * bary[1] + self.uv[2] * bary[2]
    }

    /// True when the span is the whole shutter.
    pub fn is_whole(&self) -> bool {
        self.span == [0.0, 1.0]
    }

    /// True when any corner moves in 2DH or depth during the shutter.
    pub fn is_moving(&self) -> bool {
        self.open != self.close
    }
}

/// What placing many triangles at one instant shares ([`PreparedScene::instant`]): each
/// object's transform on its curved path at that time, and whether the camera stands still.
#[derive(Debug, Clone)]
pub struct Instant {
    t: f64,
    paths: Vec<Option<DAffine3>>,
    still_camera: bool,
}

/// A splat in its object's space (before placement and motion): the disc its set's curved
/// path moves ([`PreparedScene::splat_disc_at`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplatLocal {
    /// Centre.
    pub centre: DVec3,
    /// Unit normal.
    pub normal: DVec3,
    /// Radius.
    pub radius: f64,
}

impl SplatLocal {
    /// Two tangent axes of length `radius` spanning the disc (normal's
    /// `any_orthonormal_pair`): the disc is `centre + cos a · u + sin a · v`.
    pub fn axes(&self) -> (DVec3, DVec3) {
        let (u, v) = self.normal.any_orthonormal_pair();
        (u * self.radius, v * self.radius)
    }
}

/// One splat (an oriented disc) at the start ("open") and end ("close") of its time span.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedSplat {
    /// Index into [`PreparedScene::splat_objects`].
    pub object: u32,
    /// World-space centre at open.
    pub centre_open: DVec3,
    /// World-space centre at close.
    pub centre_close: DVec3,
    /// World-space unit normal at open.
    pub normal_open: DVec3,
    /// World-space unit normal at close.
    pub normal_close: DVec3,
    /// World-space radius at open.
    pub radius_open: f64,
    /// World-space radius at close.
    pub radius_close: f64,
    /// Linear RGBA, straight alpha.
    pub color: [f64; 4],
    /// 2DH centre and depth at open.
    pub open: Vertex2dh,
    /// 2DH centre and depth at close.
    pub close: Vertex2dh,
    /// The part `[t0, t1]` of the normalised shutter the splat exists in: `[0, 1]` for
    /// straight motion, one segment of a curved path (or of the camera's keys) otherwise
    /// (`*_open` is at `t0`, `*_close` at `t1`).
    pub span: [f64; 2],
    /// The disc in its object's space when its set's path is curved
    /// ([`ObjectInfo::path`]); `None` for straight motion.
    pub local: Option<SplatLocal>,
}

impl PreparedSplat {
    /// The local time u ∈ \[0, 1\] of shutter time `t` in the span.
    pub fn local_time(&self, t: f64) -> f64 {
        span_local_time(self.span, t)
    }
}

/// Per-object summary kept for the analysis and for messages.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectInfo {
    /// The object's name.
    pub name: String,
    /// Range of its triangles in [`PreparedScene::triangles`] (or splats for splat objects).
    pub range: std::ops::Range<usize>,
    /// Its material (triangle objects).
    pub material: u32,
    /// World-space axis-aligned bounds over the ends of every span (min, max); linear
    /// motion keeps every intermediate position inside, a curved path bulges out by at most
    /// its chord error.
    pub swept_bounds: (DVec3, DVec3),
    /// The object's true path when it is curved (some key pair turns); `None` for straight
    /// motion, where the spans' chords are the motion.
    pub path: Option<MotionPath>,
    /// Segments the shutter is cut into for this object (1 for straight motion and a static
    /// camera).
    pub segments: u32,
}

/// A scene ready to render.
#[derive(Debug, Clone)]
pub struct PreparedScene {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Linear RGB background.
    pub background: [f64; 3],
    /// Shutter response.
    pub shutter: Shutter,
    /// Camera at shutter open.
    pub camera_open: CameraFrame,
    /// Camera at shutter close.
    pub camera_close: CameraFrame,
    /// Camera keys when the camera's motion is given as more than its two ends (first at
    /// 0 with `camera_open`, last at 1 with `camera_close`); empty otherwise.
    pub camera_keys: Vec<CameraKey>,
    /// Near clipping depth.
    pub near: f64,
    /// Far clipping depth.
    pub far: f64,
    /// Triangle objects.
    pub objects: Vec<ObjectInfo>,
    /// All triangles, grouped by object.
    pub triangles: Vec<PreparedTriangle>,
    /// Splat objects (`range` indexes `splats`).
    pub splat_objects: Vec<ObjectInfo>,
    /// All splats, grouped by object.
    pub splats: Vec<PreparedSplat>,
    /// Materials.
    pub materials: Vec<Material>,
    /// Textures.
    pub textures: Vec<Texture>,
    /// Lights; only lit materials ([`Material::shading`]) see them.
    pub lights: Vec<Light>,
}

impl PreparedScene {
    /// The texture of material `m` (`None` when it has none or its index is out of range).
    pub fn texture_of(&self, m: &Material) -> Option<&Texture> {
        m.texture.and_then(|t| self.textures.get(t as usize))
    }

    /// Premultiplied linear RGBA of `material` at texture coordinate `uv`.
    pub fn shade(&self, material: u32, uv: DVec2) -> [f64; 4] {
        let Some(m) = self.materials.get(material as usize) else {
            return [0.0; 4];
        };
        crate::surface_track::albedo(m, self.texture_of(m), uv)
    }

    /// True when `material` has alpha 1 everywhere (colour alpha 1, texture without alpha).
    pub fn is_opaque(&self, material: u32) -> bool {
        self.materials
            .get(material as usize)
            .is_some_and(|m| m.color[3] >= 1.0 && self.texture_of(m).is_none_or(|t| !t.has_alpha()))
    }

    /// True when the camera pose differs between open and close or between keys.
    pub fn camera_moves(&self) -> bool {
        self.camera_open != self.camera_close
            || self
                .camera_keys
                .windows(2)
                .any(|k| k[0].frame != k[1].frame)
    }

    /// The 2DH position of world point `p` at normalised time `t`: linear in 2DH between
    /// the camera's keys (or its open and close poses).
    pub fn project_at(&self, t: f64, p: DVec3) -> Vertex2dh {
        if self.camera_keys.is_empty() {
            if t <= 0.0 {
                self.camera_open.project(p)
            } else if t >= 1.0 {
                self.camera_close.project(p)
            } else {
                self.camera_open
                    .project(p)
                    .lerp(self.camera_close.project(p), t)
            }
        } else {
            project_at(&self.camera_keys, t, p)
        }
    }

    /// The corners of `tri` at normalised shutter time `t` on the true motion: the
    /// object's curved path projected at `t` when it has one, else the span's chord.
    pub fn corners_at(&self, tri: &PreparedTriangle, t: f64) -> [Vertex2dh; 3] {
        let affine = self
            .objects
            .get(tri.object as usize)
            .and_then(|o| o.path.as_ref())
            .map(|path| path.affine(t));
        self.place(tri, t, affine.as_ref(), false)
    }

    /// What placing many triangles at time `t` shares ([`PreparedScene::corners_at_instant`]).
    pub fn instant(&self, t: f64) -> Instant {
        let bits = |m: &glam::DMat4| m.to_cols_array().map(f64::to_bits);
        let (a, b) = (&self.camera_open, &self.camera_close);
        Instant {
            t,
            paths: self
                .objects
                .iter()
                .map(|o| o.path.as_ref().map(|p| p.affine(t)))
                .collect(),
            still_camera: self.camera_keys.is_empty()
                && bits(&a.view) == bits(&b.view)
                && bits(&a.clip_from_view) == bits(&b.clip_from_view)
                && bits(&a.pixel_from_clip) == bits(&b.pixel_from_clip),
        }
    }

    /// [`PreparedScene::corners_at`] at `instant`'s time, bit for bit, with each object's
    /// path transform computed once and, under a still camera, one projection per corner.
    pub fn corners_at_instant(&self, tri: &PreparedTriangle, instant: &Instant) -> [Vertex2dh; 3] {
        let affine = instant
            .paths
            .get(tri.object as usize)
            .and_then(Option::as_ref);
        self.place(tri, instant.t, affine, instant.still_camera)
    }

    /// `tri`'s corners at `t`: on its object's path transform `affine` when it has one, else
    /// on its span's chord. `still_camera`: the open and close poses project identically
    /// and there are no camera keys, so the open pose's projection stands for both.
    fn place(
        &self,
        tri: &PreparedTriangle,
        t: f64,
        affine: Option<&DAffine3>,
        still_camera: bool,
    ) -> [Vertex2dh; 3] {
        match (affine, tri.local) {
            (Some(a), Some(local)) => local.map(|p| {
                let p = a.transform_point3(p);
                if still_camera && t > 0.0 && t < 1.0 {
                    let v = self.camera_open.project(p);
                    v.lerp(v, t)
                } else {
                    self.project_at(t, p)
                }
            }),
            _ => tri.at(tri.local_time(t)),
        }
    }

    /// The true path of splat `s`'s set when it is curved, with the splat's object-space
    /// disc; `None` for straight motion.
    pub fn splat_path<'a>(
        &'a self,
        s: &'a PreparedSplat,
    ) -> Option<(&'a MotionPath, &'a SplatLocal)> {
        let path = self.splat_objects.get(s.object as usize)?.path.as_ref()?;
        Some((path, s.local.as_ref()?))
    }

    /// The disc of a splat on a curved path at normalised time `t`: its object-space disc
    /// moved by the path's transform at `t` (world centre and the two tangent axes, each
    /// of the disc's radius; a non-uniform scale makes it an ellipse). `None` for straight
    /// motion.
    pub fn splat_disc_at(&self, s: &PreparedSplat, t: f64) -> Option<[DVec3; 3]> {
        let (path, local) = self.splat_path(s)?;
        let a = path.affine(t);
        let (u, v) = local.axes();
        Some([
            a.transform_point3(local.centre),
            a.transform_vector3(u),
            a.transform_vector3(v),
        ])
    }

    /// True when splat `s` changes on screen during the shutter: its centre, normal or
    /// radius changes, or the camera moves. A camera that rolls about a splat's centre or
    /// orbits it leaves the projected centre in place but turns or reshapes the disc, so
    /// camera motion alone counts.
    pub fn splat_moves(&self, s: &PreparedSplat) -> bool {
        self.camera_moves()
            || s.open != s.close
            || s.centre_open != s.centre_close
            || s.normal_open != s.normal_close
            || s.radius_open != s.radius_close
    }
}
