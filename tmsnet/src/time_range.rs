//! Samples in a time interval: since point j of a time-ordered net has time `j / 2^m`, the
//! points with time in `[t0, t1]` are one contiguous index range (Munkberg 2011, §5).

use core::ops::Range;

use num_traits::Float;

use crate::error::{Error, check_m};

/// The indices `j` whose time `j / 2^m` lies in the closed interval `[t0, t1]`, in O(1).
///
/// The comparison is exact (`t * 2^m` is exact in f64 for f32 and f64 input), so
/// `j` is in the range exactly when `t0 <= j / 2^m <= t1`. Bounds outside [0, 1] are
/// clipped: `t1 >= 1` includes the last point `(2^m - 1) / 2^m`, `t0 <= 0` includes j = 0.
/// `t0 > t1`, or an interval that falls between two sample times, gives an empty range
/// (`start == end`, with `start` in `0..=2^m`). A single point `t0 == t1 == j / 2^m`
/// gives exactly `j..j+1`.
///
/// Errors: [`Error::InvalidM`] unless `1 <= m <= 31`; [`Error::NonFiniteTime`] if either
/// bound is NaN or infinite, whatever the order of the bounds.
///
/// ```
/// // 2^4 samples at times 0, 1/16, ..., 15/16.
/// assert_eq!(tmsnet::time_index_range(0.25f32, 0.5, 4).unwrap(), 4..9);
/// assert_eq!(tmsnet::time_index_range(0.9f64, 1.0, 4).unwrap(), 15..16);
/// assert!(tmsnet::time_index_range(0.51f64, 0.55, 4).unwrap().is_empty());
/// ```
pub fn time_index_range<F: Float>(t0: F, t1: F, m: u32) -> Result<Range<u32>, Error> {
    check_m(m)?;
    let t0 = finite_f64(t0)?;
    let t1 = finite_f64(t1)?;
    let n = f64::from(1u32 << m);
    // ceil(t0 2^m) is the first j with j >= t0 2^m; floor(t1 2^m) the last with j <= t1 2^m.
    // Clipping in f64 before the cast keeps huge or negative values in range.
    let start = (t0 * n).ceil().clamp(0.0, n);
    let last = (t1 * n).floor().clamp(-1.0, n - 1.0);
    let end = (last + 1.0).max(start);
    // Both values are integers in 0..=2^31 here, so the casts are exact.
    Ok(start as u32..end as u32)
}

/// The time `j / 2^m` of point `j`, rounded once to `F` (exact in f64 for every m <= 31,
/// and in f32 for m <= 24). Errors as [`crate::get_xy()`] does for bad `m` or `j`.
pub fn sample_time<F: Float>(j: u32, m: u32) -> Result<F, Error> {
    check_m(m)?;
    if j >> m != 0 {
        return Err(Error::IndexOutOfRange { j, m });
    }
    F::from(f64::from(j) / f64::from(1u32 << m)).ok_or(Error::Conversion)
}

fn finite_f64<F: Float>(t: F) -> Result<f64, Error> {
    match t.to_f64() {
        Some(v) if v.is_finite() => Ok(v),
        _ => Err(Error::NonFiniteTime),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_interval() {
        assert_eq!(time_index_range(0.0f64, 1.0, 3).unwrap(), 0..8);
        assert_eq!(time_index_range(-5.0f64, 7.0, 31).unwrap(), 0..(1u32 << 31));
    }

    #[test]
    fn reversed_is_empty() {
        assert!(time_index_range(0.75f64, 0.25, 3).unwrap().is_empty());
    }

    #[test]
    fn non_finite_is_error() {
        assert_eq!(
            time_index_range(f64::NAN, 1.0, 3),
            Err(Error::NonFiniteTime)
        );
        assert_eq!(
            time_index_range(0.0, f32::INFINITY, 3),
            Err(Error::NonFiniteTime)
        );
    }

    #[test]
    fn sample_times() {
        assert_eq!(sample_time::<f64>(3, 2).unwrap(), 0.75);
        assert_eq!(sample_time::<f32>(0, 31).unwrap(), 0.0);
        assert!(sample_time::<f32>(4, 2).is_err());
    }
}
