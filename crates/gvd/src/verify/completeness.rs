//! Check c (completeness): every label change between neighbours of an N × N grid is
//! covered by an output edge of the same pair or a vertex listing both.

use super::field::Field;
use super::report::MAX_LIST;
use super::Checker;
use crate::geom::grid::BucketGrid;
use crate::geom::{Aabb, Point};
use crate::par::map_range;
use std::collections::BTreeMap;

/// How often a grid step is split where a third generator is nearer at the crossing
/// (2^8 pieces: a step may cross that many cells narrower than it, as on outlines of
/// chords far shorter than the grid; the Python checker splits as deep).
const MAX_SPLIT_DEPTH: u32 = 8;

impl Checker<'_> {
    /// The crossings of the bisectors between the nearest generators `a` at `qa` and
    /// `b` at `qb`: bisection of `d_a − d_b` (14 steps, then linear interpolation);
    /// where a third generator is
    /// nearer at the crossing, both halves are searched again (depth ≤
    /// [`MAX_SPLIT_DEPTH`]; deeper, the step holds no crossing of `a` and `b`). An edge or
    /// piece whose foot at the crossing is its end corner, beyond it by more than the
    /// last bracket, becomes that corner (the bisection crossed the corner's zone
    /// boundary). Crossings in ties of coincident feet (or feet at a shared point and
    /// within two brackets of it), inside closed sites and outside the medial-axis
    /// region are skipped.
    pub(super) fn crossings(
        &self,
        qa: Point,
        qb: Point,
        a: usize,
        b: usize,
        depth: u32,
        out: &mut Vec<(Point, usize, usize)>,
    ) {
        let (mut lo, mut hi) = (0.0, 1.0);
        let (mut d_lo, mut d_hi) = (f64::NAN, f64::NAN);
        for _ in 0..14 {
            let mid = 0.5 * (lo + hi);
            let q = qa.lerp(qb, mid);
            let (va, vb) = (self.fields[a].value(q), self.fields[b].value(q));
            if va <= vb {
                (lo, d_lo) = (mid, va - vb);
            } else {
                (hi, d_hi) = (mid, va - vb);
            }
        }
        // The tie inside the last bracket by linear interpolation of d_a − d_b (as the
        // Python checker does): the bracket's middle can be half a bracket off, enough
        // to separate the feet at a tie through one point (a shared end's wedge).
        let frac = d_lo / (d_lo - d_hi);
        let t = if frac.is_finite() {
            lo + frac.clamp(0.0, 1.0) * (hi - lo)
        } else {
            0.5 * (lo + hi)
        };
        let x = qa.lerp(qb, t);
        let (da, ga) = self.eval(a, x);
        let (db, gb) = self.eval(b, x);
        // The crossing is known within the last bracket: only beyond a corner by more
        // than that did the bisection cross the corner's zone boundary (a tangent
        // joint's crossing lies on the boundary, on either side by rounding).
        let bracket = qa.dist(qb) * (hi - lo);
        let (a, b) = if self.gens.featured {
            (
                self.gens.corner_if_at_end(a, x, self.tiny, bracket),
                self.gens.corner_if_at_end(b, x, self.tiny, bracket),
            )
        } else {
            (a, b)
        };
        // after the relabelling, a corner and its own edge: the crossing lies on that
        // corner's zone boundary, which is no Voronoi edge (the Python checker keeps
        // these; they arise where a corner's wedge is narrower than the grid)
        if self.gens.featured && self.gens.zone_boundary(a, b) {
            return;
        }
        let Some(hit) = self.near.at(x) else {
            return;
        };
        let (dmin, gmin) = if da <= db { (da, ga) } else { (db, gb) };
        let k = hit.gen;
        if k != a && k != b {
            let (_, gk) = self.eval(k, x);
            if super::excess_length(dmin - hit.value, gmin, gk) > 1e-9 * self.scale {
                // still nearer after MAX_SPLIT_DEPTH splits (a cascade of cells narrower
                // than the grid: a curve drawn with chords far shorter than its step):
                // no crossing of a and b, and no edge of theirs could cover it
                if depth < MAX_SPLIT_DEPTH {
                    self.crossings(qa, x, a, k, depth + 1, out);
                    self.crossings(x, qb, k, b, depth + 1, out);
                }
                return;
            }
        }
        let tie = match (self.fields[a].foot(x), self.fields[b].foot(x)) {
            (Some(fa), Some(fb)) => {
                // at the edge of a shared point's tie zone, the feet of a crossing
                // known within the last bracket are up to about the bracket apart
                let apart = fa.dist(fb);
                let shared = |f: Point| !self.gens.shared.owners_at(f).is_empty();
                apart <= 1e-7 * self.scale || (apart <= 2.0 * bracket && (shared(fa) || shared(fb)))
            }
            _ => false,
        };
        if !tie && self.in_region(x) {
            out.push((x, a, b));
        }
    }

    /// Where the ridge of the whole curve `g` (its self-bisector, the medial axis inside
    /// a closed curve) crosses the grid step `qa`–`qb`, whose nearest feet lie far
    /// apart: bisection keeps the half whose ends' feet differ more (a point's foot is
    /// the nearest of its own and the slides from the two ends' feet), down to `1e-12`
    /// of the scene;
    /// a jump of more than `1e-6` of the scene across that is a crossing (a continuous
    /// foot would move by about `1e-12 · ρ/(ρ − d)` of it, `ρ` the radius of curvature
    /// and `d` the distance).
    fn ridge_crossing(&self, qa: Point, qb: Point, g: usize) -> Option<Point> {
        let Field::Curve(curve) = &self.fields[g] else {
            return None;
        };
        let (mut a, mut b) = (qa, qb);
        let (mut fa, mut fb) = (curve.foot(a)?, curve.foot(b)?);
        while a.dist(b) > 1e-12 * self.scale {
            let m = a.lerp(b, 0.5);
            let fm = [curve.foot(m)?, curve.slide(m, fa), curve.slide(m, fb)]
                .into_iter()
                .min_by(|p, q| m.dist(*p).total_cmp(&m.dist(*q)))?;
            if fm.dist(fa) >= fm.dist(fb) {
                (b, fb) = (m, fm);
            } else {
                (a, fa) = (m, fm);
            }
        }
        let x = a.lerp(b, 0.5);
        (fa.dist(fb) > 1e-6 * self.scale && self.in_region(x)).then_some(x)
    }

    /// `g` and the generators that may name its region at `x` instead: where `g`'s foot
    /// from `x` is a point that other sites share (see [`generators::SharedPoints`]),
    /// their generators there that tie with `g` at `x`; and the generators of other
    /// sites through that same foot, tied with `g` at `x` (segments that overlap or
    /// repeat one another, a crossing: their common points, like shared ends, may be
    /// named by any of them).
    pub(super) fn owners(&self, g: usize, x: Point) -> Vec<usize> {
        let mut out = vec![g];
        let Some(foot) = self.fields[g].foot(x) else {
            return out;
        };
        let shared = &self.gens.shared;
        let (site, dg) = (self.gens.labels[g].site(), self.fields[g].value(x));
        let tol = 2.0 * shared.radius();
        for (h, other) in shared.owners_at(foot) {
            let tie = (self.fields[h].value(x) - dg).abs() <= tol;
            if other != site && tie && !out.contains(&h) {
                out.push(h);
            }
        }
        for h in self.near.within(x, dg + tol) {
            let through = self.fields[h]
                .foot(x)
                .is_some_and(|f| f.dist(foot) <= shared.radius());
            if through && self.gens.labels[h].site() != site && !out.contains(&h) {
                out.push(h);
            }
        }
        out
    }

    /// Check c: returns the fraction of covered crossings.
    pub(super) fn completeness(&self, problems: &mut Vec<String>) -> f64 {
        let dom = self.scene.domain();
        let n = self.opts.grid;
        let (hx, hy) = (dom.width() / n as f64, dom.height() / n as f64);
        let r = 2.0 * self.tol + hx.max(hy);
        let node = |i: usize, j: usize| {
            Point::new(
                dom.min.x + (i as f64 + 0.5) * hx,
                dom.min.y + (j as f64 + 0.5) * hy,
            )
        };
        let labels = map_range(n * n, 1, |k| {
            let q = node(k % n, k / n);
            if self.in_region(q) {
                self.near.at(q).map(|h| h.gen)
            } else {
                None
            }
        });
        // the nearest feet on whole curves, whose jumps are their ridges' crossings
        let feet = map_range(n * n, 1, |k| {
            let g = labels[k].filter(|&g| self.gens.whole_curve_field(g))?;
            self.fields[g].foot(node(k % n, k / n))
        });
        let mut pairs = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let Some(a) = labels[j * n + i] else { continue };
                for (di, dj) in [(1, 0), (0, 1)] {
                    if i + di < n && j + dj < n {
                        let k = (j + dj) * n + i + di;
                        if let Some(b) = labels[k] {
                            let jump = match (feet[j * n + i], feet[k]) {
                                (Some(fa), Some(fb)) => a == b && fa.dist(fb) > 4.0 * hx.max(hy),
                                _ => false,
                            };
                            if (a != b && !self.gens.zone_boundary(a, b)) || jump {
                                pairs.push((node(i, j), node(i + di, j + dj), a, b));
                            }
                        }
                    }
                }
            }
        }
        let found = map_range(pairs.len(), 1, |p| {
            let (qa, qb, a, b) = pairs[p];
            let mut out = Vec::new();
            if a == b {
                out.extend(self.ridge_crossing(qa, qb, a).map(|x| (x, a, a)));
            } else {
                self.crossings(qa, qb, a, b, 0, &mut out);
            }
            out
        });
        let crossings: Vec<(Point, usize, usize)> = found.into_iter().flatten().collect();
        // the output edges as pieces of length ≤ R, bucketed by their midpoints
        let mut pieces: Vec<(Point, Point, (usize, usize))> = Vec::new();
        for ge in &self.edges {
            let key = (ge.a.min(ge.b), ge.a.max(ge.b));
            for w in self.diagram.edges[ge.index].points.windows(2) {
                let m = ((w[1].dist(w[0]) / r).ceil() as usize).clamp(1, 1 << 16);
                pieces.extend((0..m).map(|j| {
                    let t = |j: usize| j as f64 / m as f64;
                    (w[0].lerp(w[1], t(j)), w[0].lerp(w[1], t(j + 1)), key)
                }));
            }
        }
        let mids: Vec<Point> = pieces.iter().map(|p| p.0.lerp(p.1, 0.5)).collect();
        let pb = point_buckets(&mids, dom, r);
        let vat: Vec<Point> = self.diagram.vertices.iter().map(|v| v.at).collect();
        let vb = point_buckets(&vat, dom, r);
        let covered_by = |x: Point, a: usize, b: usize| {
            let key = (a.min(b), a.max(b));
            // a piece's midpoint lies within R + R/2 of x: at most 2 cells away
            pb.any_around(x, 2, |p| {
                let p = p as usize;
                pieces[p].2 == key
                    && crate::geom::segment_distance(x, pieces[p].0, pieces[p].1) <= r
            }) || vb.any_around(x, 1, |v| {
                let v = v as usize;
                vat[v].dist(x) <= r
                    && self.vgens[v]
                        .as_ref()
                        .is_some_and(|g| g.contains(&a) && g.contains(&b))
            })
        };
        let covered = map_range(crossings.len(), 1, |c| {
            let (x, a, b) = crossings[c];
            covered_by(x, a, b) || {
                // either label may be another owner of a shared point
                let (oa, ob) = (self.owners(a, x), self.owners(b, x));
                (oa.len() > 1 || ob.len() > 1)
                    && oa.iter().any(|&a2| {
                        ob.iter()
                            .any(|&b2| a2 != b2 && (a2, b2) != (a, b) && covered_by(x, a2, b2))
                    })
            }
        });
        let mut missing: BTreeMap<(usize, usize), (usize, Point)> = BTreeMap::new();
        for (c, &ok) in covered.iter().enumerate() {
            if !ok {
                let (x, a, b) = crossings[c];
                missing.entry((a.min(b), a.max(b))).or_insert((0, x)).0 += 1;
            }
        }
        let mut miss: Vec<_> = missing.into_iter().collect();
        miss.sort_by_key(|m| std::cmp::Reverse(m.1 .0));
        for &((a, b), (count, x)) in miss.iter().take(MAX_LIST) {
            problems.push(format!(
                "completeness: no edge between sites {} and {} near {} ({count} crossings uncovered)",
                self.name(a),
                self.name(b),
                self.at(x)
            ));
        }
        if miss.len() > MAX_LIST {
            problems.push(format!(
                "completeness: ... and {} more missing pairs",
                miss.len() - MAX_LIST
            ));
        }
        let good = covered.iter().filter(|&&c| c).count();
        if crossings.is_empty() {
            1.0
        } else {
            good as f64 / crossings.len() as f64
        }
    }
}

/// Points bucketed in the shared grid over `area` in cells of side `cell` (points
/// outside it land in its border cells).
pub(super) fn point_buckets(points: &[Point], area: Aabb, cell: f64) -> BucketGrid {
    BucketGrid::new(area, cell, 4097, points.len(), |k| {
        Aabb::new(points[k], points[k])
    })
}
