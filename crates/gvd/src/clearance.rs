//! The clearance of a diagram's vertices: the distance from each to its generators
//! (equidistant, so the first one suffices).

use crate::complex::{FeatureKind, Generator, VoronoiComplex};
use crate::geom::arc::Arc;
use crate::geom::{segment_distance, Point};
use crate::scene::{Metric, Scene, SiteKind};
use crate::site::{DistanceField, SiteField};

impl VoronoiComplex {
    /// Every vertex's clearance in `scene`: the distance to its first generator,
    /// Euclidean for points, circles (`|q − c| − r`), segments, arcs, polylines and
    /// polygons (and their corners and edges), the field's value for the other kinds,
    /// NaN for Bézier and B-spline curves.
    pub fn clearances(&self, scene: &Scene) -> Vec<f64> {
        self.vertices
            .iter()
            .map(|v| {
                v.sites
                    .first()
                    .map_or(f64::NAN, |g| clearance(scene, g, v.at))
            })
            .collect()
    }
}

/// The distance from `q` to `generator` of `scene`: Euclidean for the geometric kinds
/// (points, circles as `|q − c| − r`, segments, arcs, polylines, polygons' boundaries,
/// their corners and edges), the site's field value for the others (point metrics,
/// ellipses, algebraic curves, fields); NaN where neither is known here (Bézier and
/// B-spline curves).
pub(crate) fn clearance(scene: &Scene, generator: &Generator, q: Point) -> f64 {
    let Some(site) = scene.sites().get(generator.site()) else {
        return f64::NAN;
    };
    let chain = |points: &[Point], closed: bool| -> Vec<(Point, Point)> {
        let n = points.len();
        let edges = if closed { n } else { n.saturating_sub(1) };
        (0..edges)
            .map(|k| (points[k], points[(k + 1) % n]))
            .collect()
    };
    let edges: Vec<(Point, Point)> = match &site.kind {
        SiteKind::Polyline { points } => chain(points, false),
        SiteKind::Polygon { rings } => rings.iter().flat_map(|r| chain(r, true)).collect(),
        _ => Vec::new(),
    };
    if let Generator::Feature { feature, index, .. } = *generator {
        let corners: Vec<Point> = edges.iter().map(|e| e.0).collect();
        let corners = match &site.kind {
            SiteKind::Polyline { points } => points.clone(),
            _ => corners,
        };
        match feature {
            FeatureKind::Corner => {
                if let Some(c) = corners.get(index) {
                    return q.dist(*c);
                }
            }
            FeatureKind::Edge => {
                if let Some((a, b)) = edges.get(index) {
                    return segment_distance(q, *a, *b);
                }
            }
            FeatureKind::Piece => {}
        }
    }
    match &site.kind {
        SiteKind::Point {
            at,
            metric: Metric::Euclidean,
        } => q.dist(*at),
        SiteKind::Circle { center, radius } => q.dist(*center) - radius,
        SiteKind::Segment { from, to } => segment_distance(q, *from, *to),
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            let arc = Arc::from_angles(*center, *radius, *start_angle, *end_angle);
            let d = q - *center;
            if arc.spans(d.y.atan2(d.x)) {
                (d.norm() - radius).abs()
            } else {
                let [a, b] = arc.ends();
                q.dist(a).min(q.dist(b))
            }
        }
        SiteKind::Polyline { .. } | SiteKind::Polygon { .. } => edges
            .iter()
            .map(|(a, b)| segment_distance(q, *a, *b))
            .fold(f64::INFINITY, f64::min),
        kind => SiteField::from_site(generator.site(), kind, &scene.domain())
            .map(|f| f.value(q))
            .unwrap_or(f64::NAN),
    }
}
