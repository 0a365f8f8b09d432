//! The `accum` method: N static renders at evenly spaced (or jittered) times, averaged with
//! the shutter response — the ground truth the analytic, prism, stochastic and EWA methods
//! are compared against.
//!
//! The shutter [0, 1] is cut into N equal strata; stratum k is rendered at its midpoint (or
//! at a seeded uniform time inside it with jitter) and weighted by the exact integral of
//! w(t) over the stratum divided by the integral over [0, 1]. Each sub-frame is an ordinary
//! static render ([`crate::static_path`]): near-plane clipping, LESS_EQUAL depth, transparent
//! fragments sorted and blended front to back. Splats are drawn as oriented 16-sided discs
//! of their radius ([`crate::static_path::discs`]; the EWA method filters them with
//! Gaussians instead).

use rand::{RngExt, SeedableRng};
use rayon::prelude::*;

use crate::aa::Antialiasing;
use crate::error::{Error, Result};
use crate::image::Image;
use crate::prepared::{PreparedScene, PreparedTriangle};
use crate::progress::Progress;
use crate::static_path::{Exposure, splats_as_discs};

/// Largest accepted sub-frame count (`AccumOptions::times`).
pub const MAX_TIMES: u32 = 1 << 16;

/// Options of the accumulation method.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AccumOptions {
    /// Number of sub-frames; `None` picks [`auto_times`].
    pub times: Option<u32>,
    /// Seed for jittered times within each stratum; `None` uses stratum midpoints.
    pub jitter: Option<u64>,
    /// Sample positions per pixel and their filter ([`crate::aa`]); one, the pixel centre,
    /// by default.
    pub aa: Antialiasing,
}

impl AccumOptions {
    /// Checks the options: `times`, when given, in 1..=[`MAX_TIMES`].
    pub fn validate(&self) -> Result<()> {
        self.aa.validate()?;
        match self.times {
            Some(n) if n == 0 || n > MAX_TIMES => Err(Error::Setting {
                method: "accum",
                setting: "times",
                message: format!("must be between 1 and {MAX_TIMES}, got {n}"),
            }),
            _ => Ok(()),
        }
    }

    /// One line saying what the method will do for this scene.
    pub fn describe(&self, scene: &PreparedScene) -> String {
        let n = self.times.unwrap_or_else(|| auto_times(scene));
        let how = if self.times.is_some() {
            ""
        } else {
            " (automatic: <= 0.5 px of motion between sub-frames)"
        };
        let jitter = if self.jitter.is_some() {
            ", jittered"
        } else {
            ""
        };
        format!(
            "accum: {n} sub-frame{}{how}{jitter}",
            if n == 1 { "" } else { "s" }
        )
    }
}

/// The largest screen-space displacement (pixels) of any vertex or splat centre over the
/// shutter (vertices behind the eye are ignored).
pub fn max_motion_pixels(scene: &PreparedScene) -> f64 {
    let disp = |a: crate::camera::Vertex2dh, b: crate::camera::Vertex2dh| {
        if a.w > 0.0 && b.w > 0.0 {
            let ((ax, ay), (bx, by)) = (a.screen(), b.screen());
            let d = ((bx - ax).powi(2) + (by - ay).powi(2)).sqrt();
            if d.is_finite() { d } else { 0.0 }
        } else {
            0.0
        }
    };
    let tri = scene
        .triangles
        .par_iter()
        .filter(|t| t.is_moving())
        .map(|t| {
            // Per segment: its displacement spread over the whole shutter.
            let share = (t.span[1] - t.span[0]).max(f64::MIN_POSITIVE);
            (0..3)
                .map(|k| disp(t.open[k], t.close[k]) / share)
                .fold(0.0, f64::max)
        })
        .reduce(|| 0.0, f64::max);
    let spl = scene
        .splats
        .iter()
        .map(|s| disp(s.open, s.close) / (s.span[1] - s.span[0]).max(f64::MIN_POSITIVE))
        .fold(0.0, f64::max);
    tri.max(spl)
}

/// Automatic sub-frame count: one frame for a static scene, otherwise enough that no vertex
/// moves more than half a pixel between sub-frames (at least 16, at most 4096).
pub fn auto_times(scene: &PreparedScene) -> u32 {
    let moving = scene.triangles.iter().any(PreparedTriangle::is_moving)
        || scene.triangles.iter().any(|t| scene.shading_varies(t))
        || scene.splats.iter().any(|s| scene.splat_moves(s));
    if !moving {
        return 1;
    }
    let m = max_motion_pixels(scene);
    ((2.0 * m).ceil() as u32).clamp(16, 4096)
}

/// The sub-frame times and weights (weights sum to 1).
pub fn sample_times(scene: &PreparedScene, n: u32, jitter: Option<u64>) -> Vec<(f64, f64)> {
    let total = scene.shutter.integral(0.0, 1.0);
    let mut rng = jitter.map(rand_pcg::Pcg32::seed_from_u64);
    let nf = f64::from(n);
    (0..n)
        .map(|k| {
            let (a, b) = (f64::from(k) / nf, f64::from(k + 1) / nf);
            let u = rng.as_mut().map_or(0.5, |r| r.random::<f64>());
            (a + (b - a) * u, scene.shutter.integral(a, b) / total)
        })
        .filter(|&(_, w)| w > 0.0)
        .collect()
}

/// One sub-frame: the static render at time `t` ([`crate::static_path::render_at`]).
pub use crate::static_path::render_at as render_static;

/// Renders with N sub-frames (the ground truth). Reports one progress step per sub-frame.
///
/// Static triangles (no 2DH motion over the whole shutter) are rasterised and resolved once
/// into a base layer; per sub-frame only moving triangles are rasterised over it, only the
/// columns they change in each row are resolved again and returned to the base afterwards
/// ([`Exposure`]). Each segment of a curved path is drawn only at the instants of its span
/// and placed on the true path there ([`PreparedScene::corners_at`]), so curved motion is
/// rendered exactly in the limit of many sub-frames.
pub fn render(
    scene: &PreparedScene,
    opts: &AccumOptions,
    progress: &dyn Progress,
) -> Result<Image> {
    let n = opts.times.unwrap_or_else(|| auto_times(scene));
    if n == 0 || n > MAX_TIMES {
        return Err(Error::Setting {
            method: "accum",
            setting: "times",
            message: format!("must be between 1 and {MAX_TIMES}, got {n}"),
        });
    }
    let scene = splats_as_discs(scene);
    let times = sample_times(&scene, n, opts.jitter);
    let (moving, fixed): (Vec<u32>, Vec<u32>) = (0..scene.triangles.len() as u32).partition(|&i| {
        let t = &scene.triangles[i as usize];
        t.is_moving() || !t.is_whole() || scene.shading_varies(t)
    });
    let mut exposure = Exposure::new(&scene);
    progress.start(times.len() as u64, "sub-frames");
    let per_frame = if fixed.is_empty() || times.len() == 1 {
        (0..scene.triangles.len() as u32).collect()
    } else {
        exposure.set_base(&fixed, 0.0);
        moving
    };
    for &(t, w) in &times {
        exposure.add(&per_frame, t, w);
        progress.advance(1);
    }
    progress.finish();
    Ok(exposure.image())
}
