//! Property suites: tile tests are conservative against edge-eqn's exact coverage, every
//! traversal matches the brute-force reference bit for bit, and motion back-face culling is
//! conservative against dense sampling of the orientation cubic, and its time-dependent
//! windows (`facing_windows`) hold every instant the triangle may face the camera and
//! remove the clearly hidden rest.

mod common;

use common::{
    Certainty, LEVELS, certainty_f64, check_facing_windows, check_levels_in, random_triangle, tri,
};
use edge_eqn::MovingTriangle;
use num_traits::Float;
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use raster_hier::{
    EdgeTest, Facing, Footprint, Rect, TileTester, TimeInterval, covered, facing, frustum_interval,
    screen_bound,
};

const SCREEN: f64 = 64.0;

/// f64 in-front test at (x, y, t): the hit μ = −det / Σe is positive.
fn front_f64(tri: &MovingTriangle<f64>, x: f64, y: f64, t: f64) -> bool {
    let s = tri.setup();
    let det = s.orientation_at(t);
    let sum: f64 = s.edges().iter().map(|e| e.eval(x, y, t)).sum();
    det * sum < 0.0
}

/// Checks one triangle against random tiles (16, 8 or 4 px), points and times for all five
/// edge tests, on the tile and on the 2x2 quad and the pixel holding each point (the
/// levels below the 4x4 pattern tile).
/// Returns (pairs checked, misses, covered pairs, rounding-only hits as [proved uncovered,
/// degenerate]). A miss is a
/// (sample, time) outside the tile's interval (or rejected by culling) that is covered —
/// provably so by the independent f64 reference with error bound ([`certainty_f64`] on the
/// triangle, point and time as the rasteriser sees them), or by the rasteriser's inside test
/// at that time or one of edge-eqn's coverage spans (in front of the eye) unless the f64
/// reference proves it uncovered or the triangle degenerate at that time. Those are the
/// rounding-only hits: at an instant where the triangle collapses to a segment (det(t) = 0)
/// the inside rule holds on the whole line through it (all e = 0), and near that instant the
/// `F` signs of three noise-level edge values can agree at points the triangle never reaches
/// (hard case `sample_on_the_line_of_a_collapsing_triangle_is_not_a_tile_miss_f32`).
fn check_triangle<F: Float + core::fmt::Debug>(
    q64: [[f64; 3]; 3],
    r64: [[f64; 3]; 3],
    rng: &mut Pcg64,
    tiles: usize,
) -> (u64, u64, u64, [u64; 2]) {
    let t = tri::<F>(q64, r64, 0).triangle;
    let t64 = MovingTriangle::new(q64, r64);
    let (q, r) = (t.q, t.r);
    let wide = |v: F| v.to_f64().unwrap_or(f64::NAN);
    let (qw, rw) = (q.map(|p| p.map(wide)), r.map(|p| p.map(wide)));
    let setup = t.setup();
    let all_w = q.iter().chain(r.iter()).all(|v| v[2] > F::zero());
    let f = |v: f64| F::from(v).unwrap_or_else(F::zero);
    let size = f(SCREEN);
    let frustum = frustum_interval(&q, &r, size, size);
    let bound = screen_bound(&q, &r, frustum, size, size);
    let culled = !setup.is_valid() || frustum.is_empty() || bound.rect.is_empty();
    let tester = TileTester::new(&q, &r, *setup.edges(), facing(&q, &r), frustum, bound.rect);
    // The collapse instant (a root of det(t) by bisection, when det changes sign) and the
    // line through the collapsed triangle: points on it, at that time, are where the edge
    // signs are all at noise level (the region of the deep-CI report).
    let collapse = {
        let sw = MovingTriangle::new(qw, rw).setup();
        let (mut a, mut b) = (0.0f64, 1.0f64);
        let da = sw.orientation_at(a);
        if da * sw.orientation_at(b) < 0.0 {
            for _ in 0..60 {
                let m = 0.5 * (a + b);
                if sw.orientation_at(m) * da > 0.0 {
                    a = m;
                } else {
                    b = m;
                }
            }
            let at = |i: usize| -> [f64; 3] {
                core::array::from_fn(|c| qw[i][c] + a * (rw[i][c] - qw[i][c]))
            };
            let (p0, p1) = (at(0), at(1));
            (p0[2] > 0.0 && p1[2] > 0.0 && (p1[0] / p1[2] - p0[0] / p0[2]).abs() > 1e-3).then(
                || {
                    (
                        a,
                        [p0[0] / p0[2], p0[1] / p0[2]],
                        [p1[0] / p1[2], p1[1] / p1[2]],
                    )
                },
            )
        } else {
            None
        }
    };
    let (mut pairs, mut misses, mut hits, mut noise) = (0u64, 0u64, 0u64, [0u64; 2]);
    for _ in 0..tiles {
        let level = [16u32, 8, 4][rng.random_range(0..3usize)];
        let n = SCREEN as u32 / level;
        // Mostly tiles around a point of the triangle at a random time, else anywhere.
        let (mut tx, mut ty) = (
            rng.random_range(0..n) * level,
            rng.random_range(0..n) * level,
        );
        if rng.random_bool(0.8) {
            let tt = rng.random_range(0.0..1.0);
            let (a, b) = (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
            let (a, b) = if a + b > 1.0 {
                (1.0 - a, 1.0 - b)
            } else {
                (a, b)
            };
            let p: [f64; 3] = core::array::from_fn(|c| {
                let v = |i: usize| q64[i][c] + tt * (r64[i][c] - q64[i][c]);
                v(0) * (1.0 - a - b) + v(1) * a + v(2) * b
            });
            if p[2] > 0.0 {
                let cell = |v: f64| ((v / p[2]).clamp(0.0, SCREEN - 1.0) as u32) / level * level;
                (tx, ty) = (cell(p[0]), cell(p[1]));
            }
        }
        let tile = Rect::new(
            f(f64::from(tx)),
            f(f64::from(ty)),
            f(f64::from(tx + level)),
            f(f64::from(ty + level)),
        );
        let coarse = Rect::new(
            f(f64::from(tx / 16 * 16)),
            f(f64::from(ty / 16 * 16)),
            f(f64::from(tx / 16 * 16 + 16)),
            f(f64::from(ty / 16 * 16 + 16)),
        );
        let per_tile = tester.linearise(coarse.intersect(&bound.rect));
        // Every edge test of `rect`, then the per-level window test inside a parent window
        // that contains the tested times below only when it should: the window result must
        // contain every covered time of the window. (The window is derived from the tile,
        // not drawn, so recorded seeds replay the same tiles.)
        let wa = f64::from((tx * 7 + ty * 13 + level) % 17) / 34.0;
        let window = TimeInterval::new(f(wa), f(wa + 0.5));
        let tests = |rect: &Rect<F>| {
            [
                tester.test(rect, EdgeTest::LinearisedSetup, &tester.setup),
                tester.test(rect, EdgeTest::LinearisedPerTile, &per_tile),
                tester.test(rect, EdgeTest::Exact, &tester.setup),
                tester.test_window(
                    rect,
                    EdgeTest::LinearisedPerLevel,
                    &tester.setup,
                    TimeInterval::full(),
                    false,
                ),
                tester.test_window(
                    rect,
                    EdgeTest::ExactFinest,
                    &tester.setup,
                    TimeInterval::full(),
                    true,
                ),
                tester.test_window(
                    rect,
                    EdgeTest::LinearisedPerLevel,
                    &tester.setup,
                    window,
                    false,
                ),
            ]
        };
        let ivs = tests(&tile);
        for point in 0..24 {
            let x64 = f64::from(tx) + rng.random_range(0.0..f64::from(level));
            let mut y64 = f64::from(ty) + rng.random_range(0.0..f64::from(level));
            if let Some((_, a, b)) = collapse.filter(|_| point % 2 == 1) {
                // Every other point on the collapse line, if it crosses the tile at this x
                // (no extra random draws, so seeds replay the same tiles and times).
                let yl = a[1] + (x64 - a[0]) * (b[1] - a[1]) / (b[0] - a[0]);
                if (f64::from(ty)..f64::from(ty + level)).contains(&yl) {
                    y64 = yl;
                }
            }
            let (x, y) = (f(x64), f(y64));
            // The 2x2 quad and the pixel holding the point (levels below the 4x4 pattern
            // tile), derived from the point: no extra random draws.
            let cell = |s: f64| {
                let (x0, y0) = ((wide(x) / s).floor() * s, (wide(y) / s).floor() * s);
                Rect::new(f(x0), f(y0), f(x0 + s), f(y0 + s))
            };
            let sub = [2.0f64, 1.0].map(|s| tests(&cell(s)));
            // The traversal's path below the pattern tile: the 4x4 tile's window test, its
            // linearisation around the resulting interval, evaluated on the quad and on the
            // pixel inside the quad's interval.
            let tile4 = cell(4.0);
            let iv4 = tester.test_window(
                &tile4,
                EdgeTest::LinearisedPerLevel,
                &tester.setup,
                TimeInterval::full(),
                false,
            );
            let ew = tester.edge_window(&tile4, iv4);
            let quad_iv = tester.sub_tile_interval(&ew, &cell(2.0), iv4);
            let cheap = [
                iv4,
                quad_iv,
                tester.sub_tile_interval(&ew, &cell(1.0), quad_iv),
            ];
            let cov = setup.coverage(x, y);
            let mut times: Vec<F> = (0..24)
                .map(|_| f(f64::from(rng.random_range(0..256u32)) / 256.0))
                .collect();
            for s in cov.iter() {
                times.push(s.mid());
            }
            if let Some((tc, _, _)) = collapse {
                times.push(f(tc));
            }
            for tt in times {
                let t64v = tt.to_f64().unwrap_or(0.0);
                let claimed = covered(&setup, all_w, x, y, tt)
                    || (cov.contains(tt) && (all_w || front_f64(&t64, x64, y64, t64v)));
                let cert = certainty_f64(qw, rw, wide(x), wide(y), t64v);
                let inside =
                    cert == Certainty::Covered || (claimed && matches!(cert, Certainty::Uncertain));
                pairs += 1;
                hits += u64::from(inside);
                if claimed && !inside {
                    noise[usize::from(cert == Certainty::Degenerate)] += 1;
                }
                // Tile, quad, pixel: every whole-shutter interval, and the window result
                // when the time is in the window.
                let miss_in = |iv: &[TimeInterval<F>; 6]| {
                    iv[..5].iter().any(|i| !i.contains(tt))
                        || (window.contains(tt) && !iv[5].contains(tt))
                };
                let cheap_miss = cheap.iter().any(|i| !i.contains(tt));
                if inside && (culled || miss_in(&ivs) || sub.iter().any(miss_in) || cheap_miss) {
                    misses += 1;
                    eprintln!(
                        "miss: q={q64:?} r={r64:?} tile=({tx},{ty},{level}) x={x64} y={y64} t={t64v} {cert:?} culled={culled} ivs={ivs:?} quad/pixel={sub:?} sub-tile path={cheap:?}"
                    );
                }
            }
        }
    }
    (pairs, misses, hits, noise)
}

proptest! {
    #[test]
    fn tile_tests_are_conservative_f32(seed in any::<u64>()) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let (q, r) = random_triangle(&mut rng, SCREEN);
        let (_, misses, _, _) = check_triangle::<f32>(q, r, &mut rng, 3);
        prop_assert_eq!(misses, 0);
    }

    #[test]
    fn tile_tests_are_conservative_f64(seed in any::<u64>()) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let (q, r) = random_triangle(&mut rng, SCREEN);
        let (_, misses, _, _) = check_triangle::<f64>(q, r, &mut rng, 3);
        prop_assert_eq!(misses, 0);
    }

    #[test]
    fn backface_culling_is_conservative(seed in any::<u64>()) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let (q, r) = random_triangle(&mut rng, SCREEN);
        let t32 = tri::<f32>(q, r, 0).triangle;
        let s64 = MovingTriangle::new(q, r).setup();
        // f32 input decides; dense f64 sampling of the orientation cubic must agree.
        let q32 = t32.q.map(|v| v.map(f64::from));
        let r32 = t32.r.map(|v| v.map(f64::from));
        let s32in64 = MovingTriangle::new(q32, r32).setup();
        match facing(&t32.q, &t32.r) {
            Facing::Back => for i in 0..=2048 {
                let tt = f64::from(i) / 2048.0;
                prop_assert!(s32in64.orientation_at(tt) < 0.0, "t={tt}");
            },
            Facing::Front => for i in 0..=2048 {
                let tt = f64::from(i) / 2048.0;
                prop_assert!(s32in64.orientation_at(tt) > 0.0, "t={tt}");
            },
            Facing::Mixed => {}
        }
        if facing(&q, &r) == Facing::Back {
            for i in 0..=2048 {
                prop_assert!(s64.orientation_at(f64::from(i) / 2048.0) < 0.0);
            }
        }
    }

    #[test]
    fn facing_windows_match_dense_sampling(seed in any::<u64>()) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let (q, r) = random_triangle(&mut rng, SCREEN);
        for hidden in [Facing::Back, Facing::Front] {
            for c in [
                check_facing_windows::<f64>(q, r, hidden, 4096),
                check_facing_windows::<f32>(q, r, hidden, 4096),
            ] {
                prop_assert_eq!(c.misses, 0, "{:?}", c);
                // Kept hidden time lies next to a root: within 2⁻⁶ of the shutter of an
                // instant that is not clearly hidden.
                prop_assert!(c.kept_reach <= 1.0 / 64.0, "{:?}", c);
            }
        }
    }

    #[test]
    fn all_traversals_match_brute_force(seed in any::<u64>()) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let n = rng.random_range(1..5usize);
        let tris: Vec<_> = (0..n).map(|i| {
            let (q, r) = random_triangle(&mut rng, 40.0);
            (q, r, i as u32)
        }).collect();
        // One level configuration and one footprint per case (16 → 8 → 4, down to quads,
        // down to pixels; samples spread over the pixel or at its centre), so the suite
        // costs what one configuration costs.
        let levels = [LEVELS[(seed / 2 % 3) as usize]];
        let footprint = Footprint::ALL[(seed / 6 % 2) as usize];
        if seed % 2 == 0 {
            let t: Vec<_> = tris.iter().map(|(q, r, i)| tri::<f32>(*q, *r, *i)).collect();
            check_levels_in(40, 24, 4, &t, &levels, footprint);
        } else {
            let t: Vec<_> = tris.iter().map(|(q, r, i)| tri::<f64>(*q, *r, *i)).collect();
            check_levels_in(40, 24, 4, &t, &levels, footprint);
        }
    }
}

/// The deep-CI report (seed 16590656960658491793) replayed through the same path: its f32
/// triangle collapses to a segment at t ≈ 0.95006, edge-eqn's f32 coverage reports a span a
/// few ulps long there for a point on the segment's line outside the triangle, and the f64
/// reference proves that pair uncovered; no pair that is or may be covered is missed.
#[test]
fn deep_ci_seed_16590656960658491793_rounding_only_hit_is_not_a_miss() {
    // The reported vertices (generated before kind 7 became "collapsing"; that kind's mirror
    // draws no random numbers, so the tiles, points and times that follow are the same).
    let q = [
        [39.6308386041319, 75.80659827527666, 1.0903443902340528],
        [69.75287257713141, 54.91686773491771, 0.9101015718940324],
        [57.38562839120724, 78.50066084994533, 1.2141166464273367],
    ];
    let r = [
        [1.5858846883097408, 54.84881679077027, 0.8829102578062236],
        [25.923637533758598, 43.22266499223, 0.8864969606378891],
        [-15.30579894349728, 97.4408155257048, 1.4216791500726527],
    ];
    let mut rng = Pcg64::seed_from_u64(16590656960658491793);
    let (q_gen, _) = random_triangle(&mut rng, SCREEN);
    assert_eq!(q_gen, q);
    let (pairs, misses, hits, noise) = check_triangle::<f32>(q, r, &mut rng, 3);
    assert_eq!(misses, 0);
    assert!(
        noise[0] >= 1 && hits > 0 && pairs > 0,
        "{pairs} {hits} {noise:?}"
    );
}

/// The deep conservativeness run: millions of (sample, triangle) pairs with MBLUR_DEEP=1.
#[test]
fn tile_tests_conservative_many_pairs() {
    let deep = std::env::var("MBLUR_DEEP").is_ok_and(|v| v == "1");
    let triangles = if deep { 6000 } else { 300 };
    let mut rng = Pcg64::seed_from_u64(0x5eed);
    let (mut pairs, mut misses, mut hits, mut noise) = (0, 0, 0, [0u64; 2]);
    for i in 0..triangles {
        let (q, r) = random_triangle(&mut rng, SCREEN);
        let (p, m, h, n) = if i % 2 == 0 {
            check_triangle::<f32>(q, r, &mut rng, 8)
        } else {
            check_triangle::<f64>(q, r, &mut rng, 8)
        };
        pairs += p;
        misses += m;
        hits += h;
        noise[0] += n[0];
        noise[1] += n[1];
    }
    eprintln!(
        "tile-test conservativeness: {pairs} (sample, time, triangle) pairs x 5 edge tests x (tile, 2x2 quad, pixel), {hits} covered, {misses} misses, rounding-only hits: {} proved uncovered, {} at degenerate instants",
        noise[0], noise[1]
    );
    assert_eq!(misses, 0);
    assert!(hits * 20 > pairs, "too few covered pairs to be meaningful");
    assert!(pairs > if deep { 2_000_000 } else { 100_000 });
}
