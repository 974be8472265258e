//! The nearest generator to a point, exactly (brute force over a certified candidate
//! set).
//!
//! Every generator with a radial lower bound `field(q) ≥ lower(|q − anchor|)` is bucketed by
//! its anchor in a uniform grid of cell size `c`. The search scans rings of cells around
//! the query; after ring `k` every unscanned anchor is farther than `k·c`, so no
//! unscanned site can beat `G(k·c) = min_i lower_i(k·c)` (precomputed for every `k`), and
//! the search stops as soon as `G(k·c) ≥ best`. Sites without a bound are always
//! evaluated. Points inside a masked closed site have no nearest generator; where the
//! foot on the nearest edge/piece is an end corner, the hit names the corner.

use super::field::Bound;
use super::generators::{Gens, Mask};
use crate::geom::grid::BucketGrid;
use crate::geom::{Aabb, Point};

/// The nearest-site index of a scene.
pub(super) struct Nearest<'a> {
    gens: &'a Gens,
    /// generators evaluated for every query
    always: Vec<usize>,
    /// `1e-12` of the scene's size: feet closer than this to an end are at the end
    tiny: f64,
    /// the anchored generators, by anchor (item `k` is `anchored[k]`)
    grid: BucketGrid,
    anchored: Vec<usize>,
    /// `G(k·c)` for `k = 0..=max(nx, ny)`
    ring_bound: Vec<f64>,
}

/// The result of a query: the nearest generator and its field value.
#[derive(Clone, Copy, Debug)]
pub(super) struct Hit {
    pub gen: usize,
    pub value: f64,
}

impl<'a> Nearest<'a> {
    pub(super) fn new(gens: &'a Gens, domain: Aabb) -> Self {
        let mut always = Vec::new();
        let mut anchored = Vec::new();
        let (mut lo, mut hi) = (domain.min, domain.max);
        for (i, f) in gens.fields.iter().enumerate() {
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
        // about one anchor a cell; `w·h` would underflow in a domain of 1e-300 (a grid
        // of 2048² empty cells, each query scanning them all)
        let cell =
            (w.sqrt() * h.sqrt() / (anchored.len().max(1) as f64).sqrt()).max(w.max(h) / 2048.0);
        let grid = BucketGrid::new(Aabb::new(lo, hi), cell, 2049, anchored.len(), |k| {
            Aabb::new(anchored[k].1, anchored[k].1)
        });
        let (nx, ny) = grid.dims();
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
            gens,
            always,
            tiny: 1e-12 * domain.longest_side(),
            grid,
            anchored: anchored.iter().map(|&(i, _, _)| i).collect(),
            ring_bound,
        }
    }

    /// How deep `q` lies inside a masked closed site (0 outside all of them).
    pub(super) fn inside_depth(&self, q: Point) -> f64 {
        self.gens
            .masks
            .iter()
            .map(|m| match m {
                Mask::Ellipse { gen } => self.gens.fields[*gen].inside_depth(q),
                Mask::Polygon { region } => region.depth(q),
            })
            .fold(0.0, f64::max)
    }

    /// Whether `q` lies inside a masked closed site.
    pub(super) fn masked(&self, q: Point) -> bool {
        self.gens.masks.iter().any(|m| match m {
            Mask::Ellipse { gen } => self.gens.fields[*gen].inside(q),
            Mask::Polygon { region } => region.contains(q),
        })
    }

    /// The nearest generator at `q`, or `None` inside a closed site (or with no
    /// generators).
    pub(super) fn at(&self, q: Point) -> Option<Hit> {
        if self.masked(q) {
            return None;
        }
        self.at_unmasked(q)
    }

    /// The nearest generator at `q`, inside closed sites too.
    pub(super) fn at_unmasked(&self, q: Point) -> Option<Hit> {
        let fields = &self.gens.fields;
        let mut best = Hit {
            gen: usize::MAX,
            value: f64::INFINITY,
        };
        let consider = |i: usize, best: &mut Hit| {
            let v = fields[i].value(q);
            if v < best.value || (v == best.value && i < best.gen) {
                *best = Hit { gen: i, value: v };
            }
        };
        for &i in &self.always {
            consider(i, &mut best);
        }
        let c = self.grid.cell_of(q);
        let (nx, ny) = self.grid.dims();
        for ring in 0..=nx.max(ny) {
            self.grid
                .for_each_in_ring(c, ring, |k| consider(self.anchored[k as usize], &mut best));
            if self.ring_bound[ring] >= best.value {
                break;
            }
        }
        if best.gen == usize::MAX {
            return None;
        }
        best.gen = self.gens.end_corner(best.gen, q, self.tiny);
        Some(best)
    }

    /// Every generator whose field at `q` is at most `value` (outside closed sites
    /// too): the generators tied with one of field `value` there, and nearer ones.
    pub(super) fn within(&self, q: Point, value: f64) -> Vec<usize> {
        let fields = &self.gens.fields;
        let mut out: Vec<usize> = Vec::new();
        let mut consider = |i: usize| {
            if fields[i].value(q) <= value {
                out.push(i);
            }
        };
        self.always.iter().for_each(|&i| consider(i));
        let c = self.grid.cell_of(q);
        let (nx, ny) = self.grid.dims();
        for ring in 0..=nx.max(ny) {
            self.grid
                .for_each_in_ring(c, ring, |k| consider(self.anchored[k as usize]));
            if self.ring_bound[ring] > value {
                break;
            }
        }
        out
    }
}
