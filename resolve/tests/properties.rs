//! Property tests of the resolve against independent references (dense time sampling,
//! f32 vs f64, dense quadrature of textures).

mod common;

use common::*;
use interval_buffer::{Interval, Rgba, Textured};
use proptest::prelude::*;
use resolve::reference::brute_force;
use resolve::{
    BilinearTexture, ExactFilter, Flat, Resolver, SegmentTexture, Settings, TapFilter, Texture,
    resolve_pixel,
};

const SAMPLES: usize = 2048;

fn background() -> impl Strategy<Value = Rgba<f64>> {
    (channel(), channel(), channel()).prop_map(|(r, g, b)| Rgba::opaque(r, g, b))
}

proptest! {
    /// Transparent resolve with crossings = average over dense times of "sort alive
    /// intervals by depth, composite front to back".
    #[test]
    fn transparent_matches_dense_sampling(ivs in intervals(6), sh in shutter(), bg in background()) {
        let s = Settings::transparent().with_threshold(0.0).with_shutter(sh.clone()).with_background(bg);
        let got = resolve_pixel(&ivs, &Flat, &s).unwrap();
        let want = brute_force(&ivs, &Flat, &s, SAMPLES);
        let tol = sampling_tolerance(ivs.len(), &sh, SAMPLES);
        prop_assert!(max_diff(got, want) <= tol, "{got:?} vs {want:?} tol {tol}");
    }

    /// Opaque resolve with crossings = dense sampling of the nearest interval.
    #[test]
    fn opaque_matches_dense_sampling(ivs in intervals(6), sh in shutter(), bg in background()) {
        let s = Settings::opaque().with_shutter(sh.clone()).with_background(bg);
        let got = resolve_pixel(&ivs, &Flat, &s).unwrap();
        let want = brute_force(&ivs, &Flat, &s, SAMPLES);
        let tol = sampling_tolerance(ivs.len(), &sh, SAMPLES);
        prop_assert!(max_diff(got, want) <= tol, "{got:?} vs {want:?} tol {tol}");
    }

    /// Many lines through one (time, depth) point: all reorder at one event, whatever the
    /// rounding of their pairwise crossing times.
    #[test]
    fn lines_through_one_point_match_dense_sampling(
        t0 in time(), d0 in 0.5..2.0_f64, slopes in prop::collection::vec((slope(), [channel(), channel(), channel(), channel()]), 2..7),
        opaque: bool,
    ) {
        let ivs: Vec<_> = slopes.iter().map(|&(k, c)| flat(0.0, 1.0, d0 - k * t0, k, c)).collect();
        let s = if opaque { Settings::opaque() } else { Settings::transparent().with_threshold(0.0) };
        let got = resolve_pixel(&ivs, &Flat, &s).unwrap();
        let want = brute_force(&ivs, &Flat, &s, SAMPLES);
        let tol = sampling_tolerance(ivs.len(), &s.shutter, SAMPLES);
        prop_assert!(max_diff(got, want) <= tol, "{got:?} vs {want:?} tol {tol}");
    }

    /// Without crossings (all slopes equal) intersection handling changes nothing, in
    /// every sweep implementation.
    #[test]
    fn parallel_depths_need_no_intersection_handling(ivs in intervals(8), k in slope()) {
        let ivs: Vec<_> = ivs.into_iter().map(|iv| Interval { k, ..iv }).collect();
        for s in [Settings::transparent(), Settings::opaque()] {
            let on = resolve_pixel(&ivs, &Flat, &s).unwrap();
            for sweep in SWEEPS {
                let off = Resolver::new(s.clone().with_intersections(false)).with_sweep(sweep)
                    .resolve(&ivs, &Flat).unwrap();
                prop_assert!(max_diff(on, off) <= 1e-12, "{sweep:?}: {on:?} vs {off:?}");
            }
        }
    }

    /// Every sweep implementation (the kinetic one from the first start, the active list,
    /// and the default hand-over) matches dense time sampling on small random sets, with
    /// intersection handling, opaque and transparent with early termination.
    #[test]
    fn every_sweep_matches_dense_sampling(
        ivs in intervals(6), sh in shutter(), bg in background(), opaque: bool,
        threshold in prop_oneof![Just(0.0), Just(1e-4), 0.0..0.3_f64],
    ) {
        let s = if opaque { Settings::opaque() } else { Settings::transparent().with_threshold(threshold) };
        let s = s.with_shutter(sh.clone()).with_background(bg);
        let want = brute_force(&ivs, &Flat, &s, SAMPLES);
        // Early termination may drop up to `threshold` against the sampled exact composite.
        let tol = sampling_tolerance(ivs.len(), &sh, SAMPLES) + if opaque { 0.0 } else { threshold };
        for sweep in SWEEPS {
            let got = Resolver::new(s.clone()).with_sweep(sweep).resolve(&ivs, &Flat).unwrap();
            prop_assert!(max_diff(got, want) <= tol, "{sweep:?}: {got:?} vs {want:?} tol {tol}");
        }
    }

    /// Dense sets (every interval overlaps mid-shutter, so all are active at once and the
    /// default sweep hands over to the kinetic one; grid values make many simultaneous
    /// crossings, coincident ends and exact ties): every sweep equals the exhaustive-event
    /// reference (all O(n²) pairwise crossings as cut points) up to rounding, for opaque
    /// and transparent blending with and without early termination.
    #[test]
    fn dense_sets_match_the_exhaustive_event_reference(
        ivs in dense_intervals(33, 44), sh in shutter(), bg in background(), opaque: bool,
        threshold in prop_oneof![Just(0.0), Just(1e-4), 0.0..0.3_f64],
    ) {
        let s = if opaque { Settings::opaque() } else { Settings::transparent().with_threshold(threshold) };
        let s = s.with_shutter(sh.clone()).with_background(bg);
        let want = exhaustive_events(&ivs, &sh, bg, opaque, threshold);
        for sweep in SWEEPS {
            let got = Resolver::new(s.clone()).with_sweep(sweep).resolve(&ivs, &Flat).unwrap();
            prop_assert!(max_diff(got, want) <= 1e-9, "{sweep:?}: {got:?} vs {want:?}");
        }
    }

    /// Dense sets of bundles of lines through a few common (time, depth) points: dozens of
    /// crossings at exactly the same time, in the kinetic view and its tournament.
    #[test]
    fn dense_bundles_crossing_at_common_points_match_the_reference(
        points in prop::collection::vec((time(), 0.5..2.0_f64), 1..4),
        lines in prop::collection::vec((0..4usize, slope(), [channel(), channel(), channel(), channel()]), 33..45),
        opaque: bool, threshold in prop_oneof![Just(0.0), Just(1e-4), 0.0..0.3_f64],
    ) {
        let ivs: Vec<Flat64> = lines.iter().map(|&(p, k, c)| {
            let (t0, d0) = points[p % points.len()];
            flat(0.0, 1.0, d0 - k * t0, k, c)
        }).collect();
        let s = if opaque { Settings::opaque() } else { Settings::transparent().with_threshold(threshold) };
        let want = exhaustive_events(&ivs, &s.shutter, s.background, opaque, threshold);
        for sweep in SWEEPS {
            let got = Resolver::new(s.clone()).with_sweep(sweep).resolve(&ivs, &Flat).unwrap();
            prop_assert!(max_diff(got, want) <= 1e-9, "{sweep:?}: {got:?} vs {want:?}");
        }
    }

    /// Without intersection handling, dense sets whose lines never cross (one slope) are
    /// exact in every sweep (the rank order is the depth order), against the reference.
    #[test]
    fn dense_parallel_sets_without_handling_match_the_reference(
        ivs in dense_intervals(17, 60), k in slope(), opaque: bool,
        threshold in prop_oneof![Just(0.0), Just(1e-4), 0.0..0.3_f64],
    ) {
        let ivs: Vec<_> = ivs.into_iter().map(|iv| Interval { k, ..iv }).collect();
        let s = if opaque { Settings::opaque() } else { Settings::transparent().with_threshold(threshold) };
        let s = s.with_intersections(false);
        let want = exhaustive_events(&ivs, &s.shutter, s.background, opaque, threshold);
        for sweep in SWEEPS {
            let got = Resolver::new(s.clone()).with_sweep(sweep).resolve(&ivs, &Flat).unwrap();
            prop_assert!(max_diff(got, want) <= 1e-9, "{sweep:?}: {got:?} vs {want:?}");
        }
    }

    /// Every sweep's partitions tile [0, 1] and sum to ∫ w on dense sets too, and their
    /// boundaries agree between the sweeps up to the few-ulp nudges of crossing times.
    #[test]
    fn dense_partitions_tile_the_shutter_in_every_sweep(
        ivs in dense_intervals(33, 40), sh in shutter(), opaque: bool, handling: bool,
    ) {
        let s = if opaque { Settings::opaque() } else { Settings::transparent() };
        let s = s.with_shutter(sh.clone()).with_intersections(handling);
        let mut spans = Vec::new();
        for sweep in SWEEPS {
            let (mut sum, mut t, mut mine) = (0.0, 0.0, Vec::new());
            Resolver::new(s.clone()).with_sweep(sweep).resolve_partitions(&ivs, &Flat, |p| {
                assert_eq!(p.t0, t);
                assert!(p.t1 > p.t0);
                t = p.t1;
                sum += p.weight;
                mine.push((p.t0, p.t1));
            }).unwrap();
            prop_assert_eq!(t, 1.0);
            prop_assert!((sum - sh.total()).abs() <= 1e-12 * sh.total());
            spans.push(mine);
        }
        if handling {
            // Every boundary of one sweep is within 1e-12 of a boundary of the others.
            for a in &spans {
                for b in &spans {
                    for p in a {
                        let near = b.iter().any(|q| (q.0 - p.0).abs() <= 1e-12);
                        prop_assert!(near, "boundary {} missing in {b:?}", p.0);
                    }
                }
            }
        }
    }

    /// Eq. 17 conservation: the partitions tile [0, 1] and their weights sum to ∫ w; with an
    /// opaque interval covering the whole shutter no partition shows background.
    #[test]
    fn partition_weights_sum_to_the_shutter_integral(
        ivs in intervals(8), sh in shutter(), cover in 0.0..4.0_f64, handling: bool, opaque: bool,
    ) {
        let mut ivs = ivs;
        ivs.insert(0, flat(0.0, 1.0, cover, 0.0, [0.5, 0.5, 0.5, 1.0]));
        let s = if opaque { Settings::opaque() } else { Settings::transparent() };
        let s = s.with_shutter(sh.clone()).with_intersections(handling);
        let mut r = Resolver::new(s);
        let (mut sum, mut t, mut background) = (0.0, 0.0, 0.0);
        r.resolve_partitions(&ivs, &Flat, |p| {
            assert_eq!(p.t0, t);
            t = p.t1;
            sum += p.weight;
            if p.front.is_none() { background += p.weight; }
        }).unwrap();
        prop_assert_eq!(t, 1.0);
        prop_assert!((sum - sh.total()).abs() <= 1e-12 * sh.total(), "{sum} vs {}", sh.total());
        prop_assert_eq!(background, 0.0);
    }

    /// The uncovered time shows the background with exactly its ∫ w share.
    #[test]
    fn background_weight_is_the_uncovered_time(ivs in intervals(6), sh in shutter()) {
        let s = Settings::opaque().with_shutter(sh.clone());
        let mut background = 0.0;
        Resolver::new(s).resolve_partitions(&ivs, &Flat, |p| {
            if p.front.is_none() { background += p.weight; }
        }).unwrap();
        // Uncovered set from the union of [ts, te), integrated with the shutter.
        let mut spans: Vec<(f64, f64)> = ivs.iter().filter(|i| i.te > i.ts).map(|i| (i.ts, i.te)).collect();
        spans.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (mut covered, mut end) = (0.0, 0.0_f64);
        for (a, b) in spans {
            let a = a.max(end);
            if b > a { covered += sh.integral(a, b); end = b; }
        }
        let want = sh.total() - covered;
        prop_assert!((background - want).abs() <= 1e-12, "{background} vs {want}");
    }

    /// Early termination costs at most the threshold per channel.
    #[test]
    fn early_termination_error_is_below_the_threshold(
        ivs in intervals(8), threshold in prop_oneof![Just(1e-4), 0.0..0.5_f64], bg in background(),
    ) {
        let exact = Settings::transparent().with_threshold(0.0).with_background(bg);
        let early = exact.clone().with_threshold(threshold);
        let a = resolve_pixel(&ivs, &Flat, &exact).unwrap();
        let b = resolve_pixel(&ivs, &Flat, &early).unwrap();
        prop_assert!(max_diff(a, b) <= threshold + 1e-12, "{a:?} vs {b:?}");
    }

    /// f32 agrees with f64 to f32 precision times the number of events.
    #[test]
    fn f32_agrees_with_f64(ivs in intervals(6), opaque: bool) {
        let to32 = |iv: &Flat64| Interval::new(iv.ts as f32, iv.te as f32, iv.z as f32, iv.k as f32,
            Rgba::new(iv.payload.r as f32, iv.payload.g as f32, iv.payload.b as f32, iv.payload.a as f32));
        let ivs32: Vec<_> = ivs.iter().map(to32).collect();
        // Round-trip the f64 input through f32 so both resolve the same numbers.
        let ivs64: Vec<Flat64> = ivs32.iter().map(|iv| Interval::new(f64::from(iv.ts), f64::from(iv.te),
            f64::from(iv.z), f64::from(iv.k), Rgba::new(f64::from(iv.payload.r), f64::from(iv.payload.g),
            f64::from(iv.payload.b), f64::from(iv.payload.a)))).collect();
        let (s32, s64) = if opaque { (Settings::<f32>::opaque(), Settings::<f64>::opaque()) }
            else { (Settings::<f32>::transparent(), Settings::<f64>::transparent()) };
        let a = resolve_pixel(&ivs32, &Flat, &s32).unwrap();
        let b = resolve_pixel(&ivs64, &Flat, &s64).unwrap();
        let a = Rgba::new(f64::from(a.r), f64::from(a.g), f64::from(a.b), f64::from(a.a));
        // A crossing time moves by ~1e-7 relative per pair, rounding adds ~1e-7 per event.
        let tol = 1e-5 * events(ivs.len(), &resolve::Shutter::box_filter());
        prop_assert!(max_diff(a, b) <= tol, "{a:?} vs {b:?}");
    }

    /// The exact segment integral in f32 agrees with f64 (f32 texels, coordinates and
    /// weights converted exactly).
    #[test]
    fn bilinear_segment_integral_f32_agrees_with_f64(
        w in 1usize..5, h in 1usize..5, seed in any::<u64>(),
        uv0 in [-2.0..2.0_f32, -2.0..2.0_f32], duv in [-1.5..1.5_f32, -1.5..1.5_f32],
        w0 in 0.0..2.0_f32, w1 in 0.0..2.0_f32,
    ) {
        let t64 = random_texture(w, h, seed);
        let texels32: Vec<Rgba<f32>> = (0..w * h).map(|k| {
            let c = t64.sample(0, [((k % w) as f64 + 0.5) / w as f64, ((k / w) as f64 + 0.5) / h as f64]);
            Rgba::new(c.r as f32, c.g as f32, c.b as f32, c.a as f32)
        }).collect();
        let texels64: Vec<Rgba<f64>> = texels32.iter().map(|c| Rgba::new(f64::from(c.r), f64::from(c.g), f64::from(c.b), f64::from(c.a))).collect();
        let t32 = BilinearTexture::new(w, h, &texels32).unwrap();
        let t64 = BilinearTexture::new(w, h, &texels64).unwrap();
        let uv1 = [uv0[0] + duv[0], uv0[1] + duv[1]];
        let a = t32.segment_average(0, uv0, uv1, w0, w1);
        let b = t64.segment_average(0, uv0.map(f64::from), uv1.map(f64::from), f64::from(w0), f64::from(w1));
        for k in 0..4 {
            prop_assert!((f64::from(a[k]) - b[k]).abs() <= 1e-4, "channel {k}: {} vs {}", a[k], b[k]);
        }
    }

    /// The exact bilinear segment integral equals dense midpoint quadrature of point lookups.
    #[test]
    fn bilinear_segment_integral_matches_quadrature(
        w in 1usize..5, h in 1usize..5, seed in any::<u64>(),
        uv0 in [-2.0..2.0_f64, -2.0..2.0_f64], duv in [-1.5..1.5_f64, -1.5..1.5_f64],
        w0 in 0.0..2.0_f64, w1 in 0.0..2.0_f64,
    ) {
        let tex = random_texture(w, h, seed);
        let uv1 = [uv0[0] + duv[0], uv0[1] + duv[1]];
        let exact = tex.segment_average(0, uv0, uv1, w0, w1);
        // Midpoint rule: O(h²) per cell and per kink at cell boundaries.
        let n = 4_000;
        let mut sum = [0.0; 4];
        let mut weights = 0.0;
        for i in 0..n {
            let s = (i as f64 + 0.5) / n as f64;
            let c = tex.sample(0, [uv0[0] + duv[0] * s, uv0[1] + duv[1] * s]).premultiplied();
            let wt = if w0 + w1 > 0.0 { w0 + (w1 - w0) * s } else { 1.0 };
            for k in 0..4 { sum[k] += wt * c[k]; }
            weights += wt;
        }
        for k in 0..4 {
            let q = sum[k] / weights;
            prop_assert!((exact[k] - q).abs() <= 2e-5, "channel {k}: {} vs {q}", exact[k]);
        }
    }

    /// Textured resolve with the exact filter = dense time sampling of the texture.
    #[test]
    fn textured_resolve_matches_dense_sampling(
        ivs in intervals(4), seed in any::<u64>(), uvs in prop::collection::vec([-1.0..1.0_f64, -1.0..1.0_f64, -1.0..1.0_f64, -1.0..1.0_f64], 4),
        sh in shutter(),
    ) {
        // Opaque texels: with texel alpha varying inside a partition, OVER of the partition
        // averages is not the average of OVER (Rønnow 2021 makes the same approximation), so
        // transparency comes from the constant material alpha here.
        let tex = [opaque_texture(random_texture(3, 2, seed))];
        let ivs: Vec<_> = ivs.iter().zip(&uvs).map(|(iv, uv)| iv.with_payload(Textured {
            uv_start: [uv[0], uv[1]], uv_end: [uv[2], uv[3]], material: 0,
            alpha: iv.payload.a,
        })).collect();
        let s = Settings::transparent().with_threshold(0.0).with_shutter(sh.clone());
        let got = resolve_pixel(&ivs, &ExactFilter::new(&tex[..]), &s).unwrap();
        let want = brute_force(&ivs, &ExactFilter::new(&tex[..]), &s, 2 * SAMPLES);
        let tol = sampling_tolerance(ivs.len(), &sh, 2 * SAMPLES);
        prop_assert!(max_diff(got, want) <= tol, "{got:?} vs {want:?} tol {tol}");
        // Many taps converge to the exact filter.
        let taps = resolve_pixel(&ivs, &TapFilter::new(&tex[..], 64), &s).unwrap();
        prop_assert!(max_diff(got, taps) <= 2e-3, "{got:?} vs {taps:?}");
    }
}

proptest! {
    /// A colour that does not depend on UV: `uniform_colour` gives the one-tap filter's
    /// bits (any UV ends, any shutter weights, zero weights included), and the filtered
    /// colour is the colour itself times the material alpha (a weighted mean of a
    /// constant), to rounding, in f32 and f64.
    #[test]
    fn uniform_colour_is_the_one_tap_filter_of_a_constant(
        rgb in [0.0..1.0_f64, 0.0..1.0_f64, 0.0..1.0_f64], a in 0.0..1.0_f64, alpha in 0.0..1.0_f64,
        uv in [-4.0..4.0_f64, -4.0..4.0_f64, -4.0..4.0_f64, -4.0..4.0_f64],
        w in prop::sample::select(vec![[0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.25, 0.75], [1.0, 0.0]]),
        w_random in [0.0..2.0_f64, 0.0..2.0_f64], random_weights in any::<bool>(),
    ) {
        let [w0, w1] = if random_weights { w_random } else { w };
        check_uniform::<f64>(rgb, a, alpha, uv, [w0, w1], 1e-15)?;
        check_uniform::<f32>(rgb, a, alpha, uv, [w0, w1], 1e-6)?;
    }
}

fn check_uniform<F: num_traits::Float + std::fmt::Debug>(
    rgb: [f64; 3],
    a: f64,
    alpha: f64,
    uv: [f64; 4],
    w: [f64; 2],
    tol: f64,
) -> Result<(), TestCaseError> {
    let f = |v: f64| F::from(v).unwrap();
    let colour = Rgba::new(f(rgb[0]), f(rgb[1]), f(rgb[2]), f(a));
    let constant = move |_: u32, _: [F; 2]| colour;
    let c = constant.sample_premultiplied(0, [F::zero(); 2]);
    let (alpha, w0, w1) = (f(alpha), f(w[0]), f(w[1]));
    let got = resolve::uniform_colour(c, alpha, w0, w1);
    let filter = TapFilter::new(&constant, 1);
    let want = filter.shade_segment(
        (0, alpha),
        [f(uv[0]), f(uv[1])],
        [f(uv[2]), f(uv[3])],
        w0,
        w1,
    );
    prop_assert_eq!(got, want);
    for k in 0..4 {
        let exact = c[k].to_f64().unwrap() * alpha.to_f64().unwrap();
        let g = got[k].to_f64().unwrap();
        prop_assert!((g - exact).abs() <= tol, "channel {k}: {g} vs {exact}");
    }
    Ok(())
}

/// The same texture with alpha 1 everywhere.
pub fn opaque_texture(t: BilinearTexture<f64>) -> BilinearTexture<f64> {
    let texels: Vec<_> = (0..t.width() * t.height())
        .map(|k| {
            let uv = [
                ((k % t.width()) as f64 + 0.5) / t.width() as f64,
                ((k / t.width()) as f64 + 0.5) / t.height() as f64,
            ];
            let c = t.sample(0, uv);
            Rgba::opaque(c.r, c.g, c.b)
        })
        .collect();
    BilinearTexture::new(t.width(), t.height(), &texels).unwrap()
}

/// A texture with texels from a small LCG (deterministic per seed).
pub fn random_texture(w: usize, h: usize, seed: u64) -> BilinearTexture<f64> {
    let mut x = seed | 1;
    let mut next = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let texels: Vec<_> = (0..w * h)
        .map(|_| Rgba::new(next(), next(), next(), next()))
        .collect();
    BilinearTexture::new(w, h, &texels).unwrap()
}

#[test]
fn dense_sampling_error_shrinks_with_the_sample_count() {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(7);
    for _ in 0..20 {
        let mut ivs: Vec<Flat64> = (0..6)
            .map(|_| {
                let a: f64 = rng.random_range(0.0..1.0);
                let b: f64 = rng.random_range(0.0..1.0);
                let c = [
                    rng.random_range(0.0..1.0),
                    rng.random_range(0.0..1.0),
                    rng.random_range(0.0..1.0),
                    rng.random_range(0.0..1.0),
                ];
                flat(
                    a.min(b),
                    a.max(b),
                    rng.random_range(0.0..2.0),
                    rng.random_range(-2.0..2.0),
                    c,
                )
            })
            .collect();
        ivs.sort_by(|a, b| a.ts.total_cmp(&b.ts));
        let s = Settings::transparent().with_threshold(0.0);
        let got = resolve_pixel(&ivs, &Flat, &s).unwrap();
        let mut previous = f64::INFINITY;
        let deep = std::env::var("MBLUR_DEEP").is_ok_and(|v| v == "1");
        let counts: &[usize] = if deep {
            &[256, 2048, 16384, 131072, 1 << 20]
        } else {
            &[256, 2048, 16384, 131072]
        };
        for &samples in counts {
            let err = max_diff(got, brute_force(&ivs, &Flat, &s, samples));
            let tol = sampling_tolerance(ivs.len(), &s.shutter, samples);
            assert!(err <= tol, "{samples}: {err} > {tol}");
            previous = previous.min(tol);
        }
        assert!(previous < 1e-3);
    }
}
