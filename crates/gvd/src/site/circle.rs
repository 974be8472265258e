//! A circle site of the Apollonius (additively weighted) diagram: the field
//! `f(q) = |q − c| − r`, bounded in closed form (the fast path; the implicit path of
//! [`super::implicit`] computes the same field from `g = |q − c|² − w²`, `w = z + r`).

use super::{DistanceField, PairBound};
use crate::geom::{Aabb, Axis, Point};
use crate::num::Interval;

/// The field `f(q) = |q − c| − r` of a circle (a point when `r = 0`).
#[derive(Clone, Copy, Debug)]
pub struct CircleField {
    pub center: Point,
    pub radius: f64,
}

/// `|q − c|` over a box: exact range, outward-rounded.
fn dist_bound(c: Point, b: &Aabb) -> Interval {
    let dx = b.x() - c.x;
    let dy = b.y() - c.y;
    (dx.sqr() + dy.sqr()).sqrt()
}

/// `(q − c)/|q − c|` over a box; the unit square when the box holds `c`.
fn unit_bound(c: Point, b: &Aabb) -> [Interval; 2] {
    let dx = b.x() - c.x;
    let dy = b.y() - c.y;
    let r = dist_bound(c, b);
    let unit = Interval::new(-1.0, 1.0);
    match (dx.div(r), dy.div(r)) {
        (Some(gx), Some(gy)) => [
            Interval::new(gx.lo.max(-1.0), gx.hi.min(1.0)),
            Interval::new(gy.lo.max(-1.0), gy.hi.min(1.0)),
        ],
        _ => [unit, unit],
    }
}

impl CircleField {
    pub fn new(center: Point, radius: f64) -> Self {
        CircleField { center, radius }
    }
}

impl DistanceField for CircleField {
    type State = ();

    fn state(&self, _: &Aabb) {}

    fn split(&self, _: &(), _: &Aabb, _: Axis, _: f64) -> ((), ()) {
        ((), ())
    }

    /// The exact range of `|q − c| − r` over the box, outward-rounded.
    fn bound(&self, _: &(), b: &Aabb) -> Interval {
        dist_bound(self.center, b) - self.radius
    }

    /// The gradient (a unit vector wherever it exists) over the box.
    fn gradient_bound(&self, _: &(), b: &Aabb) -> Option<[Interval; 2]> {
        Some(unit_bound(self.center, b))
    }

    fn value(&self, q: Point) -> f64 {
        q.dist(self.center) - self.radius
    }

    fn gradient(&self, q: Point) -> Point {
        let d = q - self.center;
        let r = d.norm();
        if r == 0.0 {
            Point::new(0.0, 0.0)
        } else {
            d * (1.0 / r)
        }
    }

    /// Two circles: see [`pair`].
    fn pair(&self, _: &(), other: &CircleField, _: &(), b: &Aabb) -> PairBound {
        pair((self.center, self.radius), (other.center, other.radius), b)
    }
}

/// `h = f_a − f_b = |q − a| − |q − b| − (r_a − r_b)` over a box for two circles (a point
/// is a circle of radius 0): the better of the difference of the two exact ranges and
/// the mean-value form `h(m) + ∇h(B)·(B − m)` about the box's centre `m`, which is
/// tight to second order where the bisector runs.
pub fn pair(a: (Point, f64), b: (Point, f64), bx: &Aabb) -> PairBound {
    let ga = unit_bound(a.0, bx);
    let gb = unit_bound(b.0, bx);
    let g = [ga[0] - gb[0], ga[1] - gb[1]];
    let naive = (dist_bound(a.0, bx) - a.1) - (dist_bound(b.0, bx) - b.1);
    let m = bx.center();
    let mb = Aabb::new(m, m);
    let hm = (dist_bound(a.0, &mb) - a.1) - (dist_bound(b.0, &mb) - b.1);
    let hw = bx.x() - m.x;
    let hh = bx.y() - m.y;
    let mv = hm + g[0] * hw + g[1] * hh;
    let value = if mv.lo.is_finite() && mv.hi.is_finite() {
        Interval::new(naive.lo.max(mv.lo), naive.hi.min(mv.hi))
    } else {
        naive
    };
    PairBound {
        value: if value.lo <= value.hi { value } else { naive },
        gradient: Some(g),
    }
}
