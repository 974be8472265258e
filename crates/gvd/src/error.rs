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
    /// The run was stopped by its cancel flag ([`crate::Control::cancel`]) before it
    /// ended.
    #[error("cancelled: the run was stopped by its cancel flag before it ended")]
    Cancelled,
}

impl Error {
    /// The index of the site at fault, when the error names one (`Site`, `Unsupported`,
    /// the first of a `Conflict`): for bindings that carry it as a structured value.
    pub fn site_index(&self) -> Option<usize> {
        match self {
            Error::Site { site, .. }
            | Error::Unsupported { site, .. }
            | Error::Conflict { site, .. } => Some(*site),
            _ => None,
        }
    }
    /// The field at fault (`domain`, `epsilon`, `at`, `metric.p`, …), when the error names
    /// one (`Scene`, `Site`), or the option's name for `InvalidOption`.
    pub fn field(&self) -> Option<&str> {
        match self {
            Error::Scene { field, .. } | Error::Site { field, .. } => Some(field),
            Error::InvalidOption { option, .. } => Some(option),
            _ => None,
        }
    }
    /// The reason alone, without the site and field the [`std::fmt::Display`] text
    /// prefixes.
    pub fn message(&self) -> &str {
        match self {
            Error::Json(m) | Error::Internal(m) | Error::Diagram(m) => m,
            Error::Scene { message, .. }
            | Error::Site { message, .. }
            | Error::Unsupported { message, .. }
            | Error::Conflict { message, .. }
            | Error::InvalidOption { message, .. }
            | Error::Budget { message, .. } => message,
            Error::Cancelled => "cancelled",
        }
    }
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

#[cfg(test)]
mod tests {
    use super::Error;

    #[test]
    fn structured_accessors() {
        let e = Error::site(3, "metric.p", "p must be even");
        assert_eq!(
            (e.site_index(), e.field(), e.message()),
            (Some(3), Some("metric.p"), "p must be even")
        );
        let e = Error::scene("domain", "empty");
        assert_eq!((e.site_index(), e.field()), (None, Some("domain")));
        let e = Error::Conflict {
            site: 1,
            other: 4,
            message: "they cross".into(),
        };
        assert_eq!((e.site_index(), e.field()), (Some(1), None));
        assert_eq!(Error::Json("eof".into()).message(), "eof");
    }
}
