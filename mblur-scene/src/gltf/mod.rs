//! glTF 2.0 import (`.gltf` with `data:` URIs or relative files, and `.glb`): meshes,
//! materials, the node hierarchy, cameras and animations (node TRS channels with LINEAR,
//! STEP and CUBICSPLINE interpolation, morph-target weights, skins), sampled over a shutter
//! window into the renderer's motion keys ([`GltfScene::prepare`]).
//!
//! What is not supported is an error naming it (sparse accessors, primitive modes other
//! than triangles, a second UV set, more than four joints per vertex, a texture sampler
//! that does not repeat, a required extension other than `KHR_materials_unlit` and
//! `KHR_lights_punctual`). Punctual lights become the scene's lights (directional and point;
//! spot cones and ranges are reported as warnings, [`GltfFrame::warnings`]); with lights,
//! every material but `KHR_materials_unlit` ones is Lambert with its base colour, without
//! them every material renders unlit. Metallic-roughness, normal, occlusion and emissive
//! textures are reported as warnings.
//!
//! Files are read with bounds: the glTF or GLB file and each buffer file at most 1 GiB,
//! accessors at most [`data::MAX_ACCESSOR_COUNT`] elements, each checked against its
//! buffer view before it is read; textures as [`crate::texture_file`].

pub mod anim;
mod build;
pub mod data;
pub mod mesh;

use std::path::{Path, PathBuf};

use glam::{DQuat, DVec3};

use mblur::PreparedScene;

use crate::error::{Error, Result};
use crate::mesh as mesh_desc;
use crate::segments::MotionOptions;

/// Extensions whose absence would change the image and which are read.
const SUPPORTED_REQUIRED: [&str; 2] = ["KHR_materials_unlit", "KHR_lights_punctual"];

/// A glTF document with its buffers decoded, ready to be prepared at any shutter window.
#[derive(Debug, Clone)]
pub struct GltfScene {
    doc: ::gltf::Document,
    buffers: data::Buffers,
    /// The file name used in messages.
    pub label: String,
    path: PathBuf,
    base: PathBuf,
    rig: anim::Rig,
    /// The nodes of the rendered glTF scene, hierarchy included (depth first).
    nodes: Vec<usize>,
}

/// What to render of a glTF file.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfOptions {
    /// The camera: a camera node's name or a camera's name (`None`: the first camera
    /// node of the scene).
    pub camera: Option<String>,
    /// The animation: its name or index (`None`: the first animation, if any).
    pub animation: Option<String>,
    /// Image width (`None`: from the height and the camera's aspect ratio).
    pub width: Option<u32>,
    /// Image height (`None`: 480, or from the width and the aspect ratio).
    pub height: Option<u32>,
    /// The shutter window in seconds of the animation's timeline, open < close.
    pub window: [f64; 2],
}

impl Default for GltfOptions {
    fn default() -> Self {
        GltfOptions {
            camera: None,
            animation: None,
            width: None,
            height: None,
            window: [0.0, 1.0 / 48.0],
        }
    }
}

/// A prepared glTF frame and what was ignored in it.
#[derive(Debug, Clone)]
pub struct GltfFrame {
    /// The renderer's input.
    pub scene: PreparedScene,
    /// Parts of the file without effect on the image (lights, lighting textures,
    /// optional extensions), one line each.
    pub warnings: Vec<String>,
}

/// True for a path ending in `.gltf` or `.glb` (any case).
pub fn is_gltf_path(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// The message of a failed glTF parse or validation.
fn gltf_error(e: ::gltf::Error) -> String {
    match e {
        ::gltf::Error::Validation(list) => {
            let items: Vec<String> = list
                .iter()
                .take(5)
                .map(|(path, err)| format!("{}: {err}", path.as_str()))
                .collect();
            format!("invalid glTF: {}", items.join("; "))
        }
        ::gltf::Error::Binary(b) => format!("invalid GLB: {b}"),
        ::gltf::Error::Deserialize(d) => format!("invalid glTF JSON: {d}"),
        other => format!("invalid glTF: {other}"),
    }
}

impl GltfScene {
    /// Reads, parses, validates a `.gltf` or `.glb` file and decodes its buffers.
    pub fn load(path: impl AsRef<Path>) -> Result<GltfScene> {
        let path = path.as_ref();
        let bytes = crate::input::read_bounded(path, crate::input::MAX_MESH_BYTES, "glTF file")?;
        let bad = |m: String| Error::format(path, m);
        let raw =
            ::gltf::Gltf::from_slice_without_validation(&bytes).map_err(|e| bad(gltf_error(e)))?;
        let ::gltf::Gltf { document, blob } = raw;
        let root = document.into_json();
        for ext in &root.extensions_required {
            if !SUPPORTED_REQUIRED.contains(&ext.as_str()) {
                return Err(bad(format!(
                    "requires extension {ext}, which is not supported (supported: {})",
                    SUPPORTED_REQUIRED.join(", ")
                )));
            }
        }
        let doc = ::gltf::Document::from_json(root).map_err(|e| bad(gltf_error(e)))?;
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let buffers = data::Buffers::load(&doc, blob, path, &base)?;
        let (rig, nodes) = hierarchy(&doc).map_err(bad)?;
        Ok(GltfScene {
            doc,
            buffers,
            label: path.display().to_string(),
            path: path.to_path_buf(),
            base,
            rig,
            nodes,
        })
    }

    /// The animation `name` (a name or an index; `None`: the first, or none when the
    /// file has no animation).
    fn animation(&self, name: Option<&str>) -> Result<anim::Animation> {
        let count = self.doc.animations().count();
        let index = match name {
            None if count == 0 => return Ok(anim::Animation::default()),
            None => 0,
            Some(n) => self
                .doc
                .animations()
                .position(|a| a.name() == Some(n))
                .or_else(|| n.parse::<usize>().ok().filter(|&i| i < count))
                .ok_or_else(|| {
                    let names: Vec<String> = self
                        .doc
                        .animations()
                        .enumerate()
                        .map(|(i, a)| a.name().map_or(i.to_string(), str::to_string))
                        .collect();
                    Error::format(
                        &self.path,
                        format!(
                            "has no animation `{n}` (animations: {})",
                            if names.is_empty() {
                                "none".into()
                            } else {
                                names.join(", ")
                            }
                        ),
                    )
                })?,
        };
        anim::Animation::read(&self.doc, &self.buffers, index)
            .map_err(|m| Error::format(&self.path, m))
    }

    /// The time (seconds) of the last key of animation `name` (see
    /// [`GltfOptions::animation`]); 0 without animation. Past it every channel holds its
    /// last key.
    pub fn duration(&self, name: Option<&str>) -> Result<f64> {
        Ok(self.animation(name)?.duration())
    }

    /// Every mesh instance of the rendered scene merged into one mesh, each placed by its
    /// node's rest world matrix (no animation, morph targets and skins at rest: base
    /// positions), normals turned by the inverse transpose: the geometry a JSON object with
    /// `"mesh": {"file": "model.glb"}` takes (its own material, transform and motion apply;
    /// the file's materials, cameras, lights and animations do not).
    pub fn rest_mesh(&self) -> Result<mesh_desc::Mesh> {
        let mut out = mesh_desc::Mesh::default();
        let nodes: Vec<::gltf::Node<'_>> = self.doc.nodes().collect();
        for &ni in &self.nodes {
            let Some(m) = nodes.get(ni).and_then(|n| n.mesh()) else {
                continue;
            };
            let world = self.rig.world(ni, 0.0, false);
            let normals = glam::DMat3::from_mat4(world).inverse().transpose();
            for (pi, p) in m.primitives().enumerate() {
                let at = format!("nodes[{ni}] mesh {} primitive {pi}", m.index());
                let prim = mesh::primitive(&self.buffers, &p, &at)
                    .map_err(|e| Error::format(&self.path, e))?;
                let offset = u32::try_from(out.positions.len())
                    .map_err(|_| Error::format(&self.path, "more than 2^32 vertices in all"))?;
                out.positions.extend(
                    prim.mesh
                        .positions
                        .iter()
                        .map(|q| world.transform_point3(*q)),
                );
                out.triangles.extend(prim.mesh.triangles.iter().map(|t| {
                    t.map(|c| mesh_desc::Corner {
                        position: c.position + offset,
                        uv: c.uv,
                        normal: (normals * c.normal).normalize_or_zero(),
                    })
                }));
            }
        }
        if out.triangles.is_empty() {
            return Err(Error::format(
                &self.path,
                "the scene has no triangles to use as a mesh",
            ));
        }
        Ok(out)
    }

    /// Prepares the frame whose shutter is open over `opts.window`, curved rigid motion
    /// cut into segments as `motion` says.
    pub fn prepare(&self, opts: &GltfOptions, motion: &MotionOptions) -> Result<GltfFrame> {
        let mut rig = self.rig.clone();
        rig.animation = self.animation(opts.animation.as_deref())?;
        build::prepare(self, &rig, opts, motion)
    }
}

/// Parents, rest transforms and rest weights of every node, and the nodes of the rendered
/// scene in depth-first order; a node with two parents or a cycle is an error.
fn hierarchy(doc: &::gltf::Document) -> std::result::Result<(anim::Rig, Vec<usize>), String> {
    let n = doc.nodes().count();
    let mut parents = vec![None; n];
    for node in doc.nodes() {
        for c in node.children() {
            let slot = parents
                .get_mut(c.index())
                .ok_or("node index out of range")?;
            if slot.is_some() {
                return Err(format!("nodes[{}] has two parents", c.index()));
            }
            *slot = Some(node.index());
        }
    }
    let rest = doc
        .nodes()
        .map(|node| {
            let (t, r, s) = node.transform().decomposed();
            let (t, s) = (
                DVec3::from_array(t.map(f64::from)),
                DVec3::from_array(s.map(f64::from)),
            );
            let r = DQuat::from_array(r.map(f64::from));
            (t, r, s)
        })
        .collect();
    let weights = doc
        .nodes()
        .map(|node| {
            let w = node
                .weights()
                .or_else(|| node.mesh().and_then(|m| m.weights()))
                .unwrap_or(&[]);
            w.iter().map(|x| f64::from(*x)).collect()
        })
        .collect();
    let scene = doc.default_scene().or_else(|| doc.scenes().next());
    let mut stack: Vec<usize> = match &scene {
        Some(s) => s.nodes().map(|n| n.index()).collect(),
        None => (0..n)
            .filter(|&i| parents.get(i).copied().flatten().is_none())
            .collect(),
    };
    stack.reverse();
    let all: Vec<::gltf::Node<'_>> = doc.nodes().collect();
    let mut order = Vec::new();
    let mut seen = vec![false; n];
    while let Some(i) = stack.pop() {
        match seen.get_mut(i) {
            Some(s) if !*s => *s = true,
            _ => {
                return Err(format!(
                    "nodes[{i}] is reached twice: the hierarchy has a cycle"
                ));
            }
        }
        order.push(i);
        if let Some(node) = all.get(i) {
            let mut kids: Vec<usize> = node.children().map(|c| c.index()).collect();
            kids.reverse();
            stack.extend(kids);
        }
    }
    let rig = anim::Rig {
        parents,
        rest,
        weights,
        animation: anim::Animation::default(),
    };
    Ok((rig, order))
}
