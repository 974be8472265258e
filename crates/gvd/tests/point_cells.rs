//! Cells of Euclidean point scenes, traced from the incremental graph's faces, against
//! the generic `cells::build_cells` on the same edges and against the exact clipped
//! cells (Sutherland–Hodgman), on ordinary and degenerate scenes.

use gvd::complex::Cell;
use gvd::geom::{Aabb, Point};
use gvd::internals::build_cells;
use gvd::scene::{Metric, Mode, Site, SiteKind};
use gvd::{compute, Options, Scene};

fn scene(domain: Aabb, points: &[Point]) -> Scene {
    Scene::new(
        domain,
        1e-4,
        Mode::Voronoi,
        points
            .iter()
            .map(|&at| Site {
                id: None,
                kind: SiteKind::Point {
                    at,
                    metric: Metric::Euclidean,
                },
            })
            .collect(),
    )
    .expect("a valid scene")
}

fn signed_area(ring: &[Point]) -> f64 {
    let n = ring.len();
    0.5 * (0..n)
        .map(|i| ring[i].cross(ring[(i + 1) % n]))
        .sum::<f64>()
}

fn area(c: &Cell) -> f64 {
    c.rings.iter().map(|r| signed_area(r)).sum()
}

/// The nearest point, the least index among equals.
fn nearest(points: &[Point], q: Point) -> usize {
    (0..points.len()).fold(0, |m, i| {
        if q.dist(points[i]) < q.dist(points[m]) {
            i
        } else {
            m
        }
    })
}

/// The exact area of point `i`'s cell clipped to the domain (Sutherland–Hodgman against
/// each bisector's half-plane; a copy of a point of smaller index has no cell).
fn exact_area(points: &[Point], i: usize, b: &Aabb) -> f64 {
    if points[..i].contains(&points[i]) {
        return 0.0;
    }
    let mut poly = b.corners().to_vec();
    let si = points[i];
    for &sj in points.iter().filter(|&&sj| sj != si) {
        let f = |p: Point| (p - si).dot(p - si) - (p - sj).dot(p - sj);
        let mut next = Vec::new();
        for k in 0..poly.len() {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            if f(p) <= 0.0 {
                next.push(p);
            }
            if (f(p) < 0.0) != (f(q) < 0.0) && f(p) != f(q) {
                next.push(p.lerp(q, f(p) / (f(p) - f(q))));
            }
        }
        poly = next;
    }
    if poly.len() < 3 {
        0.0
    } else {
        signed_area(&poly)
    }
}

/// Computes the scene's cells (from the faces) and checks them against `build_cells`
/// and the exact areas; returns them.
fn check(name: &str, domain: Aabb, points: &[Point]) -> Vec<Cell> {
    check_with(name, domain, points, true)
}

/// [`check`], against `build_cells` only if `against_edges`.
fn check_with(name: &str, domain: Aabb, points: &[Point], against_edges: bool) -> Vec<Cell> {
    let d = compute(&scene(domain, points), &Options::default()).unwrap();
    assert_eq!(d.stats["engine"], "incremental");
    assert!(
        !d.stats.contains_key("cells_from_edges"),
        "{name}: fell back to build_cells"
    );
    let size = domain.longest_side();
    let tol = 1e-9 * size;
    let whole = domain.width() * domain.height();

    // Sorted by site, one counter-clockwise ring each, not closed by a repeated point.
    assert!(d.cells.windows(2).all(|w| w[0].site < w[1].site), "{name}");
    for c in &d.cells {
        assert_eq!(c.rings.len(), 1, "{name}: site {}", c.site);
        let r = &c.rings[0];
        assert!(signed_area(r) > 0.0, "{name}: site {}", c.site);
        assert_ne!(r.first(), r.last(), "{name}: site {}", c.site);
        assert!(
            r.windows(2).all(|w| w[0] != w[1]),
            "{name}: site {}",
            c.site
        );
        assert!(
            r.iter().all(|&p| domain.contains(p)),
            "{name}: site {}",
            c.site
        );
    }

    // The same cells as build_cells on the same edges.
    let old = if against_edges {
        build_cells(&d, &domain, &|q| nearest(points, q))
    } else {
        d.cells.clone()
    };
    assert_eq!(
        d.cells.iter().map(|c| c.site).collect::<Vec<_>>(),
        old.iter().map(|c| c.site).collect::<Vec<_>>(),
        "{name}: sites with a cell"
    );
    let near = |p: Point, ring: &[Point]| ring.iter().any(|q| q.dist(p) <= tol);
    for (c, o) in d.cells.iter().zip(&old) {
        assert_eq!(o.rings.len(), 1, "{name}: site {}", c.site);
        assert!(
            (area(c) - area(o)).abs() <= 1e-12 * whole,
            "{name}: site {}: area {} vs build_cells {}",
            c.site,
            area(c),
            area(o)
        );
        let (r, s) = (&c.rings[0], &o.rings[0]);
        assert!(
            r.iter().all(|&p| near(p, s)) && s.iter().all(|&p| near(p, r)),
            "{name}: site {}: ring {r:?} vs build_cells {s:?}",
            c.site
        );
    }

    // The exact clipped cells (small scenes only: quadratic).
    if points.len() <= 400 {
        for i in 0..points.len() {
            let want = exact_area(points, i, &domain);
            let got = d.cells.iter().find(|c| c.site == i).map_or(0.0, area);
            assert!(
                (got - want).abs() <= 1e-9 * whole,
                "{name}: site {i}: area {got} vs exact {want}"
            );
        }
    }
    let total: f64 = d.cells.iter().map(area).sum();
    assert!(
        (total - whole).abs() <= 1e-9 * whole,
        "{name}: cells cover {total} of {whole}"
    );
    d.cells
}

fn random_points(n: usize, seed: u64, lo: f64, hi: f64) -> Vec<Point> {
    let mut s = seed;
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((s >> 11) as f64 / (1u64 << 53) as f64)
    };
    (0..n).map(|_| Point::new(next(), next())).collect()
}

const UNIT: Aabb = Aabb::new(Point::new(0.0, 0.0), Point::new(1.0, 1.0));

#[test]
fn random_points_inside_and_around_the_domain() {
    check("random 300", UNIT, &random_points(300, 1, 0.0, 1.0));
    check("random 300 around", UNIT, &random_points(300, 2, -0.3, 1.3));
    check("random 5000", UNIT, &random_points(5000, 3, 0.0, 1.0));
    let far = Aabb::from_array([-1e6, 3e6, -0.5e6, 3.2e6]);
    let pts: Vec<Point> = random_points(200, 4, 0.0, 1.0)
        .into_iter()
        .map(|p| Point::new(-1e6 + 0.5e6 * p.x, 3e6 + 0.2e6 * p.y))
        .collect();
    check("random 200, far from the origin", far, &pts);
}

#[test]
fn grids_cocircular_points_on_the_boundary() {
    let grid = |k: usize| -> Vec<Point> {
        (0..k * k)
            .map(|i| Point::new((i % k) as f64, (i / k) as f64))
            .collect()
    };
    // Sites on the boundary and at the corners; vertices on the boundary.
    check("grid 5x5", Aabb::from_array([0.0, 0.0, 4.0, 4.0]), &grid(5));
    check(
        "grid 6x6 with margins",
        Aabb::from_array([-0.5, -0.5, 5.5, 5.5]),
        &grid(6),
    );
    check(
        "grid 20x20 cut",
        Aabb::from_array([2.25, 3.25, 11.0, 17.25]),
        &grid(20),
    );
    // Rows of bisectors on the lower and upper sides: build_cells leaves the rows of
    // cells along them out (an edge on the boundary confuses its face labels), so only
    // the exact areas are checked.
    check_with(
        "grid 20x20 cut along bisectors",
        Aabb::from_array([2.25, 3.5, 11.0, 17.5]),
        &grid(20),
        false,
    );
    // Twelve cocircular points and the centre.
    let mut ring: Vec<Point> = (0..12)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 12.0;
            Point::new(0.5 + 0.3 * a.cos(), 0.5 + 0.3 * a.sin())
        })
        .collect();
    check("cocircular 12", UNIT, &ring);
    ring.push(Point::new(0.5, 0.5));
    check("cocircular 12 and centre", UNIT, &ring);
    // Four exactly cocircular points whose circle's centre is a domain corner.
    let square = [
        Point::new(1.0, 0.0),
        Point::new(0.0, 1.0),
        Point::new(-1.0, 0.0),
        Point::new(0.0, -1.0),
    ];
    check(
        "vertex at a corner",
        Aabb::from_array([0.0, 0.0, 2.0, 2.0]),
        &square,
    );
}

#[test]
fn collinear_points() {
    let line: Vec<Point> = (0..20).map(|i| Point::new(0.05 * i as f64, 0.3)).collect();
    check("collinear horizontal", UNIT, &line);
    let diag: Vec<Point> = (0..20)
        .map(|i| Point::new(0.05 * i as f64, 0.05 * i as f64))
        .collect();
    check("collinear diagonal", UNIT, &diag);
    // Bisectors parallel to the sides, one of them on a side.
    let on_side: Vec<Point> = (0..5)
        .map(|i| Point::new(0.5, -1.0 + 0.5 * i as f64))
        .collect();
    // build_cells leaves the cell along that side out, as for the grid above.
    check_with(
        "bisector along a side",
        Aabb::from_array([0.0, -0.75, 1.0, 1.0]),
        &on_side,
        false,
    );
}

#[test]
fn duplicate_points_are_refused_naming_the_later_copy() {
    let mut pts = random_points(100, 5, 0.0, 1.0);
    pts.insert(40, pts[7]);
    let sites = pts.iter().map(|&at| Site::point(at)).collect();
    match Scene::new(UNIT, 1e-4, Mode::Voronoi, sites) {
        Err(gvd::Error::Site {
            site,
            field,
            message,
        }) => {
            assert_eq!((site, field.as_str()), (40, "at"));
            assert!(message.contains("duplicate of site 7"), "{message}");
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn one_two_and_no_points() {
    let one = check("one point", UNIT, &[Point::new(0.3, 0.9)]);
    assert_eq!(one.len(), 1);
    assert_eq!(one[0].rings[0], UNIT.corners().to_vec());
    check("one point outside", UNIT, &[Point::new(-5.0, 7.0)]);
    let two = check(
        "two points",
        UNIT,
        &[Point::new(0.2, 0.3), Point::new(0.7, 0.6)],
    );
    assert_eq!(two.len(), 2);
    check(
        "two points, bisector through corners",
        UNIT,
        &[Point::new(0.0, 0.0), Point::new(1.0, 1.0)],
    );
    check(
        "two points outside, the bisector outside",
        UNIT,
        &[Point::new(-1.0, 0.5), Point::new(-3.0, 0.5)],
    );
    check(
        "three points outside, the domain in one cell",
        UNIT,
        &[
            Point::new(3.0, 3.0),
            Point::new(5.0, 3.0),
            Point::new(4.0, 5.0),
        ],
    );
    let d = compute(&scene(UNIT, &[]), &Options::default()).unwrap();
    assert!(d.cells.is_empty());
}

#[test]
fn points_on_the_boundary() {
    let mut pts: Vec<Point> = random_points(40, 6, 0.0, 1.0)
        .into_iter()
        .enumerate()
        .map(|(i, p)| match i % 4 {
            0 => Point::new(p.x, 0.0),
            1 => Point::new(1.0, p.y),
            2 => Point::new(p.x, 1.0),
            _ => Point::new(0.0, p.y),
        })
        .collect();
    pts.extend(UNIT.corners());
    check("on the boundary", UNIT, &pts);
    pts.extend(random_points(60, 7, 0.0, 1.0));
    check("on the boundary and inside", UNIT, &pts);
}
