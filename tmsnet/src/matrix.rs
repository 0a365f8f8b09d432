//! Binary m x m generator matrices over F_2, stored as columns of `u32` bit vectors.
//!
//! Munkberg 2011, Eq. 11: component i of point j is
//! `(2^-1, ..., 2^-m) [C_i (d_0(j), ..., d_{m-1}(j))^T]` in F_2, with `d_0` the least
//! significant bit of j. We keep the paper's 1-based indices `(k, l)` (row k, column l) and
//! store column l as an m-bit word in which row k is bit `m - k`. Then the matrix-vector
//! product is the XOR of the columns selected by the bits of j, and the result read as an
//! integer is the component as an m-bit fixed-point number (row 1 is its top bit).

use crate::MAX_M;
use crate::error::{Error, check_m, low_mask};

/// A binary `m x m` matrix over F_2 with `1 <= m <= 31` (Munkberg 2011, Eq. 11).
///
/// Column `l` (1-based) multiplies bit `d_{l-1}(j)` of the index; row `k` (1-based) is bit
/// `m - k` of the column word, i.e. the digit of weight 2^-k.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BitMatrix {
    m: u32,
    cols: [u32; MAX_M as usize],
}

impl BitMatrix {
    /// Builds the matrix whose entry at row `k`, column `l` (both 1-based, as in the
    /// paper) is `entry(k, l)`. Errors with [`Error::InvalidM`] unless `1 <= m <= 31`.
    pub fn from_fn(m: u32, mut entry: impl FnMut(u32, u32) -> bool) -> Result<Self, Error> {
        check_m(m)?;
        let mut cols = [0u32; MAX_M as usize];
        for (l, col) in (1..=m).zip(cols.iter_mut()) {
            for k in 1..=m {
                if entry(k, l) {
                    *col |= 1 << (m - k);
                }
            }
        }
        Ok(Self { m, cols })
    }

    /// Builds the matrix from its `m` column words (column l at index l - 1, row k at bit
    /// m - k). Errors if the count is not m or a word has bits at or above bit m.
    pub fn from_columns(m: u32, columns: &[u32]) -> Result<Self, Error> {
        check_m(m)?;
        let bad = Error::BadColumns {
            m,
            count: columns.len(),
        };
        if columns.len() != m as usize || columns.iter().any(|&c| c & !low_mask(m) != 0) {
            return Err(bad);
        }
        let mut cols = [0u32; MAX_M as usize];
        for (dst, &src) in cols.iter_mut().zip(columns) {
            *dst = src;
        }
        Ok(Self { m, cols })
    }

    /// The identity matrix (van der Corput radical inverse as a generator).
    pub fn identity(m: u32) -> Result<Self, Error> {
        Self::from_fn(m, |k, l| k == l)
    }

    /// The exchange (anti-diagonal) matrix; its component is `j / 2^m`, i.e. the integer
    /// `j` itself (Munkberg 2011, Eq. 13, C_1, and Eq. 12, C'_3).
    pub fn exchange(m: u32) -> Result<Self, Error> {
        Self::from_fn(m, |k, l| k + l == m + 1)
    }

    /// The size m.
    #[inline]
    pub fn m(&self) -> u32 {
        self.m
    }

    /// The `m` column words (column l at index l - 1).
    #[inline]
    pub fn columns(&self) -> &[u32] {
        self.cols.get(..self.m as usize).unwrap_or(&[])
    }

    /// Entry at row `k`, column `l` (1-based); `None` outside `1..=m`.
    pub fn entry(&self, k: u32, l: u32) -> Option<bool> {
        if !(1..=self.m).contains(&k) || !(1..=self.m).contains(&l) {
            return None;
        }
        let col = self.cols.get(l as usize - 1)?;
        Some(col >> (self.m - k) & 1 == 1)
    }

    /// Row `k` (1-based) as a word with column `l` at bit `l - 1`; 0 outside `1..=m`.
    pub fn row(&self, k: u32) -> u32 {
        if !(1..=self.m).contains(&k) {
            return 0;
        }
        let shift = self.m - k;
        self.columns()
            .iter()
            .enumerate()
            .fold(0, |acc, (l, &c)| acc | ((c >> shift) & 1) << l)
    }

    /// The matrix-vector product `C (d_0(j), ..., d_{m-1}(j))^T` of Eq. 11 read as an m-bit
    /// integer (divide by 2^m for the component in [0, 1)). Bits of `j` at or above m are
    /// ignored.
    #[inline]
    pub fn apply(&self, j: u32) -> u32 {
        let mut bits = j & low_mask(self.m);
        let mut acc = 0;
        while bits != 0 {
            // trailing_zeros < m <= 31 here, so `get` always succeeds.
            acc ^= self
                .cols
                .get(bits.trailing_zeros() as usize)
                .copied()
                .unwrap_or(0);
            bits &= bits - 1;
        }
        acc
    }

    /// Matrix product `self * rhs` over F_2. Errors if the sizes differ.
    pub fn mul(&self, rhs: &BitMatrix) -> Result<BitMatrix, Error> {
        if self.m != rhs.m {
            return Err(Error::SizeMismatch {
                expected: self.m,
                found: rhs.m,
            });
        }
        let mut cols = [0u32; MAX_M as usize];
        for (dst, &c) in cols.iter_mut().zip(rhs.columns()) {
            // Column word of rhs has row i at bit m - i; as a digit vector for `apply`,
            // digit i must sit at bit i - 1: reverse the m low bits.
            *dst = self.apply(reverse_low_bits(c, self.m));
        }
        Ok(BitMatrix { m: self.m, cols })
    }

    /// Rank over F_2 (Gaussian elimination on the column words).
    pub fn rank(&self) -> u32 {
        rank_of(self.columns().iter().copied())
    }

    /// True when the matrix is invertible over F_2.
    pub fn is_invertible(&self) -> bool {
        self.rank() == self.m
    }
}

/// Reverses the order of the `m` low bits of `w` (bit i goes to bit m - 1 - i).
#[inline]
pub(crate) fn reverse_low_bits(w: u32, m: u32) -> u32 {
    if m == 0 {
        0
    } else {
        w.reverse_bits() >> (32 - m.min(32))
    }
}

/// Rank over F_2 of a set of bit vectors (XOR basis keyed by leading bit).
pub(crate) fn rank_of(vectors: impl IntoIterator<Item = u32>) -> u32 {
    let mut basis = [0u32; 32];
    let mut rank = 0;
    for mut v in vectors {
        while v != 0 {
            let lead = 31 - v.leading_zeros();
            match basis.get_mut(lead as usize) {
                Some(b) if *b == 0 => {
                    *b = v;
                    rank += 1;
                    break;
                }
                Some(b) => v ^= *b,
                None => break,
            }
        }
    }
    rank
}

/// `binom(n, k) mod 2` by Lucas' theorem: odd exactly when the bits of `k` are a subset of
/// the bits of `n` (this is also 0 for `k > n`, as required by Eq. 14, 17, 19).
#[inline]
pub const fn binomial_mod2(n: u32, k: u32) -> bool {
    k & !n == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exchange_applies_to_identity_integer() {
        let e = BitMatrix::exchange(7).unwrap();
        for j in 0..128 {
            assert_eq!(e.apply(j), j);
        }
    }

    #[test]
    fn identity_is_bit_reversal() {
        let i = BitMatrix::identity(5).unwrap();
        assert_eq!(i.apply(0b00001), 0b10000);
        assert_eq!(i.apply(0b00110), 0b01100);
    }

    #[test]
    fn product_matches_apply_composition() {
        // (A B) d = A (B d): compose through the digit reversal by hand.
        let a = BitMatrix::from_fn(6, |k, l| (k * 3 + l * 5) % 7 < 3).unwrap();
        let b = BitMatrix::from_fn(6, |k, l| (k + 2 * l) % 5 < 2).unwrap();
        let ab = a.mul(&b).unwrap();
        for j in 0..64 {
            let bd = b.apply(j);
            assert_eq!(ab.apply(j), a.apply(reverse_low_bits(bd, 6)));
        }
    }

    #[test]
    fn entry_row_column_agree() {
        let a = BitMatrix::from_fn(9, |k, l| (k ^ l) % 3 == 1).unwrap();
        for k in 1..=9 {
            for l in 1..=9 {
                let e = a.entry(k, l).unwrap();
                assert_eq!(e, (k ^ l) % 3 == 1);
                assert_eq!(e, a.row(k) >> (l - 1) & 1 == 1);
            }
        }
        assert_eq!(a.entry(0, 1), None);
        assert_eq!(a.entry(1, 10), None);
    }

    #[test]
    fn rank_detects_singular() {
        let mut cols = [0u32; 4];
        cols[0] = 0b1000;
        cols[1] = 0b0100;
        cols[2] = 0b1100;
        cols[3] = 0b0001;
        let a = BitMatrix::from_columns(4, &cols).unwrap();
        assert_eq!(a.rank(), 3);
        assert!(!a.is_invertible());
        assert!(BitMatrix::identity(31).unwrap().is_invertible());
    }

    #[test]
    fn rejects_bad_sizes() {
        assert_eq!(
            BitMatrix::identity(0).unwrap_err(),
            Error::InvalidM { m: 0 }
        );
        assert_eq!(
            BitMatrix::identity(32).unwrap_err(),
            Error::InvalidM { m: 32 }
        );
        assert!(BitMatrix::from_columns(3, &[1, 2]).is_err());
        assert!(BitMatrix::from_columns(3, &[1, 2, 8]).is_err());
    }
}
