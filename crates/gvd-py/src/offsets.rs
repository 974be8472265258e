//! `gvd.Offset`: offset curves of lines and arcs, with their scene.

use crate::diagram::to_python;
use gvd::{Offset, Scene};
use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyList;
use std::sync::Arc;

/// Offset curves at one distance from the sites: each curve a chain of exact lines and
/// circular arcs (`curves`), or as polylines (`polylines()`).
#[pyclass(name = "Offset", module = "gvd", frozen)]
pub struct PyOffset {
    scene: Arc<Scene>,
    offset: Offset,
}

impl PyOffset {
    /// The offset curves `offset` of `scene`.
    pub fn new(scene: Arc<Scene>, offset: Offset) -> PyOffset {
        PyOffset { scene, offset }
    }
}

#[pymethods]
impl PyOffset {
    /// The offset distance.
    #[getter]
    fn distance(&self) -> f64 {
        self.offset.distance
    }

    /// The curves as dicts `{"closed": bool, "primitives": [...]}`, each primitive
    /// `{"kind": "line", "from", "to"}` or `{"kind": "arc", "center", "radius",
    /// "start_angle", "end_angle"}` (`docs/SCENE_FORMAT.md`, "Offsets").
    #[getter]
    fn curves<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.offset.curves)
    }

    /// Whether each curve is closed.
    #[getter]
    fn closed(&self) -> Vec<bool> {
        self.offset.curves.iter().map(|c| c.closed).collect()
    }

    /// Figures of the run.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.offset.stats)
    }

    /// Every curve as a k×2 array of points within `tolerance` of it (default: the
    /// scene's epsilon); a closed curve repeats its first point last.
    #[pyo3(signature = (tolerance=None))]
    fn polylines<'py>(
        &self,
        py: Python<'py>,
        tolerance: Option<f64>,
    ) -> PyResult<Bound<'py, PyList>> {
        let tol = tolerance.unwrap_or(self.scene.epsilon());
        if !(tol.is_finite() && tol > 0.0) {
            return Err(crate::errors::option_error(
                "tolerance",
                format!("must be a finite number > 0, found {tol}"),
            ));
        }
        let arrays = self.offset.curves.iter().map(|c| {
            let pts = c.polyline(tol);
            let flat: Vec<f64> = pts.iter().flat_map(|q| [q.x, q.y]).collect();
            Array2::from_shape_vec((pts.len(), 2), flat)
                .expect("two columns")
                .into_pyarray(py)
        });
        PyList::new(py, arrays)
    }

    /// The curves as JSON (`docs/SCENE_FORMAT.md`, "Offsets").
    fn to_json(&self) -> String {
        self.offset.to_json()
    }

    fn __len__(&self) -> usize {
        self.offset.curves.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Offset(distance={}, {} curves, {} closed)",
            self.offset.distance,
            self.offset.curves.len(),
            self.offset.curves.iter().filter(|c| c.closed).count()
        )
    }
}
