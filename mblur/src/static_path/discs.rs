//! Splats drawn as triangles for the static rasteriser: each splat an oriented polygon of
//! [`SPLAT_DISC_SIDES`] sides and its radius, moving with the splat (how `accum` and
//! `stochastic` draw splats; the `ewa` method filters them with Gaussians instead, Heinzle
//! 2010).

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use crate::prepared::{Material, ObjectInfo, PreparedScene, PreparedTriangle};

/// Sides of the polygon a splat is drawn as.
pub const SPLAT_DISC_SIDES: u32 = 16;

fn basis(n: DVec3) -> (DVec3, DVec3) {
    n.any_orthonormal_pair()
}

/// The scene with every splat replaced by an oriented disc of triangles (one material per
/// distinct splat colour), for static rasterisation. Each splat's disc exists over the
/// splat's span; on a curved path its corners are kept in object space (the splat's
/// [`SplatLocal`](crate::prepared::SplatLocal) disc) and its set is entered as an object
/// with that path, so [`PreparedScene::corners_at`] places it on the true path at every
/// instant.
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
    // A corner of the disc centred at `c` with unit tangents `u`, `v` scaled by `r`.
    let ring = |c: DVec3, u: DVec3, v: DVec3, r: f64, k: u32| {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(sides);
        c + (u * a.cos() + v * a.sin()) * r
    };
    for (si, o) in scene.splat_objects.iter().enumerate() {
        let start = out.triangles.len();
        for s in scene.splats.get(o.range.clone()).unwrap_or(&[]) {
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
            let mut open = (s.centre_open, uo, vo, s.radius_open);
            let mut close = (s.centre_close, uc, vc, s.radius_close);
            // On a curved path the segment's ends are the object-space disc moved by the
            // path (the same disc ewa's keys take), its axes already scaled.
            let local = scene.splat_path(s).map(|(_, l)| {
                let (u, v) = l.axes();
                (l.centre, u, v, 1.0)
            });
            if let (Some([c, u, v]), Some([d, p, q])) = (
                scene.splat_disc_at(s, s.span[0]),
                scene.splat_disc_at(s, s.span[1]),
            ) {
                open = (c, u, v, 1.0);
                close = (d, p, q, 1.0);
            }
            let corners = |(c, u, v, r): (DVec3, DVec3, DVec3, f64), k: u32, k1: u32| {
                [c, ring(c, u, v, r, k), ring(c, u, v, r, k1)]
            };
            for k in 0..sides {
                let k1 = (k + 1) % sides;
                let world_open = corners(open, k, k1);
                let world_close = corners(close, k, k1);
                out.triangles.push(PreparedTriangle {
                    object: object_base + s.object,
                    material,
                    open: world_open.map(|p| scene.project_at(s.span[0], p)),
                    close: world_close.map(|p| scene.project_at(s.span[1], p)),
                    world_open,
                    world_close,
                    uv: [DVec2::ZERO; 3],
                    normal_open: [s.normal_open; 3],
                    normal_close: [s.normal_close; 3],
                    span: s.span,
                    local: local.map(|l| corners(l, k, k1)),
                });
            }
        }
        // The set as an object (index `object_base + si`), with its path.
        debug_assert_eq!(out.objects.len() as u32, object_base + si as u32);
        out.objects.push(ObjectInfo {
            range: start..out.triangles.len(),
            ..o.clone()
        });
    }
    out
}
