//! The incremental engine on points, segments, polylines and polygons, checked by brute
//! force: every edge sample and every vertex must be equidistant (within epsilon) from
//! its generators, with no generator nearer. The distances here are computed directly
//! from the scene's features and share no code with the engine.

use gvd::complex::{Generator, VoronoiComplex};
use gvd::geom::Point;
use gvd::{compute, Engine, Error, Options, Scene};
use std::path::Path;

mod common;
use common::{dist, generators};

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/data/scenes/{name}.json"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn incremental(s: &Scene) -> Result<VoronoiComplex, Error> {
    let options = Options {
        engine: Engine::Incremental,
        ..Options::default()
    };
    compute(s, &options)
}

/// Brute-force soundness: returns the worst error in units of epsilon.
fn worst_error(s: &Scene, d: &VoronoiComplex) -> f64 {
    let all = generators(s);
    let nearest = |q: Point| {
        all.iter()
            .map(|g| dist(s, g, q))
            .fold(f64::INFINITY, f64::min)
    };
    let mut worst: f64 = 0.0;
    let mut sample = |q: Point, gens: &[Generator]| {
        let ds: Vec<f64> = gens.iter().map(|g| dist(s, g, q)).collect();
        let (lo, hi) = ds
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), &v| (l.min(v), h.max(v)));
        let err = (hi - lo).max(lo - nearest(q));
        worst = worst.max(err / s.epsilon());
    };
    for e in &d.edges {
        for w in e.points.windows(2) {
            sample(w[0], &e.sites);
            sample(w[0].lerp(w[1], 0.5), &e.sites);
        }
    }
    for v in &d.vertices {
        sample(v.at, &v.sites);
    }
    worst
}

#[track_caller]
fn assert_sound(name: &str) {
    let s = scene(name);
    let d = incremental(&s).unwrap();
    d.check_invariants().unwrap();
    assert!(!d.edges.is_empty(), "{name}: no edges");
    let err = worst_error(&s, &d);
    assert!(err <= 1.0, "{name}: worst error {err} epsilon");
}

#[test]
fn corpus_scenes_are_sound() {
    for name in [
        "degenerate-triangle-segments",
        "polyline-zigzag-complex",
        "polyline-zigzag-points-voronoi",
        "polygons-convex5-voronoi",
        "polygons-convex5-complex",
        "polygon-holes2-medial_axis",
        "polygon-bugtrap-complex",
        "polygon-star50-complex",
    ] {
        assert_sound(name);
    }
}

/// Dense random segments (`gen_scene.py segments 1000 --seed 1`), where endpoints come
/// within 1e-6 of other segments; and nine of them around such a near T-junction. A
/// point that close keeps a needle of its face through the new segment's region, whose
/// crossing of an old edge splits the conflict tree.
#[test]
fn dense_and_near_touching_segments_are_sound() {
    assert_sound("segments-near-touching-9");
    assert_sound("segments-dense-1000");
}

fn json_scene(mode: &str, sites: &str) -> Scene {
    Scene::from_json(&format!(
        r#"{{"domain": [-2, -2, 2, 2], "epsilon": 0.001, "mode": "{mode}", "sites": [{sites}]}}"#
    ))
    .unwrap()
}

#[test]
fn degenerate_inputs_are_sound() {
    let cases = [
        // A square: parallel edges, a medial axis vertex of degree four.
        (
            "medial_axis",
            r#"{"kind": "polygon", "rings": [[[-1,-1],[1,-1],[1,1],[-1,1]]]}"#,
        ),
        (
            "complex",
            r#"{"kind": "polygon", "rings": [[[-1,-1],[1,-1],[1,1],[-1,1]]]}"#,
        ),
        // A spike: four segments from one point.
        (
            "voronoi",
            r#"{"kind": "segment", "from": [0,0], "to": [1,0]},
                       {"kind": "segment", "from": [0,0], "to": [0,1]},
                       {"kind": "segment", "from": [0,0], "to": [-1,0.2]},
                       {"kind": "segment", "from": [0,0], "to": [0.3,-1]}"#,
        ),
        // A collinear chain and a point on its supporting line.
        (
            "complex",
            r#"{"kind": "polyline", "points": [[-1,0],[0,0],[1,0]]},
                       {"kind": "point", "at": [1.5, 0]}"#,
        ),
        // Axis-parallel segments sharing corners.
        (
            "voronoi",
            r#"{"kind": "segment", "from": [-1,0.5], "to": [1,0.5]},
                       {"kind": "segment", "from": [1,0.5], "to": [1,-0.5]},
                       {"kind": "point", "at": [1.5, 0]}"#,
        ),
    ];
    for (mode, sites) in cases {
        let s = json_scene(mode, sites);
        let d = incremental(&s).unwrap();
        d.check_invariants().unwrap();
        let err = worst_error(&s, &d);
        assert!(err <= 1.0, "{mode} {sites}: worst error {err} epsilon");
    }
}

/// A point between two parallel segments: the upper segment's region wraps around the
/// point's face, so the lower segment's face meets `T` in two chains.
#[test]
fn point_between_parallel_segments() {
    let s = json_scene(
        "voronoi",
        r#"{"kind": "segment", "from": [-1,0.5], "to": [1,0.5]},
           {"kind": "segment", "from": [-1,-0.5], "to": [1,-0.5]},
           {"kind": "point", "at": [0, 0.1]}"#,
    );
    let d = incremental(&s).unwrap();
    assert!(worst_error(&s, &d) <= 1.0);
}

#[test]
fn crossing_and_overlapping_segments_are_refused_naming_both_when_strict() {
    // (by default they are split: tests/split_crossings.rs)
    let incremental = |s: &Scene| {
        let options = Options {
            engine: Engine::Incremental,
            incremental: gvd::IncrementalOptions {
                strict: true,
                ..Default::default()
            },
            ..Options::default()
        };
        compute(s, &options)
    };
    let crossing = json_scene(
        "voronoi",
        r#"{"kind": "point", "at": [1.5, 1.5]},
           {"kind": "segment", "from": [-1,-1], "to": [1,1]},
           {"kind": "segment", "from": [-1,1], "to": [1,-1]}"#,
    );
    let err = incremental(&crossing).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Conflict {
                site: 1,
                other: 2,
                ..
            }
        ),
        "{err}"
    );
    let overlap = json_scene(
        "voronoi",
        r#"{"kind": "segment", "from": [-1,0], "to": [0.5,0]},
           {"kind": "segment", "from": [0,0], "to": [1,0]}"#,
    );
    assert!(matches!(
        incremental(&overlap),
        Err(Error::Conflict {
            site: 0,
            other: 1,
            ..
        })
    ));
    let touching = json_scene(
        "voronoi",
        r#"{"kind": "segment", "from": [-1,0], "to": [1,0]},
           {"kind": "segment", "from": [0,0], "to": [0,1]}"#,
    );
    assert!(matches!(
        incremental(&touching),
        Err(Error::Conflict {
            site: 0,
            other: 1,
            ..
        })
    ));
}

#[test]
fn auto_engine_takes_linear_scenes() {
    let s = scene("polyline-zigzag-complex");
    let d = compute(&s, &Options::default()).unwrap();
    assert_eq!(d.stats["engine"], "incremental");
}
