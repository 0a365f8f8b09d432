//! The `prism` method (Rønnow, Assarsson, Sintorn and Fratarcangeli 2021): each moving
//! triangle's space-time prism (two cap triangles and three bilinear side patches in
//! (x, y, t)) is intersected with the time line of every pixel centre (bilinear-patch,
//! §3-4.1), giving coverage spans with depth and barycentrics at both ends (Fig. 6); these
//! go into exact unbounded per-pixel lists (interval-buffer, §4.1-4.2) and are resolved by
//! the time sweep (resolve, §4.3, Algorithm 1).
//!
//! The method is the interval chain ([`crate::chain`]) with the prism as the sweep of
//! moving triangles (its emission: `chain/emit/prism.rs`): static triangles take the static
//! rasteriser as one `[0, 1]` interval, moving triangles touching the near plane are time-
//! sliced through the static rasteriser, a static opaque scene takes the static path with no
//! interval storage, and the pipeline picks opaque or transparent resolve, intersection
//! handling and texturing. Unlike edge-eqn, the prism moves the *projected* vertices
//! linearly in screen space (and depth linearly with them), which is exact only when w is
//! constant over the shutter (orthographic camera, or motion parallel to the image plane);
//! under perspective with changing w it is Rønnow's approximation. Textured spans are cut
//! into pieces (at most 1/[`crate::chain::TEXTURE_PIECES`] of the shutter, as few as
//! [`crate::chain::TEXTURE_TOLERANCE`] allows) with UV and depth from the screen-space
//! barycentrics at each piece end (the paper keeps one UV segment per span). Splats are not
//! supported. Back faces of opaque closed meshes are culled conservatively
//! ([`crate::cull`]); arithmetic is f32 or f64 ([`Precision`]).

use crate::aa::Antialiasing;
use crate::chain::prim::Sweep;
use crate::chain::{ChainOptions, Description, IntervalStats, Precision, check_supported};
use crate::effects::Pipeline;
use crate::error::Result;
use crate::image::Image;
use crate::lighting::ShadingSamples;
use crate::prepared::PreparedScene;
use crate::progress::Progress;

/// Options of the prism method (exact interval lists only).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PrismOptions {
    /// Arithmetic of the chain (bilinear-patch, interval-buffer, resolve).
    pub precision: Precision,
    /// Memory budget of the exact interval lists in bytes, shared by the rows in flight (one
    /// per thread); a row that needs more fails with
    /// [`Error::MemoryBudget`](crate::Error::MemoryBudget). `None`: no limit.
    pub max_memory: Option<u64>,
    /// Sample positions per pixel and their filter ([`crate::aa`]); one, the pixel centre,
    /// by default.
    pub aa: Antialiasing,
    /// Where lit materials are shaded over each partition of an interval (ignored by
    /// unlit scenes).
    pub shading: ShadingSamples,
}

/// Renders with the prism method in f32.
pub fn render(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    progress: &dyn Progress,
) -> Result<Image> {
    render_stats(scene, pipeline, &PrismOptions::default(), progress).map(|(image, _)| image)
}

/// Renders with the prism method and says what the interval lists held (`None` for a
/// static opaque scene).
pub fn render_stats(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    options: &PrismOptions,
    progress: &dyn Progress,
) -> Result<(Image, Option<IntervalStats>)> {
    check_supported("prism", scene)?;
    crate::chain::render(
        scene,
        pipeline,
        ChainOptions {
            method: "prism",
            intervals: 0,
            sweep: Sweep::Prism,
            precision: options.precision,
            cull: true,
            max_memory: options.max_memory,
            shading: options.shading,
        },
        progress,
    )
}

impl PrismOptions {
    /// One line saying what the method will do for this pipeline.
    pub fn describe(&self, scene: &PreparedScene, p: &Pipeline) -> String {
        Description {
            method: "prism",
            via: "ray-prism intersection",
            lists: "exact interval lists",
            precision: self.precision,
            cull: true,
            shading: self.shading,
        }
        .line(scene, p)
    }
}
