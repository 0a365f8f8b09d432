//! With zero motion the renderer equals ordinary static EWA splatting (ray-plane
//! intersection, Gaussian weights, ternary depth test, normalisation) of the same splats.

mod common;

use common::{deep, max_diff, mean_diff, supersample};
use ewa_splat::{Camera, KernelParams, RenderSettings, Splat, SplatKey, Visibility, render};
use glam::DVec3;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

const BG: [f32; 4] = [0.05, 0.1, 0.2, 1.0];

/// A tilted, gently curved sheet of overlapping splats with varied colours and a smaller
/// sheet in front of it (two surfaces, so the ternary depth test matters).
fn scene(seed: u64, n: usize) -> Vec<Splat> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let u = (i as f64 + 0.5) / n as f64 * 2.0 - 1.0;
            let v = (j as f64 + 0.5) / n as f64 * 2.0 - 1.0;
            let c = DVec3::new(1.6 * u, 1.6 * v, 0.3 * u + 0.1 * v * v);
            let normal = DVec3::new(-0.3, -0.2 * v, 1.0);
            let col = [
                rng.random::<f32>(),
                rng.random::<f32>(),
                rng.random::<f32>(),
                1.0,
            ];
            out.push(Splat::fixed(SplatKey::disc(c, normal, 2.4 / n as f64), col));
        }
    }
    for k in 0..4 {
        let c = DVec3::new(-0.3 + 0.25 * k as f64, 0.2, 1.2);
        out.push(Splat::fixed(
            SplatKey::disc(c, DVec3::new(0.1, 0.0, 1.0), 0.25),
            [1.0, 1.0, 0.2, 1.0],
        ));
    }
    out
}

fn camera() -> Camera {
    Camera::look_at_perspective(
        DVec3::new(0.4, 0.3, 5.0),
        DVec3::ZERO,
        DVec3::Y,
        0.8,
        0.1,
        100.0,
        40,
        32,
    )
}

#[test]
fn zero_motion_equals_static_ewa_abuffer_and_approx() {
    let n = if deep() { 10 } else { 6 };
    let splats = scene(7, n);
    let cam = camera();
    let kernel = KernelParams {
        min_a3_rel: 1e-7,
        ..KernelParams::default()
    };
    let reference = supersample(&cam, &splats, BG, kernel.delta, 1.0, 1);
    // The scene is not trivial: the sheet, the front surface and the background all show.
    let is = |p: &[f64; 4], c: [f64; 3]| (0..3).all(|k| (p[k] - c[k]).abs() < 1e-6);
    let yellow = reference.iter().filter(|p| is(p, [1.0, 1.0, 0.2])).count();
    let bg = reference.iter().filter(|p| is(p, [0.05, 0.1, 0.2])).count();
    assert!(
        yellow > 20 && bg > 20 && yellow + bg + 200 < reference.len(),
        "{yellow} {bg}"
    );
    for visibility in [Visibility::ABuffer, Visibility::Approximate] {
        for subframes in [1, 3] {
            let settings = RenderSettings {
                kernel,
                visibility,
                subframes,
                ..RenderSettings::default()
            };
            let f = render(&cam, &splats, BG, &settings).unwrap();
            let err = max_diff(&f.pixels, &reference);
            assert!(err < 1e-4, "{visibility:?} x{subframes}: max error {err}");
        }
    }
}

#[test]
fn default_safeguards_stay_close_to_static_ewa() {
    // With the default minimum a3 (1e-3 of the splat radius) the slab has a small
    // thickness, so weights differ by O(1e-3) and a few pixels on cut-off edges differ.
    let splats = scene(11, 6);
    let cam = camera();
    let settings = RenderSettings::default();
    let reference = supersample(&cam, &splats, BG, settings.kernel.delta, 1.0, 1);
    let f = render(&cam, &splats, BG, &settings).unwrap();
    let mean = mean_diff(&f.pixels, &reference);
    assert!(mean < 2e-3, "mean error {mean}");
}
