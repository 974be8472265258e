//! `gvd::verify` on segments, polylines, polygons and arcs, in `voronoi`, `complex` and
//! `medial_axis` modes: the engine's diagrams of shipped scenes pass, an exact medial
//! axis passes, and corrupted diagrams (a moved vertex, a dropped edge, a relabelled
//! edge, an edge naming an edge instead of its end corner, a zone boundary offered as an
//! edge) fail.

use gvd::complex::{smallvec, Edge, FeatureKind, Generator, Vertex, VoronoiComplex};
use gvd::geom::{Aabb, Point};
use gvd::scene::{Mode, Site, SiteKind};
use gvd::verify::{verify, Report, VerifyOptions};
use gvd::{compute, Options, Scene};
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/data/scenes/{name}.json"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn check(s: &Scene, d: &VoronoiComplex) -> Report {
    verify(s, d, &VerifyOptions::default()).unwrap()
}

fn computed(name: &str) -> (Scene, VoronoiComplex) {
    let s = scene(name);
    let d = compute(&s, &Options::default()).unwrap();
    (s, d)
}

fn length(e: &Edge) -> f64 {
    e.points.windows(2).map(|w| w[0].dist(w[1])).sum()
}

fn longest_edge(d: &VoronoiComplex) -> usize {
    (0..d.edges.len())
        .max_by(|&a, &b| length(&d.edges[a]).total_cmp(&length(&d.edges[b])))
        .unwrap()
}

/// Scenes of every mode whose computed diagrams must pass.
const PASSING: &[&str] = &[
    "degenerate-triangle-segments",
    "degenerate-triangle-polyline-complex",
    "polyline-zigzag-points-voronoi",
    "polyline-zigzag-complex",
    "polygons-convex5-voronoi",
    "polygons-convex5-complex",
    "polygons-convex5-medial_axis",
    "polygon-star50-complex",
    "polygon-star50-medial_axis",
    "polygon-holes2-complex",
    "polygon-holes2-medial_axis",
    "polygon-bugtrap-complex",
    "polygon-bugtrap-medial_axis",
    "segments-0200",
    "arcs-0030-points-0020",
    "arcs-0030-points-0020-complex",
];

#[test]
fn computed_diagrams_pass() {
    for name in PASSING {
        let (s, d) = computed(name);
        let r = check(&s, &d);
        assert!(r.passed, "{name}: {}\n{:#?}", r.summary_line(), r.problems);
        assert_eq!(r.sound, 1.0, "{name}");
        assert_eq!(r.complete, 1.0, "{name}");
    }
}

/// The vertex of highest degree, moved by `10 ε` along x with its edges' ends.
fn move_busiest_vertex(s: &Scene, d: &mut VoronoiComplex) {
    let mut degree = vec![0usize; d.vertices.len()];
    for e in &d.edges {
        for v in [e.from, e.to].into_iter().flatten() {
            degree[v] += 1;
        }
    }
    let v = (0..degree.len()).max_by_key(|&v| degree[v]).unwrap();
    let shift = Point::new(10.0 * s.epsilon(), 0.0);
    d.vertices[v].at = d.vertices[v].at + shift;
    for e in &mut d.edges {
        let n = e.points.len();
        if e.from == Some(v) {
            e.points[0] = e.points[0] + shift;
        }
        if e.to == Some(v) {
            e.points[n - 1] = e.points[n - 1] + shift;
        }
    }
}

#[test]
fn moved_vertex_fails() {
    for name in [
        "polygon-star50-complex",
        "polygon-bugtrap-medial_axis",
        "segments-0200",
    ] {
        let (s, mut d) = computed(name);
        move_busiest_vertex(&s, &mut d);
        let r = check(&s, &d);
        assert!(!r.passed, "{name}");
        assert!(
            r.vertices_ok.0 < r.vertices_ok.1,
            "{name}: {}",
            r.summary_line()
        );
    }
}

#[test]
fn dropped_edge_fails_completeness() {
    for name in [
        "polygon-star50-complex",
        "polygon-holes2-medial_axis",
        "polyline-zigzag-points-voronoi",
        "arcs-0030-points-0020-complex",
    ] {
        let (s, mut d) = computed(name);
        d.edges.remove(longest_edge(&d));
        let r = check(&s, &d);
        assert!(
            !r.passed && r.complete < 1.0,
            "{name}: {}",
            r.summary_line()
        );
        assert!(
            r.problems.iter().any(|p| p.starts_with("completeness")),
            "{name}: {:?}",
            r.problems
        );
    }
}

#[test]
fn relabelled_edge_fails_soundness() {
    for name in [
        "polygon-bugtrap-complex",
        "polygons-convex5-medial_axis",
        "segments-0200",
    ] {
        let (s, mut d) = computed(name);
        let k = longest_edge(&d);
        // a generator of the edge farthest away
        let mid = d.edges[k].points[d.edges[k].points.len() / 2];
        let far = (0..d.edges.len())
            .max_by(|&a, &b| {
                d.edges[a].points[0]
                    .dist(mid)
                    .total_cmp(&d.edges[b].points[0].dist(mid))
            })
            .unwrap();
        let other = *d.edges[far]
            .sites
            .iter()
            .find(|g| !d.edges[k].sites.contains(g))
            .unwrap();
        d.edges[k].sites[0] = other;
        let r = check(&s, &d);
        assert!(!r.passed && r.sound < 1.0, "{name}: {}", r.summary_line());
    }
}

/// An edge labelled with a corner, relabelled with an edge ending at that corner: past
/// the edge's end the nearest feature is the corner, so the edge is labelled wrongly.
#[test]
fn edge_named_instead_of_its_corner_fails() {
    let (s, mut d) = computed("polygon-star50-complex");
    let mut order: Vec<usize> = (0..d.edges.len()).collect();
    order.sort_by(|&a, &b| length(&d.edges[b]).total_cmp(&length(&d.edges[a])));
    let (k, side, site, index) = order
        .iter()
        .find_map(|&k| {
            d.edges[k]
                .sites
                .iter()
                .enumerate()
                .find_map(|(i, g)| match *g {
                    Generator::Feature {
                        site,
                        feature: FeatureKind::Corner,
                        index,
                    } => Some((k, i, site, index)),
                    _ => None,
                })
        })
        .unwrap();
    d.edges[k].sites[side] = Generator::Feature {
        site,
        feature: FeatureKind::Edge,
        index,
    };
    let r = check(&s, &d);
    assert!(!r.passed && r.sound < 1.0, "{}", r.summary_line());
    assert!(
        r.problems.iter().any(|p| p.contains("end corner")),
        "{:?}",
        r.problems
    );
}

fn corner(site: usize, index: usize) -> Generator {
    Generator::Feature {
        site,
        feature: FeatureKind::Corner,
        index,
    }
}

fn edge_gen(site: usize, index: usize) -> Generator {
    Generator::Feature {
        site,
        feature: FeatureKind::Edge,
        index,
    }
}

/// The rectangle `[-1, 1] × [-0.5, 0.5]` as a polygon, and its exact medial axis:
/// four corner bisectors and the middle segment between the long edges.
fn rectangle_medial_axis() -> (Scene, VoronoiComplex) {
    let p = Point::new;
    let s = Scene::new(
        Aabb::from_array([-3.0, -1.0, 3.0, 1.0]),
        1e-3,
        Mode::MedialAxis,
        vec![Site {
            id: None,
            kind: SiteKind::Polygon {
                rings: vec![vec![p(-1.0, -0.5), p(1.0, -0.5), p(1.0, 0.5), p(-1.0, 0.5)]],
            },
        }],
    )
    .expect("a valid scene");
    // edges: 0 bottom, 1 right, 2 top, 3 left
    let (v0, v1) = (p(-0.5, 0.0), p(0.5, 0.0));
    let d = VoronoiComplex {
        vertices: vec![
            Vertex {
                clearance: None,
                at: v0,
                sites: smallvec![edge_gen(0, 0), edge_gen(0, 2), edge_gen(0, 3)],
            },
            Vertex {
                clearance: None,
                at: v1,
                sites: smallvec![edge_gen(0, 0), edge_gen(0, 1), edge_gen(0, 2)],
            },
        ],
        edges: vec![
            Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites: [edge_gen(0, 0), edge_gen(0, 2)],
                from: Some(0),
                bisector: Vec::new(),
                parametric: Vec::new(),
                to: Some(1),
                points: smallvec![v0, v1],
            },
            Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites: [edge_gen(0, 0), edge_gen(0, 3)],
                from: None,
                bisector: Vec::new(),
                parametric: Vec::new(),
                to: Some(0),
                points: smallvec![p(-1.0, -0.5), v0],
            },
            Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites: [edge_gen(0, 2), edge_gen(0, 3)],
                from: None,
                bisector: Vec::new(),
                parametric: Vec::new(),
                to: Some(0),
                points: smallvec![p(-1.0, 0.5), v0],
            },
            Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites: [edge_gen(0, 0), edge_gen(0, 1)],
                from: None,
                bisector: Vec::new(),
                parametric: Vec::new(),
                to: Some(1),
                points: smallvec![p(1.0, -0.5), v1],
            },
            Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites: [edge_gen(0, 1), edge_gen(0, 2)],
                from: None,
                bisector: Vec::new(),
                parametric: Vec::new(),
                to: Some(1),
                points: smallvec![p(1.0, 0.5), v1],
            },
        ],
        ..Default::default()
    };
    (s, d)
}

#[test]
fn exact_medial_axis_of_a_rectangle_passes() {
    let (s, d) = rectangle_medial_axis();
    let r = check(&s, &d);
    assert!(r.passed, "{}\n{:#?}", r.summary_line(), r.problems);
    assert!(r.worst_edge_error < 1e-12, "{}", r.summary_line());
    // the corner ends are null ends on the site: warnings only
    assert!(!r.warnings.is_empty());
}

#[test]
fn medial_axis_outside_the_region_and_zone_boundaries_fail() {
    // a bisector of the long edges continued outside the rectangle
    let (s, mut d) = rectangle_medial_axis();
    d.edges[0].points = smallvec![Point::new(-0.5, 0.0), Point::new(-2.5, 0.0)];
    d.edges[0].to = None;
    let r = check(&s, &d);
    assert!(!r.passed, "{}", r.summary_line());
    assert!(
        r.problems.iter().any(|p| p.contains("medial-axis region")),
        "{:?}",
        r.problems
    );
    // complex mode outside the rectangle: the zone boundary of corner 1 and the bottom
    // edge (the vertical ray down from (1, −0.5)) is not a Voronoi edge
    let (s, _) = rectangle_medial_axis();
    let s = s.with_mode(Mode::Complex);
    let d = VoronoiComplex {
        edges: vec![Edge {
            clearance: Vec::new(),
            sites_along: Vec::new(),
            sites: [corner(0, 1), edge_gen(0, 0)],
            from: None,
            bisector: Vec::new(),
            parametric: Vec::new(),
            to: None,
            points: smallvec![Point::new(1.0, -0.5), Point::new(1.0, -1.0)],
        }],
        ..Default::default()
    };
    let r = check(&s, &d);
    assert!(!r.passed, "{}", r.summary_line());
    assert!(
        r.problems.iter().any(|p| p.contains("zone boundary")),
        "{:?}",
        r.problems
    );
}

#[test]
fn labels_must_fit_the_mode() {
    // voronoi mode: a feature label is invalid; complex mode: a bare polygon index is
    let (s, d) = computed("polygons-convex5-voronoi");
    let mut bad = d.clone();
    bad.edges[0].sites[0] = corner(0, 0);
    let r = check(&s, &bad);
    assert!(!r.passed && r.problems.iter().any(|p| p.contains("voronoi mode")));
    let (s, d) = computed("polygons-convex5-complex");
    let mut bad = d.clone();
    bad.edges[0].sites[0] = Generator::Site(0);
    let r = check(&s, &bad);
    assert!(!r.passed && r.problems.iter().any(|p| p.contains("has features")));
    // a corner index beyond the site's corners
    let mut bad = d;
    bad.edges[0].sites[0] = corner(0, 1000);
    assert!(!check(&s, &bad).passed);
}

/// A convex polygon in `complex` mode has no Voronoi edges outside it (only zone
/// boundaries). Where a corner's wedge is narrower than the grid, two neighbouring nodes
/// name the corner's two edges, and the bisection between them ends on the corner's
/// zone boundary: that crossing must be skipped (the shared checker reports it).
#[test]
fn narrow_corner_wedges_are_not_missing_edges() {
    let p = Point::new;
    let s = Scene::new(
        Aabb::from_array([-2.0, -2.0, 2.0, 2.0]),
        1e-3,
        Mode::Complex,
        vec![Site {
            id: None,
            kind: SiteKind::Polygon {
                rings: vec![vec![
                    p(0.8957248794821712, 1.2945652184316796),
                    p(-0.6732639262764998, 1.4230031096491547),
                    p(-1.568988805758671, 0.1284378912174756),
                    p(-0.8957248794821714, -1.2945652184316794),
                    p(0.673263926276499, -1.4230031096491549),
                    p(1.568988805758671, -0.1284378912174751),
                ]],
            },
        }],
    )
    .expect("a valid scene");
    for grid in [128, 512] {
        let opts = VerifyOptions {
            grid,
            ..VerifyOptions::default()
        };
        let r = verify(&s, &VoronoiComplex::default(), &opts).unwrap();
        assert!(
            r.passed,
            "grid {grid}: {} {:?}",
            r.summary_line(),
            r.problems
        );
    }
}
