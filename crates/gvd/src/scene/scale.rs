//! Exact power-of-two rescaling of a scene. A scene whose field values reach beyond
//! `2^±200` is best computed at a scale where its largest coordinate is about 1 (frames
//! around the sites, squared distances, lp powers and the conics' coefficients then
//! neither overflow nor underflow), and its diagram scaled back
//! ([`crate::VoronoiComplex::scale`]). Multiplying by a power of two is exact, so
//! nothing is rounded on the way.

use super::{Metric, Scene, SiteKind};
use crate::geom::{Aabb, Point};

impl Scene {
    /// The factor `2^e` that brings the largest coordinate (domain, sites, radii) near 1,
    /// or `None` when there is no need or no way: every field value `m^k` (`k` the
    /// fields' common degree, [`Scene::field_degree`]) already lies within `2^±200`, or
    /// the fields have no common degree (a scene mixing degrees is not the same diagram
    /// at another scale).
    pub fn unit_scale(&self) -> Option<f64> {
        let k = self.field_degree()?;
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
                SiteKind::Arc { center, radius, .. } | SiteKind::Circle { center, radius } => {
                    see(*center);
                    see(Point::new(*radius, 0.0));
                }
                SiteKind::Ellipse {
                    center, semi_axes, ..
                } => {
                    see(*center);
                    see(Point::new(semi_axes[0], semi_axes[1]));
                }
                SiteKind::Polyline { points } => points.iter().copied().for_each(&mut see),
                SiteKind::Polygon { rings } => rings.iter().flatten().copied().for_each(&mut see),
                SiteKind::Bezier { control_points, .. }
                | SiteKind::Bspline { control_points, .. } => {
                    control_points.iter().copied().for_each(&mut see)
                }
                SiteKind::Algebraic { .. }
                | SiteKind::Field { .. }
                | SiteKind::ImplicitField { .. } => {}
            }
        }
        let bound = 200.0 / f64::from(k);
        if m == 0.0 || m.log2().abs() < bound {
            return None;
        }
        let s = 2f64.powi(-(m.log2().ceil() as i32));
        // a domain far smaller than a site would land among the subnormals: no help there
        let extent = self.domain.longest_side();
        (extent * s > 2f64.powi(-900)).then_some(s)
    }

    /// The degree `k` shared by every site's field ([`SiteKind::field_degree`]), so that
    /// scaling the scene by `s` scales every field by `s^k` and keeps the diagram.
    /// `None` when the sites differ or one cannot be scaled.
    pub fn field_degree(&self) -> Option<u32> {
        let mut degrees = self.sites.iter().map(|s| s.kind.field_degree());
        let first = degrees.next().unwrap_or(Some(1))?;
        degrees.all(|k| k == Some(first)).then_some(first)
    }

    /// The scene with every coordinate and length times `s` (a power of two keeps it
    /// exact), and the weights of the quadratic metrics times `s` (power: `w` is a
    /// length) or `s²`. Sites without a [`SiteKind::field_degree`] are left as they are.
    pub fn scaled(&self, s: f64) -> Scene {
        let p = |q: &Point| *q * s;
        let mut out = self.clone();
        out.domain = Aabb::new(p(&self.domain.min), p(&self.domain.max));
        out.epsilon = self.epsilon * s;
        for site in &mut out.sites {
            match &mut site.kind {
                SiteKind::Point { at, metric } => {
                    *at = p(at);
                    match metric {
                        Metric::Power { weight } => *weight *= s,
                        Metric::Anisotropic { weight, .. } | Metric::Moebius { weight, .. } => {
                            *weight *= s * s
                        }
                        Metric::Euclidean | Metric::Lp { .. } => {}
                    }
                }
                SiteKind::Segment { from, to } => (*from, *to) = (p(from), p(to)),
                SiteKind::Arc { center, radius, .. } | SiteKind::Circle { center, radius } => {
                    (*center, *radius) = (p(center), *radius * s)
                }
                SiteKind::Ellipse {
                    center, semi_axes, ..
                } => {
                    *center = p(center);
                    semi_axes.iter_mut().for_each(|a| *a *= s);
                }
                SiteKind::Polyline { points } => points.iter_mut().for_each(|q| *q = p(q)),
                SiteKind::Polygon { rings } => rings.iter_mut().flatten().for_each(|q| *q = p(q)),
                SiteKind::Bezier { control_points, .. }
                | SiteKind::Bspline { control_points, .. } => {
                    control_points.iter_mut().for_each(|q| *q = p(q))
                }
                SiteKind::Algebraic { .. }
                | SiteKind::Field { .. }
                | SiteKind::ImplicitField { .. } => {}
            }
        }
        out
    }
}

impl SiteKind {
    /// The degree of the site's field as a function of lengths: 1 for distances
    /// (Euclidean points, circles, ellipses, segments, arcs, polylines, polygons,
    /// free-form curves: their control points scale, their weights and knots do not),
    /// 2 for the quadratic metrics (anisotropic, power, Möbius, whose weights scale
    /// with them), `p` for lp; `None` for sites given by equations, which
    /// [`Scene::scaled`] does not scale.
    pub fn field_degree(&self) -> Option<u32> {
        match self {
            SiteKind::Point { metric, .. } => Some(match metric {
                Metric::Euclidean => 1,
                Metric::Lp { p } => *p,
                Metric::Anisotropic { .. } | Metric::Power { .. } | Metric::Moebius { .. } => 2,
            }),
            SiteKind::Circle { .. }
            | SiteKind::Ellipse { .. }
            | SiteKind::Segment { .. }
            | SiteKind::Arc { .. }
            | SiteKind::Polyline { .. }
            | SiteKind::Polygon { .. }
            | SiteKind::Bezier { .. }
            | SiteKind::Bspline { .. } => Some(1),
            SiteKind::Algebraic { .. }
            | SiteKind::Field { .. }
            | SiteKind::ImplicitField { .. } => None,
        }
    }
}
