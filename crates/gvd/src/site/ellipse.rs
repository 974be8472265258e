//! An ellipse site: the Euclidean distance to the ellipse curve from outside, 0 inside
//! (the inside is part of the site). Box bounds come from the implicit path with the
//! ellipse's offset polynomial; point values from a closed form (Newton on the
//! monotone Lagrange equation).
//!
//! **The offset polynomial.** In the ellipse's frame (`u, v`, semi-axes `a, b`), the
//! circle of radius `z` about `q = (u, v)` is tangent to the ellipse exactly when the
//! pencil `det(λ A + B)` of the two conics (`A = diag(1/a², 1/b², −1)`, `B` the circle)
//! has a double root in `λ`. Cleared of denominators,
//! `(λ + a²)(λ + b²)(S − λ) − a²u²(λ + b²) − b²v²(λ + a²) = c₃λ³ + c₂λ² + c₁λ + c₀` with
//! `S = u² + v² − D`, `D = z²`, `p = a² + b²`, `m = a²b²`:
//! `c₃ = −1`, `c₂ = S − p`, `c₁ = pS − m − a²u² − b²v²`, `c₀ = −mD`,
//! and the offset polynomial is the cubic's discriminant
//! `Δ = 18c₃c₂c₁c₀ − 4c₂³c₀ + c₂²c₁² − 4c₃c₁³ − 27c₃²c₀²`: degree 4 in `D` (8 in `z`,
//! even, so the implicit path works in `D`) and 8 in `u, v`, leading coefficient
//! `(a² − b²)²` in `D`. Its real roots `D ≥ 0` are the squared critical distances from
//! `q` to the ellipse; the smallest is the squared distance (tested against the closed
//! form). At `D = 0`, `Δ = m²E²(c₂² + 4c₁)` with `E = b²u² + a²v² − m`: a double zero on
//! the curve.

use super::implicit::{ImplicitField, ImplicitState};
use super::DistanceField;
use crate::geom::{Aabb, Axis, Point};
use crate::num::poly::Poly;
use crate::num::Interval;

/// The distance field of an ellipse (0 inside).
#[derive(Clone, Debug)]
pub struct EllipseField {
    center: Point,
    a: f64,
    b: f64,
    cos: f64,
    sin: f64,
    implicit: ImplicitField,
}

/// The offset polynomial `Δ(x, y, z)` of the ellipse with semi-axes `a, b` rotated by
/// `(cos, sin)`, in coordinates local to its centre; and its inside polynomial `E`.
pub fn offset_polynomial(a: f64, b: f64, cos: f64, sin: f64) -> (Poly, Poly) {
    let x = Poly::var(0);
    let y = Poly::var(1);
    let z = Poly::var(2);
    let u = x.scale(cos).add(&y.scale(sin));
    let v = y.scale(cos).sub(&x.scale(sin));
    let (a2, b2) = (a * a, b * b);
    let p = a2 + b2;
    let m = a2 * b2;
    let d = z.mul(&z);
    let (uu, vv) = (u.mul(&u), v.mul(&v));
    let s = uu.add(&vv).sub(&d);
    let c2 = s.sub(&Poly::constant(p));
    let c1 = s
        .scale(p)
        .sub(&Poly::constant(m))
        .sub(&uu.scale(a2))
        .sub(&vv.scale(b2));
    let c0 = d.scale(-m);
    // c3 = −1
    let c2c1 = c2.mul(&c1);
    let disc = c2c1
        .mul(&c0)
        .scale(-18.0)
        .sub(&c2.pow(3).mul(&c0).scale(4.0))
        .add(&c2c1.mul(&c2c1))
        .add(&c1.pow(3).scale(4.0))
        .sub(&c0.mul(&c0).scale(27.0));
    let inside = uu.scale(b2).add(&vv.scale(a2)).sub(&Poly::constant(m));
    (disc, inside)
}

impl EllipseField {
    pub fn new(center: Point, semi_axes: [f64; 2], rotation: f64) -> Self {
        let (sin, cos) = rotation.sin_cos();
        let [a, b] = semi_axes;
        let (g, inside) = offset_polynomial(a, b, cos, sin);
        let implicit = ImplicitField::local_field(center, g, 0.0, Some(inside), true);
        EllipseField {
            center,
            a,
            b,
            cos,
            sin,
            implicit,
        }
    }

    /// The implicit field that bounds this ellipse over boxes.
    pub fn implicit(&self) -> &ImplicitField {
        &self.implicit
    }

    /// `q` in the ellipse's frame.
    fn to_local(&self, q: Point) -> Point {
        let d = q - self.center;
        Point::new(
            self.cos * d.x + self.sin * d.y,
            -self.sin * d.x + self.cos * d.y,
        )
    }

    /// The distance and the unit normal (global frame) at `q`; `None` inside.
    fn distance(&self, q: Point) -> Option<(f64, Point)> {
        let l = self.to_local(q);
        let (y0, y1) = (l.x.abs(), l.y.abs());
        let (a, b) = (self.a, self.b);
        let (a2, b2) = (a * a, b * b);
        if (y0 / a).powi(2) + (y1 / b).powi(2) < 1.0 {
            return None;
        }
        // F(t) = (a y0/(t + a²))² + (b y1/(t + b²))² − 1: convex, decreasing for
        // t > −min(a², b²), F(0) ≥ 0 outside; its root t ≥ 0 gives the foot
        // (a² y0/(t + a²), b² y1/(t + b²)).
        let f = |t: f64| {
            let (r0, r1) = (a * y0 / (t + a2), b * y1 / (t + b2));
            let v = r0 * r0 + r1 * r1 - 1.0;
            let d = -2.0 * (r0 * r0 / (t + a2) + r1 * r1 / (t + b2));
            (v, d)
        };
        let (mut lo, mut hi) = (0.0f64, (a2 * y0 * y0 + b2 * y1 * y1).sqrt());
        let mut t = 0.0;
        for _ in 0..200 {
            let (v, d) = f(t);
            if v == 0.0 {
                break;
            }
            if v > 0.0 {
                lo = lo.max(t);
            } else {
                hi = hi.min(t);
            }
            let mut next = t - v / d;
            if !(next > lo && next < hi && next.is_finite()) {
                next = 0.5 * (lo + hi);
            }
            if (next - t).abs() <= 4.0 * f64::EPSILON * t.abs().max(f64::MIN_POSITIVE) {
                t = next;
                break;
            }
            t = next;
        }
        let n0 = y0 / (t + a2);
        let n1 = y1 / (t + b2);
        let dist = t * n0.hypot(n1);
        let len = n0.hypot(n1);
        let (nx, ny) = if len > 0.0 {
            (
                (n0 / len).copysign(if l.x < 0.0 { -1.0 } else { 1.0 }),
                (n1 / len).copysign(if l.y < 0.0 { -1.0 } else { 1.0 }),
            )
        } else {
            (0.0, 0.0)
        };
        let g = Point::new(self.cos * nx - self.sin * ny, self.sin * nx + self.cos * ny);
        Some((dist, g))
    }
}

impl DistanceField for EllipseField {
    type State = ImplicitState;

    fn state(&self, b: &Aabb) -> ImplicitState {
        self.implicit.state(b)
    }

    fn split(
        &self,
        s: &ImplicitState,
        b: &Aabb,
        axis: Axis,
        at: f64,
    ) -> (ImplicitState, ImplicitState) {
        self.implicit.split(s, b, axis, at)
    }

    fn bound(&self, s: &ImplicitState, b: &Aabb) -> Interval {
        let r = self.implicit.bound(s, b);
        Interval::new(r.lo.max(0.0), r.hi.max(0.0))
    }

    fn gradient_bound(&self, s: &ImplicitState, b: &Aabb) -> Option<[Interval; 2]> {
        self.implicit.gradient_bound(s, b)
    }

    fn value(&self, q: Point) -> f64 {
        self.distance(q).map_or(0.0, |d| d.0)
    }

    fn gradient(&self, q: Point) -> Point {
        self.distance(q).map_or(Point::new(0.0, 0.0), |d| d.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force: the nearest of many points of the curve.
    fn brute(a: f64, b: f64, l: Point) -> f64 {
        let n = 200_000;
        (0..n)
            .map(|k| {
                let th = std::f64::consts::TAU * k as f64 / n as f64;
                l.dist(Point::new(a * th.cos(), b * th.sin()))
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn closed_form_and_offset_polynomial_agree_with_brute_force() {
        let e = EllipseField::new(Point::new(0.3, -0.2), [0.3, 0.08], 0.7);
        for k in 0..60 {
            let th = 0.37 * k as f64;
            let r = 0.05 + 0.04 * k as f64;
            let q = Point::new(0.3 + r * th.cos(), -0.2 + r * th.sin());
            let l = e.to_local(q);
            let inside = (l.x / 0.3).powi(2) + (l.y / 0.08).powi(2) < 1.0;
            let v = e.value(q);
            if inside {
                assert_eq!(v, 0.0);
                continue;
            }
            let bf = brute(0.3, 0.08, l);
            assert!(
                (v - bf).abs() < 1e-6,
                "closed form {v} vs brute {bf} at {q:?}"
            );
            let imp = e.implicit.value(q);
            assert!(
                (imp - bf).abs() < 1e-6 * (1.0 + bf),
                "offset polynomial {imp} vs brute {bf} at {q:?}"
            );
        }
    }
}
