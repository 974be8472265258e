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
    Scene {
        /// The field at fault.
        field: String,
        /// Why it was refused.
        message: String,
    },
    /// A site's field is missing or invalid.
    #[error("site {site} field '{field}': {message}")]
    Site {
        /// The site's index in the scene.
        site: usize,
        /// The field at fault (`at`, `metric.p`, `rings`, …).
        field: String,
        /// Why it was refused.
        message: String,
    },
    /// The site is valid but the chosen algorithm cannot compute it (yet).
    #[error("site {site} (kind '{kind}'): {message}")]
    Unsupported {
        /// The site's index in the scene.
        site: usize,
        /// The site's kind (`bezier`, …).
        kind: String,
        /// What the engine cannot do.
        message: String,
    },
    /// Two sites cross, overlap, or one touches the other's interior.
    #[error("sites {site} and {other}: {message}")]
    Conflict {
        /// The first site's index.
        site: usize,
        /// The other site's index.
        other: usize,
        /// How they meet.
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
    InvalidOption {
        /// The option's name.
        option: String,
        /// Why it was refused.
        message: String,
    },
    /// A computation reached a work limit (`what`: "boxes" or "points") before it ended.
    #[error("{message}")]
    Budget {
        /// What ran out: "boxes" or "points".
        what: String,
        /// The limit that was reached.
        limit: usize,
        /// What happened and which option raises the limit.
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
