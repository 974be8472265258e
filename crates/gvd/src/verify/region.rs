//! Regions bounded by closed sites, for the checker.
//!
//! A [`Region`] is the even-odd interior of a set of boundary segments. It serves two
//! purposes, as in the shared Python checker (`tools/README.md`, "Closed sites bound
//! regions"):
//!
//! * in `voronoi` and `complex` modes the inside of each polygon belongs to no diagram:
//!   the nearest-site search masks it, and an edge sample inside counts its depth;
//! * in `medial_axis` mode the diagram lives in the even-odd interior of all closed
//!   sites plus the chains of open sites whose ends join up into loops.
//!
//! Closed free-form curves bound regions as polygons do; closed algebraic curves by
//! the sign of their equation ([`Curve::encloses`]).

use super::curve::Curve;
use super::parametric::spline_site;
use crate::geom::bspline::RationalBspline;
use crate::geom::ring::RayCrossings;
use crate::geom::{segment_distance, Point};
use crate::scene::{Scene, SiteKind};
use std::f64::consts::TAU;

/// The even-odd interior of a set of segments and implicit curves.
#[derive(Clone, Debug)]
pub(super) struct Region {
    lo: Point,
    hi: Point,
    crossings: RayCrossings,
    curves: Vec<Curve>,
}

impl Region {
    pub(super) fn new(segs: Vec<(Point, Point)>) -> Self {
        let (lo, hi) = super::field::bounds(&segs);
        Region {
            crossings: RayCrossings::new(segs),
            lo,
            hi,
            curves: Vec::new(),
        }
    }

    /// Whether the region has no boundary at all.
    pub(super) fn is_empty(&self) -> bool {
        self.crossings.segments().is_empty() && self.curves.is_empty()
    }

    /// Even-odd over the segments and over what each curve encloses.
    pub(super) fn contains(&self, q: Point) -> bool {
        self.curves
            .iter()
            .fold(self.segments_contain(q), |inside, c| {
                inside != c.encloses(q)
            })
    }

    /// Even-odd test: a segment counts when `min y ≤ q.y < max y` and it crosses the
    /// horizontal line through `q` to the right of `q` (the Python checker's rule).
    fn segments_contain(&self, q: Point) -> bool {
        let inside_bounds =
            q.x >= self.lo.x && q.x <= self.hi.x && q.y >= self.lo.y && q.y <= self.hi.y;
        inside_bounds && self.crossings.odd(q)
    }

    /// The distance from `q` to the boundary.
    pub(super) fn boundary_distance(&self, q: Point) -> f64 {
        let curves = self
            .curves
            .iter()
            .filter_map(|c| c.foot(q))
            .map(|f| q.dist(f));
        self.crossings
            .segments()
            .iter()
            .map(|&(a, b)| segment_distance(q, a, b))
            .chain(curves)
            .fold(f64::INFINITY, f64::min)
    }

    /// How deep `q` lies inside the region (0 outside).
    pub(super) fn depth(&self, q: Point) -> f64 {
        if self.contains(q) {
            self.boundary_distance(q)
        } else {
            0.0
        }
    }
}

/// The two end points of an open curve-like site (segment, polyline, open arc).
fn open_ends(site: &SiteKind) -> Option<(Point, Point)> {
    match site {
        SiteKind::Segment { from, to } => Some((*from, *to)),
        SiteKind::Polyline { points } if points.len() >= 2 => {
            Some((points[0], points[points.len() - 1]))
        }
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            let sweep = crate::geom::arc::sweep(*start_angle, *end_angle);
            if sweep >= TAU {
                return None;
            }
            let at = |a: f64| *center + Point::new(a.cos(), a.sin()) * *radius;
            Some((at(*start_angle), at(start_angle + sweep)))
        }
        SiteKind::Bezier {
            control_points,
            weights,
        } => Some(RationalBspline::bezier(control_points, weights.as_deref()).ends()),
        SiteKind::Bspline {
            degree,
            control_points,
            knots,
            weights,
            closed: false,
        } => Some(RationalBspline::new(*degree, control_points, knots, weights.as_deref()).ends()),
        _ => None,
    }
}

/// The open sites whose ends join up (within `1e-9` of the scene's size) into closed
/// loops: sites with a free end are peeled off until none is left.
pub(super) fn closed_chains(scene: &Scene) -> Vec<usize> {
    let tol = 1e-9 * scene.domain().longest_side();
    let ends: Vec<(usize, Point, Point)> = scene
        .sites()
        .iter()
        .enumerate()
        .filter_map(|(i, s)| open_ends(&s.kind).map(|(a, b)| (i, a, b)))
        .collect();
    let mut alive = vec![true; ends.len()];
    loop {
        let joined = |k: usize, p: Point| {
            ends.iter().enumerate().any(|(j, &(_, a, b))| {
                alive[j] && (j != k) && (a.dist(p) <= tol || b.dist(p) <= tol)
            })
        };
        let free: Vec<usize> = (0..ends.len())
            .filter(|&k| {
                let (_, a, b) = ends[k];
                alive[k] && a.dist(b) > tol && (!joined(k, a) || !joined(k, b))
            })
            .collect();
        if free.is_empty() {
            break;
        }
        for k in free {
            alive[k] = false;
        }
    }
    (0..ends.len())
        .filter(|&k| alive[k])
        .map(|k| ends[k].0)
        .collect()
}

/// The boundary segments of a site that bounds or closes a region: a polygon's rings,
/// a polyline's or segment's pieces, an arc as chords of sagitta at most `sagitta`, a
/// free-form curve as chords at most `spacing` long (`scale`: the scene's size).
pub(super) fn boundary_segments(
    site: &SiteKind,
    sagitta: f64,
    spacing: f64,
    scale: f64,
) -> Vec<(Point, Point)> {
    if let Some(spline) = spline_site(site, scale, spacing) {
        return spline
            .pieces
            .iter()
            .flat_map(|p| {
                let line = p.outline(spacing);
                (1..line.len())
                    .map(move |k| (line[k - 1], line[k]))
                    .collect::<Vec<_>>()
            })
            .collect();
    }
    match site {
        SiteKind::Polygon { rings } => super::field::ring_segments(rings),
        SiteKind::Polyline { points } => points.windows(2).map(|w| (w[0], w[1])).collect(),
        SiteKind::Segment { from, to } => vec![(*from, *to)],
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            let sweep = crate::geom::arc::sweep(*start_angle, *end_angle);
            // chord of angle θ has sagitta r (1 − cos(θ/2))
            let theta = 2.0 * (1.0 - (sagitta / radius).min(1.0)).acos();
            let n = ((sweep / theta.max(1e-9)).ceil() as usize).clamp(8, 200_000);
            let at = |k: usize| {
                let a = start_angle + sweep * k as f64 / n as f64;
                *center + Point::new(a.cos(), a.sin()) * *radius
            };
            (0..n).map(|k| (at(k), at(k + 1))).collect()
        }
        _ => Vec::new(),
    }
}

/// The `medial_axis` region of a scene: the even-odd interior of its polygons, closed
/// free-form curves, the chains of open sites that close up and the algebraic `curves`
/// (the checker's samples of the scene's algebraic sites).
pub(super) fn medial_region(scene: &Scene, curves: Vec<Curve>) -> Region {
    let (sagitta, spacing) = (1e-3 * scene.epsilon(), 0.25 * scene.epsilon());
    let scale = scene.domain().longest_side();
    let bounds = |s: &SiteKind| {
        matches!(s, SiteKind::Polygon { .. })
            || spline_site(s, scale, spacing).is_some_and(|c| c.closed)
    };
    let mut segs = Vec::new();
    for s in scene.sites() {
        if bounds(&s.kind) {
            segs.extend(boundary_segments(&s.kind, sagitta, spacing, scale));
        }
    }
    for i in closed_chains(scene) {
        segs.extend(boundary_segments(
            &scene.sites()[i].kind,
            sagitta,
            spacing,
            scale,
        ));
    }
    Region {
        curves,
        ..Region::new(segs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_with_hole() {
        let p = |x: f64, y: f64| Point::new(x, y);
        let outer = vec![p(0.0, 0.0), p(4.0, 0.0), p(4.0, 4.0), p(0.0, 4.0)];
        let hole = vec![p(1.0, 1.0), p(3.0, 1.0), p(3.0, 3.0), p(1.0, 3.0)];
        let r = Region::new(super::super::field::ring_segments(&[outer, hole]));
        assert!(r.contains(p(0.5, 2.0)));
        assert!(!r.contains(p(2.0, 2.0)));
        assert!(!r.contains(p(5.0, 2.0)));
        assert!((r.depth(p(0.5, 2.0)) - 0.5).abs() < 1e-15);
        assert_eq!(r.depth(p(2.0, 2.0)), 0.0);
    }
}
