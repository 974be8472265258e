//! `gvd.Scene`: a scene built site by site through the library's [`SceneBuilder`] (so
//! every check and message is the library's), or read from a file.

use crate::errors::{scene_error, site_error, to_py};
use crate::read::{format_of, read};
use gvd::io::{Format, LocalProjection};
use gvd::{Aabb, Metric, Mode, Point, Scene, SceneBuilder, Site};
use numpy::{AllowTypeChange, PyArrayLike2};
use pyo3::prelude::*;
use std::sync::Arc;

/// The mode named `name` (`voronoi`, `complex`, `medial_axis`).
pub fn parse_mode(name: &str) -> PyResult<Mode> {
    match name {
        "voronoi" => Ok(Mode::Voronoi),
        "complex" => Ok(Mode::Complex),
        "medial_axis" => Ok(Mode::MedialAxis),
        other => Err(scene_error(
            "mode",
            format!("unknown mode '{other}' (known: voronoi, complex, medial_axis)"),
        )),
    }
}

/// The format's name of `mode`.
pub fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Voronoi => "voronoi",
        Mode::Complex => "complex",
        Mode::MedialAxis => "medial_axis",
    }
}

/// A box `[xmin, ymin, xmax, ymax]` from any sequence of four numbers.
pub fn extract_box(obj: &Bound<'_, PyAny>, on_error: impl Fn(String) -> PyErr) -> PyResult<Aabb> {
    obj.extract::<[f64; 4]>()
        .map(Aabb::from_array)
        .map_err(|_| on_error("expected [xmin, ymin, xmax, ymax]".into()))
}

/// A scene: sites in a domain, with a resolution and a mode.
///
/// Sites are checked as they are added (the same checks and messages as JSON input);
/// the checks between sites (duplicates, overlaps) run when the scene is computed or
/// built. Refusals raise `gvd.SceneError` with the site index and field. A scene read
/// with `project="local"` is in metres about the data's centre; sites added to it are
/// too, and its diagrams' GeoJSON comes back in longitude and latitude.
#[pyclass(name = "Scene", module = "gvd")]
pub struct PyScene {
    domain: Aabb,
    epsilon: Option<f64>,
    mode: Mode,
    /// The projection a reader took longitudes and latitudes through; the scene keeps
    /// it when sites are added (their coordinates are the projected metres).
    projection: Option<LocalProjection>,
    /// The sites added so far (`None` after a reader built the scene, until a site is
    /// added to it).
    builder: Option<SceneBuilder>,
    /// The validated scene, once built and until a site is added.
    built: Option<Arc<Scene>>,
}

impl PyScene {
    /// A wrapper of a scene a reader built.
    pub fn from_scene(scene: Scene) -> PyScene {
        PyScene {
            domain: scene.domain(),
            epsilon: Some(scene.epsilon()),
            mode: scene.mode(),
            projection: scene.projection().copied(),
            builder: None,
            built: Some(Arc::new(scene)),
        }
    }

    /// The validated scene (built and kept until the next site is added).
    pub fn scene(&mut self) -> PyResult<Arc<Scene>> {
        if let Some(s) = &self.built {
            return Ok(s.clone());
        }
        let builder = self.builder()?.clone();
        let scene = builder
            .build()
            .map_err(to_py)?
            .with_projection(self.projection);
        let scene = Arc::new(scene);
        self.built = Some(scene.clone());
        Ok(scene)
    }

    fn new_builder(&self) -> PyResult<SceneBuilder> {
        let mut b = SceneBuilder::new(self.domain)
            .map_err(to_py)?
            .mode(self.mode);
        if let Some(e) = self.epsilon {
            b = b.epsilon(e).map_err(to_py)?;
        }
        Ok(b)
    }

    fn builder(&mut self) -> PyResult<&mut SceneBuilder> {
        let b = match self.builder.take() {
            Some(b) => b,
            None => {
                let mut b = self.new_builder()?;
                if let Some(scene) = &self.built {
                    for site in scene.sites() {
                        b.add(site.clone()).map_err(to_py)?;
                    }
                }
                b
            }
        };
        Ok(self.builder.insert(b))
    }

    /// Checks and appends `site`; a [`gvd::Error::Scene`] of a constructor (an equation
    /// that does not parse) becomes the error of this site.
    fn push(&mut self, site: Result<Site, gvd::Error>, id: Option<String>) -> PyResult<usize> {
        let index = self.next_index()?;
        let site = site.map_err(|e| match e {
            gvd::Error::Scene { field, message } => site_error(index, &field, message),
            other => to_py(other),
        })?;
        let site = match id {
            Some(id) => site.with_id(id),
            None => site,
        };
        let i = self.builder()?.add(site).map_err(to_py)?;
        self.built = None;
        Ok(i)
    }

    fn next_index(&mut self) -> PyResult<usize> {
        Ok(self.builder()?.len())
    }

    /// Points `[[x, y], ...]` (any array-like of shape (n, 2)) of the next site's `field`.
    fn points(&mut self, obj: &Bound<'_, PyAny>, field: &str) -> PyResult<Vec<Point>> {
        let index = self.next_index()?;
        points(obj).map_err(|m| site_error(index, field, m))
    }

    fn point(&mut self, obj: &Bound<'_, PyAny>, field: &str) -> PyResult<Point> {
        let index = self.next_index()?;
        obj.extract::<[f64; 2]>()
            .map(Point::from)
            .map_err(|_| site_error(index, field, "expected a point [x, y]"))
    }
}

/// The rows of an (n, 2) array-like as points.
fn points(obj: &Bound<'_, PyAny>) -> Result<Vec<Point>, String> {
    let arr: PyArrayLike2<'_, f64, AllowTypeChange> = obj
        .extract()
        .map_err(|_| "expected a list of points [[x, y], ...]".to_string())?;
    let view = arr.as_array();
    if view.ncols() != 2 {
        return Err(format!(
            "expected points [x, y], found an array of shape ({}, {})",
            view.nrows(),
            view.ncols()
        ));
    }
    Ok(view
        .rows()
        .into_iter()
        .map(|r| Point::new(r[0], r[1]))
        .collect())
}

#[pymethods]
impl PyScene {
    /// A scene over `domain` `[xmin, ymin, xmax, ymax]` with resolution `epsilon`
    /// (default: 1e-3 of the domain's longest side) in `mode` (`"voronoi"`,
    /// `"complex"` or `"medial_axis"`).
    #[new]
    #[pyo3(signature = (domain, epsilon=None, mode="voronoi"))]
    fn new(domain: &Bound<'_, PyAny>, epsilon: Option<f64>, mode: &str) -> PyResult<PyScene> {
        let domain = extract_box(domain, |m| scene_error("domain", m))?;
        let mut s = PyScene {
            domain,
            epsilon,
            mode: parse_mode(mode)?,
            projection: None,
            builder: None,
            built: None,
        };
        s.builder = Some(s.new_builder()?);
        Ok(s)
    }

    /// Parses and validates a scene from JSON text (`docs/SCENE_FORMAT.md`); unknown
    /// fields are warned about (`UserWarning`) and ignored.
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str) -> PyResult<PyScene> {
        read(py, text.as_bytes(), Format::Json, None, None, None, None)
    }

    /// Reads a scene file: the format from `format` (`json`, `geojson`, `wkt`, `dxf`, `svg`) or
    /// the extension. `domain`, `epsilon` and `mode` override the file's; formats
    /// without a domain get the sites' bounding box grown by a tenth of its longest
    /// side. `project="local"` takes GeoJSON coordinates as longitude and latitude in
    /// degrees, projected to metres about the data's centre (azimuthal equidistant); the
    /// diagram's GeoJSON comes back in longitude and latitude. Reader warnings (DXF
    /// entities not read) are `UserWarning`s.
    #[staticmethod]
    #[pyo3(signature = (path, format=None, *, domain=None, epsilon=None, mode=None, project=None))]
    fn read(
        py: Python<'_>,
        path: std::path::PathBuf,
        format: Option<&str>,
        domain: Option<&Bound<'_, PyAny>>,
        epsilon: Option<f64>,
        mode: Option<&str>,
        project: Option<&str>,
    ) -> PyResult<PyScene> {
        let format = format_of(format, Some(&path))?;
        let data = std::fs::read(&path).map_err(|e| {
            pyo3::exceptions::PyOSError::new_err(format!("cannot read {}: {e}", path.display()))
        })?;
        read(py, &data, format, domain, epsilon, mode, project)
    }

    /// Reads a scene from GeoJSON text (Point, MultiPoint → points; LineString →
    /// polylines; Polygon, MultiPolygon → polygons with holes); `project` as for `read`.
    #[staticmethod]
    #[pyo3(signature = (text, *, domain=None, epsilon=None, mode=None, project=None))]
    fn from_geojson(
        py: Python<'_>,
        text: &str,
        domain: Option<&Bound<'_, PyAny>>,
        epsilon: Option<f64>,
        mode: Option<&str>,
        project: Option<&str>,
    ) -> PyResult<PyScene> {
        read(
            py,
            text.as_bytes(),
            Format::GeoJson,
            domain,
            epsilon,
            mode,
            project,
        )
    }

    /// Reads a scene from WKT text (one geometry per line).
    #[staticmethod]
    #[pyo3(signature = (text, *, domain=None, epsilon=None, mode=None))]
    fn from_wkt(
        py: Python<'_>,
        text: &str,
        domain: Option<&Bound<'_, PyAny>>,
        epsilon: Option<f64>,
        mode: Option<&str>,
    ) -> PyResult<PyScene> {
        read(
            py,
            text.as_bytes(),
            Format::Wkt,
            domain,
            epsilon,
            mode,
            None,
        )
    }

    /// Reads a scene from ASCII DXF (LINE, ARC, CIRCLE, POINT, LWPOLYLINE, POLYLINE).
    #[staticmethod]
    #[pyo3(signature = (data, *, domain=None, epsilon=None, mode=None))]
    fn from_dxf(
        py: Python<'_>,
        data: &[u8],
        domain: Option<&Bound<'_, PyAny>>,
        epsilon: Option<f64>,
        mode: Option<&str>,
    ) -> PyResult<PyScene> {
        read(py, data, Format::Dxf, domain, epsilon, mode, None)
    }

    /// A scene from a shapely geometry (or anything with `__geo_interface__`: points,
    /// line strings, polygons with holes, their multi-parts and collections), read as
    /// GeoJSON.
    #[staticmethod]
    #[pyo3(signature = (geometry, *, domain=None, epsilon=None, mode=None))]
    fn from_shapely(
        py: Python<'_>,
        geometry: &Bound<'_, PyAny>,
        domain: Option<&Bound<'_, PyAny>>,
        epsilon: Option<f64>,
        mode: Option<&str>,
    ) -> PyResult<PyScene> {
        let gi = geometry.getattr("__geo_interface__")?;
        let text: String = py.import("json")?.call_method1("dumps", (gi,))?.extract()?;
        read(
            py,
            text.as_bytes(),
            Format::GeoJson,
            domain,
            epsilon,
            mode,
            None,
        )
    }

    /// The scene as JSON text (`docs/SCENE_FORMAT.md`), which `Scene.from_json` reads
    /// back; runs the checks between sites first.
    // the Python method's name; `&mut` because the scene is built on first use
    #[allow(clippy::wrong_self_convention)]
    fn to_json(&mut self, py: Python<'_>) -> PyResult<String> {
        let scene = self.scene()?;
        Ok(py.detach(|| gvd::io::json::write_scene(&scene)))
    }

    /// The domain `(xmin, ymin, xmax, ymax)`.
    #[getter]
    fn domain(&self) -> (f64, f64, f64, f64) {
        let a = self.domain.to_array();
        (a[0], a[1], a[2], a[3])
    }

    /// The resolution: every output curve is within `epsilon` of the true one.
    #[getter]
    fn epsilon(&self) -> f64 {
        self.epsilon
            .unwrap_or_else(|| Scene::default_epsilon(&self.domain))
    }

    /// `"voronoi"`, `"complex"` or `"medial_axis"`.
    #[getter]
    fn mode(&self) -> &'static str {
        mode_name(self.mode)
    }

    /// The same sites in another mode (a new scene).
    fn with_mode(&mut self, mode: &str) -> PyResult<PyScene> {
        let scene = self.scene()?;
        Ok(PyScene::from_scene(
            (*scene).clone().with_mode(parse_mode(mode)?),
        ))
    }

    /// Runs the checks between sites now (duplicates, overlaps, precision) and returns
    /// the scene, instead of at the first computation.
    fn validate(mut slf: PyRefMut<'_, Self>) -> PyResult<PyRefMut<'_, Self>> {
        slf.scene()?;
        Ok(slf)
    }

    /// The kind name of each site, in order.
    fn kinds(&mut self) -> PyResult<Vec<&'static str>> {
        let scene = self.scene()?;
        Ok(scene.sites().iter().map(|s| s.kind.name()).collect())
    }

    fn __len__(&self) -> usize {
        match (&self.built, &self.builder) {
            (_, Some(b)) => b.len(),
            (Some(s), None) => s.sites().len(),
            (None, None) => 0,
        }
    }

    fn __repr__(&self) -> PyResult<String> {
        let d = self.domain.to_array();
        Ok(format!(
            "Scene(domain=[{}, {}, {}, {}], epsilon={}, mode='{}', {} sites)",
            d[0],
            d[1],
            d[2],
            d[3],
            self.epsilon(),
            self.mode(),
            self.__len__()
        ))
    }

    /// Adds a point; returns its index. `metric`: `"euclidean"` (default), `"lp"`
    /// (with even `p` ≥ 2), `"anisotropic"` (`matrix` [[a, b], [b, c]] positive-definite,
    /// `weight`), `"power"` (`weight`) or `"moebius"` (`scale` > 0, `weight`).
    #[pyo3(signature = (at, metric="euclidean", *, p=None, matrix=None, weight=None, scale=None, id=None))]
    #[allow(clippy::too_many_arguments)]
    fn add_point(
        &mut self,
        at: &Bound<'_, PyAny>,
        metric: &str,
        p: Option<i64>,
        matrix: Option<[[f64; 2]; 2]>,
        weight: Option<f64>,
        scale: Option<f64>,
        id: Option<String>,
    ) -> PyResult<usize> {
        let at = self.point(at, "at")?;
        let index = self.next_index()?;
        let missing = |f: &str| site_error(index, &format!("metric.{f}"), "missing required field");
        let metric = match metric {
            "euclidean" => Metric::Euclidean,
            "lp" => {
                let p = p.ok_or_else(|| missing("p"))?;
                let p = u32::try_from(p).map_err(|_| {
                    site_error(
                        index,
                        "metric.p",
                        format!("p must be an even integer >= 2, found {p}"),
                    )
                })?;
                Metric::Lp { p }
            }
            "anisotropic" => Metric::Anisotropic {
                matrix: matrix.ok_or_else(|| missing("matrix"))?,
                weight: weight.unwrap_or(0.0),
            },
            "power" => Metric::Power {
                weight: weight.unwrap_or(0.0),
            },
            "moebius" => Metric::Moebius {
                scale: scale.ok_or_else(|| missing("scale"))?,
                weight: weight.unwrap_or(0.0),
            },
            other => {
                return Err(site_error(
                    index,
                    "metric.kind",
                    format!(
                    "unknown metric '{other}' (known: euclidean, lp, anisotropic, power, moebius)"
                ),
                ))
            }
        };
        self.push(Ok(Site::point_with(at, metric)), id)
    }

    /// Adds many Euclidean points (an (n, 2) array-like); returns the index of the first.
    fn add_points(&mut self, points: &Bound<'_, PyAny>) -> PyResult<usize> {
        let first = self.next_index()?;
        for q in self.points(points, "at")? {
            self.push(Ok(Site::point(q)), None)?;
        }
        Ok(first)
    }

    /// Adds a circle (an Apollonius site: distance `|q − center| − radius`).
    #[pyo3(signature = (center, radius, *, id=None))]
    fn add_circle(
        &mut self,
        center: &Bound<'_, PyAny>,
        radius: f64,
        id: Option<String>,
    ) -> PyResult<usize> {
        let center = self.point(center, "center")?;
        self.push(Ok(Site::circle(center, radius)), id)
    }

    /// Adds an ellipse with semi-axes `(a, b)` turned by `rotation` radians.
    #[pyo3(signature = (center, semi_axes, rotation=0.0, *, id=None))]
    fn add_ellipse(
        &mut self,
        center: &Bound<'_, PyAny>,
        semi_axes: &Bound<'_, PyAny>,
        rotation: f64,
        id: Option<String>,
    ) -> PyResult<usize> {
        let center = self.point(center, "center")?;
        let axes = self.point(semi_axes, "semi_axes")?;
        self.push(Ok(Site::ellipse(center, [axes.x, axes.y], rotation)), id)
    }

    /// Adds the closed segment from `a` to `b`.
    #[pyo3(signature = (a, b, *, id=None))]
    fn add_segment(
        &mut self,
        a: &Bound<'_, PyAny>,
        b: &Bound<'_, PyAny>,
        id: Option<String>,
    ) -> PyResult<usize> {
        let from = self.point(a, "from")?;
        let to = self.point(b, "to")?;
        self.push(Ok(Site::segment(from, to)), id)
    }

    /// Adds the arc of the circle `(center, radius)` counter-clockwise from
    /// `start_angle` to `end_angle` (radians; a whole turn is the full circle).
    #[pyo3(signature = (center, radius, start_angle, end_angle, *, id=None))]
    fn add_arc(
        &mut self,
        center: &Bound<'_, PyAny>,
        radius: f64,
        start_angle: f64,
        end_angle: f64,
        id: Option<String>,
    ) -> PyResult<usize> {
        let center = self.point(center, "center")?;
        self.push(Ok(Site::arc(center, radius, start_angle, end_angle)), id)
    }

    /// Adds the open chain through `points` (an (n, 2) array-like, n ≥ 2).
    #[pyo3(signature = (points, *, id=None))]
    fn add_polyline(&mut self, points: &Bound<'_, PyAny>, id: Option<String>) -> PyResult<usize> {
        let points = self.points(points, "points")?;
        self.push(Ok(Site::polyline(points)), id)
    }

    /// Adds a polygon: `rings` is the outer ring, then the holes, each an (n, 2)
    /// array-like closed implicitly (a repeated first point is refused by the checks).
    #[pyo3(signature = (rings, *, id=None))]
    fn add_polygon(&mut self, rings: &Bound<'_, PyAny>, id: Option<String>) -> PyResult<usize> {
        let index = self.next_index()?;
        let list: Vec<Bound<'_, PyAny>> = rings
            .try_iter()
            .and_then(|it| it.collect())
            .map_err(|_| site_error(index, "rings", "expected a list of rings"))?;
        let mut out = Vec::with_capacity(list.len());
        for (k, ring) in list.iter().enumerate() {
            out.push(self.points(ring, &format!("rings[{k}]"))?);
        }
        self.push(Ok(Site::polygon(out)), id)
    }

    /// Adds the algebraic curve `{f = 0} ∩ clip` of the polynomial `equation` in `x`, `y`
    /// (text, e.g. `"x^2 + y^2 - 1"`); `clip` defaults to the domain.
    #[pyo3(signature = (equation, clip=None, *, id=None))]
    fn add_algebraic(
        &mut self,
        equation: &str,
        clip: Option<&Bound<'_, PyAny>>,
        id: Option<String>,
    ) -> PyResult<usize> {
        let index = self.next_index()?;
        let clip = clip
            .map(|c| extract_box(c, |m| site_error(index, "clip", m)))
            .transpose()?;
        self.push(Site::algebraic(equation, clip), id)
    }

    /// Adds a Bézier curve (rational with `weights`, one per control point, > 0).
    #[pyo3(signature = (control_points, weights=None, *, id=None))]
    fn add_bezier(
        &mut self,
        control_points: &Bound<'_, PyAny>,
        weights: Option<Vec<f64>>,
        id: Option<String>,
    ) -> PyResult<usize> {
        let cps = self.points(control_points, "control_points")?;
        self.push(Ok(Site::bezier(cps, weights)), id)
    }

    /// Adds a B-spline (NURBS with `weights`) of `degree` over `knots`.
    #[pyo3(signature = (degree, control_points, knots, weights=None, closed=false, *, id=None))]
    fn add_bspline(
        &mut self,
        degree: usize,
        control_points: &Bound<'_, PyAny>,
        knots: Vec<f64>,
        weights: Option<Vec<f64>>,
        closed: bool,
        id: Option<String>,
    ) -> PyResult<usize> {
        let cps = self.points(control_points, "control_points")?;
        self.push(Ok(Site::bspline(degree, cps, knots, weights, closed)), id)
    }

    /// Adds an explicit polynomial distance field `f(x, y)` (text).
    #[pyo3(signature = (equation, *, id=None))]
    fn add_field(&mut self, equation: &str, id: Option<String>) -> PyResult<usize> {
        self.push(Site::field(equation), id)
    }

    /// Adds the implicit distance field of `g(x, y, z)` (text): its smallest
    /// non-negative root `z`.
    #[pyo3(signature = (equation, *, id=None))]
    fn add_implicit_field(&mut self, equation: &str, id: Option<String>) -> PyResult<usize> {
        self.push(Site::implicit_field(equation), id)
    }
}
