//! The scene model: validated sites in a domain.
//!
//! A [`Scene`] can only be built through [`Scene::new`] or a [`SceneBuilder`], which run
//! the same checks whatever the source (code, JSON, the other readers), so every
//! refusal is the same [`Error`] naming the site index and the field. JSON decoding
//! (`parse.rs`) is a thin reader on top.

mod check;
mod curve_contacts;
mod parse;
mod polygon_overlap;
mod scale;
mod unknown;
mod validate;

use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::num::poly::Poly;

/// What the diagram separates (see `docs/SCENE_FORMAT.md`, `mode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Mode {
    /// The Voronoi diagram of the sites.
    #[default]
    Voronoi,
    /// The Voronoi complex: corners and edges of polygonal sites are separate features.
    Complex,
    /// The medial axis: the complex inside the regions bounded by closed sites.
    MedialAxis,
}

impl Mode {
    /// The `mode` string of the format.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Voronoi => "voronoi",
            Mode::Complex => "complex",
            Mode::MedialAxis => "medial_axis",
        }
    }
}

/// The distance field of a point site (`docs/SCENE_FORMAT.md`, point metrics;
/// (EMM13) §1.1).
#[derive(Clone, Debug, PartialEq)]
pub enum Metric {
    /// `|q − p|`
    Euclidean,
    /// `(x − px)^p + (y − py)^p`, `p` even ≥ 2
    Lp {
        /// The exponent, even and ≥ 2.
        p: u32,
    },
    /// `(q − p)ᵀ M (q − p) − w`, `M` symmetric positive-definite
    Anisotropic {
        /// The matrix `M`.
        matrix: [[f64; 2]; 2],
        /// The weight `w`.
        weight: f64,
    },
    /// `|q − p|² − w²`
    Power {
        /// The weight `w`.
        weight: f64,
    },
    /// `v |q − p|² − w`, `v > 0`
    Moebius {
        /// The scale `v`.
        scale: f64,
        /// The weight `w`.
        weight: f64,
    },
}

/// An equation as the user wrote it, with its parsed polynomial.
#[derive(Clone, Debug, PartialEq)]
pub struct Equation {
    text: String,
    poly: Poly,
}

impl Equation {
    /// Parses `text` as a polynomial in `vars` (`['x', 'y']`, or `['x', 'y', 'z']` for an
    /// implicit field); the error says where it does not parse.
    pub fn parse(text: &str, vars: &[char]) -> Result<Equation, String> {
        let poly = Poly::parse(text, vars).map_err(|e| format!("does not parse: {e}"))?;
        Ok(Equation {
            text: text.to_string(),
            poly,
        })
    }
    /// The text as given.
    pub fn text(&self) -> &str {
        &self.text
    }
    /// The parsed polynomial.
    pub fn poly(&self) -> &Poly {
        &self.poly
    }
}

/// A site's kind and data, as in `docs/SCENE_FORMAT.md` (checked when added to a
/// [`Scene`]).
#[derive(Clone, Debug, PartialEq)]
pub enum SiteKind {
    /// A point under a metric.
    Point {
        /// Where the point is.
        at: Point,
        /// Its distance field.
        metric: Metric,
    },
    /// A circle (Apollonius site): distance `|q − center| − radius`.
    Circle {
        /// The centre.
        center: Point,
        /// The radius, ≥ 0.
        radius: f64,
    },
    /// An ellipse: Euclidean distance to the curve, outside.
    Ellipse {
        /// The centre.
        center: Point,
        /// The semi-axes `[a, b]`, > 0.
        semi_axes: [f64; 2],
        /// The angle of the first axis, in radians.
        rotation: f64,
    },
    /// A closed segment.
    Segment {
        /// The first end.
        from: Point,
        /// The last end.
        to: Point,
    },
    /// A circular arc, counter-clockwise from `start_angle` to `end_angle`.
    Arc {
        /// The circle's centre.
        center: Point,
        /// The circle's radius, > 0.
        radius: f64,
        /// The first end's angle (radians).
        start_angle: f64,
        /// The last end's angle (radians; a whole turn from the start is a full circle).
        end_angle: f64,
    },
    /// An open chain of segments.
    Polyline {
        /// Its points (≥ 2, consecutive ones distinct).
        points: Vec<Point>,
    },
    /// A polygon with holes.
    Polygon {
        /// The outer ring, then the holes; each closed implicitly.
        rings: Vec<Vec<Point>>,
    },
    /// The algebraic curve `{f = 0} ∩ clip`.
    Algebraic {
        /// `f(x, y)`.
        equation: Equation,
        /// The clip box (default: the domain).
        clip: Option<Aabb>,
    },
    /// A (rational) Bézier curve.
    Bezier {
        /// Its control points (≥ 2, not all equal).
        control_points: Vec<Point>,
        /// Its weights (one per control point, > 0); `None`: polynomial.
        weights: Option<Vec<f64>>,
    },
    /// A B-spline or NURBS curve.
    Bspline {
        /// Its degree, ≥ 1.
        degree: usize,
        /// Its control points (more than `degree`).
        control_points: Vec<Point>,
        /// Its knots (control points + degree + 1, non-decreasing).
        knots: Vec<f64>,
        /// Its weights (NURBS); `None`: polynomial.
        weights: Option<Vec<f64>>,
        /// Whether the curve is closed (and bounds a region).
        closed: bool,
    },
    /// An explicit polynomial distance field in `x`, `y`.
    Field {
        /// The field `f(x, y)`.
        equation: Equation,
    },
    /// The smallest non-negative root `z` of `g(x, y, z)`.
    ImplicitField {
        /// `g(x, y, z)`.
        equation: Equation,
    },
}

impl SiteKind {
    /// The `kind` string of the format.
    pub fn name(&self) -> &'static str {
        match self {
            SiteKind::Point { .. } => "point",
            SiteKind::Circle { .. } => "circle",
            SiteKind::Ellipse { .. } => "ellipse",
            SiteKind::Segment { .. } => "segment",
            SiteKind::Arc { .. } => "arc",
            SiteKind::Polyline { .. } => "polyline",
            SiteKind::Polygon { .. } => "polygon",
            SiteKind::Algebraic { .. } => "algebraic",
            SiteKind::Bezier { .. } => "bezier",
            SiteKind::Bspline { .. } => "bspline",
            SiteKind::Field { .. } => "field",
            SiteKind::ImplicitField { .. } => "implicit_field",
        }
    }
}

/// A site: its kind with its data, and the optional user id echoed in outputs. Building
/// one checks nothing; a [`Scene`] checks its sites.
#[derive(Clone, Debug, PartialEq)]
pub struct Site {
    /// The user's id, echoed in outputs.
    pub id: Option<String>,
    /// The kind and its data.
    pub kind: SiteKind,
}

impl Site {
    /// A site of `kind` without an id.
    pub fn new(kind: SiteKind) -> Site {
        Site { id: None, kind }
    }
    /// The same site with the user id `id`.
    pub fn with_id(mut self, id: impl Into<String>) -> Site {
        self.id = Some(id.into());
        self
    }
    /// A Euclidean point.
    pub fn point(at: impl Into<Point>) -> Site {
        Site::point_with(at, Metric::Euclidean)
    }
    /// A point under `metric`.
    pub fn point_with(at: impl Into<Point>, metric: Metric) -> Site {
        Site::new(SiteKind::Point {
            at: at.into(),
            metric,
        })
    }
    /// A circle (an Apollonius site when `radius > 0`).
    pub fn circle(center: impl Into<Point>, radius: f64) -> Site {
        Site::new(SiteKind::Circle {
            center: center.into(),
            radius,
        })
    }
    /// An ellipse with semi-axes `[a, b]` turned by `rotation` radians.
    pub fn ellipse(center: impl Into<Point>, semi_axes: [f64; 2], rotation: f64) -> Site {
        Site::new(SiteKind::Ellipse {
            center: center.into(),
            semi_axes,
            rotation,
        })
    }
    /// The closed segment from `from` to `to`.
    pub fn segment(from: impl Into<Point>, to: impl Into<Point>) -> Site {
        Site::new(SiteKind::Segment {
            from: from.into(),
            to: to.into(),
        })
    }
    /// The arc of the circle `(center, radius)` counter-clockwise from `start_angle` to
    /// `end_angle` (radians; a whole turn is the full circle, see [`crate::geom::arc`]).
    pub fn arc(center: impl Into<Point>, radius: f64, start_angle: f64, end_angle: f64) -> Site {
        Site::new(SiteKind::Arc {
            center: center.into(),
            radius,
            start_angle,
            end_angle,
        })
    }
    /// The open chain through `points`.
    pub fn polyline<P: Into<Point>>(points: impl IntoIterator<Item = P>) -> Site {
        Site::new(SiteKind::Polyline {
            points: points.into_iter().map(Into::into).collect(),
        })
    }
    /// A polygon: the outer ring first, then its holes (each ring closed implicitly).
    pub fn polygon<P: Into<Point>, R: IntoIterator<Item = P>>(
        rings: impl IntoIterator<Item = R>,
    ) -> Site {
        Site::new(SiteKind::Polygon {
            rings: rings
                .into_iter()
                .map(|r| r.into_iter().map(Into::into).collect())
                .collect(),
        })
    }
    /// The curve `{f = 0} ∩ clip` of the polynomial `equation` in `x`, `y`.
    pub fn algebraic(equation: &str, clip: Option<Aabb>) -> Result<Site, Error> {
        let equation =
            Equation::parse(equation, &['x', 'y']).map_err(|m| Error::scene("equation", m))?;
        Ok(Site::new(SiteKind::Algebraic { equation, clip }))
    }
    /// A (rational, with `weights`) Bézier curve.
    pub fn bezier<P: Into<Point>>(
        control_points: impl IntoIterator<Item = P>,
        weights: Option<Vec<f64>>,
    ) -> Site {
        Site::new(SiteKind::Bezier {
            control_points: control_points.into_iter().map(Into::into).collect(),
            weights,
        })
    }
    /// A B-spline (NURBS with `weights`) of `degree` over `knots`.
    pub fn bspline<P: Into<Point>>(
        degree: usize,
        control_points: impl IntoIterator<Item = P>,
        knots: Vec<f64>,
        weights: Option<Vec<f64>>,
        closed: bool,
    ) -> Site {
        Site::new(SiteKind::Bspline {
            degree,
            control_points: control_points.into_iter().map(Into::into).collect(),
            knots,
            weights,
            closed,
        })
    }
    /// An explicit polynomial distance field in `x`, `y`.
    pub fn field(equation: &str) -> Result<Site, Error> {
        let equation =
            Equation::parse(equation, &['x', 'y']).map_err(|m| Error::scene("equation", m))?;
        Ok(Site::new(SiteKind::Field { equation }))
    }
    /// The implicit distance field of `g(x, y, z)`: its smallest non-negative root `z`.
    pub fn implicit_field(equation: &str) -> Result<Site, Error> {
        let equation =
            Equation::parse(equation, &['x', 'y', 'z']).map_err(|m| Error::scene("equation", m))?;
        Ok(Site::new(SiteKind::ImplicitField { equation }))
    }
}

/// A validated scene: sites in a domain, with the resolution `epsilon` and the mode.
/// Its fields are read through accessors; it is built by [`Scene::new`], a
/// [`SceneBuilder`] or a reader ([`Scene::from_json`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    domain: Aabb,
    epsilon: f64,
    mode: Mode,
    sites: Vec<Site>,
    projection: Option<crate::io::LocalProjection>,
}

impl Scene {
    /// Refuses a segment site identical to an earlier one, as the scene refuses other
    /// repeated sites: for the engines that do not merge repeated segments (the
    /// segment engine does).
    pub(crate) fn refuse_repeated_segments(&self) -> Result<(), Error> {
        validate::duplicate_site(&self.sites, true)
    }

    /// Refuses Euclidean point sites too close for the subdivision's fields, as the
    /// scene refuses such points of the other metrics: for the subdivision engine (the
    /// exact engine separates them).
    pub(crate) fn refuse_near_coincident_points(&self) -> Result<(), Error> {
        validate::near_coincident_sites(&self.domain, self.epsilon, &self.sites, true)
    }

    /// Refuses a point site inside a polygon site in the modes where polygons are solid
    /// (checked per run: the mode may change after the scene is built).
    pub(crate) fn refuse_points_inside_polygons(&self) -> Result<(), Error> {
        polygon_overlap::points_inside_polygons(&self.sites, self.mode)
    }

    /// Refuses a site reaching strictly inside a polygon site, seen at `samples(i)`,
    /// points along site `i`: for the engines that take a polygon by its boundary.
    pub(crate) fn refuse_sites_inside_polygons(
        &self,
        samples: impl Fn(usize) -> Vec<Point>,
    ) -> Result<(), Error> {
        polygon_overlap::sites_inside_polygons(&self.sites, samples)
    }

    /// Refuses free-form curves that cross or touch other than end to end in the modes
    /// where they bound regions (checked per run: the mode may change after the scene
    /// is built).
    pub(crate) fn refuse_crossing_curves(&self) -> Result<(), Error> {
        curve_contacts::crossing_curves(&self.domain, self.mode, &self.sites)
    }

    /// True when some free-form curves cross or touch other than end to end (or may).
    pub(crate) fn curves_meet(&self) -> bool {
        curve_contacts::curves_meet(&self.domain, &self.sites)
    }

    /// Checks and builds a scene. Refusals name the field (`domain`, `epsilon`) or the
    /// site index and its field, as for JSON input.
    pub fn new(domain: Aabb, epsilon: f64, mode: Mode, sites: Vec<Site>) -> Result<Scene, Error> {
        let mut b = SceneBuilder::new(domain)?.epsilon(epsilon)?.mode(mode);
        for site in sites {
            b.add(site)?;
        }
        b.build()
    }

    /// The default resolution of a domain: 10⁻³ of its longest side.
    pub fn default_epsilon(domain: &Aabb) -> f64 {
        1e-3 * domain.longest_side()
    }

    /// Parses and validates a scene from JSON text.
    pub fn from_json(text: &str) -> Result<Scene, Error> {
        parse::scene_from_json(text)
    }

    /// Parses and validates a scene from a JSON value.
    pub fn from_value(value: &serde_json::Value) -> Result<Scene, Error> {
        parse::scene_from_value(value)
    }

    /// The domain the diagram is computed in.
    pub fn domain(&self) -> Aabb {
        self.domain
    }
    /// The resolution: edges are polylines within `epsilon` of the true bisectors.
    pub fn epsilon(&self) -> f64 {
        self.epsilon
    }
    /// What the diagram separates.
    pub fn mode(&self) -> Mode {
        self.mode
    }
    /// The sites, in input order (outputs name them by index).
    pub fn sites(&self) -> &[Site] {
        &self.sites
    }
    /// The sites, for the engines' exact rewrites of a scene (a nearly round ellipse as
    /// its circle); whatever they write must pass the site checks.
    pub(crate) fn sites_mut(&mut self) -> &mut [Site] {
        &mut self.sites
    }
    /// The same scene in another mode (every mode accepts the same sites).
    pub fn with_mode(mut self, mode: Mode) -> Scene {
        self.mode = mode;
        self
    }
    /// The projection that took the scene's longitudes and latitudes to its planar
    /// coordinates (metres), when it was read so; the GeoJSON writers project back.
    pub fn projection(&self) -> Option<&crate::io::LocalProjection> {
        self.projection.as_ref()
    }
    /// The same scene, its coordinates declared the image of longitudes and latitudes
    /// under `projection` (or planar, for `None`).
    pub fn with_projection(mut self, projection: Option<crate::io::LocalProjection>) -> Scene {
        self.projection = projection;
        self
    }
}

/// Builds a [`Scene`] site by site, checking each as it comes (the JSON reader and the
/// Python package use it, so refusals come in input order).
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    domain: Aabb,
    epsilon: Option<f64>,
    mode: Mode,
    sites: Vec<Site>,
}

impl SceneBuilder {
    /// A builder over `domain` (checked: finite, non-empty), with the default epsilon
    /// and mode.
    pub fn new(domain: Aabb) -> Result<SceneBuilder, Error> {
        check::check_box(&domain).map_err(|m| Error::scene("domain", m))?;
        Ok(SceneBuilder {
            domain,
            epsilon: None,
            mode: Mode::default(),
            sites: Vec::new(),
        })
    }
    /// Sets the resolution (checked: finite and > 0).
    pub fn epsilon(mut self, epsilon: f64) -> Result<SceneBuilder, Error> {
        check::check_epsilon(epsilon).map_err(|m| Error::scene("epsilon", m))?;
        self.epsilon = Some(epsilon);
        Ok(self)
    }
    /// Sets the mode.
    pub fn mode(mut self, mode: Mode) -> SceneBuilder {
        self.mode = mode;
        self
    }
    /// Checks `site` and appends it; returns its index.
    pub fn add(&mut self, mut site: Site) -> Result<usize, Error> {
        let i = self.sites.len();
        check::check_site(&mut site.kind).map_err(|(field, m)| Error::site(i, &field, m))?;
        self.sites.push(site);
        Ok(i)
    }
    /// The number of sites added so far.
    pub fn len(&self) -> usize {
        self.sites.len()
    }
    /// Whether no site was added yet.
    pub fn is_empty(&self) -> bool {
        self.sites.is_empty()
    }
    /// The scene, after the checks between sites: no duplicate sites, no overlapping
    /// circles, ellipses or polygons, no number that f64 cannot resolve at the scene's epsilon, no
    /// two points of one metric too close for it.
    pub fn build(self) -> Result<Scene, Error> {
        if let Some((i, j)) = validate::duplicate_point(&self.sites) {
            return Err(Error::site(i, "at", format!("duplicate of site {j}")));
        }
        let epsilon = self
            .epsilon
            .unwrap_or_else(|| Scene::default_epsilon(&self.domain));
        validate::duplicate_site(&self.sites, false)?;
        validate::check_precision(&self.domain, epsilon, &self.sites)?;
        validate::near_coincident_sites(&self.domain, epsilon, &self.sites, false)?;
        validate::overlapping_ovals(&self.sites)?;
        polygon_overlap::overlapping_polygons(&self.sites)?;
        Ok(Scene {
            epsilon,
            domain: self.domain,
            mode: self.mode,
            sites: self.sites,
            projection: None,
        })
    }
}
