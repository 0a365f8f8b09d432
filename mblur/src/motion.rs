//! Curved motion: an object's true path through motion keys, and the camera's keys.
//!
//! An object's motion is a list of keys (times strictly increasing from 0 to 1), each a
//! scale, a rotation and a translation applied after the object's placement. Between two
//! keys the translation and the scale are linear in time and the rotation turns at a
//! constant rate about one axis ([`Turn`]): the path of a vertex is an arc, not a chord.
//! Renderers that handle straight-line motion exactly cut this path into segments whose
//! ends lie on it ([`PreparedTriangle::span`](crate::PreparedTriangle::span)); `accum`
//! evaluates the path itself ([`crate::PreparedScene::corners_at`]).
//!
//! The camera's keys are poses; between two of them a point's 2DH position is the linear
//! blend of its projections with the two poses, which for a static point is the same
//! linear 2DH motion as a camera moving between shutter open and close.

use glam::{DAffine3, DQuat, DVec3};

use crate::camera::{CameraFrame, Vertex2dh};

/// One key of an object's motion: the transform (scale, then rotate, then translate) at
/// normalised time `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionKey {
    /// Normalised shutter time in \[0, 1\].
    pub t: f64,
    /// Translation.
    pub translate: DVec3,
    /// Rotation.
    pub rotation: DQuat,
    /// Per-axis scale.
    pub scale: DVec3,
}

/// The rotation between two consecutive keys: a turn by `angle` radians about the unit
/// `axis`, at a constant rate, applied on top of the first key's rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turn {
    /// Unit axis (any unit vector when `angle` is 0).
    pub axis: DVec3,
    /// Angle in radians; may exceed π (a spin of 350° turns 350°, not -10°).
    pub angle: f64,
}

impl Turn {
    /// No rotation.
    pub const NONE: Turn = Turn {
        axis: DVec3::Z,
        angle: 0.0,
    };

    /// The shortest turn from rotation `a` to rotation `b` (quaternion slerp). At exactly
    /// 180° both directions are equally short; the turn then goes the positive way about
    /// the axis of `b · a⁻¹` as glam reports it.
    pub fn slerp(a: DQuat, b: DQuat) -> Turn {
        let mut q = (b * a.inverse()).normalize();
        if q.w < 0.0 {
            q = -q;
        }
        let (axis, angle) = q.to_axis_angle();
        if angle.abs() < 1e-15 || !axis.is_finite() {
            Turn::NONE
        } else {
            Turn { axis, angle }
        }
    }

    /// The shortest turn taking unit direction `a` to unit direction `b` (spherical linear
    /// interpolation of directions), about `a × b`. At exactly 180° every axis normal to
    /// `a` is equally short; the turn then goes about `a × Y` (the direction passes through
    /// the side of world up), or about `a × X` when `a` is along ±Y. `Turn::NONE` when the
    /// directions agree.
    pub fn between(a: DVec3, b: DVec3) -> Turn {
        let c = a.cross(b);
        let (s, d) = (c.length(), a.dot(b));
        if s > 0.0 && s.is_finite() {
            return Turn {
                axis: c / s,
                angle: s.atan2(d),
            };
        }
        if d >= 0.0 || !d.is_finite() {
            return Turn::NONE;
        }
        let up = a.cross(DVec3::Y);
        let axis = if up.length_squared() > 0.0 {
            up
        } else {
            a.cross(DVec3::X)
        };
        Turn {
            axis: axis.normalize_or(DVec3::Z),
            angle: std::f64::consts::PI,
        }
    }

    /// Unit direction `a` turned by the fraction `u` of this turn.
    pub fn turn(&self, a: DVec3, u: f64) -> DVec3 {
        if self.angle == 0.0 {
            a
        } else {
            DQuat::from_axis_angle(self.axis, u * self.angle) * a
        }
    }
}

/// The key pair `(i, i + 1)` of `keys` (times strictly increasing, read by `time`) holding
/// time `t`, and the fraction `u` ∈ \[0, 1\] of the way from key `i` to key `i + 1` (`t`
/// before the first key gives the first pair at 0, after the last the last pair at 1).
/// `(0, 0.0)` for fewer than two keys.
pub fn key_pair<K>(keys: &[K], time: impl Fn(&K) -> f64, t: f64) -> (usize, f64) {
    let n = keys.len().saturating_sub(1).max(1);
    let i = keys
        .iter()
        .skip(1)
        .position(|k| t < time(k))
        .unwrap_or(n - 1)
        .min(n - 1);
    match (keys.get(i), keys.get(i + 1)) {
        (Some(a), Some(b)) => (i, ((t - time(a)) / (time(b) - time(a))).clamp(0.0, 1.0)),
        _ => (0, 0.0),
    }
}

/// An object's motion through its keys: `keys.len() - 1` key pairs, one [`Turn`] each.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionPath {
    /// The keys, times strictly increasing from 0 to 1.
    pub keys: Vec<MotionKey>,
    /// `turns[i]` turns `keys[i].rotation` into `keys[i + 1].rotation`.
    pub turns: Vec<Turn>,
    /// The object's placement, applied before the motion.
    pub place: DAffine3,
}

impl MotionPath {
    /// The key pair holding time `t` and the fraction `u` of the way through it.
    fn pair(&self, t: f64) -> (usize, f64) {
        key_pair(&self.keys, |k| k.t, t)
    }

    /// The whole transform (motion after placement) at normalised time `t`.
    pub fn affine(&self, t: f64) -> DAffine3 {
        let (i, u) = self.pair(t);
        let Some(a) = self.keys.get(i) else {
            return self.place;
        };
        let b = self.keys.get(i + 1).unwrap_or(a);
        let turn = self.turns.get(i).copied().unwrap_or(Turn::NONE);
        // At the pair's ends the key's own rotation, so a key is reached exactly.
        let rotation = if u >= 1.0 {
            b.rotation
        } else {
            DQuat::from_axis_angle(turn.axis, u * turn.angle) * a.rotation
        };
        // (1 - u) a + u b: exact at both ends.
        let lerp = |a: DVec3, b: DVec3| a * (1.0 - u) + b * u;
        let motion = DAffine3::from_scale_rotation_translation(
            lerp(a.scale, b.scale),
            rotation,
            lerp(a.translate, b.translate),
        );
        motion * self.place
    }

    /// True when some key pair turns: the vertices' paths are arcs.
    pub fn is_curved(&self) -> bool {
        self.turns.iter().any(|t| t.angle != 0.0)
    }

    /// The key times.
    pub fn times(&self) -> Vec<f64> {
        self.keys.iter().map(|k| k.t).collect()
    }
}

/// One camera key: the pose at normalised time `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraKey {
    /// Normalised shutter time in \[0, 1\].
    pub t: f64,
    /// The pose.
    pub frame: CameraFrame,
}

/// The 2DH position of world point `p` at normalised time `t` for a camera with `keys`
/// (times strictly increasing from 0 to 1): the blend of its projections with the two poses
/// around `t`, linear in time.
pub fn project_at(keys: &[CameraKey], t: f64, p: DVec3) -> Vertex2dh {
    let (i, u) = key_pair(keys, |k| k.t, t);
    match (keys.get(i), keys.get(i + 1)) {
        (Some(a), Some(b)) => {
            if u <= 0.0 {
                a.frame.project(p)
            } else if u >= 1.0 {
                b.frame.project(p)
            } else {
                a.frame.project(p).lerp(b.frame.project(p), u)
            }
        }
        (Some(a), None) => a.frame.project(p),
        _ => Vertex2dh::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spin(degrees: f64) -> MotionPath {
        let key = |t: f64, r: DQuat| MotionKey {
            t,
            translate: DVec3::ZERO,
            rotation: r,
            scale: DVec3::ONE,
        };
        MotionPath {
            keys: vec![
                key(0.0, DQuat::IDENTITY),
                key(1.0, DQuat::from_rotation_z(degrees.to_radians())),
            ],
            turns: vec![Turn {
                axis: DVec3::Z,
                angle: degrees.to_radians(),
            }],
            place: DAffine3::IDENTITY,
        }
    }

    #[test]
    fn a_spin_follows_the_arc_and_reaches_each_key() {
        let path = spin(350.0);
        for k in 0..=64 {
            let t = f64::from(k) / 64.0;
            let p = path.affine(t).transform_point3(DVec3::X);
            let a = (350.0 * t).to_radians();
            assert!(
                (p - DVec3::new(a.cos(), a.sin(), 0.0)).length() < 1e-12,
                "{t}"
            );
        }
        // The last key's own rotation, not the turn's rounding of it.
        let end = path.affine(1.0);
        let want = glam::DAffine3::from_quat(DQuat::from_rotation_z(350f64.to_radians()));
        assert_eq!(end, want);
    }

    #[test]
    fn slerp_takes_the_short_way_and_180_degrees_goes_positive() {
        let t = Turn::slerp(DQuat::IDENTITY, DQuat::from_rotation_z(350f64.to_radians()));
        assert!((t.axis * t.angle - DVec3::Z * (-10f64).to_radians()).length() < 1e-12);
        let h = Turn::slerp(
            DQuat::IDENTITY,
            DQuat::from_rotation_z(std::f64::consts::PI),
        );
        assert!(
            (h.angle - std::f64::consts::PI).abs() < 1e-12 && h.axis.z > 0.0,
            "{h:?}"
        );
    }
}
