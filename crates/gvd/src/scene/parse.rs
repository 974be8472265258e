//! Scene parsing and validation, by hand from a `serde_json::Value`, so that every refusal
//! names the site index and the exact field (`SCENE_FORMAT.md`, "Bad input"). Unknown
//! fields are ignored; an optional field that is `null` counts as absent.

use super::validate::{
    check_precision, check_rings, duplicate_point, duplicate_site, overlapping_ovals,
};
use super::{Equation, Metric, Mode, Scene, Site, SiteKind};
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::num::poly::{Poly, MAX_DEGREE};
use serde_json::{Map, Value};

/// The site kinds of the format, in the order of `SCENE_FORMAT.md`.
const KINDS: &str = "point, circle, ellipse, segment, arc, polyline, polygon, algebraic, \
                     bezier, bspline, field, implicit_field";

pub(super) fn scene_from_json(text: &str) -> Result<Scene, Error> {
    let v: Value = serde_json::from_str(text).map_err(|e| Error::Json(e.to_string()))?;
    scene_from_value(&v)
}

pub(super) fn scene_from_value(v: &Value) -> Result<Scene, Error> {
    let obj = v.as_object().ok_or_else(|| {
        Error::scene(
            "scene",
            format!("expected an object, found {}", describe(v)),
        )
    })?;
    let domain = match present(obj, "domain") {
        Some(d) => aabb(d).map_err(|m| Error::scene("domain", m))?,
        None => return Err(Error::scene("domain", "missing required field 'domain'")),
    };
    let epsilon = match present(obj, "epsilon") {
        Some(e) => {
            let e = number(e).map_err(|m| Error::scene("epsilon", m))?;
            if e <= 0.0 {
                return Err(Error::scene(
                    "epsilon",
                    format!("epsilon must be > 0, found {e}"),
                ));
            }
            e
        }
        None => 1e-3 * domain.longest_side(),
    };
    let mode = match present(obj, "mode") {
        None => Mode::default(),
        Some(Value::String(s)) => match s.as_str() {
            "voronoi" => Mode::Voronoi,
            "complex" => Mode::Complex,
            "medial_axis" => Mode::MedialAxis,
            other => {
                return Err(Error::scene(
                    "mode",
                    format!(
                        "unknown mode '{}' (expected voronoi, complex or medial_axis)",
                        clip_text(other)
                    ),
                ))
            }
        },
        Some(m) => {
            return Err(Error::scene(
                "mode",
                format!("expected a string, found {}", describe(m)),
            ))
        }
    };
    let list = match present(obj, "sites") {
        Some(Value::Array(a)) => a,
        Some(s) => {
            return Err(Error::scene(
                "sites",
                format!("expected a list of sites, found {}", describe(s)),
            ))
        }
        None => return Err(Error::scene("sites", "missing required field 'sites'")),
    };
    let sites = list
        .iter()
        .enumerate()
        .map(|(i, s)| site(i, s))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some((i, j)) = duplicate_point(&sites) {
        return Err(Error::site(i, "at", format!("duplicate of site {j}")));
    }
    duplicate_site(&sites)?;
    check_precision(&domain, epsilon, &sites)?;
    overlapping_ovals(&sites)?;
    Ok(Scene {
        domain,
        epsilon,
        mode,
        sites,
    })
}

/// The fields of site `i`, with errors naming the site and the field.
struct Fields<'a> {
    i: usize,
    obj: &'a Map<String, Value>,
}

impl<'a> Fields<'a> {
    fn err(&self, field: &str, message: impl Into<String>) -> Error {
        Error::site(self.i, field, message)
    }
    fn req(&self, field: &str) -> Result<&'a Value, Error> {
        present(self.obj, field).ok_or_else(|| self.err(field, "missing required field"))
    }
    /// Reads required `field` with `read`.
    fn get<T>(&self, field: &str, read: fn(&Value) -> Result<T, String>) -> Result<T, Error> {
        read(self.req(field)?).map_err(|m| self.err(field, m))
    }
    /// Reads optional `field` with `read`.
    fn opt<T>(
        &self,
        field: &str,
        read: fn(&Value) -> Result<T, String>,
    ) -> Result<Option<T>, Error> {
        present(self.obj, field)
            .map(|v| read(v).map_err(|m| self.err(field, m)))
            .transpose()
    }
    /// A required number satisfying `ok`, else `requirement` (e.g. "radius must be > 0").
    fn number_where(
        &self,
        field: &str,
        ok: fn(f64) -> bool,
        requirement: &str,
    ) -> Result<f64, Error> {
        let x = self.get(field, number)?;
        if ok(x) {
            Ok(x)
        } else {
            Err(self.err(field, format!("{requirement}, found {x}")))
        }
    }
    fn equation(&self, vars: &[char]) -> Result<Equation, Error> {
        let text = self.get("equation", string)?;
        let poly = Poly::parse(&text, vars)
            .map_err(|e| self.err("equation", format!("does not parse: {e}")))?;
        Ok(Equation { text, poly })
    }
}

fn site(i: usize, v: &Value) -> Result<Site, Error> {
    let obj = v.as_object().ok_or_else(|| {
        Error::site(
            i,
            "site",
            format!("expected an object, found {}", describe(v)),
        )
    })?;
    let f = Fields { i, obj };
    let id = f.opt("id", string)?;
    let kind = f.get("kind", string)?;
    let kind = match kind.as_str() {
        "point" => SiteKind::Point {
            at: f.get("at", point)?,
            metric: metric(&f)?,
        },
        "circle" => SiteKind::Circle {
            center: f.get("center", point)?,
            radius: f.number_where("radius", |r| r >= 0.0, "radius must be >= 0")?,
        },
        "ellipse" => {
            let center = f.get("center", point)?;
            let semi_axes = f.get("semi_axes", numbers::<2>)?;
            if semi_axes.iter().any(|&s| s <= 0.0) {
                return Err(f.err(
                    "semi_axes",
                    format!(
                        "semi-axes must be > 0, found [{}, {}]",
                        semi_axes[0], semi_axes[1]
                    ),
                ));
            }
            SiteKind::Ellipse {
                center,
                semi_axes,
                rotation: f.opt("rotation", number)?.unwrap_or(0.0),
            }
        }
        "segment" => {
            let (from, to) = (f.get("from", point)?, f.get("to", point)?);
            if from == to {
                return Err(f.err("to", "zero-length segment (from == to)"));
            }
            SiteKind::Segment { from, to }
        }
        "arc" => {
            let center = f.get("center", point)?;
            let radius = f.number_where("radius", |r| r > 0.0, "radius must be > 0")?;
            let start_angle = f.get("start_angle", number)?;
            let end_angle = f.get("end_angle", number)?;
            if start_angle == end_angle {
                return Err(f.err(
                    "end_angle",
                    "equal to start_angle: the arc is empty (a full circle ends at start_angle + 2π)",
                ));
            }
            SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            }
        }
        "polyline" => {
            let points = f.get("points", points)?;
            if points.len() < 2 {
                return Err(f.err(
                    "points",
                    format!("a polyline needs at least 2 points, found {}", points.len()),
                ));
            }
            if let Some(k) = (1..points.len()).find(|&k| points[k] == points[k - 1]) {
                return Err(f.err(
                    "points",
                    format!("points {} and {k} coincide (zero-length edge)", k - 1),
                ));
            }
            SiteKind::Polyline { points }
        }
        "polygon" => {
            let rings = f.get("rings", rings)?;
            check_rings(&rings).map_err(|m| f.err("rings", m))?;
            SiteKind::Polygon { rings }
        }
        "algebraic" => {
            let equation = f.equation(&['x', 'y'])?;
            if equation.poly.total_degree() == 0 {
                return Err(f.err(
                    "equation",
                    "the equation is constant: its curve is empty or the whole plane",
                ));
            }
            SiteKind::Algebraic {
                equation,
                clip: f.opt("clip", aabb)?,
            }
        }
        "bezier" => {
            let control_points = f.get("control_points", points)?;
            if control_points.len() < 2 {
                return Err(f.err(
                    "control_points",
                    format!(
                        "a Bézier curve needs at least 2 control points, found {}",
                        control_points.len()
                    ),
                ));
            }
            not_all_equal(&f, &control_points)?;
            let weights = weights(&f, control_points.len())?;
            SiteKind::Bezier {
                control_points,
                weights,
            }
        }
        "bspline" => bspline(&f)?,
        "field" => SiteKind::Field {
            equation: f.equation(&['x', 'y'])?,
        },
        "implicit_field" => {
            let equation = f.equation(&['x', 'y', 'z'])?;
            if equation.poly.degree_in(2) == 0 {
                return Err(f.err("equation", "an implicit field must involve z"));
            }
            SiteKind::ImplicitField { equation }
        }
        other => {
            return Err(f.err(
                "kind",
                format!(
                    "unknown kind '{}' (expected one of {KINDS})",
                    clip_text(other)
                ),
            ))
        }
    };
    Ok(Site { id, kind })
}

fn metric(f: &Fields) -> Result<Metric, Error> {
    let Some(v) = present(f.obj, "metric") else {
        return Ok(Metric::Euclidean);
    };
    let obj = v.as_object().ok_or_else(|| {
        f.err(
            "metric",
            format!("expected an object, found {}", describe(v)),
        )
    })?;
    let field = |name: &str| format!("metric.{name}");
    let get = |name: &str| -> Result<f64, Error> {
        let v = present(obj, name).ok_or_else(|| f.err(&field(name), "missing required field"))?;
        number(v).map_err(|msg| f.err(&field(name), msg))
    };
    let weight = || present(obj, "weight").map_or(Ok(0.0), |_| get("weight"));
    let kind = present(obj, "kind")
        .ok_or_else(|| f.err("metric.kind", "missing required field"))
        .and_then(|k| string(k).map_err(|msg| f.err("metric.kind", msg)))?;
    match kind.as_str() {
        "euclidean" => Ok(Metric::Euclidean),
        "lp" => {
            let p = get("p")?;
            let limit = f64::from(MAX_DEGREE);
            if p < 2.0 || p.fract() != 0.0 || p % 2.0 != 0.0 {
                Err(f.err(
                    "metric.p",
                    format!("p must be an even integer >= 2, found {p}"),
                ))
            } else if p > limit {
                Err(f.err(
                    "metric.p",
                    format!("p = {p} exceeds the largest supported exponent {MAX_DEGREE}"),
                ))
            } else {
                Ok(Metric::Lp { p: p as u32 })
            }
        }
        "anisotropic" => {
            let v = present(obj, "matrix")
                .ok_or_else(|| f.err("metric.matrix", "missing required field"))?;
            let matrix = spd_matrix(v).map_err(|msg| f.err("metric.matrix", msg))?;
            Ok(Metric::Anisotropic {
                matrix,
                weight: weight()?,
            })
        }
        "power" => Ok(Metric::Power { weight: weight()? }),
        "moebius" => {
            let scale = get("scale")?;
            if scale <= 0.0 {
                return Err(f.err("metric.scale", format!("scale must be > 0, found {scale}")));
            }
            Ok(Metric::Moebius {
                scale,
                weight: weight()?,
            })
        }
        other => Err(f.err(
            "metric.kind",
            format!(
                "unknown metric '{}' (expected euclidean, lp, anisotropic, power or moebius)",
                clip_text(other)
            ),
        )),
    }
}

/// A symmetric positive-definite 2×2 matrix `[[a, b], [b, c]]`. Off-diagonal entries that
/// differ by rounding only (relative 1e-12) are averaged.
fn spd_matrix(v: &Value) -> Result<[[f64; 2]; 2], String> {
    let rows = array(v, "a 2×2 matrix [[a, b], [b, c]]")?;
    if rows.len() != 2 {
        return Err(format!("expected 2 rows, found {}", rows.len()));
    }
    let mut m = [[0.0; 2]; 2];
    for (r, row) in rows.iter().enumerate() {
        m[r] = numbers::<2>(row).map_err(|e| format!("row {r}: {e}"))?;
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

fn bspline(f: &Fields) -> Result<SiteKind, Error> {
    let degree = f.number_where(
        "degree",
        |d| d >= 1.0 && d.fract() == 0.0,
        "degree must be an integer >= 1",
    )?;
    let control_points = f.get("control_points", points)?;
    let n = control_points.len();
    if degree >= n as f64 {
        return Err(f.err(
            "control_points",
            format!(
                "degree {degree} needs at least {} control points, found {n}",
                degree + 1.0
            ),
        ));
    }
    // `degree < n`, so the cast is exact and `n + degree + 1` cannot overflow.
    let degree = degree as usize;
    not_all_equal(f, &control_points)?;
    let knots = f.get("knots", numbers_vec)?;
    let need = n + degree + 1;
    if knots.len() != need {
        return Err(f.err(
            "knots",
            format!(
                "{} knots, but degree {degree} with {n} control points needs {need}",
                knots.len()
            ),
        ));
    }
    if let Some(k) = (1..need).find(|&k| knots[k] < knots[k - 1]) {
        return Err(f.err(
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
        return Err(f.err(
            "knots",
            format!(
                "the parameter range [knots[{degree}], knots[{n}]] = [{}, {}] is empty",
                knots[degree], knots[n]
            ),
        ));
    }
    let weights = weights(f, n)?;
    let closed = f.opt("closed", boolean)?.unwrap_or(false);
    Ok(SiteKind::Bspline {
        degree,
        control_points,
        knots,
        weights,
        closed,
    })
}

/// Optional rational weights: one per control point, each > 0.
fn weights(f: &Fields, n: usize) -> Result<Option<Vec<f64>>, Error> {
    let Some(w) = f.opt("weights", numbers_vec)? else {
        return Ok(None);
    };
    if w.len() != n {
        return Err(f.err(
            "weights",
            format!("{} weights for {n} control points", w.len()),
        ));
    }
    if let Some(k) = w.iter().position(|&x| x <= 0.0) {
        return Err(f.err(
            "weights",
            format!("weights must be > 0, weight {k} is {}", w[k]),
        ));
    }
    Ok(Some(w))
}

fn not_all_equal(f: &Fields, pts: &[Point]) -> Result<(), Error> {
    if pts.iter().all(|&p| p == pts[0]) {
        return Err(f.err(
            "control_points",
            "all control points coincide: the curve is a single point",
        ));
    }
    Ok(())
}

/// `obj[field]` unless absent or `null`.
fn present<'a>(obj: &'a Map<String, Value>, field: &str) -> Option<&'a Value> {
    obj.get(field).filter(|v| !v.is_null())
}

/// A short description of a JSON value for messages: `the string "NaN"`, `an object`.
fn describe(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("{b}"),
        Value::Number(n) => format!("the number {n}"),
        Value::String(s) => format!("the string {:?}", clip_text(s)),
        Value::Array(a) => format!("an array of {} elements", a.len()),
        Value::Object(_) => "an object".into(),
    }
}

/// At most 40 characters of user text, for messages.
fn clip_text(s: &str) -> String {
    match s.char_indices().nth(40) {
        Some((k, _)) => format!("{}…", &s[..k]),
        None => s.to_string(),
    }
}

fn number(v: &Value) -> Result<f64, String> {
    match v.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => Err(format!("expected a finite number, found {}", describe(v))),
    }
}

fn string(v: &Value) -> Result<String, String> {
    v.as_str()
        .map(str::to_string)
        .ok_or_else(|| format!("expected a string, found {}", describe(v)))
}

fn boolean(v: &Value) -> Result<bool, String> {
    v.as_bool()
        .ok_or_else(|| format!("expected true or false, found {}", describe(v)))
}

fn array<'a>(v: &'a Value, what: &str) -> Result<&'a Vec<Value>, String> {
    v.as_array()
        .ok_or_else(|| format!("expected {what}, found {}", describe(v)))
}

fn numbers_vec(v: &Value) -> Result<Vec<f64>, String> {
    array(v, "a list of numbers")?
        .iter()
        .enumerate()
        .map(|(k, x)| number(x).map_err(|e| format!("element {k}: {e}")))
        .collect()
}

fn numbers<const N: usize>(v: &Value) -> Result<[f64; N], String> {
    let a = array(v, &format!("an array of {N} numbers"))?;
    if a.len() != N {
        return Err(format!("expected {N} numbers, found {}", a.len()));
    }
    let mut out = [0.0; N];
    for (k, x) in a.iter().enumerate() {
        out[k] = number(x).map_err(|e| format!("element {k}: {e}"))?;
    }
    Ok(out)
}

fn point(v: &Value) -> Result<Point, String> {
    let a = array(v, "a point [x, y]")?;
    if a.len() != 2 {
        return Err(format!(
            "expected a point [x, y], found {} numbers",
            a.len()
        ));
    }
    Ok(Point::new(
        number(&a[0]).map_err(|e| format!("x: {e}"))?,
        number(&a[1]).map_err(|e| format!("y: {e}"))?,
    ))
}

fn points(v: &Value) -> Result<Vec<Point>, String> {
    array(v, "a list of points [[x, y], ...]")?
        .iter()
        .enumerate()
        .map(|(k, p)| point(p).map_err(|e| format!("point {k}: {e}")))
        .collect()
}

fn rings(v: &Value) -> Result<Vec<Vec<Point>>, String> {
    array(v, "a list of rings (lists of points)")?
        .iter()
        .enumerate()
        .map(|(r, ring)| points(ring).map_err(|e| format!("ring {r}: {e}")))
        .collect()
}

/// A box `[xmin, ymin, xmax, ymax]` with `xmin < xmax`, `ymin < ymax` and finite sides.
fn aabb(v: &Value) -> Result<Aabb, String> {
    let a = numbers::<4>(v).map_err(|e| format!("{e} (expected [xmin, ymin, xmax, ymax])"))?;
    let b = Aabb::from_array(a);
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
    Ok(b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn scene_with(site: Value) -> Value {
        json!({"domain": [-2, -2, 2, 2], "sites": [{"kind": "point", "at": [0, 0]}, site]})
    }

    /// `(site, field, message)` of the refusal of `v`.
    fn refusal(v: Value) -> (Option<usize>, String, String) {
        match scene_from_value(&v).expect_err("must be refused") {
            Error::Site {
                site,
                field,
                message,
            } => (Some(site), field, message),
            Error::Scene { field, message } => (None, field, message),
            e => panic!("unexpected error {e}"),
        }
    }

    fn site_refusal(site: Value) -> (String, String) {
        let (i, field, message) = refusal(scene_with(site));
        assert_eq!(i, Some(1), "{field}: {message}");
        (field, message)
    }

    #[test]
    fn defaults() {
        let s = scene_from_value(&json!({"domain": [0, 0, 4, 2], "sites": []})).unwrap();
        assert_eq!(s.epsilon, 4e-3);
        assert_eq!(s.mode, Mode::Voronoi);
        let s = scene_from_value(&json!({
            "domain": [0, 0, 4, 2], "epsilon": 0.5, "mode": "medial_axis", "extra": 1,
            "sites": [{"kind": "point", "at": [1, 1], "id": "a", "metric": null}]
        }))
        .unwrap();
        assert_eq!(s.epsilon, 0.5);
        assert_eq!(s.mode, Mode::MedialAxis);
        assert_eq!(s.sites[0].id.as_deref(), Some("a"));
        assert_eq!(
            s.sites[0].kind,
            SiteKind::Point {
                at: Point::new(1.0, 1.0),
                metric: Metric::Euclidean
            }
        );
    }

    #[test]
    fn every_kind_reads() {
        let s = scene_from_value(&json!({"domain": [-2, -2, 2, 2], "sites": [
            {"kind": "point", "at": [0, 1], "metric": {"kind": "lp", "p": 4}},
            {"kind": "point", "at": [0, 1], "metric": {"kind": "anisotropic", "matrix": [[2, 1], [1, 2]]}},
            {"kind": "point", "at": [0, 1], "metric": {"kind": "power", "weight": 0.5}},
            {"kind": "point", "at": [0, 1], "metric": {"kind": "moebius", "scale": 2, "weight": 0.1}},
            {"kind": "circle", "center": [1, 1], "radius": 0},
            {"kind": "ellipse", "center": [1, 1], "semi_axes": [0.2, 0.1], "rotation": 0.3},
            {"kind": "segment", "from": [0, 0], "to": [1, 0]},
            {"kind": "arc", "center": [0, 0], "radius": 1, "start_angle": 0, "end_angle": 3},
            {"kind": "polyline", "points": [[0, 0], [1, 0], [1, 1], [0, 0]]},
            {"kind": "polygon", "rings": [[[0, 0], [1, 0], [0, 1]]]},
            {"kind": "algebraic", "equation": "x^2 + y^2 - 1", "clip": [-1, -1, 1, 1]},
            {"kind": "bezier", "control_points": [[0, 0], [1, 1], [2, 0]], "weights": [1, 2, 1]},
            {"kind": "bspline", "degree": 2, "control_points": [[0, 0], [1, 1], [2, 0]],
             "knots": [0, 0, 0, 1, 1, 1], "closed": false},
            {"kind": "field", "equation": "x^2 + y^2"},
            {"kind": "implicit_field", "equation": "x^2 + y^2 - (z + 0.5)^2"}
        ]}))
        .unwrap();
        let names: Vec<&str> = s.sites.iter().map(|s| s.kind.name()).collect();
        assert_eq!(names.len(), 15);
        assert_eq!(
            s.sites[1].kind,
            SiteKind::Point {
                at: Point::new(0.0, 1.0),
                metric: Metric::Anisotropic {
                    matrix: [[2.0, 1.0], [1.0, 2.0]],
                    weight: 0.0
                }
            }
        );
        assert!(matches!(
            s.sites[12].kind,
            SiteKind::Bspline { degree: 2, .. }
        ));
        assert!(matches!(
            &s.sites[10].kind,
            SiteKind::Algebraic { clip: Some(_), .. }
        ));
    }

    #[test]
    fn scene_level_refusals() {
        let d = json!([-2, -2, 2, 2]);
        for (v, field, needle) in [
            (json!([]), "scene", "expected an object"),
            (json!({"sites": []}), "domain", "missing"),
            (
                json!({"domain": [0, 0, 1], "sites": []}),
                "domain",
                "expected 4 numbers",
            ),
            (
                json!({"domain": [0, 0, 0, 1], "sites": []}),
                "domain",
                "empty",
            ),
            (
                json!({"domain": [0, 1, 1, 0], "sites": []}),
                "domain",
                "inverted",
            ),
            (
                json!({"domain": [-1e308, 0, 1e308, 1], "sites": []}),
                "domain",
                "too large",
            ),
            (
                json!({"domain": d, "epsilon": 0, "sites": []}),
                "epsilon",
                "> 0",
            ),
            (
                json!({"domain": d, "epsilon": "1", "sites": []}),
                "epsilon",
                "the string \"1\"",
            ),
            (
                json!({"domain": d, "mode": "fast", "sites": []}),
                "mode",
                "unknown mode 'fast'",
            ),
            (json!({"domain": d}), "sites", "missing"),
            (json!({"domain": d, "sites": {}}), "sites", "an object"),
        ] {
            let (site, f, message) = refusal(v);
            assert_eq!((site, f.as_str()), (None, field), "{message}");
            assert!(message.contains(needle), "{field}: {message}");
        }
    }

    #[test]
    fn site_refusals() {
        for (site, field, needle) in [
            (json!(3), "site", "expected an object"),
            (json!({"at": [0, 0]}), "kind", "missing"),
            (json!({"kind": 3}), "kind", "expected a string"),
            (json!({"kind": "hexagon"}), "kind", "unknown kind 'hexagon'"),
            (
                json!({"kind": "point", "at": [1, 2], "id": 7}),
                "id",
                "expected a string",
            ),
            (
                json!({"kind": "point", "at": ["NaN", 0]}),
                "at",
                "the string \"NaN\"",
            ),
            (
                json!({"kind": "point", "at": [1, 2, 3]}),
                "at",
                "found 3 numbers",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": 1}),
                "metric",
                "expected an object",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {}}),
                "metric.kind",
                "missing",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "l9"}}),
                "metric.kind",
                "unknown metric 'l9'",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "lp", "p": 3}}),
                "metric.p",
                "even integer",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "lp", "p": 0}}),
                "metric.p",
                "even integer",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "lp", "p": 4.5}}),
                "metric.p",
                "even integer",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "lp", "p": 2048}}),
                "metric.p",
                "exceeds",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "anisotropic", "matrix": [[1, 2], [2, 1]]}}),
                "metric.matrix",
                "not positive-definite (eigenvalues 3 and -1)",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "anisotropic", "matrix": [[1, 0], [0.5, 1]]}}),
                "metric.matrix",
                "not symmetric",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "anisotropic", "matrix": [[1, 0]]}}),
                "metric.matrix",
                "2 rows",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "anisotropic", "matrix": [[1, 0], [0, 1]], "weight": "x"}}),
                "metric.weight",
                "expected a finite number",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "moebius", "scale": 0}}),
                "metric.scale",
                "> 0",
            ),
            (
                json!({"kind": "point", "at": [1, 2], "metric": {"kind": "moebius"}}),
                "metric.scale",
                "missing",
            ),
            (
                json!({"kind": "circle", "center": [1, 2], "radius": -1}),
                "radius",
                ">= 0",
            ),
            (
                json!({"kind": "ellipse", "center": [1, 2], "semi_axes": [1, 0]}),
                "semi_axes",
                "> 0",
            ),
            (
                json!({"kind": "ellipse", "center": [1, 2], "semi_axes": [1, 1], "rotation": true}),
                "rotation",
                "found true",
            ),
            (
                json!({"kind": "segment", "from": [1, 2], "to": [1, 2]}),
                "to",
                "zero-length",
            ),
            (
                json!({"kind": "arc", "center": [1, 2], "radius": 0, "start_angle": 0, "end_angle": 1}),
                "radius",
                "> 0",
            ),
            (
                json!({"kind": "arc", "center": [1, 2], "radius": 1, "start_angle": 1, "end_angle": 1}),
                "end_angle",
                "empty",
            ),
            (
                json!({"kind": "polyline", "points": [[0, 0]]}),
                "points",
                "at least 2",
            ),
            (
                json!({"kind": "polyline", "points": [[0, 0], [1, 1], [1, 1]]}),
                "points",
                "points 1 and 2 coincide",
            ),
            (
                json!({"kind": "polygon", "rings": [[[0, 0], [1, 0]]]}),
                "rings",
                "ring 0 has fewer than 3 distinct points",
            ),
            (
                json!({"kind": "polygon", "rings": [[[0, 0], [1, 0], [0, "a"]]]}),
                "rings",
                "ring 0: point 2: y:",
            ),
            (
                json!({"kind": "polygon", "rings": [[[-1, -1], [1, 1], [1, -0.5], [-1, 1]]]}),
                "rings",
                "self-intersecting",
            ),
            (
                json!({"kind": "algebraic", "equation": "x^2 + * y - 1"}),
                "equation",
                "does not parse",
            ),
            (
                json!({"kind": "algebraic", "equation": "x + z"}),
                "equation",
                "does not parse",
            ),
            (
                json!({"kind": "algebraic", "equation": "3"}),
                "equation",
                "constant",
            ),
            (
                json!({"kind": "algebraic", "equation": "x", "clip": [1, 1, 0, 0]}),
                "clip",
                "inverted",
            ),
            (
                json!({"kind": "field", "equation": "x^2 + z"}),
                "equation",
                "does not parse",
            ),
            (
                json!({"kind": "implicit_field", "equation": "x^2 + y^2"}),
                "equation",
                "must involve z",
            ),
            (
                json!({"kind": "implicit_field", "equation": 5}),
                "equation",
                "expected a string",
            ),
            (
                json!({"kind": "bezier", "control_points": [[0, 0]]}),
                "control_points",
                "at least 2",
            ),
            (
                json!({"kind": "bezier", "control_points": [[0, 0], [0, 0]]}),
                "control_points",
                "coincide",
            ),
            (
                json!({"kind": "bezier", "control_points": [[0, 0], [1, 0]], "weights": [1]}),
                "weights",
                "1 weights for 2",
            ),
            (
                json!({"kind": "bezier", "control_points": [[0, 0], [1, 0]], "weights": [1, 0]}),
                "weights",
                "> 0",
            ),
            (
                json!({"kind": "bspline", "degree": 0, "control_points": [[0, 0], [1, 0]], "knots": [0, 1]}),
                "degree",
                ">= 1",
            ),
            (
                json!({"kind": "bspline", "degree": 1.5, "control_points": [[0, 0], [1, 0]], "knots": [0, 1]}),
                "degree",
                "integer",
            ),
            (
                json!({"kind": "bspline", "degree": 1e300, "control_points": [[0, 0], [1, 0]], "knots": [0, 1]}),
                "control_points",
                "needs at least",
            ),
            (
                json!({"kind": "bspline", "degree": 3, "control_points": [[0, 0], [1, 0], [1, 1], [0, 1], [-0.5, 0.5]],
                    "knots": [0, 0, 0, 0, 1, 1, 1, 1]}),
                "knots",
                "8 knots, but degree 3 with 5 control points needs 9",
            ),
            (
                json!({"kind": "bspline", "degree": 1, "control_points": [[0, 0], [1, 0]], "knots": [0, 0, 2, 1]}),
                "knots",
                "non-decreasing",
            ),
            (
                json!({"kind": "bspline", "degree": 1, "control_points": [[0, 0], [1, 0]], "knots": [0, 1, 1, 2]}),
                "knots",
                "is empty",
            ),
            (
                json!({"kind": "bspline", "degree": 1, "control_points": [[0, 0], [1, 0]], "knots": [0, 0, 1, 1], "closed": 1}),
                "closed",
                "true or false",
            ),
        ] {
            let (f, message) = site_refusal(site.clone());
            assert_eq!(f, field, "{site}: {message}");
            assert!(message.contains(needle), "{site}: {message}");
        }
    }

    #[test]
    fn duplicate_points() {
        let v = json!({"domain": [-2, -2, 2, 2], "sites": [
            {"kind": "point", "at": [0, 0]},
            {"kind": "point", "at": [1, 0]},
            {"kind": "point", "at": [-0.0, 0]}
        ]});
        let (site, field, message) = refusal(v);
        assert_eq!(
            (site, field.as_str(), message.as_str()),
            (Some(2), "at", "duplicate of site 0")
        );
        // The same location under another metric is a different site.
        let v = json!({"domain": [-2, -2, 2, 2], "sites": [
            {"kind": "point", "at": [0, 0]},
            {"kind": "point", "at": [0, 0], "metric": {"kind": "power", "weight": 0.1}}
        ]});
        assert!(scene_from_value(&v).is_ok());
        // The first repeating site is named, with the first earlier site it repeats.
        let v = json!({"domain": [-2, -2, 2, 2], "sites": [
            {"kind": "point", "at": [0, 0], "metric": {"kind": "power", "weight": 0.1}},
            {"kind": "point", "at": [1, 1]},
            {"kind": "point", "at": [0, 0]},
            {"kind": "circle", "center": [1, 1], "radius": 0.5},
            {"kind": "point", "at": [0, 0]},
            {"kind": "point", "at": [0, 0], "metric": {"kind": "power", "weight": 0.1}},
            {"kind": "point", "at": [1, 1]}
        ]});
        let (site, _, message) = refusal(v);
        assert_eq!((site, message.as_str()), (Some(4), "duplicate of site 2"));
    }

    #[test]
    fn error_display_names_site_and_field() {
        let e = scene_from_value(&scene_with(
            json!({"kind": "segment", "from": [0, 0], "to": [0, 0]}),
        ))
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "site 1 field 'to': zero-length segment (from == to)"
        );
    }
}
