//! Results of `scripts/fuzz_mutate.py` that failed `gvd verify` (docs/FUZZING.md): each
//! scene in `tests/data/fuzz/` now gives a diagram that verify passes, or a clear error.

use gvd::verify::{verify, VerifyOptions};
use gvd::{compute, Engine, Error, Options, Scene};
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/fuzz")
        .join(format!("{name}.json"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn grid64() -> VerifyOptions {
    VerifyOptions {
        grid: 64,
        ..Default::default()
    }
}

#[test]
fn a_fine_arc_bisector_is_drawn_whole_or_refused_never_cut_to_chords() {
    // The conic between an arc and a point inside needs some 130,000 points at epsilon
    // 1e-9: it was cut to chords after 100,000 (an error of 0.02); at 1e-12 it needs
    // more than the points budget.
    let sc = scene("arc-span-4-point-inside-eps1e-9");
    let options = Options {
        engine: Engine::Incremental,
        ..Default::default()
    };
    let d = compute(&sc, &options).unwrap();
    let report = verify(&sc, &d, &grid64()).unwrap();
    assert!(report.passed, "{}", report.summary_line());
    let finer = Scene::new(sc.domain(), 1e-12, sc.mode(), sc.sites().to_vec()).unwrap();
    match compute(&finer, &options) {
        Err(Error::Budget { what, .. }) => assert_eq!(what, "points"),
        other => panic!("{:?}", other.map(|d| d.edges.len())),
    }
}
