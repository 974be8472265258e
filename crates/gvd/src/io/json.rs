//! The diagram as JSON (`SCENE_FORMAT.md`, "Diagram"): points are `[x, y]` arrays.

use crate::complex::VoronoiComplex;
use crate::error::Error;
use crate::geom::Point;
use crate::scene::{Metric, Scene, SiteKind};
use serde_json::{json, Value};

/// Reads a diagram. Refuses invalid JSON, missing or mistyped required fields and
/// non-finite coordinates with [`Error::Diagram`]; structural consistency (indices,
/// end points) is left to [`crate::verify()`], which reports it per edge.
pub fn read_diagram(text: &str) -> Result<VoronoiComplex, Error> {
    let d: VoronoiComplex =
        serde_json::from_str(text).map_err(|e| Error::Diagram(e.to_string()))?;
    let finite = |p: &Point| p.x.is_finite() && p.y.is_finite();
    if let Some(k) = d.vertices.iter().position(|v| !finite(&v.at)) {
        return Err(Error::Diagram(format!("vertex {k}: 'at' is not finite")));
    }
    for (k, e) in d.edges.iter().enumerate() {
        if let Some(i) = e.points.iter().position(|p| !finite(p)) {
            return Err(Error::Diagram(format!("edge {k}: point {i} is not finite")));
        }
    }
    Ok(d)
}

/// Writes a diagram as compact JSON. Numbers are printed in their shortest exact form,
/// so reading the text back gives the same diagram. Algorithms emit finite coordinates
/// only; a non-finite one would be written as `null` and refused on reading.
pub fn write_diagram(diagram: &VoronoiComplex) -> String {
    // serializing plain data to a string cannot fail
    serde_json::to_string(diagram).unwrap_or_default()
}

/// [`write_diagram`] into `out` (the same bytes), without holding the whole text: for
/// large diagrams written to a file. Large lists are formatted in chunks, in parallel
/// with the `parallel` feature. Give a buffered writer; only `out`'s errors are
/// returned.
pub fn write_diagram_to<W: std::io::Write>(
    diagram: &VoronoiComplex,
    out: &mut W,
) -> std::io::Result<()> {
    // The field order and the skipped empty `cells` and `site_ids` of `VoronoiComplex`'s derive.
    out.write_all(b"{\"vertices\":")?;
    write_list(&diagram.vertices, out)?;
    out.write_all(b",\"edges\":")?;
    write_list(&diagram.edges, out)?;
    if !diagram.cells.is_empty() {
        out.write_all(b",\"cells\":")?;
        write_list(&diagram.cells, out)?;
    }
    if !diagram.site_ids.is_empty() {
        out.write_all(b",\"site_ids\":")?;
        serde_json::to_writer(&mut *out, &diagram.site_ids)?;
    }
    out.write_all(b",\"stats\":")?;
    serde_json::to_writer(&mut *out, &diagram.stats)?;
    out.write_all(b"}")
}

/// A JSON array of `items`, as serde_json writes it: chunks formatted into buffers (in
/// parallel, a bounded number at a time, the buffers reused), then written in order.
fn write_list<T: serde::Serialize + Sync, W: std::io::Write>(
    items: &[T],
    out: &mut W,
) -> std::io::Result<()> {
    const CHUNK: usize = 1 << 14;
    const BATCH: usize = 16;
    let format = |(chunk, buf): (&[T], &mut Vec<u8>)| {
        buf.clear();
        for item in chunk {
            buf.push(b',');
            // plain data into a vector: cannot fail
            serde_json::to_writer(&mut *buf, item).unwrap_or_default();
        }
    };
    let mut bufs: Vec<Vec<u8>> = vec![Vec::new(); BATCH.min(items.len().div_ceil(CHUNK))];
    out.write_all(b"[")?;
    for (b, batch) in items.chunks(CHUNK * BATCH).enumerate() {
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            batch
                .par_chunks(CHUNK)
                .zip(bufs.par_iter_mut())
                .for_each(format);
        }
        #[cfg(not(feature = "parallel"))]
        batch.chunks(CHUNK).zip(bufs.iter_mut()).for_each(format);
        let used = batch.len().div_ceil(CHUNK);
        for (k, buf) in bufs[..used].iter().enumerate() {
            // no comma before the first item
            let skip = usize::from(b == 0 && k == 0);
            out.write_all(&buf[skip..])?;
        }
    }
    out.write_all(b"]")
}

/// Writes a scene in the scene format (`docs/SCENE_FORMAT.md`): what
/// [`Scene::from_json`] reads back as the same scene. Scenes read from other formats
/// (GeoJSON, WKT, DXF) or built in code are converted this way.
pub fn write_scene(scene: &Scene) -> String {
    let xy = |p: &Point| json!([p.x, p.y]);
    let list = |ps: &[Point]| Value::Array(ps.iter().map(xy).collect());
    let sites: Vec<Value> = scene
        .sites()
        .iter()
        .map(|s| {
            let mut v = match &s.kind {
                SiteKind::Point { at, metric } => {
                    let metric = match metric {
                        Metric::Euclidean => json!({"kind": "euclidean"}),
                        Metric::Lp { p } => json!({"kind": "lp", "p": p}),
                        Metric::Anisotropic { matrix, weight } => {
                            json!({"kind": "anisotropic", "matrix": matrix, "weight": weight})
                        }
                        Metric::Power { weight } => json!({"kind": "power", "weight": weight}),
                        Metric::Moebius { scale, weight } => {
                            json!({"kind": "moebius", "scale": scale, "weight": weight})
                        }
                    };
                    json!({"at": xy(at), "metric": metric})
                }
                SiteKind::Circle { center, radius } => {
                    json!({"center": xy(center), "radius": radius})
                }
                SiteKind::Ellipse {
                    center,
                    semi_axes,
                    rotation,
                } => json!({"center": xy(center), "semi_axes": semi_axes, "rotation": rotation}),
                SiteKind::Segment { from, to } => json!({"from": xy(from), "to": xy(to)}),
                SiteKind::Arc {
                    center,
                    radius,
                    start_angle,
                    end_angle,
                } => json!({"center": xy(center), "radius": radius,
                            "start_angle": start_angle, "end_angle": end_angle}),
                SiteKind::Polyline { points } => json!({"points": list(points)}),
                SiteKind::Polygon { rings } => {
                    json!({"rings": rings.iter().map(|r| list(r)).collect::<Vec<_>>()})
                }
                SiteKind::Algebraic { equation, clip } => {
                    let mut v = json!({"equation": equation.text()});
                    if let Some(c) = clip {
                        v["clip"] = json!(c.to_array());
                    }
                    v
                }
                SiteKind::Bezier {
                    control_points,
                    weights,
                } => {
                    let mut v = json!({"control_points": list(control_points)});
                    if let Some(w) = weights {
                        v["weights"] = json!(w);
                    }
                    v
                }
                SiteKind::Bspline {
                    degree,
                    control_points,
                    knots,
                    weights,
                    closed,
                } => {
                    let mut v = json!({"degree": degree, "control_points": list(control_points),
                                       "knots": knots, "closed": closed});
                    if let Some(w) = weights {
                        v["weights"] = json!(w);
                    }
                    v
                }
                SiteKind::Field { equation } | SiteKind::ImplicitField { equation } => {
                    json!({"equation": equation.text()})
                }
            };
            v["kind"] = json!(s.kind.name());
            if let Some(id) = &s.id {
                v["id"] = json!(id);
            }
            v
        })
        .collect();
    let mode = scene.mode().name();
    let v = json!({
        "domain": scene.domain().to_array(),
        "epsilon": scene.epsilon(),
        "mode": mode,
        "sites": sites,
    });
    // serializing plain data cannot fail
    serde_json::to_string(&v).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::{smallvec, Edge, Generator, Vertex};

    #[test]
    fn a_written_scene_reads_back_the_same() {
        use crate::scene::{Mode, Site};
        let scene = Scene::new(
            crate::Aabb::from_array([-3.0, -3.0, 3.0, 3.0]),
            1e-3,
            Mode::Complex,
            vec![
                Site::point_with([0.1, 0.2], Metric::Lp { p: 4 }).with_id("a"),
                Site::point_with(
                    [2.0, 2.0],
                    Metric::Moebius {
                        scale: 2.0,
                        weight: 0.5,
                    },
                ),
                Site::circle([-2.0, 2.0], 0.25),
                Site::segment([1.0, -1.0], [2.0, -2.5]),
                Site::arc([-1.5, -1.5], 0.5, 0.0, 1.0 / 3.0),
                Site::polyline([[0.0, -2.0], [0.5, -2.5], [1.0, -2.0]]),
                Site::polygon([[[-2.5, 0.0], [-1.5, 0.0], [-2.0, 1.0]]]),
                Site::algebraic("x^2 + y^2 - 0.01", None).unwrap(),
            ],
        )
        .unwrap();
        assert_eq!(Scene::from_json(&write_scene(&scene)).unwrap(), scene);
    }

    #[test]
    fn round_trip_and_errors() {
        let d = VoronoiComplex {
            vertices: vec![Vertex {
                clearance: None,
                at: Point::new(0.1, -0.2),
                sites: smallvec![Generator::Site(0), Generator::Site(3), Generator::Site(7)],
            }],
            edges: vec![Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites: [Generator::Site(0), Generator::Site(3)],
                from: Some(0),
                bisector: Vec::new(),
                parametric: Vec::new(),
                to: None,
                points: smallvec![Point::new(0.1, -0.2), Point::new(1.0 / 3.0, 2.0)],
            }],
            ..Default::default()
        };
        let text = write_diagram(&d);
        let mut streamed = Vec::new();
        write_diagram_to(&d, &mut streamed).unwrap();
        assert_eq!(String::from_utf8(streamed).unwrap(), text);
        assert!(
            text.contains("\"points\":[[0.1,-0.2],[0.3333333333333333,2.0]]"),
            "{text}"
        );
        assert!(text.contains("\"to\":null"));
        assert_eq!(read_diagram(&text).unwrap(), d);
        let missing = r#"{"vertices": [], "edges": [{"sites": [0, 1], "from": null, "to": null}]}"#;
        match read_diagram(missing) {
            Err(Error::Diagram(m)) => assert!(m.contains("missing field `points`"), "{m}"),
            other => panic!("{other:?}"),
        }
        assert!(matches!(read_diagram("[1, 2"), Err(Error::Diagram(_))));
        let huge = r#"{"vertices": [{"at": [1e999, 0], "sites": [0]}], "edges": []}"#;
        assert!(matches!(read_diagram(huge), Err(Error::Diagram(_))));
    }

    #[test]
    fn streamed_text_is_the_same_for_long_and_empty_lists() {
        let mut d = VoronoiComplex::default();
        let mut streamed = Vec::new();
        write_diagram_to(&d, &mut streamed).unwrap();
        assert_eq!(String::from_utf8(streamed).unwrap(), write_diagram(&d));
        // more than one batch of chunks, so buffers are reused
        for i in 0..300_000 {
            let p = Point::new(i as f64 / 7.0, -1.0 / (i as f64 + 1.0));
            d.vertices.push(Vertex {
                clearance: None,
                at: p,
                sites: smallvec![Generator::Site(i), Generator::Site(i + 1)],
            });
            if i % 3 == 0 {
                d.edges.push(Edge {
                    clearance: Vec::new(),
                    sites_along: Vec::new(),
                    sites: [Generator::Site(i), Generator::Site(i + 2)],
                    from: Some(i),
                    bisector: Vec::new(),
                    parametric: Vec::new(),
                    to: None,
                    points: smallvec![p, Point::new(0.5, 1e-300)],
                });
            }
        }
        d.cells.push(crate::complex::Cell {
            site: 3,
            rings: smallvec![vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(0.0, 1.0),
            ]],
        });
        d.stats.insert("seconds".into(), serde_json::json!(0.25));
        let mut streamed = Vec::new();
        write_diagram_to(&d, &mut streamed).unwrap();
        assert_eq!(String::from_utf8(streamed).unwrap(), write_diagram(&d));
    }
}
