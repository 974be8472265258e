//! The bisectors in parameter space (HREK07 §3, §7.1, after Elber–Kim): the function
//! `F3(t, r)` of two spans as a bivariate Bernstein form, the bisector point `P(t, r)`
//! (eq. 5), the point/curve bisector `B(t)` (eq. 29), and the per-span polynomials of
//! the foot-point equation used for distances.
//!
//! With a span in homogeneous form `H = (X, Y, W)`, `C = (X, Y)/W` and `C' = T/W²` with
//! `T = (X'W − XW', Y'W − YW')`. The normal line at `t` is `a·P = S` with `a = W T`,
//! `S = X T_x + Y T_y` (eq. 4 times `W`). Cramer's rule gives `P = N / det` with
//! `det = a₀ × a₁`, `N = (S₀ a₁y − S₁ a₀y, a₀x S₁ − a₁x S₀)`, and eq. 3 times
//! `2 det W₀² W₁²` is
//! `F3 = 2 W₀W₁ ⟨N, E⟩ − det · Q`, `E = (X₀W₁ − X₁W₀, Y₀W₁ − Y₁W₀)`,
//! `Q = (X₀² + Y₀²) W₁² − (X₁² + Y₁²) W₀²`. Polynomial spans take `W = 1`, `T = H'`.

use super::trim::Eval;
use crate::geom::bezier::RationalBezier;
use crate::geom::Point;
use crate::num::bernstein::{Bernstein1, Bernstein2};

/// The univariate Bernstein forms of one span used by the bisector functions.
#[derive(Clone, Debug)]
pub struct SpanForms {
    /// `X`, `Y`, `W` of the homogeneous curve (`W = 1` for polynomial spans).
    pub x: Bernstein1,
    /// See `x`.
    pub y: Bernstein1,
    /// See `x`.
    pub w: Bernstein1,
    /// `a = W T`, the normal line's coefficients.
    pub ax: Bernstein1,
    /// See `ax`.
    pub ay: Bernstein1,
    /// `S = X T_x + Y T_y`, the normal line's right-hand side.
    pub s: Bernstein1,
}

impl SpanForms {
    /// The forms of `c`.
    pub fn new(c: &RationalBezier) -> SpanForms {
        let h = c.homogeneous();
        let coord =
            |k: usize, scale: f64| Bernstein1::exact(h.iter().map(|p| p[k] * scale).collect());
        if c.is_polynomial() {
            let inv = 1.0 / h[0][2];
            let (x, y) = (coord(0, inv), coord(1, inv));
            let (tx, ty) = (x.derivative(), y.derivative());
            let s = x.mul(&tx).add(&y.mul(&ty));
            SpanForms {
                w: Bernstein1::constant(1.0),
                ax: tx,
                ay: ty,
                s,
                x,
                y,
            }
        } else {
            let (x, y, w) = (coord(0, 1.0), coord(1, 1.0), coord(2, 1.0));
            let wd = w.derivative();
            let tx = x.derivative().mul(&w).sub(&x.mul(&wd));
            let ty = y.derivative().mul(&w).sub(&y.mul(&wd));
            let s = x.mul(&tx).add(&y.mul(&ty));
            SpanForms {
                ax: w.mul(&tx),
                ay: w.mul(&ty),
                s,
                x,
                y,
                w,
            }
        }
    }

    /// The foot-point polynomial `G(t) = W ⟨C(t) − q, T(t)⟩ … ` whose roots are the
    /// parameters where `C(t) − q ⟂ C'(t)`: `G = S − q_x a_x − q_y a_y` (a positive
    /// multiple `W²` of `⟨C − q, C'⟩ W³`).
    pub fn foot(&self, q: Point) -> Bernstein1 {
        self.s.sub(&self.ax.scale(q.x)).sub(&self.ay.scale(q.y))
    }
}

/// `F3(t, r)` of spans `a` (parameter `t`, first variable) and `b` (`r`) (eq. 7).
pub fn f3(a: &SpanForms, b: &SpanForms) -> Bernstein2 {
    let t = Bernstein2::tensor;
    let det = t(&a.ax, &b.ay).sub(&t(&a.ay, &b.ax));
    let nx = t(&a.s, &b.ay).sub(&t(&a.ay, &b.s));
    let ny = t(&a.ax, &b.s).sub(&t(&a.s, &b.ax));
    let ex = t(&a.x, &b.w).sub(&t(&a.w, &b.x));
    let ey = t(&a.y, &b.w).sub(&t(&a.w, &b.y));
    let q = t(&a.x.mul(&a.x).add(&a.y.mul(&a.y)), &b.w.mul(&b.w))
        .sub(&t(&a.w.mul(&a.w), &b.x.mul(&b.x).add(&b.y.mul(&b.y))));
    let ww = t(&a.w.scale(2.0), &b.w);
    ww.mul(&nx.mul(&ex).add(&ny.mul(&ey))).sub(&det.mul(&q))
}

/// The corners `(t, r)` of the parameter square where spans `a` and `b` share an end
/// point (within rounding of the knot insertion).
pub fn shared_ends(a: &RationalBezier, b: &RationalBezier) -> Vec<Point> {
    let mut out = Vec::new();
    let tol = 1e-12 * (1.0 + a.control_box().longest_side() + a.eval(0.0).norm());
    for t in [0.0, 1.0] {
        for r in [0.0, 1.0] {
            if a.eval(t).dist(b.eval(r)) <= tol {
                out.push(Point::new(t, r));
            }
        }
    }
    out
}

/// The intersection of the normal lines of `a` at `t` and of `b` at `r` (eq. 5), or
/// `None` where they are parallel.
pub fn normals_meet(a: &RationalBezier, t: f64, b: &RationalBezier, r: f64) -> Option<Point> {
    let [c0, d0, _] = a.derivatives(t);
    let [c1, d1, _] = b.derivatives(r);
    solve2(d0, c0.dot(d0), d1, c1.dot(d1))
}

/// The point on the normal of `a` at `t` equidistant from `a(t)` and `b(r)`:
/// `P = C₀ + s n̂` with `|P − C₀|² = |P − C₁|²`, i.e. `s = |C₁ − C₀|² / (2⟨n̂, C₁ − C₀⟩)`.
/// At a zero of `F3` it is `P(t, r)` of eq. 5, and it stays well conditioned where the
/// normals are parallel: for two parallel lines `F3 = 0` is the line of their common
/// normals, along which eq. 5 is `0/0` and the bisector point is the feet's midpoint.
/// `None` where `C₁ − C₀` is tangent to `a`.
pub fn equidistant_on_normal(
    a: &RationalBezier,
    t: f64,
    b: &RationalBezier,
    r: f64,
) -> Option<Point> {
    let [c0, d0, _] = a.derivatives(t);
    let v = b.eval(r) - c0;
    let n = d0.perp() * (1.0 / d0.norm());
    let h = n.dot(v);
    if h.is_nan() || h.abs() <= 1e-14 * v.norm() {
        return None;
    }
    Some(c0 + n * (0.5 * v.dot(v) / h))
}

/// The point/curve bisector point `B(t)` of corner `p` and span `c` (eqs. 27–29):
/// `⟨B, C'⟩ = ⟨C, C'⟩`, `⟨B, C − p⟩ = (|C|² − |p|²)/2`; `None` at a pole.
pub fn point_curve(c: &RationalBezier, t: f64, p: Point) -> Option<Point> {
    let [q, d, _] = c.derivatives(t);
    let v = q - p;
    solve2(d, q.dot(d), v, 0.5 * (q.dot(q) - p.dot(p)))
}

/// Where the feet `a(t)` and `b(r)` coincide (within `tol`) with parallel normals: the
/// centre of curvature there, the limit of the bisector of two parts of one curve at a
/// vertex (the end of a ridge, HREK07 §8).
pub fn ridge_end(a: &RationalBezier, t: f64, b: &RationalBezier, r: f64, tol: f64) -> Option<Eval> {
    let p = a.eval(t);
    if p.dist(b.eval(r)) > tol {
        return None;
    }
    let centre = centre_of_curvature(a, t)?;
    Some(Eval {
        p: centre,
        d: centre.dist(p),
        feet: [Some(t), Some(r)],
        at_ends: false,
    })
}

/// The centre of curvature `C + N̂/κ` of `c` at `t`, `None` where `κ = 0`.
pub fn centre_of_curvature(c: &RationalBezier, t: f64) -> Option<Point> {
    let [p, d1, d2] = c.derivatives(t);
    let len2 = d1.dot(d1);
    let k = d1.cross(d2) / (len2 * len2.sqrt());
    if k.is_nan() || k == 0.0 {
        return None;
    }
    let n = d1.perp() * (1.0 / len2.sqrt());
    Some(p + n * (1.0 / k))
}

/// The local nearest point of span `c` to `q` near parameter `t`: Newton on
/// `g'(t) = ⟨C(t) − q, C'(t)⟩`, with `g''(t) = |C'|² + ⟨C(t) − q, C''⟩ > 0` (a minimum
/// of the distance, the curvature constraint of eq. 22) all along. `None` where that
/// minimum has gone: `q` lies beyond the evolute there, or the foot leaves the span.
pub fn local_foot(c: &RationalBezier, mut t: f64, q: Point) -> Option<f64> {
    for _ in 0..16 {
        let [p, d1, d2] = c.derivatives(t);
        let v = p - q;
        let (g1, g2) = (v.dot(d1), d1.dot(d1) + v.dot(d2));
        if g2.is_nan() || g2 <= 0.0 {
            return None;
        }
        let step = g1 / g2;
        t -= step;
        if !(0.0..=1.0).contains(&t) {
            return None;
        }
        // the existence of the minimum is the question, not its last digits
        if step.abs() <= 1e-10 {
            return Some(t);
        }
    }
    None
}

/// `x` with `⟨x, u⟩ = a`, `⟨x, v⟩ = b` (Cramer's rule), `None` when `u ∥ v`.
fn solve2(u: Point, a: f64, v: Point, b: f64) -> Option<Point> {
    let det = u.x * v.y - u.y * v.x;
    let scale = u.norm() * v.norm();
    if det.is_nan() || det.abs() <= 1e-14 * scale {
        return None;
    }
    Some(Point::new(
        (a * v.y - b * u.y) / det,
        (u.x * b - v.x * a) / det,
    ))
}

/// The signed offset `⟨q − C(t), N_L(t)⟩ / |C'|` of `q` from span `c` at `t` (eq. 8),
/// and the curvature test value `⟨q − C(t), κ N̂⟩` (eq. 22; the constraint is `< 1`).
pub fn side_and_curvature(c: &RationalBezier, t: f64, q: Point) -> (f64, f64) {
    let [p, d1, d2] = c.derivatives(t);
    let n = d1.perp(); // (−y', x')
    let len2 = d1.dot(d1);
    let v = q - p;
    let side = v.dot(n) / len2.sqrt();
    // κ N̂ = (C' × C'') / |C'|⁴ · N_L
    let k = d1.cross(d2) / (len2 * len2);
    (side, k * v.dot(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arc(c: Point, r: f64, a0: f64, a1: f64) -> RationalBezier {
        // a circular arc of less than π as a rational quadratic (Farin02)
        let h = 0.5 * (a1 - a0);
        let m = 0.5 * (a0 + a1);
        let p0 = c + Point::new(a0.cos(), a0.sin()) * r;
        let p2 = c + Point::new(a1.cos(), a1.sin()) * r;
        let p1 = c + Point::new(m.cos(), m.sin()) * (r / h.cos());
        RationalBezier::new(&[p0, p1, p2], Some(&[1.0, h.cos(), 1.0]))
    }

    #[test]
    fn f3_vanishes_exactly_on_bisector_points() {
        // two cubic spans; F3's zero set gives equidistant normal intersections
        let a = RationalBezier::new(
            &[
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.5),
                Point::new(2.0, -0.5),
                Point::new(3.0, 0.2),
            ],
            None,
        );
        let b = arc(Point::new(1.5, 3.0), 1.0, -2.5, -0.6);
        let f = f3(&SpanForms::new(&a), &SpanForms::new(&b));
        let mut found = 0;
        for i in 1..20 {
            let t = i as f64 / 20.0;
            let col = f.restrict(crate::geom::Axis::X, t);
            for root in crate::num::roots::isolate(&col, 1e-12) {
                if !root.certified {
                    continue;
                }
                let r = crate::num::roots::refine(&col, root.lo, root.hi);
                let p = normals_meet(&a, t, &b, r).unwrap();
                let (d0, d1) = (p.dist(a.eval(t)), p.dist(b.eval(r)));
                assert!((d0 - d1).abs() < 1e-9 * (1.0 + d0), "{d0} {d1}");
                found += 1;
            }
        }
        assert!(found > 5, "{found}");
    }

    #[test]
    fn point_curve_bisector_is_equidistant_and_curvature_of_arc_is_one_over_r() {
        let c = arc(Point::new(0.0, 0.0), 2.0, 0.2, 1.4);
        let p = Point::new(3.0, 3.0);
        for t in [0.1, 0.5, 0.9] {
            let b = point_curve(&c, t, p).unwrap();
            assert!((b.dist(p) - b.dist(c.eval(t))).abs() < 1e-12);
            // the centre is to the left of a counter-clockwise arc at distance 2:
            // the curvature test value there is exactly 1
            let (side, k) = side_and_curvature(&c, t, Point::new(0.0, 0.0));
            assert!(
                (side - 2.0).abs() < 1e-12 && (k - 1.0).abs() < 1e-12,
                "{side} {k}"
            );
        }
    }
}
