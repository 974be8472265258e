//! The freeform engine (HREK07) against independent references: a dense sampling of
//! the curves written here (Cox–de Boor, not the engine's knot insertion), the
//! incremental engine on segments, and the subdivision engine on circles.

mod common;

use common::edge_pairs;
use gvd::{compute, Engine, Error, Mode, Options, Point, Scene, SiteKind, VoronoiComplex};
use std::path::Path;

fn scene(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/freeform")
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
    d
}

/// `n + 1` points of a B-spline (or a Bézier) by the Cox–de Boor recursion.
fn dense(kind: &SiteKind, n: usize) -> Vec<Point> {
    let (p, ctrl, knots, weights) = match kind {
        SiteKind::Bezier {
            control_points,
            weights,
        } => {
            let d = control_points.len() - 1;
            let mut k = vec![0.0; d + 1];
            k.extend(vec![1.0; d + 1]);
            (d, control_points.clone(), k, weights.clone())
        }
        SiteKind::Bspline {
            degree,
            control_points,
            knots,
            weights,
            ..
        } => (
            *degree,
            control_points.clone(),
            knots.clone(),
            weights.clone(),
        ),
        _ => panic!("not a curve"),
    };
    let m = ctrl.len();
    let (a, b) = (knots[p], knots[m]);
    let basis = |i: usize, k: usize, u: f64| -> f64 {
        fn rec(kn: &[f64], i: usize, k: usize, u: f64, last: bool) -> f64 {
            if k == 0 {
                let inside = kn[i] <= u && u < kn[i + 1];
                let at_end = last && u == kn[i + 1] && kn[i] < kn[i + 1];
                return if inside || at_end { 1.0 } else { 0.0 };
            }
            let mut s = 0.0;
            if kn[i + k] > kn[i] {
                s += (u - kn[i]) / (kn[i + k] - kn[i]) * rec(kn, i, k - 1, u, last);
            }
            if kn[i + k + 1] > kn[i + 1] {
                s += (kn[i + k + 1] - u) / (kn[i + k + 1] - kn[i + 1])
                    * rec(kn, i + 1, k - 1, u, last);
            }
            s
        }
        rec(&knots, i, k, u, u == b)
    };
    (0..=n)
        .map(|j| {
            let u = a + (b - a) * j as f64 / n as f64;
            let (mut x, mut y, mut w) = (0.0, 0.0, 0.0);
            for i in 0..m {
                let bi = basis(i, p, u) * weights.as_ref().map_or(1.0, |w| w[i]);
                x += bi * ctrl[i].x;
                y += bi * ctrl[i].y;
                w += bi;
            }
            Point::new(x / w, y / w)
        })
        .collect()
}

fn seg_dist(q: Point, a: Point, b: Point) -> f64 {
    let d = b - a;
    let t = ((q - a).dot(d) / d.dot(d)).clamp(0.0, 1.0);
    q.dist(a + d * t)
}

fn poly_dist(q: Point, pts: &[Point]) -> f64 {
    pts.windows(2)
        .map(|w| seg_dist(q, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

/// Even-odd inside the closed loops that `curves` (polylines joined end to end) make.
fn inside_of(q: Point, curves: &[Vec<Point>]) -> bool {
    let mut c = false;
    for w in curves.iter().flat_map(|c| c.windows(2)) {
        let (a, b) = (w[0], w[1]);
        if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            c = !c;
        }
    }
    c
}

fn inside(q: Point, ring: &[Point]) -> bool {
    inside_of(q, std::slice::from_ref(&ring.to_vec()))
}

/// Every edge point of a `voronoi` diagram is outside the closed curves, at equal
/// distance (within epsilon) from its two sites, and no site is nearer.
fn check_by_brute_force(sc: &Scene, d: &VoronoiComplex) {
    let curves: Vec<Vec<Point>> = sc.sites().iter().map(|s| dense(&s.kind, 20000)).collect();
    let eps = sc.epsilon();
    let mut checked = 0;
    for e in &d.edges {
        let (i, j) = (e.sites[0].site(), e.sites[1].site());
        // the polyline's points and the middles of its pieces
        let middles = e.points.windows(2).map(|w| w[0].lerp(w[1], 0.5));
        for q in e.points.iter().copied().chain(middles) {
            let dist: Vec<f64> = curves.iter().map(|c| poly_dist(q, c)).collect();
            assert!(
                (dist[i] - dist[j]).abs() < eps,
                "{q:?}: {} vs {}",
                dist[i],
                dist[j]
            );
            let others = (0..dist.len())
                .filter(|&k| k != i && k != j)
                .map(|k| dist[k]);
            assert!(
                others.fold(f64::INFINITY, f64::min) > dist[i].min(dist[j]) - eps,
                "{q:?}"
            );
            for (k, c) in curves.iter().enumerate() {
                if c[0].dist(*c.last().unwrap()) < 1e-9 {
                    assert!(!inside(q, c) || dist[k] < eps, "{q:?} inside site {k}");
                }
            }
            checked += 1;
        }
    }
    assert!(checked > 30, "{checked} points checked");
}

#[test]
fn corpus_voronoi_scenes_pass_a_brute_force_check() {
    for name in [
        "freeform-convex3-voronoi.json",
        "freeform-nonconvex2-voronoi.json",
        "freeform-closed6-voronoi.json",
    ] {
        let sc = scene(name);
        let d = run(&sc, Engine::Freeform);
        assert_eq!(d.stats["engine"], "freeform");
        check_by_brute_force(&sc, &d);
        // the cells cover the domain once
        let area: f64 = d
            .cells
            .iter()
            .flat_map(|c| c.rings.iter().enumerate())
            .map(|(k, r)| {
                let a = gvd::geom::ring::signed_area(r).abs();
                if k == 0 {
                    a
                } else {
                    -a
                }
            })
            .sum();
        assert!((area - 16.0).abs() < 1e-6, "{name}: cells cover {area}");
    }
}

#[test]
fn auto_picks_the_freeform_engine_for_curves() {
    let d = run(&scene("freeform-convex3-voronoi.json"), Engine::Auto);
    assert_eq!(d.stats["engine"], "freeform");
}

/// Vertices of two diagrams, matched one to one within `tol`.
fn same_vertices(a: &VoronoiComplex, b: &VoronoiComplex, tol: f64) {
    assert_eq!(a.vertices.len(), b.vertices.len());
    for v in &a.vertices {
        let m = b.vertices.iter().find(|w| v.at.dist(w.at) < tol);
        let w = m.unwrap_or_else(|| panic!("no vertex near {:?}", v.at));
        let (mut s, mut t) = (v.sites.to_vec(), w.sites.to_vec());
        s.sort();
        t.sort();
        assert_eq!(s, t);
    }
}

#[test]
fn degree_one_beziers_agree_with_the_incremental_segments() {
    let ff = run(&scene("freeform-segments4.json"), Engine::Freeform);
    let inc = run(&scene("segments4.json"), Engine::Incremental);
    same_vertices(&ff, &inc, 1e-9);
    assert_eq!(ff.edges.len(), inc.edges.len());
}

#[test]
fn nurbs_circles_agree_with_the_subdivision_circles() {
    let ff = run(&scene("freeform-nurbs-circles3.json"), Engine::Freeform);
    let sub = run(&scene("circles3.json"), Engine::Subdivision);
    same_vertices(&ff, &sub, 1e-6);
    assert_eq!(ff.edges.len(), sub.edges.len());
}

/// A `medial_axis` diagram of a domain bounded by a chain of curves (given in order)
/// against a dense sampling of them: its vertices and every `step`-th edge point lie
/// inside (or on a curve: a vertex at a corner), at equal distance (within epsilon) from
/// their generators' curves, with no curve nearer, and a vertex's clearance (where set)
/// is that distance.
fn check_medial_axis_by_brute_force(sc: &Scene, d: &VoronoiComplex, step: usize) {
    assert_eq!(sc.mode(), Mode::MedialAxis);
    assert!(!d.edges.is_empty() && !d.vertices.is_empty());
    let curves: Vec<Vec<Point>> = sc.sites().iter().map(|s| dense(&s.kind, 4000)).collect();
    let eps = sc.epsilon();
    // the distances to the generators' curves, and the nearest of all
    let check = |q: Point, sites: &[usize]| -> f64 {
        let dist: Vec<f64> = curves.iter().map(|c| poly_dist(q, c)).collect();
        let on_curve = dist.iter().any(|&x| x < 1e-9 * eps);
        assert!(
            on_curve || inside_of(q, &curves),
            "{q:?} outside the domain"
        );
        let own: Vec<f64> = sites.iter().map(|&i| dist[i]).collect();
        let (lo, hi) = own
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(hi - lo < eps, "{q:?}: {own:?}");
        let nearest = dist.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(nearest > lo - eps, "{q:?}: a curve at {nearest} < {lo}");
        nearest
    };
    for v in &d.vertices {
        let sites: Vec<usize> = v.sites.iter().map(|g| g.site()).collect();
        let nearest = check(v.at, &sites);
        if let Some(c) = v.clearance {
            assert!(
                (c - nearest).abs() < eps,
                "{:?}: clearance {c} vs {nearest}",
                v.at
            );
        }
    }
    for e in &d.edges {
        let sites = [e.sites[0].site(), e.sites[1].site()];
        for q in e.points.iter().step_by(step) {
            check(*q, &sites);
        }
    }
}

#[test]
fn medial_axis_of_a_bezier_domain_stays_inside_and_is_equidistant() {
    let sc = scene("freeform-bezier4-medial_axis.json");
    check_medial_axis_by_brute_force(&sc, &run(&sc, Engine::Freeform), 5);
}

#[test]
fn medial_axis_of_a_glyph_of_twenty_joined_cubics() {
    // r(θ) = 1 + 0.3 cos 5θ as 20 cubic Bézier sites joined end to end (coordinates
    // rounded to 6 decimals: kinks of a few 1e-6 rad at some joints), the scene of
    // `gvd bench freeform`
    let sc = scene("freeform-glyph20-medial_axis.json");
    let d = run(&sc, Engine::Freeform);
    check_medial_axis_by_brute_force(&sc, &d, 3);
    // the chain bounds the domain: no corner at the joints, nothing outside
    assert_eq!(d.stats["corners"], 0);
    // the five arms meet at the centre, 0.7 from the five notches
    let centre = d
        .vertices
        .iter()
        .find(|v| v.at.norm() < 1e-3)
        .expect("a vertex at the centre");
    let clearance = sc
        .sites()
        .iter()
        .map(|s| poly_dist(centre.at, &dense(&s.kind, 4000)))
        .fold(f64::INFINITY, f64::min);
    assert!((clearance - 0.7).abs() < 1e-3, "{clearance}");
    // the zone boundary of every joint runs along its normal from the joint: one edge
    // ends there
    let loose: Vec<Point> = d
        .edges
        .iter()
        .flat_map(|e| [(e.from, e.points[0]), (e.to, *e.points.last().unwrap())])
        .filter_map(|(v, p)| v.is_none().then_some(p))
        .collect();
    for s in sc.sites() {
        let SiteKind::Bezier { control_points, .. } = &s.kind else {
            unreachable!()
        };
        let joint = control_points[0];
        let ends = loose.iter().filter(|p| p.dist(joint) < 1e-6).count();
        assert_eq!(ends, 1, "{ends} edges end at the joint {joint:?}");
    }
    assert_eq!(loose.len(), sc.sites().len());
}

/// The centre of the circle through `a`, `b`, `c`.
fn circumcentre(a: Point, b: Point, c: Point) -> Point {
    let (b, c) = (b - a, c - a);
    let d = 2.0 * b.cross(c);
    let (bb, cc) = (b.dot(b), c.dot(c));
    a + Point::new(c.y * bb - b.y * cc, b.x * cc - c.x * bb) * (1.0 / d)
}

#[test]
fn deep_concavity_axis_ends_at_centres_of_curvature_and_verify_checks_it() {
    let sc = scene("freeform-deep-concavity-medial_axis.json");
    let d = run(&sc, Engine::Freeform);
    let eps = sc.epsilon();
    // the axis' free ends are the centres of curvature at the curve's curvature
    // maxima: the circle through three dense samples about each end's foot
    let curve = dense(&sc.sites()[0].kind, 200_000);
    let ends: Vec<_> = d.vertices.iter().filter(|v| v.sites.len() == 2).collect();
    assert_eq!(ends.len(), 2, "{:?}", d.vertices);
    for v in ends {
        let (k, _) = curve
            .iter()
            .enumerate()
            .map(|(k, p)| (k, p.dist(v.at)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        let n = curve.len() - 1; // the last point repeats the first
        let at = |j: isize| curve[(k as isize + j).rem_euclid(n as isize) as usize];
        // the tightest circle through samples 100 apart near the foot: the curvature
        // maximum
        let centre = (-3000..=3000)
            .map(|j| circumcentre(at(j - 100), at(j), at(j + 100)))
            .zip((-3000..=3000).map(at))
            .min_by(|a, b| a.0.dist(a.1).total_cmp(&b.0.dist(b.1)))
            .unwrap()
            .0;
        assert!(centre.dist(v.at) < 0.5 * eps, "{:?} vs {centre:?}", v.at);
    }
    // `gvd verify` passes the diagram, and fails it moved by 10ε or with an end
    // pushed 10ε beyond its centre of curvature
    let verified = |d: &VoronoiComplex| gvd::verify(&sc, d, &Default::default()).unwrap();
    let report = verified(&d);
    assert!(report.passed, "{:?}", report.problems);
    let mut moved = d.clone();
    let shift = Point::new(10.0 * eps, 0.0);
    moved
        .edges
        .iter_mut()
        .for_each(|e| e.points.iter_mut().for_each(|p| *p = *p + shift));
    moved.vertices.iter_mut().for_each(|v| v.at = v.at + shift);
    assert!(!verified(&moved).passed);
    let mut longer = d.clone();
    let edge = &mut longer.edges[0];
    let (last, before) = (
        edge.points[edge.points.len() - 1],
        edge.points[edge.points.len() - 20],
    );
    let beyond = last + (last - before) * (10.0 * eps / last.dist(before));
    edge.points.push(beyond);
    let end = edge.to.expect("the axis ends at a vertex");
    longer.vertices[end].at = beyond;
    assert!(!verified(&longer).passed);
}

#[test]
fn near_a_ridge_end_the_axis_keeps_to_points_with_two_nearest_points() {
    // near the end of a ridge, the points with two nearest points on the curve are a
    // cusp between two branches of the evolute, narrowing like σ^{3/2} with the
    // distance σ from the end; a chord within ε of the deep concavity's axis left it
    // 0.005 from the end (both engines), and its points there had one nearest point
    let sc = scene("freeform-deep-concavity-medial_axis.json");
    let eps = sc.epsilon();
    let curve = dense(&sc.sites()[0].kind, 200_000);
    let n = curve.len() - 1; // the last point repeats the first
    for engine in [Engine::Freeform, Engine::Subdivision] {
        let d = run(&sc, engine);
        let ends: Vec<Point> = d
            .vertices
            .iter()
            .filter(|v| v.sites.len() == 2)
            .map(|v| v.at)
            .collect();
        assert_eq!(ends.len(), 2, "{engine:?}: {:?}", d.vertices);
        let mut tested = 0;
        for w in d.edges.iter().flat_map(|e| e.points.windows(2)) {
            for k in 0..16 {
                let q = w[0] + (w[1] - w[0]) * (k as f64 / 16.0);
                let sigma = ends.iter().map(|c| c.dist(q)).fold(f64::INFINITY, f64::min);
                if !(eps..0.05).contains(&sigma) {
                    continue;
                }
                let dist: Vec<f64> = curve[..n].iter().map(|p| p.dist(q)).collect();
                let nearest = dist.iter().copied().fold(f64::INFINITY, f64::min);
                let minima = (0..n)
                    .filter(|&i| {
                        let (before, after) = (dist[(i + n - 1) % n], dist[(i + 1) % n]);
                        dist[i] <= before && dist[i] < after && dist[i] <= nearest + eps
                    })
                    .count();
                assert!(
                    minima >= 2,
                    "{engine:?}: {q:?}, {sigma:.4} from the axis' end, has one nearest point"
                );
                tested += 1;
            }
        }
        assert!(tested > 20, "{engine:?}: {tested} points near the ends");
    }
}

#[test]
fn a_bspline_with_an_interior_cusp_gets_a_corner_and_its_point_bisector() {
    // a cubic with a triple interior knot: a C0 corner at the knot (pointing at the
    // segment below), beside a straight cubic
    let text = r#"{"domain": [-2, -2, 2, 2], "epsilon": 0.001, "sites": [
        {"kind": "bspline", "degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2],
         "control_points": [[-1.2, 0.8], [-0.9, 0.3], [-0.4, 0.1], [0.0, -0.3], [0.4, 0.1], [0.9, 0.3], [1.2, 0.8]]},
        {"kind": "bezier", "control_points": [[-1.0, -1.0], [-0.3, -1.1], [0.3, -0.9], [1.0, -1.0]]}]}"#;
    let sc = Scene::from_json(text).unwrap();
    let d = run(&sc, Engine::Freeform);
    assert_eq!(d.stats["corners"], 5); // the cusp and the four open ends
    check_by_brute_force(&sc, &d);
    // the edge passes below the cusp, where the cusp point itself is the nearest
    let below = Point::new(0.0, -0.3 - 0.5 * (1.0 - 0.3));
    let near = d
        .edges
        .iter()
        .flat_map(|e| e.points.iter())
        .map(|p| p.dist(below))
        .fold(f64::INFINITY, f64::min);
    assert!(near < 0.05, "no edge below the cusp ({near})");
}

#[test]
fn other_site_kinds_are_refused_by_name() {
    let text = r#"{"domain": [-2, -2, 2, 2], "sites": [
        {"kind": "bezier", "control_points": [[0, 0], [1, 1]]},
        {"kind": "point", "at": [1, -1]}]}"#;
    let sc = Scene::from_json(text).unwrap();
    let err = compute(
        &sc,
        &Options {
            engine: Engine::Freeform,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(matches!(err, Error::Unsupported { site: 1, .. }), "{err}");
}

/// The letter O of DejaVu Serif, read from the shipped SVG (22 quadratic pieces in two
/// contours under a flipping transform): its medial axis lies in the ring between the
/// contours (the counter is a hole), equidistant from its generators; pruned at λ = 20
/// font units it is one closed loop with no vertex, a third of the ring's width and
/// more from both contours.
#[test]
fn medial_axis_of_the_letter_o_read_from_svg() {
    use gvd::io::{read_scene, Format, ReadOptions};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/glyph-O.svg");
    let options = ReadOptions {
        mode: Some(Mode::MedialAxis),
        ..Default::default()
    };
    let (sc, warnings) = read_scene(&std::fs::read(path).unwrap(), Format::Svg, &options).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(sc.sites().len(), 22);
    let d = run(&sc, Engine::Auto);
    check_medial_axis_by_brute_force(&sc, &d, 2);
    let counter: Vec<Point> = sc.sites()[..8]
        .iter()
        .flat_map(|s| dense(&s.kind, 400))
        .collect();
    for e in &d.edges {
        for q in &e.points {
            assert!(!inside(*q, &counter), "{q:?} in the counter");
        }
    }
    let pruned = compute(
        &sc,
        &Options {
            prune: gvd::Pruning {
                lambda: Some(20.0),
                object_angle: None,
            },
            ..Default::default()
        },
    )
    .unwrap();
    assert!(
        pruned.vertices.is_empty(),
        "{} vertices",
        pruned.vertices.len()
    );
    assert_eq!(pruned.edges.len(), 1);
    let ring = &pruned.edges[0];
    assert_eq!((ring.from, ring.to), (None, None));
    assert_eq!(ring.points.first(), ring.points.last());
    let curves: Vec<Vec<Point>> = sc.sites().iter().map(|s| dense(&s.kind, 400)).collect();
    for q in &ring.points {
        let to_counter = curves[..8]
            .iter()
            .map(|c| poly_dist(*q, c))
            .fold(f64::INFINITY, f64::min);
        let to_outside = curves[8..]
            .iter()
            .map(|c| poly_dist(*q, c))
            .fold(f64::INFINITY, f64::min);
        assert!(
            (to_counter - to_outside).abs() < 2.0 * sc.epsilon(),
            "{q:?}"
        );
        assert!(to_counter > 50.0, "{q:?} {to_counter}");
    }
}

/// The letter A of DejaVu Sans, its outline (a contour and a triangular counter) as
/// pieces joined end to end: degree-1 Bézier sites, or one polygon.
const GLYPH_A: [&[[f64; 2]]; 2] = [
    &[
        [586.0, 1493.0],
        [815.0, 1493.0],
        [1384.0, 0.0],
        [1174.0, 0.0],
        [1038.0, 383.0],
        [365.0, 383.0],
        [229.0, 0.0],
        [16.0, 0.0],
    ],
    &[[700.0, 1294.0], [426.0, 551.0], [975.0, 551.0]],
];

fn glyph_a_scene(sites: &str) -> Scene {
    Scene::from_json(&format!(
        r#"{{"domain": [-133, -149, 1533, 1642], "epsilon": 1.79, "mode": "medial_axis",
             "sites": [{sites}]}}"#
    ))
    .unwrap()
}

/// Every end of an edge that is no vertex lies at one of `joints` (the zone boundary of
/// a joint without a corner starts there), or on the domain's boundary.
fn no_loose_ends(sc: &Scene, d: &VoronoiComplex, joints: &[Point]) {
    let domain = sc.domain();
    for e in &d.edges {
        for (v, p) in [(e.from, e.points[0]), (e.to, *e.points.last().unwrap())] {
            let on_boundary = [p.x - domain.min.x, domain.max.x - p.x]
                .into_iter()
                .chain([p.y - domain.min.y, domain.max.y - p.y])
                .any(|s| s.abs() < 1e-9 * domain.longest_side());
            let at_joint = joints
                .iter()
                .any(|j| j.dist(p) < 1e-6 * domain.longest_side());
            assert!(
                v.is_some() || on_boundary || at_joint,
                "edge {:?} ends loose at {p:?}",
                e.sites
            );
        }
    }
}

/// The outline of a letter of straight pieces as degree-1 Bézier sites, through the
/// free-form engine (bisectors in parameter space), against the same outline as a
/// polygon through the incremental engine (topology-oriented): the same vertices (the
/// parallel bar and counter bottom share a bisector along which both normals are one
/// line), and every edge of each within epsilon of the other's. At each of the six
/// convex corners of the contour a vertex ends the axis.
#[test]
fn lines_as_degree_one_beziers_agree_with_the_incremental_polygon() {
    let pieces: Vec<String> = GLYPH_A
        .iter()
        .flat_map(|ring| {
            (0..ring.len()).map(move |k| {
                let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
                format!(r#"{{"kind": "bezier", "control_points": [{a:?}, {b:?}]}}"#)
            })
        })
        .collect();
    let ff_scene = glyph_a_scene(&pieces.join(", "));
    let ff = run(&ff_scene, Engine::Freeform);
    assert_eq!(ff.stats["engine"], "freeform");
    let rings: Vec<String> = GLYPH_A.iter().map(|r| format!("{r:?}")).collect();
    let polygon = format!(r#"{{"kind": "polygon", "rings": [{}]}}"#, rings.join(", "));
    let inc = run(&glyph_a_scene(&polygon), Engine::Incremental);
    let eps = ff_scene.epsilon();
    assert_eq!(ff.vertices.len(), inc.vertices.len());
    for v in &ff.vertices {
        let near = inc.vertices.iter().map(|w| w.at.dist(v.at));
        let d = near.fold(f64::INFINITY, f64::min);
        assert!(d < 1e-3 * eps, "no incremental vertex at {:?} ({d})", v.at);
    }
    for (a, b) in [(&ff, &inc), (&inc, &ff)] {
        for q in a.edges.iter().flat_map(|e| e.points.iter()) {
            let d = b
                .edges
                .iter()
                .map(|e| poly_dist(*q, &e.points))
                .fold(f64::INFINITY, f64::min);
            assert!(d < eps, "{q:?} is {d} from the other diagram");
        }
    }
    no_loose_ends(&ff_scene, &ff, &[]);
    // (the two reflex corners, at the bar's ends, are generators)
    for c in GLYPH_A[0].iter().filter(|c| c[1] != 383.0) {
        let c = Point::new(c[0], c[1]);
        assert!(ff.vertices.iter().any(|v| v.at == c), "no vertex at {c:?}");
    }
}

/// The ends of the sites of a chain, where they join.
fn joints(sc: &Scene) -> Vec<Point> {
    sc.sites()
        .iter()
        .map(|s| match &s.kind {
            SiteKind::Bezier { control_points, .. } => control_points[0],
            k => panic!("{k:?}"),
        })
        .collect()
}

/// The joints of a chain where the tangent turns by more than `angle` (radians).
fn corners(sc: &Scene, angle: f64) -> Vec<Point> {
    let ends: Vec<(Point, Point, Point, Point)> = sc
        .sites()
        .iter()
        .map(|s| match &s.kind {
            SiteKind::Bezier {
                control_points: c, ..
            } => {
                let n = c.len() - 1;
                (c[0], c[1] - c[0], c[n], c[n] - c[n - 1])
            }
            k => panic!("{k:?}"),
        })
        .collect();
    let unit = |v: Point| v * (1.0 / v.norm());
    let mut out = Vec::new();
    for &(at, t_out, ..) in &ends {
        let Some(&(.., t_in)) = ends.iter().find(|e| e.2 == at) else {
            continue;
        };
        if unit(t_in).dot(unit(t_out)) < angle.cos() {
            out.push(at);
        }
    }
    out
}

/// A corner where the axis arrives (convex) is a vertex; a reflex one is a generator of
/// a vertex (corner 0 of a Bézier site is its start, corner 1 its end).
fn corners_are_vertices_or_generators(sc: &Scene, d: &VoronoiComplex, corners: &[Point]) {
    let tol = 1e-9 * sc.domain().longest_side();
    let corner_at = |g: &gvd::complex::Generator| match *g {
        gvd::complex::Generator::Feature {
            site,
            feature: gvd::complex::FeatureKind::Corner,
            index,
        } => match &sc.sites()[site].kind {
            SiteKind::Bezier { control_points, .. } => {
                Some(control_points[index * (control_points.len() - 1)])
            }
            k => panic!("{k:?}"),
        },
        _ => None,
    };
    for &c in corners {
        let vertex = d.vertices.iter().any(|v| v.at.dist(c) < tol);
        let generator = d
            .vertices
            .iter()
            .flat_map(|v| v.sites.iter())
            .any(|g| corner_at(g).is_some_and(|p| p.dist(c) < tol));
        assert!(
            vertex || generator,
            "the corner {c:?} is neither a vertex nor a generator"
        );
    }
}

/// The letter g of DejaVu Sans read from the shipped SVG, whose outline mixes lines and
/// quadratic pieces: one chain of Bézier sites per contour (lines of degree 1), its
/// medial axis inside the ink and equidistant from its generators, with no loose end,
/// a vertex at each convex corner and the reflex ones among the generators.
#[test]
fn medial_axis_of_the_letter_g_with_lines_read_from_svg() {
    use gvd::io::{read_scene, Format, ReadOptions};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/glyph-g.svg");
    let options = ReadOptions {
        mode: Some(Mode::MedialAxis),
        ..Default::default()
    };
    let (sc, warnings) = read_scene(&std::fs::read(path).unwrap(), Format::Svg, &options).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let degree = |s: &gvd::Site| match &s.kind {
        SiteKind::Bezier { control_points, .. } => control_points.len() - 1,
        k => panic!("{k:?}"),
    };
    let lines = sc.sites().iter().filter(|s| degree(s) == 1).count();
    assert_eq!((sc.sites().len(), lines), (29, 5));
    let d = run(&sc, Engine::Auto);
    assert_eq!(d.stats["engine"], "freeform");
    check_medial_axis_by_brute_force(&sc, &d, 2);
    no_loose_ends(&sc, &d, &joints(&sc));
    let sharp = corners(&sc, 0.1);
    assert_eq!(sharp.len(), 6, "{sharp:?}");
    corners_are_vertices_or_generators(&sc, &d, &sharp);
}

/// The glyph of 20 joined cubics with one control point moved off the tangent at a
/// joint: a real corner there, convex or reflex. Convex, the axis reaches it along the
/// bisector of its two pieces and ends at a vertex there; reflex, it is a point
/// generator; either way no edge ends loose.
#[test]
fn a_corner_at_one_joint_of_a_chain() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/freeform/freeform-glyph20-medial_axis.json");
    let base: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    // site 3's second control point moved along its last leg P₃ − P₂: its joint with
    // site 2 turns, while its curvature at the far end, (2/3) |(P₁ − P₂) × (P₃ − P₂)| /
    // |P₃ − P₂|³, stays as it was
    for (s, convex) in [(0.4, true), (-0.4, false)] {
        let mut v = base.clone();
        let cp = |v: &serde_json::Value, k: usize, c: usize| {
            v["sites"][3]["control_points"][k][c].as_f64().unwrap()
        };
        for c in 0..2 {
            let moved = cp(&v, 1, c) + s * (cp(&v, 3, c) - cp(&v, 2, c));
            v["sites"][3]["control_points"][1][c] = serde_json::json!(moved);
        }
        let sc = Scene::from_json(&v.to_string()).unwrap();
        let d = run(&sc, Engine::Freeform);
        check_medial_axis_by_brute_force(&sc, &d, 3);
        no_loose_ends(&sc, &d, &joints(&sc));
        let corner = joints(&sc)[3];
        assert_eq!(corners(&sc, 1e-3), [corner]);
        let at_corner = d.vertices.iter().any(|v| v.at.dist(corner) < 1e-9);
        assert_eq!(at_corner, convex, "s {s}");
        corners_are_vertices_or_generators(&sc, &d, &[corner]);
    }
}

/// The two cubic sites of the 20-cubic glyph that meet at a notch, where the curvature
/// of both peaks at the joint (-16.628, the two within 1e-5 of each other, and a kink
/// of 1.3e-5 rad from the rounded coordinates, below what the output resolves: no
/// corner). Along the joint's normal both feet stay at the joint past the centre of
/// curvature (the distance to either curve there is flat to fourth order), until the
/// ridge of the two curves takes over. The curvature constraint used to stop the
/// normal at the centre of curvature, 2.7e-4 short of the ridge's trace: two loose
/// ends, in `voronoi` mode (the two sites alone) and in `medial_axis` mode (closed by
/// two lines on the notch's concave side), and `gvd verify` failed their structure.
#[test]
fn the_normal_at_a_notch_runs_past_the_centre_of_curvature_into_the_ridge() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/freeform/freeform-glyph20-medial_axis.json");
    let glyph: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let (a, b) = (&glyph["sites"][5], &glyph["sites"][6]);
    let (start, end) = (&a["control_points"][0], &b["control_points"][3]);
    let top = serde_json::json!([-0.3, 1.6]);
    let line = |p: &serde_json::Value, q: &serde_json::Value| serde_json::json!({"kind": "bezier", "control_points": [p, q]});
    for (mode, sites) in [
        ("voronoi", serde_json::json!([a, b])),
        (
            "medial_axis",
            serde_json::json!([a, b, line(end, &top), line(&top, start)]),
        ),
    ] {
        let v = serde_json::json!({"domain": [-1.0, 0.4, 0.6, 2.0], "epsilon": 0.001,
                                   "mode": mode, "sites": sites});
        let sc = Scene::from_json(&v.to_string()).unwrap();
        let d = run(&sc, Engine::Freeform);
        no_loose_ends(&sc, &d, &joints(&sc));
        let options = gvd::VerifyOptions {
            grid: 128,
            ..Default::default()
        };
        let report = gvd::verify(&sc, &d, &options).unwrap();
        assert!(report.passed, "{mode}: {report:?}");
    }
}

/// The subdivision engine's distance field of free-form curves (a tree of sub-spans)
/// against the free-form engine (bisectors in parameter space): two algorithm families,
/// the same vertices within a few epsilon with the same generators, and the same
/// adjacency; the subdivision's edges pass the brute-force check too.
#[test]
fn the_subdivision_engine_agrees_with_the_freeform_engine() {
    for name in [
        "freeform-convex3-voronoi.json",
        "freeform-nonconvex2-voronoi.json",
        "freeform-closed6-voronoi.json",
    ] {
        let sc = scene(name);
        let sub = run(&sc, Engine::Subdivision);
        let ff = run(&sc, Engine::Freeform);
        assert_eq!(sub.stats["engine"], "subdivision");
        check_by_brute_force(&sc, &sub);
        same_vertices(&sub, &ff, 4.0 * sc.epsilon());
        assert_eq!(edge_pairs(&sub), edge_pairs(&ff), "{name}");
    }
}

/// Free-form curves mix with points, circles and algebraic curves in one scene (only
/// the subdivision engine takes them all): `auto` picks it, and `gvd verify`, with its
/// own distances to the curves, passes the diagram.
#[test]
fn curves_mix_with_points_circles_and_algebraic_curves() {
    let sc = scene("mixed-kinds-voronoi.json");
    let d = run(&sc, Engine::Auto);
    assert_eq!(d.stats["engine"], "subdivision");
    assert_eq!(d.stats["uncertified_boxes"], 0);
    assert_eq!(d.cells.len(), sc.sites().len());
    let report = gvd::verify(&sc, &d, &gvd::VerifyOptions::default()).unwrap();
    assert!(report.passed, "{report:?}");
    // every site meets another: 10 edges about 5 vertices
    assert_eq!((d.vertices.len(), d.edges.len()), (5, 10));
}

/// Segments, polylines, arcs and polygons are curves of straight and exact circular
/// spans to the subdivision engine, so they mix with free-form curves, points and
/// circles in one `voronoi` scene: `auto` picks it, and `gvd verify` passes the
/// diagram. Such a site sharing an end with another is refused (a tie over a wedge).
#[test]
fn curves_mix_with_segments_polylines_arcs_and_polygons() {
    let sc = scene("mixed-linear-voronoi.json");
    let d = run(&sc, Engine::Auto);
    assert_eq!(d.stats["engine"], "subdivision");
    assert_eq!(d.cells.len(), sc.sites().len());
    let report = gvd::verify(&sc, &d, &gvd::VerifyOptions::default()).unwrap();
    assert!(report.passed, "{report:?}");
    // every site has a cell that meets another's
    let pairs = edge_pairs(&d);
    for i in 0..sc.sites().len() {
        assert!(
            pairs.iter().any(|p| p.contains(&i)),
            "site {i} meets no other"
        );
    }
    // the segment moved to start where the curve ends
    let mut shared = sc.sites().to_vec();
    shared[1] = gvd::Site::segment([0.0, 1.5], [1.0, 2.2]);
    let shared = Scene::new(sc.domain(), sc.epsilon(), sc.mode(), shared).unwrap();
    let err = compute(&shared, &Options::default()).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Conflict {
                site: 0,
                other: 1,
                ..
            }
        ),
        "{err}"
    );
}

/// The same segments, polyline, arc, polygon and points by the subdivision engine (as
/// fields: the arc keeps it off the soft-predicate path) and by the exact incremental
/// engine: the same vertices within epsilon with the same sites, the same edge pairs.
#[test]
fn segment_arc_and_polygon_fields_agree_with_the_incremental_engine() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/scenes/linear-arcs-points-voronoi.json");
    let sc = Scene::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let sub = run(&sc, Engine::Subdivision);
    let inc = run(&sc, Engine::Incremental);
    assert_eq!(sub.stats["engine"], "subdivision");
    assert_eq!(inc.stats["engine"], "incremental");
    same_vertices(&sub, &inc, sc.epsilon());
    assert_eq!(edge_pairs(&sub), edge_pairs(&inc));
}

/// A polygon is solid: the subdivision engine, which sees it by its boundary's
/// distance, refuses a site that reaches inside it, naming both; in `complex` mode it
/// refuses segments beside other kinds (their generators there are ends and edges).
#[test]
fn the_subdivision_engine_refuses_sites_inside_polygons_and_whole_segments_in_complex_mode() {
    let text = |mode: &str, arc_radius: f64| {
        format!(
            r#"{{"domain": [-2, -2, 2, 2], "epsilon": 0.001, "mode": "{mode}", "sites": [
            {{"kind": "bezier", "control_points": [[-1, 0], [-0.5, 1], [0.5, -1], [1, 0]]}},
            {{"kind": "arc", "center": [0, 0], "radius": {arc_radius}, "start_angle": 0.5, "end_angle": 2.5}},
            {{"kind": "polygon", "rings": [[[1.2, 0.8], [1.6, 0.8], [1.6, 1.2]]]}}]}}"#
        )
    };
    let compute_text = |t: String| {
        compute(
            &Scene::from_json(&t).unwrap(),
            &Options {
                engine: Engine::Subdivision,
                ..Default::default()
            },
        )
    };
    // the arc of radius 1.6 runs through the triangle; at radius 1.3 it passes by
    match compute_text(text("voronoi", 1.6)) {
        Err(Error::Conflict {
            site: 1,
            other: 2,
            message,
        }) => {
            assert!(message.contains("reaches inside the polygon"), "{message}")
        }
        other => panic!("{other:?}"),
    }
    assert!(compute_text(text("voronoi", 1.3)).is_ok());
    let circle_and_segment = r#"{"domain": [-2, -2, 2, 2], "mode": "complex", "sites": [
        {"kind": "circle", "center": [0, 0], "radius": 0.5},
        {"kind": "segment", "from": [1, -1], "to": [1, 1]}]}"#;
    for engine in [Engine::Auto, Engine::Subdivision] {
        let err = compute(
            &Scene::from_json(circle_and_segment).unwrap(),
            &Options {
                engine,
                ..Default::default()
            },
        )
        .unwrap_err();
        assert!(
            matches!(&err, Error::Unsupported { site: 1, .. })
                && err.to_string().contains("'voronoi' mode only"),
            "{engine:?}: {err}"
        );
    }
}

/// In `complex` and `medial_axis` modes the subdivision engine computes curves by
/// their pieces and corners (runs of spans without a ridge of their own, corners as
/// points, zone boundaries removed): the same vertices as the free-form engine within a
/// few epsilon with the same generators (a corner, a piece twice on a ridge's ends),
/// the same edge pairs, and `gvd verify` passes.
#[test]
fn the_subdivision_engine_agrees_by_features_in_complex_and_medial_axis_modes() {
    for name in [
        "freeform-bezier4-medial_axis.json",
        "freeform-piecewise-c1-complex.json",
        "freeform-deep-concavity-medial_axis.json",
    ] {
        let sc = scene(name);
        let sub = run(&sc, Engine::Subdivision);
        let ff = run(&sc, Engine::Freeform);
        assert_eq!(sub.stats["engine"], "subdivision");
        same_vertices(&sub, &ff, 4.0 * sc.epsilon());
        assert_eq!(edge_pairs(&sub), edge_pairs(&ff), "{name}");
        let report = gvd::verify(&sc, &sub, &gvd::VerifyOptions::default()).unwrap();
        assert!(report.passed, "{name}: {report:?}");
    }
}

/// In `medial_axis` mode both engines refuse curves that bound no region (a fuzzed
/// bezier4 whose chain no longer closes up was computed by the subdivision engine
/// with loose edges).
#[test]
fn open_curves_have_no_medial_axis_by_either_engine() {
    let text = r#"{"domain": [-1, -1, 3, 3], "epsilon": 0.01, "mode": "medial_axis", "sites": [
        {"kind": "bezier", "control_points": [[0, 0], [1, 2], [2, 0]]}]}"#;
    let sc = Scene::from_json(text).unwrap();
    for engine in [Engine::Freeform, Engine::Subdivision] {
        let err = compute(
            &sc,
            &Options {
                engine,
                ..Default::default()
            },
        )
        .unwrap_err();
        assert!(err.to_string().contains("bound none"), "{engine:?}: {err}");
    }
}

/// Beside free-form curves in those modes the subdivision engine refuses sites whose
/// features it does not name (a segment), and in `medial_axis` mode any other kind,
/// naming the site.
#[test]
fn the_subdivision_engine_refuses_other_featured_sites_beside_curves() {
    let curve = r#"{"kind": "bezier", "control_points": [[0, 0], [1, 2], [2, 0]]}"#;
    for (mode, other) in [
        (
            "complex",
            r#"{"kind": "segment", "from": [3, 0], "to": [3, 1]}"#,
        ),
        ("medial_axis", r#"{"kind": "point", "at": [3, 0]}"#),
    ] {
        let text = format!(
            r#"{{"domain": [-1, -1, 4, 3], "epsilon": 0.01, "mode": "{mode}", "sites": [{curve}, {other}]}}"#
        );
        let sc = Scene::from_json(&text).unwrap();
        let err = compute(
            &sc,
            &Options {
                engine: Engine::Subdivision,
                ..Default::default()
            },
        )
        .unwrap_err();
        assert!(
            matches!(&err, Error::Unsupported { site: 1, message, .. } if message.contains("--engine freeform")),
            "{mode}: {err}"
        );
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// The subdivision engine's field of a rational cubic B-spline: over random boxes
    /// the bounds enclose the distance of a dense Cox–de Boor sampling, the point value
    /// agrees with it, and the gradient bound holds the gradient at the point.
    #[test]
    fn freeform_box_bounds_enclose_the_sampled_distance(
        x in -2.0f64..1.9, y in -2.0f64..1.9, w in 0.0005f64..0.5, u in 0.0f64..1.0, v in 0.0f64..1.0
    ) {
        use gvd::internals::{DistanceField, SiteField};
        let sc = scene("freeform-nonconvex2-voronoi.json");
        let kind = &sc.sites()[0].kind;
        let curve = dense(kind, 20000);
        let f = SiteField::from_site(0, kind, &sc.domain()).unwrap();
        let b = gvd::Aabb::from_array([x, y, x + w, y + w]);
        let s = f.state(&b);
        let q = Point::new(x + u * w, y + v * w);
        let d = poly_dist(q, &curve);
        let r = f.bound(&s, &b);
        // the sampling's chords lie within 1e-7 of the curve
        proptest::prop_assert!(r.lo <= d + 1e-12 && d <= r.hi + 1e-7, "{r} vs {d} at {q:?}");
        proptest::prop_assert!((f.value(q) - d).abs() < 1e-7, "value {} vs {d}", f.value(q));
        proptest::prop_assert!((f.value_in(&s, q) - d).abs() < 1e-7);
        let g = f.gradient(q);
        let gb = f.gradient_bound(&s, &b).unwrap();
        proptest::prop_assert!(gb[0].contains(g.x) && gb[1].contains(g.y), "{gb:?} vs {g:?}");
    }
}

/// The end points of a Bézier or B-spline site (its first and last control points).
fn ends(kind: &SiteKind) -> [Point; 2] {
    let pts = match kind {
        SiteKind::Bezier { control_points, .. } | SiteKind::Bspline { control_points, .. } => {
            control_points
        }
        _ => panic!("not a curve"),
    };
    [pts[0], pts[pts.len() - 1]]
}

/// Open sites joined end to end in `voronoi` mode (the letter O's 22 pieces read from
/// SVG, each its own site): the common normal at each smooth joint is an edge of the two
/// sites, so every pair of sites that share an end point has an edge; the diagram
/// passes `gvd verify` (it failed completeness without those edges) and agrees with the
/// subdivision engine's, which takes each site's exact distance: each of its edge pairs
/// is there, and each vertex of three sites or more lies within epsilon of one of its
/// vertices with the same sites or more (a vertex of four sites on the glyph's mirror axis may come as two of
/// three, closer than epsilon).
#[test]
fn joined_sites_in_voronoi_mode_are_split_by_the_normals_at_their_joints() {
    use gvd::io::{read_scene, Format, ReadOptions};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/glyph-O.svg");
    let (sc, _) = read_scene(
        &std::fs::read(path).unwrap(),
        Format::Svg,
        &ReadOptions::default(),
    )
    .unwrap();
    assert_eq!(sc.mode(), Mode::Voronoi);
    let ff = run(&sc, Engine::Freeform);
    let pairs = edge_pairs(&ff);
    let sites = sc.sites();
    let tol = 1e-9 * sc.domain().longest_side();
    let mut joined = 0;
    for i in 0..sites.len() {
        for j in i + 1..sites.len() {
            let (a, b) = (ends(&sites[i].kind), ends(&sites[j].kind));
            if a.iter().any(|p| b.iter().any(|q| p.dist(*q) <= tol)) {
                joined += 1;
                assert!(
                    pairs.contains(&[i, j]),
                    "no edge between joined sites {i} and {j}"
                );
            }
        }
    }
    assert_eq!(joined, 22);
    let options = gvd::VerifyOptions {
        grid: 128,
        ..Default::default()
    };
    let report = gvd::verify(&sc, &ff, &options).unwrap();
    assert!(report.passed, "{report:?}");
    let sub = run(&sc, Engine::Subdivision);
    for p in edge_pairs(&sub) {
        assert!(pairs.contains(&p), "subdivision edge {p:?} missing");
    }
    // (vertices of two sites only mark where an edge's nearest spans change)
    for v in ff.vertices.iter().filter(|v| v.sites.len() >= 3) {
        assert!(
            sub.vertices
                .iter()
                .any(|w| w.at.dist(v.at) < sc.epsilon()
                    && v.sites.iter().all(|s| w.sites.contains(s))),
            "vertex {:?} of {:?}",
            v.at,
            v.sites
        );
    }
}

/// A point and the unit tangent of the rational Bézier of homogeneous control points
/// `h` at `t` (de Casteljau, and the tangent by a central difference).
fn bezier_at(h: &[[f64; 3]], t: f64) -> (Point, Point) {
    let eval = |t: f64| {
        let mut v = h.to_vec();
        for r in (1..v.len()).rev() {
            for i in 0..r {
                v[i] = std::array::from_fn(|k| v[i][k] + (v[i + 1][k] - v[i][k]) * t);
            }
        }
        Point::new(v[0][0] / v[0][2], v[0][1] / v[0][2])
    };
    let dt = 1e-7;
    let d = eval((t + dt).min(1.0)) - eval((t - dt).max(0.0));
    (eval(t), d * (1.0 / d.norm()))
}

/// Where the normals of two curves at `a` (tangent `ta`) and `b` (tangent `tb`) meet.
fn normals_meet(a: Point, ta: Point, b: Point, tb: Point) -> Option<Point> {
    // (p − a)·ta = 0 and (p − b)·tb = 0
    let det = ta.x * tb.y - ta.y * tb.x;
    if det.abs() < 1e-12 {
        return None;
    }
    let (ca, cb) = (a.dot(ta), b.dot(tb));
    Some(Point::new(
        (ca * tb.y - cb * ta.y) / det,
        (ta.x * cb - tb.x * ca) / det,
    ))
}

/// The arc length along the polyline `pts` to its point nearest to `p`.
fn along(p: Point, pts: &[Point]) -> f64 {
    let mut best = (f64::INFINITY, 0.0);
    let mut run = 0.0;
    for w in pts.windows(2) {
        let d = w[1] - w[0];
        let len = d.norm();
        let u = if len > 0.0 {
            ((p - w[0]).dot(d) / (len * len)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let dist = p.dist(w[0] + d * u);
        if dist < best.0 {
            best = (dist, run + u * len);
        }
        run += len;
    }
    best.1
}

/// The free-form engine's edges carry their pieces in parameter space: at each piece's
/// end feet and at its middle (`r` found here by bisection on the equal-distance
/// condition), the point where the two spans' normals meet is equidistant from them and
/// lies within epsilon of the edge's polyline, and each piece runs in the edge's
/// direction.
#[test]
fn edges_carry_their_pieces_in_parameter_space() {
    for name in [
        "freeform-convex3-voronoi.json",
        "freeform-closed6-voronoi.json",
    ] {
        let sc = scene(name);
        let d = run(&sc, Engine::Freeform);
        let eps = sc.epsilon();
        let mut checked = 0;
        for e in &d.edges {
            assert!(!e.parametric.is_empty(), "{name}: an edge without pieces");
            let on_edge = |p: Point| poly_dist(p, &e.points) < eps;
            for piece in &e.parametric {
                let [c0, c1] = &piece.curves;
                let (Some(t0), Some(r0), Some(t1), Some(r1)) =
                    (piece.from[0], piece.from[1], piece.to[0], piece.to[1])
                else {
                    continue;
                };
                if c0.len() < 2 || c1.len() < 2 {
                    continue;
                }
                let point = |t: f64, r: f64| {
                    let ((a, ta), (b, tb)) = (bezier_at(c0, t), bezier_at(c1, r));
                    normals_meet(a, ta, b, tb).map(|p| (p, p.dist(a) - p.dist(b)))
                };
                for (t, r) in [(t0, r0), (t1, r1)] {
                    // (feet at a joint of two spans: the normals are parallel there)
                    if let Some((p, diff)) = point(t, r) {
                        assert!(diff.abs() < eps && on_edge(p), "{name}: {p:?} {diff}");
                        checked += 1;
                    }
                }
                // the piece runs in the edge's direction
                if let (Some((p, _)), Some((q, _))) = (point(t0, r0), point(t1, r1)) {
                    let (a, b) = (along(p, &e.points), along(q, &e.points));
                    assert!(
                        a <= b + eps,
                        "{name}: piece from {a} to {b} against the edge"
                    );
                }
                // the middle: bisection on r for equal distances
                let t = 0.5 * (t0 + t1);
                let (mut lo, mut hi) = (r0.min(r1), r0.max(r1));
                let sign = |r: f64| point(t, r).map(|(_, diff)| diff.signum());
                let (Some(slo), Some(shi)) = (sign(lo), sign(hi)) else {
                    continue;
                };
                if slo == shi || (t1 - t0).abs() < 1e-6 {
                    continue;
                }
                for _ in 0..60 {
                    let m = 0.5 * (lo + hi);
                    if sign(m) == Some(slo) {
                        lo = m;
                    } else {
                        hi = m;
                    }
                }
                let (p, _) = point(t, 0.5 * (lo + hi)).unwrap();
                assert!(on_edge(p), "{name}: middle {p:?} off the edge");
                checked += 1;
            }
        }
        assert!(checked > 10, "{name}: {checked} points checked");
    }
}

/// The glyph of 20 joined cubics in `voronoi` mode: where a joint's normal runs past
/// the joint's centre of curvature into the bisector of the two spans, the trimming
/// leaves stubs of a few micrometres beside it, and they made a vertex of only two
/// sites there. The free-form engine's vertices are now the subdivision engine's
/// vertices of three sites or more, one to one, with the same sites (the subdivision
/// also leaves dangling ends of two sites beside some joints, not compared here).
#[test]
fn joints_in_voronoi_mode_make_no_vertices_of_two_sites() {
    let sc = scene("freeform-glyph20-medial_axis.json").with_mode(Mode::Voronoi);
    let ff = run(&sc, Engine::Freeform);
    let sub = run(&sc, Engine::Subdivision);
    let real: Vec<_> = sub.vertices.iter().filter(|v| v.sites.len() >= 3).collect();
    assert_eq!(ff.vertices.len(), real.len());
    for v in &ff.vertices {
        let w = real.iter().find(|w| w.at.dist(v.at) < sc.epsilon());
        let w = w.unwrap_or_else(|| panic!("no subdivision vertex near {:?}", v.at));
        assert_eq!(v.sites, w.sites);
    }
    assert_eq!(edge_pairs(&ff), edge_pairs(&sub));
    let report = gvd::verify(&sc, &ff, &gvd::VerifyOptions::default()).unwrap();
    assert!(report.passed, "{}", report.summary_line());
}

/// `complex` mode of the glyph of 20 joined open cubics: the chain bounds no solid (only
/// a closed curve is one, as a polygon is), so the diagram lies on both sides. It lay
/// outside only, as if the glyph were filled (both checkers: completeness 0.59; found
/// by fuzzing). Inside it is the medial axis: every vertex of the `medial_axis` diagram
/// is one of the complex's, with the same generators; and `gvd verify` passes it.
#[test]
fn a_chain_of_open_curves_has_its_complex_on_both_sides() {
    let medial = scene("freeform-glyph20-medial_axis.json");
    let complex = medial.clone().with_mode(Mode::Complex);
    let axis = run(&medial, Engine::Freeform);
    let whole = run(&complex, Engine::Freeform);
    assert!(whole.vertices.len() > axis.vertices.len());
    for v in &axis.vertices {
        let w = whole.vertices.iter().find(|w| w.at.dist(v.at) < 1e-9);
        let w = w.unwrap_or_else(|| panic!("medial-axis vertex {:?} missing", v.at));
        assert_eq!(v.sites, w.sites);
    }
    let report = gvd::verify(&complex, &whole, &gvd::VerifyOptions::default()).unwrap();
    assert!(report.passed, "{}", report.summary_line());
}

/// No vertex of degree two joins two edges of the same two generators: such a vertex
/// would only cut one edge in two.
fn no_vertex_inside_an_edge(d: &VoronoiComplex) {
    for (v, vertex) in d.vertices.iter().enumerate() {
        let pairs: Vec<_> = d
            .edges
            .iter()
            .filter(|e| e.from == Some(v) || e.to == Some(v))
            .map(|e| &e.sites)
            .collect();
        assert!(
            !(pairs.len() == 2 && pairs[0] == pairs[1]),
            "vertex {v} at {:?} only cuts an edge of {:?}",
            vertex.at,
            pairs[0]
        );
    }
}

#[test]
fn a_ridge_ending_beside_a_span_a_hundred_times_longer_stays_whole() {
    // the glyph with one control point of site 2 moved down (y 0.620384 → 0.30): a
    // spike at a notch, whose curvature maximum on its far side (radius 0.009) splits
    // a span 0.0006 long from one 0.38 long; the ridge that ends at its centre of
    // curvature came out in three pieces with loose ends 2e-4 apart
    let sc = scene("freeform-glyph20-spike-medial_axis.json");
    let d = run(&sc, Engine::Freeform);
    no_loose_ends(&sc, &d, &joints(&sc));
    no_vertex_inside_an_edge(&d);
    let report = gvd::verify(&sc, &d, &gvd::VerifyOptions::default()).unwrap();
    assert!(report.passed, "{:?}", report.problems);
    // the ridge's end is the centre of the tightest circle through dense samples of
    // site 2 past the spike's inflection
    let curve = dense(&sc.sites()[2].kind, 200_000);
    let centre = (62_000..69_000)
        .map(|k| {
            (
                circumcentre(curve[k - 100], curve[k], curve[k + 100]),
                curve[k],
            )
        })
        .min_by(|a, b| a.0.dist(a.1).total_cmp(&b.0.dist(b.1)))
        .unwrap()
        .0;
    let end = d
        .vertices
        .iter()
        .find(|v| v.at.dist(centre) < 0.5 * sc.epsilon());
    let end = end.unwrap_or_else(|| panic!("no vertex at the ridge's end {centre:?}"));
    assert_eq!(end.sites.len(), 2);
    assert_eq!(end.sites[0], end.sites[1]);
    // the glyph itself: the tip's normal and ridge meet without a vertex
    let sc = scene("freeform-glyph20-medial_axis.json");
    no_vertex_inside_an_edge(&run(&sc, Engine::Freeform));
}

#[test]
fn a_normal_past_its_centre_of_curvature_beside_a_short_span_leaves_no_loose_end() {
    // the same control point at y = 0.36: the notch's normal passes its centre of
    // curvature where site 2's first span, 0.02 long, meets site 1's, 0.4 long; the
    // branch of `F3` beside the normal ran along it 6e-4 past the vertex, a loose end
    let sc = scene("freeform-glyph20-pinched-medial_axis.json");
    let d = run(&sc, Engine::Freeform);
    no_loose_ends(&sc, &d, &joints(&sc));
    no_vertex_inside_an_edge(&d);
}

#[test]
fn a_column_root_that_is_noise_at_a_side_does_not_cut_the_branch() {
    // the glyph with site 19's third control point moved onto its fourth (y −0.136 →
    // −1.4e-151, fuzz_mutate.py): near the joint of sites 18 and 19, `F3(t, ·)` of
    // their spans showed an uncertified cluster at r ∈ [0, 4e-6] (`F3` is below its
    // error bound by the shared end) beside the branch's root at r ≈ 0.04, the count
    // no longer matched and the branch was lost for 5e-3 of its length: two loose ends
    let sc = scene("freeform-glyph20-coincident-end-medial_axis.json");
    let d = run(&sc, Engine::Freeform);
    no_loose_ends(&sc, &d, &joints(&sc));
}
