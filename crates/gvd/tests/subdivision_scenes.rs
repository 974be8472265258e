//! Point and field scenes through the subdivision engine, each checked by the library's
//! independent brute-force checker (`gvd::verify`), and the parallel run against the
//! sequential one.

use gvd::verify::{verify, VerifyOptions};
use gvd::{compute, Engine, Options, Scene};
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/scenes")
        .join(name);
    Scene::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

fn check(name: &str, reference: &str) {
    let opts = Options {
        engine: Engine::Subdivision,
        ..Default::default()
    };
    let d = compute(&scene(name), &opts).unwrap();
    d.check_invariants().unwrap();
    let opts = VerifyOptions {
        grid: 256,
        ..Default::default()
    };
    let report = verify(&scene(reference), &d, &opts).unwrap();
    assert!(
        report.passed,
        "{name}: {}\n{}",
        report.summary_line(),
        report.problems.join("\n")
    );
}

#[test]
fn anisotropic_points() {
    check(
        "points-anisotropic-0050.json",
        "points-anisotropic-0050.json",
    );
}

#[test]
fn lp4_and_lp8_points() {
    check("points-lp4-0050.json", "points-lp4-0050.json");
    check("points-lp8-0050.json", "points-lp8-0050.json");
}

#[test]
fn mixed_metrics() {
    check("points-mixed-0030.json", "points-mixed-0030.json");
}

#[test]
fn moebius_and_power() {
    check("points-moebius-0100.json", "points-moebius-0100.json");
    check("points-power-0200.json", "points-power-0200.json");
}

#[test]
fn degenerate_inputs() {
    check("degenerate-grid-4x4.json", "degenerate-grid-4x4.json");
    check(
        "degenerate-cocircular-12-center.json",
        "degenerate-cocircular-12-center.json",
    );
    check(
        "degenerate-collinear-20.json",
        "degenerate-collinear-20.json",
    );
}

#[test]
fn field_scenes_match_their_sources() {
    check("field-euclidean-0100.json", "points-euclidean-0100.json");
    check("field-lp4-0050.json", "points-lp4-0050.json");
}

#[test]
fn parallel_and_sequential_runs_agree() {
    for name in [
        "points-anisotropic-0050.json",
        "points-euclidean-0200.json",
        "degenerate-grid-4x4.json",
    ] {
        let sc = scene(name);
        let mut a = compute(
            &sc,
            &Options {
                engine: Engine::Subdivision,
                parallel: true,
                ..Default::default()
            },
        )
        .unwrap();
        let mut b = compute(
            &sc,
            &Options {
                engine: Engine::Subdivision,
                parallel: false,
                ..Default::default()
            },
        )
        .unwrap();
        a.stats.clear();
        b.stats.clear();
        assert_eq!(a, b, "{name}");
    }
}

#[test]
fn epsilon_below_f64_resolution_is_floored_not_hung() {
    // coordinates near 1e6 resolve about 1e-10: epsilon 1e-9 would ask for boxes of a
    // few ulps; the engine floors the resolution (and says so in stats) instead
    let sc = Scene::from_json(
        r#"{"domain": [1e6, 1e6, 1.000004e6, 1.000004e6], "epsilon": 1e-9, "sites": [
            {"kind": "point", "at": [1000001.0, 1000001.0], "metric": {"kind": "anisotropic", "matrix": [[2, 0.1], [0.1, 1]]}},
            {"kind": "point", "at": [1000003.0, 1000002.5], "metric": {"kind": "lp", "p": 4}},
            {"kind": "point", "at": [1000002.0, 1000003.5]}]}"#,
    )
    .unwrap();
    let d = compute(&sc, &Options::default()).unwrap();
    d.check_invariants().unwrap();
    assert!(d.stats["resolution"].as_f64().unwrap() > 1e-9);
    let coarse = Scene::new(sc.domain(), 1e-4, sc.mode(), sc.sites().to_vec()).unwrap();
    let report = verify(
        &coarse,
        &d,
        &VerifyOptions {
            grid: 256,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(report.passed, "{}", report.summary_line());
}

/// Whether a polyline goes out and comes back along itself (its `i`-th point from
/// either end agree within `tol`).
fn retraces(points: &[gvd::Point], tol: f64) -> bool {
    let n = points.len();
    (0..n / 2).all(|i| points[i].dist(points[n - 1 - i]) <= tol)
}

/// No edge goes out from a point and back along itself: four mutually tangent circles
/// (Shou et al.'s fourth example) once gave eight such spikes beside the four edges of
/// the centre (uncertified boxes at the tangencies linked a piece to its own return),
/// and 800 anisotropic points gave one.
#[test]
fn no_edge_retraces_itself() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/algebraic/shou-ex4-four-circles.json");
    let tangent = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    for (what, s) in [
        ("four tangent circles", tangent),
        (
            "800 anisotropic points",
            scene("points-anisotropic-0800.json"),
        ),
    ] {
        let d = compute(&s, &Options::default()).unwrap();
        for e in &d.edges {
            assert!(
                !(e.from == e.to && retraces(&e.points, s.epsilon())),
                "{what}: edge {:?} from {:?} retraces itself: {:?}",
                e.sites,
                e.from,
                e.points
            );
        }
        let report = verify(&s, &d, &VerifyOptions::default()).unwrap();
        assert!(report.passed, "{what}: {}", report.summary_line());
    }
}
