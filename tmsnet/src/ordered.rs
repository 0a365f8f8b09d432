//! A net ordered in time: point j has time `j / 2^m` and spatial coordinates from two
//! generator matrices, enumerated incrementally over any contiguous index range.

use core::ops::Range;

use crate::MAX_M;
use crate::error::{Error, low_mask};
use crate::generators::{gk_c2, gk_c3, permuted_c1, permuted_c2};
use crate::matrix::BitMatrix;

/// The spatial part of a time-ordered (0,m,3)-net: point j has time `j / 2^m` and
/// `(x, y) = (C_x d(j), C_y d(j))` (Munkberg 2011, Eq. 11-12).
///
/// Besides the direct product it stores prefix XORs of the columns, so that consecutive
/// points cost one XOR per coordinate: `d(j) xor d(j+1)` is the run of the low
/// `tz(j+1) + 1` bits, hence `x(j+1) = x(j) xor (c_0 xor ... xor c_tz)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimeOrderedNet {
    cx: BitMatrix,
    cy: BitMatrix,
    prefix_x: [u32; MAX_M as usize],
    prefix_y: [u32; MAX_M as usize],
}

impl TimeOrderedNet {
    /// From explicit x and y generator matrices of equal size (time is the exchange
    /// matrix implicitly). Whether the result is a (0,m,3)-net is the caller's business;
    /// check with [`crate::DigitalNet::is_zero_quality`].
    pub fn from_matrices(cx: BitMatrix, cy: BitMatrix) -> Result<Self, Error> {
        if cx.m() != cy.m() {
            return Err(Error::SizeMismatch {
                expected: cx.m(),
                found: cy.m(),
            });
        }
        Ok(Self {
            prefix_x: prefix_xor(&cx),
            prefix_y: prefix_xor(&cy),
            cx,
            cy,
        })
    }

    /// The paper's permuted net: x from C'_1, y from C'_2, spatial projection = the
    /// Larcher-Pillichshammer points (Munkberg 2011, Eq. 12, 17, 19; Fig. 7 right).
    pub fn permuted(m: u32) -> Result<Self, Error> {
        Self::from_matrices(permuted_c1(m)?, permuted_c2(m)?)
    }

    /// The original Grünschloß-Keller ordering used as a sampler: time from its ordered
    /// component C_1, x from C_2 and y from C_3 (Munkberg 2011, Eq. 13-14; Fig. 7 left).
    pub fn original(m: u32) -> Result<Self, Error> {
        Self::from_matrices(gk_c2(m)?, gk_c3(m)?)
    }

    /// The size exponent m.
    #[inline]
    pub fn m(&self) -> u32 {
        self.cx.m()
    }

    /// The x and y generator matrices.
    #[inline]
    pub fn matrices(&self) -> (&BitMatrix, &BitMatrix) {
        (&self.cx, &self.cy)
    }

    /// `(x, y)` of point `j` as m-bit integers; errors if `j >= 2^m`.
    #[inline]
    pub fn xy(&self, j: u32) -> Result<(u32, u32), Error> {
        if j > low_mask(self.m()) {
            return Err(Error::IndexOutOfRange { j, m: self.m() });
        }
        Ok((self.cx.apply(j), self.cy.apply(j)))
    }

    /// Iterator over `(j, x, y)` for `j` in `range`, one XOR per coordinate per step.
    /// The range is clipped to `0..2^m` (an out-of-range or reversed range is empty).
    pub fn iter_range(&self, range: Range<u32>) -> XyIter<'_> {
        let n = 1u32 << self.m();
        let end = range.end.min(n);
        let start = range.start.min(end);
        let (x, y) = (self.cx.apply(start), self.cy.apply(start));
        XyIter {
            net: self,
            j: start,
            end,
            x,
            y,
        }
    }

    /// XOR to apply to `(x, y)` when stepping from index `j - 1` to `j` (for `j >= 1`).
    #[inline]
    pub(crate) fn step(&self, j: u32) -> (u32, u32) {
        let tz = j.trailing_zeros() as usize;
        (
            self.prefix_x.get(tz).copied().unwrap_or(0),
            self.prefix_y.get(tz).copied().unwrap_or(0),
        )
    }
}

fn prefix_xor(c: &BitMatrix) -> [u32; MAX_M as usize] {
    let mut out = [0u32; MAX_M as usize];
    let mut acc = 0;
    for (dst, &col) in out.iter_mut().zip(c.columns()) {
        acc ^= col;
        *dst = acc;
    }
    out
}

/// Incremental iterator over `(j, x, y)` of a [`TimeOrderedNet`] on a contiguous index
/// range, created by [`TimeOrderedNet::iter_range`].
#[derive(Clone, Debug)]
pub struct XyIter<'a> {
    net: &'a TimeOrderedNet,
    j: u32,
    end: u32,
    x: u32,
    y: u32,
}

impl Iterator for XyIter<'_> {
    type Item = (u32, u32, u32);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        if self.j >= self.end {
            return None;
        }
        let out = (self.j, self.x, self.y);
        self.j += 1;
        if self.j < self.end {
            let (dx, dy) = self.net.step(self.j);
            self.x ^= dx;
            self.y ^= dy;
        }
        Some(out)
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.end - self.j) as usize;
        (n, Some(n))
    }
}

impl ExactSizeIterator for XyIter<'_> {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn incremental_matches_direct_on_subranges() {
        for m in [1, 2, 5, 9] {
            for net in [
                TimeOrderedNet::permuted(m).unwrap(),
                TimeOrderedNet::original(m).unwrap(),
            ] {
                let n = 1u32 << m;
                for start in 0..n.min(40) {
                    for end in [start, start + 1, n / 2, n, n + 5] {
                        let got: Vec<_> = net.iter_range(start..end).collect();
                        let want: Vec<_> = (start..end.min(n).max(start))
                            .map(|j| {
                                let (x, y) = net.xy(j).unwrap();
                                (j, x, y)
                            })
                            .collect();
                        assert_eq!(got, want, "m = {m}, {start}..{end}");
                    }
                }
            }
        }
    }

    #[test]
    fn reversed_and_out_of_range_ranges_are_empty() {
        let net = TimeOrderedNet::permuted(4).unwrap();
        #[allow(clippy::reversed_empty_ranges)]
        let reversed = 10..3;
        assert_eq!(net.iter_range(reversed).count(), 0);
        assert_eq!(net.iter_range(16..40).count(), 0);
        assert_eq!(net.iter_range(0..u32::MAX).len(), 16);
    }
}
