//! Euclidean and power diagrams of points from the subdivision engine against exact
//! references: spade's Delaunay triangulation (Euclidean), and a brute-force
//! enumeration of power vertices with exact orientation tests (power).

use gvd::geom::{Aabb, Point};
use gvd::scene::{Metric, Mode, Scene, Site, SiteKind};
use spade::{DelaunayTriangulation, Point2, Triangulation};
use std::collections::BTreeSet;

fn subdivision() -> gvd::Options {
    gvd::Options {
        engine: gvd::Engine::Subdivision,
        ..Default::default()
    }
}

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn scene(points: &[(Point, Metric)], eps: f64) -> Scene {
    scene_in(Aabb::from_array([-2.0, -2.0, 2.0, 2.0]), points, eps)
}

fn scene_in(domain: Aabb, points: &[(Point, Metric)], eps: f64) -> Scene {
    Scene::new(
        domain,
        eps,
        Mode::Voronoi,
        points
            .iter()
            .map(|(at, m)| Site {
                id: None,
                kind: SiteKind::Point {
                    at: *at,
                    metric: m.clone(),
                },
            })
            .collect(),
    )
    .expect("a valid scene")
}

/// An exact vertex: its location and sorted generators.
type ExactVertex = (Point, Vec<usize>);

fn circumcenter(a: Point, b: Point, c: Point) -> Point {
    let (b, c) = (b - a, c - a);
    let d = 2.0 * b.cross(c);
    let (b2, c2) = (b.dot(b), c.dot(c));
    a + Point::new((c.y * b2 - b.y * c2) / d, (b.x * c2 - c.x * b2) / d)
}

/// Exact Voronoi vertices and adjacent pairs (with the length of their edge inside the
/// domain) from spade's Delaunay triangulation.
fn delaunay_reference(
    points: &[Point],
    domain: &Aabb,
) -> (Vec<ExactVertex>, Vec<([usize; 2], f64)>) {
    let mut t: DelaunayTriangulation<Point2<f64>> = DelaunayTriangulation::new();
    for p in points {
        t.insert(Point2::new(p.x, p.y)).unwrap();
    }
    // spade may renumber its vertices while the triangulation is degenerate: map by position
    let site_of = |h: spade::handles::FixedVertexHandle| {
        let p = t.vertex(h).position();
        points
            .iter()
            .position(|q| q.x == p.x && q.y == p.y)
            .unwrap()
    };
    let mut verts: Vec<ExactVertex> = Vec::new();
    for f in t.inner_faces() {
        let v = f.vertices();
        let ids: Vec<usize> = v.iter().map(|x| site_of(x.fix())).collect();
        let c = circumcenter(points[ids[0]], points[ids[1]], points[ids[2]]);
        match verts.iter_mut().find(|(p, _)| p.dist(c) < 1e-9) {
            Some((_, s)) => s.extend(ids),
            None => verts.push((c, ids)),
        }
    }
    for (_, s) in verts.iter_mut() {
        s.sort_unstable();
        s.dedup();
    }
    verts.retain(|(p, _)| domain.contains(*p));
    let mut pairs = Vec::new();
    for e in t.undirected_edges() {
        let [a, b] = e.vertices().map(|v| site_of(v.fix()));
        let (pa, pb) = (points[a], points[b]);
        let de = e.as_directed();
        let centre =
            |f: spade::handles::FaceHandle<'_, spade::handles::PossiblyOuterTag, _, _, _, _>| {
                f.as_inner().map(|f| {
                    let v = f.vertices().map(|x| points[site_of(x.fix())]);
                    circumcenter(v[0], v[1], v[2])
                })
            };
        let (c1, c2) = (centre(de.face()), centre(de.rev().face()));
        let mid = pa.lerp(pb, 0.5);
        let dir = (pb - pa).perp();
        // the edge as {mid + s·dir : s in [lo, hi]}
        let s_of = |c: Point| (c - mid).dot(dir) / dir.dot(dir);
        let far = f64::INFINITY;
        let (lo, hi) = match (c1, c2) {
            (Some(x), Some(y)) => (s_of(x).min(s_of(y)), s_of(x).max(s_of(y))),
            (Some(x), None) | (None, Some(x)) => {
                // a ray away from the triangle's third vertex
                let f = if c1.is_some() {
                    de.face()
                } else {
                    de.rev().face()
                };
                let third = f
                    .as_inner()
                    .unwrap()
                    .vertices()
                    .map(|v| points[site_of(v.fix())]);
                let other = third
                    .iter()
                    .find(|p| **p != pa && **p != pb)
                    .copied()
                    .unwrap();
                if (other - mid).dot(dir) > 0.0 {
                    (-far, s_of(x))
                } else {
                    (s_of(x), far)
                }
            }
            (None, None) => (-far, far),
        };
        let len = clip_length(mid, dir, lo, hi, domain);
        pairs.push(([a.min(b), a.max(b)], len));
    }
    (verts, pairs)
}

/// Length of {m + s·d : s ∈ [lo, hi]} inside the box (Liang–Barsky).
fn clip_length(m: Point, d: Point, mut lo: f64, mut hi: f64, b: &Aabb) -> f64 {
    for (p, dp, min, max) in [(m.x, d.x, b.min.x, b.max.x), (m.y, d.y, b.min.y, b.max.y)] {
        if dp == 0.0 {
            if p < min || p > max {
                return 0.0;
            }
        } else {
            let (t1, t2) = ((min - p) / dp, (max - p) / dp);
            lo = lo.max(t1.min(t2));
            hi = hi.min(t1.max(t2));
        }
    }
    ((hi - lo).max(0.0)) * d.norm()
}

fn output_sets(d: &gvd::VoronoiComplex) -> (Vec<ExactVertex>, BTreeSet<[usize; 2]>) {
    let verts = d
        .vertices
        .iter()
        .map(|v| {
            let mut s: Vec<usize> = v.sites.iter().map(|g| g.site()).collect();
            s.sort_unstable();
            (v.at, s)
        })
        .collect();
    let pairs = d.edges.iter().map(|e| {
        let (a, b) = (e.sites[0].site(), e.sites[1].site());
        [a.min(b), a.max(b)]
    });
    (verts, pairs.collect())
}

fn assert_matches(sc: &Scene, exact_v: &[ExactVertex], exact_pairs: &[([usize; 2], f64)]) {
    let d = gvd::compute(sc, &subdivision()).unwrap();
    d.check_invariants().unwrap();
    assert_diagram_matches(&d, sc, exact_v, exact_pairs);
}

/// [`assert_matches`] on a diagram `d` of `sc` (or of `sc` scaled, brought back).
fn assert_diagram_matches(
    d: &gvd::VoronoiComplex,
    sc: &Scene,
    exact_v: &[ExactVertex],
    exact_pairs: &[([usize; 2], f64)],
) {
    let eps = sc.epsilon();
    let domain = sc.domain();
    let (out_v, out_pairs) = output_sets(d);
    for (p, s) in exact_v {
        if domain.outside_distance(*p) == 0.0
            && [
                p.x - domain.min.x,
                domain.max.x - p.x,
                p.y - domain.min.y,
                domain.max.y - p.y,
            ]
            .iter()
            .all(|m| *m > eps)
        {
            assert!(
                out_v.iter().any(|(q, t)| t == s && q.dist(*p) <= eps),
                "exact vertex {s:?} at {p:?} has no output vertex with the same generators"
            );
        }
    }
    for (q, t) in &out_v {
        assert!(
            exact_v.iter().any(|(p, s)| s == t && q.dist(*p) <= eps),
            "output vertex {t:?} at {q:?} is not an exact vertex"
        );
    }
    for (pair, len) in exact_pairs {
        if *len > 2.0 * eps {
            assert!(
                out_pairs.contains(pair),
                "edge {pair:?} (length {len}) is missing"
            );
        }
    }
    for pair in &out_pairs {
        assert!(
            exact_pairs.iter().any(|(p, l)| p == pair && *l > 0.0),
            "output edge {pair:?} is not an edge of the exact diagram"
        );
    }
}

fn check_euclidean(points: &[Point], eps: f64) {
    let sc = scene(
        &points
            .iter()
            .map(|p| (*p, Metric::Euclidean))
            .collect::<Vec<_>>(),
        eps,
    );
    let (v, p) = delaunay_reference(points, &sc.domain());
    assert_matches(&sc, &v, &p);
}

#[test]
fn random_euclidean_points_match_delaunay() {
    for (seed, n) in [(1u64, 10usize), (2, 50), (3, 200)] {
        let mut r = Rng(seed);
        let pts: Vec<Point> = (0..n)
            .map(|_| Point::new(4.0 * r.next() - 2.0, 4.0 * r.next() - 2.0))
            .collect();
        check_euclidean(&pts, 1e-3);
    }
}

#[test]
fn grid_has_degree_four_vertices() {
    let pts: Vec<Point> = (0..16)
        .map(|k| Point::new(-1.5 + (k % 4) as f64, -1.5 + (k / 4) as f64))
        .collect();
    check_euclidean(&pts, 1e-3);
}

#[test]
fn cocircular_points_with_centre() {
    let mut pts: Vec<Point> = (0..12)
        .map(|k| {
            let a = k as f64 * std::f64::consts::PI / 6.0 + 0.1;
            Point::new(1.5 * a.cos(), 1.5 * a.sin())
        })
        .collect();
    pts.push(Point::new(0.0, 0.0));
    check_euclidean(&pts, 1e-3);
}

/// Point sets whose bisectors lie on lines of the subdivision's lattice over
/// `[-2, 2]²` (x or y = 0, ±0.25, ±0.5, ±0.75, ±1, ...) at several depths, and whose
/// vertices lie on them or on its nodes: rings of 4, 8 and 12 points about a centre
/// point, the axes' points, grids, pairs mirrored about a line, and a mix.
fn lattice_tie_families() -> Vec<(String, Vec<Point>)> {
    let mut out = Vec::new();
    for n in [4, 8, 12] {
        for r in [0.5, 1.0, 1.5] {
            let mut pts: Vec<Point> = (0..n)
                .map(|k| {
                    let a = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                    Point::new(r * a.cos(), r * a.sin())
                })
                .collect();
            pts.push(Point::new(0.0, 0.0));
            out.push((format!("ring of {n}, radius {r}, and its centre"), pts));
        }
    }
    for a in [0.5, 0.75, 1.0, 1.5] {
        let pts = [(a, 0.0), (-a, 0.0), (0.0, a), (0.0, -a), (0.0, 0.0)];
        out.push((
            format!("axes at {a}"),
            pts.map(|(x, y)| Point::new(x, y)).to_vec(),
        ));
    }
    for (h, o) in [(0.5, 0.25), (0.5, 0.0), (1.0, 0.5)] {
        let k = (2.0 / h) as i32;
        let pts = (-k..k)
            .flat_map(|i| (-k..k).map(move |j| Point::new(o + h * i as f64, o + h * j as f64)))
            .filter(|p| p.x > -2.0 && p.y > -2.0)
            .collect();
        out.push((format!("grid of step {h} from {o}"), pts));
    }
    for c in [0.0, 0.5, -0.75, 0.25, 1.0] {
        let pairs = [(0.25, -1.2), (0.5, 0.1), (0.75, 1.3)];
        let pts = pairs
            .iter()
            .flat_map(|&(r, y)| [Point::new(c - r, y), Point::new(c + r, y)])
            .collect();
        out.push((format!("pairs mirrored about x = {c}"), pts));
    }
    let mix = [
        (0.0, 0.0),
        (1.0, 0.0),
        (0.5, 0.8),
        (0.5, -0.7),
        (-1.0, 0.3),
        (-1.0, -0.3),
    ];
    out.push(("mix".into(), mix.map(|(x, y)| Point::new(x, y)).to_vec()));
    out
}

#[test]
fn bisectors_on_lattice_lines_match_delaunay_at_any_scale() {
    let grid64 = gvd::verify::VerifyOptions {
        grid: 64,
        ..Default::default()
    };
    for (name, pts) in lattice_tie_families() {
        let unit = scene(
            &pts.iter()
                .map(|p| (*p, Metric::Euclidean))
                .collect::<Vec<_>>(),
            1e-3,
        );
        let (v, p) = delaunay_reference(&pts, &unit.domain());
        // exact scales keep every tie; 1e-150 and 1e300 round the points
        for s in [1.0, 2f64.powi(-497), 2f64.powi(497), 1e-150, 1e300] {
            let k = |q: &Point| Point::new(q.x * s, q.y * s);
            let scaled: Vec<(Point, Metric)> =
                pts.iter().map(|q| (k(q), Metric::Euclidean)).collect();
            let domain = Aabb::new(k(&unit.domain().min), k(&unit.domain().max));
            let sc = scene_in(domain, &scaled, 1e-3 * s);
            let mut d = gvd::compute(&sc, &subdivision()).unwrap();
            d.check_invariants().unwrap();
            let report = gvd::verify::verify(&sc, &d, &grid64).unwrap();
            assert!(report.passed, "{name} ×{s:e}: {}", report.summary_line());
            if s.log2().fract() == 0.0 {
                d.scale(1.0 / s);
                assert_diagram_matches(&d, &unit, &v, &p);
            }
        }
    }
}

#[test]
fn collinear_points() {
    // dyadic coordinates: exactly collinear in f64, so the reference has no sliver triangles
    let pts: Vec<Point> = (0..20)
        .map(|k| Point::new(-1.1875 + 0.125 * k as f64, -0.5 + 0.0625 * k as f64))
        .collect();
    check_euclidean(&pts, 1e-3);
}

/// Power vertices by brute force: the power centre of each triple that no other site
/// undercuts, and the pairs adjacent along a positive-length edge (from the vertices
/// and from the domain boundary crossings).
fn power_reference(points: &[Point], w: &[f64], domain: &Aabb) -> Vec<ExactVertex> {
    let pow = |i: usize, q: Point| q.dist(points[i]).powi(2) - w[i] * w[i];
    let n = points.len();
    let mut out: Vec<ExactVertex> = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                // power centre: pow_i = pow_j = pow_k is linear
                let (a, b, c) = (points[i], points[j], points[k]);
                let r1 = Point::new(2.0 * (b.x - a.x), 2.0 * (b.y - a.y));
                let r2 = Point::new(2.0 * (c.x - a.x), 2.0 * (c.y - a.y));
                let s1 = b.dot(b) - a.dot(a) - w[j] * w[j] + w[i] * w[i];
                let s2 = c.dot(c) - a.dot(a) - w[k] * w[k] + w[i] * w[i];
                let det = r1.cross(r2);
                if det.abs() < 1e-12 {
                    continue;
                }
                let q = Point::new((s1 * r2.y - s2 * r1.y) / det, (r1.x * s2 - r2.x * s1) / det);
                if !domain.contains(q) {
                    continue;
                }
                let v = pow(i, q);
                if (0..n).all(|m| pow(m, q) >= v - 1e-9) {
                    let ids: Vec<usize> =
                        (0..n).filter(|&m| (pow(m, q) - v).abs() <= 1e-9).collect();
                    if !out.iter().any(|(p, _)| p.dist(q) < 1e-9) {
                        out.push((q, ids));
                    }
                }
            }
        }
    }
    out
}

#[test]
fn random_power_points_match_brute_force() {
    let mut r = Rng(9);
    let n = 40;
    let pts: Vec<Point> = (0..n)
        .map(|_| Point::new(4.0 * r.next() - 2.0, 4.0 * r.next() - 2.0))
        .collect();
    let w: Vec<f64> = (0..n).map(|_| 0.3 * r.next()).collect();
    let sc = scene(
        &pts.iter()
            .zip(&w)
            .map(|(p, w)| (*p, Metric::Power { weight: *w }))
            .collect::<Vec<_>>(),
        1e-3,
    );
    let exact = power_reference(&pts, &w, &sc.domain());
    let d = gvd::compute(&sc, &subdivision()).unwrap();
    let (out_v, _) = output_sets(&d);
    for (p, s) in &exact {
        assert!(
            out_v
                .iter()
                .any(|(q, t)| t == s && q.dist(*p) <= sc.epsilon()),
            "power vertex {s:?} at {p:?} missing"
        );
    }
    for (q, t) in &out_v {
        assert!(
            exact
                .iter()
                .any(|(p, s)| s == t && q.dist(*p) <= sc.epsilon()),
            "output vertex {t:?} at {q:?} is not a power vertex"
        );
    }
}
