//! Scenes from files: the library's readers, chosen by format name or extension, their
//! warnings raised as Python `UserWarning`s.

use crate::errors::{option_error, scene_error, to_py};
use crate::scene::{extract_box, parse_mode, PyScene};
use gvd::io::{Format, Projection, ReadOptions};
use pyo3::prelude::*;
use std::path::Path;

/// The format called `name`, or of `path`'s extension.
pub fn format_of(name: Option<&str>, path: Option<&Path>) -> PyResult<Format> {
    let known = "known: json, geojson, wkt, dxf, svg";
    match (name, path) {
        (Some(n), _) => Format::from_name(n)
            .ok_or_else(|| option_error("format", format!("unknown format '{n}' ({known})"))),
        (None, Some(p)) => Format::from_path(p).ok_or_else(|| {
            option_error(
                "format",
                format!(
                    "cannot tell the format of '{}' from its extension ({known}); give format=",
                    p.display()
                ),
            )
        }),
        (None, None) => Ok(Format::Json),
    }
}

/// How coordinates are taken: `None` or `"none"` planar, `"local"` longitude and latitude
/// projected about the data's centre.
fn parse_projection(name: Option<&str>) -> PyResult<Projection> {
    match name {
        None | Some("none") => Ok(Projection::None),
        Some("local") => Ok(Projection::Local),
        Some(other) => Err(option_error(
            "project",
            format!("unknown projection '{other}' (known: none, local)"),
        )),
    }
}

/// Reads a scene from `data` in `format`; `domain`, `epsilon` and `mode` override the
/// file's, `project` says how its coordinates are taken.
pub fn read(
    py: Python<'_>,
    data: &[u8],
    format: Format,
    domain: Option<&Bound<'_, PyAny>>,
    epsilon: Option<f64>,
    mode: Option<&str>,
    project: Option<&str>,
) -> PyResult<PyScene> {
    let options = ReadOptions {
        project: parse_projection(project)?,
        domain: domain
            .map(|d| extract_box(d, |m| scene_error("domain", m)))
            .transpose()?,
        epsilon,
        mode: mode.map(parse_mode).transpose()?,
    };
    let (scene, warnings) = py
        .detach(|| gvd::io::read_scene(data, format, &options))
        .map_err(to_py)?;
    let warn = py.import("warnings")?;
    for w in warnings {
        warn.call_method1(
            "warn",
            (w, py.get_type::<pyo3::exceptions::PyUserWarning>(), 2),
        )?;
    }
    Ok(PyScene::from_scene(scene))
}
