//! Lights and where they are at an instant: directions and positions given at keys over
//! the shutter (times strictly increasing from 0 to 1), interpolated as object motion is
//! ([`crate::motion`]): a direction turns at a constant rate along the great circle to the
//! next key's ([`Turn::between`]; at exactly 180° through the side of world up), a position
//! moves on the straight line. A light that moves only between shutter open and close is
//! the two-key case; a still light has one key.

use glam::DVec3;

use crate::motion::{Turn, key_pair};

/// A light's direction or position at normalised shutter time `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightKey {
    /// Normalised shutter time in \[0, 1\].
    pub t: f64,
    /// Unit travel direction (directional lights) or world position (point lights).
    pub value: DVec3,
}

/// A light, possibly moving over the shutter through its keys.
#[derive(Debug, Clone, PartialEq)]
pub enum Light {
    /// Light from everywhere: adds `albedo × colour`.
    Ambient {
        /// Linear RGB.
        colour: [f64; 3],
    },
    /// Parallel light travelling along a unit direction (from the light towards the scene).
    Directional {
        /// Unit travel directions at the keys (one key: a still light).
        directions: Vec<LightKey>,
        /// Linear RGB.
        colour: [f64; 3],
        /// Irradiance scale.
        intensity: f64,
    },
    /// A point light with inverse-square falloff.
    Point {
        /// World positions at the keys (one key: a still light).
        positions: Vec<LightKey>,
        /// Linear RGB.
        colour: [f64; 3],
        /// Intensity: the irradiance at unit distance.
        intensity: f64,
    },
}

/// Keys at shutter open and close, or one key when both agree.
fn ends(open: DVec3, close: DVec3) -> Vec<LightKey> {
    let mut keys = vec![LightKey {
        t: 0.0,
        value: open,
    }];
    if close != open {
        keys.push(LightKey {
            t: 1.0,
            value: close,
        });
    }
    keys
}

impl Light {
    /// A directional light turning from unit direction `open` at shutter open to `close`
    /// at shutter close (two keys).
    pub fn directional(open: DVec3, close: DVec3, colour: [f64; 3], intensity: f64) -> Light {
        Light::Directional {
            directions: ends(open, close),
            colour,
            intensity,
        }
    }

    /// A point light moving from `open` at shutter open to `close` at shutter close (two
    /// keys).
    pub fn point(open: DVec3, close: DVec3, colour: [f64; 3], intensity: f64) -> Light {
        Light::Point {
            positions: ends(open, close),
            colour,
            intensity,
        }
    }

    /// True when the light changes over the shutter.
    pub fn moves(&self) -> bool {
        match self {
            Light::Ambient { .. } => false,
            Light::Directional {
                directions: keys, ..
            }
            | Light::Point {
                positions: keys, ..
            } => keys.windows(2).any(|w| w[0].value != w[1].value),
        }
    }

    /// The unit travel direction of a directional light at normalised time `t`: between two
    /// keys the shortest turn from one to the other at a constant rate ([`Turn::between`]),
    /// exactly the key's direction at a key. `None` for other lights.
    pub fn direction_at(&self, t: f64) -> Option<DVec3> {
        let Light::Directional { directions, .. } = self else {
            return None;
        };
        let (i, u) = key_pair(directions, |k| k.t, t);
        let a = directions.get(i)?.value;
        Some(match directions.get(i + 1) {
            Some(b) if u >= 1.0 => b.value,
            Some(b) if u > 0.0 => Turn::between(a, b.value).turn(a, u),
            _ => a,
        })
    }

    /// The world position of a point light at normalised time `t`: linear between two
    /// keys, exactly the key's position at a key. `None` for other lights.
    pub fn position_at(&self, t: f64) -> Option<DVec3> {
        let Light::Point { positions, .. } = self else {
            return None;
        };
        let (i, u) = key_pair(positions, |k| k.t, t);
        let a = positions.get(i)?.value;
        Some(match positions.get(i + 1) {
            Some(b) => a * (1.0 - u) + b.value * u,
            None => a,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn keys(values: &[(f64, DVec3)]) -> Vec<LightKey> {
        values
            .iter()
            .map(|&(t, value)| LightKey { t, value })
            .collect()
    }

    /// A direction keyed at 0°, 120° and 270° in the XY plane follows the unit circle at a
    /// constant rate per key pair (the angle from the trigonometric parametrisation, not
    /// from the code's quaternions), each pair the short way (120° -> 270° is +150°).
    #[test]
    fn keyed_direction_turns_on_the_great_circle_at_a_constant_rate() {
        let at = |deg: f64| DVec3::new(deg.to_radians().cos(), deg.to_radians().sin(), 0.0);
        let light = Light::Directional {
            directions: keys(&[(0.0, at(0.0)), (0.25, at(120.0)), (1.0, at(270.0))]),
            colour: [1.0; 3],
            intensity: 1.0,
        };
        for k in 0..=400 {
            let t = f64::from(k) / 400.0;
            let want = if t <= 0.25 {
                at(120.0 * t / 0.25)
            } else {
                at(120.0 + 150.0 * (t - 0.25) / 0.75)
            };
            let got = light.direction_at(t).unwrap();
            assert!((got - want).length() < 1e-12, "t {t}: {got} vs {want}");
        }
        assert_eq!(light.direction_at(0.25), Some(at(120.0)));
        assert_eq!(light.direction_at(1.0), Some(at(270.0)));
    }

    /// Exactly opposite directions: the documented choice, checked with Rodrigues' formula
    /// at every instant (a half circle through the side of world up).
    #[test]
    fn a_half_turn_passes_through_the_side_of_world_up() {
        let light = Light::directional(DVec3::X, -DVec3::X, [1.0; 3], 1.0);
        for k in 0..=64 {
            let u = f64::from(k) / 64.0;
            let (s, c) = (u * PI).sin_cos();
            let want = DVec3::new(c, s, 0.0);
            let got = light.direction_at(u).unwrap();
            assert!((got - want).length() < 1e-12, "{u}: {got}");
        }
        // Along Y itself, about Y × X = -Z: through +X.
        let mid = Turn::between(DVec3::Y, -DVec3::Y).turn(DVec3::Y, 0.5);
        assert!((mid - DVec3::X).length() < 1e-12, "{mid}");
    }

    #[test]
    fn keyed_position_is_linear_between_keys_and_open_close_is_two_keys() {
        let p = Light::Point {
            positions: keys(&[
                (0.0, DVec3::ZERO),
                (0.5, DVec3::new(2.0, 0.0, 0.0)),
                (1.0, DVec3::new(2.0, 4.0, 0.0)),
            ]),
            colour: [1.0; 3],
            intensity: 1.0,
        };
        assert_eq!(p.position_at(0.25), Some(DVec3::new(1.0, 0.0, 0.0)));
        assert_eq!(p.position_at(0.75), Some(DVec3::new(2.0, 2.0, 0.0)));
        assert!(p.moves());
        let two = Light::point(DVec3::ZERO, DVec3::X, [1.0; 3], 1.0);
        assert_eq!(two.position_at(0.3), Some(DVec3::X * 0.3));
        let still = Light::point(DVec3::X, DVec3::X, [1.0; 3], 1.0);
        assert!(!still.moves() && still.position_at(0.7) == Some(DVec3::X));
    }
}
