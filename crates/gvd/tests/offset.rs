//! Offset curves against independent facts: sampled points at distance d from the
//! sites (brute force over every site), every point of the true offset covered, known
//! shapes (circles, stadiums, squares, bent stadiums around arcs, slots), and refusals.

use gvd::complex::{Edge, FeatureKind, Generator, Vertex};
use gvd::geom::{segment_distance, Point};
use gvd::offset::{offset, offset_scene, Curve, Offset, Primitive};
use gvd::scene::{Mode, Site, SiteKind};
use gvd::{Options, Scene, VoronoiComplex};
use std::f64::consts::{PI, TAU};

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

fn points_scene(points: &[Point]) -> Scene {
    let sites: Vec<String> = points
        .iter()
        .map(|q| format!(r#"{{"kind": "point", "at": [{}, {}]}}"#, q.x, q.y))
        .collect();
    Scene::from_json(&format!(
        r#"{{"domain": [-2, -2, 2, 2], "epsilon": 0.001, "sites": [{}]}}"#,
        sites.join(",")
    ))
    .unwrap()
}

/// The exact distance from `q` to the arc of the circle `(c, r)` from `a0`
/// counter-clockwise to `a1`: to the circle when the direction of `q` from `c` is
/// within the span, else to the nearer end.
fn arc_distance(q: Point, c: Point, r: f64, a0: f64, a1: f64) -> f64 {
    let span = (a1 - a0).rem_euclid(TAU);
    let v = q - c;
    if (v.y.atan2(v.x) - a0).rem_euclid(TAU) <= span {
        (v.norm() - r).abs()
    } else {
        let [e0, e1] = arc_ends(c, r, a0, a1);
        q.dist(e0).min(q.dist(e1))
    }
}

/// The ends of an arc site, computed as the engine computes its end generators (a
/// segment sharing an end with an arc must have these very coordinates).
fn arc_ends(c: Point, r: f64, a0: f64, a1: f64) -> [Point; 2] {
    let span = (a1 - a0).rem_euclid(TAU);
    [a0, a0 + span].map(|a| c + p(a.cos(), a.sin()) * r)
}

/// The distance from `q` to the nearest site, by brute force: points, arcs, and the
/// boundaries of segments, polylines and polygons.
fn site_distance(scene: &Scene, q: Point) -> f64 {
    sites_distance(scene, q, usize::MAX)
}

/// The distance from `q` to the nearest site other than site `except`.
fn sites_distance(scene: &Scene, q: Point, except: usize) -> f64 {
    let chain = |pts: &[Point], closed: bool| {
        let n = pts.len();
        let edges = if closed { n } else { n - 1 };
        (0..edges)
            .map(|k| segment_distance(q, pts[k], pts[(k + 1) % n]))
            .fold(f64::INFINITY, f64::min)
    };
    scene
        .sites()
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != except)
        .map(|(_, s)| match &s.kind {
            SiteKind::Point { at, .. } => q.dist(*at),
            SiteKind::Segment { from, to } => segment_distance(q, *from, *to),
            &SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => arc_distance(q, center, radius, start_angle, end_angle),
            SiteKind::Polyline { points } => chain(points, false),
            SiteKind::Polygon { rings } => rings
                .iter()
                .map(|r| chain(r, true))
                .fold(f64::INFINITY, f64::min),
            other => panic!("no brute-force distance for {}", other.name()),
        })
        .fold(f64::INFINITY, f64::min)
}

/// Every primitive sampled: at distance d from the nearest site (within `tol`); curves
/// connected end to start; open curves end on the domain's boundary.
fn check_samples(scene: &Scene, off: &Offset, tol: f64) {
    let d = off.distance;
    for (c, curve) in off.curves.iter().enumerate() {
        for prim in &curve.primitives {
            for k in 0..=40 {
                let q = prim.point_at(k as f64 / 40.0);
                let dist = site_distance(scene, q);
                assert!(
                    (dist - d).abs() <= tol,
                    "curve {c}: {q:?} at {dist}, not {d}"
                );
                assert!(
                    scene.domain().outside_distance(q) <= tol,
                    "curve {c}: {q:?} outside"
                );
            }
        }
        for w in curve.primitives.windows(2) {
            assert!(w[0].end().dist(w[1].start()) <= tol, "curve {c} is broken");
        }
        let (first, last) = (
            curve.primitives[0].start(),
            curve.primitives.last().unwrap().end(),
        );
        if curve.closed {
            assert!(first.dist(last) <= tol, "curve {c} is not closed");
        } else {
            for e in [first, last] {
                assert!(
                    scene.domain().outside_distance(e) == 0.0,
                    "curve {c} ends at {e:?}"
                );
                let b = scene.domain();
                let edge = [e.x - b.min.x, b.max.x - e.x, e.y - b.min.y, b.max.y - e.y];
                assert!(
                    edge.iter().any(|v| v.abs() <= tol),
                    "curve {c} ends inside at {e:?}"
                );
            }
        }
    }
}

/// The distance from `q` to a primitive (an arc counter-clockwise or clockwise).
fn primitive_distance(prim: &Primitive, q: Point) -> f64 {
    match *prim {
        Primitive::Line { from, to } => segment_distance(q, from, to),
        Primitive::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            let (lo, hi) = if start_angle <= end_angle {
                (start_angle, end_angle)
            } else {
                (end_angle, start_angle)
            };
            let a = (q - center).y.atan2((q - center).x);
            let rel = (a - lo).rem_euclid(TAU);
            if rel <= hi - lo {
                (q.dist(center) - radius).abs()
            } else {
                q.dist(prim.start()).min(q.dist(prim.end()))
            }
        }
    }
}

fn covered(off: &Offset, q: Point, tol: f64) -> bool {
    off.curves
        .iter()
        .flat_map(|c| &c.primitives)
        .any(|prim| primitive_distance(prim, q) <= tol)
}

/// Deterministic pseudo-random points in `[-r, r]²`.
fn random_points(n: usize, r: f64, mut seed: u64) -> Vec<Point> {
    let mut next = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 * r - r
    };
    (0..n).map(|_| p(next(), next())).collect()
}

fn signed_area(curve: &Curve) -> f64 {
    let pts: Vec<Point> = curve
        .primitives
        .iter()
        .flat_map(|prim| (0..16).map(move |k| prim.point_at(k as f64 / 16.0)))
        .collect();
    (0..pts.len())
        .map(|k| pts[k].cross(pts[(k + 1) % pts.len()]) / 2.0)
        .sum()
}

#[test]
fn one_point_gives_one_circle() {
    let scene = points_scene(&[p(0.1, 0.2)]);
    let (off, _) = offset_scene(&scene, 0.5, &Options::default()).unwrap();
    assert_eq!(off.curves.len(), 1);
    let c = &off.curves[0];
    assert!(c.closed);
    match c.primitives.as_slice() {
        [Primitive::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        }] => {
            assert_eq!((*center, *radius), (p(0.1, 0.2), 0.5));
            assert!((end_angle - start_angle - TAU).abs() < 1e-12);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn two_close_points_give_two_arcs_meeting_on_the_bisector() {
    let scene = points_scene(&[p(-0.3, 0.1), p(0.3, 0.1)]);
    let (off, _) = offset_scene(&scene, 0.5, &Options::default()).unwrap();
    assert_eq!(off.curves.len(), 1);
    let c = &off.curves[0];
    assert!(c.closed && c.primitives.len() == 2, "{c:?}");
    for prim in &c.primitives {
        let Primitive::Arc { radius, .. } = prim else {
            panic!("{prim:?}")
        };
        assert_eq!(*radius, 0.5);
        for end in [prim.start(), prim.end()] {
            // on the bisector x = 0, at height 0.1 ± 0.4
            assert!(end.x.abs() < 1e-12 && ((end.y - 0.1).abs() - 0.4).abs() < 1e-12);
        }
    }
    assert!(signed_area(c) > 0.0, "counter-clockwise around the sites");
    check_samples(&scene, &off, 1e-9);
}

#[test]
fn points_far_apart_give_separate_circles() {
    let scene = points_scene(&[p(-1.0, 0.0), p(1.0, 0.0)]);
    let (off, _) = offset_scene(&scene, 0.5, &Options::default()).unwrap();
    assert_eq!(off.curves.len(), 2);
    assert!(off
        .curves
        .iter()
        .all(|c| c.closed && c.primitives.len() == 1));
}

#[test]
fn random_points_against_brute_force() {
    let points = random_points(60, 1.9, 7);
    let scene = points_scene(&points);
    for d in [0.05, 0.2, 0.4] {
        let (off, _) = offset_scene(&scene, d, &Options::default()).unwrap();
        check_samples(&scene, &off, 1e-9);
        // every split came from the diagram, exactly
        assert_eq!(
            (
                off.stats["repairs"].as_u64(),
                off.stats["fallbacks"].as_u64()
            ),
            (Some(0), Some(0))
        );
        // completeness: points of the true offset (on a site's circle, strictly nearer
        // to that site than to any other, inside the domain) lie on some primitive
        let mut tested = 0;
        for (i, c) in points.iter().enumerate() {
            for k in 0..90 {
                let a = TAU * k as f64 / 90.0;
                let q = *c + p(a.cos(), a.sin()) * d;
                let others = points
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(_, o)| q.dist(*o))
                    .fold(f64::INFINITY, f64::min);
                if others > d + 1e-6 && scene.domain().contains(q) {
                    tested += 1;
                    assert!(covered(&off, q, 1e-9), "d {d}: {q:?} of site {i} missed");
                }
            }
        }
        assert!(tested > 50, "d {d}: only {tested} tested");
    }
}

fn corner(site: usize, index: usize) -> Generator {
    Generator::Feature {
        site,
        feature: FeatureKind::Corner,
        index,
    }
}

fn edge(site: usize, index: usize) -> Generator {
    Generator::Feature {
        site,
        feature: FeatureKind::Edge,
        index,
    }
}

fn diagram_edge(sites: [Generator; 2], points: Vec<Point>) -> Edge {
    Edge {
        clearance: Vec::new(),
        sites_along: Vec::new(),
        sites,
        from: None,
        bisector: Vec::new(),
        parametric: Vec::new(),
        to: None,
        points: points.into(),
    }
}

/// The Voronoi complex of one segment from (-0.5, 0) to (0.5, 0): the normals at its
/// ends separate the corners' cells from the edge's.
fn stadium() -> (Scene, VoronoiComplex) {
    let scene = Scene::from_json(
        r#"{"domain": [-2, -2, 2, 2], "epsilon": 0.001, "mode": "complex",
            "sites": [{"kind": "segment", "from": [-0.5, 0], "to": [0.5, 0]}]}"#,
    )
    .unwrap();
    let mut edges = Vec::new();
    for (k, x) in [(0, -0.5), (1, 0.5)] {
        for y in [-2.0, 2.0] {
            edges.push(diagram_edge(
                [corner(0, k), edge(0, 0)],
                vec![p(x, 0.0), p(x, y)],
            ));
        }
    }
    let diagram = VoronoiComplex {
        edges,
        ..Default::default()
    };
    (scene, diagram)
}

#[test]
fn a_segment_gives_a_stadium() {
    let (scene, diagram) = stadium();
    let off = offset(&scene, &diagram, 0.25).unwrap();
    assert_eq!(off.curves.len(), 1, "{off:?}");
    let c = &off.curves[0];
    assert!(c.closed && c.primitives.len() == 4, "{c:?}");
    let (mut lines, mut arcs) = (0, 0);
    for prim in &c.primitives {
        match *prim {
            Primitive::Line { from, to } => {
                lines += 1;
                assert!((from.dist(to) - 1.0).abs() < 1e-12 && (from.y.abs() - 0.25).abs() < 1e-12);
            }
            Primitive::Arc {
                radius,
                start_angle,
                end_angle,
                ..
            } => {
                arcs += 1;
                assert!(radius == 0.25 && (end_angle - start_angle - PI).abs() < 1e-9);
            }
        }
    }
    assert_eq!((lines, arcs), (2, 2));
    assert!(signed_area(c) > 0.0);
    check_samples(&scene, &off, 1e-9);
    // the strips' ends are known without the diagram: the same stadium from no edges
    let bare = offset(&scene, &VoronoiComplex::default(), 0.25).unwrap();
    assert_eq!(bare.curves, off.curves);
}

/// The square [-1, 1]² as a polygon site, in the given mode.
fn square(mode: &str) -> Scene {
    Scene::from_json(&format!(
        r#"{{"domain": [-2, -2, 2, 2], "epsilon": 0.001, "mode": "{mode}",
            "sites": [{{"kind": "polygon", "rings": [[[-1, -1], [1, -1], [1, 1], [-1, 1]]]}}]}}"#
    ))
    .unwrap()
}

const SQUARE: [(f64, f64); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];

#[test]
fn a_square_pocket_gives_a_smaller_square() {
    // medial axis: the diagonals, edge k-1 against edge k from corner k to the centre
    let scene = square("medial_axis");
    let edges = (0..4)
        .map(|k| {
            let (x, y) = SQUARE[k];
            diagram_edge(
                [edge(0, (k + 3) % 4), edge(0, k)],
                vec![p(x, y), p(0.0, 0.0)],
            )
        })
        .collect();
    let diagram = VoronoiComplex {
        vertices: vec![Vertex {
            clearance: None,
            at: p(0.0, 0.0),
            sites: (0..4).map(|k| edge(0, k)).collect(),
        }],
        edges,
        ..Default::default()
    };
    let off = offset(&scene, &diagram, 0.25).unwrap();
    assert_eq!(off.curves.len(), 1, "{off:?}");
    let c = &off.curves[0];
    assert!(c.closed && c.primitives.len() == 4, "{c:?}");
    for prim in &c.primitives {
        let Primitive::Line { from, to } = *prim else {
            panic!("{prim:?}")
        };
        assert!((from.dist(to) - 1.5).abs() < 1e-12);
        assert!((from.x.abs() - 0.75).abs() < 1e-12 && (from.y.abs() - 0.75).abs() < 1e-12);
    }
    assert!(signed_area(c) < 0.0, "clockwise: the boundary on the left");
    check_samples(&scene, &off, 1e-9);
    assert_eq!(off.stats["repairs"], 0);
    assert!(offset(&scene, &diagram, 1.5).unwrap().curves.is_empty());
    // without the diagram every crossing is missed: the sampled check notices and the
    // exact local splits repair the lines
    let bare = offset(&scene, &VoronoiComplex::default(), 0.25).unwrap();
    assert_eq!(bare.stats["repairs"], 4);
    assert_eq!(bare.curves.len(), 1);
    assert!(bare.curves[0].closed && bare.curves[0].primitives.len() == 4);
    check_samples(&scene, &bare, 1e-9);
}

#[test]
fn a_square_site_gives_a_rounded_square_outside_only() {
    // complex: the corners' normals, corner k against edges k-1 and k
    let scene = square("complex");
    let mut edges = Vec::new();
    for (k, &(x, y)) in SQUARE.iter().enumerate() {
        edges.push(diagram_edge(
            [corner(0, k), edge(0, (k + 3) % 4)],
            if k % 2 == 0 {
                vec![p(x, y), p(x, 2.0 * y)]
            } else {
                vec![p(x, y), p(2.0 * x, y)]
            },
        ));
        edges.push(diagram_edge(
            [corner(0, k), edge(0, k)],
            if k % 2 == 0 {
                vec![p(x, y), p(2.0 * x, y)]
            } else {
                vec![p(x, y), p(x, 2.0 * y)]
            },
        ));
    }
    let diagram = VoronoiComplex {
        edges,
        ..Default::default()
    };
    let off = offset(&scene, &diagram, 0.25).unwrap();
    assert_eq!(off.curves.len(), 1, "{off:?}");
    let c = &off.curves[0];
    assert!(c.closed && c.primitives.len() == 8, "{c:?}");
    let arcs = c
        .primitives
        .iter()
        .filter(|prim| matches!(prim, Primitive::Arc { .. }))
        .count();
    assert_eq!(arcs, 4);
    assert!(signed_area(c) > 0.0);
    check_samples(&scene, &off, 1e-9);
}

#[test]
fn bad_distances_and_sites_are_refused() {
    let scene = points_scene(&[p(0.0, 0.0)]);
    for d in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        match offset_scene(&scene, d, &Options::default()) {
            Err(gvd::Error::Scene { field, .. }) => assert_eq!(field, "distance"),
            other => panic!("{d}: {other:?}"),
        }
    }
    let circle = Scene::from_json(
        r#"{"domain": [-2, -2, 2, 2], "sites": [{"kind": "circle", "center": [0, 0], "radius": 1}]}"#,
    )
    .unwrap();
    match offset(&circle, &VoronoiComplex::default(), 0.5) {
        Err(gvd::Error::Unsupported { site: 0, kind, .. }) => assert_eq!(kind, "circle"),
        other => panic!("{other:?}"),
    }
    let stray = VoronoiComplex {
        edges: vec![diagram_edge(
            [Generator::Site(0), Generator::Site(5)],
            vec![p(0.0, 0.0), p(1.0, 0.0)],
        )],
        ..Default::default()
    };
    assert!(matches!(
        offset(&scene, &stray, 0.5),
        Err(gvd::Error::Diagram(_))
    ));
}

/// The shipped pocket, once the engine computes polygons: every sampled point at
/// distance d from the boundary, inside the pocket.
#[test]
fn shipped_pocket_against_brute_force() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/scenes/pocket.json"
    );
    let scene = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    for d in [0.05, 0.15] {
        match offset_scene(&scene, d, &Options::default()) {
            Ok((off, _)) => {
                assert!(!off.curves.is_empty());
                check_samples(&scene, &off, 10.0 * scene.epsilon());
            }
            Err(gvd::Error::Unsupported { .. }) => {
                eprintln!("pocket: polygons are not computed yet, skipped");
                return;
            }
            Err(e) => panic!("{e}"),
        }
    }
}

/// Points of the true offset of an arc, segment or point site `i` at distance `d`: its
/// concentric arcs (or lines) at `d` and the circles of radius `d` around its ends,
/// sampled.
fn true_offset_candidates(scene: &Scene, i: usize, d: f64) -> Vec<Point> {
    let circle = |c: Point, r: f64, a0: f64, span: f64, n: usize| -> Vec<Point> {
        (0..=n)
            .map(|k| {
                let a = a0 + span * k as f64 / n as f64;
                c + p(a.cos(), a.sin()) * r
            })
            .collect::<Vec<_>>()
    };
    match scene.sites()[i].kind {
        SiteKind::Point { at, .. } => circle(at, d, 0.0, TAU, 90),
        SiteKind::Segment { from, to } => {
            let n = (to - from).perp() * (d / from.dist(to));
            let mut out: Vec<Point> = (0..=40)
                .flat_map(|k| {
                    let m = from.lerp(to, k as f64 / 40.0);
                    [m + n, m - n]
                })
                .collect();
            out.extend(circle(from, d, 0.0, TAU, 60));
            out.extend(circle(to, d, 0.0, TAU, 60));
            out
        }
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            let span = (end_angle - start_angle).rem_euclid(TAU);
            let mut out = circle(center, radius + d, start_angle, span, 60);
            if d < radius {
                out.extend(circle(center, radius - d, start_angle, span, 60));
            }
            for e in arc_ends(center, radius, start_angle, end_angle) {
                out.extend(circle(e, d, 0.0, TAU, 60));
            }
            out
        }
        _ => Vec::new(),
    }
}

/// Completeness: every sampled point of the true offset (at distance d from its site,
/// nearest to that site by a margin, inside the domain by a margin) lies on some
/// primitive; returns how many were tested.
fn check_complete(scene: &Scene, off: &Offset, tol: f64) -> usize {
    let d = off.distance;
    let mut tested = 0;
    for i in 0..scene.sites().len() {
        for q in true_offset_candidates(scene, i, d) {
            let own = site_distance(scene, q);
            let inside = scene.domain().outside_distance(q) == 0.0
                && [
                    q.x - scene.domain().min.x,
                    scene.domain().max.x - q.x,
                    q.y - scene.domain().min.y,
                    scene.domain().max.y - q.y,
                ]
                .iter()
                .all(|&m| m > 1e-6);
            // at distance d from site i (not nearer to one of its other parts)
            if (own - d).abs() > 1e-12 || !inside {
                continue;
            }
            if sites_distance(scene, q, i) > d + 1e-6 {
                tested += 1;
                assert!(covered(off, q, tol), "d {d}: {q:?} of site {i} missed");
            }
        }
    }
    tested
}

/// A scene built directly, not parsed: a segment sharing an end with an arc must have
/// the arc's computed end to the bit (else the engine refuses them as touching), and
/// JSON numbers with round-trip digits are not always read back to the bits written
/// (`0.19866933079506122` reads as `0.1986693307950612`).
fn scene_of(domain: [f64; 4], mode: Mode, sites: Vec<SiteKind>) -> Scene {
    Scene::new(
        gvd::geom::Aabb::from_array(domain),
        0.001,
        mode,
        sites
            .into_iter()
            .map(|kind| Site { id: None, kind })
            .collect(),
    )
    .expect("a valid scene")
}

fn arc_site(center: Point, radius: f64, start_angle: f64, end_angle: f64) -> SiteKind {
    SiteKind::Arc {
        center,
        radius,
        start_angle,
        end_angle,
    }
}

fn segment_site(from: Point, to: Point) -> SiteKind {
    SiteKind::Segment { from, to }
}

/// The radii of a curve's arcs, and how many of them run clockwise.
fn arc_radii(c: &Curve) -> (Vec<f64>, usize) {
    let mut radii = Vec::new();
    let mut clockwise = 0;
    for prim in &c.primitives {
        if let Primitive::Arc {
            radius,
            start_angle,
            end_angle,
            ..
        } = *prim
        {
            radii.push(radius);
            clockwise += usize::from(end_angle < start_angle);
            assert!((0.0..TAU).contains(&start_angle), "{prim:?}");
            assert!((end_angle - start_angle).abs() <= TAU, "{prim:?}");
        }
    }
    (radii, clockwise)
}

#[test]
fn an_arc_gives_a_bent_stadium() {
    let (c, r) = (p(0.2, -0.1), 1.0);
    for (a0, a1) in [(0.3, 2.5), (-2.0, 3.5), (5.0, 5.0 + 4.0)] {
        let scene = scene_of(
            [-3.0, -3.0, 3.0, 3.0],
            Mode::Voronoi,
            vec![arc_site(c, r, a0, a1)],
        );
        let d = 0.3;
        let (off, _) = offset_scene(&scene, d, &Options::default()).unwrap();
        assert_eq!(off.curves.len(), 1, "{off:?}");
        let curve = &off.curves[0];
        assert!(curve.closed && curve.primitives.len() == 4, "{curve:?}");
        // outside r + d counter-clockwise, inside r − d clockwise, two half-turn caps
        let (mut radii, clockwise) = arc_radii(curve);
        radii.sort_by(f64::total_cmp);
        assert_eq!(radii, vec![d, d, r - d, r + d]);
        assert_eq!(clockwise, 1);
        for prim in &curve.primitives {
            if let Primitive::Arc {
                radius,
                start_angle,
                end_angle,
                ..
            } = *prim
            {
                let sweep = (end_angle - start_angle).abs();
                let want = if radius == d { PI } else { a1 - a0 };
                assert!((sweep - want).abs() < 1e-9, "{prim:?}");
            }
        }
        assert!(signed_area(curve) > 0.0);
        check_samples(&scene, &off, 1e-9);
        assert!(check_complete(&scene, &off, 1e-9) > 100);
    }
}

#[test]
fn an_arc_whose_inner_offset_vanishes() {
    let (c, r) = (p(0.0, 0.3), 0.4);
    // a wide arc: its caps meet inside; a narrow one: they do not reach each other
    for (a1, d, caps_meet) in [(4.5, 0.6, true), (1.2, 0.5, false)] {
        let scene = scene_of(
            [-3.0, -3.0, 3.0, 3.0],
            Mode::Complex,
            vec![arc_site(c, r, 0.5, a1)],
        );
        let (off, _) = offset_scene(&scene, d, &Options::default()).unwrap();
        assert_eq!(off.curves.len(), 1, "{off:?}");
        let curve = &off.curves[0];
        assert!(curve.closed, "{curve:?}");
        let (radii, clockwise) = arc_radii(curve);
        assert_eq!(clockwise, 0, "no inner arc: {curve:?}");
        assert!(radii.iter().all(|&x| x == d || x == r + d), "{radii:?}");
        assert_eq!(radii.iter().filter(|&&x| x == r + d).count(), 1);
        assert_eq!(curve.primitives.len(), 3, "{caps_meet}: {curve:?}");
        assert!(signed_area(curve) > 0.0);
        check_samples(&scene, &off, 1e-9);
        assert!(check_complete(&scene, &off, 1e-9) > 50);
    }
}

/// A slot: two half circles of radius `r` around `(±half, 0)` and the two segments
/// between their ends, four sites sharing ends.
fn slot(half: f64, r: f64) -> Scene {
    let h = PI / 2.0;
    let right = (p(half, 0.0), -h, h);
    let left = (p(-half, 0.0), h, 3.0 * h);
    let [r0, r1] = arc_ends(right.0, r, right.1, right.2);
    let [l0, l1] = arc_ends(left.0, r, left.1, left.2);
    scene_of(
        [-3.0, -2.0, 3.0, 2.0],
        Mode::Complex,
        vec![
            segment_site(l1, r0),
            arc_site(right.0, r, right.1, right.2),
            segment_site(r1, l0),
            arc_site(left.0, r, left.1, left.2),
        ],
    )
}

#[test]
fn a_slot_of_arcs_and_segments() {
    let (half, r) = (0.8, 0.5);
    let scene = slot(half, r);
    for d in [0.1, 0.3, 0.45] {
        let (off, _) = offset_scene(&scene, d, &Options::default()).unwrap();
        check_samples(&scene, &off, 1e-9);
        assert!(check_complete(&scene, &off, 1e-9) > 100);
        // a stadium outside, a smaller one inside running clockwise: each of two lines
        // and two half turns (the shared ends give no caps, and no piece twice)
        assert_eq!(off.curves.len(), 2, "d {d}: {off:?}");
        for curve in &off.curves {
            assert!(curve.closed && curve.primitives.len() == 4, "{curve:?}");
            let (radii, clockwise) = arc_radii(curve);
            let outside = signed_area(curve) > 0.0;
            let want = if outside { r + d } else { r - d };
            assert_eq!(radii, vec![want, want], "{curve:?}");
            assert_eq!(clockwise, if outside { 0 } else { 2 });
            let area = signed_area(curve).abs();
            let exact = 4.0 * half * want + PI * want * want;
            assert!((area - exact).abs() < 0.02 * exact, "{area} {exact}");
        }
    }
    // wider than the slot: only the outer stadium
    let (off, _) = offset_scene(&scene, 0.7, &Options::default()).unwrap();
    assert_eq!(off.curves.len(), 1);
    assert!(off.curves[0].closed && off.curves[0].primitives.len() == 4);
    check_samples(&scene, &off, 1e-9);
}

/// A chain of arcs and segments sharing ends at angles (segment, arc, segment, arc,
/// segment, sharp and reflex corners): the round caps around the shared ends join the
/// sides.
#[test]
fn arcs_and_segments_meeting_at_corners() {
    let (ca, cb) = (p(0.0, 0.0), p(-1.2, 1.9));
    let [a0, a1] = arc_ends(ca, 1.0, 0.2, 1.6);
    let [b0, b1] = arc_ends(cb, 0.6, -0.5, 2.0);
    let scene = scene_of(
        [-4.0, -4.0, 4.0, 4.0],
        Mode::Complex,
        vec![
            segment_site(p(2.0, -0.5), a0),
            arc_site(ca, 1.0, 0.2, 1.6),
            segment_site(a1, b0),
            arc_site(cb, 0.6, -0.5, 2.0),
            segment_site(b1, p(-2.5, 0.5)),
        ],
    );
    for d in [0.05, 0.2, 0.6] {
        match offset_scene(&scene, d, &Options::default()) {
            Ok((off, _)) => {
                check_samples(&scene, &off, 1e-9);
                assert!(check_complete(&scene, &off, 1e-9) > 50);
                assert!(off.curves.iter().all(|c| c.closed), "d {d}: {off:?}");
            }
            Err(e) => panic!("d {d}: {e}"),
        }
    }
}

/// The corpus' random arcs with points, at several distances: every sample at distance
/// d, every point of the true offset covered, curves closed unless clipped.
#[test]
fn random_arcs_against_brute_force() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/scenes/arcs-0030-points-0020.json"
    );
    let scene = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    for d in [0.01, 0.05, 0.15, 0.3] {
        let (off, _) = offset_scene(&scene, d, &Options::default()).unwrap();
        check_samples(&scene, &off, 1e-7);
        let tested = check_complete(&scene, &off, 1e-7);
        assert!(tested > 1000, "d {d}: only {tested} tested");
        assert!(off.stats["closed_curves"].as_u64().unwrap() > 0);
        // every split came from the diagram, exactly
        assert_eq!(
            (
                off.stats["repairs"].as_u64(),
                off.stats["fallbacks"].as_u64()
            ),
            (Some(0), Some(0)),
            "d {d}"
        );
    }
}

/// The shipped slot pocket: arcs and segments with a polygon island and a pill island.
#[test]
fn shipped_slot_pocket_against_brute_force() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/scenes/slot-pocket.json"
    );
    let scene = Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    // 0.7 is the notch's radius: its inner offset shrinks to its centre
    for (d, curves) in [(0.2, 5), (0.45, 2), (0.7, 3), (1.0, 3)] {
        let (off, _) = offset_scene(&scene, d, &Options::default()).unwrap();
        check_samples(&scene, &off, 1e-9);
        assert!(check_complete(&scene, &off, 1e-9) > 200);
        assert_eq!(off.curves.len(), curves, "d {d}");
        assert!(off.curves.iter().all(|c| c.closed));
    }
}

#[test]
fn a_full_circle_arc_is_refused() {
    let scene = scene_of(
        [-2.0, -2.0, 2.0, 2.0],
        Mode::Complex,
        vec![arc_site(p(0.0, 0.0), 1.0, 0.5, 0.5 + TAU)],
    );
    match offset(&scene, &VoronoiComplex::default(), 0.3) {
        Err(gvd::Error::Unsupported { site: 0, kind, .. }) => assert_eq!(kind, "arc"),
        other => panic!("{other:?}"),
    }
}
