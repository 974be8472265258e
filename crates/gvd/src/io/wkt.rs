//! Well-known text in and out.
//!
//! In: one geometry per line (or one `GEOMETRYCOLLECTION`): `POINT` and `MULTIPOINT`
//! become points, `LINESTRING` and `MULTILINESTRING` polylines, `POLYGON` and
//! `MULTIPOLYGON` polygons with holes (the closing point of each ring dropped). Z and M
//! values are ignored; empty geometries are skipped with a warning. The domain is the
//! sites' bounding box grown by a tenth unless [`ReadOptions`] sets it.
//!
//! Out: [`write_diagram`] gives three lines: the vertices as a `MULTIPOINT`, the edges as
//! a `MULTILINESTRING` and the cells as a `MULTIPOLYGON` (rings closed, as WKT wants).

use super::read::{build_scene, open_ring, FileValues, Found, ReadOptions};
use crate::complex::VoronoiComplex;
use crate::error::Error;
use crate::geom::Point;
use crate::scene::{Scene, Site};
use std::fmt::Write;
use wkt::types::{Coord, LineString, Polygon};
use wkt::Wkt;

/// Reads a scene from WKT text.
pub fn read_scene(text: &str, options: &ReadOptions) -> Result<(Scene, Vec<String>), Error> {
    let mut found = Vec::new();
    let mut warnings = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let origin = format!("line {}", k + 1);
        let geometry: Wkt<f64> = line
            .parse()
            .map_err(|e| Error::Json(format!("WKT, {origin}: {e}")))?;
        let before = found.len();
        add(&geometry, &origin, &mut found);
        if found.len() == before {
            warnings.push(format!("{origin}: an empty geometry, skipped"));
        }
    }
    Ok((
        build_scene(found, FileValues::default(), options)?,
        warnings,
    ))
}

fn xy(c: &Coord<f64>) -> Point {
    Point::new(c.x, c.y)
}

fn line(l: &LineString<f64>) -> Vec<Point> {
    l.coords().iter().map(xy).collect()
}

fn polygon(p: &Polygon<f64>) -> Option<Site> {
    let rings: Vec<Vec<Point>> = p.rings().iter().map(|r| open_ring(line(r))).collect();
    (!rings.is_empty()).then(|| Site::polygon(rings))
}

fn add(g: &Wkt<f64>, origin: &str, found: &mut Vec<Found>) {
    let mut push = |site: Site| {
        found.push(Found {
            site,
            origin: origin.to_string(),
        })
    };
    match g {
        Wkt::Point(p) => p.coord().into_iter().for_each(|c| push(Site::point(xy(c)))),
        Wkt::MultiPoint(m) => m
            .points()
            .iter()
            .filter_map(|p| p.coord())
            .for_each(|c| push(Site::point(xy(c)))),
        Wkt::LineString(l) if !l.coords().is_empty() => push(Site::polyline(line(l))),
        Wkt::LineString(_) => {}
        Wkt::MultiLineString(m) => m
            .line_strings()
            .iter()
            .filter(|l| !l.coords().is_empty())
            .for_each(|l| push(Site::polyline(line(l)))),
        Wkt::Polygon(p) => polygon(p).into_iter().for_each(push),
        Wkt::MultiPolygon(m) => m.polygons().iter().filter_map(polygon).for_each(push),
        Wkt::GeometryCollection(c) => {
            for g in c.geometries() {
                add(g, origin, found);
            }
        }
    }
}

fn coords(out: &mut String, pts: impl Iterator<Item = Point>) {
    out.push('(');
    for (k, p) in pts.enumerate() {
        if k > 0 {
            out.push_str(", ");
        }
        // writing to a String cannot fail
        let _ = write!(out, "{:?} {:?}", p.x, p.y);
    }
    out.push(')');
}

/// The diagram as three WKT lines: `MULTIPOINT` (vertices), `MULTILINESTRING` (edges),
/// `MULTIPOLYGON` (cells); an empty list is written as `... EMPTY`.
pub fn write_diagram(diagram: &VoronoiComplex) -> String {
    let mut out = String::new();
    let list =
        |out: &mut String, name: &str, n: usize, item: &mut dyn FnMut(&mut String, usize)| {
            out.push_str(name);
            if n == 0 {
                out.push_str(" EMPTY\n");
                return;
            }
            out.push_str(" (");
            for k in 0..n {
                if k > 0 {
                    out.push_str(", ");
                }
                item(out, k);
            }
            out.push_str(")\n");
        };
    list(
        &mut out,
        "MULTIPOINT",
        diagram.vertices.len(),
        &mut |o, k| coords(o, std::iter::once(diagram.vertices[k].at)),
    );
    list(
        &mut out,
        "MULTILINESTRING",
        diagram.edges.len(),
        &mut |o, k| coords(o, diagram.edges[k].points.iter().copied()),
    );
    list(
        &mut out,
        "MULTIPOLYGON",
        diagram.cells.len(),
        &mut |o, k| {
            o.push('(');
            for (r, ring) in diagram.cells[k].rings.iter().enumerate() {
                if r > 0 {
                    o.push_str(", ");
                }
                coords(o, ring.iter().chain(ring.first()).copied());
            }
            o.push(')');
        },
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SiteKind;

    #[test]
    fn reads_lines_of_geometries() {
        let text = "POINT (0 0)\n# a comment\nMULTIPOINT ((1 1), (2 0))\n\
            LINESTRING (3 0, 4 1, 5 0)\n\
            POLYGON ((10 0, 20 0, 20 10, 10 10, 10 0), (12 2, 12 4, 14 4, 14 2, 12 2))\n\
            POINT EMPTY\n";
        let (scene, warnings) = read_scene(text, &ReadOptions::default()).unwrap();
        let kinds: Vec<&str> = scene.sites().iter().map(|s| s.kind.name()).collect();
        assert_eq!(kinds, ["point", "point", "point", "polyline", "polygon"]);
        assert_eq!(warnings, ["line 6: an empty geometry, skipped"]);
        let SiteKind::Polygon { rings } = &scene.sites()[4].kind else {
            panic!()
        };
        assert_eq!((rings.len(), rings[0].len()), (2, 4));
        match read_scene(
            "POINT (0 0)\nLINESTRING (1 1, 1 1)\n",
            &ReadOptions::default(),
        ) {
            Err(Error::Site {
                site: 1, message, ..
            }) => assert!(message.contains("line 2")),
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            read_scene("POLYGON ((0 0, 1", &ReadOptions::default()),
            Err(Error::Json(_))
        ));
    }

    #[test]
    fn writes_what_it_reads() {
        let text = "MULTIPOINT ((0 0), (1 0), (0 1), (1.5 1.25))\n";
        let (scene, _) = read_scene(text, &ReadOptions::default()).unwrap();
        let d = crate::compute(&scene, &Default::default()).unwrap();
        let out = write_diagram(&d);
        let lines: Vec<Wkt<f64>> = out.lines().map(|l| l.parse().unwrap()).collect();
        let Wkt::MultiLineString(edges) = &lines[1] else {
            panic!("{out}")
        };
        assert_eq!(edges.line_strings().len(), d.edges.len());
        let Wkt::MultiPolygon(cells) = &lines[2] else {
            panic!("{out}")
        };
        assert_eq!(cells.polygons().len(), 4);
    }
}
