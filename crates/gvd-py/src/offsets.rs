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
            let mut rows = Array2::zeros((pts.len(), 2));
            for (mut row, q) in rows.rows_mut().into_iter().zip(&pts) {
                row[0] = q.x;
                row[1] = q.y;
            }
            rows.into_pyarray(py)
        });
        PyList::new(py, arrays)
    }

    /// The curves as GeoJSON LineStrings, arcs as chords within `tolerance` (default:
    /// the scene's epsilon).
    #[pyo3(signature = (tolerance=None))]
    fn to_geojson(&self, tolerance: Option<f64>) -> String {
        gvd::io::geojson::write_offset(
            &self.scene,
            &self.offset,
            tolerance.unwrap_or(self.scene.epsilon()),
        )
    }

    /// The curves as DXF `LINE` and `ARC` entities (what CAM software opens).
    fn to_dxf(&self) -> String {
        gvd::io::dxf::write_offset(&self.offset)
    }

    /// A picture of the sites, the diagram's edges and the offset curves (SVG text).
    #[pyo3(signature = (width=800.0))]
    fn to_svg(&self, py: Python<'_>, width: f64) -> PyResult<String> {
        let scene = self.scene.clone();
        let opts = gvd::io::svg::SvgOptions {
            width_px: width,
            ..Default::default()
        };
        let complex = py
            .detach(|| {
                let scene = if scene.mode() == gvd::Mode::Voronoi {
                    scene.as_ref().clone().with_mode(gvd::Mode::Complex)
                } else {
                    scene.as_ref().clone()
                };
                gvd::compute(&scene, &gvd::Options::default())
            })
            .map_err(crate::errors::to_py)?;
        Ok(gvd::io::svg::render_offset_svg(
            &self.scene,
            &complex,
            &self.offset,
            &opts,
        ))
    }

    /// Draws the curves with matplotlib into `ax` (new axes when None).
    #[pyo3(signature = (ax=None, **kwargs))]
    fn plot<'py>(
        slf: &Bound<'py, Self>,
        ax: Option<Bound<'py, PyAny>>,
        kwargs: Option<&Bound<'py, pyo3::types::PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        slf.py()
            .import("gvd.plot")?
            .getattr("plot_offset")?
            .call((slf, ax), kwargs)
    }

    /// The curves as shapely geometries: LinearRings for closed curves, LineStrings
    /// for open ones, arcs as chords within `tolerance`.
    #[pyo3(signature = (tolerance=None))]
    fn to_shapely<'py>(
        slf: &Bound<'py, Self>,
        tolerance: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        slf.py()
            .import("gvd.geometry")?
            .call_method1("offsets", (slf, tolerance))
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
