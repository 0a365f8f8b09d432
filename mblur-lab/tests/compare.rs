//! `mblur compare` and its metrics: the metrics against hand-computed values and a
//! brute-force SSIM from the definition (Wang et al. 2004, Eq. 13 and 17); an interrupted
//! comparison keeps what it gathered. (A tiny comparison run through the command, writing
//! every file with one row per ladder entry, and bad input failing clearly, are in
//! `mblur-cli/tests/compare.rs`.)

use std::sync::atomic::{AtomicBool, Ordering};

use mblur::{Image, TraversalChoice};
use mblur_lab::compare::{self, CompareOptions, Event, LadderSize, Outcome};
use mblur_lab::metrics::{self, Metrics, SSIM_K1, SSIM_K2, SSIM_WINDOW};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

fn noise_image(w: u32, h: u32, seed: u64) -> Image {
    let mut rng = Pcg64::seed_from_u64(seed);
    Image {
        width: w,
        height: h,
        pixels: (0..w * h)
            .map(|_| [0; 3].map(|_: u8| rng.random_range(0.1f32..0.9)))
            .collect(),
    }
}

#[test]
fn psnr_of_a_uniform_offset_is_known() {
    // Every channel off by 1/64 (exact in f32): MSE = 2^-12, PSNR = 120 log10(2) dB.
    let a = noise_image(20, 13, 1);
    let mut b = a.clone();
    for p in &mut b.pixels {
        for c in p.iter_mut() {
            *c = (f64::from(*c) + 1.0 / 64.0) as f32;
        }
    }
    let m = Metrics::of(&b, &a).unwrap();
    let offset: f64 = 1.0 / 64.0;
    // f32 rounding of the shifted values: at most half an ulp of 1.0 per channel.
    let tol = f64::from(f32::EPSILON);
    assert!((m.rmse - offset).abs() < tol, "{}", m.rmse);
    assert!((m.max_abs - offset).abs() < tol, "{}", m.max_abs);
    let want_psnr = 120.0 * 2f64.log10();
    assert!(
        (m.psnr - want_psnr).abs() < 1e-3,
        "{} vs {want_psnr}",
        m.psnr
    );
    assert!(m.ssim.unwrap() < 1.0);
    // 10 log10(1 / 0.01) = 20 dB exactly.
    assert_eq!(metrics::psnr_from_mse(0.01), 20.0);
}

#[test]
fn metrics_of_two_pixels_by_hand() {
    let a = Image::filled(2, 1, [0.0; 3]);
    let mut b = a.clone();
    b.pixels[0] = [0.5, 0.0, 0.0];
    b.pixels[1] = [0.0, 0.25, 0.0];
    let m = Metrics::of(&b, &a).unwrap();
    // (0.25 + 0.0625) / 6.
    assert_eq!(m.mse, 0.3125 / 6.0);
    assert_eq!(m.max_abs, 0.5);
    assert_eq!(m.ssim, None, "smaller than the 11 x 11 window");
    assert!(Metrics::of(&a, &Image::filled(1, 2, [0.0; 3])).is_none());
}

#[test]
fn identical_images_have_infinite_psnr_and_ssim_one() {
    let a = noise_image(40, 23, 2);
    let m = Metrics::of(&a, &a).unwrap();
    assert_eq!(m.mse, 0.0);
    assert_eq!(m.psnr, f64::INFINITY);
    assert_eq!(m.max_abs, 0.0);
    assert!((m.ssim.unwrap() - 1.0).abs() < 1e-12);
}

#[test]
fn ssim_of_two_constant_images_is_the_luminance_term() {
    // Zero variance: SSIM = (2 a b + C1) / (a^2 + b^2 + C1) (Eq. 13 with the C2 / C2 factor).
    let (a, b) = (0.2, 0.3);
    let (w, h) = (15, 12);
    let x = vec![a; w * h];
    let y = vec![b; w * h];
    let c1 = SSIM_K1 * SSIM_K1;
    let want = (2.0 * a * b + c1) / (a * a + b * b + c1); // 0.1201 / 0.1301
    assert!((want - 0.1201 / 0.1301).abs() < 1e-15);
    let got = metrics::ssim_gray(&x, &y, w, h).unwrap();
    assert!((got - want).abs() < 1e-12, "{got} vs {want}");
}

/// SSIM from the definition: for every window position, the Gaussian-weighted means,
/// variances and covariance summed directly over the 11 x 11 window (2-D weights
/// exp(-r^2 / 2σ^2) normalised over the window), then Eq. 13, then the mean.
fn ssim_brute_force(x: &[f64], y: &[f64], w: usize, h: usize) -> f64 {
    let r = SSIM_WINDOW / 2;
    let mut weights = vec![0.0; SSIM_WINDOW * SSIM_WINDOW];
    for j in 0..SSIM_WINDOW {
        for i in 0..SSIM_WINDOW {
            let (dx, dy) = (i as f64 - r as f64, j as f64 - r as f64);
            weights[j * SSIM_WINDOW + i] = (-(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5)).exp();
        }
    }
    let total: f64 = weights.iter().sum();
    let (c1, c2) = (SSIM_K1 * SSIM_K1, SSIM_K2 * SSIM_K2);
    let mut sum = 0.0;
    let mut count = 0;
    for oy in 0..=h - SSIM_WINDOW {
        for ox in 0..=w - SSIM_WINDOW {
            let at = |v: &[f64], i: usize, j: usize| v[(oy + j) * w + ox + i];
            let (mut mx, mut my) = (0.0, 0.0);
            for j in 0..SSIM_WINDOW {
                for i in 0..SSIM_WINDOW {
                    let g = weights[j * SSIM_WINDOW + i] / total;
                    mx += g * at(x, i, j);
                    my += g * at(y, i, j);
                }
            }
            let (mut vx, mut vy, mut cxy) = (0.0, 0.0, 0.0);
            for j in 0..SSIM_WINDOW {
                for i in 0..SSIM_WINDOW {
                    let g = weights[j * SSIM_WINDOW + i] / total;
                    let (dx, dy) = (at(x, i, j) - mx, at(y, i, j) - my);
                    vx += g * dx * dx;
                    vy += g * dy * dy;
                    cxy += g * dx * dy;
                }
            }
            sum += ((2.0 * mx * my + c1) * (2.0 * cxy + c2))
                / ((mx * mx + my * my + c1) * (vx + vy + c2));
            count += 1;
        }
    }
    sum / f64::from(count)
}

#[test]
fn ssim_matches_the_definition_summed_directly() {
    let mut rng = Pcg64::seed_from_u64(7);
    for (w, h) in [(11, 11), (19, 14), (32, 25)] {
        let x: Vec<f64> = (0..w * h).map(|_| rng.random_range(0.0..1.0)).collect();
        // Distortions: noise, a brightness offset, a contrast change.
        let noisy: Vec<f64> = x
            .iter()
            .map(|v| (v + rng.random_range(-0.2..0.2)).clamp(0.0, 1.0))
            .collect();
        let shifted: Vec<f64> = x.iter().map(|v| v * 0.8 + 0.15).collect();
        for y in [&noisy, &shifted, &x] {
            let want = ssim_brute_force(&x, y, w, h);
            let got = metrics::ssim_gray(&x, y, w, h).unwrap();
            assert!((got - want).abs() < 1e-10, "{w}x{h}: {got} vs {want}");
        }
    }
}

#[test]
fn ssim_falls_as_noise_grows_and_is_symmetric() {
    let mut rng = Pcg64::seed_from_u64(9);
    let (w, h) = (40, 30);
    let x: Vec<f64> = (0..w * h).map(|_| rng.random_range(0.2..0.8)).collect();
    let n: Vec<f64> = (0..w * h).map(|_| rng.random_range(-1.0..1.0)).collect();
    let mut last = 1.0 + 1e-12;
    for amp in [0.0, 0.02, 0.05, 0.1, 0.2] {
        let y: Vec<f64> = x.iter().zip(&n).map(|(a, b)| a + amp * b).collect();
        let s = metrics::ssim_gray(&x, &y, w, h).unwrap();
        let back = metrics::ssim_gray(&y, &x, w, h).unwrap();
        assert!((s - back).abs() < 1e-12);
        assert!(s < last, "amplitude {amp}: {s} !< {last}");
        last = s;
    }
    assert!(last < 0.9);
}

#[test]
fn interrupted_compare_keeps_the_runs_gathered() {
    let prepared = integration_tests::builtin("crossing-quads", 32, 18);
    let dir = tempfile::tempdir().unwrap();
    let options = CompareOptions {
        reference_times: 64,
        ladder: LadderSize::Small,
        traversals: vec![TraversalChoice::Our],
        threads: Some(1),
        ..Default::default()
    };
    let stop = AtomicBool::new(false);
    let mut seen = 0;
    let result = compare::compare(
        &prepared,
        None,
        "crossing-quads",
        &options,
        dir.path(),
        None,
        &stop,
        &mut |ev| {
            if let Event::Done(_) = ev {
                seen += 1;
                // Ctrl-C during the second run.
                if seen == 2 {
                    stop.store(true, Ordering::SeqCst);
                }
            }
        },
    )
    .unwrap();
    assert!(result.interrupted);
    assert_eq!(result.records.len(), 2);
    assert!(result.total > 2);
    let rows = integration_tests::csv_rows(dir.path());
    assert_eq!(rows.len(), 2);
    // No heap meter in this process: the figure says so instead of guessing.
    assert!(
        rows.iter().all(|r| r[4] != "ok" || r[7] == "n/a"),
        "{rows:?}"
    );
    for f in ["results.md", "plot.svg", "plot.png", "reference.png"] {
        assert!(dir.path().join(f).is_file(), "{f}");
    }
    let md = std::fs::read_to_string(dir.path().join("results.md")).unwrap();
    assert!(md.contains(&format!("2 of {} runs done", result.total)));
    for r in &result.records {
        if let Outcome::Done(s) = &r.outcome {
            assert!(s.metrics.rmse.is_finite());
        }
    }
}

/// The segments ladder: analytic with 1, 2, 4, 8, 16, 32 and automatic segments on a scene that
/// turns; nothing on one that only translates. On `spinning-wheel` the 1-segment run is
/// measurably worse than the automatic one.
#[test]
fn segments_ladder_runs_on_curved_scenes_only() {
    let options = CompareOptions {
        ladder: LadderSize::Small,
        methods: vec![mblur::Method::Analytic],
        reference_times: 256,
        repeat_budget: std::time::Duration::ZERO,
        max_repeats: 1,
        ..CompareOptions::default()
    };
    let mut scene = mblur_scene::Scene::builtin("spinning-wheel").unwrap();
    scene.set_size(Some(48), Some(36)).unwrap();
    let prepared = scene.prepare().unwrap();
    let ladder = compare::segments_ladder(&prepared, &options);
    let settings: Vec<&str> = ladder.iter().map(|e| e.setting.as_str()).collect();
    assert_eq!(
        settings,
        [
            "1 segment",
            "2 segments",
            "4 segments",
            "8 segments",
            "16 segments",
            "32 segments",
            "auto"
        ]
    );
    let flat = integration_tests::builtin("crossing-quads", 16, 12);
    assert!(compare::segments_ladder(&flat, &options).is_empty());
    let dir = tempfile::tempdir().unwrap();
    let stop = AtomicBool::new(false);
    let done = compare::compare(
        &prepared,
        Some(&scene),
        "spinning-wheel",
        &options,
        dir.path(),
        None,
        &stop,
        &mut |_| {},
    )
    .unwrap();
    let rmse = |setting: &str| {
        done.records
            .iter()
            .find(|r| r.entry.series == "analytic/segments" && r.entry.setting == setting)
            .and_then(|r| match &r.outcome {
                Outcome::Done(s) => Some(s.metrics.rmse),
                _ => None,
            })
            .unwrap_or_else(|| panic!("{setting} did not run"))
    };
    let (one, auto) = (rmse("1 segment"), rmse("auto"));
    assert!(one > 3.0 * auto, "1 segment {one}, auto {auto}");
}
