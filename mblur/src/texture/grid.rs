//! Arithmetic on the texel grid: a coordinate's integer part and fraction, floor and ceil
//! without library calls (baseline x86-64 has no rounding instruction), and the bilinear
//! blend of one cell's four texels.

/// The bilinear blend of four premultiplied texels `[t00, t10, t01, t11]` (columns x0, x1
/// of rows y0, y1) with weights `fx`, `fy` toward the second column and row.
#[inline(always)]
pub(crate) fn bilinear(fx: f64, fy: f64, [t00, t10, t01, t11]: [[f64; 4]; 4]) -> [f64; 4] {
    std::array::from_fn(|k| {
        (1.0 - fy) * ((1.0 - fx) * t00[k] + fx * t10[k]) + fy * ((1.0 - fx) * t01[k] + fx * t11[k])
    })
}

/// A texel index `i` wrapped into `0..n` and the index after it, wrapped. An integer
/// remainder is much cheaper than the float one; a power-of-two size wraps by a mask (two's
/// complement makes it the Euclidean remainder for negative indices too); an index already
/// inside the texture (uv in \[0, 1)) needs no remainder at all, and the next one wraps by
/// one comparison.
#[inline(always)]
pub(crate) fn wrap(i: i64, n: u32) -> (i64, i64) {
    let n = i64::from(n.max(1));
    let i = if n & (n - 1) == 0 {
        i & (n - 1)
    } else if (0..n).contains(&i) {
        i
    } else {
        i.rem_euclid(n)
    };
    (i, if i + 1 == n { 0 } else { i + 1 })
}

/// 1.5 · 2^52: adding it to a finite `v` with |v| < 2^51 leaves round-to-nearest(v) in the
/// low mantissa bits of the sum, and subtracting it again gives that integer as an f64
/// exactly (the sum's unit in the last place is 1).
const ROUND: f64 = 6_755_399_441_055_744.0;

/// The magnitude below which [`ROUND`] rounds exactly: 2^51.
const ROUND_EXACT: f64 = 2_251_799_813_685_248.0;

/// The integer part `floor(v)` (saturated to the range of `i64`) and the fraction
/// `v - floor(v)` of a finite `v`. Below 2^51 in magnitude by [`ROUND`]: the nearest
/// integer and its bits come from one addition, with no float-to-integer conversion (whose
/// saturation checks cost more than the rounding), and one is subtracted where it rounded
/// up; larger magnitudes take the library's `floor`.
#[inline]
pub(crate) fn split(v: f64) -> (i64, f64) {
    if v.abs() < ROUND_EXACT {
        let sum = v + ROUND;
        // Same exponent as ROUND: the bit patterns differ by the rounded integer.
        let i = sum.to_bits() as i64 - ROUND.to_bits() as i64;
        let f = sum - ROUND;
        if f > v {
            (i - 1, v - (f - 1.0))
        } else {
            (i, v - f)
        }
    } else {
        let f = v.floor();
        (f as i64, v - f)
    }
}

/// `v.floor()` without the library call (baseline x86-64 has no rounding instruction, and
/// `f64::floor` is a call there): below 2^51 in magnitude the nearest integer by [`ROUND`],
/// less one where that rounded up; larger magnitudes (already integers) and NaN take
/// `floor`.
#[inline]
pub(crate) fn floor(v: f64) -> f64 {
    if v.abs() < ROUND_EXACT {
        let i = (v + ROUND) - ROUND;
        if i > v { i - 1.0 } else { i }
    } else {
        v.floor()
    }
}

/// `v.ceil()` without the library call, as [`floor`].
#[inline]
pub(crate) fn ceil(v: f64) -> f64 {
    -floor(-v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Finite values at the edges of the rounding: zeros, halves, huge magnitudes, and the
    /// half-integers just below and above 2^51 (where [`ROUND`] stops being exact) and
    /// below 2^52 (where every f64 becomes an integer).
    fn boundaries() -> Vec<f64> {
        let mut v = vec![0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2.5, -2.5, 1e300, -1e300];
        for x in [
            4_503_599_627_370_495.5,
            2_251_799_813_685_247.5,
            2_251_799_813_685_248.5,
        ] {
            v.extend([x, -x]);
        }
        v
    }

    /// 10,000 values from a seeded LCG: per step its state read as f64 bits (any class,
    /// NaN and infinities included) and a uniform value in [-4096, 4096).
    fn random(mut seed: u64) -> Vec<(f64, f64)> {
        (0..10_000)
            .map(|_| {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let uniform = (seed >> 11) as f64 / (1u64 << 40) as f64 - 4096.0;
                (f64::from_bits(seed), uniform)
            })
            .collect()
    }

    #[test]
    fn floor_matches_the_library_floor() {
        let mut v = boundaries();
        v.extend([
            f64::INFINITY,
            f64::NEG_INFINITY,
            4_503_599_627_370_496.0,
            9_007_199_254_740_993.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            1.0 - f64::EPSILON / 2.0,
            -1.0 + f64::EPSILON / 2.0,
        ]);
        v.extend(
            random(7)
                .into_iter()
                .flat_map(|(bits, uniform)| [bits, uniform]),
        );
        for x in v {
            let (got, want) = (floor(x), x.floor());
            // Equal (both NaN for NaN); -0.0 may come back as +0.0, which is the same floor.
            assert!(
                got == want || (got.is_nan() && want.is_nan()),
                "{x}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn split_is_floor_and_fraction() {
        let mut v = boundaries();
        v.extend([9e15, -9e15]);
        // `split` takes finite values only.
        for (bits, uniform) in random(99) {
            v.push(uniform);
            if bits.is_finite() {
                v.push(bits);
            }
        }
        for x in v {
            let (i, f) = split(x);
            let want = x.floor();
            assert_eq!(f, x - want, "{x}");
            assert!(
                want.abs() >= 9.2e18 || i as f64 == want,
                "{x}: {i} vs {want}"
            );
        }
    }
}
