//! Random digit scrambling per tile (Munkberg 2011, §5, after Kollig and Keller 2002):
//! XOR of x and y with two bit vectors from a hash of the tile position and a seed.

use crate::error::low_mask;

/// Two scrambling bit vectors. XOR with a constant maps every elementary interval onto an
/// elementary interval of the same shape (its top `l` bits are flipped the same way for all
/// points), so a scrambled (0,m,3)-net is still a (0,m,3)-net; time is not scrambled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Scramble {
    /// XOR mask for x (only the low m bits are used).
    pub x: u32,
    /// XOR mask for y (only the low m bits are used).
    pub y: u32,
}

impl Scramble {
    /// No scrambling.
    pub const NONE: Scramble = Scramble { x: 0, y: 0 };

    /// The scramble of the tile at `(tile_x, tile_y)`: a deterministic hash of the tile
    /// position and `seed`, so the pattern is stable from frame to frame and differs from
    /// tile to tile (Munkberg 2011, §5). Low 32 bits of the hash go to x, high to y.
    pub fn for_tile(tile_x: u32, tile_y: u32, seed: u64) -> Self {
        let h = tile_hash(tile_x, tile_y, seed);
        Scramble {
            x: h as u32,
            y: (h >> 32) as u32,
        }
    }

    /// Scrambles m-bit coordinates: `(x ^ mask_x, y ^ mask_y)` with the masks cut to m
    /// bits, so the result stays in `[0, 2^m)`.
    #[inline]
    pub fn apply(self, x: u32, y: u32, m: u32) -> (u32, u32) {
        let keep = low_mask(m);
        (x ^ (self.x & keep), y ^ (self.y & keep))
    }

    /// The same scramble with masks cut to m bits (so [`Scramble::apply`] is a plain XOR).
    #[inline]
    pub fn truncated(self, m: u32) -> Self {
        let keep = low_mask(m);
        Scramble {
            x: self.x & keep,
            y: self.y & keep,
        }
    }
}

/// 64-bit finaliser (Stafford's "Mix13" variant of MurmurHash3 fmix64, as in SplitMix64):
/// a bijection on u64 with full avalanche.
#[inline]
pub const fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Deterministic hash of a tile position and a seed. For a fixed seed it is a bijection
/// of `(tile_x, tile_y)`, so no two tiles of one frame share a scramble.
#[inline]
pub const fn tile_hash(tile_x: u32, tile_y: u32, seed: u64) -> u64 {
    let key = ((tile_y as u64) << 32) | tile_x as u64;
    mix64(key ^ mix64(seed ^ 0x9e37_79b9_7f4a_7c15))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apply_stays_in_range() {
        let s = Scramble {
            x: u32::MAX,
            y: 0xdead_beef,
        };
        assert_eq!(s.apply(0, 0, 4), (15, 0xf));
        assert_eq!(s.apply(5, 3, 31).0 >> 31, 0);
        assert_eq!(s.truncated(4).apply(5, 3, 4), s.apply(5, 3, 4));
    }

    #[test]
    fn distinct_tiles_get_distinct_hashes() {
        let mut seen = std::collections::HashSet::new();
        for ty in 0..64 {
            for tx in 0..64 {
                assert!(seen.insert(tile_hash(tx, ty, 7)));
            }
        }
    }
}
