//! Closed rings of points (the last point not repeated): area, orientation and
//! point-in-ring tests.

use super::predicates::orientation;
use super::Point;
use std::cmp::Ordering;

/// The signed area by the shoelace formula `½ Σ pᵢ × pᵢ₊₁`: positive for a
/// counter-clockwise ring.
pub fn signed_area(ring: &[Point]) -> f64 {
    let n = ring.len();
    0.5 * (0..n)
        .map(|i| ring[i].cross(ring[(i + 1) % n]))
        .sum::<f64>()
}

/// Whether the ray from `q` towards +x crosses the ring an odd number of times (the
/// even-odd rule, in f64: points within rounding of the ring may go either way).
pub fn even_odd_contains(ring: &[Point], q: Point) -> bool {
    let mut inside = false;
    for (k, &a) in ring.iter().enumerate() {
        let b = ring[(k + 1) % ring.len()];
        if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y) {
            inside = !inside;
        }
    }
    inside
}

/// The winding number of the ring around `q` (not on the ring), with exact orientation
/// signs (Sunday01).
pub fn winding_number(ring: &[Point], q: Point) -> i64 {
    let n = ring.len();
    let mut winding = 0i64;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        if a.y <= q.y {
            if b.y > q.y && orientation(a, b, q) == Ordering::Greater {
                winding += 1;
            }
        } else if b.y <= q.y && orientation(a, b, q) == Ordering::Less {
            winding -= 1;
        }
    }
    winding
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<Point> {
        [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]
            .iter()
            .map(|&(x, y)| Point::new(x, y))
            .collect()
    }

    #[test]
    fn area_sign_follows_orientation() {
        let mut r = square();
        assert_eq!(signed_area(&r), 4.0);
        r.reverse();
        assert_eq!(signed_area(&r), -4.0);
    }

    #[test]
    fn inside_and_outside_agree_between_the_two_rules() {
        let r = square();
        for (x, y, inside) in [
            (1.0, 1.0, true),
            (3.0, 1.0, false),
            (1.0, -0.5, false),
            (0.5, 1.9, true),
        ] {
            let q = Point::new(x, y);
            assert_eq!(even_odd_contains(&r, q), inside);
            assert_eq!(winding_number(&r, q) != 0, inside);
        }
        let mut cw = square();
        cw.reverse();
        assert_eq!(winding_number(&cw, Point::new(1.0, 1.0)), -1);
    }
}
