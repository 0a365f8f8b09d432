//! The error type of the renderer library: a prepared scene a method cannot render, an option
//! out of range, or unusable input, each naming what is wrong.

/// Everything that can go wrong between a prepared scene and an image.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The requested method does not apply to this scene.
    #[error("method {method} cannot render this scene: {reason}")]
    MethodNotApplicable {
        /// The method.
        method: String,
        /// Why not.
        reason: String,
    },
    /// A render option is out of range.
    #[error("invalid option {option}: {message}")]
    Option {
        /// The option (`--times`, `--width`, ...).
        option: String,
        /// What is wrong.
        message: String,
    },
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
