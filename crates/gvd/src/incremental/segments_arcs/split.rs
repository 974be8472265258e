//! Segments cut where they cross, overlap or touch one another's inside, and where a
//! point lies inside them, so that the segment engine (which takes only segments that
//! meet at shared ends, `crossings.rs`) can compute such input.
//!
//! Every contact is found with exact orientations (`geom::predicates`, (Shewchuk97)):
//! * an end of one segment, or a point, exactly inside another cuts it there (T
//!   junctions, points on segments, and the ends of collinear overlaps: an overlap is
//!   cut at the ends of each segment that lie inside the other, and its common piece
//!   then joins the same two points twice);
//! * a proper crossing adds the crossing point `x = a + t (b − a)`,
//!   `t = o(c, d, a) / (o(c, d, a) − o(c, d, b))`, and cuts both segments there;
//! * pieces joining the same two points (repeated segments, common pieces of
//!   overlaps) are kept once, as part of the first segment.
//!
//! **Rounding.** The two orientations have opposite signs, so `t` has no cancellation
//! and lies in (0, 1); `x` lies within a few units in the last place of the line
//! `ab`, and within about `ε |ab|` of the line `cd` (ε the unit roundoff), though its
//! place along the lines moves by `ε |ab| / sin θ` at a shallow angle θ. The pieces
//! `a–x–b` and `c–x–d` share `x`, so they cannot cross each other; they bend off the
//! input by that rounding. Three segments through one point (exactly, or closer than
//! the engine resolves) give two or three computed points a few ulps apart: computed
//! points within `snap` (a quarter of the engine's resolution `near`, see
//! [`NEAR_TOUCH`](super::NEAR_TOUCH)) are one point, the first one computed, and every
//! segment through the cluster is cut there. An input point within `snap` of a
//! computed one must lie exactly on both segments (a T at a crossing); anything else
//! there is an end within `near` of a segment's inside, refused as input the engine
//! cannot resolve, as are such ends and points in the input itself. Since the pieces
//! move by less than `snap` and every end not exactly on a segment is at least `near`
//! from it, the cuts create no new contact at rounding level; the pieces are checked
//! again anyway, cut again if needed (at most [`ROUNDS`] times), and any conflict
//! that remains (a near touch the snapping made, which the argument rules out but
//! does not prove for every shallow cluster) is returned, never computed.

use super::crossings::{find_conflict, nearly_inside, segment_grid, strictly_between, Conflict};
use crate::geom::grid::SparseGrid;
use crate::geom::predicates::orient2d as orient;
use crate::geom::Point;
use rustc_hash::FxHashMap;

/// Rounds of cutting before the remaining conflicts are refused: the first one cuts
/// everything in exact input, later ones only what a snapped crossing created.
const ROUNDS: usize = 4;

/// Segments cut at their contacts: the pieces the segment engine takes.
#[derive(Debug, Default)]
pub(crate) struct Split {
    /// The computed crossing points, numbered after the input's points.
    pub(crate) new_points: Vec<Point>,
    /// The pieces, pairs of point indices, each pair once.
    pub(crate) pieces: Vec<[u32; 2]>,
    /// Per piece: the input segment it is part of (the first one, for a piece that
    /// several input segments have in common).
    pub(crate) origin: Vec<u32>,
    /// `(point, input segment)` for every point inside an input segment at which it
    /// was cut, each pair once, sorted.
    pub(crate) inside: Vec<(u32, u32)>,
    /// Distinct crossing points computed.
    pub(crate) crossings: usize,
    /// Cuts of an input segment at an input point inside it (T junctions, ends of
    /// overlaps, point sites on segments).
    pub(crate) touches: usize,
    /// Pieces left out because an earlier segment has the same piece (repeats and
    /// overlaps).
    pub(crate) merged: usize,
}

/// `segments` (pairs of indices into the distinct `points`) and the point sites
/// `lonely`, cut at every crossing, overlap and touch; ends and points within `near`
/// of a segment's inside without touching it exactly, and computed crossing points
/// within `snap` of an input point that is not on both segments, are refused as the
/// [`Conflict`] they make (segment indices the input's).
pub(crate) fn split_segments(
    points: &[Point],
    segments: &[[u32; 2]],
    lonely: &[u32],
    near: f64,
    snap: f64,
) -> Result<Split, Conflict> {
    let n_input = points.len();
    let mut all = points.to_vec();
    let mut pieces = segments.to_vec();
    let mut origin: Vec<u32> = (0..segments.len() as u32).collect();
    let mut snapper = SparseGrid::new(snap);
    for (k, &p) in points.iter().enumerate() {
        snapper.insert(p, k as u32);
    }
    let mut inside = Vec::new();
    let mut merged = 0;
    let to_input = |c: Conflict, origin: &[u32]| map_conflict(c, origin);
    for _ in 0..ROUNDS {
        let mut cutter = Cutter {
            points: &mut all,
            snapper: &mut snapper,
            n_input,
            near,
            cuts: Vec::new(),
        };
        cutter
            .find(&pieces, lonely)
            .map_err(|c| to_input(c, &origin))?;
        let cuts = cutter.cuts;
        inside.extend(cuts.iter().map(|&(s, p)| (p, origin[s as usize])));
        let before = pieces.len();
        let (cut, cut_origin) = cut_at(&all, &pieces, &origin, cuts.clone());
        let (kept, kept_origin) = dedup(cut, cut_origin);
        merged += before + count_new_pieces(&cuts) - kept.len();
        let done = cuts.is_empty();
        pieces = kept;
        origin = kept_origin;
        if done {
            break;
        }
    }
    let still_lonely: Vec<u32> = lonely
        .iter()
        .copied()
        .filter(|p| !inside.iter().any(|&(q, _)| q == *p))
        .collect();
    if let Some(c) = find_conflict(&all, &pieces, &still_lonely, near) {
        return Err(to_input(c, &origin));
    }
    inside.sort_unstable();
    inside.dedup();
    let touches = inside
        .iter()
        .filter(|&&(p, _)| (p as usize) < n_input)
        .count();
    let new_points = all.split_off(n_input);
    Ok(Split {
        crossings: new_points.len(),
        new_points,
        pieces,
        origin,
        inside,
        touches,
        merged,
    })
}

/// How many pieces the cuts add: one per distinct (segment, point) cut.
fn count_new_pieces(cuts: &[(u32, u32)]) -> usize {
    let mut c = cuts.to_vec();
    c.sort_unstable();
    c.dedup();
    c.len()
}

/// The conflict `c` among pieces, in terms of the input segments they are part of.
fn map_conflict(c: Conflict, origin: &[u32]) -> Conflict {
    let o = |s: usize| origin[s] as usize;
    match c {
        Conflict::Cross(i, j) => Conflict::Cross(o(i), o(j)),
        Conflict::Overlap(i, j) => Conflict::Overlap(o(i), o(j)),
        Conflict::Touch(i, j) => Conflict::Touch(o(i), o(j)),
        Conflict::PointOn(i, p) => Conflict::PointOn(o(i), p),
        Conflict::NearlyOn(i, j, p) => Conflict::NearlyOn(o(i), j.map(o), p),
    }
}

/// One round's search for cuts: `(segment, point)` pairs, the point strictly inside
/// the segment (an input point, or a crossing point appended to `points`).
struct Cutter<'a> {
    points: &'a mut Vec<Point>,
    /// Every input point and computed crossing point, for snapping.
    snapper: &'a mut SparseGrid<u32>,
    n_input: usize,
    near: f64,
    cuts: Vec<(u32, u32)>,
}

impl Cutter<'_> {
    fn find(&mut self, segs: &[[u32; 2]], lonely: &[u32]) -> Result<(), Conflict> {
        if segs.is_empty() {
            return Ok(());
        }
        let (grid, extent) = segment_grid(self.points, segs, self.near);
        for list in grid.buckets() {
            for (x, &i) in list.iter().enumerate() {
                for &j in &list[x + 1..] {
                    self.pair(segs, i as usize, j as usize)?;
                }
            }
        }
        let near = self.near;
        for &p in lonely {
            let q = self.points[p as usize];
            let outside = |v: f64, lo: f64, hi: f64| v < lo - near || v > hi + near;
            if outside(q.x, extent.min.x, extent.max.x) || outside(q.y, extent.min.y, extent.max.y)
            {
                continue;
            }
            for &i in grid.bucket(grid.cell_of(q)) {
                let [a, b] = segs[i as usize];
                let (pa, pb) = (self.points[a as usize], self.points[b as usize]);
                if p == a || p == b {
                    continue;
                }
                if orient(pa, pb, q) == 0.0 && strictly_between(pa, pb, q) {
                    self.cuts.push((i, p));
                } else if nearly_inside(q, pa, pb, near) {
                    return Err(Conflict::NearlyOn(i as usize, None, p as usize));
                }
            }
        }
        Ok(())
    }

    /// The cuts that segments `i` and `j` make in each other.
    fn pair(&mut self, segs: &[[u32; 2]], i: usize, j: usize) -> Result<(), Conflict> {
        let ([a, b], [c, d]) = (segs[i], segs[j]);
        if (a == c && b == d) || (a == d && b == c) {
            return Ok(()); // the same piece twice: merged after the cuts
        }
        let p = |k: u32| self.points[k as usize];
        let (pa, pb, pc, pd) = (p(a), p(b), p(c), p(d));
        let (o1, o2) = (orient(pa, pb, pc), orient(pa, pb, pd));
        let (o3, o4) = (orient(pc, pd, pa), orient(pc, pd, pb));
        // An end of one segment exactly inside the other cuts it; one within `near`
        // of its inside is beyond the engine.
        let ends = [
            (o1, c, i, j, [a, b]),
            (o2, d, i, j, [a, b]),
            (o3, a, j, i, [c, d]),
            (o4, b, j, i, [c, d]),
        ];
        for (o, e, s, other, [x, y]) in ends {
            if e == x || e == y {
                continue;
            }
            let (px, py, pe) = (p(x), p(y), p(e));
            if o == 0.0 && strictly_between(px, py, pe) {
                self.cuts.push((s as u32, e));
            } else if nearly_inside(pe, px, py, self.near) {
                return Err(Conflict::NearlyOn(s, Some(other), e as usize));
            }
        }
        let opposite = |u: f64, v: f64| (u > 0.0 && v < 0.0) || (u < 0.0 && v > 0.0);
        if opposite(o1, o2) && opposite(o3, o4) {
            let t = o3 / (o3 - o4);
            let x = pa + (pb - pa) * t;
            let k = self.crossing_point(x, [a, b, c, d], i, j)?;
            self.cuts.push((i as u32, k));
            self.cuts.push((j as u32, k));
        }
        Ok(())
    }

    /// The point for the computed crossing `x` of segments `i = ab` and `j = cd`
    /// (`ends = [a, b, c, d]`): a point within `snap` of it (an input point only if it
    /// lies exactly inside both), else a new one.
    fn crossing_point(
        &mut self,
        x: Point,
        ends: [u32; 4],
        i: usize,
        j: usize,
    ) -> Result<u32, Conflict> {
        let nearest = self
            .snapper
            .near(x)
            .min_by(|u, v| u.0.dist(x).total_cmp(&v.0.dist(x)))
            .map(|&(_, k)| k);
        match nearest {
            // an end of `i` or `j` there: the other passes within `snap` of it
            Some(k) if ends.contains(&k) => Err(Conflict::NearlyOn(i, Some(j), k as usize)),
            Some(k) if (k as usize) >= self.n_input => Ok(k),
            Some(k) => {
                let pk = self.points[k as usize];
                let p = |e: u32| self.points[e as usize];
                let [a, b, c, d] = ends;
                let on = |u: u32, v: u32| {
                    orient(p(u), p(v), pk) == 0.0 && strictly_between(p(u), p(v), pk)
                };
                if on(a, b) && on(c, d) {
                    Ok(k)
                } else {
                    Err(Conflict::NearlyOn(i, Some(j), k as usize))
                }
            }
            None => {
                let k = self.points.len() as u32;
                self.points.push(x);
                self.snapper.insert(x, k);
                Ok(k)
            }
        }
    }
}

/// Every segment cut at its cuts (in order along it), with the segment each piece comes
/// from.
fn cut_at(
    points: &[Point],
    segs: &[[u32; 2]],
    origin: &[u32],
    mut cuts: Vec<(u32, u32)>,
) -> (Vec<[u32; 2]>, Vec<u32>) {
    if cuts.is_empty() {
        return (segs.to_vec(), origin.to_vec());
    }
    let along = |s: u32, p: u32| {
        let [a, b] = segs[s as usize].map(|e| points[e as usize]);
        (points[p as usize] - a).dot(b - a)
    };
    cuts.sort_unstable_by(|&(s, p), &(t, q)| {
        s.cmp(&t)
            .then(along(s, p).total_cmp(&along(t, q)))
            .then(p.cmp(&q))
    });
    cuts.dedup();
    let mut pieces = Vec::with_capacity(segs.len() + cuts.len());
    let mut from = Vec::with_capacity(segs.len() + cuts.len());
    let mut next = cuts.iter().peekable();
    for (s, &[a, b]) in segs.iter().enumerate() {
        let mut last = a;
        while let Some(&&(_, p)) = next.peek().filter(|c| c.0 as usize == s) {
            next.next();
            pieces.push([last, p]);
            from.push(origin[s]);
            last = p;
        }
        pieces.push([last, b]);
        from.push(origin[s]);
    }
    (pieces, from)
}

/// The pieces, each pair of points once (the first of them kept, in order).
fn dedup(pieces: Vec<[u32; 2]>, origin: Vec<u32>) -> (Vec<[u32; 2]>, Vec<u32>) {
    let mut seen: FxHashMap<(u32, u32), ()> = FxHashMap::default();
    seen.reserve(pieces.len());
    let mut kept = Vec::with_capacity(pieces.len());
    let mut kept_origin = Vec::with_capacity(pieces.len());
    for (piece, o) in pieces.into_iter().zip(origin) {
        let [a, b] = piece;
        if seen.insert((a.min(b), a.max(b)), ()).is_none() {
            kept.push(piece);
            kept_origin.push(o);
        }
    }
    (kept, kept_origin)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[(f64, f64)]) -> Vec<Point> {
        v.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    fn split(p: &[Point], s: &[[u32; 2]], lonely: &[u32]) -> Split {
        split_segments(p, s, lonely, 4e-12, 1e-12).expect("splits")
    }

    #[test]
    fn an_x_is_cut_at_one_computed_point() {
        let p = pts(&[(0., 0.), (2., 2.), (0., 2.), (2., 0.)]);
        let s = split(&p, &[[0, 1], [2, 3]], &[]);
        assert_eq!(s.new_points, vec![Point::new(1., 1.)]);
        assert_eq!(s.pieces, vec![[0, 4], [4, 1], [2, 4], [4, 3]]);
        assert_eq!(s.origin, vec![0, 0, 1, 1]);
        assert_eq!((s.crossings, s.touches, s.merged), (1, 0, 0));
        assert_eq!(s.inside, vec![(4, 0), (4, 1)]);
    }

    #[test]
    fn t_junctions_overlaps_repeats_and_points_on_segments() {
        // 0–1 on the x axis; 2 is a T's foot at (1, 0) with its top 3; 4–5 overlaps
        // 0–1 from (1.5, 0) on; 1–0 repeats 0–1 reversed; point 6 lies on 0–1.
        let p = pts(&[
            (0., 0.),
            (2., 0.),
            (1., 0.),
            (1., 1.),
            (1.5, 0.),
            (3., 0.),
            (0.5, 0.),
        ]);
        let s = split(&p, &[[0, 1], [3, 2], [4, 5], [1, 0]], &[6]);
        assert_eq!(s.crossings, 0);
        // 0–1 cut at 6, 2 and 4; 4–5 cut at 1; the repeat is all merged.
        assert_eq!(
            s.pieces,
            vec![[0, 6], [6, 2], [2, 4], [4, 1], [3, 2], [1, 5]]
        );
        assert_eq!(s.origin, vec![0, 0, 0, 0, 1, 2]);
        assert_eq!(s.touches, 3 + 1 + 3);
        // the overlap's common piece 4–1 once, and the four pieces of the repeat
        assert_eq!(s.merged, 1 + 4);
        assert!(find_conflict(&p, &s.pieces, &[], 4e-12).is_none());
    }

    #[test]
    fn a_star_through_one_point_is_cut_there_once() {
        // Eight segments through (0.1, 0.3), whose crossings round differently.
        let c = Point::new(0.1, 0.3);
        let mut p = Vec::new();
        let mut segs = Vec::new();
        for k in 0..8u32 {
            let a = 0.37 * k as f64 + 0.1;
            let d = Point::new(a.cos(), a.sin());
            p.extend([c - d, c + d * 0.7]);
            segs.push([2 * k, 2 * k + 1]);
        }
        let s = split(&p, &segs, &[]);
        assert_eq!(s.crossings, 1, "{:?}", s.new_points);
        assert!(s.new_points[0].dist(c) < 1e-15);
        assert_eq!(s.pieces.len(), 16);
        assert!(find_conflict(&[p, s.new_points].concat(), &s.pieces, &[], 4e-12).is_none());
    }

    #[test]
    fn near_touches_stay_refused() {
        let p = pts(&[(-1., 0.), (1., 0.), (0., 1e-13), (0., 1.), (0.5, 1e-13)]);
        let near = |s: &[[u32; 2]], l: &[u32]| split_segments(&p, s, l, 4e-12, 1e-12).err();
        assert_eq!(
            near(&[[0, 1], [2, 3]], &[]),
            Some(Conflict::NearlyOn(0, Some(1), 2))
        );
        assert_eq!(near(&[[0, 1]], &[4]), Some(Conflict::NearlyOn(0, None, 4)));
    }
}
