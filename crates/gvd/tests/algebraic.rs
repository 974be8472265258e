//! Algebraic sites: the distance field against independent references (closed forms and
//! dense parametric sampling), special points, refusals, and scenes checked by
//! `gvd verify` and against the same scenes written with circle sites.

use gvd::geom::{Aabb, Point};
use gvd::internals::{AlgebraicField, DistanceField, Poly};
use gvd::verify::{verify, VerifyOptions};
use gvd::{compute, Error, Options, Scene};
use proptest::prelude::*;
use std::f64::consts::TAU;

fn field(eq: &str, clip: [f64; 4], res: f64) -> Result<AlgebraicField, Error> {
    let p = Poly::parse(eq, &['x', 'y']).unwrap();
    AlgebraicField::new(0, &p, Aabb::from_array(clip), res)
}

const ASTROID: &str = "(x^2 + y^2 - 1)^3 + 27*x^2*y^2";

/// The distance from `q` to the astroid `(cos³ t, sin³ t)` by dense sampling, polished
/// by golden-section search around the best sample.
fn astroid_distance(q: Point) -> f64 {
    let at = |t: f64| Point::new(t.cos().powi(3), t.sin().powi(3));
    let n = 20_000;
    let h = TAU / n as f64;
    let k = (0..n)
        .min_by(|&a, &b| {
            q.dist(at(a as f64 * h))
                .total_cmp(&q.dist(at(b as f64 * h)))
        })
        .unwrap();
    let (mut lo, mut hi) = ((k as f64 - 1.0) * h, (k as f64 + 1.0) * h);
    for _ in 0..100 {
        let (m1, m2) = (lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo));
        if q.dist(at(m1)) < q.dist(at(m2)) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    q.dist(at(0.5 * (lo + hi)))
}

fn astroid() -> AlgebraicField {
    field(ASTROID, [-1.5, -1.5, 1.5, 1.5], 1.0 / 256.0).unwrap()
}

fn circle() -> AlgebraicField {
    field(
        "(x - 0.2)^2 + (y + 0.1)^2 - 0.49",
        [-1.0, -1.0, 1.0, 1.0],
        1.0 / 512.0,
    )
    .unwrap()
}

fn circle_distance(q: Point) -> f64 {
    (q.dist(Point::new(0.2, -0.1)) - 0.7).abs()
}

/// The unit circle about (1, 0) clipped to `CLIP_ARC`: a quarter-like arc from (0, 0) to
/// (0.5, −0.866), both ends on the clip box (the tangent-circle examples' sites).
const CLIP_ARC: [f64; 4] = [-0.5, -0.8660254037844386, 0.5, 0.0];

/// The distance to the unit circle about `centre` clipped to `CLIP_ARC`, whose ends are
/// `ends`, and a nearest point: the radial foot if the clip box holds it, else the
/// nearest end (the distance along a circle is unimodal, so no other point of an arc
/// can be nearer).
fn clipped_circle_nearest(centre: Point, ends: [Point; 2], q: Point) -> (f64, Point) {
    let clip = Aabb::from_array(CLIP_ARC);
    let v = q - centre;
    let radial = centre + v * (1.0 / v.norm());
    let mut candidates = ends.to_vec();
    if clip.contains(radial) {
        candidates.push(radial);
    }
    candidates
        .into_iter()
        .map(|p| (q.dist(p), p))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap()
}

/// The arc of [`CLIP_ARC`] on the circle about (1, 0): from (0, 0) to (0.5, −0.866).
fn right_arc(q: Point) -> (f64, Point) {
    let ends = [Point::new(0.0, 0.0), Point::new(0.5, -0.8660254037844386)];
    clipped_circle_nearest(Point::new(1.0, 0.0), ends, q)
}

/// Its mirror image, on the circle about (−1, 0), tangent to it at the origin.
fn left_arc(q: Point) -> (f64, Point) {
    let ends = [Point::new(0.0, 0.0), Point::new(-0.5, -0.8660254037844386)];
    clipped_circle_nearest(Point::new(-1.0, 0.0), ends, q)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// On a curve cut by its clip box, the nodes the box state keeps (pruned by the
    /// foot-point and end conditions) still give bounds that enclose the distance and a
    /// gradient bound that holds the gradient, the nearest end's included.
    #[test]
    fn bounds_hold_on_a_clipped_arc(
        x in -0.6f64..0.6, y in -1.0f64..0.1, w in 0.0005f64..0.1, u in 0.0f64..1.0, v in 0.0f64..1.0
    ) {
        let f = field("(x - 1)^2 + y^2 - 1", CLIP_ARC, 1.0 / 256.0).unwrap();
        let b = Aabb::from_array([x, y, x + w, y + w]);
        let s = f.state(&b);
        let q = b.at(u, v);
        let (d, foot) = right_arc(q);
        let r = f.bound(&s, &b);
        prop_assert!(r.lo <= d + 1e-12 && d <= r.hi + 1e-12, "{r} vs {d} at {q:?}");
        // at a point alone the bounds are second order in the leaf size (the strips
        // below, witnesses above) where the nearest point is a foot; an end on a clip
        // corner that f64 cannot certify as a point of the curve gives a looser upper one
        let at_q = Aabb::new(q, q);
        let r = f.bound(&f.state(&at_q), &at_q);
        prop_assert!(r.lo <= d + 1e-12 && d <= r.hi + 1e-12, "point: {r} vs {d} at {q:?}");
        let clip = Aabb::from_array(CLIP_ARC);
        let at_end = foot.x == clip.max.x || foot.y == clip.max.y;
        prop_assert!(d < 0.05 || at_end || r.width() < 2e-4, "point: {r} at {q:?}");
        prop_assert!((f.value(q) - d).abs() < 1e-9, "value {} vs {d} at {q:?}", f.value(q));
        if d > 1e-9 {
            let g = f.gradient_bound(&s, &b).unwrap();
            let expected = (q - foot) * (1.0 / d);
            prop_assert!(
                g[0].contains(expected.x) && g[1].contains(expected.y),
                "{g:?} vs {expected:?} at {q:?}"
            );
        }
    }

    /// The pair bound of two tangent arcs (narrowed by the mean value form about the
    /// box's centre) encloses the difference of their distances, sampled, beside the
    /// double zero of that difference along the line of their centres.
    #[test]
    fn pair_bound_of_tangent_arcs_encloses_the_difference(
        x in -0.5f64..0.45, y in -0.2f64..0.0, w in 0.0002f64..0.05, u in 0.0f64..1.0, v in 0.0f64..1.0
    ) {
        let right = field("(x - 1)^2 + y^2 - 1", CLIP_ARC, 1.0 / 256.0).unwrap();
        let left = field("(x + 1)^2 + y^2 - 1", CLIP_ARC, 1.0 / 256.0).unwrap();
        let b = Aabb::from_array([x, y - w, x + w, y]);
        let (sr, sl) = (right.state(&b), left.state(&b));
        let h = right.pair(&sr, &left, &sl, &b).value;
        for q in [b.at(u, v), b.at(0.0, 0.0), b.at(1.0, 1.0), b.center()] {
            let exact = right_arc(q).0 - left_arc(q).0;
            prop_assert!(h.lo <= exact + 1e-12 && exact <= h.hi + 1e-12, "{h} vs {exact} at {q:?}");
        }
    }

    /// Box bounds (the state computed from scratch, and after splits) enclose the
    /// distance at points of the box; the point value is the distance.
    #[test]
    fn bounds_enclose_sampled_distances(
        x in -1.4f64..1.2, y in -1.4f64..1.2, w in 0.001f64..0.3, u in 0.0f64..1.0, v in 0.0f64..1.0
    ) {
        for (f, reference) in [
            (astroid(), astroid_distance as fn(Point) -> f64),
            (circle(), circle_distance),
        ] {
            let b = Aabb::from_array([x, y, x + w, y + w]);
            let s = f.state(&b);
            let q = b.at(u, v);
            let d = reference(q);
            let r = f.bound(&s, &b);
            prop_assert!(r.lo <= d + 1e-12 && d <= r.hi + 1e-12, "{r} vs {d} at {q:?}");
            prop_assert!((f.value(q) - d).abs() < 1e-7, "value {} vs {d} at {q:?}", f.value(q));
            let (l, _) = f.split(&s, &b, gvd::geom::Axis::X, b.center().x);
            let lb = Aabb::from_array([x, y, b.center().x, y + w]);
            let q = lb.at(u, v);
            let r = f.bound(&l, &lb);
            let d = reference(q);
            prop_assert!(r.lo <= d + 1e-12 && d <= r.hi + 1e-12, "split {r} vs {d} at {q:?}");
        }
    }

    /// The gradient bound holds the gradient, and the closest-point search agrees with
    /// the closed form of a circle.
    #[test]
    fn gradient_bound_and_closest_point_on_a_circle(
        x in -0.95f64..0.9, y in -0.95f64..0.9, w in 0.001f64..0.05, u in 0.0f64..1.0, v in 0.0f64..1.0
    ) {
        let f = circle();
        let b = Aabb::from_array([x, y, x + w, y + w]);
        let q = b.at(u, v);
        let d = circle_distance(q);
        prop_assert!((f.value(q) - d).abs() < 1e-12, "{} vs {d}", f.value(q));
        let g = f.gradient_bound(&f.state(&b), &b).unwrap();
        let c = q - Point::new(0.2, -0.1);
        let n = c * (1.0 / c.norm());
        let expected = if c.norm() > 0.7 { n } else { n * -1.0 };
        if d > 1e-9 {
            prop_assert!(g[0].contains(expected.x) && g[1].contains(expected.y), "{g:?} vs {expected:?}");
            let got = f.gradient(q);
            prop_assert!(got.dist(expected) < 1e-9, "{got:?} vs {expected:?}");
        }
    }
}

#[test]
fn astroid_cusps_are_singular_clusters_and_their_tips_are_nearest() {
    let f = astroid();
    let stats = f.stats();
    assert!(stats["singular_clusters"].as_u64().unwrap() >= 4, "{stats}");
    // beyond a cusp the nearest point is the tip itself
    for q in [
        Point::new(1.2, 0.0),
        Point::new(0.0, -1.3),
        Point::new(-1.05, 0.0),
    ] {
        let tip = if q.x != 0.0 {
            Point::new(q.x.signum(), 0.0)
        } else {
            Point::new(0.0, q.y.signum())
        };
        assert!(
            (f.value(q) - q.dist(tip)).abs() < 1e-6,
            "{} at {q:?}",
            f.value(q)
        );
    }
    assert!(f.value(Point::new(1.0, 0.0)) < 1e-6);
}

#[test]
fn node_self_crossing() {
    // y² = x²(x + 1): a node at the origin, parametrised by x = t² − 1, y = t(t² − 1)
    let f = field("y^2 - x^2*(x + 1)", [-1.5, -1.5, 1.5, 1.5], 1.0 / 256.0).unwrap();
    assert!(
        f.stats()["singular_points"].as_u64().unwrap() >= 1,
        "{}",
        f.stats()
    );
    let reference = |q: Point| {
        (0..400_000)
            .map(|k| {
                let t = -1.6 + 3.2 * k as f64 / 400_000.0;
                Point::new(t * t - 1.0, t * (t * t - 1.0))
            })
            .filter(|p| p.x.abs() <= 1.5 && p.y.abs() <= 1.5)
            .map(|p| q.dist(p))
            .fold(f64::INFINITY, f64::min)
    };
    assert!(f.value(Point::new(0.0, 0.0)) < 1e-12);
    for q in [
        Point::new(0.05, 0.0),
        Point::new(-0.3, 0.1),
        Point::new(0.2, 0.25),
    ] {
        let d = reference(q);
        assert!(
            (f.value(q) - d).abs() < 1e-5,
            "{} vs {d} at {q:?}",
            f.value(q)
        );
    }
}

#[test]
fn isolated_point_is_part_of_the_curve() {
    // the origin is an isolated real point of (x² + y²)((x − 1)² + y² − 1/4)
    let f = field(
        "(x^2 + y^2)*((x - 1)^2 + y^2 - 0.25)",
        [-1.0, -1.0, 2.0, 1.0],
        1.0 / 256.0,
    )
    .unwrap();
    let q = Point::new(-0.3, 0.0);
    assert!((f.value(q) - 0.3).abs() < 1e-9, "{}", f.value(q));
    assert!(f.value(Point::new(1.0, 0.6)) > 0.0999 && f.value(Point::new(1.0, 0.6)) < 0.1001);
    // a curve that is a single isolated point
    let g = field("x^2 + y^2", [-1.0, -1.0, 1.0, 1.0], 1.0 / 256.0).unwrap();
    assert!((g.value(Point::new(0.3, 0.4)) - 0.5).abs() < 1e-9);
}

#[test]
fn curve_tangent_to_the_clip_box() {
    // the unit circle touches all four sides of its clip box from inside
    let f = field("x^2 + y^2 - 1", [-1.0, -1.0, 1.0, 1.0], 1.0 / 256.0).unwrap();
    assert_eq!(
        f.stats()["clip_contacts"].as_u64(),
        Some(4),
        "{}",
        f.stats()
    );
    for q in [Point::new(1.0, 0.0), Point::new(0.0, -1.0)] {
        assert!(f.value(q) < 1e-12, "{} at {q:?}", f.value(q));
    }
    assert!((f.value(Point::new(0.9, 0.0)) - 0.1).abs() < 1e-12);
    // touching the clip box from outside: one point, nothing certified, refused
    let err = field("x^2 + y^2 - 1", [1.0, -1.0, 2.0, 1.0], 1.0 / 256.0).unwrap_err();
    assert!(matches!(err, Error::Unsupported { site: 0, .. }), "{err}");
}

#[test]
fn refusals_name_the_site() {
    let err = field("x^2 + y^2 + 1", [-1.0, -1.0, 1.0, 1.0], 0.01).unwrap_err();
    assert!(
        matches!(&err, Error::Site { site: 0, field, .. } if field == "equation"),
        "{err}"
    );
    let err = field("(x^2 + y^2 - 0.25)^2", [-1.0, -1.0, 1.0, 1.0], 0.01).unwrap_err();
    assert!(matches!(err, Error::Unsupported { site: 0, .. }), "{err}");
}

fn scene(name: &str) -> Scene {
    let path = format!(
        "{}/tests/data/algebraic/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn check(name: &str) -> gvd::VoronoiComplex {
    let s = scene(name);
    let d = compute(&s, &Options::default()).unwrap();
    assert!(d.stats.contains_key("uncertified_boxes"));
    let report = verify(&s, &d, &VerifyOptions::default()).unwrap();
    assert!(
        report.passed,
        "{name}: {}\n{:?}",
        report.summary_line(),
        report.problems
    );
    d
}

#[test]
fn paper_example_1_line_and_parabola() {
    let d = check("shou-ex1-line-parabola");
    assert_eq!(d.edges.len(), 1);
}

#[test]
fn paper_example_2_astroid_and_circle() {
    let d = check("shou-ex2-astroid-circle");
    // the bisector runs between the astroid's arms and the circle, through the cusps
    for cusp in [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)] {
        let c = Point::new(cusp.0, cusp.1);
        let near = d
            .edges
            .iter()
            .flat_map(|e| &e.points)
            .any(|p| p.dist(c) < 0.02);
        assert!(near, "no edge reaches the cusp {c:?}");
    }
}

/// The diagram of unit circles written as algebraic curves against the same circles as
/// `circle` sites: outside the discs, the same vertices within epsilon with the same
/// sites.
fn agrees_with_circle_sites_outside_the_discs(name: &str, centres: &[(f64, f64)]) {
    let d = check(name);
    let curves = scene(name);
    let as_circles = Scene::new(
        curves.domain(),
        curves.epsilon(),
        curves.mode(),
        centres
            .iter()
            .map(|c| gvd::Site::circle([c.0, c.1], 1.0))
            .collect(),
    )
    .unwrap();
    let e = compute(&as_circles, &Options::default()).unwrap();
    let outside = |p: Point| centres.iter().all(|c| p.dist(Point::new(c.0, c.1)) > 1.0);
    let vs: Vec<_> = d.vertices.iter().filter(|v| outside(v.at)).collect();
    let ws: Vec<_> = e.vertices.iter().filter(|v| outside(v.at)).collect();
    assert_eq!(vs.len(), ws.len(), "{vs:?} vs {ws:?}");
    assert!(!vs.is_empty());
    for v in vs {
        let w = ws
            .iter()
            .min_by(|a, b| a.at.dist(v.at).total_cmp(&b.at.dist(v.at)))
            .unwrap();
        assert!(w.at.dist(v.at) <= as_circles.epsilon(), "{v:?} vs {w:?}");
        let (mut a, mut b) = (v.sites.to_vec(), w.sites.to_vec());
        a.sort();
        b.sort();
        assert_eq!(a, b);
    }
}

#[test]
fn paper_example_3_agrees_with_circle_sites_outside_the_discs() {
    agrees_with_circle_sites_outside_the_discs(
        "shou-ex3-three-circles",
        &[(1.0, 0.0), (-1.0, 0.0), (0.0, -1.7320508075688772)],
    );
}

#[test]
fn paper_example_4_agrees_with_circle_sites_outside_the_discs() {
    agrees_with_circle_sites_outside_the_discs(
        "shou-ex4-four-circles",
        &[(-1.0, 1.0), (1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)],
    );
}

/// At epsilon 1/1024 the edge from the three circles' vertex to a corner of the domain
/// passes exactly through corners of the boxes (the scene's √3 meets the dyadic
/// lattice); it must still come out in one piece: every edge end that is not a vertex
/// lies on the domain's boundary. Besides the vertex of all three, an edge may end in a
/// vertex of two where their circles touch.
#[test]
fn paper_example_3_at_a_finer_epsilon_has_no_broken_edge() {
    let s = scene("shou-ex3-three-circles");
    let fine = Scene::new(s.domain(), 1.0 / 1024.0, s.mode(), s.sites().to_vec()).unwrap();
    let d = compute(&fine, &Options::default()).unwrap();
    let domain = fine.domain();
    let on_boundary = |p: Point| {
        [
            p.x - domain.min.x,
            domain.max.x - p.x,
            p.y - domain.min.y,
            domain.max.y - p.y,
        ]
        .iter()
        .any(|g| g.abs() < 1e-9)
    };
    for (k, e) in d.edges.iter().enumerate() {
        let ends = [(e.from, e.points[0]), (e.to, *e.points.last().unwrap())];
        for (vertex, at) in ends {
            assert!(
                vertex.is_some() || on_boundary(at),
                "edge {k} ends at {at:?}, neither at a vertex nor on the boundary"
            );
        }
    }
    let contacts = [
        (0.0, 0.0),
        (0.5, -0.8660254037844386),
        (-0.5, -0.8660254037844386),
    ];
    let mut of_three = 0;
    for v in &d.vertices {
        if v.sites.len() == 3 {
            of_three += 1;
            continue;
        }
        assert_eq!(v.sites.len(), 2, "{v:?}");
        let near = contacts
            .iter()
            .map(|c| v.at.dist(Point::new(c.0, c.1)))
            .fold(f64::INFINITY, f64::min);
        assert!(near <= fine.epsilon(), "{v:?} is no contact of two circles");
    }
    assert_eq!(of_three, 1);
}

/// The four unit circles about the corners of [−1, 1]² touch at the side midpoints; their
/// diagram is the two axes, crossing in one vertex of all four sites at the origin, each
/// ending where two circles touch. The domain's sides are the common normals of the
/// touching circles, along which the distances to both are equal with a double zero of
/// their difference: no edge may run there (occlusion drops the farther circle).
/// At epsilon 1/1024 the boxes about the origin once gave two three-site vertices joined
/// by short duplicate edges.
#[test]
fn paper_example_4_at_a_finer_epsilon_has_one_centre_vertex() {
    let s = scene("shou-ex4-four-circles");
    let fine = Scene::new(s.domain(), 1.0 / 1024.0, s.mode(), s.sites().to_vec()).unwrap();
    let d = compute(&fine, &Options::default()).unwrap();
    d.check_invariants().unwrap();
    let centres: Vec<usize> = (0..d.vertices.len())
        .filter(|&k| d.vertices[k].sites.len() > 2)
        .collect();
    assert_eq!(centres.len(), 1, "{:?}", d.vertices);
    let centre = &d.vertices[centres[0]];
    assert!(
        centre.at.dist(Point::new(0.0, 0.0)) <= fine.epsilon(),
        "{centre:?}"
    );
    let mut sites: Vec<usize> = centre.sites.iter().map(|g| g.site()).collect();
    sites.sort();
    assert_eq!(sites, [0, 1, 2, 3]);
    let contacts = [(0.0, 1.0), (0.0, -1.0), (1.0, 0.0), (-1.0, 0.0)];
    for v in d.vertices.iter().filter(|v| v.sites.len() == 2) {
        let near = contacts
            .iter()
            .map(|c| v.at.dist(Point::new(c.0, c.1)))
            .fold(f64::INFINITY, f64::min);
        assert!(near <= fine.epsilon(), "{v:?} is no contact of two circles");
    }
    assert_eq!(d.edges.len(), 4);
    for e in &d.edges {
        assert!(
            e.from == Some(centres[0]) || e.to == Some(centres[0]),
            "{e:?} misses the centre"
        );
        for q in &e.points {
            assert!(
                q.x.abs().min(q.y.abs()) <= fine.epsilon(),
                "{q:?} off the axes"
            );
        }
    }
    // no band of boxes along the sides: a few thousand, where there were 56,000
    let boxes = d.stats["boxes"].as_u64().unwrap();
    assert!(boxes < 5_000, "{boxes} boxes");
}

#[test]
fn mixed_with_points_and_circles() {
    let d = check("mixed-astroid-points-circles");
    assert!(!d.vertices.is_empty());
}

#[test]
fn verify_rejects_a_wrong_diagram() {
    let s = scene("shou-ex2-astroid-circle");
    let mut d = compute(&s, &Options::default()).unwrap();
    for e in &mut d.edges {
        for p in &mut e.points {
            *p = *p * 0.97;
        }
    }
    let report = verify(&s, &d, &VerifyOptions::default()).unwrap();
    assert!(!report.passed, "{}", report.summary_line());
}

/// Curves on one side of another: the side is found, the occlusion it proves holds at
/// sampled points (`d_A ≤ d_B` by the closed forms of the circles), and curves that cross
/// or leave the other's clip box get none.
#[test]
fn occlusion_between_curves_holds_and_is_refused_where_curves_cross() {
    let clip = [-3.0, -3.0, 3.0, 3.0];
    let circle = |site: usize, c: (f64, f64), r: f64| {
        let eq = format!("(x - {})^2 + (y - {})^2 - {}", c.0, c.1, r * r);
        let p = Poly::parse(&eq, &['x', 'y']).unwrap();
        AlgebraicField::new(site, &p, Aabb::from_array(clip), 1.0 / 256.0).unwrap()
    };
    // A: centre (−1, 0), r 1; B: centre (1, 0), r 1 (tangent at the origin);
    // C: centre (0, 0), r 2.5 holds both; D: centre (0.5, 0), r 1 crosses A and B
    let centres = [
        ((-1.0, 0.0), 1.0),
        ((1.0, 0.0), 1.0),
        ((0.0, 0.0), 2.5),
        ((0.5, 0.0), 1.0),
    ];
    let mut fields: Vec<AlgebraicField> = centres
        .iter()
        .enumerate()
        .map(|(i, &(c, r))| circle(i, c, r))
        .collect();
    let mut all: Vec<&mut AlgebraicField> = fields.iter_mut().collect();
    AlgebraicField::find_sides(&mut all);
    let occluded = |i: usize| -> Vec<u64> {
        fields[i].stats()["occluded_sites"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap())
            .collect()
    };
    assert_eq!(
        occluded(0),
        [1, 2],
        "A hides B (touching) and C (around it)"
    );
    assert_eq!(occluded(1), [0, 2]);
    assert_eq!(
        occluded(2),
        [0, 1, 3],
        "C hides the circles inside it from outside"
    );
    assert_eq!(occluded(3), [2], "D crosses A and B, and lies inside C");
    assert!(fields[0].stats()["contacts"].as_u64().unwrap() > 0);
    let exact = |i: usize, q: Point| {
        let ((cx, cy), r) = centres[i];
        (q.dist(Point::new(cx, cy)) - r).abs()
    };
    // boxes inside A right up to the contact and along the common normal (the x axis)
    let mut checked = 0;
    for k in 0..400 {
        let (x, y) = (
            -1.95 + 1.9 * (k % 20) as f64 / 19.0,
            -0.9 + 1.8 * (k / 20) as f64 / 19.0,
        );
        let b = Aabb::from_array([x, y, x + 0.04, y + 0.04]);
        if fields[0].occludes_over(&fields[1], &b) {
            checked += 1;
            for q in b.corners().into_iter().chain([b.center()]) {
                assert!(exact(0, q) <= exact(1, q) + 1e-12, "{q:?}");
            }
        }
        // never where the box reaches outside A
        if b.corners()
            .iter()
            .any(|q| q.dist(Point::new(-1.0, 0.0)) > 1.0)
        {
            assert!(!fields[0].occludes_over(&fields[1], &b), "{b:?}");
        }
    }
    assert!(checked > 100, "{checked} boxes");
    // from outside C, the circles inside are never nearer
    let b = Aabb::from_array([2.6, -0.1, 2.8, 0.1]);
    assert!(fields[2].occludes_over(&fields[1], &b));
    assert!(!fields[1].occludes_over(&fields[2], &b));
}
