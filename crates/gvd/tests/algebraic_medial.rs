//! `medial_axis` mode on closed algebraic curves, against closed forms and brute force
//! written here: the ellipse `x²/4 + y² = 1`, whose medial axis is the segment between
//! the centres of curvature of its ends `(±(a² − b²)/a, 0) = (±1.5, 0)`, with clearance
//! `√(1 − x²/3)` at `(x, 0)`; the superellipse `x⁴ + y⁴ = 1`, whose axis is its two
//! diagonals out to the centres of curvature of its diagonal vertices; a non-symmetric
//! oval; `gvd verify` on them, passing their diagrams and failing broken ones; and the
//! refusals.

use gvd::geom::Point;
use gvd::verify::{verify, VerifyOptions};
use gvd::{compute, Error, Options, Scene, VoronoiComplex};

fn scene(name: &str) -> Scene {
    let path = format!("{}/tests/data/algebraic/{name}", env!("CARGO_MANIFEST_DIR"));
    Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The least distance from `q` to a closed curve given by points `at(θ)`, θ ∈ [0, 2π),
/// densely sampled and refined by golden-section search about the best sample.
fn curve_distance(q: Point, at: &dyn Fn(f64) -> Point) -> f64 {
    let n = 20_000;
    let h = std::f64::consts::TAU / n as f64;
    let d = |t: f64| q.dist(at(t));
    let best = (0..n)
        .map(|k| k as f64 * h)
        .min_by(|a, b| d(*a).total_cmp(&d(*b)))
        .unwrap();
    let (mut lo, mut hi) = (best - h, best + h);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (a, b) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if d(a) < d(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    d(0.5 * (lo + hi))
}

fn ellipse(t: f64) -> Point {
    Point::new(2.0 * t.cos(), t.sin())
}

fn superellipse(t: f64) -> Point {
    let r = (t.cos().powi(4) + t.sin().powi(4)).powf(-0.25);
    Point::new(r * t.cos(), r * t.sin())
}

/// The ends of the ridges: the vertices of degree one.
fn ridge_ends(d: &VoronoiComplex) -> Vec<Point> {
    let mut deg = vec![0; d.vertices.len()];
    for e in &d.edges {
        for v in [e.from, e.to].into_iter().flatten() {
            deg[v] += 1;
        }
    }
    (0..d.vertices.len())
        .filter(|&v| deg[v] == 1)
        .map(|v| d.vertices[v].at)
        .collect()
}

/// Asserts that one of `ends` lies within `eps` of `end`.
fn assert_an_end_near(ends: &[Point], end: Point, eps: f64) {
    let near = ends
        .iter()
        .map(|p| p.dist(end))
        .fold(f64::INFINITY, f64::min);
    assert!(near <= eps, "a ridge end within {eps} of {end:?}: {ends:?}");
}

/// Asserts that every vertex and edge point has its clearance, equal to the brute-force
/// distance to the curve.
fn assert_clearances(d: &VoronoiComplex, at: &dyn Fn(f64) -> Point) {
    for v in &d.vertices {
        let r = v.clearance.expect("every vertex has its clearance");
        let brute = curve_distance(v.at, at);
        assert!(
            (r - brute).abs() < 1e-9,
            "vertex {:?}: {r} vs {brute}",
            v.at
        );
    }
    for e in &d.edges {
        assert_eq!(e.clearance.len(), e.points.len());
        for (q, r) in e.points.iter().zip(&e.clearance) {
            let brute = curve_distance(*q, at);
            assert!((r - brute).abs() < 1e-9, "edge point {q:?}: {r} vs {brute}");
        }
    }
}

#[test]
fn the_ellipse_has_the_segment_between_its_centres_of_curvature() {
    let s = scene("ellipse-medial.json");
    let eps = s.epsilon();
    let d = compute(&s, &Options::default()).unwrap();
    d.check_invariants().unwrap();
    let ends = ridge_ends(&d);
    assert_eq!(ends.len(), 2, "two ridge ends: {:?}", d.vertices);
    for end in [Point::new(-1.5, 0.0), Point::new(1.5, 0.0)] {
        assert_an_end_near(&ends, end, eps);
    }
    // every point on the segment, and the segment covered
    let points: Vec<Point> = d
        .edges
        .iter()
        .flat_map(|e| e.points.iter().copied())
        .collect();
    for q in &points {
        assert!(
            q.y.abs() <= eps && q.x.abs() <= 1.5 + eps,
            "{q:?} off the axis"
        );
    }
    for k in 0..=300 {
        let x = -1.5 + eps + (3.0 - 2.0 * eps) * k as f64 / 300.0;
        let covered = d.edges.iter().any(|e| {
            e.points
                .windows(2)
                .any(|w| w[0].x.min(w[1].x) <= x && x <= w[0].x.max(w[1].x))
        });
        assert!(covered, "x = {x} not covered");
    }
    for v in &d.vertices {
        let closed = (1.0 - v.at.x * v.at.x / 3.0).sqrt();
        let r = v.clearance.unwrap();
        assert!(
            (r - closed).abs() <= 2.0 * v.at.y.abs() + 1e-9,
            "{v:?} vs {closed}"
        );
    }
    assert_clearances(&d, &ellipse);
    let mic = &d.stats["max_inscribed_circle"];
    assert!(
        (mic["radius"].as_f64().unwrap() - 1.0).abs() < 1e-9,
        "{mic}"
    );
    for e in &d.edges {
        let piece = gvd::complex::Generator::Feature {
            site: 0,
            feature: gvd::complex::FeatureKind::Piece,
            index: 0,
        };
        assert_eq!(e.sites, [piece; 2]);
    }
}

#[test]
fn the_superellipse_has_its_diagonals_out_to_the_centres_of_curvature() {
    let s = scene("superellipse-medial.json");
    let eps = s.epsilon();
    let d = compute(&s, &Options::default()).unwrap();
    d.check_invariants().unwrap();
    // the vertex (c, c), c = 2^(-1/4); curvature of x⁴ + y⁴ = 1 there by the implicit
    // formula (f_xx f_y² + f_yy f_x²) / |∇f|³ with f_x = f_y = 4c³, f_xx = f_yy = 12c²
    let c = 2f64.powf(-0.25);
    let g = 4.0 * c.powi(3);
    let kappa = 2.0 * 12.0 * c * c * g * g / (2.0 * g * g).powf(1.5);
    let reach = c - 1.0 / kappa / 2f64.sqrt();
    let ends = ridge_ends(&d);
    assert_eq!(ends.len(), 4, "{:?}", d.vertices);
    for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
        let end = Point::new(sx * reach, sy * reach);
        assert_an_end_near(&ends, end, eps);
    }
    for e in &d.edges {
        for q in &e.points {
            let off = (q.x.abs() - q.y.abs()).abs() / 2f64.sqrt();
            assert!(
                off <= eps && q.x.abs() <= reach + eps,
                "{q:?} off the diagonals"
            );
        }
    }
    assert_clearances(&d, &superellipse);
}

#[test]
fn a_non_symmetric_oval_has_its_ridges_inside_with_their_clearances() {
    let s = scene("oval-medial.json");
    let d = compute(&s, &Options::default()).unwrap();
    d.check_invariants().unwrap();
    // f = x⁴/4 + x³/8 + y² − 1 along rays from the origin (inside: f(0) < 0)
    let f = |p: Point| p.x.powi(4) / 4.0 + p.x.powi(3) / 8.0 + p.y * p.y - 1.0;
    let at = |t: f64| {
        let u = Point::new(t.cos(), t.sin());
        let (mut lo, mut hi) = (0.0, 3.0);
        for _ in 0..100 {
            let m = 0.5 * (lo + hi);
            if f(u * m) < 0.0 {
                lo = m;
            } else {
                hi = m;
            }
        }
        u * lo
    };
    assert!(!d.edges.is_empty());
    for e in &d.edges {
        for q in &e.points {
            assert!(f(*q) < 0.0, "{q:?} outside the oval");
        }
    }
    assert_clearances(&d, &at);
    // symmetric about the x axis: each ridge end has its mirror image
    let ends = ridge_ends(&d);
    assert_eq!(ends.len(), 4, "{:?}", d.vertices);
    for p in &ends {
        let mirror = Point::new(p.x, -p.y);
        assert!(ends.iter().any(|q| q.dist(mirror) <= s.epsilon()), "{p:?}");
    }
    // each ridge ends at the centre of curvature of a curve vertex (a local maximum of
    // the curvature κ = (f_xx f_y² − 2 f_xy f_x f_y + f_yy f_x²) / |∇f|³), p − ∇f/(|∇f| κ)
    let centre = |t: f64| {
        let p = at(t);
        let (fx, fy) = (p.x.powi(3) + 3.0 * p.x * p.x / 8.0, 2.0 * p.y);
        let (fxx, fyy) = (3.0 * p.x * p.x + 0.75 * p.x, 2.0);
        let g = fx.hypot(fy);
        let kappa = (fxx * fy * fy + fyy * fx * fx) / g.powi(3);
        (
            kappa,
            Point::new(p.x - fx / g / kappa, p.y - fy / g / kappa),
        )
    };
    let n = 20_000;
    let h = std::f64::consts::TAU / n as f64;
    let kappa = |k: usize| centre(k as f64 * h).0;
    let centres: Vec<Point> = (0..n)
        .filter(|&k| kappa(k) > kappa((k + n - 1) % n) && kappa(k) >= kappa((k + 1) % n))
        .map(|k| centre(k as f64 * h).1)
        .collect();
    assert_eq!(centres.len(), 4, "{centres:?}");
    // the checker's centre-of-curvature test amplifies an end's offset there (the foot is
    // flat to fourth order near a curve vertex), so ask for far better than epsilon
    for p in &ends {
        assert_an_end_near(&centres, *p, s.epsilon() / 20.0);
    }
}

/// Asserts that `gvd verify` passes `d` as the diagram of `s`.
fn assert_verified(s: &Scene, d: &VoronoiComplex) {
    let report = verify(s, d, &VerifyOptions::default()).unwrap();
    assert!(
        report.passed,
        "{}\n{:?}",
        report.summary_line(),
        report.problems
    );
}

#[test]
fn verify_passes_the_three_curves_medial_axes() {
    for name in [
        "ellipse-medial.json",
        "superellipse-medial.json",
        "oval-medial.json",
    ] {
        let s = scene(name);
        assert_verified(&s, &compute(&s, &Options::default()).unwrap());
    }
}

/// Without one of its ridges, or with a ridge end moved off its centre of curvature,
/// the oval's medial axis fails: the checker finds the ridges by the jumps of the
/// nearest foot across its grid, and the ends by the centres of curvature.
#[test]
fn verify_fails_a_missing_ridge_and_a_moved_ridge_end() {
    let s = scene("oval-medial.json");
    let d = compute(&s, &Options::default()).unwrap();
    let opts = VerifyOptions {
        grid: 256,
        ..VerifyOptions::default()
    };
    let mut missing = d.clone();
    missing.edges.remove(0);
    let report = verify(&s, &missing, &opts).unwrap();
    assert!(
        !report.passed && report.complete < 1.0,
        "{}",
        report.summary_line()
    );

    let end = ridge_ends(&d)[0];
    let mut moved = d.clone();
    let k = moved.vertices.iter().position(|v| v.at == end).unwrap();
    moved.vertices[k].at = end + (end * (0.02 / end.norm()));
    let report = verify(&s, &moved, &opts).unwrap();
    assert!(
        !report.passed && report.vertices_ok.0 < report.vertices_ok.1,
        "{}",
        report.summary_line()
    );
}

#[test]
fn singular_and_open_curves_are_refused_naming_the_site() {
    let nodal = compute(&scene("nodal-medial.json"), &Options::default());
    match nodal {
        Err(Error::Unsupported {
            site, ref message, ..
        }) => {
            assert_eq!(site, 1);
            assert!(message.contains("singular"), "{message}");
        }
        other => panic!("expected a refusal naming site 1, got {other:?}"),
    }
    let open = Scene::from_json(
        r#"{"domain": [-2, -2, 2, 2], "mode": "medial_axis",
            "sites": [{"kind": "algebraic", "equation": "y - x^2"}]}"#,
    )
    .unwrap();
    match compute(&open, &Options::default()) {
        Err(Error::Unsupported {
            site, ref message, ..
        }) => {
            assert_eq!(site, 0);
            assert!(message.contains("clip box"), "{message}");
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
}
