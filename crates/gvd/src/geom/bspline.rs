//! Rational B-spline curves `C(t) = Σ wᵢ Pᵢ Nᵢ,ₚ(t) / Σ wᵢ Nᵢ,ₚ(t)` over
//! `t ∈ [t_p, t_n]` (`n` control points, degree `p`), held in homogeneous coordinates:
//! evaluation by de Boor's algorithm, the derivative by the quotient rule on the
//! homogeneous derivative curve, whose control points are
//! `p (Hᵢ₊₁ − Hᵢ) / (tᵢ₊ₚ₊₁ − tᵢ₊₁)` (Farin02, ch. 8 and 13). A Bézier curve is the
//! B-spline with knots `0 … 0 1 … 1`.

use super::Point;

/// A rational B-spline curve.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBspline {
    degree: usize,
    knots: Vec<f64>,
    homogeneous: Vec<[f64; 3]>,
    /// the homogeneous derivative curve (degree − 1, inner knots), `None` at degree 0
    derivative: Option<Box<RationalBspline>>,
}

impl RationalBspline {
    /// The curve of `degree` over `knots` (control points + degree + 1, non-decreasing)
    /// with optional positive `weights`, as the scene format validates them.
    pub fn new(
        degree: usize,
        control: &[Point],
        knots: &[f64],
        weights: Option<&[f64]>,
    ) -> RationalBspline {
        let homogeneous = control
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let w = weights.and_then(|w| w.get(i)).copied().unwrap_or(1.0);
                [p.x * w, p.y * w, w]
            })
            .collect();
        Self::from_homogeneous(degree, knots.to_vec(), homogeneous)
    }

    /// A (rational) Bézier curve of `control` points over `[0, 1]`.
    pub fn bezier(control: &[Point], weights: Option<&[f64]>) -> RationalBspline {
        let degree = control.len().saturating_sub(1);
        let knots: Vec<f64> = (0..2 * (degree + 1))
            .map(|k| if k <= degree { 0.0 } else { 1.0 })
            .collect();
        Self::new(degree, control, &knots, weights)
    }

    fn from_homogeneous(degree: usize, knots: Vec<f64>, h: Vec<[f64; 3]>) -> RationalBspline {
        let derivative = (degree > 0 && h.len() > 1).then(|| {
            let p = degree as f64;
            let d: Vec<[f64; 3]> = (0..h.len() - 1)
                .map(|i| {
                    let span = knots[i + degree + 1] - knots[i + 1];
                    let k = if span > 0.0 { p / span } else { 0.0 };
                    [0, 1, 2].map(|c| k * (h[i + 1][c] - h[i][c]))
                })
                .collect();
            Box::new(Self::from_homogeneous(
                degree - 1,
                knots[1..knots.len() - 1].to_vec(),
                d,
            ))
        });
        RationalBspline {
            degree,
            knots,
            homogeneous: h,
            derivative,
        }
    }

    /// The parameter range `[t_p, t_n]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.homogeneous.len()])
    }

    /// The homogeneous point `(w x, w y, w)` at `t` (clamped to the domain).
    fn homogeneous_at(&self, t: f64) -> [f64; 3] {
        let (lo, hi) = self.domain();
        let t = t.clamp(lo, hi);
        let p = self.degree;
        let n = self.homogeneous.len();
        // the span k with t_k ≤ t < t_{k+1} (the last non-empty span at the end)
        let mut k = p;
        while k + 1 < n && self.knots[k + 1] <= t {
            k += 1;
        }
        // de Boor's triangle in place, on the stack up to degree 15
        let mut stack = [[0.0; 3]; 16];
        let mut heap = Vec::new();
        let d: &mut [[f64; 3]] = if p < stack.len() {
            &mut stack[..=p]
        } else {
            heap.resize(p + 1, [0.0; 3]);
            &mut heap
        };
        d.copy_from_slice(&self.homogeneous[k - p..=k]);
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = k - p + j;
                let span = self.knots[i + p + 1 - r] - self.knots[i];
                let a = if span > 0.0 {
                    (t - self.knots[i]) / span
                } else {
                    0.0
                };
                d[j] = [0, 1, 2].map(|c| (1.0 - a) * d[j - 1][c] + a * d[j][c]);
            }
        }
        d[p]
    }

    /// `per_span` points along each knot span of the domain (each span's start), then
    /// the curve's end: a polyline through the curve, for pictures.
    pub fn sample(&self, per_span: usize) -> Vec<Point> {
        let (lo, hi) = self.domain();
        let mut breaks: Vec<f64> = self
            .knots
            .iter()
            .copied()
            .filter(|&k| k > lo && k < hi)
            .collect();
        breaks.dedup();
        let per_span = per_span.max(1);
        let mut out = Vec::with_capacity((breaks.len() + 1) * per_span + 1);
        let mut start = lo;
        for end in breaks.into_iter().chain([hi]) {
            out.extend(
                (0..per_span)
                    .map(|k| self.eval(start + (end - start) * k as f64 / per_span as f64)),
            );
            start = end;
        }
        out.push(self.eval(hi));
        out
    }

    /// The points at both ends of the domain.
    pub fn ends(&self) -> (Point, Point) {
        let (lo, hi) = self.domain();
        (self.eval(lo), self.eval(hi))
    }

    /// The point at `t`.
    pub fn eval(&self, t: f64) -> Point {
        let h = self.homogeneous_at(t);
        Point::new(h[0] / h[2], h[1] / h[2])
    }

    /// The derivative `C'(t) = (H'ₓᵧ − C H'_w) / H_w`.
    pub fn derivative(&self, t: f64) -> Point {
        let Some(d) = &self.derivative else {
            return Point::default();
        };
        let h = self.homogeneous_at(t);
        let dh = d.homogeneous_at(t);
        let c = Point::new(h[0] / h[2], h[1] / h[2]);
        (Point::new(dh[0], dh[1]) - c * dh[2]) * (1.0 / h[2])
    }

    /// Parameters of the tangent discontinuities: interior knots of multiplicity at
    /// least the degree where the tangent turns by more than `1e-6` rad.
    pub fn tangent_breaks(&self) -> Vec<f64> {
        let (lo, hi) = self.domain();
        let d = 1e-9 * (hi - lo);
        let mut out = Vec::new();
        let inner: Vec<f64> = self
            .knots
            .iter()
            .copied()
            .filter(|&t| t > lo && t < hi)
            .collect();
        let mut k = 0;
        while k < inner.len() {
            let t = inner[k];
            let m = inner[k..].iter().take_while(|&&u| u == t).count();
            if m >= self.degree && turn(self.derivative(t - d), self.derivative(t + d)) > 1e-6 {
                out.push(t);
            }
            k += m;
        }
        out
    }

    /// Whether the tangent turns where the curve closes (end tangent against start
    /// tangent).
    pub fn seam_turns(&self) -> bool {
        let (lo, hi) = self.domain();
        let d = 1e-9 * (hi - lo);
        turn(self.derivative(hi - d), self.derivative(lo + d)) > 1e-6
    }
}

/// Whether a curve's end points `a` and `b` meet, and so it closes up: within `1e-9` of
/// `1 + |a|`. The lengths are `hypot`s: their squares overflow near 1e154, and an
/// infinite `|a|` would make any two ends meet.
pub fn ends_meet(a: Point, b: Point) -> bool {
    (a.x - b.x).hypot(a.y - b.y) <= 1e-9 * (1.0 + a.x.hypot(a.y))
}

/// The angle between two vectors (π when one vanishes).
fn turn(u: Point, v: Point) -> f64 {
    let (nu, nv) = (u.norm(), v.norm());
    if nu == 0.0 || nv == 0.0 {
        return std::f64::consts::PI;
    }
    (u.dot(v) / (nu * nv)).clamp(-1.0, 1.0).acos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::bezier::RationalBezier;

    #[test]
    fn bezier_as_bspline_matches_de_casteljau() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 2.0),
            Point::new(3.0, -1.0),
            Point::new(4.0, 1.0),
        ];
        let w = [1.0, 0.5, 2.0, 1.0];
        let a = RationalBspline::bezier(&pts, Some(&w));
        let b = RationalBezier::new(&pts, Some(&w));
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            assert!(a.eval(t).dist(b.eval(t)) < 1e-12);
            assert!(a.derivative(t).dist(b.derivative(t)) < 1e-10);
        }
    }

    #[test]
    fn derivative_matches_differences_and_breaks_are_found() {
        // a quadratic B-spline with a double interior knot: C0 at t = 0.5, a corner
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(2.0, 0.0),
            Point::new(3.0, 1.0),
            Point::new(4.0, 0.0),
        ];
        let knots = [0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0];
        let c = RationalBspline::new(2, &pts, &knots, None);
        assert_eq!(c.domain(), (0.0, 1.0));
        assert!(
            c.eval(0.5).dist(pts[2]) < 1e-15,
            "interpolates the double knot"
        );
        let h = 1e-6;
        for t in [0.1, 0.3, 0.7, 0.9] {
            let fd = (c.eval(t + h) - c.eval(t - h)) * (0.5 / h);
            assert!(c.derivative(t).dist(fd) < 1e-6, "at {t}");
        }
        assert_eq!(c.tangent_breaks(), vec![0.5]);
        // the same control points with a single interior knot: C1, no break
        let smooth = RationalBspline::new(
            3,
            &pts,
            &[0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            None,
        );
        assert!(smooth.tangent_breaks().is_empty());
    }
}
