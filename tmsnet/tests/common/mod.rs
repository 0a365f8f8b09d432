//! Independent references shared by the integration tests.
#![allow(dead_code)]

/// True in the deep CI run.
pub fn deep() -> bool {
    std::env::var("MBLUR_DEEP").is_ok_and(|v| v == "1")
}

/// Pascal's triangle mod 2 up to row `n_max`, by the additive recurrence.
pub fn pascal_mod2(n_max: usize) -> Vec<Vec<bool>> {
    let mut rows: Vec<Vec<bool>> = vec![vec![true]];
    for n in 1..=n_max {
        let prev = &rows[n - 1];
        let row = (0..=n)
            .map(|k| prev.get(k).copied().unwrap_or(false) ^ (k > 0 && prev[k - 1]))
            .collect();
        rows.push(row);
    }
    rows
}

/// `binom(n, k) mod 2` from a Pascal table (false when k > n).
pub fn binom(p: &[Vec<bool>], n: u32, k: u32) -> bool {
    p.get(n as usize)
        .and_then(|r| r.get(k as usize))
        .copied()
        .unwrap_or(false)
}

/// Dense m x m matrix, `a[k-1][l-1]` for the paper's 1-based (k, l).
pub type Dense = Vec<Vec<bool>>;

/// C'_1 of Munkberg 2011, Eq. 17, built entry by entry from the Pascal table.
pub fn dense_c1_prime(p: &[Vec<bool>], m: u32) -> Dense {
    (1..=m)
        .map(|k| (1..=m).map(|l| binom(p, m + 1 - l, m + 1 - k)).collect())
        .collect()
}

/// C'_2 of Munkberg 2011, Eq. 19.
pub fn dense_c2_prime(p: &[Vec<bool>], m: u32) -> Dense {
    (1..=m)
        .map(|k| (1..=m).map(|l| binom(p, m - l, k - 1)).collect())
        .collect()
}

/// Eq. 11 by the book: digit k (weight 2^-k) is the F_2 dot product of row k with the bits
/// of j (d_0 least significant); returned as the m-bit integer `sum digit_k 2^(m-k)`.
pub fn dense_apply(c: &Dense, j: u32, m: u32) -> u32 {
    let mut out = 0u32;
    for k in 1..=m {
        let mut digit = false;
        for l in 1..=m {
            let d = (j >> (l - 1)) & 1 == 1;
            digit ^= c[(k - 1) as usize][(l - 1) as usize] & d;
        }
        if digit {
            out |= 1 << (m - k);
        }
    }
    out
}

/// The Larcher-Pillichshammer radical inverse as 32-bit fixed point, Kollig and Keller
/// 2002 ("Efficient multidimensional sampling"), transcribed from their C code.
pub fn lp32(mut i: u32) -> u32 {
    let mut r = 0u32;
    let mut v = 1u32 << 31;
    while i != 0 {
        if i & 1 == 1 {
            r ^= v;
        }
        i >>= 1;
        v |= v >> 1;
    }
    r
}
