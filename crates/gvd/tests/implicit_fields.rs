//! Implicit distance fields (Emiris et al. 2013, §3): circles (Apollonius), ellipses and
//! user-given implicit fields through the subdivision engine.

mod common;

use gvd::complex::Generator;
use gvd::geom::{Aabb, Axis, Point};
use gvd::internals::{DistanceField, SiteField};
use gvd::scene::{Equation, Metric, Mode, Scene, Site, SiteKind};
use gvd::FieldOptions;
use gvd::VoronoiComplex;
use proptest::prelude::*;
use std::collections::BTreeSet;

fn data(name: &str) -> Scene {
    let path = format!(
        "{}/tests/data/scenes/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The diagram through the subdivision engine with the given field choices.
fn run(scene: &Scene, options: FieldOptions) -> VoronoiComplex {
    let fields = SiteField::for_scene_with(scene, &options).unwrap();
    let params =
        gvd::internals::SubdivisionParams::for_scene(scene, None, true, Default::default());
    gvd::internals::subdivide(&fields, &params).unwrap().complex
}

fn implicit_circles() -> FieldOptions {
    FieldOptions {
        implicit_circles: true,
        ..Default::default()
    }
}

fn site(kind: SiteKind) -> Site {
    Site { id: None, kind }
}

fn scene(domain: [f64; 4], epsilon: f64, sites: Vec<SiteKind>) -> Scene {
    Scene::new(
        Aabb::from_array(domain),
        epsilon,
        Mode::Voronoi,
        sites.into_iter().map(site).collect(),
    )
    .expect("a valid scene")
}

fn circle(x: f64, y: f64, r: f64) -> SiteKind {
    SiteKind::Circle {
        center: Point::new(x, y),
        radius: r,
    }
}

fn sites_of(g: &[Generator]) -> Vec<usize> {
    let mut s: Vec<usize> = g.iter().map(|g| g.site()).collect();
    s.sort_unstable();
    s
}

// ---------------------------------------------------------------------------------------
// An independent Apollonius construction: three-circle tangency in f64.

/// The points `p` with `|p − c_i| − r_i = ρ` for the three circles (closed form: two
/// linear equations give `p(ρ)`, a quadratic gives `ρ`), refined by Newton steps.
fn apollonius_points(c: [(Point, f64); 3]) -> Vec<(Point, f64)> {
    let (p1, r1) = c[0];
    let mut out = Vec::new();
    // |p − c_k|² − (ρ + r_k)² = 0; subtract k = 1 from k = 2, 3:
    // 2(c_1 − c_k)·p + 2(r_1 − r_k)ρ = |c_1|² − |c_k|² − r_1² + r_k²  (sign as below)
    let row = |k: usize| {
        let (pk, rk) = c[k];
        let a = 2.0 * (pk.x - p1.x);
        let b = 2.0 * (pk.y - p1.y);
        let e = -2.0 * (rk - r1);
        let rhs = (pk.x * pk.x + pk.y * pk.y - rk * rk) - (p1.x * p1.x + p1.y * p1.y - r1 * r1);
        (a, b, e, rhs)
    };
    // a x + b y = rhs + (−e) ρ … written as a x + b y − e ρ = rhs
    let (a1, b1, e1, f1) = row(1);
    let (a2, b2, e2, f2) = row(2);
    let det = a1 * b2 - a2 * b1;
    if det.abs() < 1e-14 {
        return out;
    }
    // x = x0 + x1 ρ, y = y0 + y1 ρ (the −e ρ moved to the right: a x + b y = f + e ρ)
    let x0 = (f1 * b2 - f2 * b1) / det;
    let x1 = (e1 * b2 - e2 * b1) / det;
    let y0 = (a1 * f2 - a2 * f1) / det;
    let y1 = (a1 * e2 - a2 * e1) / det;
    // (x − p1x)² + (y − p1y)² = (ρ + r1)²
    let (dx, dy) = (x0 - p1.x, y0 - p1.y);
    let qa = x1 * x1 + y1 * y1 - 1.0;
    let qb = 2.0 * (dx * x1 + dy * y1) - 2.0 * r1;
    let qc = dx * dx + dy * dy - r1 * r1;
    let mut rhos = Vec::new();
    if qa.abs() < 1e-14 {
        if qb.abs() > 1e-14 {
            rhos.push(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let s = disc.sqrt();
            rhos.push((-qb + s) / (2.0 * qa));
            rhos.push((-qb - s) / (2.0 * qa));
        }
    }
    for rho in rhos {
        let mut p = Point::new(x0 + x1 * rho, y0 + y1 * rho);
        // Newton on F(p) = (d_1 − d_2, d_1 − d_3), d_k = |p − c_k| − r_k
        for _ in 0..8 {
            let d: Vec<(f64, Point)> = c
                .iter()
                .map(|&(ck, rk)| {
                    let v = p - ck;
                    let n = v.norm();
                    (n - rk, v * (1.0 / n))
                })
                .collect();
            let f = [d[0].0 - d[1].0, d[0].0 - d[2].0];
            let j = [d[0].1 - d[1].1, d[0].1 - d[2].1];
            let det = j[0].x * j[1].y - j[0].y * j[1].x;
            if det.abs() < 1e-300 || !det.is_finite() {
                break;
            }
            let sx = (f[0] * j[1].y - f[1] * j[0].y) / det;
            let sy = (j[0].x * f[1] - j[1].x * f[0]) / det;
            p = Point::new(p.x - sx, p.y - sy);
        }
        let rho = p.dist(p1) - r1;
        // a real tangency: every |p − c_k| = ρ + r_k (the quadratic also has the
        // solutions with ρ + r_k < 0 for some k)
        if c.iter()
            .all(|&(ck, rk)| ((p.dist(ck) - rk) - rho).abs() < 1e-9)
        {
            out.push((p, rho));
        }
    }
    out
}

/// The Apollonius vertices inside the domain by brute force over triples, each kept when
/// no fourth circle is nearer (emptiness).
fn brute_vertices(circles: &[(Point, f64)], domain: &Aabb) -> Vec<(Point, [usize; 3])> {
    let n = circles.len();
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                for (p, rho) in apollonius_points([circles[i], circles[j], circles[k]]) {
                    if !domain.contains(p) {
                        continue;
                    }
                    let empty = (0..n).filter(|&l| l != i && l != j && l != k).all(|l| {
                        let (cl, rl) = circles[l];
                        p.dist(cl) - rl > rho + 1e-9
                    });
                    let seen = out
                        .iter()
                        .any(|(q, s): &(Point, [usize; 3])| *s == [i, j, k] && q.dist(p) < 1e-9);
                    if empty && !seen {
                        out.push((p, [i, j, k]));
                    }
                }
            }
        }
    }
    out
}

/// The neighbouring pairs seen on a fine grid (nearest circle per node).
fn grid_pairs(circles: &[(Point, f64)], domain: &Aabb, n: usize) -> BTreeSet<[usize; 2]> {
    let label = |q: Point| {
        (0..circles.len())
            .min_by(|&a, &b| {
                let fa = q.dist(circles[a].0) - circles[a].1;
                let fb = q.dist(circles[b].0) - circles[b].1;
                fa.total_cmp(&fb)
            })
            .unwrap()
    };
    let at =
        |i: usize, j: usize| domain.at((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
    let labels: Vec<Vec<usize>> = (0..n)
        .map(|i| (0..n).map(|j| label(at(i, j))).collect())
        .collect();
    let mut pairs = BTreeSet::new();
    for i in 0..n {
        for j in 0..n {
            for (di, dj) in [(1, 0), (0, 1)] {
                if i + di < n && j + dj < n {
                    let (a, b) = (labels[i][j], labels[i + di][j + dj]);
                    if a != b {
                        pairs.insert([a.min(b), a.max(b)]);
                    }
                }
            }
        }
    }
    pairs
}

fn circles_of(scene: &Scene) -> Vec<(Point, f64)> {
    scene
        .sites()
        .iter()
        .map(|s| match s.kind {
            SiteKind::Circle { center, radius } => (center, radius),
            _ => panic!("circles only"),
        })
        .collect()
}

/// Same vertices (within `tol`, same generators) and the same adjacency as the brute
/// force construction.
fn check_apollonius(scene: &Scene, d: &VoronoiComplex, tol: f64) {
    let circles = circles_of(scene);
    let brute = brute_vertices(&circles, &scene.domain());
    let mut used = vec![false; d.vertices.len()];
    for (p, s) in &brute {
        let hit = d
            .vertices
            .iter()
            .position(|v| v.at.dist(*p) <= tol && sites_of(&v.sites) == s.to_vec());
        let Some(h) = hit else {
            panic!("brute-force vertex {p:?} of {s:?} not in the diagram");
        };
        used[h] = true;
    }
    for (k, v) in d.vertices.iter().enumerate() {
        assert!(
            used[k],
            "diagram vertex {:?} of {:?} has no brute-force match",
            v.at,
            sites_of(&v.sites)
        );
    }
    assert_eq!(d.vertices.len(), brute.len());
    // adjacency: the diagram's edge pairs are exactly the pairs of the brute-force vertices
    // and of the grid (edges without vertices cross the domain)
    let ours: BTreeSet<[usize; 2]> = common::edge_pairs(d).into_iter().collect();
    let mut theirs = grid_pairs(&circles, &scene.domain(), 500);
    for (_, s) in &brute {
        theirs.insert([s[0], s[1]]);
        theirs.insert([s[0], s[2]]);
        theirs.insert([s[1], s[2]]);
    }
    assert_eq!(ours, theirs, "adjacency differs");
}

/// Random disjoint circles plus a hidden one (inside another circle's disk) and a circle
/// of radius 0.
fn random_circles(n: usize, seed: u64) -> Scene {
    let mut state = seed;
    let mut rnd = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut cs: Vec<(Point, f64)> = Vec::new();
    while cs.len() < n {
        let c = Point::new(-1.8 + 3.6 * rnd(), -1.8 + 3.6 * rnd());
        let r = 0.02 + 0.2 * rnd();
        if cs.iter().all(|&(d, s)| c.dist(d) > r + s + 0.05) {
            cs.push((c, r));
        }
    }
    cs.push((Point::new(1.95, -1.95), 0.0));
    scene(
        [-2.0, -2.0, 2.0, 2.0],
        1e-3,
        cs.iter().map(|&(c, r)| circle(c.x, c.y, r)).collect(),
    )
}

#[test]
fn apollonius_matches_three_circle_tangency_closed_form_path() {
    for seed in [1, 2, 3] {
        let sc = random_circles(14, seed);
        let d = run(&sc, FieldOptions::default());
        check_apollonius(&sc, &d, 2e-3);
    }
}

#[test]
fn apollonius_matches_three_circle_tangency_implicit_path() {
    for seed in [1, 2] {
        let sc = random_circles(14, seed);
        let d = run(&sc, implicit_circles());
        check_apollonius(&sc, &d, 2e-3);
    }
}

#[test]
fn corpus_apollonius_matches_brute_force_on_both_paths() {
    let sc = data("apollonius-circles-0100");
    check_apollonius(&sc, &run(&sc, FieldOptions::default()), 2e-3);
    check_apollonius(&sc, &run(&sc, implicit_circles()), 2e-3);
}

#[test]
fn a_circle_inside_another_is_refused_as_overlapping() {
    let sites = [circle(-0.5, 0.0, 0.6), circle(-0.4, 0.1, 0.2)];
    let refused = Scene::new(
        Aabb::from_array([-2.0, -2.0, 2.0, 2.0]),
        1e-3,
        Mode::Voronoi,
        sites.into_iter().map(site).collect(),
    );
    assert!(
        matches!(
            refused,
            Err(gvd::Error::Conflict {
                site: 1,
                other: 0,
                ..
            })
        ),
        "{refused:?}"
    );
}

#[test]
fn radius_zero_circles_give_the_point_diagram() {
    let pts = [
        (0.1, 0.2),
        (-1.2, 0.7),
        (1.3, -0.4),
        (0.5, 1.5),
        (-0.8, -1.1),
        (1.6, 1.1),
        (-1.5, -0.2),
        (0.2, -1.6),
    ];
    let points = scene(
        [-2.0, -2.0, 2.0, 2.0],
        1e-3,
        pts.iter()
            .map(|&(x, y)| SiteKind::Point {
                at: Point::new(x, y),
                metric: Metric::Euclidean,
            })
            .collect(),
    );
    let circles = scene(
        [-2.0, -2.0, 2.0, 2.0],
        1e-3,
        pts.iter().map(|&(x, y)| circle(x, y, 0.0)).collect(),
    );
    let subdivision = gvd::Options {
        engine: gvd::Engine::Subdivision,
        ..Default::default()
    };
    let reference = gvd::compute(&points, &subdivision).unwrap();
    for opts in [FieldOptions::default(), implicit_circles()] {
        let d = run(&circles, opts);
        assert_eq!(d.vertices.len(), reference.vertices.len());
        assert_eq!(d.edges.len(), reference.edges.len());
        for v in &reference.vertices {
            assert!(
                d.vertices
                    .iter()
                    .any(|w| w.at.dist(v.at) < 1e-6 && sites_of(&w.sites) == sites_of(&v.sites)),
                "point vertex {:?} missing",
                v.at
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// Scenes that pass the independent checker.

fn verified(scene: &Scene, d: &VoronoiComplex) {
    let report = gvd::verify::verify(scene, d, &gvd::verify::VerifyOptions::default()).unwrap();
    assert!(
        report.passed,
        "{}\n{}",
        report.summary_line(),
        report.problems.join("\n")
    );
}

#[test]
fn ellipses_pass_verify() {
    let sc = data("ellipses-0020");
    let d = gvd::compute(&sc, &gvd::Options::default()).unwrap();
    assert!(d.vertices.len() >= 20);
    verified(&sc, &d);
}

#[test]
fn implicit_field_circles_pass_verify_and_match_the_circles() {
    let sc = data("implicit-field-circles-0100");
    let d = gvd::compute(&sc, &gvd::Options::default()).unwrap();
    verified(&sc, &d);
    // the same diagram as the circle scene (the checker's own scene)
    verified(&data("apollonius-circles-0100"), &d);
}

fn equation(text: &str) -> Equation {
    Equation::parse(text, &['x', 'y', 'z']).unwrap()
}

#[test]
fn mixed_scene_points_circles_ellipse_and_implicit_fields_pass_verify() {
    let sc = scene(
        [-2.0, -2.0, 2.0, 2.0],
        1e-3,
        vec![
            SiteKind::Point {
                at: Point::new(0.2, 0.3),
                metric: Metric::Euclidean,
            },
            circle(-1.0, 1.0, 0.3),
            SiteKind::Ellipse {
                center: Point::new(1.0, -0.8),
                semi_axes: [0.4, 0.15],
                rotation: 0.6,
            },
            // a circle of radius 0.25 about (-1, -1), written implicitly
            SiteKind::ImplicitField {
                equation: equation("(x+1)^2 + (y+1)^2 - (z+0.25)^2"),
            },
            // an ellipse-like anisotropic cone: z = sqrt((x-1)^2/4 + (y-1)^2) - 0.1
            SiteKind::ImplicitField {
                equation: equation("(x-1)^2/4 + (y-1)^2 - (z+0.1)^2"),
            },
            SiteKind::Point {
                at: Point::new(-0.3, -1.6),
                metric: Metric::Euclidean,
            },
        ],
    );
    let d = gvd::compute(&sc, &gvd::Options::default()).unwrap();
    assert!(d.vertices.len() >= 4);
    verified(&sc, &d);
}

/// The smallest non-negative root of `d² − z² − z³` by bisection (independent of the
/// library's root finders; the left side decreases for z ≥ 0).
fn cubic_value(q: Point) -> f64 {
    let d2 = (q.x - 0.5).powi(2) + q.y * q.y;
    let (mut lo, mut hi) = (0.0f64, 1.0 + d2);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if d2 - m * m - m * m * m > 0.0 {
            lo = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn cubic_implicit_field_edges_lie_on_the_bisectors() {
    // g has degree 3 in z: the point values go through Bernstein root isolation.
    // (`gvd verify` disagrees with the shared checker on this scene, which passes there;
    // checked here by sampling the edges against an independent evaluation.)
    let sc = scene(
        [-2.0, -2.0, 2.0, 2.0],
        2e-3,
        vec![
            SiteKind::ImplicitField {
                equation: equation("(x-0.5)^2 + y^2 - z^2*(1 + z)"),
            },
            SiteKind::Point {
                at: Point::new(-1.0, 0.4),
                metric: Metric::Euclidean,
            },
            SiteKind::Point {
                at: Point::new(-0.6, -1.2),
                metric: Metric::Euclidean,
            },
            circle(1.2, 1.3, 0.2),
        ],
    );
    let field = |k: usize, q: Point| -> (f64, f64) {
        // value and a bound of the gradient's norm near q (for a distance tolerance)
        match k {
            0 => {
                let h = 1e-6;
                let v = cubic_value(q);
                let gx = (cubic_value(q + Point::new(h, 0.0))
                    - cubic_value(q - Point::new(h, 0.0)))
                    / (2.0 * h);
                let gy = (cubic_value(q + Point::new(0.0, h))
                    - cubic_value(q - Point::new(0.0, h)))
                    / (2.0 * h);
                (v, gx.hypot(gy))
            }
            1 => (q.dist(Point::new(-1.0, 0.4)), 1.0),
            2 => (q.dist(Point::new(-0.6, -1.2)), 1.0),
            _ => (q.dist(Point::new(1.2, 1.3)) - 0.2, 1.0),
        }
    };
    let d = gvd::compute(&sc, &gvd::Options::default()).unwrap();
    assert_eq!(d.vertices.len(), 1);
    let pairs: BTreeSet<[usize; 2]> = d
        .edges
        .iter()
        .map(|e| [e.sites[0].site(), e.sites[1].site()])
        .map(|[a, b]| [a.min(b), a.max(b)])
        .collect();
    assert!(pairs.contains(&[0, 1]) && pairs.contains(&[0, 2]) && pairs.contains(&[0, 3]));
    for e in &d.edges {
        let (a, b) = (e.sites[0].site(), e.sites[1].site());
        for p in &e.points {
            let (fa, ga) = field(a, *p);
            let (fb, gb) = field(b, *p);
            // distance to the bisector, to first order
            let off = (fa - fb).abs() / (ga + gb).max(1e-3);
            assert!(off < sc.epsilon(), "edge {a}-{b} point {p:?} is {off} off");
            for k in 0..4 {
                let (fk, _) = field(k, *p);
                assert!(
                    fk >= fa.min(fb) - 2.0 * sc.epsilon(),
                    "site {k} nearer at {p:?}"
                );
            }
        }
    }
}

#[test]
fn refusals_name_the_site_and_equation_and_never_panic() {
    let dom = Aabb::from_array([-1.0, -1.0, 1.0, 1.0]);
    let no_z = SiteKind::ImplicitField {
        equation: Equation::parse("x^2 + y^2", &['x', 'y', 'z']).unwrap(),
    };
    let e = SiteField::from_site(3, &no_z, &dom)
        .unwrap_err()
        .to_string();
    assert!(e.contains("site 3") && e.contains("equation"), "{e}");
    // a field whose roots blow up along x = 0 (the z coefficient vanishes there) and that
    // has no root for x < 0: computed without panicking
    let sc = scene(
        [-1.0, -1.0, 1.0, 1.0],
        1e-2,
        vec![
            SiteKind::ImplicitField {
                equation: equation("x*z - 1"),
            },
            SiteKind::Point {
                at: Point::new(0.5, 0.5),
                metric: Metric::Euclidean,
            },
        ],
    );
    let d = gvd::compute(&sc, &gvd::Options::default()).unwrap();
    assert!(!d.edges.is_empty());
}

// ---------------------------------------------------------------------------------------
// Property tests: the §3.1 bounds enclose sampled field values.

fn check_box(f: &SiteField, b: &Aabb, samples: &[(f64, f64)], lipschitz: bool) {
    let s = f.state(b);
    let r = f.bound(&s, b);
    let g = f.gradient_bound(&s, b);
    for &(u, v) in samples {
        let q = b.at(u, v);
        let val = f.value(q);
        let tol = 1e-9 * (1.0 + val.abs());
        assert!(
            r.lo - tol <= val && val <= r.hi + tol,
            "value {val} at {q:?} outside bound {r:?} of box {b:?}"
        );
        if let Some(g) = g {
            let gq = f.gradient(q);
            let ok = |i: gvd::internals::Interval, x: f64| i.lo - 1e-6 <= x && x <= i.hi + 1e-6;
            // the closed form may be evaluated just inside a closed site's boundary
            if val > 1e-6 || !lipschitz {
                assert!(
                    ok(g[0], gq.x) && ok(g[1], gq.y),
                    "gradient {gq:?} at {q:?} outside {g:?} of box {b:?}"
                );
            }
        }
    }
    // the children's bounds (inherited, split by de Casteljau) enclose too
    let (l, rr) = f.split(&s, b, Axis::X, 0.5 * (b.min.x + b.max.x));
    let (lb, rb) = b.split(Axis::X, 0.5 * (b.min.x + b.max.x));
    for (cs, cb) in [(l, lb), (rr, rb)] {
        let cr = f.bound(&cs, &cb);
        for &(u, v) in samples {
            let q = cb.at(u, v);
            let val = f.value(q);
            let tol = 1e-9 * (1.0 + val.abs());
            assert!(cr.lo - tol <= val && val <= cr.hi + tol);
        }
    }
}

fn boxes() -> impl Strategy<Value = (Aabb, Vec<(f64, f64)>)> {
    (
        -2.0..2.0f64,
        -2.0..2.0f64,
        -3.0..0.5f64,
        0.3..3.0f64,
        proptest::collection::vec((0.0..=1.0f64, 0.0..=1.0f64), 12),
    )
        .prop_map(|(x, y, logw, aspect, s)| {
            let w = 10f64.powf(logw);
            let h = (w * aspect).min(4.0);
            (Aabb::new(Point::new(x, y), Point::new(x + w, y + h)), s)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn implicit_circle_bounds_enclose((b, s) in boxes(), cx in -1.5..1.5f64, cy in -1.5..1.5f64, r in 0.0..0.4f64) {
        let dom = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
        let f = SiteField::from_site_with(0, &circle(cx, cy, r), &dom, &implicit_circles()).unwrap();
        check_box(&f, &b, &s, true);
    }

    #[test]
    fn user_implicit_field_bounds_enclose((b, s) in boxes(), cx in -1.5..1.5f64, cy in -1.5..1.5f64, r in 0.0..0.4f64, k in 0.5..2.0f64) {
        let dom = Aabb::from_array([-2.0, -2.0, 3.0, 3.0]);
        let eq = format!("{k}*(x-({cx}))^2 + (y-({cy}))^2 - (z+{r})^2");
        let kind = SiteKind::ImplicitField { equation: equation(&eq) };
        let f = SiteField::from_site(0, &kind, &dom).unwrap();
        check_box(&f, &b, &s, false);
        // a cubic in z
        let eq = format!("(x-({cx}))^2 + (y-({cy}))^2 - z^2*(1+z) + {r}*z");
        let kind = SiteKind::ImplicitField { equation: equation(&eq) };
        let f = SiteField::from_site(0, &kind, &dom).unwrap();
        check_box(&f, &b, &s, false);
    }

    #[test]
    fn ellipse_bounds_enclose((b, s) in boxes(), cx in -1.0..1.0f64, cy in -1.0..1.0f64, a in 0.05..0.4f64, e in 0.2..1.0f64, rot in 0.0..3.2f64) {
        let dom = Aabb::from_array([-2.0, -2.0, 3.0, 3.0]);
        let kind = SiteKind::Ellipse { center: Point::new(cx, cy), semi_axes: [a, a * e], rotation: rot };
        let f = SiteField::from_site(0, &kind, &dom).unwrap();
        check_box(&f, &b, &s, true);
    }
}
