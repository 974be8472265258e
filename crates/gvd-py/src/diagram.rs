//! `gvd.Diagram`: a computed diagram with its scene, as numpy arrays (built on first
//! access, then shared and read-only) and through the library's writers.

use crate::errors::to_py;
use crate::offsets::PyOffset;
use crate::report::PyReport;
use gvd::complex::{FeatureKind, Generator};
use gvd::{Scene, VoronoiComplex};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::sync::{Arc, OnceLock};

/// Generators as rows `(site, feature, index)`: feature 0 is the whole site (index −1),
/// 1 a corner, 2 an edge, 3 a curve piece.
fn generator_row(g: &Generator) -> [i64; 3] {
    match *g {
        Generator::Site(i) => [i as i64, 0, -1],
        Generator::Feature {
            site,
            feature,
            index,
        } => {
            let f = match feature {
                FeatureKind::Corner => 1,
                FeatureKind::Edge => 2,
                FeatureKind::Piece => 3,
            };
            [site as i64, f, index as i64]
        }
    }
}

/// `value` as Python data, through JSON (stats, offsets).
pub fn to_python<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).unwrap_or_else(|_| "null".into());
    py.import("json")?.call_method1("loads", (text,))
}

/// A read-only view of a fresh array.
fn frozen<'py>(a: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let kwargs = PyDict::new(a.py());
    kwargs.set_item("write", false)?;
    a.call_method("setflags", (), Some(&kwargs))?;
    Ok(a)
}

fn points_array(points: impl Iterator<Item = gvd::Point>, n: usize) -> Array2<f64> {
    let mut rows = Array2::zeros((n, 2));
    for (mut row, p) in rows.rows_mut().into_iter().zip(points) {
        row[0] = p.x;
        row[1] = p.y;
    }
    rows
}

/// `rows` of `N` integers as an array of shape `(rows.len(), N)`.
fn int_rows<const N: usize>(rows: impl Iterator<Item = [i64; N]>, n: usize) -> Array2<i64> {
    let mut out = Array2::zeros((n, N));
    for (mut row, r) in out.rows_mut().into_iter().zip(rows) {
        for (k, v) in r.into_iter().enumerate() {
            row[k] = v;
        }
    }
    out
}

fn offsets(lengths: impl Iterator<Item = usize>) -> Array1<i64> {
    let mut out = vec![0i64];
    let mut total = 0i64;
    for n in lengths {
        total += n as i64;
        out.push(total);
    }
    Array1::from_vec(out)
}

/// A computed Voronoi diagram (or complex, or medial axis) with its scene.
///
/// Arrays: `vertices` (N×2), `vertex_generators` (rows `(site, feature, index)`,
/// CSR by `vertex_offsets`), `edge_points` (P×2, CSR by `edge_offsets`),
/// `edge_generators` (E×2×3), `edge_sites` (E×2), `edge_ends` (E×2, −1 on the domain's
/// boundary), `clearances` (N), cells as `cell_sites`, `cell_points`,
/// `cell_ring_offsets` and `cell_offsets`; also `edges` and `cells` as lists.
#[pyclass(name = "Diagram", module = "gvd", frozen)]
pub struct PyDiagram {
    pub scene: Arc<Scene>,
    pub complex: VoronoiComplex,
    cache: [OnceLock<Py<PyAny>>; 13],
}

impl PyDiagram {
    /// A diagram of `scene`.
    pub fn new(scene: Arc<Scene>, complex: VoronoiComplex) -> PyDiagram {
        PyDiagram {
            scene,
            complex,
            cache: Default::default(),
        }
    }

    fn cached<'py>(
        &self,
        py: Python<'py>,
        slot: usize,
        make: impl FnOnce(&VoronoiComplex) -> PyResult<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        if let Some(v) = self.cache[slot].get() {
            return Ok(v.bind(py).clone());
        }
        let value = make(&self.complex)?;
        let value = if value.hasattr("setflags")? {
            frozen(value)?
        } else {
            value
        };
        let _ = self.cache[slot].set(value.clone().unbind());
        Ok(value)
    }
}

#[pymethods]
impl PyDiagram {
    /// Vertex coordinates, N×2.
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 0, |d| {
            let n = d.vertices.len();
            Ok(points_array(d.vertices.iter().map(|v| v.at), n)
                .into_pyarray(py)
                .into_any())
        })
    }

    /// Every vertex's generators as rows `(site, feature, index)`, int64; vertex `k`'s
    /// are rows `vertex_offsets[k]:vertex_offsets[k + 1]`. Feature 0 is the whole site
    /// (index −1), 1 a corner, 2 an edge, 3 a curve piece.
    #[getter]
    fn vertex_generators<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 1, |d| {
            let n = d.vertices.iter().map(|v| v.sites.len()).sum();
            let rows = d
                .vertices
                .iter()
                .flat_map(|v| v.sites.iter().map(generator_row));
            Ok(int_rows(rows, n).into_pyarray(py).into_any())
        })
    }

    /// CSR offsets of `vertex_generators` (N + 1).
    #[getter]
    fn vertex_offsets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 2, |d| {
            Ok(offsets(d.vertices.iter().map(|v| v.sites.len()))
                .into_pyarray(py)
                .into_any())
        })
    }

    /// The points of every edge's polyline, P×2; edge `k`'s are rows
    /// `edge_offsets[k]:edge_offsets[k + 1]`.
    #[getter]
    fn edge_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 3, |d| {
            let n = d.edges.iter().map(|e| e.points.len()).sum();
            Ok(
                points_array(d.edges.iter().flat_map(|e| e.points.iter().copied()), n)
                    .into_pyarray(py)
                    .into_any(),
            )
        })
    }

    /// CSR offsets of `edge_points` (E + 1).
    #[getter]
    fn edge_offsets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 4, |d| {
            Ok(offsets(d.edges.iter().map(|e| e.points.len()))
                .into_pyarray(py)
                .into_any())
        })
    }

    /// The two generators of every edge, E×2×3 rows `(site, feature, index)`.
    #[getter]
    fn edge_generators<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 5, |d| {
            let rows = d
                .edges
                .iter()
                .flat_map(|e| e.sites.iter().map(generator_row));
            let flat = int_rows(rows, 2 * d.edges.len());
            let arr = flat.into_pyarray(py);
            Ok(arr.reshape([d.edges.len(), 2, 3])?.into_any())
        })
    }

    /// The two sites every edge separates, E×2 (the site of each generator).
    #[getter]
    fn edge_sites<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 6, |d| {
            let rows = d.edges.iter().map(|e| e.sites.map(|g| g.site() as i64));
            Ok(int_rows(rows, d.edges.len()).into_pyarray(py).into_any())
        })
    }

    /// Every edge's end vertices `(from, to)`, E×2; −1 where it ends on the domain's
    /// boundary.
    #[getter]
    fn edge_ends<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 7, |d| {
            let end = |v: Option<usize>| v.map_or(-1, |k| k as i64);
            let rows = d.edges.iter().map(|e| [end(e.from), end(e.to)]);
            Ok(int_rows(rows, d.edges.len()).into_pyarray(py).into_any())
        })
    }

    /// Every vertex's clearance: its distance to its generators (the field's value for
    /// sites under other metrics).
    #[getter]
    fn clearances<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let scene = self.scene.clone();
        self.cached(py, 8, |d| {
            let c = py.detach(|| d.clearances(&scene));
            Ok(Array1::from_vec(c).into_pyarray(py).into_any())
        })
    }

    /// The site of every cell (C).
    #[getter]
    fn cell_sites<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 9, |d| {
            let s: Vec<i64> = d.cells.iter().map(|c| c.site as i64).collect();
            Ok(Array1::from_vec(s).into_pyarray(py).into_any())
        })
    }

    /// The points of every cell ring, Q×2 (rings closed implicitly); ring `r`'s are
    /// rows `cell_ring_offsets[r]:cell_ring_offsets[r + 1]`.
    #[getter]
    fn cell_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 10, |d| {
            let rings = d.cells.iter().flat_map(|c| c.rings.iter());
            let n = rings.clone().map(Vec::len).sum();
            Ok(points_array(rings.flatten().copied(), n)
                .into_pyarray(py)
                .into_any())
        })
    }

    /// CSR offsets of the rings in `cell_points` (R + 1).
    #[getter]
    fn cell_ring_offsets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 11, |d| {
            Ok(
                offsets(d.cells.iter().flat_map(|c| c.rings.iter().map(Vec::len)))
                    .into_pyarray(py)
                    .into_any(),
            )
        })
    }

    /// CSR offsets of every cell's rings (C + 1): cell `k` has rings
    /// `cell_offsets[k]:cell_offsets[k + 1]`, the outer ring (counter-clockwise) first.
    #[getter]
    fn cell_offsets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cached(py, 12, |d| {
            Ok(offsets(d.cells.iter().map(|c| c.rings.len()))
                .into_pyarray(py)
                .into_any())
        })
    }

    /// The edges' polylines, one k×2 array each.
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let items = self
            .complex
            .edges
            .iter()
            .map(|e| points_array(e.points.iter().copied(), e.points.len()).into_pyarray(py));
        PyList::new(py, items)
    }

    /// The cells as `(site, [outer ring, holes...])`, each ring a k×2 array.
    #[getter]
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let mut out = Vec::with_capacity(self.complex.cells.len());
        for c in &self.complex.cells {
            let rings = PyList::new(
                py,
                c.rings
                    .iter()
                    .map(|r| points_array(r.iter().copied(), r.len()).into_pyarray(py)),
            )?;
            out.push((c.site, rings));
        }
        PyList::new(py, out)
    }

    /// Figures of the run (`engine`, `seconds`, ...).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.complex.stats)
    }

    /// The user ids of the scene's sites (None where a site has none).
    #[getter]
    fn site_ids(&self) -> Vec<Option<String>> {
        self.scene.sites().iter().map(|s| s.id.clone()).collect()
    }

    /// The scene the diagram was computed from.
    #[getter]
    fn scene(&self) -> crate::scene::PyScene {
        crate::scene::PyScene::from_scene((*self.scene).clone())
    }

    /// The diagram as JSON (`docs/SCENE_FORMAT.md`, "Diagram").
    fn to_json(&self, py: Python<'_>) -> String {
        py.detach(|| gvd::io::json::write_diagram(&self.complex))
    }

    /// The diagram as a GeoJSON FeatureCollection: vertices as Points (generators and
    /// clearance in their properties), edges as LineStrings, cells as Polygons.
    fn to_geojson(&self, py: Python<'_>) -> String {
        py.detach(|| gvd::io::geojson::write_diagram(&self.scene, &self.complex))
    }

    /// The diagram as WKT: a `MULTIPOINT` of the vertices, a `MULTILINESTRING` of the
    /// edges and a `MULTIPOLYGON` of the cells, one per line.
    fn to_wkt(&self, py: Python<'_>) -> String {
        py.detach(|| gvd::io::wkt::write_diagram(&self.complex))
    }

    /// The edges (the medial axis in `medial_axis` mode) as DXF `LINE` entities.
    fn to_dxf(&self, py: Python<'_>) -> String {
        py.detach(|| gvd::io::dxf::write_diagram(&self.complex))
    }

    /// The cells as shapely Polygons (with holes), in the order of `cell_sites`.
    fn shapely_cells<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        slf.py()
            .import("gvd.geometry")?
            .call_method1("cells", (slf,))
    }

    /// The edges as one shapely MultiLineString.
    fn shapely_edges<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        slf.py()
            .import("gvd.geometry")?
            .call_method1("edges", (slf,))
    }

    /// A picture of the sites and the diagram (SVG text, `width` pixels wide).
    #[pyo3(signature = (width=800.0))]
    fn to_svg(&self, py: Python<'_>, width: f64) -> String {
        let opts = gvd::io::svg::SvgOptions {
            width_px: width,
            ..Default::default()
        };
        py.detach(|| gvd::io::svg::render_svg(&self.scene, &self.complex, &opts))
    }

    /// The same picture as `to_svg`, as PNG: its bytes when `path` is None, else written
    /// to `path` all or none (a temporary file beside it, renamed over it; symbolic
    /// links, directories and read-only files are refused) and None returned.
    #[pyo3(signature = (path=None, width=800.0))]
    fn to_png<'py>(
        &self,
        py: Python<'py>,
        path: Option<std::path::PathBuf>,
        width: f64,
    ) -> PyResult<Option<Bound<'py, PyBytes>>> {
        let opts = gvd::io::svg::SvgOptions {
            width_px: width,
            ..Default::default()
        };
        let png = py
            .detach(|| gvd::io::png::render_png(&self.scene, &self.complex, &opts))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let Some(path) = path else {
            return Ok(Some(PyBytes::new(py, &png)));
        };
        py.detach(|| gvd::io::write_file(&path, &png))?;
        Ok(None)
    }

    /// Checks the diagram against its scene by brute force (independent of the
    /// engines); see `gvd.verify`.
    #[pyo3(signature = (grid=512, slack=1.0))]
    fn verify(&self, py: Python<'_>, grid: usize, slack: f64) -> PyResult<PyReport> {
        crate::report::verify(py, &self.scene, &self.complex, grid, slack)
    }

    /// Offset curves at `distance` from the sites, from this diagram (which must be in
    /// `complex` or `medial_axis` mode unless the scene has points only); see
    /// `gvd.offset`.
    fn offset(&self, py: Python<'_>, distance: f64) -> PyResult<PyOffset> {
        let off = py
            .detach(|| gvd::offset(&self.scene, &self.complex, distance))
            .map_err(to_py)?;
        Ok(PyOffset::new(self.scene.clone(), off))
    }

    /// Draws the diagram with matplotlib into `ax` (a new figure's axes when None);
    /// returns the axes. Keyword arguments go to `gvd.plot.plot_diagram`.
    #[pyo3(signature = (ax=None, **kwargs))]
    fn plot<'py>(
        slf: &Bound<'py, Self>,
        ax: Option<Bound<'py, PyAny>>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        py.import("gvd.plot")?
            .getattr("plot_diagram")?
            .call((slf, ax), kwargs)
    }

    fn __repr__(&self) -> String {
        let engine = self
            .complex
            .stats
            .get("engine")
            .and_then(|v| v.as_str())
            .unwrap_or("?");
        format!(
            "Diagram({} vertices, {} edges, {} cells, mode='{}', engine='{}')",
            self.complex.vertices.len(),
            self.complex.edges.len(),
            self.complex.cells.len(),
            crate::scene::mode_name(self.scene.mode()),
            engine
        )
    }
}
