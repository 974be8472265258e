//! The library's error type: every refusal names what was wrong and where.

use thiserror::Error;

/// Why a scene was refused or a computation could not run.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// The text is not valid JSON.
    #[error("invalid JSON: {0}")]
    Json(String),
    /// A scene-level field is missing or invalid (`domain`, `epsilon`, `mode`, `sites`).
    #[error("field '{field}': {message}")]
    Scene { field: String, message: String },
    /// A site's field is missing or invalid.
    #[error("site {site} field '{field}': {message}")]
    Site {
        site: usize,
        field: String,
        message: String,
    },
    /// The site is valid but the chosen algorithm cannot compute it (yet).
    #[error("site {site} (kind '{kind}'): {message}")]
    Unsupported {
        site: usize,
        kind: String,
        message: String,
    },
    /// Two sites cross, overlap, or one touches the other's interior.
    #[error("sites {site} and {other}: {message}")]
    Conflict {
        site: usize,
        other: usize,
        message: String,
    },
    /// An engine could not complete (a bug, reported instead of a wrong diagram).
    #[error("internal error: {0}")]
    Internal(String),
    /// A diagram file could not be read.
    #[error("diagram: {0}")]
    Diagram(String),
    /// An option of a computation or a check is out of its range.
    #[error("option '{option}': {message}")]
    InvalidOption { option: String, message: String },
    /// A computation reached a work limit (`what`: "boxes" or "points") before it ended.
    #[error("{message}")]
    Budget {
        what: String,
        limit: usize,
        message: String,
    },
}

impl Error {
    pub(crate) fn site(site: usize, field: &str, message: impl Into<String>) -> Self {
        Error::Site {
            site,
            field: field.to_string(),
            message: message.into(),
        }
    }
    pub(crate) fn scene(field: &str, message: impl Into<String>) -> Self {
        Error::Scene {
            field: field.to_string(),
            message: message.into(),
        }
    }
}
