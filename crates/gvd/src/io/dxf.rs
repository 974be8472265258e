//! AutoCAD DXF (ASCII) in and out, written here: the entities a CAM drawing holds are
//! a few group codes each, and the crates that read every DXF entity pull in image,
//! date and UUID libraries.
//!
//! In (the `ENTITIES` section): `POINT` becomes a point, `LINE` a segment, `ARC` an arc
//! (degrees, counter-clockwise), `CIRCLE` two half-circle arcs (arcs short of a
//! whole turn are what the incremental engine computes), `LWPOLYLINE` and
//! `POLYLINE` (with `VERTEX`es) a polygon when closed without bulges, otherwise their
//! straight runs polylines and their bulged spans arcs: a bulge `b` on the span from
//! `p` to `q` is the arc of included angle `4 atan b` (counter-clockwise for `b > 0`),
//! radius `|pq| / (2 sin(2 atan |b|))`, centre at `(p + q)/2 + (1 − b²)/(4b) · (pq)⊥`.
//! Straight ends within 1e-9 of the drawing's size of an arc's end are moved onto the
//! arc's computed end `center + r (cos a, sin a)`, so that the scene's shared-end rule
//! holds. `SPLINE` becomes a `bspline` site (rational with its weights), a whole
//! `ELLIPSE` an `ellipse` site; elliptical arcs and other entities are listed in a
//! warning. Z is ignored. Binary DXF is refused.
//!
//! Out: offset curves ([`write_offset`]) and diagram edges ([`write_diagram`]) as
//! `LINE` and `ARC` entities in an `ENTITIES`-only file (DXF R12), which CAM software
//! and ezdxf open.

use super::read::{build_scene, snap_to_arc_ends, FileValues, Found, ReadOptions};
use crate::complex::VoronoiComplex;
use crate::error::Error;
use crate::geom::Point;
use crate::offset::{Offset, Primitive};
use crate::scene::{Scene, Site};
use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};
use std::fmt::Write;

/// One entity: its type and its group codes with their values, in order.
struct Entity {
    kind: String,
    groups: Vec<(i32, String)>,
}

impl Entity {
    fn number(&self, code: i32) -> Option<f64> {
        self.groups
            .iter()
            .find(|(c, _)| *c == code)
            .and_then(|(_, v)| v.trim().parse().ok())
    }
    fn point(&self, x: i32, origin: &str) -> Result<Point, Error> {
        match (self.number(x), self.number(x + 10)) {
            (Some(px), Some(py)) => Ok(Point::new(px, py)),
            _ => Err(Error::Json(format!(
                "DXF: {origin}: missing or invalid group codes {x}/{}",
                x + 10
            ))),
        }
    }
    /// Every value of a repeated group code, in order (unparsable ones as NaN, which
    /// the scene's checks refuse).
    fn numbers(&self, code: i32) -> Vec<f64> {
        self.groups
            .iter()
            .filter(|(c, _)| *c == code)
            .map(|(_, v)| v.trim().parse().unwrap_or(f64::NAN))
            .collect()
    }
    fn flags(&self) -> i64 {
        self.number(70).map_or(0, |f| f as i64)
    }
}

/// The entities of the `ENTITIES` section.
fn entities(text: &str) -> Result<Vec<Entity>, Error> {
    let lines: Vec<&str> = text.lines().collect();
    if lines.len() % 2 == 1 && lines.last().is_some_and(|l| !l.trim().is_empty()) {
        return Err(Error::Json("DXF: an odd number of lines".into()));
    }
    let mut pairs = Vec::with_capacity(lines.len() / 2);
    for (k, pair) in lines.chunks(2).enumerate() {
        let [code, value] = pair else { break };
        let code: i32 = code.trim().parse().map_err(|_| {
            Error::Json(format!(
                "DXF: line {}: expected a group code, found '{}'",
                2 * k + 1,
                code.trim().chars().take(40).collect::<String>()
            ))
        })?;
        pairs.push((code, value.trim().to_string()));
    }
    let mut out = Vec::new();
    let mut in_entities = false;
    let mut k = 0;
    while k < pairs.len() {
        let (code, value) = &pairs[k];
        if *code == 0 && value == "SECTION" {
            in_entities = pairs
                .get(k + 1)
                .is_some_and(|(c, v)| *c == 2 && v == "ENTITIES");
        } else if *code == 0 && value == "ENDSEC" {
            in_entities = false;
        } else if *code == 0 && in_entities {
            let mut e = Entity {
                kind: value.clone(),
                groups: Vec::new(),
            };
            while k + 1 < pairs.len() && pairs[k + 1].0 != 0 {
                k += 1;
                e.groups.push(pairs[k].clone());
            }
            out.push(e);
        }
        k += 1;
    }
    Ok(out)
}

/// A vertex of a polyline with the bulge of the span that starts at it.
#[derive(Clone, Copy)]
struct Vertex {
    at: Point,
    bulge: f64,
}

/// The `LWPOLYLINE`'s vertices: each `10` starts one; `20` and `42` belong to it.
fn lw_vertices(e: &Entity) -> Vec<Vertex> {
    let mut out: Vec<Vertex> = Vec::new();
    let mut x = None;
    for (code, value) in &e.groups {
        let v: f64 = value.parse().unwrap_or(f64::NAN);
        match code {
            10 => x = Some(v),
            20 => {
                if let Some(px) = x.take() {
                    out.push(Vertex {
                        at: Point::new(px, v),
                        bulge: 0.0,
                    });
                }
            }
            42 => {
                if let Some(last) = out.last_mut() {
                    last.bulge = v;
                }
            }
            _ => {}
        }
    }
    out
}

/// The arc a bulge `b` makes of the span `p` → `q`, as the site's (centre, radius,
/// counter-clockwise start and end angles).
fn bulge_arc(p: Point, q: Point, b: f64) -> Site {
    let d = q - p;
    let mid = p.lerp(q, 0.5);
    let k = (1.0 - b * b) / (4.0 * b);
    let center = mid + d.perp() * k;
    let radius = center.dist(p);
    let angle = |x: Point| (x.y - center.y).atan2(x.x - center.x);
    let (from, to) = if b > 0.0 { (p, q) } else { (q, p) };
    let start = angle(from);
    let mut end = angle(to);
    if end <= start {
        end += TAU;
    }
    Site::arc(center, radius, start, end)
}

/// The sites of a polyline: a polygon when closed and straight, else its straight runs
/// as polylines and its bulged spans as arcs.
fn polyline_sites(vertices: &[Vertex], closed: bool) -> Vec<Site> {
    let straight = vertices.iter().all(|v| v.bulge == 0.0);
    let mut pts: Vec<Point> = vertices.iter().map(|v| v.at).collect();
    if closed && pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    if closed && straight {
        return vec![Site::polygon([pts])];
    }
    let n = pts.len();
    let spans = if closed { n } else { n.saturating_sub(1) };
    let mut out = Vec::new();
    let mut run: Vec<Point> = Vec::new();
    let flush = |run: &mut Vec<Point>, out: &mut Vec<Site>| {
        if run.len() >= 2 {
            out.push(Site::polyline(std::mem::take(run)));
        }
        run.clear();
    };
    for k in 0..spans {
        let (p, q) = (pts[k], pts[(k + 1) % n]);
        let b = vertices[k].bulge;
        if b == 0.0 || !b.is_finite() {
            if run.is_empty() {
                run.push(p);
            }
            run.push(q);
        } else {
            flush(&mut run, &mut out);
            out.push(bulge_arc(p, q, b));
        }
    }
    flush(&mut run, &mut out);
    if n == 1 {
        out.push(Site::point(pts[0]));
    }
    out
}

/// A `SPLINE`: its control points (`10`/`20`), knots (`40`), weights (`41`, when the
/// rational flag 4 is set or any weight is not 1), degree (`71`) and closed flag (`70`
/// bit 1), as a `bspline` site. A spline given by fit points alone is refused.
fn spline_site(e: &Entity, origin: &str) -> Result<Site, Error> {
    let (xs, ys) = (e.numbers(10), e.numbers(20));
    if xs.is_empty() {
        return Err(Error::Json(format!(
            "DXF: {origin}: a spline given by fit points only is not read; save it with control points"
        )));
    }
    let points: Vec<Point> = xs
        .iter()
        .zip(&ys)
        .map(|(&x, &y)| Point::new(x, y))
        .collect();
    let weights = e.numbers(41);
    let rational = e.flags() & 4 == 4 || weights.iter().any(|&w| w != 1.0);
    let degree = e.number(71).unwrap_or(3.0);
    if !((1.0..=64.0).contains(&degree) && degree.fract() == 0.0) {
        return Err(Error::Json(format!(
            "DXF: {origin}: group code 71 (degree) must be a whole number from 1 to 64, found {degree}"
        )));
    }
    Ok(Site::bspline(
        degree as usize,
        points,
        e.numbers(40),
        (rational && !weights.is_empty()).then_some(weights),
        e.flags() & 1 == 1,
    ))
}

/// A whole `ELLIPSE` (parameters `41`..`42` a full turn) as an `ellipse` site: centre
/// `10`/`20`, major axis end `11`/`21` relative to it, minor-to-major ratio `40`.
/// `None` for an elliptical arc, which is not read.
fn ellipse_site(e: &Entity, origin: &str) -> Result<Option<Site>, Error> {
    let (c, major) = (e.point(10, origin)?, e.point(11, origin)?);
    let ratio = e.number(40).unwrap_or(f64::NAN);
    let (t0, t1) = (e.number(41).unwrap_or(0.0), e.number(42).unwrap_or(TAU));
    let turn = (t1 - t0).abs();
    if (turn - TAU).abs() > 1e-9 && turn != 0.0 {
        return Ok(None);
    }
    let a = major.norm();
    Ok(Some(Site::ellipse(
        c,
        [a, ratio * a],
        major.y.atan2(major.x),
    )))
}

/// Reads a scene from an ASCII DXF file.
pub fn read_scene(data: &[u8], options: &ReadOptions) -> Result<(Scene, Vec<String>), Error> {
    if data.starts_with(b"AutoCAD Binary DXF") {
        return Err(Error::Json(
            "DXF: binary DXF is not read; save the drawing as ASCII DXF".into(),
        ));
    }
    let text = String::from_utf8_lossy(data);
    let all = entities(&text)?;
    let mut found: Vec<Found> = Vec::new();
    let mut skipped: BTreeMap<String, usize> = BTreeMap::new();
    let mut k = 0;
    while k < all.len() {
        let e = &all[k];
        let origin = format!("entity {k} ({})", e.kind);
        let mut push = |site: Site| {
            found.push(Found {
                site,
                origin: origin.clone(),
            })
        };
        match e.kind.as_str() {
            "POINT" => push(Site::point(e.point(10, &origin)?)),
            "LINE" => push(Site::segment(e.point(10, &origin)?, e.point(11, &origin)?)),
            "CIRCLE" => {
                // two half circles: the incremental engine takes arcs short of a turn
                let (c, r) = (e.point(10, &origin)?, e.number(40).unwrap_or(f64::NAN));
                push(Site::arc(c, r, 0.0, PI));
                push(Site::arc(c, r, PI, TAU));
            }
            "ARC" => {
                let start = e.number(50).unwrap_or(f64::NAN);
                let mut end = e.number(51).unwrap_or(f64::NAN);
                if end <= start {
                    end += 360.0;
                }
                push(Site::arc(
                    e.point(10, &origin)?,
                    e.number(40).unwrap_or(f64::NAN),
                    start.to_radians(),
                    end.to_radians(),
                ));
            }
            "LWPOLYLINE" => {
                for s in polyline_sites(&lw_vertices(e), e.flags() & 1 == 1) {
                    push(s);
                }
            }
            "POLYLINE" => {
                let closed = e.flags() & 1 == 1;
                let mut vertices = Vec::new();
                while k + 1 < all.len() && all[k + 1].kind == "VERTEX" {
                    k += 1;
                    let v = &all[k];
                    vertices.push(Vertex {
                        at: v.point(10, &origin)?,
                        bulge: v.number(42).unwrap_or(0.0),
                    });
                }
                if all.get(k + 1).is_some_and(|s| s.kind == "SEQEND") {
                    k += 1;
                }
                for s in polyline_sites(&vertices, closed) {
                    push(s);
                }
            }
            "SPLINE" => push(spline_site(e, &origin)?),
            "ELLIPSE" => match ellipse_site(e, &origin)? {
                Some(site) => push(site),
                None => {
                    *skipped
                        .entry("ELLIPSE (elliptical arcs; whole ellipses are read)".into())
                        .or_default() += 1
                }
            },
            other => *skipped.entry(other.to_string()).or_default() += 1,
        }
        k += 1;
    }
    let mut warnings = Vec::new();
    if !skipped.is_empty() {
        let list: Vec<String> = skipped.iter().map(|(k, n)| format!("{k} ×{n}")).collect();
        warnings.push(format!("entities not read: {}", list.join(", ")));
    }
    snap_to_arc_ends(&mut found);
    Ok((
        build_scene(found, FileValues::default(), options)?,
        warnings,
    ))
}

fn group(out: &mut String, code: i32, value: impl std::fmt::Display) {
    // writing to a String cannot fail
    let _ = write!(out, "{code}\n{value}\n");
}

fn line(out: &mut String, layer: &str, a: Point, b: Point) {
    group(out, 0, "LINE");
    group(out, 8, layer);
    for (c, v) in [
        (10, a.x),
        (20, a.y),
        (30, 0.0),
        (11, b.x),
        (21, b.y),
        (31, 0.0),
    ] {
        group(out, c, format!("{v:?}"));
    }
}

fn primitive(out: &mut String, layer: &str, p: &Primitive) {
    match *p {
        Primitive::Line { from, to } => line(out, layer, from, to),
        Primitive::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            // DXF arcs run counter-clockwise: a clockwise one is the same arc reversed
            let (s, e) = if end_angle < start_angle {
                (end_angle, start_angle)
            } else {
                (start_angle, end_angle)
            };
            if e - s >= TAU {
                group(out, 0, "CIRCLE");
            } else {
                group(out, 0, "ARC");
            }
            group(out, 8, layer);
            for (c, v) in [(10, center.x), (20, center.y), (30, 0.0), (40, radius)] {
                group(out, c, format!("{v:?}"));
            }
            if e - s < TAU {
                group(out, 50, format!("{:?}", s.to_degrees()));
                group(out, 51, format!("{:?}", e.to_degrees()));
            }
        }
    }
}

fn file(body: &str) -> String {
    format!("0\nSECTION\n2\nENTITIES\n{body}0\nENDSEC\n0\nEOF\n")
}

/// The offset curves as `LINE` and `ARC` (or `CIRCLE`) entities on layer `OFFSET`.
pub fn write_offset(offset: &Offset) -> String {
    let mut body = String::new();
    for p in offset.curves.iter().flat_map(|c| &c.primitives) {
        primitive(&mut body, "OFFSET", p);
    }
    file(&body)
}

/// The diagram's edges (the medial axis in `medial_axis` mode) as `LINE` entities on
/// layer `EDGES`, one per polyline segment.
pub fn write_diagram(diagram: &VoronoiComplex) -> String {
    let mut body = String::new();
    for e in &diagram.edges {
        for w in e.points.windows(2) {
            line(&mut body, "EDGES", w[0], w[1]);
        }
    }
    file(&body)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::arc::Arc;
    use crate::scene::SiteKind;

    fn dxf(entities: &str) -> String {
        format!("0\nSECTION\n2\nHEADER\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n{entities}0\nENDSEC\n0\nEOF\n")
    }

    #[test]
    fn a_bulge_of_one_is_a_half_circle() {
        let Site {
            kind:
                SiteKind::Arc {
                    center,
                    radius,
                    start_angle,
                    end_angle,
                },
            ..
        } = bulge_arc(Point::new(1.0, 0.0), Point::new(-1.0, 0.0), 1.0)
        else {
            panic!()
        };
        assert!(center.dist(Point::new(0.0, 0.0)) < 1e-15 && (radius - 1.0).abs() < 1e-15);
        // counter-clockwise from (1, 0) to (-1, 0): through (0, 1)
        assert!(start_angle.abs() < 1e-15 && (end_angle - std::f64::consts::PI).abs() < 1e-15);
        // a quarter turn: b = tan(π/16 · 4 / 4)
        let b = (std::f64::consts::PI / 8.0).tan();
        let Site {
            kind: SiteKind::Arc { center, .. },
            ..
        } = bulge_arc(Point::new(1.0, 0.0), Point::new(0.0, 1.0), b)
        else {
            panic!()
        };
        assert!(center.dist(Point::new(0.0, 0.0)) < 1e-15, "{center:?}");
    }

    #[test]
    fn reads_entities_and_warns_about_the_others() {
        let text = dxf("0\nLINE\n8\n0\n10\n0\n20\n0\n11\n4\n21\n0\n\
             0\nARC\n10\n6\n20\n0\n40\n2\n50\n0\n51\n180\n\
             0\nCIRCLE\n10\n0\n20\n5\n40\n1\n\
             0\nLWPOLYLINE\n90\n4\n70\n1\n10\n10\n20\n0\n10\n14\n20\n0\n10\n14\n20\n3\n10\n10\n20\n3\n\
             0\nLWPOLYLINE\n90\n3\n70\n0\n10\n20\n20\n0\n42\n1\n10\n22\n20\n0\n10\n24\n20\n0\n\
             0\nTEXT\n1\nhello\n0\nHATCH\n0\nTEXT\n");
        let (scene, warnings) = read_scene(text.as_bytes(), &ReadOptions::default()).unwrap();
        let kinds: Vec<&str> = scene.sites().iter().map(|s| s.kind.name()).collect();
        assert_eq!(
            kinds,
            ["segment", "arc", "arc", "arc", "polygon", "arc", "polyline"]
        );
        assert_eq!(warnings, ["entities not read: HATCH ×1, TEXT ×2"]);
        // the polyline's first point is the bulge arc's computed end, to the bit
        let SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } = scene.sites()[5].kind
        else {
            panic!()
        };
        let ends = Arc::from_angles(center, radius, start_angle, end_angle).ends();
        let SiteKind::Polyline { points } = &scene.sites()[6].kind else {
            panic!()
        };
        assert!(ends.contains(&points[0]), "{ends:?} {points:?}");
        assert!(read_scene(b"AutoCAD Binary DXF\r\n", &ReadOptions::default()).is_err());
        assert!(read_scene(dxf("0\nLINE\n10\nx\n").as_bytes(), &ReadOptions::default()).is_err());
    }

    #[test]
    fn splines_and_ellipses() {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let text = dxf(&format!(
            "0\nSPLINE\n70\n12\n71\n2\n72\n6\n73\n3\n\
             40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n40\n1\n\
             10\n1\n20\n0\n30\n0\n41\n1\n10\n1\n20\n1\n30\n0\n41\n{w}\n10\n0\n20\n1\n30\n0\n41\n1\n\
             0\nSPLINE\n70\n8\n71\n1\n40\n0\n40\n0\n40\n1\n40\n1\n10\n3\n20\n0\n10\n4\n20\n1\n\
             0\nELLIPSE\n10\n5\n20\n5\n11\n0\n21\n2\n40\n0.5\n41\n0\n42\n6.283185307179586\n\
             0\nELLIPSE\n10\n9\n20\n9\n11\n1\n21\n0\n40\n0.5\n41\n0\n42\n1.5\n"
        ));
        let (scene, warnings) = read_scene(text.as_bytes(), &ReadOptions::default()).unwrap();
        assert_eq!(
            warnings,
            ["entities not read: ELLIPSE (elliptical arcs; whole ellipses are read) ×1"]
        );
        match &scene.sites()[0].kind {
            SiteKind::Bspline {
                degree,
                control_points,
                knots,
                weights,
                closed,
            } => {
                assert_eq!((*degree, control_points.len(), knots.len()), (2, 3, 6));
                assert_eq!(control_points[1], Point::new(1.0, 1.0));
                assert_eq!(weights.as_deref(), Some(&[1.0, w, 1.0][..]));
                assert!(!closed);
            }
            k => panic!("{k:?}"),
        }
        // not rational: no weights
        assert!(matches!(
            scene.sites()[1].kind,
            SiteKind::Bspline {
                degree: 1,
                weights: None,
                ..
            }
        ));
        match scene.sites()[2].kind {
            SiteKind::Ellipse {
                center,
                semi_axes,
                rotation,
            } => {
                assert_eq!((center, semi_axes), (Point::new(5.0, 5.0), [2.0, 1.0]));
                assert!((rotation - PI / 2.0).abs() < 1e-15);
            }
            ref k => panic!("{k:?}"),
        }
        let fit_only = dxf("0\nSPLINE\n71\n3\n11\n0\n21\n0\n11\n1\n21\n1\n");
        let e = read_scene(fit_only.as_bytes(), &ReadOptions::default()).unwrap_err();
        assert!(e.to_string().contains("fit points only"), "{e}");
        let bad = dxf("0\nSPLINE\n71\n2\n40\n0\n40\n1\n10\n0\n20\n0\n10\n1\n20\n0\n");
        let e = read_scene(bad.as_bytes(), &ReadOptions::default()).unwrap_err();
        assert!(e.to_string().contains("entity 0 (SPLINE)"), "{e}");
    }
}
