//! The library's [`gvd::Error`] as the exceptions of `gvd.errors`, with the site index
//! and field as attributes.

use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `err` as an instance of the matching class of `gvd.errors`.
pub fn to_py(err: gvd::Error) -> PyErr {
    Python::attach(|py| match build(py, &err) {
        Ok(e) => e,
        Err(e) => e,
    })
}

fn build(py: Python<'_>, err: &gvd::Error) -> PyResult<PyErr> {
    let kwargs = PyDict::new(py);
    let class = match err {
        gvd::Error::Json(_)
        | gvd::Error::Scene { .. }
        | gvd::Error::Site { .. }
        | gvd::Error::Conflict { .. } => {
            kwargs.set_item("site", err.site_index())?;
            kwargs.set_item("field", err.field())?;
            if let gvd::Error::Conflict { other, .. } = err {
                kwargs.set_item("other", other)?;
            }
            "SceneError"
        }
        gvd::Error::Unsupported { site, kind, .. } => {
            kwargs.set_item("site", site)?;
            kwargs.set_item("kind", kind)?;
            "UnsupportedError"
        }
        gvd::Error::Budget { what, limit, .. } => {
            kwargs.set_item("what", what)?;
            kwargs.set_item("limit", limit)?;
            "BudgetError"
        }
        gvd::Error::InvalidOption { option, .. } => {
            kwargs.set_item("option", option)?;
            "OptionError"
        }
        gvd::Error::Diagram(_) => "DiagramError",
        gvd::Error::Internal(_) => "InternalError",
        gvd::Error::Cancelled => "Error",
    };
    kwargs.set_item("reason", err.message())?;
    let class = py.import("gvd.errors")?.getattr(class)?;
    let value = class.call((err.to_string(),), Some(&kwargs))?;
    Ok(PyErr::from_value(value))
}

/// A refusal of site `site`'s `field` raised before the library sees the site (a value of
/// the wrong Python type), with the library's wording.
pub fn site_error(site: usize, field: &str, message: impl Into<String>) -> PyErr {
    to_py(gvd::Error::Site {
        site,
        field: field.to_string(),
        message: message.into(),
    })
}

/// A refusal of the scene-level `field`.
pub fn scene_error(field: &str, message: impl Into<String>) -> PyErr {
    to_py(gvd::Error::Scene {
        field: field.to_string(),
        message: message.into(),
    })
}

/// A refusal of the option `option`.
pub fn option_error(option: &str, message: impl Into<String>) -> PyErr {
    to_py(gvd::Error::InvalidOption {
        option: option.to_string(),
        message: message.into(),
    })
}
