//! Frame sequences of `mblur render`: `--frames`, `--frame`, `--fps`, `--shutter-angle`,
//! `--shutter-position`, `--overwrite`, the `#` run of an output name, and the shutter
//! window of each frame on a glTF animation's timeline.
//!
//! Frame f's nominal instant is (f - 1) / fps seconds, so frame 1 is at 0. The shutter is
//! open for (angle / 360) / fps seconds: from the nominal instant (`start`), centred on it
//! (`centre`), or ending at it (`end`).

use std::path::{Path, PathBuf};

use mblur_scene::Error;

/// Most frames one `--frames` list may hold.
pub(crate) const MAX_FRAMES: usize = 1_000_000;

/// Where the shutter opens relative to a frame's nominal instant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum ShutterPosition {
    /// Opens at the frame's instant.
    Start,
    /// Centred on the frame's instant.
    #[value(alias = "center")]
    Centre,
    /// Closes at the frame's instant.
    End,
}

/// The frame flags of `mblur render`.
#[derive(clap::Args, Debug)]
pub(crate) struct FrameArgs {
    /// Frames to render from a glTF animation: ranges `A-B`, optional step `A-BxS`, and
    /// single frames, comma-separated (`1-240`, `1-240x2,300`). The output name needs a
    /// run of `#` for the frame number (`-o out_####.exr`).
    #[arg(long)]
    pub frames: Option<String>,
    /// Render only frame N (of --frames when given: a render-farm task, such as a Slurm
    /// array's $SLURM_ARRAY_TASK_ID).
    #[arg(long)]
    pub frame: Option<u32>,
    /// Frames per second of the animation timeline.
    #[arg(long, default_value_t = 24.0)]
    pub fps: f64,
    /// Shutter angle in degrees: the exposure is angle / 360 of a frame (0 < angle <= 360).
    #[arg(long, default_value_t = 180.0)]
    pub shutter_angle: f64,
    /// Where the shutter opens: at the frame's instant (start), centred on it, or ending
    /// at it. Frame f's instant is (f - 1) / fps seconds.
    #[arg(long, value_enum, default_value = "start")]
    pub shutter_position: ShutterPosition,
    /// Render frames whose output file exists (skipped by default, so a killed job resumes).
    #[arg(long)]
    pub overwrite: bool,
    /// glTF: the camera (a camera node's or camera's name; default the first).
    #[arg(long)]
    pub camera: Option<String>,
    /// glTF: the animation (name or index; default the first).
    #[arg(long)]
    pub animation: Option<String>,
}

fn opt(option: &str, message: impl Into<String>) -> Error {
    Error::Option {
        option: option.into(),
        message: message.into(),
    }
}

/// Parses a frame list: comma-separated `N`, `A-B` or `A-BxS` (A <= B, S >= 1), in order,
/// duplicates removed.
pub(crate) fn parse_frames(spec: &str) -> Result<Vec<u32>, Error> {
    let bad = |m: String| opt("--frames", m);
    let num = |s: &str, part: &str| {
        s.trim()
            .parse::<u32>()
            .map_err(|_| bad(format!("`{part}`: `{s}` is not a frame number (0 or more)")))
    };
    let mut out = Vec::new();
    for part in spec.split(',') {
        let (range, step) = match part.split_once('x') {
            Some((r, s)) => (r, num(s, part)?),
            None => (part, 1),
        };
        if step == 0 {
            return Err(bad(format!("`{part}`: the step must be 1 or more")));
        }
        let (a, b) = match range.split_once('-') {
            Some((a, b)) => (num(a, part)?, num(b, part)?),
            None if part.contains('x') => {
                return Err(bad(format!("`{part}`: a step needs a range (A-BxS)")));
            }
            None => {
                let n = num(range, part)?;
                (n, n)
            }
        };
        if a > b {
            return Err(bad(format!(
                "`{part}`: the range runs backwards ({a} > {b})"
            )));
        }
        let count = (u64::from(b) - u64::from(a)) / u64::from(step) + 1;
        if out.len() as u64 + count > MAX_FRAMES as u64 {
            return Err(bad(format!("more than {MAX_FRAMES} frames")));
        }
        out.extend((a..=b).step_by(step as usize));
    }
    let mut seen = std::collections::HashSet::new();
    out.retain(|f| seen.insert(*f));
    Ok(out)
}

impl FrameArgs {
    /// True when any frame flag other than the defaults is given.
    pub(crate) fn sequence_requested(&self) -> bool {
        self.frames.is_some() || self.frame.is_some()
    }

    /// Checks fps and shutter angle.
    pub(crate) fn check(&self) -> Result<(), Error> {
        if !(self.fps > 0.0 && self.fps.is_finite()) {
            return Err(opt(
                "--fps",
                format!("must be a positive number, got {}", self.fps),
            ));
        }
        let a = self.shutter_angle;
        if !(a > 0.0 && a <= 360.0) {
            return Err(opt(
                "--shutter-angle",
                format!("must be in (0, 360] degrees, got {a}"),
            ));
        }
        Ok(())
    }

    /// The frames to render: --frame alone, --frames, or --frame picked from --frames.
    pub(crate) fn list(&self) -> Result<Vec<u32>, Error> {
        match (&self.frames, self.frame) {
            (None, None) => Ok(vec![1]),
            (None, Some(n)) => Ok(vec![n]),
            (Some(s), None) => parse_frames(s),
            (Some(s), Some(n)) => {
                if parse_frames(s)?.contains(&n) {
                    Ok(vec![n])
                } else {
                    Err(opt("--frame", format!("frame {n} is not in --frames {s}")))
                }
            }
        }
    }

    /// The shutter window in seconds of frame `f`.
    pub(crate) fn window(&self, f: u32) -> [f64; 2] {
        let at = (f64::from(f) - 1.0) / self.fps;
        let open = self.shutter_angle / 360.0 / self.fps;
        match self.shutter_position {
            ShutterPosition::Start => [at, at + open],
            ShutterPosition::Centre => [at - 0.5 * open, at + 0.5 * open],
            ShutterPosition::End => [at - open, at],
        }
    }
}

/// The output file of frame `f`: the last run of `#` in the file name replaced by the
/// frame number, zero-padded to the run's length (`out_####.exr`, 7 -> `out_0007.exr`).
pub(crate) fn output_for(pattern: &Path, f: u32) -> PathBuf {
    let name = pattern
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let Some(end) = name.rfind('#') else {
        return pattern.to_path_buf();
    };
    let start = name[..=end].trim_end_matches('#').len();
    let width = end + 1 - start;
    let numbered = format!("{}{f:0width$}{}", &name[..start], &name[end + 1..]);
    pattern.with_file_name(numbered)
}

/// True when the output name holds a `#` run for the frame number.
pub(crate) fn has_pattern(pattern: &Path) -> bool {
    pattern
        .file_name()
        .is_some_and(|n| n.to_string_lossy().contains('#'))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_lists_parse_ranges_steps_and_singles() {
        assert_eq!(parse_frames("1-3").unwrap(), vec![1, 2, 3]);
        assert_eq!(parse_frames("1-9x4,20,2").unwrap(), vec![1, 5, 9, 20, 2]);
        assert_eq!(parse_frames("3,3-4").unwrap(), vec![3, 4]);
        for (bad, says) in [
            ("5-2", "runs backwards"),
            ("1-4x0", "step must be 1"),
            ("a-3", "not a frame number"),
            ("", "not a frame number"),
            ("-3", "not a frame number"),
            ("0-4000000000", "more than"),
        ] {
            let e = parse_frames(bad).unwrap_err().to_string();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn outputs_number_the_last_hash_run() {
        let p = |s: &str, f| output_for(Path::new(s), f).display().to_string();
        assert_eq!(p("out_####.exr", 7), "out_0007.exr");
        assert_eq!(p("d/f#.png", 12), "d/f12.png");
        assert_eq!(p("a#b_##.exr", 3), "a#b_03.exr");
        assert_eq!(p("plain.exr", 3), "plain.exr");
    }

    #[test]
    fn windows_follow_the_shutter_position() {
        let mut a = FrameArgs {
            frames: None,
            frame: None,
            fps: 24.0,
            shutter_angle: 180.0,
            shutter_position: ShutterPosition::Start,
            overwrite: false,
            camera: None,
            animation: None,
        };
        assert_eq!(a.window(1), [0.0, 1.0 / 48.0]);
        assert_eq!(a.window(25), [1.0, 1.0 + 1.0 / 48.0]);
        a.shutter_position = ShutterPosition::Centre;
        assert_eq!(a.window(1), [-1.0 / 96.0, 1.0 / 96.0]);
        a.shutter_position = ShutterPosition::End;
        assert_eq!(a.window(2), [1.0 / 24.0 - 1.0 / 48.0, 1.0 / 24.0]);
    }
}
