//! Triangle meshes: the built-in shapes and the `.obj` / `.ply` loaders.
//!
//! A [`Mesh`] keeps its vertex positions separate from its triangle corners so that explicit
//! per-vertex positions at shutter close (`motion.positions_close`) address the positions a
//! user sees in the file, while UVs and normals stay per corner (seams, hard edges).

use std::f64::consts::PI;
use std::io::BufReader;
use std::path::Path;

use glam::{DVec2, DVec3};

use crate::desc::{BoxDesc, Caps, CylinderDesc, FenceDesc, GridDesc, QuadDesc, SphereDesc};
use crate::error::{Error, Result};

/// One corner of a triangle: which position, and the corner's UV and normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    /// Index into [`Mesh::positions`].
    pub position: u32,
    /// Texture coordinate (v up: v = 0 is the bottom row of the image).
    pub uv: DVec2,
    /// Unit normal (object space), or zero when unknown (the face normal is used).
    pub normal: DVec3,
}

/// An indexed triangle mesh in object space.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles as three corners each.
    pub triangles: Vec<[Corner; 3]>,
}

impl Mesh {
    fn push_vertex(&mut self, p: DVec3) -> u32 {
        self.positions.push(p);
        (self.positions.len() - 1) as u32
    }

    fn corner(&self, i: u32, uv: DVec2, normal: DVec3) -> Corner {
        Corner {
            position: i,
            uv,
            normal,
        }
    }

    /// Appends another mesh (positions re-indexed).
    pub fn append(&mut self, other: &Mesh) {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.triangles.extend(other.triangles.iter().map(|t| {
            t.map(|c| Corner {
                position: c.position + base,
                ..c
            })
        }));
    }

    /// Total surface area (sum of triangle areas).
    pub fn area(&self) -> f64 {
        self.triangles.iter().map(|t| self.triangle_area(t)).sum()
    }

    pub(crate) fn triangle_area(&self, t: &[Corner; 3]) -> f64 {
        let [a, b, c] = t.map(|c| self.position(c.position));
        0.5 * (b - a).cross(c - a).length()
    }

    pub(crate) fn position(&self, i: u32) -> DVec3 {
        self.positions
            .get(i as usize)
            .copied()
            .unwrap_or(DVec3::ZERO)
    }
}

/// Inline triangles: three new vertices per triangle, UVs (0,0), (1,0), (0,1).
pub fn triangles(tris: &[[[f64; 3]; 3]]) -> Mesh {
    let mut m = Mesh::default();
    let uvs = [
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, 0.0),
        DVec2::new(0.0, 1.0),
    ];
    for t in tris {
        let idx = t.map(|p| m.push_vertex(DVec3::from_array(p)));
        m.triangles
            .push([0, 1, 2].map(|k| m.corner(idx[k], uvs[k], DVec3::ZERO)));
    }
    m
}

/// Adds a grid of `(nu + 1) x (nv + 1)` vertices from `f(u, v) -> (position, normal)` with
/// u, v in [0, 1], two triangles per cell; cells whose triangle collapses (poles) are skipped.
fn param_grid(m: &mut Mesh, nu: u32, nv: u32, f: impl Fn(f64, f64) -> (DVec3, DVec3)) {
    let base = m.positions.len() as u32;
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            let (u, v) = (f64::from(i) / f64::from(nu), f64::from(j) / f64::from(nv));
            let (p, n) = f(u, v);
            m.push_vertex(p);
            normals.push(n);
            uvs.push(DVec2::new(u, v));
        }
    }
    let id = |i: u32, j: u32| base + j * (nu + 1) + i;
    for j in 0..nv {
        for i in 0..nu {
            let quad = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            for tri in [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]] {
                let t = tri.map(|k| {
                    let l = (k - base) as usize;
                    Corner {
                        position: k,
                        uv: uvs[l],
                        normal: normals[l],
                    }
                });
                if m.triangle_area(&t) > 0.0 {
                    m.triangles.push(t);
                }
            }
        }
    }
}

/// UV sphere (`subdivisions` rings, twice as many segments), optionally wrinkled.
pub fn sphere(d: &SphereDesc) -> Mesh {
    let n = d.subdivisions.max(2);
    let mut m = Mesh::default();
    let (r, w, f) = (d.radius, d.wrinkle, d.wrinkle_frequency);
    param_grid(&mut m, 2 * n, n, |u, v| {
        let (phi, theta) = (2.0 * PI * u, PI * (1.0 - v));
        // Exact poles, so the pole cells collapse to single triangles.
        let (st, ct) = if v == 0.0 || v == 1.0 {
            (0.0, 1.0 - 2.0 * (1.0 - v))
        } else {
            theta.sin_cos()
        };
        let dir = DVec3::new(st * phi.cos(), ct, -st * phi.sin());
        let bump = 1.0 + w * (f * phi).sin() * (f * theta).sin();
        (dir * r * bump, dir)
    });
    m
}

/// Axis-aligned box, four vertices per face (24), UVs 0..1 on each face.
pub fn cuboid(d: &BoxDesc) -> Mesh {
    let h = DVec3::from_array(d.size) * 0.5;
    let mut m = Mesh::default();
    // (normal, u axis, v axis); u x v = normal.
    let faces = [
        (DVec3::X, DVec3::NEG_Z, DVec3::Y),
        (DVec3::NEG_X, DVec3::Z, DVec3::Y),
        (DVec3::Y, DVec3::X, DVec3::NEG_Z),
        (DVec3::NEG_Y, DVec3::X, DVec3::Z),
        (DVec3::Z, DVec3::X, DVec3::Y),
        (DVec3::NEG_Z, DVec3::NEG_X, DVec3::Y),
    ];
    for (n, u, v) in faces {
        let c = n * h;
        let (hu, hv) = (u * h, v * h);
        let idx = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(a, b)| m.push_vertex(c + hu * a + hv * b));
        let uv = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(a, b)| DVec2::new(a, b));
        for tri in [[0, 1, 2], [0, 2, 3]] {
            m.triangles.push(tri.map(|k| m.corner(idx[k], uv[k], n)));
        }
    }
    m
}

/// Quad in the XY plane facing +Z.
pub fn quad(d: &QuadDesc) -> Mesh {
    let (w, h) = (d.size[0], d.size[1]);
    let mut m = Mesh::default();
    param_grid(&mut m, 1, 1, |u, v| {
        (DVec3::new((u - 0.5) * w, (v - 0.5) * h, 0.0), DVec3::Z)
    });
    for t in &mut m.triangles {
        for c in t.iter_mut() {
            c.uv *= DVec2::from_array(d.uv_repeat);
        }
    }
    m
}

/// Subdivided sheet in the XY plane with an optional ripple in Z (cloth).
pub fn grid(d: &GridDesc) -> Mesh {
    let (w, h) = (d.size[0], d.size[1]);
    let (a, f) = (d.wave_amplitude, d.wave_frequency);
    let mut m = Mesh::default();
    param_grid(
        &mut m,
        d.divisions[0].max(1),
        d.divisions[1].max(1),
        |u, v| {
            let z = a * (2.0 * PI * f * u).sin() * (PI * f * v).cos();
            let dzdx = a * 2.0 * PI * f / w * (2.0 * PI * f * u).cos() * (PI * f * v).cos();
            let dzdy = -a * PI * f / h * (2.0 * PI * f * u).sin() * (PI * f * v).sin();
            let n = DVec3::new(-dzdx, -dzdy, 1.0).normalize_or(DVec3::Z);
            (DVec3::new((u - 0.5) * w, (v - 0.5) * h, z), n)
        },
    );
    m
}

/// A row of `slats` vertical quads along X, centred at the origin.
pub fn fence(d: &FenceDesc) -> Mesh {
    let n = d.slats.max(1);
    let total = f64::from(n) * d.slat_width + f64::from(n - 1) * d.gap;
    let mut m = Mesh::default();
    for s in 0..n {
        let x0 = -0.5 * total + f64::from(s) * (d.slat_width + d.gap);
        let mut slat = Mesh::default();
        param_grid(&mut slat, 1, 1, |u, v| {
            (
                DVec3::new(x0 + u * d.slat_width, (v - 0.5) * d.height, 0.0),
                DVec3::Z,
            )
        });
        m.append(&slat);
    }
    m
}

/// Cylinder along Y with flat, round (capsule) or no caps.
pub fn cylinder(d: &CylinderDesc) -> Mesh {
    let seg = d.segments.max(3);
    let (r, hh) = (d.radius, 0.5 * d.height);
    let mut m = Mesh::default();
    param_grid(&mut m, seg, 1, |u, v| {
        let phi = 2.0 * PI * u;
        let dir = DVec3::new(phi.cos(), 0.0, -phi.sin());
        (dir * r + DVec3::Y * (2.0 * v - 1.0) * hh, dir)
    });
    match d.caps {
        Caps::None => {}
        Caps::Flat => {
            for sign in [1.0, -1.0] {
                let mut cap = Mesh::default();
                param_grid(&mut cap, seg, 1, |u, v| {
                    let phi = 2.0 * PI * u * sign;
                    let p = DVec3::new(phi.cos(), 0.0, -phi.sin()) * r * (1.0 - v);
                    (p + DVec3::Y * sign * hh, DVec3::Y * sign)
                });
                m.append(&cap);
            }
        }
        Caps::Round => {
            let rings = (seg / 4).max(2);
            for sign in [1.0, -1.0] {
                let mut cap = Mesh::default();
                param_grid(&mut cap, seg, rings, |u, v| {
                    let phi = 2.0 * PI * u * sign;
                    let theta = 0.5 * PI * v;
                    let (st, ct) = if v == 1.0 {
                        (1.0, 0.0)
                    } else {
                        theta.sin_cos()
                    };
                    let dir = DVec3::new(ct * phi.cos(), sign * st, -ct * phi.sin());
                    (dir * r + DVec3::Y * sign * hh, dir)
                });
                m.append(&cap);
            }
        }
    }
    m
}

/// Loads a `.obj` (via tobj, triangulated) or `.ply` (ascii or binary) mesh.
pub fn load_file(path: &Path) -> Result<Mesh> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj") => load_obj(path),
        Some("gltf" | "glb") => crate::gltf::GltfScene::load(path)?.rest_mesh(),
        Some("ply") => {
            let ply = crate::ply::read(path)?;
            if ply.faces.is_empty() {
                return Err(Error::format(
                    path,
                    "PLY file has no faces (a mesh needs triangles)",
                ));
            }
            let mut m = Mesh {
                positions: ply.positions,
                triangles: Vec::new(),
            };
            for (fi, face) in ply.faces.iter().enumerate() {
                for k in 1..face.len().saturating_sub(1) {
                    let tri = [face[0], face[k], face[k + 1]];
                    let mut corners = [Corner {
                        position: 0,
                        uv: DVec2::ZERO,
                        normal: DVec3::ZERO,
                    }; 3];
                    for (c, &i) in corners.iter_mut().zip(&tri) {
                        let iu = i as usize;
                        if iu >= m.positions.len() {
                            return Err(Error::format(
                                path,
                                format!(
                                    "face {fi} refers to vertex {i}, but there are only {} vertices",
                                    m.positions.len()
                                ),
                            ));
                        }
                        c.position = i;
                        c.uv = ply
                            .uvs
                            .as_ref()
                            .and_then(|u| u.get(iu))
                            .copied()
                            .unwrap_or(DVec2::ZERO);
                        c.normal = ply
                            .normals
                            .as_ref()
                            .and_then(|n| n.get(iu))
                            .copied()
                            .unwrap_or(DVec3::ZERO);
                    }
                    m.triangles.push(corners);
                }
            }
            Ok(m)
        }
        _ => Err(Error::format(
            path,
            "unsupported mesh file type (expected .obj, .ply, .gltf or .glb)",
        )),
    }
}

/// The first face line (`f ...`) with fewer than three vertices, as an error naming its
/// line: the OBJ loader would drop it silently.
fn check_obj_faces(path: &Path, text: &[u8]) -> Result<()> {
    for (n, line) in text.split(|&b| b == b'\n').enumerate() {
        let mut words = line
            .split(|b| b.is_ascii_whitespace())
            .filter(|w| !w.is_empty());
        if words.next() == Some(b"f".as_slice()) {
            let count = words.take_while(|w| !w.starts_with(b"#")).count();
            if count < 3 {
                return Err(Error::format(
                    path,
                    format!(
                        "line {}: a face needs at least 3 vertices, this one has {count}",
                        n + 1
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The position indices (0-based, into the `v` lines) of every triangle corner of an OBJ
/// file in face order, each face fanned from its first corner as tobj triangulates it, and
/// the `v` line positions (parsed as f32, as tobj reads them).
struct ObjVertices {
    positions: Vec<DVec3>,
    corners: Vec<u32>,
}

/// Reads the `v` lines and the position index of every triangulated face corner.
fn obj_vertices(path: &Path, text: &[u8]) -> Result<ObjVertices> {
    let mut out = ObjVertices {
        positions: Vec::new(),
        corners: Vec::new(),
    };
    for (n, line) in String::from_utf8_lossy(text).lines().enumerate() {
        let mut words = line.split_whitespace().take_while(|w| !w.starts_with('#'));
        match words.next() {
            Some("v") => {
                let c: Vec<f32> = words.take(3).filter_map(|w| w.parse().ok()).collect();
                let &[x, y, z] = c.as_slice() else {
                    return Err(Error::format(
                        path,
                        format!("line {}: a `v` line needs 3 coordinates", n + 1),
                    ));
                };
                out.positions
                    .push(DVec3::new(f64::from(x), f64::from(y), f64::from(z)));
            }
            Some("f") => {
                let count = out.positions.len() as i64;
                let mut face = Vec::new();
                for w in words {
                    let i: i64 = w
                        .split('/')
                        .next()
                        .and_then(|v| v.parse().ok())
                        .unwrap_or(0);
                    let i = if i < 0 { count + i } else { i - 1 };
                    if !(0..count).contains(&i) {
                        return Err(Error::format(
                            path,
                            format!("line {}: face refers to a missing vertex", n + 1),
                        ));
                    }
                    face.push(i as u32);
                }
                for k in 1..face.len().saturating_sub(1) {
                    out.corners.extend([face[0], face[k], face[k + 1]]);
                }
            }
            _ => {}
        }
    }
    Ok(out)
}

/// Loads an OBJ file: faces, UVs and normals through tobj; vertex positions numbered as
/// the file's `v` lines (unused lines included), so `motion.positions_close` addresses
/// them in file order whatever order the faces use them in.
fn load_obj(path: &Path) -> Result<Mesh> {
    let bytes = crate::input::read_bounded(path, crate::input::MAX_MESH_BYTES, "OBJ file")?;
    check_obj_faces(path, &bytes)?;
    let mut reader = BufReader::new(bytes.as_slice());
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ..Default::default()
    };
    let (models, _materials) =
        tobj::load_obj_buf(&mut reader, &opts, |_| Err(tobj::LoadError::OpenFileFailed))
            .map_err(|e| Error::format(path, format!("cannot parse OBJ: {e}")))?;
    let obj = obj_vertices(path, &bytes)?;
    if let Some(i) = obj.positions.iter().position(|v| !v.is_finite()) {
        return Err(Error::format(path, format!("vertex {i} is not finite")));
    }
    let mut mesh = Mesh {
        positions: obj.positions,
        triangles: Vec::new(),
    };
    let mut corner_ids = obj.corners.iter();
    for model in &models {
        let tm = &model.mesh;
        let fetch2 = |data: &[f32], idx: &[u32], k: usize| -> DVec2 {
            idx.get(k)
                .and_then(|&i| data.get(2 * i as usize..2 * i as usize + 2))
                .map_or(DVec2::ZERO, |s| {
                    DVec2::new(f64::from(s[0]), f64::from(s[1]))
                })
        };
        let fetch3 = |data: &[f32], idx: &[u32], k: usize| -> DVec3 {
            idx.get(k)
                .and_then(|&i| data.get(3 * i as usize..3 * i as usize + 3))
                .map_or(DVec3::ZERO, |s| {
                    DVec3::new(f64::from(s[0]), f64::from(s[1]), f64::from(s[2]))
                })
        };
        for ti in 0..tm.indices.len() / 3 {
            let mut corners = [Corner {
                position: 0,
                uv: DVec2::ZERO,
                normal: DVec3::ZERO,
            }; 3];
            for (k, c) in corners.iter_mut().enumerate() {
                let fk = 3 * ti + k;
                let loaded = fetch3(&tm.positions, &tm.indices, fk);
                // The corner's `v` line must hold the position tobj loaded for it.
                let v = corner_ids
                    .next()
                    .copied()
                    .filter(|&v| mesh.positions.get(v as usize) == Some(&loaded))
                    .ok_or_else(|| {
                        Error::format(path, format!("face {ti}: cannot match its `v` lines"))
                    })?;
                c.position = v;
                c.uv = fetch2(&tm.texcoords, &tm.texcoord_indices, fk);
                c.normal = fetch3(&tm.normals, &tm.normal_indices, fk).normalize_or_zero();
            }
            mesh.triangles.push(corners);
        }
    }
    if mesh.triangles.is_empty() {
        return Err(Error::format(path, "OBJ file has no faces"));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
    }

    #[test]
    fn sphere_area_converges_to_4_pi_r2() {
        let m = sphere(&SphereDesc {
            radius: 2.0,
            subdivisions: 64,
            wrinkle: 0.0,
            wrinkle_frequency: 8.0,
        });
        let exact = 4.0 * PI * 4.0;
        assert!((m.area() - exact).abs() / exact < 2e-3, "{}", m.area());
    }

    #[test]
    fn sphere_triangle_count_is_about_4n2() {
        let m = sphere(&SphereDesc {
            radius: 1.0,
            subdivisions: 128,
            wrinkle: 0.0,
            wrinkle_frequency: 8.0,
        });
        // Two pole bands have one triangle per cell, the others two.
        assert_eq!(m.triangles.len(), 2 * 256 * 126 + 2 * 256);
    }

    #[test]
    fn box_area_and_counts() {
        let m = cuboid(&BoxDesc {
            size: [1.0, 2.0, 3.0],
        });
        assert_eq!(m.positions.len(), 24);
        assert_eq!(m.triangles.len(), 12);
        assert!(close(m.area(), 2.0 * (2.0 + 3.0 + 6.0)));
    }

    #[test]
    fn fence_width_matches_parameters() {
        let m = fence(&FenceDesc {
            slats: 5,
            slat_width: 0.2,
            gap: 0.1,
            height: 1.0,
        });
        assert_eq!(m.triangles.len(), 10);
        assert!(close(m.area(), 5.0 * 0.2));
        let xs: Vec<f64> = m.positions.iter().map(|p| p.x).collect();
        let (lo, hi) = xs
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(close(lo, -0.7) && close(hi, 0.7));
    }

    #[test]
    fn capsule_area_is_cylinder_plus_sphere() {
        let m = cylinder(&CylinderDesc {
            radius: 0.5,
            height: 2.0,
            segments: 128,
            caps: Caps::Round,
        });
        let exact = 2.0 * PI * 0.5 * 2.0 + 4.0 * PI * 0.25;
        assert!(
            (m.area() - exact).abs() / exact < 5e-3,
            "{} vs {exact}",
            m.area()
        );
    }

    #[test]
    fn flat_grid_area_is_exact() {
        let m = grid(&GridDesc {
            size: [3.0, 2.0],
            divisions: [7, 5],
            wave_amplitude: 0.0,
            wave_frequency: 1.0,
        });
        assert_eq!(m.triangles.len(), 70);
        assert!(close(m.area(), 6.0));
    }
}
