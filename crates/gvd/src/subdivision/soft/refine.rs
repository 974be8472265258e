//! The subdivision and refinement phases (YSL12 ¶18–19): split boxes until `C(B)`
//! holds (or the resolution cut-off), then balance the candidate boxes (those with
//! two or more features) so that none is more than twice the size of a neighbour.

use super::predicate::{self, BoxSet};
use super::Filters;
use crate::geom::Aabb;
use crate::site::polygonal::Polygonal;
use crate::subdivision::budget::Budget;
use crate::subdivision::filter::Certificate;
use crate::subdivision::segments;
use crate::subdivision::tree::{IBox, Lattice, Leaf};

/// A leaf of the soft subdivision.
#[derive(Clone, Debug)]
pub struct Node {
    /// Its box in lattice coordinates.
    pub ib: IBox,
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
            ib,
            aabb,
            bs,
            uncertified: false,
        }
    }

    /// Whether a node may be split (above the cut-off, within the lattice).
    pub fn can_split(&self, n: &Node) -> bool {
        let [x0, y0] = n.ib.lo;
        let [x1, y1] = n.ib.hi;
        n.aabb.longest_side() > self.min_box && x1 - x0 >= 2 && y1 - y0 >= 2
    }

    /// The four quarters of a node (`None` at the lattice's limit or the cut-off).
    pub fn split(&self, n: &Node) -> Option<[Node; 4]> {
        if !self.can_split(n) {
            return None;
        }
        let [x0, y0] = n.ib.lo;
        let [x1, y1] = n.ib.hi;
        let (xm, ym) = (x0 + (x1 - x0) / 2, y0 + (y1 - y0) / 2);
        let q = |lo: [u64; 2], hi: [u64; 2]| self.node(IBox { lo, hi }, &n.bs.set);
        Some([
            q([x0, y0], [xm, ym]),
            q([xm, y0], [x1, ym]),
            q([x0, ym], [xm, y1]),
            q([xm, ym], [x1, y1]),
        ])
    }

    /// The subdivision phase from the root box with every feature.
    pub fn subdivide(&self) -> Vec<Node> {
        let all: Vec<u32> = (0..self.poly.features.len() as u32).collect();
        let mut stack = vec![self.node(self.lattice.root(), &all)];
        let mut leaves = Vec::new();
        while let Some(n) = stack.pop() {
            if !self.budget.take_box() {
                break;
            }
            if n.bs.set.len() <= 1 || predicate::holds(self.poly, &n.bs, &n.aabb, self.filters) {
                leaves.push(n);
                continue;
            }
            match self.split(&n) {
                Some(kids) => stack.extend(kids.into_iter().rev()),
                None => leaves.push(Node {
                    uncertified: true,
                    ..n
                }),
            }
        }
        leaves
    }

    /// Replaces the marked leaves by their quarters (taking one box each); returns how
    /// many were split.
    pub fn split_marked(&self, leaves: &mut Vec<Node>, marked: &[bool]) -> usize {
        let mut out = Vec::with_capacity(leaves.len());
        let mut count = 0;
        for (n, &m) in leaves.drain(..).zip(marked) {
            let kids = if m && self.budget.take_box() {
                self.split(&n)
            } else {
                None
            };
            match kids {
                Some(k) => {
                    count += 1;
                    out.extend(k);
                }
                None => out.push(n),
            }
        }
        *leaves = out;
        count
    }

    /// The refinement phase: splits candidate boxes more than twice as large as a
    /// neighbour until none is. Returns the number of splits.
    pub fn balance(&self, leaves: &mut Vec<Node>) -> usize {
        let mut total = 0;
        loop {
            let segs = segments::build(&as_leaves(leaves), self.lattice);
            let mut marked = vec![false; leaves.len()];
            for s in &segs.segments {
                if let [Some(a), Some(b)] = s.leaves {
                    let (a, b) = (a as usize, b as usize);
                    let (sa, sb) = (leaves[a].aabb.longest_side(), leaves[b].aabb.longest_side());
                    if leaves[a].candidate() && sa > 2.0 * sb * (1.0 + 1e-9) {
                        marked[a] = true;
                    }
                    if leaves[b].candidate() && sb > 2.0 * sa * (1.0 + 1e-9) {
                        marked[b] = true;
                    }
                }
            }
            let n = self.split_marked(leaves, &marked);
            total += n;
            if n == 0 || self.budget.exhausted() {
                return total;
            }
        }
    }
}

/// The nodes as the generic engine's leaves (for its side segments).
pub fn as_leaves(nodes: &[Node]) -> Vec<Leaf> {
    nodes
        .iter()
        .map(|n| Leaf {
            ib: n.ib,
            aabb: n.aabb,
            sites: n.bs.set.clone(),
            certificate: Certificate::None,
            uncertified: n.uncertified,
        })
        .collect()
}
