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
use crate::subdivision::resolve::{End, FoundVertex, LeafOutput, Piece, Port, PortId};
use crate::subdivision::segments::Segments;

/// Tolerances of the construction.
#[derive(Clone, Copy, Debug)]
pub struct Tol {
    /// Ties and zone membership are decided up to this length.
    pub tie: f64,
    /// Arcs stray at most this far from their bisector.
    pub trace: f64,
}

/// Whether `q` is a point of the Voronoi curve of `f` and `g`: they tie there, in
/// their oriented zones, at positive clearance in the free space, and no feature of
/// `others` is nearer. Returns the clearance.
pub fn valid_tie(poly: &Polygonal, f: u32, g: u32, q: Point, others: &[u32], tol: f64) -> Option<f64> {
    if poly.zone_boundary(f, g) {
        return None;
    }
    let (ff, fg) = (&poly.features[f as usize], &poly.features[g as usize]);
    let (df, dg) = (ff.distance(q), fg.distance(q));
    if (df - dg).abs() > tol {
        return None;
    }
    let d = df.min(dg);
    if d <= tol || !ff.oriented_zone.contains(q, tol) || !fg.oriented_zone.contains(q, tol) {
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

/// The sorted intersection of two sorted lists.
fn intersect(a: &[u32], b: &[u32]) -> Vec<u32> {
    a.iter().filter(|x| b.binary_search(x).is_ok()).copied().collect()
}

/// The via nodes of every segment: for each pair of the features both leaves keep
/// (conservative on the shared segment), the valid crossings of their bisector.
pub fn via_nodes(poly: &Polygonal, leaves: &[Node], segs: &Segments, tol: f64) -> Vec<Vec<(Point, [u32; 2])>> {
    segs.segments
        .iter()
        .map(|s| {
            let cands = match s.leaves {
                [Some(a), Some(b)] => intersect(&leaves[a as usize].bs.set, &leaves[b as usize].bs.set),
                [Some(a), None] | [None, Some(a)] => leaves[a as usize].bs.set.clone(),
                [None, None] => Vec::new(),
            };
            let mut out: Vec<(f64, Point, [u32; 2])> = Vec::new();
            for (i, &f) in cands.iter().enumerate() {
                for &g in &cands[i + 1..] {
                    for t in poly.crossings(f, g, s.from, s.to) {
                        let q = s.from.lerp(s.to, t);
                        if valid_tie(poly, f, g, q, &cands, tol).is_some() {
                            out.push((t, q, [f, g]));
                        }
                    }
                }
            }
            out.sort_by(|a, b| a.0.total_cmp(&b.0));
            out.into_iter().map(|(_, q, p)| (q, p)).collect()
        })
        .collect()
}

/// Why a box could not be resolved.
pub struct Unresolved;

/// Resolves one leaf from its nodes: `Err` when they fit no certified pattern.
pub struct Resolver<'a> {
    pub poly: &'a Polygonal,
    pub tol: Tol,
    pub budget: &'a Budget,
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
            && valid_tie(self.poly, pair[0], pair[1], m, set, self.tol.tie).is_some()
    }

    /// The concave corner where the curve of two edges ends, when it lies in `b`.
    fn end_corner(&self, pair: [u32; 2], b: &Aabb) -> Option<(u32, Point)> {
        let c = self.poly.shared_corner(pair[0], pair[1])?;
        let Shape::Corner(at) = self.poly.features[c as usize].shape else {
            return None;
        };
        let inside = b.min.x <= at.x && at.x < b.max.x && b.min.y <= at.y && at.y < b.max.y;
        inside.then_some((c, at))
    }

    /// The Voronoi vertex test (¶22): the points of `b` equidistant from its three
    /// features that are Voronoi points.
    fn vertices(&self, set: &[u32], b: &Aabb) -> Vec<Point> {
        if set.len() != 3 {
            return Vec::new();
        }
        let t = [set[0], set[1], set[2]];
        let tol = self.tol.tie;
        let mut out: Vec<Point> = Vec::new();
        for q in self.poly.ties3(t) {
            if b.outside_distance(q) > tol {
                continue;
            }
            let d: Vec<f64> = t.iter().map(|&f| self.poly.features[f as usize].distance(q)).collect();
            let (lo, hi) = (d.iter().copied().fold(f64::INFINITY, f64::min), d.iter().copied().fold(0.0, f64::max));
            let zones = t.iter().all(|&f| self.poly.features[f as usize].oriented_zone.contains(q, tol));
            if hi - lo <= tol && lo > tol && zones && self.poly.free(q) && !out.iter().any(|p| p.dist(q) <= tol) {
                out.push(q);
            }
        }
        out
    }

    /// Resolves leaf `n` (index `leaf`) with its boundary nodes `ports`.
    pub fn resolve(&self, n: &Node, ports: &[Port], can_split: bool) -> Result<LeafOutput, Unresolved> {
        let mut out = LeafOutput::default();
        if ports.is_empty() {
            return Ok(out);
        }
        let set = &n.bs.set;
        let b = &n.aabb;
        let certified = !n.uncertified && set.len() <= 3;
        let attempt = if certified { self.pattern(set, b, ports) } else { None };
        match attempt {
            Some(o) => Ok(o),
            None if can_split => Err(Unresolved),
            None => {
                // the cut-off: every node meets at one vertex of their features
                let vs = if set.len() == 3 { self.vertices(set, b) } else { Vec::new() };
                let at = vs.first().copied().unwrap_or_else(|| {
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
                        points: vec![p.at, at],
                    });
                }
                out.uncertified = 1;
                Ok(out)
            }
        }
    }

    /// The certified patterns: one Voronoi vertex joined to every node (Fig. 6(d,e),
    /// and the degree-2 vertices where a curve crosses a zone boundary), or arcs
    /// joining the nodes of each pair in their order along the bisector (Figs. 4, 5),
    /// each possibly ending at the concave corner of its two edges.
    fn pattern(&self, set: &[u32], b: &Aabb, ports: &[Port]) -> Option<LeafOutput> {
        let mut out = LeafOutput::default();
        let vs = self.vertices(set, b);
        if vs.len() >= 2 {
            return None;
        }
        if let Some(&v) = vs.first() {
            let mut seen: Vec<[u32; 2]> = Vec::new();
            out.vertices.push(FoundVertex {
                at: v,
                sites: set.to_vec(),
            });
            for p in ports {
                if seen.contains(&p.pair) || !self.arc_ok(p.pair, p.at, v, set, b) {
                    return None;
                }
                seen.push(p.pair);
                out.pieces.push(self.piece(p.pair, [End::Port(p.id), End::Vertex(0)], p.at, v));
            }
            let mut degree = seen.len();
            for (i, &f) in set.iter().enumerate() {
                for &g in &set[i + 1..] {
                    let pair = [f, g];
                    if seen.contains(&pair) || self.poly.zone_boundary(f, g) {
                        continue;
                    }
                    // a curve without a node must end at its edges' corner in the box
                    let (c, at) = self.end_corner(pair, b)?;
                    if !self.arc_ok(pair, v, at, set, b) {
                        return None;
                    }
                    let k = out.vertices.len() as u32;
                    out.vertices.push(FoundVertex {
                        at,
                        sites: sorted([c, f, g]),
                    });
                    out.pieces.push(self.piece(pair, [End::Vertex(0), End::Vertex(k)], v, at));
                    degree += 1;
                }
            }
            return (degree >= 2).then_some(out);
        }
        let mut pairs: Vec<[u32; 2]> = ports.iter().map(|p| p.pair).collect();
        pairs.sort_unstable();
        pairs.dedup();
        for pair in pairs {
            let mut mine: Vec<&Port> = ports.iter().filter(|p| p.pair == pair).collect();
            mine.sort_by(|x, y| {
                let (kx, tx) = self.poly.bisector_param(pair[0], pair[1], x.at);
                let (ky, ty) = self.poly.bisector_param(pair[0], pair[1], y.at);
                kx.cmp(&ky).then(tx.total_cmp(&ty))
            });
            let mut i = 0;
            while i < mine.len() {
                if i + 1 < mine.len() && self.arc_ok(pair, mine[i].at, mine[i + 1].at, set, b) {
                    let ends = [End::Port(mine[i].id), End::Port(mine[i + 1].id)];
                    out.pieces.push(self.piece(pair, ends, mine[i].at, mine[i + 1].at));
                    i += 2;
                    continue;
                }
                let (c, at) = self.end_corner(pair, b)?;
                if !self.arc_ok(pair, mine[i].at, at, set, b)
                    || out.vertices.iter().any(|v| v.at == at)
                {
                    return None;
                }
                let k = out.vertices.len() as u32;
                out.vertices.push(FoundVertex {
                    at,
                    sites: sorted([c, pair[0], pair[1]]),
                });
                out.pieces.push(self.piece(pair, [End::Port(mine[i].id), End::Vertex(k)], mine[i].at, at));
                i += 1;
            }
        }
        Some(out)
    }
}

fn sorted(mut s: [u32; 3]) -> Vec<u32> {
    s.sort_unstable();
    s.to_vec()
}

/// The nodes on leaf `l`'s boundary, from the shared segments.
pub fn ports_of(l: usize, segs: &Segments, nodes: &[Vec<(Point, [u32; 2])>]) -> Vec<Port> {
    let mut ports = Vec::new();
    for &s in &segs.members[segs.rows[l]..segs.rows[l + 1]] {
        for (k, &(at, pair)) in nodes[s as usize].iter().enumerate() {
            ports.push(Port {
                id: PortId::Segment {
                    segment: s,
                    index: k as u32,
                },
                at,
                pair,
            });
        }
    }
    ports
}
