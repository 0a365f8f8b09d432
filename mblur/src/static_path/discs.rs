//! Splats drawn as triangles for the static rasteriser: each splat an oriented polygon of
//! [`SPLAT_DISC_SIDES`] sides and its radius, moving with the splat (how `accum` and
//! `stochastic` draw splats; the `ewa` method filters them with Gaussians instead, Heinzle
//! 2010).

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use crate::prepared::{Material, PreparedScene, PreparedTriangle};

/// Sides of the polygon a splat is drawn as.
pub const SPLAT_DISC_SIDES: u32 = 16;

fn basis(n: DVec3) -> (DVec3, DVec3) {
    n.any_orthonormal_pair()
}

/// The scene with every splat replaced by an oriented disc of triangles (one material per
/// distinct splat colour), for static rasterisation.
pub fn splats_as_discs(scene: &PreparedScene) -> PreparedScene {
    let mut out = scene.clone();
    if scene.splats.is_empty() {
        return out;
    }
    // One material per distinct (colour, splat object): a lit object's splats take its
    // shading model with their own colour as albedo.
    let mut mats: HashMap<([u64; 4], u32), u32> = HashMap::new();
    let sides = SPLAT_DISC_SIDES;
    let object_base = out.objects.len() as u32;
    for s in &scene.splats {
        let lit = scene.splat_material(s);
        let key = (
            s.color.map(f64::to_bits),
            lit.map_or(u32::MAX, |_| s.object),
        );
        let material = *mats.entry(key).or_insert_with(|| {
            out.materials.push(match lit {
                Some(m) => Material {
                    color: s.color,
                    ..m.clone()
                },
                None => Material::unlit(s.color, None),
            });
            (out.materials.len() - 1) as u32
        });
        let (uo, vo) = basis(s.normal_open);
        let (uc, vc) = basis(s.normal_close);
        let ring = |c: DVec3, u: DVec3, v: DVec3, r: f64, k: u32| {
            let a = std::f64::consts::TAU * f64::from(k) / f64::from(sides);
            c + (u * a.cos() + v * a.sin()) * r
        };
        for k in 0..sides {
            let k1 = (k + 1) % sides;
            let world_open = [
                s.centre_open,
                ring(s.centre_open, uo, vo, s.radius_open, k),
                ring(s.centre_open, uo, vo, s.radius_open, k1),
            ];
            let world_close = [
                s.centre_close,
                ring(s.centre_close, uc, vc, s.radius_close, k),
                ring(s.centre_close, uc, vc, s.radius_close, k1),
            ];
            out.triangles.push(PreparedTriangle {
                object: object_base + s.object,
                material,
                open: world_open.map(|p| scene.camera_open.project(p)),
                close: world_close.map(|p| scene.camera_close.project(p)),
                world_open,
                world_close,
                uv: [DVec2::ZERO; 3],
                normal_open: [s.normal_open; 3],
                normal_close: [s.normal_close; 3],
                span: [0.0, 1.0],
                local: None,
            });
        }
    }
    out
}
