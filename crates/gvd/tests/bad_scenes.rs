//! Scene refusals (the bad corpus of `shared/corpus/bad/README.md`), acceptance of the
//! corpus scenes, and robustness of the parser on random and mutated JSON.

use gvd::{Error, Scene};
use proptest::prelude::*;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

fn data(dir: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(dir)
}

fn parse_file(path: &Path) -> Result<Scene, Error> {
    Scene::from_json(&std::fs::read_to_string(path).expect("readable file"))
}

/// The `.json` files of `dir`, sorted.
fn json_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("readable directory")
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    files
}

/// The table of `shared/corpus/bad/README.md`, then this project's additions: file,
/// site index, field (`None`, `None` for text that is not JSON).
const BAD: &[(&str, Option<usize>, Option<&str>)] = &[
    ("invalid-json.json", None, None),
    ("missing-domain.json", None, Some("domain")),
    ("inverted-domain.json", None, Some("domain")),
    ("nan-string.json", Some(1), Some("at")),
    ("nan-literal.json", None, None),
    ("negative-epsilon.json", None, Some("epsilon")),
    ("zero-epsilon.json", None, Some("epsilon")),
    ("zero-length-segment.json", Some(1), Some("to")),
    ("polygon-ring-2-points.json", Some(0), Some("rings")),
    ("polygon-self-intersecting.json", Some(0), Some("rings")),
    ("anisotropic-not-spd.json", Some(1), Some("metric.matrix")),
    ("lp-odd-p.json", Some(0), Some("metric.p")),
    ("algebraic-unparsable.json", Some(0), Some("equation")),
    ("bspline-bad-knots.json", Some(0), Some("knots")),
    ("unknown-kind.json", Some(1), Some("kind")),
    ("duplicate-points.json", Some(2), Some("at")),
    // a square inside another, and a copy of a square with one corner moved an ulp in
    ("polygons-nested.json", Some(1), Some("rings")),
    ("polygons-corner-moved-ulp.json", Some(1), Some("rings")),
];

#[test]
fn bad_scenes_are_refused_naming_site_and_field() {
    for &(file, site, field) in BAD {
        let err = parse_file(&data("bad").join(file)).expect_err(file);
        let got = match &err {
            Error::Json(_) => (None, None),
            Error::Scene { field, .. } => (None, Some(field.as_str())),
            Error::Site { site, field, .. } => (Some(*site), Some(field.as_str())),
            e => panic!("{file}: unexpected refusal: {e}"),
        };
        assert_eq!(got, (site, field), "{file}: {err}");
    }
}

#[test]
fn bad_table_covers_every_bad_file() {
    let files: Vec<String> = json_files(&data("bad"))
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    let mut listed: Vec<String> = BAD.iter().map(|(f, ..)| f.to_string()).collect();
    listed.sort();
    assert_eq!(files, listed);
}

#[test]
fn bad_scene_messages() {
    let message = |file: &str| parse_file(&data("bad").join(file)).unwrap_err().to_string();
    for (file, text) in [
        (
            "anisotropic-not-spd.json",
            "site 1 field 'metric.matrix': not positive-definite (eigenvalues 3 and -1)",
        ),
        (
            "bspline-bad-knots.json",
            "site 0 field 'knots': 8 knots, but degree 3 with 5 control points needs 9",
        ),
        (
            "duplicate-points.json",
            "site 2 field 'at': duplicate of site 0",
        ),
        (
            "zero-length-segment.json",
            "site 1 field 'to': zero-length segment (from == to)",
        ),
        (
            "polygon-ring-2-points.json",
            "site 0 field 'rings': ring 0 has fewer than 3 distinct points",
        ),
        (
            "unknown-kind.json",
            "site 1 field 'kind': unknown kind 'hexagon'",
        ),
        (
            "lp-odd-p.json",
            "site 0 field 'metric.p': p must be an even integer >= 2, found 3",
        ),
        ("polygon-self-intersecting.json", "self-intersecting"),
        ("nan-string.json", "the string \"NaN\""),
        ("algebraic-unparsable.json", "does not parse"),
        ("missing-domain.json", "field 'domain'"),
        ("inverted-domain.json", "inverted"),
        ("zero-epsilon.json", "epsilon must be > 0"),
        (
            "polygons-nested.json",
            "site 1 field 'rings': its inside overlaps that of polygon site 0: point 0 of ring 0 lies inside polygon site 0",
        ),
        (
            "polygons-corner-moved-ulp.json",
            "site 1 field 'rings': its inside overlaps that of polygon site 0: edge 0 of ring 0 lies along edge 0 of ring 0 of polygon site 0, both insides on one side",
        ),
    ] {
        let m = message(file);
        assert!(m.contains(text), "{file}: {m}");
    }
}

#[test]
fn project_scenes_parse() {
    let files = json_files(&data("scenes"));
    assert!(files.len() >= 19, "only {} scenes", files.len());
    for path in files {
        let scene = parse_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(!scene.sites().is_empty(), "{}", path.display());
        assert!(scene.epsilon() > 0.0);
    }
}

/// Every scene of the shared corpus parses (skipped when the corpus is not there).
#[test]
fn shared_corpus_parses() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    if !dir.is_dir() {
        return;
    }
    let failures: Vec<String> = json_files(&dir)
        .iter()
        .filter_map(|p| parse_file(p).err().map(|e| format!("{}: {e}", p.display())))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A valid scene with one site of every kind.
fn every_kind() -> Value {
    json!({"domain": [-2, -2, 2, 2], "epsilon": 0.01, "mode": "complex", "sites": [
        {"kind": "point", "at": [0.5, 1], "metric": {"kind": "anisotropic", "matrix": [[2, 1], [1, 2]], "weight": 0.1}},
        {"kind": "point", "at": [0.7, 1], "metric": {"kind": "moebius", "scale": 2, "weight": 0.1}},
        {"kind": "circle", "center": [1, 1], "radius": 0.2},
        {"kind": "ellipse", "center": [1, -1], "semi_axes": [0.2, 0.1], "rotation": 0.3},
        {"kind": "segment", "from": [0, 0], "to": [1, 0]},
        {"kind": "arc", "center": [0, 0], "radius": 1, "start_angle": 0, "end_angle": 3},
        {"kind": "polyline", "points": [[0, 0], [1, 0], [1, 1]]},
        {"kind": "polygon", "rings": [[[-2, -2], [-1, -2], [-1, -1], [-2, -1]], [[-1.8, -1.8], [-1.5, -1.8], [-1.5, -1.5]]]},
        {"kind": "algebraic", "equation": "x^2 + y^2 - 1", "clip": [-1, -1, 1, 1]},
        {"kind": "bezier", "control_points": [[0, 0], [1, 1], [2, 0]], "weights": [1, 2, 1]},
        {"kind": "bspline", "degree": 2, "control_points": [[0, 0], [1, 1], [2, 0]],
         "knots": [0, 0, 0, 1, 1, 1], "weights": [1, 1, 1], "closed": false, "id": "s"},
        {"kind": "field", "equation": "x^2 + y^2"},
        {"kind": "implicit_field", "equation": "x^2 + y^2 - (z + 0.5)^2"}
    ]})
}

const FIELDS: &[&str] = &[
    "kind",
    "at",
    "metric",
    "center",
    "radius",
    "semi_axes",
    "rotation",
    "from",
    "to",
    "start_angle",
    "end_angle",
    "points",
    "rings",
    "equation",
    "clip",
    "control_points",
    "weights",
    "degree",
    "knots",
    "closed",
    "id",
];

fn arb_json() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        any::<i64>().prop_map(Value::from),
        (-4.0f64..4.0).prop_map(Value::from),
        any::<f64>().prop_map(Value::from),
        Just(json!("NaN")),
        "[a-z0-9 ^*+()-.]{0,12}".prop_map(Value::String),
    ];
    leaf.prop_recursive(4, 48, 6, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..6).prop_map(Value::Array),
            prop::collection::vec(inner.clone(), 2..=2).prop_map(Value::Array),
            prop::collection::vec((prop::sample::select(FIELDS), inner), 0..5).prop_map(|kv| {
                Value::Object(kv.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
            }),
        ]
    })
}

#[test]
fn every_kind_scene_is_valid() {
    let scene = Scene::from_value(&every_kind()).unwrap();
    assert_eq!(scene.sites().len(), 13);
}

#[test]
fn a_closed_bspline_whose_ends_do_not_meet_is_refused() {
    // The free-form engine took the flag on trust: a loop joined by an edge that is
    // not there. At 1e300 the ends' distance and the first end's norm both overflowed
    // to infinity in the test of whether ends meet, and any two ends met.
    let scene = |scale: f64, last: [f64; 2], closed: bool| {
        let cps: Vec<[f64; 2]> = [[1.0, 1.0], [2.0, 2.0], [3.0, 1.0], [2.0, 0.0], last]
            .iter()
            .map(|p| [p[0] * scale, p[1] * scale])
            .collect();
        Scene::from_value(
            &json!({"domain": [-4.0 * scale, -4.0 * scale, 4.0 * scale, 4.0 * scale],
            "epsilon": 0.01 * scale, "sites": [
            {"kind": "point", "at": [3.0 * scale, 3.0 * scale]},
            {"kind": "bspline", "degree": 2, "control_points": cps,
             "knots": [0, 0, 0, 1, 2, 3, 3, 3], "closed": closed}]}),
        )
    };
    for scale in [1.0, 1e300] {
        let err = scene(scale, [1.5, 1.0], true).unwrap_err();
        match &err {
            Error::Site { site: 1, field, .. } if field == "closed" => {}
            e => panic!("at {scale}: {e}"),
        }
        let m = err.to_string();
        assert!(
            m.contains("site 1 field 'closed': the curve is marked closed, but its ends"),
            "{m}"
        );
        // the same curve open, or closed with its ends meeting, is kept
        assert!(scene(scale, [1.5, 1.0], false).is_ok());
        assert!(scene(scale, [1.0, 1.0], true).is_ok());
    }
}

proptest! {
    #[test]
    fn random_json_never_panics(v in arb_json()) {
        let _ = Scene::from_value(&v);
        let _ = Scene::from_json(&v.to_string());
    }

    /// Replacing one field of one valid site by a random value is accepted or refused
    /// naming that site, never a panic.
    #[test]
    fn mutated_site_never_panics(
        site in 0usize..13,
        field in prop::sample::select(FIELDS),
        value in arb_json(),
    ) {
        let mut v = every_kind();
        v["sites"][site][field] = value;
        match Scene::from_value(&v) {
            Ok(_) => {}
            Err(Error::Site { site: s, .. }) => prop_assert_eq!(s, site),
            // a site grown or moved into another: both are named, the mutated one among them
            Err(Error::Conflict { site: s, other, .. }) => {
                prop_assert!(s == site || other == site, "sites {} and {}, mutated {}", s, other, site)
            }
            Err(e) => prop_assert!(false, "unexpected refusal {}", e),
        }
    }

    /// Replacing a scene-level field is accepted or refused naming that field.
    #[test]
    fn mutated_scene_never_panics(
        field in prop::sample::select(&["domain", "epsilon", "mode", "sites"][..]),
        value in arb_json(),
    ) {
        let mut v = every_kind();
        v[field] = value;
        match Scene::from_value(&v) {
            Ok(_) | Err(Error::Site { .. }) => {}
            Err(Error::Scene { field: f, .. }) => prop_assert_eq!(f.as_str(), field),
            Err(e) => prop_assert!(false, "unexpected refusal {}", e),
        }
    }

    /// Random polygons never panic the ring checks.
    #[test]
    fn random_polygons_never_panic(
        rings in prop::collection::vec(
            prop::collection::vec((-3i32..3, -3i32..3), 0..8), 0..4),
    ) {
        let rings: Vec<Vec<[f64; 2]>> = rings
            .into_iter()
            .map(|r| r.into_iter().map(|(x, y)| [f64::from(x), f64::from(y)]).collect())
            .collect();
        let v = json!({"domain": [-4, -4, 4, 4], "sites": [{"kind": "polygon", "rings": rings}]});
        if let Err(e) = Scene::from_value(&v) {
            prop_assert!(matches!(e, Error::Site { site: 0, ref field, .. } if field == "rings"), "{}", e);
        }
    }
}
