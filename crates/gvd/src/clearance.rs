//! The clearance of a diagram's points (the distance to their generators: the radius
//! of the maximal empty disc centred there) and the feet (the generators' nearest
//! points), which the medial axis's pruning ([`crate::complex::prune`]) measures.

use crate::complex::{FeatureKind, Generator, VoronoiComplex};
use crate::geom::arc::Arc;
use crate::geom::{segment_foot, Point};
use crate::scene::{Metric, Scene, Site, SiteKind};
use crate::site::{DistanceField, SiteField};

impl VoronoiComplex {
    /// Every vertex's clearance in `scene`: its stored [`crate::complex::Vertex::clearance`]
    /// where set, else the least distance to its generators:
    /// Euclidean for the geometric kinds, the field's value for the other kinds.
    pub fn clearances(&self, scene: &Scene) -> Vec<f64> {
        if let Some(stored) = self.vertices.iter().map(|v| v.clearance).collect() {
            return stored;
        }
        with_feet(scene, |feet| {
            self.vertices
                .iter()
                .map(|v| {
                    v.clearance
                        .unwrap_or_else(|| feet.generators_clearance(&v.sites, v.at))
                })
                .collect()
        })
    }

    /// Stores the clearance of every vertex ([`crate::complex::Vertex::clearance`]) and
    /// of every point of every edge ([`crate::complex::Edge::clearance`]): the least
    /// distance to the generators (which agree within epsilon). Left unset where
    /// unknown: a vertex's is `None`, an edge with any unknown point gets none.
    pub fn add_clearances(&mut self, scene: &Scene) {
        with_feet(scene, |feet| self.store_clearances(feet))
    }

    /// [`VoronoiComplex::add_clearances`] with the feet of the scene's generators.
    pub(crate) fn store_clearances(&mut self, feet: &Feet) {
        for v in &mut self.vertices {
            let r = feet.generators_clearance(&v.sites, v.at);
            v.clearance = r.is_finite().then_some(r);
        }
        for e in &mut self.edges {
            let radii: Vec<f64> = e
                .points
                .iter()
                .map(|&q| feet.generators_clearance(&e.sites, q))
                .collect();
            e.clearance = if radii.iter().all(|r| r.is_finite()) {
                radii
            } else {
                Vec::new()
            };
        }
    }
}

impl VoronoiComplex {
    /// The largest stored clearance, at a vertex or an edge point, with where it is:
    /// in `medial_axis` mode the maximum inscribed circle of the regions (its centre
    /// lies on the medial axis, where the distance to the boundary has its local
    /// maxima). `None` before [`VoronoiComplex::add_clearances`] or without any.
    pub fn max_inscribed_circle(&self) -> Option<(Point, f64)> {
        let at_vertices = self
            .vertices
            .iter()
            .filter_map(|v| v.clearance.map(|r| (v.at, r)));
        let along_edges = self
            .edges
            .iter()
            .flat_map(|e| e.points.iter().copied().zip(e.clearance.iter().copied()));
        at_vertices
            .chain(along_edges)
            .filter(|(_, r)| r.is_finite())
            .max_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// The feet and clearances of a scene's generators, with what the free-form curves need
/// built once ([`with_feet`]).
pub(crate) struct Feet<'a> {
    scene: &'a Scene,
    freeform: &'a dyn Fn(&Generator, Point) -> Option<Point>,
}

/// Runs `work` with the [`Feet`] of `scene`.
pub(crate) fn with_feet<R>(scene: &Scene, work: impl FnOnce(&Feet) -> R) -> R {
    crate::freeform::with_feet(scene, |freeform| work(&Feet { scene, freeform }))
}

impl Feet<'_> {
    /// The least of the distances from `q` to `generators` ([`Feet::clearance`]); NaN
    /// if any is unknown or there are none. A generator listed twice (the two sides of
    /// a medial axis edge inside one piece) is measured once.
    pub(crate) fn generators_clearance(&self, generators: &[Generator], q: Point) -> f64 {
        let mut least = f64::NAN;
        for (k, g) in generators.iter().enumerate() {
            if generators[..k].contains(g) {
                continue;
            }
            let r = self.clearance(g, q);
            if r.is_nan() {
                return f64::NAN;
            }
            least = if least.is_nan() { r } else { least.min(r) };
        }
        least
    }

    /// The distance from `q` to `generator`: Euclidean for the geometric kinds (points,
    /// circles as `|q − c| − r`, segments, arcs, polylines, polygons' boundaries, Bézier
    /// and B-spline curves, their corners, edges and pieces: `|q − foot|`, see
    /// [`Feet::foot`]), the site's field value for the others (point metrics, ellipses,
    /// algebraic curves, fields); NaN for an index out of range.
    pub(crate) fn clearance(&self, generator: &Generator, q: Point) -> f64 {
        let Some(site) = self.scene.sites().get(generator.site()) else {
            return f64::NAN;
        };
        if let SiteKind::Circle { center, radius } = site.kind {
            return q.dist(center) - radius;
        }
        if let Some(f) = self.foot(generator, q) {
            return q.dist(f);
        }
        SiteField::from_site(generator.site(), &site.kind, &self.scene.domain())
            .map(|f| f.value(q))
            .unwrap_or(f64::NAN)
    }

    /// The point of `generator` nearest to `q` ([`foot`]; free-form curves, their
    /// pieces and corners by a certified foot-point search).
    pub(crate) fn foot(&self, generator: &Generator, q: Point) -> Option<Point> {
        match self.scene.sites().get(generator.site())?.kind {
            SiteKind::Bezier { .. } | SiteKind::Bspline { .. } => (self.freeform)(generator, q),
            _ => foot(self.scene, generator, q),
        }
    }
}

/// The point of `generator` nearest to `q` (its foot): a Euclidean point or a corner is
/// its own foot; a segment or polygon edge gives the orthogonal projection clamped to
/// it; an arc the radial projection `c + r·(q − c)/|q − c|` where the arc spans that
/// direction, else its nearer end; a circle the radial projection; a whole polyline or
/// polygon the nearest of its edges' feet (at a circle's or arc's centre, where every
/// point is nearest, the one at angle 0). `None` for the other kinds (point metrics,
/// ellipses, algebraic curves, fields; free-form curves: [`Feet::foot`]) and for an
/// index out of range.
fn foot(scene: &Scene, generator: &Generator, q: Point) -> Option<Point> {
    let site = scene.sites().get(generator.site())?;
    if let Generator::Feature { feature, index, .. } = *generator {
        match feature {
            FeatureKind::Corner => return corner(site, index),
            FeatureKind::Edge => {
                let (a, b) = chain_edge(site, index)?;
                return Some(segment_foot(q, a, b));
            }
            FeatureKind::Piece => {}
        }
    }
    // At the centre every point of the circle is nearest: take the one at angle 0 (an
    // arc reaches here only if it spans that angle).
    let radial = |center: Point, radius: f64| {
        let d = q - center;
        let n = d.norm();
        Some(if n > 0.0 {
            center + d * (radius / n)
        } else {
            center + Point::new(radius, 0.0)
        })
    };
    match &site.kind {
        SiteKind::Point {
            at,
            metric: Metric::Euclidean,
        } => Some(*at),
        SiteKind::Circle { center, radius } => radial(*center, *radius),
        SiteKind::Segment { from, to } => Some(segment_foot(q, *from, *to)),
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            let arc = Arc::from_angles(*center, *radius, *start_angle, *end_angle);
            let d = q - *center;
            if arc.spans(d.y.atan2(d.x)) {
                radial(*center, *radius)
            } else {
                let [a, b] = arc.ends();
                Some(if q.dist(a) <= q.dist(b) { a } else { b })
            }
        }
        SiteKind::Polyline { .. } | SiteKind::Polygon { .. } => chain_edges(site)?
            .map(|(a, b)| segment_foot(q, a, b))
            .min_by(|f, g| q.dist2(*f).total_cmp(&q.dist2(*g))),
        _ => None,
    }
}

/// The edges of a segment (itself), a polyline, or a polygon's rings in order
/// (numbered as the features are); `None` for other kinds.
fn chain_edges(site: &Site) -> Option<Box<dyn Iterator<Item = (Point, Point)> + '_>> {
    fn chain(points: &[Point], closed: bool) -> impl Iterator<Item = (Point, Point)> + '_ {
        let n = points.len();
        let edges = if closed { n } else { n.saturating_sub(1) };
        (0..edges).map(move |k| (points[k], points[(k + 1) % n]))
    }
    let rings: Vec<(&[Point], bool)> = match &site.kind {
        SiteKind::Segment { from, to } => return Some(Box::new(std::iter::once((*from, *to)))),
        SiteKind::Polyline { points } => vec![(points.as_slice(), false)],
        SiteKind::Polygon { rings } => rings.iter().map(|r| (r.as_slice(), true)).collect(),
        _ => return None,
    };
    Some(Box::new(
        rings
            .into_iter()
            .flat_map(move |(r, closed)| chain(r, closed)),
    ))
}

/// Corner `index` of a segment or an arc (its ends), a polyline (its points) or a
/// polygon (its rings' points in order), found ring by ring (a polygon of 10^5
/// corners asks for each of them); `None` for other kinds or an index out of range.
fn corner(site: &Site, index: usize) -> Option<Point> {
    match &site.kind {
        SiteKind::Segment { from, to } => [*from, *to].get(index).copied(),
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => Arc::from_angles(*center, *radius, *start_angle, *end_angle)
            .ends()
            .get(index)
            .copied(),
        SiteKind::Polyline { points } => points.get(index).copied(),
        SiteKind::Polygon { rings } => {
            let (ring, k) = ring_index(rings, index)?;
            Some(ring[k])
        }
        _ => None,
    }
}

/// Edge `index` of a segment (itself), a polyline, or a polygon's rings (numbered as
/// [`chain_edges`] gives them), found ring by ring; `None` for other kinds or an index
/// out of range.
fn chain_edge(site: &Site, index: usize) -> Option<(Point, Point)> {
    match &site.kind {
        SiteKind::Segment { from, to } => (index == 0).then_some((*from, *to)),
        SiteKind::Polyline { points } => Some((*points.get(index)?, *points.get(index + 1)?)),
        SiteKind::Polygon { rings } => {
            let (ring, k) = ring_index(rings, index)?;
            Some((ring[k], ring[(k + 1) % ring.len()]))
        }
        _ => None,
    }
}

/// The ring holding item `index` of the rings' points (or closing edges) numbered
/// across them, and its index there.
fn ring_index(rings: &[Vec<Point>], mut index: usize) -> Option<(&[Point], usize)> {
    for ring in rings {
        if index < ring.len() {
            return Some((ring, index));
        }
        index -= ring.len();
    }
    None
}
