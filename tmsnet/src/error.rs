//! The crate's error type.

use core::fmt;

/// Everything that can go wrong in `tmsnet`. Library functions return this instead of
/// panicking; see each function for which variants it can produce.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// The net size exponent `m` is outside `1..=31` (a net of 2^m points with m-bit
    /// coordinates in a `u32`; m = 0 has no bits and m >= 32 overflows the index).
    InvalidM {
        /// The rejected exponent.
        m: u32,
    },
    /// The point index `j` is not below 2^m.
    IndexOutOfRange {
        /// The rejected index.
        j: u32,
        /// The net size exponent.
        m: u32,
    },
    /// A time bound was NaN or infinite.
    NonFiniteTime,
    /// A tile dimension or sample count is zero or not a power of two.
    NotPowerOfTwo {
        /// Which quantity: `"width"`, `"height"` or `"samples per pixel"`.
        what: &'static str,
        /// The rejected value.
        value: u32,
    },
    /// A tile's total sample count W·H·S is 1 (m = 0) or above 2^31.
    TileTooLarge {
        /// log2(W·H·S), which must lie in `1..=31`.
        log2_samples: u32,
    },
    /// Two objects that must share `m` (matrices of one net, net and tile) do not.
    SizeMismatch {
        /// The size exponent that was expected.
        expected: u32,
        /// The size exponent that was found.
        found: u32,
    },
    /// A generator matrix column has bits at or above bit m, or the column count is not m.
    BadColumns {
        /// The matrix size m.
        m: u32,
        /// The number of columns supplied.
        count: usize,
    },
    /// The generator chosen as time is not the exchange matrix, so its component is not
    /// j / 2^m and the net is not ordered in time (Munkberg 2011, Appendix A: C'_3 = C_1).
    NotTimeOrdered {
        /// The dimension that was asked to be time.
        dim: usize,
    },
    /// A point set handed to a quality measure is malformed: wrong point count for 2^m,
    /// coordinates out of range, or non-finite / outside [0, 1)^2.
    BadPointSet,
    /// A number could not be represented in the requested float type.
    Conversion,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::InvalidM { m } => write!(f, "net size exponent m = {m} is outside 1..=31"),
            Error::IndexOutOfRange { j, m } => {
                write!(f, "point index {j} is not below 2^{m}")
            }
            Error::NonFiniteTime => write!(f, "time bound is NaN or infinite"),
            Error::NotPowerOfTwo { what, value } => {
                write!(f, "{what} = {value} is not a power of two >= 1")
            }
            Error::TileTooLarge { log2_samples } => write!(
                f,
                "tile sample count 2^{log2_samples} is outside 2^1..=2^31"
            ),
            Error::SizeMismatch { expected, found } => {
                write!(
                    f,
                    "size exponent mismatch: expected m = {expected}, found m = {found}"
                )
            }
            Error::BadColumns { m, count } => write!(
                f,
                "generator matrix for m = {m} needs m columns below 2^m, got {count} columns"
            ),
            Error::NotTimeOrdered { dim } => write!(
                f,
                "generator {dim} is not the exchange matrix, so that component is not j / 2^m"
            ),
            Error::BadPointSet => write!(f, "malformed point set for the quality measure"),
            Error::Conversion => write!(f, "value not representable in the float type"),
        }
    }
}

impl std::error::Error for Error {}

/// Checks `1 <= m <= 31`.
pub(crate) fn check_m(m: u32) -> Result<(), Error> {
    if (1..=crate::MAX_M).contains(&m) {
        Ok(())
    } else {
        Err(Error::InvalidM { m })
    }
}

/// `2^m - 1` for `m` in `0..=32` without overflowing shifts.
#[inline]
pub(crate) const fn low_mask(m: u32) -> u32 {
    if m >= 32 { u32::MAX } else { (1u32 << m) - 1 }
}
