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

    /// The curve of homogeneous control points `(wᵢ xᵢ, wᵢ yᵢ, wᵢ)` (weights positive).
    pub fn from_homogeneous(homogeneous: Vec<[f64; 3]>) -> RationalBezier {
        RationalBezier { homogeneous }
    }

    /// The homogeneous control points `(wᵢ xᵢ, wᵢ yᵢ, wᵢ)`.
    pub fn homogeneous(&self) -> &[[f64; 3]] {
        &self.homogeneous
    }

    /// The control points `Pᵢ` (projected).
    pub fn control_points(&self) -> Vec<Point> {
        self.homogeneous.iter().map(|&h| project(h)).collect()
    }

    /// True when every weight is the same (the curve is polynomial).
    pub fn is_polynomial(&self) -> bool {
        let w0 = self.homogeneous.first().map_or(1.0, |h| h[2]);
        self.homogeneous.iter().all(|h| h[2] == w0)
    }

    /// The bounding box of the control points, which holds the curve (convex hull
    /// property, weights positive).
    pub fn control_box(&self) -> crate::geom::Aabb {
        let pts = self.control_points();
        let mut b = crate::geom::Aabb::from_array([
            f64::INFINITY,
            f64::INFINITY,
            -f64::INFINITY,
            -f64::INFINITY,
        ]);
        for p in pts {
            b.min.x = b.min.x.min(p.x);
            b.min.y = b.min.y.min(p.y);
            b.max.x = b.max.x.max(p.x);
            b.max.y = b.max.y.max(p.y);
        }
        b
    }

    /// The tangent directions at `t = 0` and `t = 1` from the control polygon: towards
    /// the first control point distinct from the start, and from the last distinct from
    /// the end (exact directions even where the derivative vanishes; zero if the curve is
    /// a point).
    pub fn end_tangents(&self) -> (Point, Point) {
        let pts = self.control_points();
        let (first, last) = (pts[0], pts[pts.len() - 1]);
        let start = pts
            .iter()
            .find(|&&p| p != first)
            .map_or(Point::new(0.0, 0.0), |&p| p - first);
        let end = pts
            .iter()
            .rev()
            .find(|&&p| p != last)
            .map_or(Point::new(0.0, 0.0), |&p| last - p);
        (start, end)
    }

    /// The point, first and second derivatives at `t`: with `H = (X, Y, W)`,
    /// `C = H/W`, `C' = (H' − W' C)/W`, `C'' = (H'' − 2 W' C' − W'' C)/W` (per coordinate).
    pub fn derivatives(&self, t: f64) -> [Point; 3] {
        let n = self.degree();
        let h0 = de_casteljau(&self.homogeneous, t, |_, _| {});
        let diff = |pts: &[[f64; 3]], k: usize| -> Vec<[f64; 3]> {
            pts.windows(2)
                .map(|p| std::array::from_fn(|c| k as f64 * (p[1][c] - p[0][c])))
                .collect()
        };
        let d1 = if n >= 1 {
            diff(&self.homogeneous, n)
        } else {
            Vec::new()
        };
        let d2 = if n >= 2 { diff(&d1, n - 1) } else { Vec::new() };
        let at = |v: &[[f64; 3]]| {
            if v.is_empty() {
                [0.0; 3]
            } else {
                de_casteljau(v, t, |_, _| {})
            }
        };
        let (h1, h2) = (at(&d1), at(&d2));
        let w = h0[2];
        let c = Point::new(h0[0] / w, h0[1] / w);
        let c1 = Point::new((h1[0] - h1[2] * c.x) / w, (h1[1] - h1[2] * c.y) / w);
        let c2 = Point::new(
            (h2[0] - 2.0 * h1[2] * c1.x - h2[2] * c.x) / w,
            (h2[1] - 2.0 * h1[2] * c1.y - h2[2] * c.y) / w,
        );
        [c, c1, c2]
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

    /// The same curve reparametrised so that its end weights are 1 (the standard form,
    /// Farin02 §13.3): `wᵢ ↦ wᵢ cⁱ / w₀` with `cⁿ = w₀ / wₙ`, the Möbius map
    /// `t ↦ c t / (1 − t + c t)` of the parameter.
    pub fn standard_form(&self) -> RationalBezier {
        let Some(&[.., w0]) = self.homogeneous.first() else {
            return self.clone();
        };
        let n = self.homogeneous.len() - 1;
        let wn = self.homogeneous[n][2];
        let c = (w0 / wn).powf(1.0 / n.max(1) as f64);
        let homogeneous = self
            .homogeneous
            .iter()
            .zip(std::iter::successors(Some(1.0 / w0), |s| Some(s * c)))
            .map(|(h, s)| h.map(|v| v * s))
            .collect();
        RationalBezier { homogeneous }
    }

    /// The largest weight over the smallest (1 for a polynomial curve).
    pub fn weight_ratio(&self) -> f64 {
        let weights = self.homogeneous.iter().map(|h| h[2]);
        let (lo, hi) = weights.fold((f64::INFINITY, 0.0f64), |(lo, hi), w| {
            (lo.min(w), hi.max(w))
        });
        hi / lo
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

    #[test]
    fn the_standard_form_is_the_same_curve_under_its_moebius_map() {
        let c = [(0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 1.0)].map(|(x, y)| Point::new(x, y));
        let curve = RationalBezier::new(&c, Some(&[2.0, 50.0, 0.3, 0.5]));
        let standard = curve.standard_form();
        let weights: Vec<f64> = standard.homogeneous().iter().map(|h| h[2]).collect();
        assert!((weights[0] - 1.0).abs() < 1e-15 && (weights[3] - 1.0).abs() < 1e-14);
        let scale = (2.0f64 / 0.5).cbrt();
        for k in 0..=10 {
            let s = k as f64 / 10.0;
            let t = scale * s / (1.0 - s + scale * s);
            assert!(standard.eval(s).dist(curve.eval(t)) < 1e-13, "{s}");
        }
    }

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
    fn second_derivative_matches_differences_and_circle_curvature() {
        let c = quarter_circle();
        for t in [0.2, 0.5, 0.8] {
            let [p, d1, d2] = c.derivatives(t);
            assert!(p.dist(c.eval(t)) < 1e-15);
            assert!(d1.dist(c.derivative(t)) < 1e-12);
            let h = 1e-5;
            let fd = (c.derivative(t + h) - c.derivative(t - h)) * (0.5 / h);
            assert!(d2.dist(fd) < 1e-6, "{d2:?} {fd:?}");
            // unit circle: curvature (x'y'' − y'x'')/|C'|³ = 1
            let k = d1.cross(d2) / d1.norm().powi(3);
            assert!((k - 1.0).abs() < 1e-12, "{k}");
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
