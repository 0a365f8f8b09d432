//! glTF animations: channels read and checked once, evaluated at any time (LINEAR, STEP,
//! CUBICSPLINE), node transforms and world matrices at a time, and the instants a shutter
//! window is sampled at.

use glam::{DMat4, DQuat, DVec3};

use ::gltf::Document;
use ::gltf::accessor::Dimensions;
use ::gltf::animation::{Interpolation, Property};

use super::data::{Buffers, read};

/// Samples per key interval of a curve that keys cannot follow exactly (a CUBICSPLINE
/// channel, a transform under an animated parent, a skin): the interval between two
/// sampled instants is cut into this many equal parts.
pub const CURVE_SAMPLES: usize = 8;

/// What a channel animates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Node translation.
    Translation,
    /// Node rotation (unit quaternion x, y, z, w).
    Rotation,
    /// Node scale.
    Scale,
    /// Morph-target weights of the node's mesh.
    Weights,
}

/// One animation channel, read and checked.
#[derive(Debug, Clone)]
pub struct Channel {
    /// Index of the animated node.
    pub node: usize,
    /// The animated property.
    pub target: Target,
    /// Interpolation between keys.
    pub interpolation: Interpolation,
    /// Key times in seconds (strictly increasing).
    pub times: Vec<f64>,
    /// Values, `width` per element; CUBICSPLINE keys hold in-tangent, value, out-tangent.
    pub values: Vec<f64>,
    /// Components per value (3, 4, or the number of morph targets).
    pub width: usize,
}

/// The channels of one animation.
#[derive(Debug, Clone, Default)]
pub struct Animation {
    /// Its name (or `animations[i]`).
    pub name: String,
    /// Its channels.
    pub channels: Vec<Channel>,
}

impl Animation {
    /// Reads animation `index` of `doc`; the error names the channel and problem.
    pub fn read(doc: &Document, buffers: &Buffers, index: usize) -> Result<Animation, String> {
        let Some(anim) = doc.animations().nth(index) else {
            return Err(format!("has no animations[{index}]"));
        };
        let name = anim
            .name()
            .map_or_else(|| format!("animations[{index}]"), str::to_string);
        let mut channels = Vec::new();
        for (ci, ch) in anim.channels().enumerate() {
            let at = format!("animation \"{name}\" channel {ci}");
            let s = ch.sampler();
            let (times, _) = read(
                buffers,
                &s.input(),
                &[Dimensions::Scalar],
                &format!("{at} input"),
            )?;
            if times.is_empty() {
                return Err(format!("{at}: has no keys"));
            }
            if times.windows(2).any(|w| w[1] <= w[0]) {
                return Err(format!("{at}: key times must strictly increase"));
            }
            let target = match ch.target().property() {
                Property::Translation => Target::Translation,
                Property::Rotation => Target::Rotation,
                Property::Scale => Target::Scale,
                Property::MorphTargetWeights => Target::Weights,
            };
            let dims: &[Dimensions] = match target {
                Target::Rotation => &[Dimensions::Vec4],
                Target::Weights => &[Dimensions::Scalar],
                _ => &[Dimensions::Vec3],
            };
            let (values, n) = read(buffers, &s.output(), dims, &format!("{at} output"))?;
            let per_key = if s.interpolation() == Interpolation::CubicSpline {
                3
            } else {
                1
            };
            let keys = times.len() * per_key;
            let width = match target {
                Target::Weights => values.len() / keys,
                _ => n,
            };
            if width == 0 || values.len() != keys * width {
                return Err(format!(
                    "{at}: {} output values do not match {} keys ({:?})",
                    values.len(),
                    times.len(),
                    s.interpolation()
                ));
            }
            channels.push(Channel {
                node: ch.target().node().index(),
                target,
                interpolation: s.interpolation(),
                times,
                values,
                width,
            });
        }
        Ok(Animation { name, channels })
    }

    /// The time of the last key of any channel (0 without channels).
    pub fn duration(&self) -> f64 {
        self.channels
            .iter()
            .filter_map(|c| c.times.last().copied())
            .fold(0.0, f64::max)
    }
}

impl Channel {
    /// Value element `k` (its middle part for CUBICSPLINE), `part` 0 in-tangent, 1 value,
    /// 2 out-tangent.
    fn element(&self, k: usize, part: usize) -> &[f64] {
        let w = self.width;
        let i = if self.interpolation == Interpolation::CubicSpline {
            (3 * k + part) * w
        } else {
            k * w
        };
        self.values.get(i..i + w).unwrap_or_default()
    }

    /// The value at time `t` (seconds); `left` takes the limit from the left, which
    /// differs from the value at `t` only at a STEP key. Before the first key the first
    /// value holds, after the last the last.
    pub fn at(&self, t: f64, left: bool) -> Vec<f64> {
        let n = self.times.len();
        let last = n.saturating_sub(1);
        let next = if left {
            self.times.iter().position(|&k| k >= t)
        } else {
            self.times.iter().position(|&k| k > t)
        };
        let k = match next {
            None => return self.element(last, 1).to_vec(),
            Some(0) => return self.element(0, 1).to_vec(),
            Some(j) => j - 1,
        };
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        let s = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        let (a, b) = (self.element(k, 1), self.element(k + 1, 1));
        let mut v: Vec<f64> = match self.interpolation {
            Interpolation::Step => return a.to_vec(),
            Interpolation::Linear if self.target == Target::Rotation => {
                return slerp(a, b, s).to_vec();
            }
            Interpolation::Linear => a
                .iter()
                .zip(b)
                .map(|(a, b)| a * (1.0 - s) + b * s)
                .collect(),
            Interpolation::CubicSpline => {
                let (d, s2, s3) = (t1 - t0, s * s, s * s * s);
                let out_a = self.element(k, 2);
                let in_b = self.element(k + 1, 0);
                (0..self.width)
                    .map(|i| {
                        let g = |x: &[f64]| x.get(i).copied().unwrap_or(0.0);
                        (2.0 * s3 - 3.0 * s2 + 1.0) * g(a)
                            + (s3 - 2.0 * s2 + s) * d * g(out_a)
                            + (-2.0 * s3 + 3.0 * s2) * g(b)
                            + (s3 - s2) * d * g(in_b)
                    })
                    .collect()
            }
        };
        if self.target == Target::Rotation {
            v = quat(&v).normalize().to_array().to_vec();
        }
        v
    }

    /// True when the channel jumps at some instant inside `(t0, t1]` (a STEP key whose
    /// value differs from the previous one).
    pub fn jumps_within(&self, t0: f64, t1: f64) -> bool {
        self.interpolation == Interpolation::Step
            && self
                .times
                .iter()
                .enumerate()
                .skip(1)
                .any(|(k, &t)| t > t0 && t <= t1 && self.element(k, 1) != self.element(k - 1, 1))
    }

    /// True when the channel jumps exactly at `t` (a STEP key changing the value).
    pub fn jumps_at(&self, t: f64) -> bool {
        let k = self.times.iter().position(|&k| k == t);
        self.interpolation == Interpolation::Step
            && k.is_some_and(|k| k > 0 && self.element(k, 1) != self.element(k - 1, 1))
    }
}

/// A quaternion from 4 values (x, y, z, w); identity when short.
pub fn quat(v: &[f64]) -> DQuat {
    match v {
        [x, y, z, w, ..] => DQuat::from_xyzw(*x, *y, *z, *w),
        _ => DQuat::IDENTITY,
    }
}

/// Shortest-path spherical interpolation of two quaternions given as 4 values.
fn slerp(a: &[f64], b: &[f64], s: f64) -> [f64; 4] {
    let (a, mut b) = (quat(a).normalize(), quat(b).normalize());
    if a.dot(b) < 0.0 {
        b = -b;
    }
    a.slerp(b, s).normalize().to_array()
}

/// The node hierarchy of a glTF scene with the animation applied.
#[derive(Debug, Clone)]
pub struct Rig {
    /// Parent of each node (`None` for roots and nodes outside the scene).
    pub parents: Vec<Option<usize>>,
    /// Rest translation, rotation and scale of each node.
    pub rest: Vec<(DVec3, DQuat, DVec3)>,
    /// Rest morph weights of each node (the node's, else its mesh's).
    pub weights: Vec<Vec<f64>>,
    /// The animation (empty without one).
    pub animation: Animation,
}

impl Rig {
    /// The local transform of node `n` at `t` (limit from the left when `left`).
    pub fn local(&self, n: usize, t: f64, left: bool) -> DMat4 {
        let (mut tr, mut r, mut s) = self.rest.get(n).copied().unwrap_or_default();
        for c in self.animation.channels.iter().filter(|c| c.node == n) {
            let v = c.at(t, left);
            let v3 = || match v.as_slice() {
                [x, y, z, ..] => DVec3::new(*x, *y, *z),
                _ => DVec3::ZERO,
            };
            match c.target {
                Target::Translation => tr = v3(),
                Target::Rotation => r = quat(&v).normalize(),
                Target::Scale => s = v3(),
                Target::Weights => {}
            }
        }
        DMat4::from_scale_rotation_translation(s, r, tr)
    }

    /// The world matrix of node `n` at `t`: its local transform after its ancestors'.
    pub fn world(&self, n: usize, t: f64, left: bool) -> DMat4 {
        let mut m = self.local(n, t, left);
        let mut at = n;
        // The hierarchy was checked acyclic; the bound only guards the loop.
        for _ in 0..self.parents.len() {
            match self.parents.get(at).copied().flatten() {
                Some(p) => {
                    m = self.local(p, t, left) * m;
                    at = p;
                }
                None => break,
            }
        }
        m
    }

    /// The morph weights of node `n` at `t`.
    pub fn weights_at(&self, n: usize, t: f64, left: bool) -> Vec<f64> {
        let mut w = self.weights.get(n).cloned().unwrap_or_default();
        for c in self.animation.channels.iter().filter(|c| c.node == n) {
            if c.target == Target::Weights {
                w = c.at(t, left);
            }
        }
        w
    }

    /// Node `n` and its ancestors.
    pub fn chain(&self, n: usize) -> Vec<usize> {
        let mut out = vec![n];
        let mut at = n;
        while let Some(p) = self.parents.get(at).copied().flatten() {
            if out.len() > self.parents.len() {
                break;
            }
            out.push(p);
            at = p;
        }
        out
    }

    /// The channels that move any of `nodes`.
    pub fn channels_of<'a>(&'a self, nodes: &'a [usize]) -> impl Iterator<Item = &'a Channel> {
        self.animation
            .channels
            .iter()
            .filter(|c| nodes.contains(&c.node))
    }

    /// The instants (seconds) at which anything depending on `nodes` is sampled in the
    /// window `[t0, t1]`: both ends, every key of their channels inside, and
    /// [`CURVE_SAMPLES`] parts per interval when `dense` or some channel is CUBICSPLINE.
    /// A key where a STEP channel jumps is listed twice (the limit from the left, then
    /// the value from there on).
    pub fn sample_times(&self, nodes: &[usize], t0: f64, t1: f64, dense: bool) -> Vec<(f64, bool)> {
        let channels: Vec<&Channel> = self.channels_of(nodes).collect();
        let mut times = vec![t0, t1];
        for c in &channels {
            times.extend(c.times.iter().copied().filter(|&t| t > t0 && t < t1));
        }
        times.sort_by(f64::total_cmp);
        times.dedup();
        let dense = dense
            || channels
                .iter()
                .any(|c| c.interpolation == Interpolation::CubicSpline);
        let mut out = Vec::new();
        for (i, &t) in times.iter().enumerate() {
            let jump = i > 0 && channels.iter().any(|c| c.jumps_at(t));
            if jump {
                out.push((t, true));
            }
            out.push((t, false));
            if let (true, Some(&next)) = (dense, times.get(i + 1)) {
                for k in 1..CURVE_SAMPLES {
                    let u = k as f64 / CURVE_SAMPLES as f64;
                    out.push(((1.0 - u) * t + u * next, false));
                }
            }
        }
        out
    }
}
