//! The method flags of `mblur render`: each belongs to one method (or two), becomes a field
//! of that method's options, and is an error when the method that renders the scene does
//! not use it (under `auto`, the method auto picks), so no flag is silently ignored. Errors
//! of the library name the options' fields; here they are named as flags.

use mblur::ewa::{ErfArg, VisibilityArg};
use mblur::{
    AccumOptions, AnalyticOptions, AutoOptions, EwaOptions, Footprint, Method, MethodOptions,
    Precision, PrismOptions, StochasticOptions, TraversalChoice,
};
use mblur_scene::Error;

/// The help of `--aa`, with the default render's sample count from
/// [`mblur::aa::AUTO_SAMPLES`].
fn aa_help() -> String {
    format!(
        "accum, analytic, prism: sample positions per pixel, 1 (the pixel centre) or a power \
         of two up to 1024, spread over the --filter's support by a (0,2)-sequence and \
         weighted by the filter: spatial antialiasing. Default: {} under -m auto (the \
         default render), 1 (the pixel centre) for a method asked for by name",
        mblur::aa::AUTO_SAMPLES
    )
}

/// The help of `--filter-radius`, its range and each filter's default from the library.
fn filter_radius_help() -> String {
    let defaults: Vec<String> = mblur::aa::Filter::ALL
        .iter()
        .map(|f| format!("{} {}", f.name(), f.default_radius()))
        .collect();
    format!(
        "accum, analytic, prism with --aa, and stochastic: the filter's support radius in \
         pixels, {} to {} (default: {})",
        mblur::aa::MIN_RADIUS,
        mblur::aa::MAX_RADIUS,
        defaults.join(", ")
    )
}

/// The help of `--shading-samples`, with the library's largest sample count.
fn shading_samples_help() -> String {
    format!(
        "analytic, prism: where lit materials are shaded over each partition of an interval: \
         start (the interval's start, Rønnow 2021), mid (the partition's midpoint), N (N \
         samples, 1..={}) or adaptive (bisection until the colour is within \
         --shading-tolerance of its chord; the default)",
        mblur::lighting::MAX_SHADING_SAMPLES
    )
}

/// The help of `--shading-tolerance`, with the library's default.
fn shading_tolerance_help() -> String {
    format!(
        "analytic, prism with --shading-samples adaptive: the tolerance in linear colour \
         units (default {})",
        mblur::lighting::DEFAULT_SHADING_TOLERANCE
    )
}

/// The help of `--subframes`, with the library's limit and default.
fn subframes_help() -> String {
    format!(
        "ewa: equidistant subframes of the motion path (Heinzle 2010, §5.5), 1..={} \
         (default {})",
        mblur::ewa::MAX_SUBFRAMES,
        mblur::EwaOptions::default().subframes
    )
}

/// The help of `--spp`, with the library's default.
fn spp_help() -> String {
    format!(
        "stochastic: samples per pixel, a power of two (default {})",
        mblur::stochastic::DEFAULT_SPP
    )
}

#[derive(clap::Args)]
pub(crate) struct MethodArgs {
    /// Method: auto, accum, analytic, prism, stochastic, ewa (auto picks ewa for scenes with
    /// splats, with or without triangles, accum when ewa refuses such a scene, analytic
    /// otherwise; a static opaque scene takes the static path). A flag of another method
    /// than the one that renders is an error.
    #[arg(short, long, default_value = "auto")]
    method: Method,
    /// accum: number of sub-frames (default: automatic, <= 0.5 px of motion between them).
    #[arg(long)]
    times: Option<u32>,
    /// accum: jitter each sub-frame's time inside its stratum (seeded, see --seed).
    #[arg(long)]
    jitter: bool,
    /// analytic: intervals per pixel (0 = exact unbounded lists, the default; K > 0 = at
    /// most K, compressed with the paper's oracle).
    #[arg(long)]
    intervals: Option<u32>,
    /// analytic, prism: arithmetic of the interval chain, f32 (default) or f64.
    #[arg(long)]
    precision: Option<Precision>,
    // Help texts that name a default or a limit are built from the library's constants.
    #[arg(long, help = aa_help())]
    aa: Option<u32>,
    /// accum, analytic, prism with --aa, and stochastic (its area footprint): the pixel
    /// filter, box (the pixel square, the default), tent, gaussian or blackman-harris.
    #[arg(long)]
    filter: Option<mblur::aa::Filter>,
    #[arg(long, help = filter_radius_help())]
    filter_radius: Option<f64>,
    /// analytic, prism: memory budget of the exact interval lists, shared by the rows in
    /// flight (one per thread): bytes, or with a unit (512M, 2G, 1.5GiB). A row that needs
    /// more fails early, naming the row and its intervals (bound the lists with --intervals
    /// K). Default: half the machine's RAM (4 GiB where /proc/meminfo is unreadable).
    #[arg(long, value_parser = parse_size)]
    max_memory: Option<u64>,
    #[arg(long, help = shading_samples_help())]
    shading_samples: Option<mblur::ShadingSamples>,
    #[arg(long, help = shading_tolerance_help())]
    shading_tolerance: Option<f64>,
    /// accum --jitter, stochastic: seed of the random times or the sample pattern (default 0).
    #[arg(long)]
    seed: Option<u64>,
    #[arg(long, help = subframes_help())]
    subframes: Option<u32>,
    /// ewa: visibility, abuffer (A-buffer, §4.4: which surface is in front is exact at every
    /// instant, also where splat surfaces pass through each other; kernels stay fixed per
    /// subframe; the default) or approx (the GPU passes of §5).
    #[arg(long)]
    visibility: Option<VisibilityArg>,
    /// ewa: erf evaluation of the line integrals, full (libm, the default), poly
    /// (Chebyshev) or table.
    #[arg(long)]
    erf: Option<ErfArg>,
    #[arg(long, help = spp_help())]
    spp: Option<u32>,
    /// stochastic: traversal of moving triangles: our, our-exact, our-per-tile, our-fine
    /// (tile tests down to single pixels), bbox, convex, interleave, fallback (OUR with the
    /// §7 fallback to INTERLEAVE; the default).
    #[arg(long)]
    traversal: Option<TraversalChoice>,
    /// stochastic: where the samples lie in their pixel: area (spread over it, spatial
    /// antialiasing; the default) or centre (at the pixel centre, time only, as accum and
    /// analytic sample; a scene where nothing moves then takes the static path).
    #[arg(long)]
    footprint: Option<Footprint>,
    /// stochastic: most samples one pass may hold, counted over the image rounded up to
    /// whole 16-pixel bins (12 bytes a sample; default and maximum 134217728 = 2^27,
    /// 1.5 GiB); more samples per pixel than fit are taken in several passes and averaged.
    #[arg(long)]
    max_pass_samples: Option<u64>,
}

impl MethodArgs {
    /// The flags given, each with the methods that use it.
    fn given(&self) -> Vec<(&'static str, &'static [Method])> {
        use Method::*;
        let flags: [(&'static str, bool, &'static [Method]); 18] = [
            ("--times", self.times.is_some(), &[Accum]),
            ("--jitter", self.jitter, &[Accum]),
            ("--intervals", self.intervals.is_some(), &[Analytic]),
            ("--precision", self.precision.is_some(), &[Analytic, Prism]),
            (
                "--max-memory",
                self.max_memory.is_some(),
                &[Analytic, Prism],
            ),
            ("--aa", self.aa.is_some(), &[Accum, Analytic, Prism]),
            (
                "--filter",
                self.filter.is_some(),
                &[Accum, Analytic, Prism, Stochastic],
            ),
            (
                "--filter-radius",
                self.filter_radius.is_some(),
                &[Accum, Analytic, Prism, Stochastic],
            ),
            (
                "--shading-samples",
                self.shading_samples.is_some(),
                &[Analytic, Prism],
            ),
            (
                "--shading-tolerance",
                self.shading_tolerance.is_some(),
                &[Analytic, Prism],
            ),
            ("--seed", self.seed.is_some(), &[Accum, Stochastic]),
            ("--subframes", self.subframes.is_some(), &[Ewa]),
            ("--visibility", self.visibility.is_some(), &[Ewa]),
            ("--erf", self.erf.is_some(), &[Ewa]),
            ("--spp", self.spp.is_some(), &[Stochastic]),
            ("--traversal", self.traversal.is_some(), &[Stochastic]),
            ("--footprint", self.footprint.is_some(), &[Stochastic]),
            (
                "--max-pass-samples",
                self.max_pass_samples.is_some(),
                &[Stochastic],
            ),
        ];
        flags
            .into_iter()
            .filter(|f| f.1)
            .map(|(name, _, methods)| (name, methods))
            .collect()
    }

    /// The method's options from the flags (defaults where a flag is absent), checked.
    pub(crate) fn options(&self) -> Result<MethodOptions, Error> {
        if self.method != Method::Auto {
            self.check_used_by(self.method)?;
        }
        let seed = self.seed.unwrap_or(0);
        let aa = mblur::aa::Antialiasing {
            samples: self.aa.unwrap_or(if self.method == Method::Auto {
                mblur::aa::AUTO_SAMPLES
            } else {
                1
            }),
            filter: self.filter.unwrap_or_default(),
            radius: self.filter_radius,
        };
        let accum = AccumOptions {
            times: self.times,
            jitter: self.jitter.then_some(seed),
            aa,
        };
        let analytic = AnalyticOptions {
            intervals: self.intervals.unwrap_or(0),
            precision: self.precision.unwrap_or_default(),
            keep_backfaces: false,
            max_memory: Some(self.max_memory.unwrap_or_else(default_max_memory)),
            aa,
            shading: self.shading()?,
        };
        let defaults = EwaOptions::default();
        let ewa = EwaOptions {
            subframes: self.subframes.unwrap_or(defaults.subframes),
            visibility: self.visibility.map_or(defaults.visibility, |v| v.0),
            erf: self.erf.map_or(defaults.erf, |e| e.0),
        };
        let options = match self.method {
            Method::Auto => MethodOptions::Auto(AutoOptions {
                analytic,
                ewa,
                accum,
            }),
            Method::Accum => MethodOptions::Accum(accum),
            Method::Analytic => MethodOptions::Analytic(analytic),
            Method::Prism => MethodOptions::Prism(PrismOptions {
                precision: analytic.precision,
                max_memory: analytic.max_memory,
                aa,
                shading: analytic.shading,
            }),
            Method::Ewa => MethodOptions::Ewa(ewa),
            Method::Stochastic => MethodOptions::Stochastic(StochasticOptions {
                spp: self.spp,
                traversal: self.traversal.unwrap_or_default(),
                seed,
                footprint: self.footprint.unwrap_or_default(),
                filter: aa.filter,
                filter_radius: aa.radius,
                max_pass_samples: self.max_pass_samples,
            }),
        };
        options.validate().map_err(flag_error)?;
        Ok(options)
    }

    /// The shading samples from `--shading-samples` and `--shading-tolerance`.
    fn shading(&self) -> Result<mblur::ShadingSamples, Error> {
        let samples = self.shading_samples.unwrap_or_default();
        match (samples, self.shading_tolerance) {
            (_, None) => Ok(samples),
            (mblur::ShadingSamples::Adaptive { .. }, Some(tolerance)) => {
                Ok(mblur::ShadingSamples::Adaptive { tolerance })
            }
            (other, Some(_)) => Err(Error::Option {
                option: "--shading-tolerance".into(),
                message: format!("is a setting of --shading-samples adaptive, not {other}"),
            }),
        }
    }

    /// An error naming the first flag given that `method` (the method that renders) does
    /// not use.
    pub(crate) fn check_used_by(&self, method: Method) -> Result<(), Error> {
        let Some((flag, users)) = self.given().into_iter().find(|f| !f.1.contains(&method)) else {
            return Ok(());
        };
        let names: Vec<&str> = users.iter().map(|m| m.name()).collect();
        let how = if self.method == Method::Auto {
            format!("auto picked {method} for this scene")
        } else {
            format!("-m {method} was asked for")
        };
        Err(Error::Option {
            option: flag.into(),
            message: format!(
                "is a setting of {} and {how}, which does not use it (pass -m {} to use it)",
                names.join(" and "),
                names[0]
            ),
        })
    }
}

/// The flag of a field of a method's options.
fn flag(setting: &str) -> String {
    format!("--{}", setting.replace('_', "-"))
}

/// A library error about an option's field, named as the flag that sets it.
pub(crate) fn flag_error(e: mblur::Error) -> Error {
    match e {
        mblur::Error::Setting {
            setting, message, ..
        } => Error::Option {
            option: flag(setting),
            message,
        },
        e @ mblur::Error::MemoryBudget { .. } => Error::Option {
            option: "--max-memory".into(),
            message: format!(
                "{e}; bound the lists with --intervals K (K per pixel), use fewer --threads, \
                 or raise --max-memory"
            ),
        },
        other => Error::Render(other),
    }
}

/// Any error of a subcommand, with the library's option fields named as flags.
pub(crate) fn named(e: Error) -> Error {
    match e {
        Error::Render(r) => flag_error(r),
        other => other,
    }
}

/// A size in bytes: a number with an optional unit, K/M/G/T (powers of 1024, with or without
/// `iB`/`B`), e.g. `512M`, `2G`, `1.5GiB`, `1000000`.
pub(crate) fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let scale: u64 = match unit.to_ascii_lowercase().as_str() {
        "" | "b" => 1,
        "k" | "kb" | "kib" => 1 << 10,
        "m" | "mb" | "mib" => 1 << 20,
        "g" | "gb" | "gib" => 1 << 30,
        "t" | "tb" | "tib" => 1 << 40,
        other => {
            return Err(format!(
                "unknown unit `{other}` in `{s}` (use K, M, G or T)"
            ));
        }
    };
    let v: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a size (a number of bytes, or e.g. 512M, 2G)"))?;
    let bytes = v * scale as f64;
    if !(bytes >= 1.0 && bytes < 2f64.powi(63)) {
        return Err(format!("`{s}` must be at least 1 byte and below 8 EiB"));
    }
    Ok(bytes as u64)
}

/// Half the machine's RAM (`MemTotal` of /proc/meminfo), or 4 GiB where that is unreadable:
/// the default `--max-memory`.
pub(crate) fn default_max_memory() -> u64 {
    let total_kib = std::fs::read_to_string("/proc/meminfo").ok().and_then(|m| {
        m.lines()
            .find_map(|l| l.strip_prefix("MemTotal:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
    });
    total_kib.map_or(4 << 30, |k| k.saturating_mul(1024) / 2)
}

#[cfg(test)]
mod tests {
    use super::parse_size;

    #[test]
    fn sizes_parse_with_binary_units() {
        assert_eq!(parse_size("1000"), Ok(1000));
        assert_eq!(parse_size("512M"), Ok(512 << 20));
        assert_eq!(parse_size("2G"), Ok(2 << 30));
        assert_eq!(parse_size("1.5GiB"), Ok(3 << 29));
        assert_eq!(parse_size("64kb"), Ok(64 << 10));
        assert!(parse_size("0").is_err());
        assert!(parse_size("-1G").is_err());
        assert!(parse_size("2X").is_err());
        assert!(parse_size("G").is_err());
        assert!(parse_size("1e30T").is_err());
        assert!(parse_size("nan").is_err());
    }
}
