//! Geometric validation of sites with exact orientation predicates: simple polygon rings,
//! holes inside the outer ring, duplicate point sites.

use super::{Site, SiteKind};
use crate::geom::predicates::orientation as orient;
use crate::geom::ring::winding_number;
use crate::geom::Point;
use std::cmp::Ordering;

/// Whether `p`, known to be collinear with segment `ab`, lies on the closed segment.
fn on_segment(a: Point, b: Point, p: Point) -> bool {
    a.x.min(b.x) <= p.x && p.x <= a.x.max(b.x) && a.y.min(b.y) <= p.y && p.y <= a.y.max(b.y)
}

/// How two closed segments meet.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Contact {
    None,
    /// They cross at a single point interior to both.
    Cross,
    /// They share at least one point, an endpoint of one of them or a collinear overlap.
    Touch,
}

fn contact(a: Point, b: Point, c: Point, d: Point) -> Contact {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    let opposite = |p: Ordering, q: Ordering| p != Ordering::Equal && q == p.reverse();
    if opposite(o1, o2) && opposite(o3, o4) {
        return Contact::Cross;
    }
    let touches = (o1 == Ordering::Equal && on_segment(a, b, c))
        || (o2 == Ordering::Equal && on_segment(a, b, d))
        || (o3 == Ordering::Equal && on_segment(c, d, a))
        || (o4 == Ordering::Equal && on_segment(c, d, b));
    if touches {
        Contact::Touch
    } else {
        Contact::None
    }
}

/// An edge of a polygon: ring index, edge index in the ring, endpoints.
struct Edge {
    ring: usize,
    index: usize,
    a: Point,
    b: Point,
}

impl Edge {
    fn xmin(&self) -> f64 {
        self.a.x.min(self.b.x)
    }
    fn xmax(&self) -> f64 {
        self.a.x.max(self.b.x)
    }
}

/// Checks that polygon rings (outer ring first, then holes) bound a proper region: each ring
/// has at least 3 distinct points and no zero-length edge, no ring meets itself or another
/// ring (not even touching), every hole lies inside the outer ring and outside the other
/// holes. The message names the ring and edges at fault.
pub(super) fn check_rings(rings: &[Vec<Point>]) -> Result<(), String> {
    if rings.is_empty() {
        return Err("a polygon needs at least one ring (its outer boundary)".into());
    }
    for (r, ring) in rings.iter().enumerate() {
        if distinct_count(ring) < 3 {
            return Err(format!("ring {r} has fewer than 3 distinct points"));
        }
        let n = ring.len();
        for i in 0..n {
            let j = (i + 1) % n;
            if ring[i] == ring[j] {
                return Err(format!(
                    "ring {r}: points {i} and {j} coincide (zero-length edge; rings are closed implicitly, do not repeat the first point)"
                ));
            }
        }
        for i in 0..n {
            let (prev, here, next) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            if orient(prev, here, next) == Ordering::Equal && (prev - here).dot(next - here) > 0.0 {
                return Err(format!(
                    "ring {r} is self-intersecting: edges {} and {i} overlap (the ring turns back at point {i})",
                    (i + n - 1) % n
                ));
            }
        }
    }
    check_crossings(rings)?;
    let outer = &rings[0];
    for (h, hole) in rings.iter().enumerate().skip(1) {
        if winding_number(outer, hole[0]) == 0 {
            return Err(format!("hole ring {h} lies outside the outer ring 0"));
        }
        for (g, other) in rings.iter().enumerate().skip(1) {
            if g != h && winding_number(other, hole[0]) != 0 {
                return Err(format!("hole ring {h} lies inside hole ring {g}"));
            }
        }
    }
    Ok(())
}

fn distinct_count(ring: &[Point]) -> usize {
    let mut pts: Vec<(f64, f64)> = ring.iter().map(|p| (p.x, p.y)).collect();
    pts.sort_by(|p, q| p.partial_cmp(q).unwrap_or(Ordering::Equal));
    pts.dedup();
    pts.len()
}

/// Any contact between edges of the rings other than the shared corner of two edges
/// adjacent in one ring (a sweep over x-extents; adjacent overlaps are checked by the caller).
fn check_crossings(rings: &[Vec<Point>]) -> Result<(), String> {
    let mut edges: Vec<Edge> = rings
        .iter()
        .enumerate()
        .flat_map(|(ring, pts)| {
            (0..pts.len()).map(move |index| Edge {
                ring,
                index,
                a: pts[index],
                b: pts[(index + 1) % pts.len()],
            })
        })
        .collect();
    edges.sort_by(|e, f| e.xmin().total_cmp(&f.xmin()));
    for (k, e) in edges.iter().enumerate() {
        for f in edges[k + 1..].iter().take_while(|f| f.xmin() <= e.xmax()) {
            let c = contact(e.a, e.b, f.a, f.b);
            if c == Contact::None {
                continue;
            }
            let (e, f) = if (e.ring, e.index) < (f.ring, f.index) {
                (e, f)
            } else {
                (f, e)
            };
            if e.ring == f.ring {
                let n = rings[e.ring].len();
                let adjacent = f.index == e.index + 1 || (e.index == 0 && f.index == n - 1);
                if adjacent && c == Contact::Touch {
                    continue;
                }
                let how = if c == Contact::Cross {
                    "cross"
                } else {
                    "touch"
                };
                return Err(format!(
                    "ring {} is self-intersecting: edges {} and {} {how}",
                    e.ring, e.index, f.index
                ));
            }
            return Err(format!(
                "rings {} and {} intersect: edge {} of ring {} meets edge {} of ring {}",
                e.ring, f.ring, e.index, e.ring, f.index, f.ring
            ));
        }
    }
    Ok(())
}

/// The first point site that repeats an earlier one (same location and same metric), as
/// `(later, earlier)` site indices.
pub(super) fn duplicate_point(sites: &[Site]) -> Option<(usize, usize)> {
    // Sorted by location (then index), equal locations are runs: no hashing and no
    // allocation per point, which counts at a million points.
    let key = |p: Point| ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits());
    let mut points: Vec<((u64, u64), usize)> = sites
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.kind {
            SiteKind::Point { at, .. } => Some((key(*at), i)),
            _ => None,
        })
        .collect();
    points.sort_unstable();
    let metric = |i: usize| match &sites[i].kind {
        SiteKind::Point { metric, .. } => Some(metric),
        _ => None,
    };
    let mut first: Option<(usize, usize)> = None;
    for run in points.chunk_by(|a, b| a.0 == b.0).filter(|r| r.len() > 1) {
        // The earliest point of the run repeating an earlier one of the same metric.
        for (k, &(_, i)) in run.iter().enumerate().skip(1) {
            if first.is_some_and(|(f, _)| f < i) {
                break;
            }
            if let Some(&(_, j)) = run[..k].iter().find(|&&(_, j)| metric(j) == metric(i)) {
                first = Some((i, j));
                break;
            }
        }
    }
    first
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ring(pts: &[[f64; 2]]) -> Vec<Point> {
        pts.iter().map(|&p| Point::from(p)).collect()
    }

    #[test]
    fn simple_rings_pass() {
        let square = ring(&[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]]);
        let hole = ring(&[[1.0, 1.0], [2.0, 1.0], [1.0, 2.0]]);
        let hole2 = ring(&[[3.0, 3.0], [3.5, 3.0], [3.5, 3.5]]);
        assert_eq!(check_rings(std::slice::from_ref(&square)), Ok(()));
        assert_eq!(check_rings(&[square, hole, hole2]), Ok(()));
        // A non-convex ring with collinear consecutive points going forward is fine.
        let l = ring(&[
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ]);
        assert_eq!(check_rings(&[l]), Ok(()));
    }

    #[test]
    fn bad_rings_are_refused() {
        let msg = |rings: &[Vec<Point>]| check_rings(rings).unwrap_err();
        assert!(
            msg(&[ring(&[[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]])]).contains("fewer than 3 distinct")
        );
        let bowtie = ring(&[[-1.0, -1.0], [1.0, 1.0], [1.0, -0.5], [-1.0, 1.0]]);
        assert!(msg(&[bowtie]).contains("edges 0 and 2 cross"));
        let repeated = ring(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]);
        assert!(msg(&[repeated]).contains("zero-length edge"));
        let flat = ring(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]);
        assert!(msg(&[flat]).contains("overlap"));
        // A corner touching a non-adjacent edge.
        let pinched = ring(&[[0.0, 0.0], [4.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]);
        assert!(msg(&[pinched]).contains("touch"));
        let square = ring(&[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]]);
        let outside = ring(&[[5.0, 5.0], [6.0, 5.0], [5.0, 6.0]]);
        assert!(msg(&[square.clone(), outside]).contains("outside the outer ring"));
        let crossing = ring(&[[3.0, 3.0], [5.0, 3.0], [3.0, 5.0]]);
        assert!(msg(&[square.clone(), crossing]).contains("rings 0 and 1 intersect"));
        let big = ring(&[[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]]);
        let small = ring(&[[1.5, 1.5], [2.0, 1.5], [1.5, 2.0]]);
        assert!(msg(&[square, big, small]).contains("hole ring 2 lies inside hole ring 1"));
        assert!(msg(&[]).contains("at least one ring"));
    }
}
