//! The rendering methods and their options: [`MethodOptions`] holds one options struct per
//! method, each validating itself; [`run`] renders with one and returns the image with what
//! it cost ([`Stats`]).
//!
//! Every method consumes the same [`PreparedScene`]: per triangle the 2DH vertices and view
//! depths at shutter open and close ([`crate::PreparedTriangle::open`] / `close`, moving
//! linearly in between, Gribel 2010 Eq. 2), the UVs and the material
//! ([`PreparedScene::shade`] gives premultiplied RGBA), plus the splats; and the same
//! [`Pipeline`] saying which stages the scene needs: `accum` (the ground truth), `analytic`
//! (edge-eqn -> interval-buffer -> resolve), `prism` (bilinear-patch -> exact lists ->
//! resolve), `stochastic` (raster-hier + tmsnet) and `ewa` (ewa-splat).

use std::fmt;
use std::str::FromStr;

use crate::aa::Antialiasing;
use crate::accum::{self, AccumOptions};
use crate::analytic::{AnalyticOptions, IntervalStats};
use crate::effects::Pipeline;
use crate::error::Result;
use crate::ewa::EwaOptions;
use crate::image::Image;
use crate::prepared::PreparedScene;
use crate::prism::PrismOptions;
use crate::progress::Progress;
use crate::stochastic::StochasticOptions;

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
        crate::names::parse_by_name(s, &Method::ALL, Method::name, "method")
    }
}

/// The options of the methods `auto` may pick: the one it picks renders with its own. By
/// default analytic and accum take [`Antialiasing::auto`] ([`crate::aa::AUTO_SAMPLES`]
/// positions per pixel), so the default render antialiases edges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutoOptions {
    /// For triangle scenes (and static ones, through analytic's static path).
    pub analytic: AnalyticOptions,
    /// For scenes with splats.
    pub ewa: EwaOptions,
    /// For scenes with splats that ewa refuses.
    pub accum: AccumOptions,
}

impl Default for AutoOptions {
    fn default() -> Self {
        AutoOptions {
            analytic: AnalyticOptions {
                aa: Antialiasing::auto(),
                ..AnalyticOptions::default()
            },
            ewa: EwaOptions::default(),
            accum: AccumOptions {
                aa: Antialiasing::auto(),
                ..AccumOptions::default()
            },
        }
    }
}

/// A method with its options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MethodOptions {
    /// Pick the method per scene ([`crate::auto::choose`]).
    Auto(AutoOptions),
    /// N static renders averaged: the ground truth.
    Accum(AccumOptions),
    /// Analytic coverage intervals (Gribel 2010).
    Analytic(AnalyticOptions),
    /// Ray / bilinear-patch prisms (Rønnow 2021).
    Prism(PrismOptions),
    /// Hierarchical stochastic rasterisation (Munkberg 2011).
    Stochastic(StochasticOptions),
    /// EWA splatting (Heinzle 2010).
    Ewa(EwaOptions),
}

impl Default for MethodOptions {
    fn default() -> Self {
        MethodOptions::Auto(AutoOptions::default())
    }
}

impl MethodOptions {
    /// `method` with its default options.
    pub fn defaults(method: Method) -> Self {
        match method {
            Method::Auto => MethodOptions::Auto(AutoOptions::default()),
            Method::Accum => MethodOptions::Accum(AccumOptions::default()),
            Method::Analytic => MethodOptions::Analytic(AnalyticOptions::default()),
            Method::Prism => MethodOptions::Prism(PrismOptions::default()),
            Method::Stochastic => MethodOptions::Stochastic(StochasticOptions::default()),
            Method::Ewa => MethodOptions::Ewa(EwaOptions::default()),
        }
    }

    /// The method.
    pub fn method(&self) -> Method {
        match self {
            MethodOptions::Auto(_) => Method::Auto,
            MethodOptions::Accum(_) => Method::Accum,
            MethodOptions::Analytic(_) => Method::Analytic,
            MethodOptions::Prism(_) => Method::Prism,
            MethodOptions::Stochastic(_) => Method::Stochastic,
            MethodOptions::Ewa(_) => Method::Ewa,
        }
    }

    /// Checks every setting ([`crate::Error::Setting`] names the method and the field).
    pub fn validate(&self) -> Result<()> {
        match self {
            MethodOptions::Auto(a) => {
                a.analytic.validate()?;
                a.ewa.validate()?;
                a.accum.validate()
            }
            MethodOptions::Accum(o) => o.validate(),
            MethodOptions::Analytic(o) => o.validate(),
            MethodOptions::Prism(o) => {
                o.aa.validate()?;
                o.shading.validate("prism")
            }
            MethodOptions::Stochastic(o) => o.validate(),
            MethodOptions::Ewa(o) => o.validate(),
        }
    }

    /// The sample positions of the method (accum, analytic and prism; `None` for the others
    /// and for `auto`, which renders with the options of the method it picks).
    pub fn antialiasing(&self) -> Option<Antialiasing> {
        match self {
            MethodOptions::Accum(o) => Some(o.aa),
            MethodOptions::Analytic(o) => Some(o.aa),
            MethodOptions::Prism(o) => Some(o.aa),
            _ => None,
        }
    }

    /// The same options with the sample positions `aa` (for `auto`, those of the analytic and
    /// accum options it may pick; unchanged for a method without them).
    pub fn with_antialiasing(&self, aa: Antialiasing) -> MethodOptions {
        let mut out = *self;
        match &mut out {
            MethodOptions::Auto(a) => {
                a.analytic.aa = aa;
                a.accum.aa = aa;
            }
            MethodOptions::Accum(o) => o.aa = aa,
            MethodOptions::Analytic(o) => o.aa = aa,
            MethodOptions::Prism(o) => o.aa = aa,
            _ => {}
        }
        out
    }

    /// The options `auto` renders `scene` with, and its note; other methods are returned
    /// as they are, without a note.
    pub fn resolve(
        &self,
        scene: &PreparedScene,
        pipeline: &Pipeline,
    ) -> (MethodOptions, Option<String>) {
        let MethodOptions::Auto(a) = self else {
            return (*self, None);
        };
        let choice = crate::auto::choose(scene, pipeline);
        let chosen = match choice.method {
            Method::Ewa => MethodOptions::Ewa(a.ewa),
            Method::Accum => MethodOptions::Accum(a.accum),
            _ => MethodOptions::Analytic(a.analytic),
        };
        (chosen, Some(choice.note))
    }

    /// One line saying what the method will do for this scene and pipeline (`auto` as the
    /// method it picks).
    pub fn describe(&self, scene: &PreparedScene, pipeline: &Pipeline) -> String {
        let line = match self {
            MethodOptions::Auto(_) => self.resolve(scene, pipeline).0.describe(scene, pipeline),
            MethodOptions::Accum(o) => o.describe(scene),
            MethodOptions::Analytic(o) => o.describe(scene, pipeline),
            MethodOptions::Prism(o) => o.describe(scene, pipeline),
            MethodOptions::Stochastic(o) => o.describe(scene, pipeline),
            MethodOptions::Ewa(o) => o.describe(scene, pipeline),
        };
        match self.antialiasing().filter(|aa| aa.samples > 1) {
            Some(aa) => format!(
                "{line}; {} sample positions per pixel, {} filter of radius {} px",
                aa.samples,
                aa.filter,
                aa.radius()
            ),
            None => line,
        }
    }
}

/// What a render cost, as the method counts it.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Stats {
    /// The method counts nothing (accum, ewa).
    #[default]
    None,
    /// What the interval buffers held (analytic, prism; `None` inside when the scene took
    /// the static path and stored no intervals).
    Intervals(Option<IntervalStats>),
    /// raster-hier's counters (stochastic).
    Samples(String),
}

impl fmt::Display for Stats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Stats::None | Stats::Intervals(None) => Ok(()),
            Stats::Intervals(Some(s)) => write!(f, "{s}"),
            Stats::Samples(s) => f.write_str(s),
        }
    }
}

/// Renders `scene` with a method other than `auto` (resolve `auto` first with
/// [`MethodOptions::resolve`]) and says what it cost.
pub fn run(
    scene: &PreparedScene,
    pipeline: &Pipeline,
    options: &MethodOptions,
    progress: &dyn Progress,
) -> Result<(Image, Stats)> {
    options.validate()?;
    if let Some(aa) = options.antialiasing().filter(|aa| aa.samples > 1) {
        // Each sample position is one render of the method at the pixel centres of the
        // scene shifted by the position, without antialiasing of its own.
        let single = options.with_antialiasing(Antialiasing::default());
        let image = crate::aa::render_taps(scene, &aa, progress, |s, p| {
            run(s, pipeline, &single, p).map(|(image, _)| image)
        })?;
        return Ok((image, Stats::None));
    }
    match options {
        MethodOptions::Auto(_) => {
            let (chosen, _) = options.resolve(scene, pipeline);
            run(scene, pipeline, &chosen, progress)
        }
        MethodOptions::Accum(o) => Ok((accum::render(scene, o, progress)?, Stats::None)),
        MethodOptions::Analytic(o) => {
            let (image, stats) = crate::analytic::render_stats(scene, pipeline, o, progress)?;
            Ok((image, Stats::Intervals(stats)))
        }
        MethodOptions::Prism(o) => {
            let (image, stats) = crate::prism::render_stats(scene, pipeline, o, progress)?;
            Ok((image, Stats::Intervals(stats)))
        }
        MethodOptions::Stochastic(o) => {
            let (image, counters) = o.run(scene, pipeline, progress)?;
            Ok((image, Stats::Samples(counters)))
        }
        MethodOptions::Ewa(o) => Ok((o.render(scene, pipeline, progress)?, Stats::None)),
    }
}
