//! Hostile input (issue 15): the fuzz reproducers of each class end in seconds with a
//! diagram that an independent check accepts, or with an error naming the cause (the
//! site and field, the exhausted budget, the bad option). Scenes in
//! `tests/data/hostile/` are the reproducers as found.

use gvd::verify::{verify, VerifyOptions};
use gvd::{compute, Error, Options, Scene, VoronoiComplex};
use serde_json::Value;
use std::path::Path;
use std::time::Instant;

fn text(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/hostile")
        .join(format!("{name}.json"));
    std::fs::read_to_string(path).unwrap()
}

fn scene(name: &str) -> Scene {
    Scene::from_json(&text(name)).unwrap()
}

/// The scene's refusal by validation.
fn refused(name: &str) -> Error {
    Scene::from_json(&text(name)).expect_err(name)
}

/// The site, field and message of a site refusal.
fn site_error(e: &Error) -> (usize, &str, &str) {
    match e {
        Error::Site {
            site,
            field,
            message,
        } => (*site, field.as_str(), message.as_str()),
        other => panic!("expected a site error, got {other:?}"),
    }
}

/// `compute` with the default options, timed: no reproducer may take long.
fn timed_compute(scene: &Scene, options: &Options) -> Result<VoronoiComplex, Error> {
    let start = Instant::now();
    let out = compute(scene, options);
    let secs = start.elapsed().as_secs_f64();
    assert!(secs < 10.0, "took {secs:.1} s");
    out
}

#[test]
fn identical_circles_and_fields_are_duplicates() {
    for (name, field) in [
        ("H04_two_identical_circles", "center"),
        ("O05_two_identical_fields", "equation"),
    ] {
        let e = refused(name);
        let (site, f, message) = site_error(&e);
        assert_eq!((site, f), (1, field), "{name}: {e}");
        assert!(message.contains("identical to site 0"), "{e}");
    }
    // the same polynomial written otherwise is a duplicate too
    let fields = r#"{"domain": [-2, -2, 2, 2], "sites": [
        {"kind": "field", "equation": "x^2 + y^2"}, {"kind": "point", "at": [1, 1]},
        {"kind": "field", "equation": "y^2+x*x"}]}"#;
    assert_eq!(site_error(&Scene::from_json(fields).unwrap_err()).0, 2);
    let segments = r#"{"domain": [-2, -2, 2, 2], "sites": [
        {"kind": "segment", "from": [0, 0], "to": [1, 0]},
        {"kind": "segment", "from": [0, 0], "to": [1, 0]}]}"#;
    // the same segment twice: the segment engine merges it, the subdivision engine
    // refuses it as a duplicate
    let twice = Scene::from_json(segments).unwrap();
    let merged = compute(&twice, &Options::default()).unwrap();
    assert_eq!(merged.stats["merged_duplicates"], 1);
    let subdivision = Options {
        engine: gvd::Engine::Subdivision,
        ..Default::default()
    };
    let e = compute(&twice, &subdivision).unwrap_err();
    assert!(e.to_string().contains("identical to site 0"), "{e}");
    // equal radii at different centres are not
    let circles = r#"{"domain": [-2, -2, 2, 2], "sites": [
        {"kind": "circle", "center": [0, 0], "radius": 0.5},
        {"kind": "circle", "center": [1.5, 0], "radius": 0.5}]}"#;
    assert!(Scene::from_json(circles).is_ok());
}

#[test]
fn overlapping_ellipses_are_refused_and_disjoint_ones_kept() {
    // W03b: W03 at 1e300, where the centres' squared distance overflows (fuzzing)
    for name in [
        "W03_overlapping_ellipses",
        "W03b_overlapping_ellipses_1e300",
        "H07_ellipse_semi_axis_1e10",
    ] {
        match refused(name) {
            Error::Conflict {
                site: 1, other: 0, ..
            } => {}
            other => panic!("{name}: {other:?}"),
        }
    }
    let ellipses = |second: &str| {
        format!(
            r#"{{"domain": [-2, -2, 2, 2], "sites": [
            {{"kind": "ellipse", "center": [0, 0], "semi_axes": [0.5, 0.2]}}, {second}]}}"#
        )
    };
    // inside the first one, crossing it, and clear of it
    let inside = r#"{"kind": "ellipse", "center": [0.1, 0], "semi_axes": [0.1, 0.05]}"#;
    let crossing = r#"{"kind": "circle", "center": [0.55, 0], "radius": 0.1}"#;
    let clear =
        r#"{"kind": "ellipse", "center": [0, 0.5], "semi_axes": [0.5, 0.2], "rotation": 0.3}"#;
    assert!(Scene::from_json(&ellipses(inside)).is_err());
    assert!(Scene::from_json(&ellipses(crossing)).is_err());
    assert!(Scene::from_json(&ellipses(clear)).is_ok());
}

#[test]
fn numbers_f64_cannot_resolve_are_refused_naming_site_and_field() {
    for (name, site, field) in [
        ("W01_segment_end_at_1e308", 1, "to"),
        ("W07_segment_endpoints_1e300_and_point", 0, "from"),
        ("H03_aniso_point_at_1e308", 1, "at"),
        ("H09_power_weight_1e154", 0, "metric.weight"),
        ("W05_arc_angles_1e17", 0, "start_angle"),
    ] {
        let e = refused(name);
        let (s, f, message) = site_error(&e);
        assert_eq!((s, f), (site, field), "{name}: {e}");
        assert!(message.contains("too large for epsilon"), "{e}");
    }
    // an epsilon far below the domain's ulps: the domain reaching 1e308, and 1e15
    for name in [
        "W08_segments_domain_ymax_1e308",
        "H02_lp4_two_points_domain_1e15",
    ] {
        match refused(name) {
            Error::Scene { field, message } => {
                assert_eq!(field, "epsilon", "{name}");
                assert!(message.contains("far finer than f64 resolves"), "{message}");
            }
            other => panic!("{name}: {other:?}"),
        }
    }
}

#[test]
fn nearly_coincident_points_of_one_metric_are_refused() {
    // one ulp apart, their bisector could lie anywhere in their cell
    let e = refused("H08_lp4_points_1ulp_apart");
    let (site, field, message) = site_error(&e);
    assert_eq!((site, field), (1, "at"), "{e}");
    assert!(message.contains("from site 0 of the same metric"), "{e}");
}

#[test]
fn an_epsilon_near_f64s_floor_runs_out_of_points_not_memory() {
    // 1e-15 is floored to the lattice's resolution (7e-12 here), 1e-12 too: either
    // way the lp4 bisector would need millions of points
    for name in [
        "H01_lp4_two_points_eps1e-15",
        "H01b_lp4_two_points_eps1e-12",
    ] {
        match timed_compute(&scene(name), &Options::default()) {
            Err(Error::Budget { what, message, .. }) => {
                assert_eq!(what, "points");
                assert!(message.contains("polyline points at epsilon"), "{message}");
            }
            other => panic!("{name}: {:?}", other.map(|d| d.edges.len())),
        }
    }
    let sc = scene("H01b_lp4_two_points_eps1e-12");
    // with a coarser epsilon the same scene is computed, at the resolution asked
    let coarse = Scene::new(sc.domain(), 1e-6, sc.mode(), sc.sites().to_vec()).unwrap();
    let d = timed_compute(&coarse, &Options::default()).unwrap();
    assert_eq!(d.edges.len(), 1);
    assert!(!d.stats.contains_key("epsilon_floored_from"));
}

#[test]
fn a_max_box_that_is_not_a_length_or_needs_too_many_boxes_is_refused() {
    let sc = scene("H11_lp4_two_points_for_maxbox0");
    for bad in [0.0, -1.0, f64::NAN] {
        let options = Options {
            subdivision: gvd::SubdivisionOptions {
                max_box: Some(bad),
                ..Default::default()
            },
            ..Default::default()
        };
        match timed_compute(&sc, &options) {
            Err(Error::InvalidOption { option, .. }) => assert_eq!(option, "max_box"),
            other => panic!("{bad}: {:?}", other.map(|d| d.edges.len())),
        }
    }
    let tiny = Options {
        subdivision: gvd::SubdivisionOptions {
            max_box: Some(1e-6),
            ..Default::default()
        },
        ..Default::default()
    };
    assert!(matches!(
        timed_compute(&sc, &tiny),
        Err(Error::Budget { .. })
    ));
}

/// The largest distance from a point of `a`'s edges to `b`'s edges (after scaling `a` by
/// `s`), by brute force over the polylines' segments.
fn one_sided_hausdorff(a: &VoronoiComplex, s: f64, b: &VoronoiComplex) -> f64 {
    let segs: Vec<_> = b
        .edges
        .iter()
        .flat_map(|e| e.points.windows(2).map(|w| (w[0], w[1])))
        .collect();
    a.edges
        .iter()
        .flat_map(|e| e.points.iter())
        .map(|&p| {
            let p = p * s;
            segs.iter()
                .map(|&(u, v)| gvd::geom::segment_distance(p, u, v))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

/// Every number under the scene's geometric keys times `f`.
fn scaled_scene(text: &str, f: f64) -> Scene {
    fn scale_all(v: &mut Value, f: f64) {
        match v {
            Value::Number(n) => *v = Value::from(n.as_f64().unwrap() * f),
            Value::Array(items) => items.iter_mut().for_each(|x| scale_all(x, f)),
            _ => {}
        }
    }
    let mut v: Value = serde_json::from_str(text).unwrap();
    for key in ["domain", "epsilon"] {
        scale_all(&mut v[key], f);
    }
    for site in v["sites"].as_array_mut().unwrap() {
        for key in ["at", "center", "semi_axes", "radius"] {
            if let Some(x) = site.get_mut(key) {
                scale_all(x, f);
            }
        }
    }
    Scene::from_value(&v).unwrap()
}

#[test]
fn scaled_scenes_give_the_unscaled_diagram_scaled() {
    // lp4 points at 1e-150 (their fields would underflow) and ellipses at 1e-300
    for (name, f) in [
        ("H14_lp4_scaled_1e-150", 1e150),
        ("W04_ellipses_scaled_1e-300", 1e300),
    ] {
        let small = scene(name);
        let unit = scaled_scene(&text(name), f);
        let ds = timed_compute(&small, &Options::default()).unwrap();
        let du = timed_compute(&unit, &Options::default()).unwrap();
        assert_eq!(ds.edges.len(), du.edges.len(), "{name}");
        assert_eq!(ds.vertices.len(), du.vertices.len(), "{name}");
        assert!(!ds.edges.is_empty(), "{name}");
        let eps = unit.epsilon();
        let there = one_sided_hausdorff(&ds, f, &du);
        let back = one_sided_hausdorff(&du, 1.0 / f, &ds) * f;
        assert!(
            there <= 2.0 * eps && back <= 2.0 * eps,
            "{name}: {there} {back}"
        );
        // and the independent checker accepts the small diagram in its own coordinates
        let report = verify(&small, &ds, &VerifyOptions::default()).unwrap();
        assert!(report.passed, "{name}: {}", report.summary_line());
    }
}

#[test]
fn mixed_degrees_at_extreme_scale_are_refused_not_rescaled() {
    // lp4 (degree 4) beside a Euclidean point (degree 1) at 1e-300: scaling would change
    // the diagram, and the lp4 field underflows
    let e = timed_compute(
        &scene("H15_mixed_points_scaled_1e-300"),
        &Options::default(),
    )
    .unwrap_err();
    let (site, field, message) = site_error(&e);
    assert_eq!((site, field), (0, "kind"));
    assert!(message.contains("underflow"), "{message}");
}

#[test]
fn round_ellipses_are_computed_as_circles() {
    let sc = scene("H06_two_round_ellipses");
    let d = timed_compute(&sc, &Options::default()).unwrap();
    assert_eq!(d.edges.len(), 1);
    let report = verify(&sc, &d, &VerifyOptions::default()).unwrap();
    assert!(report.passed, "{}", report.summary_line());
}

#[test]
fn a_polynomial_f64_cannot_evaluate_is_refused() {
    let e = timed_compute(&scene("H10_field_degree64"), &Options::default()).unwrap_err();
    let (site, field, message) = site_error(&e);
    assert_eq!((site, field), (0, "equation"));
    assert!(message.contains("coarser than epsilon"), "{message}");
}

#[test]
fn medial_axis_without_a_closed_site_is_refused() {
    let points = r#"{"domain": [-2, -2, 2, 2], "mode": "medial_axis", "sites": [
        {"kind": "point", "at": [0, 0]}, {"kind": "point", "at": [1, 0]}]}"#;
    match compute(&Scene::from_json(points).unwrap(), &Options::default()) {
        Err(Error::Scene { field, message }) => {
            assert_eq!(field, "mode");
            assert!(message.contains("no"), "{message}");
        }
        other => panic!("{:?}", other.map(|d| d.edges.len())),
    }
}

#[test]
fn verify_refuses_absurd_grids_and_bounds_its_samples() {
    let sc = scene("V03_polylines_eps1e-9_scene");
    let d = timed_compute(&sc, &Options::default()).unwrap();
    for grid in [0, 1, usize::MAX, 1 << 32, 100_000] {
        let opts = VerifyOptions {
            grid,
            ..Default::default()
        };
        assert!(
            matches!(verify(&sc, &d, &opts), Err(Error::InvalidOption { .. })),
            "{grid}"
        );
    }
    let nan_slack = VerifyOptions {
        slack: f64::NAN,
        ..Default::default()
    };
    assert!(verify(&sc, &d, &nan_slack).is_err());
    // at epsilon 1e-9 the edges would need some 10^10 samples: a verdict in bounded work
    let start = Instant::now();
    let report = verify(&sc, &d, &VerifyOptions::default()).unwrap();
    assert!(start.elapsed().as_secs_f64() < 10.0);
    assert!(
        report
            .warnings
            .iter()
            .any(|w| w.contains("not every eps/2")),
        "{:?}",
        report.warnings
    );
}
