//! Hard cases by name (issue 9): each is checked bit for bit against the brute-force
//! reference for every traversal, plus the case's own expectation.

mod common;

use common::{
    ALL, Certainty, LEVELS, certainty_f64, check_all, check_levels, check_levels_in, render,
    render_levels, tri,
};
use num_traits::Float;
use raster_hier::{
    EdgeTest, Footprint, Rect, TileTester, Traversal, covered, facing, frustum_interval,
    screen_bound,
};

fn counters_of(v: &[(Traversal, raster_hier::Counters)], t: Traversal) -> raster_hier::Counters {
    v.iter()
        .find(|(tr, _)| *tr == t)
        .map(|(_, c)| *c)
        .expect("traversal present")
}

#[test]
fn triangle_crossing_w_zero_during_shutter() {
    // Vertex 0 starts in front (w = 1) and ends behind the eye (w = -0.5).
    let q = [[8.0, 8.0, 1.0], [30.0, 10.0, 1.0], [12.0, 28.0, 1.0]];
    let r = [[-4.0, 8.0, -0.5], [34.0, 12.0, 1.0], [14.0, 30.0, 1.2]];
    for f32_case in [true, false] {
        let v = if f32_case {
            let c = check_all::<f32>(48, 40, 4, &[tri(q, r, 1)]);
            c.iter().map(|(_, c)| c.samples_written).collect::<Vec<_>>()
        } else {
            let c = check_all::<f64>(48, 40, 4, &[tri(q, r, 1)]);
            c.iter().map(|(_, c)| c.samples_written).collect::<Vec<_>>()
        };
        assert!(v.iter().all(|&n| n == v[0] && n > 0), "{v:?}");
    }
}

#[test]
fn triangle_entirely_behind_the_eye() {
    let q = [[8.0, 8.0, -1.0], [-30.0, 10.0, -1.0], [12.0, 28.0, -2.0]];
    let r = q.map(|[x, y, w]| [x + 5.0, y, w]);
    for tr in ALL {
        let (_, c) = render::<f32>(32, 32, 4, &[tri(q, r, 0)], tr, false);
        assert_eq!(c.frustum_culled, 1, "{tr:?}");
        assert_eq!(
            c.sample_tests + c.tile_tests + c.samples_written,
            0,
            "{tr:?}"
        );
    }
}

#[test]
fn sliver_triangle_spanning_the_screen() {
    // 0.05 px thick, corner to corner, moving 3 px down.
    let q = [[0.5, 0.7, 1.0], [63.5, 60.3, 1.0], [63.5, 60.35, 1.0]];
    let r = q.map(|[x, y, w]| [x, y + 3.0, w]);
    let c = check_all::<f32>(64, 64, 16, &[tri(q, r, 2)]);
    let bbox = counters_of(&c, Traversal::Bbox);
    let our = counters_of(&c, Traversal::Our(EdgeTest::LinearisedPerTile));
    assert!(
        our.sample_tests * 4 < bbox.sample_tests,
        "{our:?} vs {bbox:?}"
    );
    check_all::<f64>(64, 64, 16, &[tri(q, r, 2)]);
}

#[test]
fn subpixel_triangle_moving_200_pixels() {
    let q = [[10.2, 20.1, 1.0], [10.8, 20.2, 1.0], [10.4, 20.7, 1.0]];
    let r = q.map(|[x, y, w]| [x + 200.0, y + 3.0, w]);
    let c = check_all::<f32>(224, 32, 16, &[tri(q, r, 3)]);
    let fallback = counters_of(&c, Traversal::OurFallback(EdgeTest::LinearisedSetup));
    assert_eq!(fallback.fallbacks, 1);
    let bbox = counters_of(&c, Traversal::Bbox);
    let our = counters_of(&c, Traversal::Our(EdgeTest::LinearisedSetup));
    assert!(
        our.sample_tests * 10 < bbox.sample_tests,
        "{our:?} vs {bbox:?}"
    );
    assert!(bbox.samples_written > 0);
}

/// Finest 4x4 tiles of a 64x64 image that a static triangle overlaps, by the separating
/// axis theorem in f64 (an independent count of what a static hierarchical rasteriser visits).
fn sat_tiles(p: [[f64; 2]; 3]) -> u64 {
    sat_cells(p, 4.0)
}

/// Cells of side `s` of a 64x64 image that a static triangle overlaps (separating axes).
fn sat_cells(p: [[f64; 2]; 3], s: f64) -> u64 {
    let cells = (64.0 / s) as u32;
    let mut n = 0;
    for ty in 0..cells {
        for tx in 0..cells {
            let (x0, y0) = (f64::from(tx) * s, f64::from(ty) * s);
            let rect = [[x0, y0], [x0 + s, y0], [x0, y0 + s], [x0 + s, y0 + s]];
            let mut axes = vec![[1.0, 0.0], [0.0, 1.0]];
            for i in 0..3 {
                let (a, b) = (p[i], p[(i + 1) % 3]);
                axes.push([b[1] - a[1], a[0] - b[0]]);
            }
            let separated = axes.iter().any(|ax| {
                let proj = |v: &[f64; 2]| v[0] * ax[0] + v[1] * ax[1];
                let (tmin, tmax) = p
                    .iter()
                    .map(proj)
                    .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
                let (rmin, rmax) = rect
                    .iter()
                    .map(proj)
                    .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
                tmax < rmin || rmax < tmin
            });
            if !separated {
                n += 1;
            }
        }
    }
    n
}

#[test]
fn static_triangle_costs_what_a_static_hierarchical_rasteriser_costs() {
    let p = [[3.3, 5.1, 1.0], [41.7, 9.9, 1.0], [13.1, 50.6, 1.0]];
    let c = check_all::<f32>(64, 64, 16, &[tri(p, p, 4)]);
    let expected = sat_tiles([[3.3, 5.1], [41.7, 9.9], [13.1, 50.6]]) * 256;
    for tr in [
        Traversal::Convex,
        Traversal::Our(EdgeTest::LinearisedSetup),
        Traversal::Our(EdgeTest::LinearisedPerTile),
        Traversal::Our(EdgeTest::Exact),
        Traversal::Our(EdgeTest::LinearisedPerLevel),
        Traversal::Our(EdgeTest::ExactFinest),
        Traversal::OurFallback(EdgeTest::LinearisedSetup),
    ] {
        let k = counters_of(&c, tr);
        assert_eq!(k.sample_tests, expected, "{tr:?}");
        assert_eq!(k.fallbacks, 0);
    }
}

#[test]
fn triangle_entering_the_frustum_mid_shutter() {
    // Entirely left of the screen at t = 0; its right-most vertex crosses x = 0 at t = 0.5.
    let q = [[-40.0, 4.0, 1.0], [-20.0, 6.0, 1.0], [-36.0, 24.0, 1.0]];
    let r = q.map(|[x, y, w]| [x + 40.0, y, w]);
    let iv = frustum_interval(
        &tri::<f64>(q, r, 0).triangle.q,
        &tri::<f64>(q, r, 0).triangle.r,
        32.0,
        32.0,
    );
    assert!((iv.lo - 0.5).abs() < 1e-6 && iv.hi == 1.0, "{iv:?}");
    let c = check_all::<f32>(32, 32, 16, &[tri(q, r, 5)]);
    let (buf, our) = render::<f32>(
        32,
        32,
        16,
        &[tri(q, r, 5)],
        Traversal::Our(EdgeTest::LinearisedSetup),
        false,
    );
    let bbox = counters_of(&c, Traversal::Bbox);
    assert!(our.samples_written > 0 && our.sample_tests < bbox.sample_tests);
    buf.for_each_sample(|_, _, _, _, t, _, id| {
        if id != raster_hier::NO_HIT {
            assert!(t >= 0.5 - 1e-6);
        }
    });
}

#[test]
fn back_facing_for_half_the_shutter() {
    // Vertex 2 crosses the opposite edge at t = 0.5: front-facing, then back-facing.
    let q = [[4.0, 4.0, 1.0], [28.0, 4.0, 1.0], [16.0, 24.0, 1.0]];
    let mut r = q;
    r[2] = [16.0, -16.0, 1.0];
    let t = tri::<f32>(q, r, 6);
    assert!(!raster_hier::is_backfacing(&t.triangle.q, &t.triangle.r));
    let setup = t.triangle.setup();
    assert!(setup.orientation_at(0.25) * setup.orientation_at(0.75) < 0.0);
    check_all::<f32>(32, 32, 16, &[t]);
    // With back-face culling it is kept (front-facing for half the shutter) and drawn
    // in full, both halves.
    let (_, c) = render::<f32>(32, 32, 16, &[t], Traversal::Our(EdgeTest::Exact), true);
    assert_eq!(c.backface_culled, 0);
    let (_, full) = render::<f32>(32, 32, 16, &[t], Traversal::Bbox, false);
    assert_eq!(c.samples_written, full.samples_written);
    // The same triangle reversed at both ends is back-facing throughout and culled.
    let rev = tri::<f32>([q[0], q[2], q[1]], [q[0], q[2], q[1]], 7);
    let (_, c) = render::<f32>(32, 32, 16, &[rev], Traversal::Our(EdgeTest::Exact), true);
    assert_eq!(c.backface_culled, 1);
    assert_eq!(c.samples_written, 0);
    // Both halves really are covered: some sample before and after the flip.
    let s = t.triangle.setup();
    assert!(covered(&s, true, 16.0, 6.0, 0.1) && covered(&s, true, 16.0, 2.0, 0.9));
}

#[test]
fn non_finite_triangle_is_rejected_without_nan() {
    let q = [[f64::NAN, 8.0, 1.0], [30.0, 10.0, 1.0], [12.0, 28.0, 1.0]];
    let r = [
        [8.0, 8.0, 1.0],
        [30.0, f64::INFINITY, 1.0],
        [12.0, 28.0, 1.0],
    ];
    for tr in ALL {
        let (buf, c) = render::<f32>(32, 32, 4, &[tri(q, q, 0), tri(q, r, 1)], tr, false);
        assert_eq!(c.frustum_culled, 2, "{tr:?}");
        assert_eq!(c.samples_written, 0);
        assert!(buf.depths().iter().all(|d| *d == f32::INFINITY));
    }
}

#[test]
fn edges_through_sample_positions_exactly() {
    // Dyadic vertices and motion: edges pass exactly through sample positions (offsets are
    // multiples of 1/2^k) at exact sample times; the tile margins must keep those samples.
    let q = [[4.0, 4.0, 1.0], [20.0, 4.0, 1.0], [4.0, 20.0, 1.0]];
    let r = q.map(|[x, y, w]| [x + 8.0, y + 4.0, w]);
    let c = check_all::<f32>(
        32,
        32,
        16,
        &[tri(q, r, 1), tri([q[1], q[0], q[2]], [r[1], r[0], r[2]], 2)],
    );
    assert!(
        c.iter()
            .all(|(_, k)| k.samples_written == c[0].1.samples_written)
    );
    check_all::<f64>(32, 32, 16, &[tri(q, r, 1)]);
}

/// With every sample at its pixel centre, edges through pixel centres at sample times: two
/// triangles sharing a moving edge through centres, each traversal and level configuration
/// against the brute-force reference; every covered sample on the shared edge is written
/// by exactly one of the pair (here the tie rule: the later one), none is lost.
#[test]
fn edges_through_pixel_centres_with_centre_footprint() {
    // Half-integer vertices moving by whole pixels: the shared edge (4.5, 4.5)-(20.5, 20.5)
    // passes through pixel centres at every sample time.
    let q = [[4.5, 4.5, 1.0], [20.5, 4.5, 1.0], [20.5, 20.5, 1.0]];
    let p = [[4.5, 4.5, 1.0], [20.5, 20.5, 1.0], [4.5, 20.5, 1.0]];
    let shift = |v: [[f64; 3]; 3]| v.map(|[x, y, w]| [x + 6.0, y + 2.0, w]);
    let pair32 = [tri::<f32>(q, shift(q), 1), tri::<f32>(p, shift(p), 2)];
    let pair = [tri::<f64>(q, shift(q), 1), tri::<f64>(p, shift(p), 2)];
    check_levels_in::<f32>(32, 32, 16, &pair32, &LEVELS, Footprint::Centre);
    check_levels_in::<f64>(32, 32, 16, &pair, &LEVELS, Footprint::Centre);
    for tr in ALL {
        let (buf, _) =
            render_levels::<f64>(32, 32, 16, &pair, tr, false, LEVELS[0], Footprint::Centre);
        // Strictly inside the moving square, a centre sample (on the diagonal or not) is
        // covered by one of the pair.
        buf.for_each_sample(|_, _, x, y, t, _, id| {
            let (lx, ly) = (x - 6.0 * t, y - 2.0 * t);
            if lx > 4.5 && lx < 20.5 && ly > 4.5 && ly < 20.5 {
                assert!(id == 1 || id == 2, "{tr:?}: ({x}, {y}) at {t} lost");
            }
        });
    }
}

#[test]
fn other_level_configurations_give_the_same_buffer() {
    use raster_hier::{RasterConfig, SampleBuffer, benchmark_scene, rasterise};
    let tris = benchmark_scene::<f32>(40, 10.0, 1.5, 64, 64, 8);
    let mut reference: Option<Vec<u32>> = None;
    // (levels, bin, sub_tile_min_samples)
    for (levels, bin, min) in [
        (vec![16, 8, 4], 16, 0),
        (vec![32, 16, 8, 4], 32, 0),
        (vec![8, 4], 8, 0),
        (vec![4], 4, 0),
        // Below the 4x4 pattern tile: quads and pixels get their own tile tests.
        (vec![16, 8, 4, 2], 16, 0),
        (vec![16, 8, 4, 2, 1], 16, 0),
        (vec![16, 8, 4, 2, 1], 16, 1),
        (vec![16, 8, 4, 2], 16, 3),
        (vec![16, 8, 2], 16, 0),
        (vec![16, 1], 16, 0),
        (vec![8, 4, 2, 1], 8, 0),
        (vec![4, 2, 1], 4, 0),
    ] {
        for tr in ALL {
            let mut buf = SampleBuffer::<f32>::new(64, 64, 4, 4, bin, 4, 11).expect("valid");
            let mut cfg = RasterConfig::new(tr);
            cfg.levels = levels.clone();
            cfg.sub_tile_min_samples = min;
            rasterise(&mut buf, &tris, &cfg).expect("valid");
            let mut ids = Vec::new();
            buf.for_each_sample(|_, _, _, _, _, _, id| ids.push(id));
            match &reference {
                None => reference = Some(ids),
                Some(r) => assert_eq!(r, &ids, "{levels:?} {min} {tr:?}"),
            }
        }
    }
}

#[test]
fn levels_must_end_at_or_below_the_pattern_tile() {
    use raster_hier::{Error, RasterConfig, SampleBuffer};
    let mut buf = SampleBuffer::<f32>::new(32, 32, 4, 4, 16, 4, 1).expect("valid");
    let tris = [tri(
        [[1.0, 1.0, 1.0], [9.0, 1.0, 1.0], [1.0, 9.0, 1.0]],
        [[1.0, 1.0, 1.0], [9.0, 1.0, 1.0], [1.0, 9.0, 1.0]],
        0,
    )];
    for levels in [
        vec![16, 8],
        vec![8, 4, 2],
        vec![16, 8, 4, 3],
        vec![16, 4, 8, 2],
        vec![],
    ] {
        let mut cfg = RasterConfig::new(Traversal::Our(EdgeTest::LinearisedPerLevel));
        cfg.levels = levels.clone();
        assert!(
            matches!(
                raster_hier::rasterise(&mut buf, &tris, &cfg),
                Err(Error::InvalidConfig(_))
            ),
            "{levels:?}"
        );
    }
}

/// Levels below the pattern tile on the sub-pixel triangle moving 200 px: every
/// traversal still matches the brute-force reference at every level configuration, and
/// per-pixel intervals cut the sample tests of the tile-interval traversal to about what
/// the triangle's path needs (its pixels × the time it spends over each).
#[test]
fn subpixel_triangle_moving_200_pixels_with_pixel_levels() {
    let q = [[10.2, 20.1, 1.0], [10.8, 20.2, 1.0], [10.4, 20.7, 1.0]];
    let r = q.map(|[x, y, w]| [x + 200.0, y + 3.0, w]);
    for f32_case in [true, false] {
        let c = if f32_case {
            check_levels::<f32>(224, 32, 16, &[tri(q, r, 3)])
        } else {
            check_levels::<f64>(224, 32, 16, &[tri(q, r, 3)])
        };
        let get = |levels: &[u32], tr: Traversal| {
            c.iter()
                .find(|(l, t, _)| l.as_slice() == levels && *t == tr)
                .map(|(_, _, k)| *k)
                .expect("present")
        };
        let bbox = get(&[16, 8, 4], Traversal::Bbox);
        assert!(bbox.samples_written > 0);
        for m in [
            EdgeTest::LinearisedPerLevel,
            EdgeTest::ExactFinest,
            EdgeTest::Exact,
        ] {
            let tile = get(&[16, 8, 4], Traversal::Our(m));
            let quad = get(&[16, 8, 4, 2], Traversal::Our(m));
            let pixel = get(&[16, 8, 4, 2, 1], Traversal::Our(m));
            // Same coverage; more tile tests, fewer sample tests at each finer level.
            assert!(
                tile.samples_written == pixel.samples_written
                    && quad.samples_written == pixel.samples_written,
                "{m:?}"
            );
            assert!(
                tile.tile_tests < quad.tile_tests && quad.tile_tests < pixel.tile_tests,
                "{m:?}"
            );
            assert!(
                pixel.sample_tests < quad.sample_tests && quad.sample_tests < tile.sample_tests,
                "{m:?}: {} {} {}",
                tile.sample_tests,
                quad.sample_tests,
                pixel.sample_tests
            );
            // The path crosses ~200 pixel columns in 1 px rows of 2-3 pixels; each pixel is
            // overlapped for ~1.6 px / 200 px of the shutter, so ~16 · 3 · 2 · 0.008 samples
            // per column; with tile intervals every pixel of a 4x4 tile is tested over the
            // tile's interval instead.
            assert!(pixel.sample_tests * 3 < tile.sample_tests, "{m:?}");
        }
    }
}

/// A static triangle with levels down to single pixels costs what a static per-pixel
/// rasteriser costs: the samples of exactly the pixels the triangle overlaps (separating
/// axis theorem in f64).
#[test]
fn static_triangle_with_pixel_levels_tests_only_overlapped_pixels() {
    let p = [[3.3, 5.1, 1.0], [41.7, 9.9, 1.0], [13.1, 50.6, 1.0]];
    let c = check_levels::<f32>(64, 64, 16, &[tri(p, p, 4)]);
    let expected = sat_cells([[3.3, 5.1], [41.7, 9.9], [13.1, 50.6]], 1.0) * 16;
    for m in [
        EdgeTest::LinearisedSetup,
        EdgeTest::LinearisedPerTile,
        EdgeTest::Exact,
        EdgeTest::LinearisedPerLevel,
        EdgeTest::ExactFinest,
    ] {
        let k = c
            .iter()
            .find(|(l, t, _)| l.as_slice() == [16, 8, 4, 2, 1] && *t == Traversal::Our(m))
            .map(|(_, _, k)| *k)
            .expect("present");
        assert_eq!(k.sample_tests, expected, "{m:?}");
    }
}

#[test]
fn occluded_moving_triangle_is_zmax_culled() {
    // A near full-screen static quad (w = 1) drawn first, then a far triangle (w = 3)
    // moving behind it: whole tiles are culled by the time-dependent z-max, and the buffer
    // still equals the brute-force reference.
    let quad = [
        tri(
            [[-8.0, -8.0, 1.0], [48.0, -8.0, 1.0], [-8.0, 48.0, 1.0]],
            [[-8.0, -8.0, 1.0], [48.0, -8.0, 1.0], [-8.0, 48.0, 1.0]],
            1,
        ),
        tri(
            [[48.0, -8.0, 1.0], [48.0, 48.0, 1.0], [-8.0, 48.0, 1.0]],
            [[48.0, -8.0, 1.0], [48.0, 48.0, 1.0], [-8.0, 48.0, 1.0]],
            2,
        ),
    ];
    let far = |x: f64| {
        [
            [x * 3.0, 6.0, 3.0],
            [(x + 14.0) * 3.0, 6.0 * 3.0, 3.0],
            [x * 3.0, 20.0 * 3.0, 3.0],
        ]
    };
    let scene = [quad[0], quad[1], tri(far(4.0), far(14.0), 3)];
    let c = check_all::<f32>(32, 32, 16, &scene);
    for (tr, k) in &c {
        assert!(k.zmax_culls > 0, "{tr:?}: {k:?}");
    }
}

/// Deep-CI report (seed 16590656960658491793, regression cc 1de8f34d…): 2DH vertices at open
/// and close of a triangle whose orientation cubic has a root at t ≈ 0.95006 (it collapses
/// to a segment and flips), with the sample (32.48…, 48.96…) on the line through the
/// collapsed triangle, 0.8 px beyond vertex 1, at t = 0.95004… .
const DEGENERATE_Q: [[f64; 3]; 3] = [
    [39.6308386041319, 75.80659827527666, 1.0903443902340528],
    [69.75287257713141, 54.91686773491771, 0.9101015718940324],
    [57.38562839120724, 78.50066084994533, 1.2141166464273367],
];
const DEGENERATE_R: [[f64; 3]; 3] = [
    [1.5858846883097408, 54.84881679077027, 0.8829102578062236],
    [25.923637533758598, 43.22266499223, 0.8864969606378891],
    [-15.30579894349728, 97.4408155257048, 1.4216791500726527],
];

fn degenerate_instant_case<F: Float + Send + Sync + core::fmt::Debug>() {
    let (x64, y64, t64) = (32.48118573004146, 48.96392804927663, 0.9500454068183899);
    let tri = tri::<F>(DEGENERATE_Q, DEGENERATE_R, 0).triangle;
    let (q, r) = (tri.q, tri.r);
    let w = |v: F| v.to_f64().expect("finite");
    // The triangle, point and time exactly as the rasteriser sees them, widened to f64.
    let (q64, r64) = (q.map(|p| p.map(w)), r.map(|p| p.map(w)));
    let f = |v: f64| F::from(v).expect("finite");
    let (x, y, t) = (f(x64), f(y64), f(t64));
    let (xs, ys, ts) = (w(x), w(y), w(t));

    // The tile tests exactly as the property suite runs them (tile 32..48 x 48..64).
    let setup = tri.setup();
    let size = f(64.0);
    let frustum = frustum_interval(&q, &r, size, size);
    let bound = screen_bound(&q, &r, frustum, size, size);
    let tester = TileTester::new(&q, &r, *setup.edges(), facing(&q, &r), frustum, bound.rect);
    let tile = Rect::new(f(32.0), f(48.0), f(48.0), f(64.0));
    let per_tile = tester.linearise(tile.intersect(&bound.rect));
    let ivs = [
        tester.test(&tile, EdgeTest::LinearisedSetup, &tester.setup),
        tester.test(&tile, EdgeTest::LinearisedPerTile, &per_tile),
        tester.test(&tile, EdgeTest::Exact, &tester.setup),
    ];

    // 1. The reported pair is not covered: the f64 reference with an error bound proves two
    //    edges have opposite signs at (x, y, t), and at every time of a dense grid.
    assert_eq!(certainty_f64(q64, r64, xs, ys, ts), Certainty::NotCovered);
    for i in 0..=100_000 {
        let tt = f64::from(i) / 100_000.0;
        assert_ne!(
            certainty_f64(q64, r64, xs, ys, tt),
            Certainty::Covered,
            "t={tt}"
        );
    }
    // 2. Why the box test may reject it: at t every projected vertex is left of the tile
    //    (max x/w ≈ 31.67 < 32), so the triangle's projection cannot reach x = 32.48.
    for i in 0..3 {
        let p: [f64; 3] = core::array::from_fn(|c| q64[i][c] + ts * (r64[i][c] - q64[i][c]));
        assert!(p[2] > 0.0 && p[0] / p[2] < 31.7, "vertex {i}: {p:?}");
    }
    // 3. t sits at the degenerate instant: the 2DH determinant changes sign within 1e-4.
    let s64 = edge_eqn::MovingTriangle::new(q64, r64).setup();
    assert!(s64.orientation_at(ts - 1e-4) * s64.orientation_at(ts + 1e-4) < 0.0);
    // So any span of F coverage containing t is rounding of three edge values that are all
    // at noise level, never longer than a few ulps of t.
    for span in setup.coverage(x, y).iter().filter(|s| s.contains(t)) {
        assert!(w(span.len()) < 1e-5, "{span:?}");
    }
    // 4. The tile intervals are conservative against the independent reference over the
    //    whole tile: every (point, time) that the f64 evaluation finds covered or cannot
    //    decide (within the error bound, triangle not degenerate at t) lies in every
    //    edge-test variant's interval.
    let mut checked = 0u32;
    for j in 0..=32 {
        for i in 0..=32 {
            let (px, py) = (f(32.0 + 0.5 * f64::from(i)), f(48.0 + 0.5 * f64::from(j)));
            for k in 0..=1024 {
                let tt = f(f64::from(k) / 1024.0);
                let c = certainty_f64(q64, r64, w(px), w(py), w(tt));
                if matches!(c, Certainty::Covered | Certainty::Uncertain) {
                    checked += 1;
                    for iv in &ivs {
                        assert!(iv.contains(tt), "({px:?}, {py:?}) t={tt:?} {c:?} {ivs:?}");
                    }
                }
            }
        }
    }
    // The tile is covered for much of the shutter, so step 4 is not vacuous.
    assert!(checked > 10_000, "{checked}");
    // 5. Every traversal renders it bit for bit like the brute-force reference.
    check_all::<F>(64, 64, 4, &[common::tri(DEGENERATE_Q, DEGENERATE_R, 1)]);
}

#[test]
fn sample_on_the_line_of_a_collapsing_triangle_is_not_a_tile_miss_f32() {
    degenerate_instant_case::<f32>();
}

#[test]
fn sample_on_the_line_of_a_collapsing_triangle_is_not_a_tile_miss_f64() {
    degenerate_instant_case::<f64>();
}

/// A triangle turning 180° about the screen centre, given as `pieces` chords whose ends lie
/// on the arc, piece k (id k) over its span [k / n, (k + 1) / n] (the `span` of
/// `RasterTriangle`). Every traversal matches the brute-force reference bit for bit, and
/// against an independent f64 evaluation of the given chords at the sample's local time:
/// a sample the piece holding its time certainly covers is written by that piece (or, at
/// a shared end, its neighbour), a sample no piece holding its time can cover stays empty
/// (no piece is drawn outside its span; no gap at the boundaries).
fn pieces_of_a_turning_triangle<F: Float + Send + Sync + core::fmt::Debug>(pieces: u32) {
    let corner = |k: usize, t: f64| {
        let a = std::f64::consts::PI * t + std::f64::consts::TAU * k as f64 / 3.0;
        [16.0 + 12.0 * a.cos(), 16.0 + 12.0 * a.sin(), 1.0]
    };
    let at = |t: f64| [0, 1, 2].map(|k| corner(k, t));
    let n = f64::from(pieces);
    let given: Vec<_> = (0..pieces)
        .map(|k| (at(f64::from(k) / n), at(f64::from(k + 1) / n)))
        .collect();
    let tris: Vec<raster_hier::RasterTriangle<F>> = given
        .iter()
        .enumerate()
        .map(|(k, (q, r))| {
            let mut t = tri::<F>(*q, *r, k as u32);
            let f = |v: f64| F::from(v).expect("span");
            t.span = raster_hier::TimeInterval::new(f(k as f64 / n), f((k + 1) as f64 / n));
            t
        })
        .collect();
    check_all::<F>(32, 32, 16, &tris);
    let (buf, _) = render::<F>(
        32,
        32,
        16,
        &tris,
        Traversal::Our(EdgeTest::LinearisedPerLevel),
        false,
    );
    let (mut covered_seen, mut checked) = (0, 0);
    let f64_of = |v: F| v.to_f64().expect("finite");
    let as_f = |v: [[f64; 3]; 3]| v.map(|p| p.map(|x| f64_of(F::from(x).expect("finite"))));
    buf.for_each_sample(|_, _, x, y, t, _, id| {
        let (x, y, t) = (f64_of(x), f64_of(y), f64_of(t));
        let holding: Vec<usize> = (0..pieces as usize)
            .filter(|&k| k as f64 / n <= t && t <= (k + 1) as f64 / n)
            .collect();
        let says: Vec<Certainty> = holding
            .iter()
            .map(|&k| {
                let u = (t - k as f64 / n) * n;
                certainty_f64(as_f(given[k].0), as_f(given[k].1), x, y, u)
            })
            .collect();
        checked += 1;
        if says.contains(&Certainty::Covered) {
            covered_seen += 1;
            assert!(
                holding.iter().any(|&k| k as u32 == id),
                "sample ({x}, {y}, {t}) covered by pieces {holding:?} got id {id}"
            );
        } else if says.iter().all(|c| *c == Certainty::NotCovered) {
            assert_eq!(id, raster_hier::NO_HIT, "sample ({x}, {y}, {t})");
        }
    });
    // Not vacuous (one chord of the half turn shrinks through the centre: few samples).
    assert!(covered_seen > checked / 32, "{covered_seen} of {checked}");
}

#[test]
fn pieces_of_a_curved_path_take_only_their_span_f64() {
    for pieces in [1, 2, 3, 8] {
        pieces_of_a_turning_triangle::<f64>(pieces);
    }
}

#[test]
fn pieces_of_a_curved_path_take_only_their_span_f32() {
    for pieces in [2, 3, 8] {
        pieces_of_a_turning_triangle::<f32>(pieces);
    }
}

/// [`raster_hier::facing_windows`] of a named case against dense sampling (f64 and f32
/// input, both hidden windings): nothing the triangle may show is removed, and kept hidden
/// time lies next to a root. Returns the f64 windows for `hidden`.
fn windows_case(
    q: [[f64; 3]; 3],
    r: [[f64; 3]; 3],
    hidden: raster_hier::Facing,
) -> raster_hier::FacingWindows {
    use raster_hier::Facing;
    for h in [Facing::Back, Facing::Front] {
        for c in [
            common::check_facing_windows::<f64>(q, r, h, 8192),
            common::check_facing_windows::<f32>(q, r, h, 8192),
        ] {
            assert_eq!(c.misses, 0, "{h:?} {c:?}");
            assert!(c.kept_reach <= 1.0 / 64.0, "{h:?} {c:?}");
        }
    }
    raster_hier::facing_windows(&q, &r, hidden)
}

/// Two vertices shrink into the first and grow out again: det = 16 (2t − 1)², positive but
/// for a tangent root at t = ½ (the triangle is a point there). Culling the front windings
/// keeps only a sliver of time around ½; culling the back windings keeps everything.
#[test]
fn facing_windows_tangent_root() {
    use raster_hier::Facing;
    let q = [[0.0, 0.0, 1.0], [-4.0, 0.0, 1.0], [0.0, -4.0, 1.0]];
    let r = [[0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 4.0, 1.0]];
    let w = windows_case(q, r, Facing::Front);
    assert!(w.contains(0.5) && w.len() < 1e-3, "{w:?}");
    assert!(windows_case(q, r, Facing::Back).is_all());
    // Lifted off zero by 10⁻⁹ of its size: no root, but a tangent point all the same.
    let lift = [
        [0.0, 0.0, 1.0],
        [4.0, 0.0, 1.0],
        [0.0, 4.0 * (1.0 + 1e-9), 1.0],
    ];
    let (q2, r2) = (
        [q[0], q[1], [lift[2][0], -4.0, 1.0]],
        [r[0], r[1], [0.0, 4.0, 1.0]],
    );
    let w = windows_case(q2, r2, Facing::Front);
    assert!(w.len() < 1e-3, "{w:?}");
}

/// det = 16 t (root at the span's start) and det = 16 (t − 1) (root at its end): the whole
/// span but a sliver at the root is removed.
#[test]
fn facing_windows_root_at_span_end() {
    use raster_hier::Facing;
    let start = (
        [[0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 0.0, 1.0]],
        [[0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 4.0, 1.0]],
    );
    let w = windows_case(start.0, start.1, Facing::Front);
    assert!(w.contains(0.0) && w.len() < 1e-3, "{w:?}");
    let end = (
        [[0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, -4.0, 1.0]],
        [[0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 0.0, 1.0]],
    );
    let w = windows_case(end.0, end.1, Facing::Back);
    assert!(w.contains(1.0) && w.len() < 1e-3, "{w:?}");
}

/// A triangle collinear for the whole shutter (its vertices slide along one line) and one
/// whose vertices coincide: the orientation is identically zero and nothing is removed.
#[test]
fn facing_windows_degenerate_and_identically_zero_orientation() {
    use raster_hier::Facing;
    let line = |s: f64| [[s, s, 1.0], [2.0 + s, 2.0 + s, 1.0], [5.0, 5.0, 1.0]];
    for hidden in [Facing::Back, Facing::Front] {
        assert!(windows_case(line(0.0), line(3.0), hidden).is_all());
        let point = [[1.0, 2.0, 1.0]; 3];
        assert!(windows_case(point, point, hidden).is_all());
    }
}

/// The triangle of the deep-CI report that collapses to a segment and flips at t ≈ 0.95006:
/// one window on each side of the flip.
#[test]
fn facing_windows_collapse_and_flip() {
    use raster_hier::Facing;
    let (front, back) = (
        windows_case(DEGENERATE_Q, DEGENERATE_R, Facing::Back),
        windows_case(DEGENERATE_Q, DEGENERATE_R, Facing::Front),
    );
    // Front windings from the flip on, back ones up to it, overlapping by a few 10⁻⁶
    // around it.
    let (from, to) = (front.as_slice()[0][0], back.as_slice()[0][1]);
    assert!(from < to && to - from < 1e-5, "{front:?} {back:?}");
    assert!((from - 0.95005).abs() < 1e-4 && front.contains(1.0) && back.contains(0.0));
    assert!(
        (front.len() + back.len() - 1.0).abs() < 1e-3,
        "{front:?} {back:?}"
    );
}

/// det = (t − 0.2)(t − 0.5)(t − 0.8) (an upper-triangular 2DH matrix; one w crosses zero):
/// three simple roots, two windows for each hidden winding.
#[test]
fn facing_windows_three_roots() {
    use raster_hier::Facing;
    let q = [[-0.2, 0.0, 1.0], [0.0, -0.5, 1.0], [0.0, 0.0, -0.8]];
    let r = [[0.8, 0.0, 1.0], [0.0, 0.5, 1.0], [0.0, 0.0, 0.2]];
    let w = windows_case(q, r, Facing::Back);
    assert_eq!(w.as_slice().len(), 2, "{w:?}");
    assert!(w.contains(0.21) && w.contains(0.49) && w.contains(0.81) && w.contains(1.0));
    assert!(!w.contains(0.1) && !w.contains(0.65), "{w:?}");
    let w = windows_case(q, r, Facing::Front);
    assert_eq!(w.as_slice().len(), 2, "{w:?}");
    assert!(w.contains(0.0) && w.contains(0.19) && w.contains(0.51) && w.contains(0.79));
}

/// Perspective motion whose orientation cubic has a leading coefficient 10⁻¹² of its
/// others (w changes by 10⁻¹² of itself): the derivative's quadratic solve must not blow
/// up, and the one root is found.
#[test]
fn facing_windows_near_zero_leading_coefficient() {
    use raster_hier::Facing;
    let q = [[0.0, 0.0, 1.0], [4.0, 0.0, 1.0], [0.0, 4.0, 1.0]];
    let r = [
        [0.0, 0.0, 1.0 + 1e-12],
        [4.0, 1.0, 1.0],
        [8.0, -4.0, 1.0 + 1e-12],
    ];
    let w = windows_case(q, r, Facing::Back);
    assert_eq!(w.as_slice().len(), 1, "{w:?}");
    assert!(
        w.as_slice()[0][0] == 0.0 && w.as_slice()[0][1] < 1.0,
        "{w:?}"
    );
}
