//! The leaves as a quadtree of their lattice boxes, kept from the refinement through
//! the construction: neighbour look-ups climb from a leaf to the first ancestor that
//! holds the point looked for and descend from there (a few levels, not from the
//! root), and the side segments of a leaf come from its neighbours, so a construction
//! round visits only the leaves it resolves.
//!
//! Boxes are cut at their midpoints, so along either axis two boxes' intervals are
//! nested or disjoint: where two leaves touch, the segment they share is the whole
//! side of the one whose interval along it is the shorter (either when equal). That
//! side names the segment ([`SideSegment::id`]), the same from both leaves and in
//! every round until one of the two is split.

use super::refine::Node;
use crate::geom::Point;
use crate::subdivision::tree::{IBox, Lattice};

/// No node (the root's parent; a leaf's quarters).
const NONE: u32 = u32::MAX;

/// The sides of a box, in the order of a leaf's segments along its boundary: left
/// (`x = lo`), right (`x = hi`), bottom (`y = lo`), top (`y = hi`), each from its
/// lower end (the order in which [`crate::subdivision::segments::build`] lists them).
const SIDES: [Side; 4] = [
    Side {
        axis: 0,
        high: false,
    },
    Side {
        axis: 0,
        high: true,
    },
    Side {
        axis: 1,
        high: false,
    },
    Side {
        axis: 1,
        high: true,
    },
];

#[derive(Clone, Copy)]
struct Side {
    /// The axis the side is perpendicular to.
    axis: usize,
    /// At the box's upper coordinate on that axis.
    high: bool,
}

/// A piece of a leaf's boundary shared with one neighbour (or the root box's
/// boundary), from `from` to `to` in increasing coordinate.
#[derive(Clone, Copy, Debug)]
pub struct SideSegment {
    /// `4 · node + side` of the leaf whose whole side it is (of the two, the one on
    /// the lower side of the line when both).
    pub id: u32,
    pub from: Point,
    pub to: Point,
    /// The leaf across, `None` on the root box's boundary.
    pub other: Option<u32>,
}

struct TreeNode {
    ib: IBox,
    parent: u32,
    /// The first of four consecutive quarters (lower left, lower right, upper left,
    /// upper right), [`NONE`] for a leaf.
    quarters: u32,
    /// The leaf's node in [`Quadtree::leaves`]; [`NONE`] for an inner node.
    leaf: u32,
}

/// The tree's nodes, small for fast walks, and its leaves' nodes apart.
pub struct Quadtree {
    nodes: Vec<TreeNode>,
    /// The leaves' nodes, with those of leaves since split.
    leaves: Vec<Node>,
    /// The number of leaves.
    live: usize,
}

impl Quadtree {
    /// The tree of the root box alone, not yet a leaf.
    pub fn new(root: IBox) -> Self {
        Quadtree {
            nodes: vec![TreeNode {
                ib: root,
                parent: NONE,
                quarters: NONE,
                leaf: NONE,
            }],
            leaves: Vec::new(),
            live: 0,
        }
    }

    /// The number of leaves.
    pub fn leaf_count(&self) -> usize {
        self.live
    }

    /// Makes node `at` a leaf with node `n` (of its box).
    pub fn set_leaf(&mut self, at: u32, n: Node) {
        self.nodes[at as usize].leaf = self.leaves.len() as u32;
        self.leaves.push(n);
        self.live += 1;
    }

    /// Ids are below this.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Appends the four quarters of node `at` (as [`super::refine::Ctx::split`]
    /// cuts), without leaves; returns the first one's id.
    pub fn add_quarters(&mut self, at: u32) -> u32 {
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
                parent: at,
                quarters: NONE,
                leaf: NONE,
            });
        }
        self.nodes[at as usize].quarters
    }

    /// Which sides of node `at` (in the order of [`SIDES`]) face one of its siblings:
    /// two for a quarter (the lower left quarter's right and top sides, …), none for
    /// the root.
    pub fn sibling_sides(&self, at: u32) -> [bool; 4] {
        let parent = self.nodes[at as usize].parent;
        if parent == NONE {
            return [false; 4];
        }
        let q = at - self.nodes[parent as usize].quarters;
        let (right, upper) = (q & 1 == 1, q >> 1 == 1);
        [right, !right, upper, !upper]
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

    /// The leaf holding lattice point `p`, searched from node `from` up to the first
    /// ancestor that holds it; `None` outside the root box.
    pub fn locate_from(&self, from: u32, p: [u64; 2]) -> Option<u32> {
        let holds = |ib: &IBox| (0..2).all(|k| ib.lo[k] <= p[k] && p[k] < ib.hi[k]);
        if !holds(&self.nodes[0].ib) {
            return None;
        }
        let mut at = from;
        while !holds(&self.nodes[at as usize].ib) {
            at = self.nodes[at as usize].parent;
        }
        while self.nodes[at as usize].quarters != NONE {
            at = self.quarter_of(at, p);
        }
        Some(at)
    }

    /// Node `at`'s box in lattice coordinates.
    pub fn ib(&self, at: u32) -> IBox {
        self.nodes[at as usize].ib
    }

    /// The extent of node `at`'s box in lattice units.
    pub fn extent(&self, at: u32) -> [u64; 2] {
        let ib = &self.nodes[at as usize].ib;
        [ib.hi[0] - ib.lo[0], ib.hi[1] - ib.lo[1]]
    }

    /// The node of leaf `at`, `None` for an inner node.
    pub fn leaf(&self, at: u32) -> Option<&Node> {
        let k = self.nodes[at as usize].leaf;
        (k != NONE).then(|| &self.leaves[k as usize])
    }

    /// The ids of the leaves, in the order of their ids.
    pub fn leaf_ids(&self) -> Vec<u32> {
        (0..self.nodes.len() as u32)
            .filter(|&i| self.nodes[i as usize].leaf != NONE)
            .collect()
    }

    /// The ids of the leaves in depth-first order, quarters in order.
    pub fn depth_first(&self) -> Vec<u32> {
        let mut out = Vec::new();
        let mut stack = vec![0u32];
        while let Some(at) = stack.pop() {
            let t = &self.nodes[at as usize];
            if t.leaf != NONE {
                out.push(at);
            } else if t.quarters != NONE {
                stack.extend((t.quarters..t.quarters + 4).rev());
            }
        }
        out
    }

    /// Replaces leaf `at` by its `quarters`; returns their ids.
    pub fn split(&mut self, at: u32, quarters: [Node; 4]) -> std::ops::Range<u32> {
        self.nodes[at as usize].leaf = NONE;
        self.live -= 1;
        let first = self.add_quarters(at);
        for (k, n) in quarters.into_iter().enumerate() {
            self.set_leaf(first + k as u32, n);
        }
        first..first + 4
    }

    /// The leaves in depth-first order (quarters in order), each with the node
    /// across each of its sides (in the order of [`SIDES`]; `None` on the root box's
    /// boundary) that holds the whole side's length: the neighbour of the same depth,
    /// or a larger leaf. Passed down from parent to quarters (a quarter's neighbours
    /// are its siblings or the quarters of its parent's neighbours), so no look-up
    /// climbs the tree, and the walk visits the tree in the order it was built.
    pub fn leaves_with_neighbours(&self, mut visit: impl FnMut(u32, [Option<u32>; 4])) {
        let mut stack = vec![(0u32, [None; 4])];
        while let Some((at, across)) = stack.pop() {
            let first = self.nodes[at as usize].quarters;
            if first == NONE {
                if self.nodes[at as usize].leaf != NONE {
                    visit(at, across);
                }
                continue;
            }
            // the quarter of a same-depth neighbour, or the larger leaf itself
            let quarter_of = |n: Option<u32>, q: u32| match n {
                Some(n) if self.nodes[n as usize].quarters != NONE => {
                    Some(self.nodes[n as usize].quarters + q)
                }
                other => other,
            };
            for q in (0..4u32).rev() {
                let (right, upper) = (q & 1, q >> 1);
                let sibling = |r: u32, u: u32| Some(first + r + 2 * u);
                let quarter = [
                    if right == 1 {
                        sibling(0, upper)
                    } else {
                        quarter_of(across[0], 1 + 2 * upper)
                    },
                    if right == 0 {
                        sibling(1, upper)
                    } else {
                        quarter_of(across[1], 2 * upper)
                    },
                    if upper == 1 {
                        sibling(right, 0)
                    } else {
                        quarter_of(across[2], right + 2)
                    },
                    if upper == 0 {
                        sibling(right, 1)
                    } else {
                        quarter_of(across[3], right)
                    },
                ];
                stack.push((first + q, quarter));
            }
        }
    }

    /// Appends the segments of leaf `x`'s boundary to `out`, in the order of
    /// [`SIDES`], each side from its lower end; the leaves across are found by
    /// climbing from `x` to the first ancestor holding the point just across each side.
    pub fn side_segments(&self, x: u32, lattice: &Lattice, out: &mut Vec<SideSegment>) {
        let ib = self.nodes[x as usize].ib;
        let holds = |at: u32, p: [u64; 2]| {
            let b = &self.nodes[at as usize].ib;
            (0..2).all(|k| b.lo[k] <= p[k] && p[k] < b.hi[k])
        };
        let starts = SIDES.map(|side| {
            let across = self.across(&ib, side)?;
            let mut p = [0u64; 2];
            p[side.axis] = across;
            p[1 - side.axis] = ib.lo[1 - side.axis];
            let mut at = x;
            while !holds(at, p) {
                at = self.nodes[at as usize].parent;
            }
            Some(at)
        });
        self.side_segments_from(x, starts, lattice, out);
    }

    /// The lattice coordinate just across `side` of box `ib` on the side's axis,
    /// `None` on the root box's boundary.
    fn across(&self, ib: &IBox, side: Side) -> Option<u64> {
        let root = &self.nodes[0].ib;
        let a = side.axis;
        if side.high {
            (ib.hi[a] < root.hi[a]).then_some(ib.hi[a])
        } else {
            (ib.lo[a] > root.lo[a]).then(|| ib.lo[a] - 1)
        }
    }

    /// [`Self::side_segments`] from `starts`: for each side, a node holding the
    /// lattice points just across it along its whole length (`None` on the root box's
    /// boundary), whose leaves on that line are the side's neighbours.
    pub fn side_segments_from(
        &self,
        x: u32,
        starts: [Option<u32>; 4],
        lattice: &Lattice,
        out: &mut Vec<SideSegment>,
    ) {
        let ib = self.nodes[x as usize].ib;
        // the box's plane coordinates, each converted once
        let lo_at = [lattice.coord(0, ib.lo[0]), lattice.coord(1, ib.lo[1])];
        let hi_at = [lattice.coord(0, ib.hi[0]), lattice.coord(1, ib.hi[1])];
        for (s, side) in SIDES.iter().enumerate() {
            let (a, along) = (side.axis, 1 - side.axis);
            let line_at = if side.high { hi_at[a] } else { lo_at[a] };
            let (lo, hi) = (ib.lo[along], ib.hi[along]);
            let at = |t: f64| {
                if a == 0 {
                    Point::new(line_at, t)
                } else {
                    Point::new(t, line_at)
                }
            };
            let point = |t: u64| {
                if t == lo {
                    at(lo_at[along])
                } else if t == hi {
                    at(hi_at[along])
                } else {
                    at(lattice.coord(along, t))
                }
            };
            let (Some(start), Some(across)) = (starts[s], self.across(&ib, *side)) else {
                out.push(SideSegment {
                    id: 4 * x + s as u32,
                    from: point(lo),
                    to: point(hi),
                    other: None,
                });
                continue;
            };
            // the side of the neighbour facing this one
            let facing = (s ^ 1) as u32;
            // the leaves holding the line `across` within [lo, hi), in increasing order
            let mut stack: smallvec::SmallVec<[u32; 64]> = smallvec::smallvec![start];
            while let Some(n) = stack.pop() {
                let t = &self.nodes[n as usize];
                let (nlo, nhi) = (t.ib.lo[along], t.ib.hi[along]);
                if t.quarters != NONE {
                    let column = u32::from(across >= t.ib.lo[a] + (t.ib.hi[a] - t.ib.lo[a]) / 2);
                    let quarter = |upper: u32| {
                        t.quarters
                            + if a == 0 {
                                column + 2 * upper
                            } else {
                                upper + 2 * column
                            }
                    };
                    let mid = nlo + (nhi - nlo) / 2;
                    if hi > mid {
                        stack.push(quarter(1));
                    }
                    if lo < mid {
                        stack.push(quarter(0));
                    }
                    continue;
                }
                if nlo <= lo && hi <= nhi {
                    // one neighbour along the whole side
                    let id = if (nlo, nhi) == (lo, hi) && !side.high {
                        4 * n + facing
                    } else {
                        4 * x + s as u32
                    };
                    out.push(SideSegment {
                        id,
                        from: point(lo),
                        to: point(hi),
                        other: Some(n),
                    });
                    break;
                }
                out.push(SideSegment {
                    id: 4 * n + facing,
                    from: point(nlo),
                    to: point(nhi),
                    other: Some(n),
                });
            }
        }
    }
}
