//! glTF meshes and materials: a primitive as an indexed [`Mesh`] with its morph targets and
//! skin weights, and a material as the renderer's [`Material`] and texture.

use glam::{DMat4, DVec2, DVec3};

use ::gltf::accessor::Dimensions;
use ::gltf::material::AlphaMode;
use ::gltf::mesh::{Mode, Semantic};
use ::gltf::texture::WrappingMode;

use mblur::Material;
use mblur::texture::Texture;

use super::data::{Buffers, read, read_indices};
use crate::mesh::{Corner, Mesh};

/// Linear-blend-skinning data of a primitive: four joints and weights per vertex.
#[derive(Debug, Clone, Default)]
pub struct SkinWeights {
    /// Joint indices (into the skin's joints) per vertex.
    pub joints: Vec<[u32; 4]>,
    /// Weights per vertex.
    pub weights: Vec<[f64; 4]>,
}

/// One triangle primitive of a glTF mesh.
#[derive(Debug, Clone)]
pub struct Primitive {
    /// Vertices (mesh space) and triangles with UVs (v up) and normals.
    pub mesh: Mesh,
    /// Per-vertex displacement of each morph target.
    pub targets: Vec<Vec<DVec3>>,
    /// Skin weights, when the primitive has `JOINTS_0` / `WEIGHTS_0`.
    pub skin: Option<SkinWeights>,
    /// Index of its glTF material (`None`: the default material).
    pub material: Option<usize>,
}

fn vec3s(v: &[f64]) -> Vec<DVec3> {
    v.chunks_exact(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect()
}

/// Reads primitive `pi` of `mesh`; `at` names the mesh in messages.
pub fn primitive(
    buffers: &Buffers,
    p: &::gltf::Primitive<'_>,
    at: &str,
) -> Result<Primitive, String> {
    if p.mode() != Mode::Triangles {
        return Err(format!(
            "{at}: primitive mode {:?} is not supported (only TRIANGLES)",
            p.mode()
        ));
    }
    let pos = p
        .get(&Semantic::Positions)
        .ok_or_else(|| format!("{at}: has no POSITION attribute"))?;
    let (pv, _) = read(
        buffers,
        &pos,
        &[Dimensions::Vec3],
        &format!("{at} POSITION"),
    )?;
    let positions = vec3s(&pv);
    let n = positions.len();
    let attr = |s: Semantic, d: Dimensions, name: &str| -> Result<Option<Vec<f64>>, String> {
        let Some(a) = p.get(&s) else { return Ok(None) };
        if a.count() != n {
            return Err(format!(
                "{at}: {name} has {} elements but POSITION has {n}",
                a.count()
            ));
        }
        read(buffers, &a, &[d], &format!("{at} {name}")).map(|v| Some(v.0))
    };
    for (s, _) in p.attributes() {
        if matches!(s, Semantic::TexCoords(k) | Semantic::Joints(k) | Semantic::Weights(k) if k > 0)
        {
            return Err(format!(
                "{at}: attribute {s:?} is not supported (one UV set and at most 4 joints per \
                 vertex)"
            ));
        }
    }
    let normals = attr(Semantic::Normals, Dimensions::Vec3, "NORMAL")?.map(|v| vec3s(&v));
    let uvs = attr(Semantic::TexCoords(0), Dimensions::Vec2, "TEXCOORD_0")?;
    let indices = match p.indices() {
        Some(a) => read_indices(buffers, &a, Dimensions::Scalar, n, &format!("{at} indices"))?,
        None => (0..n as u32).collect(),
    };
    if !indices.len().is_multiple_of(3) {
        return Err(format!(
            "{at}: {} indices do not make whole triangles",
            indices.len()
        ));
    }
    let corner = |i: u32| {
        let k = i as usize;
        let uv = uvs
            .as_ref()
            .and_then(|u| u.get(2 * k..2 * k + 2))
            .map_or(DVec2::ZERO, |u| DVec2::new(u[0], 1.0 - u[1]));
        let normal = normals
            .as_ref()
            .and_then(|v| v.get(k))
            .map_or(DVec3::ZERO, |v| v.normalize_or_zero());
        Corner {
            position: i,
            uv,
            normal,
        }
    };
    let triangles = indices
        .chunks_exact(3)
        .map(|t| [corner(t[0]), corner(t[1]), corner(t[2])])
        .collect();
    let mut targets = Vec::new();
    for (k, t) in p.morph_targets().enumerate() {
        let Some(a) = t.positions() else {
            targets.push(vec![DVec3::ZERO; n]);
            continue;
        };
        if a.count() != n {
            return Err(format!(
                "{at}: morph target {k} has {} positions but the primitive has {n}",
                a.count()
            ));
        }
        let (v, _) = read(
            buffers,
            &a,
            &[Dimensions::Vec3],
            &format!("{at} target {k}"),
        )?;
        targets.push(vec3s(&v));
    }
    Ok(Primitive {
        mesh: Mesh {
            positions,
            triangles,
        },
        targets,
        skin: skin_weights(buffers, p, n, at)?,
        material: p.material().index(),
    })
}

/// The `JOINTS_0` / `WEIGHTS_0` of a primitive with `n` vertices.
fn skin_weights(
    buffers: &Buffers,
    p: &::gltf::Primitive<'_>,
    n: usize,
    at: &str,
) -> Result<Option<SkinWeights>, String> {
    let (Some(j), Some(w)) = (p.get(&Semantic::Joints(0)), p.get(&Semantic::Weights(0))) else {
        return Ok(None);
    };
    if j.count() != n || w.count() != n {
        return Err(format!(
            "{at}: JOINTS_0 and WEIGHTS_0 need one element per vertex ({n})"
        ));
    }
    let joints = read_indices(
        buffers,
        &j,
        Dimensions::Vec4,
        u32::MAX as usize,
        &format!("{at} JOINTS_0"),
    )?;
    let (weights, _) = read(buffers, &w, &[Dimensions::Vec4], &format!("{at} WEIGHTS_0"))?;
    Ok(Some(SkinWeights {
        joints: joints
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect(),
        weights: weights
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect(),
    }))
}

impl Primitive {
    /// Mesh-space positions with morph `weights` applied.
    pub fn morphed(&self, weights: &[f64]) -> Vec<DVec3> {
        let mut out = self.mesh.positions.clone();
        for (t, w) in self.targets.iter().zip(weights) {
            if *w != 0.0 {
                for (p, d) in out.iter_mut().zip(t) {
                    *p += *d * *w;
                }
            }
        }
        out
    }

    /// World positions of skinned vertices `positions` with joint matrices `joints`
    /// (world matrix of each joint times its inverse bind matrix); a joint index past the
    /// skin's joints is an error.
    pub fn skinned(&self, positions: &[DVec3], joints: &[DMat4]) -> Result<Vec<DVec3>, String> {
        let Some(s) = &self.skin else {
            return Ok(positions.to_vec());
        };
        positions
            .iter()
            .zip(s.joints.iter().zip(&s.weights))
            .enumerate()
            .map(|(v, (p, (j, w)))| {
                let mut sum = DVec3::ZERO;
                for (ji, wi) in j.iter().zip(w) {
                    if *wi == 0.0 {
                        continue;
                    }
                    let m = joints.get(*ji as usize).ok_or_else(|| {
                        format!(
                            "vertex {v}: joint {ji} is out of range (the skin has {} joints)",
                            joints.len()
                        )
                    })?;
                    sum += m.transform_point3(*p) * *wi;
                }
                Ok(sum)
            })
            .collect()
    }
}

/// How a material's alpha is used.
fn alpha_of(m: &::gltf::Material<'_>, a: f64) -> f64 {
    match m.alpha_mode() {
        AlphaMode::Opaque => 1.0,
        AlphaMode::Blend => a,
        AlphaMode::Mask => {
            if a >= f64::from(m.alpha_cutoff().unwrap_or(0.5)) {
                1.0
            } else {
                0.0
            }
        }
    }
}

/// The renderer's material for glTF material `m` (base colour factor and texture, alpha
/// mode applied); `decode` turns an image index into its size and sRGB RGBA8 texels.
/// Lighting inputs the renderer has no use for (metallic-roughness, normal, occlusion
/// and emissive textures) are listed in `ignored`.
pub fn material(
    m: &::gltf::Material<'_>,
    at: &str,
    decode: &mut dyn FnMut(usize) -> crate::Result<(u32, u32, Vec<u8>)>,
    ignored: &mut Vec<String>,
) -> crate::Result<(Material, Option<Texture>)> {
    let pbr = m.pbr_metallic_roughness();
    let f = pbr.base_color_factor().map(f64::from);
    let masked = m.alpha_mode() == AlphaMode::Mask;
    let mut color = [f[0], f[1], f[2], alpha_of(m, f[3])];
    for (has, what) in [
        (
            pbr.metallic_roughness_texture().is_some(),
            "metallicRoughnessTexture",
        ),
        (m.normal_texture().is_some(), "normalTexture"),
        (m.occlusion_texture().is_some(), "occlusionTexture"),
        (m.emissive_texture().is_some(), "emissiveTexture"),
    ] {
        if has {
            ignored.push(format!("{at}: {what}"));
        }
    }
    let Some(info) = pbr.base_color_texture() else {
        return Ok((Material::unlit(color, None), None));
    };
    let err = |m: String| crate::Error::invalid(at, "baseColorTexture", m);
    if info.tex_coord() != 0 {
        return Err(err(format!(
            "uses TEXCOORD_{}; only TEXCOORD_0 is supported",
            info.tex_coord()
        )));
    }
    let tex = info.texture();
    let s = tex.sampler();
    for (axis, w) in [("wrapS", s.wrap_s()), ("wrapT", s.wrap_t())] {
        if w != WrappingMode::Repeat {
            return Err(err(format!(
                "sampler {axis} {w:?} is not supported (textures wrap around: REPEAT)"
            )));
        }
    }
    let (w, h, mut texels) = decode(tex.source().index())?;
    for px in texels.chunks_exact_mut(4) {
        let a = f64::from(px[3]) / 255.0;
        px[3] = match m.alpha_mode() {
            AlphaMode::Opaque => 255,
            AlphaMode::Blend => px[3],
            // The cutoff applies to the factor's alpha times the texel's.
            AlphaMode::Mask => (alpha_of(m, a * f[3]) * 255.0) as u8,
        };
    }
    if masked {
        color[3] = 1.0;
    }
    let texture = Texture::from_srgb8(w, h, texels)
        .ok_or_else(|| err("decoded texel count does not match the image size".into()))?;
    Ok((Material::unlit(color, None), Some(texture)))
}
