//! `mblur compare`: what accuracy costs in time. Renders a reference (accum with many
//! sub-frames; for splat-only scenes the ewa A-buffer with many subframes), then a ladder of
//! settings for every method — analytic with K intervals per pixel and unbounded, prism,
//! stochastic at several sample counts for each traversal (samples at pixel centres, like
//! the reference: [`STOCHASTIC_FOOTPRINT`]), accum at several sub-frame counts,
//! ewa at several subframe counts — and measures for each run the wall time (median of
//! repeats for short runs), the peak heap the render allocated, and the error metrics of
//! [`crate::metrics`] against the reference. A method that refuses the scene is recorded as
//! skipped with its reason.
//!
//! Entry points: [`ladder`] (the settings), [`fn@reference`] (the reference render),
//! [`run_entry`] (one measured run), [`compare`] (everything, writing the files of
//! [`crate::report`] and [`crate::plot`] after every run so an interruption keeps what was
//! gathered).

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use mblur::aa::Antialiasing;
use mblur::ewa;
use mblur::{
    AccumOptions, AnalyticOptions, EwaOptions, Footprint, Image, Method, MethodOptions, NoProgress,
    PreparedScene, PrismOptions, ShadingSamples, StochasticOptions, TraversalChoice,
};
use mblur_scene::segments::{MotionOptions, Segments};
use mblur_scene::{Error, Result, Scene};

use crate::metrics::Metrics;
pub use crate::record::{LadderEntry, Outcome, Reference, RunRecord, RunStats, SceneInfo};

/// Default sub-frame count of the accum reference.
pub const DEFAULT_REFERENCE_TIMES: u32 = 1024;
/// Default subframe count of the ewa A-buffer reference for splat-only scenes.
pub const DEFAULT_REFERENCE_SUBFRAMES: u32 = 256;

/// Where the stochastic runs put their samples: at the pixel centre, where the reference
/// and every other method sample. Spread over the pixel (the `render` default) the
/// estimator converges to the box-filtered image, and its error against the pixel-centre
/// reference stops falling at that difference (46.6 dB on billiards at 64 and 256 spp)
/// however many samples it takes.
pub const STOCHASTIC_FOOTPRINT: Footprint = Footprint::Centre;

/// Reads the heap the process has allocated; the `mblur` binary implements it with a
/// counting global allocator. Renders are measured one at a time, so the process-wide
/// figures are the render's.
pub trait HeapMeter: Sync {
    /// Bytes currently allocated.
    fn current(&self) -> usize;
    /// Largest [`HeapMeter::current`] since the last [`HeapMeter::reset_peak`].
    fn peak(&self) -> usize;
    /// Restarts the peak at the current figure.
    fn reset_peak(&self);
}

/// How many settings per method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LadderSize {
    /// Every setting of the issue: analytic K = 2, 4, 8, 16, 64 and unbounded; prism;
    /// stochastic 1, 4, 16, 64, 256 spp; accum 4, 16, 64, 256 times; ewa 1, 2, 4, 8, 16
    /// subframes.
    #[default]
    Full,
    /// A short ladder for quick looks and tests: analytic K = 4 and unbounded; prism;
    /// stochastic 4 and 16 spp; accum 4 and 16 times; ewa 1 and 4 subframes.
    Small,
}

impl LadderSize {
    /// The name `--ladder` takes.
    pub fn name(self) -> &'static str {
        match self {
            LadderSize::Full => "full",
            LadderSize::Small => "small",
        }
    }
}

impl std::str::FromStr for LadderSize {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        let all = [LadderSize::Full, LadderSize::Small];
        mblur::names::parse_by_name(s, &all, LadderSize::name, "ladder")
    }
}

/// Options of a comparison.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareOptions {
    /// Sub-frames of the accum reference.
    pub reference_times: u32,
    /// Subframes of the ewa A-buffer reference (splat-only scenes).
    pub reference_subframes: u32,
    /// Which ladder.
    pub ladder: LadderSize,
    /// The methods to run (`auto` is never in a ladder); empty = every method.
    pub methods: Vec<Method>,
    /// Stochastic traversals to run (each gets the whole spp ladder).
    pub traversals: Vec<TraversalChoice>,
    /// Stochastic samples per pixel to run, each a power of two up to
    /// [`mblur::stochastic::MAX_SPP`]; `None` = the ladder's own (1, 4, 16, 64, 256 for
    /// [`LadderSize::Full`], 4 and 16 for [`LadderSize::Small`]).
    pub stochastic_spp: Option<Vec<u32>>,
    /// Worker threads (`None` = all cores); one pool serves every run.
    pub threads: Option<usize>,
    /// Repeat a run while the repeats so far took less than this in total ...
    pub repeat_budget: Duration,
    /// ... but at most this many times; the reported time is the median.
    pub max_repeats: u32,
    /// Difference images map this absolute error (linear units) to full heat.
    pub diff_scale: f64,
    /// An image to measure every run against instead of rendering a reference (from another
    /// renderer, say); it must have the scene's size.
    pub external_reference: Option<ExternalReference>,
    /// Sample positions of every run of accum, analytic and prism and of the accum
    /// reference ([`mblur::aa`]), so the comparison stays exact in time at the same
    /// positions; one (the pixel centre) by default.
    pub aa: Antialiasing,
    /// Positions of the accum reference when it should differ from `aa` (a heavily
    /// supersampled reference, against which the runs' spatial error shows too).
    pub reference_aa: Option<u32>,
    /// The PSNR floor (dB) of the [Pareto check](crate::pareto) in `results.md`.
    pub pareto_floor: f64,
}

/// A reference image made elsewhere.
#[derive(Debug, Clone, PartialEq)]
pub struct ExternalReference {
    /// The image (linear RGB).
    pub image: Image,
    /// Where it came from, for the report (a file name).
    pub source: String,
}

impl CompareOptions {
    /// The sample positions of the accum reference: `aa` with `reference_aa` positions when
    /// given.
    pub fn reference_antialiasing(&self) -> Antialiasing {
        Antialiasing {
            samples: self.reference_aa.unwrap_or(self.aa.samples),
            ..self.aa
        }
    }
}

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            reference_times: DEFAULT_REFERENCE_TIMES,
            reference_subframes: DEFAULT_REFERENCE_SUBFRAMES,
            ladder: LadderSize::Full,
            methods: Vec::new(),
            traversals: TraversalChoice::ALL.to_vec(),
            stochastic_spp: None,
            threads: None,
            repeat_budget: Duration::from_secs(1),
            max_repeats: 5,
            diff_scale: 0.1,
            external_reference: None,
            aa: Antialiasing::default(),
            reference_aa: None,
            pareto_floor: crate::pareto::DEFAULT_PSNR_FLOOR,
        }
    }
}

/// The ladder of settings, in the order they run: analytic, prism, stochastic (per
/// traversal), accum, ewa; each method from cheap to expensive; only
/// [`CompareOptions::methods`] when given.
pub fn ladder(options: &CompareOptions) -> Vec<LadderEntry> {
    let mut all = full_ladder(options);
    if !options.methods.is_empty() {
        all.retain(|e| options.methods.contains(&e.options.method()));
    }
    all
}

fn full_ladder(options: &CompareOptions) -> Vec<LadderEntry> {
    let small = options.ladder == LadderSize::Small;
    let pick = |full: &'static [u32], short: &'static [u32]| if small { short } else { full };
    let mut out = Vec::new();
    for &k in pick(&[2, 4, 8, 16, 64, 0], &[4, 0]) {
        let setting = if k == 0 {
            "unbounded".to_string()
        } else {
            format!("K={k}")
        };
        out.push(LadderEntry::new(
            "analytic",
            setting,
            MethodOptions::Analytic(AnalyticOptions {
                intervals: k,
                ..Default::default()
            }),
        ));
    }
    out.push(LadderEntry::new(
        "prism",
        "exact",
        MethodOptions::Prism(PrismOptions::default()),
    ));
    for &traversal in &options.traversals {
        let spps = options.stochastic_spp.as_deref();
        for &spp in spps.unwrap_or_else(|| pick(&[1, 4, 16, 64, 256], &[4, 16])) {
            out.push(LadderEntry::new(
                format!("stochastic/{}", traversal.name()),
                format!("{spp} spp"),
                MethodOptions::Stochastic(StochasticOptions {
                    spp: Some(spp),
                    traversal,
                    footprint: STOCHASTIC_FOOTPRINT,
                    ..Default::default()
                }),
            ));
        }
    }
    for &times in pick(&[4, 16, 64, 256], &[4, 16]) {
        out.push(LadderEntry::new(
            "accum",
            format!("{times} times"),
            MethodOptions::Accum(AccumOptions {
                times: Some(times),
                jitter: None,
                ..Default::default()
            }),
        ));
    }
    for &subframes in pick(&[1, 2, 4, 8, 16], &[1, 4]) {
        out.push(LadderEntry::new(
            "ewa",
            format!(
                "{subframes} subframe{}",
                if subframes == 1 { "" } else { "s" }
            ),
            MethodOptions::Ewa(EwaOptions {
                subframes,
                ..Default::default()
            }),
        ));
    }
    out
}

/// Segment counts of the segments ladder ([`segments_ladder`]); automatic segments end it.
pub const SEGMENTS_LADDER: [u32; 6] = [1, 2, 4, 8, 16, 32];

/// The segments ladder of a scene with curved motion: analytic (unbounded intervals) with
/// the scene prepared with 1, 2, 4, 8, 16 and 32 segments per turning key pair and with
/// automatic segments; empty when no object turns or analytic is not among the methods asked for.
pub fn segments_ladder(scene: &PreparedScene, options: &CompareOptions) -> Vec<LadderEntry> {
    let curved = scene.objects.iter().any(|o| o.path.is_some());
    let wanted = options.methods.is_empty() || options.methods.contains(&Method::Analytic);
    if !curved || !wanted {
        return Vec::new();
    }
    let counts = SEGMENTS_LADDER.map(Segments::Fixed);
    counts
        .into_iter()
        .chain([Segments::Auto])
        .map(|seg| {
            let setting = match seg {
                Segments::Fixed(1) => "1 segment".to_string(),
                Segments::Fixed(n) => format!("{n} segments"),
                Segments::Auto => "auto".to_string(),
            };
            LadderEntry {
                segments: Some(seg),
                ..LadderEntry::new(
                    "analytic/segments",
                    setting,
                    MethodOptions::Analytic(AnalyticOptions::default()),
                )
            }
        })
        .collect()
}

/// The shading ladder of a scene with lit materials: analytic (unbounded intervals) with
/// `--shading-samples` start, mid, 4 and adaptive; empty when nothing is lit or analytic
/// is not among the methods asked for.
pub fn shading_ladder(scene: &PreparedScene, options: &CompareOptions) -> Vec<LadderEntry> {
    let wanted = options.methods.is_empty() || options.methods.contains(&Method::Analytic);
    if !scene.any_lit() || !wanted {
        return Vec::new();
    }
    [
        ShadingSamples::Start,
        ShadingSamples::Mid,
        ShadingSamples::Fixed(4),
        ShadingSamples::default(),
    ]
    .into_iter()
    .map(|shading| {
        let setting = match shading {
            ShadingSamples::Fixed(n) => format!("{n} samples"),
            ShadingSamples::Adaptive { .. } => "adaptive".to_string(),
            other => other.to_string(),
        };
        LadderEntry::new(
            "analytic/shading",
            setting,
            MethodOptions::Analytic(AnalyticOptions {
                shading,
                ..Default::default()
            }),
        )
    })
    .collect()
}

/// The reference options for `scene`: the ewa A-buffer with `reference_subframes` for
/// splat-only scenes, else accum with `reference_times` sub-frames.
pub fn reference_options(scene: &PreparedScene, options: &CompareOptions) -> MethodOptions {
    if ewa::applies(scene) && ewa::check_scene(scene).is_ok() {
        MethodOptions::Ewa(EwaOptions {
            subframes: options.reference_subframes,
            ..Default::default()
        })
    } else {
        MethodOptions::Accum(AccumOptions {
            times: Some(options.reference_times),
            jitter: None,
            aa: options.reference_antialiasing(),
        })
    }
}

/// Renders the reference (on the calling thread's rayon pool), or takes the external one,
/// which must have the scene's size.
pub fn reference(scene: &PreparedScene, options: &CompareOptions) -> Result<Reference> {
    if let Some(ext) = &options.external_reference {
        let (w, h) = (ext.image.width, ext.image.height);
        if (w, h) != (scene.width, scene.height) {
            return Err(Error::Option {
                option: "--reference".into(),
                message: format!(
                    "{} is {w} x {h}, the scene renders at {} x {} (set --width/--height)",
                    ext.source, scene.width, scene.height
                ),
            });
        }
        return Ok(Reference {
            image: ext.image.clone(),
            description: format!("external reference {}", ext.source),
            seconds: 0.0,
            note: None,
        });
    }
    let opts = reference_options(scene, options);
    let note = match (ewa::applies(scene), ewa::check_scene(scene)) {
        (true, Err(e)) => Some(format!("accum reference because {e}")),
        _ => None,
    };
    let t0 = Instant::now();
    let out = mblur::render(scene, &opts, &NoProgress)?;
    Ok(Reference {
        image: out.image,
        description: out.description,
        seconds: t0.elapsed().as_secs_f64(),
        note,
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => v[n / 2],
        _ => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// Renders one ladder entry, repeating it while the total stays under
/// [`CompareOptions::repeat_budget`] (at most [`CompareOptions::max_repeats`] times), and
/// measures it against `reference`. Returns the outcome and the image of the first repeat.
/// Runs on the calling thread's rayon pool.
pub fn run_entry(
    scene: &PreparedScene,
    entry: &LadderEntry,
    reference: &Image,
    options: &CompareOptions,
    heap: Option<&dyn HeapMeter>,
) -> (Outcome, Option<Image>) {
    let opts = entry.options.with_antialiasing(options.aa);
    let mut times = Vec::new();
    let mut heap_max: Option<usize> = None;
    let mut first: Option<mblur::Rendered> = None;
    let budget = options.repeat_budget.as_secs_f64();
    while times.len() < options.max_repeats.max(1) as usize {
        let base = heap.map(|h| {
            h.reset_peak();
            h.current()
        });
        let t0 = Instant::now();
        let result = mblur::render(scene, &opts, &NoProgress);
        let dt = t0.elapsed().as_secs_f64();
        if let (Some(h), Some(b)) = (heap, base) {
            let grow = h.peak().saturating_sub(b);
            heap_max = Some(heap_max.map_or(grow, |m| m.max(grow)));
        }
        match result {
            Ok(r) => {
                times.push(dt);
                if first.is_none() {
                    first = Some(r);
                }
            }
            Err(e @ (mblur::Error::MethodNotApplicable { .. } | mblur::Error::Setting { .. })) => {
                return (Outcome::Skipped(e.to_string()), None);
            }
            Err(e) => return (Outcome::Failed(e.to_string()), None),
        }
        if times.iter().sum::<f64>() >= budget {
            break;
        }
    }
    let Some(first) = first else {
        return (Outcome::Failed("no run completed".into()), None);
    };
    let Some(metrics) = Metrics::of(&first.image, reference) else {
        return (
            Outcome::Failed("the image size differs from the reference".into()),
            None,
        );
    };
    let stats = RunStats {
        seconds: median(times.clone()),
        repeats: times.len() as u32,
        heap_bytes: heap_max,
        metrics,
        description: first.description,
    };
    (Outcome::Done(stats), Some(first.image))
}

/// What [`compare`] reports while it works.
#[derive(Debug)]
pub enum Event<'a> {
    /// The reference is done.
    Reference(&'a Reference),
    /// Run `index` (1-based) of `total` starts.
    Start {
        /// 1-based position.
        index: usize,
        /// Ladder length.
        total: usize,
        /// The entry.
        entry: &'a LadderEntry,
    },
    /// A run finished (its files are written).
    Done(&'a RunRecord),
}

/// The results of [`compare`].
#[derive(Debug, Clone)]
pub struct Comparison {
    /// The reference.
    pub reference: Reference,
    /// One record per ladder entry that ran (all of them unless interrupted).
    pub records: Vec<RunRecord>,
    /// How many runs the ladder came to: its length less the settings of methods that
    /// refused the scene (each such method is run once).
    pub total: usize,
    /// True when `stop` ended it early.
    pub interrupted: bool,
}

/// Runs the whole comparison: creates `out_dir`, renders the reference (writing
/// `reference.png`), then every ladder entry, writing after each run its side-by-side image
/// (`run-NN-SLUG.png`: the run | the heat-mapped difference), `results.csv`, `results.md`,
/// `plot.svg` and `plot.png`. When `stop` becomes true it stops after the current run (the
/// files then hold what was gathered). Builds one thread pool of `options.threads`. With
/// `source` (the scene `scene` was prepared from) a scene with curved motion also runs the
/// [`segments_ladder`], re-preparing `source` for each count.
#[allow(clippy::too_many_arguments)]
pub fn compare(
    scene: &PreparedScene,
    source: Option<&Scene>,
    name: &str,
    options: &CompareOptions,
    out_dir: &Path,
    heap: Option<&dyn HeapMeter>,
    stop: &AtomicBool,
    events: &mut dyn FnMut(Event<'_>),
) -> Result<Comparison> {
    check_options(options)?;
    crate::report::prepare_dir(out_dir)?;
    let pool = crate::threads::thread_pool(options.threads)?;
    let info = SceneInfo {
        name: name.to_string(),
        width: scene.width,
        height: scene.height,
        threads: pool.current_num_threads(),
    };
    let reference = pool.install(|| reference(scene, options))?;
    crate::report::save_png(&reference.image, &out_dir.join("reference.png"))?;
    events(Event::Reference(&reference));
    let mut entries = ladder(options);
    let at = entries
        .iter()
        .position(|e| e.options.method() != Method::Analytic)
        .unwrap_or(entries.len());
    entries.splice(at..at, shading_ladder(scene, options));
    if source.is_some() {
        entries.splice(at..at, segments_ladder(scene, options));
    }
    let total = entries.len();
    // The tables and plot are rewritten after every run, so an interrupted ladder leaves
    // what it gathered on disk.
    let write = |records: &[RunRecord], total: usize| {
        crate::report::write_all(
            out_dir,
            &info,
            &reference,
            records,
            total,
            options.diff_scale,
            options.pareto_floor,
        )?;
        crate::plot::write_plots(out_dir, &info, &reference, records)
    };
    let mut records: Vec<RunRecord> = Vec::new();
    write(&records, total)?;
    let mut interrupted = false;
    // A method that refuses the scene refuses every setting: it is run once, recorded as
    // skipped once, and its other settings are left out.
    let mut refused: Vec<Method> = Vec::new();
    let mut total = total;
    let methods: Vec<Method> = entries.iter().map(|e| e.options.method()).collect();
    for (i, entry) in entries.into_iter().enumerate() {
        if stop.load(Ordering::SeqCst) {
            interrupted = true;
            break;
        }
        if refused.contains(&entry.options.method()) {
            continue;
        }
        events(Event::Start {
            index: i + 1,
            total,
            entry: &entry,
        });
        let resegmented = match (entry.segments, source) {
            (Some(segments), Some(src)) => Some(src.prepare_with(&MotionOptions {
                segments,
                ..MotionOptions::default()
            })?),
            _ => None,
        };
        let run_scene = resegmented.as_ref().unwrap_or(scene);
        let (outcome, image) =
            pool.install(|| run_entry(run_scene, &entry, &reference.image, options, heap));
        if matches!(outcome, Outcome::Skipped(_)) {
            let method = entry.options.method();
            refused.push(method);
            total -= methods[i + 1..].iter().filter(|&&m| m == method).count();
        }
        let image_file = save_run_image(i, &entry, image.as_ref(), &reference, options, out_dir)?;
        records.push(RunRecord {
            index: i + 1,
            entry,
            outcome,
            image_file,
        });
        write(&records, total)?;
        if let Some(last) = records.last() {
            events(Event::Done(last));
        }
    }
    if stop.load(Ordering::SeqCst) && records.len() < total {
        interrupted = true;
    }
    Ok(Comparison {
        reference,
        records,
        total,
        interrupted,
    })
}

/// Checks the options [`compare`] needs before it writes anything: traversals, stochastic
/// sample counts, the reference sub-frame count and the Pareto floor.
fn check_options(options: &CompareOptions) -> Result<()> {
    if !options.pareto_floor.is_finite() {
        return Err(Error::Option {
            option: "--pareto-floor".into(),
            message: format!(
                "must be a finite number of dB, got {}",
                options.pareto_floor
            ),
        });
    }
    for (aa, flag) in [
        (options.aa, "--aa"),
        (options.reference_antialiasing(), "--reference-aa"),
    ] {
        aa.validate().map_err(|e| Error::Option {
            option: flag.into(),
            message: match e {
                mblur::Error::Setting { message, .. } => message,
                other => other.to_string(),
            },
        })?;
    }
    if options.traversals.is_empty() {
        return Err(Error::Option {
            option: "--traversals".into(),
            message: "needs at least one traversal".into(),
        });
    }
    if let Some(spps) = &options.stochastic_spp {
        for &spp in spps {
            mblur::stochastic::StochasticOptions {
                spp: Some(spp),
                ..Default::default()
            }
            .spp()?;
        }
        if spps.is_empty() {
            return Err(Error::Option {
                option: "--spp".into(),
                message: "needs at least one sample count".into(),
            });
        }
    }
    if options.reference_times == 0 || options.reference_times > mblur::accum::MAX_TIMES {
        return Err(Error::Option {
            option: "--reference-times".into(),
            message: format!(
                "must be between 1 and {}, got {}",
                mblur::accum::MAX_TIMES,
                options.reference_times
            ),
        });
    }
    Ok(())
}

/// Saves the side-by-side image of run `i` (0-based) when it produced one; returns its
/// file name.
fn save_run_image(
    i: usize,
    entry: &LadderEntry,
    image: Option<&Image>,
    reference: &Reference,
    options: &CompareOptions,
    out_dir: &Path,
) -> Result<Option<String>> {
    Ok(match image {
        Some(img) => {
            let file = format!("run-{:02}-{}.png", i + 1, entry.slug());
            crate::report::save_side_by_side(
                img,
                &reference.image,
                options.diff_scale,
                &out_dir.join(&file),
            )?;
            Some(file)
        }
        None => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_ladder_has_every_setting_of_the_issue() {
        let l = ladder(&CompareOptions::default());
        // 6 analytic + 1 prism + 8 traversals x 5 spp + 4 accum + 5 ewa.
        assert_eq!(l.len(), 6 + 1 + 40 + 4 + 5);
        let labels: Vec<String> = l.iter().map(LadderEntry::label).collect();
        for want in [
            "analytic K=2",
            "analytic unbounded",
            "prism exact",
            "stochastic/our 1 spp",
            "stochastic/interleave 256 spp",
            "stochastic/our-fine 16 spp",
            "accum 256 times",
            "ewa 16 subframes",
        ] {
            assert!(labels.iter().any(|l| l == want), "{want} missing");
        }
        let slugs: std::collections::HashSet<String> = l.iter().map(LadderEntry::slug).collect();
        assert_eq!(slugs.len(), l.len(), "slugs are unique");
        // Stochastic samples where the reference samples: at pixel centres.
        let mut stochastic = l
            .iter()
            .filter(|e| e.options.method() == Method::Stochastic);
        assert_eq!(stochastic.clone().count(), 40);
        assert!(stochastic.all(|e| matches!(e.options, MethodOptions::Stochastic(o) if o.footprint == Footprint::Centre)));
    }

    #[test]
    fn spp_ladder_can_be_chosen() {
        let options = CompareOptions {
            traversals: vec![TraversalChoice::Our, TraversalChoice::Fallback],
            stochastic_spp: Some(vec![2, 1024]),
            ..Default::default()
        };
        let labels: Vec<String> = ladder(&options)
            .iter()
            .filter(|e| e.options.method() == Method::Stochastic)
            .map(|e| e.label())
            .collect();
        assert_eq!(
            labels,
            [
                "stochastic/our 2 spp",
                "stochastic/our 1024 spp",
                "stochastic/fallback 2 spp",
                "stochastic/fallback 1024 spp"
            ]
        );
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 2.0, 3.0]), 2.5);
    }
}
