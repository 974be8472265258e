//! The construction rounds over the quadtree of the leaves: each round resolves the
//! leaves without an output (all of them in the first round; then the quarters of the
//! leaves split in the round before and their neighbours, whose sides those splits
//! cut) and splits the leaves whose nodes fit no pattern. Every other leaf has the
//! same sides, neighbours and nodes as when it was resolved, hence the same output:
//! its ports name their segments by [`SideSegment::id`], which stays the same while
//! neither leaf of the segment is split.

use super::construct::{segment_nodes, Resolver};
use super::quadtree::{Quadtree, SideSegment};
use super::refine::Ctx;
use crate::control::Watch;
use crate::error::Error;
use crate::geom::Point;
use crate::subdivision::resolve::{End, FoundVertex, LeafOutput, Piece, Port, PortId};
use std::ops::Range;

/// Rounds of local splitting of unresolved boxes before the cut-off decides.
const MAX_ROUNDS: usize = 48;

/// What the rounds leave: the leaves in depth-first order, their outputs joined in
/// that order into one (each leaf's vertex numbers moved past the vertices before
/// it, as [`crate::subdivision::assemble::assemble`] numbers them), the number of
/// leaves split and the number of rounds after the first.
pub struct Constructed {
    pub order: Vec<u32>,
    pub output: LeafOutput,
    pub local_splits: usize,
    pub rounds: usize,
}

/// The via nodes of the segments met in one round, each computed once: `slot[id]`
/// indexes `ranges`, whose range of `nodes` are the segment's nodes in order.
struct NodeCache {
    slot: Vec<u32>,
    ranges: Vec<(u32, u32, u32)>,
    nodes: Vec<(Point, [u32; 2])>,
}

const UNSEEN: u32 = u32::MAX;

/// A tree node's state in [`Outputs::state`]: not resolved (an inner node, or a leaf
/// to resolve this round), or resolved with an empty output; other values index
/// [`Outputs::kept`].
const UNRESOLVED: u32 = u32::MAX;
const EMPTY: u32 = u32::MAX - 1;

/// The outputs of the resolved leaves: a state per tree node, four bytes, and the
/// outputs that are not empty apart (a slot per node would be 56 bytes for each of
/// the million nodes at 10^4 segments, nearly all empty), their pieces and vertices
/// in one store (not two vectors a leaf: allocating and freeing those took about a
/// tenth of the run).
#[derive(Default)]
struct Outputs {
    state: Vec<u32>,
    kept: Vec<Kept>,
    pieces: Vec<Piece>,
    vertices: Vec<FoundVertex>,
}

/// A kept output: its ranges in [`Outputs::pieces`] and [`Outputs::vertices`].
struct Kept {
    pieces: Range<usize>,
    vertices: Range<usize>,
    uncertified: u32,
}

impl Outputs {
    /// Keeps leaf `x`'s `output`, emptying it.
    fn set(&mut self, x: u32, output: &mut LeafOutput) {
        let empty = output.pieces.is_empty()
            && output.vertices.is_empty()
            && output.uncertified == 0
            && output.local_splits == 0;
        self.state[x as usize] = if empty {
            EMPTY
        } else {
            let (p, v) = (self.pieces.len(), self.vertices.len());
            self.pieces.append(&mut output.pieces);
            self.vertices.append(&mut output.vertices);
            self.kept.push(Kept {
                pieces: p..self.pieces.len(),
                vertices: v..self.vertices.len(),
                uncertified: output.uncertified,
            });
            (self.kept.len() - 1) as u32
        };
    }

    /// Forgets leaf `x`'s output (its pieces stay in the store, unused).
    fn reset(&mut self, x: u32) {
        self.state[x as usize] = UNRESOLVED;
    }

    /// The outputs of the leaves `order`, joined in that order.
    fn join(mut self, order: &[u32]) -> LeafOutput {
        let mut out = LeafOutput::default();
        for &x in order {
            let k = match self.state[x as usize] {
                UNRESOLVED => panic!("every leaf is resolved"),
                EMPTY => continue,
                k => &self.kept[k as usize],
            };
            let base = out.vertices.len() as u32;
            let moved = |e: End| match e {
                End::Vertex(v) => End::Vertex(base + v),
                port => port,
            };
            out.pieces
                .extend(self.pieces[k.pieces.clone()].iter_mut().map(|p| Piece {
                    pair: p.pair,
                    ends: p.ends.map(moved),
                    points: std::mem::take(&mut p.points),
                }));
            out.vertices
                .extend(
                    self.vertices[k.vertices.clone()]
                        .iter_mut()
                        .map(|v| FoundVertex {
                            at: v.at,
                            sites: std::mem::take(&mut v.sites),
                        }),
                );
            out.uncertified += k.uncertified;
        }
        out
    }
}

impl NodeCache {
    /// The range in `nodes` of segment `s`'s nodes, computed on the first request.
    fn of(
        &mut self,
        s: &SideSegment,
        leaf_set: &[u32],
        tree: &Quadtree,
        resolver: &Resolver,
        scratch: &mut Scratch,
    ) -> std::ops::Range<usize> {
        let id = s.id as usize;
        if self.slot.len() <= id {
            self.slot.resize(id + 1, UNSEEN);
        }
        if self.slot[id] == UNSEEN {
            let cands: &[u32] = match s.other {
                Some(n) => {
                    let other = &tree.leaf(n).expect("neighbours are leaves").bs.set;
                    scratch.cands.clear();
                    scratch.cands.extend(
                        leaf_set
                            .iter()
                            .filter(|f| other.binary_search(f).is_ok())
                            .copied(),
                    );
                    &scratch.cands
                }
                None => leaf_set,
            };
            let start = self.nodes.len() as u32;
            segment_nodes(
                resolver.poly,
                cands,
                s.from,
                s.to,
                &resolver.tol,
                &mut scratch.crossings,
                &mut self.nodes,
            );
            self.slot[id] = self.ranges.len() as u32;
            self.ranges.push((s.id, start, self.nodes.len() as u32));
        }
        let (_, a, b) = self.ranges[self.slot[id] as usize];
        a as usize..b as usize
    }

    /// Forgets the round's segments (their leaves may be split before the next).
    fn clear(&mut self) {
        for &(id, _, _) in &self.ranges {
            self.slot[id as usize] = UNSEEN;
        }
        self.ranges.clear();
        self.nodes.clear();
    }
}

/// Buffers reused from segment to segment.
#[derive(Default)]
struct Scratch {
    cands: Vec<u32>,
    crossings: Vec<(f64, Point, [u32; 2])>,
    sides: Vec<SideSegment>,
    ports: Vec<Port>,
}

/// One round's resolution of leaves: their ports from their side segments' via
/// nodes (each segment's computed once), then the patterns.
struct Round<'a> {
    ctx: &'a Ctx<'a>,
    resolver: &'a Resolver<'a>,
    cache: &'a mut NodeCache,
    scratch: &'a mut Scratch,
    outputs: &'a mut Outputs,
    /// The output of the leaf being resolved, its buffers reused.
    output: LeafOutput,
    /// The leaves whose nodes fit no pattern, to split.
    marked: Vec<u32>,
    /// The last round: boxes are not split.
    last: bool,
}

impl Round<'_> {
    /// Resolves leaf `x`, its side segments put in `out` by `sides`.
    fn leaf(&mut self, tree: &Quadtree, x: u32, sides: impl FnOnce(&mut Vec<SideSegment>)) {
        let n = tree.leaf(x).expect("rounds resolve leaves");
        if !n.candidate() {
            // no pair of features, so no node on any side
            self.outputs.state[x as usize] = EMPTY;
            return;
        }
        let scratch = &mut *self.scratch;
        let mut segments = std::mem::take(&mut scratch.sides);
        segments.clear();
        sides(&mut segments);
        let mut ports = std::mem::take(&mut scratch.ports);
        ports.clear();
        for s in &segments {
            let range = self.cache.of(s, &n.bs.set, tree, self.resolver, scratch);
            for (k, &(at, pair)) in self.cache.nodes[range].iter().enumerate() {
                ports.push(Port {
                    id: PortId::Segment {
                        segment: s.id,
                        index: k as u32,
                    },
                    at,
                    pair,
                });
            }
        }
        scratch.sides = segments;
        let can_split = !self.last && self.ctx.can_split(&tree.ib(x), n);
        match self
            .resolver
            .resolve(n, &ports, can_split, &mut self.output)
        {
            Ok(()) => self.outputs.set(x, &mut self.output),
            Err(_) => self.marked.push(x),
        }
        scratch.ports = ports;
    }
}

/// Resolves the leaves of `tree`, splitting those whose nodes fit no pattern (not
/// balanced again: the construction takes sides of any number of segments) until all
/// are resolved or the cut-off or [`MAX_ROUNDS`] decides. The first round walks the
/// whole tree, each leaf with its neighbours passed down
/// ([`Quadtree::leaves_with_neighbours`]); later rounds find the few leaves to resolve
/// again and their neighbours by climbing.
pub fn construct(
    ctx: &Ctx,
    resolver: &Resolver,
    tree: &mut Quadtree,
    watch: &Watch,
) -> Result<Constructed, Error> {
    let mut outputs = Outputs::default();
    let mut cache = NodeCache {
        slot: Vec::new(),
        ranges: Vec::new(),
        nodes: Vec::new(),
    };
    let mut scratch = Scratch::default();
    let mut local_splits = 0;
    let mut rounds = 0;
    loop {
        watch.check()?;
        outputs.state.resize(tree.len(), UNRESOLVED);
        let mut round = Round {
            ctx,
            resolver,
            cache: &mut cache,
            scratch: &mut scratch,
            outputs: &mut outputs,
            output: LeafOutput::default(),
            marked: Vec::new(),
            last: rounds >= MAX_ROUNDS || ctx.budget.exhausted(),
        };
        if rounds == 0 {
            let tree: &Quadtree = tree;
            tree.leaves_with_neighbours(|x, across| {
                round.leaf(tree, x, |out| {
                    tree.side_segments_from(x, across, ctx.lattice, out)
                })
            });
        } else {
            let todo: Vec<u32> = tree
                .leaf_ids()
                .into_iter()
                .filter(|&x| round.outputs.state[x as usize] == UNRESOLVED)
                .collect();
            for x in todo {
                round.leaf(tree, x, |out| tree.side_segments(x, ctx.lattice, out));
            }
        }
        // in the order of their ids, as the later rounds list them
        let mut marked = round.marked;
        marked.sort_unstable();
        cache.clear();
        if marked.is_empty() {
            break;
        }
        for &x in &marked {
            scratch.sides.clear();
            tree.side_segments(x, ctx.lattice, &mut scratch.sides);
            for s in &scratch.sides {
                if let Some(n) = s.other {
                    outputs.reset(n);
                }
            }
        }
        for &x in &marked {
            if !ctx.budget.take_box() {
                continue;
            }
            let n = tree.leaf(x).expect("marked leaves are leaves");
            if let Some(quarters) = ctx.split(&tree.ib(x), n) {
                tree.split(x, quarters);
                local_splits += 1;
            }
        }
        rounds += 1;
    }
    let order = tree.depth_first();
    let output = outputs.join(&order);
    Ok(Constructed {
        order,
        output,
        local_splits,
        rounds,
    })
}
