//! The scene's opaque triangles as raster-hier takes them — static and moving lists, the
//! near plane handled — and the shading of the samples that hit them: flat colours, or
//! textures at the perspective-correct UV from edge-eqn's `barycentrics_at(x, y, t)`,
//! averaged per pixel or over the filter's support (weighted by the shutter response when it
//! is not a box).

use edge_eqn::{MovingTriangle, TriangleSetup};
use glam::DVec2;
use raster_hier::{NO_HIT, RasterTriangle, SampleBuffer, TimeInterval};

use super::filter::SampleFilter;
use super::not_applicable;
use crate::camera::Vertex2dh;
use crate::corners::xyw;
use crate::error::Result;
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::prepared::span_local_time;
use crate::static_path::clip::clip_near;

/// How a raster id is shaded.
pub(super) enum Shading {
    /// Opaque flat colour (premultiplied = straight, alpha 1).
    Flat([f64; 3]),
    /// Textured: perspective-correct barycentrics from the setup (at the sample's time local
    /// to the triangle's `span`), then the UV.
    Textured {
        setup: Box<TriangleSetup<f64>>,
        span: [f64; 2],
        uv: [DVec2; 3],
        material: u32,
    },
    /// Lit: perspective-correct barycentrics from the setup (local time as for
    /// `Textured`), mapped to the weights of the scene triangle's corners (`bary`, corners
    /// 1 and 2), then [`PreparedScene::shade_surface`] at the sample's instant.
    Lit {
        setup: Box<TriangleSetup<f64>>,
        span: [f64; 2],
        bary: [DVec2; 3],
        tri: u32,
    },
}

/// A triangle ready for raster-hier: 2DH corners and depths at the start and end of its
/// span, UVs, material.
pub(super) struct Input {
    open: [Vertex2dh; 3],
    close: [Vertex2dh; 3],
    /// The part of the shutter it exists in (a segment of curved motion, or `[0, 1]`).
    span: [f64; 2],
    uv: [DVec2; 3],
    material: u32,
    /// Weights of the scene triangle's corners 1 and 2 at each corner (they differ from
    /// the unit weights only after near-plane clipping).
    bary: [DVec2; 3],
    /// Index of the scene triangle.
    tri: u32,
}

/// The weights of corners 1 and 2 at a triangle's own corners.
const UNIT_BARY: [DVec2; 3] = [DVec2::ZERO, DVec2::X, DVec2::Y];

/// Clips a static triangle to view depth >= near ([`clip_near`], the static path's
/// clipper, with the UVs and barycentric weights as attributes), fanned into triangles.
fn clip_static(t: &Input, near: f64, out: &mut Vec<Input>) {
    let corners = std::array::from_fn(|k| (t.open[k], (t.uv[k], t.bary[k])));
    for c in clip_near(&corners, near) {
        let open = c.map(|p| p.0);
        out.push(Input {
            open,
            close: open,
            span: t.span,
            uv: c.map(|p| p.1.0),
            material: t.material,
            bary: c.map(|p| p.1.1),
            tri: t.tri,
        });
    }
}

/// The opaque triangles of the scene split into static and moving lists, near-plane
/// handled: triangles entirely nearer than `near` or entirely beyond `far` during their
/// span are dropped, static triangles crossing `near` are clipped, moving ones crossing it
/// are an error naming the object.
///
/// Every segment of curved motion ([`crate::PreparedTriangle::span`]) is its own raster
/// triangle over its own span, so a sample at time t is tested only against the segment
/// that exists then, at t's local time: the samples follow the segments' chords, which
/// lie on the true arc at their ends.
pub(super) fn inputs(scene: &PreparedScene) -> Result<(Vec<Input>, Vec<Input>)> {
    let (mut fixed, mut moving) = (Vec::new(), Vec::new());
    for (index, tri) in scene.triangles.iter().enumerate() {
        let depths = tri.open.iter().chain(&tri.close).map(|v| v.depth);
        let (lo, hi) = depths.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
        if hi < scene.near || lo > scene.far {
            continue;
        }
        let input = Input {
            open: tri.open,
            close: tri.close,
            span: tri.span,
            uv: tri.uv,
            material: tri.material,
            bary: UNIT_BARY,
            tri: index as u32,
        };
        let is_moving = tri.is_moving();
        if lo >= scene.near {
            if is_moving {
                moving.push(input);
            } else {
                fixed.push(input);
            }
        } else if !is_moving {
            clip_static(&input, scene.near, &mut fixed);
        } else {
            let name = scene
                .objects
                .get(tri.object as usize)
                .map_or("?", |o| o.name.as_str());
            return Err(not_applicable(format!(
                "object \"{name}\" crosses the near plane (depth {lo} < near {}) while moving; \
                 moving triangles are rasterised unclipped",
                scene.near
            )));
        }
    }
    Ok((fixed, moving))
}

/// The raster-hier triangle of `t` with raster id `id`, view depth as its depth attribute.
pub(super) fn raster_triangle(t: &Input, id: u32) -> RasterTriangle<f64> {
    let triangle = MovingTriangle::new(xyw(&t.open), xyw(&t.close))
        .with_depth(t.open.map(|v| v.depth), t.close.map(|v| v.depth));
    RasterTriangle {
        triangle,
        id,
        span: TimeInterval::new(t.span[0], t.span[1]),
    }
}

/// How samples that hit `t` (raster triangle `r`) are shaded.
pub(super) fn shading(scene: &PreparedScene, t: &Input, r: &RasterTriangle<f64>) -> Shading {
    let textured = scene
        .materials
        .get(t.material as usize)
        .is_some_and(|m| m.texture.is_some());
    if scene.is_lit(t.material) {
        Shading::Lit {
            setup: Box::new(r.triangle.setup()),
            span: t.span,
            bary: t.bary,
            tri: t.tri,
        }
    } else if textured {
        Shading::Textured {
            setup: Box::new(r.triangle.setup()),
            span: t.span,
            uv: t.uv,
            material: t.material,
        }
    } else {
        let c = scene.shade(t.material, DVec2::ZERO);
        Shading::Flat([c[0], c[1], c[2]])
    }
}

/// The colour of one sample: the background where it hit nothing (`missed`), else its
/// triangle's shading at the sample's position and instant.
fn sample_colour(
    scene: &PreparedScene,
    shade: &[Shading],
    x: f64,
    y: f64,
    t: f64,
    missed: bool,
    id: u32,
) -> [f64; 3] {
    if missed {
        return scene.background;
    }
    match shade.get(id as usize) {
        Some(Shading::Flat(c)) => *c,
        Some(Shading::Textured {
            setup,
            span,
            uv,
            material,
        }) => {
            let l = setup.barycentrics_at(x, y, span_local_time(*span, t));
            let st = uv[0] * l[0] + uv[1] * l[1] + uv[2] * l[2];
            let c = scene.shade(*material, st);
            [c[0], c[1], c[2]]
        }
        Some(Shading::Lit {
            setup,
            span,
            bary,
            tri,
        }) => {
            let l = setup.barycentrics_at(x, y, span_local_time(*span, t));
            let b = bary[0] * l[0] + bary[1] * l[1] + bary[2] * l[2];
            match scene.triangles.get(*tri as usize) {
                Some(p) => {
                    let c = scene.shade_surface(p, [1.0 - b.x - b.y, b.x, b.y], t);
                    [c[0], c[1], c[2]]
                }
                None => scene.background,
            }
        }
        None => {
            debug_assert!(false, "raster id {id} has no shading");
            scene.background
        }
    }
}

/// Resolve: per pixel the mean of its samples' colours (weighted by w(t) for a non-box
/// shutter response), or with `filter` the filter-weighted mean over the samples its support
/// holds ([`SampleFilter::splat`]); background for samples that hit nothing or only geometry
/// beyond the far plane. The image has the unpadded size.
pub(super) fn resolve(
    scene: &PreparedScene,
    buf: &SampleBuffer<f64>,
    shade: &[Shading],
    filter: Option<&SampleFilter>,
) -> Image {
    let pad = filter.map_or(0, SampleFilter::pad);
    let (width, height) = (scene.width - 2 * pad, scene.height - 2 * pad);
    let w = width as usize;
    // Per pixel: weighted sum, weight, sum without the shutter weight and its weight
    // (fallback when all shutter weights are zero).
    let mut acc = vec![([0.0f64; 3], 0.0f64, [0.0f64; 3], 0.0f64); w * height as usize];
    let weighted = !scene.shutter.is_box();
    let far = scene.far;
    buf.for_each_sample(|px, py, x, y, t, depth, id| {
        let c = sample_colour(scene, shade, x, y, t, depth > far || id == NO_HIT, id);
        let wt = if weighted {
            scene.shutter.weight(t)
        } else {
            1.0
        };
        let mut add = |pixel: usize, fw: f64| {
            if let Some(p) = acc.get_mut(pixel) {
                for ((sum, plain), ck) in p.0.iter_mut().zip(&mut p.2).zip(c) {
                    *sum += wt * fw * ck;
                    *plain += fw * ck;
                }
                p.1 += wt * fw;
                p.3 += fw;
            }
        };
        match filter {
            Some(f) => f.splat(x, y, add),
            None => add(py as usize * w + px as usize, 1.0),
        }
    });
    Image {
        width,
        height,
        pixels: acc
            .iter()
            .map(|(sum, wsum, plain, psum)| {
                let c: [f64; 3] = if *wsum > 0.0 {
                    sum.map(|v| v / wsum)
                } else if *psum > 0.0 {
                    plain.map(|v| v / psum)
                } else {
                    scene.background
                };
                c.map(|v| if v.is_finite() { v as f32 } else { 0.0 })
            })
            .collect(),
    }
}
