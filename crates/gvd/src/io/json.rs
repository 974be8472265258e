//! The diagram as JSON (`SCENE_FORMAT.md`, "Diagram"): points are `[x, y]` arrays.

use crate::complex::VoronoiComplex;
use crate::error::Error;
use crate::geom::Point;

/// Reads a diagram. Refuses invalid JSON, missing or mistyped required fields and
/// non-finite coordinates with [`Error::Diagram`]; structural consistency (indices,
/// end points) is left to [`crate::verify`], which reports it per edge.
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::{Edge, Generator, Vertex};

    #[test]
    fn round_trip_and_errors() {
        let d = VoronoiComplex {
            vertices: vec![Vertex {
                at: Point::new(0.1, -0.2),
                sites: vec![Generator::Site(0), Generator::Site(3), Generator::Site(7)],
            }],
            edges: vec![Edge {
                sites: [Generator::Site(0), Generator::Site(3)],
                from: Some(0),
                to: None,
                points: vec![Point::new(0.1, -0.2), Point::new(1.0 / 3.0, 2.0)],
            }],
            ..Default::default()
        };
        let text = write_diagram(&d);
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
}
