//! The exact bisectors the incremental engine gives its edges (`--bisectors`), checked
//! against brute-force distances to the edge's two generators and against the edge's
//! own polyline, on points, segments, polygons (every mode) and arcs.

mod common;

use gvd::complex::{Edge, VoronoiComplex};
use gvd::geom::Point;
use gvd::{Engine, Options, Scene};
use std::path::Path;

fn scene(rel: &str) -> Scene {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let path = [
        root.join("tests/data/scenes").join(rel),
        root.join("../..").join(rel),
    ]
    .into_iter()
    .find(|p| p.exists())
    .unwrap_or_else(|| panic!("no scene {rel}"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn with_bisectors(s: &Scene) -> VoronoiComplex {
    let options = Options {
        engine: Engine::Incremental,
        incremental: gvd::IncrementalOptions {
            bisectors: true,
            ..Default::default()
        },
        ..Default::default()
    };
    gvd::compute(s, &options).unwrap()
}

/// The distance from `q` to the polyline `points`.
fn polyline_dist(q: Point, points: &[Point]) -> f64 {
    points
        .windows(2)
        .map(|w| common::seg_dist(q, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

/// Checks every edge: its pieces join up from the first point of its polyline to the
/// last; each piece's points at sampled clearances t are at distance t from both
/// generators and within epsilon of the polyline. An edge without pieces must have
/// constant clearance (parallel segments, concentric arcs). Returns the number of
/// edges with pieces.
fn check(name: &str, s: &Scene, d: &VoronoiComplex) -> usize {
    check_within(name, s, d, 1e-9 * s.domain().longest_side())
}

/// [`check`] with the distances of the forms' points to both generators within `tol`.
fn check_within(name: &str, s: &Scene, d: &VoronoiComplex, tol: f64) -> usize {
    let scale = s.domain().longest_side();
    let mut with = 0;
    for (k, e) in d.edges.iter().enumerate() {
        let Edge {
            sites,
            points,
            bisector,
            ..
        } = e;
        let clearance = |q: Point| sites.map(|g| common::dist(s, &g, q));
        if bisector.is_empty() {
            let t0 = clearance(points[0])[0];
            for &q in points {
                let [a, b] = clearance(q);
                assert!(
                    (a - t0).abs() <= 1e-6 * scale && (b - t0).abs() <= 1e-6 * scale,
                    "{name}: edge {k} {sites:?} has no bisector but its clearance varies"
                );
            }
            continue;
        }
        with += 1;
        let (first, last) = (bisector[0], bisector[bisector.len() - 1]);
        let ends = [first.at(first.t[0]), last.at(last.t[1])];
        let near = |p: Point, q: Point| p.dist(q) <= 1e-7 * scale;
        // An end at a vertex is on the curve; an end cut by the domain is on a chord
        // of the polyline, within epsilon of it.
        let end_ok = |form: Point, end: Point, vertex: Option<usize>| {
            form.dist(end)
                <= if vertex.is_some() {
                    1e-7 * scale
                } else {
                    s.epsilon()
                }
        };
        assert!(
            end_ok(ends[0], points[0], e.from) && end_ok(ends[1], points[points.len() - 1], e.to),
            "{name}: edge {k} {sites:?}: pieces run {ends:?}, the polyline {:?} to {:?}",
            points[0],
            points[points.len() - 1]
        );
        for w in bisector.windows(2) {
            assert!(
                near(w[0].at(w[0].t[1]), w[1].at(w[1].t[0])),
                "{name}: edge {k}: pieces do not join"
            );
        }
        for piece in bisector {
            assert!(piece.sign == 1 || piece.sign == -1);
            for i in 0..=8 {
                let t = piece.t[0] + (piece.t[1] - piece.t[0]) * i as f64 / 8.0;
                let q = piece.at(t);
                for (g, d) in sites.iter().zip(clearance(q)) {
                    assert!(
                        (d - t).abs() <= tol + 1e-9 * t.abs(),
                        "{name}: edge {k}: at t = {t} the point {q:?} is {d} from {g:?}"
                    );
                }
                let off = polyline_dist(q, points);
                assert!(
                    off <= s.epsilon(),
                    "{name}: edge {k}: at t = {t} the form is {off} from the polyline (epsilon {})",
                    s.epsilon()
                );
            }
        }
    }
    with
}

#[test]
fn point_edges_follow_their_bisectors() {
    for name in [
        "points-euclidean-0100.json",
        "degenerate-grid-4x4.json",
        "degenerate-cocircular-12-center.json",
        "degenerate-collinear-20.json",
    ] {
        let s = scene(name);
        let d = with_bisectors(&s);
        // Every point–point bisector has a form.
        assert_eq!(check(name, &s, &d), d.edges.len(), "{name}");
        // An edge that passes the midpoint of its two sites splits there.
        let split = d.edges.iter().filter(|e| e.bisector.len() == 2).count();
        assert!(split > 0, "{name}: no edge passes its sites' midpoint");
    }
}

#[test]
fn segment_and_polygon_edges_follow_their_bisectors() {
    for name in [
        "segments-0200.json",
        "segments-near-touching-9.json",
        "degenerate-triangle-segments.json",
        "degenerate-triangle-polyline-complex.json",
        "polyline-zigzag-complex.json",
        "polyline-zigzag-points-voronoi.json",
        "polygons-convex5-voronoi.json",
        "polygons-convex5-complex.json",
        "polygons-convex5-medial_axis.json",
        "polygon-star50-complex.json",
        "polygon-holes2-medial_axis.json",
        "polygon-bugtrap-medial_axis.json",
    ] {
        let s = scene(name);
        let d = with_bisectors(&s);
        let with = check(name, &s, &d);
        assert!(with > 0, "{name}: no edge has a bisector");
    }
}

/// Segments sharing nearly straight ends (cut from road networks and a coastline, at
/// coordinates up to 1.5e9): an edge along the common normal at the shared end runs
/// from one side of the segments' line through the end to the other, and its pieces
/// join there (the part beyond the end was missing: a gap of 1.1e7 on the road cut).
/// The engine's vertices at those ends are off by up to 2e-7 of the scene, so the
/// forms' distances are held to 1e-3 of epsilon there.
#[test]
fn pieces_join_through_nearly_straight_shared_ends() {
    for name in [
        "regressions/shared-endpoint-84segments.json",
        "regressions/shared-endpoint-4segments.json",
        "regressions/shared-endpoint-labels-3segments.json",
    ] {
        let s = scene(name);
        let d = with_bisectors(&s);
        assert!(check_within(name, &s, &d, 1e-3 * s.epsilon()) > 0, "{name}");
    }
}

#[test]
fn arc_edges_follow_their_bisectors() {
    for name in [
        "arcs-0030-points-0020.json",
        "arcs-0030-points-0020-complex.json",
        "examples/scenes/slot-pocket.json",
        "examples/scenes/rounded-rect-slot.json",
    ] {
        let s = scene(name);
        let d = with_bisectors(&s);
        let with = check(name, &s, &d);
        assert!(with > 0, "{name}: no edge has a bisector");
    }
}

#[test]
fn bisectors_are_only_given_when_asked() {
    let s = scene("segments-0200.json");
    let d = gvd::compute(&s, &Options::default()).unwrap();
    assert!(d.edges.iter().all(|e| e.bisector.is_empty()));
    let json = gvd::io::json::write_diagram(&d);
    assert!(!json.contains("bisector"));
    let d = with_bisectors(&s);
    let json = gvd::io::json::write_diagram(&d);
    let back = gvd::io::json::read_diagram(&json).unwrap();
    assert_eq!(back.edges[0].bisector, d.edges[0].bisector);
}

/// The picture draws edges with exact bisectors from them, coloured by clearance,
/// with a legend; without bisectors it draws the polylines and no legend.
#[test]
fn pictures_colour_exact_edges_by_clearance() {
    let s = scene("examples/scenes/slot-pocket.json");
    let opts = gvd::io::svg::SvgOptions::default();
    // Without exact bisectors, each polyline step is coloured by its points' clearance.
    let d = gvd::compute(&s, &Options::default()).unwrap();
    let plain = gvd::io::svg::render_svg(&s, &d, &opts);
    let steps: usize = d.edges.iter().map(|e| e.points.len() - 1).sum();
    assert!(plain.contains("clearance-legend"));
    assert_eq!(plain.matches("<line ").count(), steps);
    // With them, each piece is drawn in eight strokes from its form (and an edge without
    // one step by step).
    let exact_diagram = with_bisectors(&s);
    let pieces: usize = exact_diagram.edges.iter().map(|e| e.bisector.len()).sum();
    assert!(pieces >= 30, "{pieces} pieces");
    let bare_steps: usize = exact_diagram
        .edges
        .iter()
        .filter(|e| e.bisector.is_empty())
        .map(|e| e.points.len() - 1)
        .sum();
    let exact = gvd::io::svg::render_svg(&s, &exact_diagram, &opts);
    assert!(exact.contains("clearance-legend") && exact.contains("clearance 0 … "));
    assert_eq!(exact.matches("<line ").count(), 8 * pieces + bare_steps);
}
