//! # mblur
//!
//! The motion-blur renderer library. Its input contract is a [`PreparedScene`]: world-space
//! triangles and splats with their 2DH vertices at shutter open and close (Gribel 2010,
//! Eq. 2: vertices move linearly in homogeneous clip space), materials, textures, the
//! camera and the shutter response (`mblur-scene` builds one from a scene file). [`render`]
//! analyses which effects the scene calls for ([`Effects`], [`Pipeline`]: motion,
//! transparency, textures, possible interpenetration, splats) and renders it with a
//! [`Method`] into a linear RGB [`Image`]; a method asked for a scene feature it does not
//! support returns an error naming it, never a silent fallback.
//!
//! ```
//! use mblur::{AccumOptions, MethodOptions};
//! let mut scene = mblur_scene::Scene::builtin("static")?;
//! scene.set_size(Some(32), Some(18))?;
//! let options = MethodOptions::Accum(AccumOptions { times: Some(4), jitter: None, ..Default::default() });
//! let out = mblur::render(&scene.prepare()?, &options, &mblur::NoProgress)?;
//! assert_eq!(out.image.pixels.len(), 32 * 18);
//! # Ok::<(), mblur_scene::Error>(())
//! ```

pub mod aa;
pub mod accum;
pub mod analytic;
pub mod aov;
pub mod auto;
mod bands;
pub mod camera;
pub mod chain;
mod corners;
pub mod cull;
pub mod effects;
pub mod error;
pub mod ewa;
pub mod image;
pub mod inspect;
pub mod lighting;
pub mod lights;
pub mod method;
pub mod motion;
pub mod names;
pub mod prepared;
pub mod prism;
pub mod progress;
pub mod shutter;
pub mod static_path;
pub mod stochastic;
pub mod surface_track;
mod surfaces;
pub mod texture;

pub use crate::accum::AccumOptions;
pub use crate::analytic::AnalyticOptions;
pub use crate::aov::{AovOptions, AovSet, Aovs, render_aovs};
pub use crate::auto::AutoChoice;
pub use crate::camera::{CameraFrame, Vertex2dh};
pub use crate::chain::{IntervalStats, Precision};
pub use crate::effects::{Effects, ObjectEffects, ObjectKind, Pipeline};
pub use crate::error::{Error, Result};
pub use crate::ewa::EwaOptions;
pub use crate::image::Image;
pub use crate::lighting::{Light, LightKey, ShadingModel, ShadingSamples};
pub use crate::method::{AutoOptions, Method, MethodOptions, Stats};
pub use crate::prepared::{
    Material, ObjectInfo, PreparedScene, PreparedSplat, PreparedTriangle, SplatLocal,
};
pub use crate::prism::PrismOptions;
pub use crate::progress::{NoProgress, Progress};
pub use crate::stochastic::{StochasticOptions, TraversalChoice};
pub use raster_hier::Footprint;

/// A finished render.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// The linear RGB image.
    pub image: Image,
    /// The scene analysis.
    pub effects: Effects,
    /// The method that ran (`auto` resolved to the one it picked).
    pub method: Method,
    /// What the method did (e.g. `accum: 64 sub-frames`).
    pub description: String,
    /// A note on method selection (how `auto` resolved), if any.
    pub note: Option<String>,
    /// What the render cost, as the method counts it.
    pub stats: Stats,
}

/// Analyses and renders a prepared scene with a method and its options (`auto` picks the
/// method per scene, [`auto::choose`]). Runs on rayon's current thread pool: install one
/// (`rayon::ThreadPool::install`) to choose the thread count.
pub fn render(
    scene: &PreparedScene,
    options: &MethodOptions,
    progress: &dyn Progress,
) -> Result<Rendered> {
    options.validate()?;
    let effects = Effects::analyse(scene);
    let pipeline = effects.pipeline();
    let (chosen, note) = options.resolve(scene, &pipeline);
    let description = chosen.describe(scene, &pipeline);
    let (image, stats) = method::run(scene, &pipeline, &chosen, progress)?;
    Ok(Rendered {
        image,
        effects,
        method: chosen.method(),
        description,
        note,
        stats,
    })
}
