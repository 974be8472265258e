//! Exact detection of segments that cross, overlap or touch another one's interior,
//! and of points inside a segment, with a uniform grid over the segments' boxes.

use crate::geom::grid::{bounds_of_points, BucketGrid};
use crate::geom::predicates::orient2d as orient;
use crate::geom::{Aabb, Point};

/// Two generators that the segment engine cannot take together.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Conflict {
    /// Segments `i` and `j` cross at one interior point.
    Cross(usize, usize),
    /// Segments `i` and `j` overlap along a piece of positive length.
    Overlap(usize, usize),
    /// An endpoint of segment `j` lies inside segment `i`.
    Touch(usize, usize),
    /// Point `p` lies inside segment `i`.
    PointOn(usize, usize),
    /// An endpoint of segment `j`, or point `p` (`j = None`), lies within the engine's
    /// resolution of segment `i`'s inside without touching it exactly.
    NearlyOn(usize, Option<usize>, usize),
}

/// Gaps between an end and a segment's inside below this fraction of the scene's size
/// are beyond the engine: its constructions round there (a diagram would be wrong), so
/// such input is refused. Found by shrinking the gap of a T until `gvd verify` failed
/// the diagram: at 7.5e-13 of the domain's size it did, from 1e-12 up it passed; this
/// keeps a factor 4 from there.
pub(crate) const NEAR_TOUCH: f64 = 4e-12;

/// Refuses, naming `domain`, sites (the corners and ends `points`) that all lie within
/// the near-touch tolerance of one another: in a domain some 10^12 times their size
/// every end counts as nearly on every segment (and at unit scale their coordinates'
/// products underflow, so exact predicates find overlaps), which the per-pair
/// refusals would blame on the sites.
pub(crate) fn check_sites_beside_tolerance(
    points: impl IntoIterator<Item = Point>,
    domain: &Aabb,
) -> Result<(), crate::Error> {
    let mut points = points.into_iter().peekable();
    if points.peek().is_none() {
        return Ok(());
    }
    let side = domain.longest_side();
    let extent = bounds_of_points(points).longest_side();
    if extent > NEAR_TOUCH * side {
        return Ok(());
    }
    Err(crate::Error::scene(
        "domain",
        format!(
            "the segments, polylines, polygons and arcs span only {:.1e} of the domain's size, within the tolerance of a near touch ({NEAR_TOUCH:e} of it): every end would count as touching every segment; give a domain nearer the sites' size",
            extent / side
        ),
    ))
}

/// Whether `p` lies within `near` of the inside of segment `ab`, its foot strictly
/// between `a` and `b`.
pub(super) fn nearly_inside(p: Point, a: Point, b: Point, near: f64) -> bool {
    let d = b - a;
    let t = (p - a).dot(d) / d.dot(d);
    t > 0.0 && t < 1.0 && p.dist(a + d * t) <= near
}

/// Whether `c`, collinear with `a` and `b`, lies strictly between them.
pub(super) fn strictly_between(a: Point, b: Point, c: Point) -> bool {
    let inside = |lo: f64, hi: f64, v: f64| lo.min(hi) < v && v < lo.max(hi);
    if a.x != b.x {
        inside(a.x, b.x, c.x)
    } else {
        inside(a.y, b.y, c.y)
    }
}

fn segment_pair(
    pts: &[Point],
    segs: &[[u32; 2]],
    i: usize,
    j: usize,
    near: f64,
) -> Option<Conflict> {
    let [a, b] = segs[i];
    let [c, d] = segs[j];
    if (a == c && b == d) || (a == d && b == c) {
        return Some(Conflict::Overlap(i, j));
    }
    let (pa, pb, pc, pd) = (
        pts[a as usize],
        pts[b as usize],
        pts[c as usize],
        pts[d as usize],
    );
    let (o1, o2) = (orient(pa, pb, pc), orient(pa, pb, pd));
    let (o3, o4) = (orient(pc, pd, pa), orient(pc, pd, pb));
    if o1 == 0.0 && o2 == 0.0 {
        // Collinear: they overlap iff an endpoint of one is strictly inside the other,
        // or both coincide (handled above).
        let overlap = strictly_between(pa, pb, pc)
            || strictly_between(pa, pb, pd)
            || strictly_between(pc, pd, pa)
            || strictly_between(pc, pd, pb);
        return overlap.then_some(Conflict::Overlap(i, j));
    }
    if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
        return Some(Conflict::Cross(i, j));
    }
    let touch = |o: f64, s: u32, p: Point, x: u32, y: u32, q: Point, r: Point| {
        o == 0.0 && s != x && s != y && strictly_between(q, r, p)
    };
    if touch(o1, c, pc, a, b, pa, pb) || touch(o2, d, pd, a, b, pa, pb) {
        return Some(Conflict::Touch(i, j));
    }
    if touch(o3, a, pa, c, d, pc, pd) || touch(o4, b, pb, c, d, pc, pd) {
        return Some(Conflict::Touch(j, i));
    }
    let nearly = |s: u32, p: Point, x: u32, y: u32, q: Point, r: Point| {
        s != x && s != y && nearly_inside(p, q, r, near)
    };
    if nearly(c, pc, a, b, pa, pb) || nearly(d, pd, a, b, pa, pb) {
        return Some(Conflict::NearlyOn(
            i,
            Some(j),
            if nearly(c, pc, a, b, pa, pb) { c } else { d } as usize,
        ));
    }
    if nearly(a, pa, c, d, pc, pd) || nearly(b, pb, c, d, pc, pd) {
        return Some(Conflict::NearlyOn(
            j,
            Some(i),
            if nearly(a, pa, c, d, pc, pd) { a } else { b } as usize,
        ));
    }
    None
}

/// A uniform grid over `segments`, each in the cells it passes through (thickened by
/// `near`, so that an end that nearly touches a segment shares a cell with it), and the
/// segments' extent: about one segment per cell, at most ~8 cells per segment on
/// average.
pub(super) fn segment_grid(
    points: &[Point],
    segments: &[[u32; 2]],
    near: f64,
) -> (BucketGrid, Aabb) {
    let ends = |k: usize| segments[k].map(|e| points[e as usize]);
    let extent = bounds_of_points(segments.iter().flatten().map(|&e| points[e as usize]));
    let total: f64 = (0..segments.len())
        .map(|k| ends(k)[0].dist(ends(k)[1]))
        .sum();
    // cells no smaller than `near`, by which each segment's box grows: else a `near`
    // far beyond the segments' extent (a domain of 1e307 about a coastline) lists every
    // segment in every cell, and the pairs are tested once per cell
    let side = BucketGrid::segment_cell_side(&extent, segments.len(), total).max(near);
    let grid = BucketGrid::of_segments(extent, side, 4096, segments.len(), ends, near);
    (grid, extent)
}

/// The first conflict among `segments` (pairs of indices into `points`, which are
/// distinct) and the isolated points `lonely`, if any; ends and points within `near` of
/// a segment's inside are conflicts too.
pub(crate) fn find_conflict(
    points: &[Point],
    segments: &[[u32; 2]],
    lonely: &[u32],
    near: f64,
) -> Option<Conflict> {
    if segments.is_empty() {
        return None;
    }
    let (grid, extent) = segment_grid(points, segments, near);
    for list in grid.buckets() {
        for (x, &i) in list.iter().enumerate() {
            for &j in &list[x + 1..] {
                if let Some(c) = segment_pair(points, segments, i as usize, j as usize, near) {
                    return Some(c);
                }
            }
        }
    }
    for &p in lonely {
        let q = points[p as usize];
        let outside = |v: f64, lo: f64, hi: f64| v < lo - near || v > hi + near;
        if outside(q.x, extent.min.x, extent.max.x) || outside(q.y, extent.min.y, extent.max.y) {
            continue;
        }
        for &i in grid.bucket(grid.cell_of(q)) {
            let [a, b] = segments[i as usize];
            let (pa, pb) = (points[a as usize], points[b as usize]);
            if p != a && p != b && orient(pa, pb, q) == 0.0 && strictly_between(pa, pb, q) {
                return Some(Conflict::PointOn(i as usize, p as usize));
            }
            if p != a && p != b && nearly_inside(q, pa, pb, near) {
                return Some(Conflict::NearlyOn(i as usize, None, p as usize));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[(f64, f64)]) -> Vec<Point> {
        v.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    #[test]
    fn ends_and_points_nearly_on_a_segment_are_conflicts() {
        let p = pts(&[
            (-1., 0.),
            (1., 0.),
            (0., 1e-17),
            (0., 1.),
            (0.5, -1e-15),
            (2., 2.),
        ]);
        let near = 4e-12;
        assert_eq!(
            find_conflict(&p, &[[0, 1], [2, 3]], &[], near),
            Some(Conflict::NearlyOn(0, Some(1), 2))
        );
        assert_eq!(
            find_conflict(&p, &[[0, 1]], &[4], near),
            Some(Conflict::NearlyOn(0, None, 4))
        );
        // beyond the gap, or with a foot outside the segment: no conflict
        assert_eq!(find_conflict(&p, &[[0, 1], [2, 3]], &[], 1e-18), None);
        assert_eq!(find_conflict(&p, &[[0, 1], [3, 5]], &[], near), None);
    }

    #[test]
    fn finds_each_kind_of_conflict() {
        let p = pts(&[
            (0., 0.),
            (2., 2.),
            (0., 2.),
            (2., 0.),
            (1., 1.),
            (3., 3.),
            (4., 0.),
        ]);
        assert_eq!(
            find_conflict(&p, &[[0, 1], [2, 3]], &[], 0.0),
            Some(Conflict::Cross(0, 1))
        );
        assert_eq!(
            find_conflict(&p, &[[0, 1], [4, 5]], &[], 0.0),
            Some(Conflict::Overlap(0, 1))
        );
        assert_eq!(
            find_conflict(&p, &[[0, 1], [4, 3]], &[], 0.0),
            Some(Conflict::Touch(0, 1))
        );
        assert_eq!(
            find_conflict(&p, &[[0, 1]], &[4], 0.0),
            Some(Conflict::PointOn(0, 4))
        );
        // Shared endpoints, collinear neighbours and a point on the supporting line
        // beyond the segment are fine.
        assert_eq!(
            find_conflict(&p, &[[0, 4], [4, 1], [0, 3], [3, 6]], &[5], 0.0),
            None
        );
    }
}
