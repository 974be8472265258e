//! The topology-oriented incremental Voronoi diagram of points against spade's exact
//! Delaunay triangulation (vertices with their generator sets, adjacent site pairs),
//! plus graph invariants checked here from the public half-edge accessors.

use gvd::complex::{Generator, VoronoiComplex};
use gvd::geom::{Aabb, Point};
use gvd::internals::{points_voronoi, Face, PointDiagram};
use proptest::prelude::*;
use robust::Coord;
use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};
use std::collections::{BTreeMap, BTreeSet, HashMap};

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

fn c(p: Point) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

/// The circumcentre in f64, relative to the vertex opposite the longest side, with the
/// 2×2 determinant evaluated by Kahan's fused-multiply-add method (slivers with two
/// nearly coincident vertices need both).
fn circumcenter(a: Point, b: Point, cc: Point) -> Point {
    let l = |p: Point, q: Point| (q - p).dot(q - p);
    let (a, b, cc) = if l(b, cc) >= l(a, b).max(l(cc, a)) {
        (a, b, cc)
    } else if l(cc, a) >= l(a, b) {
        (b, cc, a)
    } else {
        (cc, a, b)
    };
    let (b, cc) = (b - a, cc - a);
    let (p, q) = (b.x * cc.y, b.y * cc.x);
    let d = 2.0 * ((p - q) + (b.x.mul_add(cc.y, -p) - b.y.mul_add(cc.x, -q)));
    let (b2, c2) = (b.dot(b), cc.dot(cc));
    a + Point::new((cc.y * b2 - b.y * c2) / d, (b.x * c2 - cc.x * b2) / d)
}

/// The length inside `b` of the part `s ∈ [s0, s1]` of the line `m + s·dir`.
fn clip_len(m: Point, dir: Point, (mut s0, mut s1): (f64, f64), b: &Aabb) -> f64 {
    for (den, num) in [
        (-dir.x, m.x - b.min.x),
        (dir.x, b.max.x - m.x),
        (-dir.y, m.y - b.min.y),
        (dir.y, b.max.y - m.y),
    ] {
        if den == 0.0 {
            if num < 0.0 {
                return 0.0;
            }
        } else if den < 0.0 {
            s0 = s0.max(num / den);
        } else {
            s1 = s1.min(num / den);
        }
    }
    if s0 < s1 {
        (s1 - s0) * dir.norm()
    } else {
        0.0
    }
}

fn boundary_dist(b: &Aabb, p: Point) -> f64 {
    let inside = (p.x - b.min.x)
        .min(b.max.x - p.x)
        .min(p.y - b.min.y)
        .min(b.max.y - p.y);
    inside.abs().max(b.outside_distance(p))
}

struct V {
    p: Point2<f64>,
    i: usize,
}
impl HasPosition for V {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.p
    }
}

/// The exact reference: Voronoi vertices in the domain (cocircular triangles merged by
/// exact incircle = 0 across their common side) and adjacent pairs with the length of
/// their common edge inside the domain.
struct Reference {
    vertices: BTreeMap<Vec<usize>, Point>,
    pairs: BTreeMap<[usize; 2], f64>,
}

fn reference(points: &[Point], domain: &Aabb) -> Reference {
    let t: DelaunayTriangulation<V> = DelaunayTriangulation::bulk_load(
        points
            .iter()
            .enumerate()
            .map(|(i, p)| V {
                p: Point2::new(p.x, p.y),
                i,
            })
            .collect(),
    )
    .unwrap();
    let nf = t.num_all_faces();
    let mut parent: Vec<usize> = (0..nf).collect();
    fn find(p: &mut [usize], mut v: usize) -> usize {
        while p[v] != v {
            v = p[v];
        }
        v
    }
    let pos = |v: &spade::handles::VertexHandle<V>| points[v.data().i];
    let mut center = vec![Point::default(); nf];
    for f in t.inner_faces() {
        let [a, b, cc] = f.vertices();
        center[f.fix().index()] = circumcenter(pos(&a), pos(&b), pos(&cc));
    }
    for e in t.directed_edges() {
        let (Some(f), Some(g)) = (e.face().as_inner(), e.rev().face().as_inner()) else {
            continue;
        };
        let [a, b, cc] = f.vertices();
        let x = e.rev().opposite_vertex().unwrap();
        if robust::incircle(c(pos(&a)), c(pos(&b)), c(pos(&cc)), c(pos(&x))) == 0.0 {
            let (rf, rg) = (
                find(&mut parent, f.fix().index()),
                find(&mut parent, g.fix().index()),
            );
            parent[rf.max(rg)] = rf.min(rg);
        }
    }
    let mut groups: BTreeMap<usize, BTreeSet<usize>> = BTreeMap::new();
    for f in t.inner_faces() {
        let r = find(&mut parent, f.fix().index());
        groups
            .entry(r)
            .or_default()
            .extend(f.vertices().iter().map(|v| v.data().i));
    }
    let vertices = groups
        .into_iter()
        .filter(|(r, _)| domain.contains(center[*r]))
        .map(|(r, s)| (s.into_iter().collect(), center[r]))
        .collect();

    let mut pairs = BTreeMap::new();
    for e in t.undirected_edges() {
        let d = e.as_directed();
        let (a, b) = (pos(&d.from()), pos(&d.to()));
        let (ia, ib) = (d.from().data().i, d.to().data().i);
        // The bisector m + s·dir with dir = (b − a)⊥: s grows from the face right of
        // a → b towards the face on its left.
        let (m, dir) = (a.lerp(b, 0.5), (b - a).perp());
        let param = |p: Point| (p - m).dot(dir) / dir.dot(dir);
        let (fl, fr) = (d.face().as_inner(), d.rev().face().as_inner());
        let range = match (fl, fr) {
            (Some(f), Some(g)) => {
                let (rf, rg) = (
                    find(&mut parent, f.fix().index()),
                    find(&mut parent, g.fix().index()),
                );
                if rf == rg {
                    continue;
                }
                (param(center[rg]), param(center[rf]))
            }
            (Some(f), None) => (
                f64::NEG_INFINITY,
                param(center[find(&mut parent, f.fix().index())]),
            ),
            (None, Some(g)) => (
                param(center[find(&mut parent, g.fix().index())]),
                f64::INFINITY,
            ),
            (None, None) => (f64::NEG_INFINITY, f64::INFINITY),
        };
        pairs.insert([ia.min(ib), ia.max(ib)], clip_len(m, dir, range, domain));
    }
    Reference { vertices, pairs }
}

fn site(g: &Generator) -> usize {
    match g {
        Generator::Site(i) => *i,
        other => panic!("unexpected generator {other:?}"),
    }
}

/// Compares our complex with the reference within `1e-9` relative; features within
/// the tolerance of the domain boundary (or edges shorter than it) may differ.
fn compare(points: &[Point], domain: Aabb, ours: &VoronoiComplex) {
    ours.check_invariants().unwrap();
    let r = reference(points, &domain);
    let scale = domain
        .longest_side()
        .max(points.iter().map(|p| p.norm()).fold(0.0, f64::max));
    let tol = 1e-9 * scale;

    let mut mine: BTreeMap<Vec<usize>, Point> = BTreeMap::new();
    for v in &ours.vertices {
        let key: Vec<usize> = v.sites.iter().map(site).collect();
        assert!(
            key.windows(2).all(|w| w[0] < w[1]),
            "unsorted or repeated sites {key:?}"
        );
        assert!(key.len() >= 3);
        let d0 = v.at.dist(points[key[0]]);
        for &s in &key {
            assert!(
                (v.at.dist(points[s]) - d0).abs() <= tol,
                "vertex {key:?} at {:?} not equidistant from {:?}",
                v.at,
                key.iter().map(|&k| points[k]).collect::<Vec<_>>()
            );
        }
        assert!(
            mine.insert(key.clone(), v.at).is_none(),
            "vertex {key:?} listed twice"
        );
    }
    for (key, at) in &r.vertices {
        match mine.get(key) {
            Some(p) => assert!(p.dist(*at) <= tol, "vertex {key:?}: {p:?} vs {at:?}"),
            None => assert!(
                boundary_dist(&domain, *at) <= tol,
                "missing vertex {key:?} at {at:?}"
            ),
        }
    }
    for (key, at) in &mine {
        if !r.vertices.contains_key(key) {
            assert!(
                boundary_dist(&domain, *at) <= tol,
                "extra vertex {key:?} at {at:?}"
            );
        }
    }

    let mut my_pairs: BTreeMap<[usize; 2], f64> = BTreeMap::new();
    for e in &ours.edges {
        let (a, b) = (site(&e.sites[0]), site(&e.sites[1]));
        let len = e.points[0].dist(e.points[1]);
        for p in &e.points {
            assert!(
                domain.outside_distance(*p) <= tol,
                "edge point {p:?} outside the domain"
            );
            assert!(
                (p.dist(points[a]) - p.dist(points[b])).abs() <= tol,
                "edge {a}-{b} off its bisector"
            );
        }
        // sites[0] lies to the left of from → to: the edge turns right from a → b.
        if len > tol {
            let d = e.points[1] - e.points[0];
            assert!(
                d.cross(points[b] - points[a]) < 0.0,
                "edge {a}-{b} orientation"
            );
        }
        for (end, p) in [(e.from, e.points[0]), (e.to, e.points[1])] {
            if let Some(v) = end {
                assert_eq!(ours.vertices[v].at, p);
            } else {
                assert!(
                    boundary_dist(&domain, p) <= tol,
                    "free end {p:?} not on the boundary"
                );
            }
        }
        assert!(
            my_pairs.insert([a.min(b), a.max(b)], len).is_none(),
            "pair {a}-{b} twice"
        );
    }
    for (k, &len) in &r.pairs {
        if len > tol {
            assert!(
                my_pairs.contains_key(k),
                "missing edge {k:?} (length {len})"
            );
        }
    }
    for (k, &len) in &my_pairs {
        if len > tol {
            let l = r.pairs.get(k).copied().unwrap_or(0.0);
            assert!(
                (l - len).abs() <= 1e-6 * scale,
                "edge {k:?}: length {len} vs {l}"
            );
        }
    }
}

/// Half-edge invariants: twins, next/prev, every face one cycle, Euler's formula, one
/// face per distinct point.
fn check_structure(d: &PointDiagram, points: &[Point]) {
    let nh = d.half_edge_count();
    assert_eq!(nh, 3 * d.vertex_count());
    let mut faces: HashMap<Face, Vec<usize>> = HashMap::new();
    for h in 0..nh {
        let t = d.twin(h);
        assert!(t != h && d.twin(t) == h, "twin of {h}");
        assert_eq!(d.next(d.prev(h)), h);
        assert_eq!(d.prev(d.next(h)), h);
        assert_eq!(
            d.origin(d.next(h)),
            d.origin(t),
            "next({h}) must leave where {h} ends"
        );
        assert_eq!(d.left(d.next(h)), d.left(h));
        assert_ne!(d.left(t), d.left(h));
        let g = d.generators(d.origin(h));
        assert!(g.contains(&d.left(h)) && g.contains(&d.left(t)));
        faces.entry(d.left(h)).or_default().push(h);
    }
    for (f, hs) in &faces {
        let mut h = hs[0];
        let mut len = 0;
        loop {
            len += 1;
            h = d.next(h);
            assert!(len <= hs.len(), "face {f:?} is not a single cycle");
            if h == hs[0] {
                break;
            }
        }
        assert_eq!(len, hs.len(), "face {f:?} has more than one cycle");
        assert!(len >= 2);
    }
    let (v, e, f) = (d.vertex_count() as i64, nh as i64 / 2, faces.len() as i64);
    assert_eq!(v - e + f, 2, "Euler");
    assert_eq!(
        faces.len(),
        points.len() - d.duplicates().len() - d.skipped().len() + 3
    );
}

/// The exact geometry: every vertex counter-clockwise (clockwise at infinity) and every
/// edge locally Delaunay (so the whole graph is the exact Voronoi diagram), with no
/// sign overruled and no point skipped.
fn check_geometry(d: &PointDiagram, points: &[Point]) {
    assert!(d.skipped().is_empty());
    assert_eq!(d.topology_counts().0, 0, "C4/C5 overruled an exact sign");
    let nh = d.half_edge_count();
    let far = d.far_generators();
    let at = |f: Face| match f {
        Face::Site(i) => points[i],
        Face::Far(k) => far[k],
    };
    for v in 0..d.vertex_count() {
        let [a, b, cc] = d.generators(v).map(at);
        let o = robust::orient2d(c(a), c(b), c(cc));
        assert!(
            if d.is_at_infinity(v) {
                o < 0.0
            } else {
                o > 0.0
            },
            "vertex {v} orientation"
        );
    }
    for h in 0..nh {
        let (u, w) = (d.origin(h), d.origin(d.twin(h)));
        if d.is_at_infinity(u) || d.is_at_infinity(w) {
            continue;
        }
        let [a, b, cc] = d.generators(u).map(at);
        let x = d
            .generators(w)
            .into_iter()
            .find(|g| !d.generators(u).contains(g))
            .unwrap();
        assert!(
            robust::incircle(c(a), c(b), c(cc), c(at(x))) <= 0.0,
            "edge {h} not locally Delaunay"
        );
    }
}

fn run(points: &[Point], domain: Aabb) -> VoronoiComplex {
    let d = PointDiagram::new(points, domain).unwrap();
    check_structure(&d, points);
    check_geometry(&d, points);
    let out = d.to_complex();
    compare(points, domain, &out);
    out
}

fn grid(k: usize) -> Vec<Point> {
    (0..k * k)
        .map(|i| Point::new((i % k) as f64, (i / k) as f64))
        .collect()
}

#[test]
fn small_grid() {
    let out = run(&grid(4), Aabb::from_array([-0.3, -0.3, 3.3, 3.3]));
    // Nine vertices of degree four at the half-integers.
    assert_eq!(out.vertices.len(), 9);
    assert!(out.vertices.iter().all(|v| v.sites.len() == 4));
}

#[test]
fn large_grid() {
    let out = run(&grid(30), Aabb::from_array([-0.3, -0.7, 29.6, 29.2]));
    assert_eq!(out.vertices.len(), 29 * 29);
    assert!(out.vertices.iter().all(|v| v.sites.len() == 4));
}

/// The points with integer coordinates on the circle of radius `r` (exactly
/// cocircular), from one octant's representatives `(x, y)`, `x > y >= 0`.
fn lattice_circle(reps: &[(f64, f64)]) -> Vec<Point> {
    let mut v = BTreeSet::new();
    for &(x, y) in reps {
        for (x, y) in [(x, y), (y, x)] {
            for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
                // `+ 0.0` turns −0 into +0.
                v.insert(((sx * x + 0.0f64).to_bits(), (sy * y + 0.0f64).to_bits()));
            }
        }
    }
    v.into_iter()
        .map(|(x, y)| Point::new(f64::from_bits(x), f64::from_bits(y)))
        .collect()
}

#[test]
fn cocircular_points_give_one_vertex() {
    let mut pts = lattice_circle(&[(5.0, 0.0), (4.0, 3.0)]);
    assert_eq!(pts.len(), 12);
    let dom = Aabb::from_array([-7.0, -6.0, 8.0, 6.5]);
    let out = run(&pts, dom);
    assert_eq!(out.vertices.len(), 1);
    assert_eq!(out.vertices[0].sites.len(), 12);
    assert!(out.vertices[0].at.norm() < 1e-12);
    assert_eq!(out.edges.len(), 12);
    // With the centre: a 12-gon cell around it.
    pts.push(Point::new(0.0, 0.0));
    let out = run(&pts, dom);
    assert_eq!(out.vertices.len(), 12);
    let centre = Generator::Site(12);
    assert_eq!(
        out.edges
            .iter()
            .filter(|e| e.sites.contains(&centre))
            .count(),
        12
    );
    // 20 cocircular points, then with the centre.
    let mut pts = lattice_circle(&[(25.0, 0.0), (24.0, 7.0), (20.0, 15.0)]);
    assert_eq!(pts.len(), 20);
    let dom = Aabb::from_array([-30.0, -31.0, 29.0, 32.0]);
    let out = run(&pts, dom);
    assert_eq!(out.vertices.len(), 1);
    assert_eq!(out.vertices[0].sites.len(), 20);
    pts.push(Point::new(0.0, 0.0));
    run(&pts, dom);
}

#[test]
fn collinear_points() {
    let pts: Vec<Point> = (0..20)
        .map(|i| Point::new(i as f64, 2.0 * i as f64 + 1.0))
        .collect();
    let out = run(&pts, Aabb::from_array([-5.0, -5.0, 25.0, 45.0]));
    assert!(out.vertices.is_empty());
    assert_eq!(out.edges.len(), 19);
    assert!(out.edges.iter().all(|e| e.from.is_none() && e.to.is_none()));
    let pts: Vec<Point> = (0..20).map(|i| Point::new(0.1 * i as f64, 0.3)).collect();
    run(&pts, Aabb::from_array([-1.0, -1.0, 3.0, 1.0]));
}

#[test]
fn concentric_circles() {
    let mut pts = vec![];
    for (r, m) in [(1.0, 40), (2.0, 40), (3.0, 17)] {
        for k in 0..m {
            let t = std::f64::consts::TAU * k as f64 / m as f64;
            pts.push(Point::new(r * t.cos(), r * t.sin()));
        }
    }
    run(&pts, Aabb::from_array([-2.5, -2.7, 2.6, 2.4]));
}

#[test]
fn tiny_cases_and_errors() {
    let dom = Aabb::from_array([-1.0, -1.0, 2.0, 2.0]);
    let out = points_voronoi(&[], dom).unwrap();
    assert!(out.vertices.is_empty() && out.edges.is_empty());
    let out = run(&[Point::new(0.5, 0.5)], dom);
    assert!(out.edges.is_empty());
    let out = run(&[Point::new(0.0, 0.0), Point::new(1.0, 1.0)], dom);
    assert_eq!(out.edges.len(), 1);
    assert!(points_voronoi(&[Point::new(f64::NAN, 0.0)], dom).is_err());
    assert!(points_voronoi(&[Point::new(0.0, f64::INFINITY)], dom).is_err());
    assert!(points_voronoi(
        &[Point::new(0.0, 0.0)],
        Aabb::from_array([1.0, 0.0, 0.0, 1.0])
    )
    .is_err());
    // Duplicates: no crash, the first copy owns the cell.
    let pts = [
        Point::new(0.0, 0.0),
        Point::new(1.0, 0.0),
        Point::new(0.0, 0.0),
        Point::new(0.3, 0.9),
    ];
    let d = PointDiagram::new(&pts, dom).unwrap();
    check_structure(&d, &pts);
    check_geometry(&d, &pts);
    let mut dups = d.duplicates().to_vec();
    dups.sort_unstable();
    assert!(dups == [(2, 0)] || dups == [(0, 2)]);
    assert_eq!(d.to_complex().vertices.len(), 1);
}

fn random(n: usize, seed: u64) -> Vec<Point> {
    let mut r = Rng(seed);
    (0..n).map(|_| Point::new(r.next(), r.next())).collect()
}

#[test]
fn ten_thousand_random_points() {
    let pts = random(10_000, 7);
    let out = run(&pts, Aabb::from_array([0.0, 0.0, 1.0, 1.0]));
    assert!(out.vertices.len() > 19_000);
}

#[test]
fn huge_and_tiny_coordinates() {
    // Big offsets: compared with spade directly.
    for (offset, scale) in [(1e9, 1.0), (1e15, 64.0), (-3e7, 1e-3)] {
        let pts: Vec<Point> = random(300, 11)
            .into_iter()
            .map(|p| Point::new(offset + scale * p.x, offset - scale * p.y))
            .collect();
        run(
            &pts,
            Aabb::from_array([offset, offset - scale, offset + scale, offset]),
        );
    }
    // Magnitudes where the reference's own predicates would under- or overflow: the
    // result must be the exact power-of-two rescaling of the result at unit scale.
    let unit = random(300, 13);
    let dom = Aabb::from_array([0.0, 0.0, 1.0, 1.0]);
    let reference = run(&unit, dom);
    for k in [-700, -300, 300, 700] {
        let f = 2f64.powi(k);
        let pts: Vec<Point> = unit.iter().map(|&p| p * f).collect();
        let mut out = points_voronoi(&pts, Aabb::new(dom.min * f, dom.max * f)).unwrap();
        for v in out.vertices.iter_mut() {
            v.at = v.at * (1.0 / f);
        }
        for e in out.edges.iter_mut() {
            for p in e.points.iter_mut() {
                *p = *p * (1.0 / f);
            }
        }
        assert_eq!(out.vertices, reference.vertices, "scale 2^{k}");
        assert_eq!(out.edges, reference.edges, "scale 2^{k}");
    }
}

#[test]
fn nearly_coincident_points() {
    // Pairs a few ulps apart, on a grid (cocircular quadruples) and at random.
    let mut pts = vec![];
    for p in grid(6) {
        pts.push(p);
        pts.push(Point::new(p.x + 1e-13, p.y));
        pts.push(Point::new(p.x, p.y + 2f64.powi(-50)));
    }
    run(&pts, Aabb::from_array([-0.2, -0.3, 5.4, 5.1]));
    let mut pts = random(200, 3);
    let extra: Vec<Point> = pts
        .iter()
        .map(|p| Point::new(p.x.next_up(), p.y.next_down()))
        .collect();
    pts.extend(extra);
    run(&pts, Aabb::from_array([0.0, 0.0, 1.0, 1.0]));
}

/// Sites outside the domain, a domain much larger than the sites, and a degenerate
/// (zero-width) domain.
#[test]
fn domain_and_sites_apart() {
    let pts: Vec<Point> = random(200, 23)
        .into_iter()
        .map(|p| p + Point::new(3.0, -0.5))
        .collect();
    run(&pts, Aabb::from_array([0.0, 0.0, 1.0, 1.0]));
    run(&pts, Aabb::from_array([-1e4, -2e4, 3e4, 1e4]));
    let out = run(&pts, Aabb::from_array([3.5, -1.0, 3.5, 1.0]));
    assert!(out.vertices.len() <= 1);
}

/// Spreads of magnitude beyond the exact range (products underflow): whatever the
/// signs say, the graph stays valid and the output consistent — no panic, no hang.
#[test]
fn beyond_the_exact_range_the_graph_stays_valid() {
    let mut pts: Vec<Point> = grid(5).into_iter().map(|p| p * 1e-300).collect();
    pts.extend([
        Point::new(1.0, 1.0),
        Point::new(-1.0, 0.5),
        Point::new(0.3, -0.7),
    ]);
    pts.extend(random(50, 5).into_iter().map(|p| p * 1e-170));
    pts.extend([Point::new(1e300, -1e300), Point::new(-1.5e300, 2e299)]);
    let dom = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
    let d = PointDiagram::new(&pts, dom).unwrap();
    check_structure(&d, &pts);
    d.to_complex().check_invariants().unwrap();
    let d = PointDiagram::new(&pts[..28], dom).unwrap();
    check_structure(&d, &pts[..28]);
    d.to_complex().check_invariants().unwrap();
}

/// Coincident copies: the least index owns the cell, the result equals that of the
/// points without the later copies.
#[test]
fn duplicates_keep_the_least_index() {
    let base = random(400, 17);
    let mut pts = base.clone();
    for k in 0..300 {
        pts.push(base[(k * 7) % 400]);
    }
    pts.extend_from_slice(&base[..50]);
    let dom = Aabb::from_array([0.0, 0.0, 1.0, 1.0]);
    let d = PointDiagram::new(&pts, dom).unwrap();
    check_structure(&d, &pts);
    check_geometry(&d, &pts);
    assert_eq!(d.duplicates().len(), 350);
    for &(dup, owner) in d.duplicates() {
        assert!(
            owner < 400 && dup >= 400 && pts[dup] == pts[owner],
            "({dup}, {owner})"
        );
    }
    let (out, reference) = (d.to_complex(), points_voronoi(&base, dom).unwrap());
    let key = |c: &VoronoiComplex| {
        let mut v: Vec<_> = c.vertices.iter().map(|v| (v.sites.clone(), v.at)).collect();
        v.sort_by(|a, b| a.0.cmp(&b.0));
        let mut e: Vec<([Generator; 2], f64)> = c
            .edges
            .iter()
            .map(|e| {
                let mut s = e.sites;
                s.sort();
                (s, e.points[0].dist(e.points[1]))
            })
            .collect();
        e.sort_by_key(|a| a.0);
        (v, e)
    };
    let ((v1, e1), (v2, e2)) = (key(&out), key(&reference));
    assert_eq!(v1.len(), v2.len());
    assert_eq!(e1.len(), e2.len());
    for (a, b) in v1.iter().zip(&v2) {
        assert!(a.0 == b.0 && a.1.dist(b.1) < 1e-14, "{a:?} vs {b:?}");
    }
    for (a, b) in e1.iter().zip(&e2) {
        assert!(a.0 == b.0 && (a.1 - b.1).abs() < 1e-14, "{a:?} vs {b:?}");
    }
}

fn dedup(mut v: Vec<Point>) -> Vec<Point> {
    let mut seen = BTreeSet::new();
    v.retain(|p| seen.insert((p.x.to_bits(), p.y.to_bits())));
    v
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn random_points(pts in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 1..80)) {
        let pts = dedup(pts.into_iter().map(|(x, y)| Point::new(x, y)).collect());
        run(&pts, Aabb::from_array([-1.1, -0.9, 0.8, 1.2]));
    }

    #[test]
    fn integer_lattice_points(pts in prop::collection::vec((-4i32..5, -4i32..5), 1..60)) {
        let pts = dedup(pts.into_iter().map(|(x, y)| Point::new(x as f64, y as f64)).collect());
        run(&pts, Aabb::from_array([-4.3, -3.9, 4.1, 4.6]));
    }

    #[test]
    fn lattice_with_tiny_perturbations(
        pts in prop::collection::vec((-3i32..4, -3i32..4, 0u8..3), 1..50)
    ) {
        let pts = dedup(pts.into_iter().map(|(x, y, k)| {
            Point::new(x as f64 + f64::from(k) * 1e-14, y as f64 - f64::from(k % 2) * 3e-15)
        }).collect());
        run(&pts, Aabb::from_array([-3.3, -2.9, 3.2, 3.4]));
    }
}
