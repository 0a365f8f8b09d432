//! Temporal visibility (§4.4), the approximate GPU passes (§5) and motion-path subframes
//! (§5.5) against temporal supersampling of static EWA splatting (box shutter).

mod common;

use common::{max_diff, supersample};
use ewa_splat::{Camera, RenderSettings, Splat, SplatKey, Visibility, render};
use glam::DVec3;

const BG: [f32; 4] = [0.1, 0.1, 0.1, 1.0];

fn cam(w: u32, h: u32) -> Camera {
    Camera::look_at_perspective(
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::ZERO,
        DVec3::Y,
        0.8,
        0.1,
        100.0,
        w,
        h,
    )
}

fn approx() -> RenderSettings {
    RenderSettings {
        visibility: Visibility::Approximate,
        ..RenderSettings::default()
    }
}

#[test]
fn moving_splat_occluding_a_static_one_matches_supersampling() {
    let c = cam(32, 20);
    let splats = vec![
        Splat::fixed(
            SplatKey::disc(DVec3::ZERO, DVec3::Z, 0.7),
            [1.0, 0.0, 0.0, 1.0],
        ),
        Splat::moving_disc(
            DVec3::new(-1.0, 0.1, 1.5),
            DVec3::new(1.8, 0.0, 0.0),
            DVec3::Z,
            0.3,
            [0.0, 1.0, 0.0, 1.0],
        ),
    ];
    let reference = supersample(&c, &splats, BG, 2.0, 1.0, 2048);
    let a = render(&c, &splats, BG, &RenderSettings::default()).unwrap();
    let err = max_diff(&a.pixels, &reference);
    assert!(err < 3e-3, "A-buffer max error {err}");
    // The GPU passes cannot separate the time the green splat hides the red one: visibly wrong.
    let g = render(&c, &splats, BG, &approx()).unwrap();
    let gerr = max_diff(&g.pixels, &reference);
    assert!(gerr > 0.1, "approximate passes error {gerr}");
}

#[test]
fn briefly_visible_at_start_and_end_fig9() {
    // Two fast splats cross the centre pixel only near shutter open and near shutter close.
    let c = cam(33, 9);
    let col = [1.0, 1.0, 1.0, 1.0];
    let splats = vec![
        Splat::moving_disc(
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(-4.0, 0.0, 0.0),
            DVec3::Z,
            0.6,
            col,
        ),
        Splat::moving_disc(
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(-4.0, 0.0, 0.0),
            DVec3::Z,
            0.6,
            col,
        ),
    ];
    let reference = supersample(&c, &splats, BG, 2.0, 1.0, 4096);
    let a = render(&c, &splats, BG, &RenderSettings::default()).unwrap();
    let g = render(&c, &splats, BG, &approx()).unwrap();
    let centre = 4 * 33 + 16;
    let covered = (reference[centre][0] - 0.1) / 0.9;
    assert!(
        covered > 0.2 && covered < 0.35,
        "reference coverage {covered}"
    );
    assert!((a.pixels[centre][0] as f64 - reference[centre][0]).abs() < 2e-3);
    // t_min = 0, t_max = 1: the approximation calls the whole exposure covered.
    assert!(
        (g.pixels[centre][0] - 1.0).abs() < 1e-6,
        "{:?}",
        g.pixels[centre]
    );
    assert!(max_diff(&a.pixels, &reference) < 3e-3);
}

#[test]
fn approximate_passes_equal_the_abuffer_for_a_single_splat() {
    let c = cam(24, 16);
    let splats = vec![Splat::moving_disc(
        DVec3::new(-0.6, -0.2, 0.0),
        DVec3::new(1.2, 0.5, 0.3),
        DVec3::new(0.2, 0.0, 1.0),
        0.3,
        [0.3, 0.7, 0.9, 1.0],
    )];
    let a = render(&c, &splats, BG, &RenderSettings::default()).unwrap();
    let g = render(&c, &splats, BG, &approx()).unwrap();
    let gf: Vec<[f64; 4]> = g.pixels.iter().map(|p| p.map(|v| v as f64)).collect();
    assert!(max_diff(&a.pixels, &gf) < 1e-5);
    assert!(a.stats.fragments > 10, "{:?}", a.stats);
}

#[test]
fn subframes_follow_a_curved_path() {
    // A splat sweeping a half circle, given as 9 keys; 8 subframes reproduce the path.
    let c = cam(32, 32);
    let keys: Vec<SplatKey> = (0..9)
        .map(|i| {
            let a = std::f64::consts::PI * i as f64 / 8.0;
            SplatKey::disc(
                DVec3::new(1.0 * a.cos(), 1.0 * a.sin() - 0.4, 0.0),
                DVec3::Z,
                0.25,
            )
        })
        .collect();
    let splats = vec![Splat {
        keys,
        colour: [1.0, 0.6, 0.1, 1.0],
        span: [0.0, 1.0],
    }];
    let reference = supersample(&c, &splats, BG, 2.0, 1.0, 2048);
    let fine = render(
        &c,
        &splats,
        BG,
        &RenderSettings {
            subframes: 8,
            ..RenderSettings::default()
        },
    )
    .unwrap();
    let coarse = render(
        &c,
        &splats,
        BG,
        &RenderSettings {
            subframes: 1,
            ..RenderSettings::default()
        },
    )
    .unwrap();
    let fine_err = max_diff(&fine.pixels, &reference);
    let coarse_err = max_diff(&coarse.pixels, &reference);
    assert!(fine_err < 3e-3, "8 subframes: {fine_err}");
    assert!(coarse_err > 0.2, "1 subframe (chord): {coarse_err}");
    // the approximate passes with subframes stay close for a single splat too
    let g = render(
        &c,
        &splats,
        BG,
        &RenderSettings {
            subframes: 8,
            visibility: Visibility::Approximate,
            ..RenderSettings::default()
        },
    )
    .unwrap();
    assert!(max_diff(&g.pixels, &reference) < 3e-3);
}

#[test]
fn gaussian_shutter_weights_time_like_weighted_supersampling() {
    // The Fig. 9 pixel under the paper's exp(-t'^2) shutter: the early and late visits
    // weigh less than under the box shutter.
    let c = cam(33, 9);
    let col = [1.0, 1.0, 1.0, 1.0];
    let splats = vec![
        Splat::moving_disc(DVec3::ZERO, DVec3::new(-4.0, 0.0, 0.0), DVec3::Z, 0.6, col),
        Splat::moving_disc(
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(-4.0, 0.0, 0.0),
            DVec3::Z,
            0.6,
            col,
        ),
    ];
    let settings = RenderSettings {
        shutter: ewa_splat::Shutter::Gaussian,
        ..RenderSettings::default()
    };
    let f = render(&c, &splats, BG, &settings).unwrap();
    let (o, d) = common::pixel_ray(&c, 16.5, 4.5);
    let n = 8192;
    let (mut acc, mut wsum) = (0.0, 0.0);
    for k in 0..n {
        let t = (k as f64 + 0.5) / n as f64;
        let w = (-(2.0 * t - 1.0f64).powi(2)).exp();
        let p = common::static_ewa_pixel(&splats, t, o, d, 2.0, 1.0, common::premul(BG));
        acc += w * p[0];
        wsum += w;
    }
    let want = acc / wsum;
    let got = f.pixels[4 * 33 + 16][0] as f64;
    assert!((got - want).abs() < 1e-3, "{got} vs {want}");
    let boxed = render(&c, &splats, BG, &RenderSettings::default()).unwrap();
    assert!(
        boxed.pixels[4 * 33 + 16][0] as f64 > got + 0.02,
        "the Gaussian shutter de-weights the ends"
    );
}
