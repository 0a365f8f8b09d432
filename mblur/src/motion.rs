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
    keys: Vec<MotionKey>,
    /// `turns[i]` turns `keys[i].rotation` into `keys[i + 1].rotation`.
    turns: Vec<Turn>,
    /// The object's placement, applied before the motion.
    place: DAffine3,
    /// Per key: its scale and rotation after the placement, where an [`Arc`] through the
    /// key's pair starts (computed once here rather than per arc).
    bases: Vec<DAffine3>,
}

impl MotionPath {
    /// The path through `keys` (times strictly increasing from 0 to 1) with `turns[i]`
    /// turning `keys[i].rotation` into `keys[i + 1].rotation`, after the placement `place`.
    pub fn new(keys: Vec<MotionKey>, turns: Vec<Turn>, place: DAffine3) -> Self {
        let bases = keys
            .iter()
            .map(|k| {
                DAffine3::from_scale_rotation_translation(k.scale, k.rotation, DVec3::ZERO) * place
            })
            .collect();
        MotionPath {
            keys,
            turns,
            place,
            bases,
        }
    }

    /// The keys, times strictly increasing from 0 to 1.
    pub fn keys(&self) -> &[MotionKey] {
        &self.keys
    }

    /// The turns: `turns()[i]` turns `keys()[i].rotation` into `keys()[i + 1].rotation`.
    pub fn turns(&self) -> &[Turn] {
        &self.turns
    }

    /// The object's placement, applied before the motion.
    pub fn place(&self) -> DAffine3 {
        self.place
    }

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

    /// The path of the points `local` (object space) for times in `[ta, tb]`, set up for
    /// evaluation at many instants, when that range lies in one key pair whose scale does
    /// not change; `None` otherwise (then [`MotionPath::affine`] serves).
    pub fn arc(&self, local: &[DVec3; 3], [ta, tb]: [f64; 2]) -> Option<Arc> {
        let (i, _) = self.pair(ta);
        let (a, b) = (self.keys.get(i)?, self.keys.get(i + 1)?);
        if !(a.t <= ta && ta <= tb && tb <= b.t && b.t > a.t) || a.scale != b.scale {
            return None;
        }
        let base = self.bases.get(i)?;
        let turned = local.map(|p| base.transform_point3(p));
        Some(Arc {
            times: [a.t, b.t],
            turn: self.turns.get(i).copied().unwrap_or(Turn::NONE),
            turned,
            translate: [a.translate, b.translate],
            face: (turned[1] - turned[0]).cross(turned[2] - turned[0]),
        })
    }
}

/// Three points on their arc through one key pair of constant scale ([`MotionPath::arc`]):
/// each point scaled, rotated by the first key and placed once, so an instant costs one
/// turn by Rodrigues' rotation formula and a translation instead of a whole transform. It
/// agrees with [`MotionPath::affine`] up to rounding.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// The key pair's times.
    times: [f64; 2],
    /// The pair's turn.
    turn: Turn,
    /// The points with the first key's scale and rotation and the placement applied.
    turned: [DVec3; 3],
    /// The keys' translations.
    translate: [DVec3; 2],
    /// `(turned[1] - turned[0]) x (turned[2] - turned[0])`: a rotation carries it along.
    face: DVec3,
}

impl Arc {
    /// The normalised time at which the arc's key pair starts.
    pub(crate) fn pair_start(&self) -> f64 {
        self.times[0]
    }

    /// True when normalised time `t` lies in the arc's key pair.
    pub fn holds(&self, t: f64) -> bool {
        self.times[0] <= t && t <= self.times[1]
    }

    /// The rotation (Rodrigues' formula: v cos + (k x v) sin + k (k . v) (1 - cos)) and
    /// the translation at normalised time `t` (clamped to the key pair).
    fn motion_at(&self, t: f64) -> (impl Fn(DVec3) -> DVec3, DVec3) {
        let [ta, tb] = self.times;
        let u = ((t - ta) / (tb - ta)).clamp(0.0, 1.0);
        let (s, c) = (u * self.turn.angle).sin_cos();
        let k = self.turn.axis;
        let shift = self.translate[0] * (1.0 - u) + self.translate[1] * u;
        (
            move |v: DVec3| v * c + k.cross(v) * s + k * (k.dot(v) * (1.0 - c)),
            shift,
        )
    }

    /// The three points at normalised time `t` (clamped to the key pair).
    pub fn at(&self, t: f64) -> [DVec3; 3] {
        let (turn, shift) = self.motion_at(t);
        let p = &self.turned;
        [turn(p[0]) + shift, turn(p[1]) + shift, turn(p[2]) + shift]
    }

    /// The point with weights `bary` (summing to 1) of the three points at normalised time
    /// `t`, and the cross product `(p1 - p0) x (p2 - p0)` of the points then: a rigid turn
    /// carries the weighted point and the cross product, so each costs one rotation
    /// instead of one per point.
    pub fn point_and_face(&self, bary: [f64; 3], t: f64) -> (DVec3, DVec3) {
        let (turn, shift) = self.motion_at(t);
        let p = &self.turned;
        let point = p[0] * bary[0] + p[1] * bary[1] + p[2] * bary[2];
        (turn(point) + shift, turn(self.face))
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
        MotionPath::new(
            vec![
                key(0.0, DQuat::IDENTITY),
                key(1.0, DQuat::from_rotation_z(degrees.to_radians())),
            ],
            vec![Turn {
                axis: DVec3::Z,
                angle: degrees.to_radians(),
            }],
            DAffine3::IDENTITY,
        )
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

    /// The arc's points against the whole transform at dense instants, with a scale, a
    /// placement, a translation and a turn of more than half a circle.
    #[test]
    fn an_arc_follows_the_whole_transform() {
        let key = |t: f64, r: DQuat, x: f64| MotionKey {
            t,
            translate: DVec3::new(x, 0.5, -1.0),
            rotation: r,
            scale: DVec3::new(2.0, 0.5, 1.5),
        };
        let axis = DVec3::new(1.0, 2.0, -0.5).normalize();
        let start = DQuat::from_rotation_x(0.3);
        let path = MotionPath::new(
            vec![
                key(0.0, start, 0.0),
                key(0.4, DQuat::from_axis_angle(axis, 4.0) * start, 3.0),
                key(1.0, DQuat::from_axis_angle(axis, 4.0) * start, 3.0),
            ],
            vec![Turn { axis, angle: 4.0 }, Turn::NONE],
            DAffine3::from_translation(DVec3::new(0.2, -0.1, 0.7)) * DAffine3::from_rotation_y(0.8),
        );
        let local = [
            DVec3::X,
            DVec3::new(0.3, -1.2, 0.4),
            DVec3::new(-2.0, 0.1, 1.0),
        ];
        let arc = path.arc(&local, [0.1, 0.4]).unwrap();
        for k in 0..=1000 {
            let t = 0.4 * f64::from(k) / 1000.0;
            let a = path.affine(t);
            for (p, q) in arc.at(t).iter().zip(local) {
                assert!((*p - a.transform_point3(q)).length() < 1e-12, "{t}");
            }
        }
        // The weighted point and the face normal, against the transformed corners.
        for k in 0..=100 {
            let t = 0.1 + 0.3 * f64::from(k) / 100.0;
            let bary = [0.2 + 0.005 * f64::from(k), 0.5, 0.3 - 0.005 * f64::from(k)];
            let c = arc.at(t);
            let (p, face) = arc.point_and_face(bary, t);
            let want = c[0] * bary[0] + c[1] * bary[1] + c[2] * bary[2];
            let want_face = (c[1] - c[0]).cross(c[2] - c[0]);
            assert!((p - want).length() < 1e-12, "{t}");
            assert!(
                (face - want_face).length() < 1e-11 * want_face.length(),
                "{t}"
            );
        }
        // Ranges across a key or past the pair take the whole transform.
        assert!(path.arc(&local, [0.3, 0.5]).is_none());
        assert!(path.arc(&local, [0.5, 0.9]).is_some());
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
