//! The sides of the leaves, cut into elementary segments where a neighbour's corner
//! falls (T-junctions), and the label changes of the lower envelope along each segment.
//!
//! A segment is computed once and shared by the two leaves it separates, so both see the
//! same transitions: the global diagram is stitched through them.

use super::tree::{IBox, Lattice};
use crate::control::Watch;
use crate::geom::{Aabb, Point};
use crate::site::DistanceField;

/// An elementary segment: a piece of a leaf side between two lattice nodes, with the
/// leaves on its two sides (`None` outside the domain).
#[derive(Clone, Debug)]
pub struct Segment {
    pub from: Point,
    pub to: Point,
    pub leaves: [Option<u32>; 2],
}

/// A point where the nearest site changes from `pair[0]` to `pair[1]` along a segment.
#[derive(Clone, Copy, Debug)]
pub struct Transition {
    pub at: Point,
    pub pair: [u32; 2],
}

struct Side {
    line: u64,
    after: bool,
    lo: u64,
    hi: u64,
    leaf: u32,
}

/// All elementary segments, and for each leaf the indices of the segments on its
/// boundary (compressed rows: `rows[l]..rows[l + 1]` in `members`).
pub struct Segments {
    pub segments: Vec<Segment>,
    pub rows: Vec<usize>,
    pub members: Vec<u32>,
}

/// The segments of the leaves with boxes `boxes` (which tile the lattice's root box).
pub fn build(boxes: &[IBox], lattice: &Lattice) -> Segments {
    let mut segments = Vec::new();
    for axis in 0..2 {
        // sides perpendicular to `axis` lie on lines `coord[axis] = const`
        let other = 1 - axis;
        let mut sides: Vec<Side> = Vec::with_capacity(2 * boxes.len());
        for (k, ib) in boxes.iter().enumerate() {
            let (lo, hi) = (ib.lo[other], ib.hi[other]);
            sides.push(Side {
                line: ib.lo[axis],
                after: true,
                lo,
                hi,
                leaf: k as u32,
            });
            sides.push(Side {
                line: ib.hi[axis],
                after: false,
                lo,
                hi,
                leaf: k as u32,
            });
        }
        // by (line, after, lo), packed (lattice coordinates are below 2^63); the keys
        // are distinct, as leaves do not overlap
        sides.sort_unstable_by_key(|s| {
            (u128::from(s.line) << 64) | (u128::from(s.after) << 63) | u128::from(s.lo)
        });
        let mut start = 0;
        while start < sides.len() {
            let line = sides[start].line;
            let end = start + sides[start..].partition_point(|s| s.line == line);
            let mid = start + sides[start..end].partition_point(|s| !s.after);
            merge_line(
                &sides[start..mid],
                &sides[mid..end],
                axis,
                line,
                lattice,
                &mut segments,
            );
            start = end;
        }
    }
    let mut counts = vec![0usize; boxes.len() + 1];
    for s in &segments {
        for l in s.leaves.iter().flatten() {
            counts[*l as usize + 1] += 1;
        }
    }
    for k in 1..counts.len() {
        counts[k] += counts[k - 1];
    }
    let mut fill = counts.clone();
    let mut members = vec![0u32; counts[boxes.len()]];
    for (i, s) in segments.iter().enumerate() {
        for l in s.leaves.iter().flatten() {
            members[fill[*l as usize]] = i as u32;
            fill[*l as usize] += 1;
        }
    }
    Segments {
        segments,
        rows: counts,
        members,
    }
}

/// Cuts one lattice line into segments: `before` are the sides of leaves ending on the
/// line, `after` those of leaves starting on it, each sorted along the line.
fn merge_line(
    before: &[Side],
    after: &[Side],
    axis: usize,
    line: u64,
    lattice: &Lattice,
    out: &mut Vec<Segment>,
) {
    let point = |t: u64| {
        if axis == 0 {
            lattice.point(line, t)
        } else {
            lattice.point(t, line)
        }
    };
    let mut push = |lo: u64, hi: u64, a: Option<u32>, b: Option<u32>| {
        out.push(Segment {
            from: point(lo),
            to: point(hi),
            leaves: [a, b],
        });
    };
    if before.is_empty() || after.is_empty() {
        for s in before.iter().chain(after) {
            push(s.lo, s.hi, Some(s.leaf), None);
        }
        return;
    }
    let (mut i, mut j) = (0, 0);
    while i < before.len() && j < after.len() {
        let (a, b) = (&before[i], &after[j]);
        let lo = a.lo.max(b.lo);
        let hi = a.hi.min(b.hi);
        if lo < hi {
            push(lo, hi, Some(a.leaf), Some(b.leaf));
        }
        if a.hi <= b.hi {
            i += 1;
        } else {
            j += 1;
        }
    }
}

/// Two values closer than this many ulps (of the larger) are ordered by the fields'
/// exact comparison where they have one: a Euclidean distance is computed to about 2.5
/// ulps, so farther apart the f64 order is the exact one.
const ROUNDING_ULPS: f64 = 16.0;

/// The nearest of `cands` at `q`; ties go to the smallest site index, so every caller
/// labels a point alike whatever superset of the true nearest sites it passes.
pub fn label<F: DistanceField>(fields: &[F], cands: &[u32], q: Point) -> u32 {
    nearest_of(
        fields,
        q,
        cands.iter().map(|&c| (c, fields[c as usize].value(q))),
    )
}

/// [`label`] among `sites` at a point `q` of the box their states were made for.
fn label_in<F: DistanceField>(fields: &[F], sites: &[(u32, F::State)], q: Point) -> u32 {
    nearest_of(
        fields,
        q,
        sites
            .iter()
            .map(|(c, s)| (*c, fields[*c as usize].value_in(s, q))),
    )
}

/// Whether two field values are within [`ROUNDING_ULPS`] of each other.
fn within_rounding(v: f64, w: f64) -> bool {
    (v - w).abs() <= ROUNDING_ULPS * f64::EPSILON * v.abs().max(w.abs())
}

/// The site of least value at `q` among `(site, value)`, the smallest index among equals.
///
/// Values within rounding of each other are compared exactly where the fields can
/// ([`DistanceField::exact_cmp`]): along a bisector of two points that lies on a box
/// side, the f64 distances differ by rounding alone, and the side would change label
/// at random points (ports that the leaves on either side join differently); exactly,
/// the side is tied all along and takes the smaller index, as the filter, exact for
/// such pairs, assumes.
fn nearest_of<F: DistanceField>(
    fields: &[F],
    q: Point,
    values: impl Iterator<Item = (u32, f64)>,
) -> u32 {
    let nearer = |(c, v): (u32, f64), (b, w): (u32, f64)| {
        if within_rounding(v, w) {
            if let Some(order) = fields[c as usize].exact_cmp(&fields[b as usize], q) {
                return order.then(c.cmp(&b)).is_lt();
            }
        }
        v < w || (v == w && c < b)
    };
    let mut best = (u32::MAX, f64::INFINITY);
    for cv in values {
        if best.0 == u32::MAX || nearer(cv, best) {
            best = cv;
        }
    }
    best.0
}

/// The box of the segment `p0 → p1` (without extent across an axis-parallel one).
pub fn segment_box(p0: Point, p1: Point) -> Aabb {
    Aabb::new(
        Point::new(p0.x.min(p1.x), p0.y.min(p1.y)),
        Point::new(p0.x.max(p1.x), p0.y.max(p1.y)),
    )
}

/// The label changes along the segment `p0 → p1` among the sorted sites `sites`, with
/// their states over [`segment_box`], in order from `p0`. Sub-segments are discarded by
/// the same lower-envelope filter as boxes; label changes are isolated to `min_len` and
/// then refined to full precision.
pub fn transitions<F: DistanceField>(
    fields: &[F],
    sites: Vec<(u32, F::State)>,
    p0: Point,
    p1: Point,
    min_len: f64,
    watch: &Watch,
) -> Vec<Transition> {
    let mut out = Vec::new();
    // a stopped run evaluates no field here (each value may search a curve's tree)
    if sites.len() < 2 || !watch.tick(0) {
        return out;
    }
    let b = segment_box(p0, p1);
    let scan = Scan {
        fields,
        p0,
        p1,
        len: p0.dist(p1),
        min_len,
        watch,
    };
    // one site left over the whole segment: no change, and no labels to evaluate
    let envelope = super::filter::lower_envelope(fields, &b, sites);
    if envelope.sites.len() <= 1 {
        return out;
    }
    let l0 = label_in(fields, &envelope.sites, p0);
    let l1 = label_in(fields, &envelope.sites, p1);
    scan.scan(0.0, 1.0, l0, l1, b, envelope, &mut out);
    out
}

/// [`transitions`] with the states of `cands` built afresh.
pub fn transitions_of<F: DistanceField>(
    fields: &[F],
    cands: &[u32],
    p0: Point,
    p1: Point,
    min_len: f64,
    watch: &Watch,
) -> Vec<Transition> {
    let b = segment_box(p0, p1);
    let sites = cands
        .iter()
        .map(|&c| (c, fields[c as usize].state(&b)))
        .collect();
    transitions(fields, sites, p0, p1, min_len, watch)
}

struct Scan<'a, F> {
    fields: &'a [F],
    p0: Point,
    p1: Point,
    len: f64,
    min_len: f64,
    /// A stopped run (cancel flag, time limit) scans no further.
    watch: &'a Watch,
}

impl<F: DistanceField> Scan<'_, F> {
    fn at(&self, t: f64) -> Point {
        if t == 1.0 {
            self.p1
        } else {
            self.p0.lerp(self.p1, t)
        }
    }

    /// A piece shorter than `min_len` whose ends have the same label: changes closer
    /// than that are not looked for.
    fn settled(&self, t0: f64, t1: f64, l0: u32, l1: u32) -> bool {
        (t1 - t0) * self.len <= self.min_len && l0 == l1
    }

    #[allow(clippy::too_many_arguments)]
    fn rec(
        &self,
        t0: f64,
        t1: f64,
        l0: u32,
        l1: u32,
        b: Aabb,
        sites: Vec<(u32, F::State)>,
        out: &mut Vec<Transition>,
    ) {
        if self.settled(t0, t1, l0, l1) || !self.watch.tick(0) {
            return;
        }
        let envelope = super::filter::lower_envelope(self.fields, &b, sites);
        self.scan(t0, t1, l0, l1, b, envelope, out);
    }

    /// [`Self::rec`] over the sites that the filter left on the piece.
    #[allow(clippy::too_many_arguments)]
    fn scan(
        &self,
        t0: f64,
        t1: f64,
        l0: u32,
        l1: u32,
        b: Aabb,
        envelope: super::filter::Envelope<F::State>,
        out: &mut Vec<Transition>,
    ) {
        let short = (t1 - t0) * self.len <= self.min_len;
        if envelope.sites.len() <= 1 && l0 == l1 {
            return;
        }
        let pair = (envelope.sites.len() == 2).then(|| envelope.pair_of_two(self.fields, &b));
        let sites = envelope.sites;
        if let Some(p) = &pair {
            // an exact tie along the whole piece (a bisector lying on a box side, as in
            // grids): the labels follow the tie rule, so there is nothing to find inside
            let scale = self.fields[sites[0].0 as usize]
                .bound(&sites[0].1, &b)
                .mag();
            if l0 == l1 && p.value.mag() <= 1e-12 * scale {
                return;
            }
        }
        let simple = pair.as_ref().is_some_and(|p| {
            // one root at most when h is monotone along the segment
            p.gradient.is_some_and(|g| {
                // the derivative along the segment (a segment's box has no extent, hence
                // no gradient bound, across it)
                let d = self.p1 - self.p0;
                let along = match (d.x == 0.0, d.y == 0.0) {
                    (false, true) => g[0].scale(d.x),
                    (true, false) => g[1].scale(d.y),
                    _ => g[0].scale(d.x) + g[1].scale(d.y),
                };
                along.excludes_zero()
            })
        });
        if short || simple || sites.len() <= 1 {
            if l0 != l1 {
                // the two labels join the sites if the filter dropped them (rounding)
                let mut with: Vec<(u32, Option<&F::State>)> =
                    sites.iter().map(|(c, s)| (*c, Some(s))).collect();
                for l in [l0, l1] {
                    if let Err(k) = with.binary_search_by_key(&l, |s| s.0) {
                        with.insert(k, (l, None));
                    }
                }
                self.refine(t0, t1, l0, l1, &with, out);
            }
            return;
        }
        let tm = 0.5 * (t0 + t1);
        let pm = self.at(tm);
        let lm = label_in(self.fields, &sites, pm);
        if self.settled(t0, tm, l0, lm) && self.settled(tm, t1, lm, l1) {
            return; // no states to split for halves that end at once
        }
        let axis = if b.width() >= b.height() {
            crate::geom::Axis::X
        } else {
            crate::geom::Axis::Y
        };
        let at = pm.coord(axis);
        let (lb, rb) = b.split(axis, at);
        let mut lower = Vec::with_capacity(sites.len());
        let mut upper = Vec::with_capacity(sites.len());
        for (i, s) in &sites {
            let (l, r) = self.fields[*i as usize].split(s, &b, axis, at);
            lower.push((*i, l));
            upper.push((*i, r));
        }
        // the half nearer p0 comes first along the segment
        let forward = self.p1.coord(axis) >= self.p0.coord(axis);
        let (first, second) = if forward {
            ((lb, lower), (rb, upper))
        } else {
            ((rb, upper), (lb, lower))
        };
        self.rec(t0, tm, l0, lm, first.0, first.1, out);
        self.rec(tm, t1, lm, l1, second.0, second.1, out);
    }

    /// Bisection on the label between `t0` (label `l0`) and `t1` (label `l1`) among
    /// `sites` (with their states over the piece, or `None`); a third label met on the
    /// way splits the search in two.
    #[allow(clippy::too_many_arguments)]
    fn refine(
        &self,
        mut t0: f64,
        mut t1: f64,
        l0: u32,
        l1: u32,
        sites: &[(u32, Option<&F::State>)],
        out: &mut Vec<Transition>,
    ) {
        let value = |(c, s): (u32, Option<&F::State>), q: Point| {
            let f = &self.fields[c as usize];
            s.map_or_else(|| f.value(q), |s| f.value_in(s, q))
        };
        let site = |l: u32| {
            sites
                .iter()
                .find(|s| s.0 == l)
                .copied()
                .unwrap_or((l, None))
        };
        if sites.len() == 2 {
            // one bisector: its root, by regula falsi; but where the fields compare
            // exactly and their values at an end are within rounding, the f64 difference
            // may be noise along the piece, and the bisection below on the (exact)
            // labels finds the change
            let (a, b) = (site(l0), site(l1));
            let values = |t: f64| {
                let q = self.at(t);
                (value(a, q), value(b, q))
            };
            let ((a0, b0), (a1, b1)) = (values(t0), values(t1));
            let (h0, h1) = (a0 - b0, a1 - b1);
            let exact = || {
                let (fa, fb) = (&self.fields[a.0 as usize], &self.fields[b.0 as usize]);
                fa.exact_cmp(fb, self.p0).is_some()
            };
            let noise = (within_rounding(a0, b0) || within_rounding(a1, b1)) && exact();
            if !noise && h0 <= 0.0 && h1 >= 0.0 && h0 != h1 {
                let h = |t: f64| {
                    let (x, y) = values(t);
                    x - y
                };
                let t = super::trace::illinois(h, t0, t1, h0, h1);
                out.push(Transition {
                    at: self.at(t),
                    pair: [l0, l1],
                });
                return;
            }
        }
        for _ in 0..64 {
            let tm = 0.5 * (t0 + t1);
            if tm <= t0 || tm >= t1 {
                break;
            }
            let q = self.at(tm);
            let lm = nearest_of(self.fields, q, sites.iter().map(|&s| (s.0, value(s, q))));
            if lm == l0 {
                t0 = tm;
            } else if lm == l1 {
                t1 = tm;
            } else {
                self.refine(t0, tm, l0, lm, sites, out);
                self.refine(tm, t1, lm, l1, sites, out);
                return;
            }
        }
        out.push(Transition {
            at: self.at(0.5 * (t0 + t1)),
            pair: [l0, l1],
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::Control;
    use crate::geom::Axis;
    use crate::num::Interval;
    use crate::site::EuclideanPoint;
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};
    use std::sync::Arc;

    /// A point's field that counts its evaluations.
    struct Counted<'a>(EuclideanPoint, &'a AtomicUsize);

    impl DistanceField for Counted<'_> {
        type State = ();
        fn state(&self, _: &Aabb) {}
        fn split(&self, _: &(), _: &Aabb, _: Axis, _: f64) -> ((), ()) {
            ((), ())
        }
        fn bound(&self, s: &(), b: &Aabb) -> Interval {
            self.0.bound(s, b)
        }
        fn gradient_bound(&self, s: &(), b: &Aabb) -> Option<[Interval; 2]> {
            self.0.gradient_bound(s, b)
        }
        fn value(&self, q: Point) -> f64 {
            self.1.fetch_add(1, Relaxed);
            self.0.value(q)
        }
        fn gradient(&self, q: Point) -> Point {
            self.0.gradient(q)
        }
    }

    #[test]
    fn a_side_along_a_bisector_changes_label_where_exact_arithmetic_does() {
        // the centre, the ring point at (−1.5, 0) (its y rounded from sin π), and the
        // ring point below it: the first two's bisector is the side x = −0.75, tilted by
        // 1e-16, which it crosses at y = b.y/2; the third takes over below their vertex
        let a = EuclideanPoint::new(Point::new(0.0, 0.0));
        let b = EuclideanPoint::new(Point::new(-1.5, 1.8369701987210296e-16));
        let c = EuclideanPoint::new(Point::new(-1.2990381056766582, -0.7499999999999996));
        let fields = [a, b, c];
        let (p0, p1) = (Point::new(-0.75, -0.5), Point::new(-0.75, 0.5));
        let found = transitions_of(&fields, &[0, 1, 2], p0, p1, 1e-3, &Watch::default());
        let pairs: Vec<[u32; 2]> = found.iter().map(|t| t.pair).collect();
        assert_eq!(pairs, [[2, 0], [0, 1]], "{found:?}");
        let vertex_y = -0.20096189432334194;
        assert!((found[0].at.y - vertex_y).abs() < 1e-12, "{found:?}");
        // exactly: |q − a|² − |q − b|² = b.y (2y − b.y) changes sign at y = b.y / 2 (to
        // the resolution of the side's parameter)
        assert!((found[1].at.y - 0.5 * b.at.y).abs() <= 1e-15, "{found:?}");
    }

    #[test]
    fn a_stopped_run_evaluates_no_field_on_a_side() {
        let calls = AtomicUsize::new(0);
        let fields = [
            Counted(EuclideanPoint::new(Point::new(-1.0, 0.0)), &calls),
            Counted(EuclideanPoint::new(Point::new(1.0, 0.0)), &calls),
        ];
        let (p0, p1) = (Point::new(-2.0, 0.5), Point::new(2.0, 0.5));
        let scan = |watch: &Watch| transitions_of(&fields, &[0, 1], p0, p1, 1e-3, watch);
        let found = scan(&Watch::default());
        assert_eq!(found.len(), 1);
        assert!(calls.load(Relaxed) > 0);

        let cancel = Arc::new(AtomicBool::new(true));
        let watch = Watch::start(&Control {
            cancel: Some(cancel),
            ..Default::default()
        })
        .unwrap();
        assert!(watch.check().is_err());
        calls.store(0, Relaxed);
        assert!(scan(&watch).is_empty());
        assert_eq!(calls.load(Relaxed), 0);
    }
}
