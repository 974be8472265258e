//! The subdivision and refinement phases (YSL12 ¶18–19): split boxes until `C(B)`
//! holds (or the resolution cut-off), then balance the candidate boxes (those with
//! two or more features) so that none is more than twice the size of a neighbour.

use super::predicate::{self, BoxSet};
use super::Filters;
use crate::geom::Aabb;
use crate::site::polygonal::Polygonal;
use crate::subdivision::budget::Budget;
use crate::subdivision::filter::Certificate;
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

    /// Replaces the marked leaves by their quarters (taking one box each), with `kept`
    /// alongside (`None` for the quarters); returns how many were split.
    pub fn split_marked<T>(
        &self,
        leaves: &mut Vec<Node>,
        kept: &mut Vec<Option<T>>,
        marked: &[bool],
    ) -> usize {
        let mut out = Vec::with_capacity(leaves.len());
        let mut out_kept = Vec::with_capacity(leaves.len());
        let mut count = 0;
        for ((n, k), &m) in leaves.drain(..).zip(kept.drain(..)).zip(marked) {
            let quarters = if m && self.budget.take_box() {
                self.split(&n)
            } else {
                None
            };
            match quarters {
                Some(q) => {
                    count += 1;
                    out.extend(q);
                    out_kept.extend([None, None, None, None]);
                }
                None => {
                    out.push(n);
                    out_kept.push(k);
                }
            }
        }
        *leaves = out;
        *kept = out_kept;
        count
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
    pub fn balance(&self, leaves: &mut Vec<Node>) -> usize {
        let mut tree = Quadtree::new(self.lattice.root(), std::mem::take(leaves));
        let mut work: Vec<u32> = tree.leaf_ids();
        let mut total = 0;
        'work: while let Some(x) = work.pop() {
            let Some(ib) = tree.leaf(x).map(|n| n.ib) else {
                continue; // split since it was queued: its quarters are queued
            };
            let side = tree.nodes[x as usize].aabb_side;
            let [x0, y0] = ib.lo;
            let [x1, y1] = ib.hi;
            let probes = [
                x0.checked_sub(1).map(|x| [x, y0]),
                Some([x1, y0]),
                y0.checked_sub(1).map(|y| [x0, y]),
                Some([x0, y1]),
            ];
            for p in probes.into_iter().flatten() {
                while let Some(a) = tree.locate(p) {
                    let n = tree.leaf(a).expect("located nodes are leaves");
                    let too_large =
                        n.candidate() && n.aabb.longest_side() > 2.0 * side * (1.0 + 1e-9);
                    if !too_large || !self.can_split(n) {
                        break;
                    }
                    if !self.budget.take_box() {
                        break 'work;
                    }
                    let quarters = self.split(n).expect("a splittable node splits");
                    work.extend(tree.split(a, quarters));
                    total += 1;
                }
            }
        }
        *leaves = tree.into_leaves();
        total
    }
}

/// The leaves as a quadtree of their boxes, for neighbour look-ups.
struct Quadtree {
    nodes: Vec<TreeNode>,
}

struct TreeNode {
    ib: IBox,
    /// The longest side of the box in the plane.
    aabb_side: f64,
    /// The first of four consecutive quarters (lower left, lower right, upper left,
    /// upper right), 0 for a leaf.
    quarters: u32,
    /// The leaf's node; `None` for an inner node.
    leaf: Option<Node>,
}

impl Quadtree {
    /// The tree whose leaves are `leaves`, quarters of quarters of `root` listed in
    /// depth-first order.
    fn new(root: IBox, leaves: Vec<Node>) -> Self {
        let mut tree = Quadtree {
            nodes: vec![TreeNode {
                ib: root,
                aabb_side: 0.0,
                quarters: 0,
                leaf: None,
            }],
        };
        for n in leaves {
            let mut at = 0u32;
            while tree.nodes[at as usize].ib != n.ib {
                if tree.nodes[at as usize].quarters == 0 {
                    tree.add_quarters(at);
                }
                at = tree.quarter_of(at, n.ib.lo);
            }
            let t = &mut tree.nodes[at as usize];
            t.aabb_side = n.aabb.longest_side();
            t.leaf = Some(n);
        }
        tree
    }

    /// Appends the four quarters of node `at` (as [`Ctx::split`] cuts), without leaves.
    fn add_quarters(&mut self, at: u32) {
        let [x0, y0] = self.nodes[at as usize].ib.lo;
        let [x1, y1] = self.nodes[at as usize].ib.hi;
        let (xm, ym) = (x0 + (x1 - x0) / 2, y0 + (y1 - y0) / 2);
        self.nodes[at as usize].quarters = self.nodes.len() as u32;
        for (lo, hi) in [
            ([x0, y0], [xm, ym]),
            ([xm, y0], [x1, ym]),
            ([x0, ym], [xm, y1]),
            ([xm, ym], [x1, y1]),
        ] {
            self.nodes.push(TreeNode {
                ib: IBox { lo, hi },
                aabb_side: 0.0,
                quarters: 0,
                leaf: None,
            });
        }
    }

    /// The quarter of inner node `at` that holds lattice point `p` (half-open boxes).
    fn quarter_of(&self, at: u32, p: [u64; 2]) -> u32 {
        let t = &self.nodes[at as usize];
        let [x0, y0] = t.ib.lo;
        let [x1, y1] = t.ib.hi;
        let right = p[0] >= x0 + (x1 - x0) / 2;
        let upper = p[1] >= y0 + (y1 - y0) / 2;
        t.quarters + u32::from(right) + 2 * u32::from(upper)
    }

    /// The leaf holding lattice point `p`, `None` outside the root box.
    fn locate(&self, p: [u64; 2]) -> Option<u32> {
        let root = &self.nodes[0].ib;
        if p[0] >= root.hi[0] || p[1] >= root.hi[1] {
            return None;
        }
        let mut at = 0u32;
        while self.nodes[at as usize].quarters != 0 {
            at = self.quarter_of(at, p);
        }
        Some(at)
    }

    fn leaf(&self, at: u32) -> Option<&Node> {
        self.nodes[at as usize].leaf.as_ref()
    }

    /// The ids of the leaves.
    fn leaf_ids(&self) -> Vec<u32> {
        (0..self.nodes.len() as u32)
            .filter(|&i| self.nodes[i as usize].leaf.is_some())
            .collect()
    }

    /// Replaces leaf `at` by its `quarters`; returns their ids.
    fn split(&mut self, at: u32, quarters: [Node; 4]) -> std::ops::Range<u32> {
        self.nodes[at as usize].leaf = None;
        self.add_quarters(at);
        let first = self.nodes[at as usize].quarters;
        for (k, n) in quarters.into_iter().enumerate() {
            let t = &mut self.nodes[first as usize + k];
            t.aabb_side = n.aabb.longest_side();
            t.leaf = Some(n);
        }
        first..first + 4
    }

    /// The leaves in depth-first order, quarters in order.
    fn into_leaves(mut self) -> Vec<Node> {
        let mut out = Vec::new();
        let mut stack = vec![0u32];
        while let Some(at) = stack.pop() {
            let t = &mut self.nodes[at as usize];
            if let Some(n) = t.leaf.take() {
                out.push(n);
            } else if t.quarters != 0 {
                stack.extend((t.quarters..t.quarters + 4).rev());
            }
        }
        out
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
