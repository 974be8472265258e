//! GeoJSON (RFC 7946) in and out.
//!
//! In: `Point` and `MultiPoint` become points (a `Point` whose feature has a numeric
//! `radius` property becomes a circle), `LineString` and `MultiLineString` polylines,
//! `Polygon` and `MultiPolygon` polygons with holes (the repeated closing point of each
//! ring dropped), `GeometryCollection` its members. A feature's `id` (or its `id`
//! property) becomes the site's id. The collection's foreign members `domain`
//! (`[xmin, ymin, xmax, ymax]`), `epsilon` and `mode` set the scene's, under the
//! caller's [`ReadOptions`].
//!
//! Out: the diagram as a `FeatureCollection` of vertices (`Point`s with their
//! `generators`, `site_ids` and `clearance`), edges (`LineString`s with `generators`
//! and the end vertices `from`, `to`) and cells (`Polygon`s with `site` and `site_id`),
//! every feature with a `type` property (`vertex`, `edge`, `cell`); offsets as
//! `LineString`s, their arcs as chords within a tolerance.

use super::read::{build_scene, mode_named, open_ring, FileValues, Found, ReadOptions};
use crate::complex::VoronoiComplex;
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::offset::Offset;
use crate::scene::{Scene, Site};
use geojson::{GeoJson, Geometry, GeometryValue, Position};
use serde_json::{json, Map, Value};

/// Reads a scene from GeoJSON text.
pub fn read_scene(text: &str, options: &ReadOptions) -> Result<(Scene, Vec<String>), Error> {
    let gj: GeoJson = text
        .parse()
        .map_err(|e| Error::Json(format!("GeoJSON: {e}")))?;
    let mut found = Vec::new();
    let mut file = FileValues::default();
    match gj {
        GeoJson::Geometry(g) => geometry(&g, None, None, "the geometry", &mut found)?,
        GeoJson::Feature(f) => feature(&f, "the feature", &mut found)?,
        GeoJson::FeatureCollection(fc) => {
            if let Some(members) = &fc.foreign_members {
                file = file_values(members)?;
            }
            for (k, f) in fc.features.iter().enumerate() {
                feature(f, &format!("feature {k}"), &mut found)?;
            }
        }
    }
    Ok((build_scene(found, file, options)?, Vec::new()))
}

/// The scene-level values among a collection's foreign members.
fn file_values(members: &Map<String, Value>) -> Result<FileValues, Error> {
    let mut file = FileValues::default();
    if let Some(v) = members.get("domain") {
        let a: [f64; 4] = serde_json::from_value(v.clone())
            .map_err(|_| Error::scene("domain", "expected [xmin, ymin, xmax, ymax]"))?;
        file.domain = Some(Aabb::from_array(a));
    }
    if let Some(v) = members.get("epsilon") {
        file.epsilon = Some(
            v.as_f64()
                .ok_or_else(|| Error::scene("epsilon", "expected a number"))?,
        );
    }
    if let Some(v) = members.get("mode") {
        let name = v
            .as_str()
            .ok_or_else(|| Error::scene("mode", "expected a string"))?;
        file.mode = Some(mode_named(name)?);
    }
    Ok(file)
}

fn feature(f: &geojson::Feature, origin: &str, found: &mut Vec<Found>) -> Result<(), Error> {
    let props = f.properties.as_ref();
    let id = match (&f.id, props.and_then(|p| p.get("id"))) {
        (Some(geojson::feature::Id::String(s)), _) => Some(s.clone()),
        (Some(geojson::feature::Id::Number(n)), _) => Some(n.to_string()),
        (None, Some(Value::String(s))) => Some(s.clone()),
        (None, Some(Value::Number(n))) => Some(n.to_string()),
        _ => None,
    };
    let radius = props.and_then(|p| p.get("radius")).and_then(Value::as_f64);
    match &f.geometry {
        Some(g) => geometry(g, id, radius, origin, found),
        None => Ok(()),
    }
}

fn point(p: &Position, origin: &str) -> Result<Point, Error> {
    match p.as_slice() {
        [x, y, ..] => Ok(Point::new(*x, *y)),
        _ => Err(Error::Json(format!(
            "GeoJSON: {origin}: a position needs two coordinates"
        ))),
    }
}

fn points(ps: &[Position], origin: &str) -> Result<Vec<Point>, Error> {
    ps.iter().map(|p| point(p, origin)).collect()
}

fn polygon(rings: &[Vec<Position>], origin: &str) -> Result<Site, Error> {
    let rings = rings
        .iter()
        .map(|r| points(r, origin).map(open_ring))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Site::polygon(rings))
}

fn geometry(
    g: &Geometry,
    id: Option<String>,
    radius: Option<f64>,
    origin: &str,
    found: &mut Vec<Found>,
) -> Result<(), Error> {
    let mut push = |site: Site| {
        let site = match &id {
            Some(id) => site.with_id(id.clone()),
            None => site,
        };
        found.push(Found {
            site,
            origin: origin.to_string(),
        });
    };
    match &g.value {
        GeometryValue::Point { coordinates } => {
            let at = point(coordinates, origin)?;
            push(match radius {
                Some(r) => Site::circle(at, r),
                None => Site::point(at),
            });
        }
        GeometryValue::MultiPoint { coordinates } => {
            for p in coordinates {
                push(Site::point(point(p, origin)?));
            }
        }
        GeometryValue::LineString { coordinates } => {
            push(Site::polyline(points(coordinates, origin)?))
        }
        GeometryValue::MultiLineString { coordinates } => {
            for l in coordinates {
                push(Site::polyline(points(l, origin)?));
            }
        }
        GeometryValue::Polygon { coordinates } => push(polygon(coordinates, origin)?),
        GeometryValue::MultiPolygon { coordinates } => {
            for p in coordinates {
                push(polygon(p, origin)?);
            }
        }
        GeometryValue::GeometryCollection { geometries } => {
            for g in geometries {
                geometry(g, id.clone(), radius, origin, found)?;
            }
        }
    }
    Ok(())
}

fn xy(p: &Point) -> Value {
    json!([p.x, p.y])
}

/// A closed GeoJSON ring (first point repeated last).
fn closed_ring(ring: &[Point]) -> Value {
    let mut pts: Vec<Value> = ring.iter().map(xy).collect();
    if let Some(first) = ring.first() {
        pts.push(xy(first));
    }
    Value::Array(pts)
}

fn feature_of(geometry: Value, properties: Value) -> Value {
    json!({"type": "Feature", "geometry": geometry, "properties": properties})
}

fn collection(features: Vec<Value>) -> String {
    // serializing plain data cannot fail
    serde_json::to_string(&json!({"type": "FeatureCollection", "features": features}))
        .unwrap_or_default()
}

/// Writes a diagram of `scene` as a GeoJSON FeatureCollection (see the module's
/// documentation for its features and properties).
pub fn write_diagram(scene: &Scene, diagram: &VoronoiComplex) -> String {
    let ids = |gens: &mut dyn Iterator<Item = usize>| -> Value {
        gens.map(|i| {
            scene
                .sites()
                .get(i)
                .and_then(|s| s.id.clone())
                .map_or(Value::Null, Value::String)
        })
        .collect()
    };
    let clearances = diagram.clearances(scene);
    let mut features =
        Vec::with_capacity(diagram.vertices.len() + diagram.edges.len() + diagram.cells.len());
    for (k, v) in diagram.vertices.iter().enumerate() {
        let c = clearances[k];
        features.push(feature_of(
            json!({"type": "Point", "coordinates": xy(&v.at)}),
            json!({
                "type": "vertex",
                "index": k,
                "generators": v.sites,
                "site_ids": ids(&mut v.sites.iter().map(|g| g.site())),
                "clearance": if c.is_finite() { json!(c) } else { Value::Null },
            }),
        ));
    }
    for (k, e) in diagram.edges.iter().enumerate() {
        features.push(feature_of(
            json!({"type": "LineString", "coordinates": e.points.iter().map(xy).collect::<Vec<_>>()}),
            json!({
                "type": "edge",
                "index": k,
                "generators": e.sites,
                "site_ids": ids(&mut e.sites.iter().map(|g| g.site())),
                "from": e.from,
                "to": e.to,
            }),
        ));
    }
    for c in &diagram.cells {
        let rings: Vec<Value> = c.rings.iter().map(|r| closed_ring(r)).collect();
        features.push(feature_of(
            json!({"type": "Polygon", "coordinates": rings}),
            json!({
                "type": "cell",
                "site": c.site,
                "site_id": scene.sites().get(c.site).and_then(|s| s.id.clone()),
            }),
        ));
    }
    collection(features)
}

/// Writes offset curves as GeoJSON `LineString`s (closed curves repeat their first
/// point), arcs as chords within `tolerance`; properties `type` (`offset`), `distance`
/// and `closed`.
pub fn write_offset(offset: &Offset, tolerance: f64) -> String {
    let features = offset
        .curves
        .iter()
        .map(|c| {
            let pts: Vec<Value> = c.polyline(tolerance).iter().map(xy).collect();
            feature_of(
                json!({"type": "LineString", "coordinates": pts}),
                json!({"type": "offset", "distance": offset.distance, "closed": c.closed}),
            )
        })
        .collect();
    collection(features)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SiteKind;

    #[test]
    fn reads_every_geometry_and_the_collection_values() {
        let text = r#"{"type": "FeatureCollection", "mode": "complex", "epsilon": 0.01,
            "features": [
              {"type": "Feature", "id": "a", "properties": {},
               "geometry": {"type": "Point", "coordinates": [0, 0]}},
              {"type": "Feature", "properties": {"radius": 0.5},
               "geometry": {"type": "Point", "coordinates": [5, 5]}},
              {"type": "Feature", "properties": {"id": 7},
               "geometry": {"type": "LineString", "coordinates": [[2, 0], [3, 1], [4, 0]]}},
              {"type": "Feature", "properties": null,
               "geometry": {"type": "Polygon", "coordinates": [
                 [[10, 0], [20, 0], [20, 10], [10, 10], [10, 0]],
                 [[12, 2], [12, 4], [14, 4], [14, 2], [12, 2]]]}},
              {"type": "Feature", "properties": null,
               "geometry": {"type": "MultiPoint", "coordinates": [[0, 8], [1, 9]]}}
            ]}"#;
        let (scene, _) = read_scene(text, &ReadOptions::default()).unwrap();
        assert_eq!(scene.mode(), crate::Mode::Complex);
        assert_eq!(scene.epsilon(), 0.01);
        let kinds: Vec<&str> = scene.sites().iter().map(|s| s.kind.name()).collect();
        assert_eq!(
            kinds,
            ["point", "circle", "polyline", "polygon", "point", "point"]
        );
        assert_eq!(scene.sites()[0].id.as_deref(), Some("a"));
        assert_eq!(scene.sites()[2].id.as_deref(), Some("7"));
        match &scene.sites()[3].kind {
            SiteKind::Polygon { rings } => {
                assert_eq!(rings.len(), 2);
                assert_eq!(rings[0].len(), 4, "the closing point is dropped");
            }
            other => panic!("{other:?}"),
        }
        // the default domain: the bounding box [0, 0, 20, 10] grown by 2
        assert_eq!(scene.domain().to_array(), [-2.0, -2.0, 22.0, 12.0]);
    }

    #[test]
    fn refusals_name_the_site_and_the_feature() {
        let text = r#"{"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": null, "geometry": {"type": "Point", "coordinates": [0, 0]}},
            {"type": "Feature", "properties": null,
             "geometry": {"type": "Polygon", "coordinates": [[[0, 1], [1, 1], [0, 1]]]}}]}"#;
        match read_scene(text, &ReadOptions::default()) {
            Err(Error::Site {
                site,
                field,
                message,
            }) => {
                assert_eq!(site, 1);
                assert!(field.starts_with("rings"), "{field}");
                assert!(message.contains("(feature 1)"), "{message}");
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            read_scene("{", &ReadOptions::default()),
            Err(Error::Json(_))
        ));
    }

    #[test]
    fn a_written_diagram_reads_back_as_geojson() {
        let scene = Scene::new(
            Aabb::from_array([-2.0, -2.0, 2.0, 2.0]),
            1e-3,
            crate::Mode::Voronoi,
            vec![
                Site::point([0.0, 0.0]).with_id("o"),
                Site::point([1.0, 0.2]),
                Site::point([0.3, 1.1]),
            ],
        )
        .unwrap();
        let d = crate::compute(&scene, &Default::default()).unwrap();
        let text = write_diagram(&scene, &d);
        let gj: GeoJson = text.parse().unwrap();
        let GeoJson::FeatureCollection(fc) = gj else {
            panic!("not a collection")
        };
        assert_eq!(
            fc.features.len(),
            d.vertices.len() + d.edges.len() + d.cells.len()
        );
        let vertex = &fc.features[0];
        let c = vertex.properties.as_ref().unwrap()["clearance"]
            .as_f64()
            .unwrap();
        assert!((c - d.vertices[0].at.dist(Point::new(0.0, 0.0))).abs() < 1e-12);
        assert!(text.contains("\"site_id\":\"o\""));
    }
}
