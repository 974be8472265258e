//! Rational Bézier curves `P(t) = Σ wᵢ Pᵢ Bᵢⁿ(t) / Σ wᵢ Bᵢⁿ(t)`, `t ∈ [0, 1]`, held in
//! homogeneous coordinates `(w x, w y, w)` so that every operation is polynomial
//! (Farin02, ch. 13): evaluation and subdivision by de Casteljau's algorithm, and the
//! derivative by the quotient rule on the homogeneous hodograph.

use super::Point;

/// A rational Bézier curve of degree `n = control points − 1`; weights all 1 make it
/// polynomial.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBezier {
    /// Homogeneous control points `(wᵢ xᵢ, wᵢ yᵢ, wᵢ)`.
    homogeneous: Vec<[f64; 3]>,
}

impl RationalBezier {
    /// The curve of `control` points with optional `weights` (one per point, positive).
    /// An empty control polygon gives an empty curve, which evaluates to NaN.
    pub fn new(control: &[Point], weights: Option<&[f64]>) -> RationalBezier {
        let homogeneous = control
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let w = weights.and_then(|w| w.get(i)).copied().unwrap_or(1.0);
                [p.x * w, p.y * w, w]
            })
            .collect();
        RationalBezier { homogeneous }
    }

    /// The degree `n`.
    pub fn degree(&self) -> usize {
        self.homogeneous.len().saturating_sub(1)
    }

    /// The point at `t`, by de Casteljau's algorithm in homogeneous coordinates.
    pub fn eval(&self, t: f64) -> Point {
        let h = de_casteljau(&self.homogeneous, t, |_, _| {});
        project(h)
    }

    /// The first derivative `P'(t) = (W X' − W' X) / W²` (per coordinate), with the
    /// homogeneous derivative `n Σ (Hᵢ₊₁ − Hᵢ) Bᵢⁿ⁻¹(t)`.
    pub fn derivative(&self, t: f64) -> Point {
        let n = self.degree();
        if n == 0 {
            return Point::new(0.0, 0.0);
        }
        let h = de_casteljau(&self.homogeneous, t, |_, _| {});
        let diff: Vec<[f64; 3]> = self
            .homogeneous
            .windows(2)
            .map(|p| std::array::from_fn(|k| n as f64 * (p[1][k] - p[0][k])))
            .collect();
        let d = de_casteljau(&diff, t, |_, _| {});
        let w2 = h[2] * h[2];
        Point::new(
            (h[2] * d[0] - d[2] * h[0]) / w2,
            (h[2] * d[1] - d[2] * h[1]) / w2,
        )
    }

    /// The two halves `[0, t]` and `[t, 1]`, each reparametrised to `[0, 1]`.
    pub fn split(&self, t: f64) -> (RationalBezier, RationalBezier) {
        let n = self.homogeneous.len();
        let mut left = Vec::with_capacity(n);
        let mut right = Vec::with_capacity(n);
        let last = de_casteljau(&self.homogeneous, t, |row, level| {
            left.push(row[0]);
            right.push(row[level]);
        });
        if n > 0 {
            left.push(last);
            right.push(last);
        }
        right.reverse();
        (
            RationalBezier { homogeneous: left },
            RationalBezier { homogeneous: right },
        )
    }

    /// `n + 1` points at `t = 0, 1/n, …, 1`.
    pub fn sample(&self, n: usize) -> Vec<Point> {
        let n = n.max(1);
        (0..=n).map(|k| self.eval(k as f64 / n as f64)).collect()
    }
}

fn project(h: [f64; 3]) -> Point {
    Point::new(h[0] / h[2], h[1] / h[2])
}

/// Runs de Casteljau's triangle on `points` at `t` and returns its apex. Before each
/// level is reduced, `row(level_points, last_index)` sees it (for subdivision).
fn de_casteljau(points: &[[f64; 3]], t: f64, mut row: impl FnMut(&[[f64; 3]], usize)) -> [f64; 3] {
    let mut h = points.to_vec();
    if h.is_empty() {
        return [f64::NAN; 3];
    }
    for r in (1..h.len()).rev() {
        row(&h, r);
        for i in 0..r {
            let (a, b) = (h[i], h[i + 1]);
            h[i] = std::array::from_fn(|k| a[k] + (b[k] - a[k]) * t);
        }
    }
    h[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quarter_circle() -> RationalBezier {
        // x² + y² = 1 from (1, 0) to (0, 1): weights 1, √2/2, 1
        let c = [
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        ];
        RationalBezier::new(&c, Some(&[1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0]))
    }

    #[test]
    fn rational_quadratic_is_exactly_a_circle() {
        let c = quarter_circle();
        for k in 0..=16 {
            let p = c.eval(k as f64 / 16.0);
            assert!((p.norm() - 1.0).abs() < 1e-15, "{p:?}");
        }
        assert_eq!(c.eval(0.0), Point::new(1.0, 0.0));
        assert_eq!(c.eval(1.0), Point::new(0.0, 1.0));
    }

    #[test]
    fn derivative_matches_central_differences_and_is_tangent() {
        let c = quarter_circle();
        for t in [0.1, 0.37, 0.5, 0.9] {
            let h = 1e-6;
            let fd = (c.eval(t + h) - c.eval(t - h)) * (0.5 / h);
            let d = c.derivative(t);
            assert!(d.dist(fd) < 1e-8, "{d:?} {fd:?}");
            assert!(d.dot(c.eval(t)).abs() < 1e-12); // tangent ⟂ radius
        }
    }

    #[test]
    fn split_halves_trace_the_same_curve() {
        let c = RationalBezier::new(
            &[
                Point::new(0.0, 0.0),
                Point::new(1.0, 2.0),
                Point::new(3.0, -1.0),
                Point::new(4.0, 1.0),
            ],
            Some(&[1.0, 2.0, 0.5, 1.0]),
        );
        let (l, r) = c.split(0.3);
        for k in 0..=10 {
            let u = k as f64 / 10.0;
            assert!(l.eval(u).dist(c.eval(0.3 * u)) < 1e-13);
            assert!(r.eval(u).dist(c.eval(0.3 + 0.7 * u)) < 1e-13);
        }
    }
}
