//! Arcs that cross or touch a segment or another arc away from a shared endpoint, and
//! points on an arc's inside: the segment engine cannot take them together.
//!
//! Unlike segments (exact orientation tests), these tests are in floating point with a
//! tolerance of `1e-12` of the scene's size: an intersection that close to a shared
//! endpoint counts as that endpoint.

use crate::geom::Point;

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

    fn bbox_overlaps(&self, lo: Point, hi: Point, pad: f64) -> bool {
        let r = self.r + pad;
        !(hi.x < self.c.x - r || lo.x > self.c.x + r || hi.y < self.c.y - r || lo.y > self.c.y + r)
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

/// The first conflict of an arc with a segment, another arc or a lonely point.
pub(crate) fn find_arc_conflict(
    points: &[Point],
    segments: &[[u32; 2]],
    arcs: &[ArcSpec],
    lonely: &[u32],
    scale: f64,
) -> Option<ArcConflict> {
    let tol = 1e-12 * scale;
    for (i, arc) in arcs.iter().enumerate() {
        for (j, &[a, b]) in segments.iter().enumerate() {
            let (pa, pb) = (points[a as usize], points[b as usize]);
            let (lo, hi) = (
                Point::new(pa.x.min(pb.x), pa.y.min(pb.y)),
                Point::new(pa.x.max(pb.x), pa.y.max(pb.y)),
            );
            if !arc.bbox_overlaps(lo, hi, tol) {
                continue;
            }
            let shared = |q: Point| shared_end(points, arc, &[a, b], q, tol);
            if line_circle(pa, pb, arc.c, arc.r, tol)
                .into_iter()
                .any(|q| arc.spans(q, tol / arc.r) && !shared(q))
            {
                return Some(ArcConflict::Segment(i, j));
            }
        }
        for (j, other) in arcs.iter().enumerate().skip(i + 1) {
            let meets = circle_circle(arc, other, tol);
            let Some(qs) = meets else {
                // One circle: they overlap iff the spans share more than end points.
                if spans_overlap(arc, other) {
                    return Some(ArcConflict::Arc(i, j));
                }
                continue;
            };
            let shared = |q: Point| shared_end(points, arc, &other.ends, q, tol);
            if qs
                .into_iter()
                .any(|q| arc.spans(q, tol / arc.r) && other.spans(q, tol / other.r) && !shared(q))
            {
                return Some(ArcConflict::Arc(i, j));
            }
        }
        for &p in lonely {
            let q = points[p as usize];
            if (q.dist(arc.c) - arc.r).abs() <= tol && arc.spans(q, -tol / arc.r) {
                return Some(ArcConflict::Point(i, p as usize));
            }
        }
    }
    None
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
}
