//! PLY reading (ascii and binary, via ply-rs-bw) into plain arrays: positions, optional
//! normals, UVs, colours and radii, and polygon faces.

use std::path::Path;

use glam::{DVec2, DVec3};
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};

use crate::error::{Error, Result};

/// The content of a PLY file that the renderer uses.
#[derive(Debug, Clone, Default)]
pub struct PlyData {
    /// `x y z` per vertex.
    pub positions: Vec<DVec3>,
    /// `nx ny nz` per vertex, if present.
    pub normals: Option<Vec<DVec3>>,
    /// `u v` / `s t` / `texture_u texture_v` per vertex, if present.
    pub uvs: Option<Vec<DVec2>>,
    /// `red green blue` per vertex in [0, 1] (8-bit values are divided by 255), if present.
    pub colors: Option<Vec<[f64; 3]>>,
    /// `radius` per vertex, if present.
    pub radii: Option<Vec<f64>>,
    /// Polygons (vertex indices), from `vertex_indices` / `vertex_index`.
    pub faces: Vec<Vec<u32>>,
}

fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => f64::from(v),
        Property::UChar(v) => f64::from(v),
        Property::Short(v) => f64::from(v),
        Property::UShort(v) => f64::from(v),
        Property::Int(v) => f64::from(v),
        Property::UInt(v) => f64::from(v),
        Property::Float(v) => f64::from(v),
        Property::Double(v) => v,
        _ => return None,
    })
}

fn list(p: &Property) -> Option<Vec<i64>> {
    Some(match p {
        Property::ListChar(v) => v.iter().map(|&x| i64::from(x)).collect(),
        Property::ListUChar(v) => v.iter().map(|&x| i64::from(x)).collect(),
        Property::ListShort(v) => v.iter().map(|&x| i64::from(x)).collect(),
        Property::ListUShort(v) => v.iter().map(|&x| i64::from(x)).collect(),
        Property::ListInt(v) => v.iter().map(|&x| i64::from(x)).collect(),
        Property::ListUInt(v) => v.iter().map(|&x| i64::from(x)).collect(),
        _ => return None,
    })
}

fn is_byte(p: &Property) -> bool {
    matches!(p, Property::UChar(_) | Property::Char(_))
}

/// Reads a PLY file. Errors carry the path and the OS or parser reason.
pub fn read(path: &Path) -> Result<PlyData> {
    let bytes = crate::input::read_bounded(path, crate::input::MAX_MESH_BYTES, "PLY file")?;
    let mut reader = std::io::Cursor::new(bytes);
    let parser = Parser::<DefaultElement>::new();
    let ply = parser
        .read_ply(&mut reader)
        .map_err(|e| Error::format(path, format!("cannot parse PLY: {e}")))?;
    let verts = ply
        .payload
        .get("vertex")
        .ok_or_else(|| Error::format(path, "PLY file has no `vertex` element"))?;
    fn get<'e>(e: &'e DefaultElement, names: &[&str]) -> Option<&'e Property> {
        names.iter().find_map(|n| e.get(*n))
    }
    let mut out = PlyData::default();
    let first = verts.first();
    let has = |names: &[&str]| first.is_some_and(|e| get(e, names).is_some());
    let want_n = has(&["nx"]);
    let want_uv = has(&["u", "s", "texture_u"]);
    let want_c = has(&["red"]);
    let want_r = has(&["radius"]);
    let (mut normals, mut uvs, mut colors, mut radii) = (vec![], vec![], vec![], vec![]);
    for (i, e) in verts.iter().enumerate() {
        let num = |names: &[&str]| -> Result<f64> {
            let v = get(e, names).and_then(scalar).ok_or_else(|| {
                Error::format(
                    path,
                    format!("vertex {i}: missing numeric property `{}`", names[0]),
                )
            })?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(Error::format(
                    path,
                    format!("vertex {i}: `{}` is not finite", names[0]),
                ))
            }
        };
        out.positions
            .push(DVec3::new(num(&["x"])?, num(&["y"])?, num(&["z"])?));
        if want_n {
            normals.push(DVec3::new(num(&["nx"])?, num(&["ny"])?, num(&["nz"])?));
        }
        if want_uv {
            uvs.push(DVec2::new(
                num(&["u", "s", "texture_u"])?,
                num(&["v", "t", "texture_v"])?,
            ));
        }
        if want_c {
            let scale = if get(e, &["red"]).is_some_and(is_byte) {
                1.0 / 255.0
            } else {
                1.0
            };
            colors.push([
                num(&["red"])? * scale,
                num(&["green"])? * scale,
                num(&["blue"])? * scale,
            ]);
        }
        if want_r {
            radii.push(num(&["radius"])?);
        }
    }
    out.normals = want_n.then_some(normals);
    out.uvs = want_uv.then_some(uvs);
    out.colors = want_c.then_some(colors);
    out.radii = want_r.then_some(radii);
    if let Some(faces) = ply.payload.get("face") {
        for (fi, f) in faces.iter().enumerate() {
            let idx = get(f, &["vertex_indices", "vertex_index"])
                .and_then(list)
                .ok_or_else(|| {
                    Error::format(path, format!("face {fi}: no `vertex_indices` list"))
                })?;
            let mut face = Vec::with_capacity(idx.len());
            for i in idx {
                match u32::try_from(i) {
                    Ok(u) if (u as usize) < out.positions.len() => face.push(u),
                    _ => {
                        return Err(Error::format(
                            path,
                            format!(
                                "face {fi} refers to vertex {i}, but there are only {} vertices",
                                out.positions.len()
                            ),
                        ));
                    }
                }
            }
            if face.len() >= 3 {
                out.faces.push(face);
            }
        }
    }
    Ok(out)
}
