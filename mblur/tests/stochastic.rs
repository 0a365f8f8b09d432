//! The stochastic method (raster-hier + tmsnet) against an independent reference: `accum`
//! (pixel-centre static renders at many evenly spaced times) rendered at K x K the
//! resolution and box-filtered down, which approximates the same pixel integral (box filter
//! over the pixel area and the shutter) that the stochastic estimator converges to. A plain
//! accum image samples pixel centres only, so its difference to any area-sampling method
//! does not shrink with more samples; the supersampled reference does.

use integration_tests::{assert_finite, builtin as scene, max_abs, rmse};
use mblur::stochastic::{self, StochasticOptions, TraversalChoice};
use mblur::{AccumOptions, Footprint, Image, NoProgress, PreparedScene};
use mblur_scene::Scene;

/// accum at `k` x the size with `times` sub-frames, box-filtered back to w x h.
fn reference(name: &str, w: u32, h: u32, k: u32, times: u32) -> Image {
    let big = scene(name, w * k, h * k);
    let img = mblur::accum::render(
        &big,
        &AccumOptions {
            times: Some(times),
            jitter: None,
        },
        &NoProgress,
    )
    .unwrap();
    let mut pixels = vec![[0.0f32; 3]; (w * h) as usize];
    let inv = 1.0 / (k * k) as f64;
    for y in 0..h {
        for x in 0..w {
            let mut acc = [0.0f64; 3];
            for sy in 0..k {
                for sx in 0..k {
                    let p = img.pixels[((y * k + sy) * w * k + x * k + sx) as usize];
                    for c in 0..3 {
                        acc[c] += f64::from(p[c]);
                    }
                }
            }
            pixels[(y * w + x) as usize] = acc.map(|v| (v * inv) as f32);
        }
    }
    Image {
        width: w,
        height: h,
        pixels,
    }
}

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

/// A ladder from [`rmse_ladder`] falls at every step, by at least 2.5x from 4 to 64 spp
/// (pure Monte Carlo gives 4), to below `bound64` at 64 spp.
fn assert_converges(name: &str, errs: &[f64], bound64: f64) {
    assert!(errs.windows(2).all(|e| e[1] < e[0]), "{name}: {errs:?}");
    assert!(errs[1] / errs[3] >= 2.5, "{name}: {errs:?}");
    assert!(errs[3] < bound64, "{name}: {errs:?}");
}

/// RMSE against the 4x4-supersampled accum reference at 512 times falls roughly like
/// 1 / sqrt(spp): RMSE(4) / RMSE(64) >= 2.5 (pure Monte Carlo gives 4; the reference's own
/// 16-position spatial error is the floor), RMSE(64) under a per-scene bound, and each step
/// from 1 to 64 lowers it.
#[test]
fn rmse_against_supersampled_accum_falls_with_spp() {
    let (w, h) = (64, 36);
    // (scene, bound on RMSE at 64 spp)
    for (name, bound64) in [
        ("billiards", 0.01),
        ("crossing-quads", 0.01),
        ("fence", 0.02),
        ("textured-quad", 0.01),
    ] {
        let p = scene(name, w, h);
        let reference = reference(name, w, h, 4, 512);
        let errs = rmse_ladder(&p, &reference, name, Footprint::Area);
        eprintln!("{name}: RMSE at spp 1, 4, 16, 64: {errs:?}");
        assert_converges(name, &errs, bound64);
    }
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
        let p = scene(name, w, h);
        let reference = reference(name, w, h, 1, 512);
        let (centre, area) = (
            rmse_ladder(&p, &reference, name, Footprint::Centre),
            rmse_ladder(&p, &reference, name, Footprint::Area),
        );
        eprintln!("{name}: RMSE at spp 1, 4, 16, 64: centre {centre:?}, area {area:?}");
        assert_converges(name, &centre, bound64);
        assert!(area[3] > 2.0 * centre[3], "{name}: {area:?} vs {centre:?}");
    }
}

/// On a static scene every sample of a pixel at its centre sees what the static path's
/// one pixel-centre sample sees: the same image, to f32 rounding of the colour sums.
#[test]
fn centre_footprint_on_a_static_scene_is_the_static_path() {
    let (w, h) = (64, 36);
    let p = scene("static", w, h);
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
    use mblur::{Effects, Renderer, StochasticRenderer};
    let (w, h) = (64, 36);
    let p = scene("static", w, h);
    let pipeline = Effects::analyse(&p).pipeline();
    let still = mblur::accum::render_static(&p, 0.5);
    let method = |spp: u32, footprint: Footprint| {
        StochasticRenderer::new(StochasticOptions {
            spp: Some(spp),
            footprint,
            ..Default::default()
        })
        .unwrap()
    };
    for spp in [1, 16, 256] {
        let r = method(spp, Footprint::Centre);
        assert!(r.describe(&p, &pipeline).contains("the static path"));
        let img = r.render(&p, &pipeline, &NoProgress).unwrap();
        assert_eq!(img.pixels, still.pixels, "{spp} spp");
        assert_eq!(
            r.statistics().as_deref(),
            Some("static path: no samples taken")
        );
    }
    let area = method(16, Footprint::Area);
    assert!(
        area.describe(&p, &pipeline)
            .contains("spread over the pixel")
    );
    let img = area.render(&p, &pipeline, &NoProgress).unwrap();
    assert!(area.statistics().unwrap().contains("sample tests"));
    let worst = max_abs(&img, &still);
    assert!(
        worst > 0.05,
        "box-filtered edges differ from the static path: {worst}"
    );
    let moving = scene("billiards", w, h);
    let moving_pipeline = Effects::analyse(&moving).pipeline();
    let centre = method(4, Footprint::Centre);
    assert!(
        centre
            .describe(&moving, &moving_pipeline)
            .contains("traversal")
    );
    centre
        .render(&moving, &moving_pipeline, &NoProgress)
        .unwrap();
    assert!(centre.statistics().unwrap().contains("moving pass"));
}

/// More samples than a pass may hold are taken in passes: 64 spp with room for 16 per
/// pixel runs four passes of 16 (seeds s, s + 1, s + 2, s + 3) and averages them. Against
/// the pixel-centre accum reference the error is well below one pass of 16 spp; the image
/// is the mean of the four single-pass renders and the counters their sum.
#[test]
fn samples_beyond_the_pass_limit_are_taken_in_passes() {
    let (w, h) = (64u32, 36u32);
    let p = scene("billiards", w, h);
    let reference = reference("billiards", w, h, 1, 512);
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
        e.contains("--max-pass-samples") && e.contains("at most 100 samples"),
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
    let tent = |w: u32, h: u32| {
        let mut s = Scene::from_json(&json, "tent.json", ".").unwrap();
        s.set_size(Some(w), Some(h)).unwrap();
        s.prepare().unwrap()
    };
    let p = tent(w, h);
    assert!(!p.shutter.is_box());
    let k = 4;
    let big = mblur::accum::render(
        &tent(w * k, h * k),
        &AccumOptions {
            times: Some(512),
            jitter: None,
        },
        &NoProgress,
    )
    .unwrap();
    let reference = Image {
        width: w,
        height: h,
        pixels: (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                let mut acc = [0.0f64; 3];
                for s in 0..k * k {
                    let px = big.pixels[((y * k + s / k) * w * k + x * k + s % k) as usize];
                    for (a, v) in acc.iter_mut().zip(px) {
                        *a += f64::from(v) / f64::from(k * k);
                    }
                }
                acc.map(|v| v as f32)
            })
            .collect(),
    };
    let img = stoch(&p, 64, TraversalChoice::Fallback, 1).image;
    let boxed = stoch(
        &scene("crossing-quads", w, h),
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
        let p = scene(name, 64, 36);
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
    let p = scene("crossing-quads", 64, 36);
    let reference = reference("crossing-quads", 64, 36, 4, 512);
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
    let p = scene("static", w, h);
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
    let reference = reference("static", w, h, k, 1);
    let e = rmse(&r.image, &reference);
    eprintln!("static: RMSE vs 8x8 supersampled static path {e}");
    assert!(e < 0.02, "{e}");
    let big = mblur::accum::render_static(&scene("static", w * k, h * k), 0.0);
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
        let p = scene(name, 32, 18);
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
fn every_opaque_builtin_scene_renders_without_nan() {
    for name in [
        "billiards",
        "fence",
        "crossing-quads",
        "static",
        "textured-quad",
        "clothball",
        "splat-ball",
    ] {
        let p = scene(name, 48, 32);
        for spp in [1, 16] {
            let r = stoch(&p, spp, TraversalChoice::Fallback, 0);
            assert_finite(&r.image, name);
            let bg = p.background.map(|c| c as f32);
            assert!(r.image.pixels.iter().any(|px| *px != bg), "{name}: empty");
        }
    }
}

#[test]
fn bad_spp_is_an_option_error() {
    let p = scene("static", 16, 16);
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
        assert!(e.contains("--spp"), "{e}");
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
    let p = Scene::from_json(json, "dart.json", ".")
        .unwrap()
        .prepare()
        .unwrap();
    let e = stochastic::render(&p, &StochasticOptions::default(), &NoProgress)
        .unwrap_err()
        .to_string();
    assert!(e.contains("\"dart\"") && e.contains("near plane"), "{e}");
}

/// Through the generic entry point: the method is available, describes itself and reports
/// its counters.
#[test]
fn render_through_the_library_reports_counters() {
    let p = scene("billiards", 48, 32);
    let out = mblur::render(
        &p,
        &mblur::RenderOptions {
            method: mblur::Method::Stochastic,
            spp: Some(4),
            ..Default::default()
        },
        &NoProgress,
    )
    .unwrap();
    assert_eq!(out.method, "stochastic");
    assert!(
        out.description.contains("4 samples per pixel"),
        "{}",
        out.description
    );
    let stats = out.statistics.unwrap();
    assert!(
        stats.contains("static pass") && stats.contains("sample tests"),
        "{stats}"
    );
}
