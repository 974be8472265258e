//! A `bezier` or `bspline` site as a distance field of the subdivision engine: the
//! Euclidean distance to the curve, without approximating it by lines or arcs. Segments,
//! polylines, polygon boundaries and arcs are such curves too (degree-1 spans, and exact
//! rational quadratic spans): that is how they mix with the other fields.
//!
//! The curve's rational Bézier spans (B-splines cut by knot insertion, as the
//! free-form engine does, HREK07 §7) are split by de Casteljau's algorithm at `t = ½`
//! into a binary tree of sub-spans down to the scene's resolution; the spans' trees
//! hang under a balanced tree of groups. Each node knows (Farin02, ch. 13, weights
//! positive):
//! * its **box**: the control points' box, which holds the sub-span (convex hull);
//! * its **tangent cone**: the derivative of a rational Bézier is a positive
//!   combination of the control polygon's edges `Pᵢ₊₁ − Pᵢ`, so its direction lies in
//!   the hull of their unit vectors (when that hull keeps clear of 0);
//! * a **witness**, its first control point, a point of the curve to the rounding of the
//!   subdivision (`slack`);
//! * for a leaf, its **chord** `P₀Pₙ` and flatness, the largest distance of a control
//!   point from the chord: the sub-span lies within it of the chord.
//!
//! [`curve_tree`] turns these into the engine's bounds. A point of the sub-span is
//! nearest to `q` only at a foot, `(q − p) · C'(t) = 0`, or at an end of its span, from
//! which the span, followed inwards, gets no nearer to `q`: interval forms over the box
//! and the node that exclude both prove a node irrelevant. Point values are the
//! certified foot-point search of the free-form engine ([`span_distance`]).

use super::curve_tree::{
    direction, meet_normal, unit_bound, CurveField, CurveState, CurveTree, NONE,
};
use crate::error::Error;
use crate::freeform::bisector::SpanForms;
use crate::freeform::nearest::span_distance;
use crate::geom::arc::Arc;
use crate::geom::bezier::RationalBezier;
use crate::geom::{Aabb, Point};
use crate::num::interval::{round_down, round_up};
use crate::num::Interval;
use crate::scene::SiteKind;

/// The spans of a site drawn as curves: free-form curves (cut at their knots), the edges
/// of segments, polylines and polygon rings (zero-length edges dropped) and the quarter
/// turns of arcs; `None` for the other kinds. A polygon's distance is that to its
/// boundary, which outside it is the distance to the solid polygon.
pub(crate) fn curve_spans(kind: &SiteKind) -> Option<Vec<RationalBezier>> {
    let edges = |points: &mut dyn Iterator<Item = (Point, Point)>| -> Vec<RationalBezier> {
        points
            .filter(|(a, b)| a != b)
            .map(|(a, b)| RationalBezier::new(&[a, b], None))
            .collect()
    };
    match kind {
        SiteKind::Bezier { .. } | SiteKind::Bspline { .. } => {
            crate::freeform::pieces::site_spans(kind).map(|(spans, _)| spans)
        }
        SiteKind::Segment { from, to } => Some(edges(&mut std::iter::once((*from, *to)))),
        SiteKind::Polyline { points } => Some(edges(&mut points.windows(2).map(|w| (w[0], w[1])))),
        SiteKind::Polygon { rings } => {
            Some(edges(&mut rings.iter().flat_map(|ring| {
                (0..ring.len()).map(move |i| (ring[i], ring[(i + 1) % ring.len()]))
            })))
        }
        SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => Some(Arc::from_angles(*center, *radius, *start_angle, *end_angle).bezier_spans()),
        _ => None,
    }
}

/// Deepest subdivision of a span.
const MAX_DEPTH: u32 = 40;
/// Most nodes a curve's tree may hold: bounded memory for a curve far longer than the
/// resolution.
const MAX_NODES: usize = 1 << 21;

/// The distance field of a free-form curve.
#[derive(Clone, Debug)]
pub struct FreeformField {
    spans: Vec<RationalBezier>,
    /// Each span's control box, which holds it.
    span_boxes: Vec<Aabb>,
    forms: Vec<SpanForms>,
    nodes: Vec<Node>,
    kids: Vec<u32>,
    /// A bound of the rounding of the sub-spans' control points.
    slack: f64,
}

/// An end of a span: its point and the tangent direction there.
type SpanEnd = (Point, Point);

/// A sub-span (or a group of spans) of the tree.
#[derive(Clone, Debug)]
struct Node {
    /// Holds the curve under the node.
    bbox: Aabb,
    /// Children: `kids[first..first + count]`.
    first: u32,
    count: u32,
    /// The span (`NONE` for a group of spans).
    span: u32,
    /// A point of the curve under the node, within `slack`.
    witness: Point,
    /// An enclosure of a vector along the tangent at every point of a sub-span, and
    /// of the unit normal; `None` for groups and where the cone may hold 0.
    tangent: Option<[Interval; 2]>,
    unit_normal: Option<[Interval; 2]>,
    /// The span's start with its tangent leaving, and its end with the tangent
    /// arriving, where they are under the node.
    start: Option<SpanEnd>,
    end: Option<SpanEnd>,
    /// For a leaf: its chord and the largest distance of its control points from it.
    chord: Option<(Point, Point, f64)>,
}

impl FreeformField {
    /// The field of site `site`, the curve of `spans`, with leaves no longer than
    /// `resolution`; refuses a curve whose tree would hold more than [`MAX_NODES`].
    pub fn new(site: usize, spans: Vec<RationalBezier>, resolution: f64) -> Result<Self, Error> {
        let (mut magnitude, mut weights) = (0.0f64, (f64::INFINITY, 0.0f64));
        for h in spans.iter().flat_map(|s| s.homogeneous()) {
            magnitude = magnitude.max((h[0] / h[2]).abs()).max((h[1] / h[2]).abs());
            weights = (weights.0.min(h[2]), weights.1.max(h[2]));
        }
        let degree = spans.iter().map(|s| s.degree()).max().unwrap_or(0) as f64;
        // each level of de Casteljau at ½ rounds once per coordinate; a projection
        // X/W magnifies that by the weights' spread
        let slack = 8.0
            * (f64::from(MAX_DEPTH) + 2.0 * degree + 4.0)
            * f64::EPSILON
            * magnitude
            * (weights.1 / weights.0);
        let leaf_size = resolution.max(1e-12 * magnitude);
        let mut field = FreeformField {
            forms: spans.iter().map(SpanForms::new).collect(),
            span_boxes: spans.iter().map(RationalBezier::control_box).collect(),
            spans: Vec::new(),
            nodes: Vec::new(),
            kids: Vec::new(),
            slack,
        };
        let mut tops = Vec::new();
        for (k, span) in spans.iter().enumerate() {
            let (tin, tout) = span.end_tangents();
            let ends = (Some((span.eval(0.0), tin)), Some((span.eval(1.0), tout)));
            tops.push(field.sub_span(k as u32, span, ends, leaf_size, 0));
            if field.nodes.len() > MAX_NODES {
                return Err(Error::site(
                    site,
                    "control_points",
                    format!(
                        "the curve is too long beside the resolution {resolution:e} for the subdivision engine (more than {MAX_NODES} pieces); raise epsilon or use --engine freeform"
                    ),
                ));
            }
        }
        field.spans = spans;
        field.group(tops);
        Ok(field)
    }

    /// Adds the tree of `span`'s sub-span `c`, whose span ends `ends` (start, end) lie
    /// under it where given, and returns its node.
    fn sub_span(
        &mut self,
        span: u32,
        c: &RationalBezier,
        ends: (Option<SpanEnd>, Option<SpanEnd>),
        leaf_size: f64,
        depth: u32,
    ) -> u32 {
        let control = c.control_points();
        let grow = self.slack;
        let b = c.control_box();
        let bbox = Aabb::new(
            Point::new(b.min.x - grow, b.min.y - grow),
            Point::new(b.max.x + grow, b.max.y + grow),
        );
        let tangent = tangent_cone(&control);
        let unit_normal = tangent.and_then(|t| direction(-t[1], t[0]));
        let leaf =
            b.longest_side() <= leaf_size || depth >= MAX_DEPTH || self.nodes.len() > MAX_NODES;
        let (first, count, chord) = if leaf {
            let (a, z) = (control[0], control[control.len() - 1]);
            let flat = control
                .iter()
                .map(|&p| crate::geom::segment_distance(p, a, z))
                .fold(0.0, f64::max);
            (self.kids.len() as u32, 0, Some((a, z, flat)))
        } else {
            let (l, r) = c.split(0.5);
            let kids = [
                self.sub_span(span, &l, (ends.0, None), leaf_size, depth + 1),
                self.sub_span(span, &r, (None, ends.1), leaf_size, depth + 1),
            ];
            self.kids.extend_from_slice(&kids);
            (self.kids.len() as u32 - 2, 2, None)
        };
        self.nodes.push(Node {
            bbox,
            first,
            count,
            span,
            witness: control[0],
            tangent,
            unit_normal,
            start: ends.0,
            end: ends.1,
            chord,
        });
        self.nodes.len() as u32 - 1
    }

    /// Joins the nodes `level` into a balanced binary tree of groups; the root is the
    /// last node.
    fn group(&mut self, mut level: Vec<u32>) {
        while level.len() > 1 {
            let mut next = Vec::with_capacity(level.len().div_ceil(2));
            for pair in level.chunks(2) {
                if let [a, b] = *pair {
                    let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
                    let bbox = Aabb::new(
                        Point::new(
                            na.bbox.min.x.min(nb.bbox.min.x),
                            na.bbox.min.y.min(nb.bbox.min.y),
                        ),
                        Point::new(
                            na.bbox.max.x.max(nb.bbox.max.x),
                            na.bbox.max.y.max(nb.bbox.max.y),
                        ),
                    );
                    let first = self.kids.len() as u32;
                    self.kids.extend_from_slice(&[a, b]);
                    self.nodes.push(Node {
                        bbox,
                        first,
                        count: 2,
                        span: NONE,
                        witness: na.witness,
                        tangent: None,
                        unit_normal: None,
                        start: None,
                        end: None,
                        chord: None,
                    });
                    next.push(self.nodes.len() as u32 - 1);
                } else {
                    next.push(pair[0]);
                }
            }
            level = next;
        }
        // the root must be the last node: a single span's top already is
    }

    /// The curve's two ends: its first span's start and its last span's end.
    pub fn ends(&self) -> [Point; 2] {
        match (self.spans.first(), self.spans.last()) {
            (Some(a), Some(z)) => [a.eval(0.0), z.eval(1.0)],
            _ => [Point::new(f64::NAN, f64::NAN); 2],
        }
    }

    /// True when over `b` no point of the curve can be nearest but span ends within
    /// the rounding `slack` of `p` (the tests of [`CurveTree::holds_no_foot`] on the
    /// nodes `s` kept): then the distance over `b` is `|q − p|`, and any field with a
    /// point at `p` is at least as near.
    pub fn only_ends_at(&self, s: &CurveState, b: &Aabb, p: Point) -> bool {
        let near = |e: Point| e.dist(p) <= self.slack;
        s.nodes.iter().all(|&n| {
            let node = &self.nodes[n as usize];
            let Some(t) = node.tangent else {
                return false;
            };
            let (dx, dy) = (b.x() - node.bbox.x(), b.y() - node.bbox.y());
            let along = |(e, t): SpanEnd| (b.x() - e.x).scale(t.x) + (b.y() - e.y).scale(t.y);
            (dx * t[0] + dy * t[1]).excludes_zero()
                && node.start.is_none_or(|e| along(e).lo > 0.0 || near(e.0))
                && node.end.is_none_or(|e| along(e).hi < 0.0 || near(e.0))
        })
    }

    /// The nearest point of the curve to `q`, the unit tangent there, and which end of
    /// the curve it is (0: the start, 1: the end), if one.
    pub fn foot(&self, q: Point) -> Option<(Point, Point, Option<usize>)> {
        let (_, k, t) = self.nearest_span(q, 0..self.spans.len())?;
        let c = &self.spans[k];
        let end = if k == 0 && t == 0.0 {
            Some(0)
        } else if k + 1 == self.spans.len() && t == 1.0 {
            Some(1)
        } else {
            None
        };
        let mut tangent = c.derivative(t);
        if tangent.norm() == 0.0 {
            let (tin, tout) = c.end_tangents();
            tangent = if t < 0.5 { tin } else { tout };
        }
        Some((c.eval(t), tangent * (1.0 / tangent.norm()), end))
    }

    /// The distance from `q` to the curve and the nearest point, over the spans of
    /// `nodes` (every span when a group is among them).
    fn nearest(&self, q: Point, nodes: &[u32]) -> (f64, Point) {
        let mut spans: Vec<u32> = nodes.iter().map(|&n| self.nodes[n as usize].span).collect();
        if spans.contains(&NONE) || spans.is_empty() {
            spans = (0..self.spans.len() as u32).collect();
        }
        spans.sort_unstable();
        spans.dedup();
        self.nearest_span(q, spans.into_iter().map(|k| k as usize))
            .map_or((f64::INFINITY, q), |(d, k, t)| (d, self.spans[k].eval(t)))
    }

    /// Among `spans`, the distance from `q`, the span and the parameter of the nearest
    /// point (the first span of least distance); a span whose box is no nearer than the
    /// best so far is skipped.
    fn nearest_span(
        &self,
        q: Point,
        spans: impl Iterator<Item = usize>,
    ) -> Option<(f64, usize, f64)> {
        let mut best: Option<(f64, usize, f64)> = None;
        for k in spans {
            if best.is_some_and(|(d, _, _)| self.span_boxes[k].outside_distance(q) >= d) {
                continue;
            }
            let (d, t) = span_distance(&self.spans[k], &self.forms[k], q);
            if best.is_none_or(|(b, _, _)| d < b) {
                best = Some((d, k, t));
            }
        }
        best
    }
}

/// The hull of the unit vectors along the control polygon's edges (zero-length edges
/// skipped), widened by a few ulps; `None` where it may hold 0 (the cone is half a turn
/// or more wide).
fn tangent_cone(control: &[Point]) -> Option<[Interval; 2]> {
    let mut hull: Option<[Interval; 2]> = None;
    for w in control.windows(2) {
        let d = w[1] - w[0];
        let len = d.norm();
        if len == 0.0 {
            continue;
        }
        let u = [d.x / len, d.y / len];
        let wide = |v: f64| Interval::new(v - 4.0 * f64::EPSILON, v + 4.0 * f64::EPSILON);
        let u = [wide(u[0]), wide(u[1])];
        hull = Some(match hull {
            None => u,
            Some(h) => [h[0].hull(u[0]), h[1].hull(u[1])],
        });
    }
    hull.filter(|h| h[0].excludes_zero() || h[1].excludes_zero())
}

impl CurveTree for FreeformField {
    fn root(&self) -> Option<u32> {
        self.nodes.len().checked_sub(1).map(|r| r as u32)
    }

    fn bbox(&self, n: u32) -> &Aabb {
        &self.nodes[n as usize].bbox
    }

    fn children(&self, n: u32) -> &[u32] {
        let node = &self.nodes[n as usize];
        &self.kids[node.first as usize..(node.first + node.count) as usize]
    }

    /// The largest distance from `b` to the node's witness, plus its rounding.
    fn witness_upper(&self, b: &Aabb, n: u32) -> f64 {
        let w = self.nodes[n as usize].witness;
        let far = b
            .corners()
            .iter()
            .map(|c| c.dist2(w))
            .fold(0.0, f64::max)
            .sqrt();
        round_up(far * (1.0 + 4.0 * f64::EPSILON) + self.slack)
    }

    /// A sub-span holds a nearest point of some `q ∈ b` only at a foot,
    /// `(q − p) · C'(t) = 0`, or at one of its span's ends from which the span gets no
    /// nearer: `(q − P₀) · T₀ ≤ 0` at the start, `(q − Pₙ) · Tₙ ≥ 0` at the end.
    fn holds_no_foot(&self, b: &Aabb, n: u32) -> bool {
        let node = &self.nodes[n as usize];
        let Some(t) = node.tangent else {
            return false;
        };
        let (dx, dy) = (b.x() - node.bbox.x(), b.y() - node.bbox.y());
        if !(dx * t[0] + dy * t[1]).excludes_zero() {
            return false;
        }
        let along = |(p, t): SpanEnd| (b.x() - p.x).scale(t.x) + (b.y() - p.y).scale(t.y);
        node.start.is_none_or(|e| along(e).lo > 0.0) && node.end.is_none_or(|e| along(e).hi < 0.0)
    }

    /// The distance from `b` to the leaf's chord less its flatness and rounding.
    fn leaf_gap(&self, b: &Aabb, n: u32) -> f64 {
        let Some((a, z, flat)) = self.nodes[n as usize].chord else {
            return 0.0;
        };
        let d = b.segment_distance(a, z);
        let scale = [b.min.x, b.min.y, b.max.x, b.max.y, a.x, a.y]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        round_down(
            d * (1.0 - 8.0 * f64::EPSILON)
                - 16.0 * f64::EPSILON * scale
                - flat * (1.0 + 8.0 * f64::EPSILON)
                - self.slack,
        )
        .max(0.0)
    }

    /// The directions from the node to `b`; where the nearest point must be a foot (no
    /// span end under the node), met with `±` the unit normal on `b`'s side.
    fn gradient_from(&self, b: &Aabb, n: u32) -> [Interval; 2] {
        let node = &self.nodes[n as usize];
        let between = unit_bound(b, &node.bbox);
        match (node.unit_normal, node.start.or(node.end)) {
            (Some(unit), None) => {
                let side = (b.x() - node.bbox.x()) * unit[0] + (b.y() - node.bbox.y()) * unit[1];
                meet_normal(between, unit, side)
            }
            _ => between,
        }
    }
}

impl CurveField for FreeformField {
    /// Over the spans of the nodes `from` (every span for the whole curve).
    fn nearest_point(&self, q: Point, from: Option<&[u32]>) -> (f64, Point) {
        self.nearest(q, from.unwrap_or(&[]))
    }
}
