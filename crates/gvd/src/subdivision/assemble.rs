//! Stitching: the leaves' pieces are chained through their shared ports into edges from
//! vertex to vertex (or to the domain boundary); vertices closer than the tolerance
//! along an edge are merged into one vertex of higher degree; polylines are simplified.

use super::resolve::{End, FoundVertex, LeafOutput, PiecePoints, PortId};
use crate::complex::{Edge, Generator, Vertex, VoronoiComplex};
use crate::disjoint_sets::DisjointSets;
use crate::geom::Point;

/// A piece end after the leaf-local vertex numbers became global.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum GEnd {
    Port(PortId),
    Vertex(usize),
}

struct GPiece {
    pair: [u32; 2],
    ends: [GEnd; 2],
    points: PiecePoints,
}

/// Chains all pieces into the complex's vertices and edges.
pub fn assemble(outputs: Vec<LeafOutput>, merge_len: f64, simplify_tol: f64) -> VoronoiComplex {
    let mut vertices: Vec<FoundVertex> =
        Vec::with_capacity(outputs.iter().map(|o| o.vertices.len()).sum());
    let mut pieces: Vec<GPiece> = Vec::with_capacity(outputs.iter().map(|o| o.pieces.len()).sum());
    for o in outputs {
        let base = vertices.len();
        let g = |e: End| match e {
            End::Port(p) => GEnd::Port(p),
            End::Vertex(v) => GEnd::Vertex(base + v as usize),
        };
        pieces.extend(o.pieces.into_iter().map(|p| GPiece {
            pair: p.pair,
            ends: [g(p.ends[0]), g(p.ends[1])],
            points: p.points,
        }));
        vertices.extend(o.vertices);
    }
    // link piece ends that share a port: the ends sorted by port, pairs linked
    let mut at_port: Vec<(PortId, usize, usize)> = Vec::with_capacity(2 * pieces.len());
    for (k, p) in pieces.iter().enumerate() {
        for e in 0..2 {
            if let GEnd::Port(id) = p.ends[e] {
                at_port.push((id, k, e));
            }
        }
    }
    at_port.sort_unstable_by_key(|x| x.0);
    let mut link: Vec<[Option<(usize, usize)>; 2]> = vec![[None, None]; pieces.len()];
    for group in at_port.chunk_by(|x, y| x.0 == y.0) {
        if let [(_, ak, ae), (_, bk, be)] = *group {
            link[ak][ae] = Some((bk, be));
            link[bk][be] = Some((ak, ae));
        }
    }
    let mut used = vec![false; pieces.len()];
    let mut chains: Vec<Chain> = Vec::new();
    // open chains start at an unlinked end (a vertex or a port on the domain boundary)
    for k in 0..pieces.len() {
        for e in 0..2 {
            if !used[k] && link[k][e].is_none() {
                chains.push(walk(&pieces, &link, &mut used, k, e));
            }
        }
    }
    // what is left are closed loops
    for k in 0..pieces.len() {
        if !used[k] {
            let mut c = walk(&pieces, &link, &mut used, k, 0);
            c.closed = true;
            if let (Some(&f), Some(&l)) = (c.points.first(), c.points.last()) {
                if f != l {
                    c.points.push(f);
                }
            }
            chains.push(c);
        }
    }
    build_complex(vertices, chains, merge_len, simplify_tol)
}

struct Chain {
    pair: [u32; 2],
    ends: [Option<usize>; 2],
    points: Vec<Point>,
    closed: bool,
}

/// Follows linked pieces from end `e` of piece `k` until an unlinked end or a loop.
fn walk(
    pieces: &[GPiece],
    link: &[[Option<(usize, usize)>; 2]],
    used: &mut [bool],
    k: usize,
    e: usize,
) -> Chain {
    let vertex_of = |g: GEnd| match g {
        GEnd::Vertex(v) => Some(v),
        GEnd::Port(_) => None,
    };
    let first = vertex_of(pieces[k].ends[e]);
    let mut points: Vec<Point> = Vec::new();
    let (mut k, mut e) = (k, e);
    loop {
        used[k] = true;
        let p = &pieces[k];
        let mut add = |q: Point| {
            if points.last() != Some(&q) {
                points.push(q);
            }
        };
        if e == 0 {
            p.points.iter().for_each(|&q| add(q));
        } else {
            p.points.iter().rev().for_each(|&q| add(q));
        }
        let out_end = 1 - e;
        match link[k][out_end] {
            Some((nk, ne)) if !used[nk] => {
                k = nk;
                e = ne;
            }
            _ => {
                return Chain {
                    pair: pieces[k].pair,
                    ends: [first, vertex_of(pieces[k].ends[out_end])],
                    points,
                    closed: false,
                };
            }
        }
    }
}

/// Merges vertices joined by chains shorter than `merge_len`, then writes the complex.
fn build_complex(
    found: Vec<FoundVertex>,
    chains: Vec<Chain>,
    merge_len: f64,
    tol: f64,
) -> VoronoiComplex {
    let mut sets = DisjointSets::new(found.len());
    let mut short = vec![false; chains.len()];
    for (k, c) in chains.iter().enumerate() {
        if let [Some(a), Some(b)] = c.ends {
            if length(&c.points) <= merge_len || is_split_vertex(&found[a], &found[b], c, merge_len)
            {
                short[k] = true;
                sets.union(a, b);
            }
        }
    }
    // merged vertices: mean position, union of generators
    let mut index = vec![usize::MAX; found.len()];
    let mut acc: Vec<(Point, usize, Vec<u32>)> = Vec::new();
    for (v, fv) in found.iter().enumerate() {
        let r = sets.find(v);
        if index[r] == usize::MAX {
            index[r] = acc.len();
            acc.push((Point::new(0.0, 0.0), 0, Vec::new()));
        }
        let a = &mut acc[index[r]];
        a.0 = a.0 + fv.at;
        a.1 += 1;
        a.2.extend_from_slice(&fv.sites);
    }
    let mut out = VoronoiComplex::default();
    for (sum, n, mut sites) in acc {
        sites.sort_unstable();
        sites.dedup();
        out.vertices.push(Vertex {
            clearance: None,
            at: sum * (1.0 / n as f64),
            sites: sites
                .into_iter()
                .map(|s| Generator::Site(s as usize))
                .collect(),
        });
    }
    let mut vid = |v: usize| index[sets.find(v)];
    for (k, mut c) in chains.into_iter().enumerate() {
        if short[k] {
            continue;
        }
        let ends = [c.ends[0].map(&mut vid), c.ends[1].map(&mut vid)];
        for (e, end) in ends.iter().enumerate() {
            if let Some(v) = end {
                let at = out.vertices[*v].at;
                if e == 0 {
                    c.points[0] = at;
                } else if let Some(l) = c.points.last_mut() {
                    *l = at;
                }
            }
        }
        let points = simplify(&c.points, tol, c.closed);
        if points.len() < 2 || (ends[0] == ends[1] && retraces(&points, merge_len)) {
            continue;
        }
        out.edges.push(Edge {
            clearance: Vec::new(),
            sites_along: Vec::new(),
            sites: [
                Generator::Site(c.pair[0] as usize),
                Generator::Site(c.pair[1] as usize),
            ],
            from: ends[0],
            to: ends[1],
            points: points.into(),
            bisector: Vec::new(),
            parametric: Vec::new(),
        });
    }
    out
}

/// Whether chain `c` between vertices `a` and `b` joins two halves of one vertex: both
/// ends have three or more sites and lie within `tol` of each other, and the chain,
/// however bent, stays within `tol / 2` of their midpoint. At a vertex of four or more
/// tied sites (the centre of Shou et al.'s four circles) the leaves around it find two
/// vertices a leaf side apart, joined by chains that follow the sides between them.
fn is_split_vertex(a: &FoundVertex, b: &FoundVertex, c: &Chain, tol: f64) -> bool {
    let mid = (a.at + b.at) * 0.5;
    a.sites.len() >= 3
        && b.sites.len() >= 3
        && a.at.dist(b.at) <= tol
        && c.points.iter().all(|q| q.dist(mid) <= 0.5 * tol)
}

/// Whether a polyline goes out and comes back along itself within `tol` (its `i`-th
/// point from either end agree): a spike of no extent between two ends that are one,
/// left where uncertified boxes at a tangency of two sites link a piece to its own
/// return (two tangent circles of Shou et al.'s fourth example).
fn retraces(points: &[Point], tol: f64) -> bool {
    let n = points.len();
    (0..n / 2).all(|i| points[i].dist(points[n - 1 - i]) <= tol)
}

fn length(points: &[Point]) -> f64 {
    points.windows(2).map(|w| w[0].dist(w[1])).sum()
}

/// Douglas–Peucker simplification keeping both ends (and, for a loop, the farthest point).
fn simplify(points: &[Point], tol: f64, closed: bool) -> Vec<Point> {
    if points.len() <= 2 {
        return points.to_vec();
    }
    let mut keep = vec![false; points.len()];
    keep[0] = true;
    keep[points.len() - 1] = true;
    if closed {
        let far = (1..points.len() - 1)
            .max_by(|&i, &j| {
                points[i]
                    .dist(points[0])
                    .total_cmp(&points[j].dist(points[0]))
            })
            .unwrap_or(1);
        keep[far] = true;
        dp(points, 0, far, tol, &mut keep);
        dp(points, far, points.len() - 1, tol, &mut keep);
    } else {
        dp(points, 0, points.len() - 1, tol, &mut keep);
    }
    points
        .iter()
        .zip(keep)
        .filter(|(_, k)| *k)
        .map(|(p, _)| *p)
        .collect()
}

fn dp(points: &[Point], i: usize, j: usize, tol: f64, keep: &mut [bool]) {
    if j <= i + 1 {
        return;
    }
    let (a, b) = (points[i], points[j]);
    let dist = |p: Point| crate::geom::segment_distance(p, a, b);
    let (k, worst) = (i + 1..j)
        .map(|k| (k, dist(points[k])))
        .fold((i + 1, -1.0), |acc, x| if x.1 > acc.1 { x } else { acc });
    if worst > tol {
        keep[k] = true;
        dp(points, i, k, tol, keep);
        dp(points, k, j, tol, keep);
    }
}
