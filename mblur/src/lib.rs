//! # mblur
//!
//! The motion-blur renderer: reads a JSON scene ([`Scene`], format in the workspace's `docs/SCENE_FORMAT.md`),
//! prepares world-space triangles and their 2DH vertices at shutter open and close
//! ([`PreparedScene`], Gribel 2010 Eq. 2: vertices move linearly in homogeneous clip space),
//! analyses which effects the scene calls for ([`Effects`], [`Pipeline`]: motion,
//! transparency, textures, possible interpenetration, splats) and renders it with a
//! [`Method`], writing PNG (sRGB 8-bit), EXR or PFM (linear float) atomically ([`Image`]).
//!
//! Phase 1 provides the scene format, validation, preparation, analysis, the static
//! rasteriser and the `accum` method (N static renders averaged with the shutter response:
//! the ground truth). The analytic (edge-eqn, interval-buffer, resolve), prism
//! (bilinear-patch), stochastic (raster-hier, tmsnet) and EWA (ewa-splat) methods plug in as
//! [`Renderer`] implementations consuming the same [`PreparedScene`]; a method asked for a
//! scene feature it does not support returns an error naming it, never a silent fallback.
//!
//! Entry points: [`Scene::load`] / [`Scene::builtin`], [`Scene::prepare`], [`render`]
//! (`--method auto` resolves with [`auto::choose`]), [`Image::save`], and
//! [`inspect::pixel_intervals`] (the temporal pixel visualiser, `mblur inspect`).
//! [`compare::compare`] (the `mblur compare` command) renders a reference and a ladder of
//! settings per method and reports time, peak heap and error ([`metrics`]) as a table, CSV,
//! Markdown and an error-vs-time plot.
//!
//! ```
//! use mblur::{Method, RenderOptions, Scene};
//! let mut scene = Scene::builtin("static")?;
//! scene.set_size(Some(32), Some(18))?;
//! let out = mblur::render(&scene.prepare()?, &RenderOptions { method: Method::Accum, ..Default::default() }, &mblur::NoProgress)?;
//! assert_eq!(out.image.pixels.len(), 32 * 18);
//! # Ok::<(), mblur::Error>(())
//! ```

pub mod accum;
pub mod analytic;
pub mod atomic;
pub mod auto;
pub mod builtin;
pub mod camera;
pub mod compare;
pub mod cull;
pub mod effects;
pub mod error;
pub mod ewa;
pub mod hull;
pub mod image;
pub mod inspect;
pub mod mesh;
pub mod method;
pub mod metrics;
pub mod plot;
pub mod ply;
pub mod prepare;
pub mod prism;
pub mod progress;
pub mod raster;
pub mod report;
pub mod scene;
pub mod shutter;
pub mod stochastic;
mod surfaces;
pub mod texture;
pub mod validate;

use std::path::{Path, PathBuf};

pub use crate::accum::AccumOptions;
pub use crate::analytic::{AnalyticOptions, AnalyticRenderer, IntervalStats, Precision};
pub use crate::auto::AutoChoice;
pub use crate::camera::{CameraFrame, Vertex2dh};
pub use crate::effects::{Effects, ObjectEffects, ObjectKind, Pipeline};
pub use crate::error::{Error, Result};
pub use crate::image::{Format, Image};
pub use crate::method::{AccumRenderer, Method, RenderOptions, Renderer, renderer_for};
pub use crate::prepare::{Material, ObjectInfo, PreparedScene, PreparedSplat, PreparedTriangle};
pub use crate::prism::PrismRenderer;
pub use crate::progress::{NoProgress, Progress};
pub use crate::scene::SceneDesc;
pub use crate::stochastic::{StochasticOptions, StochasticRenderer, TraversalChoice};
pub use raster_hier::Footprint;

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
        let text = std::fs::read_to_string(path).map_err(|e| Error::read(path, e))?;
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
        validate::validate(&desc, label)?;
        Ok(Scene {
            desc,
            label: label.to_string(),
            base_dir: base_dir.into(),
        })
    }

    /// Validates a scene built in code (relative paths resolve against the current folder).
    pub fn from_desc(desc: SceneDesc) -> Result<Scene> {
        validate::validate(&desc, "<scene>")?;
        Ok(Scene {
            desc,
            label: "<scene>".into(),
            base_dir: PathBuf::new(),
        })
    }

    /// A built-in scene by name (see [`builtin::SCENES`]).
    pub fn builtin(name: &str) -> Result<Scene> {
        let json = builtin::json(name).ok_or_else(|| Error::UnknownScene(name.to_string()))?;
        Scene::from_json(json, &format!("<built-in {name}>"), PathBuf::new())
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
        validate::validate(&desc, &self.label)?;
        self.desc = desc;
        Ok(())
    }

    /// Loads meshes and textures and builds the world-space triangles and 2DH vertices.
    pub fn prepare(&self) -> Result<PreparedScene> {
        prepare::prepare(&self.desc, &self.label, &self.base_dir)
    }
}

/// A finished render.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// The linear RGB image.
    pub image: Image,
    /// The scene analysis.
    pub effects: Effects,
    /// The method that ran.
    pub method: &'static str,
    /// What the method did (e.g. `accum: 64 sub-frames`).
    pub description: String,
    /// A note on method selection (e.g. how `auto` resolved), if any.
    pub note: Option<String>,
    /// What the render cost, if the method reports it (e.g. the stochastic method's
    /// raster-hier counters).
    pub statistics: Option<String>,
}

/// Analyses and renders a prepared scene with the chosen method (on `options.threads`
/// threads when given).
pub fn render(
    scene: &PreparedScene,
    options: &RenderOptions,
    progress: &dyn Progress,
) -> Result<Rendered> {
    let effects = Effects::analyse(scene);
    let pipeline = effects.pipeline();
    let (renderer, note) = if options.method == Method::Auto {
        let choice = auto::choose(scene, &pipeline);
        let chosen = RenderOptions {
            method: choice.method,
            ..*options
        };
        (renderer_for(&chosen)?.0, Some(choice.note))
    } else {
        renderer_for(options)?
    };
    let description = renderer.describe(scene, &pipeline);
    let run = || renderer.render(scene, &pipeline, progress);
    let image = match options.threads {
        None => run()?,
        Some(0) => {
            return Err(Error::Option {
                option: "--threads".into(),
                message: "must be at least 1".into(),
            });
        }
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| Error::Option {
                option: "--threads".into(),
                message: e.to_string(),
            })?
            .install(run)?,
    };
    Ok(Rendered {
        image,
        effects,
        method: renderer.name(),
        description,
        note,
        statistics: renderer.statistics(),
    })
}
