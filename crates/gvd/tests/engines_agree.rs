//! The two algorithm families on the inputs they share: Euclidean point scenes through
//! the incremental engine and the subdivision engine give the same vertices (same
//! generators, within epsilon) and the same adjacent pairs.

use gvd::{compute, Engine, Options, Scene, VoronoiComplex};
use std::collections::BTreeSet;
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/scenes")
        .join(name);
    Scene::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

fn run(sc: &Scene, engine: Engine) -> VoronoiComplex {
    let d = compute(
        sc,
        &Options {
            engine,
            ..Default::default()
        },
    )
    .unwrap();
    d.check_invariants().unwrap();
    assert_eq!(
        d.stats["engine"],
        match engine {
            Engine::Incremental => "incremental",
            _ => "subdivision",
        }
    );
    d
}

fn generators(d: &VoronoiComplex) -> Vec<(gvd::geom::Point, Vec<usize>)> {
    d.vertices
        .iter()
        .map(|v| {
            let mut s: Vec<usize> = v.sites.iter().map(|g| g.site()).collect();
            s.sort_unstable();
            (v.at, s)
        })
        .collect()
}

fn pairs(d: &VoronoiComplex) -> BTreeSet<[usize; 2]> {
    d.edges
        .iter()
        .map(|e| {
            let (a, b) = (e.sites[0].site(), e.sites[1].site());
            [a.min(b), a.max(b)]
        })
        .collect()
}

#[test]
fn incremental_and_subdivision_agree_on_point_scenes() {
    for name in [
        "points-euclidean-0050.json",
        "points-euclidean-0200.json",
        "degenerate-grid-4x4.json",
        "degenerate-cocircular-12-center.json",
        "degenerate-collinear-20.json",
    ] {
        let sc = scene(name);
        let inc = run(&sc, Engine::Incremental);
        let sub = run(&sc, Engine::Subdivision);
        let eps = sc.epsilon();
        let (vi, vs) = (generators(&inc), generators(&sub));
        // vertices within epsilon of the boundary may be cut differently: compare inside
        let inner = |p: gvd::geom::Point| {
            p.x - sc.domain().min.x > eps
                && sc.domain().max.x - p.x > eps
                && p.y - sc.domain().min.y > eps
                && sc.domain().max.y - p.y > eps
        };
        for (p, s) in vi.iter().filter(|(p, _)| inner(*p)) {
            assert!(
                vs.iter().any(|(q, t)| t == s && q.dist(*p) <= eps),
                "{name}: incremental vertex {s:?} at {p:?} missing from the subdivision"
            );
        }
        for (p, s) in vs.iter().filter(|(p, _)| inner(*p)) {
            assert!(
                vi.iter().any(|(q, t)| t == s && q.dist(*p) <= eps),
                "{name}: subdivision vertex {s:?} at {p:?} missing from the incremental"
            );
        }
        assert_eq!(pairs(&inc), pairs(&sub), "{name}: adjacent pairs differ");
    }
}

#[test]
fn incremental_engine_refuses_other_sites_by_name() {
    let sc = scene("points-anisotropic-0050.json");
    let err = compute(
        &sc,
        &Options {
            engine: Engine::Incremental,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(err.to_string().contains("site 0"), "{err}");
}

#[test]
fn empty_and_single_site_scenes_on_both_engines() {
    for sites in ["[]", r#"[{"kind": "point", "at": [0.5, 0.5]}]"#] {
        let sc =
            Scene::from_json(&format!(r#"{{"domain": [0, 0, 1, 1], "sites": {sites}}}"#)).unwrap();
        for engine in [Engine::Incremental, Engine::Subdivision] {
            let d = run(&sc, engine);
            assert!(d.vertices.is_empty() && d.edges.is_empty());
            assert_eq!(d.cells.len(), sc.sites().len());
        }
    }
}
