//! Errors of the interval buffers.

use std::fmt;

/// Why a buffer operation failed. No operation panics on finite input; these are returned
/// instead.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// An interval had a non-finite parameter or `ts > te`.
    InvalidInterval,
    /// A pixel coordinate or index outside the image.
    PixelOutOfRange {
        /// The offending pixel index (`y * width + x`, saturated).
        pixel: usize,
        /// Number of pixels in the image.
        pixels: usize,
    },
    /// The bounded capacity K must be at least 1 and fit in `u32`.
    InvalidCapacity(usize),
    /// `width * height * capacity` does not fit in memory indices.
    TooLarge,
    /// The exact strategy's total interval count exceeds `u32::MAX` (Rønnow 2021 §4.1 indexes
    /// the global interval buffer with 32-bit offsets), or a pixel's counter overflowed.
    TooManyIntervals {
        /// The total that was requested (saturated at `u64::MAX`).
        total: u64,
    },
    /// The exact strategy's fill pass pushed more intervals into a pixel than were counted.
    PushOverCount {
        /// The pixel index.
        pixel: usize,
        /// What the count pass recorded for it.
        counted: u32,
    },
    /// The exact strategy's fill pass ended with fewer intervals in a pixel than counted.
    CountMismatch {
        /// The pixel index.
        pixel: usize,
        /// What the count pass recorded for it.
        counted: u32,
        /// What the fill pass pushed.
        pushed: u32,
    },
    /// A compact interval needs times in [0, 1].
    TimeOutOfRange,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::InvalidInterval => write!(f, "interval has a non-finite parameter or ts > te"),
            Error::PixelOutOfRange { pixel, pixels } => {
                write!(f, "pixel index {pixel} outside an image of {pixels} pixels")
            }
            Error::InvalidCapacity(k) => write!(f, "capacity {k} must be in 1..=u32::MAX"),
            Error::TooLarge => write!(f, "width * height * capacity overflows usize"),
            Error::TooManyIntervals { total } => write!(
                f,
                "{total} intervals exceed the u32 offsets of the exact buffer (max {})",
                u32::MAX
            ),
            Error::PushOverCount { pixel, counted } => {
                write!(
                    f,
                    "pixel {pixel}: more intervals pushed than the {counted} counted"
                )
            }
            Error::CountMismatch {
                pixel,
                counted,
                pushed,
            } => write!(
                f,
                "pixel {pixel}: counted {counted} intervals but pushed {pushed}"
            ),
            Error::TimeOutOfRange => write!(f, "compact intervals need times in [0, 1]"),
        }
    }
}

impl std::error::Error for Error {}
