//! Pruning of the medial axis (λ-medial axis and object angle) against brute force: the
//! nearest boundary points of every kept and every removed point, computed here from
//! the polygons' edges; and the notch test: a rectangle with one tiny notch, pruned,
//! is the plain rectangle pruned.

use gvd::complex::VoronoiComplex;
use gvd::geom::{Aabb, Point};
use gvd::scene::{Mode, Site, SiteKind};
use gvd::{compute, Error, Options, Pruning, Scene};

fn scene(name: &str) -> Scene {
    let path = format!("{}/tests/data/scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn pruned(sc: &Scene, pruning: Pruning) -> Result<VoronoiComplex, Error> {
    compute(
        sc,
        &Options {
            prune: pruning,
            ..Default::default()
        },
    )
}

fn lambda(l: f64) -> Pruning {
    Pruning {
        lambda: Some(l),
        object_angle: None,
    }
}

fn angle_degrees(t: f64) -> Pruning {
    Pruning {
        lambda: None,
        object_angle: Some(t.to_radians()),
    }
}

/// A 4×2 rectangle, with a 0.1×0.1 slot cut into its bottom side at x = 2 if `notch`.
fn rectangle(notch: bool) -> Scene {
    let mut ring = vec![[0.0, 0.0]];
    if notch {
        ring.extend([[1.95, 0.0], [1.95, -0.1], [2.05, -0.1], [2.05, 0.0]]);
    }
    ring.extend([[4.0, 0.0], [4.0, 2.0], [0.0, 2.0]]);
    Scene::new(
        Aabb::from_array([-1.0, -1.0, 5.0, 3.0]),
        1e-3,
        Mode::MedialAxis,
        vec![Site::polygon([ring])],
    )
    .unwrap()
}

/// The nearest points of the polygons' boundaries to `q`: every edge's foot within
/// 1e-9 of the least distance, repeats (a corner shared by two edges) once.
fn brute_feet(sc: &Scene, q: Point) -> Vec<Point> {
    let mut feet: Vec<(f64, Point)> = Vec::new();
    for site in sc.sites() {
        let SiteKind::Polygon { rings } = &site.kind else {
            panic!("polygon scenes only")
        };
        for ring in rings {
            for k in 0..ring.len() {
                let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
                let d = b - a;
                let t = ((q - a).dot(d) / d.dot(d)).clamp(0.0, 1.0);
                let f = a + d * t;
                feet.push((q.dist(f), f));
            }
        }
    }
    let least = feet.iter().map(|f| f.0).fold(f64::INFINITY, f64::min);
    let mut nearest: Vec<Point> = Vec::new();
    for (r, f) in feet {
        if r <= least + 1e-9 && nearest.iter().all(|g| g.dist(f) > 1e-9) {
            nearest.push(f);
        }
    }
    nearest
}

/// Every edge point of `d`, with the vertices' positions.
fn all_points(d: &VoronoiComplex) -> Vec<Point> {
    let mut pts: Vec<Point> = d.vertices.iter().map(|v| v.at).collect();
    pts.extend(d.edges.iter().flat_map(|e| e.points.iter().copied()));
    pts
}

/// The distance from `q` to the polylines of `d`.
fn distance_to(d: &VoronoiComplex, q: Point) -> f64 {
    let mut best = f64::INFINITY;
    for e in &d.edges {
        for w in e.points.windows(2) {
            let dd = w[1] - w[0];
            let t = if dd.dot(dd) > 0.0 {
                ((q - w[0]).dot(dd) / dd.dot(dd)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            best = best.min(q.dist(w[0] + dd * t));
        }
    }
    best
}

/// Checks the graph: edge ends exist and list the generators (`check_invariants`),
/// every vertex ends an edge, none has degree two (a loop counts twice).
fn assert_mended(d: &VoronoiComplex, what: &str) {
    d.check_invariants()
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    let mut degree = vec![0; d.vertices.len()];
    for e in &d.edges {
        for v in [e.from, e.to].into_iter().flatten() {
            degree[v] += 1;
        }
        assert!(
            e.points.len() >= 2,
            "{what}: an edge of fewer than two points"
        );
    }
    for (v, &n) in degree.iter().enumerate() {
        assert!(n != 0 && n != 2, "{what}: vertex {v} has degree {n}");
    }
}

/// Pruning at λ keeps exactly the points whose two nearest boundary points are at least
/// 2λ apart: every kept edge point passes (brute force), every point of the unpruned
/// axis farther than 2ε from the kept set fails.
#[test]
fn lambda_medial_axis_keeps_exactly_the_wide_points() {
    for (sc, name, l) in [
        (rectangle(true), "notched rectangle", 0.1),
        (scene("polygon-bugtrap-medial_axis.json"), "bugtrap", 0.05),
        (scene("polygon-holes2-medial_axis.json"), "holes2", 0.05),
        (scene("polygon-star50-medial_axis.json"), "star50", 0.02),
    ] {
        let eps = sc.epsilon();
        let full = pruned(&sc, Pruning::default()).unwrap();
        let kept = pruned(&sc, lambda(l)).unwrap();
        assert_mended(&kept, name);
        let half_gap = |q: Point| {
            let feet = brute_feet(&sc, q);
            (feet.len() == 2).then(|| feet[0].dist(feet[1]) / 2.0)
        };
        let mut checked = 0;
        for e in &kept.edges {
            // the points, and the middles of straight steps (on the bisector too)
            let middles = e.points.windows(2).map(|w| w[0].lerp(w[1], 0.5));
            let on_bisector = e
                .points
                .iter()
                .copied()
                .chain(middles.take_while(|_| e.points.len() == 2));
            for q in on_bisector {
                if let Some(r) = half_gap(q) {
                    assert!(r >= l - eps, "{name}: kept {q:?} with half gap {r} < {l}");
                    checked += 1;
                }
            }
        }
        let mut removed = 0;
        for q in all_points(&full) {
            if distance_to(&kept, q) > 2.0 * eps {
                if let Some(r) = half_gap(q) {
                    assert!(
                        r <= l + eps,
                        "{name}: removed {q:?} with half gap {r} > {l}"
                    );
                    removed += 1;
                }
            }
        }
        assert!(
            checked >= 8 && removed > 0,
            "{name}: {checked} kept, {removed} removed"
        );
    }
}

/// On a rectangle with one tiny notch, pruning removes exactly the notch's branches:
/// the pruned notched rectangle has the plain rectangle's pruned axis (same counts,
/// within 0.01), though unpruned it has more edges.
#[test]
fn pruning_removes_exactly_a_notchs_branches() {
    let plain = pruned(&rectangle(false), lambda(0.1)).unwrap();
    let notched = pruned(&rectangle(true), lambda(0.1)).unwrap();
    let unpruned = pruned(&rectangle(true), Pruning::default()).unwrap();
    let plain_unpruned = pruned(&rectangle(false), Pruning::default()).unwrap();
    assert!(unpruned.edges.len() > plain_unpruned.edges.len());
    assert!(
        unpruned
            .edges
            .iter()
            .flat_map(|e| &e.points)
            .any(|q| q.y < 0.0),
        "the unpruned axis enters the slot"
    );
    assert_eq!(
        (notched.vertices.len(), notched.edges.len()),
        (plain.vertices.len(), plain.edges.len())
    );
    assert_eq!((plain.vertices.len(), plain.edges.len()), (6, 5));
    for q in all_points(&notched) {
        assert!(
            distance_to(&plain, q) < 0.01,
            "{q:?} is not on the plain axis"
        );
    }
    for q in all_points(&plain) {
        assert!(distance_to(&notched, q) < 0.01, "{q:?} is missing");
    }
}

/// The object angle: the corner branches of a rectangle subtend 90° and the middle line
/// 180°, so 100° keeps the middle line alone and 80° everything but the corners; every
/// kept point's nearest boundary points subtend at least the angle (brute force).
#[test]
fn object_angle_keeps_the_wide_angles() {
    let sc = rectangle(false);
    let middle = pruned(&sc, angle_degrees(100.0)).unwrap();
    assert_mended(&middle, "100°");
    assert_eq!((middle.vertices.len(), middle.edges.len()), (2, 1));
    let ends: Vec<Point> = middle.vertices.iter().map(|v| v.at).collect();
    for want in [Point::new(1.0, 1.0), Point::new(3.0, 1.0)] {
        assert!(
            ends.iter().any(|v| v.dist(want) < 1e-9),
            "{want:?} in {ends:?}"
        );
    }
    let most = pruned(&sc, angle_degrees(80.0)).unwrap();
    assert_mended(&most, "80°");
    assert_eq!((most.vertices.len(), most.edges.len()), (6, 5));
    for name in [
        "polygon-bugtrap-medial_axis.json",
        "polygon-holes2-medial_axis.json",
    ] {
        let sc = scene(name);
        let kept = pruned(&sc, angle_degrees(60.0)).unwrap();
        assert_mended(&kept, name);
        for q in kept
            .edges
            .iter()
            .flat_map(|e| &e.points[1..e.points.len() - 1])
        {
            let feet = brute_feet(&sc, *q);
            if let [f1, f2] = feet[..] {
                let (a, b) = (f1 - *q, f2 - *q);
                let angle = a.cross(b).atan2(a.dot(b)).abs().to_degrees();
                assert!(angle >= 60.0 - 1e-3, "{name}: {q:?} subtends {angle}°");
            }
        }
    }
}

/// Pruning keeps the clearances right (new cut points included), leaves the cells and
/// the largest inscribed circle alone, and a larger λ keeps a subset.
#[test]
fn pruned_diagrams_keep_clearances_and_shrink_with_lambda() {
    let sc = scene("polygon-bugtrap-medial_axis.json");
    let full = pruned(&sc, Pruning::default()).unwrap();
    let small = pruned(&sc, lambda(0.02)).unwrap();
    let large = pruned(&sc, lambda(0.08)).unwrap();
    assert_eq!(
        small.stats["max_inscribed_circle"],
        full.stats["max_inscribed_circle"]
    );
    assert_eq!(small.cells.len(), full.cells.len());
    for d in [&small, &large] {
        for e in &d.edges {
            assert_eq!(e.clearance.len(), e.points.len());
            for (q, r) in e.points.iter().zip(&e.clearance) {
                let want = q.dist(brute_feet(&sc, *q)[0]);
                assert!((r - want).abs() <= sc.epsilon(), "{q:?}: {r} vs {want}");
            }
        }
    }
    for q in all_points(&large) {
        assert!(distance_to(&small, q) <= 2.0 * sc.epsilon(), "{q:?}");
    }
    assert!(all_points(&large).len() < all_points(&small).len());
    assert_eq!(small.stats["pruning"]["lambda"], 0.02);
}

/// Refusals: a bad λ or angle, pruning with exact bisectors, and generators whose
/// nearest points are unknown (an lp point), naming the site.
#[test]
fn pruning_refuses_what_it_cannot_do() {
    let sc = rectangle(false);
    for bad in [
        lambda(f64::NAN),
        lambda(-1.0),
        angle_degrees(0.0),
        angle_degrees(181.0),
    ] {
        assert!(
            matches!(pruned(&sc, bad), Err(Error::InvalidOption { .. })),
            "{bad:?}"
        );
    }
    let with_bisectors = Options {
        prune: lambda(0.1),
        incremental: gvd::IncrementalOptions {
            bisectors: true,
            ..Default::default()
        },
        ..Default::default()
    };
    assert!(matches!(
        compute(&sc, &with_bisectors),
        Err(Error::InvalidOption { .. })
    ));
    let lp = Scene::new(
        Aabb::from_array([0.0, 0.0, 1.0, 1.0]),
        1e-3,
        Mode::Voronoi,
        vec![
            Site::point([0.2, 0.2]),
            Site::point_with([0.8, 0.7], gvd::Metric::Lp { p: 4 }),
            Site::point([0.3, 0.9]),
        ],
    )
    .unwrap();
    match pruned(&lp, lambda(0.1)) {
        Err(Error::Unsupported { site, .. }) => assert_eq!(site, 1),
        other => panic!("{:?}", other.map(|d| d.edges.len())),
    }
}

/// Both engines that compute polygons, the incremental and the soft-predicate one,
/// prune the shipped serrated pocket to the same axis: the same counts, within epsilon.
#[test]
fn both_engines_prune_to_the_same_axis() {
    let path = format!(
        "{}/../../examples/scenes/serrated-pocket.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let sc = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    let run = |engine| {
        compute(
            &sc,
            &Options {
                engine,
                prune: lambda(0.1),
                ..Default::default()
            },
        )
        .unwrap()
    };
    let incremental = run(gvd::Engine::Incremental);
    let soft = run(gvd::Engine::Subdivision);
    assert_eq!(soft.stats["engine"], "subdivision");
    assert_mended(&soft, "soft");
    assert_eq!(
        (incremental.vertices.len(), incremental.edges.len()),
        (soft.vertices.len(), soft.edges.len())
    );
    for (a, b) in [(&incremental, &soft), (&soft, &incremental)] {
        for q in all_points(a) {
            assert!(distance_to(b, q) <= sc.epsilon(), "{q:?}");
        }
    }
}
