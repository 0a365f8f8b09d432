//! # mblur-scene
//!
//! Scene files for the [`mblur`] renderer: the JSON format ([`SceneDesc`], described in the
//! workspace's `docs/SCENE_FORMAT.md`), its validation with errors that name the file and
//! field, the built-in scenes, glTF 2.0 import with its animations ([`gltf`]), OBJ/PLY
//! meshes and PNG textures, and image files (PNG, EXR,
//! PFM, written atomically). [`Scene::prepare`] produces the renderer's input contract,
//! [`mblur::PreparedScene`].
//!
//! ```
//! use mblur_scene::Scene;
//! let mut scene = Scene::builtin("static")?;
//! scene.set_size(Some(32), Some(18))?;
//! let prepared = scene.prepare()?;
//! assert_eq!((prepared.width, prepared.height), (32, 18));
//! # Ok::<(), mblur_scene::Error>(())
//! ```

pub mod atomic;
pub mod builtin;
pub mod desc;
pub mod error;
pub mod gltf;
pub mod image_io;
pub mod input;
pub mod layered_exr;
mod lights;
pub mod mesh;
pub mod ply;
pub mod prepare;
pub mod segments;
mod splat_motion;
pub mod texture_file;
pub mod validate;
pub(crate) mod vertex_motion;

use std::path::{Path, PathBuf};

use mblur::PreparedScene;

pub use crate::desc::SceneDesc;
pub use crate::error::{Error, Result};
pub use crate::image_io::Format;

/// A parsed and validated scene, with the name used in messages and the folder relative
/// paths resolve against.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The scene description.
    pub desc: SceneDesc,
    /// The file name (or `<built-in NAME>`, `<scene>`) used in error messages.
    pub label: String,
    /// Folder that relative mesh, texture and PLY paths resolve against.
    pub base_dir: PathBuf,
}

fn json_error(label: &str, e: serde_path_to_error::Error<serde_json::Error>) -> Error {
    let path = e.path().to_string();
    let inner = e.into_inner();
    let (line, column) = (inner.line(), inner.column());
    let mut message = inner.to_string();
    let suffix = format!(" at line {line} column {column}");
    if let Some(stripped) = message.strip_suffix(&suffix) {
        message = stripped.to_string();
    }
    let at = if path.is_empty() || path == "." {
        String::new()
    } else {
        format!("{path}: ")
    };
    Error::Json {
        file: label.to_string(),
        line,
        column,
        at,
        message,
    }
}

impl Scene {
    /// Reads, parses and validates a scene file.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene> {
        let path = path.as_ref();
        let bytes = input::read_bounded(path, input::MAX_SCENE_BYTES, "scene file")?;
        let text = String::from_utf8(bytes)
            .map_err(|e| Error::format(path, format!("is not UTF-8 text: {e}")))?;
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Scene::from_json(&text, &path.display().to_string(), base)
    }

    /// Parses and validates scene JSON; `label` names it in errors, relative paths resolve
    /// against `base_dir`.
    pub fn from_json(json: &str, label: &str, base_dir: impl Into<PathBuf>) -> Result<Scene> {
        let mut de = serde_json::Deserializer::from_str(json);
        let desc: SceneDesc =
            serde_path_to_error::deserialize(&mut de).map_err(|e| json_error(label, e))?;
        de.end().map_err(|inner| Error::Json {
            file: label.to_string(),
            line: inner.line(),
            column: inner.column(),
            at: String::new(),
            message: "unexpected characters after the scene object".into(),
        })?;
        crate::validate::validate(&desc, label)?;
        Ok(Scene {
            desc,
            label: label.to_string(),
            base_dir: base_dir.into(),
        })
    }

    /// Validates a scene built in code (relative paths resolve against the current folder).
    pub fn from_desc(desc: SceneDesc) -> Result<Scene> {
        crate::validate::validate(&desc, "<scene>")?;
        Ok(Scene {
            desc,
            label: "<scene>".into(),
            base_dir: PathBuf::new(),
        })
    }

    /// A built-in scene by name (see [`builtin::SCENES`]).
    /// A name with [`builtin::UNLIT_SUFFIX`] gives the lit scene without its lights and
    /// with every material unlit.
    pub fn builtin(name: &str) -> Result<Scene> {
        let (json, unlit) =
            builtin::lookup(name).ok_or_else(|| Error::UnknownScene(name.to_string()))?;
        let mut scene = Scene::from_json(json, &format!("<built-in {name}>"), PathBuf::new())?;
        if unlit {
            scene.desc.lights.clear();
            for o in &mut scene.desc.objects {
                o.material.shading = desc::ShadingDesc::Unlit;
            }
        }
        Ok(scene)
    }

    /// Overrides the image size (re-validated against the limits).
    pub fn set_size(&mut self, width: Option<u32>, height: Option<u32>) -> Result<()> {
        let mut desc = self.desc.clone();
        if let Some(w) = width {
            desc.camera.width = w;
        }
        if let Some(h) = height {
            desc.camera.height = h;
        }
        crate::validate::validate(&desc, &self.label)?;
        self.desc = desc;
        Ok(())
    }

    /// Loads meshes and textures and builds the world-space triangles and 2DH vertices,
    /// curved motion cut into segments automatically ([`segments::MotionOptions`]).
    pub fn prepare(&self) -> Result<PreparedScene> {
        crate::prepare::prepare(&self.desc, &self.label, &self.base_dir)
    }

    /// As [`Scene::prepare`], with the segments of curved motion chosen by `motion`.
    pub fn prepare_with(&self, motion: &segments::MotionOptions) -> Result<PreparedScene> {
        crate::prepare::prepare_with(&self.desc, &self.label, &self.base_dir, motion)
    }
}
