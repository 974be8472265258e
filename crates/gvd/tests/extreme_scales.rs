//! Scenes of segments, arcs and polygons scaled towards the ends of f64's range: the
//! incremental engine computes them (at an exact power-of-two scale near 1), polygon
//! validation keeps its exact answers, and `gvd verify` passes the result with the same
//! numbers of vertices and edges as at scale 1.

use gvd::verify::{verify, VerifyOptions};
use gvd::{Engine, Options, Scene};
use serde_json::Value;
use std::path::Path;

fn scene_value(name: &str) -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/scenes")
        .join(name);
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Every coordinate and length of the scene times `f`.
fn scaled(v: &Value, f: f64) -> Scene {
    fn scale_all(v: &mut Value, f: f64) {
        match v {
            Value::Number(n) => *v = Value::from(n.as_f64().unwrap() * f),
            Value::Array(items) => items.iter_mut().for_each(|x| scale_all(x, f)),
            _ => {}
        }
    }
    let mut v = v.clone();
    for key in ["domain", "epsilon"] {
        if let Some(x) = v.get_mut(key) {
            scale_all(x, f);
        }
    }
    for site in v["sites"].as_array_mut().unwrap() {
        for key in ["at", "from", "to", "center", "radius", "points", "rings"] {
            if let Some(x) = site.get_mut(key) {
                scale_all(x, f);
            }
        }
    }
    Scene::from_value(&v).unwrap()
}

#[test]
fn far_scales_compute_and_verify() {
    let options = Options {
        engine: Engine::Incremental,
        ..Default::default()
    };
    for name in [
        "segments-0200.json",
        "arcs-0030-points-0020.json",
        "polygon-bugtrap-medial_axis.json",
        "polygon-holes2-complex.json",
    ] {
        let v = scene_value(name);
        let base = gvd::compute(&scaled(&v, 1.0), &options).unwrap();
        for f in [1e300, 1e-300, 2f64.powi(700), 1e-200] {
            let s = scaled(&v, f);
            let d =
                gvd::compute(&s, &options).unwrap_or_else(|e| panic!("{name} at scale {f:e}: {e}"));
            assert_eq!(
                (d.vertices.len(), d.edges.len()),
                (base.vertices.len(), base.edges.len()),
                "{name} at scale {f:e}"
            );
            let report = verify(&s, &d, &VerifyOptions::default()).unwrap();
            assert!(
                report.passed,
                "{name} at scale {f:e}: {}",
                report.summary_line()
            );
        }
    }
}

/// A vertex moved off its place at scale 1e300 and 1e-300: `gvd verify` fails the
/// diagram and names the vertex where it is, in the scene's own coordinates.
#[test]
fn far_scale_problems_are_located_in_scene_coordinates() {
    let options = Options {
        engine: Engine::Incremental,
        ..Default::default()
    };
    let v = scene_value("segments-0200.json");
    for f in [1e300, 1e-300] {
        let s = scaled(&v, f);
        let mut d = gvd::compute(&s, &options).unwrap();
        let (x, y) = (0.31234 * f, 0.61234 * f);
        d.vertices[0].at = gvd::geom::Point::new(x, y);
        let report = verify(&s, &d, &VerifyOptions::default()).unwrap();
        assert!(!report.passed, "scale {f:e}");
        let place = format!("({x:.5e}, {y:.5e})");
        assert!(
            report.problems.iter().any(|p| p.contains(&place)),
            "scale {f:e}: {place} not in {:#?}",
            report.problems
        );
    }
}
