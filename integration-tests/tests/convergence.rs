//! Error falls as the accuracy knob grows, measured against the ground truth:
//! - the stochastic method (raster-hier + tmsnet samples, a box filter over pixel area and
//!   shutter) against accum supersampled 8x8 per pixel at 512 sub-frames, over
//!   spp = 1, 4, 16, 64, averaged over seeds: the fitted log-log slope is at least as steep as
//!   1/sqrt(spp) (the (t, m, s)-net samples are stratified, so they converge faster);
//! - the analytic method with K intervals per pixel (Gribel 2010 §5.2, the oracle of Eq. 19)
//!   against accum at 512 sub-frames, K = 1, 2, 4, 8, 16 and unbounded (0);
//! - the fence, Gribel's own failure case (Gribel 2010, Fig. 11): at K = 16 the error stays
//!   far above the unbounded lists.

use integration_tests::{accum, builtin, loglog_slope, render, rmse, supersampled_accum};
use mblur::{Method, RenderOptions};

/// Mean RMSE over `seeds` of the stochastic method at each spp against `reference`.
fn stochastic_errors(name: &str, w: u32, h: u32, reference: &mblur::Image) -> Vec<(f64, f64)> {
    let p = builtin(name, w, h);
    let seeds = 4;
    [1u32, 4, 16, 64]
        .iter()
        .map(|&spp| {
            let mean = (0..seeds)
                .map(|seed| {
                    let img = render(
                        &p,
                        &RenderOptions {
                            method: Method::Stochastic,
                            spp: Some(spp),
                            seed,
                            ..Default::default()
                        },
                    )
                    .image;
                    rmse(&img, reference)
                })
                .sum::<f64>()
                / f64::from(seeds as u32);
            (f64::from(spp), mean)
        })
        .collect()
}

fn check_stochastic(name: &str, max_slope: f64) {
    let (w, h) = (48, 27);
    let reference = supersampled_accum(name, w, h, 8, 512);
    let errs = stochastic_errors(name, w, h, &reference);
    let slope = loglog_slope(&errs);
    eprintln!("{name} {w}x{h}: stochastic mean rmse per spp {errs:?}, slope {slope:.3}");
    assert!(
        errs.windows(2).all(|e| e[1].1 < e[0].1),
        "{name}: error does not fall with spp: {errs:?}"
    );
    assert!(
        slope <= max_slope,
        "{name}: log-log slope {slope} is shallower than {max_slope}"
    );
}

/// 1/sqrt(spp) is slope -0.5; the bound -0.45 leaves a margin of 0.05 for the reference's
/// own error (64 positions per pixel), which flattens the curve at 64 spp.
#[test]
fn stochastic_error_falls_at_least_like_inverse_sqrt_spp_on_crossing_quads() {
    check_stochastic("crossing-quads", -0.45);
}

/// As above on billiards (about 10k triangles, perspective, rolling and spinning balls).
#[test]
fn stochastic_error_falls_at_least_like_inverse_sqrt_spp_on_billiards() {
    check_stochastic("billiards", -0.45);
}

/// RMSE against accum 512 of analytic with each K (0 = unbounded lists).
fn k_errors(name: &str, ks: &[u32]) -> Vec<(u32, f64)> {
    let p = builtin(name, 64, 36);
    let reference = accum(&p, 512);
    let errs: Vec<(u32, f64)> = ks
        .iter()
        .map(|&k| {
            let img = render(
                &p,
                &RenderOptions {
                    method: Method::Analytic,
                    intervals: k,
                    ..Default::default()
                },
            )
            .image;
            (k, rmse(&img, &reference))
        })
        .collect();
    eprintln!("{name} 64x36: analytic rmse per K (0 = unbounded) {errs:?}");
    errs
}

const KS: [u32; 6] = [1, 2, 4, 8, 16, 0];

/// Error never grows with K (up to `slack`, the noise of the oracle's merge choices), the
/// unbounded lists are the best, and K = 1 is clearly worse than unbounded.
fn check_k(name: &str, slack: f64, k1_over_exact: f64) {
    let errs = k_errors(name, &KS);
    for pair in errs.windows(2) {
        assert!(
            pair[1].1 <= pair[0].1 + slack,
            "{name}: error grows from K = {} to K = {}: {errs:?}",
            pair[0].0,
            pair[1].0
        );
    }
    let exact = errs[5].1;
    assert!(
        errs.iter().all(|&(_, e)| e >= exact - slack),
        "{name}: {errs:?}"
    );
    assert!(
        errs[0].1 > k1_over_exact * exact,
        "{name}: K = 1 not clearly worse: {errs:?}"
    );
}

#[test]
fn compressed_analytic_error_falls_with_k_on_transparent_cubes() {
    check_k("transparent-cubes", 1e-4, 2.0);
}

#[test]
fn compressed_analytic_error_falls_with_k_on_billiards() {
    check_k("billiards", 1e-4, 2.0);
}

/// Gribel 2010, Fig. 11: the fence moves about 18 slat periods per frame, so each pixel sees
/// about 19 short slat intervals over the static checkerboard, a square-wave visibility
/// function. With K = 16 the oracle must merge intervals of different surfaces, which
/// destroys either the slats or the background in that stretch of the shutter, and the error
/// stays far above the unbounded lists (the paper: "about 40 intervals are needed"). Once K
/// holds every interval (K = 32 here) the error drops to the unbounded one. For contrast, billiards at
/// K = 16 (test above) is within a few times of its unbounded error.
#[test]
fn fence_shows_gribel_failure_at_k16() {
    let errs = k_errors("fence", &[16, 32, 64, 0]);
    let (k16, k32, k64, exact) = (errs[0].1, errs[1].1, errs[2].1, errs[3].1);
    assert!(
        k16 > 0.01 && k16 > 30.0 * exact,
        "fence: K = 16 {k16} vs unbounded {exact}"
    );
    assert!(
        k32 < 2.0 * exact && k64 < 2.0 * exact,
        "fence: K = 32 {k32}, K = 64 {k64} vs unbounded {exact}"
    );
}
