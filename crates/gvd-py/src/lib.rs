//! The `gvd._gvd` extension module: the Rust side of the `gvd` Python package
//! (`python/gvd`). Scenes are built through the library's `SceneBuilder`, computations
//! run with the GIL released, and the library's errors become the exceptions of
//! `gvd.errors` with the site index and field as attributes.

mod diagram;
mod errors;
mod offsets;
mod read;
mod report;
mod scene;

use diagram::PyDiagram;
use errors::{option_error, to_py};
use offsets::PyOffset;
use pyo3::prelude::*;
use report::PyReport;
use scene::PyScene;

/// Computes the diagram of `scene` (see `gvd.compute`, which also takes dicts, JSON
/// text and paths).
#[pyfunction]
// the keyword arguments of the Python function
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (scene, engine="auto", *, parallel=true, max_box=None, max_boxes=None, max_points=None, bisectors=false))]
fn compute(
    py: Python<'_>,
    scene: &mut PyScene,
    engine: &str,
    parallel: bool,
    max_box: Option<f64>,
    max_boxes: Option<usize>,
    max_points: Option<usize>,
    bisectors: bool,
) -> PyResult<PyDiagram> {
    let engine = match engine {
        "auto" => gvd::Engine::Auto,
        "subdivision" => gvd::Engine::Subdivision,
        "incremental" => gvd::Engine::Incremental,
        other => {
            return Err(option_error(
                "engine",
                format!("unknown engine '{other}' (known: auto, subdivision, incremental)"),
            ))
        }
    };
    if let Some(b) = max_box {
        if !(b.is_finite() && b > 0.0) {
            return Err(option_error(
                "max_box",
                format!("must be a finite number > 0, found {b}"),
            ));
        }
    }
    let options = gvd::Options {
        engine,
        parallel,
        subdivision: gvd::SubdivisionOptions {
            max_box,
            limits: gvd::Limits {
                max_boxes,
                max_points,
            },
            ..Default::default()
        },
        incremental: gvd::IncrementalOptions {
            bisectors,
            ..Default::default()
        },
        ..Default::default()
    };
    let scene = scene.scene()?;
    let complex = py
        .detach(|| gvd::compute(&scene, &options))
        .map_err(to_py)?;
    Ok(PyDiagram::new(scene, complex))
}

/// The offset curves of `scene` at `distance` (the diagram computed in `complex` mode
/// for a `voronoi` scene).
#[pyfunction]
fn offset(py: Python<'_>, scene: &mut PyScene, distance: f64) -> PyResult<PyOffset> {
    let scene = scene.scene()?;
    let (off, _) = py
        .detach(|| gvd::offset_scene(&scene, distance, &gvd::Options::default()))
        .map_err(to_py)?;
    Ok(PyOffset::new(scene, off))
}

/// Checks `diagram` against `scene` by brute force.
#[pyfunction]
#[pyo3(signature = (scene, diagram, grid=512, slack=1.0))]
fn verify(
    py: Python<'_>,
    scene: &mut PyScene,
    diagram: &PyDiagram,
    grid: usize,
    slack: f64,
) -> PyResult<PyReport> {
    let scene = scene.scene()?;
    report::verify(py, &scene, &diagram.complex, grid, slack)
}

/// Reads a diagram from JSON text and pairs it with `scene` (for `gvd.verify` of a
/// diagram written by another tool).
#[pyfunction]
fn read_diagram(scene: &mut PyScene, text: &str) -> PyResult<PyDiagram> {
    let complex = gvd::io::json::read_diagram(text).map_err(to_py)?;
    Ok(PyDiagram::new(scene.scene()?, complex))
}

#[pymodule]
fn _gvd(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<PyScene>()?;
    m.add_class::<PyDiagram>()?;
    m.add_class::<PyOffset>()?;
    m.add_class::<PyReport>()?;
    m.add_function(wrap_pyfunction!(compute, m)?)?;
    m.add_function(wrap_pyfunction!(offset, m)?)?;
    m.add_function(wrap_pyfunction!(verify, m)?)?;
    m.add_function(wrap_pyfunction!(read_diagram, m)?)?;
    Ok(())
}
