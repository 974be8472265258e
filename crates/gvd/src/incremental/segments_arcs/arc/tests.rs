//! Arc bisectors against brute force: distances computed independently here.

use super::super::geometry::{Bisector, Line, Shape};
use super::{Arc, Conic};
use crate::geom::{Aabb, Point};
use std::f64::consts::{PI, TAU};

/// xorshift64*: deterministic and dependency-free.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn unit(&mut self) -> Point {
        let a = self.range(-PI, PI);
        Point::new(a.cos(), a.sin())
    }
    fn sign(&mut self) -> f64 {
        if self.next() < 0.5 {
            -1.0
        } else {
            1.0
        }
    }
    fn arc(&mut self, ends: [u32; 2]) -> Arc {
        let c = Point::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0));
        let a0 = self.range(-4.0, 4.0);
        let span = self.range(0.3, TAU);
        Arc::new(c, self.range(0.2, 2.0), a0, a0 + span, ends)
    }
}

/// Distance to a circle, to a line (through `a` and `b`), to a point.
fn circle_dist(x: Point, c: Point, r: f64) -> f64 {
    ((x.x - c.x).hypot(x.y - c.y) - r).abs()
}
fn line_dist(x: Point, a: Point, b: Point) -> f64 {
    ((b - a).cross(x - a) / (b.x - a.x).hypot(b.y - a.y)).abs()
}

/// Whether `x` is in the closed wedge of `arc`, by rotating `x − c` back by `a0`.
fn in_closed_wedge(arc: &Arc, x: Point) -> bool {
    let v = x - arc.c;
    let (s, c) = arc.a0.sin_cos();
    let rot = Point::new(c * v.x + s * v.y, -s * v.x + c * v.y);
    let a = rot.y.atan2(rot.x);
    let a = if a < 0.0 { a + TAU } else { a };
    a <= arc.span + 1e-9 || a >= TAU - 1e-9
}

/// The other generator of a test, with its independent distance.
enum Other {
    Point(Point),
    Segment(Line),
    Arc(Arc),
}

impl Other {
    fn dist(&self, x: Point) -> f64 {
        match self {
            Other::Point(p) => x.dist(*p),
            Other::Segment(l) => line_dist(x, l.a, l.a + l.d * l.len),
            Other::Arc(b) => circle_dist(x, b.c, b.r),
        }
    }
    fn shape(&self) -> Shape<'_> {
        match self {
            Other::Point(p) => Shape::Point(7, *p),
            Other::Segment(l) => Shape::Segment(l),
            Other::Arc(b) => Shape::Arc(b),
        }
    }
}

/// A random generator at distance `t0` from `x0`.
fn other_through(rng: &mut Rng, x0: Point, t0: f64, kind: usize) -> Option<Other> {
    match kind {
        0 => Some(Other::Point(x0 + rng.unit() * t0)),
        1 => {
            let n = rng.unit();
            let foot = x0 - n * (t0 * rng.sign());
            let len = rng.range(0.5, 3.0);
            let a = foot + n.perp() * rng.range(-len, 0.0);
            Some(Other::Segment(Line::new(a, a + n.perp() * len, [8, 9])))
        }
        _ => {
            let c2 = Point::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
            let rho2 = x0.dist(c2);
            let r2 = if rng.next() < 0.5 || rho2 - t0 < 0.05 {
                rho2 + t0
            } else {
                rho2 - t0
            };
            let a0 = rng.range(-4.0, 4.0);
            Some(Other::Arc(Arc::new(c2, r2, a0, a0 + 5.0, [10, 11])))
        }
    }
}

/// A random point of the wedge of `arc`, off the circle, with its distance.
fn point_in_wedge(rng: &mut Rng, arc: &Arc) -> (Point, f64) {
    let rel = arc.span * rng.range(0.05, 0.95);
    let mut rho = arc.r * rng.range(0.1, 2.5);
    if (rho - arc.r).abs() < 0.05 * arc.r {
        rho = 1.5 * arc.r;
    }
    (arc.at(rel, rho - arc.r), (rho - arc.r).abs())
}

fn conic_of(b: &Bisector) -> Option<Conic> {
    match b {
        Bisector::Conic(c) => Some(*c),
        _ => None,
    }
}

#[test]
fn arc_basics() {
    let arc = Arc::new(Point::new(1.0, 2.0), 2.0, 0.0, PI / 2.0, [0, 1]);
    assert!((arc.span - PI / 2.0).abs() < 1e-15);
    assert!(arc.end_points[0].dist(Point::new(3.0, 2.0)) < 1e-15);
    assert!(arc.end_points[1].dist(Point::new(1.0, 4.0)) < 1e-15);
    let x = Point::new(1.0 + 3.0 * 0.6, 2.0 + 3.0 * 0.8);
    assert!((arc.open_distance(x) - 1.0).abs() < 1e-12);
    assert!(arc.claims(x, 1.1) && !arc.claims(x, 0.9));
    let inner = Point::new(1.5, 2.5);
    assert!((arc.open_distance(inner) - (2.0 - 0.5f64.sqrt())).abs() < 1e-12);
    for out in [
        Point::new(0.0, 3.0),
        Point::new(2.0, 1.0),
        Point::new(5.0, 2.0),
    ] {
        assert_eq!(arc.open_distance(out), f64::INFINITY);
        assert!(!arc.claims(out, 100.0));
    }
    // The centre is in no wedge, even of a full circle.
    assert_eq!(arc.open_distance(arc.c), f64::INFINITY);
    let full = Arc::new(Point::new(0.0, 0.0), 1.0, 0.3, 0.3, [0, 0]);
    assert_eq!(full.span, TAU);
    assert_eq!(full.open_distance(full.c), f64::INFINITY);
    assert!((full.open_distance(Point::new(-2.0, 0.0)) - 1.0).abs() < 1e-15);
    let wrap = Arc::new(Point::new(0.0, 0.0), 1.0, 1.0, 1.0 - PI / 2.0, [0, 1]);
    assert!((wrap.span - 1.5 * PI).abs() < 1e-12);
    // The parameter is continuous across the wedge, cut opposite its middle.
    let p = arc.param(arc.at(-0.1, 0.5));
    assert!((p + 0.1).abs() < 1e-12, "{p}");
    assert!((arc.param(arc.at(PI / 2.0 + 0.1, 0.5)) - (PI / 2.0 + 0.1)).abs() < 1e-12);
}

/// Every point of every random conic is equidistant from both generators.
#[test]
fn conic_points_are_equidistant() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut checked = 0;
    for case in 0..600 {
        let arc = rng.arc([0, 1]);
        let (x0, t0) = point_in_wedge(&mut rng, &arc);
        let Some(other) = other_through(&mut rng, x0, t0, case % 3) else {
            continue;
        };
        let near = Point::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
        let b = Bisector::of(Shape::Arc(&arc), other.shape(), near);
        let Some(conic) = conic_of(&b) else { continue };
        for k in 0..200 {
            let s = -PI + TAU * (k as f64 + 0.5) / 200.0;
            let Some((x, t)) = conic.point(s) else {
                continue;
            };
            let scale = 1.0 + x.dist(arc.c);
            let da = circle_dist(x, arc.c, arc.r);
            let db = other.dist(x);
            assert!((da - db).abs() <= 1e-9 * scale, "case {case}: {da} vs {db}");
            assert!((t - da).abs() <= 1e-9 * scale, "case {case}: t {t} vs {da}");
            checked += 1;
        }
    }
    assert!(checked > 30_000, "{checked}");
}

/// `of` picks the conic through `near` (a point equidistant from both).
#[test]
fn branch_through_near() {
    let mut rng = Rng(12345);
    let mut checked = [0; 3];
    for case in 0..3000 {
        let kind = case % 3;
        let arc = rng.arc([0, 1]);
        let (x0, t0) = point_in_wedge(&mut rng, &arc);
        let Some(other) = other_through(&mut rng, x0, t0, kind) else {
            continue;
        };
        // Near, not on: a realistic midpoint of two nearby vertices.
        let near = x0 + rng.unit() * (1e-3 * t0);
        for (a, b) in [
            (Shape::Arc(&arc), other.shape()),
            (other.shape(), Shape::Arc(&arc)),
        ] {
            let bis = Bisector::of(a, b, near);
            let Some(conic) = conic_of(&bis) else {
                // Only ties of a focus arc with another arc of the other's order.
                continue;
            };
            let s = conic.param(x0);
            let (x, t) = conic.point(s).expect("x0 is on the curve");
            // A thin conic hugging a ray (semi-latus rectum |N/M| ≪ ρ: near tangency)
            // loses accuracy in its polar angle: the ray is a pole of ρ(θ).
            let thin = (conic.n / conic.m).abs() < 1e-6 * x0.dist(arc.c);
            let scale = (1.0 + x0.dist(arc.c)) * if thin { 1e4 } else { 1.0 };
            assert!(
                x.dist(x0) <= 1e-9 * scale,
                "case {case}: {x:?} vs {x0:?} {conic:?}"
            );
            assert!((t - t0).abs() <= 1e-9 * scale, "case {case}");
            checked[kind] += 1;

            // The midpoint of two points of the curve on either side of x0, as the
            // engine passes it: it tells the candidates apart while the chord's
            // sagitta is small beside the clearance (else see `of_edge`).
            let ds = 0.1 * t0 / x0.dist(conic.arc.c);
            let (Some((xa, _)), Some((xb, _))) = (conic.point(s - ds), conic.point(s + ds)) else {
                continue;
            };
            let Some(k) = conic_of(&Bisector::of(a, b, xa.lerp(xb, 0.5))) else {
                continue;
            };
            let (x, _) = k.point(s).expect("x0 is on the curve");
            assert!(x.dist(x0) <= 1e-9 * scale, "case {case}: midpoint");

            // Both ends of an edge, however far apart along the curve.
            let Some((xc, _)) = conic.point(rng.range(0.0, arc.span)) else {
                continue;
            };
            let Some(k) = conic_of(&Bisector::of_edge(a, b, x0, xc)) else {
                continue;
            };
            let (x, _) = k.point(s).expect("x0 is on the curve");
            assert!(x.dist(x0) <= 1e-9 * scale, "case {case}: edge");
        }
    }
    assert!(checked.iter().all(|&n| n > 1500), "{checked:?}");
}

/// Two points of a conic inside the arc's wedge, valid all the way between.
fn piece(rng: &mut Rng, conic: &Conic, arc: &Arc) -> Option<(f64, f64)> {
    let (s0, s1) = (rng.range(0.0, arc.span), rng.range(0.0, arc.span));
    for k in 0..=400 {
        let s = s0 + (s1 - s0) * k as f64 / 400.0;
        let (x, _) = conic.point(s)?;
        if x.dist(arc.c) > 50.0 {
            return None;
        }
    }
    Some((s0, s1))
}

/// `boundary` finds the crossing of `|x − q| > t` that brute-force sampling brackets,
/// and `polyline` stays within `tol` of the curve.
#[test]
fn boundary_and_polyline() {
    let mut rng = Rng(777);
    let (mut crossings, mut polylines) = (0, 0);
    for case in 0..1500 {
        let arc = rng.arc([0, 1]);
        let (x0, t0) = point_in_wedge(&mut rng, &arc);
        let Some(other) = other_through(&mut rng, x0, t0, case % 3) else {
            continue;
        };
        let bis = Bisector::of(Shape::Arc(&arc), other.shape(), x0);
        let Some(conic) = conic_of(&bis) else {
            continue;
        };
        let Some((s0, s1)) = piece(&mut rng, &conic, &arc) else {
            continue;
        };
        let (from, _) = conic.point(s0).unwrap();
        let (to, _) = conic.point(s1).unwrap();
        assert!(in_closed_wedge(&arc, from) && in_closed_wedge(&arc, to));
        let scale = 1.0 + from.dist(arc.c) + to.dist(arc.c);

        // A third point q at the clearance of a random point of the piece.
        let (xs, ts) = conic.point(rng.range(s0.min(s1), s0.max(s1))).unwrap();
        let q = xs + rng.unit() * ts;
        let g = |x: Point, t: f64| x.dist(q) - t;
        const N: usize = 4000;
        let samples: Vec<(f64, f64)> = (0..=N)
            .map(|k| {
                let s = s0 + (s1 - s0) * k as f64 / N as f64;
                let (x, t) = conic.point(s).unwrap();
                (s, g(x, t))
            })
            .collect();
        let changes: Vec<usize> = (0..N)
            .filter(|&k| (samples[k].1 > 0.0) != (samples[k + 1].1 > 0.0))
            .collect();
        if samples[0].1 > 0.0 && changes.len() == 1 {
            let k = changes[0];
            let (at, t) = bis.boundary(from, to, |x, t| g(x, t) > 0.0);
            let s = conic.param(at);
            let (lo, hi) = (
                samples[k].0.min(samples[k + 1].0),
                samples[k].0.max(samples[k + 1].0),
            );
            assert!(
                s >= lo - 1e-12 && s <= hi + 1e-12,
                "case {case}: {s} not in [{lo}, {hi}]"
            );
            assert!(g(at, t).abs() <= 1e-9 * scale, "case {case}: {}", g(at, t));
            assert!((t - other.dist(at)).abs() <= 1e-9 * scale);
            crossings += 1;
        }

        for tol in [1e-2, 1e-4] {
            let mut pts = Vec::new();
            let everywhere = Aabb::new(Point::new(-1e300, -1e300), Point::new(1e300, 1e300));
            assert!(bis.polyline(from, to, tol, &everywhere, 100_000, &mut pts));
            assert_eq!((pts[0], *pts.last().unwrap()), (from, to));
            assert!(pts.len() < 100_000);
            for k in 0..=1000 {
                let (x, _) = bis.at_fraction(from, to, k as f64 / 1000.0);
                let d = pts
                    .windows(2)
                    .map(|w| crate::geom::segment_distance(x, w[0], w[1]))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d <= tol * (1.0 + 1e-6) + 1e-12 * scale,
                    "case {case}: {d} > {tol}"
                );
            }
            for w in pts.windows(2) {
                let mid = conic.point(0.5 * (conic.param(w[0]) + conic.param(w[1])));
                assert!(mid.is_some(), "case {case}: samples off the piece");
            }
        }
        polylines += 1;
    }
    assert!(
        crossings > 200 && polylines > 600,
        "{crossings} {polylines}"
    );
}

/// The straight and degenerate cases.
#[test]
fn degenerate_bisectors() {
    let c = Point::new(0.5, -0.5);
    let arc = Arc::new(c, 2.0, 0.2, 2.0, [3, 4]);
    let [e0, e1] = arc.end_points;

    // An arc and its own endpoint: the ray from the centre through it.
    for (id, e) in [(3, e0), (4, e1)] {
        let b = Bisector::of(Shape::Point(id, e), Shape::Arc(&arc), c);
        let Bisector::Line { origin, dir, .. } = b else {
            panic!("{b:?}")
        };
        assert!(origin.dist(e) < 1e-15 && (e - c).cross(dir).abs() < 1e-12);
        let (x, t) = b.at_fraction(c, e + (e - c), 0.25);
        assert!((t - circle_dist(x, c, 2.0)).abs() < 1e-12 && (t - x.dist(e)).abs() < 1e-12);
    }

    // A point on the circle outside the arc: a chord.
    let p = arc.point_at(-1.0);
    let b = Bisector::of(Shape::Point(9, p), Shape::Arc(&arc), c);
    assert!(matches!(b, Bisector::Chord { .. }), "{b:?}");

    // A point at the centre: the circle of radius r/2.
    let b = Bisector::of(Shape::Point(9, c), Shape::Arc(&arc), c);
    let (x, t) = conic_of(&b).unwrap().point(1.0).unwrap();
    assert!((x.dist(c) - 1.0).abs() < 1e-15 && (t - 1.0).abs() < 1e-15);

    // A segment tangent at the start, on its inner side: the ray through the tangent
    // point; on the outer side, a parabola.
    let tangent = (e0 - c).perp();
    let seg = Line::new(e0 - tangent, e0, [5, 3]);
    let inside = c.lerp(e0, 0.5);
    let b = Bisector::of(Shape::Segment(&seg), Shape::Arc(&arc), inside);
    let Bisector::Line { origin, dir, .. } = b else {
        panic!("{b:?}")
    };
    assert!(origin.dist(c) < 1e-12 && (e0 - c).cross(dir).abs() < 1e-12);
    let (x, t) = b.at_fraction(c, e0, 0.3);
    assert!((t - line_dist(x, seg.a, e0)).abs() < 1e-12);
    let outside = c + (e0 - c).perp() * 2.0;
    let b = Bisector::of(Shape::Segment(&seg), Shape::Arc(&arc), outside);
    let k = conic_of(&b).unwrap();
    let (x, t) = k.point(k.param(outside)).unwrap();
    assert!(x.dist(outside) < 1e-12 && (t - 2.0).abs() < 1e-12);

    // Externally tangent arcs: the ray through the tangent point.
    let m = arc.point_at(0.5);
    let arc2 = Arc::new(m + (m - c) * 0.5, 1.0, 0.0, 6.0, [6, 7]);
    let b = Bisector::of(Shape::Arc(&arc), Shape::Arc(&arc2), m.lerp(c, 0.1));
    let Bisector::Line { origin, dir, .. } = b else {
        panic!("{b:?}")
    };
    assert!(origin.dist(c) < 1e-12 && (m - c).cross(dir).abs() < 1e-12);

    // Two arcs of one circle sharing an endpoint: the ray through it; concentric
    // arcs: the middle circle.
    let arc3 = Arc::new(c, 2.0, 2.0, 4.0, [4, 8]);
    let b = Bisector::of(Shape::Arc(&arc), Shape::Arc(&arc3), c);
    let Bisector::Line { origin, dir, .. } = b else {
        panic!("{b:?}")
    };
    assert!(origin.dist(e1) < 1e-12 && (e1 - c).cross(dir).abs() < 1e-12);
    let arc4 = Arc::new(c, 3.0, 1.0, 3.0, [10, 11]);
    for near in [c, c + Point::new(2.5, 0.0)] {
        let b = Bisector::of(Shape::Arc(&arc), Shape::Arc(&arc4), near);
        let (x, t) = conic_of(&b).unwrap().point(0.4).unwrap();
        assert!((x.dist(c) - 2.5).abs() < 1e-12 && (t - 0.5).abs() < 1e-12);
    }
}
