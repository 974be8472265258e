//! Exact detection of segments that cross, overlap or touch another one's interior,
//! and of points inside a segment, with a uniform grid over the segments' boxes.

use crate::geom::predicates::orient2d as orient;
use crate::geom::Point;

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
}

/// Whether `c`, collinear with `a` and `b`, lies strictly between them.
fn strictly_between(a: Point, b: Point, c: Point) -> bool {
    let inside = |lo: f64, hi: f64, v: f64| lo.min(hi) < v && v < lo.max(hi);
    if a.x != b.x {
        inside(a.x, b.x, c.x)
    } else {
        inside(a.y, b.y, c.y)
    }
}

fn segment_pair(pts: &[Point], segs: &[[u32; 2]], i: usize, j: usize) -> Option<Conflict> {
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
    None
}

/// The first conflict among `segments` (pairs of indices into `points`, which are
/// distinct) and the isolated points `lonely`, if any.
pub(crate) fn find_conflict(
    points: &[Point],
    segments: &[[u32; 2]],
    lonely: &[u32],
) -> Option<Conflict> {
    if segments.is_empty() {
        return None;
    }
    let (mut lo, mut hi) = (
        points[segments[0][0] as usize],
        points[segments[0][0] as usize],
    );
    let mut total = 0.0;
    for &[a, b] in segments {
        for p in [points[a as usize], points[b as usize]] {
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        total += points[a as usize].dist(points[b as usize]);
    }
    // Cells about as long as the average segment, at most ~4 per segment.
    let n = segments.len() as f64;
    let ext = (hi.x - lo.x).max(hi.y - lo.y).max(f64::MIN_POSITIVE);
    let side = (total / n).max(ext / (2.0 * n).sqrt()).max(ext / 4096.0);
    let (nx, ny) = (
        ((hi.x - lo.x) / side).floor() as usize + 1,
        ((hi.y - lo.y) / side).floor() as usize + 1,
    );
    let cell = |p: Point| {
        let cx = (((p.x - lo.x) / side).floor().max(0.0) as usize).min(nx - 1);
        let cy = (((p.y - lo.y) / side).floor().max(0.0) as usize).min(ny - 1);
        (cx, cy)
    };
    // Calls `f` with each cell that segment `k`'s box meets.
    let for_cells = |k: usize, f: &mut dyn FnMut(usize)| {
        let [a, b] = segments[k];
        let (c0, c1) = (cell(points[a as usize]), cell(points[b as usize]));
        for cy in c0.1.min(c1.1)..=c0.1.max(c1.1) {
            for cx in c0.0.min(c1.0)..=c0.0.max(c1.0) {
                f(cy * nx + cx);
            }
        }
    };
    // The segments over each cell, grouped by cell in one list (a counting sort):
    // cell `c`'s are `list[start[c]..start[c + 1]]`.
    let mut start = vec![0usize; nx * ny + 1];
    for k in 0..segments.len() {
        for_cells(k, &mut |c| start[c + 1] += 1);
    }
    for c in 0..nx * ny {
        start[c + 1] += start[c];
    }
    let mut fill = start.clone();
    let mut list = vec![0u32; start[nx * ny]];
    for k in 0..segments.len() {
        for_cells(k, &mut |c| {
            list[fill[c]] = k as u32;
            fill[c] += 1;
        });
    }
    let cells = |c: usize| &list[start[c]..start[c + 1]];
    for c in 0..nx * ny {
        let list = cells(c);
        for (x, &i) in list.iter().enumerate() {
            for &j in &list[x + 1..] {
                if let Some(c) = segment_pair(points, segments, i as usize, j as usize) {
                    return Some(c);
                }
            }
        }
    }
    for &p in lonely {
        let q = points[p as usize];
        if q.x < lo.x || q.y < lo.y || q.x > hi.x || q.y > hi.y {
            continue;
        }
        let (cx, cy) = cell(q);
        for &i in cells(cy * nx + cx) {
            let [a, b] = segments[i as usize];
            let (pa, pb) = (points[a as usize], points[b as usize]);
            if p != a && p != b && orient(pa, pb, q) == 0.0 && strictly_between(pa, pb, q) {
                return Some(Conflict::PointOn(i as usize, p as usize));
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
            find_conflict(&p, &[[0, 1], [2, 3]], &[]),
            Some(Conflict::Cross(0, 1))
        );
        assert_eq!(
            find_conflict(&p, &[[0, 1], [4, 5]], &[]),
            Some(Conflict::Overlap(0, 1))
        );
        assert_eq!(
            find_conflict(&p, &[[0, 1], [4, 3]], &[]),
            Some(Conflict::Touch(0, 1))
        );
        assert_eq!(
            find_conflict(&p, &[[0, 1]], &[4]),
            Some(Conflict::PointOn(0, 4))
        );
        // Shared endpoints, collinear neighbours and a point on the supporting line
        // beyond the segment are fine.
        assert_eq!(
            find_conflict(&p, &[[0, 4], [4, 1], [0, 3], [3, 6]], &[5]),
            None
        );
    }
}
