//! Nearest-site queries after the subdivision: the leaf that holds a point keeps every
//! site that can be nearest there, so the answer is the best of a few sites.

use super::segments::label;
use super::tree::Leaf;
use crate::geom::{Aabb, Point};
use crate::site::DistanceField;

/// A uniform grid over the domain listing, per grid cell, the leaves that overlap it.
pub struct Locator<'a, F> {
    fields: &'a [F],
    leaves: &'a [Leaf],
    domain: Aabb,
    n: [usize; 2],
    cells: Vec<Vec<u32>>,
}

impl<'a, F: DistanceField> Locator<'a, F> {
    pub fn new(fields: &'a [F], leaves: &'a [Leaf], domain: Aabb) -> Self {
        let side = ((leaves.len() as f64).sqrt().ceil() as usize).clamp(1, 4096);
        let n = [side, side];
        let mut cells = vec![Vec::new(); n[0] * n[1]];
        let grid = Locator {
            fields,
            leaves,
            domain,
            n,
            cells: Vec::new(),
        };
        for (k, l) in leaves.iter().enumerate() {
            let (i0, j0) = grid.cell_of(l.aabb.min);
            let (i1, j1) = grid.cell_of(l.aabb.max);
            for i in i0..=i1 {
                for j in j0..=j1 {
                    cells[j * n[0] + i].push(k as u32);
                }
            }
        }
        Locator { cells, ..grid }
    }

    fn cell_of(&self, p: Point) -> (usize, usize) {
        let u = (p.x - self.domain.min.x) / self.domain.width() * self.n[0] as f64;
        let v = (p.y - self.domain.min.y) / self.domain.height() * self.n[1] as f64;
        let clamp = |t: f64, n: usize| (t.max(0.0) as usize).min(n - 1);
        (clamp(u, self.n[0]), clamp(v, self.n[1]))
    }

    /// The nearest site to `q` (ties to the smaller index, as everywhere in the engine);
    /// points outside the domain are clamped onto it.
    pub fn nearest(&self, q: Point) -> usize {
        let c = Point::new(
            q.x.clamp(self.domain.min.x, self.domain.max.x),
            q.y.clamp(self.domain.min.y, self.domain.max.y),
        );
        let (i, j) = self.cell_of(c);
        let leaf = self.cells[j * self.n[0] + i]
            .iter()
            .map(|&k| &self.leaves[k as usize])
            .find(|l| l.aabb.contains(c));
        match leaf {
            Some(l) if !l.sites.is_empty() => label(self.fields, &l.sites, q) as usize,
            _ => {
                let all: Vec<u32> = (0..self.fields.len() as u32).collect();
                label(self.fields, &all, q) as usize
            }
        }
    }
}
