//! Exact signs of the plane's two basic determinants, the only home of Shewchuk's
//! adaptive predicates (crate `robust`) (Shewchuk97).
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
