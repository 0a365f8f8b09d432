//! Property tests (case count from PROPTEST_CASES): time ranges against brute-force
//! scans, GetXY against the binomial matrix product at random large m, the tile iterator
//! against direct per-sample evaluation, the exact discrepancy against brute force, the
//! rank criterion against exhaustive counting, and scrambling against the net check.

mod common;

use common::{dense_apply, dense_c1_prime, dense_c2_prime, pascal_mod2};
use proptest::prelude::*;
use tmsnet::quality::{net_violation, star_discrepancy};
use tmsnet::{BitMatrix, DigitalNet, Scramble, TileLayout, TileSampler, get_xy, time_index_range};

/// Times near sample times: `j / 2^m` nudged by a few ulps, or arbitrary values in a
/// range wider than [0, 1].
fn time_near(m: u32) -> impl Strategy<Value = f64> {
    prop_oneof![
        (0u64..=(1u64 << m), -3i64..=3).prop_map(move |(j, ulps)| {
            let t = j as f64 / (1u64 << m) as f64;
            let bits = t.to_bits() as i64 + ulps;
            if t == 0.0 && ulps < 0 {
                -f64::from_bits((-ulps) as u64)
            } else {
                f64::from_bits(bits.max(0) as u64)
            }
        }),
        -0.5f64..1.5,
    ]
}

proptest! {
    #[test]
    fn time_range_equals_brute_force_scan((m, t0, t1) in (1u32..=10).prop_flat_map(|m| (Just(m), time_near(m), time_near(m)))) {
        let r = time_index_range(t0, t1, m).unwrap();
        let n = 1u32 << m;
        let want: Vec<u32> = (0..n).filter(|&j| {
            let t = f64::from(j) / f64::from(n);
            t0 <= t && t <= t1
        }).collect();
        let got: Vec<u32> = r.clone().collect();
        prop_assert_eq!(got, want);
        prop_assert!(r.start <= n && r.end <= n);
    }

    #[test]
    fn time_range_boundaries_exact_at_large_m(m in 11u32..=31, t0 in -0.1f64..1.1, t1 in -0.1f64..1.1) {
        // O(1) check of the range ends with exact f64 arithmetic (j / 2^m is exact).
        let r = time_index_range(t0, t1, m).unwrap();
        let n = 1u64 << m;
        let t = |j: u64| j as f64 / n as f64;
        if !r.is_empty() {
            prop_assert!(t(u64::from(r.start)) >= t0 && t(u64::from(r.end - 1)) <= t1);
            if r.start > 0 { prop_assert!(t(u64::from(r.start) - 1) < t0); }
            if u64::from(r.end) < n { prop_assert!(t(u64::from(r.end)) > t1); }
        } else {
            // No sample time between t0 and t1: the first j >= t0 is past t1 (or there is none).
            let first = (t0 * n as f64).ceil().max(0.0) as u64;
            prop_assert!(first >= n || t(first) > t1);
        }
    }

    #[test]
    fn time_range_f32_matches_f64(m in 1u32..=31, t0 in -0.1f32..1.1, t1 in -0.1f32..1.1) {
        prop_assert_eq!(
            time_index_range(t0, t1, m).unwrap(),
            time_index_range(f64::from(t0), f64::from(t1), m).unwrap()
        );
    }

    #[test]
    fn get_xy_equals_matrix_product_for_random_j_at_large_m(m in 17u32..=31, j in any::<u32>()) {
        let j = j & (u32::MAX >> (32 - m));
        let p = pascal_mod2(33);
        let want = (
            dense_apply(&dense_c1_prime(&p, m), j, m),
            dense_apply(&dense_c2_prime(&p, m), j, m),
        );
        prop_assert_eq!(get_xy(j, m).unwrap(), want);
    }

    #[test]
    fn tile_iterator_yields_exactly_the_samples_in_range(
        a in 0u32..=4, b in 0u32..=4, s in 0u32..=6, tx in any::<u32>(), ty in any::<u32>(),
        seed in any::<u64>(), t0 in -0.1f64..1.1, t1 in -0.1f64..1.1,
    ) {
        prop_assume!(a + b + s >= 1);
        let layout = TileLayout::new(1 << a, 1 << b, 1 << s).unwrap();
        let m = layout.m();
        let tile = TileSampler::new(layout, tx, ty, seed).unwrap();
        let got: Vec<_> = tile.samples_in(t0, t1).unwrap().collect();
        let n = 1u32 << m;
        let want: Vec<u32> = (0..n).filter(|&j| {
            let t = f64::from(j) / f64::from(n);
            t0 <= t && t <= t1
        }).collect();
        prop_assert_eq!(got.iter().map(|s| s.index).collect::<Vec<_>>(), want);
        let scr = Scramble::for_tile(tx, ty, seed);
        for smp in &got {
            let direct = tile.sample::<f64>(smp.index).unwrap();
            prop_assert_eq!(smp, &direct);
            // Scrambled GetXY, independently of the tile's incremental iterator.
            let (x, y) = get_xy(smp.index, m).unwrap();
            prop_assert_eq!((smp.x, smp.y), scr.apply(x, y, m));
            // Fixed point back from pixel + offset, exact in f64.
            let (bx, by) = (layout.sub_bits_x(), layout.sub_bits_y());
            let pos = smp.position();
            prop_assert_eq!(pos[0] * f64::from(1u32 << bx), f64::from(smp.x));
            prop_assert_eq!(pos[1] * f64::from(1u32 << by), f64::from(smp.y));
            prop_assert!(smp.pixel[0] < layout.width() && smp.pixel[1] < layout.height());
            prop_assert!((0.0..1.0).contains(&smp.offset[0]) && (0.0..1.0).contains(&smp.offset[1]));
            prop_assert_eq!(smp.t, f64::from(smp.index) / f64::from(n));
        }
    }

    #[test]
    fn f32_samples_are_f64_samples_rounded(seed in any::<u64>(), j in 0u32..256) {
        let tile = TileSampler::new(TileLayout::new(4, 4, 16).unwrap(), 7, 1, seed).unwrap();
        let a = tile.sample::<f32>(j).unwrap();
        let b = tile.sample::<f64>(j).unwrap();
        prop_assert_eq!((a.x, a.y, a.pixel), (b.x, b.y, b.pixel));
        prop_assert_eq!(a.t, b.t as f32);
        prop_assert_eq!(a.offset, [b.offset[0] as f32, b.offset[1] as f32]);
    }

    #[test]
    fn star_discrepancy_equals_brute_force(pts in proptest::collection::vec((0u32..8, 0u32..8, any::<bool>()), 1..20)) {
        // Coordinates on a coarse grid (many ties) or arbitrary, in [0, 1).
        let pts: Vec<[f64; 2]> = pts.iter().enumerate().map(|(i, &(x, y, grid))| {
            if grid { [f64::from(x) / 8.0, f64::from(y) / 8.0] }
            else { [((i as f64 * 0.618_034) + f64::from(x) * 0.013).fract(), ((i as f64 * 0.414_214) + f64::from(y) * 0.017).fract()] }
        }).collect();
        let fast = star_discrepancy(&pts).unwrap();
        let brute = brute_star_discrepancy(&pts);
        prop_assert!((fast - brute).abs() <= 1e-12 * brute.max(1.0), "{} vs {}", fast, brute);
    }

    #[test]
    fn star_discrepancy_bounds_every_local_discrepancy(seed in any::<u32>(), a in 0.0f64..=1.0, b in 0.0f64..=1.0) {
        let m = 6;
        let s = Scramble { x: seed, y: seed.rotate_left(13) };
        let pts: Vec<[f64; 2]> = (0..1u32 << m).map(|j| {
            let (x, y) = get_xy(j, m).unwrap();
            let (x, y) = s.apply(x, y, m);
            [f64::from(x) / 64.0, f64::from(y) / 64.0]
        }).collect();
        let d = star_discrepancy(&pts).unwrap();
        let n = pts.len() as f64;
        let open = pts.iter().filter(|p| p[0] < a && p[1] < b).count() as f64 / n;
        let closed = pts.iter().filter(|p| p[0] <= a && p[1] <= b).count() as f64 / n;
        prop_assert!((open - a * b).abs() <= d + 1e-12);
        prop_assert!((closed - a * b).abs() <= d + 1e-12);
    }

    #[test]
    fn rank_criterion_agrees_with_exhaustive_count(m in 1u32..=5, cols in proptest::collection::vec(any::<u32>(), 15), near in any::<bool>()) {
        let mask = (1u32 << m) - 1;
        let take = |i: usize| -> Vec<u32> { cols[i * 5..i * 5 + m as usize].iter().map(|c| c & mask).collect() };
        let mut gens = [0, 1, 2].map(|i| BitMatrix::from_columns(m, &take(i)).unwrap());
        if near {
            // Start from the permuted net and flip one entry of one matrix: nets and
            // non-nets both occur.
            let net = DigitalNet::permuted(m).unwrap();
            let i = (cols[0] % 3) as usize;
            let l = (cols[1] % m) as usize;
            gens = *net.generators();
            let mut c: Vec<u32> = gens[i].columns().to_vec();
            c[l] ^= 1 << (cols[2] % m);
            gens[i] = BitMatrix::from_columns(m, &c).unwrap();
        }
        let net = DigitalNet::new(gens).unwrap();
        let pts: Vec<[u32; 3]> = net.points().collect();
        prop_assert_eq!(net.is_zero_quality(), net_violation(&pts, m).unwrap().is_none());
    }

    #[test]
    fn random_scrambles_keep_the_net(m in 1u32..=8, sx in any::<u32>(), sy in any::<u32>()) {
        let s = Scramble { x: sx, y: sy };
        let pts: Vec<[u32; 3]> = (0..1u32 << m).map(|j| {
            let (x, y) = get_xy(j, m).unwrap();
            let (x, y) = s.apply(x, y, m);
            [x, y, j]
        }).collect();
        prop_assert_eq!(net_violation(&pts, m).unwrap(), None);
    }
}

/// O(n^3) star discrepancy: every candidate box corner, counts by scanning.
fn brute_star_discrepancy(pts: &[[f64; 2]]) -> f64 {
    let n = pts.len() as f64;
    let mut xs: Vec<f64> = pts.iter().map(|p| p[0]).chain([1.0]).collect();
    let mut ys: Vec<f64> = pts.iter().map(|p| p[1]).chain([1.0]).collect();
    xs.sort_by(f64::total_cmp);
    ys.sort_by(f64::total_cmp);
    let mut d = 0.0f64;
    for &a in &xs {
        for &b in &ys {
            let open = pts.iter().filter(|p| p[0] < a && p[1] < b).count() as f64;
            let closed = pts.iter().filter(|p| p[0] <= a && p[1] <= b).count() as f64;
            d = d.max(a * b - open / n).max(closed / n - a * b);
        }
    }
    d
}
