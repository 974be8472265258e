//! One uniform bucket grid for every spatial lookup of the crate: items are bucketed by
//! their bounding boxes into square cells over an extent, stored in one list grouped by
//! cell (a counting sort: cell `c` holds `items[start[c]..start[c + 1]]`).
//!
//! Cells are numbered row by row; a point maps to the cell `⌊(p − origin)/side⌋`,
//! clamped to the grid, so points outside the extent fall into its border cells. Each
//! user chooses the cell side that suits its queries (about one item per cell for
//! nearest-point searches, at least the query radius for range searches).

use super::{Aabb, Point};
use rustc_hash::FxHashMap;

/// Items bucketed by their boxes in a uniform grid of square cells.
#[derive(Clone, Debug)]
pub struct BucketGrid {
    origin: Point,
    side: f64,
    nx: usize,
    ny: usize,
    /// Cell `c` holds `items[start[c]..start[c + 1]]`.
    start: Vec<usize>,
    items: Vec<u32>,
}

impl BucketGrid {
    /// Buckets items `0..count` over `extent` in cells of side `side` (at most
    /// `max_per_axis` along each axis; the last cell of an axis takes the rest): item `k`
    /// goes into every cell that its box `bounds_of(k)` meets.
    pub fn new(
        extent: Aabb,
        side: f64,
        max_per_axis: usize,
        count: usize,
        bounds_of: impl Fn(usize) -> Aabb,
    ) -> BucketGrid {
        Self::build(extent, side, max_per_axis, count, |grid, k, f| {
            grid.for_cells_of(&bounds_of(k), f)
        })
    }

    /// Buckets segments `0..count` as [`BucketGrid::new`] does, but item `k` goes only
    /// into the cells that segment `ends_of(k)`, thickened by `pad`, meets (row by row),
    /// not into every cell of its box: long oblique segments then share few cells. Two
    /// segments that come within `pad` of each other share a cell.
    pub fn of_segments(
        extent: Aabb,
        side: f64,
        max_per_axis: usize,
        count: usize,
        ends_of: impl Fn(usize) -> [Point; 2],
        pad: f64,
    ) -> BucketGrid {
        Self::build(extent, side, max_per_axis, count, |grid, k, f| {
            grid.for_cells_along(ends_of(k), pad, f)
        })
    }

    /// [`BucketGrid::of_segments`] over the edges of closed rings (every edge's end is
    /// another's start, so the starts span them all), sized by
    /// [`BucketGrid::segment_cell_side`], without padding.
    pub fn of_ring_edges(count: usize, ends_of: impl Fn(usize) -> [Point; 2]) -> BucketGrid {
        let extent = bounds_of_points((0..count).map(|k| ends_of(k)[0]));
        let total: f64 = (0..count)
            .map(|k| {
                let [a, b] = ends_of(k);
                a.dist(b)
            })
            .sum();
        let side = Self::segment_cell_side(&extent, count, total);
        Self::of_segments(extent, side, 4096, count, ends_of, 0.0)
    }

    /// A cell side for [`BucketGrid::of_segments`] over `count` segments of total length
    /// `total_length` in `extent`: about one segment per cell, but at most about eight
    /// cells per segment on average.
    pub fn segment_cell_side(extent: &Aabb, count: usize, total_length: f64) -> f64 {
        let n = count as f64;
        (extent.longest_side() / (2.0 * n).sqrt()).max(total_length / (8.0 * n))
    }

    fn build(
        extent: Aabb,
        side: f64,
        max_per_axis: usize,
        count: usize,
        cells_of: impl Fn(&BucketGrid, usize, &mut dyn FnMut(usize)),
    ) -> BucketGrid {
        let side = if side > 0.0 && side.is_finite() {
            side
        } else {
            f64::MAX
        };
        let cells_along = |len: f64| {
            let n = (len / side).floor();
            if n.is_finite() && n >= 0.0 {
                (n as usize).saturating_add(1).clamp(1, max_per_axis.max(1))
            } else {
                1
            }
        };
        let mut grid = BucketGrid {
            origin: extent.min,
            side,
            nx: cells_along(extent.width()),
            ny: cells_along(extent.height()),
            start: Vec::new(),
            items: Vec::new(),
        };
        let mut start = vec![0usize; grid.nx * grid.ny + 1];
        for k in 0..count {
            cells_of(&grid, k, &mut |c| start[c + 1] += 1);
        }
        for c in 0..grid.nx * grid.ny {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; start[grid.nx * grid.ny]];
        for k in 0..count {
            cells_of(&grid, k, &mut |c| {
                items[fill[c]] = k as u32;
                fill[c] += 1;
            });
        }
        grid.start = start;
        grid.items = items;
        grid
    }

    /// The number of cells along x and along y.
    pub fn dims(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The cell `(i, j)` of `p`, clamped to the grid.
    pub fn cell_of(&self, p: Point) -> (usize, usize) {
        let at =
            |v: f64, o: f64, n: usize| (((v - o) / self.side).floor().max(0.0) as usize).min(n - 1);
        (
            at(p.x, self.origin.x, self.nx),
            at(p.y, self.origin.y, self.ny),
        )
    }

    /// The items of cell `(i, j)`, in increasing order.
    pub fn bucket(&self, (i, j): (usize, usize)) -> &[u32] {
        let c = j * self.nx + i;
        &self.items[self.start[c]..self.start[c + 1]]
    }

    /// Every cell's items, row by row.
    pub fn buckets(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.start.windows(2).map(|w| &self.items[w[0]..w[1]])
    }

    /// Calls `f(cell, item)` for each item of each cell that the box `b` meets (an item
    /// in several of these cells is seen once per cell).
    pub fn for_each_in(&self, b: &Aabb, mut f: impl FnMut((usize, usize), u32)) {
        let ((i0, j0), (i1, j1)) = (self.cell_of(b.min), self.cell_of(b.max));
        for j in j0..=j1 {
            for i in i0..=i1 {
                for &k in self.bucket((i, j)) {
                    f((i, j), k);
                }
            }
        }
    }

    /// Whether `pred` holds for some item of a cell that the box `b` meets (stops at
    /// the first; an item in several of these cells may be tried once per cell).
    pub fn any_in(&self, b: &Aabb, mut pred: impl FnMut(u32) -> bool) -> bool {
        let ((i0, j0), (i1, j1)) = (self.cell_of(b.min), self.cell_of(b.max));
        (j0..=j1).any(|j| (i0..=i1).any(|i| self.bucket((i, j)).iter().any(|&k| pred(k))))
    }

    /// Whether `pred` holds for some item of the cells within `reach` cells (Chebyshev
    /// distance) of `p`'s cell, tried row by row.
    pub fn any_around(&self, p: Point, reach: usize, mut pred: impl FnMut(u32) -> bool) -> bool {
        let (i, j) = self.cell_of(p);
        let (i0, i1) = (i.saturating_sub(reach), (i + reach).min(self.nx - 1));
        let (j0, j1) = (j.saturating_sub(reach), (j + reach).min(self.ny - 1));
        (j0..=j1).any(|j| (i0..=i1).any(|i| self.bucket((i, j)).iter().any(|&k| pred(k))))
    }

    /// Calls `f` for each item of the cells at Chebyshev distance exactly `ring` from
    /// cell `c` (ring 0 is `c` itself), row by row. After rings `0..=k` every item whose
    /// box lies outside them is farther than `k · side` from any point of `c`. Visits
    /// only the ring's cells (at most `8 · ring`), not the square inside it: a search
    /// through many rings stays linear in their cells.
    pub fn for_each_in_ring(&self, c: (usize, usize), ring: usize, mut f: impl FnMut(u32)) {
        let (ci, cj) = c;
        let (i0, i1) = (ci.saturating_sub(ring), (ci + ring).min(self.nx - 1));
        let (j0, j1) = (cj.saturating_sub(ring), (cj + ring).min(self.ny - 1));
        let mut visit = |i: usize, j: usize| self.bucket((i, j)).iter().for_each(|&k| f(k));
        for j in j0..=j1 {
            if j.abs_diff(cj) == ring {
                (i0..=i1).for_each(|i| visit(i, j));
                continue;
            }
            // the ring's left and right cells of this row, where inside the grid
            if ci >= ring {
                visit(ci - ring, j);
            }
            if ring > 0 && ci + ring < self.nx {
                visit(ci + ring, j);
            }
        }
    }

    /// The item nearest to `q` by `dist(item)` (the smallest index among equals), with
    /// its distance; `None` when the grid holds no item. Rings of cells are searched
    /// outwards until the next ring is farther than the best distance, so `dist` must be
    /// at least the distance from `q` to the item's box.
    pub fn nearest_by(&self, q: Point, mut dist: impl FnMut(u32) -> f64) -> Option<(f64, u32)> {
        let c = self.cell_of(q);
        let mut best: Option<(f64, u32)> = None;
        for ring in 0..=self.nx.max(self.ny) {
            // items in ring `ring` or beyond are at least (ring − 1) cells away from q
            if let Some((d, _)) = best {
                if ring > 0 && d < (ring - 1) as f64 * self.side {
                    break;
                }
            }
            self.for_each_in_ring(c, ring, |k| {
                let d = dist(k);
                if best.is_none_or(|(bd, bk)| d < bd || (d == bd && k < bk)) {
                    best = Some((d, k));
                }
            });
        }
        best
    }

    /// Calls `f` with the index of each cell that the box `b` meets.
    fn for_cells_of(&self, b: &Aabb, f: &mut dyn FnMut(usize)) {
        let ((i0, j0), (i1, j1)) = (self.cell_of(b.min), self.cell_of(b.max));
        for j in j0..=j1 {
            for i in i0..=i1 {
                f(j * self.nx + i);
            }
        }
    }

    /// Calls `f` for each cell that segment `ab`, thickened by `pad`, meets: per row of
    /// cells, the x-range of the piece of `ab` within the row's band (both widened by
    /// `pad` and by a margin for the rounding of the row's bounds and of the
    /// interpolation, so that no cell the exact segment meets is missed).
    fn for_cells_along(&self, [a, b]: [Point; 2], pad: f64, f: &mut dyn FnMut(usize)) {
        let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
        let scale = [a.x, a.y, b.x, b.y, self.origin.x, self.origin.y]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let reach = pad + 16.0 * f64::EPSILON * scale + 1e-9 * self.side.min(f64::MAX / 2.0);
        let (xmin, xmax) = (lo.x.min(hi.x) - reach, lo.x.max(hi.x) + reach);
        let (_, j0) = self.cell_of(Point::new(lo.x, lo.y - reach));
        let (_, j1) = self.cell_of(Point::new(hi.x, hi.y + reach));
        for j in j0..=j1 {
            // rows at the grid's border take everything beyond it (cells are clamped)
            let band_lo = if j == 0 {
                f64::NEG_INFINITY
            } else {
                self.origin.y + j as f64 * self.side - reach
            };
            let band_hi = if j + 1 == self.ny {
                f64::INFINITY
            } else {
                self.origin.y + (j + 1) as f64 * self.side + reach
            };
            let (x0, x1) = if hi.y > lo.y {
                let x_at = |y: f64| lo.x + (hi.x - lo.x) * ((y - lo.y) / (hi.y - lo.y));
                let (xa, xb) = (x_at(lo.y.max(band_lo)), x_at(hi.y.min(band_hi)));
                (
                    (xa.min(xb) - reach).max(xmin),
                    (xa.max(xb) + reach).min(xmax),
                )
            } else {
                (xmin, xmax)
            };
            let (i0, _) = self.cell_of(Point::new(x0, lo.y));
            let (i1, _) = self.cell_of(Point::new(x1, lo.y));
            for i in i0..=i1 {
                f(j * self.nx + i);
            }
        }
    }
}

/// Items at points in a sparse grid of square cells of side `radius` (a hash map of
/// the occupied cells): for sets that grow while they are searched, and for radii so
/// small against the extent that a dense grid would not fit.
#[derive(Clone, Debug)]
pub struct SparseGrid<T> {
    radius: f64,
    cells: FxHashMap<(i64, i64), Vec<(Point, T)>>,
}

impl<T> SparseGrid<T> {
    /// An empty grid for queries of radius `radius`.
    pub fn new(radius: f64) -> SparseGrid<T> {
        SparseGrid {
            radius,
            cells: FxHashMap::default(),
        }
    }

    fn cell_of(&self, p: Point) -> (i64, i64) {
        let at = |v: f64| (v / self.radius).floor() as i64;
        (at(p.x), at(p.y))
    }

    /// Adds `item` at `p`.
    pub fn insert(&mut self, p: Point, item: T) {
        let c = self.cell_of(p);
        self.cells.entry(c).or_default().push((p, item));
    }

    /// The items within `radius` of `p`: by cell (x, then y), then in the order they
    /// were inserted.
    pub fn near(&self, p: Point) -> impl Iterator<Item = &(Point, T)> + '_ {
        let (i, j) = self.cell_of(p);
        (-1..=1i64)
            .flat_map(move |di| {
                (-1..=1i64).map(move |dj| (i.saturating_add(di), j.saturating_add(dj)))
            })
            .filter_map(|c| self.cells.get(&c))
            .flatten()
            .filter(move |e| e.0.dist(p) <= self.radius)
    }

    /// Every item, in no particular order.
    pub fn items(&self) -> impl Iterator<Item = &(Point, T)> + '_ {
        self.cells.values().flatten()
    }
}

/// The bounding box of `points` (an empty, inverted box when there are none).
pub fn bounds_of_points(points: impl IntoIterator<Item = Point>) -> Aabb {
    points.into_iter().fold(
        Aabb::new(
            Point::new(f64::MAX, f64::MAX),
            Point::new(f64::MIN, f64::MIN),
        ),
        |b, p| {
            Aabb::new(
                Point::new(b.min.x.min(p.x), b.min.y.min(p.y)),
                Point::new(b.max.x.max(p.x), b.max.y.max(p.y)),
            )
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::segment_distance;
    use proptest::prelude::*;

    fn square(c: Point, r: f64) -> Aabb {
        Aabb::new(c - Point::new(r, r), c + Point::new(r, r))
    }

    proptest! {
        /// Every item whose box meets a query box is reported by `for_each_in`.
        #[test]
        fn range_queries_find_every_overlapping_box(
            items in proptest::collection::vec((-5.0..5.0f64, -5.0..5.0f64, 0.0..1.0f64), 1..40),
            q in (-6.0..6.0f64, -6.0..6.0f64, 0.0..2.0f64),
            side in 0.05..3.0f64,
        ) {
            let boxes: Vec<Aabb> = items.iter().map(|&(x, y, r)| square(Point::new(x, y), r)).collect();
            let extent = Aabb::new(Point::new(-5.0, -5.0), Point::new(5.0, 5.0));
            let grid = BucketGrid::new(extent, side, 64, boxes.len(), |k| boxes[k]);
            let query = square(Point::new(q.0, q.1), q.2);
            let mut seen = vec![false; boxes.len()];
            grid.for_each_in(&query, |_, k| seen[k as usize] = true);
            for (k, b) in boxes.iter().enumerate() {
                let meets = b.min.x <= query.max.x && query.min.x <= b.max.x
                    && b.min.y <= query.max.y && query.min.y <= b.max.y;
                prop_assert!(!meets || seen[k], "box {k} meets the query but was not seen");
            }
        }

        /// Segments that come within the pad of each other (or cross) share a cell.
        #[test]
        fn segments_that_meet_share_a_cell(
            ends in proptest::collection::vec((-5.0..5.0f64, -5.0..5.0f64, -1.0..1.0f64, -1.0..1.0f64), 2..60),
            side in 0.05..3.0f64,
            pad in 0.0..0.5f64,
        ) {
            let segs: Vec<[Point; 2]> = ends.iter()
                .map(|&(x, y, dx, dy)| [Point::new(x, y), Point::new(x + dx, y + dy)]).collect();
            let extent = bounds_of_points(segs.iter().flatten().copied());
            let grid = BucketGrid::of_segments(extent, side, 64, segs.len(), |k| segs[k], pad);
            let mut cells = vec![Vec::new(); segs.len()];
            for (c, bucket) in grid.buckets().enumerate() {
                for &k in bucket {
                    cells[k as usize].push(c);
                }
            }
            let gap = |[a, b]: [Point; 2], [c, d]: [Point; 2]| {
                let cross = |p: Point, q: Point, r: Point| (q - p).cross(r - p);
                let crossing = cross(a, b, c) * cross(a, b, d) < 0.0 && cross(c, d, a) * cross(c, d, b) < 0.0;
                if crossing { 0.0 } else {
                    segment_distance(a, c, d).min(segment_distance(b, c, d))
                        .min(segment_distance(c, a, b)).min(segment_distance(d, a, b))
                }
            };
            for i in 0..segs.len() {
                for j in i + 1..segs.len() {
                    if gap(segs[i], segs[j]) <= pad * 0.99 {
                        prop_assert!(cells[i].iter().any(|c| cells[j].contains(c)),
                            "segments {i} and {j} meet but share no cell");
                    }
                }
            }
        }

        /// The rings around a cell visit every item exactly once per cell it lies in.
        #[test]
        fn rings_cover_the_grid(
            pts in proptest::collection::vec((-5.0..5.0f64, -5.0..5.0f64), 1..40),
            q in (-6.0..6.0f64, -6.0..6.0f64),
        ) {
            let points: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
            let grid = BucketGrid::new(bounds_of_points(points.iter().copied()), 0.7, 2048,
                                       points.len(), |k| Aabb::new(points[k], points[k]));
            let c = grid.cell_of(Point::new(q.0, q.1));
            let mut seen = vec![0; points.len()];
            let (nx, ny) = grid.dims();
            for ring in 0..=nx.max(ny) {
                grid.for_each_in_ring(c, ring, |k| seen[k as usize] += 1);
            }
            prop_assert!(seen.iter().all(|&s| s == 1));
        }
    }

    /// Padding widens a row's x-range too: two parallel steep segments on either side
    /// of a column boundary, closer than the pad, share a cell.
    #[test]
    fn steep_neighbours_across_a_column_boundary_share_a_cell() {
        let segs = [
            [Point::new(0.98, 0.1), Point::new(0.99, 3.9)],
            [Point::new(1.02, 0.1), Point::new(1.01, 3.9)],
        ];
        let extent = Aabb::new(Point::new(0.0, 0.0), Point::new(4.0, 4.0));
        let grid = BucketGrid::of_segments(extent, 1.0, 64, 2, |k| segs[k], 0.05);
        let shared = grid.buckets().filter(|b| b.len() == 2).count();
        assert!(shared > 0, "no shared cell");
    }

    #[test]
    fn a_long_oblique_segment_does_not_fill_its_box() {
        let diagonal = [Point::new(-5.0, -5.0), Point::new(5.0, 5.0)];
        let extent = Aabb::new(diagonal[0], diagonal[1]);
        let grid = BucketGrid::of_segments(extent, 0.1, 1024, 1, |_| diagonal, 0.0);
        let filled = grid.buckets().filter(|b| !b.is_empty()).count();
        assert!((100..400).contains(&filled), "{filled} cells of 10,000");
    }
}
