//! Splat surfaces passing through each other (Heinzle 2010, §4.4) against a dense
//! time-sampling reference: at each of N = 4096 instants the front surface is determined
//! by static EWA splatting of the splats' geometry at that instant (exact ray-plane depths,
//! weights exp(-δ r²), the ternary depth test; `tests/common`, no crate code), and the mean
//! over the instants is the box-shutter integral.
//!
//! The sheets face the camera and move along its axis, each with its own linear depth
//! motion, so every pair of depths is linear in t and enters or leaves the other's depth
//! tolerance at most once on each side and crosses it at most once: at most three
//! discontinuities per pair, each costing the midpoint rule at most one sample. The
//! per-instant weight ratio of two sheets is constant in time (the ray meets each plane at
//! a fixed point of it), so normalising per piece is exact here too, and the tolerance
//! `(3 pairs + 1) / N` is the same for every number of subframes.

mod common;

use common::{pixel_ray, premul, static_ewa_pixel, unpremul};
use ewa_splat::{Camera, KernelParams, RenderSettings, Splat, SplatKey, render};
use glam::DVec3;
use proptest::prelude::*;

/// One pixel looking down -z from (0, 0, 5) along the axis through its centre. Its field
/// of view (0.02 rad) makes a sheet span 5-20 pixels, so the low-pass leaves the axes, and
/// with them the depth tolerance, as in the reference.
fn one_pixel() -> Camera {
    Camera::look_at_perspective(
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::ZERO,
        DVec3::Y,
        0.02,
        0.1,
        100.0,
        1,
        1,
    )
}

/// A sheet: a splat of radius `radius` facing the camera, centred `off` (less than 0.75
/// radii) from the pixel's ray, moving along z from `z0` to `z1` (or static when they are
/// equal). Its depth tolerance is `depth_epsilon` radii.
#[derive(Clone, Copy, Debug)]
struct Sheet {
    radius: f64,
    off: (f64, f64),
    z0: f64,
    z1: f64,
    colour: [f32; 4],
}

impl Sheet {
    fn splat(&self) -> Splat {
        let at = |z| SplatKey::disc(DVec3::new(self.off.0, self.off.1, z), DVec3::Z, self.radius);
        if self.z0 == self.z1 {
            Splat::fixed(at(self.z0), self.colour)
        } else {
            Splat::linear(at(self.z0), at(self.z1), self.colour)
        }
    }
}

fn sheet() -> impl Strategy<Value = Sheet> {
    (
        (0.8f64..1.5, 0.0f64..0.75, 0.0f64..std::f64::consts::TAU),
        -3.0f64..3.0,
        prop_oneof![1 => Just(0.0), 4 => -3.0f64..3.0],
        prop::array::uniform3(0.0f32..1.0),
        prop_oneof![Just(1.0f32), 0.2f32..1.0],
    )
        .prop_map(|((radius, r, a), z0, dz, rgb, alpha)| Sheet {
            radius,
            off: (radius * r * a.cos(), radius * r * a.sin()),
            z0,
            z1: (z0 + dz).clamp(-3.0, 3.0),
            colour: [rgb[0], rgb[1], rgb[2], alpha],
        })
}

const N: usize = 4096;
const BG: [f32; 4] = [0.1, 0.2, 0.3, 1.0];

/// The mean over N instants of static EWA splatting at each instant (straight alpha).
fn dense(c: &Camera, splats: &[Splat], depth_epsilon: f64) -> [f64; 4] {
    let (o, d) = pixel_ray(c, 0.5, 0.5);
    let mut acc = [0.0; 4];
    for k in 0..N {
        let t = (k as f64 + 0.5) / N as f64;
        let p = static_ewa_pixel(splats, t, o, d, 2.0, depth_epsilon, premul(BG));
        for (a, v) in acc.iter_mut().zip(p) {
            *a += v / N as f64;
        }
    }
    unpremul(acc)
}

proptest! {
    /// Two or three sheets with random linear depth motions (static ones included),
    /// colours, alphas, radii, offsets, depth tolerances and 1-16 subframes, against the dense
    /// per-instant reference: the error bound does not depend on the subframes. (Static
    /// sheets take a minimum temporal axis of 1e-7 of their radius here, so that their
    /// kernels' depth does not sweep; the default 1e-3 is measured in the README.)
    #[test]
    fn crossing_sheets_match_dense_per_instant_visibility(
        sheets in proptest::collection::vec(sheet(), 2..4),
        depth_epsilon in prop_oneof![Just(0.0f64), 0.02f64..0.8],
        subframes in 1u32..17,
    ) {
        let c = one_pixel();
        let splats: Vec<Splat> = sheets.iter().map(Sheet::splat).collect();
        let settings = RenderSettings {
            subframes,
            depth_epsilon,
            kernel: KernelParams {
                min_a3_rel: 1e-7,
                ..KernelParams::default()
            },
            ..RenderSettings::default()
        };
        let got = render(&c, &splats, BG, &settings).unwrap().pixels[0];
        let want = dense(&c, &splats, depth_epsilon);
        let pairs = sheets.len() * (sheets.len() - 1) / 2;
        let tol = (3 * pairs + 1) as f64 / N as f64 + 1e-5;
        for k in 0..4 {
            prop_assert!(
                (f64::from(got[k]) - want[k]).abs() <= tol,
                "channel {k}: got {got:?}, dense {want:?}, tol {tol}"
            );
        }
    }
}

/// The dense reference is not too coarse to tell the piece-midpoint rule from the exact
/// one: a red sheet crossing a static green one at t = 0.3 with no depth tolerance gives
/// 0.3 red within 1/N; deciding the whole exposure at its middle would give 0.
#[test]
fn reference_resolves_a_crossing_to_one_sample() {
    let c = one_pixel();
    let red = Sheet {
        radius: 1.0,
        off: (0.0, 0.0),
        z0: 1.0,
        z1: -1.0 / 0.3 + 1.0,
        colour: [1.0, 0.0, 0.0, 1.0],
    };
    let green = Sheet {
        radius: 1.0,
        off: (0.2, 0.0),
        z0: 0.0,
        z1: 0.0,
        colour: [0.0, 1.0, 0.0, 1.0],
    };
    let splats = [red.splat(), green.splat()];
    let want = dense(&c, &splats, 0.0);
    assert!((want[0] - 0.3).abs() <= 1.0 / N as f64, "{want:?}");
    for subframes in [1, 3, 8] {
        let settings = RenderSettings {
            subframes,
            depth_epsilon: 0.0,
            kernel: KernelParams {
                min_a3_rel: 1e-7,
                ..KernelParams::default()
            },
            ..RenderSettings::default()
        };
        let got = render(&c, &splats, BG, &settings).unwrap().pixels[0];
        assert!(
            (f64::from(got[0]) - 0.3).abs() < 1e-6,
            "{subframes}: {got:?}"
        );
        assert!(
            (f64::from(got[1]) - 0.7).abs() < 1e-6,
            "{subframes}: {got:?}"
        );
    }
}
