//! Polynomial distance fields: point sites under the lp, anisotropic, power and Möbius
//! metrics, and the general `field` kind (Emiris et al. 2013, §1.1). Each box carries
//! the field's Bernstein coefficients over it, split by de Casteljau; the range of the
//! coefficients bounds the field (the convex-hull property).

use super::{DistanceField, PairBound};
use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::Bernstein2;
use crate::num::poly::Poly;
use crate::num::Interval;
use crate::scene::Metric;

/// An explicit polynomial field `f(x, y) = g(x − o.x, y − o.y)`, kept in coordinates
/// local to an origin `o` (a point site's position), where its expansion is short and
/// well conditioned: `(x − a)^8` stays one monomial instead of nine large ones.
#[derive(Clone, Debug)]
pub struct PolynomialField {
    origin: Point,
    poly: Poly,
    dx: Poly,
    dy: Poly,
}

impl PolynomialField {
    /// The field `poly(x, y)` in global coordinates.
    pub fn new(poly: Poly) -> Self {
        PolynomialField::local(Point::new(0.0, 0.0), poly)
    }

    /// The field `poly(x − origin.x, y − origin.y)`.
    pub fn local(origin: Point, poly: Poly) -> Self {
        let dx = poly.partial(0);
        let dy = poly.partial(1);
        PolynomialField {
            origin,
            poly,
            dx,
            dy,
        }
    }

    /// The polynomial field of a point site under a non-Euclidean metric.
    pub fn from_metric(at: Point, metric: &Metric) -> Self {
        // in local coordinates u = x − px, v = y − py
        let u = Poly::var(0);
        let v = Poly::var(1);
        let r2 = u.mul(&u).add(&v.mul(&v));
        let poly = match *metric {
            Metric::Euclidean => r2, // not used: Euclidean points have their own field
            Metric::Lp { p } => u.pow(p).add(&v.pow(p)),
            Metric::Anisotropic { matrix: m, weight } => u
                .mul(&u)
                .scale(m[0][0])
                .add(&u.mul(&v).scale(m[0][1] + m[1][0]))
                .add(&v.mul(&v).scale(m[1][1]))
                .sub(&Poly::constant(weight)),
            Metric::Power { weight } => r2.sub(&Poly::constant(weight * weight)),
            Metric::Moebius { scale, weight } => r2.scale(scale).sub(&Poly::constant(weight)),
        };
        PolynomialField::local(at, poly)
    }
}

impl DistanceField for PolynomialField {
    type State = Bernstein2;

    /// The Bernstein form of the field over `b`.
    fn state(&self, b: &Aabb) -> Bernstein2 {
        let local = Aabb::new(b.min - self.origin, b.max - self.origin);
        Bernstein2::from_poly(&self.poly, &local)
    }

    /// The halves of a Bernstein form split by de Casteljau. The absolute error bound is
    /// inherited from the parent; where it has grown large against the child's own
    /// coefficient spread (fields that are tiny near their site, like `(x−a)^8`), the child
    /// is converted afresh from the power basis over its own box.
    fn split(&self, bf: &Bernstein2, b: &Aabb, axis: Axis, at: f64) -> (Bernstein2, Bernstein2) {
        let t = match axis {
            Axis::X => (at - b.min.x) / b.width(),
            Axis::Y => (at - b.min.y) / b.height(),
        };
        let (l, r) = bf.split(axis, t);
        let (lb, rb) = b.split(axis, at);
        let refresh = |c: Bernstein2, cb: &Aabb| {
            let spread = c.range().width();
            if c.err > 1e-6 * spread {
                self.state(cb)
            } else {
                c
            }
        };
        (refresh(l, &lb), refresh(r, &rb))
    }

    fn bound(&self, s: &Bernstein2, _: &Aabb) -> Interval {
        s.range()
    }

    fn gradient_bound(&self, s: &Bernstein2, b: &Aabb) -> Option<[Interval; 2]> {
        Some(gradient_bound(s, b))
    }

    fn value(&self, q: Point) -> f64 {
        let u = q - self.origin;
        self.poly.eval(u.x, u.y, 0.0)
    }

    fn gradient(&self, q: Point) -> Point {
        let u = q - self.origin;
        Point::new(self.dx.eval(u.x, u.y, 0.0), self.dy.eval(u.x, u.y, 0.0))
    }

    fn pair(&self, s: &Bernstein2, _: &Self, so: &Bernstein2, b: &Aabb) -> PairBound {
        pair(s, so, b)
    }
}

/// `∇f` over the box from the Bernstein form's derivatives (taken in the box's relative
/// coordinates, hence divided by the box's width and height).
/// A side of zero length (a box degenerated to a segment) gives no bound in its direction.
fn gradient_bound(bf: &Bernstein2, b: &Aabb) -> [Interval; 2] {
    let per_unit = |axis: Axis, len: f64| {
        if len > 0.0 {
            bf.derivative(axis).range().scale(1.0 / len)
        } else {
            Interval::new(f64::NEG_INFINITY, f64::INFINITY)
        }
    };
    [per_unit(Axis::X, b.width()), per_unit(Axis::Y, b.height())]
}

/// `h = f_a − f_b` in Bernstein form over the box: far tighter than subtracting the two
/// ranges, since the common leading terms cancel (the difference of two quadrics with
/// equal quadratic parts is linear).
fn pair(fa: &Bernstein2, fb: &Bernstein2, b: &Aabb) -> PairBound {
    let (value, [gx, gy]) = fa.difference_bounds(fb);
    let per_unit = |g: Interval, len: f64| {
        if len > 0.0 {
            g.scale(1.0 / len)
        } else {
            Interval::new(f64::NEG_INFINITY, f64::INFINITY)
        }
    };
    PairBound {
        value,
        gradient: Some([per_unit(gx, b.width()), per_unit(gy, b.height())]),
    }
}
