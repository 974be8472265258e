//! An `algebraic` site: the Euclidean distance to the curve `{f = 0} ∩ clip` of a
//! bivariate polynomial (SCENE_FORMAT.md), as a distance field of the subdivision
//! engine (after Shou, Yuan, Miao, Wang 2011, whose quadtree of curve pixels this
//! replaces by a certified enclosure with witnesses and Newton-refined feet).
//!
//! * **Enclosure** ([`enclosure`]): every point of the curve lies in a leaf of a
//!   quadtree over the clip box built with Bernstein range exclusion; leaf sides with
//!   certified sign changes of `f` give *witnesses*, certified points of the curve.
//! * **Box bounds.** Over a box `B` the distance is at least the least gap from `B` to
//!   a node that may hold the curve, and at most the least over witnesses `w` of the
//!   largest distance from `B` to `w`'s bracket. The per-box state is the list of
//!   enclosure nodes that may hold a nearest point for some point of `B`; children
//!   inherit it, opening nodes larger than half the box (a dual-tree descent), so the
//!   enclosure is refined only where the diagram looks at it.
//! * **Gradient bound.** Where the distance is differentiable its gradient is the unit
//!   vector from the nearest point to `q`; it lies in the hull of the unit vectors from
//!   the kept nodes to `B` (and so does the generalized gradient on the curve's ridges).
//! * **Point values** ([`nearest`]): best-first search and Newton on the foot-point
//!   system.
//! * **Special points** ([`special`]): singular points by the 2-D certified solver,
//!   tangential contacts with the clip box; counted in [`AlgebraicField::stats`].
//! * **Medial axis** ([`medial`]): a closed smooth curve cut at its vertices into arcs
//!   of monotone curvature, each a field of its own.

mod dense;
mod enclosure;
pub mod medial;
mod nearest;
mod special;

use super::{DistanceField, PairBound};
use crate::error::Error;
use crate::geom::{Aabb, Axis, Point};
use crate::num::interval::{round_down, round_up};
use crate::num::poly::Poly;
use crate::num::Interval;
use dense::Jet;
use enclosure::{Enclosure, NONE};
use special::Special;

/// Singular clusters longer than this fraction of the clip box are not isolated
/// points: the curve is singular along a branch (`f` has a repeated factor).
const MAX_CLUSTER: f64 = 1e-4;

/// The distance field of an algebraic curve.
#[derive(Clone, Debug)]
pub struct AlgebraicField {
    clip: Aabb,
    jet: Jet,
    enclosure: Enclosure,
    special: Special,
    leaf_size: f64,
}

/// The per-box state: the enclosure nodes that may hold a nearest point, with the
/// bounds they give.
#[derive(Clone, Debug)]
pub struct AlgebraicState {
    nodes: Vec<u32>,
    lo: f64,
    hi: f64,
    gradient: [Interval; 2],
}

impl AlgebraicField {
    /// The field of site `site`, the curve `{f = 0} ∩ clip`, with enclosure leaves no
    /// longer than `resolution`. Refuses a curve with no point in the clip box, one with
    /// no certified point, and one singular along a whole branch.
    pub fn new(site: usize, f: &Poly, clip: Aabb, resolution: f64) -> Result<Self, Error> {
        let jet = Jet::new(f);
        let leaf_size = resolution.max(1e-12 * clip.longest_side());
        let Some(mut enclosure) = Enclosure::build(f, &jet, &clip, leaf_size) else {
            return Err(Error::site(
                site,
                "equation",
                format!(
                    "enclosing the curve over its clip box ({:e} wide) at {leaf_size:e} needs \
                     more than {} boxes (the curve is tiny beside the box, or f64 cannot \
                     resolve it there); give a 'clip' box around the curve, a smaller domain \
                     or a coarser epsilon",
                    clip.longest_side(),
                    enclosure::MAX_BOXES
                ),
            ));
        };
        if enclosure.root().is_none() {
            return Err(Error::site(
                site,
                "equation",
                "the curve has no real point in its clip box (certified by Bernstein bounds)",
            ));
        }
        let special = special::analyse(f, &jet, &clip, &mut enclosure);
        let unsupported = |message: &str| Error::Unsupported {
            site,
            kind: "algebraic".into(),
            message: message.into(),
        };
        if special.largest_cluster > MAX_CLUSTER * clip.longest_side() {
            return Err(unsupported(
                "the curve is singular along a whole branch (f = ∂f/∂x = ∂f/∂y = 0 on a curve: a repeated factor?)",
            ));
        }
        if enclosure.witnesses.is_empty() {
            return Err(unsupported(
                "no point of the curve could be certified in its clip box (it may only touch the box, or lie within rounding of it)",
            ));
        }
        Ok(AlgebraicField {
            clip,
            jet,
            enclosure,
            special,
            leaf_size,
        })
    }

    /// Figures of the enclosure and the special points, for a diagram's `stats`.
    pub fn stats(&self) -> serde_json::Value {
        serde_json::json!({
            "enclosure_leaves": self.enclosure.leaves.len(),
            "witnesses": self.enclosure.witnesses.len(),
            "leaf_size": self.leaf_size,
            "singular_points": self.special.singular_points,
            "singular_clusters": self.special.singular_clusters,
            "clip_contacts": self.special.clip_contacts,
        })
    }

    /// The nodes of `from` (and their descendants) that may hold a nearest point for a
    /// point of `b`, and the bounds they give.
    fn refine(&self, b: &Aabb, from: &[u32]) -> AlgebraicState {
        let (kept, lo, hi) = self.kept_nodes(b, from);
        let unit = Interval::new(-1.0, 1.0);
        let mut gradient: Option<[Interval; 2]> = None;
        for &n in &kept {
            let g = self.gradient_from(b, &self.enclosure.nodes[n as usize]);
            gradient = Some(match gradient {
                None => g,
                Some(h) => [h[0].hull(g[0]), h[1].hull(g[1])],
            });
        }
        AlgebraicState {
            nodes: kept,
            lo,
            hi,
            gradient: gradient.unwrap_or([unit, unit]),
        }
    }

    /// [`refine`](Self::refine) without the gradient bound: the nodes kept and the
    /// distance bounds `(lo, hi)` they give.
    fn kept_nodes(&self, b: &Aabb, from: &[u32]) -> (Vec<u32>, f64, f64) {
        let e = &self.enclosure;
        let mut hi = f64::INFINITY;
        for &n in from {
            hi = hi.min(self.witness_upper(b, n));
        }
        // nodes whose diagonal is longer than half the box's are opened (squared lengths)
        let open = 0.25 * diagonal_squared(b);
        let mut work = from.to_vec();
        let mut kept: Vec<(u32, f64)> = Vec::new();
        while let Some(n) = work.pop() {
            let node = &e.nodes[n as usize];
            let lo = gap(b, &node.bbox);
            if lo > hi || holds_no_foot(&self.clip, b, &node.bbox, &node.normal) {
                continue;
            }
            if node.leaf == NONE && diagonal_squared(&node.bbox) > open {
                // nearer child last, so that it is opened next and tightens `hi` early
                let mut kids = [(f64::INFINITY, NONE); 2];
                for (k, &c) in e.children(n).iter().enumerate().take(2) {
                    kids[k] = (gap(b, &e.nodes[c as usize].bbox), c);
                }
                if kids[0].0 < kids[1].0 {
                    kids.swap(0, 1);
                }
                for (_, c) in kids.into_iter().filter(|k| k.1 != NONE) {
                    hi = hi.min(self.witness_upper(b, c));
                    work.push(c);
                }
            } else {
                kept.push((n, lo.max(self.strip_gap(b, n))));
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

    /// An enclosure of the distance's gradient `(q − p)/|q − p|` at the points `q` of `b`
    /// whose nearest point `p` lies in `node`. Where `p` must be a foot (the node is
    /// clear of the clip box's sides) on a known side of the curve, the gradient is also
    /// `±∇f(p)/|∇f(p)|`, far tighter where the node is not small beside its distance.
    fn gradient_from(&self, b: &Aabb, node: &enclosure::Node) -> [Interval; 2] {
        let (n, normal) = (&node.bbox, &node.normal);
        let between = unit_bound(b, n);
        let inside = !clip_sides(&self.clip, n).iter().any(|s| s.0);
        let side = (b.x() - n.x()) * normal[0] + (b.y() - n.y()) * normal[1];
        if !inside || !side.excludes_zero() {
            return between;
        }
        let Some(unit) = node.unit_normal else {
            return between;
        };
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

    /// A lower bound of the distance from `b` to the curve in node `n` by the strip of
    /// its leaf (0 without one): second order in the leaf's size, where the gap to the
    /// leaf's box is first order.
    fn strip_gap(&self, b: &Aabb, n: u32) -> f64 {
        let node = &self.enclosure.nodes[n as usize];
        if node.leaf == NONE {
            return 0.0;
        }
        let Some(strip) = &self.enclosure.leaves[node.leaf as usize].strip else {
            return 0.0;
        };
        let d = b.segment_distance(strip.a, strip.b);
        let scale = [b.min.x, b.min.y, b.max.x, b.max.y, strip.a.x, strip.a.y]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        round_down(d * (1.0 - 8.0 * f64::EPSILON) - 16.0 * f64::EPSILON * scale - strip.half_width)
            .max(0.0)
    }

    /// The largest distance from `b` to node `n`'s witness bracket (∞ without one).
    fn witness_upper(&self, b: &Aabb, n: u32) -> f64 {
        let w = self.enclosure.nodes[n as usize].witness;
        if w == NONE {
            return f64::INFINITY;
        }
        let w = &self.enclosure.witnesses[w as usize];
        // one square root of the largest square (the same value: sqrt is monotone)
        let far = b
            .corners()
            .iter()
            .map(|c| c.dist2(w.a).max(c.dist2(w.b)))
            .fold(0.0, f64::max)
            .sqrt();
        round_up(far * (1.0 + 4.0 * f64::EPSILON))
    }

    /// The nearest point of the curve to `q`, searched in the nodes `from`, which hold
    /// every point of the curve that can be nearest to `q` (`None`: the whole curve).
    fn nearest(&self, q: Point, from: Option<&[u32]>) -> Option<nearest::Nearest> {
        let root: Vec<u32>;
        let from = match from {
            Some(nodes) => nodes,
            None => {
                root = self.enclosure.root().into_iter().collect();
                &root
            }
        };
        nearest::nearest(
            &self.enclosure,
            &self.jet,
            &self.clip,
            q,
            from,
            4.0 * self.leaf_size,
        )
    }
}

/// True when no point of the curve `{f = 0} ∩ clip` in a node (box `n`, gradient
/// enclosure `normal`) is nearest to any point `q` of `b`. A nearest point `p` is
/// singular (`∇f = 0`), a foot, where `(q − p) × ∇f(p) = 0`, or an end on a side of
/// the clip box from which the curve, followed inward along its tangent `t`, gets no
/// nearer: `(q − p) · t ≤ 0`. Interval forms over `b × n` that exclude each case prove it.
/// (Distance bounds alone keep every node within the upper bound, a span of `√|b|`
/// along a curve that bends away from `b`; this keeps a span of about `|b|`.)
fn holds_no_foot(clip: &Aabb, b: &Aabb, n: &Aabb, normal: &[Interval; 2]) -> bool {
    let (dx, dy) = (b.x() - n.x(), b.y() - n.y());
    if !(dx * normal[1] - dy * normal[0]).excludes_zero() {
        return false;
    }
    let tangent = [-normal[1], normal[0]];
    clip_sides(clip, n)
        .iter()
        .filter(|s| s.0)
        .all(|&(_, inward)| {
            let across = tangent[0].scale(inward[0]) + tangent[1].scale(inward[1]);
            if !across.excludes_zero() {
                return false; // the curve may run along the side
            }
            let sign = if across.lo > 0.0 { 1.0 } else { -1.0 };
            let along = dx * tangent[0].scale(sign) + dy * tangent[1].scale(sign);
            along.lo > 0.0
        })
}

/// The clip box's four sides by their inward normals, each with whether box `n`
/// reaches it.
fn clip_sides(clip: &Aabb, n: &Aabb) -> [(bool, [f64; 2]); 4] {
    [
        (n.min.x <= clip.min.x, [1.0, 0.0]),
        (n.max.x >= clip.max.x, [-1.0, 0.0]),
        (n.min.y <= clip.min.y, [0.0, 1.0]),
        (n.max.y >= clip.max.y, [0.0, -1.0]),
    ]
}

/// The squared length of a box's diagonal.
fn diagonal_squared(b: &Aabb) -> f64 {
    b.width() * b.width() + b.height() * b.height()
}

/// The least distance between two boxes, rounded down.
fn gap(a: &Aabb, b: &Aabb) -> f64 {
    let dx = (a.min.x - b.max.x).max(b.min.x - a.max.x).max(0.0);
    let dy = (a.min.y - b.max.y).max(b.min.y - a.max.y).max(0.0);
    if dx == 0.0 && dy == 0.0 {
        return 0.0;
    }
    round_down((dx * dx + dy * dy).sqrt() * (1.0 - 4.0 * f64::EPSILON)).max(0.0)
}

/// The unit vectors `(q − p)/|q − p|`, `q ∈ b`, `p ∈ n`; the unit square where the boxes
/// meet.
fn unit_bound(b: &Aabb, n: &Aabb) -> [Interval; 2] {
    let unit = Interval::new(-1.0, 1.0);
    direction(b.x() - n.x(), b.y() - n.y()).unwrap_or([unit, unit])
}

/// The unit vectors `v/|v|`, `v ∈ dx × dy`; `None` when the box may hold 0.
fn direction(dx: Interval, dy: Interval) -> Option<[Interval; 2]> {
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

impl DistanceField for AlgebraicField {
    type State = AlgebraicState;

    fn state(&self, b: &Aabb) -> AlgebraicState {
        let root: Vec<u32> = self.enclosure.root().into_iter().collect();
        self.refine(b, &root)
    }

    fn split(
        &self,
        s: &AlgebraicState,
        b: &Aabb,
        axis: Axis,
        at: f64,
    ) -> (AlgebraicState, AlgebraicState) {
        let (l, r) = b.split(axis, at);
        (self.refine(&l, &s.nodes), self.refine(&r, &s.nodes))
    }

    fn bound(&self, s: &AlgebraicState, _b: &Aabb) -> Interval {
        Interval::new(s.lo, s.hi)
    }

    fn gradient_bound(&self, s: &AlgebraicState, _b: &Aabb) -> Option<[Interval; 2]> {
        Some(s.gradient)
    }

    fn restricts(&self) -> bool {
        true
    }

    /// The nodes of `s` that may hold a nearest point for some point of `to`.
    fn restrict(&self, s: &AlgebraicState, to: &Aabb) -> AlgebraicState {
        self.refine(to, &s.nodes)
    }

    fn value(&self, q: Point) -> f64 {
        self.nearest(q, None).map_or(f64::INFINITY, |n| n.dist)
    }

    /// The search for the nearest point starts from the nodes that `s` kept (from the
    /// root when they hold no sample).
    fn value_in(&self, s: &AlgebraicState, q: Point) -> f64 {
        self.nearest(q, Some(&s.nodes))
            .or_else(|| self.nearest(q, None))
            .map_or(f64::INFINITY, |n| n.dist)
    }

    fn gradient(&self, q: Point) -> Point {
        match self.nearest(q, None) {
            Some(n) if n.dist > 0.0 => (q - n.foot) * (1.0 / n.dist),
            _ => Point::new(0.0, 0.0),
        }
    }

    /// The difference of the two bounds, narrowed by the mean value form about the
    /// box's centre `c`: `h(q) ∈ h(c) + ∇h(B)·(q − c)` (Lebourg's theorem for these
    /// Lipschitz fields, whose generalized gradients the gradient bounds hold), with
    /// `h(c)` from the bounds at `c` alone, which are second order in the leaf size.
    /// Beside a double zero of `h` (tangent curves) the plain difference is as wide
    /// as the box and the leaves; this is as wide as the box times `|∇h|`.
    fn pair(&self, s: &AlgebraicState, other: &Self, so: &AlgebraicState, b: &Aabb) -> PairBound {
        let plain = super::bound_difference(self, s, other, so, b);
        let Some(g) = plain.gradient else {
            return plain;
        };
        let c = b.center();
        let at_c = Aabb::new(c, c);
        let ((_, s_lo, s_hi), (_, o_lo, o_hi)) = (
            self.kept_nodes(&at_c, &s.nodes),
            other.kept_nodes(&at_c, &so.nodes),
        );
        let centre = Interval::new(s_lo, s_hi) - Interval::new(o_lo, o_hi);
        let mean = centre + g[0] * (b.x() - c.x) + g[1] * (b.y() - c.y);
        let (lo, hi) = (plain.value.lo.max(mean.lo), plain.value.hi.min(mean.hi));
        if lo > hi {
            return plain; // disjoint only through rounding: both hold h
        }
        PairBound {
            value: Interval::new(lo, hi),
            gradient: plain.gradient,
        }
    }
}
