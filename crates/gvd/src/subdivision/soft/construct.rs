//! The construction phase (YSL12 ¶20–22): via nodes where a Voronoi curve crosses a
//! segment (a side piece shared by two leaves), the Voronoi vertex test in boxes of
//! three features, and arcs along the features' bisectors.
//!
//! Nodes are placed exactly (the roots of the bisector's quadratic along the segment,
//! kept where the two features are the nearest, in their oriented zones), not at the
//! middle of bichromatic segments: a segment crossed twice (¶21, Fig. 4(g)) then
//! shows both nodes, and arcs can follow the bisector within epsilon. A box whose
//! nodes fit none of the patterns below is split again (counted in `local_splits`);
//! at the cut-off its nodes meet at one vertex, counted in `uncertified_boxes`.

use super::refine::Node;
use crate::geom::{Aabb, Point};
use crate::site::polygonal::{Polygonal, Shape};
use crate::subdivision::budget::Budget;
use crate::subdivision::resolve::{End, FoundVertex, LeafOutput, Piece, Port};
use smallvec::{smallvec, SmallVec};

/// Tolerances of the construction.
#[derive(Clone, Copy, Debug)]
pub struct Tol {
    /// Ties and zone membership are decided up to this length.
    pub tie: f64,
    /// Arcs stray at most this far from their bisector.
    pub trace: f64,
    /// Ties of less clearance are not via nodes: a box side passing this close to a
    /// corner would otherwise cut the end of the curve that ends there.
    pub clear: f64,
}

/// Whether `q` is a point of the Voronoi curve of `f` and `g`: they tie there, in
/// their oriented zones, at positive clearance in the free space, and no feature of
/// `others` is nearer. Returns the clearance.
pub fn valid_tie(
    poly: &Polygonal,
    f: u32,
    g: u32,
    q: Point,
    others: &[u32],
    tol: &Tol,
) -> Option<f64> {
    let (clear, tol) = (tol.clear, tol.tie);
    if poly.zone_boundary(f, g) {
        return None;
    }
    let (ff, fg) = (&poly.features[f as usize], &poly.features[g as usize]);
    let (df, dg) = (ff.distance(q), fg.distance(q));
    if (df - dg).abs() > tol {
        return None;
    }
    let d = df.min(dg);
    if d <= clear || !ff.oriented_zone.contains(q, tol) || !fg.oriented_zone.contains(q, tol) {
        return None;
    }
    if others
        .iter()
        .any(|&h| h != f && h != g && poly.features[h as usize].distance(q) < d - tol)
    {
        return None;
    }
    poly.free(q).then_some(d)
}

/// Appends to `out` the via nodes of the segment `from → to` in their order along it:
/// for each pair of `cands` (the features both leaves of the segment keep,
/// conservative on it), the valid crossings of their bisector. `crossings` is scratch.
pub fn segment_nodes(
    poly: &Polygonal,
    cands: &[u32],
    from: Point,
    to: Point,
    tol: &Tol,
    crossings: &mut Vec<(f64, Point, [u32; 2])>,
    out: &mut Vec<(Point, [u32; 2])>,
) {
    crossings.clear();
    for (i, &f) in cands.iter().enumerate() {
        for &g in &cands[i + 1..] {
            for t in poly.crossings(f, g, from, to) {
                let q = from.lerp(to, t);
                if valid_tie(poly, f, g, q, cands, tol).is_some() {
                    crossings.push((t, q, [f, g]));
                }
            }
        }
    }
    crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.extend(crossings.iter().map(|&(_, q, p)| (q, p)));
}

/// Why a box could not be resolved.
pub struct Unresolved;

/// Resolves one leaf from its nodes: `Err` when they fit no certified pattern.
pub struct Resolver<'a> {
    pub poly: &'a Polygonal,
    pub tol: Tol,
    pub budget: &'a Budget,
    /// The output names sites, not features (`voronoi` mode).
    pub by_sites: bool,
}

impl Resolver<'_> {
    fn piece(&self, pair: [u32; 2], ends: [End; 2], from: Point, to: Point) -> Piece {
        let points = self.poly.trace(pair[0], pair[1], from, to, self.tol.trace);
        for _ in 0..points.len() {
            if !self.budget.take_point() {
                break;
            }
        }
        Piece { pair, ends, points }
    }

    /// Whether the arc of `pair` between `p` and `q` stays a Voronoi curve in `b`
    /// (tested at its middle).
    fn arc_ok(&self, pair: [u32; 2], p: Point, q: Point, set: &[u32], b: &Aabb) -> bool {
        let m = self.poly.bisector_midpoint(pair[0], pair[1], p, q);
        b.outside_distance(m) <= self.tol.tie
            && valid_tie(self.poly, pair[0], pair[1], m, set, &self.tol).is_some()
    }

    /// [`Self::arc_ok`] for an arc ending at a corner `c`: arcs shorter than twice
    /// the least clearance of a via node pass (their middle is closer still).
    fn corner_arc_ok(&self, pair: [u32; 2], p: Point, c: Point, set: &[u32], b: &Aabb) -> bool {
        p.dist(c) <= 2.0 * self.tol.clear || self.arc_ok(pair, p, c, set, b)
    }

    /// The order of two points along the bisector of `pair`.
    fn order(&self, pair: [u32; 2], p: Point, q: Point) -> std::cmp::Ordering {
        let (kp, tp) = self.poly.bisector_param(pair[0], pair[1], p);
        let (kq, tq) = self.poly.bisector_param(pair[0], pair[1], q);
        kp.cmp(&kq).then(tp.total_cmp(&tq))
    }

    /// The concave corner where the curve of two edges ends, when it lies in `b`
    /// (or as close to it as via nodes may be to a corner).
    fn end_corner(&self, pair: [u32; 2], b: &Aabb) -> Option<(u32, Point)> {
        let c = self.poly.shared_corner(pair[0], pair[1])?;
        let Shape::Corner(at) = self.poly.features[c as usize].shape else {
            return None;
        };
        (b.outside_distance(at) <= self.tol.clear).then_some((c, at))
    }

    /// The Voronoi vertex test (¶22): the points of `b` equidistant from three of its
    /// features, in their oriented zones, with no feature of the set nearer; each with
    /// its three features.
    fn vertices(&self, set: &[u32], b: &Aabb) -> Vec<(Point, [u32; 3])> {
        let tol = self.tol.tie;
        let mut out: Vec<(Point, [u32; 3])> = Vec::new();
        let n = set.len();
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let t = [set[i], set[j], set[k]];
                    for q in self.poly.ties3(t) {
                        // half-open, so that a vertex on a shared side belongs to one
                        // box (its neighbours compute the same point from the same
                        // three features)
                        if !half_open(b, q) || !self.is_vertex(t, q, set) {
                            continue;
                        }
                        if !out.iter().any(|(p, _)| p.dist(q) <= tol) {
                            out.push((q, t));
                        }
                    }
                }
            }
        }
        out
    }

    /// Whether `q` is a Voronoi point of the three features `t` among `set`.
    fn is_vertex(&self, t: [u32; 3], q: Point, set: &[u32]) -> bool {
        let tol = self.tol.tie;
        let d = t.map(|f| self.poly.features[f as usize].distance(q));
        let lo = d.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = d.iter().copied().fold(0.0, f64::max);
        hi - lo <= tol
            && lo > self.tol.clear
            && t.iter().all(|&f| {
                self.poly.features[f as usize]
                    .oriented_zone
                    .contains(q, tol)
            })
            && set
                .iter()
                .all(|&h| t.contains(&h) || self.poly.features[h as usize].distance(q) >= lo - tol)
            && self.poly.free(q)
    }

    /// Resolves leaf `n` with its boundary nodes `ports` into `out` (cleared first, so
    /// one buffer serves every leaf): `Err` when they fit no pattern and the box may
    /// still be split.
    pub fn resolve(
        &self,
        n: &Node,
        ports: &[Port],
        can_split: bool,
        out: &mut LeafOutput,
    ) -> Result<(), Unresolved> {
        clear(out);
        if ports.is_empty() {
            return Ok(());
        }
        let set = &n.bs.set;
        let b = &n.aabb;
        let certified = !n.uncertified && set.len() <= 3;
        if certified || !can_split {
            // at the cut-off the patterns are tried too (a near-degenerate cluster of
            // vertices closer than the resolution), but the box counts as uncertified
            if self.pattern(set, b, ports, out).is_some() {
                out.uncertified = u32::from(!certified);
                return Ok(());
            }
            clear(out);
        }
        if can_split {
            return Err(Unresolved);
        }
        if ports.iter().all(|p| p.pair == ports[0].pair) && ports.len() % 2 == 0 {
            // one pair: its nodes joined in their order on the bisector
            let pair = ports[0].pair;
            let mut mine: SmallVec<[&Port; 8]> = ports.iter().collect();
            mine.sort_by(|x, y| self.order(pair, x.at, y.at));
            for w in mine.chunks(2) {
                out.pieces.push(Piece {
                    pair,
                    ends: [End::Port(w[0].id), End::Port(w[1].id)],
                    points: smallvec![w[0].at, w[1].at],
                });
            }
        } else if let Some(pieces) = self.apart_by_sites(b, ports) {
            out.pieces.extend(pieces);
        } else {
            // every node meets at one vertex of their features
            let vs = self.vertices(set, b);
            let at = vs.first().map(|v| v.0).unwrap_or_else(|| {
                let s = ports.iter().fold(Point::new(0.0, 0.0), |s, p| s + p.at);
                s * (1.0 / ports.len() as f64)
            });
            let mut sites: Vec<u32> = ports.iter().flat_map(|p| p.pair).collect();
            sites.sort_unstable();
            sites.dedup();
            out.vertices.push(FoundVertex { at, sites });
            for p in ports {
                out.pieces.push(Piece {
                    pair: p.pair,
                    ends: [End::Port(p.id), End::Vertex(0)],
                    points: smallvec![p.at, at],
                });
            }
        }
        out.uncertified = 1;
        Ok(())
    }

    /// At the cut-off in `voronoi` mode, the ports of box `b` grouped by the pair of
    /// sites they separate, joined two by two, when every group has two ports and no
    /// two groups' chords cross around the box. Such a box holds curves that pass it
    /// apart: two curves of a shared site, one through the zone boundaries of a far
    /// segment's corners and edge, meet at a vertex about an epsilon away, not in the
    /// box, and one vertex of all the ports would be a false one. Each join is a chord
    /// of the box, so only boxes whose diagonal is at most `4 · trace` (epsilon) are
    /// taken (larger ones stop at the round limit, not at the resolution).
    fn apart_by_sites(&self, b: &Aabb, ports: &[Port]) -> Option<Vec<Piece>> {
        if !self.by_sites || b.min.dist(b.max) > 4.0 * self.tol.trace {
            return None;
        }
        let site = |f: u32| self.poly.features[f as usize].owners[0].site();
        let key = |p: &Port| {
            let (s, t) = (site(p.pair[0]), site(p.pair[1]));
            (s.min(t), s.max(t))
        };
        let mut groups: Vec<((usize, usize), Vec<&Port>)> = Vec::new();
        for p in ports {
            match groups.iter_mut().find(|g| g.0 == key(p)) {
                Some(g) => g.1.push(p),
                None => groups.push((key(p), vec![p])),
            }
        }
        if groups.len() < 2 || groups.iter().any(|g| g.1.len() != 2 || g.0 .0 == g.0 .1) {
            return None;
        }
        // the ports lie on the box's boundary: their angles about its centre order them
        let c = b.center();
        let angle = |p: &Port| (p.at.y - c.y).atan2(p.at.x - c.x);
        let chords: Vec<(f64, f64)> = groups
            .iter()
            .map(|g| {
                let (x, y) = (angle(g.1[0]), angle(g.1[1]));
                (x.min(y), x.max(y))
            })
            .collect();
        let within = |t: f64, ch: (f64, f64)| ch.0 < t && t < ch.1;
        for (i, a) in chords.iter().enumerate() {
            for d in &chords[i + 1..] {
                if within(d.0, *a) != within(d.1, *a) {
                    return None;
                }
            }
        }
        Some(
            groups
                .iter()
                .map(|g| Piece {
                    pair: g.1[0].pair,
                    ends: [End::Port(g.1[0].id), End::Port(g.1[1].id)],
                    points: smallvec![g.1[0].at, g.1[1].at],
                })
                .collect(),
        )
    }

    /// The patterns: Voronoi vertices (Fig. 6(d,e), and the degree-2 vertices where a
    /// curve crosses a zone boundary), each node joined to the one vertex whose
    /// features hold its pair, vertices sharing a pair joined to each other; or,
    /// without a vertex, the nodes of each pair joined in their order along the
    /// bisector (Figs. 4, 5). A curve may end at the concave corner of its two edges.
    fn pattern(&self, set: &[u32], b: &Aabb, ports: &[Port], out: &mut LeafOutput) -> Option<()> {
        let vs = self.vertices(set, b);
        if vs.is_empty() {
            return self.arcs_only(set, b, ports, out);
        }
        for (at, t) in &vs {
            // a curve crossing the normal at a flat corner: the corner is a generator
            let mut sites = sorted(*t);
            for (f, g) in [(t[0], t[1]), (t[0], t[2]), (t[1], t[2])] {
                sites.extend(self.poly.flat_corner(f, g));
            }
            sites.sort_unstable();
            sites.dedup();
            out.vertices.push(FoundVertex { at: *at, sites });
        }
        let holds = |t: &[u32; 3], pair: [u32; 2]| t.contains(&pair[0]) && t.contains(&pair[1]);
        let mut degree: SmallVec<[usize; 4]> = smallvec![0; vs.len()];
        let mut joined: SmallVec<[(usize, [u32; 2]); 8]> = SmallVec::new();
        for p in ports {
            let mut owners = (0..vs.len()).filter(|&v| holds(&vs[v].1, p.pair));
            let (Some(v), None) = (owners.next(), owners.next()) else {
                return None;
            };
            if joined.contains(&(v, p.pair)) || !self.arc_ok(p.pair, p.at, vs[v].0, set, b) {
                return None;
            }
            joined.push((v, p.pair));
            degree[v] += 1;
            let ends = [End::Port(p.id), End::Vertex(v as u32)];
            out.pieces.push(self.piece(p.pair, ends, p.at, vs[v].0));
        }
        for v in 0..vs.len() {
            let t = vs[v].1;
            for pair in [[t[0], t[1]], [t[0], t[2]], [t[1], t[2]]] {
                if joined.contains(&(v, pair)) || self.poly.zone_boundary(pair[0], pair[1]) {
                    continue;
                }
                let other = (0..vs.len()).find(|&w| w != v && holds(&vs[w].1, pair));
                if let Some(w) = other {
                    // an edge between two vertices of the box
                    if !self.arc_ok(pair, vs[v].0, vs[w].0, set, b) {
                        return None;
                    }
                    joined.push((v, pair));
                    joined.push((w, pair));
                    degree[v] += 1;
                    degree[w] += 1;
                    let ends = [End::Vertex(v as u32), End::Vertex(w as u32)];
                    out.pieces.push(self.piece(pair, ends, vs[v].0, vs[w].0));
                    continue;
                }
                // a curve without a node must end at its edges' corner in the box
                let (c, at) = self.end_corner(pair, b)?;
                if !self.corner_arc_ok(pair, vs[v].0, at, set, b) {
                    return None;
                }
                let k = out.vertices.len() as u32;
                out.vertices.push(FoundVertex {
                    at,
                    sites: sorted([c, pair[0], pair[1]]),
                });
                out.pieces.push(self.piece(
                    pair,
                    [End::Vertex(v as u32), End::Vertex(k)],
                    vs[v].0,
                    at,
                ));
                degree[v] += 1;
            }
        }
        degree.iter().all(|&d| d >= 2).then_some(())
    }

    /// The nodes of each pair joined in their order along its bisector, an odd one out
    /// ending at its edges' concave corner in the box.
    fn arcs_only(&self, set: &[u32], b: &Aabb, ports: &[Port], out: &mut LeafOutput) -> Option<()> {
        let mut pairs: SmallVec<[[u32; 2]; 8]> = ports.iter().map(|p| p.pair).collect();
        pairs.sort_unstable();
        pairs.dedup();
        for pair in pairs {
            let mut mine: SmallVec<[&Port; 8]> = ports.iter().filter(|p| p.pair == pair).collect();
            mine.sort_by(|x, y| self.order(pair, x.at, y.at));
            let mut i = 0;
            while i < mine.len() {
                if i + 1 < mine.len() && self.arc_ok(pair, mine[i].at, mine[i + 1].at, set, b) {
                    let ends = [End::Port(mine[i].id), End::Port(mine[i + 1].id)];
                    out.pieces
                        .push(self.piece(pair, ends, mine[i].at, mine[i + 1].at));
                    i += 2;
                    continue;
                }
                let (c, at) = self.end_corner(pair, b)?;
                if !self.corner_arc_ok(pair, mine[i].at, at, set, b)
                    || out.vertices.iter().any(|v| v.at == at)
                {
                    return None;
                }
                let k = out.vertices.len() as u32;
                out.vertices.push(FoundVertex {
                    at,
                    sites: sorted([c, pair[0], pair[1]]),
                });
                out.pieces.push(self.piece(
                    pair,
                    [End::Port(mine[i].id), End::Vertex(k)],
                    mine[i].at,
                    at,
                ));
                i += 1;
            }
        }
        Some(())
    }
}

/// Whether `q` lies in `[min, max)²` of `b`.
fn half_open(b: &Aabb, q: Point) -> bool {
    b.min.x <= q.x && q.x < b.max.x && b.min.y <= q.y && q.y < b.max.y
}

/// Empties `out`, keeping its buffers.
fn clear(out: &mut LeafOutput) {
    out.pieces.clear();
    out.vertices.clear();
    out.uncertified = 0;
    out.local_splits = 0;
}

fn sorted(mut s: [u32; 3]) -> Vec<u32> {
    s.sort_unstable();
    s.to_vec()
}
