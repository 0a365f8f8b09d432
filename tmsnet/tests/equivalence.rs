//! The permuted net against independent references (Munkberg 2011, §5, Appendix A):
//! the fast GetXY equals Eq. 11 with C'_1, C'_2 built entry by entry from Pascal's triangle
//! (Eq. 17, 19); the permuted and original nets are the same point set; the spatial
//! projection is the Larcher-Pillichshammer point set (Kollig and Keller 2002 code); times
//! are exactly j / 2^m in order.

mod common;

use common::{dense_apply, dense_c1_prime, dense_c2_prime, lp32, pascal_mod2};
use tmsnet::{
    DigitalNet, TimeOrderedNet, get_xy, get_xy_paper_loop, get_xy_unchecked, sample_time,
};

fn max_m() -> u32 {
    if common::deep() { 20 } else { 14 }
}

#[test]
fn get_xy_equals_binomial_matrix_product_for_all_j_up_to_m16() {
    let p = pascal_mod2(40);
    for m in 1..=16 {
        let (c1, c2) = (dense_c1_prime(&p, m), dense_c2_prime(&p, m));
        for j in 0..1u32 << m {
            let want = (dense_apply(&c1, j, m), dense_apply(&c2, j, m));
            assert_eq!(get_xy(j, m).unwrap(), want, "m = {m}, j = {j}");
            assert_eq!(get_xy_unchecked(j, m), want);
            assert_eq!(get_xy_paper_loop(j, m), want);
        }
    }
}

#[test]
fn time_ordered_net_and_digital_net_agree_with_get_xy() {
    for m in 1..=max_m().min(16) {
        let net = TimeOrderedNet::permuted(m).unwrap();
        let full = DigitalNet::permuted(m).unwrap();
        for (j, x, y) in net.iter_range(0..u32::MAX) {
            let (gx, gy) = get_xy(j, m).unwrap();
            assert_eq!((x, y), (gx, gy), "m = {m}, j = {j}");
            assert_eq!(full.point(j).unwrap(), [gx, gy, j]);
        }
    }
}

#[test]
fn permuted_and_original_are_the_same_point_set() {
    // Appendix A: C'_i = C_i D with D invertible only reorders the points.
    for m in 1..=max_m() {
        let mut a: Vec<[u32; 3]> = DigitalNet::permuted(m).unwrap().points().collect();
        let mut b: Vec<[u32; 3]> = DigitalNet::grunschloss_keller(m)
            .unwrap()
            .points()
            .collect();
        // ... and really in a different order (for m >= 2).
        if m >= 2 {
            assert_ne!(a, b, "m = {m}");
        }
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b, "m = {m}");
    }
}

#[test]
fn spatial_projection_is_the_larcher_pillichshammer_point_set() {
    for m in 1..=max_m() {
        let mut ours: Vec<(u32, u32)> = (0..1u32 << m).map(|j| get_xy(j, m).unwrap()).collect();
        let mut lp: Vec<(u32, u32)> = (0..1u32 << m).map(|i| (i, lp32(i) >> (32 - m))).collect();
        ours.sort_unstable();
        lp.sort_unstable();
        assert_eq!(ours, lp, "m = {m}");
    }
}

#[test]
fn original_ordering_projection_is_not_lp_but_same_3d_set() {
    // The original ordering used as a sampler (time = C_1 component) has spatial
    // projection (C_2, C_3): a different 2D point set than LP for m >= 3 (Fig. 7 left).
    for m in 3..=10 {
        let net = TimeOrderedNet::original(m).unwrap();
        let gk = DigitalNet::grunschloss_keller(m).unwrap();
        let mut proj: Vec<(u32, u32)> = Vec::new();
        for (j, x, y) in net.iter_range(0..u32::MAX) {
            let p = gk.point(j).unwrap();
            assert_eq!([j, x, y], p, "time is C_1 = j, x = C_2, y = C_3");
            proj.push((x, y));
        }
        let mut lp: Vec<(u32, u32)> = (0..1u32 << m).map(|i| (i, lp32(i) >> (32 - m))).collect();
        proj.sort_unstable();
        lp.sort_unstable();
        assert_ne!(proj, lp, "m = {m}");
    }
}

#[test]
fn sample_times_are_exactly_j_over_2m_in_order() {
    for m in 1..=max_m() {
        let net = DigitalNet::permuted(m).unwrap();
        let scale = 2f64.powi(-(m as i32));
        let mut prev = -1.0f64;
        for (j, p) in net.points().enumerate() {
            let j = j as u32;
            assert_eq!(p[2], j);
            let t: f64 = sample_time(j, m).unwrap();
            assert_eq!(t, f64::from(j) * scale);
            assert!(t > prev);
            prev = t;
        }
    }
}
