//! The value checks of a site, shared by every way of building a scene (JSON, the
//! builders, the readers to come): each refusal names the field at fault. Types and
//! presence of fields are the readers' business; ranges and geometry are checked here.

use super::validate::check_rings;
use super::{Metric, SiteKind};
use crate::geom::bspline::{ends_meet, RationalBspline};
use crate::geom::{Aabb, Point};
use crate::num::poly::MAX_DEGREE;

/// A refusal of one site: the field at fault (`metric.p`, `rings`, …) and why.
pub(crate) type Refusal = (String, String);

fn refuse(field: &str, message: impl Into<String>) -> Refusal {
    (field.to_string(), message.into())
}

/// Checks a box `[xmin, ymin, xmax, ymax]`: `xmin < xmax`, `ymin < ymax`, finite sides.
pub(crate) fn check_box(b: &Aabb) -> Result<(), String> {
    let a = b.to_array();
    if a.iter().any(|x| !x.is_finite()) {
        return Err(format!(
            "expected finite numbers, found [{}, {}, {}, {}]",
            a[0], a[1], a[2], a[3]
        ));
    }
    if !(b.min.x < b.max.x && b.min.y < b.max.y) {
        let what = if b.min.x > b.max.x || b.min.y > b.max.y {
            "inverted"
        } else {
            "empty"
        };
        return Err(format!(
            "{what}: need xmin < xmax and ymin < ymax, found [{}, {}, {}, {}]",
            a[0], a[1], a[2], a[3]
        ));
    }
    if !b.longest_side().is_finite() {
        return Err("too large: its sides overflow".into());
    }
    Ok(())
}

/// Checks the scene's resolution.
pub(crate) fn check_epsilon(e: f64) -> Result<(), String> {
    if e.is_nan() || e <= 0.0 || e.is_infinite() {
        return Err(format!("epsilon must be > 0, found {e}"));
    }
    Ok(())
}

/// Checks one site's values, normalising what differs from the format by rounding only
/// (the off-diagonal entries of an anisotropic matrix).
pub(crate) fn check_site(kind: &mut SiteKind) -> Result<(), Refusal> {
    match kind {
        SiteKind::Point { at, metric } => {
            finite_point("at", *at)?;
            check_metric(metric)
        }
        SiteKind::Circle { center, radius } => {
            finite_point("center", *center)?;
            number_where("radius", *radius, |r| r >= 0.0, "radius must be >= 0")
        }
        SiteKind::Ellipse {
            center,
            semi_axes,
            rotation,
        } => {
            finite_point("center", *center)?;
            finite("semi_axes", semi_axes[0])?;
            finite("semi_axes", semi_axes[1])?;
            if semi_axes.iter().any(|&s| s <= 0.0) {
                return Err(refuse(
                    "semi_axes",
                    format!(
                        "semi-axes must be > 0, found [{}, {}]",
                        semi_axes[0], semi_axes[1]
                    ),
                ));
            }
            finite("rotation", *rotation)
        }
        SiteKind::Segment { from, to } => {
            finite_point("from", *from)?;
            finite_point("to", *to)?;
            if from == to {
                return Err(refuse("to", "zero-length segment (from == to)"));
            }
            Ok(())
        }
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            finite_point("center", *center)?;
            number_where("radius", *radius, |r| r > 0.0, "radius must be > 0")?;
            finite("start_angle", *start_angle)?;
            finite("end_angle", *end_angle)?;
            if start_angle == end_angle {
                return Err(refuse(
                    "end_angle",
                    "equal to start_angle: the arc is empty (a full circle ends at start_angle + 2π)",
                ));
            }
            Ok(())
        }
        SiteKind::Polyline { points } => {
            finite_points("points", points)?;
            if points.len() < 2 {
                return Err(refuse(
                    "points",
                    format!("a polyline needs at least 2 points, found {}", points.len()),
                ));
            }
            if let Some(k) = (1..points.len()).find(|&k| points[k] == points[k - 1]) {
                return Err(refuse(
                    "points",
                    format!("points {} and {k} coincide (zero-length edge)", k - 1),
                ));
            }
            Ok(())
        }
        SiteKind::Polygon { rings } => {
            for ring in rings.iter() {
                finite_points("rings", ring)?;
            }
            check_rings(rings).map_err(|m| refuse("rings", m))
        }
        SiteKind::Algebraic { equation, clip } => {
            if equation.poly().total_degree() == 0 {
                return Err(refuse(
                    "equation",
                    "the equation is constant: its curve is empty or the whole plane",
                ));
            }
            match clip {
                Some(c) => check_box(c).map_err(|m| refuse("clip", m)),
                None => Ok(()),
            }
        }
        SiteKind::Bezier {
            control_points,
            weights,
        } => {
            finite_points("control_points", control_points)?;
            if control_points.len() < 2 {
                return Err(refuse(
                    "control_points",
                    format!(
                        "a Bézier curve needs at least 2 control points, found {}",
                        control_points.len()
                    ),
                ));
            }
            not_all_equal(control_points)?;
            check_weights(weights.as_deref(), control_points.len())
        }
        SiteKind::Bspline {
            degree,
            control_points,
            knots,
            weights,
            closed,
        } => check_bspline(*degree, control_points, knots, weights.as_deref(), *closed),
        SiteKind::Field { .. } => Ok(()),
        SiteKind::ImplicitField { equation } => {
            if equation.poly().degree_in(2) == 0 {
                return Err(refuse("equation", "an implicit field must involve z"));
            }
            Ok(())
        }
    }
}

fn check_metric(metric: &mut Metric) -> Result<(), Refusal> {
    match metric {
        Metric::Euclidean => Ok(()),
        Metric::Lp { p } => {
            if *p < 2 || *p % 2 != 0 {
                Err(refuse(
                    "metric.p",
                    format!("p must be an even integer >= 2, found {p}"),
                ))
            } else if *p > MAX_DEGREE {
                Err(refuse(
                    "metric.p",
                    format!("p = {p} exceeds the largest supported exponent {MAX_DEGREE}"),
                ))
            } else {
                Ok(())
            }
        }
        Metric::Anisotropic { matrix, weight } => {
            *matrix = spd_matrix(*matrix).map_err(|m| refuse("metric.matrix", m))?;
            finite("metric.weight", *weight)
        }
        Metric::Power { weight } => finite("metric.weight", *weight),
        Metric::Moebius { scale, weight } => {
            finite("metric.scale", *scale)?;
            if *scale <= 0.0 {
                return Err(refuse(
                    "metric.scale",
                    format!("scale must be > 0, found {scale}"),
                ));
            }
            finite("metric.weight", *weight)
        }
    }
}

/// A symmetric positive-definite 2×2 matrix `[[a, b], [b, c]]`. Off-diagonal entries that
/// differ by rounding only (relative 1e-12) are averaged.
fn spd_matrix(m: [[f64; 2]; 2]) -> Result<[[f64; 2]; 2], String> {
    if m.iter().flatten().any(|x| !x.is_finite()) {
        return Err("expected finite entries".into());
    }
    let scale = m.iter().flatten().fold(0.0f64, |s, x| s.max(x.abs()));
    if (m[0][1] - m[1][0]).abs() > 1e-12 * scale {
        return Err(format!(
            "not symmetric ({} and {} off the diagonal)",
            m[0][1], m[1][0]
        ));
    }
    let b = 0.5 * (m[0][1] + m[1][0]);
    let (a, c) = (m[0][0], m[1][1]);
    let mean = 0.5 * (a + c);
    let radius = (0.5 * (a - c)).hypot(b);
    let high = mean + radius;
    let det = a.mul_add(c, -(b * b));
    if !(high.is_finite() && det.is_finite()) {
        return Err("entries too large (the determinant overflows)".into());
    }
    // The accurate small eigenvalue is det / the large one.
    let low = if high > 0.0 {
        det / high
    } else {
        mean - radius
    };
    if low <= 0.0 || high <= 0.0 {
        return Err(format!(
            "not positive-definite (eigenvalues {high} and {low})"
        ));
    }
    Ok([[a, b], [b, c]])
}

fn check_bspline(
    degree: usize,
    control_points: &[Point],
    knots: &[f64],
    weights: Option<&[f64]>,
    closed: bool,
) -> Result<(), Refusal> {
    if degree < 1 {
        return Err(refuse(
            "degree",
            format!("degree must be an integer >= 1, found {degree}"),
        ));
    }
    finite_points("control_points", control_points)?;
    let n = control_points.len();
    if degree >= n {
        return Err(refuse(
            "control_points",
            format!(
                "degree {degree} needs at least {} control points, found {n}",
                degree + 1
            ),
        ));
    }
    not_all_equal(control_points)?;
    if let Some(k) = knots.iter().position(|x| !x.is_finite()) {
        return Err(refuse(
            "knots",
            format!("element {k}: expected a finite number, found {}", knots[k]),
        ));
    }
    // `degree < n`, so `n + degree + 1` cannot overflow.
    let need = n + degree + 1;
    if knots.len() != need {
        return Err(refuse(
            "knots",
            format!(
                "{} knots, but degree {degree} with {n} control points needs {need}",
                knots.len()
            ),
        ));
    }
    if let Some(k) = (1..need).find(|&k| knots[k] < knots[k - 1]) {
        return Err(refuse(
            "knots",
            format!(
                "knots must be non-decreasing: knot {k} ({}) < knot {} ({})",
                knots[k],
                k - 1,
                knots[k - 1]
            ),
        ));
    }
    if knots[degree] >= knots[n] {
        return Err(refuse(
            "knots",
            format!(
                "the parameter range [knots[{degree}], knots[{n}]] = [{}, {}] is empty",
                knots[degree], knots[n]
            ),
        ));
    }
    check_weights(weights, n)?;
    // the engines take a closed curve for a loop that bounds a region
    if closed {
        let (a, b) = RationalBspline::new(degree, control_points, knots, weights).ends();
        if !ends_meet(a, b) {
            return Err(refuse(
                "closed",
                format!(
                    "the curve is marked closed, but its ends [{}, {}] and [{}, {}] do not meet",
                    a.x, a.y, b.x, b.y
                ),
            ));
        }
    }
    Ok(())
}

/// Optional rational weights: one per control point, each > 0.
fn check_weights(weights: Option<&[f64]>, n: usize) -> Result<(), Refusal> {
    let Some(w) = weights else {
        return Ok(());
    };
    if w.len() != n {
        return Err(refuse(
            "weights",
            format!("{} weights for {n} control points", w.len()),
        ));
    }
    if let Some(k) = w.iter().position(|&x| !(x > 0.0 && x.is_finite())) {
        return Err(refuse(
            "weights",
            format!("weights must be > 0, weight {k} is {}", w[k]),
        ));
    }
    Ok(())
}

fn not_all_equal(pts: &[Point]) -> Result<(), Refusal> {
    if pts.iter().all(|&p| p == pts[0]) {
        return Err(refuse(
            "control_points",
            "all control points coincide: the curve is a single point",
        ));
    }
    Ok(())
}

fn finite(field: &str, x: f64) -> Result<(), Refusal> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(refuse(
            field,
            format!("expected a finite number, found {x}"),
        ))
    }
}

fn number_where(
    field: &str,
    x: f64,
    ok: fn(f64) -> bool,
    requirement: &str,
) -> Result<(), Refusal> {
    finite(field, x)?;
    if ok(x) {
        Ok(())
    } else {
        Err(refuse(field, format!("{requirement}, found {x}")))
    }
}

fn finite_point(field: &str, p: Point) -> Result<(), Refusal> {
    if p.x.is_finite() && p.y.is_finite() {
        Ok(())
    } else {
        Err(refuse(
            field,
            format!("expected finite coordinates, found [{}, {}]", p.x, p.y),
        ))
    }
}

fn finite_points(field: &str, pts: &[Point]) -> Result<(), Refusal> {
    match pts
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        Some(k) => Err(refuse(
            field,
            format!(
                "point {k}: expected finite coordinates, found [{}, {}]",
                pts[k].x, pts[k].y
            ),
        )),
        None => Ok(()),
    }
}
