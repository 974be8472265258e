//! Distances from a point to the spans and corners: the foot-point equation
//! `⟨C(t) − q, C'(t)⟩ = 0` solved by certified Bernstein root isolation (`isolate`,
//! then bisection), the span's ends added, the nearest kept. Boxes of the control
//! polygons prune the spans that cannot be nearer than a given bound.

use super::bisector::SpanForms;
use super::pieces::{Feature, Pieces};
use crate::geom::bezier::RationalBezier;
use crate::geom::Point;
use crate::num::bernstein::Bernstein1;
use crate::num::roots::{isolate, refine_by_newton};

/// The pieces with their foot-point forms, ready for distance queries.
pub struct Features<'a> {
    /// The spans and corners.
    pub pieces: &'a Pieces,
    /// Per span: its forms.
    pub forms: Vec<SpanForms>,
    /// Per polynomial span: the forms of its squared distance (`None` for rational ones).
    squared: Vec<Option<SquaredDistance>>,
    /// The active corners (indices into `pieces.corners`).
    pub active: Vec<usize>,
}

/// A polynomial span's squared distance to `q`, `|C|² − 2⟨q, C⟩ + |q|²`, as Bernstein
/// forms of degree `2n`: `|C|² = X² + Y²` and `X`, `Y` raised to that degree.
struct SquaredDistance {
    norm: Bernstein1,
    x: Bernstein1,
    y: Bernstein1,
}

impl SquaredDistance {
    fn new(forms: &SpanForms) -> Self {
        let norm = forms.x.mul(&forms.x).add(&forms.y.mul(&forms.y));
        let to = norm.degree();
        SquaredDistance {
            x: forms.x.elevate(to),
            y: forms.y.elevate(to),
            norm,
        }
    }

    /// A lower bound of the squared distance from `q` to the span: its smallest
    /// Bernstein coefficient (convex hull property) less every coefficient's error, and
    /// less `32 ε` of the terms' magnitude, which covers the rounding of the combination
    /// and that of a distance evaluated on the span (de Casteljau of degree `n`, a few
    /// ulps of the coordinates, so that a span skipped here is never one that
    /// [`span_distance`] finds nearer).
    fn lower_bound(&self, q: Point) -> f64 {
        let q2 = q.dot(q);
        let (mut least, mut magnitude) = (f64::INFINITY, q2);
        for ((&n, &x), &y) in self.norm.coef.iter().zip(&self.x.coef).zip(&self.y.coef) {
            least = least.min(n - 2.0 * (q.x * x + q.y * y) + q2);
            magnitude = magnitude.max(n.abs() + 2.0 * (q.x * x).abs() + 2.0 * (q.y * y).abs());
        }
        let err = self.norm.err + 2.0 * (q.x.abs() * self.x.err + q.y.abs() * self.y.err);
        least - err - 32.0 * f64::EPSILON * (magnitude + q2)
    }
}

impl<'a> Features<'a> {
    /// Prepares the queries over `pieces`.
    pub fn new(pieces: &'a Pieces) -> Self {
        let forms: Vec<SpanForms> = pieces
            .spans
            .iter()
            .map(|s| SpanForms::new(&s.curve))
            .collect();
        Features {
            squared: pieces
                .spans
                .iter()
                .zip(&forms)
                .map(|(s, f)| s.curve.is_polynomial().then(|| SquaredDistance::new(f)))
                .collect(),
            forms,
            active: (0..pieces.corners.len())
                .filter(|&k| pieces.corners[k].active)
                .collect(),
            pieces,
        }
    }

    /// The distance from `q` to span `k` and the parameter of its nearest point.
    pub fn span_distance(&self, k: usize, q: Point) -> (f64, f64) {
        span_distance(&self.pieces.spans[k].curve, &self.forms[k], q)
    }

    /// True when span `k` is certainly no nearer to `q` than `limit`: its box is not, or
    /// (polynomial spans) its squared distance's lower bound is above `limit²` by a
    /// margin over the rounding of its distance, so that [`Self::span_distance`] would
    /// not find it nearer.
    pub fn farther(&self, k: usize, q: Point, limit: f64) -> bool {
        self.pieces.spans[k].bbox.outside_distance(q) >= limit
            || self.squared[k]
                .as_ref()
                .is_some_and(|sq| sq.lower_bound(q) >= limit * limit * (1.0 + 1e-12))
    }

    /// The nearest feature to `q` among those closer than `bound` (spans and active
    /// corners), or `None` when nothing is closer than `bound`.
    pub fn nearest_below(&self, q: Point, bound: f64) -> Option<(Feature, f64)> {
        let mut best: Option<(Feature, f64)> = None;
        let mut limit = bound;
        for &k in &self.active {
            let d = self.pieces.corners[k].at.dist(q);
            if d < limit {
                limit = d;
                best = Some((Feature::Corner(k), d));
            }
        }
        for k in 0..self.pieces.spans.len() {
            if self.farther(k, q, limit) {
                continue;
            }
            let (d, _) = self.span_distance(k, q);
            if d < limit {
                limit = d;
                best = Some((Feature::Span(k), d));
            }
        }
        best
    }

    /// The nearest feature to `q` (spans and active corners) and its distance.
    pub fn nearest(&self, q: Point) -> Option<(Feature, f64)> {
        self.nearest_below(q, f64::INFINITY)
    }
}

/// The distance from `q` to the span `c` (with its `forms`) and the parameter of its
/// nearest point: the ends and the certified roots of the foot-point polynomial.
pub fn span_distance(c: &RationalBezier, forms: &SpanForms, q: Point) -> (f64, f64) {
    let g = forms.foot(q);
    let mut best = (c.eval(0.0).dist(q), 0.0);
    let end = c.eval(1.0).dist(q);
    if end < best.0 {
        best = (end, 1.0);
    }
    for root in isolate(&g, 1e-13) {
        let t = if root.certified {
            refine_by_newton(&g, root.lo, root.hi)
        } else {
            0.5 * (root.lo + root.hi)
        };
        let d = c.eval(t).dist(q);
        if d < best.0 {
            best = (d, t);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn squared_distance_bound_is_below_the_distance_and_useful_away_from_the_span() {
        let c = RationalBezier::new(
            &[
                Point::new(0.0, 0.0),
                Point::new(1.0, 2.0),
                Point::new(2.0, -1.0),
                Point::new(3.0, 0.5),
            ],
            None,
        );
        let sq = SquaredDistance::new(&SpanForms::new(&c));
        for i in 0..40 {
            for j in 0..40 {
                let q = Point::new(-2.0 + 0.2 * i as f64, -3.0 + 0.2 * j as f64);
                let (d, _) = span_distance(&c, &SpanForms::new(&c), q);
                let sampled = (0..=2000)
                    .map(|k| c.eval(k as f64 / 2000.0).dist(q))
                    .fold(f64::INFINITY, f64::min);
                let bound = sq.lower_bound(q);
                assert!(bound <= d * d && bound <= sampled * sampled, "{q:?}");
                // far from the control polygon's hull the bound is close
                if q.y < -2.5 {
                    assert!(bound > 0.5 * d * d, "{q:?}: {bound} vs {}", d * d);
                }
            }
        }
    }
}
