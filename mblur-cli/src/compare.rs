//! `mblur compare`: the command-line side of [`mblur_lab::compare`] — arguments, the progress
//! bar over the ladder, the [Pareto check](mblur_lab::pareto) printed at the end, the Ctrl-C
//! handler (stop after the current run) and the heap meter
//! (a counting global allocator, so each run's peak heap is measured, not estimated).

use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use mblur::TraversalChoice;
use mblur_lab::compare::{
    self, CompareOptions, Event, ExternalReference, HeapMeter, LadderSize, Outcome,
};
use mblur_lab::{pareto, report};
use mblur_scene::Error;

/// Counts every heap allocation of the process (current and peak bytes).
#[global_allocator]
static HEAP: peak_alloc::PeakAlloc = peak_alloc::PeakAlloc;

/// Set by Ctrl-C: stop after the current run.
static STOP: AtomicBool = AtomicBool::new(false);

struct Meter;

impl HeapMeter for Meter {
    fn current(&self) -> usize {
        HEAP.current_usage()
    }
    fn peak(&self) -> usize {
        HEAP.peak_usage()
    }
    fn reset_peak(&self) {
        HEAP.reset_peak_usage();
    }
}

#[derive(clap::Args)]
pub(crate) struct CompareArgs {
    /// A scene file (.json) or the name of a built-in scene (default: billiards).
    scene: Option<String>,
    /// Output folder for results.csv, results.md, plot.svg, plot.png, reference.png and the
    /// per-run images (created if missing).
    #[arg(short, long, default_value = "out/compare")]
    out: PathBuf,
    /// Sub-frames of the accum reference.
    #[arg(long, default_value_t = compare::DEFAULT_REFERENCE_TIMES)]
    reference_times: u32,
    /// Subframes of the ewa A-buffer reference (splat-only scenes).
    #[arg(long, default_value_t = compare::DEFAULT_REFERENCE_SUBFRAMES)]
    reference_subframes: u32,
    /// Measure every run against this image (PNG, EXR or PFM of the scene's size, linear
    /// except PNG, which is decoded from sRGB) instead of rendering a reference: an image
    /// from another renderer, say.
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Sample positions per pixel (a power of two up to 1024) of every accum, analytic and
    /// prism run and of the accum reference, with the --filter (box by default): the same
    /// positions everywhere, so the runs stay comparable in time. stochastic spreads its
    /// samples over the pixel (a box) whatever this is; ewa samples the pixel centre.
    #[arg(long, default_value_t = 1)]
    aa: u32,
    /// The pixel filter of --aa: box, tent, gaussian or blackman-harris.
    #[arg(long, default_value = "box")]
    filter: mblur::aa::Filter,
    /// Sample positions of the accum reference alone (default: --aa), e.g. 256 for a
    /// reference supersampled beyond the runs.
    #[arg(long)]
    reference_aa: Option<u32>,
    /// The ladder: full (analytic K = 2,4,8,16,64,unbounded; prism; stochastic 1..256 spp
    /// unless --spp is given;
    /// accum 4..256 times; ewa 1..16 subframes) or small (two settings per method).
    #[arg(long, default_value = "full")]
    ladder: LadderSize,
    /// Short ladder: the same as --ladder small, and only the fallback traversal unless
    /// --traversals is given.
    #[arg(long)]
    quick: bool,
    /// Methods to run, comma-separated (default: every method: analytic, prism,
    /// stochastic, accum, ewa). A method that cannot render the scene is skipped with one
    /// line saying why.
    #[arg(long, value_delimiter = ',')]
    methods: Option<Vec<mblur::Method>>,
    /// Stochastic traversals to run, comma-separated (default: all of our, our-exact,
    /// our-per-tile, our-fine, bbox, convex, interleave, fallback).
    #[arg(long, value_delimiter = ',')]
    traversals: Option<Vec<TraversalChoice>>,
    /// Stochastic samples per pixel to run, comma-separated powers of two up to 1024
    /// (default: the ladder's, 1,4,16,64,256; above what one sample buffer holds the
    /// samples are taken in passes).
    #[arg(long, value_delimiter = ',')]
    spp: Option<Vec<u32>>,
    /// Difference images map this absolute error (linear) to full heat.
    #[arg(long, default_value_t = 0.1)]
    diff_scale: f64,
    /// The Pareto check (printed at the end and in results.md) looks at every accum and
    /// stochastic run at or above this PSNR (dB): does some analytic run reach at least its
    /// PSNR in at most its time?
    #[arg(long, default_value_t = mblur_lab::pareto::DEFAULT_PSNR_FLOOR)]
    pareto_floor: f64,
    #[command(flatten)]
    size: super::SizeArgs,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// No progress bar and no table on the terminal (the files are still written).
    #[arg(short, long)]
    quiet: bool,
}

/// Runs `mblur compare`: checks the arguments, then runs the comparison with a progress bar
/// and a Ctrl-C handler, printing the table and the Pareto check unless quiet.
pub(crate) fn run(args: CompareArgs) -> Result<(), Error> {
    let options = compare_options(&args)?;
    let (mut scene, stem) = super::load_scene(args.scene.as_deref())?;
    args.size.apply(&mut scene)?;
    // Fail on an unwritable folder before the (long) reference render.
    report::prepare_dir(&args.out)?;
    let prepared = scene.prepare()?;
    let quiet = args.quiet;
    let total =
        compare::ladder(&options).len() + compare::segments_ladder(&prepared, &options).len();
    let bar = progress_bar(total, quiet);
    set_ctrlc_handler();
    if !quiet {
        println!(
            "mblur compare: {} ({} x {}), {} ladder entries",
            scene.label, prepared.width, prepared.height, total
        );
    }
    let ref_opts = compare::reference_options(&prepared, &options);
    bar.set_message(match &args.reference {
        Some(path) => format!("reference ({})", path.display()),
        None => format!("reference ({})", ref_opts.method()),
    });
    let mut on_event = |ev: Event<'_>| match ev {
        Event::Reference(r) => {
            if !quiet {
                bar.suspend(|| {
                    println!("reference: {} in {:.2} s", r.description, r.seconds);
                    if let Some(n) = &r.note {
                        println!("note: {n}");
                    }
                    println!("{}", report::table_header());
                });
            }
        }
        Event::Start { entry, .. } => bar.set_message(entry.label()),
        Event::Done(rec) => {
            bar.inc(1);
            if !quiet {
                match &rec.outcome {
                    Outcome::Skipped(why) => {
                        let method = rec.entry.options.method();
                        bar.suspend(|| println!("skipped: {method} ({why})"));
                    }
                    _ => bar.suspend(|| println!("{}", report::table_row(rec))),
                }
            }
        }
    };
    let result = compare::compare(
        &prepared,
        Some(&scene),
        &stem,
        &options,
        &args.out,
        Some(&Meter),
        &STOP,
        &mut on_event,
    );
    bar.finish_and_clear();
    let done = result?;
    if !quiet {
        println!(
            "\n{}",
            pareto::markdown_section(&pareto::check(&done.records, options.pareto_floor))
        );
        println!(
            "wrote {}: results.csv, results.md, plot.svg, plot.png, reference.png and {} run images",
            args.out.display(),
            done.records
                .iter()
                .filter(|r| r.image_file.is_some())
                .count()
        );
    }
    if done.interrupted {
        eprintln!(
            "interrupted after {} of {} runs; the files in {} hold the runs gathered so far",
            done.records.len(),
            done.total,
            args.out.display()
        );
        std::process::exit(130);
    }
    Ok(())
}

/// Checks the arguments and builds the comparison options from them.
fn compare_options(args: &CompareArgs) -> Result<CompareOptions, Error> {
    if !(args.diff_scale.is_finite() && args.diff_scale > 0.0) {
        return Err(Error::Option {
            option: "--diff-scale".into(),
            message: format!("must be a positive number, got {}", args.diff_scale),
        });
    }
    if args.reference_subframes == 0 || args.reference_subframes > mblur::ewa::MAX_SUBFRAMES {
        return Err(Error::Option {
            option: "--reference-subframes".into(),
            message: format!(
                "must be between 1 and {}, got {}",
                mblur::ewa::MAX_SUBFRAMES,
                args.reference_subframes
            ),
        });
    }
    let quick = args.quick || args.ladder == LadderSize::Small;
    let traversals = match args.traversals.clone() {
        Some(t) => t,
        None if args.quick => vec![TraversalChoice::Fallback],
        None => TraversalChoice::ALL.to_vec(),
    };
    Ok(CompareOptions {
        reference_times: args.reference_times,
        reference_subframes: args.reference_subframes,
        ladder: if quick {
            LadderSize::Small
        } else {
            LadderSize::Full
        },
        methods: args.methods.clone().unwrap_or_default(),
        traversals,
        stochastic_spp: args.spp.clone(),
        threads: args.threads,
        diff_scale: args.diff_scale,
        pareto_floor: args.pareto_floor,
        aa: mblur::aa::Antialiasing {
            samples: args.aa,
            filter: args.filter,
            radius: None,
        },
        reference_aa: args.reference_aa,
        external_reference: match &args.reference {
            Some(path) => Some(ExternalReference {
                image: mblur_scene::image_io::read(path)?,
                source: path.display().to_string(),
            }),
            None => None,
        },
        ..Default::default()
    })
}

/// The progress bar over `total` ladder entries, drawn on stderr when it is a terminal and
/// not `quiet`.
fn progress_bar(total: usize, quiet: bool) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::hidden());
    if !quiet && std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::stderr());
        bar.enable_steady_tick(Duration::from_millis(250));
    }
    if let Ok(style) = ProgressStyle::with_template("{bar:30} {pos}/{len} {elapsed} {msg}") {
        bar.set_style(style);
    }
    bar
}

/// Installs the Ctrl-C handler: the first stops after the current run, the second quits.
fn set_ctrlc_handler() {
    if let Err(e) = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            eprintln!("\ninterrupted twice: quitting now");
            std::process::exit(130);
        }
        eprintln!("\nstopping after the current run (Ctrl-C again to quit now)");
    }) {
        eprintln!("warning: no Ctrl-C handler ({e}); an interruption loses the current run");
    }
}
