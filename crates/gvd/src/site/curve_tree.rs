//! The distance to a curve held in a binary tree of boxes, as the subdivision engine
//! needs it: the enclosure of an implicit curve ([`super::algebraic`]) and the
//! sub-spans of a parametric one ([`super::freeform`]) share it.
//!
//! * **Box bounds.** Over a box `B` the distance is at least the least gap from `B` to
//!   a node that may hold a nearest point, and at most the least over the nodes' certified
//!   points `w` of the largest distance from `B` to `w`. The per-box state is the list of
//!   nodes that may hold a nearest point for some point of `B`; children inherit it,
//!   opening nodes larger than half the box (a dual-tree descent), so the tree is
//!   searched deeply only where the diagram looks at it.
//! * **Gradient bound.** Where the distance is differentiable its gradient is the unit
//!   vector from the nearest point to `q`; it lies in the hull of what the kept nodes
//!   allow (and so does the generalized gradient on the curve's ridges).
//! * **Pair bound.** The difference of two such fields, narrowed by the mean value form.

use super::{DistanceField, PairBound};
use crate::geom::{Aabb, Axis, Point};
use crate::num::interval::round_down;
use crate::num::Interval;

/// No node.
pub(super) const NONE: u32 = u32::MAX;

/// A binary tree of boxes over a curve, each node holding every point of the curve
/// under it.
pub(super) trait CurveTree {
    /// The node at the top of the tree.
    fn root(&self) -> Option<u32>;
    /// A box holding every point of the curve under node `n`.
    fn bbox(&self, n: u32) -> &Aabb;
    /// The children of node `n` (at most two; none for a leaf).
    fn children(&self, n: u32) -> &[u32];
    /// An upper bound of the distance from every point of `b` to the curve under `n`
    /// (∞ when `n` has no certified point).
    fn witness_upper(&self, b: &Aabb, n: u32) -> f64;
    /// True when no point of the curve under `n` is nearest to any point of `b`.
    fn holds_no_foot(&self, b: &Aabb, n: u32) -> bool;
    /// A lower bound of the distance from `b` to the curve in leaf `n` tighter than
    /// the gap to its box where the leaf knows more of its curve (0 otherwise).
    fn leaf_gap(&self, b: &Aabb, n: u32) -> f64;
    /// An enclosure of the distance's gradient at the points `q` of `b` whose nearest
    /// point lies under `n`.
    fn gradient_from(&self, b: &Aabb, n: u32) -> [Interval; 2];
}

/// A curve's distance field over its [`CurveTree`], given the nearest point of the curve
/// to a point; [`DistanceField`] follows.
pub(super) trait CurveField: CurveTree + Send + Sync {
    /// The distance from `q` to the curve and a nearest point of it, searched in the
    /// nodes `from` (which hold every point of the curve that can be nearest to `q`), or
    /// over the whole curve (`None`); `(∞, q)` where none is found.
    fn nearest_point(&self, q: Point, from: Option<&[u32]>) -> (f64, Point);
}

impl<T: CurveField> DistanceField for T {
    type State = CurveState;

    fn state(&self, b: &Aabb) -> CurveState {
        state(self, b)
    }

    fn split(&self, s: &CurveState, b: &Aabb, axis: Axis, at: f64) -> (CurveState, CurveState) {
        let (l, r) = b.split(axis, at);
        (refine(self, &l, &s.nodes), refine(self, &r, &s.nodes))
    }

    fn bound(&self, s: &CurveState, _b: &Aabb) -> Interval {
        s.bound()
    }

    fn gradient_bound(&self, s: &CurveState, _b: &Aabb) -> Option<[Interval; 2]> {
        Some(s.gradient)
    }

    fn restricts(&self) -> bool {
        true
    }

    /// The nodes of `s` that may hold a nearest point for some point of `to`.
    fn restrict(&self, s: &CurveState, to: &Aabb) -> CurveState {
        refine(self, to, &s.nodes)
    }

    fn value(&self, q: Point) -> f64 {
        self.nearest_point(q, None).0
    }

    /// The search starts from the nodes that `s` kept.
    fn value_in(&self, s: &CurveState, q: Point) -> f64 {
        self.nearest_point(q, Some(&s.nodes)).0
    }

    fn gradient(&self, q: Point) -> Point {
        match self.nearest_point(q, None) {
            (d, foot) if d > 0.0 && d.is_finite() => (q - foot) * (1.0 / d),
            _ => Point::new(0.0, 0.0),
        }
    }

    /// The mean value form about the box's centre (`curve_tree::pair`).
    fn pair(&self, s: &CurveState, other: &Self, so: &CurveState, b: &Aabb) -> PairBound {
        pair(self, s, other, so, b)
    }
}

/// The per-box state: the nodes that may hold a nearest point, with the bounds they
/// give.
#[derive(Clone, Debug)]
pub struct CurveState {
    pub(super) nodes: Vec<u32>,
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) gradient: [Interval; 2],
}

impl CurveState {
    /// The distance bounds over the state's box.
    pub(super) fn bound(&self) -> Interval {
        Interval::new(self.lo, self.hi)
    }
}

/// The state over `b` from the root.
pub(super) fn state<T: CurveTree>(tree: &T, b: &Aabb) -> CurveState {
    let root: Vec<u32> = tree.root().into_iter().collect();
    refine(tree, b, &root)
}

/// The nodes of `from` (and their descendants) that may hold a nearest point for a
/// point of `b`, the bounds they give, and the gradient hull.
pub(super) fn refine<T: CurveTree>(tree: &T, b: &Aabb, from: &[u32]) -> CurveState {
    let (kept, lo, hi) = kept_nodes(tree, b, from);
    let unit = Interval::new(-1.0, 1.0);
    let mut gradient: Option<[Interval; 2]> = None;
    for &n in &kept {
        let g = tree.gradient_from(b, n);
        gradient = Some(match gradient {
            None => g,
            Some(h) => [h[0].hull(g[0]), h[1].hull(g[1])],
        });
    }
    CurveState {
        nodes: kept,
        lo,
        hi,
        gradient: gradient.unwrap_or([unit, unit]),
    }
}

/// [`refine`] without the gradient bound: the nodes kept and the distance bounds
/// `(lo, hi)` they give.
pub(super) fn kept_nodes<T: CurveTree>(tree: &T, b: &Aabb, from: &[u32]) -> (Vec<u32>, f64, f64) {
    let mut hi = f64::INFINITY;
    for &n in from {
        hi = hi.min(tree.witness_upper(b, n));
    }
    // nodes whose diagonal is longer than half the box's are opened (squared lengths)
    let open = 0.25 * diagonal_squared(b);
    let mut work = from.to_vec();
    let mut kept: Vec<(u32, f64)> = Vec::new();
    while let Some(n) = work.pop() {
        let bbox = tree.bbox(n);
        let lo = gap(b, bbox);
        if lo > hi || tree.holds_no_foot(b, n) {
            continue;
        }
        let kids = tree.children(n);
        if !kids.is_empty() && diagonal_squared(bbox) > open {
            // nearer child last, so that it is opened next and tightens `hi` early
            let mut near = [(f64::INFINITY, NONE); 2];
            for (k, &c) in kids.iter().enumerate().take(2) {
                near[k] = (gap(b, tree.bbox(c)), c);
            }
            if near[0].0 < near[1].0 {
                near.swap(0, 1);
            }
            for (_, c) in near.into_iter().filter(|k| k.1 != NONE) {
                hi = hi.min(tree.witness_upper(b, c));
                work.push(c);
            }
        } else {
            let tighter = if kids.is_empty() {
                tree.leaf_gap(b, n)
            } else {
                0.0
            };
            kept.push((n, lo.max(tighter)));
        }
    }
    kept.retain(|k| k.1 <= hi);
    let lo = kept.iter().map(|k| k.1).fold(f64::INFINITY, f64::min);
    (
        kept.into_iter().map(|k| k.0).collect(),
        round_down(lo.min(hi)).max(0.0),
        hi,
    )
}

/// Bounds of `f_a − f_b` over `b`: the difference of the two bounds, narrowed by the
/// mean value form about the box's centre `c`: `h(q) ∈ h(c) + ∇h(B)·(q − c)`
/// (Lebourg's theorem for these Lipschitz fields, whose generalized gradients the
/// gradient bounds hold), with `h(c)` from the bounds at `c` alone, which are second
/// order in the leaf size where [`CurveTree::leaf_gap`] is. Beside a double zero of
/// `h` (tangent curves) the plain difference is as wide as the box and the leaves;
/// this is as wide as the box times `|∇h|`.
pub(super) fn pair<A: CurveTree, B: CurveTree>(
    a: &A,
    sa: &CurveState,
    other: &B,
    so: &CurveState,
    b: &Aabb,
) -> PairBound {
    let g = [
        sa.gradient[0] - so.gradient[0],
        sa.gradient[1] - so.gradient[1],
    ];
    let plain = sa.bound() - so.bound();
    let c = b.center();
    let at_c = Aabb::new(c, c);
    let ((_, s_lo, s_hi), (_, o_lo, o_hi)) = (
        kept_nodes(a, &at_c, &sa.nodes),
        kept_nodes(other, &at_c, &so.nodes),
    );
    let centre = Interval::new(s_lo, s_hi) - Interval::new(o_lo, o_hi);
    let mean = centre + g[0] * (b.x() - c.x) + g[1] * (b.y() - c.y);
    let (lo, hi) = (plain.lo.max(mean.lo), plain.hi.min(mean.hi));
    let value = if lo > hi {
        plain // disjoint only through rounding: both hold h
    } else {
        Interval::new(lo, hi)
    };
    PairBound {
        value,
        gradient: Some(g),
    }
}

/// [`pair`] for the field `|q − p|` of a point `p` against a curve: the mean value
/// form about the box's centre, where the point's distance is known to rounding.
pub(super) fn pair_with_point<T: CurveTree>(
    p: Point,
    curve: &T,
    so: &CurveState,
    b: &Aabb,
) -> PairBound {
    let distance = |b: &Aabb| ((b.x() - p.x).sqr() + (b.y() - p.y).sqr()).sqrt();
    let to_p = unit_bound(b, &Aabb::new(p, p));
    let g = [to_p[0] - so.gradient[0], to_p[1] - so.gradient[1]];
    let plain = distance(b) - so.bound();
    let c = b.center();
    let at_c = Aabb::new(c, c);
    let (_, o_lo, o_hi) = kept_nodes(curve, &at_c, &so.nodes);
    let centre = distance(&at_c) - Interval::new(o_lo, o_hi);
    let mean = centre + g[0] * (b.x() - c.x) + g[1] * (b.y() - c.y);
    let (lo, hi) = (plain.lo.max(mean.lo), plain.hi.min(mean.hi));
    PairBound {
        value: if lo > hi {
            plain
        } else {
            Interval::new(lo, hi)
        },
        gradient: Some(g),
    }
}

/// The squared length of a box's diagonal.
fn diagonal_squared(b: &Aabb) -> f64 {
    b.width() * b.width() + b.height() * b.height()
}

/// The least distance between two boxes, rounded down.
pub(super) fn gap(a: &Aabb, b: &Aabb) -> f64 {
    let dx = (a.min.x - b.max.x).max(b.min.x - a.max.x).max(0.0);
    let dy = (a.min.y - b.max.y).max(b.min.y - a.max.y).max(0.0);
    if dx == 0.0 && dy == 0.0 {
        return 0.0;
    }
    round_down((dx * dx + dy * dy).sqrt() * (1.0 - 4.0 * f64::EPSILON)).max(0.0)
}

/// The unit vectors `(q − p)/|q − p|`, `q ∈ b`, `p ∈ n`; the unit square where the boxes
/// meet.
pub(super) fn unit_bound(b: &Aabb, n: &Aabb) -> [Interval; 2] {
    let unit = Interval::new(-1.0, 1.0);
    direction(b.x() - n.x(), b.y() - n.y()).unwrap_or([unit, unit])
}

/// The unit vectors `v/|v|`, `v ∈ dx × dy`; `None` when the box may hold 0.
pub(super) fn direction(dx: Interval, dy: Interval) -> Option<[Interval; 2]> {
    let r = (dx.sqr() + dy.sqr()).sqrt();
    if r.lo <= 0.0 {
        return None;
    }
    let (gx, gy) = (dx.div(r)?, dy.div(r)?);
    Some([
        Interval::new(gx.lo.max(-1.0), gx.hi.min(1.0)),
        Interval::new(gy.lo.max(-1.0), gy.hi.min(1.0)),
    ])
}

/// True when the unit normal enclosure `unit` (of either orientation) meets `between`
/// on the side of the curve where `b` lies (`side`: an enclosure of `(q − p)·normal`):
/// the gradient is `±unit`, far tighter than the directions between the boxes where
/// the node is not small beside its distance.
pub(super) fn meet_normal(
    between: [Interval; 2],
    unit: [Interval; 2],
    side: Interval,
) -> [Interval; 2] {
    if !side.excludes_zero() {
        return between;
    }
    let sign = if side.lo > 0.0 { 1.0 } else { -1.0 };
    let meet = |a: Interval, u: Interval| {
        let u = u.scale(sign);
        let (lo, hi) = (a.lo.max(u.lo), a.hi.min(u.hi));
        // empty only through rounding (both hold the gradient): keep the boxes' one
        if lo <= hi {
            Interval::new(lo, hi)
        } else {
            a
        }
    };
    [meet(between[0], unit[0]), meet(between[1], unit[1])]
}
