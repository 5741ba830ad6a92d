//! The library's error type: every failure a user's input can cause, each naming the file,
//! line or field at fault.

use std::path::PathBuf;

/// Errors raised while loading scenes and writing images.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The OS's reason is part of the message and not also returned by `source()`, so
    /// that a printed chain (anyhow's `{:#}`) says it once.
    #[error("cannot read {path}: {reason}")]
    Io {
        path: PathBuf,
        reason: std::io::Error,
    },
    #[error("{path}:{line}:{column}: {message}")]
    Syntax {
        path: PathBuf,
        line: usize,
        column: usize,
        message: String,
    },
    #[error("{path}: {message}")]
    Invalid { path: PathBuf, message: String },
    #[error("{path}: OBJ/MTL error: {message}")]
    Obj { path: PathBuf, message: String },
    #[error("{path}: texture: {message}")]
    Texture { path: PathBuf, message: String },
    #[error("cannot write {path}: {message}")]
    Write { path: PathBuf, message: String },
    #[error("{0}")]
    Other(String),
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    pub fn invalid(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Error::Invalid {
            path: path.into(),
            message: message.into(),
        }
    }
}
