//! Insertion of one open segment (or arc, through [`NewSite`]) into the diagram of its
//! endpoints and the generators inserted before it (steps B1, B2, A2–A4 of the wiki
//! page, with `H(v) = d(v, s) − t(v)` for the distance `d` to the open segment and the
//! clearance `t` of `v`).
//!
//! * B1: the seed is the vertex of least `H` on the faces around the segment's
//!   endpoints (their own faces and those of segments already inserted there), else on
//!   the faces near them, else a new vertex where an edge there crosses the segment.
//! * B2: `T` grows from the seed, most negative `H` first, by vertices with `H < 0`
//!   that keep `T` a tree (C4: at most one edge to `T`). An edge into `T` whose middle
//!   the segment does not claim first gets a vertex there, kept out. C5 of the point
//!   algorithm does not hold here: the new region can wrap around an old face, so
//!   another old face may meet `T` in several chains. Vertices next to the vertex at
//!   infinity stay out (they lie near the far generators, far outside the domain).
//! * A2: on every edge from `T` to a vertex out of `T`, the new vertex is the point of
//!   the edge's bisector where it leaves the segment's region: where the clearance
//!   equals the distance to the segment, or where the foot leaves the segment (the
//!   endpoints' separators): a root of a quadratic in the bisector's parameter
//!   (`pieces.rs`), by bisection where the pieces are sampled (conics of arcs).
//! * A3, A4: on every old face that meets `T`, each chain of `T` vertices is replaced
//!   by one new edge (the bisector of the face's generator and the segment); the twins of
//!   the new edges form the segment's face; `T` and its edges are deleted.
//!
//! Every decision that shapes the graph is combinatorial, so the graph stays a valid
//! planar map whatever the rounding; geometry near exact ties is within rounding.

use super::geometry::{ray_exit, Arc, Bisector, Gen, Line, Shape};
use super::graph::{Graph, GHOST, NONE};
use super::new_site::NewSite;
use crate::geom::Point;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Why a segment could not be inserted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum InsertError {
    /// No vertex near the endpoints is nearer to the segment than to its generators.
    NoSeed,
    /// A chain of the conflict tree along an old face does not end at a new vertex.
    BrokenChain,
}

/// Vertex states during one insertion (stamped, so no clearing between insertions).
#[derive(Default)]
pub(crate) struct Scratch {
    stamp: u32,
    vertex_stamp: Vec<u32>,
    vertex_in: Vec<bool>,
    tree: Vec<u32>,
    /// Reused buffers: half-edges around a vertex, the candidates of `grow_tree`, and
    /// A2's splits, their index by edge, and A3's chains.
    around: Vec<u32>,
    heap: BinaryHeap<Candidate>,
    splits: Vec<(u32, u32)>,
    split_of: Vec<(u32, u32)>,
    chains: Vec<(usize, usize)>,
    twin_from_exit: Vec<u32>,
    new_edges: Vec<(u32, usize, usize)>,
    /// Vertices with `H < 0` that C4 kept out of `T`, and new vertices placed on an
    /// old vertex because the edge's far end was claimed too: 0 when the signs were
    /// consistent; otherwise the geometry near them may be off.
    pub(crate) overrides: usize,
}

#[derive(PartialEq)]
struct Candidate {
    h: f64,
    v: u32,
}
impl Eq for Candidate {}
impl PartialOrd for Candidate {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Candidate {
    fn cmp(&self, o: &Self) -> Ordering {
        // Max-heap on −H: the most negative H first.
        o.h.total_cmp(&self.h).then(o.v.cmp(&self.v))
    }
}

/// What the insertion needs to know of the generators.
pub(crate) struct Sites<'a> {
    pub(crate) points: &'a [Point],
    pub(crate) lines: &'a [Line],
    pub(crate) arcs: &'a [Arc],
    /// The faces of the segments and arcs inserted so far at each point generator
    /// (point generator `p`'s own face is `p`).
    pub(crate) faces_at_point: &'a [Vec<u32>],
}

impl Sites<'_> {
    /// The bisector of generators `a` and `b` between two of its points (or near them).
    pub(crate) fn bisector(&self, a: Gen, b: Gen, from: Point, to: Point) -> Bisector {
        Bisector::of_edge(self.shape(a), self.shape(b), from, to)
    }

    pub(crate) fn shape(&self, g: Gen) -> Shape<'_> {
        match g {
            Gen::Point(i) => Shape::Point(i, self.points[i as usize]),
            Gen::Segment(i) => Shape::Segment(&self.lines[i as usize]),
            Gen::Arc(i) => Shape::Arc(&self.arcs[i as usize]),
        }
    }
}

impl Scratch {
    fn begin(&mut self, g: &Graph) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.vertex_stamp.iter_mut().for_each(|s| *s = 0);
            self.stamp = 1;
        }
        self.fit(g);
        self.tree.clear();
    }

    /// Makes room for vertices added during the insertion (undecided).
    fn fit(&mut self, g: &Graph) {
        self.vertex_stamp.resize(g.vertices.len(), 0);
        self.vertex_in.resize(g.vertices.len(), false);
    }

    /// Whether `v` is in `T` (vertices made during this insertion never are).
    fn is_in(&self, v: u32) -> bool {
        self.decided(v) && self.vertex_in[v as usize]
    }

    fn decided(&self, v: u32) -> bool {
        self.vertex_stamp.get(v as usize) == Some(&self.stamp)
    }

    fn decide(&mut self, v: u32, inside: bool) {
        self.vertex_stamp[v as usize] = self.stamp;
        self.vertex_in[v as usize] = inside;
    }
}

/// Inserts `site`, the generator `gen` (an open segment or arc whose endpoints are in
/// the diagram); returns its new face.
pub(crate) fn insert_site(
    g: &mut Graph,
    sites: &Sites,
    site: &impl NewSite,
    gen: Gen,
    scratch: &mut Scratch,
) -> Result<u32, InsertError> {
    let h = |g: &Graph, v: u32| -> f64 {
        let vx = &g.vertices[v as usize];
        if v == GHOST || !vx.alive {
            return f64::INFINITY;
        }
        site.open_distance(vx.at) - vx.t
    };
    // An endpoint without segments yet has a face around it whose vertices may all be
    // claimed (a parabolic edge can wrap around behind it); a vertex behind it on its
    // boundary, which the segment never claims, keeps T a tree.
    let fresh = site
        .ends()
        .map(|p| sites.faces_at_point[p as usize].is_empty());
    for (k, &p) in site.ends().iter().enumerate() {
        if fresh[k] {
            split_behind(g, sites, p, site.away(k));
        }
    }
    let seed = match find_seed(g, sites, site, &h) {
        Some(v) => v,
        None => split_crossing(g, sites, site).ok_or(InsertError::NoSeed)?,
    };
    scratch.begin(g);
    grow_tree(g, sites, site, seed, &h, scratch);

    // A2: a new vertex on every edge leaving T.
    let new_face = g.faces.len() as u32;
    g.faces.push(super::graph::Face { gen, edge: NONE });
    let inside = |x: Point, t: f64| site.claims(x, t);
    // (new vertex, the old half-edge now leaving it)
    let mut splits = std::mem::take(&mut scratch.splits);
    let mut around = std::mem::take(&mut scratch.around);
    splits.clear();
    for &u in &scratch.tree {
        around.clear();
        around.extend(g.outgoing(u));
        for &e in &around {
            let w = g.target(e);
            if scratch.is_in(w) {
                continue;
            }
            let left = g.edges[e as usize].face;
            let right = g.edges[g.edges[e as usize].twin as usize].face;
            let (from, to) = (g.vertices[u as usize].at, g.vertices[w as usize].at);
            let (gl, gr) = (g.faces[left as usize].gen, g.faces[right as usize].gen);
            let bis = sites.bisector(gl, gr, from, to);
            let (at, t) = leave_region(&bis, from, to, site, inside);
            // The topology overrules a sign only where the segment claims `to` too. An
            // exit that rounds onto an unclaimed `to` is a degenerate crossing with
            // consistent signs: `to` is the segment's own endpoint (the joint's vertex,
            // reached along the neighbour's separator on the side the joint bends to)
            // or an old vertex on the segment's separator (cocircular on grid data).
            if at == to && inside(to, g.vertices[w as usize].t) {
                scratch.overrides += 1;
            }
            let x = g.add_vertex(at, t);
            // The old half-edge u → w becomes x → w.
            g.edges[e as usize].origin = x;
            g.vertices[x as usize].out = e;
            splits.push((x, e));
        }
    }
    scratch.around = around;
    let result = connect_chains(g, &splits, new_face, scratch);
    scratch.splits = splits;
    let new_edges = result?;

    // A fresh endpoint gets a vertex of its own, on its separator: later segments there
    // never claim it.
    for (k, &p) in site.ends().iter().enumerate() {
        if fresh[k] {
            let on_p = new_edges.iter().find(|e| g.edges[e.0 as usize].face == p);
            if let Some(&(ne, _, _)) = on_p {
                g.split_edge(ne, sites.points[p as usize], 0.0);
            }
        }
    }
    scratch.new_edges = new_edges;

    // A4: delete T.
    for &u in &scratch.tree {
        g.vertices[u as usize].alive = false;
    }
    Ok(new_face)
}

/// A3: each chain of T along an old face F runs from an entry vertex xa (on a split
/// edge whose right face is F) to the next exit vertex xb along F (a split edge whose
/// left face is F); it becomes one new edge xa → xb. A face may meet T in several
/// chains: the new region can wrap around another face. Found by walking F from xa
/// through T (its links are still the old ones). A4's twins of the new edges form the
/// new face. Returns the new edges (half-edge on the old face, entry split, exit
/// split), in the buffer `sc.new_edges`.
fn connect_chains(
    g: &mut Graph,
    splits: &[(u32, u32)],
    new_face: u32,
    sc: &mut Scratch,
) -> Result<Vec<(u32, usize, usize)>, InsertError> {
    // The split of each old half-edge, by binary search (edge, split index). The
    // buffers are lost on an error, which ends the whole construction.
    let mut split_of = std::mem::take(&mut sc.split_of);
    split_of.clear();
    split_of.extend(splits.iter().enumerate().map(|(k, &(_, e))| (e, k as u32)));
    split_of.sort_unstable();
    let mut chains = std::mem::take(&mut sc.chains);
    chains.clear();
    for (a, &(_, ea)) in splits.iter().enumerate() {
        let mut h = g.edges[g.edges[ea as usize].twin as usize].next;
        let mut steps = 0;
        while sc.is_in(g.edges[h as usize].origin) {
            h = g.edges[h as usize].next;
            steps += 1;
            if steps > g.edges.len() {
                return Err(InsertError::BrokenChain);
            }
        }
        let b = split_of
            .binary_search_by_key(&h, |&(e, _)| e)
            .map_err(|_| InsertError::BrokenChain)?;
        chains.push((a, split_of[b].1 as usize));
    }
    // Remember each new edge's twin (on the segment's face) by its start, the exit.
    let twin_from_exit = &mut sc.twin_from_exit;
    twin_from_exit.clear();
    twin_from_exit.resize(splits.len(), NONE);
    let mut new_edges = std::mem::take(&mut sc.new_edges);
    new_edges.clear();
    for &(a, b) in &chains {
        let (xa, ea) = splits[a];
        let (xb, eb) = splits[b];
        let into_a = g.edges[ea as usize].twin;
        let f = g.edges[into_a as usize].face;
        let ne = g.add_edge(xa, xb, f, new_face);
        // Face F: (w' → xa) then xa → xb then (xb → w).
        g.link(into_a, ne);
        g.link(ne, eb);
        g.faces[f as usize].edge = ne;
        if twin_from_exit[b] != NONE {
            return Err(InsertError::BrokenChain);
        }
        twin_from_exit[b] = ne + 1;
        new_edges.push((ne, a, b));
    }
    // The segment's face: the twin xb → xa is followed by the twin leaving xa, i.e. the
    // new edge whose exit vertex is xa.
    for &(ne, a, _) in &new_edges {
        let next = twin_from_exit[a];
        if next == NONE {
            return Err(InsertError::BrokenChain);
        }
        g.link(ne + 1, next);
    }
    g.faces[new_face as usize].edge = new_edges[0].0 + 1;
    sc.split_of = split_of;
    sc.chains = chains;
    Ok(new_edges)
}

/// Splits the boundary of point `p`'s face where the ray from `p` in direction `dir`
/// leaves it (the face is star-shaped around `p`, so the ray meets one edge), unless
/// a vertex lies on the ray already.
fn split_behind(g: &mut Graph, sites: &Sites, p: u32, dir: Point) {
    let c = sites.points[p as usize];
    let phi = dir.y.atan2(dir.x);
    let turn = |from: f64, to: f64| (to - from).rem_euclid(std::f64::consts::TAU);
    let angle = |x: Point| (x.y - c.y).atan2(x.x - c.x);
    let mut hit = None;
    let first = g.faces[p as usize].edge;
    if first == NONE {
        return;
    }
    // The angle of each edge's origin is the previous edge's target's.
    let mut tb = angle(g.vertices[g.edges[first as usize].origin as usize].at);
    for e in g.cycle(p) {
        let ta = tb;
        let b = g.vertices[g.target(e) as usize].at;
        tb = angle(b);
        let (span, to_ray) = (turn(ta, tb), turn(ta, phi));
        if to_ray == 0.0 {
            return;
        }
        if to_ray < span {
            let a = g.vertices[g.edges[e as usize].origin as usize].at;
            hit = Some((e, a, b, ta, to_ray));
            break;
        }
    }
    let Some((e, a, b, ta, to_ray)) = hit else {
        return;
    };
    let he = g.edges[e as usize];
    let other = g.faces[g.edges[he.twin as usize].face as usize].gen;
    // Bisection from the closed form's point where it applies and brackets the
    // crossing (there, near the ray, a point is before it when it lies clockwise of
    // it), else over the whole edge.
    let bis = sites.bisector(Gen::Point(p), other, a, b);
    let near = ray_exit(p, c, dir, sites.shape(other)).and_then(|s| {
        let guess = bis.fraction(a, b, c + dir * s);
        bis.boundary_near(a, b, guess, |x, _| dir.cross(x - c) < 0.0)
    });
    let (at, t) = near.unwrap_or_else(|| bis.boundary(a, b, |x, _| turn(ta, angle(x)) < to_ray));
    g.split_edge(e, at, t);
}

/// When no vertex is claimed (the segment's region only cuts edges in their middle):
/// a new vertex of degree two where an edge of a face around an endpoint crosses the
/// open segment; it is claimed, being (almost) on the segment.
fn split_crossing(g: &mut Graph, sites: &Sites, site: &impl NewSite) -> Option<u32> {
    for f in endpoint_faces(sites, site) {
        for e in g.cycle(f).collect::<Vec<_>>() {
            let (a, b) = (g.edges[e as usize].origin, g.target(e));
            if a == GHOST || b == GHOST {
                continue;
            }
            let (pa, pb) = (g.vertices[a as usize].at, g.vertices[b as usize].at);
            let (sa, sb) = (site.side(pa), site.side(pb));
            if sa * sb >= 0.0 || (sa * sb).is_nan() {
                continue;
            }
            let other = g.edges[g.edges[e as usize].twin as usize].face;
            let bis = sites.bisector(g.faces[f as usize].gen, g.faces[other as usize].gen, pa, pb);
            let (at, t) = bis.boundary(pa, pb, |x, _| (site.side(x) < 0.0) == (sa < 0.0));
            if site.claims(at, t) {
                return Some(g.split_edge(e, at, t));
            }
        }
    }
    None
}

/// The faces around the segment's endpoints: theirs, and those of the segments
/// inserted there before.
fn endpoint_faces(sites: &Sites, site: &impl NewSite) -> Vec<u32> {
    let mut faces = Vec::new();
    for p in site.ends() {
        faces.push(p);
        faces.extend_from_slice(&sites.faces_at_point[p as usize]);
    }
    faces
}

/// B1: the vertex of least `H < 0` on the faces around the endpoints; failing that
/// (rounding at a near tie), on the faces reached from them across edges, nearest
/// faces first, up to a bound.
fn find_seed(
    g: &Graph,
    sites: &Sites,
    site: &impl NewSite,
    h: &impl Fn(&Graph, u32) -> f64,
) -> Option<u32> {
    let mut best: Option<(f64, u32)> = None;
    let consider = |f: u32, best: &mut Option<(f64, u32)>| {
        for e in g.cycle(f) {
            let v = g.edges[e as usize].origin;
            let hv = h(g, v);
            if hv < 0.0 && best.is_none_or(|(b, _)| hv < b) && !next_to_ghost(g, v) {
                *best = Some((hv, v));
            }
        }
    };
    let start = endpoint_faces(sites, site);
    for &f in &start {
        consider(f, &mut best);
    }
    if best.is_some() {
        return best.map(|(_, v)| v);
    }
    let mut seen: std::collections::HashSet<u32> = start.iter().copied().collect();
    let mut queue: std::collections::VecDeque<u32> = start.into();
    while let Some(f) = queue.pop_front() {
        if seen.len() > 4096 {
            break;
        }
        for e in g.cycle(f).collect::<Vec<_>>() {
            let other = g.edges[g.edges[e as usize].twin as usize].face;
            if seen.insert(other) {
                consider(other, &mut best);
                queue.push_back(other);
            }
        }
        if best.is_some() {
            break;
        }
    }
    best.map(|(_, v)| v)
}

fn next_to_ghost(g: &Graph, v: u32) -> bool {
    g.outgoing(v).any(|e| g.target(e) == GHOST)
}

/// B2: grows `T` from `seed` under C4 and C5. A vertex that fails C5 stays undecided:
/// it is tried again when a neighbour joins `T` (the vertices of `T` are taken most
/// negative `H` first, which need not be the order in which a face's chain grows).
fn grow_tree(
    g: &mut Graph,
    sites: &Sites,
    site: &impl NewSite,
    seed: u32,
    h: &impl Fn(&Graph, u32) -> f64,
    sc: &mut Scratch,
) {
    let mut heap = std::mem::take(&mut sc.heap);
    heap.clear();
    heap.push(Candidate {
        h: h(g, seed),
        v: seed,
    });
    while let Some(Candidate { h: hv, v }) = heap.pop() {
        if sc.decided(v) {
            continue;
        }
        if v != seed {
            if hv.is_nan() || hv >= 0.0 || next_to_ghost(g, v) {
                sc.decide(v, false);
                continue;
            }
            split_unclaimed_edges(g, sites, site, v, sc);
            match tree_test(g, v, sc) {
                // Its only edges to T were split: it may join later through another
                // neighbour (pushed again then).
                TreeTest::Detached => continue,
                TreeTest::Cycle => {
                    sc.decide(v, false);
                    sc.overrides += 1;
                    continue;
                }
                TreeTest::Ok => {}
            }
        }
        sc.decide(v, true);
        sc.tree.push(v);
        for e in g.outgoing(v) {
            let w = g.target(e);
            if !sc.decided(w) {
                heap.push(Candidate { h: h(g, w), v: w });
            }
        }
    }
    sc.heap = heap;
}

/// An edge from `v` to `T` whose two ends the segment claims may leave its region in
/// the middle (a bisector bending around an endpoint, or crossing the needle that a
/// point next to the segment keeps): `T` would then swallow a piece that stays. Such
/// an edge gets a vertex of degree two in its unclaimed part, kept out of `T`.
fn split_unclaimed_edges(
    g: &mut Graph,
    sites: &Sites,
    site: &impl NewSite,
    v: u32,
    sc: &mut Scratch,
) {
    let mut to_tree = std::mem::take(&mut sc.around);
    to_tree.clear();
    to_tree.extend(g.outgoing(v).filter(|&e| sc.is_in(g.target(e))));
    for &e in &to_tree {
        let (from, to) = (
            g.vertices[v as usize].at,
            g.vertices[g.target(e) as usize].at,
        );
        let left = g.faces[g.edges[e as usize].face as usize].gen;
        let right = g.faces[g.edges[g.edges[e as usize].twin as usize].face as usize].gen;
        let bis = sites.bisector(left, right, from, to);
        let pieces = site.pieces(&bis, from, to);
        let unclaimed = pieces
            .iter()
            .filter(|p| !p.claimed)
            .max_by(|a, b| (a.hi - a.lo).total_cmp(&(b.hi - b.lo)));
        if let Some(piece) = unclaimed {
            let (at, t) = bis.at_fraction(from, to, piece.mid());
            let x = g.split_edge(e, at, t);
            sc.fit(g);
            sc.decide(x, false);
        }
    }
    sc.around = to_tree;
}

/// A2's new vertex on the edge from `from` (in `T`) to `to` (out of it): where the
/// bisector first leaves the segment's region. Where the pieces are exact, that is the
/// start of the first unclaimed piece, a root of one of the quadratics of `pieces.rs`;
/// otherwise (sampled pieces, or an unclaimed first piece: rounding at `from`) by
/// bisection between the middles of the last claimed and the first unclaimed piece; by
/// bisection over the whole edge when rounding hid the unclaimed piece (`to` if it is
/// claimed too: topology wins).
fn leave_region(
    bis: &Bisector,
    from: Point,
    to: Point,
    site: &impl NewSite,
    inside: impl Fn(Point, f64) -> bool,
) -> (Point, f64) {
    let pieces = site.pieces(bis, from, to);
    let Some(k) = pieces.iter().position(|p| !p.claimed) else {
        return bis.boundary(from, to, inside);
    };
    if k > 0 && pieces.exact {
        return bis.at_fraction(from, to, pieces[k].lo);
    }
    let lo = if k == 0 { 0.0 } else { pieces[k - 1].mid() };
    let (a, _) = bis.at_fraction(from, to, lo);
    let (b, _) = bis.at_fraction(from, to, pieces[k].mid());
    bis.boundary(a, b, inside)
}

enum TreeTest {
    Ok,
    /// No edge to `T` (they were all split): joining would disconnect `T`.
    Detached,
    /// C4 fails: `v` has two or more edges to `T`.
    Cycle,
}

/// C4 and C5 for adding `v` to `T`.
fn tree_test(g: &Graph, v: u32, sc: &Scratch) -> TreeTest {
    let mut in_neighbours = 0;
    for e in g.outgoing(v) {
        if sc.is_in(g.target(e)) {
            in_neighbours += 1;
        }
    }
    match in_neighbours {
        0 => TreeTest::Detached,
        1 => TreeTest::Ok,
        _ => TreeTest::Cycle,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::incremental::segments_arcs::geometry::testing::{linear_bisector, rng};

    /// A2's closed form (the start of the first unclaimed piece, a quadratic's root)
    /// against bisection between the middles of the last claimed and the first
    /// unclaimed piece, on random point/point, point/segment and segment/segment
    /// bisectors and a new segment.
    #[test]
    fn leave_region_matches_bisection() {
        let mut rnd = rng(0x0123_4567_89ab_cdefu64);
        let site = Line::new(Point::new(0.3, 0.4), Point::new(0.7, 0.55), [0, 1]);
        let inside = |x: Point, t: f64| site.claims(x, t);
        let mut checked = 0;
        for case in 0..3000 {
            let mut point = || Point::new(rnd(), rnd());
            let (p, q) = (point(), point());
            let other = Line::new(point(), point(), [4, 5]);
            let third = Line::new(point(), point(), [6, 7]);
            let bis = linear_bisector(case, p, q, &other, &third);
            let (from, to) = (point(), point());
            let (a, ta) = bis.at_fraction(from, to, 0.0);
            let (b, tb) = bis.at_fraction(from, to, 1.0);
            if !(a.x.is_finite() && b.x.is_finite() && inside(a, ta)) || inside(b, tb) {
                continue;
            }
            let pieces = site.pieces(&bis, a, b);
            let Some(k) = pieces.iter().position(|p| !p.claimed).filter(|&k| k > 0) else {
                continue;
            };
            let (x, t) = leave_region(&bis, a, b, &site, inside);
            let (lo, _) = bis.at_fraction(a, b, pieces[k - 1].mid());
            let (hi, _) = bis.at_fraction(a, b, pieces[k].mid());
            let (y, u) = bis.boundary(lo, hi, inside);
            let scale = 1.0 + a.dist(b);
            assert!(x.dist(y) <= 1e-9 * scale, "case {case}: {x:?} vs {y:?}");
            assert!((t - u).abs() <= 1e-9 * scale, "case {case}: {t} vs {u}");
            checked += 1;
        }
        assert!(checked > 200, "{checked}");
    }
}
