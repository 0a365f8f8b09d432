//! Rendering methods and the [`Renderer`] trait each one implements.
//!
//! Every method consumes the same [`PreparedScene`]: per triangle the 2DH vertices and view
//! depths at shutter open and close ([`crate::PreparedTriangle::open`] / `close`, moving
//! linearly in between, Gribel 2010 Eq. 2), the UVs and the material
//! ([`PreparedScene::shade`] gives premultiplied RGBA), plus the splats; and the same
//! [`Pipeline`] saying which stages the scene needs. Phase 1 wires `accum` (the ground
//! truth); `analytic` (edge-eqn -> interval-buffer -> resolve), `prism` (bilinear-patch ->
//! exact lists -> resolve), `stochastic` (raster-hier + tmsnet) and `ewa` (ewa-splat) plug in
//! as further `Renderer` implementations selected in [`renderer_for`].

use std::fmt;
use std::str::FromStr;

use crate::accum::{self, AccumOptions};
use crate::effects::Pipeline;
use crate::error::Result;
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::progress::Progress;

/// A rendering method, as chosen with `--method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Method {
    /// Pick the method for the scene ([`crate::auto::choose`]): `ewa` for scenes with
    /// splats (with or without triangles; `accum` when ewa refuses the scene), else
    /// `analytic` (which takes the static path, without interval storage, for a fully
    /// static opaque scene).
    #[default]
    Auto,
    /// N static renders averaged: the ground truth.
    Accum,
    /// Analytic coverage intervals: edge-eqn -> interval-buffer -> resolve (Gribel 2010).
    Analytic,
    /// Ray / bilinear-patch prism intersections -> exact lists -> resolve.
    Prism,
    /// Hierarchical stochastic rasterisation with (t, m, s)-net samples.
    Stochastic,
    /// EWA splatting of point clouds (Heinzle), with any triangles of the scene composited
    /// in its A-buffer as surface intervals from the analytic chain.
    Ewa,
}

impl Method {
    /// All methods, in the order `--help` lists them.
    pub const ALL: [Method; 6] = [
        Method::Auto,
        Method::Accum,
        Method::Analytic,
        Method::Prism,
        Method::Stochastic,
        Method::Ewa,
    ];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Auto => "auto",
            Method::Accum => "accum",
            Method::Analytic => "analytic",
            Method::Prism => "prism",
            Method::Stochastic => "stochastic",
            Method::Ewa => "ewa",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        parse_by_name(s, &Method::ALL, Method::name, "method")
    }
}

/// Finds the option in `all` whose `name` is `s`, or says which names were expected
/// (the `FromStr` of the CLI's named choices).
pub(crate) fn parse_by_name<T: Copy>(
    s: &str,
    all: &[T],
    name: fn(T) -> &'static str,
    what: &str,
) -> std::result::Result<T, String> {
    all.iter().copied().find(|&m| name(m) == s).ok_or_else(|| {
        let names: Vec<_> = all.iter().map(|&m| name(m)).collect();
        format!(
            "unknown {what} `{s}` (expected one of: {})",
            names.join(", ")
        )
    })
}

/// Options shared by all methods (each method reads the ones it uses).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RenderOptions {
    /// The method.
    pub method: Method,
    /// `accum`: sub-frame count (`None` = automatic, see [`accum::auto_times`]).
    pub times: Option<u32>,
    /// `accum`: jitter the sub-frame times with this seed.
    pub jitter: Option<u64>,
    /// Worker threads (`None` = rayon's default, all cores).
    pub threads: Option<usize>,
    /// `ewa`: subframes, visibility and erf evaluation.
    pub ewa: crate::ewa::EwaOptions,
    /// `stochastic`: samples per pixel (`None` = [`crate::stochastic::DEFAULT_SPP`]).
    pub spp: Option<u32>,
    /// `stochastic`: traversal of the moving triangles.
    pub traversal: crate::stochastic::TraversalChoice,
    /// `stochastic`: seed of the sample pattern.
    pub seed: u64,
    /// `stochastic`: where the samples lie in their pixel (area or centre).
    pub footprint: raster_hier::Footprint,
    /// `stochastic`: most samples one pass may hold (`None` =
    /// [`crate::stochastic::MAX_SAMPLES`]); see
    /// [`crate::stochastic::StochasticOptions::max_pass_samples`].
    pub max_pass_samples: Option<u64>,
    /// `analytic`: intervals per pixel (0 = exact unbounded lists).
    pub intervals: u32,
    /// `analytic`, `prism`: arithmetic of the interval chain (f32 or f64).
    pub precision: crate::analytic::Precision,
}

/// A rendering method.
pub trait Renderer: Send + Sync {
    /// The method's name.
    fn name(&self) -> &'static str;
    /// One line saying what the method will do for this pipeline (printed by `mblur render`).
    fn describe(&self, scene: &PreparedScene, pipeline: &Pipeline) -> String;
    /// Renders the prepared scene to a linear RGB image.
    fn render(
        &self,
        scene: &PreparedScene,
        pipeline: &Pipeline,
        progress: &dyn Progress,
    ) -> Result<Image>;
    /// What the last [`Renderer::render`] cost, for methods that count it (printed by
    /// `mblur render`); `None` by default.
    fn statistics(&self) -> Option<String> {
        None
    }
}

/// The `accum` method (ground truth).
#[derive(Debug, Clone, Copy, Default)]
pub struct AccumRenderer {
    /// Its options.
    pub options: AccumOptions,
}

impl Renderer for AccumRenderer {
    fn name(&self) -> &'static str {
        "accum"
    }

    fn describe(&self, scene: &PreparedScene, _pipeline: &Pipeline) -> String {
        let n = self
            .options
            .times
            .unwrap_or_else(|| accum::auto_times(scene));
        let how = if self.options.times.is_some() {
            ""
        } else {
            " (automatic: <= 0.5 px of motion between sub-frames)"
        };
        let jitter = if self.options.jitter.is_some() {
            ", jittered"
        } else {
            ""
        };
        format!(
            "accum: {n} sub-frame{}{how}{jitter}",
            if n == 1 { "" } else { "s" }
        )
    }

    fn render(
        &self,
        scene: &PreparedScene,
        _pipeline: &Pipeline,
        progress: &dyn Progress,
    ) -> Result<Image> {
        accum::render(scene, &self.options, progress)
    }
}

/// The renderer for `options.method`; methods not wired yet are an error, never a silent
/// fallback. `auto` needs the scene to choose ([`crate::render`] resolves it with
/// [`crate::auto::choose`]); without one it resolves to `analytic`, the choice for triangle
/// scenes (the returned note says so).
pub fn renderer_for(options: &RenderOptions) -> Result<(Box<dyn Renderer>, Option<String>)> {
    let accum = || {
        Box::new(AccumRenderer {
            options: AccumOptions {
                times: options.times,
                jitter: options.jitter,
            },
        })
    };
    match options.method {
        Method::Accum => Ok((accum(), None)),
        Method::Ewa => Ok((
            Box::new(crate::ewa::EwaRenderer {
                options: options.ewa,
            }),
            None,
        )),
        Method::Stochastic => Ok((
            Box::new(crate::stochastic::StochasticRenderer::new(
                crate::stochastic::StochasticOptions {
                    spp: options.spp,
                    traversal: options.traversal,
                    seed: options.seed,
                    footprint: options.footprint,
                    max_pass_samples: options.max_pass_samples,
                },
            )?),
            None,
        )),
        Method::Analytic => Ok((
            Box::new(crate::analytic::AnalyticRenderer::new(
                crate::analytic::AnalyticOptions {
                    intervals: options.intervals,
                    precision: options.precision,
                    keep_backfaces: false,
                },
            )),
            None,
        )),
        Method::Prism => Ok((
            Box::new(crate::prism::PrismRenderer::new(options.precision)),
            None,
        )),
        Method::Auto => Ok((
            renderer_for(&RenderOptions {
                method: Method::Analytic,
                ..*options
            })?
            .0,
            Some(
                "method auto: using analytic (the choice for triangle scenes; mblur::render picks per scene)"
                    .into(),
            ),
        )),
    }
}
