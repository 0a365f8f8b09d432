//! The triangles of a mixed scene as ewa-splat surface intervals: the analytic chain's
//! per-pixel emission (Gribel 2010: edge-eqn coverage spans with linear depth, Eq. 16, for
//! moving triangles; the static rasteriser's one `[0, 1]` interval for static ones; time
//! slices for near-plane crossings; the interval chain's emission, [`crate::chain::emit`])
//! converted to
//! [`ewa_splat::SurfaceInterval`]s, which ewa-splat's A-buffer resolves together with the
//! splat fragments (Heinzle 2010, §4.4; [`ewa_splat::render_with_surfaces`]).
//!
//! **Depth.** mblur's depth is the view-space distance `z` along the viewing direction
//! (`-z_view`, [`crate::camera::Vertex2dh::depth`]); ewa-splat's is the parameter `s` of
//! its pixel ray `o + s d` (origin on the near plane, unit direction; the ewa camera is the
//! shutter-open camera, and camera motion is carried by the geometry in that camera's
//! frame, see [`crate::ewa`]). Along the ray the view depth is affine in `s`:
//! `z(s) = z(o) + s c` with `z(o)` the view depth of the origin (the near distance) and `c =
//! -(view · d).z` the cosine between ray and viewing direction (1 for orthographic), so an
//! interval's depth `z + k (t - ts)` becomes `s = (z - z(o)) / c` with slope `k / c`,
//! exactly. In both renderers the depth of a moving surface at time t is its view depth in
//! the camera at t, so the conversion holds with camera motion too.
//!
//! **Colour.** Each surface interval carries one premultiplied colour: the shader's average
//! over it under the box shutter (`ewa` refuses other responses): the material colour for
//! flat materials; for textured ones the adaptive tap filter over the interval's UV
//! segment. The A-buffer may show only part of an interval (a splat in front for the rest),
//! so textured intervals are cut into surface intervals of at most 1 /
//! [`crate::chain::TEXTURE_PIECES`] of the shutter, each shaded over its own part of the
//! UV segment: the colour is constant over at most that long.

use ewa_splat::{Camera, SurfaceInterval, SurfaceLists};
use glam::DMat4;
use interval_buffer::Interval;
use resolve::Shader;

use crate::bands::Bins;
use crate::chain::TEXTURE_PIECES;
use crate::chain::emit::{RowSpan, emit};
use crate::chain::payload::{MakePayload, WithPayloads, with_payloads};
use crate::chain::pieces::piece_end;
use crate::chain::prim::{Prim, Primitives, Sweep};
use crate::effects::Pipeline;
use crate::error::{Error, Result};
use crate::lighting::ShadingSamples;
use crate::prepared::PreparedScene;

/// The triangles of a scene ready to be emitted band by band: the interval chain's
/// primitives (f64, edge-eqn, time-dependent back-face culling of opaque closed meshes)
/// binned by bands of image rows.
pub(crate) struct Triangles {
    prims: Vec<Prim<f64>>,
    bins: Bins,
}

/// One band of image rows of the ewa camera: the rows `y0..y0 + camera.height` of the
/// image, `camera` the ewa camera of the band and `view` the shutter-open world-to-view
/// matrix.
#[derive(Clone, Copy)]
pub(crate) struct Band<'a> {
    /// The band's ewa camera.
    pub camera: &'a Camera,
    /// The shutter-open world-to-view matrix.
    pub view: &'a DMat4,
    /// The band's first image row.
    pub y0: u32,
}

impl Triangles {
    /// Builds the primitives of every triangle of `scene` and bins them by bands of
    /// `band_rows` rows.
    pub(crate) fn new(scene: &PreparedScene, band_rows: u32) -> Self {
        let built = Primitives::<f64>::build(scene, Sweep::EdgeEqn, true);
        let bins = built.bins(scene.height, band_rows);
        Triangles {
            prims: built.prims,
            bins,
        }
    }

    /// The surface lists of `band`: textured intervals are cut into surface intervals of at
    /// most 1 / [`TEXTURE_PIECES`] of the shutter, flat ones are not cut.
    pub(crate) fn band(
        &self,
        scene: &PreparedScene,
        pipeline: &Pipeline,
        band: Band<'_>,
    ) -> Result<SurfaceLists> {
        let pieces = if pipeline.textures { TEXTURE_PIECES } else { 1 };
        let job = BandJob {
            triangles: self,
            scene,
            band,
            pieces,
        };
        with_payloads::<f64, _>(scene, pipeline.textures, ShadingSamples::default(), job)
    }
}

/// [`Triangles::band`] once the payloads are chosen; intervals are cut into surface
/// intervals of at most 1 / `pieces` of the shutter.
struct BandJob<'a> {
    triangles: &'a Triangles,
    scene: &'a PreparedScene,
    band: Band<'a>,
    pieces: u32,
}

impl WithPayloads<f64> for BandJob<'_> {
    type Output = Result<SurfaceLists>;

    fn run<M: MakePayload<f64>, S: Shader<f64, M::P> + Sync>(
        self,
        mk: &M,
        shader: &S,
    ) -> Self::Output {
        let BandJob {
            triangles,
            scene,
            band,
            pieces,
        } = self;
        let (w, rows) = (band.camera.width, band.camera.height);
        // Per pixel of the band: the view depth of the ray origin and per unit of s.
        let rays: Vec<Option<RayDepth>> = (0..rows)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| ray_depth(band.camera, band.view, i, j))
            .collect();
        let mut entries = Vec::new();
        for j in 0..rows {
            let y = band.y0 + j;
            for &p in triangles.bins.band(band.y0) {
                let prim = triangles.prims.get(p as usize).ok_or_else(|| {
                    Error::internal(
                        "ewa surface intervals",
                        format!("primitive {p} out of range"),
                    )
                })?;
                emit(scene, prim, RowSpan::row(y, scene.width), mk, |x, iv| {
                    let ray = rays.get(j as usize * w as usize + x).ok_or_else(|| {
                        Error::internal("ewa surface intervals", format!("column {x} out of range"))
                    })?;
                    if let Some(r) = *ray {
                        for s in to_surfaces(&iv, r, shader, pieces) {
                            entries.push((x as u32, j, s));
                        }
                    }
                    Ok(())
                })?;
            }
        }
        SurfaceLists::new(w, rows, &entries).map_err(|e| Error::MethodNotApplicable {
            method: "ewa".into(),
            reason: format!("triangle intervals: {e}"),
        })
    }
}

/// How view depth grows along a pixel's ray `o + s d`: `z(s) = origin + s per_unit`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RayDepth {
    /// `z(o)`, the view depth of the ray's origin.
    pub origin: f64,
    /// `c`, the view depth gained per unit of ray parameter.
    pub per_unit: f64,
}

/// The [`RayDepth`] of the ray of pixel (i, j) of `camera`. `None` when the ray does not
/// point into the view (never for a valid camera).
pub(crate) fn ray_depth(camera: &Camera, view: &DMat4, i: u32, j: u32) -> Option<RayDepth> {
    let (o, d) = camera.pixel_ray(f64::from(i) + 0.5, f64::from(j) + 0.5)?;
    let z0 = -view.transform_point3(o).z;
    let c = -view.transform_vector3(d).z;
    (z0.is_finite() && c.is_finite() && c > 0.0).then_some(RayDepth {
        origin: z0,
        per_unit: c,
    })
}

/// One emitted interval as surface intervals (depth converted, colour shaded): equal parts
/// of at most 1 / `pieces` of the shutter, each shaded over its own time range; none when
/// the interval is empty or not finite.
fn to_surfaces<P, S: Shader<f64, P>>(
    iv: &Interval<f64, P>,
    ray: RayDepth,
    shader: &S,
    pieces: u32,
) -> impl Iterator<Item = SurfaceInterval> {
    let (z0, c) = (ray.origin, ray.per_unit);
    let (t0, t1) = (iv.ts.clamp(0.0, 1.0), iv.te.clamp(0.0, 1.0));
    let slope = iv.k / c;
    let ok = t1 > t0 && slope.is_finite();
    let n = if ok {
        ((t1 - t0) * f64::from(pieces.max(1)))
            .ceil()
            .clamp(1.0, f64::from(pieces.max(1))) as u32
    } else {
        0
    };
    let end = move |j: u32| piece_end(t0, t1, j, n);
    (0..n).filter_map(move |j| {
        let (a, b) = (end(j), end(j + 1));
        let colour = shader.shade(iv, a, b, 1.0, 1.0);
        let alpha = colour[3].clamp(0.0, 1.0);
        let colour =
            [colour[0], colour[1], colour[2], alpha].map(|v| if v.is_finite() { v } else { 0.0 });
        let depth = (iv.z + iv.k * (a - iv.ts) - z0) / c;
        (b > a && depth.is_finite()).then_some(SurfaceInterval {
            t0: a,
            t1: b,
            depth,
            depth_slope: slope,
            colour,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{CameraFrame, Lens, Projection};
    use crate::shutter::Shutter;
    use glam::DVec3;

    /// The point at ray parameter `s` on pixel (i, j)'s ray.
    fn point_on_ray(camera: &Camera, i: u32, j: u32, s: f64) -> Option<DVec3> {
        let (o, d) = camera.pixel_ray(f64::from(i) + 0.5, f64::from(j) + 0.5)?;
        Some(o + s * d)
    }

    /// A scene with nothing in it but the camera (the depth conversion needs no more).
    fn camera_only(projection: Projection) -> PreparedScene {
        let lens = Lens {
            width: 9,
            height: 7,
            projection,
            near: 0.3,
            far: 40.0,
        };
        let camera = CameraFrame::new(&lens, DVec3::new(1.0, 2.0, 6.0), DVec3::ZERO, DVec3::Y);
        PreparedScene {
            width: lens.width,
            height: lens.height,
            background: [0.0; 3],
            shutter: Shutter {
                open: 0.0,
                close: 1.0,
                points: vec![(0.0, 1.0), (1.0, 1.0)],
            },
            camera_open: camera,
            camera_close: camera,
            camera_keys: Vec::new(),
            near: lens.near,
            far: lens.far,
            objects: Vec::new(),
            triangles: Vec::new(),
            splat_objects: Vec::new(),
            splats: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            lights: Vec::new(),
        }
    }

    /// The depth conversion against the projection itself: a point at ray parameter s
    /// projects back onto the pixel centre, and its view depth maps to s.
    #[test]
    fn view_depth_maps_to_the_ray_parameter_exactly() {
        for projection in [
            Projection::Perspective { fov_y_deg: 50.0 },
            Projection::Orthographic { height: 3.0 },
        ] {
            let scene = camera_only(projection);
            let cam = crate::ewa::camera(&scene);
            let view = scene.camera_open.view;
            for (i, j) in [(0, 0), (4, 3), (8, 6), (2, 5)] {
                let RayDepth {
                    origin: z0,
                    per_unit: c,
                } = ray_depth(&cam, &view, i, j).unwrap();
                assert!((z0 - 0.3).abs() < 1e-9, "origin on the near plane: {z0}");
                for s in [0.0, 0.7, 5.0, 20.0] {
                    let p = point_on_ray(&cam, i, j, s).unwrap();
                    let v = scene.camera_open.project(p);
                    let (x, y) = v.screen();
                    assert!((x - (f64::from(i) + 0.5)).abs() < 1e-9, "{x}");
                    assert!((y - (f64::from(j) + 0.5)).abs() < 1e-9, "{y}");
                    assert!(((v.depth - z0) / c - s).abs() < 1e-9 * (1.0 + s));
                }
            }
        }
    }
}
