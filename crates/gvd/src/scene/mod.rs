//! The scene model: validated sites in a domain. Parsing and validation live in
//! `parse.rs`; every refusal is an [`Error`] naming the site index and the field.

mod parse;
mod validate;

use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::num::poly::Poly;

/// What the diagram separates (see `SCENE_FORMAT.md`, `mode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Mode {
    #[default]
    Voronoi,
    Complex,
    MedialAxis,
}

/// The distance field of a point site (`SCENE_FORMAT.md`, point metrics).
#[derive(Clone, Debug, PartialEq)]
pub enum Metric {
    /// `|q − p|`
    Euclidean,
    /// `(x − px)^p + (y − py)^p`, `p` even ≥ 2
    Lp { p: u32 },
    /// `(q − p)ᵀ M (q − p) − w`, `M` symmetric positive-definite
    Anisotropic { matrix: [[f64; 2]; 2], weight: f64 },
    /// `|q − p|² − w²`
    Power { weight: f64 },
    /// `v |q − p|² − w`, `v > 0`
    Moebius { scale: f64, weight: f64 },
}

/// An equation as the user wrote it, with its parsed polynomial.
#[derive(Clone, Debug, PartialEq)]
pub struct Equation {
    pub text: String,
    pub poly: Poly,
}

/// A validated site.
#[derive(Clone, Debug, PartialEq)]
pub enum SiteKind {
    Point {
        at: Point,
        metric: Metric,
    },
    Circle {
        center: Point,
        radius: f64,
    },
    Ellipse {
        center: Point,
        semi_axes: [f64; 2],
        rotation: f64,
    },
    Segment {
        from: Point,
        to: Point,
    },
    Arc {
        center: Point,
        radius: f64,
        start_angle: f64,
        end_angle: f64,
    },
    Polyline {
        points: Vec<Point>,
    },
    Polygon {
        rings: Vec<Vec<Point>>,
    },
    Algebraic {
        equation: Equation,
        clip: Option<Aabb>,
    },
    Bezier {
        control_points: Vec<Point>,
        weights: Option<Vec<f64>>,
    },
    Bspline {
        degree: usize,
        control_points: Vec<Point>,
        knots: Vec<f64>,
        weights: Option<Vec<f64>>,
        closed: bool,
    },
    /// An explicit polynomial distance field in `x`, `y`.
    Field {
        equation: Equation,
    },
    /// The smallest non-negative root `z` of `g(x, y, z)`.
    ImplicitField {
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

/// The counter-clockwise angle an arc sweeps from `start_angle` to `end_angle`, in
/// `(0, 2π]`: a nonzero whole number of turns is the full circle.
pub fn arc_sweep(start_angle: f64, end_angle: f64) -> f64 {
    let d = end_angle - start_angle;
    let sweep = d.rem_euclid(std::f64::consts::TAU);
    if d >= std::f64::consts::TAU || (sweep == 0.0 && d != 0.0) {
        std::f64::consts::TAU
    } else {
        sweep
    }
}

/// A site: its kind with its data, and the optional user id echoed in outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct Site {
    pub id: Option<String>,
    pub kind: SiteKind,
}

/// A validated scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub domain: Aabb,
    pub epsilon: f64,
    pub mode: Mode,
    pub sites: Vec<Site>,
}

impl Scene {
    /// Parses and validates a scene from JSON text.
    pub fn from_json(text: &str) -> Result<Scene, Error> {
        parse::scene_from_json(text)
    }

    /// Parses and validates a scene from a JSON value.
    pub fn from_value(value: &serde_json::Value) -> Result<Scene, Error> {
        parse::scene_from_value(value)
    }
}
