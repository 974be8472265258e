use super::report::fmt_g3;
use super::*;
use crate::complex::{smallvec, Edge, Vertex};
use crate::geom::Aabb;
use crate::scene::{Equation, Metric, Site, SiteKind};

const EPS: f64 = 1e-3;

fn domain() -> Aabb {
    Aabb::from_array([-1.0, -1.0, 1.0, 1.0])
}

fn scene(sites: Vec<SiteKind>) -> Scene {
    Scene::new(
        domain(),
        EPS,
        Mode::Voronoi,
        sites
            .into_iter()
            .map(|kind| Site { id: None, kind })
            .collect(),
    )
    .expect("a valid scene")
}

fn euclid(p: &[(f64, f64)]) -> Vec<SiteKind> {
    p.iter()
        .map(|&(x, y)| SiteKind::Point {
            at: Point::new(x, y),
            metric: Metric::Euclidean,
        })
        .collect()
}

fn edge(a: usize, b: usize, from: Option<usize>, to: Option<usize>, pts: &[Point]) -> Edge {
    Edge {
        clearance: Vec::new(),
        sites_along: Vec::new(),
        sites: [Generator::Site(a), Generator::Site(b)],
        from,
        bisector: Vec::new(),
        parametric: Vec::new(),
        to,
        points: pts.into(),
    }
}

fn vertex(at: Point, sites: &[usize]) -> Vertex {
    Vertex {
        clearance: None,
        at,
        sites: sites.iter().map(|&s| Generator::Site(s)).collect(),
    }
}

fn check(s: &Scene, d: &VoronoiComplex) -> Report {
    verify(s, d, &VerifyOptions::default()).unwrap()
}

/// Where the ray `c + t d` (t ≥ 0, `c` inside) leaves the domain.
fn ray_exit(c: Point, d: Point, dom: Aabb) -> Point {
    let along = |p: f64, v: f64, lo: f64, hi: f64| {
        if v > 0.0 {
            (hi - p) / v
        } else if v < 0.0 {
            (lo - p) / v
        } else {
            f64::INFINITY
        }
    };
    let t = along(c.x, d.x, dom.min.x, dom.max.x).min(along(c.y, d.y, dom.min.y, dom.max.y));
    c + d * t
}

fn circumcenter(a: Point, b: Point, c: Point) -> Point {
    let d = 2.0 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
    let (a2, b2, c2) = (a.dot(a), b.dot(b), c.dot(c));
    Point::new(
        (a2 * (b.y - c.y) + b2 * (c.y - a.y) + c2 * (a.y - b.y)) / d,
        (a2 * (c.x - b.x) + b2 * (a.x - c.x) + c2 * (b.x - a.x)) / d,
    )
}

fn two_points() -> (Scene, VoronoiComplex) {
    let s = scene(euclid(&[(-0.5, 0.1), (0.5, 0.1)]));
    let d = VoronoiComplex {
        edges: vec![edge(
            0,
            1,
            None,
            None,
            &[Point::new(0.0, -1.0), Point::new(0.0, 1.0)],
        )],
        ..Default::default()
    };
    (s, d)
}

fn three_points() -> (Scene, VoronoiComplex) {
    let p = [
        Point::new(-0.5, -0.3),
        Point::new(0.5, -0.35),
        Point::new(0.1, 0.6),
    ];
    let s = scene(euclid(&[
        (p[0].x, p[0].y),
        (p[1].x, p[1].y),
        (p[2].x, p[2].y),
    ]));
    let c = circumcenter(p[0], p[1], p[2]);
    let mut d = VoronoiComplex {
        vertices: vec![vertex(c, &[0, 1, 2])],
        ..Default::default()
    };
    for (i, j, k) in [(0, 1, 2), (1, 2, 0), (0, 2, 1)] {
        let mut dir = (p[j] - p[i]).perp();
        if dir.dot(p[i] - p[k]) < 0.0 {
            dir = dir * -1.0;
        }
        d.edges
            .push(edge(i, j, Some(0), None, &[c, ray_exit(c, dir, domain())]));
    }
    (s, d)
}

#[test]
fn exact_diagrams_pass() {
    let (s, d) = two_points();
    let r = check(&s, &d);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
    let (s, d) = three_points();
    let r = check(&s, &d);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
    assert_eq!(r.vertices_ok, (1, 1));
    assert!(r.summary_line().ends_with("PASS"));
}

#[test]
fn square_with_degree_four_vertex_passes() {
    let s = scene(euclid(&[
        (-0.5, -0.5),
        (0.5, -0.5),
        (0.5, 0.5),
        (-0.5, 0.5),
    ]));
    let o = Point::default();
    let d = VoronoiComplex {
        vertices: vec![vertex(o, &[0, 1, 2, 3])],
        edges: vec![
            edge(0, 1, Some(0), None, &[o, Point::new(0.0, -1.0)]),
            edge(1, 2, Some(0), None, &[o, Point::new(1.0, 0.0)]),
            edge(2, 3, Some(0), None, &[o, Point::new(0.0, 1.0)]),
            edge(3, 0, Some(0), None, &[o, Point::new(-1.0, 0.0)]),
        ],
        ..Default::default()
    };
    let r = check(&s, &d);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
}

#[test]
fn power_points_pass_and_euclidean_bisector_fails() {
    let power = |x: f64, w: f64| SiteKind::Point {
        at: Point::new(x, 0.0),
        metric: Metric::Power { weight: w },
    };
    let s = scene(vec![power(-0.5, 0.4), power(0.5, 0.1)]);
    // (x + 0.5)² − 0.16 = (x − 0.5)² − 0.01  ⇔  x = 0.075
    let line = |x: f64| edge(0, 1, None, None, &[Point::new(x, -1.0), Point::new(x, 1.0)]);
    let good = VoronoiComplex {
        edges: vec![line(0.075)],
        ..Default::default()
    };
    let r = check(&s, &good);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
    let euclidean = VoronoiComplex {
        edges: vec![line(0.0)],
        ..Default::default()
    };
    let r = check(&s, &euclidean);
    assert!(
        !r.passed && r.sound == 0.0 && r.complete < 1.0,
        "{}",
        r.summary_line()
    );
}

#[test]
fn moved_vertex_fails_vertex_check() {
    let (s, mut d) = three_points();
    d.vertices[0].at = d.vertices[0].at + Point::new(10.0 * EPS, 0.0);
    let r = check(&s, &d);
    assert!(!r.passed);
    assert_eq!(r.vertices_ok, (0, 1), "{}", r.summary_line());
    assert!(
        r.problems
            .iter()
            .any(|p| p.contains("vertex 0") && p.contains("not tied")),
        "{:?}",
        r.problems
    );
    // the edge ends now lie 10 eps from the vertex they name
    assert!(
        r.problems
            .iter()
            .any(|p| p.starts_with("structure: edge 0: 'from' end")),
        "{:?}",
        r.problems
    );
}

#[test]
fn dropped_edge_fails_completeness() {
    let (s, mut d) = three_points();
    d.edges.remove(1);
    let r = check(&s, &d);
    assert!(!r.passed && r.complete < 0.9, "{}", r.summary_line());
    assert_eq!(r.sound, 1.0);
    assert!(
        r.problems
            .iter()
            .any(|p| p.contains("no edge between sites 1 and 2")),
        "{:?}",
        r.problems
    );
}

#[test]
fn swapped_labels_fail_soundness() {
    let (s, mut d) = three_points();
    let (a, b) = (d.edges[0].sites, d.edges[1].sites);
    d.edges[0].sites = b;
    d.edges[1].sites = a;
    let r = check(&s, &d);
    assert!(
        !r.passed && r.sound < 0.5 && r.complete < 1.0,
        "{}",
        r.summary_line()
    );
    assert!(
        r.problems
            .iter()
            .any(|p| p.starts_with("soundness: edge 0")),
        "{:?}",
        r.problems
    );
}

#[test]
fn bent_edge_fails_beyond_tolerance_only() {
    let bent = |by: f64| {
        let (s, mut d) = two_points();
        d.edges[0].points = smallvec![
            Point::new(0.0, -1.0),
            Point::new(by, 0.0),
            Point::new(0.0, 1.0),
        ];
        check(&s, &d)
    };
    let r = bent(3.0 * EPS);
    assert!(!r.passed && r.sound < 1.0, "{}", r.summary_line());
    assert!(
        (r.worst_edge_error - 3.0 * EPS).abs() < 1e-6,
        "{}",
        r.worst_edge_error
    );
    let r = bent(0.5 * EPS);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
}

#[test]
fn dangling_end_and_bad_labels_fail_structure() {
    let (s, mut d) = two_points();
    d.edges[0].points[1] = Point::new(0.0, 0.5);
    let r = check(&s, &d);
    assert!(!r.passed, "{}", r.summary_line());
    assert!(
        r.problems
            .iter()
            .any(|p| p.contains("not on the domain boundary")),
        "{:?}",
        r.problems
    );
    let (s, mut d) = two_points();
    d.edges[0].sites[1] = Generator::Site(7);
    let r = check(&s, &d);
    assert!(
        !r.passed
            && r.problems
                .iter()
                .any(|p| p.contains("site 7 does not exist"))
    );
}

#[test]
fn implicit_field_and_segments() {
    // (x + 0.5)² + y² − (z + 0.2)²: the circle of radius 0.2 about (−0.5, 0)
    let implicit = SiteKind::ImplicitField {
        equation: Equation::parse("(x+0.5)^2 + y^2 - (z+0.2)^2", &['x', 'y', 'z']).unwrap(),
    };
    let circle = SiteKind::Circle {
        center: Point::new(0.5, 0.0),
        radius: 0.2,
    };
    let (_, d) = two_points();
    let r = check(&scene(vec![implicit, circle]), &d);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
    let seg = |x: f64| SiteKind::Segment {
        from: Point::new(x, -0.5),
        to: Point::new(x, 0.5),
    };
    let r = check(&scene(vec![seg(-0.5), seg(0.5)]), &d);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
}

#[test]
fn free_form_curves_are_checked_by_their_own_distance() {
    // two Béziers, a straight one and a parabola, checked against the diagram of the
    // same curves as a segment and a polyline, then against that diagram with its
    // edge moved off the bisector
    let line = [Point::new(-0.6, -0.5), Point::new(0.6, -0.5)];
    let arch = [
        Point::new(-0.6, 0.2),
        Point::new(0.0, 0.8),
        Point::new(0.6, 0.2),
    ];
    let curves = scene(vec![
        SiteKind::Bezier {
            control_points: line.to_vec(),
            weights: None,
        },
        SiteKind::Bezier {
            control_points: arch.to_vec(),
            weights: None,
        },
    ]);
    let parabola: Vec<Point> = (0..=400)
        .map(|k| crate::geom::bspline::RationalBspline::bezier(&arch, None).eval(k as f64 / 400.0))
        .collect();
    let drawn = scene(vec![
        SiteKind::Segment {
            from: line[0],
            to: line[1],
        },
        SiteKind::Polyline { points: parabola },
    ]);
    let d = crate::compute(&drawn, &crate::Options::default()).unwrap();
    let r = check(&curves, &d);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
    let mut moved = d.clone();
    for e in &mut moved.edges {
        for p in &mut e.points {
            p.y += 0.05;
        }
    }
    assert!(!check(&curves, &moved).passed);
}

#[test]
fn unsupported_kinds_and_modes_are_refused() {
    let d = VoronoiComplex::default();
    let s = scene(vec![SiteKind::Ellipse {
        center: Point::default(),
        semi_axes: [0.5, 0.25],
        rotation: 0.0,
    }])
    .with_mode(Mode::MedialAxis);
    assert!(matches!(
        verify(&s, &d, &VerifyOptions::default()),
        Err(Error::Unsupported { site: 0, .. })
    ));
    let s = s.with_mode(Mode::Complex);
    assert!(verify(&s, &d, &VerifyOptions::default()).is_ok());
}

#[test]
fn summary_numbers_format_like_python() {
    assert_eq!(fmt_g3(0.0012), "0.0012");
    assert_eq!(fmt_g3(0.00123456), "0.00123");
    assert_eq!(fmt_g3(1.5e-5), "1.5e-05");
    assert_eq!(fmt_g3(12.345), "12.3");
    assert_eq!(fmt_g3(1234.0), "1.23e+03");
    assert_eq!(fmt_g3(0.0), "0");
    assert_eq!(fmt_g3(9.9999e-8), "1e-07");
    assert_eq!(fmt_g3(1.04e-315), "1.04e-315");
    assert_eq!(fmt_g3(-2.5e300), "-2.5e+300");
}

/// The Euclidean Voronoi diagram of `p` clipped to `dom`, from spade's Delaunay
/// triangulation: one edge per Delaunay edge, between the circumcentres of its faces
/// (a ray outwards on the hull), clipped to the box.
fn spade_diagram(p: &[Point], dom: Aabb) -> VoronoiComplex {
    use spade::handles::{FixedFaceHandle, InnerTag};
    use spade::{DelaunayTriangulation, Point2, Triangulation};
    let mut t = DelaunayTriangulation::<Point2<f64>>::new();
    for q in p {
        t.insert(Point2::new(q.x, q.y)).unwrap();
    }
    let pt = |q: Point2<f64>| Point::new(q.x, q.y);
    let mut d = VoronoiComplex::default();
    let mut vid = std::collections::HashMap::<FixedFaceHandle<InnerTag>, usize>::new();
    for f in t.inner_faces() {
        let c = pt(f.circumcenter());
        if dom.contains(c) {
            vid.insert(f.fix(), d.vertices.len());
            let s: Vec<usize> = f.vertices().iter().map(|v| v.fix().index()).collect();
            d.vertices.push(vertex(c, &s));
        }
    }
    for e in t.undirected_edges() {
        let e = e.as_directed();
        let (a, b) = (e.from().fix().index(), e.to().fix().index());
        let (fa, fb) = (e.face().as_inner(), e.rev().face().as_inner());
        // the Voronoi edge as c0 + t·dir, t ∈ [0, t1]
        let (c0, f0, dir, t1, f1) = match (fa, fb) {
            (Some(f), Some(g)) => {
                let (c, c1) = (pt(f.circumcenter()), pt(g.circumcenter()));
                (c, Some(f.fix()), c1 - c, 1.0, Some(g.fix()))
            }
            (Some(f), None) | (None, Some(f)) => {
                let c = pt(f.circumcenter());
                let (pa, pb) = (pt(e.from().position()), pt(e.to().position()));
                let third = f
                    .vertices()
                    .iter()
                    .map(|v| pt(v.position()))
                    .find(|&q| q != pa && q != pb)
                    .unwrap();
                let mut dir = (pb - pa).perp();
                if dir.dot(pa - third) < 0.0 {
                    dir = dir * -1.0;
                }
                (c, Some(f.fix()), dir, f64::INFINITY, None)
            }
            (None, None) => continue,
        };
        // Liang–Barsky clipping
        let (mut lo, mut hi) = (0.0f64, t1);
        for (p0, v, min, max) in [
            (c0.x, dir.x, dom.min.x, dom.max.x),
            (c0.y, dir.y, dom.min.y, dom.max.y),
        ] {
            if v == 0.0 {
                if p0 < min || p0 > max {
                    hi = -1.0;
                }
                continue;
            }
            let (ta, tb) = ((min - p0) / v, (max - p0) / v);
            lo = lo.max(ta.min(tb));
            hi = hi.min(ta.max(tb));
        }
        if hi <= lo {
            continue;
        }
        let end = |f: Option<FixedFaceHandle<InnerTag>>, t: f64, lim: f64| {
            if t == lim {
                f.and_then(|f| vid.get(&f).copied())
            } else {
                None
            }
        };
        d.edges.push(edge(
            a,
            b,
            end(f0, lo, 0.0),
            end(f1, hi, t1),
            &[c0 + dir * lo, c0 + dir * hi],
        ));
    }
    d
}

fn random_points(n: usize, seed: u64) -> Vec<Point> {
    let mut s = seed;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 1.8 - 0.9
    };
    (0..n).map(|_| Point::new(next(), next())).collect()
}

fn random_check(n: usize, grid: usize) -> (Report, std::time::Duration) {
    let p = random_points(n, 0x9e3779b97f4a7c15);
    let s = scene(
        p.iter()
            .map(|q| SiteKind::Point {
                at: *q,
                metric: Metric::Euclidean,
            })
            .collect(),
    );
    let d = spade_diagram(&p, domain());
    let opts = VerifyOptions {
        grid,
        ..Default::default()
    };
    let t = std::time::Instant::now();
    let r = verify(&s, &d, &opts).unwrap();
    (r, t.elapsed())
}

#[test]
fn random_points_against_delaunay_pass() {
    let (r, _) = random_check(150, 256);
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
}

/// On the common normal of a tangent joint (an arc and a segment, turned so that no
/// coordinate is exact) the two distances agree to second order across the normal:
/// the edge along it passes (the sign change of `d_a − d_b` certifies it where the
/// first-order estimate is rounding over rounding), and the same edge moved by 3ε does
/// not.
#[test]
fn tangent_joint_normal_passes_and_moved_fails() {
    let (theta, r) = (0.3f64, 0.5);
    let u = Point::new(theta.cos(), theta.sin());
    let p = u * r;
    let tangent = Point::new(theta.sin(), -theta.cos());
    let s = scene(vec![
        SiteKind::Arc {
            center: Point::new(0.0, 0.0),
            radius: r,
            start_angle: theta,
            end_angle: theta + 1.5,
        },
        SiteKind::Segment {
            from: p,
            to: p + tangent * 0.4,
        },
    ]);
    let normal = |shift: f64| {
        let off = u.perp() * shift;
        let pts: Vec<Point> = (1..=40)
            .map(|k| u * (0.02 + 0.009 * k as f64) + off)
            .collect();
        VoronoiComplex {
            vertices: Vec::new(),
            edges: vec![edge(0, 1, None, None, &pts)],
            ..VoronoiComplex::default()
        }
    };
    let r = check(&s, &normal(0.0));
    assert!(r.sound == 1.0, "{} {:?}", r.summary_line(), r.problems);
    assert!(r.worst_edge_error < 1e-6, "{}", r.worst_edge_error);
    let r = check(&s, &normal(3.0 * EPS));
    assert!(r.sound < 1.0, "{}", r.summary_line());
}

/// Two segments sharing the end `P = (0, 0)` at a right angle, and a point site at
/// (0.5, 0.5) in the quadrant whose points are nearest to `P` (both segments tie
/// there). The exact diagram, written out here: the segments' inner bisector, the
/// parabolas of each segment and the point, and the line `x + y = 0.5` between `P`'s
/// region and the point. `SCENE_FORMAT.md` lets either segment name `P`'s region: the
/// diagram passes with either owner on that line, and fails with a third site's label.
fn shared_end_diagram(owner: usize) -> (Scene, VoronoiComplex) {
    let s = scene(vec![
        SiteKind::Segment {
            from: Point::new(0.0, 0.0),
            to: Point::new(-1.0, 0.0),
        },
        SiteKind::Segment {
            from: Point::new(0.0, 0.0),
            to: Point::new(0.0, -1.0),
        },
        euclid(&[(0.5, 0.5)]).remove(0),
    ]);
    // y = (x − ½)² + ¼ above segment 0, out of the domain at y = 1
    let top = 0.5 - 0.75f64.sqrt();
    let parabola = |k: usize, n: usize| {
        let x = top * (1.0 - k as f64 / n as f64);
        Point::new(x, (x - 0.5) * (x - 0.5) + 0.25)
    };
    let above: Vec<Point> = (0..=200).map(|k| parabola(k, 200)).collect();
    let right: Vec<Point> = above.iter().rev().map(|p| Point::new(p.y, p.x)).collect();
    let line: Vec<Point> = (0..=100)
        .map(|k| Point::new(0.5, 0.0).lerp(Point::new(0.0, 0.5), k as f64 / 100.0))
        .collect();
    let (at_segment_0, at_segment_1) = if owner == 0 {
        (vec![0, 2], vec![0, 1, 2])
    } else {
        (vec![0, 1, 2], vec![1, 2])
    };
    let d = VoronoiComplex {
        vertices: vec![
            vertex(Point::new(0.0, 0.0), &[0, 1]),
            vertex(Point::new(0.0, 0.5), &at_segment_0),
            vertex(Point::new(0.5, 0.0), &at_segment_1),
        ],
        edges: vec![
            edge(
                0,
                1,
                Some(0),
                None,
                &[Point::new(0.0, 0.0), Point::new(-1.0, -1.0)],
            ),
            edge(0, 2, None, Some(1), &above),
            edge(owner, 2, Some(2), Some(1), &line),
            edge(1, 2, Some(2), None, &right),
        ],
        ..VoronoiComplex::default()
    };
    (s, d)
}

#[test]
fn either_owner_of_a_shared_end_may_name_its_region() {
    for owner in [0, 1] {
        let (s, d) = shared_end_diagram(owner);
        let r = check(&s, &d);
        assert!(
            r.passed,
            "owner {owner}: {} {:?}",
            r.summary_line(),
            r.problems
        );
    }
    // An edge between the shared end's region and the point is still needed, under
    // whichever owner: without the line, crossings there are uncovered.
    for owner in [0, 1] {
        let (s, mut d) = shared_end_diagram(owner);
        d.edges.remove(2);
        let r = check(&s, &d);
        assert!(r.complete < 1.0 && !r.passed, "{}", r.summary_line());
    }
}

/// Two arcs at 1e-170 checked without the unit rescaling: the nearest-site grid's cell
/// (from `width · height`, which underflowed to 0) became 1/2048 of the domain, and each
/// query scanned a million empty cells (`gvd verify` ran for minutes).
#[test]
fn the_nearest_site_grid_of_a_tiny_domain_stays_small() {
    let r = 1e-170;
    let arc = |a0: f64, a1: f64| SiteKind::Arc {
        center: Point::new(0.0, 0.0),
        radius: r,
        start_angle: a0,
        end_angle: a1,
    };
    use std::f64::consts::{FRAC_PI_2, PI};
    let sc = Scene::new(
        Aabb::from_array([-2.0 * r, -2.0 * r, 2.0 * r, 2.0 * r]),
        1e-3 * r,
        Mode::Voronoi,
        [arc(FRAC_PI_2, PI), arc(PI, 1.5 * PI)]
            .into_iter()
            .map(|kind| Site { id: None, kind })
            .collect(),
    )
    .unwrap();
    let d = crate::compute(&sc, &crate::Options::default()).unwrap();
    let opts = VerifyOptions {
        grid: 64,
        ..Default::default()
    };
    let start = std::time::Instant::now();
    let report = super::check(&sc, &d, &opts, 1.0).unwrap();
    assert!(start.elapsed().as_secs_f64() < 5.0, "{:?}", start.elapsed());
    assert!(report.passed, "{}", report.summary_line());
}

/// Möbius points of equal scale `s` and weight 0: `s·|q − p|²`, whose diagram is the
/// Euclidean one at every `s`.
fn moebius(p: &[Point], s: f64) -> Vec<SiteKind> {
    p.iter()
        .map(|&at| SiteKind::Point {
            at,
            metric: Metric::Moebius {
                scale: s,
                weight: 0.0,
            },
        })
        .collect()
}

#[test]
fn verdicts_do_not_change_when_every_field_is_multiplied_by_one_factor() {
    // gradients of 1e300 (their squares overflow) and of 1e-300 (theirs underflow)
    for s in [1.0, 2f64.powi(996), 2f64.powi(-996)] {
        let (euclidean, exact) = three_points();
        let p: Vec<Point> = euclidean
            .sites()
            .iter()
            .filter_map(|x| match x.kind {
                SiteKind::Point { at, .. } => Some(at),
                _ => None,
            })
            .collect();
        let sc = scene(moebius(&p, s));
        let r = check(&sc, &exact);
        assert!(r.passed, "s = {s:e}: {} {:?}", r.summary_line(), r.problems);
        let mut bent = exact.clone();
        let c = bent.vertices[0].at;
        let end = bent.edges[0].points[1];
        let off = (end - c).perp() * (3.0 * EPS / end.dist(c));
        bent.edges[0].points = smallvec![c, c.lerp(end, 0.5) + off, end];
        let r = check(&sc, &bent);
        assert!(
            !r.passed && r.sound < 1.0,
            "s = {s:e}: {}",
            r.summary_line()
        );
        assert!(
            (r.worst_edge_error / (3.0 * EPS) - 1.0).abs() < 0.2,
            "s = {s:e}: {}",
            r.summary_line()
        );
        let mut moved = exact.clone();
        moved.vertices[0].at = c + Point::new(3.0 * EPS, 0.0);
        let r = check(&sc, &moved);
        assert_eq!(r.vertices_ok, (0, 1), "s = {s:e}: {}", r.summary_line());
    }
}

#[test]
fn a_crossing_through_a_third_region_is_split_at_every_factor() {
    // c's region separates a's from b's below the domain's bottom row of grid nodes
    // (grid 2: nodes at ±0.5); the diagram has the edges (a, c) and (b, c) only, their
    // vertex at (0, −1.3) outside the domain
    let p = [
        Point::new(-0.6, -0.5),
        Point::new(0.6, -0.5),
        Point::new(0.0, -0.3),
    ];
    let mut d = VoronoiComplex::default();
    for (i, j) in [(0, 2), (1, 2)] {
        let (m, dir) = (p[i].lerp(p[j], 0.5), (p[j] - p[i]).perp());
        let ends = [
            ray_exit(m, dir, domain()),
            ray_exit(m, dir * -1.0, domain()),
        ];
        d.edges.push(edge(i, j, None, None, &ends));
    }
    let opts = VerifyOptions {
        grid: 2,
        ..Default::default()
    };
    for s in [1.0, 2f64.powi(996), 2f64.powi(-996)] {
        let r = verify(&scene(moebius(&p, s)), &d, &opts).unwrap();
        assert!(r.passed, "s = {s:e}: {} {:?}", r.summary_line(), r.problems);
    }
}

#[test]
fn far_bisector_of_near_points_is_checked_to_rounding() {
    // two ends 0.01 apart (from a cut of a coastline), seen from 1e7 away: their
    // distances differ from f64's by an ulp (1.9e-9) and their gradients by 3e-10
    let p = [
        Point::new(4.7233925, 60.998646),
        Point::new(4.732553, 60.997696),
    ];
    let dom = Aabb::from_array([-1e7, -1e7, 1e7, 1e7]);
    let sites = euclid(&[(p[0].x, p[0].y), (p[1].x, p[1].y)]);
    let eps = 1.2e-3;
    let sc = Scene::new(
        dom,
        eps,
        Mode::Voronoi,
        sites
            .into_iter()
            .map(|kind| Site { id: None, kind })
            .collect(),
    )
    .unwrap();
    let across = (p[1] - p[0]) * (1.0 / p[1].dist(p[0]));
    let line = |by: f64| {
        let m = p[0].lerp(p[1], 0.5) + across * by;
        let ends = [
            ray_exit(m, across.perp(), dom),
            ray_exit(m, across.perp() * -1.0, dom),
        ];
        VoronoiComplex {
            edges: vec![edge(0, 1, None, None, &ends)],
            ..Default::default()
        }
    };
    let r = check(&sc, &line(0.0));
    assert!(r.passed, "{} {:?}", r.summary_line(), r.problems);
    assert!(r.worst_edge_error < 0.1 * eps, "{}", r.summary_line());
    let r = check(&sc, &line(3.0 * eps));
    assert!(!r.passed, "{}", r.summary_line());
    assert!(
        (r.worst_edge_error / (3.0 * eps) - 1.0).abs() < 0.1,
        "{}",
        r.summary_line()
    );
}
