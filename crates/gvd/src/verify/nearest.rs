//! The nearest site to a point, exactly (brute force over a certified candidate set).
//!
//! Every site with a radial lower bound `field(q) ≥ lower(|q − anchor|)` is bucketed by
//! its anchor in a uniform grid of cell size `c`. The search scans rings of cells around
//! the query; after ring `k` every unscanned anchor is farther than `k·c`, so no
//! unscanned site can beat `G(k·c) = min_i lower_i(k·c)` (precomputed for every `k`), and
//! the search stops as soon as `G(k·c) ≥ best`. Sites without a bound are always
//! evaluated.

use super::field::{Bound, Field};
use crate::geom::{Aabb, Point};

/// The nearest-site index of a scene.
pub(super) struct Nearest<'a> {
    fields: &'a [Field],
    /// sites evaluated for every query
    always: Vec<usize>,
    /// closed sites (their insides belong to no cell)
    closed: Vec<usize>,
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    /// bucket `b` holds `ids[start[b]..start[b + 1]]`
    start: Vec<usize>,
    ids: Vec<usize>,
    /// `G(k·c)` for `k = 0..=max(nx, ny)`
    ring_bound: Vec<f64>,
}

/// The result of a query: the nearest site and its field value.
#[derive(Clone, Copy, Debug)]
pub(super) struct Hit {
    pub site: usize,
    pub value: f64,
}

impl<'a> Nearest<'a> {
    pub(super) fn new(fields: &'a [Field], domain: Aabb) -> Self {
        let mut always = Vec::new();
        let mut anchored = Vec::new();
        let mut closed = Vec::new();
        let (mut lo, mut hi) = (domain.min, domain.max);
        for (i, f) in fields.iter().enumerate() {
            if matches!(f, Field::Ellipse { .. }) {
                closed.push(i);
            }
            match f.bound() {
                (_, Bound::None) => always.push(i),
                (p, b) => {
                    lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
                    hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
                    anchored.push((i, p, b));
                }
            }
        }
        let (w, h) = ((hi.x - lo.x).max(1e-300), (hi.y - lo.y).max(1e-300));
        let cell = (w * h / anchored.len().max(1) as f64)
            .sqrt()
            .max(w.max(h) / 2048.0);
        let nx = ((w / cell).ceil() as usize).clamp(1, 2048);
        let ny = ((h / cell).ceil() as usize).clamp(1, 2048);
        let mut count = vec![0usize; nx * ny + 1];
        let key = |p: Point| {
            let i = (((p.x - lo.x) / cell) as usize).min(nx - 1);
            let j = (((p.y - lo.y) / cell) as usize).min(ny - 1);
            j * nx + i
        };
        for &(_, p, _) in &anchored {
            count[key(p) + 1] += 1;
        }
        for b in 0..nx * ny {
            count[b + 1] += count[b];
        }
        let start = count.clone();
        let mut ids = vec![0; anchored.len()];
        for &(i, p, _) in &anchored {
            let b = key(p);
            ids[count[b]] = i;
            count[b] += 1;
        }
        let ring_bound = (0..=nx.max(ny))
            .map(|k| {
                let r = k as f64 * cell;
                anchored
                    .iter()
                    .map(|&(_, _, b)| b.lower(r))
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        Nearest {
            fields,
            always,
            closed,
            origin: lo,
            cell,
            nx,
            ny,
            start,
            ids,
            ring_bound,
        }
    }

    /// The nearest site at `q`, or `None` inside a closed site (or with no sites).
    pub(super) fn at(&self, q: Point) -> Option<Hit> {
        if self.closed.iter().any(|&i| self.fields[i].inside(q)) {
            return None;
        }
        let mut best = Hit {
            site: usize::MAX,
            value: f64::INFINITY,
        };
        let consider = |i: usize, best: &mut Hit| {
            let v = self.fields[i].value(q);
            if v < best.value || (v == best.value && i < best.site) {
                *best = Hit { site: i, value: v };
            }
        };
        for &i in &self.always {
            consider(i, &mut best);
        }
        let cx = ((q.x - self.origin.x) / self.cell)
            .floor()
            .clamp(0.0, (self.nx - 1) as f64) as i64;
        let cy = ((q.y - self.origin.y) / self.cell)
            .floor()
            .clamp(0.0, (self.ny - 1) as f64) as i64;
        let (nx, ny) = (self.nx as i64, self.ny as i64);
        for k in 0..=nx.max(ny) {
            for j in (cy - k).max(0)..=(cy + k).min(ny - 1) {
                let mut visit = |i: i64| {
                    let b = (j * nx + i) as usize;
                    for &s in &self.ids[self.start[b]..self.start[b + 1]] {
                        consider(s, &mut best);
                    }
                };
                if j == cy - k || j == cy + k {
                    ((cx - k).max(0)..=(cx + k).min(nx - 1)).for_each(&mut visit);
                } else {
                    // inner rows: only the two cells of the ring
                    if cx - k >= 0 {
                        visit(cx - k);
                    }
                    if cx + k < nx {
                        visit(cx + k);
                    }
                }
            }
            if self.ring_bound[k as usize] >= best.value {
                break;
            }
        }
        (best.site != usize::MAX).then_some(best)
    }
}
