//! Closed rings of points (the last point not repeated): area, orientation and
//! point-in-ring tests.

use super::grid::{bounds_of_points, BucketGrid};
use super::predicates::orientation;
use super::{Aabb, Point};
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
        if ray_crossing(a, ring[(k + 1) % ring.len()], q).is_some() {
            inside = !inside;
        }
    }
    inside
}

/// Whether the ray from `q` towards +x crosses the segment `a b` under the rule of
/// [`even_odd_contains`], and where.
fn ray_crossing(a: Point, b: Point, q: Point) -> Option<f64> {
    if (a.y > q.y) == (b.y > q.y) {
        return None;
    }
    let x = a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y);
    (q.x < x).then_some(x)
}

/// The even-odd test of [`even_odd_contains`] against a fixed set of segments (the
/// edges of any number of rings: the parity of the crossings of all of them is the
/// parity of the rings that hold `q`), with the segments bucketed in a grid so that a
/// ray meets only the cells of its row: about `√n` segments a query, not `n`.
pub(crate) struct RayCrossings {
    segments: Vec<(Point, Point)>,
    grid: BucketGrid,
}

impl RayCrossings {
    /// The index of `segments`.
    pub(crate) fn new(segments: Vec<(Point, Point)>) -> RayCrossings {
        let extent = bounds_of_points(segments.iter().flat_map(|&(a, b)| [a, b]));
        let side = extent.longest_side() / (segments.len() as f64).sqrt().max(1.0);
        let grid = BucketGrid::new(extent, side, 4096, segments.len(), |k| {
            let (a, b) = segments[k];
            bounds_of_points([a, b])
        });
        RayCrossings { segments, grid }
    }

    /// Whether the ray from `q` towards +x crosses the segments an odd number of times.
    pub(crate) fn odd(&self, q: Point) -> bool {
        if self.segments.is_empty() {
            return false;
        }
        let far = Point::new(f64::MAX, q.y);
        let mut odd = false;
        // a segment lies in every cell of the row its box meets: it is counted in the
        // cell that holds its crossing point (clamped to its box against rounding)
        self.grid.for_each_in(&Aabb::new(q, far), |cell, k| {
            let (a, b) = self.segments[k as usize];
            if let Some(x) = ray_crossing(a, b, q) {
                let x = x.clamp(a.x.min(b.x), a.x.max(b.x));
                if self.grid.cell_of(Point::new(x, q.y)) == cell {
                    odd = !odd;
                }
            }
        });
        odd
    }
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
    #[test]
    fn ray_crossings_agree_with_the_ring_by_ring_test() {
        use super::*;
        // a wavy ring, a square hole and a separate triangle, probed on a grid that
        // hits their vertices' coordinates exactly too
        let wavy: Vec<Point> = (0..400)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 400.0;
                let r = 1.0 + 0.3 * (7.0 * a).sin();
                Point::new(r * a.cos(), r * a.sin())
            })
            .collect();
        let hole = vec![
            Point::new(-0.25, -0.25),
            Point::new(0.25, -0.25),
            Point::new(0.25, 0.25),
            Point::new(-0.25, 0.25),
        ];
        let tri = vec![
            Point::new(1.5, 1.5),
            Point::new(1.9, 1.5),
            Point::new(1.7, 1.9),
        ];
        let rings = [wavy, hole, tri];
        let edges = rings
            .iter()
            .flat_map(|r| (0..r.len()).map(move |k| (r[k], r[(k + 1) % r.len()])))
            .collect();
        let index = RayCrossings::new(edges);
        for i in -40..=40 {
            for j in -40..=40 {
                let q = Point::new(i as f64 / 20.0, j as f64 / 20.0);
                let want = rings.iter().filter(|r| even_odd_contains(r, q)).count() % 2 == 1;
                assert_eq!(index.odd(q), want, "at {q:?}");
            }
        }
    }

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
