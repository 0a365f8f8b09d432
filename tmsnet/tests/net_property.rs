//! Exhaustive (0,m,3)-net property (Munkberg 2011, Eq. 10): every elementary interval of
//! volume 2^-m, for every split l1 + l2 + l3 = m, holds exactly one point — checked by
//! counting all 2^m points, for the permuted net, the original Grünschloß-Keller ordering
//! and scrambled versions of both. m = 1..=12, up to 17 with MBLUR_DEEP=1.

mod common;

use tmsnet::quality::net_violation;
use tmsnet::{DigitalNet, Scramble, TileLayout, TileSampler, TimeOrderedNet, get_xy};

fn max_m() -> u32 {
    if common::deep() { 17 } else { 12 }
}

fn assert_net(points: &[[u32; 3]], m: u32, what: &str) {
    let v = net_violation(points, m).expect("well-formed point set");
    assert_eq!(v, None, "{what}, m = {m}");
}

#[test]
fn permuted_net_from_get_xy_is_a_0m3_net() {
    for m in 1..=max_m() {
        let pts: Vec<[u32; 3]> = (0..1u32 << m)
            .map(|j| {
                let (x, y) = get_xy(j, m).unwrap();
                [x, y, j]
            })
            .collect();
        assert_net(&pts, m, "permuted (GetXY)");
    }
}

#[test]
fn original_grunschloss_keller_net_is_a_0m3_net() {
    for m in 1..=max_m() {
        let pts: Vec<[u32; 3]> = DigitalNet::grunschloss_keller(m)
            .unwrap()
            .points()
            .collect();
        assert_net(&pts, m, "original Grünschloß-Keller");
    }
}

#[test]
fn scrambled_nets_stay_0m3_nets() {
    for m in 1..=max_m() {
        for (tx, ty, seed) in [(0, 0, 0), (3, 9, 1), (1000, 77, 0xdead_beef)] {
            let s = Scramble::for_tile(tx, ty, seed);
            for net in [
                TimeOrderedNet::permuted(m).unwrap(),
                TimeOrderedNet::original(m).unwrap(),
            ] {
                let pts: Vec<[u32; 3]> = net
                    .iter_range(0..u32::MAX)
                    .map(|(j, x, y)| {
                        let (x, y) = s.apply(x, y, m);
                        [x, y, j]
                    })
                    .collect();
                assert_net(&pts, m, "scrambled");
            }
        }
    }
}

#[test]
fn tile_sampler_output_is_a_0m3_net_and_each_pixel_a_0m2_net() {
    // The scrambled tile samples as delivered to the rasteriser, for square and
    // non-square tiles: the whole tile is a (0,m,3)-net, and the S samples of each pixel
    // (sub-pixel offsets as integers) form a (0, log2 S, 2)-net.
    let layouts = [(4, 4, 16), (2, 8, 4), (8, 1, 32), (1, 1, 64), (16, 16, 16)];
    for (w, h, s) in layouts {
        let layout = TileLayout::new(w, h, s).unwrap();
        if layout.m() > max_m() + 2 {
            continue;
        }
        let m = layout.m();
        let tile = TileSampler::new(layout, 5, 11, 99).unwrap();
        let all: Vec<_> = tile.samples_in(0.0f64, 1.0).unwrap().collect();
        assert_eq!(all.len(), 1 << m);
        let pts: Vec<[u32; 3]> = all.iter().map(|s| [s.x, s.y, s.index]).collect();
        assert_net(&pts, m, "tile sampler");
        let sbits = s.trailing_zeros();
        let mut per_pixel = vec![Vec::new(); (w * h) as usize];
        for smp in &all {
            let (pix, sub) = layout.split(smp.x, smp.y);
            // Sub-pixel integers have m - log2 W bits in x; their top log2 S bits decide the
            // pixel-relative elementary intervals.
            let sx = sub[0] >> (layout.sub_bits_x() - sbits);
            let sy = sub[1] >> (layout.sub_bits_y() - sbits);
            per_pixel[(pix[1] * w + pix[0]) as usize].push([sx, sy]);
        }
        for (p, pts) in per_pixel.iter().enumerate() {
            assert_eq!(pts.len(), s as usize, "pixel {p} of {w}x{h}x{s}");
            if sbits >= 1 {
                assert_eq!(net_violation(pts, sbits).unwrap(), None, "pixel {p}");
            }
        }
    }
}

#[test]
fn spatial_projection_is_a_0m2_net() {
    for m in 1..=max_m() {
        let pts: Vec<[u32; 2]> = (0..1u32 << m)
            .map(|j| {
                let (x, y) = get_xy(j, m).unwrap();
                [x, y]
            })
            .collect();
        assert_eq!(net_violation(&pts, m).unwrap(), None, "m = {m}");
    }
}
