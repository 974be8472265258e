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
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// Computes the diagram of `scene` (see `gvd.compute`, which also takes dicts, JSON
/// text and paths).
#[pyfunction]
// the keyword arguments of the Python function
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (scene, engine="auto", *, parallel=true, max_box=None, max_boxes=None, max_points=None, bisectors=false, strict=false, timeout=None, prune_lambda=None, prune_angle=None))]
fn compute(
    py: Python<'_>,
    scene: &mut PyScene,
    engine: &str,
    parallel: bool,
    max_box: Option<f64>,
    max_boxes: Option<usize>,
    max_points: Option<usize>,
    bisectors: bool,
    strict: bool,
    timeout: Option<f64>,
    prune_lambda: Option<f64>,
    prune_angle: Option<f64>,
) -> PyResult<PyDiagram> {
    let engine = match engine {
        "auto" => gvd::Engine::Auto,
        "subdivision" => gvd::Engine::Subdivision,
        "incremental" => gvd::Engine::Incremental,
        "freeform" => gvd::Engine::Freeform,
        other => {
            return Err(option_error(
                "engine",
                format!(
                    "unknown engine '{other}' (known: auto, subdivision, incremental, freeform)"
                ),
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
    let timeout = match timeout {
        None => None,
        Some(t) if t.is_finite() && t > 0.0 => Some(Duration::from_secs_f64(t)),
        Some(t) => {
            return Err(option_error(
                "timeout",
                format!("must be a finite number of seconds > 0, found {t}"),
            ))
        }
    };
    let cancel = Arc::new(AtomicBool::new(false));
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
        incremental: gvd::IncrementalOptions { bisectors, strict },
        control: gvd::Control {
            cancel: Some(cancel.clone()),
            timeout,
            progress: None,
        },
        prune: gvd::Pruning {
            lambda: prune_lambda,
            object_angle: prune_angle.map(f64::to_radians),
        },
    };
    let scene = scene.scene()?;
    let complex = interruptible(py, &cancel, || gvd::compute(&scene, &options))?;
    Ok(PyDiagram::new(scene, complex.map_err(to_py)?))
}

/// Runs `work` on a thread of its own without the GIL, looking for signals (Ctrl-C)
/// every 20 ms; on one it sets `cancel`, waits for `work` to stop and raises the
/// signal's exception (`KeyboardInterrupt`).
fn interruptible<T: Send>(
    py: Python<'_>,
    cancel: &AtomicBool,
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    std::thread::scope(|scope| {
        let worker = scope.spawn(work);
        loop {
            let finished = py.detach(|| {
                for _ in 0..4 {
                    if worker.is_finished() {
                        return true;
                    }
                    std::thread::sleep(Duration::from_millis(5));
                }
                worker.is_finished()
            });
            if finished {
                break;
            }
            if let Err(signal) = py.check_signals() {
                cancel.store(true, Ordering::Relaxed);
                let _ = worker.join();
                return Err(signal);
            }
        }
        worker
            .join()
            .map_err(|_| to_py(gvd::Error::Internal("the computation panicked".into())))
    })
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
