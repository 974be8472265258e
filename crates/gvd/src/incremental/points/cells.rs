//! Cells straight from the graph's faces: each site's face is a convex polygon, walked
//! counter-clockwise along its half-edges; its clipped edges (the very segments the
//! complex lists) are joined along the domain boundary, corners included, where the
//! face leaves the domain and comes back.

use super::PointDiagram;
use crate::complex::{smallvec, Cell};
use crate::geom::ring::signed_area;
use crate::geom::{Aabb, Point};
use crate::par::map_range;

/// Why a face could not be traced; the caller then falls back to the generic
/// [`crate::complex::cells::build_cells`]. Not expected with exact signs.
#[derive(Debug)]
pub(super) struct Inconsistent;

/// The cells of `d`, sorted by site. `segment(h)` is the output edge of half-edge `h`
/// from its origin on (the segment clipped to the domain, input coordinates), `None` if
/// no edge is output for it. `domain` is in input coordinates.
pub(super) fn face_cells(
    d: &PointDiagram,
    segment: impl Fn(u32) -> Option<(Point, Point)> + Sync,
    domain: Aabb,
) -> Result<Vec<Cell>, Inconsistent> {
    let g = &d.graph;
    let n = d.input.len();
    let (w, h) = (domain.width(), domain.height());
    if n == 0 || !(w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite()) {
        return Ok(Vec::new());
    }

    // One half-edge of every site's face (in insertion order).
    let mut start = vec![u32::MAX; n];
    for h in 0..g.twin.len() as u32 {
        let s = g.left(h) as usize;
        if s < n && start[s] == u32::MAX {
            start[s] = h;
        }
    }
    let frame = Frame::new(domain);
    let trace = |s: usize| -> Result<Option<Cell>, Inconsistent> {
        let h0 = start[s];
        if h0 == u32::MAX {
            return Ok(None); // a duplicate: no face
        }
        // The face's clipped edges in counter-clockwise order, joined along the
        // boundary where one ends short of where the next begins.
        let mut ring: Vec<Point> = Vec::new();
        let mut h = h0;
        loop {
            if let Some((a, b)) = segment(h) {
                let (a, b) = (frame.snap(a), frame.snap(b));
                match ring.last() {
                    None => ring.reserve(8),
                    Some(&last) if last != a => frame.walk(last, a, &mut ring)?,
                    Some(_) => {}
                }
                for p in [a, b] {
                    if ring.last() != Some(&p) {
                        ring.push(p);
                    }
                }
            }
            h = g.next(h);
            if h == h0 {
                break;
            }
        }
        let (Some(&first), Some(&last)) = (ring.first(), ring.last()) else {
            return Ok(None);
        };
        if last != first {
            frame.walk(last, first, &mut ring)?;
        }
        while ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
        let area = signed_area(&ring);
        Ok(
            (ring.len() >= 3 && area > 0.0 && area.is_finite()).then(|| Cell {
                site: d.input[s] as usize,
                rings: smallvec![ring],
            }),
        )
    };

    // Traced in insertion order (neighbouring faces share vertices), then gathered by
    // site: input point i was inserted at position `at[i]`.
    let mut traced = map_range(n, 1 << 10, trace);
    let mut at = vec![0u32; n];
    for (s, &i) in d.input.iter().enumerate() {
        at[i as usize] = s as u32;
    }
    let mut cells = Vec::new();
    for &s in &at {
        if let Some(c) = std::mem::replace(&mut traced[s as usize], Ok(None))? {
            cells.push(c);
        }
    }
    if cells.is_empty() {
        // No edge meets the domain: it lies in one cell, the nearest site's to its
        // centre (the least index among equals).
        let c = d.domain.center();
        let key = |s: usize| (d.pts[s].dist(c), d.input[s]);
        let best = (1..n).fold(0, |b, s| {
            if key(s).partial_cmp(&key(b)) == Some(std::cmp::Ordering::Less) {
                s
            } else {
                b
            }
        });
        return Ok(vec![Cell {
            site: d.input[best] as usize,
            rings: smallvec![domain.corners().to_vec()],
        }]);
    }
    Ok(cells)
}

/// The domain boundary, parametrized counter-clockwise from `min` by arc length.
struct Frame {
    domain: Aabb,
    perimeter: f64,
    /// Distances below this are rounding: points this near the boundary are on it.
    tol: f64,
}

impl Frame {
    fn new(domain: Aabb) -> Frame {
        Frame {
            domain,
            perimeter: 2.0 * (domain.width() + domain.height()),
            tol: 1e-10 * domain.longest_side(),
        }
    }

    /// `p` moved onto the boundary if it lies within `tol` of it (as
    /// [`crate::complex::cells::build_cells`] does), else `p`.
    fn snap(&self, p: Point) -> Point {
        let (a, b) = (self.domain.min, self.domain.max);
        let dist = [p.y - a.y, b.x - p.x, b.y - p.y, p.x - a.x];
        let side = (0..4).fold(0, |m, i| if dist[i] < dist[m] { i } else { m });
        if dist[side].abs() > self.tol {
            return p;
        }
        match side {
            0 => Point::new(p.x, a.y),
            1 => Point::new(b.x, p.y),
            2 => Point::new(p.x, b.y),
            _ => Point::new(a.x, p.y),
        }
    }

    /// The boundary position of `p`'s nearest boundary point, if `p` lies within `tol`
    /// of the boundary.
    fn param(&self, p: Point) -> Option<f64> {
        let (a, b) = (self.domain.min, self.domain.max);
        let dist = [p.y - a.y, b.x - p.x, b.y - p.y, p.x - a.x];
        let side = (0..4).fold(0, |m, i| if dist[i] < dist[m] { i } else { m });
        if dist[side].abs() > self.tol {
            return None;
        }
        let (w, h) = (self.domain.width(), self.domain.height());
        let t = match side {
            0 => p.x - a.x,
            1 => w + p.y - a.y,
            2 => w + h + b.x - p.x,
            _ => 2.0 * w + h + b.y - p.y,
        };
        Some(t.clamp(0.0, self.perimeter))
    }

    /// Appends the corners met going counter-clockwise along the boundary from `from`
    /// (where the face leaves the domain) to `to` (where it comes back). A backward
    /// step within `tol` is rounding, not a full turn.
    fn walk(&self, from: Point, to: Point, ring: &mut Vec<Point>) -> Result<(), Inconsistent> {
        let (Some(t0), Some(t1)) = (self.param(from), self.param(to)) else {
            return Err(Inconsistent);
        };
        let p = self.perimeter;
        let mut len = (t1 - t0).rem_euclid(p);
        if len > p - self.tol {
            len = 0.0;
        }
        let (w, h) = (self.domain.width(), self.domain.height());
        let corners = self.domain.corners();
        // Corner k sits at boundary position tk[k]; the walk may wrap past `min` once.
        let tk = [0.0, w, w + h, 2.0 * w + h];
        for lap in [0.0, p] {
            for k in 0..4 {
                let off = tk[k] + lap - t0;
                if off > self.tol && off < len - self.tol {
                    ring.push(corners[k]);
                }
            }
        }
        Ok(())
    }
}
