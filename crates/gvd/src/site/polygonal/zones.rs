//! Zones of polygonal features (YSL12 §IV): the region where a feature's own closest
//! point is attained. An edge's zone is the strip over it (a half-strip on the free
//! side when oriented, Z*(e)); a corner's is the cone `⋂ₖ {(q − c)·dₖ ≤ 0}` over its
//! incident edges' directions `dₖ` (away from the corner), empty (Z*(c) = ∅) where the
//! cone lies in the material: at concave corners.

use crate::geom::Point;
use smallvec::SmallVec;

/// A zone, closed (boundaries are measure-zero ties, decided by the distances).
#[derive(Clone, Debug, PartialEq)]
pub enum Zone {
    /// No point: a concave (or flat) corner's oriented zone.
    Empty,
    /// The whole plane (the zone filter switched off, or an isolated corner).
    Plane,
    /// The strip `0 ≤ (q − a)·u ≤ len`, restricted to `(q − a)·n ≥ 0` when `side` is
    /// `Some(n)`.
    Strip {
        /// The edge's first end.
        a: Point,
        /// The unit direction from `a` to the other end.
        u: Point,
        /// The edge's length.
        len: f64,
        /// The unit normal of the free side, for an oriented zone.
        side: Option<Point>,
    },
    /// The cone `⋂ₖ {(q − c)·dₖ ≤ 0}` (unit `dₖ`).
    Cone {
        /// The apex: the corner.
        c: Point,
        /// The incident edges' unit directions away from the corner.
        dirs: SmallVec<[Point; 2]>,
    },
}

impl Zone {
    /// `Sep(q, Z)`: the distance from `q` to the zone (0 inside, ∞ for an empty zone).
    /// A disc of radius `ρ` about `q` meets the zone iff this is at most `ρ`.
    pub fn distance(&self, q: Point) -> f64 {
        match self {
            Zone::Empty => f64::INFINITY,
            Zone::Plane => 0.0,
            Zone::Strip { a, u, len, side } => {
                let t = (q - *a).dot(*u);
                let dt = (-t).max(t - len).max(0.0);
                let ds = side.map_or(0.0, |n| (-(q - *a).dot(n)).max(0.0));
                // hypot(x, 0) = |x| exactly: most points are off the strip one way only
                if dt == 0.0 || ds == 0.0 {
                    dt.max(ds)
                } else {
                    dt.hypot(ds)
                }
            }
            Zone::Cone { c, dirs } => {
                let g = |d: &Point, p: Point| (p - *c).dot(*d);
                if dirs.iter().all(|d| g(d, q) <= 0.0) {
                    return 0.0;
                }
                // the nearest point of a convex cone lies on a face or at the apex
                let mut best = q.dist(*c);
                for d in dirs {
                    let s = g(d, q);
                    if s <= 0.0 {
                        continue;
                    }
                    let foot = q - *d * s;
                    let scale = 1e-12 * (1.0 + q.dist(*c));
                    if dirs.iter().all(|e| g(e, foot) <= scale) {
                        best = best.min(s);
                    }
                }
                best
            }
        }
    }

    /// Whether `q` lies in the zone, up to `tol`.
    pub fn contains(&self, q: Point, tol: f64) -> bool {
        self.distance(q) <= tol
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use smallvec::smallvec;

    #[test]
    fn strip_and_half_strip_distances() {
        let strip = Zone::Strip {
            a: Point::new(0.0, 0.0),
            u: Point::new(1.0, 0.0),
            len: 2.0,
            side: None,
        };
        assert_eq!(strip.distance(Point::new(1.0, -5.0)), 0.0);
        assert!((strip.distance(Point::new(5.0, 4.0)) - 3.0).abs() < 1e-15);
        let half = Zone::Strip {
            a: Point::new(0.0, 0.0),
            u: Point::new(1.0, 0.0),
            len: 2.0,
            side: Some(Point::new(0.0, 1.0)),
        };
        assert!((half.distance(Point::new(3.0, -4.0)) - 17f64.sqrt()).abs() < 1e-15);
        assert_eq!(half.distance(Point::new(1.0, 4.0)), 0.0);
    }

    #[test]
    fn cone_distance_is_to_its_faces_or_apex() {
        // the quadrant x ≥ 0, y ≥ 0 as the cone of a corner at the origin with edges
        // going in −x and −y
        let cone = Zone::Cone {
            c: Point::new(0.0, 0.0),
            dirs: smallvec![Point::new(-1.0, 0.0), Point::new(0.0, -1.0)],
        };
        assert_eq!(cone.distance(Point::new(1.0, 2.0)), 0.0);
        assert!((cone.distance(Point::new(-3.0, 2.0)) - 3.0).abs() < 1e-15);
        assert!((cone.distance(Point::new(-3.0, -4.0)) - 5.0).abs() < 1e-15);
        assert_eq!(Zone::Empty.distance(Point::new(0.0, 0.0)), f64::INFINITY);
    }
}
