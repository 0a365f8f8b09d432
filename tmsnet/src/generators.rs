//! The generator matrices of Munkberg 2011, Appendix A: the original Grünschloß-Keller
//! (0,m,3)-net (Eq. 13-14) and the permuted, time-ordered one (Eq. 12, 17, 19).

use crate::error::Error;
use crate::matrix::{BitMatrix, binomial_mod2};

/// Grünschloß-Keller C_1: the exchange matrix, component `j / 2^m` (Munkberg 2011, Eq. 13).
pub fn gk_c1(m: u32) -> Result<BitMatrix, Error> {
    BitMatrix::exchange(m)
}

/// Grünschloß-Keller C_2: ones on and above the diagonal, `1 if k <= l` — with C_1 this
/// gives the Larcher-Pillichshammer points (Munkberg 2011, Eq. 13).
pub fn gk_c2(m: u32) -> Result<BitMatrix, Error> {
    BitMatrix::from_fn(m, |k, l| k <= l)
}

/// Grünschloß-Keller C_3 = `(binom(l, k) mod 2)`, k, l = 1..m (Munkberg 2011, Eq. 14).
/// It is its own inverse over F_2 (Eq. 15-16).
pub fn gk_c3(m: u32) -> Result<BitMatrix, Error> {
    BitMatrix::from_fn(m, |k, l| binomial_mod2(l, k))
}

/// Permuted C'_1 = C_1 C_3 C_1 = `(binom(m+1-l, m+1-k) mod 2)` (Munkberg 2011, Eq. 12, 17).
pub fn permuted_c1(m: u32) -> Result<BitMatrix, Error> {
    BitMatrix::from_fn(m, |k, l| binomial_mod2(m + 1 - l, m + 1 - k))
}

/// Permuted C'_2 = C_2 C_3 C_1 = `(binom(m-l, k-1) mod 2)` (Munkberg 2011, Eq. 12, 19).
pub fn permuted_c2(m: u32) -> Result<BitMatrix, Error> {
    BitMatrix::from_fn(m, |k, l| binomial_mod2(m - l, k - 1))
}

/// Permuted C'_3 = C_1, the exchange matrix, so the third component (time) is `j / 2^m`
/// (Munkberg 2011, Eq. 12 and Appendix A).
pub fn permuted_c3(m: u32) -> Result<BitMatrix, Error> {
    BitMatrix::exchange(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pascal's triangle mod 2 by the additive recurrence, independent of Lucas' theorem.
    fn pascal_mod2(n_max: usize) -> Vec<Vec<bool>> {
        let mut rows = vec![vec![true]];
        for n in 1..=n_max {
            let prev = &rows[n - 1];
            let row = (0..=n)
                .map(|k| {
                    let a = if k < prev.len() { prev[k] } else { false };
                    let b = if k > 0 { prev[k - 1] } else { false };
                    a ^ b
                })
                .collect();
            rows.push(row);
        }
        rows
    }

    fn binom(p: &[Vec<bool>], n: u32, k: u32) -> bool {
        p.get(n as usize)
            .and_then(|r| r.get(k as usize))
            .copied()
            .unwrap_or(false)
    }

    #[test]
    fn generators_match_pascal_triangle_definitions() {
        let p = pascal_mod2(33);
        for m in 1..=31 {
            let c3 = gk_c3(m).unwrap();
            let c1p = permuted_c1(m).unwrap();
            let c2p = permuted_c2(m).unwrap();
            for k in 1..=m {
                for l in 1..=m {
                    assert_eq!(c3.entry(k, l), Some(binom(&p, l, k)));
                    assert_eq!(c1p.entry(k, l), Some(binom(&p, m + 1 - l, m + 1 - k)));
                    assert_eq!(c2p.entry(k, l), Some(binom(&p, m - l, k - 1)));
                }
            }
        }
    }

    #[test]
    fn c3_is_an_involution() {
        // Munkberg 2011, Eq. 15-16: C_3^2 = I over F_2.
        for m in 1..=31 {
            let c3 = gk_c3(m).unwrap();
            assert_eq!(c3.mul(&c3).unwrap(), BitMatrix::identity(m).unwrap());
        }
    }

    #[test]
    fn permuted_matrices_equal_products_of_appendix_a() {
        // C'_i = C_i D with D = C_3^{-1} C_1 = C_3 C_1 (Eq. 17, 18-19).
        for m in 1..=31 {
            let c1 = gk_c1(m).unwrap();
            let c2 = gk_c2(m).unwrap();
            let c3 = gk_c3(m).unwrap();
            let d = c3.mul(&c1).unwrap();
            assert_eq!(
                c1.mul(&d).unwrap(),
                permuted_c1(m).unwrap(),
                "C'_1, m = {m}"
            );
            assert_eq!(
                c2.mul(&d).unwrap(),
                permuted_c2(m).unwrap(),
                "C'_2, m = {m}"
            );
            assert_eq!(
                c3.mul(&d).unwrap(),
                permuted_c3(m).unwrap(),
                "C'_3, m = {m}"
            );
        }
    }

    #[test]
    fn eq18_sum_identity() {
        // The experimental identity under Eq. 18: sum_{i=k}^{l} binom(l, i) = binom(l-1, k-1)
        // mod 2 for k <= l, checked with exact integer binomials.
        let mut c = vec![vec![0u128; 40]; 40];
        for n in 0..40 {
            c[n][0] = 1;
            for k in 1..=n {
                c[n][k] = c[n - 1][k - 1] + if k < n { c[n - 1][k] } else { 0 };
            }
        }
        for l in 1..40 {
            for k in 1..=l {
                let s: u128 = (k..=l).map(|i| c[l][i]).sum();
                assert_eq!(s % 2, c[l - 1][k - 1] % 2, "k = {k}, l = {l}");
            }
        }
    }
}
