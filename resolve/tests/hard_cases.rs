//! Named hard cases of the temporal resolve (issue 7), each checked against an analytic
//! value or the dense-sampling reference.

mod common;

use common::*;
use interval_buffer::{Interval, Rgba, Textured};
use num_traits::Float;
use resolve::reference::brute_force;
use resolve::{
    BilinearTexture, ExactFilter, Flat, ResolveError, Resolver, Settings, Shader, Shutter,
    TapFilter, resolve_frame,
};

/// `resolve::resolve_pixel` (the default sweep), after checking that every sweep
/// implementation gives the same colour (to 64 ulps) or the same error: every hard case
/// below runs through the kinetic sweep and the active list as well.
fn resolve_pixel<F: Float + std::fmt::Debug, P, S: Shader<F, P>>(
    ivs: &[Interval<F, P>],
    shader: &S,
    s: &Settings<F>,
) -> Result<Rgba<F>, ResolveError> {
    let want = resolve::resolve_pixel(ivs, shader, s);
    for sweep in SWEEPS {
        let got = Resolver::new(s.clone())
            .with_sweep(sweep)
            .resolve(ivs, shader);
        match (&got, &want) {
            (Ok(a), Ok(b)) => {
                let tol = F::epsilon() * F::from(64.0).unwrap_or_else(F::one);
                let close = [(a.r, b.r), (a.g, b.g), (a.b, b.b), (a.a, b.a)]
                    .iter()
                    .all(|&(x, y)| (x - y).abs() <= tol);
                assert!(close, "{sweep:?}: {a:?} vs {b:?}");
            }
            _ => assert_eq!(got, want, "{sweep:?}"),
        }
    }
    want
}

const RED: [f64; 4] = [1.0, 0.0, 0.0, 1.0];
const GREEN: [f64; 4] = [0.0, 1.0, 0.0, 1.0];
const BLUE: [f64; 4] = [0.0, 0.0, 1.0, 1.0];

fn close(a: Rgba<f64>, b: [f64; 4], tol: f64) -> bool {
    max_diff(a, Rgba::new(b[0], b[1], b[2], b[3])) <= tol
}

/// Premultiplied front-to-back OVER of straight colours, then an opaque background.
fn over(layers: &[[f64; 4]], bg: [f64; 3]) -> [f64; 4] {
    let mut c = [0.0; 3];
    let mut t = 1.0;
    for l in layers {
        for k in 0..3 {
            c[k] += t * l[3] * l[k];
        }
        t *= 1.0 - l[3];
    }
    [c[0] + t * bg[0], c[1] + t * bg[1], c[2] + t * bg[2], 1.0]
}

fn mix(parts: &[(f64, [f64; 4])]) -> [f64; 4] {
    let mut m = [0.0; 4];
    for (w, c) in parts {
        for k in 0..4 {
            m[k] += w * c[k];
        }
    }
    m
}

fn check_against_reference(ivs: &[Flat64], s: &Settings<f64>) {
    let got = resolve_pixel(ivs, &Flat, s).unwrap();
    let samples = 1 << 16;
    let want = brute_force(ivs, &Flat, s, samples);
    let tol = sampling_tolerance(ivs.len(), &s.shutter, samples);
    assert!(
        max_diff(got, want) <= tol,
        "{got:?} vs {want:?} (tol {tol})"
    );
}

#[test]
fn ronnow_fig11_quads_moving_through_each_other_are_yellow_with_handling() {
    // Red moves from back to front, green from front to back; depths cross at t = 0.5.
    let red = flat(0.0, 1.0, 2.0, -1.0, RED);
    let green = flat(0.0, 1.0, 1.0, 1.0, GREEN);
    let ivs = [red, green];
    for s in [Settings::opaque(), Settings::transparent()] {
        let c = resolve_pixel(&ivs, &Flat, &s).unwrap();
        assert!(close(c, [0.5, 0.5, 0.0, 1.0], 1e-15), "{c:?}");
    }
}

#[test]
fn ronnow_fig11_without_handling_green_keeps_its_start_order_and_wins() {
    // Without crossing events the order at the interval start (green in front at t = 0)
    // is kept for the whole shutter: all green, as in Fig. 11, left.
    let ivs = [
        flat(0.0, 1.0, 2.0, -1.0, RED),
        flat(0.0, 1.0, 1.0, 1.0, GREEN),
    ];
    for s in [Settings::opaque(), Settings::transparent()] {
        let c = resolve_pixel(&ivs, &Flat, &s.with_intersections(false)).unwrap();
        assert!(close(c, GREEN, 0.0), "{c:?}");
    }
}

#[test]
fn intervals_starting_at_the_same_time() {
    let ivs = [
        flat(0.25, 0.5, 3.0, 0.0, [1.0, 0.0, 0.0, 0.5]),
        flat(0.25, 0.75, 1.0, 2.0, [0.0, 1.0, 0.0, 0.5]),
        flat(0.25, 1.0, 2.0, -1.0, [0.0, 0.0, 1.0, 0.5]),
    ];
    check_against_reference(&ivs, &Settings::transparent().with_threshold(0.0));
    check_against_reference(&ivs, &Settings::opaque());
}

#[test]
fn intervals_ending_at_the_same_time() {
    let ivs = [
        flat(0.0, 0.625, 1.0, 0.0, [1.0, 0.0, 0.0, 0.5]),
        flat(0.125, 0.625, 0.5, 1.0, [0.0, 1.0, 0.0, 0.25]),
        flat(0.5, 0.625, 0.75, 0.0, [0.0, 0.0, 1.0, 1.0]),
    ];
    check_against_reference(&ivs, &Settings::transparent().with_threshold(0.0));
    check_against_reference(&ivs, &Settings::opaque());
    // Analytic opaque value: red on [0, .125); green (depth 0.375 + t, nearer than red
    // until .625) on [.125, .5); blue (0.75, nearer than green's 0.875+) on [.5, .625);
    // background after.
    let c = resolve_pixel(&ivs, &Flat, &Settings::opaque()).unwrap();
    let want = mix(&[
        (0.125, RED),
        (0.375, GREEN),
        (0.125, BLUE),
        (0.375, [0.0, 0.0, 0.0, 1.0]),
    ]);
    assert!(close(c, want, 1e-15), "{c:?} vs {want:?}");
}

#[test]
fn zero_length_intervals_contribute_nothing() {
    let base = flat(0.0, 1.0, 1.0, 0.0, RED);
    let ivs = [
        base,
        flat(0.5, 0.5, 0.0, 0.0, GREEN),
        flat(0.5, 0.5, 0.0, 3.0, BLUE),
    ];
    for s in [Settings::opaque(), Settings::transparent()] {
        let c = resolve_pixel(&ivs, &Flat, &s).unwrap();
        assert_eq!(c, Rgba::new(1.0, 0.0, 0.0, 1.0));
    }
    let only_zero = [flat(0.3, 0.3, 0.0, 0.0, GREEN)];
    let c = resolve_pixel(&only_zero, &Flat, &Settings::opaque()).unwrap();
    assert_eq!(c, Rgba::opaque(0.0, 0.0, 0.0));
}

#[test]
fn crossing_exactly_at_an_interval_end() {
    // Lines cross at t = 0.5, which is where the red interval ends.
    let ivs = [
        flat(0.0, 0.5, 1.0, 1.0, RED),
        flat(0.0, 1.0, 2.0, -1.0, GREEN),
    ];
    let c = resolve_pixel(&ivs, &Flat, &Settings::opaque()).unwrap();
    assert!(close(c, [0.5, 0.5, 0.0, 1.0], 1e-15), "{c:?}");
    // And where one starts: blue starts at the crossing of red and green.
    let ivs = [
        flat(0.0, 1.0, 1.0, 1.0, RED),
        flat(0.0, 1.0, 2.0, -1.0, GREEN),
        flat(0.5, 1.0, 1.5, 0.0, [0.0, 0.0, 1.0, 0.5]),
    ];
    check_against_reference(&ivs, &Settings::transparent().with_threshold(0.0));
    check_against_reference(&ivs, &Settings::opaque());
}

#[test]
fn three_intervals_crossing_at_one_time() {
    // All three lines pass through depth 1 at t = 0.5: the order reverses there.
    let a = [1.0, 0.0, 0.0, 0.5];
    let b = [0.0, 1.0, 0.0, 0.5];
    let c = [0.0, 0.0, 1.0, 0.5];
    let ivs = [
        flat(0.0, 1.0, 0.5, 1.0, a),  // nearest before, farthest after
        flat(0.0, 1.0, 1.0, 0.0, b),  // middle throughout
        flat(0.0, 1.0, 1.5, -1.0, c), // farthest before, nearest after
    ];
    let bg = [0.0, 0.0, 0.0];
    let want = mix(&[(0.5, over(&[a, b, c], bg)), (0.5, over(&[c, b, a], bg))]);
    let s = Settings::transparent().with_threshold(0.0);
    let got = resolve_pixel(&ivs, &Flat, &s).unwrap();
    assert!(close(got, want, 1e-15), "{got:?} vs {want:?}");
    let mut crossings = 0;
    Resolver::new(s)
        .resolve_partitions(&ivs, &Flat, |p| crossings += usize::from(p.t0 == 0.5))
        .unwrap();
    assert_eq!(crossings, 1, "one event reorders all three");
}

#[test]
fn six_intervals_crossing_at_one_time_in_float_rounding() {
    // Lines through (t, depth) = (0.3, 0.7) with slopes that make the crossing times round
    // differently; the result must still match dense sampling.
    let ivs: Vec<_> = (0..6)
        .map(|i| {
            let k = -1.7 + 0.61 * i as f64;
            let alpha = 0.3 + 0.1 * i as f64;
            flat(
                0.0,
                1.0,
                0.7 - k * 0.3,
                k,
                [i as f64 / 5.0, 1.0 - i as f64 / 5.0, 0.5, alpha],
            )
        })
        .collect();
    check_against_reference(&ivs, &Settings::transparent().with_threshold(0.0));
    check_against_reference(&ivs, &Settings::opaque());
}

#[test]
fn equal_depth_over_a_whole_span_later_interval_wins() {
    // LESS_EQUAL: on an exact tie the later interval in the list is nearer (the later-
    // inserted surface, since the interval buffer appends at equal ts).
    let ivs = [
        flat(0.0, 1.0, 1.0, 0.5, RED),
        flat(0.0, 1.0, 1.0, 0.5, GREEN),
    ];
    for s in [
        Settings::opaque(),
        Settings::transparent(),
        Settings::opaque().with_intersections(false),
    ] {
        let c = resolve_pixel(&ivs, &Flat, &s).unwrap();
        assert_eq!(c, Rgba::new(0.0, 1.0, 0.0, 1.0), "{s:?}");
    }
    // Same line, later start: the later interval wins while both are active.
    let ivs = [
        flat(0.0, 1.0, 1.0, 1.0, RED),
        flat(0.5, 1.0, 1.5, 1.0, GREEN),
    ];
    let c = resolve_pixel(&ivs, &Flat, &Settings::opaque()).unwrap();
    assert!(close(c, [0.5, 0.5, 0.0, 1.0], 1e-15), "{c:?}");
}

#[test]
fn alpha_zero_is_invisible_and_alpha_one_hides_everything_behind() {
    let bg = Rgba::opaque(0.2, 0.4, 0.6);
    let s = Settings::transparent().with_background(bg);
    let invisible = [flat(0.0, 1.0, 0.5, 0.0, [1.0, 1.0, 1.0, 0.0])];
    assert!(close(
        resolve_pixel(&invisible, &Flat, &s).unwrap(),
        [0.2, 0.4, 0.6, 1.0],
        1e-15
    ));
    let ivs = [
        flat(0.0, 1.0, 0.5, 0.0, [1.0, 1.0, 1.0, 0.0]),
        flat(0.0, 1.0, 1.0, 0.0, RED),
        flat(0.0, 1.0, 2.0, 0.0, GREEN),
    ];
    let c = resolve_pixel(&ivs, &Flat, &s.clone().with_threshold(0.0)).unwrap();
    assert_eq!(c, Rgba::new(1.0, 0.0, 0.0, 1.0));
    let mut layers = Vec::new();
    Resolver::new(s)
        .resolve_partitions(&ivs, &Flat, |p| layers.push(p.layers))
        .unwrap();
    assert_eq!(layers, [2], "blending stops at the opaque layer");
}

#[test]
fn gribel_fig8_semi_transparent_trio_over_white() {
    // Gribel 2010, Fig. 8: three overlapping intervals at alpha 0.6 over a white background.
    let white = Rgba::opaque(1.0, 1.0, 1.0);
    let s = Settings::transparent()
        .with_threshold(0.0)
        .with_background(white);
    let ivs = [
        flat(0.1, 0.6, 1.0, 0.0, [1.0, 0.0, 0.0, 0.6]),
        flat(0.3, 0.8, 2.0, -1.0, [0.0, 1.0, 0.0, 0.6]),
        flat(0.4, 0.9, 0.5, 1.0, [0.0, 0.0, 1.0, 0.6]),
    ];
    check_against_reference(&ivs, &s);
    let opaque = ivs.map(|iv| Interval {
        payload: Rgba {
            a: 1.0,
            ..iv.payload
        },
        ..iv
    });
    check_against_reference(&opaque, &s);
}

#[test]
fn five_hundred_thirty_intervals_in_one_pixel() {
    // Rønnow 2021, Table 1: up to ~530 intervals per pixel (character running, 4K).
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(530);
    let mut ivs: Vec<Flat64> = (0..530)
        .map(|_| {
            let ts: f64 = rng.random_range(0.0..1.0);
            let len: f64 = rng.random_range(0.0..0.05);
            let c = [
                rng.random_range(0.0..1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(0.05..0.6),
            ];
            flat(
                ts,
                (ts + len).min(1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(-1.0..1.0),
                c,
            )
        })
        .collect();
    ivs.sort_by(|a, b| a.ts.total_cmp(&b.ts));
    let s = Settings::transparent().with_threshold(0.0);
    let got = resolve_pixel(&ivs, &Flat, &s).unwrap();
    let samples = 1 << 17;
    let want = brute_force(&ivs, &Flat, &s, samples);
    // Few pairs overlap in time, so count only starts, ends and overlapping pairs.
    let mut events = 2 * ivs.len();
    for (i, a) in ivs.iter().enumerate() {
        events += ivs[i + 1..].iter().take_while(|b| b.ts < a.te).count();
    }
    let tol = events as f64 / samples as f64;
    assert!(max_diff(got, want) <= tol, "{got:?} vs {want:?} tol {tol}");
    let o = Settings::opaque();
    let got = resolve_pixel(&ivs, &Flat, &o).unwrap();
    assert!(max_diff(got, brute_force(&ivs, &Flat, &o, samples)) <= tol);
}

#[test]
fn shutter_zero_over_part_of_the_shutter() {
    // w = 1 on [0, 0.5], 0 after: only the first half is exposed.
    let half_open =
        Shutter::from_points(&[(0.0, 1.0), (0.5, 1.0), (0.5, 0.0), (1.0, 0.0)]).unwrap();
    let ivs = [
        flat(0.0, 0.25, 1.0, 0.0, RED),
        flat(0.25, 1.0, 1.0, 0.0, GREEN),
        flat(0.5, 1.0, 0.0, 0.0, BLUE),
    ];
    let s = Settings::opaque().with_shutter(half_open.clone());
    let c = resolve_pixel(&ivs, &Flat, &s).unwrap();
    assert!(close(c, [0.5, 0.5, 0.0, 1.0], 1e-15), "{c:?}");
    // Zero-weight partitions are not shaded.
    let mut shaded_after_half = 0;
    Resolver::new(s)
        .resolve_partitions(&ivs, &Flat, |p| {
            if p.t0 >= 0.5 {
                shaded_after_half += p.layers
            }
        })
        .unwrap();
    assert_eq!(shaded_after_half, 0);
    // A response that opens late: nothing before 0.4 counts.
    let late = Shutter::from_points(&[(0.4, 0.0), (0.6, 2.0), (1.0, 2.0)]).unwrap();
    check_against_reference(&ivs, &Settings::transparent().with_shutter(late));
}

#[test]
fn tent_shutter_weights_the_middle() {
    // Red on [0, .25], green on [.25, 1]: tent weight of [0, .25] is 1/16 of ∫w = 1/2.
    let ivs = [
        flat(0.0, 0.25, 1.0, 0.0, RED),
        flat(0.25, 1.0, 1.0, 0.0, GREEN),
    ];
    let c = resolve_pixel(
        &ivs,
        &Flat,
        &Settings::opaque().with_shutter(Shutter::tent()),
    )
    .unwrap();
    assert!(close(c, [0.125, 0.875, 0.0, 1.0], 1e-15), "{c:?}");
}

#[test]
fn times_outside_the_shutter_are_clamped() {
    let ivs = [
        flat(-1.0, 0.5, 1.0, 0.0, RED),
        flat(0.5, 3.0, 1.0, 0.0, GREEN),
    ];
    let c = resolve_pixel(&ivs, &Flat, &Settings::opaque()).unwrap();
    assert!(close(c, [0.5, 0.5, 0.0, 1.0], 1e-15), "{c:?}");
}

#[test]
fn transparent_background_gives_coverage_alpha() {
    let clear = Rgba::new(0.0, 0.0, 0.0, 0.0);
    let ivs = [flat(0.0, 0.5, 1.0, 0.0, [1.0, 0.5, 0.0, 0.5])];
    let c = resolve_pixel(&ivs, &Flat, &Settings::transparent().with_background(clear)).unwrap();
    // Premultiplied mean: 0.5 * (0.5, 0.25, 0, 0.5); straight: (1, 0.5, 0, 0.25).
    assert!(close(c, [1.0, 0.5, 0.0, 0.25], 1e-15), "{c:?}");
}

#[test]
fn textured_partition_uses_the_uv_segment_of_the_partition() {
    // Texture: u = 0 .. 1 maps texels black, white (2 × 1, bilinear, wrapping).
    let tex = [BilinearTexture::new(
        2,
        1,
        &[Rgba::opaque(0.0, 0.0, 0.0), Rgba::opaque(1.0, 1.0, 1.0)],
    )
    .unwrap()];
    let textured = |ts: f64, te: f64, z: f64, u0: f64, u1: f64| {
        Interval::new(
            ts,
            te,
            z,
            0.0,
            Textured {
                uv_start: [u0, 0.5],
                uv_end: [u1, 0.5],
                material: 0,
                alpha: 1.0,
            },
        )
    };
    // u goes 0.25 → 0.75 over the whole shutter (texel centre black → texel centre white):
    // the colour ramps linearly 0 → 1, mean 0.5. A nearer interval hides [0.5, 1].
    let ivs = [
        textured(0.0, 1.0, 1.0, 0.25, 0.75),
        textured(0.5, 1.0, 0.0, 0.25, 0.25),
    ];
    let s = Settings::opaque();
    let exact = resolve_pixel(&ivs, &ExactFilter::new(&tex[..]), &s).unwrap();
    // First half ramps 0 → 0.5 (mean 0.25, weight 0.5); second half black.
    assert!(close(exact, [0.125, 0.125, 0.125, 1.0], 1e-15), "{exact:?}");
    let one_tap = resolve_pixel(&ivs, &TapFilter::new(&tex[..], 1), &s).unwrap();
    assert!(
        close(one_tap, [0.125, 0.125, 0.125, 1.0], 1e-15),
        "a linear ramp needs one tap"
    );
}

#[test]
fn frame_resolve_equals_pixel_resolve() {
    let lists: Vec<Vec<Flat64>> = (0..37)
        .map(|i| {
            let f = i as f64 / 37.0;
            vec![
                flat(0.0, 1.0, 1.0, 0.0, [f, 1.0 - f, 0.5, 0.7]),
                flat(f * 0.5, 0.5 + f * 0.5, 1.5, -1.0, BLUE),
            ]
        })
        .collect();
    let s = Settings::transparent();
    let mut out = vec![Rgba::new(0.0, 0.0, 0.0, 0.0); 37];
    resolve_frame(37, 1, |i| lists[i].as_slice(), &Flat, &s, &mut out).unwrap();
    for (list, o) in lists.iter().zip(&out) {
        assert_eq!(*o, resolve_pixel(list, &Flat, &s).unwrap());
    }
    let mut short = vec![Rgba::new(0.0, 0.0, 0.0, 0.0); 3];
    assert!(resolve_frame(37, 1, |i| lists[i].as_slice(), &Flat, &s, &mut short).is_err());
    let bad = [vec![flat(0.5, 0.2, 1.0, 0.0, RED)]];
    let mut one = [Rgba::new(0.0, 0.0, 0.0, 0.0)];
    let e = resolve_frame(1, 1, |i| bad[i].as_slice(), &Flat, &s, &mut one).unwrap_err();
    assert_eq!(
        e,
        resolve::ResolveError::Pixel {
            index: 0,
            error: resolve::PixelError::InvalidInterval { index: 0 }
        }
    );
}

#[test]
fn value_stability_pinned_outputs() {
    // Deterministic input; pins the exact f64 output of the sweep (any change in event
    // order, weights or blending shows up here).
    let ivs = [
        flat(0.0, 0.8, 1.0, 0.5, [0.9, 0.1, 0.2, 0.6]),
        flat(0.1, 0.7, 1.4, -0.6, [0.2, 0.8, 0.3, 0.5]),
        flat(0.2, 1.0, 1.2, 0.1, [0.1, 0.2, 0.9, 0.7]),
        flat(0.35, 0.6, 0.9, 1.0, [1.0, 1.0, 0.0, 1.0]),
    ];
    let bg = Rgba::opaque(0.05, 0.05, 0.1);
    let t = resolve_pixel(&ivs, &Flat, &Settings::transparent().with_background(bg)).unwrap();
    let o = resolve_pixel(
        &ivs,
        &Flat,
        &Settings::opaque()
            .with_background(bg)
            .with_shutter(Shutter::tent()),
    )
    .unwrap();
    let pinned_t = [t.r, t.g, t.b, t.a];
    let pinned_o = [o.r, o.g, o.b, o.a];
    assert_eq!(pinned_t, PINNED_T, "transparent: {pinned_t:?}");
    assert_eq!(pinned_o, PINNED_O, "opaque tent: {pinned_o:?}");
    // The pinned values are themselves right: dense sampling agrees.
    check_against_reference(
        &ivs,
        &Settings::transparent()
            .with_background(bg)
            .with_threshold(0.0),
    );
    check_against_reference(
        &ivs,
        &Settings::opaque()
            .with_background(bg)
            .with_shutter(Shutter::tent()),
    );
}

const PINNED_T: [f64; 4] = [0.5026500000000002, 0.398525, 0.34878750000000003, 1.0];
const PINNED_O: [f64; 4] = [0.6599375000000003, 0.597109375, 0.2685859374999999, 1.0];

/// Every sweep implementation against the exhaustive-event reference (exact up to
/// rounding), opaque and transparent (default threshold and none), with crossings.
fn check_every_sweep_exactly(ivs: &[Flat64], shutter: &Shutter<f64>) {
    let bg = Rgba::opaque(0.1, 0.2, 0.3);
    for (opaque, threshold) in [(true, 0.0), (false, 1e-4), (false, 0.0)] {
        let s = if opaque {
            Settings::opaque()
        } else {
            Settings::transparent().with_threshold(threshold)
        };
        let s = s.with_shutter(shutter.clone()).with_background(bg);
        let want = exhaustive_events(ivs, shutter, bg, opaque, threshold);
        for sweep in SWEEPS {
            let got = Resolver::new(s.clone())
                .with_sweep(sweep)
                .resolve(ivs, &Flat)
                .unwrap();
            assert!(
                max_diff(got, want) <= 1e-9,
                "{sweep:?} opaque {opaque} threshold {threshold}: {got:?} vs {want:?}"
            );
        }
    }
}

/// `n` random intervals all covering [0.3, 0.7] at least.
fn all_overlapping(n: usize, seed: u64) -> Vec<Flat64> {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut ivs: Vec<Flat64> = (0..n)
        .map(|_| {
            let c = [
                rng.random_range(0.0..1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(0.2..0.9),
            ];
            flat(
                rng.random_range(0.0..0.3),
                rng.random_range(0.7..1.0),
                rng.random_range(0.0..1.0),
                rng.random_range(-1.0..1.0),
                c,
            )
        })
        .collect();
    ivs.sort_by(|a, b| a.ts.total_cmp(&b.ts));
    ivs
}

#[test]
fn hundreds_of_intervals_in_one_pixel_all_overlapping() {
    // 200 intervals active together: ~6 700 pairwise crossings inside the shutter; the
    // default sweep hands over to the kinetic one (view + tournament) at the 33rd start.
    let ivs = all_overlapping(200, 200);
    check_every_sweep_exactly(&ivs, &Shutter::box_filter());
    check_every_sweep_exactly(&ivs, &Shutter::tent());
}

#[test]
fn many_simultaneous_crossings() {
    // 48 lines through (0.25, 1.0), 48 through (0.5, 1.5), 48 through (0.75, 1.0), all
    // active over the whole shutter: dozens of crossings at exactly the same three times,
    // and between the bundles at many others.
    let mut ivs = Vec::new();
    for (b, (t0, d0)) in [(0.25, 1.0), (0.5, 1.5), (0.75, 1.0)]
        .into_iter()
        .enumerate()
    {
        for i in 0..48 {
            let k = (i as f64 - 23.5) / 8.0;
            let c = [
                (i % 3) as f64 / 2.0,
                b as f64 / 2.0,
                (i % 5) as f64 / 4.0,
                0.3 + (i % 4) as f64 * 0.2,
            ];
            ivs.push(flat(0.0, 1.0, d0 - k * t0, k, c));
        }
    }
    check_every_sweep_exactly(&ivs, &Shutter::box_filter());
}

#[test]
fn equal_depth_lines_all_overlapping_later_interval_wins() {
    // 40 copies of one depth line (exact ties all along: LESS_EQUAL, the later list
    // position wins) among 40 crossing ones, in the kinetic tournament.
    let mut ivs = all_overlapping(40, 41);
    for i in 0..40 {
        ivs.push(flat(
            0.0,
            1.0,
            0.5,
            0.25,
            [i as f64 / 40.0, 0.5, 1.0 - i as f64 / 40.0, 0.6],
        ));
    }
    ivs.sort_by(|a, b| a.ts.total_cmp(&b.ts));
    check_every_sweep_exactly(&ivs, &Shutter::box_filter());
}

#[test]
fn coincident_starts_and_ends_in_a_dense_pixel() {
    // 50 intervals start at 0.25 and end at 0.75 together, 30 span the whole shutter.
    let base = all_overlapping(80, 80);
    let ivs: Vec<Flat64> = base
        .iter()
        .enumerate()
        .map(|(i, iv)| {
            if i < 50 {
                Interval {
                    ts: 0.25,
                    te: 0.75,
                    ..*iv
                }
            } else {
                Interval {
                    ts: 0.0,
                    te: 1.0,
                    ..*iv
                }
            }
        })
        .collect();
    let mut ivs = ivs;
    ivs.sort_by(|a, b| a.ts.total_cmp(&b.ts));
    check_every_sweep_exactly(&ivs, &Shutter::trapezoid(0.25, 0.25).unwrap());
}

#[test]
fn burst_mid_shutter_hands_over_to_the_kinetic_sweep() {
    // Few intervals until t = 0.5, then 60 more start at once: the default sweep switches
    // implementation mid-shutter, with crossings pending.
    let mut ivs = all_overlapping(6, 6);
    for iv in all_overlapping(60, 60) {
        ivs.push(Interval {
            ts: 0.5,
            te: 0.5 + 0.5 * iv.te,
            ..iv
        });
    }
    ivs.sort_by(|a, b| a.ts.total_cmp(&b.ts));
    check_every_sweep_exactly(&ivs, &Shutter::box_filter());
}

#[test]
fn transparent_layers_with_alpha_zero_never_end_the_view() {
    // 60 invisible layers (alpha 0: the view can never terminate on them) in front of and
    // crossing 20 opaque ones.
    let mut ivs = all_overlapping(80, 7);
    for iv in ivs.iter_mut().take(60) {
        iv.payload.a = 0.0;
    }
    check_every_sweep_exactly(&ivs, &Shutter::box_filter());
}

#[test]
fn dense_pixel_in_f32_agrees_with_f64() {
    // The kinetic sweep in f32 (nudged crossing times, tournament certificates) against
    // the f64 result on 100 overlapping intervals converted exactly.
    let ivs = all_overlapping(100, 32);
    let ivs32: Vec<Interval<f32, Rgba<f32>>> = ivs
        .iter()
        .map(|iv| {
            let p = iv.payload;
            Interval::new(
                iv.ts as f32,
                iv.te as f32,
                iv.z as f32,
                iv.k as f32,
                Rgba::new(p.r as f32, p.g as f32, p.b as f32, p.a as f32),
            )
        })
        .collect();
    let ivs64: Vec<Flat64> = ivs32
        .iter()
        .map(|iv| {
            let p = iv.payload;
            flat(
                f64::from(iv.ts),
                f64::from(iv.te),
                f64::from(iv.z),
                f64::from(iv.k),
                [p.r, p.g, p.b, p.a].map(f64::from),
            )
        })
        .collect();
    for opaque in [true, false] {
        let (s32, s64) = if opaque {
            (Settings::<f32>::opaque(), Settings::<f64>::opaque())
        } else {
            (
                Settings::<f32>::transparent(),
                Settings::<f64>::transparent(),
            )
        };
        let a = resolve_pixel(&ivs32, &Flat, &s32).unwrap();
        let b = resolve_pixel(&ivs64, &Flat, &s64).unwrap();
        let a = Rgba::new(
            f64::from(a.r),
            f64::from(a.g),
            f64::from(a.b),
            f64::from(a.a),
        );
        // ~1e-7 relative per crossing time, a few hundred visible events.
        assert!(max_diff(a, b) <= 1e-4, "opaque {opaque}: {a:?} vs {b:?}");
    }
}
