//! Offset curves: the points at distance `d` from the sites, as lines and circular arcs,
//! derived from the Voronoi diagram (or complex) of the scene.
//!
//! The distance to the sites is, inside the cell of a generator `g`, the distance to `g`
//! alone; so the offset at distance `d` is the union over the generators of the level
//! curves `{x : dist(x, g) = d}` restricted to `g`'s cell. For a point or a corner `c`
//! the level curve is the circle `|x − c| = d`; for an edge `[a, b]` it is the two
//! segments `a ± d n`–`b ± d n` (`n` its unit normal) that bound its perpendicular
//! strip at distance `d`; for an arc site of circle `(c, r)` it is the two concentric
//! arcs `|x − c| = r ± d` within the arc's angular span (its wedge), the inner one only
//! when `d < r` and run clockwise (the site on its left). Coincident points (corners
//! shared by sites, an arc's end on a segment's) are one feature's circle. A level
//! curve leaves a cell where it crosses a Voronoi edge at clearance `d`:
//!
//! 1. along each diagram edge between `g1` and `g2`, the clearance
//!    `h(x) = (dist(x, g1) + dist(x, g2)) / 2 − d` changes sign (convex along each
//!    polyline segment, 1-Lipschitz, so a segment with `h(p) + h(q) ≥ |p − q|` is
//!    skipped, and otherwise its minimum is found by golden-section search); each sign
//!    change is refined by bisection, then replaced by the exact intersection of the two
//!    generators' level curves nearest to it (circle–circle, circle–line, line–line);
//! 2. the level curves are also split where they meet the domain's boundary and, for a
//!    corner's circle, where its edges' strips and its arcs' wedges begin (the normals
//!    at the corner);
//! 3. each level curve is cut at its split points (by angle on a circle, by parameter on
//!    a line); a piece is kept when its midpoint `m` is in the domain, in the wanted
//!    region, and no feature of the scene is nearer to `m` than `d` (exact distances to
//!    the features near `m`, found in a uniform grid): `m` is then in `g`'s cell;
//!    consecutive kept pieces of one level curve merge. Seven more points of each
//!    piece (and a kept piece's ends) are checked the same way; if one disagrees, the
//!    diagram missed a crossing, and that level curve is split again at its exact
//!    intersections with the level curves of every feature within reach (`repairs` in
//!    the stats);
//! 4. the pieces, oriented with their feature on the left (arcs counter-clockwise), are
//!    chained end to start into curves.
//!
//! The wanted region: in `medial_axis` mode the inside of the polygons (outside their
//! holes: a pocket); otherwise the outside of every polygon, whose inside is part of
//! the site (distance 0). In `voronoi` mode the diagram separates whole sites, so
//! [`offset_scene`] computes the `complex`-mode diagram instead (the same for scenes of
//! points). Offsets are clipped to the domain, where the diagram is known.

mod chain;
pub(crate) mod feature;
mod level;
pub(crate) mod model;

pub use model::{Curve, Offset, Primitive};

use crate::complex::{Edge, VoronoiComplex};
use crate::compute::{compute, Options};
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::scene::{Mode, Scene};
use chain::Piece;
use feature::{Features, Grid, Shape};
use level::Level;
use std::collections::BTreeMap;
use std::f64::consts::TAU;
use std::ops::Range;

/// Refuses an offset distance that is not finite and positive.
pub fn check_distance(distance: f64) -> Result<(), Error> {
    if distance.is_finite() && distance > 0.0 {
        Ok(())
    } else {
        Err(Error::scene(
            "distance",
            format!("the offset distance must be finite and positive (got {distance})"),
        ))
    }
}

/// Computes the scene's diagram (in `complex` mode for a `voronoi` scene, see the
/// module's documentation) and its offset curves at `distance`; returns both.
pub fn offset_scene(
    scene: &Scene,
    distance: f64,
    options: &Options,
) -> Result<(Offset, VoronoiComplex), Error> {
    check_distance(distance)?;
    let diagram = if scene.mode() == Mode::Voronoi {
        compute(&scene.clone().with_mode(Mode::Complex), options)?
    } else {
        compute(scene, options)?
    };
    Ok((offset(scene, &diagram, distance)?, diagram))
}

/// The offset curves of `scene` at `distance`, from its diagram `diagram` (whose
/// generators are the scene's sites or their corners and edges).
pub fn offset(scene: &Scene, diagram: &VoronoiComplex, distance: f64) -> Result<Offset, Error> {
    check_distance(distance)?;
    let start = std::time::Instant::now();
    let features = Features::of_scene(scene)?;
    let mut run = Run::new(scene, features, distance);
    for (k, e) in diagram.edges.iter().enumerate() {
        run.edge_crossings(e).ok_or_else(|| {
            Error::Diagram(format!(
                "edge {k} names a generator the scene does not have"
            ))
        })?;
    }
    run.strip_splits();
    run.domain_splits();
    let mut pieces = Vec::new();
    let mut repairs = 0;
    for l in 0..run.levels.len() {
        let (kept, repaired) = run.pieces(l);
        pieces.extend(kept);
        repairs += usize::from(repaired);
    }
    let n_pieces = pieces.len();
    let curves = chain::chain(pieces, run.join);
    let mut stats = BTreeMap::new();
    let mut put = |k: &str, v: serde_json::Value| stats.insert(k.to_string(), v);
    put("seconds", start.elapsed().as_secs_f64().into());
    put("features", run.features.shapes.len().into());
    put("crossings", run.crossings.into());
    put("fallbacks", run.fallbacks.into());
    put("repairs", repairs.into());
    put("pieces", n_pieces.into());
    put("curves", curves.len().into());
    put(
        "closed_curves",
        curves.iter().filter(|c| c.closed).count().into(),
    );
    Ok(Offset {
        distance,
        curves,
        stats,
    })
}

/// A level curve of one feature with the points where it is split.
struct LevelCurve {
    level: Level,
    splits: Vec<Point>,
}

/// The state of one offset computation.
struct Run {
    features: Features,
    grid: Grid,
    /// Per feature, its level curves (an edge's left line, then its right one; an arc's
    /// outer arc, then its inner one if any); a point shared by several features has
    /// the level curve of the first.
    level_range: Vec<Range<usize>>,
    levels: Vec<LevelCurve>,
    d: f64,
    domain: Aabb,
    medial_axis: bool,
    /// Split points closer than this along a level curve are one.
    merge: f64,
    /// Slack of the nearest-feature test.
    slack: f64,
    /// Ends of pieces closer than this are joined (split points are shared between the
    /// two level curves they end, so this only absorbs `merge`).
    join: f64,
    /// How far a crossing found on the diagram may be from the true one (the diagram's
    /// epsilon, twice).
    near: f64,
    crossings: usize,
    fallbacks: usize,
}

impl Run {
    fn new(scene: &Scene, features: Features, d: f64) -> Run {
        let mut level_range: Vec<Range<usize>> = Vec::with_capacity(features.shapes.len());
        let mut levels = Vec::new();
        for (f, s) in features.shapes.iter().enumerate() {
            let canonical = features.canonical[f];
            if canonical != f {
                level_range.push(level_range[canonical].clone());
                continue;
            }
            let curves = match *s {
                Shape::Point(c) => vec![Level::Circle {
                    center: c,
                    radius: d,
                }],
                Shape::Edge { a, b, .. } => Level::beside(a, b, d).to_vec(),
                Shape::Arc {
                    center,
                    radius,
                    start,
                    span,
                    ..
                } => Level::around(center, radius, start, span, d),
            };
            let first = levels.len();
            levels.extend(curves.into_iter().map(|level| LevelCurve {
                level,
                splits: Vec::new(),
            }));
            level_range.push(first..levels.len());
        }
        let scale = scene.domain().longest_side().max(d);
        Run {
            grid: Grid::new(&features.shapes, d),
            features,
            level_range,
            levels,
            d,
            domain: scene.domain(),
            medial_axis: scene.mode() == Mode::MedialAxis,
            merge: 1e-9 * scale,
            slack: 1e-9 * scale,
            join: 4e-9 * scale,
            near: 2.0 * scene.epsilon() + 1e-9 * scale,
            crossings: 0,
            fallbacks: 0,
        }
    }

    /// The distance from `x` to the nearest of the features `r`, and that feature.
    fn nearest_in(&self, r: &Range<usize>, x: Point) -> (f64, usize) {
        r.clone()
            .map(|f| (self.features.shapes[f].distance(x), f))
            .fold(
                (f64::INFINITY, r.start),
                |a, b| if b.0 < a.0 { b } else { a },
            )
    }

    /// The level curve of feature `f` on `x`'s side (an edge has one on each side, an
    /// arc one outside and one inside, if `d` is less than its radius).
    fn level_of(&self, f: usize, x: Point) -> usize {
        let r = &self.level_range[f];
        let second = match self.features.shapes[f] {
            Shape::Edge { a, b, .. } => (b - a).cross(x - a) < 0.0,
            Shape::Arc { center, radius, .. } => x.dist(center) < radius,
            Shape::Point(_) => false,
        };
        if second && r.len() > 1 {
            r.start + 1
        } else {
            r.start
        }
    }

    /// Splits the level curves of a diagram edge's two generators where the edge's
    /// clearance crosses `d`; `None` when a generator is not in the scene.
    fn edge_crossings(&mut self, e: &Edge) -> Option<()> {
        let r1 = self.features.of_generator(&e.sites[0])?;
        let r2 = self.features.of_generator(&e.sites[1])?;
        let h = |x: Point| (self.nearest_in(&r1, x).0 + self.nearest_in(&r2, x).0) / 2.0 - self.d;
        let mut found = Vec::new();
        for w in e.points.windows(2) {
            segment_roots(&h, w[0], w[1], &mut found);
        }
        for x in found {
            self.add_crossing(x, &r1, &r2);
        }
        Some(())
    }

    /// Splits the two generators' level curves at a clearance crossing near `x`: at the
    /// intersection of the nearest features' level curves nearest to `x`, else (no
    /// intersection near) at `x` itself, within `near` of both. One point for both
    /// curves, so that their pieces join exactly.
    fn add_crossing(&mut self, x: Point, r1: &Range<usize>, r2: &Range<usize>) {
        self.crossings += 1;
        let l1 = self.level_of(self.nearest_in(r1, x).1, x);
        let l2 = self.level_of(self.nearest_in(r2, x).1, x);
        let exact = level::intersections(&self.levels[l1].level, &self.levels[l2].level)
            .into_iter()
            .map(|p| (p.dist(x), p))
            .filter(|&(dist, _)| dist <= 10.0 * self.near)
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let p = exact.map_or(x, |(_, p)| p);
        self.levels[l1].splits.push(p);
        self.levels[l2].splits.push(p);
        self.fallbacks += usize::from(exact.is_none());
    }

    /// Splits each corner's circle where the strips of its edges begin: at `c ± d n`,
    /// the ends of the edge's lines, with `n` the edge's unit normal (for an arc, the
    /// ends of its outer and inner arcs, on the radii through its ends).
    fn strip_splits(&mut self) {
        for f in 0..self.features.shapes.len() {
            let corners = match self.features.shapes[f] {
                Shape::Edge { corners, .. } | Shape::Arc { corners, .. } => corners,
                Shape::Point(_) => continue,
            };
            for l in self.level_range[f].clone() {
                let level = self.levels[l].level;
                let Some([(_, p0), (_, p1)]) = level.ends() else {
                    continue;
                };
                // a left line runs from b to a; every other side from its feature's start
                let (at_start, at_end) = match level {
                    Level::Line { .. } if l == self.level_range[f].start => (p1, p0),
                    _ => (p0, p1),
                };
                let (c0, c1) = (
                    self.level_range[corners[0]].start,
                    self.level_range[corners[1]].start,
                );
                self.levels[c0].splits.push(at_start);
                self.levels[c1].splits.push(at_end);
            }
        }
    }

    /// Splits every level curve where it crosses the domain's boundary.
    fn domain_splits(&mut self) {
        for lc in &mut self.levels {
            let ps = level::domain_crossings(&lc.level, &self.domain);
            lc.splits.extend(ps);
        }
    }

    /// Whether `m`, a point at distance `d` from some feature, is on the offset: in the
    /// domain, in the wanted region, and no feature nearer than `d`.
    fn keeps(&self, m: Point) -> bool {
        self.domain.contains(m)
            && self.features.inside_region(m) == self.medial_axis
            && self.clear(m, self.slack)
    }

    /// Whether no feature is nearer to `m` than `d − slack`.
    fn clear(&self, m: Point, slack: f64) -> bool {
        let limit = self.d - slack;
        !self
            .grid
            .any_near(m, self.d, |f| self.features.shapes[f].distance(m) < limit)
    }

    /// The kept pieces of level curve `l`, and whether they needed the local repair.
    ///
    /// Each interval between split points is classified by its midpoint, then checked
    /// at seven more points and, if kept, at its ends: a disagreement means the diagram
    /// missed a crossing (an edge or a vertex off by more than its epsilon, or missing),
    /// and the level curve is split again at its exact intersections with the level
    /// curves of every nearby feature, the places where it can change cells.
    fn pieces(&self, l: usize) -> (Vec<Piece>, bool) {
        let lc = &self.levels[l];
        let intervals = self.intervals(&lc.level, &lc.splits);
        if intervals.iter().all(|iv| self.consistent(&lc.level, iv)) {
            return (merge_kept(&lc.level, &intervals), false);
        }
        let mut splits = lc.splits.clone();
        splits.extend(self.local_splits(l));
        (
            merge_kept(&lc.level, &self.intervals(&lc.level, &splits)),
            true,
        )
    }

    /// The intervals between consecutive cuts (cyclically on a circle; a circle with no
    /// cut is one interval from angle 0 round), classified by their midpoints.
    fn intervals(&self, level: &Level, splits: &[Point]) -> Vec<Interval> {
        let mut cuts = self.cuts(level, splits);
        let cyclic = matches!(level, Level::Circle { .. });
        if cyclic {
            if cuts.is_empty() {
                cuts.push((0.0, level.at(0.0)));
            }
            cuts.push((cuts[0].0 + TAU, cuts[0].1));
        }
        cuts.windows(2)
            .map(|w| {
                let ((t0, p0), (t1, p1)) = (w[0], w[1]);
                Interval {
                    t0,
                    p0,
                    t1,
                    p1,
                    kept: self.keeps(level.at((t0 + t1) / 2.0)),
                }
            })
            .collect()
    }

    /// Whether seven more points of the interval agree with its midpoint, and a kept
    /// interval's ends are no nearer to any feature than `d` (within `near`: crossings
    /// found on the diagram are that accurate).
    fn consistent(&self, level: &Level, iv: &Interval) -> bool {
        let ends = !iv.kept || (self.clear(iv.p0, self.near) && self.clear(iv.p1, self.near));
        ends && (1..8).all(|k| {
            let t = iv.t0 + (iv.t1 - iv.t0) * k as f64 / 8.0;
            self.keeps(level.at(t)) == iv.kept
        })
    }

    /// Where level curve `l` meets the level curves of the features that can reach it:
    /// those whose bounding boxes come within `d` of its points.
    fn local_splits(&self, l: usize) -> Vec<Point> {
        let level = self.levels[l].level;
        let (m, reach) = match level {
            Level::Circle { center, radius } | Level::Arc { center, radius, .. } => {
                (center, radius + self.d)
            }
            Level::Line { from, to } => (from.lerp(to, 0.5), from.dist(to) / 2.0 + self.d),
        };
        let mut near = Vec::new();
        self.grid.any_near(m, reach, |f| {
            near.push(f);
            false
        });
        near.sort_unstable();
        near.dedup();
        near.into_iter()
            .flat_map(|f| self.level_range[f].clone())
            .flat_map(|other| level::intersections(&level, &self.levels[other].level))
            .filter(|&p| level.holds(level.param(p)))
            .collect()
    }

    /// The split points by parameter, with a line's or an arc's two ends, those closer
    /// than `merge` (arc length) merged into the first.
    fn cuts(&self, level: &Level, splits: &[Point]) -> Vec<(f64, Point)> {
        let mut cuts: Vec<(f64, Point)> = splits.iter().map(|&p| (level.param(p), p)).collect();
        if let Some(ends) = level.ends() {
            for c in &mut cuts {
                let t = level.clamp(c.0);
                if t != c.0 {
                    // beyond an end: that end
                    *c = (t, level.at(t));
                }
            }
            cuts.extend(ends);
        }
        cuts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let step = self.merge / level.speed();
        cuts.dedup_by(|b, a| b.0 - a.0 <= step);
        let cyclic = matches!(level, Level::Circle { .. });
        if cyclic && cuts.len() > 1 && cuts[0].0 + TAU - cuts[cuts.len() - 1].0 <= step {
            cuts.pop();
        }
        cuts
    }
}

/// A part of a level curve between two consecutive cuts.
struct Interval {
    t0: f64,
    p0: Point,
    t1: f64,
    p1: Point,
    kept: bool,
}

/// The kept intervals, runs of consecutive ones merged (cyclically on a circle).
fn merge_kept(level: &Level, intervals: &[Interval]) -> Vec<Piece> {
    let kept: Vec<bool> = intervals.iter().map(|iv| iv.kept).collect();
    let n = intervals.len();
    kept_runs(&kept, matches!(level, Level::Circle { .. }))
        .into_iter()
        .map(|(k, count)| {
            let (first, last) = (&intervals[k], &intervals[(k + count - 1) % n]);
            let t1 = if k + count > n {
                last.t1 + TAU
            } else {
                last.t1
            };
            piece(level, first.t0, first.p0, t1, last.p1)
        })
        .collect()
}

/// The piece of `level` from parameter `t0` (point `p0`) to `t1` (point `p1`),
/// reversed on a clockwise arc.
fn piece(level: &Level, t0: f64, p0: Point, t1: f64, p1: Point) -> Piece {
    let (primitive, start, end) = match *level {
        Level::Circle { center, radius } => (
            Primitive::Arc {
                center,
                radius,
                start_angle: t0,
                end_angle: t1,
            },
            p0,
            p1,
        ),
        Level::Line { .. } => (Primitive::Line { from: p0, to: p1 }, p0, p1),
        Level::Arc {
            center,
            radius,
            start,
            ccw,
            ..
        } => {
            // angles from the arc's start, shifted so that the first is in [0, 2π)
            let first = if ccw { t0 } else { t1 };
            let shift = (start + first).rem_euclid(TAU) - first;
            let (a0, a1) = (shift + t0, shift + t1);
            let (start_angle, end_angle, from, to) = if ccw {
                (a0, a1, p0, p1)
            } else {
                (a1, a0, p1, p0)
            };
            (
                Primitive::Arc {
                    center,
                    radius,
                    start_angle,
                    end_angle,
                },
                from,
                to,
            )
        }
    };
    Piece {
        primitive,
        start,
        end,
    }
}

/// Maximal runs of consecutive `true`s as `(first, count)`; cyclic runs may wrap.
fn kept_runs(kept: &[bool], cyclic: bool) -> Vec<(usize, usize)> {
    let n = kept.len();
    let start = match kept.iter().position(|k| !k) {
        Some(i) if cyclic => i + 1,
        None if cyclic => return if n > 0 { vec![(0, n)] } else { Vec::new() },
        _ => 0,
    };
    let mut runs = Vec::new();
    let mut current: Option<(usize, usize)> = None;
    for j in 0..n {
        let i = (start + j) % n;
        match (kept[i], current) {
            (true, Some((f, c))) => current = Some((f, c + 1)),
            (true, None) => current = Some((i, 1)),
            (false, _) => runs.extend(current.take()),
        }
    }
    runs.extend(current);
    runs
}

/// The roots of `h` on the segment `[p, q]`, pushed to `out`. `h` is taken convex and
/// 1-Lipschitz along the segment: at most two roots, none when
/// `h(p) + h(q) ≥ |p − q|` (then `h ≥ 0` throughout).
fn segment_roots(h: &impl Fn(Point) -> f64, p: Point, q: Point, out: &mut Vec<Point>) {
    let (hp, hq) = (h(p), h(q));
    match (hp < 0.0, hq < 0.0) {
        (true, true) => {}
        (true, false) | (false, true) => out.push(bisect(h, p, q)),
        (false, false) => {
            if hp + hq >= p.dist(q) {
                return;
            }
            let m = golden_min(h, p, q);
            if h(m) < 0.0 {
                out.push(bisect(h, p, m));
                out.push(bisect(h, m, q));
            }
        }
    }
}

/// The sign change of `h` between `p` and `q` (signs differ at the ends), by bisection
/// to the last bit.
fn bisect(h: &impl Fn(Point) -> f64, mut p: Point, mut q: Point) -> Point {
    let negative_at_p = h(p) < 0.0;
    for _ in 0..64 {
        let m = p.lerp(q, 0.5);
        if m == p || m == q {
            break;
        }
        if (h(m) < 0.0) == negative_at_p {
            p = m;
        } else {
            q = m;
        }
    }
    p.lerp(q, 0.5)
}

/// The minimum of a convex `h` on `[p, q]` by golden-section search.
fn golden_min(h: &impl Fn(Point) -> f64, p: Point, q: Point) -> Point {
    const INV_PHI: f64 = 0.618_033_988_749_895;
    let (mut a, mut b) = (0.0f64, 1.0f64);
    let (mut c, mut d) = (b - INV_PHI * (b - a), a + INV_PHI * (b - a));
    let (mut hc, mut hd) = (h(p.lerp(q, c)), h(p.lerp(q, d)));
    for _ in 0..80 {
        if hc < 0.0 || hd < 0.0 {
            return p.lerp(q, if hc < hd { c } else { d });
        }
        if hc < hd {
            b = d;
            (d, hd) = (c, hc);
            c = b - INV_PHI * (b - a);
            hc = h(p.lerp(q, c));
        } else {
            a = c;
            (c, hc) = (d, hd);
            d = a + INV_PHI * (b - a);
            hd = h(p.lerp(q, d));
        }
    }
    p.lerp(q, (a + b) / 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_kept_intervals() {
        assert_eq!(
            kept_runs(&[true, false, true, true], false),
            vec![(0, 1), (2, 2)]
        );
        assert_eq!(kept_runs(&[true, false, true, true], true), vec![(2, 3)]);
        assert_eq!(kept_runs(&[true, true], true), vec![(0, 2)]);
        assert_eq!(kept_runs(&[false, false], true), vec![]);
    }

    #[test]
    fn roots_of_a_convex_clearance() {
        let h = |x: Point| x.norm() - 1.0;
        let mut out = Vec::new();
        segment_roots(&h, Point::new(-3.0, 0.5), Point::new(3.0, 0.5), &mut out);
        assert_eq!(out.len(), 2);
        for x in out {
            assert!((x.norm() - 1.0).abs() < 1e-12 && (x.y - 0.5).abs() < 1e-15);
        }
        let mut none = Vec::new();
        segment_roots(&h, Point::new(-3.0, 1.5), Point::new(3.0, 1.5), &mut none);
        assert!(none.is_empty());
    }
}
