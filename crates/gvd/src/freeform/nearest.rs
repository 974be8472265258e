//! Distances from a point to the spans and corners: the foot-point equation
//! `⟨C(t) − q, C'(t)⟩ = 0` solved by certified Bernstein root isolation (`isolate`,
//! then bisection), the span's ends added, the nearest kept. Boxes of the control
//! polygons prune the spans that cannot be nearer than a given bound.

use super::bisector::SpanForms;
use super::pieces::{Feature, Pieces};
use crate::geom::bezier::RationalBezier;
use crate::geom::Point;
use crate::num::roots::{isolate, refine_by_newton};

/// The pieces with their foot-point forms, ready for distance queries.
pub struct Features<'a> {
    /// The spans and corners.
    pub pieces: &'a Pieces,
    /// Per span: its forms.
    pub forms: Vec<SpanForms>,
    /// The active corners (indices into `pieces.corners`).
    pub active: Vec<usize>,
}

impl<'a> Features<'a> {
    /// Prepares the queries over `pieces`.
    pub fn new(pieces: &'a Pieces) -> Self {
        Features {
            forms: pieces
                .spans
                .iter()
                .map(|s| SpanForms::new(&s.curve))
                .collect(),
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
        for (k, s) in self.pieces.spans.iter().enumerate() {
            if s.bbox.outside_distance(q) >= limit {
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
