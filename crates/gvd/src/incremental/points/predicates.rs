//! Geometric predicates and constructions for point sites.
//!
//! Signs come from Shewchuk's adaptive exact predicates (`robust`); magnitudes used only
//! to *rank* candidates are plain f64 estimates, and the circumcentre is a stable f64
//! construction.

pub(crate) use crate::geom::predicates::incircle;
use crate::geom::Point;

/// An f64 estimate of the power of `d` with respect to the circumcircle of `a, b, c`,
/// `|d − o|² − r² = −incircle(a, b, c, d) / orient(a, b, c)`: a scale-aware `H` used
/// only to rank candidate seeds (signs are always re-checked exactly).
#[inline]
pub(crate) fn power_estimate(a: Point, b: Point, c: Point, d: Point) -> f64 {
    let (a, b, c) = (a - d, b - d, c - d);
    let det = a.dot(a) * b.cross(c) + b.dot(b) * c.cross(a) + c.dot(c) * a.cross(b);
    let o = (b - a).cross(c - a);
    -det / o
}

/// `u × v` to within a few ulps: the plain difference of products when it cancels
/// little (`|u × v| ≥ (|u_x v_y| + |u_y v_x|) / 16`, so its relative error is below
/// 2^-48), else Kahan's 2×2 determinant with fused multiply-adds.
#[inline]
fn cross_accurate(u: Point, v: Point) -> f64 {
    let p = u.x * v.y;
    let q = u.y * v.x;
    let d = p - q;
    if d.abs() * 16.0 >= p.abs() + q.abs() {
        return d;
    }
    let e = u.x.mul_add(v.y, -p);
    let f = u.y.mul_add(v.x, -q);
    d + (e - f)
}

/// The circumcentre of the counter-clockwise triangle `a, b, c`, computed relative to
/// the vertex shared by the two shortest sides (Shewchuk's advice): with `u = b − a`,
/// `v = c − a` and `D = 2 (u × v)` (evaluated accurately),
/// `o = a + (v_y |u|² − u_y |v|², u_x |v|² − v_x |u|²) / D`.
/// When `D` underflows to a non-positive value the centre is "at infinity": a point
/// `10^100` away in the direction of the numerator.
pub(crate) fn circumcenter(a: Point, b: Point, c: Point) -> Point {
    let (lab, lbc, lca) = ((b - a).dot(b - a), (c - b).dot(c - b), (a - c).dot(a - c));
    // Rotate so that `a` is opposite the longest side.
    let (a, b, c) = if lbc >= lab && lbc >= lca {
        (a, b, c)
    } else if lca >= lab {
        (b, c, a)
    } else {
        (c, a, b)
    };
    let (u, v) = (b - a, c - a);
    let (u2, v2) = (u.dot(u), v.dot(v));
    let num = Point::new(v.y * u2 - u.y * v2, u.x * v2 - v.x * u2);
    let d = 2.0 * cross_accurate(u, v);
    if d > 0.0 {
        a + Point::new(num.x / d, num.y / d)
    } else {
        a + num * (1e100 / num.norm().max(f64::MIN_POSITIVE))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circumcenter_of_a_sliver_with_two_close_vertices() {
        let a = Point::new(3.00000000000002, -1.0);
        let b = Point::new(2.00000000000001, -3e-15);
        let c = Point::new(2.00000000000002, 0.0);
        let (a, b, c) = if (b - a).cross(c - a) > 0.0 {
            (a, b, c)
        } else {
            (a, c, b)
        };
        let exact = Point::new(2.234926294621772, -0.7650737053782479);
        for (p, q, r) in [(a, b, c), (b, c, a), (c, a, b)] {
            assert!(circumcenter(p, q, r).dist(exact) < 1e-14);
        }
    }
}
