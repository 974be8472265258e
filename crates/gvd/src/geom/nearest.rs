//! Nearest-point queries on the shared bucket grid (expanding rings of cells).

use super::grid::{bounds_of_points, BucketGrid};
use super::{Aabb, Point};

/// Points bucketed in a grid over their bounding box, about one point per cell.
pub struct PointGrid<'a> {
    points: &'a [Point],
    grid: BucketGrid,
}

impl<'a> PointGrid<'a> {
    /// Buckets `points` in a grid of about one point per cell.
    pub fn new(points: &'a [Point]) -> Self {
        let bounds = bounds_of_points(points.iter().copied());
        let n = ((points.len() as f64).sqrt().ceil() as usize).clamp(1, 2048);
        let side = (bounds.longest_side() / n as f64).max(f64::MIN_POSITIVE);
        let grid = BucketGrid::new(bounds, side, n + 1, points.len(), |k| {
            Aabb::new(points[k], points[k])
        });
        PointGrid { points, grid }
    }

    /// The index of the point nearest to `q` (the smallest index among equals), or
    /// `None` when there are no points.
    pub fn nearest(&self, q: Point) -> Option<usize> {
        self.grid
            .nearest_by(q, |k| q.dist(self.points[k as usize]))
            .map(|(_, k)| k as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn nearest_matches_brute_force(pts in proptest::collection::vec((-2.0..2.0f64, -2.0..2.0f64), 1..60),
                                       qx in -3.0..3.0f64, qy in -3.0..3.0f64) {
            let points: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
            let q = Point::new(qx, qy);
            let got = PointGrid::new(&points).nearest(q).unwrap();
            let best = points.iter().map(|p| q.dist(*p)).fold(f64::INFINITY, f64::min);
            prop_assert_eq!(q.dist(points[got]), best);
        }
    }
}
