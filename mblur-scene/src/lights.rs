//! Lights, lit materials and shading normals from the scene description
//! (docs/SCENE_FORMAT.md, "Lights and shading").

use glam::DVec3;
use mblur::{Light, LightKey, Material, ShadingModel};

use crate::desc::{LightDesc, MaterialDesc, NormalsDesc, ShadingDesc, SplatDesc};
use crate::mesh::Corner;

/// The renderer's lights for `desc` (validated: directions non-zero, `direction` or
/// `position` present unless `keys` is). Open and close are the two keys at 0 and 1.
pub(crate) fn lights(desc: &[LightDesc]) -> Vec<Light> {
    let keyed = |t: f64, v: [f64; 3], unit: bool| {
        let v = DVec3::from_array(v);
        LightKey {
            t,
            value: if unit { v.normalize_or_zero() } else { v },
        }
    };
    let ends = |open: Option<[f64; 3]>, close: Option<[f64; 3]>, unit: bool| {
        let open = open.unwrap_or_default();
        let mut keys = vec![keyed(0.0, open, unit)];
        if let Some(c) = close.filter(|c| *c != open) {
            keys.push(keyed(1.0, c, unit));
        }
        keys
    };
    desc.iter()
        .map(|l| match l {
            LightDesc::Ambient { color } => Light::Ambient { colour: *color },
            LightDesc::Directional {
                direction,
                direction_close,
                keys,
                color,
                intensity,
            } => Light::Directional {
                directions: match keys {
                    Some(k) => k.iter().map(|k| keyed(k.t, k.direction, true)).collect(),
                    None => ends(*direction, *direction_close, true),
                },
                colour: *color,
                intensity: *intensity,
            },
            LightDesc::Point {
                position,
                position_close,
                keys,
                color,
                intensity,
            } => Light::Point {
                positions: match keys {
                    Some(k) => k.iter().map(|k| keyed(k.t, k.position, false)).collect(),
                    None => ends(*position, *position_close, false),
                },
                colour: *color,
                intensity: *intensity,
            },
        })
        .collect()
}

/// `m` with the shading fields of `desc`.
pub(crate) fn with_shading(m: Material, desc: &MaterialDesc) -> Material {
    shaded(
        m,
        desc.shading,
        desc.specular,
        desc.shininess,
        desc.emissive,
    )
}

/// The material of a splat object: white albedo (each splat carries its colour) and the
/// object's shading fields; `None` for unlit splats.
pub(crate) fn splat_material(desc: &SplatDesc) -> Option<Material> {
    (desc.shading != ShadingDesc::Unlit).then(|| {
        let white = Material::unlit([1.0; 4], None);
        shaded(
            white,
            desc.shading,
            desc.specular,
            desc.shininess,
            desc.emissive,
        )
    })
}

fn shaded(
    m: Material,
    shading: ShadingDesc,
    specular: [f64; 3],
    shininess: f64,
    emissive: [f64; 3],
) -> Material {
    Material {
        shading: match shading {
            ShadingDesc::Unlit => ShadingModel::Unlit,
            ShadingDesc::Lambert => ShadingModel::Lambert,
            ShadingDesc::BlinnPhong => ShadingModel::BlinnPhong,
        },
        specular,
        shininess,
        emissive,
        ..m
    }
}

/// Area-weighted vertex normals of the positions `world` for the triangles `tris`: per
/// position the sum of the cross products of the faces using it (twice their area times
/// their unit normal), normalised; zero where the sum is zero.
pub(crate) fn smooth_normals(world: &[DVec3], tris: &[[Corner; 3]]) -> Vec<DVec3> {
    let mut sum = vec![DVec3::ZERO; world.len()];
    let at = |i: u32| world.get(i as usize).copied().unwrap_or(DVec3::ZERO);
    for t in tris {
        let [a, b, c] = t.map(|c| at(c.position));
        let n = (b - a).cross(c - a);
        if !n.is_finite() {
            continue;
        }
        for c in t {
            if let Some(s) = sum.get_mut(c.position as usize) {
                *s += n;
            }
        }
    }
    sum.into_iter().map(DVec3::normalize_or_zero).collect()
}

/// The shading normal of corner `c` of a face with unit normal `face`: per `mode`, the
/// mesh's own normal (transformed by `normal_matrix`; `None` where positions are given
/// per key, so the mesh's normals do not follow them) when it has one, else the smooth
/// normal at its position (`smooth`, empty for `flat`), else the face normal.
pub(crate) fn corner_normal(
    mode: NormalsDesc,
    c: &Corner,
    normal_matrix: Option<&glam::DMat3>,
    smooth: &[DVec3],
    face: DVec3,
) -> DVec3 {
    let own = normal_matrix
        .filter(|_| mode == NormalsDesc::Auto && c.normal != DVec3::ZERO)
        .map(|m| (*m * c.normal).normalize_or_zero())
        .filter(|n| *n != DVec3::ZERO);
    let smooth = (mode != NormalsDesc::Flat)
        .then(|| smooth.get(c.position as usize).copied())
        .flatten()
        .filter(|n| *n != DVec3::ZERO);
    own.or(smooth).unwrap_or(face)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    fn corner(i: u32) -> Corner {
        Corner {
            position: i,
            uv: DVec2::ZERO,
            normal: DVec3::ZERO,
        }
    }

    #[test]
    fn smooth_normals_of_a_closed_tetrahedron_point_outward() {
        let p = [
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
        ];
        // Counter-clockwise seen from outside.
        let faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
        let tris: Vec<[Corner; 3]> = faces.iter().map(|f| f.map(corner)).collect();
        let n = smooth_normals(&p, &tris);
        for (v, n) in p.iter().zip(&n) {
            // By symmetry the vertex normal is the vertex direction itself.
            assert!((*n - v.normalize()).length() < 1e-12, "{v} {n}");
        }
    }

    #[test]
    fn a_degenerate_face_adds_nothing_and_a_lone_vertex_stays_zero() {
        let p = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::Z,
        ];
        let tris = vec![[0, 1, 2].map(corner), [0, 1, 3].map(corner)];
        let n = smooth_normals(&p, &tris);
        assert_eq!(n[0], DVec3::Z);
        assert_eq!(n[3], DVec3::ZERO);
        assert_eq!(n[4], DVec3::ZERO);
    }
}
