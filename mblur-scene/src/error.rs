//! The error type of scene and image files: every failure names the file, the line and column
//! or the object and field, and the OS reason where there is one.

use std::path::PathBuf;

/// Everything that can go wrong between a scene file and an image file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The scene file is not valid JSON or does not match the schema (unknown field, wrong
    /// type, missing field, number out of range such as `1e999`).
    #[error("{file}: line {line}, column {column}: {at}{message}")]
    Json {
        /// The scene file (or `<built-in NAME>`).
        file: String,
        /// 1-based line of the error.
        line: usize,
        /// 1-based column of the error.
        column: usize,
        /// Where in the document (`objects[1].material: `), empty at the top level.
        at: String,
        /// What serde expected or found.
        message: String,
    },
    /// A value parsed but is not usable: non-finite, negative size, near >= far, image too
    /// large, vertex count mismatch, ...
    #[error("{file}: {field}: {message}")]
    Invalid {
        /// The scene file (or `<built-in NAME>`, or `<scene>` for scenes built in code).
        file: String,
        /// The object and field, e.g. `objects[2] "ball".material.color[3]`.
        field: String,
        /// What is wrong with it.
        message: String,
    },
    /// A file could not be opened or read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The OS reason.
        #[source]
        source: std::io::Error,
    },
    /// A mesh, point cloud or texture file was read but its content is unusable.
    #[error("{path}: {message}")]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong with the content.
        message: String,
    },
    /// An output image could not be written (nothing is left at the target path).
    #[error("cannot write {path}: {message}")]
    Write {
        /// The target file.
        path: PathBuf,
        /// The reason.
        message: String,
    },
    /// A built-in scene name that does not exist.
    #[error("unknown built-in scene `{0}` (run `mblur scenes` for the list)")]
    UnknownScene(String),
    /// The renderer refused the prepared scene or an option.
    #[error(transparent)]
    Render(#[from] mblur::Error),
    /// A command-line option is out of range.
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

impl Error {
    /// An unusable value: `field` of `file` and what is wrong with it.
    pub fn invalid(file: &str, field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Invalid {
            file: file.to_string(),
            field: field.into(),
            message: message.into(),
        }
    }

    /// A file whose content is unusable.
    pub fn format(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Error::Format {
            path: path.into(),
            message: message.into(),
        }
    }

    /// A file that could not be opened or read, with the OS reason.
    pub fn read(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Read {
            path: path.into(),
            source,
        }
    }
}
