//! Segments that share endpoints (chains, junctions of road networks), through the
//! incremental engine, checked by brute force: every vertex's listed generators are at
//! equal distance from it, and no generator of the scene is nearer (distances computed
//! here from the scene's sites, no engine code); every edge sample likewise within
//! epsilon; and `gvd::verify` passes the diagram.
//!
//! The regression scenes are cut from real inputs (Boost.Polygon's example and
//! benchmark inputs, CGAL's `norway.cin`) where the engine once wrote a vertex at a
//! shared end that listed a generator far away: at a (nearly) straight joint the
//! bisector of the two segments was taken to be their common line instead of the
//! common normal at the joint.

use gvd::complex::{Generator, VoronoiComplex};
use gvd::geom::Point;
use gvd::verify::{verify, VerifyOptions};
use gvd::{compute, Engine, Options, Scene};

mod common;
use common::{dist, generators};

fn regression_scene(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(format!("tests/data/scenes/regressions/{name}.json"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn incremental(s: &Scene) -> VoronoiComplex {
    let options = Options {
        engine: Engine::Incremental,
        ..Options::default()
    };
    compute(s, &options).unwrap()
}

/// The worst vertex of `d`, in units of epsilon: the spread of the distances to its
/// listed generators, or how much nearer the nearest generator of the scene is, with
/// a description.
fn worst_vertex(s: &Scene, d: &VoronoiComplex) -> (f64, String) {
    let all = generators(s);
    let mut worst = (0.0f64, String::new());
    for (k, v) in d.vertices.iter().enumerate() {
        let ds: Vec<f64> = v.sites.iter().map(|g| dist(s, g, v.at)).collect();
        let lo = ds.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ds.iter().copied().fold(0.0f64, f64::max);
        let nearest = all
            .iter()
            .map(|g| dist(s, g, v.at))
            .fold(f64::INFINITY, f64::min);
        let err = (hi - lo).max(lo - nearest) / s.epsilon;
        if err > worst.0 {
            worst = (
                err,
                format!(
                    "vertex {k} at ({}, {}) lists {:?} at distances {ds:?}, nearest {nearest}",
                    v.at.x, v.at.y, v.sites
                ),
            );
        }
    }
    worst
}

/// The worst edge sample (polyline points and midpoints), in units of epsilon.
fn worst_edge(s: &Scene, d: &VoronoiComplex) -> (f64, String) {
    let all = generators(s);
    let mut worst = (0.0f64, String::new());
    let mut sample = |q: Point, gens: &[Generator], k: usize| {
        let ds: Vec<f64> = gens.iter().map(|g| dist(s, g, q)).collect();
        let lo = ds.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ds.iter().copied().fold(0.0f64, f64::max);
        let nearest = all
            .iter()
            .map(|g| dist(s, g, q))
            .fold(f64::INFINITY, f64::min);
        let err = (hi - lo).max(lo - nearest) / s.epsilon;
        if err > worst.0 {
            worst = (err, format!("edge {k} {gens:?} at ({}, {})", q.x, q.y));
        }
    };
    for (k, e) in d.edges.iter().enumerate() {
        for w in e.points.windows(2) {
            sample(w[0], &e.sites, k);
            sample(w[0].lerp(w[1], 0.5), &e.sites, k);
        }
    }
    worst
}

/// Vertices within `1e-6·epsilon` (they are computed, not sampled), edges within
/// epsilon, and `gvd::verify` passes.
#[track_caller]
fn assert_exact_vertices_and_sound(s: &Scene, what: &str) {
    let d = incremental(s);
    d.check_invariants().unwrap();
    assert!(!d.edges.is_empty(), "{what}: no edges");
    let (err, at) = worst_vertex(s, &d);
    assert!(err <= 1e-6, "{what}: {err} epsilon: {at}");
    let (err, at) = worst_edge(s, &d);
    assert!(err <= 1.0, "{what}: {err} epsilon: {at}");
    let report = verify(s, &d, &VerifyOptions::default()).unwrap();
    assert!(
        report.passed,
        "{what}: gvd verify: {} {:?}",
        report.summary_line(),
        report.problems
    );
}

/// Two long parallel segments and a straight chain of two segments between them (4 of
/// the 12 of Boost.Polygon's `polygon_012`): the vertex below the joint (60, 20) is on
/// its normal, where the lower segment ties, at clearance about 10.03.
#[test]
fn straight_joint_between_parallel_segments() {
    let s = regression_scene("shared-endpoint-4segments");
    assert_exact_vertices_and_sound(&s, "4 segments");
    let d = incremental(&s);
    let below = d
        .vertices
        .iter()
        .find(|v| v.sites.len() == 3 && v.at.y < 20.0)
        .expect("a vertex below the joint");
    assert!((below.at.y - 10.0307).abs() < 1e-3, "{:?}", below.at);
}

/// 84 segments of Boost.Polygon's road network benchmark with degree-4 junctions: the
/// joint of sites 82 and 83 bends by 1.5e-10 rad.
#[test]
fn nearly_straight_joint_in_a_road_network() {
    let s = regression_scene("shared-endpoint-84segments");
    assert_exact_vertices_and_sound(&s, "84 segments");
}
/// Three segments of a coastline (CGAL's `norway.cin`), two of them sharing an end.
#[test]
fn coastline_joint() {
    let s = regression_scene("shared-endpoint-labels-3segments");
    assert_exact_vertices_and_sound(&s, "3 segments");
}
