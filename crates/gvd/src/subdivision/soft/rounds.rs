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
use crate::subdivision::resolve::{LeafOutput, Port, PortId};

/// Rounds of local splitting of unresolved boxes before the cut-off decides.
const MAX_ROUNDS: usize = 48;

/// What the rounds leave: the leaves in depth-first order and their outputs, the
/// number of leaves split and the number of rounds after the first.
pub struct Constructed {
    pub order: Vec<u32>,
    pub outputs: Vec<LeafOutput>,
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

/// Resolves the leaves of `tree`, splitting those whose nodes fit no pattern (not
/// balanced again: the construction takes sides of any number of segments) until all
/// are resolved or the cut-off or [`MAX_ROUNDS`] decides.
pub fn construct(
    ctx: &Ctx,
    resolver: &Resolver,
    tree: &mut Quadtree,
    watch: &Watch,
) -> Result<Constructed, Error> {
    let mut kept: Vec<Option<LeafOutput>> = Vec::new();
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
        kept.resize_with(tree.len(), || None);
        let todo: Vec<u32> = tree
            .leaf_ids()
            .into_iter()
            .filter(|&x| kept[x as usize].is_none())
            .collect();
        let last = rounds >= MAX_ROUNDS || ctx.budget.exhausted();
        let mut marked = Vec::new();
        for &x in &todo {
            let n = tree.leaf(x).expect("todo holds leaves");
            if !n.candidate() {
                // no pair of features, so no node on any side
                kept[x as usize] = Some(LeafOutput::default());
                continue;
            }
            scratch.sides.clear();
            tree.side_segments(x, ctx.lattice, &mut scratch.sides);
            let mut ports = std::mem::take(&mut scratch.ports);
            ports.clear();
            let sides = std::mem::take(&mut scratch.sides);
            for s in &sides {
                let range = cache.of(s, &n.bs.set, tree, resolver, &mut scratch);
                for (k, &(at, pair)) in cache.nodes[range].iter().enumerate() {
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
            scratch.sides = sides;
            let can_split = !last && ctx.can_split(n);
            match resolver.resolve(n, &ports, can_split) {
                Ok(output) => kept[x as usize] = Some(output),
                Err(_) => marked.push(x),
            }
            scratch.ports = ports;
        }
        cache.clear();
        if marked.is_empty() {
            break;
        }
        for &x in &marked {
            scratch.sides.clear();
            tree.side_segments(x, ctx.lattice, &mut scratch.sides);
            for s in &scratch.sides {
                if let Some(n) = s.other {
                    kept[n as usize] = None;
                }
            }
        }
        for &x in &marked {
            if !ctx.budget.take_box() {
                continue;
            }
            let n = tree.leaf(x).expect("marked leaves are leaves");
            if let Some(quarters) = ctx.split(n) {
                tree.split(x, quarters);
                local_splits += 1;
            }
        }
        rounds += 1;
    }
    let order = tree.depth_first();
    let outputs = order
        .iter()
        .map(|&x| kept[x as usize].take().expect("every leaf is resolved"))
        .collect();
    Ok(Constructed {
        order,
        outputs,
        local_splits,
        rounds,
    })
}
