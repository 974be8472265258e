//! A point site under the Euclidean metric: the field `|q − p|`, bounded in closed form.

use super::{DistanceField, PairBound};
use crate::geom::{Aabb, Axis, Point};
use crate::num::Interval;

/// The field `f(q) = |q − p|` of a point `p`.
#[derive(Clone, Copy, Debug)]
pub struct EuclideanPoint {
    pub at: Point,
}

impl EuclideanPoint {
    pub fn new(at: Point) -> Self {
        EuclideanPoint { at }
    }

    fn offsets(&self, b: &Aabb) -> (Interval, Interval) {
        (b.x() - self.at.x, b.y() - self.at.y)
    }
}

impl DistanceField for EuclideanPoint {
    type State = ();

    fn state(&self, _: &Aabb) {}

    fn split(&self, _: &(), _: &Aabb, _: Axis, _: f64) -> ((), ()) {
        ((), ())
    }

    /// The exact range of `|q − p|` over the box, outward-rounded:
    /// `sqrt((X − px)² + (Y − py)²)` with tight interval squares.
    fn bound(&self, _: &(), b: &Aabb) -> Interval {
        let (dx, dy) = self.offsets(b);
        (dx.sqr() + dy.sqr()).sqrt()
    }

    /// `∇f = (q − p)/|q − p|`, bounded over the box; inside the unit square when the box
    /// holds `p` (the gradient is a unit vector wherever it exists).
    fn gradient_bound(&self, _: &(), b: &Aabb) -> Option<[Interval; 2]> {
        let (dx, dy) = self.offsets(b);
        let r = self.bound(&(), b);
        let unit = Interval::new(-1.0, 1.0);
        match (dx.div(r), dy.div(r)) {
            (Some(gx), Some(gy)) => Some([
                Interval::new(gx.lo.max(-1.0), gx.hi.min(1.0)),
                Interval::new(gy.lo.max(-1.0), gy.hi.min(1.0)),
            ]),
            _ => Some([unit, unit]),
        }
    }

    /// `sqrt(dx² + dy²)`: faster than `hypot`, and exact enough for coordinates far
    /// below 1e150.
    fn value(&self, q: Point) -> f64 {
        let (dx, dy) = (q.x - self.at.x, q.y - self.at.y);
        (dx * dx + dy * dy).sqrt()
    }

    fn gradient(&self, q: Point) -> Point {
        let d = q - self.at;
        let r = d.norm();
        if r == 0.0 {
            Point::new(0.0, 0.0)
        } else {
            d * (1.0 / r)
        }
    }

    /// `|q − a|` against `|q − b|` by the exact sign of `|q − a|² − |q − b|²`.
    fn exact_cmp(&self, other: &EuclideanPoint, q: Point) -> Option<std::cmp::Ordering> {
        Some(crate::geom::predicates::compare_distances(
            q, self.at, other.at,
        ))
    }

    /// The bisector with another point in its linear form
    /// `h(q) = |q − a|² − |q − b|² = (b − a)·(2q − a − b)`, same sign as `|q − a| − |q − b|`.
    fn pair(&self, _: &(), other: &EuclideanPoint, _: &(), b: &Aabb) -> PairBound {
        let (a, c) = (self.at, other.at);
        let ux = Interval::point(c.x) - Interval::point(a.x);
        let uy = Interval::point(c.y) - Interval::point(a.y);
        let sx = b.x().scale(2.0) - Interval::point(a.x) - Interval::point(c.x);
        let sy = b.y().scale(2.0) - Interval::point(a.y) - Interval::point(c.y);
        PairBound {
            value: ux * sx + uy * sy,
            gradient: Some([ux.scale(2.0), uy.scale(2.0)]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn bounds_enclose_samples(px in -3.0..3.0f64, py in -3.0..3.0f64, x0 in -2.0..2.0f64, y0 in -2.0..2.0f64,
                                  w in 0.001..1.0f64, h in 0.001..1.0f64, u in 0.0..1.0f64, v in 0.0..1.0f64,
                                  qx in -3.0..3.0f64, qy in -3.0..3.0f64) {
            let f = EuclideanPoint::new(Point::new(px, py));
            let g = EuclideanPoint::new(Point::new(qx, qy));
            let b = Aabb::new(Point::new(x0, y0), Point::new(x0 + w, y0 + h));
            let q = b.at(u, v);
            prop_assert!(f.bound(&(), &b).contains(f.value(q)));
            let gb = f.gradient_bound(&(), &b).unwrap();
            let gq = f.gradient(q);
            prop_assert!(gb[0].contains(gq.x) && gb[1].contains(gq.y));
            let pb = f.pair(&(), &g, &(), &b);
            let h = f.value(q) - g.value(q);
            let lin = (q - f.at).dot(q - f.at) - (q - g.at).dot(q - g.at);
            prop_assert!(pb.value.contains(lin) || lin.abs() < 1e-12);
            if pb.value.excludes_zero() {
                prop_assert!(h.signum() == pb.value.lo.signum());
            }
        }
    }
}
