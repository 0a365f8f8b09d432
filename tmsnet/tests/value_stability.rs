//! Pinned outputs of the deterministic code: GetXY, the tile hash and scramble, and the
//! first samples of a tile. A change here changes every rendered image; update the pins
//! only on purpose.

use tmsnet::{Scramble, TileLayout, TileSampler, TimeOrderedNet, get_xy, tile_hash};

#[test]
fn get_xy_pins_m8() {
    let pins = [
        (0, (0, 0)),
        (1, (128, 255)),
        (2, (127, 170)),
        (3, (255, 85)),
        (77, (177, 123)),
        (128, (1, 128)),
        (200, (26, 200)),
        (255, (192, 1)),
    ];
    for (j, xy) in pins {
        assert_eq!(get_xy(j, 8).unwrap(), xy, "j = {j}");
    }
}

#[test]
fn get_xy_pins_m31() {
    assert_eq!(get_xy(1, 31).unwrap(), (2147483647, 1431655765));
    assert_eq!(get_xy(0x1234_5678, 31).unwrap(), (205066376, 2021407240));
    assert_eq!(get_xy(0x7fff_ffff, 31).unwrap(), (1073741824, 2147483647));
}

#[test]
fn original_ordering_pins_m8() {
    let o = TimeOrderedNet::original(8).unwrap();
    let got: Vec<(u32, u32)> = [1, 77, 255].iter().map(|&j| o.xy(j).unwrap()).collect();
    // x = C_2 d(j) (LP digits; 77 = 0b01001101 gives suffix XORs 0b01101110 = 110 by
    // hand), y = C_3 d(j).
    assert_eq!(got, vec![(128, 128), (110, 142), (85, 3)]);
}

#[test]
fn tile_hash_pins() {
    assert_eq!(tile_hash(0, 0, 0), 0x4821_8226_ff3c_d4bf);
    assert_eq!(tile_hash(3, 7, 42), 0xc782_ff79_d2e5_cc8e);
    assert_eq!(
        tile_hash(u32::MAX, u32::MAX, u64::MAX),
        0xeecd_2736_9f7e_c29a
    );
    assert_eq!(
        Scramble::for_tile(3, 7, 42),
        Scramble {
            x: 3538275470,
            y: 3347251065
        }
    );
}

#[test]
fn tile_sample_pins() {
    let t = TileSampler::new(TileLayout::new(4, 4, 16).unwrap(), 3, 7, 42).unwrap();
    let got: Vec<_> = t
        .samples_in_indices::<f64>(0..3)
        .unwrap()
        .map(|s| (s.index, s.x, s.y, s.pixel, s.offset, s.t))
        .collect();
    assert_eq!(
        got,
        vec![
            (0, 142, 121, [2, 1], [0.21875, 0.890625], 0.0),
            (1, 14, 134, [0, 2], [0.21875, 0.09375], 0.00390625),
            (2, 241, 211, [3, 3], [0.765625, 0.296875], 0.0078125),
        ]
    );
}
