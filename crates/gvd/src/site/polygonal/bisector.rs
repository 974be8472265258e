//! Bisectors of two polygonal features, in closed form (YSL12 ¶24 computes them
//! numerically; here they are conics): two corners or two edges give lines, a corner
//! and an edge a parabola. Along a line `p + t·d` each feature's squared distance in
//! its regime (`|q − c|²` for a corner, `(n·(q − a))²` for an edge's supporting line)
//! is a quadratic in `t`, so crossings with a box side and the points equidistant
//! from three features are roots of quadratics.

use super::{Polygonal, Shape};
use crate::geom::Point;
use smallvec::{smallvec, SmallVec};

/// `A t² + B t + C`.
type Quadratic = [f64; 3];

/// A feature's squared regime distance along `p + t·d`.
fn squared_along(shape: Shape, p: Point, d: Point) -> Quadratic {
    match shape {
        Shape::Corner(c) => {
            let w = p - c;
            [d.dot(d), 2.0 * w.dot(d), w.dot(w)]
        }
        Shape::Edge(a, b) => {
            let n = (b - a).perp() * (1.0 / a.dist(b));
            let (s0, s1) = (n.dot(p - a), n.dot(d));
            [s1 * s1, 2.0 * s0 * s1, s0 * s0]
        }
    }
}

/// The real roots of `A t² + B t + C` (a linear or constant one when `A` vanishes
/// against the others), by the cancellation-free formula. The coefficients are squared
/// lengths (`t` of order one spans at most `length`): `A` vanishes below
/// `1e-13·max(|A|, |B|, |C|, length²)`.
fn roots(q: Quadratic, length: f64) -> SmallVec<[f64; 2]> {
    let [a, b, c] = q;
    let size = a.abs().max(b.abs()).max(c.abs());
    if size == 0.0 {
        return SmallVec::new();
    }
    if a.abs() <= 1e-13 * size.max(length * length) {
        if b.abs() <= 1e-14 * size {
            return SmallVec::new();
        }
        return smallvec::smallvec![-c / b];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < -1e-14 * b * b {
        return SmallVec::new();
    }
    let root = disc.max(0.0).sqrt();
    let qq = -0.5 * (b + b.signum() * root);
    if qq == 0.0 {
        return smallvec::smallvec![0.0];
    }
    smallvec::smallvec![qq / a, c / qq]
}

fn minus(f: Quadratic, g: Quadratic) -> Quadratic {
    [f[0] - g[0], f[1] - g[1], f[2] - g[2]]
}

impl Polygonal {
    fn shape(&self, f: u32) -> Shape {
        self.features[f as usize].shape
    }

    /// Parameters `t ∈ [0, 1]` where `f` and `g` tie along the segment `from → to`
    /// (in their regimes: the caller checks zones and nearer features).
    pub fn crossings(&self, f: u32, g: u32, from: Point, to: Point) -> SmallVec<[f64; 2]> {
        let d = to - from;
        let q = minus(
            squared_along(self.shape(f), from, d),
            squared_along(self.shape(g), from, d),
        );
        let mut out = roots(q, self.scale.max(d.norm()));
        out.retain(|t| (0.0..=1.0).contains(t));
        out
    }

    /// The lines where two features of one type tie: the perpendicular bisector of two
    /// corners; for two edges `s₁ = s₂` (with oriented sides) or `s₁ = ±s₂`, or the
    /// normal at their corner when they are collinear. Each as a point and a
    /// direction.
    pub fn bisector_lines(&self, f: u32, g: u32) -> SmallVec<[(Point, Point); 2]> {
        let mut out = SmallVec::new();
        let line = |w: Point, k: f64, out: &mut SmallVec<[(Point, Point); 2]>| {
            let ww = w.dot(w);
            if ww > 1e-24 {
                out.push((w * (k / ww), w.perp()));
            }
        };
        match (self.shape(f), self.shape(g)) {
            (Shape::Corner(a), Shape::Corner(b)) => {
                line((b - a) * 2.0, b.dot(b) - a.dot(a), &mut out);
            }
            (Shape::Edge(a1, b1), Shape::Edge(a2, b2)) => {
                if let Some(c) = self.flat_corner(f, g) {
                    // collinear edges tie on the normal at their corner
                    let Shape::Corner(at) = self.shape(c) else {
                        return out;
                    };
                    line(b1 - a1, (b1 - a1).dot(at), &mut out);
                    return out;
                }
                let (ff, fg) = (&self.features[f as usize], &self.features[g as usize]);
                let n = |a: Point, b: Point, side: Option<Point>| {
                    side.unwrap_or_else(|| (b - a).perp() * (1.0 / a.dist(b)))
                };
                let (n1, n2) = (n(a1, b1, ff.side), n(a2, b2, fg.side));
                let signs: &[f64] = if ff.side.is_some() && fg.side.is_some() {
                    &[1.0]
                } else {
                    &[1.0, -1.0]
                };
                for &s in signs {
                    line(n1 - n2 * s, n1.dot(a1) - s * n2.dot(a2), &mut out);
                }
            }
            _ => {}
        }
        out
    }

    /// Points where three features tie in their regimes (candidates for a Voronoi
    /// vertex: the caller checks zones and nearer features): on the line bisector of
    /// two features of one type, the roots of the third's tie with one of them.
    pub fn ties3(&self, t: [u32; 3]) -> SmallVec<[Point; 4]> {
        let edge = |f: u32| self.features[f as usize].is_edge();
        let [f, g, h] = if edge(t[0]) == edge(t[1]) {
            t
        } else if edge(t[0]) == edge(t[2]) {
            [t[0], t[2], t[1]]
        } else {
            [t[1], t[2], t[0]]
        };
        let mut out = SmallVec::new();
        for (p, d) in self.bisector_lines(f, g) {
            // the direction at the domain's length, so that `t` of order one spans the
            // domain and the quadratic's coefficients are squared lengths, compared with
            // the squared domain size (as in [`Polygonal::crossings`])
            let d = d * (self.scale / d.norm());
            let q = minus(
                squared_along(self.shape(f), p, d),
                squared_along(self.shape(h), p, d),
            );
            for t in roots(q, self.scale) {
                out.push(p + d * t);
            }
        }
        out
    }

    /// A parameter along the bisector of `f` and `g` that orders its points: the
    /// position along the edge for a parabola, along the line otherwise (with the
    /// line's index first for two unoriented edges, whose bisector is two lines).
    pub fn bisector_param(&self, f: u32, g: u32, q: Point) -> (usize, f64) {
        match (self.shape(f), self.shape(g)) {
            (Shape::Corner(_), Shape::Edge(a, b)) | (Shape::Edge(a, b), Shape::Corner(_)) => {
                (0, (q - a).dot(b - a))
            }
            _ => {
                let lines = self.bisector_lines(f, g);
                let residual = |(p, d): &(Point, Point)| (q - *p).cross(*d).abs() / d.norm();
                let (k, (p, d)) = lines
                    .iter()
                    .enumerate()
                    .min_by(|x, y| residual(x.1).total_cmp(&residual(y.1)))
                    .map(|(k, l)| (k, *l))
                    .unwrap_or((0, (q, Point::new(1.0, 0.0))));
                (k, (q - p).dot(d))
            }
        }
    }

    /// The parabola of corner `c` and the line of edge `(a, b)` in the edge's frame:
    /// origin `a`, unit `u` along, unit `n` towards the corner, and the corner's
    /// coordinates `(cx, cy)`, `cy > 0`.
    fn parabola(c: Point, a: Point, b: Point) -> (Point, Point, Point, f64, f64) {
        let u = (b - a) * (1.0 / a.dist(b));
        let mut n = u.perp();
        if n.dot(c - a) < 0.0 {
            n = n * -1.0;
        }
        (a, u, n, (c - a).dot(u), (c - a).dot(n))
    }

    /// The bisector of `f` and `g` from `p` to `q` (both on it) as a polyline within
    /// `tol` of it: straight for lines; for a parabola `y = ((x − cx)² + cy²)/(2 cy)`
    /// in the edge's frame, points at steps `h ≤ √(8 cy tol)` in `x`, whose chords
    /// stray at most `h²/(8 cy)` (the curvature is at most `1/cy`).
    pub fn trace(&self, f: u32, g: u32, p: Point, q: Point, tol: f64) -> SmallVec<[Point; 2]> {
        let (c, a, b) = match (self.shape(f), self.shape(g)) {
            (Shape::Corner(c), Shape::Edge(a, b)) | (Shape::Edge(a, b), Shape::Corner(c)) => {
                (c, a, b)
            }
            _ => return smallvec![p, q],
        };
        let (o, u, n, cx, cy) = Self::parabola(c, a, b);
        if cy <= 0.0 {
            return smallvec![p, q];
        }
        let (xp, xq) = ((p - o).dot(u), (q - o).dot(u));
        let step = (8.0 * cy * tol).sqrt();
        let k = (((xq - xp).abs() / step).ceil() as usize).clamp(1, 1 << 16);
        let mut out = SmallVec::with_capacity(k + 1);
        out.push(p);
        for i in 1..k {
            let x = xp + (xq - xp) * (i as f64 / k as f64);
            let y = ((x - cx) * (x - cx) + cy * cy) / (2.0 * cy);
            out.push(o + u * x + n * y);
        }
        out.push(q);
        out
    }

    /// The point of the bisector of `f` and `g` halfway (in [`Self::bisector_param`])
    /// between `p` and `q`, both on it.
    pub fn bisector_midpoint(&self, f: u32, g: u32, p: Point, q: Point) -> Point {
        let (c, a, b) = match (self.shape(f), self.shape(g)) {
            (Shape::Corner(c), Shape::Edge(a, b)) | (Shape::Edge(a, b), Shape::Corner(c)) => {
                (c, a, b)
            }
            _ => return p.lerp(q, 0.5),
        };
        let (o, u, n, cx, cy) = Self::parabola(c, a, b);
        if cy <= 0.0 {
            return p.lerp(q, 0.5);
        }
        let x = 0.5 * ((p - o).dot(u) + (q - o).dot(u));
        o + u * x + n * (((x - cx) * (x - cx) + cy * cy) / (2.0 * cy))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_roots_are_accurate_and_degrade_to_linear() {
        let r = roots([1.0, -3.0, 2.0], 1.0);
        let mut r: Vec<f64> = r.to_vec();
        r.sort_by(f64::total_cmp);
        assert!((r[0] - 1.0).abs() < 1e-15 && (r[1] - 2.0).abs() < 1e-15);
        assert_eq!(roots([0.0, 2.0, -1.0], 1.0).to_vec(), vec![0.5]);
        assert!(roots([1.0, 0.0, 1.0], 1.0).is_empty());
    }
}
