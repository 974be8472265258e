//! Property tests of the incremental segment engine on degenerate families of input:
//! grids of points (with a segment between two rows), cocircular lattice points with
//! radial segments, collinear points and segments on one line (points on a segment's
//! supporting line outside it), regular polygons with an even number of sides (parallel
//! edges) as polygons in every mode and as separate segments, spikes of k segments from
//! one point, chains (as one polyline and as separate segments sharing endpoints),
//! near-parallel segments (angle down to 1e-12), near-touching segments (gaps down to
//! 1e-9), and axis-parallel segments on a grid.
//!
//! Every case must compute (`Ok`), or, where the input really conflicts (a touching
//! T-junction), be refused with `Error::Conflict` naming both sites. Every result must
//! pass:
//! * the structure check: `check_invariants` (indices, generators listed at the ends),
//!   edge polylines that start and end on the vertex they name (within `1e-3·epsilon`), and
//!   `null` ends on the domain's boundary unless the edge is a closed loop;
//! * a brute-force soundness check written here (distances to the scene's features,
//!   no engine code): every edge sample and vertex equidistant from its generators within
//!   epsilon, with no generator nearer;
//! * `gvd::verify` (the library behind `gvd verify`, grid 128), in every mode, also
//!   where two *different* sites share an endpoint (spikes, chains of separate
//!   segments, polygons as segments): there both sites are nearest through the same
//!   point over a two-dimensional wedge, which either may own (see
//!   `shared_endpoint_ties_pass_verify`).

use gvd::complex::{Generator, VoronoiComplex};
use gvd::geom::Point;
use gvd::scene::Mode;
use gvd::verify::{verify, VerifyOptions};
use gvd::{compute, Engine, Error, Options, Scene};
use proptest::prelude::*;
use serde_json::{json, Value};

mod common;
use common::{dist, generators, seg_dist};

// ---------------------------------------------------------------- brute force

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
        let ds: Vec<f64> = gens.iter().map(|g| dist(s, g, q)).collect();
        let (lo, hi) = ds
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), &v| (l.min(v), h.max(v)));
        let err = (hi - lo).max(lo - nearest(q)) / s.epsilon();
        if err > worst.0 {
            worst = (err, format!("{what} at ({}, {}) of {gens:?}", q.x, q.y));
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
/// ends on the boundary.
fn structure(s: &Scene, d: &VoronoiComplex) -> Result<(), String> {
    d.check_invariants()?;
    // Edge ends and vertices are computed separately (bisection along the bisector);
    // they agree to about 1e-9 of the domain, far below epsilon.
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
        let closed = e.from.is_none() && e.to.is_none() && e.points.first() == e.points.last();
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

fn scene_of(mode: &str, sites: Vec<Value>) -> Scene {
    Scene::from_value(&json!({
        "domain": [-2, -2, 2, 2],
        "epsilon": 0.001,
        "mode": mode,
        "sites": sites,
    }))
    .unwrap()
}

fn incremental(s: &Scene) -> Result<VoronoiComplex, Error> {
    let options = Options {
        engine: Engine::Incremental,
        ..Options::default()
    };
    compute(s, &options)
}

/// Every check of the module doc on one scene; the scene's JSON is in the message.
fn check_scene(s: &Scene) -> Result<(), String> {
    let ctx = || {
        let sites: Vec<String> = s.sites().iter().map(|x| format!("{:?}", x.kind)).collect();
        format!("mode {:?}, sites {}", s.mode(), sites.join("; "))
    };
    let d = incremental(s).map_err(|e| format!("refused: {e} ({})", ctx()))?;
    structure(s, &d).map_err(|e| format!("structure: {e} ({})", ctx()))?;
    // One site alone has no edges in `voronoi` mode, nor a convex polygon in `complex`
    // mode (only separators outside it); a medial axis or two sites always do.
    if d.edges.is_empty() && (s.sites().len() >= 2 || s.mode() == Mode::MedialAxis) {
        return Err(format!("no edges ({})", ctx()));
    }
    let (err, at) = worst_error(s, &d);
    if err > 1.0 {
        return Err(format!("brute force: error {err} eps, {at} ({})", ctx()));
    }
    let opts = VerifyOptions {
        grid: 128,
        ..VerifyOptions::default()
    };
    let r = verify(s, &d, &opts).map_err(|e| format!("verify refused: {e}"))?;
    if !r.passed {
        return Err(format!(
            "gvd verify: {} {:?} ({})",
            r.summary_line(),
            r.problems,
            ctx()
        ));
    }
    Ok(())
}

fn pt(x: f64, y: f64) -> Value {
    json!([x, y])
}
fn point(x: f64, y: f64) -> Value {
    json!({"kind": "point", "at": [x, y]})
}
fn segment(a: (f64, f64), b: (f64, f64)) -> Value {
    json!({"kind": "segment", "from": [a.0, a.1], "to": [b.0, b.1]})
}

// ---------------------------------------------------------------- families

/// A k×k grid of points, spacing `s`, optionally with a horizontal segment between two
/// rows (every point of the two rows is then equidistant from it and its neighbours).
fn grid_scene(k: usize, s: f64, seg_row: Option<usize>) -> Scene {
    let x0 = -s * (k - 1) as f64 / 2.0;
    let mut sites = Vec::new();
    for i in 0..k {
        for j in 0..k {
            sites.push(point(x0 + i as f64 * s, x0 + j as f64 * s));
        }
    }
    if let Some(r) = seg_row {
        let y = x0 + (r as f64 + 0.5) * s;
        sites.push(segment((x0 - 0.25 * s, y), (x0 + (k as f64 - 0.75) * s, y)));
    }
    scene_of("voronoi", sites)
}

/// The 20 lattice points of x² + y² = 25², scaled by 1/16 (exact).
fn circle_points() -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for &(a, b) in &[(0, 25), (7, 24), (15, 20), (20, 15), (24, 7)] {
        for &(sx, sy) in &[(1, 1), (-1, 1), (-1, -1), (1, -1)] {
            out.push(((sx * a) as f64 / 16.0, (sy * b) as f64 / 16.0));
        }
    }
    out.sort_by(|p, q| p.partial_cmp(q).unwrap());
    out.dedup();
    out
}

/// Cocircular points (a subset of the lattice circle), radial segments inside the
/// circle towards the centre for another subset, and optionally the centre.
fn cocircular_scene(points: &[bool], radial: &[bool], centre: bool) -> Scene {
    let c = circle_points();
    let mut sites = Vec::new();
    for (k, &(x, y)) in c.iter().enumerate() {
        if points[k % points.len()] {
            sites.push(point(x, y));
        }
        if radial[k % radial.len()] {
            sites.push(segment((x * 0.25, y * 0.25), (x * 0.5, y * 0.5)));
        }
    }
    if centre {
        sites.push(point(0.0, 0.0));
    }
    if sites.len() < 2 {
        sites.push(point(1.9, 1.9));
        sites.push(point(-1.9, 1.9));
    }
    scene_of("voronoi", sites)
}

/// Tokens along the line y = 0 (and optionally a parallel copy at y = h): 0 a point,
/// 1 a gap, n ≥ 2 a segment over n − 1 slots; slots are 0.125 apart and a segment is
/// followed by a gap, so nothing touches. Points off the segments but on their
/// supporting line are what this family is about.
fn collinear_scene(tokens: &[u8], h: Option<f64>) -> Scene {
    let step = 0.125;
    let mut x = -1.75;
    let mut sites = Vec::new();
    for &t in tokens {
        if x > 1.75 {
            break;
        }
        match t {
            0 => {
                sites.push(point(x, 0.0));
                x += step;
            }
            1 => x += step,
            n => {
                let x1 = (x + step * (n - 1) as f64).min(1.875);
                sites.push(segment((x, 0.0), (x1, 0.0)));
                if let Some(h) = h {
                    sites.push(segment((x, h), (x1, h)));
                }
                x = x1 + 2.0 * step;
            }
        }
    }
    if sites.len() < 2 {
        sites.push(point(0.0, 1.0));
    }
    scene_of("voronoi", sites)
}

fn regular_polygon(n: usize, r: f64, rot: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|k| {
            let a = rot + std::f64::consts::TAU * k as f64 / n as f64;
            (r * a.cos(), r * a.sin())
        })
        .collect()
}

fn polygon_scene(n: usize, r: f64, rot: f64, mode: &str, outside_point: bool) -> Scene {
    let ring: Vec<Value> = regular_polygon(n, r, rot)
        .into_iter()
        .map(|(x, y)| pt(x, y))
        .collect();
    let mut sites = vec![json!({"kind": "polygon", "rings": [ring]})];
    if outside_point {
        sites.push(point(1.9, 1.7));
    }
    scene_of(mode, sites)
}

/// A regular polygon as separate segments sharing endpoints, optionally with its centre.
fn polygon_segments_scene(n: usize, r: f64, rot: f64, centre: bool) -> Scene {
    let p = regular_polygon(n, r, rot);
    let mut sites: Vec<Value> = (0..n).map(|k| segment(p[k], p[(k + 1) % n])).collect();
    if centre {
        sites.push(point(0.0, 0.0));
    }
    scene_of("voronoi", sites)
}

/// k segments from one point at distinct angles (at least 0.05 apart), with extra points.
fn spike_scene(c: (f64, f64), rays: &[(f64, f64)], extra: &[(f64, f64)]) -> Scene {
    let mut angles: Vec<(f64, f64)> = rays.to_vec();
    angles.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap());
    let mut kept: Vec<(f64, f64)> = Vec::new();
    for a in angles {
        let clear = |b: &(f64, f64)| {
            let d = (a.0 - b.0).rem_euclid(std::f64::consts::TAU);
            d.min(std::f64::consts::TAU - d) > 0.05
        };
        if kept.iter().all(clear) {
            kept.push(a);
        }
    }
    let mut sites: Vec<Value> = kept
        .iter()
        .map(|&(a, len)| segment(c, (c.0 + len * a.cos(), c.1 + len * a.sin())))
        .collect();
    for &(x, y) in extra {
        // Keep extra points off the rays: at least 0.01 from every segment.
        let q = Point { x, y };
        let off = kept.iter().all(|&(a, len)| {
            let b = Point {
                x: c.0 + len * a.cos(),
                y: c.1 + len * a.sin(),
            };
            seg_dist(q, Point { x: c.0, y: c.1 }, b) > 0.01
        });
        if off {
            sites.push(point(x, y));
        }
    }
    scene_of("voronoi", sites)
}

/// An x-monotone chain (so it cannot cross itself) as one polyline or as separate
/// segments sharing endpoints.
fn chain_scene(steps: &[(f64, f64)], as_polyline: bool, mode: &str) -> Scene {
    let mut pts = vec![(-1.8, 0.0)];
    for &(dx, y) in steps {
        let x = pts.last().unwrap().0 + dx;
        if x > 1.8 {
            break;
        }
        pts.push((x, y));
    }
    if pts.len() < 2 {
        pts.push((1.0, 0.5));
    }
    let sites = if as_polyline {
        let p: Vec<Value> = pts.iter().map(|&(x, y)| pt(x, y)).collect();
        vec![json!({"kind": "polyline", "points": p}), point(0.0, 1.9)]
    } else {
        let mut s: Vec<Value> = pts.windows(2).map(|w| segment(w[0], w[1])).collect();
        s.push(point(0.0, 1.9));
        s
    };
    scene_of(mode, sites)
}

/// Two (or three) segments at a tiny angle `delta`, with an optional point between.
fn near_parallel_scene(h: f64, delta: f64, third: bool, mid_point: bool) -> Scene {
    let mut sites = vec![
        segment((-1.0, 0.0), (1.0, 0.0)),
        segment((-1.0, h), (1.0, h + delta)),
    ];
    if third {
        sites.push(segment((-1.0, -h), (1.0, -h - delta)));
    }
    if mid_point {
        sites.push(point(0.25, h / 2.0));
    }
    scene_of("voronoi", sites)
}

/// A segment and another feature at a tiny gap: 0 a T-junction, 1 end to end on one
/// line, 2 end beside end at an angle, 3 a point beside the segment's inside.
fn near_touching_scene(kind: u8, gap: f64, x: f64) -> Scene {
    let a = segment((-1.0, 0.0), (0.5, 0.0));
    let other = match kind {
        0 => segment((x, gap), (x, 1.0)),
        1 => segment((0.5 + gap, 0.0), (1.5, 0.0)),
        2 => segment((0.5 + gap, gap), (1.0, 1.0)),
        _ => point(x, gap),
    };
    scene_of("voronoi", vec![a, other, point(0.0, -1.5)])
}

/// Axis-parallel segments, one per cell of an m×m grid (horizontal or vertical, 0.6 of
/// the cell), with points at some cell corners.
fn axis_grid_scene(m: usize, horizontal: &[bool], corners: &[bool]) -> Scene {
    let s = 3.6 / m as f64;
    let x0 = -1.8;
    let mut sites = Vec::new();
    for i in 0..m {
        for j in 0..m {
            let k = i * m + j;
            let (cx, cy) = (x0 + (i as f64 + 0.5) * s, x0 + (j as f64 + 0.5) * s);
            let h = 0.3 * s;
            if horizontal[k % horizontal.len()] {
                sites.push(segment((cx - h, cy), (cx + h, cy)));
            } else {
                sites.push(segment((cx, cy - h), (cx, cy + h)));
            }
            if corners[k % corners.len()] {
                sites.push(point(x0 + i as f64 * s, x0 + j as f64 * s));
            }
        }
    }
    scene_of("voronoi", sites)
}

// ---------------------------------------------------------------- properties

/// A fixed seed (so the branch stays green or red deterministically; set
/// `SEGPROPS_SEED` to explore others) and no persistence file (failures found are kept
/// as scenes under `tests/data/scenes/regressions/` with their own tests below).
fn config(cases: u32) -> ProptestConfig {
    let seed = std::env::var("SEGPROPS_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_261_123);
    ProptestConfig {
        cases,
        max_shrink_iters: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(32))]

    #[test]
    fn grids_of_points(k in 2usize..7, s in prop::sample::select(vec![0.25, 0.5]), row in prop::option::of(0usize..5)) {
        let row = row.filter(|r| r + 1 < k);
        let sc = grid_scene(k, s, row);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn cocircular_points_with_segments(points in prop::collection::vec(any::<bool>(), 1..7), radial in prop::collection::vec(any::<bool>(), 1..7), centre in any::<bool>()) {
        let sc = cocircular_scene(&points, &radial, centre);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn collinear_points_and_segments(tokens in prop::collection::vec(0u8..5, 2..20), h in prop::option::of(prop::sample::select(vec![0.125, 0.5, 1e-3]))) {
        let sc = collinear_scene(&tokens, h);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn even_regular_polygons(m in 2usize..9, r in 0.3f64..1.6, rot in 0.0f64..1.0, mode in prop::sample::select(vec!["voronoi", "complex", "medial_axis"]), outside in any::<bool>()) {
        let sc = polygon_scene(2 * m, r, rot, mode, outside);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn even_regular_polygons_as_segments(m in 2usize..9, r in 0.3f64..1.6, rot in 0.0f64..1.0) {
        let sc = polygon_segments_scene(2 * m, r, rot, false);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn spikes(cx in -0.5f64..0.5, cy in -0.5f64..0.5, rays in prop::collection::vec((0.0f64..std::f64::consts::TAU, 0.2f64..1.2), 2..3), extra in prop::collection::vec((-1.9f64..1.9, -1.9f64..1.9), 0..4)) {
        let sc = spike_scene((cx, cy), &rays, &extra);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn chains(steps in prop::collection::vec((0.05f64..0.8, -1.0f64..1.0), 1..12), as_polyline in any::<bool>(), mode in prop::sample::select(vec!["voronoi", "complex"])) {
        let sc = chain_scene(&steps, as_polyline, mode);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn near_parallel_segments(h in 0.01f64..0.8, e in 6i32..13, sign in prop::sample::select(vec![-1.0, 1.0]), third in any::<bool>()) {
        let sc = near_parallel_scene(h, sign * 10f64.powi(-e), third, false);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn near_parallel_segments_with_point(h in 0.01f64..0.8, e in 6i32..13, sign in prop::sample::select(vec![-1.0, 1.0]), third in any::<bool>()) {
        let sc = near_parallel_scene(h, sign * 10f64.powi(-e), third, true);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn near_touching_segments(kind in 0u8..3, e in 5i32..10, x in -0.9f64..0.4) {
        let sc = near_touching_scene(kind, 4.0 * 10f64.powi(-e), x);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn point_near_segment_inside(e in 5i32..10, x in -0.9f64..0.4) {
        let sc = near_touching_scene(3, 4.0 * 10f64.powi(-e), x);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn axis_parallel_grid_segments(m in 2usize..6, horizontal in prop::collection::vec(any::<bool>(), 1..9), corners in prop::collection::vec(any::<bool>(), 1..9)) {
        let sc = axis_grid_scene(m, &horizontal, &corners);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    /// A T-junction that really touches is split there and computed; with `strict` it
    /// is refused, naming both sites.
    #[test]
    fn touching_t_junction_is_split_or_refused_when_strict(x in -0.9f64..0.4) {
        let sc = near_touching_scene(0, 0.0, x);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
        let strict = Options {
            engine: Engine::Incremental,
            incremental: gvd::IncrementalOptions { strict: true, ..Default::default() },
            ..Options::default()
        };
        let r = compute(&sc, &strict);
        prop_assert!(matches!(r, Err(Error::Conflict { site: 0, other: 1, .. })), "{:?}", r.err());
    }
}

proptest! {
    // These once failed (spikes, a regular polygon's sides around its centre): searched
    // with more cases.
    #![proptest_config(config(128))]

    #[test]
    fn spikes_many(cx in -0.5f64..0.5, cy in -0.5f64..0.5, rays in prop::collection::vec((0.0f64..std::f64::consts::TAU, 0.2f64..1.2), 3..9), extra in prop::collection::vec((-1.9f64..1.9, -1.9f64..1.9), 0..4)) {
        let sc = spike_scene((cx, cy), &rays, &extra);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }

    #[test]
    fn even_regular_polygons_as_segments_with_centre(m in 2usize..9, r in 0.3f64..1.6, rot in 0.0f64..1.0) {
        let sc = polygon_segments_scene(2 * m, r, rot, true);
        prop_assert!(check_scene(&sc).is_ok(), "{}", check_scene(&sc).unwrap_err());
    }
}

fn regression_scene(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(format!("tests/data/scenes/regressions/{name}.json"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn regression_near_parallel_segments_point_between() {
    let sc = regression_scene("near-parallel-segments-point-between");
    check_scene(&sc).unwrap();
}

#[test]
fn regression_point_4e_6_above_segment() {
    let sc = regression_scene("point-4e-6-above-segment-cell-lost");
    check_scene(&sc).unwrap();
}

#[test]
fn regression_spike_8_segments() {
    let sc = regression_scene("spike-8-segments");
    check_scene(&sc).unwrap();
}

#[test]
fn regression_spike_3_segments_narrow() {
    check_scene(&regression_scene("spike-3-segments-narrow")).unwrap();
}

#[test]
fn regression_spike_3_segments() {
    check_scene(&regression_scene("spike-3-segments")).unwrap();
}

#[test]
fn regression_polygon_12_as_segments_centre() {
    check_scene(&regression_scene("polygon-12-as-segments-centre")).unwrap();
}

/// The checks can fail: a vertex moved off its place and an edge end detached from its
/// vertex are both caught.
#[test]
fn checks_detect_perturbations() {
    let sc = grid_scene(3, 0.5, Some(0));
    let d = incremental(&sc).unwrap();
    assert!(check_scene(&sc).is_ok());
    let mut moved = d.clone();
    let k = moved
        .vertices
        .iter()
        .position(|v| v.sites.len() >= 3)
        .unwrap();
    moved.vertices[k].at.x += 0.05;
    assert!(worst_error(&sc, &moved).0 > 1.0);
    assert!(structure(&sc, &moved).is_err());
    let mut cut = d.clone();
    let e = cut.edges.iter_mut().find(|e| e.points.len() > 2).unwrap();
    e.points.pop();
    e.points.pop();
    assert!(structure(&sc, &cut).is_err());
}

/// Two segments sharing an endpoint at a right angle tie over the opposite quadrant
/// (both are nearest through the shared end there). The engine names that region by
/// the first segment; `gvd::verify` (grid 128) passes it: the crossings on the
/// quadrant's sides, where the feet on the two segments meet at the shared end, are
/// ties it skips (it once took the bracket's middle for the crossing, half a bracket
/// off, and reported missing edges there).
#[test]
fn shared_endpoint_ties_pass_verify() {
    let sc = spike_scene(
        (0.0, 0.0),
        &[(0.0, 1.0), (std::f64::consts::FRAC_PI_2, 1.0)],
        &[],
    );
    let d = incremental(&sc).unwrap();
    assert!(worst_error(&sc, &d).0 <= 1.0);
    let r = verify(
        &sc,
        &d,
        &VerifyOptions {
            grid: 128,
            ..VerifyOptions::default()
        },
    )
    .unwrap();
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
}

/// A T-junction with a gap of 4e-9: the parabola around the end is narrower than any
/// tolerance (once, its chord touched the endpoint and the new vertex on the separator
/// fell onto the endpoint, the unclaimed piece being lost to rounding).
#[test]
fn regression_t_junction_gap_4e_9() {
    check_scene(&regression_scene("t-junction-gap-4e-9")).unwrap();
}
