//! Errors of the rasteriser's configuration.

use core::fmt;

/// What can go wrong when building a buffer or starting a frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// A size or level configuration that the rasteriser cannot use.
    InvalidConfig(&'static str),
    /// The sample pattern rejected the configuration.
    Sampler(tmsnet::Error),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::InvalidConfig(m) => write!(f, "invalid configuration: {m}"),
            Error::Sampler(e) => write!(f, "sample pattern: {e}"),
        }
    }
}

impl std::error::Error for Error {}

impl From<tmsnet::Error> for Error {
    fn from(e: tmsnet::Error) -> Self {
        Error::Sampler(e)
    }
}
