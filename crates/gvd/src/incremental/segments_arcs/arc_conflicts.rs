//! Arcs that cross or touch a segment or another arc away from a shared endpoint, and
//! points on an arc's inside: the segment engine cannot take them together.
//!
//! Unlike segments (exact orientation tests), these tests are in floating point with a
//! tolerance of `1e-12` of the scene's size: an intersection that close to a shared
//! endpoint counts as that endpoint.

use crate::geom::grid::{bounds_of_points, BucketGrid};
use crate::geom::{Aabb, Point};

/// A circular arc: centre, radius, start angle and counter-clockwise span in `(0, 2π)`,
/// and its two end points' generators.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ArcSpec {
    pub(crate) c: Point,
    pub(crate) r: f64,
    pub(crate) start: f64,
    pub(crate) span: f64,
    pub(crate) ends: [u32; 2],
}

impl ArcSpec {
    pub(crate) fn end_point(&self, k: usize) -> Point {
        let a = self.start + if k == 0 { 0.0 } else { self.span };
        self.c + Point::new(a.cos(), a.sin()) * self.r
    }

    /// Whether the direction of `q − c` lies within the closed span.
    fn spans(&self, q: Point, slack: f64) -> bool {
        let a = (q.y - self.c.y).atan2(q.x - self.c.x);
        let rel = (a - self.start).rem_euclid(std::f64::consts::TAU);
        rel <= self.span + slack || rel >= std::f64::consts::TAU - slack
    }
}

/// What meets an arc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ArcConflict {
    /// Arc `a` and segment `s` cross or touch away from a shared endpoint.
    Segment(usize, usize),
    /// Arcs `a` and `b` cross, touch or overlap away from a shared endpoint.
    Arc(usize, usize),
    /// Point generator `p` lies inside arc `a`.
    Point(usize, usize),
}

/// The first conflict of an arc with a segment, another arc or a lonely point: in the
/// order of the arcs, then segments before arcs before points, each in their order.
/// Only pairs whose boxes meet are tested, found through a grid over the arcs.
pub(crate) fn find_arc_conflict(
    points: &[Point],
    segments: &[[u32; 2]],
    arcs: &[ArcSpec],
    lonely: &[u32],
    scale: f64,
) -> Option<ArcConflict> {
    if arcs.is_empty() {
        return None;
    }
    let tol = 1e-12 * scale;
    let grid = ArcGrid::new(arcs, tol);
    // The least conflict by (arc, kind: segment 0, arc 1, point 2, index).
    let mut first: Option<((usize, u8, usize), ArcConflict)> = None;
    let mut found = |key: (usize, u8, usize), c: ArcConflict| {
        if first.is_none_or(|(k, _)| key < k) {
            first = Some((key, c));
        }
    };
    for (j, &[a, b]) in segments.iter().enumerate() {
        let (pa, pb) = (points[a as usize], points[b as usize]);
        let (lo, hi) = (
            Point::new(pa.x.min(pb.x), pa.y.min(pb.y)),
            Point::new(pa.x.max(pb.x), pa.y.max(pb.y)),
        );
        grid.near(lo, hi, |i| {
            let arc = &arcs[i];
            let shared = |q: Point| shared_end(points, arc, &[a, b], q, tol);
            if line_circle(pa, pb, arc.c, arc.r, tol)
                .into_iter()
                .any(|q| arc.spans(q, tol / arc.r) && !shared(q))
            {
                found((i, 0, j), ArcConflict::Segment(i, j));
            }
        });
    }
    for (j, other) in arcs.iter().enumerate() {
        let (lo, hi) = grid.boxes[j];
        grid.near(lo, hi, |i| {
            if i >= j {
                return;
            }
            let arc = &arcs[i];
            let meets = match circle_circle(arc, other, tol) {
                // One circle: they overlap iff the spans share more than end points.
                None => spans_overlap(arc, other),
                Some(qs) => qs.into_iter().any(|q| {
                    arc.spans(q, tol / arc.r)
                        && other.spans(q, tol / other.r)
                        && !shared_end(points, arc, &other.ends, q, tol)
                }),
            };
            if meets {
                found((i, 1, j), ArcConflict::Arc(i, j));
            }
        });
    }
    for (k, &p) in lonely.iter().enumerate() {
        let q = points[p as usize];
        grid.near(q, q, |i| {
            let arc = &arcs[i];
            if (q.dist(arc.c) - arc.r).abs() <= tol && arc.spans(q, -tol / arc.r) {
                found((i, 2, k), ArcConflict::Point(i, p as usize));
            }
        });
    }
    first.map(|(_, c)| c)
}

/// The arcs' boxes (their circles' boxes, padded by the tolerance) in the shared grid,
/// with cells about the size of an arc's box.
struct ArcGrid {
    boxes: Vec<(Point, Point)>,
    grid: BucketGrid,
}

impl ArcGrid {
    fn new(arcs: &[ArcSpec], pad: f64) -> ArcGrid {
        let boxes: Vec<(Point, Point)> = arcs
            .iter()
            .map(|a| {
                let r = Point::new(a.r + pad, a.r + pad);
                (a.c - r, a.c + r)
            })
            .collect();
        let extent = bounds_of_points(boxes.iter().flat_map(|&(l, h)| [l, h]));
        let size: f64 = boxes.iter().map(|&(l, h)| h.x - l.x).sum();
        let n = arcs.len() as f64;
        let ext = extent.longest_side().max(f64::MIN_POSITIVE);
        let side = (size / n).max(ext / (2.0 * n).sqrt()).max(ext / 4096.0);
        let grid = BucketGrid::new(extent, side, usize::MAX, boxes.len(), |k| {
            Aabb::new(boxes[k].0, boxes[k].1)
        });
        ArcGrid { boxes, grid }
    }

    /// Calls `f` once with each arc whose box meets the box `[lo, hi]`: in the cell of
    /// the least corner of the two boxes' overlap.
    fn near(&self, lo: Point, hi: Point, mut f: impl FnMut(usize)) {
        self.grid.for_each_in(&Aabb::new(lo, hi), |cell, k| {
            let (a, b) = self.boxes[k as usize];
            let corner = Point::new(lo.x.max(a.x), lo.y.max(a.y));
            let overlap = corner.x <= hi.x.min(b.x) && corner.y <= hi.y.min(b.y);
            if overlap && self.grid.cell_of(corner) == cell {
                f(k as usize);
            }
        });
    }
}

/// Whether `q` is an end point of `arc` that is also one of `other_ends`.
fn shared_end(points: &[Point], arc: &ArcSpec, other_ends: &[u32], q: Point, tol: f64) -> bool {
    arc.ends
        .iter()
        .any(|e| other_ends.contains(e) && points[*e as usize].dist(q) <= 1e3 * tol)
}

/// The points where the closed segment `a b` meets the circle (a tangency counts once).
fn line_circle(a: Point, b: Point, c: Point, r: f64, tol: f64) -> Vec<Point> {
    let d = b - a;
    let f = a - c;
    let (qa, qb, qc) = (d.dot(d), 2.0 * f.dot(d), f.dot(f) - r * r);
    let disc = qb * qb - 4.0 * qa * qc;
    let slack = 4.0 * qa * 2.0 * r * tol;
    if disc < -slack {
        return Vec::new();
    }
    let root = disc.max(0.0).sqrt();
    let mut out = Vec::with_capacity(2);
    for t in [(-qb - root) / (2.0 * qa), (-qb + root) / (2.0 * qa)] {
        let pad = tol / qa.sqrt();
        if (-pad..=1.0 + pad).contains(&t) {
            out.push(a + d * t.clamp(0.0, 1.0));
        }
    }
    out
}

/// The points where two circles meet, or `None` when they are one circle.
fn circle_circle(a: &ArcSpec, b: &ArcSpec, tol: f64) -> Option<Vec<Point>> {
    let d = b.c - a.c;
    let dist = d.norm();
    if dist <= tol && (a.r - b.r).abs() <= tol {
        return None;
    }
    if dist > a.r + b.r + tol || dist < (a.r - b.r).abs() - tol || dist == 0.0 {
        return Some(Vec::new());
    }
    let along = (dist * dist + a.r * a.r - b.r * b.r) / (2.0 * dist);
    let h = (a.r * a.r - along * along).max(0.0).sqrt();
    let u = d * (1.0 / dist);
    let m = a.c + u * along;
    Some(vec![m + u.perp() * h, m - u.perp() * h])
}

/// Whether two arcs of one circle share more than their end points.
fn spans_overlap(a: &ArcSpec, b: &ArcSpec) -> bool {
    let tau = std::f64::consts::TAU;
    let rel = (b.start - a.start).rem_euclid(tau);
    // b starts inside a, or a starts inside b.
    let eps = 1e-12;
    rel < a.span - eps || (tau - rel) < b.span - eps
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arc(c: (f64, f64), r: f64, start: f64, span: f64, ends: [u32; 2]) -> ArcSpec {
        ArcSpec {
            c: Point::new(c.0, c.1),
            r,
            start,
            span,
            ends,
        }
    }

    #[test]
    fn crossing_touching_and_shared_ends() {
        let half = std::f64::consts::PI;
        let upper = arc((0.0, 0.0), 1.0, 0.0, half, [0, 1]);
        let mut points = vec![upper.end_point(0), upper.end_point(1)];
        points.extend([Point::new(0.0, 0.5), Point::new(0.0, 2.0)]);
        points.extend([Point::new(0.0, -0.5), Point::new(0.0, -2.0)]);
        points.extend([Point::new(1.0, -1.0), Point::new(0.0, 1.0)]);
        let arcs = [upper];
        // A segment through the top crosses it; one below the centre does not.
        let cross = find_arc_conflict(&points, &[[2, 3]], &arcs, &[], 2.0);
        assert_eq!(cross, Some(ArcConflict::Segment(0, 0)));
        assert_eq!(find_arc_conflict(&points, &[[4, 5]], &arcs, &[], 2.0), None);
        // A segment ending at the arc's end point is fine.
        assert_eq!(find_arc_conflict(&points, &[[0, 6]], &arcs, &[], 2.0), None);
        // A point on the arc's inside is refused, not its end point.
        assert_eq!(
            find_arc_conflict(&points, &[], &arcs, &[7], 2.0),
            Some(ArcConflict::Point(0, 7))
        );
        // Two arcs of one circle overlap, or only share an end.
        let lower = arc((0.0, 0.0), 1.0, half, half, [1, 0]);
        let inside = arc((0.0, 0.0), 1.0, 0.5, 1.0, [8, 9]);
        assert_eq!(
            find_arc_conflict(&points, &[], &[upper, lower], &[], 2.0),
            None
        );
        assert_eq!(
            find_arc_conflict(&points, &[], &[upper, inside], &[], 2.0),
            Some(ArcConflict::Arc(0, 1))
        );
        // Crossing circles.
        let shifted = arc((1.0, 0.0), 1.0, 0.0, 2.0 * half - 0.1, [10, 11]);
        assert_eq!(
            find_arc_conflict(&points, &[], &[upper, shifted], &[], 2.0),
            Some(ArcConflict::Arc(0, 1))
        );
    }

    /// On a lattice of 400 half circles, the grid finds the crossings far apart and
    /// reports the least one (arc order, then segments before arcs before points).
    #[test]
    fn lattice_reports_the_first_conflict() {
        let half = std::f64::consts::PI;
        let mut points = Vec::new();
        let arcs: Vec<ArcSpec> = (0..400)
            .map(|k| {
                let c = ((k % 20) as f64, (k / 20) as f64);
                let mut a = arc(c, 0.3, 0.0, half, [0, 0]);
                a.ends = [0, 1].map(|e| {
                    points.push(a.end_point(e));
                    points.len() as u32 - 1
                });
                a
            })
            .collect();
        // Vertical segments through the tops of arcs 300 and 57, and a point on arc 120.
        let top = |k: usize| Point::new((k % 20) as f64, (k / 20) as f64 + 0.3);
        for k in [300, 57] {
            points.extend([top(k) - Point::new(0.0, 0.1), top(k) + Point::new(0.0, 0.1)]);
        }
        let n = points.len() as u32;
        let segments = [[n - 4, n - 3], [n - 2, n - 1]];
        points.push(top(120));
        let found = |segs: &[[u32; 2]], lonely: &[u32]| {
            find_arc_conflict(&points, segs, &arcs, lonely, 20.0)
        };
        assert_eq!(found(&segments, &[n]), Some(ArcConflict::Segment(57, 1)));
        assert_eq!(
            found(&segments[..1], &[n]),
            Some(ArcConflict::Point(120, n as usize))
        );
        assert_eq!(
            found(&segments[..1], &[]),
            Some(ArcConflict::Segment(300, 0))
        );
        assert_eq!(found(&[], &[]), None);
    }
}
