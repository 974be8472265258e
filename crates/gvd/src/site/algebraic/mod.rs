//! An `algebraic` site: the Euclidean distance to the curve `{f = 0} ∩ clip` of a
//! bivariate polynomial (SCENE_FORMAT.md), as a distance field of the subdivision
//! engine (after Shou, Yuan, Miao, Wang 2011, whose quadtree of curve pixels this
//! replaces by a certified enclosure with witnesses and Newton-refined feet).
//!
//! * **Enclosure** ([`enclosure`]): every point of the curve lies in a leaf of a
//!   quadtree over the clip box built with Bernstein range exclusion; leaf sides with
//!   certified sign changes of `f` give *witnesses*, certified points of the curve.
//! * **Box bounds, gradients, pairs** ([`curve_tree`]) over the enclosure: witness
//!   brackets give the upper bounds, leaf strips second-order lower bounds, and nodes
//!   clear of the clip box's sides the curve's normal `±∇f/|∇f|` as the gradient.
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
mod occlusion;
mod special;

use super::curve_tree::{meet_normal, unit_bound, CurveField, CurveTree, NONE};
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::num::interval::{round_down, round_up};
use crate::num::poly::Poly;
use crate::num::Interval;
use dense::Jet;
use enclosure::Enclosure;
use special::Special;

/// Singular clusters longer than this fraction of the clip box are not isolated
/// points: the curve is singular along a branch (`f` has a repeated factor).
const MAX_CLUSTER: f64 = 1e-4;

/// Lengths the field works with (the leaf size up to the clip box's coordinates) must
/// lie within `2^±MAX_LENGTH_EXPONENT`: distances are `√(dx² + dy²)`, so their squares
/// then stay within `2^±960`, among f64's normal numbers (`2^-1022` to `2^1024`) with
/// room for the products of the foot-point system. Beyond, squared distances underflow
/// to 0 (every node of the enclosure ties with every other, so no search is pruned) or
/// overflow. An equation is not rescaled with its scene (`Scene::unit_scale`).
const MAX_LENGTH_EXPONENT: i32 = 480;

/// The distance field of an algebraic curve.
#[derive(Clone, Debug)]
pub struct AlgebraicField {
    site: usize,
    poly: Poly,
    clip: Aabb,
    jet: Jet,
    enclosure: Enclosure,
    special: Special,
    leaf_size: f64,
    /// The sides on which other curves of the scene lie (`algebraic::occlusion`).
    sides: Vec<occlusion::Side>,
}

impl AlgebraicField {
    /// The field of site `site`, the curve `{f = 0} ∩ clip`, with enclosure leaves no
    /// longer than `resolution`. Refuses a curve with no point in the clip box, one with
    /// no certified point, and one singular along a whole branch.
    pub fn new(site: usize, f: &Poly, clip: Aabb, resolution: f64) -> Result<Self, Error> {
        let jet = Jet::new(f);
        let leaf_size = resolution.max(1e-12 * clip.longest_side());
        check_length_range(site, &clip, leaf_size)?;
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
            site,
            poly: f.clone(),
            clip,
            jet,
            enclosure,
            special,
            leaf_size,
            sides: Vec::new(),
        })
    }

    /// Finds on which side of each curve of `fields` every other one lies
    /// (`algebraic::occlusion`), for [`Self::occludes_over`].
    pub fn find_sides(fields: &mut [&mut AlgebraicField]) {
        let mut spent = 0;
        let sides: Vec<Vec<occlusion::Side>> = (0..fields.len())
            .map(|i| {
                (0..fields.len())
                    .filter(|&j| j != i)
                    .filter_map(|j| occlusion::side(fields[i], fields[j], &mut spent))
                    .collect()
            })
            .collect();
        for (f, s) in fields.iter_mut().zip(sides) {
            f.sides = s;
        }
    }

    /// True when this curve is at least as near as `other` at every point of `b`, up to
    /// the contacts of the two curves (`algebraic::occlusion`): `other` lies on the side
    /// `σ·f ≥ 0` of this curve, and `σ·f < 0` on `b`, inside the clip box.
    pub fn occludes_over(&self, other: &AlgebraicField, b: &Aabb) -> bool {
        let Some(side) = self.sides.iter().find(|s| s.site == other.site) else {
            return false;
        };
        let c = b.center();
        if !self.clip.contains_box(b) || side.sign * self.jet.f.eval(c.x, c.y) >= 0.0 {
            return false; // (the second test is only a quick refusal)
        }
        let range = crate::num::bernstein::Bernstein2::from_poly(&self.poly, b).range();
        if side.sign > 0.0 {
            range.hi < 0.0
        } else {
            range.lo > 0.0
        }
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
            "occluded_sites": self.sides.iter().map(|s| s.site).collect::<Vec<_>>(),
            "contacts": self.sides.iter().map(|s| s.contacts.len()).sum::<usize>(),
            "contact_width": self
                .sides
                .iter()
                .flat_map(|s| &s.contacts)
                .map(|c| c.longest_side())
                .fold(0.0, f64::max),
        })
    }

    /// An enclosure of the distance's gradient `(q − p)/|q − p|` at the points `q` of `b`
    /// whose nearest point `p` lies in `node`. Where `p` must be a foot (the node is
    /// clear of the clip box's sides) on a known side of the curve, the gradient is also
    /// `±∇f(p)/|∇f(p)|`, far tighter where the node is not small beside its distance.
    fn node_gradient(&self, b: &Aabb, node: &enclosure::Node) -> [Interval; 2] {
        let (n, normal) = (&node.bbox, &node.normal);
        let between = unit_bound(b, n);
        let inside = !clip_sides(&self.clip, n).iter().any(|s| s.0);
        let side = (b.x() - n.x()) * normal[0] + (b.y() - n.y()) * normal[1];
        match node.unit_normal {
            Some(unit) if inside => meet_normal(between, unit, side),
            _ => between,
        }
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

impl CurveTree for AlgebraicField {
    fn root(&self) -> Option<u32> {
        self.enclosure.root()
    }

    fn bbox(&self, n: u32) -> &Aabb {
        &self.enclosure.nodes[n as usize].bbox
    }

    fn children(&self, n: u32) -> &[u32] {
        self.enclosure.children(n)
    }

    /// The distance from `b` to the strip of leaf `n` (0 without one): second order in
    /// the leaf's size, where the gap to the leaf's box is first order.
    fn leaf_gap(&self, b: &Aabb, n: u32) -> f64 {
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

    fn holds_no_foot(&self, b: &Aabb, n: u32) -> bool {
        let node = &self.enclosure.nodes[n as usize];
        holds_no_foot(&self.clip, b, &node.bbox, &node.normal)
    }

    fn gradient_from(&self, b: &Aabb, n: u32) -> [Interval; 2] {
        self.node_gradient(b, &self.enclosure.nodes[n as usize])
    }
}

/// Refuses a curve whose clip box or leaf size lies outside the lengths f64 can square
/// ([`MAX_LENGTH_EXPONENT`]).
fn check_length_range(site: usize, clip: &Aabb, leaf_size: f64) -> Result<(), Error> {
    let (tiny, huge) = (
        2f64.powi(-MAX_LENGTH_EXPONENT),
        2f64.powi(MAX_LENGTH_EXPONENT),
    );
    let side = clip.longest_side();
    let reach = clip.to_array().iter().fold(side, |m, v| m.max(v.abs()));
    let smallest = leaf_size.min(side);
    if smallest >= tiny && reach <= huge {
        return Ok(());
    }
    let what = if smallest < tiny {
        format!("its clip box ({side:e} wide) at resolution {leaf_size:e} is too small")
    } else {
        format!("its clip box reaches {reach:e}, too far")
    };
    Err(Error::site(
        site,
        "equation",
        format!(
            "{what}: distances to the curve square lengths, and lengths outside \
             2^±{MAX_LENGTH_EXPONENT} ({tiny:.1e} to {huge:.1e}) square beyond f64's normal \
             numbers; equations are not rescaled with the scene, so give the domain (or the \
             'clip' box), epsilon and the equation at a scale nearer 1"
        ),
    ))
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

impl CurveField for AlgebraicField {
    /// From `from` first, then from the root when those nodes hold no sample.
    fn nearest_point(&self, q: Point, from: Option<&[u32]>) -> (f64, Point) {
        let found = match from {
            Some(nodes) => self
                .nearest(q, Some(nodes))
                .or_else(|| self.nearest(q, None)),
            None => self.nearest(q, None),
        };
        found.map_or((f64::INFINITY, q), |n| (n.dist, n.foot))
    }
}
