//! One triangle's surface followed through time: what shading it at an instant needs,
//! looked up once for all the instants a renderer asks about.
//!
//! The lit resolve shades one interval at three or more instants (Simpson's rule, adaptive),
//! accum and stochastic once per fragment or sample; all of them go through
//! [`SurfaceTrack::colour`], so every method shades the same function. Setting a track up
//! finds the material, its texture and the triangle's motion; over a time range inside one
//! key pair of a curved path the corners follow a prepared [`Arc`] (one turn per instant)
//! instead of the path's whole transform.

use glam::DVec3;

use crate::lighting::{LightTerms, SurfacePoint, light_terms};
use crate::motion::{Arc, MotionPath};
use crate::prepared::{Material, PreparedScene, PreparedTriangle};
use crate::texture::Texture;

/// How a track finds the triangle's world corners at an instant.
#[derive(Debug, Clone, Copy)]
enum Corners<'a> {
    /// Straight motion: the span's chord.
    Chord,
    /// Curved motion: an arc for instants in its key pair, else the path as for `Path`.
    Arc(Arc, &'a MotionPath, &'a [DVec3; 3]),
    /// Curved motion, the path's whole transform of the object-space corners.
    Path(&'a MotionPath, &'a [DVec3; 3]),
    /// Curved motion set up for one instant: the corners there (the path's transform at
    /// that instant, computed once), else the path as for `Path`.
    At(f64, [DVec3; 3], &'a MotionPath, &'a [DVec3; 3]),
}

/// A triangle of a prepared scene set up to be shaded at instants of a time range.
#[derive(Debug, Clone, Copy)]
pub struct SurfaceTrack<'a> {
    scene: &'a PreparedScene,
    tri: &'a PreparedTriangle,
    /// The triangle's material (`None`: an index out of range, shaded transparent black).
    material: Option<&'a Material>,
    /// The material's texture.
    texture: Option<&'a Texture>,
    corners: Corners<'a>,
}

impl<'a> SurfaceTrack<'a> {
    /// Sets `tri` up for instants in `times` (normalised shutter times, `times[0] <=
    /// times[1]`); instants outside the range are still right, only slower to evaluate
    /// when the object's path is curved.
    pub fn new(scene: &'a PreparedScene, tri: &'a PreparedTriangle, times: [f64; 2]) -> Self {
        let material = scene.materials.get(tri.material as usize);
        let path = scene
            .objects
            .get(tri.object as usize)
            .and_then(|o| o.path.as_ref());
        let corners = match (path, &tri.local) {
            // For one instant the whole transform costs less than preparing an arc.
            (Some(path), Some(local)) if times[0] == times[1] => {
                let a = path.affine(times[0]);
                Corners::At(times[0], local.map(|p| a.transform_point3(p)), path, local)
            }
            (Some(path), Some(local)) => match (times[1] > times[0])
                .then(|| path.arc(local, times))
                .flatten()
            {
                Some(arc) => Corners::Arc(arc, path, local),
                None => Corners::Path(path, local),
            },
            _ => Corners::Chord,
        };
        SurfaceTrack {
            scene,
            tri,
            material,
            texture: material.and_then(|m| scene.texture_of(m)),
            corners,
        }
    }

    /// Which function of time the corners follow: the start of the key pair of the arc
    /// the track was set up on, else `u64::MAX` (the span's chord, or the path's whole
    /// transform). Two tracks of one triangle with the same value give the same
    /// [`SurfaceTrack::colour`] for the same weights and instant, bit for bit.
    pub(crate) fn corners_key(&self) -> u64 {
        match &self.corners {
            Corners::Arc(arc, ..) => arc.pair_start().to_bits(),
            _ => u64::MAX,
        }
    }

    /// The world corners at normalised time `t`: on the true motion (the curved path when
    /// the object has one, else the span's chord).
    pub fn corners(&self, t: f64) -> [DVec3; 3] {
        match &self.corners {
            Corners::Chord => {
                let u = self.tri.local_time(t);
                let (a, b) = (&self.tri.world_open, &self.tri.world_close);
                [a[0].lerp(b[0], u), a[1].lerp(b[1], u), a[2].lerp(b[2], u)]
            }
            Corners::Arc(arc, ..) if arc.holds(t) => arc.at(t),
            Corners::At(at, c, ..) if *at == t => *c,
            Corners::Arc(_, path, local)
            | Corners::Path(path, local)
            | Corners::At(_, _, path, local) => {
                let a = path.affine(t);
                local.map(|p| a.transform_point3(p))
            }
        }
    }

    /// The surface point with barycentric weights `bary` (of the three corners) at
    /// normalised time `t`: the corners on the true motion, normals interpolated linearly
    /// over the span and across the triangle, then normalised.
    pub fn surface_point(&self, bary: [f64; 3], t: f64) -> SurfacePoint {
        let tri = self.tri;
        let weigh = |v: &[DVec3; 3]| v[0] * bary[0] + v[1] * bary[1] + v[2] * bary[2];
        let (position, face) = match &self.corners {
            Corners::Arc(arc, ..) if arc.holds(t) => arc.point_and_face(bary, t),
            _ => {
                let c = self.corners(t);
                (weigh(&c), (c[1] - c[0]).cross(c[2] - c[0]))
            }
        };
        let u = tri.local_time(t);
        // Written out: `array::map` here was not inlined and cost a call per corner.
        let (a, b) = (&tri.normal_open, &tri.normal_close);
        let normals = [a[0].lerp(b[0], u), a[1].lerp(b[1], u), a[2].lerp(b[2], u)];
        SurfacePoint {
            position,
            normal: weigh(&normals).normalize_or_zero(),
            // The face normal on the side of the corner normals, whatever the winding.
            geometric: if face.dot(normals[0] + normals[1] + normals[2]) < 0.0 {
                -face
            } else {
                face
            },
            uv: tri.uv_at(bary),
        }
    }

    /// The light terms of the material at `p` and time `t` (none for a missing material).
    pub fn light_terms(&self, p: &SurfacePoint, t: f64) -> LightTerms {
        match self.material {
            Some(m) => light_terms(
                m,
                &self.scene.lights,
                p,
                self.scene.view_direction(p.position, t),
                t,
            ),
            None => LightTerms::default(),
        }
    }

    /// The premultiplied albedo at barycentrics `bary`: the material's colour times its
    /// texture ([`PreparedScene::shade`]).
    pub fn albedo(&self, bary: [f64; 3]) -> [f64; 4] {
        match self.material {
            Some(m) => albedo(m, self.texture, self.tri.uv_at(bary)),
            None => [0.0; 4],
        }
    }

    /// The premultiplied colour at barycentrics `bary` and normalised time `t`: the albedo
    /// for unlit materials, else the albedo under the scene's lights at the surface point.
    pub fn colour(&self, bary: [f64; 3], t: f64) -> [f64; 4] {
        let Some(m) = self.material else {
            return [0.0; 4];
        };
        if !m.is_lit() {
            return albedo(m, self.texture, self.tri.uv_at(bary));
        }
        let p = self.surface_point(bary, t);
        self.light_terms(&p, t).apply(albedo(m, self.texture, p.uv))
    }
}

/// The premultiplied linear RGBA of material `m` with texture `texture` at coordinate `uv`:
/// its colour, times the texture's bilinear sample when it has one.
pub(crate) fn albedo(m: &Material, texture: Option<&Texture>, uv: glam::DVec2) -> [f64; 4] {
    let base = base_colour(m);
    match texture {
        None => base,
        Some(tex) => {
            let s = tex.sample(uv);
            std::array::from_fn(|k| base[k] * s[k])
        }
    }
}

/// The premultiplied linear RGBA of material `m`'s colour (what its texture multiplies).
pub(crate) fn base_colour(m: &Material) -> [f64; 4] {
    let a = m.color[3];
    [m.color[0] * a, m.color[1] * a, m.color[2] * a, a]
}
