//! Curved motion in preparation: an object's (or splat set's) [`MotionPath`] from its
//! description, the camera's keys, and the times the shutter is cut at for each object and
//! splat set (on its vertices or splat centres).
//!
//! The shutter is cut at every key time of the object and of the camera; a key pair whose
//! rotation turns is cut further into equal segments: a fixed number
//! ([`Segments::Fixed`]), or the fewest that keep every vertex's chord within
//! [`MotionOptions::path_tolerance`] pixels of its true screen path ([`Segments::Auto`]).
//! Each segment is a straight-line problem on its own part of the shutter, which every
//! exact method solves as before.

use glam::{DQuat, DVec3};
use rayon::prelude::*;

use mblur::PreparedScene;
use mblur::camera::{CameraFrame, Lens};
use mblur::motion::{CameraKey, MotionKey, MotionPath, Turn};

use crate::desc::{CameraDesc, MotionDesc, RotateDesc, ScaleDesc, TransformDesc};

/// Largest number of segments one key pair may be cut into.
pub const MAX_SEGMENTS: u32 = 64;

/// Default tolerance of [`Segments::Auto`]: a quarter pixel.
pub const DEFAULT_PATH_TOLERANCE: f64 = 0.25;

/// How many segments a turning key pair is cut into.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Segments {
    /// The fewest that keep every vertex within the path tolerance.
    #[default]
    Auto,
    /// This many (1 ..= [`MAX_SEGMENTS`]).
    Fixed(u32),
}

/// The accuracy knob of curved motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionOptions {
    /// Segments per turning key pair.
    pub segments: Segments,
    /// Largest distance (pixels) between a vertex's chord and its true screen position at
    /// the same instant, for [`Segments::Auto`].
    pub path_tolerance: f64,
}

impl Default for MotionOptions {
    fn default() -> Self {
        MotionOptions {
            segments: Segments::Auto,
            path_tolerance: DEFAULT_PATH_TOLERANCE,
        }
    }
}

impl MotionOptions {
    /// Checks the options; the message names the setting.
    pub fn validate(&self) -> Result<(), String> {
        if let Segments::Fixed(n) = self.segments
            && !(1..=MAX_SEGMENTS).contains(&n)
        {
            return Err(format!(
                "segments must be `auto` or between 1 and {MAX_SEGMENTS}, got {n}"
            ));
        }
        if !(self.path_tolerance > 0.0 && self.path_tolerance.is_finite()) {
            return Err(format!(
                "path tolerance must be a positive number of pixels, got {}",
                self.path_tolerance
            ));
        }
        Ok(())
    }
}

/// One line naming the segments chosen per object and splat set, for those cut into more
/// than one (`None` when every one is one straight segment).
pub fn describe(scene: &PreparedScene, opts: &MotionOptions) -> Option<String> {
    let cut: Vec<String> = scene
        .objects
        .iter()
        .chain(&scene.splat_objects)
        .filter(|o| o.segments > 1)
        .map(|o| format!("{} {}", o.name, o.segments))
        .collect();
    if cut.is_empty() {
        return None;
    }
    let how = match opts.segments {
        Segments::Auto => format!("auto, path tolerance {} px", opts.path_tolerance),
        Segments::Fixed(n) => format!("{n} per turning key pair"),
    };
    Some(format!("motion segments ({how}): {}", cut.join(", ")))
}

/// The rotation of a transform description (identity when absent).
pub(crate) fn rotation(r: Option<&RotateDesc>) -> DQuat {
    r.map_or(DQuat::IDENTITY, |r| {
        DQuat::from_axis_angle(
            DVec3::from_array(r.axis).normalize(),
            r.degrees.to_radians(),
        )
    })
}

/// The per-axis scale of a transform description (1 when absent).
pub(crate) fn scale(s: Option<&ScaleDesc>) -> DVec3 {
    match s {
        None => DVec3::ONE,
        Some(ScaleDesc::Uniform(s)) => DVec3::splat(*s),
        Some(ScaleDesc::PerAxis(s)) => DVec3::from_array(*s),
    }
}

/// The turn between two keys' rotations. Rotations about one axis (or one of them absent)
/// turn by the difference of their angles as given, so 350° turns 350° and several keys
/// spin past 360°; rotations about different axes take the shortest turn (slerp,
/// [`Turn::slerp`]; at exactly 180° the positive way about the relative rotation's axis).
fn turn(a: Option<&RotateDesc>, b: Option<&RotateDesc>) -> Turn {
    let axis = |r: &RotateDesc| DVec3::from_array(r.axis).normalize();
    let turn = |axis: DVec3, degrees: f64| {
        if degrees == 0.0 {
            Turn::NONE
        } else {
            Turn {
                axis,
                angle: degrees.to_radians(),
            }
        }
    };
    match (a, b) {
        (None, None) => Turn::NONE,
        (None, Some(b)) => turn(axis(b), b.degrees),
        (Some(a), None) => turn(axis(a), -a.degrees),
        (Some(a), Some(b)) => {
            let (aa, ab) = (axis(a), axis(b));
            if (aa - ab).length() < 1e-12 {
                turn(aa, b.degrees - a.degrees)
            } else if (aa + ab).length() < 1e-12 {
                turn(aa, -b.degrees - a.degrees)
            } else {
                Turn::slerp(rotation(Some(a)), rotation(Some(b)))
            }
        }
    }
}

/// The motion path of an object placed by `transform` and moving by `motion`, or `None`
/// for `positions_close` (explicit end positions: one straight segment).
pub fn motion_path(
    transform: &Option<TransformDesc>,
    motion: &Option<MotionDesc>,
) -> Option<MotionPath> {
    let m = motion.clone().unwrap_or_default();
    if m.positions_close.is_some() {
        return None;
    }
    let keys: Vec<(f64, TransformDesc)> = match &m.keys {
        Some(keys) => keys.iter().map(|k| (k.t, k.transform())).collect(),
        None => vec![
            (0.0, m.open.clone().unwrap_or_default()),
            (1.0, m.close.clone().unwrap_or_default()),
        ],
    };
    let turns = keys
        .windows(2)
        .map(|w| turn(w[0].1.rotate.as_ref(), w[1].1.rotate.as_ref()))
        .collect();
    Some(MotionPath::new(
        keys.iter()
            .map(|(t, d)| MotionKey {
                t: *t,
                translate: DVec3::from_array(d.translate),
                rotation: rotation(d.rotate.as_ref()),
                scale: scale(d.scale.as_ref()),
            })
            .collect(),
        turns,
        transform
            .as_ref()
            .map_or(glam::DAffine3::IDENTITY, crate::prepare::affine),
    ))
}

/// The camera's keys (empty unless its motion lists `keys`).
pub fn camera_keys(c: &CameraDesc, lens: &Lens) -> Vec<CameraKey> {
    let keys = c.motion.as_ref().and_then(|m| m.keys.as_ref());
    keys.map_or_else(Vec::new, |keys| {
        keys.iter()
            .map(|k| CameraKey {
                t: k.t,
                frame: CameraFrame::new(
                    lens,
                    DVec3::from_array(k.eye.unwrap_or(c.eye)),
                    DVec3::from_array(k.target.unwrap_or(c.target)),
                    DVec3::from_array(k.up.unwrap_or(c.up)),
                ),
            })
            .collect()
    })
}

/// The times (from 0 to 1) the shutter is cut at for an object with object-space vertex
/// `positions` moving on `path`, or a message when [`Segments::Auto`] needs more than
/// [`MAX_SEGMENTS`] in a key pair.
pub fn segment_times(
    scene: &PreparedScene,
    path: Option<&MotionPath>,
    positions: &[DVec3],
    opts: &MotionOptions,
) -> Result<Vec<f64>, String> {
    let mut breaks: Vec<f64> = scene.camera_keys.iter().map(|k| k.t).collect();
    breaks.extend(path.map_or_else(Vec::new, MotionPath::times));
    breaks.extend([0.0, 1.0]);
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut times = vec![0.0];
    for w in breaks.windows(2) {
        let (a, b) = (w[0], w[1]);
        let n = match path {
            Some(p) if turns_within(p, a, b) => match opts.segments {
                Segments::Fixed(n) => n,
                Segments::Auto => auto_count(scene, p, positions, a, b, opts.path_tolerance)?,
            },
            _ => 1,
        };
        for k in 1..=n {
            let u = f64::from(k) / f64::from(n);
            times.push(if k == n { b } else { (1.0 - u) * a + u * b });
        }
    }
    Ok(times)
}

/// True when the key pair of `path` holding `[a, b]` turns.
fn turns_within(path: &MotionPath, a: f64, b: f64) -> bool {
    let mid = 0.5 * (a + b);
    path.keys()
        .windows(2)
        .zip(path.turns())
        .any(|(k, t)| k[0].t <= mid && mid <= k[1].t && t.angle != 0.0)
}

/// The fewest equal segments of `[a, b]` keeping every vertex within `tol` pixels of its
/// true screen position (the error shrinks as segments are added): doubling from one
/// segment until the chords fit, then bisection between the last two counts, so a path
/// that needs few segments (the common case) costs few probes of every vertex.
fn auto_count(
    scene: &PreparedScene,
    path: &MotionPath,
    positions: &[DVec3],
    a: f64,
    b: f64,
    tol: f64,
) -> Result<u32, String> {
    let fits = |n: u32| chord_error_beyond(scene, path, positions, [a, b], n, tol) <= tol;
    let mut hi = 1;
    while hi < MAX_SEGMENTS && !fits(hi) {
        hi = (2 * hi).min(MAX_SEGMENTS);
    }
    if hi == MAX_SEGMENTS && !fits(MAX_SEGMENTS) {
        return Err(format!(
            "the motion between t = {a} and t = {b} needs more than {MAX_SEGMENTS} segments \
             to stay within {tol} px of its path; add keys or raise the path tolerance"
        ));
    }
    // `hi` fits and `lo` (half of it, or 0) does not.
    let mut lo = hi / 2;
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if fits(mid) { hi = mid } else { lo = mid }
    }
    Ok(hi)
}

/// Interior instants per segment at which [`chord_error`] compares chord and path.
const PROBES: u32 = 8;

/// Vertices per parallel task of [`chord_error`].
const CHORD_CHUNK: usize = 512;

/// The largest screen distance (pixels) between a vertex's chord and its true position at
/// the same instant, over `n` equal segments of `[a, b]`, probed at `PROBES` - 1 interior
/// instants per segment. Instants where the vertex is behind the eye are skipped. The
/// vertices are measured in parallel on the caller's rayon pool.
pub fn chord_error(
    scene: &PreparedScene,
    path: &MotionPath,
    positions: &[DVec3],
    a: f64,
    b: f64,
    n: u32,
) -> f64 {
    chord_error_beyond(scene, path, positions, [a, b], n, f64::INFINITY)
}

/// [`chord_error`], or some distance above `cap` as soon as one is found (all that
/// [`auto_count`] asks of a count that does not fit).
fn chord_error_beyond(
    scene: &PreparedScene,
    path: &MotionPath,
    positions: &[DVec3],
    [a, b]: [f64; 2],
    n: u32,
    cap: f64,
) -> f64 {
    // A camera that does not move projects alike at every instant: once, not twice and a
    // blend (the blend of two equal finite projections is that projection exactly).
    let fixed = scene.camera_keys.is_empty() && !scene.camera_moves();
    let at = |t: f64| {
        let m = path.affine(t);
        move |p: DVec3| {
            let q = m.transform_point3(p);
            if fixed {
                scene.camera_open.project(q)
            } else {
                scene.project_at(t, q)
            }
        }
    };
    let mut worst: f64 = 0.0;
    for s in 0..n {
        let t0 = a + (b - a) * f64::from(s) / f64::from(n);
        let t1 = a + (b - a) * f64::from(s + 1) / f64::from(n);
        let (e0, e1) = (at(t0), at(t1));
        let probes: Vec<_> = (1..PROBES)
            .map(|k| {
                let u = f64::from(k) / f64::from(PROBES);
                (u, at(t0 + (t1 - t0) * u))
            })
            .collect();
        // The worst distance over a run of vertices, stopping above `cap`.
        let over = |vertices: &[DVec3]| {
            let mut worst: f64 = 0.0;
            for &p in vertices {
                let (v0, v1) = (e0(p), e1(p));
                for (u, mid) in &probes {
                    let (c, q) = (v0.lerp(v1, *u), mid(p));
                    if c.w > 0.0 && q.w > 0.0 {
                        let ((cx, cy), (qx, qy)) = (c.screen(), q.screen());
                        let d = (cx - qx).hypot(cy - qy);
                        if d.is_finite() {
                            worst = worst.max(d);
                        }
                    }
                }
                if worst > cap {
                    break;
                }
            }
            worst
        };
        worst = worst.max(
            positions
                .par_chunks(CHORD_CHUNK)
                .map(over)
                .reduce(|| 0.0, f64::max),
        );
        if worst > cap {
            break;
        }
    }
    worst
}
