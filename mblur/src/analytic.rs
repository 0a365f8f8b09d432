//! The `analytic` method (Gribel, Doggett and Akenine-Möller 2010): per pixel centre, the
//! exact time spans during which each moving triangle covers it (edge-eqn, Eq. 3-9), stored
//! as intervals with linear depth (Eq. 16) in an interval buffer (exact unbounded lists, or
//! at most K per pixel with oracle compression, §5.2), then resolved by a sweep over time
//! against the shutter response (resolve, §5.1, Eq. 17).
//!
//! The method is the interval chain ([`crate::chain`]) with edge-eqn as the sweep of moving
//! triangles; what runs depends on the [`Pipeline`]:
//! - a fully static opaque scene allocates no interval storage: it is rendered by the
//!   static path exactly ([`crate::static_path::render`]);
//! - static triangles go through the static rasteriser and become one interval `[0, 1]` of
//!   constant depth; moving triangles in front of the near plane are swept exactly with
//!   edge-eqn inside the convex hull of their six projected vertices; moving triangles that
//!   touch the near plane are rasterised in [`crate::chain::NEAR_SLICES`] time slices
//!   ([`crate::chain::prim`]);
//! - flat materials carry an RGBA payload, textured materials UVs shaded through a tap
//!   filter ([`crate::chain::payload`]);
//! - opaque scenes use the opaque insertion (bounded buffers) and opaque resolve;
//!   intersection handling in the resolve only when the pipeline says objects may
//!   interpenetrate.
//!
//! Splats are not supported (use `ewa` or `accum`). Arithmetic of the chain is f32 or f64
//! ([`Precision`], `--precision`). Cost control, none of which changes what is covered:
//! time-dependent back-face culling of opaque closed meshes ([`crate::cull`], Rønnow 2021
//! §4.4 made exact with Munkberg and Akenine-Möller 2011), evaluation only inside each moving triangle's swept hull, and
//! rows emitted, buffered and resolved one at a time ([`crate::chain::row`]).

use crate::aa::Antialiasing;
use crate::chain::prim::Sweep;
use crate::chain::{ChainOptions, Description, check_supported};
pub use crate::chain::{IntervalStats, MAX_INTERVALS, Precision};
use crate::effects::Pipeline;
use crate::error::{Error, Result};
use crate::image::Image;
use crate::lighting::ShadingSamples;
use crate::prepared::PreparedScene;
use crate::progress::Progress;

/// Options of the analytic method.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AnalyticOptions {
    /// Intervals per pixel: 0 = exact unbounded lists (Rønnow 2021 §4.1-4.2), K > 0 = at
    /// most K per pixel with the paper's oracle compression (Gribel 2010 §5.2).
    pub intervals: u32,
    /// Arithmetic of the interval chain.
    pub precision: Precision,
    /// Keep the back-facing triangles of opaque closed meshes (turns off the
    /// time-dependent culling of [`crate::cull`]; for checking it).
    pub keep_backfaces: bool,
    /// Memory budget of the exact interval lists in bytes, shared by the rows in flight (one
    /// per thread); a row that needs more fails with [`Error::MemoryBudget`] as soon as it
    /// passes its share. `None`: no limit. Bounded lists (`intervals` K > 0) hold K per
    /// pixel and ignore it.
    pub max_memory: Option<u64>,
    /// Sample positions per pixel and their filter ([`crate::aa`]); one, the pixel centre,
    /// by default.
    pub aa: Antialiasing,
    /// Where lit materials are shaded over each partition of an interval (ignored by
    /// unlit scenes).
    pub shading: ShadingSamples,
}

/// Renders with the analytic method.
pub fn render(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    options: &AnalyticOptions,
    progress: &dyn Progress,
) -> Result<Image> {
    render_stats(scene, pipeline, options, progress).map(|(image, _)| image)
}

/// Renders with the analytic method and says what the interval buffers held (`None` for a
/// static opaque scene, which takes the static path).
pub fn render_stats(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    options: &AnalyticOptions,
    progress: &dyn Progress,
) -> Result<(Image, Option<IntervalStats>)> {
    check_supported("analytic", scene)?;
    options.validate()?;
    crate::chain::render(
        scene,
        pipeline,
        ChainOptions {
            method: "analytic",
            intervals: options.intervals,
            sweep: Sweep::EdgeEqn,
            precision: options.precision,
            cull: !options.keep_backfaces,
            max_memory: options.max_memory,
            shading: options.shading,
        },
        progress,
    )
}

impl AnalyticOptions {
    /// Checks the options: `intervals` at most [`MAX_INTERVALS`].
    pub fn validate(&self) -> Result<()> {
        self.aa.validate()?;
        self.shading.validate("analytic")?;
        if self.intervals > MAX_INTERVALS {
            return Err(Error::Setting {
                method: "analytic",
                setting: "intervals",
                message: format!("must be at most {MAX_INTERVALS}, got {}", self.intervals),
            });
        }
        Ok(())
    }

    /// One line saying what the method will do for this pipeline.
    pub fn describe(&self, scene: &PreparedScene, p: &Pipeline) -> String {
        let lists = if self.intervals == 0 {
            "exact interval lists".to_string()
        } else {
            format!("at most {} intervals per pixel", self.intervals)
        };
        Description {
            method: "analytic",
            via: "edge-eqn",
            lists: &lists,
            precision: self.precision,
            cull: !self.keep_backfaces,
            shading: self.shading,
        }
        .line(scene, p)
    }
}
