//! An exact power-of-two rescaling for the segment and subdivision engines, which work
//! in the scene's coordinates: a scene whose field values reach beyond `2^±200` is
//! computed at a scale where its largest coordinate is about 1 (the frame around the
//! sites, squared distances, lp powers and the conics' coefficients then neither
//! overflow nor underflow), and its diagram is scaled back. Multiplying by a power of two is exact, so nothing is rounded on the way.

use crate::complex::VoronoiComplex;
use crate::geom::Point;
use crate::scene::{Metric, Scene, SiteKind};

/// The factor `2^e` that brings the scene's largest coordinate (domain, sites, radii)
/// near 1, or `None` when there is no need or no way: every field value `m^k` (`k` the
/// fields' common degree, [`degree`]) already lies within `2^±200`, or the fields have
/// no common degree (a scene mixing degrees is not the same diagram at another scale).
pub(crate) fn factor(scene: &Scene) -> Option<f64> {
    let k = degree(scene)?;
    let mut m = scene
        .domain
        .to_array()
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let mut see = |p: Point| m = m.max(p.x.abs()).max(p.y.abs());
    for site in &scene.sites {
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
            _ => {}
        }
    }
    let bound = 200.0 / f64::from(k);
    if m == 0.0 || m.log2().abs() < bound {
        return None;
    }
    let s = 2f64.powi(-(m.log2().ceil() as i32));
    // a domain far smaller than a site would land among the subnormals: no help there
    let extent = scene.domain.longest_side();
    (extent * s > 2f64.powi(-900)).then_some(s)
}

/// The degree `k` shared by every site's field ([`site_degree`]), so that scaling the
/// scene by `s` scales every field by `s^k` and keeps the diagram. `None` when the sites
/// differ or one cannot be scaled.
pub(crate) fn degree(scene: &Scene) -> Option<u32> {
    let mut degrees = scene.sites.iter().map(|s| site_degree(&s.kind));
    let first = degrees.next().unwrap_or(Some(1))?;
    degrees.all(|k| k == Some(first)).then_some(first)
}

/// The degree of a site's field as a function of lengths: 1 for distances (Euclidean
/// points, circles, ellipses, segments, arcs, polylines, polygons), 2 for the quadratic
/// metrics (anisotropic, power, Möbius, whose weights scale with them), `p` for lp;
/// `None` for sites this module does not scale (curves and fields given by equations,
/// free-form curves).
pub(crate) fn site_degree(kind: &SiteKind) -> Option<u32> {
    match kind {
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
        | SiteKind::Polygon { .. } => Some(1),
        _ => None,
    }
}

/// `scene` with every coordinate and length times `s`, and the weights of the quadratic
/// metrics times `s` (power: `w` is a length) or `s²` (sites [`degree`] cannot scale are
/// left as they are).
pub(crate) fn scene(scene: &Scene, s: f64) -> Scene {
    let p = |q: &Point| *q * s;
    let mut out = scene.clone();
    out.domain = crate::geom::Aabb::new(p(&scene.domain.min), p(&scene.domain.max));
    out.epsilon = scene.epsilon * s;
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
            _ => {}
        }
    }
    out
}

/// Scales a diagram computed at scale `s` back by `1/s` (or, with `1/s`, a diagram to
/// scale `s`): vertices, edge points, cells, and
/// the offset forms (`x1, x2, x5, x7` and the clearances are lengths; `x3, x4, x6, x8`
/// are ratios).
pub(crate) fn unscale(c: &mut VoronoiComplex, s: f64) {
    let inv = 1.0 / s;
    for v in &mut c.vertices {
        v.at = v.at * inv;
    }
    for e in &mut c.edges {
        e.points.iter_mut().for_each(|q| *q = *q * inv);
        for piece in &mut e.bisector {
            for coeffs in [&mut piece.x, &mut piece.y] {
                for k in [0, 1, 4, 6] {
                    coeffs[k] *= inv;
                }
            }
            piece.t = piece.t.map(|t| t * inv);
        }
    }
    for cell in &mut c.cells {
        cell.rings.iter_mut().flatten().for_each(|q| *q = *q * inv);
    }
}
