//! The `mblur` command: render scenes to motion-blurred images.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use mblur::Progress;
use mblur_scene::{Error, Scene, builtin};

mod aov;
mod compare;
mod frames;
mod options;

#[derive(Parser)]
#[command(
    name = "mblur",
    version,
    about = "Correct motion blur: scenes in, motion-blurred images out"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene file or a built-in scene to an image (.png, .exr or .pfm).
    Render(RenderArgs),
    /// List the built-in scenes.
    Scenes,
    /// Draw one pixel's analytic coverage intervals over the shutter (depth vs time),
    /// exact and compressed to K, as SVG: the temporal pixel visualiser of Gribel 2010 §5.2.1.
    Inspect(InspectArgs),
    /// Render a reference and a ladder of settings for every method; report time, peak heap
    /// and error (PSNR, RMSE, max abs, SSIM) as a table, CSV, Markdown, a plot and images.
    Compare(compare::CompareArgs),
    /// Compare two images (PNG, EXR or PFM, any mix) of one size: PSNR, RMSE, largest
    /// absolute difference and SSIM of the first against the second, in linear RGB.
    Diff(DiffArgs),
}

#[derive(clap::Args)]
struct DiffArgs {
    /// The image to measure.
    image: PathBuf,
    /// The reference it is measured against.
    reference: PathBuf,
    /// Print only this metric (a bare number): psnr, rmse, max-abs or ssim. FLIP is not
    /// offered: its Rust crate builds NVIDIA's C++ code, a C++ toolchain the workspace
    /// does not require.
    #[arg(long, value_parser = ["psnr", "rmse", "max-abs", "ssim"])]
    metric: Option<String>,
}

/// The image size overrides of the subcommands that render a scene.
#[derive(clap::Args)]
struct SizeArgs {
    /// Override the image width.
    #[arg(long)]
    width: Option<u32>,
    /// Override the image height.
    #[arg(long)]
    height: Option<u32>,
}

impl SizeArgs {
    /// Applies the overrides to `scene` (an error names a bad size).
    fn apply(&self, scene: &mut Scene) -> Result<(), Error> {
        scene.set_size(self.width, self.height)
    }
}

#[derive(clap::Args)]
struct InspectArgs {
    /// A scene file (.json) or the name of a built-in scene (default: billiards).
    scene: Option<String>,
    /// The pixel, as X,Y (column, row; row 0 at the top).
    #[arg(long, value_parser = mblur_lab::inspect::parse_pixel)]
    pixel: (u32, u32),
    /// Output SVG file. Default: SCENE-X-Y.svg in the current folder.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Intervals per pixel after compression with the paper's oracle (K, 1..=1024).
    #[arg(long, default_value_t = mblur::inspect::DEFAULT_INTERVALS)]
    intervals: u32,
    #[command(flatten)]
    size: SizeArgs,
    /// Print nothing but errors.
    #[arg(short, long)]
    quiet: bool,
}

#[derive(clap::Args)]
struct RenderArgs {
    /// A scene file (.json), a glTF 2.0 file (.gltf, .glb) or the name of a built-in scene
    /// (default: billiards).
    scene: Option<String>,
    /// Output file; the extension picks the format (.png sRGB 8-bit, .exr / .pfm linear
    /// float). Default: SCENE.png in the current folder (SCENE_####.png for --frames). A
    /// run of `#` is replaced by the zero-padded frame number.
    #[arg(short, long)]
    output: Option<PathBuf>,
    #[command(flatten)]
    frames: frames::FrameArgs,
    #[command(flatten)]
    method: options::MethodArgs,
    #[command(flatten)]
    size: SizeArgs,
    #[command(flatten)]
    motion: MotionArgs,
    #[command(flatten)]
    aov: aov::AovArgs,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Print nothing but errors.
    #[arg(short, long)]
    quiet: bool,
}

/// The accuracy knob of curved motion.
#[derive(clap::Args)]
struct MotionArgs {
    /// Segments per turning key pair of curved motion: `auto` (the fewest keeping every
    /// vertex within --path-tolerance of its true path) or a count (1..=64).
    #[arg(long, default_value = "auto", value_parser = parse_segments)]
    segments: mblur_scene::segments::Segments,
    /// Largest screen distance in pixels between a vertex's chord and its true path for
    /// `--segments auto`.
    #[arg(long, default_value_t = mblur_scene::segments::DEFAULT_PATH_TOLERANCE)]
    path_tolerance: f64,
}

impl MotionArgs {
    /// The options these flags give.
    fn options(&self) -> mblur_scene::segments::MotionOptions {
        mblur_scene::segments::MotionOptions {
            segments: self.segments,
            path_tolerance: self.path_tolerance,
        }
    }
}

/// Parses `auto` or a segment count.
fn parse_segments(s: &str) -> Result<mblur_scene::segments::Segments, String> {
    use mblur_scene::segments::{MAX_SEGMENTS, Segments};
    if s == "auto" {
        return Ok(Segments::Auto);
    }
    match s.parse::<u32>() {
        Ok(n) if (1..=MAX_SEGMENTS).contains(&n) => Ok(Segments::Fixed(n)),
        _ => Err(format!("expected `auto` or 1..={MAX_SEGMENTS}, got `{s}`")),
    }
}

/// An indicatif bar that stays hidden for the first second and never shows when stderr is
/// not a terminal or with --quiet.
struct Bar {
    bar: ProgressBar,
    start: Instant,
    enabled: bool,
    shown: AtomicBool,
    lock: Mutex<()>,
}

impl Bar {
    fn new(enabled: bool) -> Self {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} {msg}  {elapsed} (eta {eta})")
        {
            bar.set_style(style);
        }
        Bar {
            bar,
            start: Instant::now(),
            enabled,
            shown: AtomicBool::new(false),
            lock: Mutex::new(()),
        }
    }
}

impl Progress for Bar {
    fn start(&self, total: u64, unit: &'static str) {
        self.bar.set_position(0);
        self.bar.set_length(total);
        self.bar.set_message(unit);
    }

    fn advance(&self, steps: u64) {
        self.bar.inc(steps);
        if self.enabled
            && !self.shown.load(Ordering::Relaxed)
            && self.start.elapsed() > Duration::from_secs(1)
        {
            let _guard = self.lock.lock();
            if !self.shown.swap(true, Ordering::Relaxed) {
                self.bar.set_draw_target(ProgressDrawTarget::stderr());
            }
        }
    }

    fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

fn load_scene(arg: Option<&str>) -> Result<(Scene, String), Error> {
    let arg = arg.unwrap_or(builtin::DEFAULT_SCENE);
    if builtin::lookup(arg).is_some() && !Path::new(arg).exists() {
        return Ok((Scene::builtin(arg)?, arg.to_string()));
    }
    let looks_like_file = arg.contains('/') || arg.contains('\\') || arg.contains('.');
    if !looks_like_file && !Path::new(arg).exists() {
        return Err(Error::UnknownScene(arg.to_string()));
    }
    let stem = Path::new(arg)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("render")
        .to_string();
    Ok((Scene::load(arg)?, stem))
}

fn render(args: RenderArgs) -> Result<(), Error> {
    let options = args.method.options()?;
    let pool = mblur_lab::threads::thread_pool(args.threads)?;
    args.frames.check()?;
    if let Some(path) = args
        .scene
        .as_deref()
        .filter(|a| mblur_scene::gltf::is_gltf_path(Path::new(a)))
    {
        return render_gltf(&args, path, &options, &pool);
    }
    let f = &args.frames;
    for (given, flag) in [
        (f.frames.is_some(), "--frames"),
        (f.frame.is_some(), "--frame"),
        (f.camera.is_some(), "--camera"),
        (f.animation.is_some(), "--animation"),
    ] {
        if given {
            return Err(Error::Option {
                option: flag.into(),
                message: "applies to glTF files (.gltf, .glb): a JSON scene's motion is given \
                          over one shutter in normalised time, with no animation timeline"
                    .into(),
            });
        }
    }
    let (mut scene, stem) = load_scene(args.scene.as_deref())?;
    args.size.apply(&mut scene)?;
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{stem}.png")));
    let t0 = Instant::now();
    let prepare = || scene.prepare_with(&args.motion.options());
    render_prepared(&args, &scene.label, prepare, &output, &options, &pool)?;
    if !args.quiet {
        eprintln!(
            "wrote {} in {:.2} s",
            output.display(),
            t0.elapsed().as_secs_f64()
        );
    }
    Ok(())
}

/// Renders the frames of a glTF file asked for by the frame flags.
fn render_gltf(
    args: &RenderArgs,
    path: &str,
    options: &mblur::MethodOptions,
    pool: &rayon::ThreadPool,
) -> Result<(), Error> {
    let list = args.frames.list()?;
    let scene = mblur_scene::gltf::GltfScene::load(path)?;
    let stem = Path::new(path)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("render")
        .to_string();
    let sequence = args.frames.sequence_requested();
    let pattern = args.output.clone().unwrap_or_else(|| {
        PathBuf::from(if sequence {
            format!("{stem}_####.png")
        } else {
            format!("{stem}.png")
        })
    });
    if list.len() > 1 && !frames::has_pattern(&pattern) {
        return Err(Error::Option {
            option: "--output".into(),
            message: format!(
                "{} frames need a run of `#` in the file name for the frame number \
                 (e.g. out_####.exr), got {}",
                list.len(),
                pattern.display()
            ),
        });
    }
    let animation = args.frames.animation.as_deref();
    let duration = scene.duration(animation)?;
    let last_close = list
        .iter()
        .map(|&f| args.frames.window(f)[1])
        .fold(f64::NEG_INFINITY, f64::max);
    if !args.quiet && last_close > duration && (sequence || duration > 0.0) {
        if duration > 0.0 {
            eprintln!(
                "note: the animation ends at {duration} s; frames whose shutter closes after \
                 it hold its last key (the range reaches {last_close:.6} s)"
            );
        } else {
            eprintln!(
                "note: {} has no animation: every frame shows the same still scene",
                scene.label
            );
        }
    }
    let outer = frame_bar(
        !args.quiet && list.len() > 1 && std::io::stderr().is_terminal(),
        list.len(),
    );
    let mut warned = false;
    for &f in &list {
        let output = frames::output_for(&pattern, f);
        if output.exists() && !args.frames.overwrite {
            if !args.quiet {
                outer.suspend(|| {
                    eprintln!(
                        "frame {f}: {} exists, skipped (--overwrite renders it again)",
                        output.display()
                    )
                });
            }
            outer.inc(1);
            continue;
        }
        let t0 = Instant::now();
        let opts = mblur_scene::gltf::GltfOptions {
            camera: args.frames.camera.clone(),
            animation: args.frames.animation.clone(),
            width: args.size.width,
            height: args.size.height,
            window: args.frames.window(f),
        };
        let prepare = || {
            let frame = scene.prepare(&opts, &args.motion.options())?;
            if !args.quiet && !warned {
                for w in &frame.warnings {
                    eprintln!("warning: {w}");
                }
            }
            Ok(frame.scene)
        };
        let label = format!(
            "{} frame {f} ([{}, {}] s)",
            scene.label, opts.window[0], opts.window[1]
        );
        outer.suspend(|| render_prepared(args, &label, prepare, &output, options, pool))?;
        warned = true;
        if !args.quiet {
            outer.suspend(|| {
                eprintln!(
                    "frame {f}: wrote {} in {:.2} s",
                    output.display(),
                    t0.elapsed().as_secs_f64()
                )
            });
        }
        outer.inc(1);
    }
    outer.finish_and_clear();
    Ok(())
}

/// A progress bar over the frames of a sequence (hidden when `enabled` is false).
fn frame_bar(enabled: bool, frames: usize) -> ProgressBar {
    if !enabled {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(frames as u64);
    if let Ok(style) =
        ProgressStyle::with_template("frames {bar:40} {pos}/{len}  {elapsed} (eta {eta})")
    {
        bar.set_style(style);
    }
    bar
}

/// Prepares a scene with `prepare`, renders it and writes `output` (with the AOV layers
/// asked for); `label` names the scene in messages.
fn render_prepared(
    args: &RenderArgs,
    label: &str,
    prepare: impl FnOnce() -> Result<mblur::PreparedScene, Error> + Send,
    output: &Path,
    options: &mblur::MethodOptions,
    pool: &rayon::ThreadPool,
) -> Result<(), Error> {
    let aovs = args.aov.request(output)?;
    // Fail on an unwritable output before the (possibly long) render.
    mblur_scene::image_io::check_writable(output)?;
    let motion = args.motion.options();
    // On the render's pool: preparation runs parts of its work in parallel too.
    let prepared = pool.install(prepare)?;
    let quiet = args.quiet;
    let bar = Bar::new(!quiet && std::io::stderr().is_terminal());
    let effects = mblur::Effects::analyse(&prepared);
    if !quiet {
        eprintln!("{label} ({} x {})", prepared.width, prepared.height);
        eprintln!("{effects}");
        if let Some(line) = mblur_scene::segments::describe(&prepared, &motion) {
            eprintln!("{line}");
        }
    }
    if prepared.triangles.is_empty() && prepared.splats.is_empty() {
        eprintln!(
            "warning: {label} has no triangles or splats to draw: the image is the background"
        );
    }
    let pipeline = effects.pipeline();
    args.method
        .check_used_by(options.resolve(&prepared, &pipeline).0.method())?;
    let out = pool
        .install(|| mblur::render(&prepared, options, &bar))
        .map_err(options::flag_error)?;
    if !quiet {
        if let Some(note) = &out.note {
            eprintln!("{note}");
        }
        eprintln!("{}", out.description);
        let stats = out.stats.to_string();
        if !stats.is_empty() {
            eprintln!("{stats}");
        }
    }
    match aovs {
        Some((set, aov_options)) => {
            let layers = pool
                .install(|| mblur::render_aovs(&prepared, set, &aov_options, &bar))
                .map_err(options::flag_error)?;
            mblur_scene::layered_exr::save(&out.image, &layers, output)?;
        }
        None => mblur_scene::image_io::save(&out.image, output)?,
    }
    Ok(())
}

fn inspect(args: InspectArgs) -> Result<(), Error> {
    let (mut scene, stem) = load_scene(args.scene.as_deref())?;
    args.size.apply(&mut scene)?;
    let (x, y) = args.pixel;
    let output = args
        .output
        .unwrap_or_else(|| PathBuf::from(format!("{stem}-{x}-{y}.svg")));
    let p = mblur::inspect::pixel_intervals(&scene.prepare()?, x, y, args.intervals)?;
    mblur_lab::inspect::save_svg(&output, &mblur_lab::inspect::to_svg(&p, &scene.label))?;
    if !args.quiet {
        eprintln!(
            "{} pixel ({x}, {y}): {} exact, {} after compression to K = {}; resolved {:?} exact, {:?} compressed",
            scene.label,
            count(p.exact.intervals.len(), "interval"),
            count(p.compressed.intervals.len(), "interval"),
            p.k,
            p.exact.colour,
            p.compressed.colour
        );
        eprintln!("wrote {}", output.display());
    }
    Ok(())
}

fn diff(args: DiffArgs) -> Result<(), Error> {
    let a = mblur_scene::image_io::read(&args.image)?;
    let b = mblur_scene::image_io::read(&args.reference)?;
    let m = mblur_lab::metrics::Metrics::of(&a, &b).ok_or_else(|| Error::Option {
        option: "IMAGE REFERENCE".into(),
        message: format!(
            "the images differ in size ({} x {} against {} x {})",
            a.width, a.height, b.width, b.height
        ),
    })?;
    let ssim = m
        .ssim
        .map_or("n/a (smaller than the 11 x 11 window)".into(), |v| {
            format!("{v:.6}")
        });
    match args.metric.as_deref() {
        Some("psnr") => println!("{}", m.psnr),
        Some("rmse") => println!("{}", m.rmse),
        Some("max-abs") => println!("{}", m.max_abs),
        Some(_) => println!("{ssim}"),
        None => println!(
            "{} against {} ({} x {}): PSNR {:.3} dB, RMSE {:.6e}, max abs {:.6e}, SSIM {ssim}",
            args.image.display(),
            args.reference.display(),
            a.width,
            a.height,
            m.psnr,
            m.rmse,
            m.max_abs
        ),
    }
    Ok(())
}

/// `n` and `noun`, plural unless `n` is 1 ("1 interval", "3 intervals").
fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Scenes => {
            for (name, about, _) in builtin::SCENES {
                let default = if name == builtin::DEFAULT_SCENE {
                    " (default)"
                } else {
                    ""
                };
                println!("{name:<18} {about}{default}");
            }
            println!(
                "\nA lit scene's name with {} appended (billiards{}) renders it unlit.",
                builtin::UNLIT_SUFFIX,
                builtin::UNLIT_SUFFIX
            );
            Ok(())
        }
        Command::Render(args) => render(args),
        Command::Inspect(args) => inspect(args),
        Command::Compare(args) => compare::run(args),
        Command::Diff(args) => diff(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", options::named(e));
            ExitCode::FAILURE
        }
    }
}
