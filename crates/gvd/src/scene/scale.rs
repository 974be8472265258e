//! Exact power-of-two rescaling of a scene. A scene whose largest coordinate lies beyond
//! `2^±200` is best computed at a scale where it is about 1 (frames around the sites,
//! squared distances and the conics' coefficients then neither overflow nor underflow),
//! and its diagram scaled back ([`crate::VoronoiComplex::scale`]). Multiplying by a
//! power of two is exact, so nothing is rounded on the way.

use super::{Scene, SiteKind};
use crate::geom::{Aabb, Point};

impl Scene {
    /// The factor `2^e` that brings the largest coordinate of the domain and of the
    /// point, segment, arc, polyline and polygon sites near 1, or `None` when it already
    /// lies within `2^±200`.
    pub fn unit_scale(&self) -> Option<f64> {
        let mut m = self
            .domain
            .to_array()
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let mut see = |p: Point| m = m.max(p.x.abs()).max(p.y.abs());
        for site in &self.sites {
            match &site.kind {
                SiteKind::Point { at, .. } => see(*at),
                SiteKind::Segment { from, to } => [*from, *to].into_iter().for_each(&mut see),
                SiteKind::Arc { center, radius, .. } => {
                    see(*center);
                    see(Point::new(*radius, 0.0));
                }
                SiteKind::Polyline { points } => points.iter().copied().for_each(&mut see),
                SiteKind::Polygon { rings } => rings.iter().flatten().copied().for_each(&mut see),
                SiteKind::Circle { .. }
                | SiteKind::Ellipse { .. }
                | SiteKind::Algebraic { .. }
                | SiteKind::Bezier { .. }
                | SiteKind::Bspline { .. }
                | SiteKind::Field { .. }
                | SiteKind::ImplicitField { .. } => {}
            }
        }
        if m == 0.0 || (m > 2f64.powi(-200) && m < 2f64.powi(200)) {
            return None;
        }
        Some(2f64.powi(-(m.log2().ceil() as i32)))
    }

    /// Whether [`Scene::scaled`] scales every site's distance exactly: the scene holds
    /// only Euclidean points, segments, arcs, polylines and polygons.
    pub fn scales_exactly(&self) -> bool {
        self.sites.iter().all(|s| match &s.kind {
            SiteKind::Point { metric, .. } => *metric == super::Metric::Euclidean,
            SiteKind::Segment { .. }
            | SiteKind::Arc { .. }
            | SiteKind::Polyline { .. }
            | SiteKind::Polygon { .. } => true,
            SiteKind::Circle { .. }
            | SiteKind::Ellipse { .. }
            | SiteKind::Algebraic { .. }
            | SiteKind::Bezier { .. }
            | SiteKind::Bspline { .. }
            | SiteKind::Field { .. }
            | SiteKind::ImplicitField { .. } => false,
        })
    }

    /// The scene with the domain, epsilon and every coordinate and length of its point,
    /// segment, arc, polyline and polygon sites times `s` (a power of two keeps it
    /// exact). Other kinds are left as they are: they take no part in
    /// [`Scene::unit_scale`].
    pub fn scaled(&self, s: f64) -> Scene {
        let p = |q: &Point| *q * s;
        let mut out = self.clone();
        out.domain = Aabb::new(p(&self.domain.min), p(&self.domain.max));
        out.epsilon = self.epsilon * s;
        for site in &mut out.sites {
            match &mut site.kind {
                SiteKind::Point { at, .. } => *at = p(at),
                SiteKind::Segment { from, to } => (*from, *to) = (p(from), p(to)),
                SiteKind::Arc { center, radius, .. } => {
                    (*center, *radius) = (p(center), *radius * s)
                }
                SiteKind::Polyline { points } => points.iter_mut().for_each(|q| *q = p(q)),
                SiteKind::Polygon { rings } => rings.iter_mut().flatten().for_each(|q| *q = p(q)),
                SiteKind::Circle { .. }
                | SiteKind::Ellipse { .. }
                | SiteKind::Algebraic { .. }
                | SiteKind::Bezier { .. }
                | SiteKind::Bspline { .. }
                | SiteKind::Field { .. }
                | SiteKind::ImplicitField { .. } => {}
            }
        }
        out
    }
}
