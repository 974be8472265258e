//! The topology-oriented incremental Voronoi diagram of points and line segments
//! (Imai 1996; Held 2001; the OpenVoronoi wiki page).
//!
//! The generators are the points (isolated points and segment endpoints, deduplicated)
//! and the open segments. Points go in first, through the exact point engine; then
//! each open segment is inserted (`insert.rs`) into the general half-edge graph made
//! from the points' graph (`graph.rs`). A segment's face is one face around both of
//! its sides; it meets each endpoint's face along the endpoint's separator (the normal
//! line through the endpoint), which is why the separators are bisectors like any
//! other here. Bisectors are lines and parabolas in offset-parameter form
//! (`geometry.rs`).
//!
//! Segments must not cross or overlap, and no endpoint or point may lie inside another
//! segment (touching at shared endpoints is fine): `crossings.rs` finds such input,
//! which callers refuse, naming the two segments, or cut into pieces that meet only at
//! shared ends (`split.rs`).

mod arc;
mod arc_conflicts;
mod crossings;
mod geometry;
mod graph;
mod insert;
pub(crate) mod joints;
mod new_site;
mod pieces;
mod split;

pub(crate) use arc_conflicts::{find_arc_conflict, ArcConflict, ArcSpec};
pub(crate) use crossings::{check_sites_beside_tolerance, find_conflict, Conflict, NEAR_TOUCH};
pub(crate) use geometry::Gen;
pub(crate) use split::{split_segments, Split};

use super::points::PointDiagram;
use crate::geom::grid::SparseGrid;
use crate::geom::{Aabb, Point};
use crate::par::{filter_map_range, map_range};
use crate::subdivision::Budget;
use crate::Error;
use geometry::{Arc, Bisector, Line};
use graph::{Graph, GHOST, NONE};
use insert::{insert_site, InsertError, Scratch, Sites};
use smallvec::SmallVec;
use std::sync::Mutex;

/// The diagram of points and non-crossing segments, as a general half-edge graph.
pub(crate) struct SegmentDiagram {
    graph: Graph,
    /// Point generators in the point graph's order (scaled), far generators last.
    points: Vec<Point>,
    /// The caller's index of each point generator (`u32::MAX` for far ones).
    point_id: Vec<u32>,
    lines: Vec<Line>,
    arcs: Vec<Arc>,
    scale: f64,
    /// The domain (scaled): polylines keep their tolerance where they can meet it.
    visible: Aabb,
    /// See [`Scratch::overrides`](insert::Scratch).
    pub(crate) overrides: usize,
    /// The output points the polylines may take, and the run's watch.
    pub(crate) budget: Budget,
}

/// An edge of the raw diagram: two generators and two vertices; its polyline is
/// [`SegmentDiagram::polyline`] of `half`.
pub(crate) struct RawEdge {
    pub(crate) gens: [Gen; 2],
    pub(crate) ends: [usize; 2],
    /// The graph's half-edge from `ends[0]` to `ends[1]`.
    pub(crate) half: u32,
    /// Whether the edge is a point: both ends and every point of its polyline coincide.
    pub(crate) zero: bool,
    /// The point generator of a tangent joint on whose normal the edge lies exactly
    /// (set by the caller, see `joints.rs`): its polyline is projected onto it.
    pub(crate) on_normal: Option<u32>,
}

/// A vertex of the raw diagram with the generators of the faces around it.
#[derive(Default)]
pub(crate) struct RawVertex {
    pub(crate) at: Point,
    /// Clearance: 0 for a vertex on a site (a segment endpoint).
    pub(crate) t: f64,
    pub(crate) gens: SmallVec<[Gen; 3]>,
}

impl SegmentDiagram {
    /// The diagram of the distinct `points` and the `segments` between them (pairs of
    /// point indices). The caller has checked that the segments do not cross. The
    /// budget's watch stops the construction early (checked per inserted site); its
    /// points bound the polylines drawn.
    pub(crate) fn new(
        points: &[Point],
        segments: &[[u32; 2]],
        arcs: &[ArcSpec],
        domain: Aabb,
        budget: Budget,
    ) -> Result<SegmentDiagram, Error> {
        let watch = budget.watch().clone();
        let n = points.len();
        let mut with_frame = points.to_vec();
        with_frame.extend(frame(points, arcs, domain));
        let pd = PointDiagram::watched(&with_frame, domain, &watch)?;
        let mut graph = Graph::from_points(&pd);
        let mut face_of_point = vec![0u32; with_frame.len()];
        let mut point_id = vec![u32::MAX; pd.pts.len()];
        for (s, &i) in pd.input.iter().enumerate() {
            face_of_point[i as usize] = s as u32;
            if (i as usize) < n {
                point_id[s] = i;
            }
        }
        let reach = super::anchor_reach(&domain) * pd.scale;
        let lines: Vec<Line> = segments
            .iter()
            .map(|&[a, b]| {
                let (fa, fb) = (face_of_point[a as usize], face_of_point[b as usize]);
                Line::anchored(pd.pts[fa as usize], pd.pts[fb as usize], [fa, fb], reach)
            })
            .collect();
        // Internal coordinates are the input's times a power of two: exact for arcs too.
        let arc_gens: Vec<Arc> = arcs
            .iter()
            .map(|a| {
                let ends = a.ends.map(|p| face_of_point[p as usize]);
                let mut arc = Arc::new(
                    a.c * pd.scale,
                    a.r * pd.scale,
                    a.start,
                    a.start + a.span,
                    ends,
                );
                arc.end_points = ends.map(|f| pd.pts[f as usize]);
                arc
            })
            .collect();
        let mut faces_at_point: Vec<Vec<u32>> = vec![Vec::new(); pd.pts.len()];
        let mut scratch = Scratch::default();
        watch.stage(
            "segments and arcs",
            Some((lines.len() + arc_gens.len()) as u64),
        );
        for k in insertion_order(&lines, &arc_gens) {
            if !watch.tick(1) {
                watch.check()?;
            }
            let sites = Sites {
                points: &pd.pts,
                lines: &lines,
                arcs: &arc_gens,
                faces_at_point: &faces_at_point,
            };
            let (face, ends) = if k < lines.len() {
                let gen = Gen::Segment(k as u32);
                (
                    insert_site(&mut graph, &sites, &lines[k], gen, &mut scratch),
                    lines[k].ends,
                )
            } else {
                let a = k - lines.len();
                let gen = Gen::Arc(a as u32);
                (
                    insert_site(&mut graph, &sites, &arc_gens[a], gen, &mut scratch),
                    arc_gens[a].ends,
                )
            };
            let face = face.map_err(|e| {
                let why = match e {
                    InsertError::NoSeed => "no Voronoi vertex nearer to it was found",
                    InsertError::BrokenChain => "its conflict region was not a tree",
                };
                let what = if k < lines.len() { "segment" } else { "arc" };
                Error::Internal(format!("{what} generator {k} could not be inserted: {why}"))
            })?;
            for p in ends {
                faces_at_point[p as usize].push(face);
            }
        }
        Ok(SegmentDiagram {
            overrides: scratch.overrides,
            graph,
            points: pd.pts,
            point_id,
            lines,
            arcs: arc_gens,
            scale: pd.scale,
            visible: Aabb::new(domain.min * pd.scale, domain.max * pd.scale),
            budget,
        })
    }

    /// Moves every vertex within `radius` (input units) of a point generator that the
    /// caller numbers `from` or later (the crossing points of `split.rs`) onto that
    /// point, with clearance 0. Those vertices are where pieces meeting at the point
    /// tie, exactly at the point; the point lies within rounding of the lines of the
    /// pieces, not on them, so the constructions put them a few ulps off, joined by
    /// edges of that length. Once on the point, such edges have zero length and merge.
    pub(crate) fn snap_vertices_to_points(&mut self, from: u32, radius: f64) {
        let r = radius * self.scale;
        let mut grid = SparseGrid::new(r);
        for (s, &i) in self.point_id.iter().enumerate() {
            if i != u32::MAX && i >= from {
                grid.insert(self.points[s], ());
            }
        }
        for v in self
            .graph
            .vertices
            .iter_mut()
            .filter(|v| v.alive && v.t <= r)
        {
            if let Some(&(p, ())) = grid
                .near(v.at)
                .min_by(|x, y| x.0.dist(v.at).total_cmp(&y.0.dist(v.at)))
            {
                v.at = p;
                v.t = 0.0;
            }
        }
    }

    /// The generator as the caller numbers it: `Point(i)` is the caller's point `i`,
    /// `Segment(j)` the caller's segment `j`; `None` for far generators.
    fn caller_gen(&self, g: Gen) -> Option<Gen> {
        match g {
            Gen::Point(s) => {
                let i = self.point_id[s as usize];
                (i != u32::MAX).then_some(Gen::Point(i))
            }
            Gen::Segment(j) => Some(Gen::Segment(j)),
            Gen::Arc(j) => Some(Gen::Arc(j)),
        }
    }

    /// Every finite vertex (with its real generators), and the edges between two real
    /// generators that are `wanted` or of zero length (judged on their polylines within
    /// `tol`), in input coordinates; an error if the graph breaks a half-edge invariant
    /// (checked here, in the same pass).
    pub(crate) fn raw(
        &self,
        tol: f64,
        wanted: impl Fn(Gen, Gen) -> bool + Sync,
    ) -> Result<(Vec<RawVertex>, Vec<RawEdge>), Error> {
        let g = &self.graph;
        let alive: Vec<bool> = g.vertices.iter().map(|v| v.alive).collect();
        let live: Vec<usize> = (0..g.vertices.len())
            .filter(|&v| alive[v] && v as u32 != GHOST)
            .collect();
        let mut index = vec![NONE; g.vertices.len()];
        for (k, &v) in live.iter().enumerate() {
            index[v] = k as u32;
        }
        // The half-edge invariants are checked on the way, before any vertex's edges
        // are walked around it; `broken` keeps the first broken one found.
        let broken: Mutex<Option<String>> = Mutex::new(None);
        let record = |e: String| {
            if let Ok(mut first) = broken.lock() {
                first.get_or_insert(e);
            }
        };
        let check = || match broken.lock().ok().and_then(|mut b| b.take()) {
            Some(e) => Err(Error::Internal(format!("invalid segment graph: {e}"))),
            None => Ok(()),
        };
        let edges = filter_map_range(g.edges.len(), 1 << 12, |h| match g.check_edge(h, &alive) {
            Ok(()) => self.raw_edge(&index, h, tol, &wanted),
            Err(e) => {
                record(e);
                None
            }
        });
        check()?;
        let vertices = map_range(live.len(), 1 << 12, |k| match g.check_vertex(live[k]) {
            Ok(()) => self.raw_vertex(live[k]),
            Err(e) => {
                record(e);
                RawVertex::default() // a placeholder: the error is returned
            }
        });
        check()?;
        Ok((vertices, edges))
    }

    /// The raw vertex of live graph vertex `v`, with its generators, each once.
    fn raw_vertex(&self, v: usize) -> RawVertex {
        let g = &self.graph;
        let vx = &g.vertices[v];
        let mut gens = SmallVec::new();
        for e in g.outgoing(v as u32) {
            let gen = self.caller_gen(g.faces[g.edges[e as usize].face as usize].gen);
            if let Some(c) = gen.filter(|c| !gens.contains(c)) {
                gens.push(c);
            }
        }
        let inv = 1.0 / self.scale;
        RawVertex {
            at: vx.at * inv,
            t: vx.t * inv,
            gens,
        }
    }

    /// The raw edge of half-edge `h` (`None` for the second half-edge of a pair, for
    /// edges at a far generator or the vertex at infinity, and for unwanted edges of
    /// positive length); `index` maps live vertices to their raw index (`NONE` for the
    /// others).
    fn raw_edge(
        &self,
        index: &[u32],
        h: usize,
        tol: f64,
        wanted: impl Fn(Gen, Gen) -> bool,
    ) -> Option<RawEdge> {
        let g = &self.graph;
        let he = &g.edges[h];
        let t = he.twin as usize;
        if h > t {
            return None;
        }
        let (a, b) = (he.origin as usize, g.edges[t].origin as usize);
        if index[a] == NONE || index[b] == NONE {
            return None;
        }
        let (fa, fb) = (he.face, g.edges[t].face);
        let (ga, gb) = (g.faces[fa as usize].gen, g.faces[fb as usize].gen);
        let (ca, cb) = (self.caller_gen(ga)?, self.caller_gen(gb)?);
        let zero = g.vertices[a].at == g.vertices[b].at && {
            let mut points = Vec::new();
            self.polyline(h as u32, tol, &mut points);
            points.windows(2).all(|w| w[0] == w[1])
        };
        (zero || wanted(ca, cb)).then_some(RawEdge {
            gens: [ca, cb],
            ends: [index[a] as usize, index[b] as usize],
            half: h as u32,
            zero,
            on_normal: None,
        })
    }

    /// Appends to `out` a polyline within `tol` of the bisector of half-edge `h` where
    /// it can meet the domain, from its origin to its target, in input coordinates.
    pub(crate) fn polyline(&self, h: u32, tol: f64, out: &mut Vec<Point>) {
        let g = &self.graph;
        let he = &g.edges[h as usize];
        let tw = &g.edges[he.twin as usize];
        let (pa, pb) = (
            g.vertices[he.origin as usize].at,
            g.vertices[tw.origin as usize].at,
        );
        let (ga, gb) = (g.faces[he.face as usize].gen, g.faces[tw.face as usize].gen);
        let inv = 1.0 / self.scale;
        let sites = Sites {
            points: &self.points,
            lines: &self.lines,
            arcs: &self.arcs,
            faces_at_point: &[],
        };
        // once the points have run out, chords (the run then ends with the budget error)
        if Bisector::is_line(sites.shape(ga), sites.shape(gb)) || self.budget.exhausted() {
            out.extend([pa * inv, pb * inv]);
            return;
        }
        let start = out.len();
        let left = self.budget.points_left();
        let drawn = sites.bisector(ga, gb, pa, pb).polyline(
            pa,
            pb,
            tol * self.scale,
            &self.visible,
            left,
            out,
        );
        out[start..].iter_mut().for_each(|p| *p = *p * inv);
        if drawn {
            self.budget.take_points(out.len() - start);
        } else {
            // the run then ends with the budget's error, never with the chord
            self.budget.run_out_of_points();
        }
    }
}

/// Eight auxiliary point generators on a circle four times the extent of the domain,
/// the points and the arcs' circles, around their centre: no domain point is nearer to
/// them than to a site, and the Voronoi vertices of the sites near the domain are then
/// never next to the far generators of the point diagram (whose vertices `T` must keep
/// out), even with few sites and an arc whose region wraps around most of the plane.
/// Their faces and edges are not output.
fn frame(points: &[Point], arcs: &[ArcSpec], domain: Aabb) -> [Point; 8] {
    let (mut lo, mut hi) = (domain.min, domain.max);
    let mut grow = |p: Point, r: f64| {
        lo = Point::new(lo.x.min(p.x - r), lo.y.min(p.y - r));
        hi = Point::new(hi.x.max(p.x + r), hi.y.max(p.y + r));
    };
    points.iter().for_each(|&p| grow(p, 0.0));
    arcs.iter().for_each(|a| grow(a.c, a.r));
    let c = lo.lerp(hi, 0.5);
    let r = 4.0 * (hi - lo).norm().max(f64::MIN_POSITIVE);
    std::array::from_fn(|k| {
        let a = std::f64::consts::TAU * k as f64 / 8.0;
        c + Point::new(a.cos(), a.sin()) * r
    })
}

/// The insertion order of the segments (indices `0..lines.len()`) and arcs (indices
/// after them): a biased randomized insertion order along a Hilbert curve of their
/// middles (`order.rs`). Random rounds keep the expected conflict trees small, as a
/// random order does; consecutive sites within a round are neighbours, so each
/// insertion finds the graph around it still in cache.
fn insertion_order(lines: &[Line], arcs: &[Arc]) -> Vec<usize> {
    let middles: Vec<Point> = lines
        .iter()
        .map(|l| l.a + l.d * (0.5 * l.len))
        .chain(arcs.iter().map(|a| {
            let mid = a.a0 + 0.5 * a.span;
            a.c + Point::new(mid.cos(), mid.sin()) * a.r
        }))
        .collect();
    super::points::order::brio(&middles)
        .into_iter()
        .map(|k| k as usize)
        .collect()
}
