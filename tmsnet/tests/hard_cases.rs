//! Hard cases by name: the extreme net sizes, the first and last index, empty and
//! degenerate time ranges, t1 = 1 exactly, non-finite input, f32 rounding at large m.

mod common;

use common::{dense_apply, dense_c1_prime, dense_c2_prime, lp32, pascal_mod2};
use tmsnet::quality::net_violation;
use tmsnet::{
    DigitalNet, Error, Scramble, TileLayout, TileSampler, TimeOrderedNet, get_xy, get_xy_unchecked,
    time_index_range,
};

fn reference_xy(j: u32, m: u32) -> (u32, u32) {
    let p = pascal_mod2(40);
    (
        dense_apply(&dense_c1_prime(&p, m), j, m),
        dense_apply(&dense_c2_prime(&p, m), j, m),
    )
}

#[test]
fn m1_is_the_two_point_net() {
    // Times 0 and 1/2; x, y in {0, 1}: (0,0) and (1,1) — a (0,1,3)-net.
    assert_eq!(get_xy(0, 1), Ok((0, 0)));
    assert_eq!(get_xy(1, 1), Ok((1, 1)));
    assert_eq!(get_xy(2, 1), Err(Error::IndexOutOfRange { j: 2, m: 1 }));
    let pts = [[0, 0, 0], [1, 1, 1]];
    assert_eq!(net_violation(&pts, 1).unwrap(), None);
    assert_eq!(time_index_range(0.0f64, 1.0, 1).unwrap(), 0..2);
    assert_eq!(time_index_range(0.25f64, 0.75, 1).unwrap(), 1..2);
}

#[test]
fn m31_extreme_indices_match_reference_product() {
    let m = 31;
    for j in [0, 1, 2, 0x4000_0000, 0x5555_5555, 0x7fff_fffe, 0x7fff_ffff] {
        assert_eq!(get_xy(j, m).unwrap(), reference_xy(j, m), "j = {j:#x}");
    }
    assert_eq!(
        get_xy(0x8000_0000, m),
        Err(Error::IndexOutOfRange { j: 0x8000_0000, m })
    );
}

#[test]
fn m31_permuted_net_has_zero_quality_by_rank_criterion() {
    // Counting 2^31 points is out of reach; the rank criterion covers m = 31.
    assert!(DigitalNet::permuted(31).unwrap().is_zero_quality());
    assert!(
        DigitalNet::grunschloss_keller(31)
            .unwrap()
            .is_zero_quality()
    );
}

#[test]
fn m31_incremental_iteration_at_the_top_of_the_range() {
    let net = TimeOrderedNet::permuted(31).unwrap();
    let start = 0x7fff_ff00;
    for (j, x, y) in net.iter_range(start..u32::MAX) {
        assert_eq!((x, y), get_xy(j, 31).unwrap());
    }
    assert_eq!(net.iter_range(start..u32::MAX).len(), 256);
}

#[test]
fn m_zero_and_m_32_are_errors_not_panics() {
    assert_eq!(get_xy(0, 0), Err(Error::InvalidM { m: 0 }));
    assert_eq!(get_xy(0, 32), Err(Error::InvalidM { m: 32 }));
    assert_eq!(get_xy(0, u32::MAX), Err(Error::InvalidM { m: u32::MAX }));
    assert_eq!(
        time_index_range(0.0f64, 1.0, 0),
        Err(Error::InvalidM { m: 0 })
    );
    assert!(TimeOrderedNet::permuted(32).is_err());
    assert!(DigitalNet::grunschloss_keller(0).is_err());
    // The unchecked variant clamps instead of overflowing a shift.
    let _ = get_xy_unchecked(5, 0);
    let _ = get_xy_unchecked(5, 32);
}

#[test]
fn j_zero_is_the_origin_for_every_m() {
    for m in 1..=31 {
        assert_eq!(get_xy(0, m), Ok((0, 0)));
    }
}

#[test]
fn j_last_is_xor_of_all_columns_for_every_m() {
    for m in 1..=31 {
        let j = u32::MAX >> (32 - m);
        assert_eq!(get_xy(j, m).unwrap(), reference_xy(j, m), "m = {m}");
    }
}

#[test]
fn empty_time_range_reversed_bounds() {
    assert!(time_index_range(0.6f64, 0.4, 8).unwrap().is_empty());
    let tile = TileSampler::new(TileLayout::new(4, 4, 16).unwrap(), 0, 0, 0).unwrap();
    assert_eq!(tile.samples_in(0.6f32, 0.4).unwrap().count(), 0);
}

#[test]
fn empty_time_range_between_two_sample_times() {
    // 1/16 < t < 2/16 holds no sample time of a 2^4 net.
    let r = time_index_range(1.0f64 / 16.0 + 1e-9, 2.0 / 16.0 - 1e-9, 4).unwrap();
    assert!(r.is_empty());
    // Just below the first sample after zero: only j = 0.
    assert_eq!(
        time_index_range(0.0f64, 1.0 / 16.0 - 1e-12, 4).unwrap(),
        0..1
    );
}

#[test]
fn empty_time_range_outside_unit_interval() {
    assert!(time_index_range(1.5f64, 2.0, 8).unwrap().is_empty());
    assert!(time_index_range(-2.0f64, -0.5, 8).unwrap().is_empty());
    // t0 just above the last sample time (255/256) but <= 1.
    assert!(
        time_index_range(255.5f64 / 256.0, 1.0, 8)
            .unwrap()
            .is_empty()
    );
    assert!(time_index_range(f64::MAX, f64::MAX, 8).unwrap().is_empty());
    assert_eq!(time_index_range(-f64::MAX, f64::MAX, 8).unwrap(), 0..256);
}

#[test]
fn single_point_time_range_on_a_sample_time() {
    for m in [1, 8, 24, 31] {
        for j in [0, 1, (1u32 << m) / 3, (1u32 << m) - 1] {
            let t = f64::from(j) / f64::from(1u32 << m);
            assert_eq!(
                time_index_range(t, t, m).unwrap(),
                j..j + 1,
                "m = {m}, j = {j}"
            );
        }
    }
    let tile = TileSampler::new(TileLayout::new(4, 4, 16).unwrap(), 1, 2, 3).unwrap();
    let v: Vec<_> = tile.samples_in(0.5f32, 0.5).unwrap().collect();
    assert_eq!(v.len(), 1);
    assert_eq!((v[0].index, v[0].t), (128, 0.5));
}

#[test]
fn single_point_time_range_off_sample_times_is_empty() {
    assert!(time_index_range(0.3f64, 0.3, 4).unwrap().is_empty());
}

#[test]
fn t1_equal_to_one_includes_the_last_sample() {
    for m in [1, 8, 31] {
        let r = time_index_range(0.0f64, 1.0, m).unwrap();
        assert_eq!(r, 0..1u32 << m);
        let r = time_index_range(1.0f32, 1.0, m).unwrap();
        assert!(r.is_empty(), "t0 = t1 = 1 lies past the last sample time");
    }
    let tile = TileSampler::new(TileLayout::new(2, 2, 4).unwrap(), 0, 0, 0).unwrap();
    let last = tile.samples_in(0.9f64, 1.0).unwrap().last().unwrap();
    assert_eq!((last.index, last.t), (15, 15.0 / 16.0));
}

#[test]
fn non_finite_time_bounds_are_errors() {
    for (a, b) in [
        (f64::NAN, 0.5),
        (0.5, f64::NAN),
        (f64::NEG_INFINITY, 0.5),
        (0.0, f64::INFINITY),
        (f64::INFINITY, 0.0),
    ] {
        assert_eq!(time_index_range(a, b, 8), Err(Error::NonFiniteTime));
    }
    let tile = TileSampler::new(TileLayout::new(4, 4, 16).unwrap(), 0, 0, 0).unwrap();
    assert!(tile.samples_in(f32::NAN, 1.0).is_err());
}

#[test]
fn f32_times_at_m31_stay_ordered_and_in_range() {
    // 2^31 times do not fit f32's 24-bit mantissa: times round, but never leave [t0, t1]
    // and never decrease.
    let tile =
        TileSampler::new(TileLayout::new(1 << 10, 1 << 10, 1 << 11).unwrap(), 0, 0, 0).unwrap();
    let (t0, t1) = (0.999_999f32, 1.0f32);
    let mut prev = 0.0f32;
    let mut n = 0;
    for s in tile.samples_in(t0, t1).unwrap() {
        assert!(s.t >= t0 && s.t <= t1 && s.t >= prev);
        assert!(s.offset[0] < 1.0 && s.offset[1] < 1.0);
        prev = s.t;
        n += 1;
    }
    // Exact count of j with t0 <= j / 2^31, evaluated in f64.
    let first = (f64::from(t0) * 2f64.powi(31)).ceil() as u64;
    assert_eq!(n as u64, (1u64 << 31) - first);
}

#[test]
fn largest_and_smallest_tiles() {
    assert!(TileLayout::new(1 << 16, 1 << 15, 1).is_ok());
    assert_eq!(
        TileLayout::new(1 << 16, 1 << 16, 1),
        Err(Error::TileTooLarge { log2_samples: 32 })
    );
    assert_eq!(
        TileLayout::new(1, 1, 1),
        Err(Error::TileTooLarge { log2_samples: 0 })
    );
    // 1 x 1 pixel at 2 spp: m = 1, the whole coordinate is sub-pixel.
    let t = TileSampler::new(TileLayout::new(1, 1, 2).unwrap(), 0, 0, 0).unwrap();
    let v: Vec<_> = t.samples_in(0.0f64, 1.0).unwrap().collect();
    assert_eq!(v.len(), 2);
    assert!(v.iter().all(|s| s.pixel == [0, 0]));
    // 2 x 1 pixels at 1 spp: m = 1, no sub-pixel bits in x, one in y; offsets x are 0.
    let t = TileSampler::new(TileLayout::new(2, 1, 1).unwrap(), 0, 0, 0).unwrap();
    let v: Vec<_> = t.samples_in(0.0f64, 1.0).unwrap().collect();
    let mut px: Vec<u32> = v.iter().map(|s| s.pixel[0]).collect();
    px.sort_unstable();
    assert_eq!(px, vec![0, 1]);
    assert!(v.iter().all(|s| s.offset[0] == 0.0));
}

#[test]
fn non_power_of_two_tiles_are_errors() {
    assert!(matches!(
        TileLayout::new(3, 4, 16),
        Err(Error::NotPowerOfTwo { what: "width", .. })
    ));
    assert!(matches!(
        TileLayout::new(4, 6, 16),
        Err(Error::NotPowerOfTwo { what: "height", .. })
    ));
    assert!(matches!(
        TileLayout::new(4, 4, 0),
        Err(Error::NotPowerOfTwo {
            what: "samples per pixel",
            ..
        })
    ));
}

#[test]
fn scramble_with_all_ones_mask_keeps_the_net() {
    // The extreme scramble flips every bit of x and y.
    for m in 1..=10 {
        let s = Scramble {
            x: u32::MAX,
            y: u32::MAX,
        };
        let pts: Vec<[u32; 3]> = (0..1u32 << m)
            .map(|j| {
                let (x, y) = get_xy(j, m).unwrap();
                let (x, y) = s.apply(x, y, m);
                [x, y, j]
            })
            .collect();
        assert_eq!(net_violation(&pts, m).unwrap(), None, "m = {m}");
    }
}

#[test]
fn lp_reference_agrees_at_m31_on_sampled_indices() {
    // The LP x coordinate of the permuted net is the index of the original LP point:
    // find it through C'_1 and check the y against Kollig and Keller's code.
    let m = 31;
    for j in [1u32, 12345, 0x3fff_ffff, 0x7fff_ffff] {
        let (x, y) = get_xy(j, m).unwrap();
        assert_eq!(y, lp32(x) >> 1, "j = {j:#x}");
    }
}
