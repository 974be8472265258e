//! Exact signs of the plane's two basic determinants, the only home of Shewchuk's
//! adaptive predicates (crate `robust`) (Shewchuk97), and the exact comparison of two
//! distances from a point and the segment's point nearest to the origin, by the same
//! expansion arithmetic.
//!
//! `orient2d` and `incircle` are exact as long as no intermediate product overflows or
//! underflows: every coordinate (and every difference of coordinates) within
//! [`ORIENT_EXACT_RANGE`] for [`orient2d`], within [`INCIRCLE_EXACT_RANGE`] for
//! [`incircle`]. The engines rescale their input to about 1 first; [`orientation`]
//! rescales by a power of two itself and takes any finite input.

use super::Point;
use robust::Coord;
use std::cmp::Ordering;

/// Magnitudes `(min, max)` of coordinates for which [`orient2d`]'s sign is exact:
/// products of two of them stay far from overflow and underflow.
pub const ORIENT_EXACT_RANGE: (f64, f64) = (1e-120, 1e120);

/// Magnitudes `(min, max)` of coordinates for which [`incircle`]'s sign is exact:
/// products of four of them stay far from overflow and underflow.
pub const INCIRCLE_EXACT_RANGE: (f64, f64) = (1e-60, 1e60);

#[inline]
fn coord(p: Point) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

/// `(b − a) × (c − a)`, with its sign exact: positive when `a, b, c` turn
/// counter-clockwise. Exact within [`ORIENT_EXACT_RANGE`].
#[inline]
pub fn orient2d(a: Point, b: Point, c: Point) -> f64 {
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// The incircle determinant `det[[a−d, |a−d|²], [b−d, |b−d|²], [c−d, |c−d|²]]`, with
/// its sign exact: for counter-clockwise `a, b, c` it is > 0 iff `d` lies strictly inside
/// their circumcircle. Exact within [`INCIRCLE_EXACT_RANGE`].
#[inline]
pub fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64 {
    robust::incircle(coord(a), coord(b), coord(c), coord(d))
}

/// The sign of [`orient2d`] for any finite input: `Greater` when counter-clockwise.
/// Coordinates outside [`ORIENT_EXACT_RANGE`] are first scaled by a power of two
/// (exact) to about 1.
pub fn orientation(a: Point, b: Point, c: Point) -> Ordering {
    let m = [a, b, c]
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let (lo, hi) = ORIENT_EXACT_RANGE;
    let s = if m == 0.0 || (m > lo && m < hi) {
        1.0
    } else {
        2f64.powi(-(m.log2().ceil() as i32))
    };
    let k = |p: Point| Point::new(p.x * s, p.y * s);
    orient2d(k(a), k(b), k(c))
        .partial_cmp(&0.0)
        .unwrap_or(Ordering::Equal)
}

/// The sign of `|q − a|² − |q − b|²`, exact: `Less` when `q` is nearer `a`, `Equal` on
/// their bisector. Each coordinate difference is split into its rounded value and its
/// error (two-diff), each square into products with their fused-multiply-add errors, and
/// the 24 terms are summed without rounding into a nonoverlapping expansion (Shewchuk's
/// grow-expansion), whose largest component carries the sign (Shewchuk97, §2). Exact
/// within [`ORIENT_EXACT_RANGE`] (the products and their errors stay normal).
pub fn compare_distances(q: Point, a: Point, b: Point) -> Ordering {
    let mut expansion: Vec<f64> = Vec::with_capacity(24);
    for (site, sign) in [(a, 1.0), (b, -1.0)] {
        for (u, v) in [(q.x, site.x), (q.y, site.y)] {
            let (h, l) = two_diff(u, v);
            // (h + l)² = h·h + 2h·l + l·l
            for (x, y) in [(h, h), (2.0 * h, l), (l, l)] {
                let p = x * y;
                let e = x.mul_add(y, -p);
                grow_expansion(&mut expansion, sign * p);
                grow_expansion(&mut expansion, sign * e);
            }
        }
    }
    let top = expansion.iter().rev().find(|c| **c != 0.0).copied();
    top.unwrap_or(0.0)
        .partial_cmp(&0.0)
        .unwrap_or(Ordering::Equal)
}

/// The point of the segment from `a` to `b` nearest to the origin, and its parameter
/// `λ ∈ [0, 1]` along `b − a`: an end itself when `λ` is 0 or 1; otherwise
/// `a + λ·b − λ·a` for the rounded `λ`, its terms split by fused multiply-adds and summed
/// as an expansion, so the point is rounded once and lies within an ulp of the segment
/// however far its ends are (in f64, `a + λ·(b − a)` is off by an ulp of the ends).
/// Lines measured from it lose no more precision near the origin than the coordinates
/// there carry.
pub fn nearest_to_origin(a: Point, b: Point) -> (Point, f64) {
    let v = b - a;
    let lambda = -a.dot(v) / v.dot(v);
    if lambda.is_nan() || lambda <= 0.0 {
        return (a, 0.0);
    }
    if lambda >= 1.0 {
        return (b, 1.0);
    }
    let on_segment = |a: f64, b: f64| {
        let mut expansion: Vec<f64> = Vec::with_capacity(5);
        grow_expansion(&mut expansion, a);
        for (x, sign) in [(b, 1.0), (a, -1.0)] {
            let p = lambda * x;
            grow_expansion(&mut expansion, sign * p);
            grow_expansion(&mut expansion, sign * lambda.mul_add(x, -p));
        }
        expansion.iter().sum::<f64>()
    };
    (
        Point::new(on_segment(a.x, b.x), on_segment(a.y, b.y)),
        lambda,
    )
}

/// The point of the segment from `a` to `b` that a line through them is best measured
/// from near the origin, with its parameter along `b − a`: `a` itself (as engines
/// always did) while both its coordinates lie within `reach`, else the point nearest
/// to the origin ([`nearest_to_origin`]): from an end 1e15 away, `x − a` rounds every
/// point `x` of a domain 4 wide to 0.125.
pub fn segment_anchor(a: Point, b: Point, reach: f64) -> (Point, f64) {
    if a.x.abs().max(a.y.abs()) <= reach {
        (a, 0.0)
    } else {
        nearest_to_origin(a, b)
    }
}

/// `a − b` as `x + y` exactly, `x` the rounded difference (Knuth's two-sum).
fn two_diff(a: f64, b: f64) -> (f64, f64) {
    two_sum(a, -b)
}

/// `a + b` as `x + y` exactly, `x` the rounded sum.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let bv = x - a;
    let av = x - bv;
    (x, (a - av) + (b - bv))
}

/// Adds `t` to a nonoverlapping expansion sorted by increasing magnitude, keeping it so
/// (zero components dropped).
fn grow_expansion(expansion: &mut Vec<f64>, t: f64) {
    let mut q = t;
    let mut k = 0;
    for i in 0..expansion.len() {
        let (sum, err) = two_sum(q, expansion[i]);
        q = sum;
        if err != 0.0 {
            expansion[k] = err;
            k += 1;
        }
    }
    expansion.truncate(k);
    if q != 0.0 {
        expansion.push(q);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_is_exact_where_f64_cancels() {
        // c is on the line through a and b up to one ulp: the naive cross product
        // rounds to zero or the wrong sign, the exact sign does not.
        let a = Point::new(0.5, 0.5);
        let b = Point::new(12.0, 12.0);
        let c = Point::new(24.0, 24.0 + 24.0 * f64::EPSILON);
        assert_eq!(orientation(a, b, c), Ordering::Greater);
        assert_eq!(orientation(a, c, b), Ordering::Less);
        assert_eq!(orientation(a, b, Point::new(24.0, 24.0)), Ordering::Equal);
    }

    #[test]
    fn orientation_survives_extreme_scales() {
        for s in [1e-300, 1e300] {
            let p = |x: f64, y: f64| Point::new(x * s, y * s);
            assert_eq!(
                orientation(p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)),
                Ordering::Greater
            );
        }
    }

    #[test]
    fn distances_compare_exactly_where_f64_ties() {
        // q on the bisector x = 0.75 of (0, 0) and (1.5, 0), and one ulp off it
        let (a, b) = (Point::new(0.0, 0.0), Point::new(1.5, 0.0));
        for y in [0.0, -0.0822283471778805, 0.3, 1.7] {
            let q = Point::new(0.75, y);
            assert_eq!(compare_distances(q, a, b), Ordering::Equal, "{y}");
            let left = Point::new(0.75 - f64::EPSILON / 2.0, y);
            assert_eq!(compare_distances(left, a, b), Ordering::Less, "{y}");
            let right = Point::new(0.75 + f64::EPSILON, y);
            assert_eq!(compare_distances(right, a, b), Ordering::Greater, "{y}");
        }
        // a bisector tilted by 2e-16: along x = 0.75 − ulp it crosses once, at y ≈ 0.25
        let tilted = Point::new(1.5, 3.0 * f64::EPSILON);
        let x = 0.75 - f64::EPSILON / 2.0;
        let near = |y: f64| compare_distances(Point::new(x, y), a, tilted);
        assert_eq!(near(0.1), Ordering::Less);
        assert_eq!(near(0.5), Ordering::Greater);
    }

    /// Segments with both ends 1e15 away, passing the unit square: the point found
    /// lies within an ulp of the segment (by the exact orientation's value over the
    /// length), where `a + λ·(b − a)` in f64 is off by about an ulp of the far ends. An
    /// end nearest to the origin is returned as it is.
    #[test]
    fn nearest_to_origin_lies_on_far_segments() {
        let mut naive_off = 0.0f64;
        for k in 0..200 {
            let angle = 0.1 + 0.0137 * k as f64;
            let dir = Point::new(angle.cos(), angle.sin());
            let a = Point::new(0.3, -0.7) + dir * -1e15;
            let b = Point::new(0.3, -0.7) + dir * (3e14 + 7e14 * (k % 2) as f64);
            let (o, lambda) = nearest_to_origin(a, b);
            assert!(lambda > 0.0 && lambda < 1.0, "{k}: {lambda}");
            let off = |p: Point| orient2d(a, b, p).abs() / a.dist(b);
            assert!(
                off(o) <= f64::EPSILON * o.norm().max(1.0),
                "{k}: {}",
                off(o)
            );
            assert!(o.norm() < 1.0, "{k}: {o:?}");
            naive_off = naive_off.max(off(a + (b - a) * lambda));
        }
        assert!(naive_off > 1e-3, "{naive_off}");
        let (a, b) = (Point::new(1e15, 0.0), Point::new(0.67, 0.0));
        assert_eq!(nearest_to_origin(a, b), (b, 1.0));
        assert_eq!(nearest_to_origin(b, a), (b, 0.0));
    }

    #[test]
    fn incircle_sign() {
        let (a, b, c) = (
            Point::new(1.0, 0.0),
            Point::new(0.0, 1.0),
            Point::new(-1.0, 0.0),
        );
        assert!(incircle(a, b, c, Point::new(0.0, 0.0)) > 0.0);
        assert!(incircle(a, b, c, Point::new(0.0, -2.0)) < 0.0);
        assert_eq!(incircle(a, b, c, Point::new(0.0, -1.0)), 0.0);
    }
}
