//! The error type of the renderer library: a prepared scene a method cannot render, an option
//! out of range, a pixel the resolve could not integrate, or an internal invariant that
//! failed, each naming what is wrong.

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
    /// A setting of a method's options is out of range.
    #[error("{method}: invalid setting `{setting}`: {message}")]
    Setting {
        /// The method whose options hold it (`accum`, `stochastic`, ...; `inspect` for the
        /// pixel visualiser).
        method: &'static str,
        /// The field of the method's options (`times`, `spp`, ...).
        setting: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The resolve (Gribel 2010, §5.1) refused the interval list of a pixel: a non-finite
    /// interval or shaded colour that emission let through. Not a property of the method:
    /// the same scene renders with the method elsewhere in the image.
    #[error("{method}: the resolve of pixel ({x}, {y}) failed: {message}")]
    Resolve {
        /// The method whose interval chain ran.
        method: String,
        /// Pixel column.
        x: u32,
        /// Pixel row.
        y: u32,
        /// The resolve's error.
        message: String,
    },
    /// The exact interval lists of one image row outgrew the row's share of the memory
    /// budget (`max_memory` of the method's options, divided among the rows in flight, one
    /// per thread). Found while the first such row is emitted, before its lists are sorted.
    /// The remedies: bound the lists to K intervals per pixel (`intervals`), fewer threads,
    /// or a larger `max_memory`.
    #[error(
        "{method}: row {row} alone needs more than {row_limit} intervals ({} per thread at \
         {bytes_per_interval} bytes each), over the memory budget of the exact interval lists",
        human_bytes(row_limit.saturating_mul(*bytes_per_interval))
    )]
    MemoryBudget {
        /// The method whose interval chain ran.
        method: String,
        /// The image row.
        row: u32,
        /// Bytes of memory per interval of the exact lists.
        bytes_per_interval: u64,
        /// Most intervals a row may hold under the budget.
        row_limit: u64,
    },
    /// An internal invariant failed (an index that cannot be out of range was, a buffer
    /// was handed intervals it rejects): a bug in mblur, never a property of the scene.
    /// Debug builds panic at the failure instead (`Error::internal`).
    #[error("internal error in {context} (a bug in mblur): {message}")]
    Internal {
        /// Where it failed.
        context: String,
        /// What failed.
        message: String,
    },
}

impl Error {
    /// The error of an internal invariant failure in `context`: panics in debug builds
    /// (`debug_assert!`), so tests stop at the bug; release builds return
    /// [`Error::Internal`] instead of a silently wrong image.
    #[track_caller]
    pub(crate) fn internal(context: &str, message: impl Into<String>) -> Error {
        let message = message.into();
        debug_assert!(false, "internal error in {context}: {message}");
        Error::Internal {
            context: context.into(),
            message,
        }
    }
}

/// `bytes` as "12.3 MiB" (binary units).
pub(crate) fn human_bytes(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["bytes", "KiB", "MiB", "GiB", "TiB"];
    let mut v = bytes as f64;
    let mut unit = 0;
    while v >= 1024.0 && unit + 1 < UNITS.len() {
        v /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} bytes")
    } else {
        format!("{v:.1} {}", UNITS[unit])
    }
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;
