//! A point site under the lp metric with even p: the field `(x − a)^p + (y − b)^p`,
//! bounded in closed form. The field is separable and each term is an even power, so
//! interval powers give its exact range over a box; the same holds for a pair's
//! difference, whose terms `(x − a)^p − (x − c)^p` are monotone in x (their derivative
//! `p[(x − a)^(p−1) − (x − c)^(p−1)]` has the sign of `c − a` everywhere). Hence the
//! bisector of two lp points is a graph over y (or over x when a = c) in the whole plane.

use super::{bound_difference, DistanceField, PairBound};
use crate::geom::{Aabb, Axis, Point};
use crate::num::interval::ipow;
use crate::num::Interval;

/// The field `(x − a)^p + (y − b)^p` of a point `(a, b)`, p even.
#[derive(Clone, Copy, Debug)]
pub struct LpPoint {
    pub at: Point,
    pub p: u32,
}

impl LpPoint {
    pub fn new(at: Point, p: u32) -> Self {
        LpPoint { at, p }
    }
}

impl DistanceField for LpPoint {
    type State = ();

    fn state(&self, _: &Aabb) {}

    fn split(&self, _: &(), _: &Aabb, _: Axis, _: f64) -> ((), ()) {
        ((), ())
    }

    /// The exact range (outward-rounded) of `(X − a)^p + (Y − b)^p`.
    fn bound(&self, _: &(), b: &Aabb) -> Interval {
        (b.x() - self.at.x).powi(self.p) + (b.y() - self.at.y).powi(self.p)
    }

    /// `∇f = p·((x − a)^(p−1), (y − b)^(p−1))`: odd powers are monotone, so exact ranges.
    fn gradient_bound(&self, _: &(), b: &Aabb) -> Option<[Interval; 2]> {
        let k = self.p as f64;
        Some([
            (b.x() - self.at.x).powi(self.p - 1).scale(k),
            (b.y() - self.at.y).powi(self.p - 1).scale(k),
        ])
    }

    fn value(&self, q: Point) -> f64 {
        ipow(q.x - self.at.x, self.p) + ipow(q.y - self.at.y, self.p)
    }

    fn gradient(&self, q: Point) -> Point {
        let (k, p) = (self.p as f64, self.p - 1);
        Point::new(k * ipow(q.x - self.at.x, p), k * ipow(q.y - self.at.y, p))
    }

    /// Bounds of `f_self − f_other`; for two lp points with the same p coordinate by
    /// coordinate: the range of a monotone term is the hull of its end values, and its
    /// derivative's range is the hull of the values at the ends and at the one critical
    /// point `(a + c)/2` of `(x − a)^(p−1) − (x − c)^(p−1)`.
    fn pair(&self, _: &(), other: &LpPoint, _: &(), b: &Aabb) -> PairBound {
        if other.p != self.p {
            return bound_difference(self, &(), other, &(), b);
        }
        let p = self.p;
        let term = |t: Interval, a: f64, c: f64| (t - a).powi(p) - (t - c).powi(p);
        let slope = |t: Interval, a: f64, c: f64| {
            ((t - a).powi(p - 1) - (t - c).powi(p - 1)).scale(p as f64)
        };
        let axis = |lo: f64, hi: f64, a: f64, c: f64| {
            let (tl, th) = (Interval::point(lo), Interval::point(hi));
            let value = term(tl, a, c).hull(term(th, a, c));
            let mut grad = slope(tl, a, c).hull(slope(th, a, c));
            let m = 0.5 * (a + c);
            if lo < m && m < hi {
                // the critical point, enclosed (the midpoint of a and c is rounded)
                let mi = Interval::new(m.next_down().max(lo), m.next_up().min(hi));
                grad = grad.hull(slope(mi, a, c));
            }
            (value, grad)
        };
        let (vx, gx) = axis(b.min.x, b.max.x, self.at.x, other.at.x);
        let (vy, gy) = axis(b.min.y, b.max.y, self.at.y, other.at.y);
        PairBound {
            value: vx + vy,
            gradient: Some([gx, gy]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn bounds_enclose_samples(px in -2.0..2.0f64, py in -2.0..2.0f64, qx in -2.0..2.0f64, qy in -2.0..2.0f64,
                                  x0 in -2.0..2.0f64, y0 in -2.0..2.0f64, w in 0.0001..1.0f64, h in 0.0001..1.0f64,
                                  u in 0.0..=1.0f64, v in 0.0..=1.0f64, half in 1u32..5) {
            let p = 2 * half;
            let (f, g) = (LpPoint::new(Point::new(px, py), p), LpPoint::new(Point::new(qx, qy), p));
            let b = Aabb::new(Point::new(x0, y0), Point::new(x0 + w, y0 + h));
            let q = b.at(u, v);
            let tol = |x: f64| 1e-12 * (1.0 + x.abs());
            let fv = f.value(q);
            prop_assert!(f.bound(&(), &b).lo - tol(fv) <= fv && fv <= f.bound(&(), &b).hi + tol(fv));
            let pb = f.pair(&(), &g, &(), &b);
            let hv = fv - g.value(q);
            prop_assert!(pb.value.lo - tol(hv) <= hv && hv <= pb.value.hi + tol(hv));
            let gq = f.gradient(q) - g.gradient(q);
            let gb = pb.gradient.unwrap();
            prop_assert!(gb[0].lo - tol(gq.x) <= gq.x && gq.x <= gb[0].hi + tol(gq.x));
            prop_assert!(gb[1].lo - tol(gq.y) <= gq.y && gq.y <= gb[1].hi + tol(gq.y));
            let fg = f.gradient_bound(&(), &b).unwrap();
            let fq = f.gradient(q);
            prop_assert!(fg[0].lo - tol(fq.x) <= fq.x && fq.x <= fg[0].hi + tol(fq.x));
        }

        #[test]
        fn distinct_sites_have_a_monotone_bisector(px in -2.0..2.0f64, qx in -2.0..2.0f64, py in -2.0..2.0f64,
                                                   x0 in -2.0..2.0f64, y0 in -2.0..2.0f64, w in 0.0001..0.5f64) {
            prop_assume!((px - qx).abs() > 1e-3);
            let (f, g) = (LpPoint::new(Point::new(px, py), 8), LpPoint::new(Point::new(qx, py + 0.3), 8));
            let b = Aabb::new(Point::new(x0, y0), Point::new(x0 + w, y0 + w));
            prop_assert!(f.pair(&(), &g, &(), &b).gradient.unwrap()[0].excludes_zero());
        }
    }
}
