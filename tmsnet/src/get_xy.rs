//! The paper's GetXY: the permuted net's spatial coordinates by bit shifts and XORs,
//! with the matrix columns of C'_1 and C'_2 generated on the fly (Munkberg 2011, §5).

use crate::error::{Error, check_m, low_mask};

/// `(x, y)` of point `j` of the permuted (0,m,3)-net, integers in `[0, 2^m)`; the point's
/// time is `j / 2^m` (Munkberg 2011, §5 GetXY; generators C'_1, C'_2 of Eq. 12, 17, 19).
///
/// Errors with [`Error::InvalidM`] unless `1 <= m <= 31`, and with
/// [`Error::IndexOutOfRange`] if `j >= 2^m`.
///
/// ```
/// // 4x4 pixel tile at 16 samples per pixel: m = 8, coordinates are 2.6 fixed point.
/// let (x, y) = tmsnet::get_xy(0b1000_0000, 8).unwrap();
/// assert_eq!((x, y), (1, 128)); // the top index bit adds column m of C'_1 and C'_2
/// assert!(tmsnet::get_xy(0, 0).is_err());
/// assert!(tmsnet::get_xy(256, 8).is_err());
/// ```
#[inline]
pub fn get_xy(j: u32, m: u32) -> Result<(u32, u32), Error> {
    check_m(m)?;
    if j > low_mask(m) {
        return Err(Error::IndexOutOfRange { j, m });
    }
    Ok(get_xy_unchecked(j, m))
}

/// [`get_xy`] without the `Result`: for the inner loop when `m` and `j` are known valid.
///
/// Never panics. Outside the contract the output is well defined but meaningless: `m` is
/// clamped to `1..=31` and bits of `j` at or above `m` are ignored.
///
/// Instead of the paper's loop over the m bits of j ([`get_xy_paper_loop`]) it uses that
/// both matrices are Pascal's triangle mod 2 (Eq. 17, 19) and that, by Lucas' theorem,
/// `binom(a, b)` is odd exactly when the bits of b are a subset of those of a. A product
/// with that matrix is then a superset-sum transform over F_2, which takes five
/// mask-shift-XOR steps on a 32-bit word; index reversals map the paper's row and column
/// order onto bit positions. Branch-free and independent of m (see BENCHMARKS.md).
/// To enumerate a contiguous range, [`crate::TimeOrderedNet`]'s incremental iterator is
/// faster still (one XOR per coordinate per sample).
#[inline]
pub fn get_xy_unchecked(j: u32, m: u32) -> (u32, u32) {
    let m = m.clamp(1, crate::MAX_M);
    let j = j & low_mask(m);
    // C'_1(k, l) = binom(m+1-l, m+1-k): with a = m+1-l, b = m+1-k in 1..=m, output bit
    // b-1 of x is the XOR over a ⊇ b of d_{m-a}(j). Put d_{m-a} at bit a: u = rev32(j) >>
    // (31 - m) (shift in 0..=30); then x = superset_sum(u) >> 1.
    let u = j.reverse_bits() >> (31 - m);
    let x = superset_sum(u) >> 1;
    // C'_2(k, l) = binom(m-l, k-1): with a = m-l, b = k-1 in 0..m, output bit m-1-b of y
    // is the XOR over a ⊇ b of d_{m-1-a}(j), i.e. y = rev_m(superset_sum(u >> 1)).
    let y = superset_sum(u >> 1).reverse_bits() >> (32 - m);
    (x, y)
}

/// `w_b = XOR over a ⊇ b of v_a` for all 32 bit positions (superset-sum / Möbius transform
/// over F_2; the transpose of multiplying by Pascal's triangle mod 2).
#[inline]
const fn superset_sum(mut v: u32) -> u32 {
    v ^= (v & 0xaaaa_aaaa) >> 1;
    v ^= (v & 0xcccc_cccc) >> 2;
    v ^= (v & 0xf0f0_f0f0) >> 4;
    v ^= (v & 0xff00_ff00) >> 8;
    v ^= (v & 0xffff_0000) >> 16;
    v
}

/// The paper's GetXY loop verbatim (early exit, one branch per bit), kept as the
/// reference the branch-free [`get_xy_unchecked`] is tested and benchmarked against.
/// Same contract as [`get_xy_unchecked`].
#[inline]
pub fn get_xy_paper_loop(j: u32, m: u32) -> (u32, u32) {
    let m = m.clamp(1, crate::MAX_M);
    let (mut x, mut y) = (0u32, 0u32);
    let mut c1: u32 = 0x3;
    let mut c2: u32 = 1 << (m - 1);
    // Shift amount 32 - m lies in 1..=31; high bits of j fall off the top.
    let mut bits = j << (32 - m);
    while bits != 0 {
        if bits & 0x8000_0000 != 0 {
            x ^= c1 >> 1;
            y ^= c2;
        }
        c1 ^= c1 << 1;
        c2 ^= c2 >> 1;
        bits <<= 1;
    }
    (x, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guards() {
        assert_eq!(get_xy(0, 0), Err(Error::InvalidM { m: 0 }));
        assert_eq!(get_xy(0, 32), Err(Error::InvalidM { m: 32 }));
        assert_eq!(get_xy(4, 2), Err(Error::IndexOutOfRange { j: 4, m: 2 }));
        assert_eq!(get_xy(0, 31), Ok((0, 0)));
        // The unchecked variant never panics, even outside its contract.
        let _ = get_xy_unchecked(u32::MAX, 0);
        let _ = get_xy_unchecked(u32::MAX, 40);
        let _ = get_xy_paper_loop(u32::MAX, 0);
        let _ = get_xy_paper_loop(u32::MAX, 40);
    }

    #[test]
    fn branch_free_equals_paper_loop() {
        for m in 1..=31 {
            for j in (0..4096u32).chain([u32::MAX, 0x5555_5555, 0x7fff_ffff]) {
                assert_eq!(
                    get_xy_unchecked(j, m),
                    get_xy_paper_loop(j, m),
                    "m {m} j {j}"
                );
            }
        }
    }

    #[test]
    fn m1_points() {
        // C'_1 = (binom(1,1)) = 1, C'_2 = (binom(0,0)) = 1: points (0,0,0) and (1,1,1/2).
        assert_eq!(get_xy(0, 1), Ok((0, 0)));
        assert_eq!(get_xy(1, 1), Ok((1, 1)));
    }
}
