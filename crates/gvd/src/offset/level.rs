//! Level curves `{x : dist(x, feature) = d}` as exact primitives — circles around points
//! and corners, lines parallel to edges, concentric arcs beside arc sites — with their
//! parameters, projections and intersections.

use crate::geom::{Aabb, Point};
use std::f64::consts::TAU;

/// Relative slack under which two level curves that miss each other by rounding are
/// taken as tangent.
const TANGENT: f64 = 1e-9;

/// Relative slack under which two level curves that cross by rounding are taken as
/// tangent: `h²` of this size is rounding noise (a few ulps of `r²`) at a tangency, as
/// between a corner's circle and the sides of the edges and arcs it ends; its square
/// root would put two points about `1e-8 r` apart where there is one.
const CROSSING: f64 = 1e-14;

/// One level curve, oriented with its feature on the left.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Level {
    /// The circle `|x − center| = radius`, parametrized by the counter-clockwise angle
    /// in `[0, 2π)`.
    Circle { center: Point, radius: f64 },
    /// The segment from `from` to `to` (a side of an edge's perpendicular strip at
    /// distance d), parametrized by `s ∈ [0, 1]`.
    Line { from: Point, to: Point },
    /// The part of the circle `|x − center| = radius` at angles `start + t`,
    /// `t ∈ [0, span]` (a side of an arc site's wedge at distance d), parametrized by
    /// `t`; traversed counter-clockwise when `ccw`, else clockwise (the outer side keeps
    /// the arc on its left counter-clockwise, the inner side clockwise).
    Arc {
        center: Point,
        radius: f64,
        start: f64,
        span: f64,
        ccw: bool,
    },
}

impl Level {
    /// The two lines at distance `d` beside the edge `[a, b]`, left side first: with
    /// `n` the unit left normal of `b − a`, `b + d n → a + d n` and `a − d n → b − d n`
    /// (both keep the edge on their left).
    pub(super) fn beside(a: Point, b: Point, d: f64) -> [Level; 2] {
        let n = unit(b - a).perp() * d;
        [
            Level::Line {
                from: b + n,
                to: a + n,
            },
            Level::Line {
                from: a - n,
                to: b - n,
            },
        ]
    }

    /// The two arcs at distance `d` beside the arc site of circle `(c, r)` from angle
    /// `start` counter-clockwise over `span`: outside (radius `r + d`, counter-clockwise)
    /// first, then inside (radius `r − d`, clockwise) when `d < r`.
    pub(super) fn around(c: Point, r: f64, start: f64, span: f64, d: f64) -> Vec<Level> {
        let side = |radius: f64, ccw: bool| Level::Arc {
            center: c,
            radius,
            start,
            span,
            ccw,
        };
        let mut out = vec![side(r + d, true)];
        if r - d > 1e-12 * r {
            out.push(side(r - d, false));
        }
        out
    }

    /// The parameter of the point of the curve nearest to `p` (for an arc, the angle
    /// from its start, in `[0, 2π)`: beyond `span` off the arc).
    pub(super) fn param(&self, p: Point) -> f64 {
        match *self {
            Level::Circle { center, .. } => {
                let v = p - center;
                v.y.atan2(v.x).rem_euclid(TAU)
            }
            Level::Line { from, to } => {
                let u = to - from;
                (p - from).dot(u) / u.dot(u)
            }
            Level::Arc { center, start, .. } => {
                let v = p - center;
                (v.y.atan2(v.x) - start).rem_euclid(TAU)
            }
        }
    }

    /// Whether parameter `t` is on the curve (not beyond a line's or an arc's ends).
    pub(super) fn holds(&self, t: f64) -> bool {
        match *self {
            Level::Circle { .. } => true,
            Level::Line { .. } => (0.0..=1.0).contains(&t),
            Level::Arc { span, .. } => (0.0..=span).contains(&t),
        }
    }

    /// The parameter `t` moved to the nearer end when beyond the curve's ends.
    pub(super) fn clamp(&self, t: f64) -> f64 {
        match *self {
            Level::Circle { .. } => t,
            Level::Line { .. } => t.clamp(0.0, 1.0),
            Level::Arc { span, .. } if t > span => {
                if t - span <= TAU - t {
                    span
                } else {
                    0.0
                }
            }
            Level::Arc { .. } => t.max(0.0),
        }
    }

    /// The ends of a line or an arc, by parameter; none for a circle.
    pub(super) fn ends(&self) -> Option<[(f64, Point); 2]> {
        match *self {
            Level::Circle { .. } => None,
            Level::Line { from, to } => Some([(0.0, from), (1.0, to)]),
            Level::Arc { span, .. } => Some([(0.0, self.at(0.0)), (span, self.at(span))]),
        }
    }

    /// The supporting circle of a circle or an arc.
    pub(super) fn circle(&self) -> Option<(Point, f64)> {
        match *self {
            Level::Circle { center, radius } | Level::Arc { center, radius, .. } => {
                Some((center, radius))
            }
            Level::Line { .. } => None,
        }
    }

    /// The point at parameter `t` (on the whole circle, on the line's support).
    pub(super) fn at(&self, t: f64) -> Point {
        match *self {
            Level::Circle { center, radius } => center + Point::new(t.cos(), t.sin()) * radius,
            Level::Line { from, to } => from.lerp(to, t),
            Level::Arc {
                center,
                radius,
                start,
                ..
            } => center + Point::new((start + t).cos(), (start + t).sin()) * radius,
        }
    }

    /// Arc length per unit of parameter: the radius, or the line's length.
    pub(super) fn speed(&self) -> f64 {
        match *self {
            Level::Circle { radius, .. } | Level::Arc { radius, .. } => radius,
            Level::Line { from, to } => from.dist(to),
        }
    }
}

fn unit(v: Point) -> Point {
    v * (1.0 / v.norm())
}

/// The intersections of two level curves, lines and arcs taken as their whole
/// supports. Curves that miss each other by less than `TANGENT` of their size meet at
/// one point.
pub(super) fn intersections(p: &Level, q: &Level) -> Vec<Point> {
    match (p.circle(), q.circle(), *p, *q) {
        (Some((c1, r1)), Some((c2, r2)), _, _) => circle_circle(c1, r1, c2, r2),
        (Some((center, radius)), None, _, Level::Line { from, to })
        | (None, Some((center, radius)), Level::Line { from, to }, _) => {
            line_circle(from, to, center, radius)
        }
        (_, _, Level::Line { from: a, to: b }, Level::Line { from: c, to: d }) => {
            line_line(a, b, c, d).into_iter().collect()
        }
        _ => Vec::new(),
    }
}

/// Circles `|x − c1| = r1`, `|x − c2| = r2`: with `L = |c2 − c1|` and `e` the unit
/// vector from `c1` to `c2`, the points `c1 + a e ± h e⊥` where
/// `a = (r1² − r2² + L²) / 2L` and `h² = r1² − a²`.
fn circle_circle(c1: Point, r1: f64, c2: Point, r2: f64) -> Vec<Point> {
    let l = c1.dist(c2);
    if l == 0.0 {
        return Vec::new();
    }
    let e = (c2 - c1) * (1.0 / l);
    let a = (r1 * r1 - r2 * r2 + l * l) / (2.0 * l);
    let h2 = r1 * r1 - a * a;
    let size = r1 * (r1 + r2);
    chord(c1 + e * a, e.perp(), h2, TANGENT * size, CROSSING * size)
}

/// The line through `a` and `b` against the circle `|x − c| = r`: the foot `f` of `c`,
/// then `f ± h u` with `h² = r² − |c − f|²`.
fn line_circle(a: Point, b: Point, c: Point, r: f64) -> Vec<Point> {
    let u = unit(b - a);
    let f = a + u * (c - a).dot(u);
    chord(
        f,
        u,
        r * r - c.dist(f).powi(2),
        TANGENT * r * r,
        CROSSING * r * r,
    )
}

/// `m ± sqrt(h2) u`: two points, one when `h2` is in `[−slack, crossing]`, none below.
fn chord(m: Point, u: Point, h2: f64, slack: f64, crossing: f64) -> Vec<Point> {
    if h2 < -slack {
        Vec::new()
    } else if h2 <= crossing {
        vec![m]
    } else {
        let h = h2.sqrt();
        vec![m + u * h, m - u * h]
    }
}

/// The supports of `[a, b]` and `[c, d]`: `a + t (b − a)` with
/// `t = (c − a) × (d − c) / ((b − a) × (d − c))`; none when parallel.
fn line_line(a: Point, b: Point, c: Point, d: Point) -> Option<Point> {
    let (u, v) = (b - a, d - c);
    let den = u.cross(v);
    if den.abs() <= 1e-12 * u.norm() * v.norm() {
        return None;
    }
    Some(a + u * ((c - a).cross(v) / den))
}

/// Where a level curve crosses the boundary of `domain` (for a line or an arc, within
/// its ends).
pub(super) fn domain_crossings(level: &Level, domain: &Aabb) -> Vec<Point> {
    let c = domain.corners();
    let mut out = Vec::new();
    for k in 0..4 {
        let (a, b) = (c[k], c[(k + 1) % 4]);
        let side = Level::Line { from: a, to: b };
        for p in intersections(level, &side) {
            if level.holds(level.param(p)) && side.holds(side.param(p)) {
                out.push(p);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(p: Point, q: Point) -> bool {
        p.dist(q) < 1e-12
    }

    #[test]
    fn intersections_and_tangency() {
        let unit_circle = Level::Circle {
            center: Point::new(0.0, 0.0),
            radius: 1.0,
        };
        let other = Level::Circle {
            center: Point::new(1.0, 0.0),
            radius: 1.0,
        };
        let ps = intersections(&unit_circle, &other);
        assert_eq!(ps.len(), 2);
        assert!(ps
            .iter()
            .all(|p| (p.x - 0.5).abs() < 1e-12 && (p.norm() - 1.0).abs() < 1e-12));
        let tangent = Level::Circle {
            center: Point::new(2.0, 0.0),
            radius: 1.0,
        };
        assert_eq!(
            intersections(&unit_circle, &tangent),
            vec![Point::new(1.0, 0.0)]
        );
        let [left, right] = Level::beside(Point::new(0.0, 0.0), Point::new(2.0, 0.0), 1.0);
        assert_eq!(
            left,
            Level::Line {
                from: Point::new(2.0, 1.0),
                to: Point::new(0.0, 1.0)
            }
        );
        let touch = intersections(&unit_circle, &left);
        assert!(touch.len() == 1 && close(touch[0], Point::new(0.0, 1.0)));
        assert!(intersections(&left, &right).is_empty());
        let cross = Level::Line {
            from: Point::new(0.25, -3.0),
            to: Point::new(0.25, 3.0),
        };
        assert!(close(
            intersections(&left, &cross)[0],
            Point::new(0.25, 1.0)
        ));
        assert!(close(
            right.at(right.param(Point::new(3.0, 0.0))),
            Point::new(3.0, -1.0)
        ));
        let dom = Aabb::from_array([-0.5, -0.5, 0.5, 0.5]);
        assert_eq!(domain_crossings(&unit_circle, &dom).len(), 0);
        assert_eq!(domain_crossings(&cross, &dom).len(), 2);
    }
}
