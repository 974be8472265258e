//! An exact power-of-two rescaling for the segment engine, which works in the scene's
//! coordinates: a scene whose largest coordinate is beyond `2^±200` is computed at a
//! scale where it is about 1 (the frame around the sites, squared distances and the
//! conics' coefficients then neither overflow nor underflow), and its diagram is scaled
//! back. Multiplying by a power of two is exact, so nothing is rounded on the way.

use crate::complex::VoronoiComplex;
use crate::geom::Point;
use crate::scene::{Scene, SiteKind};

/// The factor `2^e` that brings the scene's largest coordinate (domain, sites, radii)
/// near 1, or `None` when it already lies within `2^±200`.
pub(crate) fn factor(scene: &Scene) -> Option<f64> {
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
            SiteKind::Arc { center, radius, .. } => {
                see(*center);
                see(Point::new(*radius, 0.0));
            }
            SiteKind::Polyline { points } => points.iter().copied().for_each(&mut see),
            SiteKind::Polygon { rings } => rings.iter().flatten().copied().for_each(&mut see),
            _ => {}
        }
    }
    if m == 0.0 || (m > 2f64.powi(-200) && m < 2f64.powi(200)) {
        return None;
    }
    Some(2f64.powi(-(m.log2().ceil() as i32)))
}

/// `scene` with every coordinate and length times `s` (sites the segment engine does
/// not take are left as they are).
pub(crate) fn scene(scene: &Scene, s: f64) -> Scene {
    let p = |q: &Point| *q * s;
    let mut out = scene.clone();
    out.domain = crate::geom::Aabb::new(p(&scene.domain.min), p(&scene.domain.max));
    out.epsilon = scene.epsilon * s;
    for site in &mut out.sites {
        match &mut site.kind {
            SiteKind::Point { at, .. } => *at = p(at),
            SiteKind::Segment { from, to } => (*from, *to) = (p(from), p(to)),
            SiteKind::Arc { center, radius, .. } => (*center, *radius) = (p(center), *radius * s),
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
