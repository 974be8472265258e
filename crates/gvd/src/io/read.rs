//! Scenes from files of every format: the format by name or extension, the options a
//! caller sets over the file's, and the shared step that turns the shapes a reader found
//! into a validated [`Scene`] through [`SceneBuilder`] (the checks and messages of JSON).

use crate::error::Error;
use crate::geom::arc::Arc;
use crate::geom::{Aabb, Point};
use crate::scene::{Mode, Scene, SceneBuilder, Site, SiteKind};
use std::path::Path;

/// A scene file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// The scene format of `docs/SCENE_FORMAT.md`.
    Json,
    /// GeoJSON (RFC 7946): points, line strings, polygons with holes.
    GeoJson,
    /// Well-known text: one geometry per line, or a collection.
    Wkt,
    /// AutoCAD DXF, ASCII: LINE, ARC, CIRCLE, POINT, LWPOLYLINE and POLYLINE with bulges,
    /// SPLINE, ELLIPSE.
    Dxf,
    /// SVG drawings: lines, polylines, polygons, rects, circles, ellipses and paths.
    Svg,
}

impl Format {
    /// The format of a file name's extension (`.json`, `.geojson`, `.wkt`, `.dxf`, `.svg`, case
    /// ignored), if known.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Format::from_name(&ext)
    }
    /// The format called `name` (`json`, `geojson`, `wkt`, `dxf`, `svg`).
    pub fn from_name(name: &str) -> Option<Format> {
        match name {
            "json" => Some(Format::Json),
            "geojson" => Some(Format::GeoJson),
            "wkt" => Some(Format::Wkt),
            "dxf" => Some(Format::Dxf),
            "svg" => Some(Format::Svg),
            _ => None,
        }
    }
}

/// What a caller sets over a file's own values (formats without a domain get the
/// bounding box of their sites, grown by a tenth of its longest side on every side).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ReadOptions {
    /// The domain, instead of the file's or the default.
    pub domain: Option<Aabb>,
    /// The resolution, instead of the file's or the default.
    pub epsilon: Option<f64>,
    /// The mode, instead of the file's or `voronoi`.
    pub mode: Option<Mode>,
    /// How the file's coordinates are taken: planar, or (GeoJSON only) longitude and
    /// latitude projected to metres ([`super::Projection::Local`]; the scene then
    /// carries its [`super::LocalProjection`] and the GeoJSON writers project back).
    pub project: super::Projection,
}

/// Reads a scene in `format` from `data`; returns it with the reader's warnings (unknown
/// fields, entities not read).
pub fn read_scene(
    data: &[u8],
    format: Format,
    options: &ReadOptions,
) -> Result<(Scene, Vec<String>), Error> {
    let text = || {
        std::str::from_utf8(data)
            .map_err(|e| Error::Json(format!("the file is not UTF-8 text: {e}")))
    };
    if options.project != super::Projection::None && format != Format::GeoJson {
        return Err(Error::InvalidOption {
            option: "project".into(),
            message: "longitude and latitude are read from GeoJSON only".into(),
        });
    }
    match format {
        Format::Json => read_json(text()?, options),
        Format::GeoJson => super::geojson::read_scene(text()?, options),
        Format::Wkt => super::wkt::read_scene(text()?, options),
        Format::Dxf => super::dxf::read_scene(data, options),
        Format::Svg => super::svg_in::read_scene(text()?, options),
    }
}

fn read_json(text: &str, options: &ReadOptions) -> Result<(Scene, Vec<String>), Error> {
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| Error::Json(e.to_string()))?;
    let warnings = Scene::unknown_fields(&value);
    let scene = Scene::from_value(&value)?;
    let scene = match (options.domain, options.epsilon) {
        (None, None) => scene,
        (domain, epsilon) => Scene::new(
            domain.unwrap_or(scene.domain()),
            epsilon.unwrap_or(scene.epsilon()),
            scene.mode(),
            scene.sites().to_vec(),
        )?,
    };
    let scene = match options.mode {
        Some(mode) => scene.with_mode(mode),
        None => scene,
    };
    Ok((scene, warnings))
}

/// A site found by a reader, with where it came from (`feature 3`, `line 2`,
/// `entity 5 (ARC)`) for messages.
pub(crate) struct Found {
    pub site: Site,
    pub origin: String,
}

/// The scene-level values a file may carry.
#[derive(Default)]
pub(crate) struct FileValues {
    pub domain: Option<Aabb>,
    pub epsilon: Option<f64>,
    pub mode: Option<Mode>,
}

/// The mode named `name` in a file.
pub(crate) fn mode_named(name: &str) -> Result<Mode, Error> {
    match name {
        "voronoi" => Ok(Mode::Voronoi),
        "complex" => Ok(Mode::Complex),
        "medial_axis" => Ok(Mode::MedialAxis),
        other => Err(Error::scene(
            "mode",
            format!("unknown mode '{other}' (known: voronoi, complex, medial_axis)"),
        )),
    }
}

/// A ring without the repeated first point that closes it in GeoJSON, WKT and DXF.
pub(crate) fn open_ring(mut ring: Vec<Point>) -> Vec<Point> {
    if ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    ring
}

/// The box holding a site's points (circles and arcs by their whole circle).
fn extent(kind: &SiteKind) -> Option<Aabb> {
    let of = |pts: &mut dyn Iterator<Item = Point>| -> Option<Aabb> {
        let first = pts.next()?;
        let mut b = Aabb::new(first, first);
        for p in pts {
            b = Aabb::new(
                Point::new(b.min.x.min(p.x), b.min.y.min(p.y)),
                Point::new(b.max.x.max(p.x), b.max.y.max(p.y)),
            );
        }
        Some(b)
    };
    let round = |c: Point, r: f64| {
        let r = r.abs();
        of(&mut [c - Point::new(r, r), c + Point::new(r, r)].into_iter())
    };
    match kind {
        SiteKind::Point { at, .. } => of(&mut std::iter::once(*at)),
        SiteKind::Segment { from, to } => of(&mut [*from, *to].into_iter()),
        SiteKind::Polyline { points } => of(&mut points.iter().copied()),
        SiteKind::Polygon { rings } => of(&mut rings.iter().flatten().copied()),
        SiteKind::Circle { center, radius } | SiteKind::Arc { center, radius, .. } => {
            round(*center, *radius)
        }
        SiteKind::Bspline { control_points, .. } | SiteKind::Bezier { control_points, .. } => {
            of(&mut control_points.iter().copied())
        }
        _ => None,
    }
}

/// The default domain of `sites`: their bounding box grown by a tenth of its longest
/// side (or by 1 around a single point).
fn default_domain(sites: &[Found]) -> Result<Aabb, Error> {
    let mut boxes = sites.iter().filter_map(|f| extent(&f.site.kind));
    let first = boxes
        .next()
        .ok_or_else(|| Error::scene("sites", "the file has no site to compute"))?;
    let b = boxes.fold(first, |a, b| {
        Aabb::new(
            Point::new(a.min.x.min(b.min.x), a.min.y.min(b.min.y)),
            Point::new(a.max.x.max(b.max.x), a.max.y.max(b.max.y)),
        )
    });
    let side = b.longest_side();
    let margin = if side > 0.0 { 0.1 * side } else { 1.0 };
    let m = Point::new(margin, margin);
    Ok(Aabb::new(b.min - m, b.max + m))
}

/// The validated scene of the sites a reader found: `options` over the file's values
/// over the defaults; each site is checked as it is added, and a refusal names the site
/// index, the field, and where in the file the site came from.
pub(crate) fn build_scene(
    found: Vec<Found>,
    file: FileValues,
    options: &ReadOptions,
) -> Result<Scene, Error> {
    let domain = match options.domain.or(file.domain) {
        Some(d) => d,
        None => default_domain(&found)?,
    };
    let mut b = SceneBuilder::new(domain)?.mode(options.mode.or(file.mode).unwrap_or_default());
    if let Some(e) = options.epsilon.or(file.epsilon) {
        b = b.epsilon(e)?;
    }
    let origins: Vec<String> = found.iter().map(|f| f.origin.clone()).collect();
    let with_origin = |e: Error| match e {
        Error::Site {
            site,
            field,
            message,
        } => Error::Site {
            message: format!("{message} ({})", origins[site]),
            site,
            field,
        },
        other => other,
    };
    for f in found {
        b.add(f.site).map_err(with_origin)?;
    }
    b.build().map_err(with_origin)
}

/// Moves the ends of straight sites within 1e-9 of the drawing's size of an arc's
/// computed end `center + r (cos a, sin a)` onto it, so that the scene's shared-end rule
/// holds for drawings whose arcs were given by their ends (DXF bulges, SVG paths).
pub(crate) fn snap_to_arc_ends(found: &mut [Found]) {
    let size = found
        .iter()
        .flat_map(|f| match &f.site.kind {
            SiteKind::Segment { from, to } => vec![*from, *to],
            SiteKind::Polyline { points } => points.clone(),
            SiteKind::Arc { center, radius, .. } => {
                vec![
                    *center + Point::new(*radius, *radius),
                    *center - Point::new(*radius, *radius),
                ]
            }
            _ => Vec::new(),
        })
        .map(|p| p.x.abs().max(p.y.abs()))
        .fold(0.0, f64::max);
    let tol = 1e-9 * size.max(1e-300);
    let mut ends: Vec<Point> = found
        .iter()
        .filter_map(|f| match f.site.kind {
            SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => Some(Arc::from_angles(center, radius, start_angle, end_angle).ends()),
            _ => None,
        })
        .flatten()
        .collect();
    if ends.is_empty() {
        return;
    }
    ends.sort_by(|a, b| a.x.total_cmp(&b.x));
    let snap = |p: &mut Point| {
        let from = ends.partition_point(|e| e.x < p.x - tol);
        if let Some(e) = ends[from..]
            .iter()
            .take_while(|e| e.x <= p.x + tol)
            .find(|e| e.dist(*p) <= tol)
        {
            *p = *e;
        }
    };
    for f in found.iter_mut() {
        match &mut f.site.kind {
            SiteKind::Segment { from, to } => {
                snap(from);
                snap(to);
            }
            SiteKind::Polyline { points } => {
                let last = points.len() - 1;
                snap(&mut points[0]);
                snap(&mut points[last]);
            }
            _ => {}
        }
    }
}
