//! Errors the resolve reports instead of producing a NaN pixel.

use std::fmt;

/// Why a pixel, a shutter or a texture could not be resolved or built.
///
/// Library functions never panic on finite input; everything that would make the resolve
/// meaningless (non-finite numbers, reversed intervals, unsorted input, a shutter that
/// integrates to zero) is reported here instead (ARCHITECTURE.md, "Errors").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResolveError {
    /// The interval at `index` has a non-finite parameter, `ts > te`, or a depth line whose
    /// intercept `z - k ts` overflows.
    InvalidInterval {
        /// Position of the interval in the pixel's list.
        index: usize,
    },
    /// The interval at `index` starts before its predecessor: the input must be sorted by
    /// `ts` (Gribel 2010, §5.1; Rønnow 2021, Algorithm 1 input).
    Unsorted {
        /// Position of the first out-of-order interval.
        index: usize,
    },
    /// A colour produced by the shader (or the background) was not finite.
    NonFiniteColour,
    /// A setting is out of range (non-finite background, threshold outside [0, 1]).
    InvalidSettings,
    /// Shutter knots are not finite, not inside [0, 1], not in non-decreasing time order,
    /// have a negative weight, or the response integrates to zero.
    InvalidShutter,
    /// A texture has zero size, a texel count that does not match its size, or a
    /// non-finite texel.
    InvalidTexture,
    /// The output slice of a frame resolve does not hold `width * height` pixels.
    OutputSize {
        /// `width * height`.
        expected: usize,
        /// Length of the slice given.
        got: usize,
    },
    /// A pixel of a frame resolve failed; `error` says why.
    Pixel {
        /// Row-major pixel index `y * width + x`.
        index: usize,
        /// The pixel's own error (never another `Pixel`).
        error: PixelError,
    },
}

/// The per-pixel part of [`ResolveError::Pixel`] (the same cases as a single-pixel resolve).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelError {
    /// See [`ResolveError::InvalidInterval`].
    InvalidInterval {
        /// Position of the interval in the pixel's list.
        index: usize,
    },
    /// See [`ResolveError::Unsorted`].
    Unsorted {
        /// Position of the first out-of-order interval.
        index: usize,
    },
    /// See [`ResolveError::NonFiniteColour`].
    NonFiniteColour,
}

impl ResolveError {
    /// Wraps a single-pixel error as the error of pixel `index` of a frame.
    pub(crate) fn at_pixel(self, index: usize) -> Self {
        let error = match self {
            ResolveError::InvalidInterval { index } => PixelError::InvalidInterval { index },
            ResolveError::Unsorted { index } => PixelError::Unsorted { index },
            ResolveError::NonFiniteColour => PixelError::NonFiniteColour,
            other => return other,
        };
        ResolveError::Pixel { index, error }
    }
}

impl fmt::Display for ResolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ResolveError::InvalidInterval { index } => {
                write!(f, "interval {index} is not finite or has ts > te")
            }
            ResolveError::Unsorted { index } => {
                write!(
                    f,
                    "interval {index} starts before its predecessor (input must be sorted by ts)"
                )
            }
            ResolveError::NonFiniteColour => write!(f, "a shaded colour was not finite"),
            ResolveError::InvalidSettings => write!(f, "resolve settings out of range"),
            ResolveError::InvalidShutter => write!(f, "invalid shutter response"),
            ResolveError::InvalidTexture => write!(f, "invalid texture"),
            ResolveError::OutputSize { expected, got } => {
                write!(f, "output holds {got} pixels, expected {expected}")
            }
            ResolveError::Pixel { index, error } => write!(f, "pixel {index}: {error:?}"),
        }
    }
}

impl std::error::Error for ResolveError {}
