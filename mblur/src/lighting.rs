//! Lights, shading models and the one shading function every method calls.
//!
//! A lit material's colour at a surface point and instant is
//!
//! ```text
//! c = a albedo (ambient + Σ_lights E_l max(0, n·l)) + a Σ_lights E_l s (n·h)^shininess + a emissive
//! ```
//!
//! with `albedo` the material colour times its texture, `a` its alpha (the result is
//! premultiplied, as every shader returns), `n` the unit shading normal turned towards the
//! viewer, `l` the unit direction to the light, `h = normalize(l + v)` the half vector
//! (Blinn-Phong; Lambert drops the specular term), `s` the specular colour and `E_l` the
//! light's irradiance: `colour × intensity` for a directional light, divided by the squared
//! distance for a point light. There are no shadows: every light reaches every surface that
//! faces it.
//!
//! The colour is affine in the albedo for a fixed point and instant ([`LightTerms`]), which
//! the per-interval shading knob uses: `start` and `mid` (Rønnow 2021, §6: "lighting is
//! computed with just the start normal of every interval") evaluate the light once and
//! apply it to the texture filtered over the partition.
//!
//! Rønnow 2021, Alg. 1 (`ResolveIntervalsRange(AL, r_s, r_e, lightPos)`) resolves each
//! interval's colour from its normal, position, the light position and UVs; Gribel 2010
//! (§6, Fig. 14) shades per triangle. Here every method shades through
//! [`PreparedScene::shade_surface`]: accum and stochastic at the sample's instant, analytic
//! and prism per partition of each interval ([`crate::chain`]), EWA per splat.

use glam::{DVec2, DVec3};

pub use crate::lights::{Light, LightKey};
use crate::prepared::{Material, PreparedScene, PreparedSplat, PreparedTriangle};
use crate::surface_track::SurfaceTrack;

/// How a material responds to light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShadingModel {
    /// Colour times texture, whatever the lights (the papers' idealised input).
    #[default]
    Unlit,
    /// Diffuse only: ambient plus `max(0, n·l)` per light.
    Lambert,
    /// Diffuse plus a Blinn-Phong specular lobe.
    BlinnPhong,
}

/// Default tolerance of [`ShadingSamples::Adaptive`], in linear colour units.
pub const DEFAULT_SHADING_TOLERANCE: f64 = 1e-3;

/// Where the analytic and prism methods evaluate the lighting of an interval over each
/// partition of the resolve (the accuracy knob of lit shading; accum and stochastic shade
/// at each sample's own instant).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ShadingSamples {
    /// Once, at the interval's start (Rønnow 2021, §6: "lighting is computed with just the
    /// start normal of every interval"); the texture is still filtered over the partition.
    Start,
    /// Once, at the partition's midpoint.
    Mid,
    /// `n` samples spread over the partition (midpoint rule weighted by the shutter).
    Fixed(u32),
    /// Bisection until the shaded colour at each sub-span's midpoint is within `tolerance`
    /// of the chord through its ends (Simpson's rule on the accepted sub-spans, at most
    /// 2^[`crate::chain::ADAPTIVE_DEPTH`] of them).
    Adaptive {
        /// Largest accepted chord error per channel.
        tolerance: f64,
    },
}

impl Default for ShadingSamples {
    fn default() -> Self {
        ShadingSamples::Adaptive {
            tolerance: DEFAULT_SHADING_TOLERANCE,
        }
    }
}

/// Most samples [`ShadingSamples::Fixed`] may take per partition.
pub const MAX_SHADING_SAMPLES: u32 = 1024;

impl std::str::FromStr for ShadingSamples {
    type Err = String;

    /// `start`, `mid`, `adaptive` (with [`DEFAULT_SHADING_TOLERANCE`]) or a sample count
    /// `1..=`[`MAX_SHADING_SAMPLES`].
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "start" => Ok(ShadingSamples::Start),
            "mid" => Ok(ShadingSamples::Mid),
            "adaptive" => Ok(ShadingSamples::default()),
            n => match n.parse::<u32>() {
                Ok(k) if (1..=MAX_SHADING_SAMPLES).contains(&k) => Ok(ShadingSamples::Fixed(k)),
                _ => Err(format!(
                    "expected start, mid, adaptive or a sample count 1..={MAX_SHADING_SAMPLES}, got {s:?}"
                )),
            },
        }
    }
}

impl ShadingSamples {
    /// Checks the setting: a tolerance that is finite and positive, a count in
    /// `1..=`[`MAX_SHADING_SAMPLES`].
    pub fn validate(&self, method: &'static str) -> crate::error::Result<()> {
        let bad = |message: String| {
            Err(crate::error::Error::Setting {
                method,
                setting: "shading",
                message,
            })
        };
        match *self {
            ShadingSamples::Fixed(n) if n == 0 || n > MAX_SHADING_SAMPLES => bad(format!(
                "sample count must be 1..={MAX_SHADING_SAMPLES}, got {n}"
            )),
            ShadingSamples::Adaptive { tolerance }
                if !(tolerance > 0.0 && tolerance.is_finite()) =>
            {
                bad(format!("tolerance must be finite and > 0, got {tolerance}"))
            }
            _ => Ok(()),
        }
    }
}

impl std::fmt::Display for ShadingSamples {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ShadingSamples::Start => write!(f, "start"),
            ShadingSamples::Mid => write!(f, "mid"),
            ShadingSamples::Fixed(n) => write!(f, "{n}"),
            ShadingSamples::Adaptive { tolerance } => write!(f, "adaptive({tolerance})"),
        }
    }
}

/// A surface point at one instant: world position, unit shading normal, texture coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// World position.
    pub position: DVec3,
    /// Unit shading normal (zero when unknown: then only ambient and emissive light it).
    pub normal: DVec3,
    /// The geometric normal (any length; zero when unknown), oriented to the side the
    /// shading normals point to: which side of the surface the viewer sees. The shading
    /// normal is turned to that side, so an interpolated normal that leans away from the
    /// viewer near a silhouette is not flipped.
    pub geometric: DVec3,
    /// Texture coordinate.
    pub uv: DVec2,
}

/// The light reaching a surface point, split into what scales with the albedo and what
/// does not: the colour is `albedo ⊙ diffuse + alpha × specular` (premultiplied albedo).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LightTerms {
    /// Ambient plus diffuse irradiance, multiplied by the albedo.
    pub diffuse: [f64; 3],
    /// Specular and emissive radiance, multiplied by the alpha only.
    pub specular: [f64; 3],
}

impl LightTerms {
    /// The premultiplied colour of a surface with premultiplied albedo `albedo`.
    pub fn apply(&self, albedo: [f64; 4]) -> [f64; 4] {
        let a = albedo[3];
        [
            albedo[0] * self.diffuse[0] + a * self.specular[0],
            albedo[1] * self.diffuse[1] + a * self.specular[1],
            albedo[2] * self.diffuse[2] + a * self.specular[2],
            a,
        ]
    }
}

/// Largest finite value a shaded channel may take: huge intensities saturate here instead
/// of overflowing to infinity (f32 images keep headroom for sums of many layers).
pub const MAX_RADIANCE: f64 = 1e12;

fn clamp_finite(v: f64) -> f64 {
    if v.is_nan() {
        0.0
    } else {
        v.clamp(0.0, MAX_RADIANCE)
    }
}

/// The light terms of material `m` at point `p` seen from direction `view` (unit, from the
/// point towards the viewer) under `lights` at normalised time `t`.
pub fn light_terms(
    m: &Material,
    lights: &[Light],
    p: &SurfacePoint,
    view: DVec3,
    t: f64,
) -> LightTerms {
    let mut out = LightTerms {
        diffuse: [0.0; 3],
        specular: m.emissive,
    };
    // Two-sided: the normal is turned to the side of the surface the viewer sees, decided
    // by the geometric normal so that an interpolated normal leaning away at a silhouette
    // is kept.
    let g = if p.geometric == DVec3::ZERO {
        p.normal
    } else {
        p.geometric
    };
    let n = if g.dot(view) < 0.0 {
        -p.normal
    } else {
        p.normal
    };
    let specular = m.shading == ShadingModel::BlinnPhong;
    for light in lights {
        let (l, e) = match light {
            Light::Ambient { colour } => {
                for (d, c) in out.diffuse.iter_mut().zip(colour) {
                    *d += c;
                }
                continue;
            }
            Light::Directional {
                colour, intensity, ..
            } => {
                let d = light.direction_at(t).unwrap_or(DVec3::ZERO);
                (-d, colour.map(|c| c * intensity))
            }
            Light::Point {
                colour, intensity, ..
            } => {
                let to = light.position_at(t).unwrap_or(p.position) - p.position;
                let d2 = to.length_squared();
                if d2 <= 0.0 || !d2.is_finite() {
                    continue;
                }
                (to / d2.sqrt(), colour.map(|c| c * intensity / d2))
            }
        };
        let nl = n.dot(l);
        if nl.is_nan() || nl <= 0.0 {
            continue;
        }
        for (d, ek) in out.diffuse.iter_mut().zip(e) {
            *d += ek * nl;
        }
        if specular {
            let h = (l + view).normalize_or_zero();
            let nh = n.dot(h).max(0.0);
            let lobe = if nh > 0.0 { nh.powf(m.shininess) } else { 0.0 };
            for ((s, ek), sc) in out.specular.iter_mut().zip(e).zip(m.specular) {
                *s += ek * sc * lobe;
            }
        }
    }
    out.diffuse = out.diffuse.map(clamp_finite);
    out.specular = out.specular.map(clamp_finite);
    out
}

impl PreparedScene {
    /// True when `material` is lit (not [`ShadingModel::Unlit`]); an unlit material's colour
    /// is `color × texture` whatever the lights.
    pub fn is_lit(&self, material: u32) -> bool {
        self.materials
            .get(material as usize)
            .is_some_and(Material::is_lit)
    }

    /// The material of splat `s`'s object when that object is lit, `None` for unlit splats
    /// (their colour is their own).
    pub fn splat_material(&self, s: &PreparedSplat) -> Option<&Material> {
        let m = self.splat_objects.get(s.object as usize)?.material;
        self.materials
            .get(m as usize)
            .filter(|m| m.shading != ShadingModel::Unlit)
    }

    /// True when some light moves over the shutter.
    pub fn lights_move(&self) -> bool {
        self.lights.iter().any(Light::moves)
    }

    /// True when the shaded colour of `tri` may change over the shutter while the triangle
    /// stands still on screen: it is lit and a light moves.
    pub fn shading_varies(&self, tri: &PreparedTriangle) -> bool {
        self.is_lit(tri.material) && self.lights_move()
    }

    /// True when some material is lit.
    pub fn any_lit(&self) -> bool {
        (0..self.materials.len() as u32).any(|m| self.is_lit(m))
    }

    /// The unit direction from `p` towards the viewer at normalised time `t`: towards the
    /// eye for a perspective camera, against the viewing direction for an orthographic one.
    pub fn view_direction(&self, p: DVec3, t: f64) -> DVec3 {
        let (a, b, u) = match self.camera_keys.windows(2).find(|w| t < w[1].t) {
            Some(w) if w[1].t > w[0].t => {
                (&w[0].frame, &w[1].frame, (t - w[0].t) / (w[1].t - w[0].t))
            }
            _ if !self.camera_keys.is_empty() => (&self.camera_close, &self.camera_close, 0.0),
            _ => (&self.camera_open, &self.camera_close, t),
        };
        let u = u.clamp(0.0, 1.0);
        let eye = a.eye.lerp(b.eye, u);
        // An orthographic projection keeps w = 1 (no w from view z).
        if a.clip_from_view.w_axis.w != 0.0 {
            (eye - a.target.lerp(b.target, u)).normalize_or_zero()
        } else {
            (eye - p).normalize_or_zero()
        }
    }

    /// The surface point of `tri` with barycentric weights `bary` (of its three corners) at
    /// normalised time `t` ([`SurfaceTrack::surface_point`]).
    pub fn surface_point(&self, tri: &PreparedTriangle, bary: [f64; 3], t: f64) -> SurfacePoint {
        SurfaceTrack::new(self, tri, [t, t]).surface_point(bary, t)
    }

    /// The light terms of `tri`'s material at `p` and time `t`.
    pub fn light_terms_at(&self, tri: &PreparedTriangle, p: &SurfacePoint, t: f64) -> LightTerms {
        SurfaceTrack::new(self, tri, [t, t]).light_terms(p, t)
    }

    /// The premultiplied colour of `tri` at barycentrics `bary` and normalised time `t`:
    /// the one shading function of every method ([`SurfaceTrack::colour`]). Unlit
    /// materials give [`PreparedScene::shade`] of the interpolated texture coordinate.
    pub fn shade_surface(&self, tri: &PreparedTriangle, bary: [f64; 3], t: f64) -> [f64; 4] {
        SurfaceTrack::new(self, tri, [t, t]).colour(bary, t)
    }

    /// The premultiplied colour of a splat-like point of `material` with albedo `albedo`
    /// (straight RGBA) at `position` with unit `normal` and time `t`.
    pub fn shade_point(
        &self,
        material: &Material,
        albedo: [f64; 4],
        position: DVec3,
        normal: DVec3,
        t: f64,
    ) -> [f64; 4] {
        let a = albedo[3];
        let pre = [albedo[0] * a, albedo[1] * a, albedo[2] * a, a];
        if material.shading == ShadingModel::Unlit {
            return pre;
        }
        let p = SurfacePoint {
            position,
            normal,
            geometric: normal,
            uv: DVec2::ZERO,
        };
        light_terms(
            material,
            &self.lights,
            &p,
            self.view_direction(position, t),
            t,
        )
        .apply(pre)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn material(shading: ShadingModel, shininess: f64) -> Material {
        Material {
            shading,
            specular: [0.5; 3],
            shininess,
            ..Material::unlit([0.5, 0.5, 0.5, 1.0], None)
        }
    }

    fn at_origin(normal: DVec3) -> SurfacePoint {
        SurfacePoint {
            position: DVec3::ZERO,
            normal,
            geometric: normal,
            uv: DVec2::ZERO,
        }
    }

    fn directional(direction: DVec3, intensity: f64) -> Light {
        let d = direction.normalize();
        Light::directional(d, d, [1.0; 3], intensity)
    }

    fn point(position: DVec3, intensity: f64) -> Light {
        Light::point(position, position, [1.0; 3], intensity)
    }

    fn close(a: [f64; 4], b: [f64; 4]) {
        for k in 0..4 {
            assert!((a[k] - b[k]).abs() < 1e-12, "{a:?} vs {b:?}");
        }
    }

    const WHITE: [f64; 4] = [0.5, 0.5, 0.5, 1.0];

    #[test]
    fn lambert_under_a_directional_light_is_albedo_times_intensity_times_cosine() {
        let m = material(ShadingModel::Lambert, 0.0);
        let p = at_origin(DVec3::Z);
        // Straight down the normal: 0.5 x 2 x 1.
        let t = light_terms(&m, &[directional(-DVec3::Z, 2.0)], &p, DVec3::Z, 0.0);
        close(t.apply(WHITE), [1.0, 1.0, 1.0, 1.0]);
        // At 45 degrees: 0.5 x 2 x cos 45.
        let d = DVec3::new(0.0, -1.0, -1.0);
        let t = light_terms(&m, &[directional(d, 2.0)], &p, DVec3::Z, 0.0);
        let c = std::f64::consts::FRAC_1_SQRT_2;
        close(t.apply(WHITE), [c, c, c, 1.0]);
    }

    #[test]
    fn blinn_phong_under_a_point_light_falls_off_with_the_square_of_distance() {
        let m = material(ShadingModel::BlinnPhong, 2.0);
        let p = at_origin(DVec3::Z);
        // Light 2 above: irradiance 8 / 4 = 2; diffuse 0.5 x 2; half vector = normal, so
        // the lobe is 1 and the specular 2 x 0.5.
        let t = light_terms(&m, &[point(2.0 * DVec3::Z, 8.0)], &p, DVec3::Z, 0.0);
        close(t.apply(WHITE), [2.0, 2.0, 2.0, 1.0]);
        // Light at (2, 0, 2): irradiance 8 / 8 = 1, n.l = cos 45; h at 22.5 degrees from
        // n, lobe cos^2(22.5) = (1 + cos 45) / 2.
        let t = light_terms(
            &m,
            &[point(DVec3::new(2.0, 0.0, 2.0), 8.0)],
            &p,
            DVec3::Z,
            0.0,
        );
        let c = std::f64::consts::FRAC_1_SQRT_2;
        let want = 0.5 * c + 0.5 * (1.0 + c) / 2.0;
        close(t.apply(WHITE), [want, want, want, 1.0]);
    }

    #[test]
    fn ambient_and_emissive_need_no_normal_and_alpha_premultiplies() {
        let m = Material {
            emissive: [0.1, 0.0, 0.0],
            ..material(ShadingModel::Lambert, 0.0)
        };
        let lights = [Light::Ambient {
            colour: [0.5, 0.5, 0.5],
        }];
        let t = light_terms(&m, &lights, &at_origin(DVec3::ZERO), DVec3::Z, 0.0);
        // Premultiplied albedo (0.2, 0.4, 0.6) at alpha 0.5.
        let c = t.apply([0.1, 0.2, 0.3, 0.5]);
        close(c, [0.05 + 0.05, 0.1, 0.15, 0.5]);
    }

    #[test]
    fn a_back_facing_normal_is_turned_towards_the_viewer() {
        let m = material(ShadingModel::Lambert, 0.0);
        let front = light_terms(
            &m,
            &[directional(-DVec3::Z, 1.0)],
            &at_origin(DVec3::Z),
            DVec3::Z,
            0.0,
        );
        let back = light_terms(
            &m,
            &[directional(-DVec3::Z, 1.0)],
            &at_origin(-DVec3::Z),
            DVec3::Z,
            0.0,
        );
        assert_eq!(front, back);
    }

    #[test]
    fn a_shading_normal_leaning_away_at_a_silhouette_is_not_flipped() {
        // The face is seen from the front, its interpolated normal leans away from the
        // viewer: the light behind the normal's side must not reach it.
        let m = material(ShadingModel::Lambert, 0.0);
        let p = SurfacePoint {
            geometric: DVec3::Z,
            normal: DVec3::new(0.0, 0.9, -0.1).normalize(),
            ..at_origin(DVec3::Z)
        };
        let t = light_terms(&m, &[directional(DVec3::Y, 1.0)], &p, DVec3::Z, 0.0);
        assert_eq!(t.diffuse, [0.0; 3]);
    }

    #[test]
    fn moving_lights_interpolate_between_open_and_close() {
        let m = material(ShadingModel::Lambert, 0.0);
        let l = Light::point(
            DVec3::new(-1.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            [1.0; 3],
            1.0,
        );
        assert!(l.moves());
        // At mid-shutter the light is straight above at distance 1.
        let t = light_terms(
            &m,
            std::slice::from_ref(&l),
            &at_origin(DVec3::Z),
            DVec3::Z,
            0.5,
        );
        close(t.apply(WHITE), [0.5, 0.5, 0.5, 1.0]);
    }
}
