//! From the segment engine's raw graph to the [`VoronoiComplex`] of the scene's mode
//! (see the parent module's doc): labels, kept edges, chains, their polylines, insides
//! and clipping.

use super::phases::Phases;
use super::Generators;
use crate::complex::{BisectorPiece, Edge, Generator, SmallVec, Vertex, VoronoiComplex};
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, Point};
use crate::incremental::segments_arcs::{joints, Gen, RawEdge, RawVertex, SegmentDiagram};
use crate::par::{filter_map_range, join, map_range};
use crate::scene::{Mode, Scene};
use crate::Error;
use rustc_hash::FxHashMap;

/// An output edge before it is drawn: its kept edges in order (a range of the
/// walk's links) and its end vertices (`None` for a closed loop). Its labels are its
/// first edge's.
struct Chain {
    links: std::ops::Range<usize>,
    from: Option<usize>,
    to: Option<usize>,
}

/// A step of a chain: a kept edge, and whether it is walked from its `ends[0]`.
type Link = (usize, bool);

/// The part of a chain that one raw edge contributed: from the chain's segment `start`
/// (between points `start` and `start + 1`) to the next stretch's, on the bisector of
/// `gens`.
#[derive(Clone, Copy)]
pub(super) struct Stretch {
    pub(super) start: usize,
    pub(super) gens: [Gen; 2],
}

/// A raw edge kept for the output, its ends merged across zero-length edges.
struct Kept {
    gens: [Gen; 2],
    ends: [u32; 2],
    /// The graph's half-edge from `ends[0]` to `ends[1]`.
    half: u32,
    /// See [`RawEdge::on_normal`].
    on_normal: Option<u32>,
}

/// The labels of the vertices merged across zero-length edges (at their roots in `root`;
/// none for the others), in the order of the raw vertices and their generators, each
/// once: first the generators' names, then the other owners of shared points.
struct Labels {
    /// Root `r`'s labels are `items[start[r]..start[r] + len[r]]`.
    start: Vec<usize>,
    len: Vec<usize>,
    /// How many of them are names (the rest are other owners of shared points).
    named: Vec<usize>,
    items: Vec<Generator>,
}

impl Labels {
    fn of(g: &Generators, mode: Mode, raw: &[RawVertex], root: &[u32]) -> Labels {
        let nv = raw.len();
        let root = |v: usize| root[v] as usize;
        // Room for every generator of the vertices merged into each root.
        let mut start = vec![0usize; nv + 1];
        for (v, rv) in raw.iter().enumerate() {
            start[root(v) + 1] += rv.gens.iter().map(|&x| g.label_count(x)).sum::<usize>();
        }
        for v in 0..nv {
            start[v + 1] += start[v];
        }
        let mut labels = Labels {
            items: vec![Generator::Site(0); start[nv]],
            len: vec![0; nv],
            named: vec![0; nv],
            start,
        };
        let add = |labels: &mut Labels, r: usize, l: Generator| {
            if !labels.of_vertex(r).contains(&l) {
                labels.items[labels.start[r] + labels.len[r]] = l;
                labels.len[r] += 1;
            }
        };
        for (v, rv) in raw.iter().enumerate() {
            for &gen in &rv.gens {
                add(&mut labels, root(v), g.label(gen, mode));
            }
        }
        labels.named.copy_from_slice(&labels.len);
        for (v, rv) in raw.iter().enumerate() {
            for &gen in &rv.gens {
                if let Gen::Point(p) = gen {
                    for l in g.also_labels(p, mode) {
                        add(&mut labels, root(v), l);
                    }
                }
            }
        }
        labels
    }

    fn of_vertex(&self, v: usize) -> &[Generator] {
        &self.items[self.start[v]..self.start[v] + self.len[v]]
    }
}

/// The kept edges around each vertex, in the order of the edges (an edge from a
/// vertex to itself twice), as one flat list.
struct Incident {
    /// Vertex `v`'s edges are `edges[start[v]..start[v + 1]]`.
    start: Vec<u32>,
    edges: Vec<u32>,
}

impl Incident {
    fn of(kept: &[Kept], nv: usize) -> Incident {
        let mut start = vec![0u32; nv + 1];
        for e in kept {
            start[e.ends[0] as usize + 1] += 1;
            start[e.ends[1] as usize + 1] += 1;
        }
        for v in 0..nv {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut edges = vec![0u32; start[nv] as usize];
        for (k, e) in kept.iter().enumerate() {
            for v in e.ends.map(|v| v as usize) {
                edges[fill[v] as usize] = k as u32;
                fill[v] += 1;
            }
        }
        Incident { start, edges }
    }

    fn around(&self, v: usize) -> &[u32] {
        &self.edges[self.start[v] as usize..self.start[v + 1] as usize]
    }
}

/// Chains the kept edges through the vertices that join two labels and two kept
/// edges, away from the sites: one chain from every node (a vertex of three or more
/// named labels, not two kept edges, or `on_site`, as a tangent joint on its normal)
/// along each of its unused edges, then the closed loops left. Returns the chains and
/// the links they range over.
fn chain_edges(
    kept: &[Kept],
    incident: &Incident,
    labels: &Labels,
    on_site: impl Fn(usize) -> bool + Sync,
) -> (Vec<Chain>, Vec<Link>) {
    let nv = labels.len.len();
    let node = map_range(nv, 1 << 12, |v| {
        labels.named[v] >= 3 || incident.around(v).len() != 2 || on_site(v)
    });
    let mut used = vec![false; kept.len()];
    let mut chains: Vec<Chain> = Vec::new();
    let mut links: Vec<Link> = Vec::with_capacity(kept.len());
    // Walks from vertex `from` along `start_edge` to a node or back to the start of a
    // closed loop, recording the links; returns the last vertex.
    let walk = |start_edge: usize, from: usize, used: &mut [bool], links: &mut Vec<Link>| {
        let (mut e, mut v) = (start_edge, from);
        loop {
            used[e] = true;
            let forward = kept[e].ends[0] as usize == v;
            links.push((e, forward));
            v = kept[e].ends[usize::from(forward)] as usize;
            if node[v] {
                return v;
            }
            match incident.around(v).iter().find(|&&k| !used[k as usize]) {
                Some(&k) => e = k as usize,
                None => return v, // closed loop
            }
        }
    };
    for v in (0..nv).filter(|&v| node[v]) {
        for &k in incident.around(v) {
            let k = k as usize;
            if used[k] {
                continue;
            }
            let start = links.len();
            let end = walk(k, v, &mut used, &mut links);
            chains.push(Chain {
                links: start..links.len(),
                from: Some(v),
                to: Some(end),
            });
        }
    }
    for k in 0..kept.len() {
        if !used[k] {
            let start = links.len();
            walk(k, kept[k].ends[0] as usize, &mut used, &mut links);
            chains.push(Chain {
                links: start..links.len(),
                from: None,
                to: None,
            });
        }
    }
    (chains, links)
}

/// The complex of `diagram` (the diagram of `g`'s generators) in the scene's mode, in
/// four phases: the raw graph with its tangent joints contracted and its zero-length
/// edges merged ([`merge_raw`]); the labels and the kept edges ([`keep_edges`]); the
/// chains of kept edges, drawn, kept by the insides and clipped ([`Drawing::clip`]);
/// and the output edges and vertices, numbered in order ([`number`]).
pub(super) fn assemble(
    g: &Generators,
    scene: &Scene,
    diagram: &SegmentDiagram,
    bisectors: bool,
    phases: &mut Phases,
) -> Result<VoronoiComplex, Error> {
    let mode = scene.mode();
    let tol = scene.epsilon() / 4.0;
    let merged = merge_raw(g, scene, diagram, tol, phases)?;
    let (labels, kept, incident) = keep_edges(g, mode, &merged);
    let Merged {
        joints,
        raw_vertices,
        raw_edges,
        root,
    } = merged;
    drop((raw_edges, root));
    // Where an edge ends on a site (a corner), the two distance fields are not
    // differentiable; the polyline stops a hair (1e-9 of the domain, at most epsilon/8)
    // short of it.
    let domain = scene.domain();
    let hair = 1e-9 * domain.longest_side();
    let (chains, links) = chain_edges(&kept, &incident, &labels, |v| raw_vertices[v].t <= hair);
    let drawing = Drawing {
        g,
        mode,
        diagram,
        tol,
        hair,
        domain,
        bisectors,
        joints: &joints,
        raw_vertices: &raw_vertices,
        kept: &kept,
        links: &links,
    };
    let clipped = map_range(chains.len(), 1 << 10, |c| drawing.clip(&chains[c]));
    Ok(number(clipped, &raw_vertices, &labels, &domain))
}

/// The raw graph with the tips of its tangent joints contracted and the vertices joined
/// by zero-length edges merged (`root[v]` is the vertex `v` merged into).
struct Merged {
    joints: FxHashMap<u32, joints::Joint>,
    raw_vertices: Vec<RawVertex>,
    raw_edges: Vec<RawEdge>,
    root: Vec<u32>,
}

/// Phase 1: the engine's raw graph (edges shown in the mode, and those at tangent
/// joints), the joints' tips contracted, zero-length edges merged.
fn merge_raw(
    g: &Generators,
    scene: &Scene,
    diagram: &SegmentDiagram,
    tol: f64,
    phases: &mut Phases,
) -> Result<Merged, Error> {
    let mode = scene.mode();
    let joints = joints::tangent_joints(&g.points, &g.segments, &g.arcs);
    let at_joint = |x: Gen| matches!(x, Gen::Point(p) if joints.contains_key(&p));
    let (mut raw_vertices, mut raw_edges) = diagram.raw(tol, |a, b| {
        g.shown(a, b, mode) || at_joint(a) || at_joint(b)
    })?;
    phases.end("raw");
    let nv = raw_vertices.len();
    // Contracting a tip moves edge ends by its length: at most epsilon/8 (tips are
    // points up to rounding, which grows where the sliver's sides meet a bisector at
    // a shallow angle far out).
    let tip_tol = scene.epsilon() / 8.0;
    let length = |e: &RawEdge| {
        let mut points = Vec::new();
        diagram.polyline(e.half, tol, &mut points);
        points.windows(2).map(|w| w[0].dist(w[1])).sum()
    };
    // In voronoi mode a segment's zone boundary at an end that another site names is
    // drawn; where it has no length but rounding's (about 1e-12 at a fan of segments
    // from one point) its ends are one vertex.
    if mode == Mode::Voronoi {
        for e in raw_edges.iter_mut() {
            if !e.zero && g.is_separator(e.gens[0], e.gens[1]) && length(e) <= tip_tol {
                e.zero = true;
            }
        }
    }
    let tips = joints::collapse(&joints, tip_tol, &mut raw_vertices, &mut raw_edges, length);
    // Vertices joined by zero-length edges are one vertex, and so are the vertices
    // of a tangent joint's tip.
    let mut sets = DisjointSets::new(nv);
    let zero_ends = raw_edges.iter().filter(|e| e.zero).map(|e| e.ends);
    for [a, b] in zero_ends.chain(tips) {
        sets.union(a, b);
    }
    let root: Vec<u32> = sets.roots().into_iter().map(|r| r as u32).collect();
    Ok(Merged {
        joints,
        raw_vertices,
        raw_edges,
        root,
    })
}

/// Phase 2: the labels (sequential), side by side with the kept edges (shown, of
/// positive length, a merged vertex at its root) and the edges around each vertex.
fn keep_edges(g: &Generators, mode: Mode, m: &Merged) -> (Labels, Vec<Kept>, Incident) {
    let nv = m.raw_vertices.len();
    let (labels, (kept, incident)) = join(
        || Labels::of(g, mode, &m.raw_vertices, &m.root),
        || {
            let kept: Vec<Kept> = filter_map_range(m.raw_edges.len(), 1 << 12, |k| {
                let e = &m.raw_edges[k];
                (!e.zero && g.shown(e.gens[0], e.gens[1], mode)).then(|| Kept {
                    gens: e.gens,
                    ends: e.ends.map(|v| m.root[v]),
                    half: e.half,
                    on_normal: e.on_normal,
                })
            });
            let incident = Incident::of(&kept, nv);
            (kept, incident)
        },
    );
    (labels, kept, incident)
}

/// A clipped piece of a chain: its polyline, whether the domain cut its start and its
/// end, and its exact bisector (empty unless asked for).
type Piece = (SmallVec<[Point; 2]>, bool, bool, Vec<BisectorPiece>);

/// A chain kept by the insides: its clipped pieces, its end vertices and its labels.
type Clipped = (Vec<Piece>, Option<usize>, Option<usize>, [Generator; 2]);

/// What phase 3 reads to draw and clip a chain.
struct Drawing<'a> {
    g: &'a Generators,
    mode: Mode,
    diagram: &'a SegmentDiagram,
    tol: f64,
    hair: f64,
    domain: Aabb,
    bisectors: bool,
    joints: &'a FxHashMap<u32, joints::Joint>,
    raw_vertices: &'a [RawVertex],
    kept: &'a [Kept],
    links: &'a [Link],
}

impl Drawing<'_> {
    /// A chain's polyline: its edges' polylines in order (each projected onto its
    /// tangent joint's normal if it lies on one), from their ends' merged vertices, with
    /// the stretches they make.
    fn draw(&self, chain: &Chain) -> (SmallVec<[Point; 2]>, Vec<Stretch>) {
        // Inline for a straight edge: no heap allocation.
        let mut points: SmallVec<[Point; 2]> = SmallVec::new();
        let (mut stretches, mut edge) = (Vec::new(), Vec::new());
        for &(k, forward) in &self.links[chain.links.clone()] {
            let e = &self.kept[k];
            edge.clear();
            self.diagram.polyline(e.half, self.tol, &mut edge);
            if let Some(p) = e.on_normal {
                let joint = &self.joints[&p];
                edge.iter_mut().for_each(|q| *q = joint.onto(*q));
            }
            let last = edge.len() - 1;
            edge[0] = self.raw_vertices[e.ends[0] as usize].at;
            edge[last] = self.raw_vertices[e.ends[1] as usize].at;
            if !forward {
                edge.reverse();
            }
            stretches.push(Stretch {
                start: points.len().saturating_sub(1),
                gens: e.gens,
            });
            let skip = usize::from(!points.is_empty());
            points.extend_from_slice(&edge[skip..]);
        }
        if chain.from.is_none() && points.first() != points.last() {
            points.push(points[0]);
        }
        (points, stretches)
    }

    /// Moves a polyline's first (or last) point a hair towards the next one, by at
    /// most `tol / 2` (epsilon/8: the end stays within epsilon of its vertex).
    fn pull(&self, points: &mut [Point], at_start: bool) {
        let n = points.len();
        let (end, next) = if at_start { (0, 1) } else { (n - 1, n - 2) };
        let (p, q) = (points[end], points[next]);
        let len = p.dist(q);
        if len > 0.0 {
            points[end] = p.lerp(q, (self.hair.min(0.5 * self.tol) / len).min(0.5));
        }
    }

    /// Phase 3, one chain: drawn, pulled off the sites it ends on, kept by the insides
    /// (`None` when the mode leaves it out), clipped to the domain.
    fn clip(&self, chain: &Chain) -> Option<Clipped> {
        let (g, mode, domain, hair) = (self.g, self.mode, &self.domain, self.hair);
        let Chain { from, to, .. } = *chain;
        let first = &self.kept[self.links[chain.links.start].0];
        let sites = first.gens.map(|x| g.label(x, mode));
        let (mut points, stretches) = self.draw(chain);
        if from.is_some_and(|v| self.raw_vertices[v].t <= hair) {
            self.pull(&mut points, true);
        }
        if to.is_some_and(|v| self.raw_vertices[v].t <= hair) {
            self.pull(&mut points, false);
        }
        let mid = (points.len() - 1) / 2;
        let probe = points[mid].lerp(points[mid + 1], 0.5);
        let keep = if mode == Mode::MedialAxis {
            g.inside_region(probe)
        } else {
            !g.inside_polygons(probe)
        };
        keep.then(|| {
            // Most chains lie wholly inside the domain: kept as they are.
            let whole = points.len() >= 2 && points.iter().all(|&p| domain.contains(p));
            let pieces = if whole {
                vec![(points, false, false, 0)]
            } else {
                let pieces = clip_polyline(&points, domain, self.tol).into_iter();
                pieces
                    .map(|(p, s, e, f)| (SmallVec::from_vec(p), s, e, f))
                    .collect()
            };
            let pieces = pieces
                .into_iter()
                .map(|(piece, start_cut, end_cut, first)| {
                    let form = if self.bisectors {
                        g.bisector(&piece, first, &stretches, hair)
                    } else {
                        Vec::new()
                    };
                    (piece, start_cut, end_cut, form)
                })
                .collect::<Vec<_>>();
            (pieces, from, to, sites)
        })
    }
}

/// Phase 4: the output edges in chain order, and the vertices numbered in the order the
/// edges first meet them (those inside the domain).
fn number(
    clipped: Vec<Option<Clipped>>,
    raw_vertices: &[RawVertex],
    labels: &Labels,
    domain: &Aabb,
) -> VoronoiComplex {
    let mut out = VoronoiComplex::default();
    // `shown` lists the output vertices' raw vertices in order.
    let mut out_index: Vec<Option<usize>> = vec![None; raw_vertices.len()];
    let mut shown: Vec<usize> = Vec::new();
    let mut vertex_out = |v: usize| -> Option<usize> {
        domain.contains(raw_vertices[v].at).then(|| {
            *out_index[v].get_or_insert_with(|| {
                shown.push(v);
                shown.len() - 1
            })
        })
    };
    out.edges.reserve(clipped.len());
    for (mut pieces, from, to, sites) in clipped.into_iter().flatten() {
        let closed_loop = from.is_none();
        // A closed loop cut by the domain whose first point is inside: its last piece
        // runs on into its first (the loop repeats its first point last).
        if closed_loop && pieces.len() >= 2 && !pieces[0].1 {
            let (last, start_cut, _, last_form) = pieces.pop().expect("two pieces");
            let first = &mut pieces[0];
            first.0 = last.into_iter().chain(first.0.drain(1..)).collect();
            first.1 = start_cut;
            first.3 = if last_form.is_empty() || first.3.is_empty() {
                Vec::new()
            } else {
                last_form.into_iter().chain(first.3.drain(..)).collect()
            };
        }
        for (piece, start_cut, end_cut, bisector) in pieces {
            let from = if start_cut || closed_loop {
                None
            } else {
                from.and_then(&mut vertex_out)
            };
            let to = if end_cut || closed_loop {
                None
            } else {
                to.and_then(&mut vertex_out)
            };
            out.edges.push(Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites,
                from,
                to,
                points: piece,
                bisector,
                parametric: Vec::new(),
            });
        }
    }
    out.vertices = map_range(shown.len(), 1 << 12, |k| {
        let v = shown[k];
        let mut sites: SmallVec<[Generator; 3]> = labels.of_vertex(v).iter().copied().collect();
        sites.sort();
        Vertex {
            clearance: None,
            at: raw_vertices[v].at,
            sites,
        }
    });
    out
}

/// The pieces of a polyline inside the closed box `b`, each with whether its start and
/// its end were cut by the box, and the index of the polyline's segment it starts on
/// (its segment `j` lies on the polyline's segment `first + j`). A cut at fraction `t`
/// of a segment is rounded by about `2^-52` of the segment's length: on segments so
/// long that this could exceed `tol / 16` (an edge to a vertex of a site 1e15 away) it
/// is measured from the segment's nearer end instead ([`Aabb::segment_part`]).
fn clip_polyline(points: &[Point], b: &Aabb, tol: f64) -> Vec<(Vec<Point>, bool, bool, usize)> {
    let long = tol / 16.0 / f64::EPSILON;
    let mut pieces = Vec::new();
    let mut cur: Vec<Point> = Vec::new();
    let (mut cur_cut, mut cur_first) = (false, 0);
    for (k, w) in points.windows(2).enumerate() {
        let part = if w[0].dist(w[1]) > long {
            b.segment_part(w[0], w[1])
        } else {
            b.segment_range(w[0], w[1]).map(|(t0, t1)| {
                let ends = [w[0].lerp(w[1], t0), w[0].lerp(w[1], t1)];
                (ends, [t0 > 0.0, t1 < 1.0])
            })
        };
        let Some(([p0, p1], [start_cut, end_cut])) = part else {
            if !cur.is_empty() {
                pieces.push((std::mem::take(&mut cur), cur_cut, true, cur_first));
            }
            continue;
        };
        if cur.is_empty() {
            cur.push(b.clamp(p0));
            (cur_cut, cur_first) = (start_cut, k);
        }
        cur.push(b.clamp(p1));
        if end_cut {
            pieces.push((std::mem::take(&mut cur), cur_cut, true, cur_first));
        }
    }
    if cur.len() >= 2 {
        pieces.push((cur, cur_cut, false, cur_first));
    }
    pieces.retain(|(p, ..)| p.len() >= 2);
    pieces
}
