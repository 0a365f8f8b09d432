//! The interval chain: per pixel centre, the time intervals during which each triangle
//! covers it, with linear depth (Gribel 2010, Eq. 16) and a payload, buffered per pixel
//! and resolved by a sweep over time against the shutter response (Gribel 2010 §5.1,
//! Eq. 17; Rønnow 2021 §4.3, Algorithm 1).
//!
//! - [`prim`]: what each triangle becomes — a static rasteriser primitive covering `[0, 1]`,
//!   a moving triangle swept by edge-eqn (Gribel 2010) or by a bilinear-patch prism (Rønnow
//!   2021), or time slices for near-plane crossings; opaque closed meshes lose the times
//!   their triangles face away ([`crate::cull`]).
//! - [`emit`](mod@emit): the intervals one primitive leaves in one row, per primitive kind.
//! - [`payload`]: flat colours or texture coordinates, and their shaders.
//! - [`pieces`]: where textured spans are cut.
//! - [`row`]: the row pipeline — emit, buffer (exact lists, or K per pixel with the paper's
//!   oracle compression, Gribel 2010 §5.2), resolve — in parallel over rows.
//!
//! Its users: the `analytic` and `prism` methods (`render`), the temporal pixel
//! visualiser ([`crate::inspect`], `pixel_intervals`) and the `ewa` method's surface
//! intervals for the triangles of a mixed scene (`surfaces.rs`). Arithmetic of the whole
//! chain (edge-eqn or bilinear-patch, interval-buffer, resolve) is f32 or f64
//! ([`Precision`]); scene preparation is f64 either way.

pub mod emit;
mod end_samples;
pub mod lit;
pub mod payload;
pub mod pieces;
pub mod prim;
pub mod row;

use std::fmt;
use std::str::FromStr;

use interval_buffer::Interval;
use num_traits::Float;
use resolve::Shader;

use self::emit::{RowSpan, emit};
pub use self::lit::{ADAPTIVE_DEPTH, Lit};
use self::payload::{MakePayload, WithPayloads, with_payloads};
pub use self::payload::{TAPS_PER_TEXEL, TEXTURE_TAPS};
pub use self::pieces::{TEXTURE_PIECES, TEXTURE_TOLERANCE};
pub use self::prim::{NEAR_SLICES, ORIGIN_BLOCK};
use self::prim::{Primitives, Sweep};
use self::row::{Buffering, Resolver, RowScratch, Rows};
use crate::corners::in_front;
use crate::effects::Pipeline;
use crate::error::{Error, Result};
use crate::image::Image;
use crate::lighting::ShadingSamples;
use crate::prepared::PreparedScene;
use crate::progress::Progress;

/// Rows per bin when distributing primitives over the image.
const BAND_ROWS: u32 = 8;

/// Largest accepted number of intervals per pixel of the bounded buffer (`--intervals`).
pub const MAX_INTERVALS: u32 = 1024;

/// Floating-point type of the interval chain (edge-eqn sweep, interval buffer, resolve).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Precision {
    /// Single precision (the default; what the papers' GPU implementations use).
    #[default]
    F32,
    /// Double precision.
    F64,
}

impl Precision {
    /// Both precisions.
    pub const ALL: [Precision; 2] = [Precision::F32, Precision::F64];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}

impl fmt::Display for Precision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Precision {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        crate::names::parse_by_name(s, &Precision::ALL, Precision::name, "precision")
    }
}

/// The float types the interval chain runs in.
pub(crate) trait Real: Float + Default + Send + Sync + fmt::Debug + 'static {}

impl Real for f32 {}
impl Real for f64 {}

/// `v` in `F` (f64 -> f32 rounds; never fails for the float types used here).
#[inline]
pub(crate) fn cf<F: Real>(v: f64) -> F {
    F::from(v).unwrap_or_else(F::zero)
}

/// What the last render stored, per pixel (printed by `mblur render`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IntervalStats {
    /// Intervals emitted into the buffers (before any compression).
    pub total: u64,
    /// Largest number emitted into one pixel.
    pub max: u32,
    /// Pixels that received at least one interval.
    pub covered: u64,
    /// Pixels in the image.
    pub pixels: u64,
    /// Triangles removed by back-face culling (turned away during their whole span).
    pub culled: u64,
    /// Triangles whose intervals back-face culling clips to the times they may face the
    /// eye.
    pub clipped: u64,
}

impl IntervalStats {
    /// Mean intervals per covered pixel.
    pub fn mean(&self) -> f64 {
        if self.covered == 0 {
            0.0
        } else {
            self.total as f64 / self.covered as f64
        }
    }
}

impl fmt::Display for IntervalStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "intervals: {} total, {:.1} mean / {} max per covered pixel ({} of {} pixels covered); {} back-facing triangles culled, {} clipped to the times they face the eye",
            self.total,
            self.mean(),
            self.max,
            self.covered,
            self.pixels,
            self.culled,
            self.clipped
        )
    }
}

/// How [`render`] runs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ChainOptions {
    /// The method, for descriptions and errors.
    pub method: &'static str,
    /// 0 = exact lists, K > 0 = bounded buffer.
    pub intervals: u32,
    /// The exact sweep of moving triangles.
    pub sweep: Sweep,
    /// Arithmetic of the chain.
    pub precision: Precision,
    /// Time-dependent back-face culling of opaque closed meshes ([`crate::cull`]).
    pub cull: bool,
    /// Memory budget of the exact interval lists in bytes, shared by the rows in flight
    /// (`None`: no limit).
    pub max_memory: Option<u64>,
    /// Where lit materials are shaded over each partition.
    pub shading: ShadingSamples,
}

/// Checks the scene has no feature the interval methods lack (splats).
pub(crate) fn check_supported(method: &str, scene: &PreparedScene) -> Result<()> {
    if !scene.splats.is_empty() {
        return Err(Error::MethodNotApplicable {
            method: method.into(),
            reason: "the scene has splats (use --method ewa or accum)".into(),
        });
    }
    Ok(())
}

/// The chain as a method runs it: primitives -> interval buffer (exact when `intervals ==
/// 0`) -> resolve, row by row; a fully static opaque scene takes the static path with no
/// interval storage (and no statistics).
pub(crate) fn render(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    o: ChainOptions,
    progress: &dyn Progress,
) -> Result<(Image, Option<IntervalStats>)> {
    if !pipeline.interval_storage {
        // A fully static opaque scene: exactly the static path, no interval storage.
        return Ok((crate::static_path::render(scene, progress), None));
    }
    progress.start(u64::from(scene.height), "rows");
    let job = RenderJob {
        scene,
        pipeline,
        o,
        progress,
    };
    let (image, stats) = match o.precision {
        Precision::F32 => with_payloads::<f32, _>(scene, pipeline.textures, o.shading, job),
        Precision::F64 => with_payloads::<f64, _>(scene, pipeline.textures, o.shading, job),
    }?;
    progress.finish();
    Ok((image, Some(stats)))
}

/// [`render`] in one float type, once the payloads are chosen.
struct RenderJob<'a> {
    scene: &'a PreparedScene,
    pipeline: &'a Pipeline,
    o: ChainOptions,
    progress: &'a dyn Progress,
}

impl<F: Real> WithPayloads<F> for RenderJob<'_> {
    type Output = Result<(Image, IntervalStats)>;

    fn run<M: MakePayload<F>, S: Shader<F, M::P> + Sync>(self, mk: &M, shader: &S) -> Self::Output {
        let RenderJob {
            scene,
            pipeline,
            o,
            progress,
        } = self;
        let built = Primitives::<F>::build(scene, o.sweep, o.cull);
        let bins = built.bins(scene.height, BAND_ROWS);
        let settings = row::settings::<F>(scene, pipeline, o.method)?;
        let rows = Rows {
            scene,
            prims: &built.prims,
            bins: &bins,
            mk,
            resolver: Resolver {
                shader,
                settings: &settings,
                method: o.method,
            },
            buffering: Buffering {
                intervals: o.intervals,
                opaque: !pipeline.transparency,
                row_limit: row_limit(o.max_memory, RowScratch::<F, M::P>::BYTES_PER_INTERVAL),
            },
        };
        let (image, stats) = rows.render(progress)?;
        Ok((
            image,
            IntervalStats {
                culled: built.culled,
                clipped: built.clipped,
                ..stats
            },
        ))
    }
}

/// Most intervals one row's exact lists may hold when `max_memory` bytes are shared by the
/// rows in flight (one per thread of the current pool) at `bytes_per_interval` each.
fn row_limit(max_memory: Option<u64>, bytes_per_interval: usize) -> u64 {
    let Some(budget) = max_memory else {
        return u64::MAX;
    };
    let threads = rayon::current_num_threads().max(1) as u64;
    budget / threads / (bytes_per_interval.max(1) as u64)
}

/// Calls `f(triangle, interval)` for every interval `sweep` leaves in pixel (x, y), in f32
/// and in the order the interval buffers receive them: the same primitives (back-face
/// culling included) and emission as a full render.
pub(crate) fn pixel_intervals<M: MakePayload<f32>>(
    scene: &PreparedScene,
    sweep: Sweep,
    mk: &M,
    (x, y): (u32, u32),
    mut f: impl FnMut(u32, Interval<f32, M::P>),
) -> Result<()> {
    for prim in &Primitives::<f32>::build(scene, sweep, true).prims {
        let tri = prim.triangle();
        emit(scene, prim, RowSpan::pixel(x, y), mk, |_, iv| {
            f(tri, iv);
            Ok(())
        })?;
    }
    Ok(())
}

/// How the chain routes a scene's triangles (for the methods' descriptions).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Routes {
    /// Moving triangles (swept, or sliced when they touch the near plane).
    pub moving: usize,
    /// Moving triangles touching or crossing the near plane, rasterised in
    /// [`NEAR_SLICES`] time slices.
    pub near: usize,
    /// Static triangles, through the static rasteriser as one `[0, 1]` interval.
    pub fixed: usize,
}

impl Routes {
    /// The routes of `scene`'s triangles.
    pub(crate) fn of(scene: &PreparedScene) -> Self {
        let moving = scene.triangles.iter().filter(|t| t.is_moving()).count();
        let near = scene
            .triangles
            .iter()
            .filter(|t| t.is_moving() && !in_front(t, scene.near))
            .count();
        Routes {
            moving,
            near,
            fixed: scene.triangles.len() - moving,
        }
    }

    /// `"N moving triangles via {via} (M near-plane crossings in 64 slices), K static via
    /// the static rasteriser"`.
    pub(crate) fn summary(&self, via: &str) -> String {
        format!(
            "{} moving triangle{} via {via} ({} near-plane crossing{} in {NEAR_SLICES} slices), {} static via the static rasteriser",
            self.moving,
            plural(self.moving),
            self.near,
            plural(self.near),
            self.fixed,
        )
    }
}

/// `"s"` unless `n` is one.
pub(crate) fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// What a method's `describe` line says of the chain.
pub(crate) struct Description<'a> {
    /// The method.
    pub method: &'a str,
    /// What moving triangles in front of the near plane go through.
    pub via: &'a str,
    /// The buffer.
    pub lists: &'a str,
    /// Arithmetic of the chain.
    pub precision: Precision,
    /// Time-dependent back-face culling.
    pub cull: bool,
    /// Where lit materials are shaded.
    pub shading: ShadingSamples,
}

impl Description<'_> {
    /// The line for `scene` and pipeline `p`: what goes through the motion path, the
    /// culling, the near-plane slicing, the static path, the buffer, the resolve the
    /// pipeline enables and the arithmetic.
    pub(crate) fn line(&self, scene: &PreparedScene, p: &Pipeline) -> String {
        let method = self.method;
        if !p.interval_storage {
            return format!("{method}: static opaque scene, static path (no interval storage)");
        }
        let r = Routes::of(scene);
        // The counts come with the render's report (`RenderStats`): finding them here would
        // solve every triangle's facing windows a second time.
        let culled = if self.cull {
            "time-dependent back-face culling of opaque closed meshes".to_string()
        } else {
            "no back-face culling".to_string()
        };
        format!(
            "{method}: {}; {culled}; {}; {} resolve{}{}{}; {} arithmetic",
            r.summary(self.via),
            self.lists,
            if p.transparency {
                "transparent"
            } else {
                "opaque"
            },
            if p.intersection {
                ", intersection handling"
            } else {
                ""
            },
            if p.textures { ", textured" } else { "" },
            if p.lighting {
                format!(", lit (shading samples: {})", self.shading)
            } else {
                String::new()
            },
            self.precision,
        )
    }
}
