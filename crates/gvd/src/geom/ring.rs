//! Closed rings of points (the last point not repeated): area, orientation and
//! point-in-ring tests.

use super::grid::bounds_of_points;
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
/// parity of the rings that hold `q`), with the segments listed in equal horizontal
/// slabs of their bounds: a ray meets only the segments of its own slab. Each segment
/// is listed in every slab its y-range meets, so that a query's slab holds every segment
/// the ray can cross; the number of slabs (about one per segment) is lowered where tall
/// segments would make the lists long in total (at most about `9n` entries).
#[derive(Clone, Debug)]
pub(crate) struct RayCrossings {
    segments: Vec<(Point, Point)>,
    lo: f64,
    /// slabs per unit of y
    scale: f64,
    /// `members[rows[k]..rows[k + 1]]`: the segments of slab `k`
    rows: Vec<u32>,
    members: Vec<u32>,
}

impl RayCrossings {
    /// The index of `segments`.
    pub(crate) fn new(segments: Vec<(Point, Point)>) -> RayCrossings {
        let extent = bounds_of_points(segments.iter().flat_map(|&(a, b)| [a, b]));
        let (lo, height) = (extent.min.y, extent.height());
        let n = segments.len();
        let tall: f64 = segments.iter().map(|(a, b)| (a.y - b.y).abs()).sum();
        // Σ (h_k · slabs / height + 1) entries: at most 8n from the heights
        let by_entries = 8.0 * n as f64 * height / tall;
        let slabs = (n as f64).min(by_entries).clamp(1.0, (1u32 << 24) as f64) as usize;
        let scale = if height > 0.0 && height.is_finite() {
            slabs as f64 / height
        } else {
            0.0
        };
        let mut index = RayCrossings {
            segments,
            lo,
            scale,
            rows: vec![0; slabs + 1],
            members: Vec::new(),
        };
        let spans: Vec<(usize, usize)> = index
            .segments
            .iter()
            .map(|(a, b)| (index.slab(a.y.min(b.y)), index.slab(a.y.max(b.y))))
            .collect();
        for &(f, t) in &spans {
            for k in f..=t {
                index.rows[k + 1] += 1;
            }
        }
        for k in 1..index.rows.len() {
            index.rows[k] += index.rows[k - 1];
        }
        let mut fill = index.rows[..slabs].to_vec();
        index.members = vec![0; index.rows[slabs] as usize];
        for (i, &(f, t)) in spans.iter().enumerate() {
            for next in &mut fill[f..=t] {
                index.members[*next as usize] = i as u32;
                *next += 1;
            }
        }
        index
    }

    /// The slab of height `y` (monotone in `y`, so that a segment's slabs run from that
    /// of its lowest point to that of its highest).
    fn slab(&self, y: f64) -> usize {
        let f = (y - self.lo) * self.scale;
        let last = self.rows.len() - 2;
        if f.is_nan() {
            0
        } else {
            (f.max(0.0) as usize).min(last)
        }
    }

    /// The segments indexed.
    pub(crate) fn segments(&self) -> &[(Point, Point)] {
        &self.segments
    }

    /// Whether the ray from `q` towards +x crosses the segments an odd number of times.
    pub(crate) fn odd(&self, q: Point) -> bool {
        if self.segments.is_empty() {
            return false;
        }
        let k = self.slab(q.y);
        let row = &self.members[self.rows[k] as usize..self.rows[k + 1] as usize];
        row.iter()
            .filter(|&&i| {
                let (a, b) = self.segments[i as usize];
                ray_crossing(a, b, q).is_some()
            })
            .count()
            % 2
            == 1
    }
}

/// Where a point lies against a set of segments bounding a region by the even-odd rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Location {
    Inside,
    OnBoundary,
    Outside,
}

impl RayCrossings {
    /// Where `q` lies, exactly (orientation signs, Sunday01): on a segment, else inside
    /// when the ray from `q` towards +x crosses an odd number of them (each counted on
    /// the half-open rule of [`ray_crossing`]).
    pub(crate) fn locate(&self, q: Point) -> Location {
        if self.segments.is_empty() {
            return Location::Outside;
        }
        let k = self.slab(q.y);
        let mut odd = false;
        for &i in &self.members[self.rows[k] as usize..self.rows[k + 1] as usize] {
            let (a, b) = self.segments[i as usize];
            let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
            let side = orientation(lo, hi, q);
            let within = a.x.min(b.x) <= q.x && q.x <= a.x.max(b.x) && lo.y <= q.y && q.y <= hi.y;
            if side == Ordering::Equal && within {
                return Location::OnBoundary;
            }
            if lo.y <= q.y && q.y < hi.y && side == Ordering::Greater {
                odd = !odd;
            }
        }
        if odd {
            Location::Inside
        } else {
            Location::Outside
        }
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
