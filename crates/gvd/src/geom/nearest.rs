//! Nearest-point queries on a uniform grid of buckets (expanding rings of cells).

use super::{Aabb, Point};

/// Points bucketed in a grid over their bounding box.
pub struct PointGrid<'a> {
    points: &'a [Point],
    bounds: Aabb,
    n: usize,
    cell: f64,
    buckets: Vec<Vec<u32>>,
}

impl<'a> PointGrid<'a> {
    /// Buckets `points` in a grid of about one point per cell.
    pub fn new(points: &'a [Point]) -> Self {
        let mut bounds = Aabb::new(
            Point::new(f64::MAX, f64::MAX),
            Point::new(f64::MIN, f64::MIN),
        );
        for p in points {
            bounds.min = Point::new(bounds.min.x.min(p.x), bounds.min.y.min(p.y));
            bounds.max = Point::new(bounds.max.x.max(p.x), bounds.max.y.max(p.y));
        }
        let n = ((points.len() as f64).sqrt().ceil() as usize).clamp(1, 2048);
        let cell = (bounds.longest_side() / n as f64).max(f64::MIN_POSITIVE);
        let mut grid = PointGrid {
            points,
            bounds,
            n,
            cell,
            buckets: vec![Vec::new(); n * n],
        };
        for (k, p) in points.iter().enumerate() {
            let (i, j) = grid.cell_of(*p);
            grid.buckets[j * n + i].push(k as u32);
        }
        grid
    }

    fn cell_of(&self, p: Point) -> (usize, usize) {
        let f = |t: f64| ((t / self.cell).max(0.0) as usize).min(self.n - 1);
        (f(p.x - self.bounds.min.x), f(p.y - self.bounds.min.y))
    }

    /// The index of the point nearest to `q` (the smallest index among equals), or
    /// `None` when there are no points.
    pub fn nearest(&self, q: Point) -> Option<usize> {
        let (ci, cj) = self.cell_of(q);
        let mut best: Option<(f64, usize)> = None;
        for ring in 0..=self.n {
            // points in ring `ring` or beyond are at least (ring − 1) cells away from q
            if let Some((d, _)) = best {
                if ring > 0 && d < (ring - 1) as f64 * self.cell {
                    break;
                }
            }
            let (lo_i, hi_i) = (ci.saturating_sub(ring), (ci + ring).min(self.n - 1));
            let (lo_j, hi_j) = (cj.saturating_sub(ring), (cj + ring).min(self.n - 1));
            for j in lo_j..=hi_j {
                for i in lo_i..=hi_i {
                    if i.abs_diff(ci) != ring && j.abs_diff(cj) != ring {
                        continue; // inside the ring, already seen
                    }
                    for &k in &self.buckets[j * self.n + i] {
                        let d = q.dist(self.points[k as usize]);
                        let k = k as usize;
                        if best.is_none_or(|(bd, bk)| d < bd || (d == bd && k < bk)) {
                            best = Some((d, k));
                        }
                    }
                }
            }
        }
        best.map(|(_, k)| k)
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
