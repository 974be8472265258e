//! `gvd.Report`: what the independent checker found.

use crate::errors::to_py;
use gvd::{Report, Scene, VerifyOptions, VoronoiComplex};
use pyo3::prelude::*;

/// The checker's findings: `sound` and `complete` fractions, `vertices_ok`,
/// `worst_edge_error`, `problems`, `warnings`, `passed` (also the report's truth value).
#[pyclass(name = "Report", module = "gvd", frozen, get_all)]
pub struct PyReport {
    /// The fraction of edge samples within tolerance of their bisector.
    sound: f64,
    /// The fraction of grid bisector crossings covered by an edge or vertex.
    complete: f64,
    /// `(good, total)` vertices.
    vertices_ok: (usize, usize),
    /// The largest edge sample error, in length units.
    worst_edge_error: f64,
    /// The worst offenders of each check.
    problems: Vec<String>,
    /// Findings that do not fail the diagram.
    warnings: Vec<String>,
    /// Whether every check passed.
    passed: bool,
    summary: String,
}

/// Runs the checker with the GIL released.
pub fn verify(
    py: Python<'_>,
    scene: &Scene,
    diagram: &VoronoiComplex,
    grid: usize,
    slack: f64,
) -> PyResult<PyReport> {
    let opts = VerifyOptions {
        grid,
        slack,
        ..Default::default()
    };
    let r: Report = py
        .detach(|| gvd::verify(scene, diagram, &opts))
        .map_err(to_py)?;
    Ok(PyReport {
        summary: r.summary_line(),
        sound: r.sound,
        complete: r.complete,
        vertices_ok: r.vertices_ok,
        worst_edge_error: r.worst_edge_error,
        problems: r.problems,
        warnings: r.warnings,
        passed: r.passed,
    })
}

#[pymethods]
impl PyReport {
    fn __bool__(&self) -> bool {
        self.passed
    }

    fn __repr__(&self) -> String {
        format!("Report({})", self.summary)
    }
}
