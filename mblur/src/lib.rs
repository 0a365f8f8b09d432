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
//! use mblur::{Method, RenderOptions};
//! let mut scene = mblur_scene::Scene::builtin("static")?;
//! scene.set_size(Some(32), Some(18))?;
//! let options = RenderOptions { method: Method::Accum, ..Default::default() };
//! let out = mblur::render(&scene.prepare()?, &options, &mblur::NoProgress)?;
//! assert_eq!(out.image.pixels.len(), 32 * 18);
//! # Ok::<(), mblur_scene::Error>(())
//! ```

pub mod accum;
pub mod analytic;
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
pub mod method;
pub mod prepared;
pub mod prism;
pub mod progress;
pub mod shutter;
pub mod static_path;
pub mod stochastic;
mod surfaces;
pub mod texture;

pub use crate::accum::AccumOptions;
pub use crate::analytic::{AnalyticOptions, AnalyticRenderer};
pub use crate::auto::AutoChoice;
pub use crate::camera::{CameraFrame, Vertex2dh};
pub use crate::chain::{IntervalStats, Precision};
pub use crate::effects::{Effects, ObjectEffects, ObjectKind, Pipeline};
pub use crate::error::{Error, Result};
pub use crate::image::Image;
pub use crate::method::{AccumRenderer, Method, RenderOptions, Renderer, renderer_for};
pub use crate::prepared::{Material, ObjectInfo, PreparedScene, PreparedSplat, PreparedTriangle};
pub use crate::prism::PrismRenderer;
pub use crate::progress::{NoProgress, Progress};
pub use crate::stochastic::{StochasticOptions, StochasticRenderer, TraversalChoice};
pub use raster_hier::Footprint;

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
