//! Circular arcs in the incremental engine, checked by brute force.
//!
//! Scenes: the corpus scene `arcs-0030-points-0020` (in `tests/data/scenes/`), random
//! disjoint arcs with points (rejection sampled with an exact arc distance), arcs with
//! spans beyond π (up to 2π − 0.01), tiny and huge radii, concentric arcs, an arc with a
//! point at its centre, an arc with a point inside its circle, a "D" (a half circle and
//! its diameter as separate sites sharing both ends), a rounded rectangle (4 segments
//! and 4 quarter arcs with tangent joints, as separate sites sharing ends), in `voronoi`
//! and `complex` modes; fixed scenes and proptest families (fixed seed).
//!
//! Every result must pass:
//! * the structure check: `check_invariants`, edge polylines that start and end on the
//!   vertex they name (within `1e-3·epsilon`), `null` ends on the domain's boundary
//!   unless the edge is a closed loop, no point outside the domain;
//! * a brute-force soundness check (distances to the scene's features written here, no
//!   engine code; the distance to an arc is the distance to its circle where the
//!   direction from the centre is inside the span, else to the nearer end): every edge
//!   sample (polyline points and chord midpoints) and every vertex equidistant from its
//!   generators within epsilon, with no generator nearer (the tie measured as the
//!   distance gap over the gradient gap, taken within [1, 2]: the first-order distance
//!   to the bisector, as the shared checker measures it);
//! * a brute-force completeness check (grid 64): neighbouring grid points nearest to
//!   different generators need an edge labelled with both nearby, unless they tie over
//!   a region (sites sharing an end at an angle), a third generator is close, or the
//!   pair is a corner and an edge or piece ending there (a separator). At a tangent
//!   (G1) joint (rounded rectangles, stadiums) the joint's face has zero area and the
//!   common normal is an edge between the two features; it was once missing
//!   (`failing/arc-tangent-segment.json`, `failing/two-arcs-tangent-joint.json`).
//!
//! Former known failures (scenes under `tests/data/scenes/arcs/failing/`), all passing
//! now: one arc with a point deep inside its circle (a closed loop cut by the domain).
//! The half circle closed by its diameter once failed (both ends of its edge lie on
//! the sites, so the residuals did not decide the conic's branch; now the piece of
//! smaller clearance is taken). Scenes where an arc's cell reached the far generators
//! (two-site scenes) once failed too; they pass since the segment engine adds a frame of auxiliary points, and the
//! random families run both bare and with four guard points near the domain corners.
//!
//! Conflicts (an arc crossing a segment or another arc, arcs overlapping on one circle,
//! tangent arcs, a point on an arc) must be refused with `Error::Conflict` naming both
//! sites.
//!
//! `ARCS_DUMP_DIR=dir cargo test --test arcs dump_scenes -- --ignored` writes every
//! fixed scene (and a few of each random family) as JSON, for the shared checker.

mod common;

use common::{features, generators};
use gvd::complex::{FeatureKind, Generator, VoronoiComplex};
use gvd::geom::Point;
use gvd::scene::SiteKind;
use gvd::{compute, Engine, Error, Options, Scene};
use proptest::prelude::*;
use serde_json::{json, Value};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::path::Path;

// ---------------------------------------------------------------- brute force

fn seg_dist(q: Point, a: Point, b: Point) -> f64 {
    seg_dist_grad(q, a, b).0
}

/// An arc as centre, radius, start angle and counter-clockwise span in `(0, 2π)`.
#[derive(Clone, Copy, Debug)]
struct ArcG {
    c: Point,
    r: f64,
    start: f64,
    span: f64,
}

impl ArcG {
    fn of(center: Point, radius: f64, start_angle: f64, end_angle: f64) -> ArcG {
        ArcG {
            c: center,
            r: radius,
            start: start_angle,
            span: (end_angle - start_angle).rem_euclid(TAU),
        }
    }

    /// End `k` (0 start, 1 end), computed as the scene format's reader does: the
    /// counter-clockwise span from the start angle, so that another site can name the
    /// same point bit for bit.
    fn end(&self, k: usize) -> Point {
        let a = self.start + if k == 0 { 0.0 } else { self.span };
        self.c + Point::new(a.cos(), a.sin()) * self.r
    }

    fn at(&self, t: f64) -> Point {
        let a = self.start + t * self.span;
        self.c + Point::new(a.cos(), a.sin()) * self.r
    }

    /// Exact distance from `q` to the closed arc.
    fn dist(&self, q: Point) -> f64 {
        let v = q - self.c;
        let rel = (v.y.atan2(v.x) - self.start).rem_euclid(TAU);
        if rel <= self.span {
            (v.dot(v).sqrt() - self.r).abs()
        } else {
            q.dist(self.end(0)).min(q.dist(self.end(1)))
        }
    }

    fn json(&self) -> Value {
        json!({"kind": "arc", "center": [self.c.x, self.c.y], "radius": self.r,
               "start_angle": self.start, "end_angle": self.start + self.span})
    }
}

fn arc_of(kind: &SiteKind) -> Option<ArcG> {
    match *kind {
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => Some(ArcG::of(center, radius, start_angle, end_angle)),
        _ => None,
    }
}

/// The distance from `q` to a point, with its gradient (unit, away from the point).
fn from_point(q: Point, p: Point) -> (f64, Point) {
    let v = q - p;
    let n = v.dot(v).sqrt();
    (n, if n > 0.0 { v * (1.0 / n) } else { v })
}

fn seg_dist_grad(q: Point, a: Point, b: Point) -> (f64, Point) {
    let d = b - a;
    let t = ((q - a).dot(d) / d.dot(d)).clamp(0.0, 1.0);
    from_point(q, a + d * t)
}

impl ArcG {
    fn dist_grad(&self, q: Point) -> (f64, Point) {
        let v = q - self.c;
        let rel = (v.y.atan2(v.x) - self.start).rem_euclid(TAU);
        if rel <= self.span {
            let (n, u) = from_point(q, self.c);
            let d = n - self.r;
            (d.abs(), if d >= 0.0 { u } else { u * -1.0 })
        } else {
            let (a, b) = (from_point(q, self.end(0)), from_point(q, self.end(1)));
            if a.0 <= b.0 {
                a
            } else {
                b
            }
        }
    }
}

fn nearest_of(items: impl Iterator<Item = (f64, Point)>) -> (f64, Point) {
    items.fold((f64::INFINITY, Point::new(0.0, 0.0)), |a, b| {
        if b.0 < a.0 {
            b
        } else {
            a
        }
    })
}

/// The distance from `q` to generator `g`, with its gradient.
fn dist_grad(s: &Scene, g: &Generator, q: Point) -> (f64, Point) {
    match *g {
        Generator::Site(i) => {
            let kind = &s.sites()[i].kind;
            if let Some(a) = arc_of(kind) {
                return a.dist_grad(q);
            }
            let (pts, edges) = features(kind);
            let corners = pts.iter().map(|p| from_point(q, *p));
            let sides = edges.iter().map(|&(a, b)| seg_dist_grad(q, pts[a], pts[b]));
            nearest_of(corners.chain(sides))
        }
        Generator::Feature {
            site,
            feature,
            index,
        } => {
            let kind = &s.sites()[site].kind;
            let (pts, edges) = features(kind);
            match feature {
                FeatureKind::Corner => from_point(q, pts[index]),
                FeatureKind::Piece => {
                    assert_eq!(index, 0, "an arc has one piece");
                    arc_of(kind).expect("a piece of an arc").dist_grad(q)
                }
                FeatureKind::Edge => {
                    let (a, b) = edges[index];
                    seg_dist_grad(q, pts[a], pts[b])
                }
            }
        }
    }
}

fn dist(s: &Scene, g: &Generator, q: Point) -> f64 {
    dist_grad(s, g, q).0
}

/// The worst brute-force error, in units of epsilon, with where it is.
fn worst_error(s: &Scene, d: &VoronoiComplex) -> (f64, String) {
    let all = generators(s);
    let nearest = |q: Point| {
        all.iter()
            .map(|g| dist(s, g, q))
            .fold(f64::INFINITY, f64::min)
    };
    let mut worst = (0.0f64, String::new());
    let mut sample = |q: Point, gens: &[Generator], what: &str| {
        let ds: Vec<(f64, Point)> = gens.iter().map(|g| dist_grad(s, g, q)).collect();
        let lo = ds
            .iter()
            .cloned()
            .fold((f64::INFINITY, q), |a, b| if b.0 < a.0 { b } else { a });
        let hi = ds
            .iter()
            .cloned()
            .fold((-1.0, q), |a, b| if b.0 > a.0 { b } else { a });
        // The tie error in length units: the distance gap over the gradient gap (the
        // first-order distance to the bisector), the gradient gap taken within [1, 2]
        // so that nearly parallel gradients never excuse a gap.
        let g = hi.1 - lo.1;
        let tie = (hi.0 - lo.0) / g.dot(g).sqrt().clamp(1.0, 2.0);
        let err = tie.max(lo.0 - nearest(q)) / s.epsilon();
        if err > worst.0 {
            let ds: Vec<f64> = ds.iter().map(|d| d.0).collect();
            worst = (
                err,
                format!("{what} at ({}, {}) of {gens:?}, distances {ds:?}", q.x, q.y),
            );
        }
    };
    for (k, e) in d.edges.iter().enumerate() {
        for w in e.points.windows(2) {
            sample(w[0], &e.sites, &format!("edge {k}"));
            sample(w[0].lerp(w[1], 0.5), &e.sites, &format!("edge {k}"));
        }
        sample(*e.points.last().unwrap(), &e.sites, &format!("edge {k}"));
    }
    for (k, v) in d.vertices.iter().enumerate() {
        sample(v.at, &v.sites, &format!("vertex {k}"));
    }
    worst
}

/// Structure: invariants, polyline ends on their vertices (within `1e-3·epsilon`), null
/// ends on the boundary, everything inside the domain.
fn structure(s: &Scene, d: &VoronoiComplex) -> Result<(), String> {
    d.check_invariants()?;
    let tol = 1e-3 * s.epsilon();
    let dom = s.domain();
    let on_boundary = |p: Point| {
        let m = [
            (p.x - dom.min.x).abs(),
            (p.x - dom.max.x).abs(),
            (p.y - dom.min.y).abs(),
            (p.y - dom.max.y).abs(),
        ];
        m.iter().cloned().fold(f64::INFINITY, f64::min) <= tol
    };
    for (k, e) in d.edges.iter().enumerate() {
        if e.points.len() < 2 {
            return Err(format!("edge {k} has {} points", e.points.len()));
        }
        // A closed loop repeats its first point last (checked within `tol` here, as
        // the shared checker does; see `closed_loops_repeat_their_first_point`).
        let closed = e.from.is_none()
            && e.to.is_none()
            && e.points[0].dist(*e.points.last().unwrap()) <= tol;
        for (end, p) in [(e.from, e.points[0]), (e.to, *e.points.last().unwrap())] {
            match end {
                Some(v) => {
                    let at = d.vertices[v].at;
                    if at.dist(p) > tol {
                        return Err(format!(
                            "edge {k} ends at ({}, {}), its vertex {v} is at ({}, {})",
                            p.x, p.y, at.x, at.y
                        ));
                    }
                }
                None if !closed && !on_boundary(p) => {
                    return Err(format!(
                        "edge {k} has a null end at ({}, {}), not on the domain boundary",
                        p.x, p.y
                    ))
                }
                None => {}
            }
        }
        if e.points.iter().any(|p| !dom.contains(*p)) {
            return Err(format!("edge {k} leaves the domain"));
        }
    }
    Ok(())
}

// ---------------------------------------------------------------- completeness

/// Where a corner generator is (for matching corners at one place).
fn corner_at(s: &Scene, g: &Generator) -> Option<Point> {
    match *g {
        Generator::Feature {
            site,
            feature: FeatureKind::Corner,
            index,
        } => Some(features(&s.sites()[site].kind).0[index]),
        _ => None,
    }
}

/// Two labels for one generator: equal, or corners at the same place (where sites
/// share an end, the engine names the point by one of them).
fn same_gen(s: &Scene, a: &Generator, b: &Generator) -> bool {
    a == b || matches!((corner_at(s, a), corner_at(s, b)), (Some(p), Some(q)) if p == q)
}

/// Whether `c` is a corner at an end of the edge or piece `e` (of any site): their
/// common boundary is a separator, which the diagram leaves out.
fn separator(s: &Scene, c: &Generator, e: &Generator) -> bool {
    let Some(p) = corner_at(s, c) else {
        return false;
    };
    match *e {
        Generator::Feature { site, feature, .. } if feature != FeatureKind::Corner => {
            let (pts, _) = features(&s.sites()[site].kind);
            // Segments and arcs only here: their ends are corners 0 and 1.
            pts.contains(&p)
        }
        _ => false,
    }
}

/// A brute-force completeness check on an `n×n` grid of the domain: wherever two
/// neighbouring grid points have different nearest generators A and B, with a clear
/// margin (no tie, no third generator close to the midpoint) and not a separator pair,
/// an edge labelled {A, B} must pass within `h + 2·epsilon` of their midpoint.
fn missing_edge(s: &Scene, d: &VoronoiComplex, n: usize) -> Option<String> {
    let all = generators(s);
    let dom = s.domain();
    let h = (dom.max.x - dom.min.x) / n as f64;
    let best = |q: Point| {
        let mut ds: Vec<(f64, usize)> = all
            .iter()
            .enumerate()
            .map(|(k, g)| (dist(s, g, q), k))
            .collect();
        ds.sort_by(|a, b| a.partial_cmp(b).unwrap());
        ds
    };
    let margin = 1e-9;
    let reach = h + 2.0 * s.epsilon();
    let near_edge = |m: Point, a: &Generator, b: &Generator| {
        d.edges.iter().any(|e| {
            let labelled = (same_gen(s, &e.sites[0], a) && same_gen(s, &e.sites[1], b))
                || (same_gen(s, &e.sites[0], b) && same_gen(s, &e.sites[1], a));
            labelled
                && e.points
                    .windows(2)
                    .any(|w| seg_dist(m, w[0], w[1]) <= reach)
        })
    };
    let grid: Vec<Vec<Vec<(f64, usize)>>> = (0..=n)
        .map(|i| {
            (0..=n)
                .map(|j| {
                    best(Point::new(
                        dom.min.x + (i as f64 + 0.5) * h,
                        dom.min.y + (j as f64 + 0.5) * h,
                    ))
                })
                .collect()
        })
        .collect();
    for i in 0..n {
        for j in 0..n {
            for (i2, j2) in [(i + 1, j), (i, j + 1)] {
                if i2 >= n || j2 >= n {
                    continue;
                }
                let (p, q) = (&grid[i][j], &grid[i2][j2]);
                let (a, b) = (&all[p[0].1], &all[q[0].1]);
                if same_gen(s, a, b) || p[1].0 - p[0].0 < margin || q[1].0 - q[0].0 < margin {
                    continue;
                }
                if separator(s, a, b) || separator(s, b, a) {
                    continue;
                }
                let pp = Point::new(
                    dom.min.x + (i as f64 + 0.5) * h,
                    dom.min.y + (j as f64 + 0.5) * h,
                );
                let qq = Point::new(
                    dom.min.x + (i2 as f64 + 0.5) * h,
                    dom.min.y + (j2 as f64 + 0.5) * h,
                );
                let m = pp.lerp(qq, 0.5);
                let (da, db) = (dist(s, a, m), dist(s, b, m));
                // A tie region (two sites sharing an end, at an angle) between the two
                // grid points: the cells meet over a two-dimensional set, not an edge.
                // Two tied neighbouring sub-samples, so that a tie along a line (the
                // edge itself) does not count.
                let tied = |k: usize| {
                    let x = pp.lerp(qq, k as f64 / 64.0);
                    (dist(s, a, x) - dist(s, b, x)).abs() <= 1e-12
                };
                let tie = (0..64).any(|k| tied(k) && tied(k + 1));
                let third = all
                    .iter()
                    .filter(|g| !same_gen(s, g, a) && !same_gen(s, g, b))
                    .any(|g| dist(s, g, m) < da.min(db) + h);
                if tie || third || near_edge(m, a, b) {
                    continue;
                }
                return Some(format!(
                    "no edge {a:?} / {b:?} near ({}, {}) (between grid points ({}, {}) and ({}, {}))",
                    m.x, m.y, pp.x, pp.y, qq.x, qq.y
                ));
            }
        }
    }
    None
}

fn scene_json(mode: &str, sites: Vec<Value>) -> Value {
    json!({
        "domain": [-2, -2, 2, 2],
        "epsilon": 0.001,
        "mode": mode,
        "sites": sites,
    })
}

fn scene_of(v: &Value) -> Scene {
    Scene::from_value(v).unwrap()
}

fn incremental(s: &Scene) -> Result<VoronoiComplex, Error> {
    let options = Options {
        engine: Engine::Incremental,
        ..Options::default()
    };
    compute(s, &options)
}

/// Every check of the module doc on one scene; the scene's JSON is in the message.
fn check_value(v: &Value) -> Result<(), String> {
    let s = scene_of(v);
    let ctx = || serde_json::to_string(v).unwrap();
    let d = incremental(&s).map_err(|e| format!("refused: {e} (scene {})", ctx()))?;
    structure(&s, &d).map_err(|e| format!("structure: {e} (scene {})", ctx()))?;
    if d.edges.is_empty() && s.sites().len() >= 2 {
        return Err(format!("no edges (scene {})", ctx()));
    }
    let (err, at) = worst_error(&s, &d);
    if err > 1.0 {
        return Err(format!(
            "brute force: error {err} eps, {at} (scene {})",
            ctx()
        ));
    }
    if let Some(m) = missing_edge(&s, &d, 64) {
        return Err(format!("completeness: {m} (scene {})", ctx()));
    }
    Ok(())
}

fn point(x: f64, y: f64) -> Value {
    json!({"kind": "point", "at": [x, y]})
}
fn segment(a: Point, b: Point) -> Value {
    json!({"kind": "segment", "from": [a.x, a.y], "to": [b.x, b.y]})
}
fn arc(c: (f64, f64), r: f64, a0: f64, a1: f64) -> ArcG {
    ArcG::of(Point::new(c.0, c.1), r, a0, a1)
}

// ---------------------------------------------------------------- families

/// Whether two closed arcs are at least `gap` apart: the exact distance to `b` of dense
/// samples of `a`, less half the sample spacing (distance is 1-Lipschitz).
fn arcs_apart(a: &ArcG, b: &ArcG, gap: f64) -> bool {
    let n = 512;
    let half_step = 0.5 * a.r * a.span / n as f64;
    (0..=n).all(|k| b.dist(a.at(k as f64 / n as f64)) - half_step > gap)
}

fn inside_box(a: &ArcG, m: f64) -> bool {
    (0..=256).all(|k| {
        let p = a.at(k as f64 / 256.0);
        p.x.abs() < m && p.y.abs() < m
    })
}

/// Random disjoint arcs and points: candidates (centre, radius, start, span) are kept
/// when inside the box and `gap` away from everything kept before.
fn disjoint_scene(mode: &str, arcs: &[(f64, f64, f64, f64, f64)], points: &[(f64, f64)]) -> Value {
    let gap = 0.02;
    let mut kept: Vec<ArcG> = Vec::new();
    for &(cx, cy, r, a0, span) in arcs {
        let a = arc((cx, cy), r, a0, a0 + span);
        if inside_box(&a, 1.9) && kept.iter().all(|b| arcs_apart(&a, b, gap)) {
            kept.push(a);
        }
    }
    let mut pts: Vec<Point> = Vec::new();
    for &(x, y) in points {
        let q = Point::new(x, y);
        if kept.iter().all(|a| a.dist(q) > gap) && pts.iter().all(|p| p.dist(q) > gap) {
            pts.push(q);
        }
    }
    let mut sites: Vec<Value> = kept.iter().map(ArcG::json).collect();
    sites.extend(pts.iter().map(|p| point(p.x, p.y)));
    if sites.len() < 2 {
        sites.push(point(1.95, 1.95));
        sites.push(point(-1.95, -1.95));
    }
    scene_json(mode, sites)
}

/// Concentric arcs around `c` at radii `r0 + k·dr`, with the given starts and spans.
fn concentric_scene(
    mode: &str,
    c: (f64, f64),
    r0: f64,
    dr: f64,
    arcs: &[(f64, f64)],
    centre_point: bool,
) -> Value {
    let mut sites: Vec<Value> = arcs
        .iter()
        .enumerate()
        .map(|(k, &(a0, span))| arc(c, r0 + k as f64 * dr, a0, a0 + span).json())
        .collect();
    if centre_point {
        sites.push(point(c.0, c.1));
    }
    if sites.len() < 2 {
        sites.push(point(1.9, -1.9));
    }
    scene_json(mode, sites)
}

/// A half circle closed by its diameter, as an arc and a segment sharing both ends
/// (the segment's ends are the arc's, bit for bit), with extra points.
fn d_scene(mode: &str, c: (f64, f64), r: f64, rot: f64, extra: &[(f64, f64)]) -> Value {
    let a = arc(c, r, rot, rot + PI);
    let mut sites = vec![a.json(), segment(a.end(1), a.end(0))];
    for &(x, y) in extra {
        let q = Point::new(x, y);
        if a.dist(q) > 0.01 && seg_dist(q, a.end(0), a.end(1)) > 0.01 {
            sites.push(point(x, y));
        }
    }
    scene_json(mode, sites)
}

/// A rounded rectangle `[-w, w]×[-h, h]` (centred at `c`) with corner radius `rho`:
/// 4 quarter arcs and 4 segments joining them tangentially, separate sites sharing
/// ends. `rho == w` or `rho == h` leaves out the segments of zero length.
fn rounded_rect_scene(
    mode: &str,
    c: (f64, f64),
    w: f64,
    h: f64,
    rho: f64,
    extra: &[(f64, f64)],
) -> Value {
    let (dx, dy) = (w - rho, h - rho);
    let arcs = [
        arc((c.0 + dx, c.1 + dy), rho, 0.0, FRAC_PI_2),
        arc((c.0 - dx, c.1 + dy), rho, FRAC_PI_2, PI),
        arc((c.0 - dx, c.1 - dy), rho, PI, 1.5 * PI),
        arc((c.0 + dx, c.1 - dy), rho, -FRAC_PI_2, 0.0),
    ];
    let mut sites: Vec<Value> = arcs.iter().map(ArcG::json).collect();
    for k in 0..4 {
        let (p, q) = (arcs[k].end(1), arcs[(k + 1) % 4].end(0));
        if p != q {
            sites.push(segment(p, q));
        }
    }
    for &(x, y) in extra {
        let q = Point::new(x, y);
        let clear = arcs.iter().all(|a| a.dist(q) > 0.01)
            && (0..4).all(|k| seg_dist(q, arcs[k].end(1), arcs[(k + 1) % 4].end(0)) > 0.01);
        if clear {
            sites.push(point(x, y));
        }
    }
    scene_json(mode, sites)
}

/// An arc of radius `r` (tiny or huge) whose midpoint is at `m`, with normal
/// direction `theta` and chord about `chord` (capped at a span of 2π − 0.01), with
/// points around.
fn radius_scene(
    mode: &str,
    m: (f64, f64),
    theta: f64,
    r: f64,
    chord: f64,
    max_span: f64,
    extra: &[(f64, f64)],
) -> Value {
    let c = (m.0 - r * theta.cos(), m.1 - r * theta.sin());
    let span = (chord / r).min(max_span);
    let a = arc(c, r, theta - span / 2.0, theta + span / 2.0);
    let mut sites = vec![a.json()];
    for &(x, y) in extra {
        if a.dist(Point::new(x, y)) > 1e-3 {
            sites.push(point(x, y));
        }
    }
    if sites.len() < 2 {
        sites.push(point(-1.9, 1.9));
    }
    scene_json(mode, sites)
}

/// The scene with four guard points near the domain's corners (each kept only if
/// clear of every site): the engine's arc failures seen so far all go away once other
/// sites stand beyond the arcs (see the known failures below), so the families are
/// checked both bare (ignored where they fail) and guarded.
fn guarded(mut v: Value) -> Value {
    let s = scene_of(&v);
    let sites = v["sites"].as_array_mut().unwrap();
    for (x, y) in [(1.95, 1.95), (-1.95, 1.95), (-1.95, -1.95), (1.95, -1.95)] {
        let q = Point::new(x, y);
        let clear = (0..s.sites().len()).all(|i| dist(&s, &Generator::Site(i), q) > 0.01);
        if clear {
            sites.push(point(x, y));
        }
    }
    v
}

// ---------------------------------------------------------------- fixed scenes

fn corpus_scene() -> Value {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/scenes/arcs-0030-points-0020.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn fixed_scenes() -> Vec<(&'static str, Value)> {
    let mut out = vec![("corpus-arcs-0030-points-0020", corpus_scene())];
    for mode in ["voronoi", "complex"] {
        let name = |s: &str| -> &'static str { Box::leak(format!("{s}-{mode}").into_boxed_str()) };
        out.push((
            name("guarded-big-span"),
            guarded(scene_json(
                mode,
                vec![
                    arc((0.0, 0.0), 1.0, 0.3, 0.3 + TAU - 0.01).json(),
                    point(1.5, 0.5),
                    point(-0.2, 0.1),
                ],
            )),
        ));
        out.push((
            name("guarded-big-span-three-quarters"),
            guarded(scene_json(
                mode,
                vec![
                    arc((-0.5, 0.0), 1.0, 1.0, 1.0 + 1.5 * PI).json(),
                    arc((1.2, 0.3), 0.5, -2.0, -2.0 + 1.9 * PI).json(),
                ],
            )),
        ));
        out.push((
            name("guarded-random-disjoint"),
            guarded(disjoint_scene(
                mode,
                &[
                    (0.0, 0.0, 0.5, 0.0, 4.0),
                    (1.0, 1.0, 0.6, 2.0, 2.0),
                    (-1.0, 1.0, 0.7, 4.0, 3.0),
                    (-1.0, -1.0, 0.5, 1.0, 5.0),
                    (1.0, -1.0, 0.3, 0.0, 6.0),
                ],
                &[(0.0, 1.5), (1.5, 0.0), (-0.2, 0.1), (0.7, -0.7)],
            )),
        ));
        out.push((
            name("two-arcs"),
            scene_json(
                mode,
                vec![
                    arc((0.0, 0.0), 1.0, 0.2, 2.5).json(),
                    arc((0.3, -0.2), 0.7, 3.5, 5.5).json(),
                ],
            ),
        ));
        out.push((
            name("big-span"),
            scene_json(
                mode,
                vec![
                    arc((0.0, 0.0), 1.0, 0.3, 0.3 + TAU - 0.01).json(),
                    point(1.5, 0.5),
                    point(-0.2, 0.1),
                ],
            ),
        ));
        out.push((
            name("big-span-three-quarters"),
            scene_json(
                mode,
                vec![
                    arc((-0.5, 0.0), 1.0, 1.0, 1.0 + 1.5 * PI).json(),
                    arc((1.2, 0.3), 0.5, -2.0, -2.0 + 1.9 * PI).json(),
                ],
            ),
        ));
        out.push((
            name("tiny-radius"),
            scene_json(
                mode,
                vec![
                    arc((0.1, 0.1), 1e-3, 0.0, 4.0).json(),
                    arc((-0.5, 0.3), 1e-5, 1.0, 2.0).json(),
                    point(0.4, -0.3),
                    point(-0.9, 0.9),
                ],
            ),
        ));
        out.push((
            name("huge-radius"),
            radius_scene(
                mode,
                (0.0, 0.0),
                1.2,
                1000.0,
                3.0,
                PI,
                &[(0.5, 0.5), (-1.0, 0.2)],
            ),
        ));
        out.push((
            name("concentric"),
            concentric_scene(
                mode,
                (0.0, 0.0),
                0.3,
                0.3,
                &[(0.0, 5.0), (1.0, 3.0), (2.0, 6.0), (-1.0, 2.0)],
                false,
            ),
        ));
        out.push((
            name("concentric-centre"),
            concentric_scene(
                mode,
                (0.1, -0.1),
                0.4,
                0.4,
                &[(0.5, 2.0), (0.5, 2.0), (0.5, 2.0)],
                true,
            ),
        ));
        out.push((
            name("arc-centre-point"),
            scene_json(
                mode,
                vec![arc((0.2, 0.1), 1.0, 0.5, 3.0).json(), point(0.2, 0.1)],
            ),
        ));
        out.push((
            name("arc-point-inside"),
            scene_json(
                mode,
                vec![arc((0.0, 0.0), 1.0, 0.0, 2.0).json(), point(0.3, -0.4)],
            ),
        ));
        out.push((name("d-shape"), d_scene(mode, (0.0, 0.0), 1.0, 0.0, &[])));
        out.push((
            name("d-shape-points"),
            d_scene(
                mode,
                (0.1, 0.2),
                1.3,
                0.7,
                &[(0.0, 0.0), (1.6, 1.6), (-0.3, 0.9), (0.5, -1.5)],
            ),
        ));
        out.push((
            name("rounded-rect"),
            rounded_rect_scene(mode, (0.0, 0.0), 1.5, 1.0, 0.4, &[]),
        ));
        out.push((
            name("rounded-rect-points"),
            rounded_rect_scene(
                mode,
                (0.1, 0.0),
                1.2,
                0.8,
                0.3,
                &[(0.0, 0.0), (1.8, 1.8), (0.5, 0.2)],
            ),
        ));
        out.push((
            name("stadium"),
            rounded_rect_scene(mode, (0.0, 0.0), 1.5, 0.6, 0.6, &[]),
        ));
        out.push((
            name("short-spans-disjoint"),
            disjoint_scene(
                mode,
                &[
                    (0.0, 0.0, 0.5, 0.0, 3.0),
                    (1.0, 1.0, 0.6, 2.0, 2.0),
                    (-1.0, 1.0, 0.7, 4.0, 3.0),
                    (-1.0, -1.0, 0.5, 1.0, 1.5),
                    (1.0, -1.0, 0.3, 0.0, 2.5),
                ],
                &[(0.0, 1.5), (1.5, 0.0), (0.7, -0.7), (-1.8, 0.0)],
            ),
        ));
        out.push((
            name("random-disjoint"),
            disjoint_scene(
                mode,
                &[
                    (0.0, 0.0, 0.5, 0.0, 4.0),
                    (1.0, 1.0, 0.6, 2.0, 2.0),
                    (-1.0, 1.0, 0.7, 4.0, 3.0),
                    (-1.0, -1.0, 0.5, 1.0, 5.0),
                    (1.0, -1.0, 0.3, 0.0, 6.0),
                ],
                &[(0.0, 1.5), (1.5, 0.0), (-0.2, 0.1), (0.7, -0.7)],
            ),
        ));
    }
    out
}

fn check_fixed(prefix: &str) {
    let mut failures = Vec::new();
    let mut n = 0;
    for (name, v) in fixed_scenes() {
        if name.starts_with(prefix) {
            n += 1;
            if let Err(e) = check_value(&v) {
                failures.push(format!("{name}: {e}"));
            }
        }
    }
    assert!(n > 0, "no scene named {prefix}*");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn corpus_arcs_scene() {
    check_fixed("corpus-");
}

#[test]
fn two_arcs() {
    check_fixed("two-arcs-");
}

#[test]
fn big_spans() {
    check_fixed("big-span");
}

#[test]
fn tiny_radii() {
    check_fixed("tiny-radius-");
}

#[test]
fn huge_radius() {
    check_fixed("huge-radius-");
}

#[test]
fn concentric_arcs() {
    check_fixed("concentric");
}

#[test]
fn arc_with_point_at_centre() {
    check_fixed("arc-centre-point-");
}

#[test]
fn arc_with_point_inside_circle() {
    check_fixed("arc-point-inside-");
}

#[test]
fn d_shapes() {
    check_fixed("d-shape");
}

#[test]
fn rounded_rectangles() {
    check_fixed("rounded-rect");
}

#[test]
fn stadium() {
    check_fixed("stadium-");
}

#[test]
fn guarded_big_spans() {
    check_fixed("guarded-big-span");
}

#[test]
fn guarded_random_disjoint_fixed() {
    check_fixed("guarded-random-disjoint-");
}

#[test]
fn short_spans_disjoint_fixed() {
    check_fixed("short-spans-disjoint-");
}

#[test]
fn random_disjoint_fixed() {
    check_fixed("random-disjoint-");
}

/// Labels in `complex` mode: an arc's generators are corners 0 and 1 and piece 0, a
/// segment's corners 0 and 1 and edge 0; in `voronoi` mode all are site indices.
#[test]
fn complex_labels_of_arcs() {
    let sites = || {
        vec![
            arc((0.0, 0.0), 1.0, 0.2, 2.5).json(),
            arc((0.3, -0.2), 0.7, 3.5, 5.5).json(),
            segment(Point::new(1.2, -1.5), Point::new(1.8, 0.5)),
            point(-1.5, 1.5),
        ]
    };
    let v = scene_json("complex", sites());
    let s = scene_of(&v);
    let d = incremental(&s).unwrap();
    let used: std::collections::HashSet<Generator> = d
        .edges
        .iter()
        .flat_map(|e| e.sites.iter().cloned())
        .collect();
    for g in &used {
        if let Generator::Feature {
            site,
            feature,
            index,
        } = *g
        {
            match s.sites()[site].kind {
                SiteKind::Arc { .. } => assert!(
                    matches!(
                        (feature, index),
                        (FeatureKind::Piece, 0) | (FeatureKind::Corner, 0 | 1)
                    ),
                    "{g:?}"
                ),
                SiteKind::Segment { .. } => assert!(
                    matches!(
                        (feature, index),
                        (FeatureKind::Edge, 0) | (FeatureKind::Corner, 0 | 1)
                    ),
                    "{g:?}"
                ),
                _ => panic!("feature of a point: {g:?}"),
            }
        }
    }
    for site in 0..2 {
        assert!(
            used.contains(&Generator::Feature {
                site,
                feature: FeatureKind::Piece,
                index: 0
            }),
            "arc {site}'s piece has no edge"
        );
    }
    // In voronoi mode generators are plain site indices.
    let d = incremental(&scene_of(&scene_json("voronoi", sites()))).unwrap();
    assert!(d
        .edges
        .iter()
        .all(|e| e.sites.iter().all(|g| matches!(g, Generator::Site(_)))));
}

// ---------------------------------------------------------------- the checks can fail

/// The exact arc distance agrees with dense sampling of the arc (from above, within
/// the sampling step) on random queries, including the centre and points beyond the
/// ends.
#[test]
fn arc_distance_matches_sampling() {
    let arcs = [
        arc((0.0, 0.0), 1.0, 0.3, 0.3 + TAU - 0.01),
        arc((0.5, -0.2), 0.7, 2.0, 3.0),
        arc((0.0, 0.0), 1.0, -1.0, 1.0),
        arc((0.0, 0.0), 1.0, 5.0, 1.0),
    ];
    let mut x = 0.123_f64;
    for a in &arcs {
        let n = 20_000;
        let samples: Vec<Point> = (0..=n).map(|k| a.at(k as f64 / n as f64)).collect();
        let step = a.r * a.span / n as f64;
        for _ in 0..200 {
            x = (x * 9301.0 + 0.4927).fract();
            let y = (x * 7919.0 + 0.31).fract();
            let q = Point::new(4.0 * x - 2.0, 4.0 * y - 2.0);
            for q in [q, a.c] {
                let sampled = samples
                    .iter()
                    .map(|p| p.dist(q))
                    .fold(f64::INFINITY, f64::min);
                let exact = a.dist(q);
                assert!(
                    exact <= sampled + 1e-12 && sampled <= exact + step,
                    "{a:?} {q:?}: {exact} vs {sampled}"
                );
            }
        }
    }
}

/// A vertex moved off its place, an edge point pushed sideways, an edge's labels
/// swapped for another site, and an edge end detached from its vertex are all caught.
#[test]
fn checks_detect_perturbations() {
    let v = scene_json(
        "voronoi",
        vec![
            arc((0.0, 0.0), 1.0, 0.2, 2.5).json(),
            arc((0.3, -0.2), 0.7, 3.5, 5.5).json(),
            point(1.5, 1.5),
            point(-1.5, -1.5),
        ],
    );
    let s = scene_of(&v);
    let d = incremental(&s).unwrap();
    check_value(&v).unwrap();
    let mut moved = d.clone();
    let k = moved
        .vertices
        .iter()
        .position(|v| v.sites.len() >= 3)
        .unwrap();
    moved.vertices[k].at.x += 0.05;
    assert!(worst_error(&s, &moved).0 > 1.0);
    assert!(structure(&s, &moved).is_err());
    // An edge of the arc pushed off by 3 epsilon in the middle.
    let mut pushed = d.clone();
    let e = pushed
        .edges
        .iter_mut()
        .find(|e| e.sites.contains(&Generator::Site(0)) && e.points.len() > 4)
        .unwrap();
    let m = e.points.len() / 2;
    e.points[m].y += 3.0 * s.epsilon();
    e.points[m].x += 3.0 * s.epsilon();
    assert!(worst_error(&s, &pushed).0 > 1.0);
    let mut relabelled = d.clone();
    let e = relabelled
        .edges
        .iter_mut()
        .find(|e| e.sites.contains(&Generator::Site(0)))
        .unwrap();
    for g in e.sites.iter_mut() {
        if *g == Generator::Site(0) {
            *g = Generator::Site(3);
        }
    }
    assert!(worst_error(&s, &relabelled).0 > 1.0);
    let mut cut = d.clone();
    let e = cut
        .edges
        .iter_mut()
        .find(|e| e.points.len() > 2 && (e.from.is_some() || e.to.is_some()))
        .unwrap();
    if e.to.is_some() {
        e.points.pop();
        e.points.pop();
    } else {
        e.points.remove(0);
        e.points.remove(0);
    }
    assert!(structure(&s, &cut).is_err());
    // An edge removed: the completeness check misses it.
    assert!(missing_edge(&s, &d, 64).is_none());
    let longest = (0..d.edges.len())
        .max_by_key(|&k| d.edges[k].points.len())
        .unwrap();
    let mut dropped = d.clone();
    dropped.edges.remove(longest);
    assert!(missing_edge(&s, &dropped, 64).is_some());
    // And in complex mode, a piece label replaced by its corner.
    let v = scene_json(
        "complex",
        vec![arc((0.0, 0.0), 1.0, 0.0, 2.0).json(), point(0.3, -0.4)],
    );
    let s = scene_of(&v);
    let mut d = incremental(&s).unwrap();
    let piece = Generator::Feature {
        site: 0,
        feature: FeatureKind::Piece,
        index: 0,
    };
    let e = d
        .edges
        .iter_mut()
        .find(|e| e.sites.contains(&piece))
        .unwrap();
    for g in e.sites.iter_mut() {
        if *g == piece {
            *g = Generator::Feature {
                site: 0,
                feature: FeatureKind::Corner,
                index: 1,
            };
        }
    }
    assert!(worst_error(&s, &d).0 > 1.0);
}

// ---------------------------------------------------------------- conflicts

fn conflict(v: &Value) -> Option<(usize, usize)> {
    match incremental(&scene_of(v)) {
        Err(Error::Conflict { site, other, .. }) => Some((site, other)),
        _ => None,
    }
}

fn assert_conflict(sites: Vec<Value>, want: (usize, usize)) {
    for mode in ["voronoi", "complex"] {
        let v = scene_json(mode, sites.clone());
        let r = incremental(&scene_of(&v));
        match r {
            Err(Error::Conflict { site, other, .. }) => assert_eq!((site, other), want, "{v}"),
            other => panic!(
                "expected a conflict between {want:?}, got {:?} ({v})",
                other.map(|d| d.edges.len())
            ),
        }
    }
}

#[test]
fn crossing_arc_and_segment_conflict() {
    assert_conflict(
        vec![
            point(1.5, 1.5),
            arc((0.0, 0.0), 1.0, 0.0, PI).json(),
            point(-1.5, -1.5),
            segment(Point::new(0.1, 0.0), Point::new(-0.1, 1.8)),
        ],
        (1, 3),
    );
    // The segment first; an arc end touching the segment's inside.
    let a = arc((0.0, 0.0), 1.0, 0.0, 2.0);
    assert_conflict(
        vec![
            segment(Point::new(1.0, -1.0), Point::new(1.0, 1.0)),
            point(-1.5, 1.5),
            a.json(),
        ],
        (0, 2),
    );
    // A segment tangent to the arc's inside.
    assert_conflict(
        vec![
            arc((0.0, 0.0), 1.0, 0.5, 2.5).json(),
            segment(Point::new(-1.0, 1.0), Point::new(1.0, 1.0)),
        ],
        (0, 1),
    );
}

#[test]
fn crossing_arcs_conflict() {
    assert_conflict(
        vec![
            arc((0.0, 0.0), 1.0, -1.5, 1.5).json(),
            point(-1.8, 0.0),
            arc((1.0, 0.0), 1.0, 2.0, 4.5).json(),
        ],
        (0, 2),
    );
    // Tangent from outside.
    assert_conflict(
        vec![
            arc((-1.0, 0.0), 1.0, -1.0, 1.0).json(),
            arc((1.0, 0.0), 1.0, 2.0, 4.0).json(),
        ],
        (0, 1),
    );
}

#[test]
fn overlapping_arcs_on_one_circle_conflict() {
    assert_conflict(
        vec![
            point(0.0, 0.0),
            arc((0.0, 0.0), 1.0, 0.0, 2.0).json(),
            arc((0.0, 0.0), 1.0, 1.0, 3.0).json(),
        ],
        (1, 2),
    );
    // One inside the other.
    assert_conflict(
        vec![
            arc((0.0, 0.0), 1.0, 0.0, 5.0).json(),
            arc((0.0, 0.0), 1.0, 1.0, 2.0).json(),
        ],
        (0, 1),
    );
}

#[test]
fn point_on_arc_conflict() {
    let a = arc((0.2, 0.1), 1.3, 0.5, 3.0);
    let q = a.at(0.4);
    assert_conflict(vec![point(-1.9, -1.9), point(q.x, q.y), a.json()], (1, 2));
}

/// Not conflicts: a segment from an arc's end (bit for bit), a point at an arc's end;
/// they compute and pass the checks.
#[test]
fn shared_ends_are_not_conflicts() {
    let a = arc((0.0, 0.0), 1.0, 0.0, 2.0);
    let e = a.end(1);
    for mode in ["voronoi", "complex"] {
        // Guarded: bare, the edge between the arc and the segment outside the circle
        // is missing (failing/arc-segment-angled-joint.json).
        let v = guarded(scene_json(
            mode,
            vec![
                a.json(),
                segment(a.end(0), Point::new(1.5, -1.0)),
                point(e.x, e.y),
                point(-1.5, -1.5),
            ],
        ));
        check_value(&v).unwrap();
    }
}

// ---------------------------------------------------------------- properties

fn config(cases: u32) -> ProptestConfig {
    let seed = std::env::var("ARCS_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_261_124);
    ProptestConfig {
        cases,
        max_shrink_iters: 100,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

fn mode() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec!["voronoi", "complex"])
}

fn extra_points() -> impl Strategy<Value = Vec<(f64, f64)>> {
    prop::collection::vec((-1.9f64..1.9, -1.9f64..1.9), 0..5)
}

proptest! {
    #![proptest_config(config(48))]

    #[test]
    fn random_disjoint_arcs_and_points_guarded(
        mode in mode(),
        arcs in prop::collection::vec((-1.5f64..1.5, -1.5f64..1.5, 0.05f64..1.2, 0.0f64..TAU, 0.05f64..(TAU - 0.01)), 1..8),
        points in prop::collection::vec((-1.9f64..1.9, -1.9f64..1.9), 0..8),
    ) {
        let v = guarded(disjoint_scene(mode, &arcs, &points));
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn big_span_arcs_guarded(
        mode in mode(),
        arcs in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, 0.1f64..1.0, 0.0f64..TAU, PI..(TAU - 0.01)), 1..4),
        points in prop::collection::vec((-1.9f64..1.9, -1.9f64..1.9), 0..5),
    ) {
        let v = guarded(disjoint_scene(mode, &arcs, &points));
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn tiny_and_huge_radii_guarded(
        mode in mode(),
        mx in -1.0f64..1.0, my in -1.0f64..1.0, theta in 0.0f64..TAU,
        log_r in prop::sample::select(vec![-5.0, -4.0, -3.0, -2.0, 1.0, 2.0, 3.0, 4.0]),
        chord in 0.5f64..3.0,
        extra in extra_points(),
    ) {
        let r = 10f64.powf(log_r);
        let v = guarded(radius_scene(mode, (mx, my), theta, r, chord, TAU - 0.01, &extra));
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn concentric_guarded(
        mode in mode(),
        cx in -0.3f64..0.3, cy in -0.3f64..0.3,
        r0 in 0.05f64..0.5, dr in 0.05f64..0.4,
        arcs in prop::collection::vec((0.0f64..TAU, 0.1f64..(TAU - 0.01)), 1..5),
        centre in any::<bool>(),
    ) {
        let n = arcs.len().min(((1.6 - r0) / dr) as usize + 1).max(1);
        let v = guarded(concentric_scene(mode, (cx, cy), r0, dr, &arcs[..n], centre));
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn arc_and_point_inside_circle_guarded(
        mode in mode(),
        r in 0.2f64..1.5, a0 in 0.0f64..TAU, span in 0.1f64..(TAU - 0.01),
        t in 0.0f64..0.98, phi in 0.0f64..TAU,
    ) {
        let a = arc((0.0, 0.0), r, a0, a0 + span);
        let v = guarded(scene_json(mode, vec![a.json(), point(t * r * phi.cos(), t * r * phi.sin())]));
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn random_disjoint_arcs_and_points(
        mode in mode(),
        arcs in prop::collection::vec((-1.5f64..1.5, -1.5f64..1.5, 0.05f64..1.2, 0.0f64..TAU, 0.05f64..(TAU - 0.01)), 1..8),
        points in prop::collection::vec((-1.9f64..1.9, -1.9f64..1.9), 0..8),
    ) {
        let v = disjoint_scene(mode, &arcs, &points);
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn big_span_arcs(
        mode in mode(),
        arcs in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, 0.1f64..1.0, 0.0f64..TAU, PI..(TAU - 0.01)), 1..4),
        points in prop::collection::vec((-1.9f64..1.9, -1.9f64..1.9), 0..5),
    ) {
        let v = disjoint_scene(mode, &arcs, &points);
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    /// Tiny radii with spans up to 2π − 0.01.
    #[test]
    fn tiny_radii_big_spans(
        mode in mode(),
        mx in -1.0f64..1.0, my in -1.0f64..1.0, theta in 0.0f64..TAU,
        log_r in prop::sample::select(vec![-5.0, -4.0, -3.0, -2.0]),
        chord in 0.5f64..3.0,
        extra in extra_points(),
    ) {
        let r = 10f64.powf(log_r);
        let v = radius_scene(mode, (mx, my), theta, r, chord, TAU - 0.01, &extra);
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn concentric(
        mode in mode(),
        cx in -0.3f64..0.3, cy in -0.3f64..0.3,
        r0 in 0.05f64..0.5, dr in 0.05f64..0.4,
        arcs in prop::collection::vec((0.0f64..TAU, 0.1f64..(TAU - 0.01)), 1..5),
        centre in any::<bool>(),
    ) {
        let n = arcs.len().min(((1.6 - r0) / dr) as usize + 1).max(1);
        let v = concentric_scene(mode, (cx, cy), r0, dr, &arcs[..n], centre);
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn arc_and_point_inside_circle(
        mode in mode(),
        r in 0.2f64..1.5, a0 in 0.0f64..TAU, span in 0.1f64..(TAU - 0.01),
        t in 0.0f64..0.98, phi in 0.0f64..TAU,
    ) {
        let a = arc((0.0, 0.0), r, a0, a0 + span);
        let v = scene_json(mode, vec![a.json(), point(t * r * phi.cos(), t * r * phi.sin())]);
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn d_shapes_random(
        mode in mode(),
        cx in -0.3f64..0.3, cy in -0.3f64..0.3, r in 0.1f64..1.5, rot in 0.0f64..TAU,
        extra in extra_points(),
    ) {
        let v = d_scene(mode, (cx, cy), r, rot, &extra);
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    #[test]
    fn rounded_rectangles_random(
        mode in mode(),
        cx in -0.2f64..0.2, cy in -0.2f64..0.2,
        w in 0.2f64..1.7, h in 0.2f64..1.7, f in 0.05f64..0.95,
        extra in extra_points(),
    ) {
        let rho = f * w.min(h);
        let v = rounded_rect_scene(mode, (cx, cy), w, h, rho, &extra);
        prop_assert!(check_value(&v).is_ok(), "{}", check_value(&v).unwrap_err());
    }

    /// A segment through an inner point of an arc, transverse to it, is a conflict
    /// naming both.
    #[test]
    fn random_crossings_conflict(
        r in 0.2f64..1.5, a0 in 0.0f64..TAU, span in 0.2f64..(TAU - 0.01),
        t in 0.1f64..0.9, tilt in -1.0f64..1.0, other_arc in any::<bool>(),
    ) {
        let a = arc((0.0, 0.0), r, a0, a0 + span);
        let q = a.at(t);
        let ang = a0 + t * span + tilt; // transverse: within 1 rad of the normal
        let d = Point::new(ang.cos(), ang.sin()) * 0.3;
        let other = if other_arc {
            // A circle through q whose centre is off along d: crosses transversally.
            let c = q + d;
            let back = (q.y - c.y).atan2(q.x - c.x);
            arc((c.x, c.y), 0.3, back - 0.5, back + 0.5).json()
        } else {
            segment(q - d, q + d)
        };
        let v = scene_json("voronoi", vec![point(1.95, 1.95), other, a.json()]);
        prop_assert_eq!(conflict(&v), Some((1, 2)), "{}", v);
    }
}

// ---------------------------------------------------------------- known failures

fn failing(name: &str) -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(format!("tests/data/scenes/arcs/failing/{name}.json"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn check_failing(name: &str) {
    let v = failing(name);
    check_value(&v).unwrap();
    check_value(&guarded(v)).unwrap();
}

#[test]
fn failing_d_shape() {
    check_failing("d-shape-half-circle-diameter");
}

#[test]
fn failing_arc_point_inside_near() {
    check_failing("arc-span-1.5-point-inside-near");
}

/// Arc [3.4, 5.9] r 1 with a point at (0.26, -0.43) inside its circle: the point's
/// cell is bounded by one loop of edges, cut by the domain where its first point was
/// inside (it once came out as two edges ending there, not on the boundary).
#[test]
fn failing_arc_point_inside_deep() {
    check_failing("arc-span-2.5-point-inside-deep");
}

#[test]
fn failing_arc_span_4_point_inside() {
    check_failing("arc-span-4-point-inside");
}

#[test]
fn failing_arc_span_5_point_in_gap() {
    check_failing("arc-span-5-point-in-gap");
}

#[test]
fn failing_arc_span_6_point_in_gap() {
    check_failing("arc-span-6-point-in-gap");
}

#[test]
fn failing_concentric_two_arcs() {
    check_failing("concentric-two-arcs");
}

#[test]
fn failing_tiny_arc_big_span() {
    check_failing("tiny-arc-span-6.27");
}

#[test]
fn failing_two_arcs_big_span() {
    check_failing("two-arcs-span-5");
}

/// Tangent (G1) joints between separate sites: the common normal at the joint is an
/// edge between their cells (a line, not a tie region as at an angled joint), once
/// left out as two separators: arc [0, π/2] r 1 and segment (1, 0)-(1, -1), edge
/// Site(0)/Site(1) on y = 0.
#[test]
fn failing_arc_tangent_segment() {
    check_failing("arc-tangent-segment");
}

/// Arcs [π/2, π] and [π, 3π/2] of one circle: edge Site(0)/Site(1) on y = 0.
#[test]
fn failing_two_arcs_tangent_joint() {
    check_failing("two-arcs-tangent-joint");
}

#[test]
fn failing_arc_segment_angled_joint() {
    check_failing("arc-segment-angled-joint");
}

/// The shipped example `examples/scenes/rounded-rect-slot.json` (a rounded rectangle,
/// a stadium slot inside it and a point: eight tangent joints, separate sites sharing
/// ends), as shipped (`voronoi`) and in `complex` mode.
#[test]
fn shipped_rounded_rect_slot() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/rounded-rect-slot.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    check_value(&v).unwrap();
    v["mode"] = json!("complex");
    check_value(&v).unwrap();
}

/// The rounded rectangles and stadiums with the completeness check.
#[test]
fn tangent_joints_complete() {
    check_fixed("rounded-rect");
    check_fixed("stadium-");
}

/// A closed loop (both ends null) must repeat its first point last (SCENE_FORMAT.md):
/// checked bit for bit here. (The scene, unguarded, also fails the brute force: edge
/// Site(2)/Site(4) 4.29 eps off at (1.297, -2), the unbounded-arc-cell failure.)
#[test]
fn closed_loops_repeat_their_first_point() {
    let v = failing("closed-loop-last-point-not-first");
    let d = incremental(&scene_of(&v)).unwrap();
    for (k, e) in d.edges.iter().enumerate() {
        let (a, b) = (e.points[0], *e.points.last().unwrap());
        if e.from.is_none() && e.to.is_none() && a.dist(b) < 1e-9 {
            assert_eq!(a, b, "edge {k}");
        }
    }
}

// ---------------------------------------------------------------- scene dump

/// Writes every fixed scene and a few of each random family to `ARCS_DUMP_DIR`.
#[test]
#[ignore = "writes scene files for the shared checker; set ARCS_DUMP_DIR"]
fn dump_scenes() {
    let dir = std::env::var("ARCS_DUMP_DIR").expect("ARCS_DUMP_DIR");
    std::fs::create_dir_all(&dir).unwrap();
    let mut all = fixed_scenes();
    let mut x = 0.377_f64;
    let mut rnd = move |lo: f64, hi: f64| {
        x = (x * 9301.0 + 0.4927).fract();
        lo + (hi - lo) * x
    };
    for k in 0..4 {
        let mode = if k % 2 == 0 { "voronoi" } else { "complex" };
        let arcs: Vec<_> = (0..6)
            .map(|_| {
                (
                    rnd(-1.5, 1.5),
                    rnd(-1.5, 1.5),
                    rnd(0.05, 1.2),
                    rnd(0.0, TAU),
                    rnd(0.05, TAU - 0.01),
                )
            })
            .collect();
        let pts: Vec<_> = (0..6).map(|_| (rnd(-1.9, 1.9), rnd(-1.9, 1.9))).collect();
        let name: &'static str = Box::leak(format!("rand-disjoint-{k}-{mode}").into_boxed_str());
        all.push((name, disjoint_scene(mode, &arcs, &pts)));
        let name: &'static str =
            Box::leak(format!("rand-rounded-rect-{k}-{mode}").into_boxed_str());
        let (w, h) = (rnd(0.2, 1.7), rnd(0.2, 1.7));
        all.push((
            name,
            rounded_rect_scene(mode, (0.0, 0.0), w, h, rnd(0.05, 0.95) * w.min(h), &pts),
        ));
        let name: &'static str = Box::leak(format!("rand-radius-{k}-{mode}").into_boxed_str());
        let r = 10f64.powi([-4, -2, 2, 4][k]);
        all.push((
            name,
            radius_scene(
                mode,
                (rnd(-1.0, 1.0), rnd(-1.0, 1.0)),
                rnd(0.0, TAU),
                r,
                rnd(0.5, 3.0),
                TAU - 0.01,
                &pts,
            ),
        ));
    }
    for (name, v) in all {
        std::fs::write(
            Path::new(&dir).join(format!("{name}.json")),
            serde_json::to_string_pretty(&v).unwrap(),
        )
        .unwrap();
    }
}

/// A scene file whose segments share ends with arcs bit for bit (as written by Python's
/// or serde_json's shortest round-trip printing) must read back the same numbers;
/// serde_json without its `float_roundtrip` feature reads some of them 1 ulp off, and the
/// segment then touches the arc away from a shared end: `Error::Conflict`.
#[test]
fn shared_ends_survive_reading_the_file() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/scenes/arcs/failing/rounded-rect-points-json-read.json");
    let text = std::fs::read_to_string(path).unwrap();
    let s = Scene::from_json(&text).unwrap();
    let d = incremental(&s);
    assert!(d.is_ok(), "{:?}", d.err());
}

/// What `shared_ends_survive_reading_the_file` is about: numbers of the file read by
/// serde_json against Rust's correctly rounded `str::parse` (reported, not asserted).
#[test]
fn json_numbers_read_exactly_report() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/scenes/arcs/failing/rounded-rect-points-json-read.json");
    let text = std::fs::read_to_string(path).unwrap();
    let mut off = 0;
    for tok in
        text.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e' || c == 'E'))
    {
        if tok.len() > 8 {
            let exact: f64 = tok.parse().unwrap();
            let sj: f64 = serde_json::from_str(tok).unwrap();
            if exact != sj {
                off += 1;
                println!("{tok}: serde_json reads {sj:?}, exact {exact:?}");
            }
        }
    }
    println!("{off} numbers misread");
}
