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
//! With [`ReadOptions::project`] set to [`Projection::Local`], coordinates are longitude
//! and latitude in degrees, projected to metres by the [`LocalProjection`] about the
//! centre of their bounding box (a `domain` is in degrees too, and becomes the box in
//! metres holding its projection; `epsilon` and `radius` are in metres). The scene
//! carries the projection, and the writers here take every coordinate back to
//! longitude and latitude; clearances and offset distances stay in metres.
//!
//! Out: the diagram as a `FeatureCollection` of vertices (`Point`s with their
//! `generators`, `site_ids` and `clearance`), edges (`LineString`s with `generators`
//! and the end vertices `from`, `to`) and cells (`Polygon`s with `site` and `site_id`),
//! every feature with a `type` property (`vertex`, `edge`, `cell`); offsets as
//! `LineString`s, their arcs as chords within a tolerance.

use super::project::{LocalProjection, Projection};
use super::read::{build_scene, mode_named, open_ring, FileValues, Found, ReadOptions};
use crate::complex::VoronoiComplex;
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::offset::Offset;
use crate::scene::{Scene, Site, SiteKind};
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
    if options.project == Projection::None {
        return Ok((build_scene(found, file, options)?, Vec::new()));
    }
    let projection = project(&mut found)?;
    let options = ReadOptions {
        domain: options.domain.map(|d| projection.forward_box(&d)),
        ..options.clone()
    };
    file.domain = file.domain.map(|d| projection.forward_box(&d));
    let scene = build_scene(found, file, &options)?;
    Ok((scene.with_projection(Some(projection)), Vec::new()))
}

/// The points of the sites GeoJSON gives (points, circles' centres, polylines,
/// polygons).
fn site_points(kind: &mut SiteKind) -> Vec<&mut Point> {
    match kind {
        SiteKind::Point { at, .. } => vec![at],
        SiteKind::Circle { center, .. } => vec![center],
        SiteKind::Polyline { points } => points.iter_mut().collect(),
        SiteKind::Polygon { rings } => rings.iter_mut().flatten().collect(),
        _ => Vec::new(),
    }
}

/// Projects the sites' longitudes and latitudes to metres about the centre of their
/// bounding box; returns the projection.
fn project(found: &mut [Found]) -> Result<LocalProjection, Error> {
    let mut lo = Point::new(f64::INFINITY, f64::INFINITY);
    let mut hi = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for f in found.iter_mut() {
        for p in site_points(&mut f.site.kind) {
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        }
    }
    if lo.x > hi.x {
        return Err(Error::scene("sites", "the file has no site to compute"));
    }
    let projection = LocalProjection::about(&Aabb::new(lo, hi))?;
    for f in found.iter_mut() {
        for p in site_points(&mut f.site.kind) {
            *p = projection.forward(*p);
        }
    }
    Ok(projection)
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

/// A position: the point as it is, or back in longitude and latitude.
fn xy(p: &Point, projection: Option<&LocalProjection>) -> Value {
    let p = projection.map_or(*p, |m| m.inverse(*p));
    json!([p.x, p.y])
}

/// A GeoJSON line (closed: the first point repeated last).
fn line(pts: &[Point], closed: bool, projection: Option<&LocalProjection>) -> Value {
    let mut out: Vec<Value> = pts.iter().map(|p| xy(p, projection)).collect();
    if let (true, Some(first)) = (closed, out.first()) {
        out.push(first.clone());
    }
    Value::Array(out)
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
    let proj = scene.projection();
    let clearances = diagram.clearances(scene);
    let mut features =
        Vec::with_capacity(diagram.vertices.len() + diagram.edges.len() + diagram.cells.len());
    for (k, v) in diagram.vertices.iter().enumerate() {
        let c = clearances[k];
        features.push(feature_of(
            json!({"type": "Point", "coordinates": xy(&v.at, proj)}),
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
            json!({"type": "LineString", "coordinates": line(&e.points, false, proj)}),
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
        let rings: Vec<Value> = c.rings.iter().map(|r| line(r, true, proj)).collect();
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

/// Writes offset curves of `scene`'s diagram as GeoJSON `LineString`s (closed curves
/// repeat their first point), arcs as chords within `tolerance`; properties `type`
/// (`offset`), `distance` and `closed`.
pub fn write_offset(scene: &Scene, offset: &Offset, tolerance: f64) -> String {
    let proj = scene.projection();
    let features = offset
        .curves
        .iter()
        .map(|c| {
            let pts = line(&c.polyline(tolerance), false, proj);
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

    /// The great-circle distance in metres between two (lon, lat) points in degrees.
    fn haversine(a: Point, b: Point) -> f64 {
        let (p1, p2) = (a.y.to_radians(), b.y.to_radians());
        let (dp, dl) = (p2 - p1, (b.x - a.x).to_radians());
        let h = (dp / 2.0).sin().powi(2) + p1.cos() * p2.cos() * (dl / 2.0).sin().powi(2);
        2.0 * super::super::project::EARTH_RADIUS_M * h.sqrt().asin()
    }

    #[test]
    fn longitude_and_latitude_in_and_back_out() {
        let sites = [
            Point::new(5.0, 52.0),
            Point::new(5.6, 52.3),
            Point::new(5.2, 52.5),
        ];
        let text = format!(
            r#"{{"type": "FeatureCollection", "features": [{}]}}"#,
            sites
                .iter()
                .map(|p| format!(
                    r#"{{"type": "Feature", "properties": null, "geometry": {{"type": "Point", "coordinates": [{}, {}]}}}}"#,
                    p.x, p.y
                ))
                .collect::<Vec<_>>()
                .join(", ")
        );
        // the Voronoi vertex of the three, in longitude and latitude, and its clearance
        let vertex = |project: Projection| -> (Point, f64) {
            let options = ReadOptions {
                project,
                ..Default::default()
            };
            let (scene, _) = read_scene(&text, &options).unwrap();
            let d = crate::compute(&scene, &Default::default()).unwrap();
            let k = d
                .vertices
                .iter()
                .position(|v| {
                    let mut s: Vec<usize> = v.sites.iter().map(|g| g.site()).collect();
                    s.dedup();
                    s.len() == 3
                })
                .unwrap();
            let GeoJson::FeatureCollection(fc) = write_diagram(&scene, &d).parse().unwrap() else {
                panic!("not a collection")
            };
            let f = &fc.features[k];
            let Some(GeometryValue::Point { coordinates }) =
                f.geometry.as_ref().map(|g| g.value.clone())
            else {
                panic!("not a point")
            };
            let c = f.properties.as_ref().unwrap()["clearance"]
                .as_f64()
                .unwrap();
            (Point::new(coordinates[0], coordinates[1]), c)
        };
        let (v, clearance) = vertex(Projection::Local);
        let d: Vec<f64> = sites.iter().map(|s| haversine(v, *s)).collect();
        // Within the cap of angle c about the centre the projection stretches lengths
        // by 1 to c / sin c < 1 + c²/6, so great-circle distances are within a factor
        // 1 + c²/6 of the plane's (equal there): c < 0.0045 rad here, 3.4e-6 of the
        // 29 km clearance, 0.1 m; the rest (f64, the engine's exact vertex) is far below
        // 1e-6 m.
        let centre = Point::new(5.3, 52.25);
        let c = sites
            .iter()
            .chain([&v])
            .map(|p| haversine(centre, *p) / super::super::project::EARTH_RADIUS_M)
            .fold(0.0, f64::max);
        let tol = clearance * c * c / 6.0 + 1e-6;
        for (i, di) in d.iter().enumerate() {
            assert!(
                di - clearance <= 1e-6 && clearance - di <= tol,
                "site {i}: {di} m vs clearance {clearance} m"
            );
            for dj in &d[i + 1..] {
                assert!((di - dj).abs() <= tol, "{d:?} (tolerance {tol} m)");
            }
        }
        assert!(tol < 0.2, "{tol}");
        // the same points read as planar degrees: their vertex is far from equidistant
        let (w, _) = vertex(Projection::None);
        let e: Vec<f64> = sites.iter().map(|s| haversine(w, *s)).collect();
        assert!(
            (e[0] - e[1]).abs().max((e[0] - e[2]).abs()) > 100.0,
            "{e:?}"
        );
    }

    #[test]
    fn the_projection_is_refused_near_a_pole() {
        let text = r#"{"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": null, "geometry": {"type": "MultiPoint", "coordinates": [[0, 80], [10, 90]]}}]}"#;
        let options = ReadOptions {
            project: Projection::Local,
            ..Default::default()
        };
        let e = read_scene(text, &options).unwrap_err().to_string();
        assert!(e.contains("poles"), "{e}");
        assert!(read_scene(text, &ReadOptions::default()).is_ok());
    }
}
