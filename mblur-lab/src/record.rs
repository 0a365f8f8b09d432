//! What a comparison records: the ladder's settings, the reference, each run's outcome and
//! measurements. [`crate::compare`] produces them; [`crate::report`] and [`crate::plot`]
//! write them out.

use mblur::{Image, MethodOptions};
use mblur_scene::segments::Segments;

use crate::metrics::Metrics;

/// One setting of the ladder.
#[derive(Debug, Clone, PartialEq)]
pub struct LadderEntry {
    /// The curve it belongs to in the plot (`analytic`, `stochastic/our`, ...).
    pub series: String,
    /// The setting within the curve (`K=4`, `unbounded`, `16 spp`, ...).
    pub setting: String,
    /// The method and options of the run.
    pub options: MethodOptions,
    /// Segments of curved motion the scene is prepared with for this run; `None` keeps
    /// the scene as prepared for the comparison (automatic segments).
    pub segments: Option<Segments>,
}

impl LadderEntry {
    pub(crate) fn new(
        series: impl Into<String>,
        setting: impl Into<String>,
        options: MethodOptions,
    ) -> Self {
        LadderEntry {
            series: series.into(),
            setting: setting.into(),
            options,
            segments: None,
        }
    }

    /// `series setting`, e.g. `analytic K=4`.
    pub fn label(&self) -> String {
        format!("{} {}", self.series, self.setting)
    }

    /// A file-name-safe form of the label.
    pub fn slug(&self) -> String {
        let mut s = String::new();
        for c in self.label().chars() {
            if c.is_ascii_alphanumeric() {
                s.push(c.to_ascii_lowercase());
            } else if !s.ends_with('-') {
                s.push('-');
            }
        }
        s.trim_matches('-').to_string()
    }
}

/// The reference image and how it was made.
#[derive(Debug, Clone)]
pub struct Reference {
    /// The image.
    pub image: Image,
    /// What rendered it (the method's describe line).
    pub description: String,
    /// Its wall time in seconds (one run).
    pub seconds: f64,
    /// Why the ewa reference was not used for a splat-only scene, if it was not.
    pub note: Option<String>,
}

/// The measurements of a run that rendered.
#[derive(Debug, Clone, PartialEq)]
pub struct RunStats {
    /// Median wall time of the repeats, seconds.
    pub seconds: f64,
    /// How many times it ran.
    pub repeats: u32,
    /// Largest heap growth during any repeat (bytes above the heap before the render:
    /// buffers, primitive lists, the output image); `None` when no [`HeapMeter`](crate::compare::HeapMeter) is given.
    pub heap_bytes: Option<usize>,
    /// Errors against the reference.
    pub metrics: Metrics,
    /// The method's describe line.
    pub description: String,
}

/// What happened to a ladder entry.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// It rendered.
    Done(RunStats),
    /// The method refused the scene or the setting (the reason).
    Skipped(String),
    /// Something else went wrong (the error).
    Failed(String),
}

impl Outcome {
    /// `ok`, `skipped` or `failed`.
    pub fn status(&self) -> &'static str {
        match self {
            Outcome::Done(_) => "ok",
            Outcome::Skipped(_) => "skipped",
            Outcome::Failed(_) => "failed",
        }
    }
}

/// One row of the results.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRecord {
    /// 1-based position in the ladder.
    pub index: usize,
    /// The setting.
    pub entry: LadderEntry,
    /// What happened.
    pub outcome: Outcome,
    /// The side-by-side image file (relative to the output folder), when written.
    pub image_file: Option<String>,
}

/// Scene information printed in the report headers.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneInfo {
    /// The scene's name.
    pub name: String,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Worker threads.
    pub threads: usize,
}
