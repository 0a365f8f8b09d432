//! The stochastic method (raster-hier + tmsnet) against independent references: `accum`
//! (pixel-centre static renders at many evenly spaced times) rendered at K x K the
//! resolution and box-filtered down, which approximates the same pixel integral (box filter
//! over the pixel area and the shutter) that the stochastic estimator converges to; plain
//! accum for samples at the pixel centre; the static path for a scene where nothing moves.
//! A plain accum image samples pixel centres only, so its difference to any area-sampling
//! method does not shrink with more samples; the supersampled reference does.
//!
//! The error against spp with samples over the pixel area (against accum supersampled 8x8,
//! on four scenes) is in `integration-tests/tests/convergence.rs`; that every opaque
//! built-in scene renders finite, and that every transparent one is refused, in
//! `integration-tests/tests/finite.rs`.

use integration_tests::{
    accum, assert_finite, builtin, downsample, from_json, max_abs, rmse, supersampled_accum,
};
use mblur::stochastic::{self, StochasticOptions, TraversalChoice};
use mblur::{Footprint, Image, NoProgress, PreparedScene};

fn stoch(
    p: &PreparedScene,
    spp: u32,
    traversal: TraversalChoice,
    seed: u64,
) -> stochastic::StochasticRender {
    stochastic::render(
        p,
        &StochasticOptions {
            spp: Some(spp),
            traversal,
            seed,
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap()
}

/// RMSE against `reference` at 1, 4, 16 and 64 spp (fallback traversal, seed 1), each image
/// checked finite.
fn rmse_ladder(p: &PreparedScene, reference: &Image, name: &str, footprint: Footprint) -> Vec<f64> {
    [1, 4, 16, 64]
        .iter()
        .map(|&spp| {
            let o = StochasticOptions {
                spp: Some(spp),
                traversal: TraversalChoice::Fallback,
                seed: 1,
                footprint,
                ..Default::default()
            };
            let img = stochastic::render(p, &o, &NoProgress).unwrap().image;
            assert_finite(&img, name);
            rmse(&img, reference)
        })
        .collect()
}

/// With every sample at its pixel centre (`Footprint::Centre`) the estimator converges to
/// the plain pixel-centre accum image instead: against accum at 512 times the RMSE falls
/// with spp (RMSE(4) / RMSE(64) >= 2.5) to below a per-scene bound, while samples spread
/// over the pixel stay at the spatial-filter difference (at 64 spp at least twice the
/// centre footprint's error on these scenes). This is why `mblur compare` puts the samples
/// at the centre: its reference is the pixel-centre accum image.
#[test]
fn centre_footprint_converges_to_the_pixel_centre_accum() {
    let (w, h) = (64, 36);
    for (name, bound64) in [
        ("billiards", 0.004),
        ("crossing-quads", 0.004),
        ("fence", 0.015),
    ] {
        let p = builtin(name, w, h);
        let reference = accum(&p, 512);
        let (centre, area) = (
            rmse_ladder(&p, &reference, name, Footprint::Centre),
            rmse_ladder(&p, &reference, name, Footprint::Area),
        );
        eprintln!("{name}: RMSE at spp 1, 4, 16, 64: centre {centre:?}, area {area:?}");
        // Falls at every step, by at least 2.5x from 4 to 64 spp (pure Monte Carlo gives 4),
        // to below `bound64` at 64 spp.
        assert!(centre.windows(2).all(|e| e[1] < e[0]), "{name}: {centre:?}");
        assert!(centre[1] / centre[3] >= 2.5, "{name}: {centre:?}");
        assert!(centre[3] < bound64, "{name}: {centre:?}");
        assert!(area[3] > 2.0 * centre[3], "{name}: {area:?} vs {centre:?}");
    }
}

/// On a static scene every sample of a pixel at its centre sees what the static path's
/// one pixel-centre sample sees: the same image, to f32 rounding of the colour sums.
#[test]
fn centre_footprint_on_a_static_scene_is_the_static_path() {
    let (w, h) = (64, 36);
    let p = builtin("static", w, h);
    let o = StochasticOptions {
        spp: Some(4),
        footprint: Footprint::Centre,
        ..Default::default()
    };
    let img = stochastic::render(&p, &o, &NoProgress).unwrap().image;
    let expected = mblur::accum::render_static(&p, 0.0);
    let worst = max_abs(&img, &expected);
    assert!(worst <= 1e-6, "largest difference {worst}");
}

/// Through the `stochastic` method (the renderer `mblur render` and `mblur compare` run), a
/// scene where nothing moves, with the samples at the pixel centre, takes the static path
/// itself: the image is the static path's bit for bit at every sample count, and the
/// description and the statistics say so. With the samples spread over the pixel it samples
/// (the box-filtered image, which differs from the static path along edges), and a scene
/// that moves samples whatever the footprint.
#[test]
fn stochastic_method_takes_the_static_path_for_a_static_scene_at_pixel_centres() {
    use mblur::Effects;
    let (w, h) = (64, 36);
    let p = builtin("static", w, h);
    let pipeline = Effects::analyse(&p).pipeline();
    let still = mblur::accum::render_static(&p, 0.5);
    let method = |spp: u32, footprint: Footprint| StochasticOptions {
        spp: Some(spp),
        footprint,
        ..Default::default()
    };
    for spp in [1, 16, 256] {
        let r = method(spp, Footprint::Centre);
        assert!(r.describe(&p, &pipeline).contains("the static path"));
        let (img, stats) = r.run(&p, &pipeline, &NoProgress).unwrap();
        assert_eq!(img.pixels, still.pixels, "{spp} spp");
        assert_eq!(stats, "static path: no samples taken");
    }
    let area = method(16, Footprint::Area);
    assert!(
        area.describe(&p, &pipeline)
            .contains("spread over the pixel")
    );
    let (img, stats) = area.run(&p, &pipeline, &NoProgress).unwrap();
    assert!(stats.contains("sample tests"));
    let worst = max_abs(&img, &still);
    assert!(
        worst > 0.05,
        "box-filtered edges differ from the static path: {worst}"
    );
    let moving = builtin("billiards", w, h);
    let moving_pipeline = Effects::analyse(&moving).pipeline();
    let centre = method(4, Footprint::Centre);
    assert!(
        centre
            .describe(&moving, &moving_pipeline)
            .contains("traversal")
    );
    let (_, stats) = centre.run(&moving, &moving_pipeline, &NoProgress).unwrap();
    assert!(stats.contains("moving pass"));
}

/// More samples than a pass may hold are taken in passes: 64 spp with room for 16 per
/// pixel runs four passes of 16 (seeds s, s + 1, s + 2, s + 3) and averages them. Against
/// the pixel-centre accum reference the error is well below one pass of 16 spp; the image
/// is the mean of the four single-pass renders and the counters their sum.
#[test]
fn samples_beyond_the_pass_limit_are_taken_in_passes() {
    let (w, h) = (64u32, 36u32);
    let p = builtin("billiards", w, h);
    let reference = accum(&p, 512);
    let opts = |spp: u32, seed: u64, limit: Option<u64>| StochasticOptions {
        spp: Some(spp),
        seed,
        footprint: Footprint::Centre,
        max_pass_samples: limit,
        ..Default::default()
    };
    let limit = stochastic::buffer_pixels(w, h) * 16;
    let split = stochastic::render(&p, &opts(64, 7, Some(limit)), &NoProgress).unwrap();
    assert_eq!((split.spp, split.passes), (64, 4));
    assert_finite(&split.image, "billiards");
    let singles: Vec<_> = (7..11)
        .map(|seed| stochastic::render(&p, &opts(16, seed, None), &NoProgress).unwrap())
        .collect();
    assert!(singles.iter().all(|r| r.passes == 1));
    let (e_split, e_one) = (
        rmse(&split.image, &reference),
        rmse(&singles[0].image, &reference),
    );
    eprintln!("RMSE: 4 passes of 16 spp {e_split}, one pass of 16 spp {e_one}");
    assert!(e_split < 0.75 * e_one, "{e_split} vs {e_one}");
    for (i, px) in split.image.pixels.iter().enumerate() {
        for (c, v) in px.iter().enumerate() {
            let mean = singles.iter().map(|r| r.image.pixels[i][c]).sum::<f32>() / 4.0;
            assert!((v - mean).abs() <= 1e-6, "pixel {i}: {v} vs {mean}");
        }
    }
    let tests: u64 = singles.iter().map(|r| r.moving_counters.sample_tests).sum();
    assert_eq!(split.moving_counters.sample_tests, tests);
    // Too small a pass for one sample per pixel: a clear option error.
    let e = stochastic::render(&p, &opts(4, 0, Some(100)), &NoProgress)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`max_pass_samples`") && e.contains("at most 100 samples"),
        "{e}"
    );
}

/// A tent shutter response: each sample is weighted by w(t) of its time; the result
/// converges to the supersampled accum reference, which weights its sub-frames by the exact
/// integral of w over each stratum (and differs clearly from the box-shutter image).
#[test]
fn tent_shutter_weights_samples_by_the_response() {
    let (w, h) = (64, 36);
    let json = mblur_scene::builtin::json("crossing-quads")
        .unwrap()
        .replacen(
            "\"background\"",
            "\"shutter\": { \"open\": 0, \"close\": 1, \"response\": \"tent\" },\n  \"background\"",
            1,
        );
    let tent = |w: u32, h: u32| integration_tests::from_json_at(&json, w, h);
    let p = tent(w, h);
    assert!(!p.shutter.is_box());
    let k = 4;
    let reference = downsample(&accum(&tent(w * k, h * k), 512), k);
    let img = stoch(&p, 64, TraversalChoice::Fallback, 1).image;
    let boxed = stoch(
        &builtin("crossing-quads", w, h),
        64,
        TraversalChoice::Fallback,
        1,
    )
    .image;
    let (e, e_box) = (rmse(&img, &reference), rmse(&boxed, &reference));
    eprintln!("tent: RMSE {e}, box-shutter image vs tent reference {e_box}");
    assert!(e < 0.01 && e_box > 3.0 * e, "{e} {e_box}");
}

/// Every traversal gives the same image, bit for bit, for the same seed (they share samples
/// and the inside test; only the cost differs), and the static pass costs the same whatever
/// the traversal of the moving triangles.
#[test]
fn all_traversals_give_bit_identical_images() {
    for name in ["billiards", "fence", "crossing-quads", "textured-quad"] {
        let p = builtin(name, 64, 36);
        let base = stoch(&p, 4, TraversalChoice::Fallback, 7);
        for t in TraversalChoice::ALL {
            let r = stoch(&p, 4, t, 7);
            assert!(r.image.pixels == base.image.pixels, "{name}: {t} differs");
            assert_eq!(r.static_counters, base.static_counters, "{name}: {t}");
            assert_eq!(
                r.moving_counters.samples_written, base.moving_counters.samples_written,
                "{name}: {t}"
            );
        }
    }
}

/// Different seeds give different sample patterns (different images), both close to the
/// reference.
#[test]
fn seeds_change_the_pattern_not_the_estimate() {
    let p = builtin("crossing-quads", 64, 36);
    let reference = supersampled_accum("crossing-quads", 64, 36, 4, 512);
    let (a, b) = (
        stoch(&p, 16, TraversalChoice::Our, 1).image,
        stoch(&p, 16, TraversalChoice::Our, 2).image,
    );
    assert!(a.pixels != b.pixels);
    assert!(rmse(&a, &reference) < 0.02 && rmse(&b, &reference) < 0.02);
}

/// A static scene at 16 spp against the static path (accum, one sub-frame) rendered at 8x8
/// the resolution and box-filtered: overall RMSE < 0.02 (the residual is the 16-sample vs
/// 64-position estimate of edge-pixel coverage and texture variation), and pixels whose 64
/// reference positions all have one colour (flat interiors) match to 1e-5. Nothing moves, so
/// the moving pass does no work and no triangle takes the fallback.
#[test]
fn static_scene_matches_supersampled_static_path() {
    let (w, h) = (64, 36);
    let p = builtin("static", w, h);
    let r = stoch(&p, 16, TraversalChoice::Fallback, 3);
    assert_finite(&r.image, "static");
    assert_eq!(r.moving_triangles, 0);
    assert_eq!(r.moving_counters, Default::default());
    assert_eq!(r.static_counters.fallbacks, 0);
    // Static cost: no more than a static tiled rasteriser testing every sample of every
    // 4x4 tile its screen bounding box touches (the whole image for a clipped triangle).
    let tile_samples = 16 * 16;
    let budget: u64 = p
        .triangles
        .iter()
        .map(|t| {
            let tiles_x = u64::from(w.div_ceil(4));
            let tiles_y = u64::from(h.div_ceil(4));
            if t.open.iter().any(|v| v.depth < p.near) {
                return tiles_x * tiles_y * tile_samples;
            }
            let s = t.open.map(|v| v.screen());
            let lo = |f: fn(&(f64, f64)) -> f64| s.iter().map(f).fold(f64::INFINITY, f64::min);
            let hi = |f: fn(&(f64, f64)) -> f64| s.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
            let tiles = |a: f64, b: f64, n: u64| {
                let a = (a / 4.0).floor().clamp(0.0, n as f64 - 1.0) as u64;
                let b = (b / 4.0).floor().clamp(0.0, n as f64 - 1.0) as u64;
                b - a + 1
            };
            tiles(lo(|p| p.0), hi(|p| p.0), tiles_x)
                * tiles(lo(|p| p.1), hi(|p| p.1), tiles_y)
                * tile_samples
        })
        .sum();
    eprintln!(
        "static: {} sample tests, tiled-bbox budget {budget}",
        r.static_counters.sample_tests
    );
    assert!(r.static_counters.sample_tests <= budget);
    let k = 8;
    let reference = supersampled_accum("static", w, h, k, 1);
    let e = rmse(&r.image, &reference);
    eprintln!("static: RMSE vs 8x8 supersampled static path {e}");
    assert!(e < 0.02, "{e}");
    let big = mblur::accum::render_static(&builtin("static", w * k, h * k), 0.0);
    let (mut uniform, mut matched) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let first = big.pixels[(y * k * w * k + x * k) as usize];
            let flat = (0..k * k)
                .all(|i| big.pixels[((y * k + i / k) * w * k + x * k + i % k) as usize] == first);
            if flat {
                uniform += 1;
                let px = r.image.pixels[(y * w + x) as usize];
                if (0..3).all(|c| (px[c] - first[c]).abs() <= 1e-5) {
                    matched += 1;
                }
            }
        }
    }
    assert!(uniform > 200, "{uniform}");
    // A sliver thinner than the 8x8 grid spacing can hide inside a "flat" block: allow 1%.
    assert!(matched * 100 >= uniform * 99, "{matched} of {uniform}");
}

#[test]
fn transparent_scenes_are_a_clear_error_naming_the_objects() {
    for (name, objects) in [
        ("pills", &["pill-glass", "pill-amber"][..]),
        (
            "transparent-cubes",
            &["red-cube", "green-cube", "blue-cube"][..],
        ),
    ] {
        let p = builtin(name, 32, 18);
        let e = stochastic::render(&p, &StochasticOptions::default(), &NoProgress)
            .unwrap_err()
            .to_string();
        assert!(e.contains("transparency"), "{e}");
        for o in objects {
            assert!(e.contains(o), "{name}: {e}");
        }
    }
}

#[test]
fn bad_spp_is_an_option_error() {
    let p = builtin("static", 16, 16);
    for spp in [0, 3, 24, 4096] {
        let e = stochastic::render(
            &p,
            &StochasticOptions {
                spp: Some(spp),
                ..Default::default()
            },
            &NoProgress,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("stochastic: invalid setting `spp`"), "{e}");
    }
}

/// A moving triangle that crosses the near plane cannot be rasterised unclipped: a clear
/// error naming the object, never a silently wrong image.
#[test]
fn moving_object_through_the_near_plane_is_an_error() {
    let json = r#"{
      "camera": { "width": 32, "height": 18,
        "projection": { "perspective": { "fov_y_deg": 40 } },
        "eye": [0, 0, 6], "target": [0, 0, 0], "near": 0.5, "far": 50 },
      "background": [0, 0, 0],
      "objects": [
        { "name": "dart", "mesh": { "quad": { "size": [1, 1] } },
          "material": { "color": [1, 1, 1, 1] },
          "motion": { "open": { "translate": [0, 0, 0] }, "close": { "translate": [0, 0, 5.8] } } }
      ]
    }"#;
    let p = from_json(json);
    let e = stochastic::render(&p, &StochasticOptions::default(), &NoProgress)
        .unwrap_err()
        .to_string();
    assert!(e.contains("\"dart\"") && e.contains("near plane"), "{e}");
}

/// Through the generic entry point: the method is available, describes itself and reports
/// its counters.
#[test]
fn render_through_the_library_reports_counters() {
    let p = builtin("billiards", 48, 32);
    let out = mblur::render(
        &p,
        &mblur::MethodOptions::Stochastic(mblur::StochasticOptions {
            spp: Some(4),
            ..Default::default()
        }),
        &NoProgress,
    )
    .unwrap();
    assert_eq!(out.method, mblur::Method::Stochastic);
    assert!(
        out.description.contains("4 samples per pixel"),
        "{}",
        out.description
    );
    let stats = out.stats.to_string();
    assert!(
        stats.contains("static pass") && stats.contains("sample tests"),
        "{stats}"
    );
}
