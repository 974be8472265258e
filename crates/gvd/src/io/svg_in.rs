//! SVG drawings in (XML by `roxmltree`, attribute syntax by `svgtypes`).
//!
//! Shapes: `line` becomes a segment, `polyline` a polyline, `polygon` and `rect` a
//! polygon (a rounded `rect` a closed path), `circle` and `ellipse` two half-circle arcs
//! when drawn round (as DXF circles), else an `ellipse` site. A `path` (every command,
//! absolute and relative) is read subpath by subpath: `C`/`S` cubic and `Q`/`T`
//! quadratic pieces are `bezier` sites, and `A` pieces `arc` sites when drawn round,
//! else rational quadratic `bezier` sites of at most a quarter turn each (a conic is
//! exactly such a curve, weights `1, cos(δ/2), 1`; Farin02). A subpath holding a
//! `bezier` site (a glyph's outline) is one chain of `bezier` sites, its lines of
//! degree 1 and its arcs rational quadratics, for the free-form engine; otherwise a
//! closed subpath of straight pieces is a polygon, and straight runs are polylines
//! (segments for one piece). `transform`s of the element and its ancestors (every SVG transform) are
//! applied, exactly for points and control points; `y` is flipped so that the picture
//! keeps its orientation with `y` up (the scene of a drawing we wrote reads back where
//! it was). The element's `id` becomes the sites' id. Lengths take `px` and absolute
//! units (96 per inch); relative units are refused. Content of `defs`, `clipPath`,
//! `mask`, `marker`, `pattern` and `symbol` is not drawn and not read; other elements
//! (`text`, `image`, `use`, …) are listed in a warning.

use super::read::{build_scene, snap_to_arc_ends, FileValues, Found, ReadOptions};
use crate::error::Error;
use crate::geom::Point;
use crate::scene::{Scene, Site};
use std::collections::BTreeMap;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use svgtypes::{Length, LengthUnit, PathParser, PathSegment, PointsParser};

/// The affine map `(x, y) ↦ (a x + c y + e, b x + d y + f)`, SVG's `matrix(a b c d e f)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Affine([f64; 6]);

impl Affine {
    /// The flip `y ↦ −y` from SVG's downward `y` to the scene's upward one.
    const FLIP: Affine = Affine([1.0, 0.0, 0.0, -1.0, 0.0, 0.0]);

    /// `outer ∘ self`: this map first, then `outer`.
    fn then(self, outer: Affine) -> Affine {
        let [a, b, c, d, e, f] = self.0;
        let [oa, ob, oc, od, oe, of] = outer.0;
        Affine([
            oa * a + oc * b,
            ob * a + od * b,
            oa * c + oc * d,
            ob * c + od * d,
            oa * e + oc * f + oe,
            ob * e + od * f + of,
        ])
    }

    fn apply(&self, p: Point) -> Point {
        let [a, b, c, d, e, f] = self.0;
        Point::new(a * p.x + c * p.y + e, b * p.x + d * p.y + f)
    }

    /// The linear part's columns: the images of the unit vectors.
    fn columns(&self) -> [Point; 2] {
        let [a, b, c, d, ..] = self.0;
        [Point::new(a, b), Point::new(c, d)]
    }

    /// The map with its linear part multiplied by `diag(sx, sy)` on the right.
    fn scaled(self, sx: f64, sy: f64) -> Affine {
        let [a, b, c, d, e, f] = self.0;
        Affine([a * sx, b * sx, c * sy, d * sy, e, f])
    }

    /// The map `p ↦ center + R(phi) p`, then this one.
    fn after_placing(self, center: Point, phi: f64) -> Affine {
        let (s, c) = phi.sin_cos();
        Affine([c, s, -s, c, center.x, center.y]).then(self)
    }

    /// When the linear part is a similarity (orthogonal columns of one length, within
    /// rounding): its scale, the angle of its first column and the sign of its
    /// determinant (a circle's image is then a circle).
    fn similarity(&self) -> Option<(f64, f64, f64)> {
        let [u, v] = self.columns();
        let (lu, lv) = (u.norm(), v.norm());
        let tol = 1e-12 * lu.max(lv);
        ((lu - lv).abs() <= tol && u.dot(v).abs() <= tol * lu.max(lv) && lu > 0.0)
            .then(|| (lu, u.y.atan2(u.x), u.cross(v).signum()))
    }
}

/// The transform of an element's `transform` attribute (identity when absent).
fn transform_of(node: roxmltree::Node, origin: &str) -> Result<Affine, Error> {
    let Some(text) = node.attribute("transform") else {
        return Ok(Affine([1.0, 0.0, 0.0, 1.0, 0.0, 0.0]));
    };
    let t: svgtypes::Transform = text
        .parse()
        .map_err(|e| Error::Json(format!("SVG: {origin}: attribute 'transform': {e}")))?;
    Ok(Affine([t.a, t.b, t.c, t.d, t.e, t.f]))
}

/// The number of a length attribute in user units (`default` when absent): plain
/// numbers and `px`, absolute units at 96 per inch; relative units are refused.
fn length(node: roxmltree::Node, name: &str, default: f64, origin: &str) -> Result<f64, Error> {
    let Some(text) = node.attribute(name) else {
        return Ok(default);
    };
    let bad = |m: String| Error::Json(format!("SVG: {origin}: attribute '{name}': {m}"));
    let l: Length = text.trim().parse().map_err(|e| bad(format!("{e}")))?;
    let per = match l.unit {
        LengthUnit::None | LengthUnit::Px => 1.0,
        LengthUnit::In => 96.0,
        LengthUnit::Cm => 96.0 / 2.54,
        LengthUnit::Mm => 96.0 / 25.4,
        LengthUnit::Pt => 96.0 / 72.0,
        LengthUnit::Pc => 16.0,
        LengthUnit::Em | LengthUnit::Ex | LengthUnit::Percent => {
            return Err(bad(format!(
                "'{text}': relative units (%, em, ex) are not read; give user units"
            )))
        }
    };
    let v = l.number * per;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad(format!("'{text}' is not a finite length")))
    }
}

/// The points of a `points` attribute.
fn points_of(node: roxmltree::Node) -> Vec<Point> {
    PointsParser::from(node.attribute("points").unwrap_or(""))
        .map(|(x, y)| Point::new(x, y))
        .collect()
}

/// One piece of a path in the drawing's own coordinates.
#[derive(Clone, Copy, Debug)]
enum Piece {
    Line(Point, Point),
    Cubic([Point; 4]),
    Quad([Point; 3]),
    /// The arc `center + R(phi) (rx cos θ, ry sin θ)` for θ from `start` over `sweep`
    /// (signed).
    Arc {
        center: Point,
        radii: [f64; 2],
        phi: f64,
        start: f64,
        sweep: f64,
    },
}

/// The angle from `u` to `v`, in `(−π, π]`.
fn angle_between(u: Point, v: Point) -> f64 {
    u.cross(v).atan2(u.dot(v))
}

/// SVG's endpoint arc `from → to` in centre form (SVG 1.1, appendix F.6.5): radii
/// scaled up when too small; a straight line for a zero radius; nothing when the ends
/// coincide.
fn endpoint_arc(
    from: Point,
    to: Point,
    radii: [f64; 2],
    phi: f64,
    large: bool,
    sweep_positive: bool,
) -> Option<Piece> {
    if from == to {
        return None;
    }
    let (mut rx, mut ry) = (radii[0].abs(), radii[1].abs());
    if rx == 0.0 || ry == 0.0 {
        return Some(Piece::Line(from, to));
    }
    let (s, c) = phi.sin_cos();
    let h = (from - to) * 0.5;
    let p = Point::new(c * h.x + s * h.y, -s * h.x + c * h.y);
    let lambda = (p.x / rx).powi(2) + (p.y / ry).powi(2);
    if lambda > 1.0 {
        rx *= lambda.sqrt();
        ry *= lambda.sqrt();
    }
    let num = rx * rx * ry * ry - rx * rx * p.y * p.y - ry * ry * p.x * p.x;
    let den = rx * rx * p.y * p.y + ry * ry * p.x * p.x;
    let sign = if large == sweep_positive { -1.0 } else { 1.0 };
    let k = sign * (num / den).max(0.0).sqrt();
    let cp = Point::new(k * rx * p.y / ry, -k * ry * p.x / rx);
    let mid = from.lerp(to, 0.5);
    let center = Point::new(c * cp.x - s * cp.y + mid.x, s * cp.x + c * cp.y + mid.y);
    let u = Point::new((p.x - cp.x) / rx, (p.y - cp.y) / ry);
    let v = Point::new((-p.x - cp.x) / rx, (-p.y - cp.y) / ry);
    let start = u.y.atan2(u.x);
    let mut sweep = angle_between(u, v);
    if !sweep_positive && sweep > 0.0 {
        sweep -= TAU;
    } else if sweep_positive && sweep < 0.0 {
        sweep += TAU;
    }
    Some(Piece::Arc {
        center,
        radii: [rx, ry],
        phi,
        start,
        sweep,
    })
}

/// The pieces of a path's `d`, subpath by subpath, each with whether it was closed.
fn subpaths(d: &str, origin: &str) -> Result<Vec<(Vec<Piece>, bool)>, Error> {
    let mut out: Vec<(Vec<Piece>, bool)> = Vec::new();
    let mut cur: Vec<Piece> = Vec::new();
    let (mut at, mut start) = (Point::new(0.0, 0.0), Point::new(0.0, 0.0));
    // The last control point of a cubic or quadratic piece, for S and T.
    let (mut last_cubic, mut last_quad): (Option<Point>, Option<Point>) = (None, None);
    let flush = |cur: &mut Vec<Piece>, out: &mut Vec<(Vec<Piece>, bool)>, closed: bool| {
        if !cur.is_empty() {
            out.push((std::mem::take(cur), closed));
        }
    };
    for seg in PathParser::from(d) {
        let seg = seg.map_err(|e| Error::Json(format!("SVG: {origin}: attribute 'd': {e}")))?;
        let abs_of = |abs: bool, x: f64, y: f64| {
            if abs {
                Point::new(x, y)
            } else {
                at + Point::new(x, y)
            }
        };
        let (mut cubic_ctrl, mut quad_ctrl) = (None, None);
        match seg {
            PathSegment::MoveTo { abs, x, y } => {
                flush(&mut cur, &mut out, false);
                at = abs_of(abs, x, y);
                start = at;
            }
            PathSegment::LineTo { abs, x, y } => {
                let to = abs_of(abs, x, y);
                cur.push(Piece::Line(at, to));
                at = to;
            }
            PathSegment::HorizontalLineTo { abs, x } => {
                let to = Point::new(if abs { x } else { at.x + x }, at.y);
                cur.push(Piece::Line(at, to));
                at = to;
            }
            PathSegment::VerticalLineTo { abs, y } => {
                let to = Point::new(at.x, if abs { y } else { at.y + y });
                cur.push(Piece::Line(at, to));
                at = to;
            }
            PathSegment::CurveTo {
                abs,
                x1,
                y1,
                x2,
                y2,
                x,
                y,
            } => {
                let (c1, c2, to) = (abs_of(abs, x1, y1), abs_of(abs, x2, y2), abs_of(abs, x, y));
                cur.push(Piece::Cubic([at, c1, c2, to]));
                (at, cubic_ctrl) = (to, Some(c2));
            }
            PathSegment::SmoothCurveTo { abs, x2, y2, x, y } => {
                let c1 = last_cubic.map_or(at, |c| at + (at - c));
                let (c2, to) = (abs_of(abs, x2, y2), abs_of(abs, x, y));
                cur.push(Piece::Cubic([at, c1, c2, to]));
                (at, cubic_ctrl) = (to, Some(c2));
            }
            PathSegment::Quadratic { abs, x1, y1, x, y } => {
                let (c, to) = (abs_of(abs, x1, y1), abs_of(abs, x, y));
                cur.push(Piece::Quad([at, c, to]));
                (at, quad_ctrl) = (to, Some(c));
            }
            PathSegment::SmoothQuadratic { abs, x, y } => {
                let c = last_quad.map_or(at, |c| at + (at - c));
                let to = abs_of(abs, x, y);
                cur.push(Piece::Quad([at, c, to]));
                (at, quad_ctrl) = (to, Some(c));
            }
            PathSegment::EllipticalArc {
                abs,
                rx,
                ry,
                x_axis_rotation,
                large_arc,
                sweep,
                x,
                y,
            } => {
                let to = abs_of(abs, x, y);
                let phi = x_axis_rotation.to_radians();
                cur.extend(endpoint_arc(at, to, [rx, ry], phi, large_arc, sweep));
                at = to;
            }
            PathSegment::ClosePath { .. } => {
                if at != start {
                    cur.push(Piece::Line(at, start));
                }
                flush(&mut cur, &mut out, true);
                at = start;
            }
        }
        (last_cubic, last_quad) = (cubic_ctrl, quad_ctrl);
    }
    flush(&mut cur, &mut out, false);
    Ok(out)
}

/// The sites of an ellipse `center + R(phi) diag(radii) (cos θ, sin θ)` mapped by `t`:
/// two half-circle arcs when the image is round, else an `ellipse` site (the semi-axes
/// and rotation of the image from the singular values of its linear part).
fn ellipse_sites(t: Affine, center: Point, radii: [f64; 2], phi: f64) -> Vec<Site> {
    let m = t.after_placing(center, phi).scaled(radii[0], radii[1]);
    let c = t.apply(center);
    if let Some((r, ..)) = m.similarity() {
        return vec![Site::arc(c, r, 0.0, PI), Site::arc(c, r, PI, TAU)];
    }
    // M = R(β) diag(s1, s2) R(γ): s1, s2 = q ± r, β = (a1 + a2)/2.
    let [m00, m10, m01, m11, ..] = m.0;
    let (e, f, g, h) = (
        (m00 + m11) / 2.0,
        (m00 - m11) / 2.0,
        (m10 + m01) / 2.0,
        (m10 - m01) / 2.0,
    );
    let (q, r) = (e.hypot(h), f.hypot(g));
    let beta = (g.atan2(f) + h.atan2(e)) / 2.0;
    vec![Site::ellipse(c, [q + r, (q - r).abs()], beta)]
}

/// True when `piece` mapped by `t` is read as a `bezier` site: a cubic or quadratic, or
/// an arc that is not drawn round.
fn is_bezier(t: Affine, piece: &Piece) -> bool {
    match *piece {
        Piece::Line(..) => false,
        Piece::Cubic(_) | Piece::Quad(_) => true,
        Piece::Arc { center, phi, .. } => t.after_placing(center, phi).similarity().is_none(),
    }
}

/// The sites of a piece mapped by `t`; with `beziers` every piece is a `bezier` site (a
/// line of degree 1, an arc rational quadratics), else lines are segments and round
/// arcs `arc` sites.
fn curve_sites(t: Affine, piece: &Piece, beziers: bool) -> Vec<Site> {
    match *piece {
        Piece::Line(a, b) if beziers => vec![Site::bezier([t.apply(a), t.apply(b)], None)],
        Piece::Line(a, b) => vec![Site::segment(t.apply(a), t.apply(b))],
        Piece::Cubic(cp) => vec![Site::bezier(cp.map(|p| t.apply(p)), None)],
        Piece::Quad(cp) => vec![Site::bezier(cp.map(|p| t.apply(p)), None)],
        Piece::Arc {
            center,
            radii,
            phi,
            start,
            sweep,
        } => {
            let m = t.after_placing(center, phi).scaled(radii[0], radii[1]);
            if let Some((r, alpha, sigma)) = m.similarity().filter(|_| !beziers) {
                // the point of parameter θ is at angle α + σθ around the image centre
                let (a, b) = (alpha + sigma * start, alpha + sigma * (start + sweep));
                let (from, to) = if b > a { (a, b) } else { (b, a) };
                return vec![Site::arc(m.apply(Point::new(0.0, 0.0)), r, from, to)];
            }
            let n = (sweep.abs() / FRAC_PI_2).ceil().max(1.0) as usize;
            let delta = sweep / n as f64;
            let w = (delta / 2.0).cos();
            (0..n)
                .map(|k| {
                    let (a, b) = (start + k as f64 * delta, start + (k + 1) as f64 * delta);
                    let mid = (a + b) / 2.0;
                    let unit = |th: f64| Point::new(th.cos(), th.sin());
                    let cps = [unit(a), unit(mid) * (1.0 / w), unit(b)].map(|p| m.apply(p));
                    Site::bezier(cps, Some(vec![1.0, w, 1.0]))
                })
                .collect()
        }
    }
}

/// The sites of a path's subpath mapped by `t`. A subpath that holds a `bezier` piece is
/// one chain of `bezier` sites joined end to end (lines of degree 1), for the free-form
/// engine; otherwise straight runs are polylines (segments for one piece) or, closed,
/// a polygon.
fn subpath_sites(t: Affine, pieces: &[Piece], closed: bool) -> Vec<Site> {
    if pieces.iter().any(|p| is_bezier(t, p)) {
        return pieces
            .iter()
            .filter(|p| !matches!(p, Piece::Line(a, b) if t.apply(*a) == t.apply(*b)))
            .flat_map(|p| curve_sites(t, p, true))
            .collect();
    }
    let straight = pieces.iter().all(|p| matches!(p, Piece::Line(..)));
    if closed && straight {
        let mut ring: Vec<Point> = pieces
            .iter()
            .map(|p| match p {
                Piece::Line(a, _) => t.apply(*a),
                _ => unreachable!("straight pieces only"),
            })
            .collect();
        ring.dedup();
        while ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
        return vec![Site::polygon([ring])];
    }
    let mut out = Vec::new();
    let mut run: Vec<Point> = Vec::new();
    let flush = |run: &mut Vec<Point>, out: &mut Vec<Site>| {
        match run.len() {
            0 | 1 => {}
            2 => out.push(Site::segment(run[0], run[1])),
            _ => out.push(Site::polyline(run.clone())),
        }
        run.clear();
    };
    for piece in pieces {
        match *piece {
            Piece::Line(a, b) => {
                let (a, b) = (t.apply(a), t.apply(b));
                if a == b {
                    continue;
                }
                if run.is_empty() {
                    run.push(a);
                }
                run.push(b);
            }
            _ => {
                flush(&mut run, &mut out);
                out.extend(curve_sites(t, piece, false));
            }
        }
    }
    flush(&mut run, &mut out);
    out
}

/// A rounded rectangle as a closed path of lines and quarter arcs.
fn rounded_rect(x: f64, y: f64, w: f64, h: f64, rx: f64, ry: f64) -> String {
    format!(
        "M{} {y} H{} A{rx} {ry} 0 0 1 {} {} V{} A{rx} {ry} 0 0 1 {} {} H{} \
         A{rx} {ry} 0 0 1 {x} {} V{} A{rx} {ry} 0 0 1 {} {y} Z",
        x + rx,
        x + w - rx,
        x + w,
        y + ry,
        y + h - ry,
        x + w - rx,
        y + h,
        x + rx,
        y + h - ry,
        y + ry,
        x + rx,
    )
}

/// Elements whose content is not drawn where it stands.
const NOT_DRAWN: [&str; 10] = [
    "defs", "clipPath", "mask", "marker", "pattern", "symbol", "title", "desc", "metadata", "style",
];

/// Reads one element and its children, with `t` the transform above it.
fn walk(
    node: roxmltree::Node,
    t: Affine,
    doc: &roxmltree::Document,
    found: &mut Vec<Found>,
    skipped: &mut BTreeMap<String, usize>,
) -> Result<(), Error> {
    let tag = node.tag_name().name();
    let pos = doc.text_pos_at(node.range().start);
    let origin = format!("line {} <{tag}>", pos.row);
    let t = transform_of(node, &origin)?.then(t);
    let len = |name: &str, default: f64| length(node, name, default, &origin);
    let mut sites: Vec<Site> = Vec::new();
    match tag {
        "svg" | "g" | "a" | "switch" => {
            for child in node.children().filter(|c| c.is_element()) {
                walk(child, t, doc, found, skipped)?;
            }
        }
        "line" => {
            let a = Point::new(len("x1", 0.0)?, len("y1", 0.0)?);
            let b = Point::new(len("x2", 0.0)?, len("y2", 0.0)?);
            sites.push(Site::segment(t.apply(a), t.apply(b)));
        }
        "polyline" => {
            let pts: Vec<Point> = points_of(node).into_iter().map(|p| t.apply(p)).collect();
            sites.push(Site::polyline(pts));
        }
        "polygon" => {
            let pts: Vec<Point> = points_of(node).into_iter().map(|p| t.apply(p)).collect();
            sites.push(Site::polygon([pts]));
        }
        "rect" => {
            let (x, y, w, h) = (
                len("x", 0.0)?,
                len("y", 0.0)?,
                len("width", 0.0)?,
                len("height", 0.0)?,
            );
            let (rx, ry) = match (node.attribute("rx"), node.attribute("ry")) {
                (None, None) => (0.0, 0.0),
                (Some(_), None) => (len("rx", 0.0)?, len("rx", 0.0)?),
                (None, Some(_)) => (len("ry", 0.0)?, len("ry", 0.0)?),
                _ => (len("rx", 0.0)?, len("ry", 0.0)?),
            };
            let (rx, ry) = (rx.clamp(0.0, w / 2.0), ry.clamp(0.0, h / 2.0));
            if rx > 0.0 && ry > 0.0 {
                for (pieces, closed) in subpaths(&rounded_rect(x, y, w, h, rx, ry), &origin)? {
                    sites.extend(subpath_sites(t, &pieces, closed));
                }
            } else {
                let ring = [(x, y), (x + w, y), (x + w, y + h), (x, y + h)];
                sites.push(Site::polygon(
                    [ring.map(|(x, y)| t.apply(Point::new(x, y)))],
                ));
            }
        }
        "circle" => {
            let c = Point::new(len("cx", 0.0)?, len("cy", 0.0)?);
            let r = len("r", 0.0)?;
            sites.extend(ellipse_sites(t, c, [r, r], 0.0));
        }
        "ellipse" => {
            let c = Point::new(len("cx", 0.0)?, len("cy", 0.0)?);
            let radii = [len("rx", 0.0)?, len("ry", 0.0)?];
            sites.extend(ellipse_sites(t, c, radii, 0.0));
        }
        "path" => {
            for (pieces, closed) in subpaths(node.attribute("d").unwrap_or(""), &origin)? {
                sites.extend(subpath_sites(t, &pieces, closed));
            }
        }
        other if NOT_DRAWN.contains(&other) => {}
        other => *skipped.entry(format!("<{other}>")).or_default() += 1,
    }
    let id = node.attribute("id");
    for site in sites {
        let site = match id {
            Some(id) => site.with_id(id),
            None => site,
        };
        found.push(Found {
            site,
            origin: origin.clone(),
        });
    }
    Ok(())
}

/// Reads a scene from an SVG drawing (see the module's documentation).
pub fn read_scene(text: &str, options: &ReadOptions) -> Result<(Scene, Vec<String>), Error> {
    let doc = roxmltree::Document::parse(text).map_err(|e| Error::Json(format!("SVG: {e}")))?;
    let root = doc.root_element();
    if root.tag_name().name() != "svg" {
        return Err(Error::Json(format!(
            "SVG: the root element is <{}>, not <svg>",
            root.tag_name().name()
        )));
    }
    let mut found = Vec::new();
    let mut skipped = BTreeMap::new();
    walk(root, Affine::FLIP, &doc, &mut found, &mut skipped)?;
    let mut warnings = Vec::new();
    if !skipped.is_empty() {
        let list: Vec<String> = skipped.iter().map(|(k, n)| format!("{k} ×{n}")).collect();
        warnings.push(format!("elements not read: {}", list.join(", ")));
    }
    snap_to_arc_ends(&mut found);
    Ok((
        build_scene(found, FileValues::default(), options)?,
        warnings,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SiteKind;

    fn read(svg: &str) -> Result<(Scene, Vec<String>), Error> {
        read_scene(svg, &ReadOptions::default())
    }

    fn close(a: Point, b: Point) -> bool {
        a.dist(b) < 1e-9
    }

    #[test]
    fn shapes_with_transforms() {
        let (s, warnings) = read(
            r#"<svg xmlns="http://www.w3.org/2000/svg">
              <g transform="translate(10 0) scale(2)">
                <line id="l" x1="0" y1="0" x2="1" y2="0"/>
                <polyline points="0,5 1,6 2,5"/>
              </g>
              <polygon points="20,20 30,20 25,28" transform="matrix(1 0 0 1 0 -40)"/>
              <rect x="40" y="0" width="4" height="2"/>
              <text x="0" y="0">not read</text>
            </svg>"#,
        )
        .unwrap();
        assert_eq!(warnings, ["elements not read: <text> ×1"]);
        let kinds: Vec<&str> = s.sites().iter().map(|x| x.kind.name()).collect();
        assert_eq!(kinds, ["segment", "polyline", "polygon", "polygon"]);
        assert_eq!(s.sites()[0].id.as_deref(), Some("l"));
        // y flipped: SVG's (x, y) is the scene's (x, −y)
        match &s.sites()[0].kind {
            SiteKind::Segment { from, to } => {
                assert_eq!((*from, *to), (Point::new(10.0, 0.0), Point::new(12.0, 0.0)))
            }
            k => panic!("{k:?}"),
        }
        match &s.sites()[1].kind {
            SiteKind::Polyline { points } => assert_eq!(points[1], Point::new(12.0, -12.0)),
            k => panic!("{k:?}"),
        }
        match &s.sites()[2].kind {
            SiteKind::Polygon { rings } => assert_eq!(rings[0][0], Point::new(20.0, 20.0)),
            k => panic!("{k:?}"),
        }
    }

    #[test]
    fn circles_round_and_squashed() {
        let (s, _) = read(
            r#"<svg><circle cx="1" cy="2" r="3" transform="rotate(30) scale(2)"/>
                    <circle cx="20" cy="0" r="1" transform="scale(2 1)"/>
                    <ellipse cx="0" cy="20" rx="2" ry="1" transform="rotate(90)"/></svg>"#,
        )
        .unwrap();
        let kinds: Vec<&str> = s.sites().iter().map(|x| x.kind.name()).collect();
        assert_eq!(kinds, ["arc", "arc", "ellipse", "ellipse"]);
        match s.sites()[0].kind {
            SiteKind::Arc { center, radius, .. } => {
                let a = 30f64.to_radians();
                let want = Point::new(
                    2.0 * (a.cos() - 2.0 * a.sin()),
                    -2.0 * (a.sin() + 2.0 * a.cos()),
                );
                assert!(close(center, want), "{center:?}");
                assert!((radius - 6.0).abs() < 1e-12);
            }
            ref k => panic!("{k:?}"),
        }
        match s.sites()[2].kind {
            SiteKind::Ellipse {
                center,
                semi_axes,
                rotation,
            } => {
                assert!(close(center, Point::new(40.0, 0.0)));
                assert!((semi_axes[0] - 2.0).abs() < 1e-12 && (semi_axes[1] - 1.0).abs() < 1e-12);
                assert!((rotation.sin()).abs() < 1e-12, "{rotation}");
            }
            ref k => panic!("{k:?}"),
        }
        // rotate(90) then the flip: the long axis along y
        match s.sites()[3].kind {
            SiteKind::Ellipse {
                center,
                semi_axes,
                rotation,
            } => {
                assert!(close(center, Point::new(-20.0, 0.0)), "{center:?}");
                assert!((semi_axes[0] - 2.0).abs() < 1e-12);
                assert!(rotation.cos().abs() < 1e-12, "{rotation}");
            }
            ref k => panic!("{k:?}"),
        }
    }

    #[test]
    fn paths_lines_curves_and_arcs() {
        let (s, _) = read(
            r#"<svg>
              <path d="M0 0 h10 v10 H0 z"/>
              <path d="m20 0 l5 0 l0 5"/>
              <path d="M40 0 C41 1 42 1 43 0 S45 -1 46 0 Q47 1 48 0 T50 0"/>
              <path d="M60 0 A5 5 0 0 1 70 0 L80 0"/>
              <path d="M0 40 A4 2 0 0 0 8 40"/>
            </svg>"#,
        )
        .unwrap();
        let kinds: Vec<&str> = s.sites().iter().map(|x| x.kind.name()).collect();
        assert_eq!(
            kinds,
            [
                "polygon", "polyline", "bezier", "bezier", "bezier", "bezier", "arc", "segment",
                "bezier", "bezier"
            ]
        );
        // S reflects the previous control point: (43, 0) + ((43, 0) − (42, 1))
        match &s.sites()[3].kind {
            SiteKind::Bezier { control_points, .. } => {
                assert_eq!(control_points[1], Point::new(44.0, 1.0))
            }
            k => panic!("{k:?}"),
        }
        // the half circle over (60..70, 0), drawn with sweep 1: clockwise on screen,
        // through the top of the picture, which is +y in the scene
        match s.sites()[6].kind {
            SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => {
                assert!(close(center, Point::new(65.0, 0.0)));
                assert!((radius - 5.0).abs() < 1e-12);
                let mid = center
                    + Point::new(
                        ((start_angle + end_angle) / 2.0).cos(),
                        ((start_angle + end_angle) / 2.0).sin(),
                    ) * radius;
                assert!(close(mid, Point::new(65.0, 5.0)), "{mid:?}");
            }
            ref k => panic!("{k:?}"),
        }
        // the segment starts exactly where the arc ends
        let arc_end = match s.sites()[6].kind {
            SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => crate::geom::arc::Arc::from_angles(center, radius, start_angle, end_angle).ends(),
            _ => unreachable!(),
        };
        match s.sites()[7].kind {
            SiteKind::Segment { from, .. } => assert!(arc_end.contains(&from)),
            ref k => panic!("{k:?}"),
        }
        // an elliptical half: two rational quarters on the ellipse ((x−4)/4)² + ((y+40)/2)² = 1
        for site in &s.sites()[8..] {
            let SiteKind::Bezier {
                control_points,
                weights,
            } = &site.kind
            else {
                panic!()
            };
            let w = weights.as_ref().unwrap();
            let bez = crate::geom::bezier::RationalBezier::new(control_points, Some(w));
            for p in bez.sample(16) {
                let e = ((p.x - 4.0) / 4.0).powi(2) + ((p.y + 40.0) / 2.0).powi(2);
                assert!((e - 1.0).abs() < 1e-12, "{p:?}");
            }
        }
    }

    #[test]
    fn a_subpath_with_curves_is_one_chain_of_beziers() {
        // a line, a cubic, a round half circle and the closing line: four kinds of piece
        // in one outline, read as bezier sites joined end to end (lines of degree 1, the
        // arc two rational quarters on its circle); a path of lines and a round arc only
        // keeps its segments and arc
        let (s, _) = read(
            r#"<svg><path d="M0 0 L10 0 C12 0 12 -10 10 -10 A5 5 0 0 0 0 -10 Z"/>
                    <path d="M20 0 L30 0 A5 5 0 0 0 40 0"/></svg>"#,
        )
        .unwrap();
        let kinds: Vec<&str> = s.sites().iter().map(|x| x.kind.name()).collect();
        assert_eq!(
            kinds,
            ["bezier", "bezier", "bezier", "bezier", "bezier", "segment", "arc"]
        );
        let curves: Vec<crate::geom::bezier::RationalBezier> = s.sites()[..5]
            .iter()
            .map(|site| match &site.kind {
                SiteKind::Bezier {
                    control_points,
                    weights,
                } => crate::geom::bezier::RationalBezier::new(control_points, weights.as_deref()),
                k => panic!("{k:?}"),
            })
            .collect();
        let degrees: Vec<usize> = curves.iter().map(|c| c.degree()).collect();
        assert_eq!(degrees, [1, 3, 2, 2, 1]);
        for k in 0..5 {
            let next = &curves[(k + 1) % 5];
            assert!(close(curves[k].eval(1.0), next.eval(0.0)), "joint {k}");
        }
        for c in &curves[2..4] {
            for p in c.sample(16) {
                assert!((p.dist(Point::new(5.0, 10.0)) - 5.0).abs() < 1e-12, "{p:?}");
            }
        }
    }

    #[test]
    fn rounded_rect_and_errors() {
        let (s, _) = read(r#"<svg><rect width="10" height="6" rx="1"/></svg>"#).unwrap();
        let kinds: Vec<&str> = s.sites().iter().map(|x| x.kind.name()).collect();
        assert_eq!(kinds.iter().filter(|k| **k == "arc").count(), 4);
        assert_eq!(kinds.len(), 8);
        for (svg, want) in [
            (
                "<svg><line x1=\"1%\"/></svg>",
                "line 1 <line>: attribute 'x1'",
            ),
            ("<svg><path d=\"M0 0 L\"/></svg>", "attribute 'd'"),
            ("<html/>", "not <svg>"),
            (
                "<svg><g transform=\"skew(1\"/></svg>",
                "attribute 'transform'",
            ),
            ("<svg>", "SVG: "),
            ("<svg/>", "no site"),
        ] {
            let e = read(svg).unwrap_err().to_string();
            assert!(e.contains(want), "{svg}: {e}");
        }
        // a bad site names its element
        let e = read("<svg>\n<polygon points=\"0,0 1,1 2,2\"/></svg>").unwrap_err();
        assert!(e.to_string().contains("line 2 <polygon>"), "{e}");
    }
}
