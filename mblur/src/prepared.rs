//! The prepared scene: world-space triangles at shutter open and close, per-vertex 2DH
//! positions and view depths for both camera poses, materials and textures — the input
//! contract every rendering method consumes (`mblur-scene` builds it from a scene file).
//!
//! Vertices move linearly in 2DH between open and close (Gribel 2010, Eq. 2); camera motion is
//! folded in by projecting the open positions with the open camera and the close positions
//! with the close camera.

use glam::{DVec2, DVec3};

use crate::camera::{CameraFrame, Vertex2dh};
use crate::shutter::Shutter;
use crate::texture::Texture;

/// A surface material: straight-alpha linear colour times an optional texture.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Linear RGBA, straight alpha.
    pub color: [f64; 4],
    /// Index into [`PreparedScene::textures`].
    pub texture: Option<u32>,
}

/// One triangle ready to render: world positions, 2DH vertices and depth at shutter open and
/// close, UVs and normals.
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
}

impl PreparedTriangle {
    /// The corners at normalised time t: p(t) = (1 - t) q + t r (Gribel 2010, Eq. 2).
    pub fn at(&self, t: f64) -> [Vertex2dh; 3] {
        [0, 1, 2].map(|k| self.open[k].lerp(self.close[k], t))
    }

    /// True when any corner moves in 2DH or depth during the shutter.
    pub fn is_moving(&self) -> bool {
        self.open != self.close
    }
}

/// One splat (an oriented disc) at shutter open and close.
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
    /// World-space axis-aligned bounds over both shutter ends (min, max); linear motion
    /// keeps every intermediate position inside.
    pub swept_bounds: (DVec3, DVec3),
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
}

impl PreparedScene {
    /// Premultiplied linear RGBA of `material` at texture coordinate `uv`.
    pub fn shade(&self, material: u32, uv: DVec2) -> [f64; 4] {
        let Some(m) = self.materials.get(material as usize) else {
            return [0.0; 4];
        };
        let a = m.color[3];
        let base = [m.color[0] * a, m.color[1] * a, m.color[2] * a, a];
        match m.texture.and_then(|t| self.textures.get(t as usize)) {
            None => base,
            Some(tex) => {
                let s = tex.sample(uv);
                std::array::from_fn(|k| base[k] * s[k])
            }
        }
    }

    /// True when `material` has alpha 1 everywhere (colour alpha 1, texture without alpha).
    pub fn is_opaque(&self, material: u32) -> bool {
        self.materials.get(material as usize).is_some_and(|m| {
            m.color[3] >= 1.0
                && m.texture
                    .and_then(|t| self.textures.get(t as usize))
                    .is_none_or(|t| !t.has_alpha)
        })
    }

    /// True when the camera pose differs between open and close.
    pub fn camera_moves(&self) -> bool {
        self.camera_open != self.camera_close
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
