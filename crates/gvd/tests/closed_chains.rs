//! In `medial_axis` mode, chains of separate segment, polyline and arc sites whose ends
//! meet bound regions, as polygons do: their medial axis is computed, and it is the
//! polygon's where the chain traces one. A scene whose open sites close up nowhere is
//! refused, never an empty success.

use gvd::{compute, verify, Aabb, Mode, Options, Scene, Site, VerifyOptions, VoronoiComplex};
use std::f64::consts::PI;

fn scene(mode: Mode, sites: Vec<Site>) -> Scene {
    Scene::new(Aabb::from_array([-3.0, -3.0, 3.0, 3.0]), 1e-3, mode, sites).unwrap()
}

/// Points rounded to 1e-9, sorted.
type Points = Vec<(i64, i64)>;

/// The diagram's vertices and edge points: its geometry without its labels.
fn geometry(d: &VoronoiComplex) -> (Points, Points) {
    let key = |p: gvd::Point| ((p.x * 1e9).round() as i64, (p.y * 1e9).round() as i64);
    let mut vertices: Vec<_> = d.vertices.iter().map(|v| key(v.at)).collect();
    let mut points: Vec<_> = d
        .edges
        .iter()
        .flat_map(|e| e.points.iter().map(|&p| key(p)))
        .collect();
    vertices.sort_unstable();
    points.sort_unstable();
    (vertices, points)
}

fn passes_verify(s: &Scene, d: &VoronoiComplex) {
    let report = verify(s, d, &VerifyOptions::default()).unwrap();
    assert!(
        report.passed,
        "{}: {:?}",
        report.summary_line(),
        report.problems
    );
}

#[test]
fn four_segments_around_a_square_have_the_square_polygon_medial_axis() {
    let corners = [[-1.0, -1.0], [1.0, -0.8], [1.2, 1.0], [-0.9, 1.1]];
    let segments: Vec<Site> = (0..4)
        .map(|k| Site::segment(corners[k], corners[(k + 1) % 4]))
        .collect();
    let chain = scene(Mode::MedialAxis, segments);
    let polygon = scene(Mode::MedialAxis, vec![Site::polygon([corners])]);
    let (a, b) = (
        compute(&chain, &Options::default()).unwrap(),
        compute(&polygon, &Options::default()).unwrap(),
    );
    assert!(!a.edges.is_empty());
    assert_eq!(geometry(&a), geometry(&b));
    passes_verify(&chain, &a);
}

#[test]
fn a_polyline_and_a_segment_closing_it_bound_a_region() {
    let open = [[-1.5, -1.0], [1.5, -1.2], [1.0, 1.3], [-1.2, 0.9]];
    let sites = vec![Site::polyline(open), Site::segment(open[3], open[0])];
    let s = scene(Mode::MedialAxis, sites);
    let d = compute(&s, &Options::default()).unwrap();
    assert!(d.edges.len() >= 5, "{} edges", d.edges.len());
    passes_verify(&s, &d);
}

#[test]
fn a_stadium_of_two_half_circles_and_two_segments_has_its_spine() {
    // half circles of radius 1 about (±1, 0), joined by y = ±1
    let sites = vec![
        Site::arc([1.0, 0.0], 1.0, -PI / 2.0, PI / 2.0),
        Site::segment([1.0, 1.0], [-1.0, 1.0]),
        Site::arc([-1.0, 0.0], 1.0, PI / 2.0, 3.0 * PI / 2.0),
        Site::segment([-1.0, -1.0], [1.0, -1.0]),
    ];
    let s = scene(Mode::MedialAxis, sites);
    let d = compute(&s, &Options::default()).unwrap();
    // the spine y = 0 between the two centres is the medial axis, with clearance 1
    let on_spine = d
        .edges
        .iter()
        .flat_map(|e| e.points.iter())
        .filter(|p| p.x.abs() < 0.99)
        .all(|p| p.y.abs() < 1e-6);
    assert!(!d.edges.is_empty() && on_spine, "{:?}", d.edges);
    passes_verify(&s, &d);
}

#[test]
fn open_chains_in_medial_axis_mode_are_refused() {
    let sites = vec![
        Site::segment([-1.0, -1.0], [1.0, -1.0]),
        Site::segment([1.0, -1.0], [1.0, 1.0]),
        Site::arc([0.0, 0.0], 2.0, 0.5, 2.0),
    ];
    let err = compute(&scene(Mode::MedialAxis, sites), &Options::default()).unwrap_err();
    assert!(err.to_string().contains("medial_axis"), "{err}");
}
