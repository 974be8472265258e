//! The subdivision and refinement phases (YSL12 ¶18–19): split boxes until `C(B)`
//! holds (or the resolution cut-off), then balance the candidate boxes (those with
//! two or more features) so that none is more than twice the size of a neighbour.

use super::predicate::{self, BoxSet};
use super::quadtree::Quadtree;
use super::Filters;
use crate::geom::Aabb;
use crate::site::polygonal::Polygonal;
use crate::subdivision::budget::Budget;
use crate::subdivision::tree::{IBox, Lattice};

/// A leaf of the soft subdivision (its box in lattice coordinates is its tree node's,
/// [`Quadtree::ib`]).
#[derive(Clone, Debug)]
pub struct Node {
    /// Its box in the plane.
    pub aabb: Aabb,
    /// φ̃(B) and `Cl(m_B)`.
    pub bs: BoxSet,
    /// Stopped at the cut-off without `C(B)`.
    pub uncertified: bool,
}

impl Node {
    /// Whether the box may hold Voronoi points (two or more features).
    pub fn candidate(&self) -> bool {
        self.bs.set.len() >= 2
    }
}

/// What the phases share.
pub struct Ctx<'a> {
    pub poly: &'a Polygonal,
    pub lattice: &'a Lattice,
    pub filters: &'a Filters,
    pub min_box: f64,
    pub budget: &'a Budget,
}

impl Ctx<'_> {
    /// The node of box `ib` whose parent's set is `parent`.
    fn node(&self, ib: IBox, parent: &[u32]) -> Node {
        let aabb = self.lattice.aabb(&ib);
        let bs = predicate::feature_set(self.poly, parent, &aabb, self.filters);
        Node {
            aabb,
            bs,
            uncertified: false,
        }
    }

    /// Whether node `n` of box `ib` may be split (above the cut-off, within the
    /// lattice).
    pub fn can_split(&self, ib: &IBox, n: &Node) -> bool {
        let [x0, y0] = ib.lo;
        let [x1, y1] = ib.hi;
        n.aabb.longest_side() > self.min_box && x1 - x0 >= 2 && y1 - y0 >= 2
    }

    /// The four quarters of node `n` of box `ib` (`None` at the lattice's limit or the
    /// cut-off).
    pub fn split(&self, ib: &IBox, n: &Node) -> Option<[Node; 4]> {
        if !self.can_split(ib, n) {
            return None;
        }
        let [x0, y0] = ib.lo;
        let [x1, y1] = ib.hi;
        let (xm, ym) = (x0 + (x1 - x0) / 2, y0 + (y1 - y0) / 2);
        let q = |lo: [u64; 2], hi: [u64; 2]| self.node(IBox { lo, hi }, &n.bs.set);
        Some([
            q([x0, y0], [xm, ym]),
            q([xm, y0], [x1, ym]),
            q([x0, ym], [xm, y1]),
            q([xm, ym], [x1, y1]),
        ])
    }

    /// The subdivision phase from the root box with every feature: the quadtree of
    /// its leaves.
    pub fn subdivide(&self) -> Quadtree {
        let all: Vec<u32> = (0..self.poly.features.len() as u32).collect();
        let root = self.lattice.root();
        let mut tree = Quadtree::new(root);
        let mut stack = vec![(0u32, self.node(root, &all))];
        while let Some((at, n)) = stack.pop() {
            if !self.budget.take_box() {
                break;
            }
            if n.bs.set.len() <= 1 || predicate::holds(self.poly, &n.bs, &n.aabb, self.filters) {
                tree.set_leaf(at, n);
                continue;
            }
            match self.split(&tree.ib(at), &n) {
                Some(kids) => {
                    let first = tree.add_quarters(at);
                    stack.extend((first..first + 4).zip(kids).rev());
                }
                None => tree.set_leaf(
                    at,
                    Node {
                        uncertified: true,
                        ..n
                    },
                ),
            }
        }
        tree
    }

    /// The refinement phase: splits candidate boxes more than twice as large as a
    /// neighbour until none is. Returns the number of splits.
    ///
    /// A worklist over a quadtree of the leaves: each leaf looks across its four sides
    /// for a larger neighbour (a larger neighbour holds the whole side, so the leaf
    /// just past the side's first lattice point is it) and splits it while it is more
    /// than twice its size; the quarters of a split join the worklist. Splits only make
    /// leaves smaller, so a box once too large stays so until split: the leaves come
    /// out as the repeated global passes of the definition would leave them, in the
    /// same order (the subdivision's depth-first order, quarters in place).
    pub fn balance(&self, tree: &mut Quadtree) -> usize {
        let mut work: Vec<u32> = tree.leaf_ids();
        let mut total = 0;
        'work: while let Some(x) = work.pop() {
            let Some((ib, side)) = tree.leaf(x).map(|n| (tree.ib(x), n.aabb.longest_side())) else {
                continue; // split since it was queued: its quarters are queued
            };
            let [x0, y0] = ib.lo;
            let [x1, y1] = ib.hi;
            let probes = [
                x0.checked_sub(1).map(|x| [x, y0]),
                Some([x1, y0]),
                y0.checked_sub(1).map(|y| [x0, y]),
                Some([x0, y1]),
            ];
            // a sibling's leaves are no larger than `x`: only the other sides can face
            // a larger leaf
            let sibling = tree.sibling_sides(x);
            let outer = probes.into_iter().zip(sibling).filter(|&(_, s)| !s);
            for p in outer.filter_map(|(p, _)| p) {
                while let Some(a) = tree.locate_from(x, p) {
                    let extent = tree.extent(a);
                    if extent[0] <= 2 * (x1 - x0) && extent[1] <= 2 * (y1 - y0) {
                        break; // at most twice as large (decided without its node)
                    }
                    let n = tree.leaf(a).expect("located nodes are leaves");
                    let too_large =
                        n.candidate() && n.aabb.longest_side() > 2.0 * side * (1.0 + 1e-9);
                    if !too_large || !self.can_split(&tree.ib(a), n) {
                        break;
                    }
                    if !self.budget.take_box() {
                        break 'work;
                    }
                    let quarters = self
                        .split(&tree.ib(a), n)
                        .expect("a splittable node splits");
                    work.extend(tree.split(a, quarters));
                    total += 1;
                }
            }
        }
        total
    }
}
