//! Bisectors in Held's offset-parameter form (the OpenVoronoi wiki page): a generator
//! grown by the clearance `t` is a line `n·p + c + k·t = 0` (`|n| = 1`) or a circle
//! `|p − c| = r + k·t` (a point is a circle of radius 0 with `k = +1`; an arc's circle
//! has `k = +1` outside and `−1` inside), and the bisector of two generators is the
//! curve of points on both grown generators:
//!
//! * circle–circle, `u = (c₂ − c₁)/d`, `d = |c₂ − c₁|`: `p = c₁ + a(t)·u ± u⊥·√((r₁ + k₁t)² − a(t)²)`
//!   with `a(t) = (d² + r₁² − r₂²)/(2d) + t·(k₁r₁ − k₂r₂)/d` (the `t²` terms cancel as
//!   `k₁² = k₂² = 1`);
//! * circle–line: `p = c₁ + α(t)·n ± n⊥·√((r₁ + k₁t)² − α(t)²)` with
//!   `α(t) = −(n·c₁ + c) − k·t`;
//! * line–line: `p = p₀ + p₁·t`, the solution of the two line equations.
//!
//! In the coefficients of [`BisectorPiece`], `x1 − x2 − x3·t` is the part before the
//! root and `x4` the root's direction. Parallel lines and concentric circles have a
//! bisector of constant clearance, which this form cannot trace: no form then.

use crate::complex::BisectorPiece;
use crate::geom::predicates::segment_anchor;
use crate::geom::Point;

/// A generator grown by the clearance `t`.
#[derive(Clone, Copy, Debug)]
pub(crate) enum OffsetGen {
    /// `|p − c| = r + k·t`.
    Circle { c: Point, r: f64, k: f64 },
    /// `n·p + c + k·t = 0`, `|n| = 1`.
    Line { n: Point, c: f64, k: f64 },
}

impl OffsetGen {
    pub(crate) fn point(c: Point) -> OffsetGen {
        OffsetGen::Circle { c, r: 0.0, k: 1.0 }
    }

    /// The circle of centre `c` and radius `r`, grown towards `side` (outward when
    /// `side` lies outside the circle).
    pub(crate) fn circle(c: Point, r: f64, side: Point) -> OffsetGen {
        let k = if side.dist(c) >= r { 1.0 } else { -1.0 };
        OffsetGen::Circle { c, r, k }
    }

    /// The line through `a` and `b`, grown towards `side`; `None` if `a = b`. Its
    /// offset `c` comes from `a`, or from the segment's point nearest to the origin
    /// where `a` lies beyond `reach` (`segment_anchor`): `n·a` of an end far away
    /// cancels to the rounding of that end.
    pub(crate) fn line(a: Point, b: Point, side: Point, reach: f64) -> Option<OffsetGen> {
        let len = a.dist(b);
        if len <= 0.0 {
            return None;
        }
        let n = (b - a).perp() * (1.0 / len);
        let c = -n.dot(segment_anchor(a, b, reach).0);
        let k = if n.dot(side) + c <= 0.0 { 1.0 } else { -1.0 };
        Some(OffsetGen::Line { n, c, k })
    }

    /// The clearance `t` at which the grown generator passes through `p`.
    fn clearance(&self, p: Point) -> f64 {
        match *self {
            OffsetGen::Circle { c, r, k } => k * (p.dist(c) - r),
            OffsetGen::Line { n, c, k } => -k * (n.dot(p) + c),
        }
    }
}

/// The coefficients of a bisector (`x`, `y` as in [`BisectorPiece`]).
#[derive(Clone, Copy, Debug)]
struct Form {
    x: [f64; 8],
    y: [f64; 8],
}

impl Form {
    /// The bisector of `a` and `b`, or `None` when its clearance is constant.
    fn of(a: OffsetGen, b: OffsetGen) -> Option<Form> {
        use OffsetGen::{Circle, Line};
        match (a, b) {
            (Line { .. }, Circle { .. }) => Form::of(b, a),
            (
                Circle {
                    c: c1,
                    r: r1,
                    k: k1,
                },
                Circle {
                    c: c2,
                    r: r2,
                    k: k2,
                },
            ) => {
                let d = c1.dist(c2);
                if d <= 1e-15 * (c1.x.abs() + c1.y.abs() + r1 + r2) {
                    return None;
                }
                let u = (c2 - c1) * (1.0 / d);
                let a0 = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
                let a1 = (k1 * r1 - k2 * r2) / d;
                Some(Form::around(c1, u, a0, a1, r1, k1))
            }
            (Circle { c: c1, r, k: k1 }, Line { n, c, k }) => {
                // α(t) = −(n·c₁ + c) − k·t along n.
                let off = n.dot(c1) + c;
                Some(Form::around(c1, n, -off, -k, r, k1))
            }
            (
                Line {
                    n: n1,
                    c: c1,
                    k: k1,
                },
                Line {
                    n: n2,
                    c: c2,
                    k: k2,
                },
            ) => {
                let det = n1.cross(n2);
                if det.abs() <= 1e-12 {
                    return None;
                }
                // [n1; n2]·p = −(c + k·t), by Cramer's rule.
                let solve = |r1: f64, r2: f64| {
                    Point::new((r1 * n2.y - r2 * n1.y) / det, (n1.x * r2 - n2.x * r1) / det)
                };
                let (p0, p1) = (solve(-c1, -c2), solve(-k1, -k2));
                Some(Form {
                    x: [p0.x, 0.0, -p1.x, 0.0, 0.0, 0.0, 0.0, 0.0],
                    y: [p0.y, 0.0, -p1.y, 0.0, 0.0, 0.0, 0.0, 0.0],
                })
            }
        }
    }

    /// `p = c + (a0 + a1·t)·u ± u⊥·√((r + k·t)² − (a0 + a1·t)²)`, `|u| = 1`.
    fn around(c: Point, u: Point, a0: f64, a1: f64, r: f64, k: f64) -> Form {
        let w = u.perp();
        Form {
            x: [c.x, -a0 * u.x, -a1 * u.x, w.x, r, k, a0, a1],
            y: [c.y, -a0 * u.y, -a1 * u.y, w.y, r, k, a0, a1],
        }
    }

    /// The part before the root at clearance `t`, and the root's unit direction.
    fn base(&self, t: f64) -> (Point, Point) {
        let (x, y) = (&self.x, &self.y);
        (
            Point::new(x[0] - x[1] - x[2] * t, y[0] - y[1] - y[2] * t),
            Point::new(x[3], y[3]),
        )
    }

    /// The branch `p` lies on at clearance `t`: ±1, or 0 within `tol` of the apex.
    fn branch(&self, p: Point, t: f64, tol: f64) -> i8 {
        let (base, w) = self.base(t);
        let s = (p - base).dot(w);
        if s > tol {
            1
        } else if s < -tol {
            -1
        } else {
            0
        }
    }

    /// The apex's clearance between two points of clearance `t1` and `t2` on opposite
    /// branches: the root of `(x5 + x6·t)² = (x7 + x8·t)²` nearest to `[t1, t2]` (an
    /// extremum of the clearance: at most both, as for a parabola, or at least both,
    /// as on an ellipse inside an arc's circle).
    fn apex(&self, t1: f64, t2: f64) -> f64 {
        let (lo, hi) = (t1.min(t2), t1.max(t2));
        let [.., r, k, a0, a1] = self.x;
        let gap = |t: f64| (lo - t).max(t - hi).max(0.0);
        [(r + a0, k + a1), (r - a0, k - a1)]
            .iter()
            .filter(|&&(_, den)| den != 0.0)
            .map(|&(num, den)| -num / den)
            .filter(|t| t.is_finite())
            .min_by(|&a, &b| gap(a).total_cmp(&gap(b)))
            .unwrap_or(lo)
    }

    fn piece(&self, sign: i8, t: [f64; 2]) -> BisectorPiece {
        BisectorPiece {
            x: self.x,
            y: self.y,
            sign,
            t,
        }
    }
}

/// The pieces of the bisector of `a` and `b` under the polyline `points` (which lies
/// on it within `tol`), in order: split where the root changes sign. `None` when the
/// clearance is constant along the bisector.
pub(crate) fn pieces(
    a: OffsetGen,
    b: OffsetGen,
    points: &[Point],
    tol: f64,
) -> Option<Vec<BisectorPiece>> {
    let form = Form::of(a, b)?;
    let t: Vec<f64> = points
        .iter()
        .map(|&p| 0.5 * (a.clearance(p) + b.clearance(p)))
        .collect();
    let branch: Vec<i8> = points
        .iter()
        .zip(&t)
        .map(|(&p, &t)| form.branch(p, t, tol))
        .collect();
    let mut sign = branch.iter().copied().find(|&s| s != 0).unwrap_or(1);
    let mut out = Vec::new();
    let mut start = *t.first()?;
    for i in 1..points.len() {
        if branch[i] != 0 && branch[i] != sign {
            // The apex lies between the last point on this branch and point i.
            let apex = form.apex(t[i - 1], t[i]);
            out.push(form.piece(sign, [start, apex]));
            (start, sign) = (apex, branch[i]);
        }
    }
    out.push(form.piece(sign, [start, t[points.len() - 1]]));
    if out.len() > 1 {
        out.retain(|p| p.t[0] != p.t[1]);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(p: Point, q: Point, tol: f64) -> bool {
        p.dist(q) <= tol
    }

    /// Every kind of pair: points of the form lie on both grown generators at their
    /// clearance, and the pieces reproduce the sampled polyline.
    #[test]
    fn forms_lie_on_both_generators() {
        let p = OffsetGen::point(Point::new(0.3, -0.2));
        let q = OffsetGen::point(Point::new(1.1, 0.9));
        let side = Point::new(0.0, 2.0);
        let line = OffsetGen::line(
            Point::new(-1.0, -1.0),
            Point::new(2.0, -0.5),
            side,
            f64::INFINITY,
        )
        .unwrap();
        let line2 = OffsetGen::line(
            Point::new(-1.0, 3.0),
            Point::new(1.0, 1.5),
            side,
            f64::INFINITY,
        )
        .unwrap();
        let outside = OffsetGen::circle(Point::new(3.0, 2.0), 0.7, side);
        let inside = OffsetGen::circle(Point::new(0.5, 1.0), 3.0, side);
        let pairs = [
            (p, q),
            (p, line),
            (line, q),
            (line, line2),
            (p, outside),
            (outside, line),
            (inside, p),
            (outside, inside),
        ];
        for (k, &(a, b)) in pairs.iter().enumerate() {
            let form = Form::of(a, b).unwrap();
            for sign in [-1, 1] {
                for i in 0..=40 {
                    let t = 0.05 + 0.1 * i as f64;
                    let piece = form.piece(sign, [t, t]);
                    let x = piece.at(t);
                    let (u, v) = (form.x[4] + form.x[5] * t, form.x[6] + form.x[7] * t);
                    if u * u < v * v {
                        continue; // no point at this clearance
                    }
                    for g in [a, b] {
                        let err = (g.clearance(x) - t).abs();
                        assert!(err < 1e-9, "pair {k}, sign {sign}, t {t}: off by {err}");
                    }
                }
            }
        }
    }

    /// The bisector of two points, sampled across their midpoint: two pieces that meet
    /// at the apex, clearance half the distance.
    #[test]
    fn two_points_split_at_the_apex() {
        let (a, b) = (Point::new(0.0, 0.0), Point::new(2.0, 0.0));
        let line = [
            Point::new(1.0, -3.0),
            Point::new(1.0, 0.5),
            Point::new(1.0, 4.0),
        ];
        let pieces = pieces(OffsetGen::point(a), OffsetGen::point(b), &line, 1e-12).unwrap();
        assert_eq!(pieces.len(), 2);
        assert!((pieces[0].t[1] - 1.0).abs() < 1e-12 && (pieces[1].t[0] - 1.0).abs() < 1e-12);
        assert!(near(pieces[0].at(pieces[0].t[0]), line[0], 1e-12));
        assert!(near(pieces[1].at(pieces[1].t[1]), line[2], 1e-12));
        assert!(near(pieces[0].at(1.0), Point::new(1.0, 0.0), 1e-12));
        assert_ne!(pieces[0].sign, pieces[1].sign);
    }

    #[test]
    fn constant_clearance_has_no_form() {
        let side = Point::new(0.0, 0.5);
        let l1 = OffsetGen::line(
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            side,
            f64::INFINITY,
        )
        .unwrap();
        let l2 = OffsetGen::line(
            Point::new(0.0, 1.0),
            Point::new(1.0, 1.0),
            side,
            f64::INFINITY,
        )
        .unwrap();
        assert!(Form::of(l1, l2).is_none());
        let c = Point::new(0.0, 0.0);
        assert!(Form::of(OffsetGen::point(c), OffsetGen::circle(c, 1.0, side)).is_none());
    }
}
