//! From the half-edge graph to the clipped [`VoronoiComplex`].

use super::cells::{face_cells, Inconsistent};
use super::graph::GHOST;
use super::predicates::{circumcenter, incircle};
use super::PointDiagram;
use crate::complex::{Edge, Generator, Vertex, VoronoiComplex};
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, Point};
use crate::par::{filter_map_range, map_range, unzip_range};

/// What the edge pass needs of a vertex, packed so that the random access to an
/// edge's far end costs one cache miss: its group's position, group and output index.
#[derive(Clone, Copy)]
struct Node {
    at: Point,
    group: u32,
    out: u32,
}

/// The clipped complex; with `with_cells`, also its cells traced from the graph's faces
/// (`false` when a face could not be traced consistently; `cells` is then empty).
pub(super) fn to_complex(d: &PointDiagram, with_cells: bool) -> (VoronoiComplex, bool) {
    let (mut nodes, parent) = vertex_groups(d);
    let vertices = output_vertices(d, &mut nodes, parent.as_deref());
    let edges = output_edges(d, &nodes);
    let mut c = VoronoiComplex {
        vertices,
        edges,
        ..Default::default()
    };
    let traced = !with_cells || trace_cells(d, &nodes, &mut c);
    record_stats(d, &mut c);
    (c, traced)
}

/// Whether vertex `v` is a vertex of three input sites (not the vertex at infinity, no
/// far generator).
fn is_real(d: &PointDiagram, v: usize) -> bool {
    let n = d.input.len() as u32;
    v != GHOST as usize && d.graph.gens[v].iter().all(|&s| s < n)
}

/// The vertices' circumcentres (scaled coordinates; the vertex at infinity gets a
/// dummy) and, where zero-length edges join vertices of exactly cocircular generators,
/// each vertex's group as its least member (`None` when no two vertices coincide).
fn vertex_groups(d: &PointDiagram) -> (Vec<Node>, Option<Vec<u32>>) {
    let g = &d.graph;
    let nv = g.gens.len();
    let pos = |s: u32| d.pts[s as usize];
    let real = |v: usize| is_real(d, v);
    // In the same pass as the circumcentres, the zero-length edges: bit k of `zero[v]`
    // marks half-edge 3v + k as joining `v` to a vertex of exactly cocircular
    // generators. A vertex with a far generator lies outside the domain, so only real
    // ones matter.
    let (nodes, zero): (Vec<Node>, Vec<u8>) = unzip_range(nv, 1 << 12, |v| {
        let [a, b, c] = g.gens[v].map(pos);
        let at = if v == GHOST as usize {
            Point::default()
        } else {
            circumcenter(a, b, c)
        };
        let mut zero = 0;
        if real(v) {
            for k in 0..3 {
                let h = 3 * v + k;
                let t = g.twin[h] as usize;
                if h < t && real(t / 3) {
                    let x = pos(g.gens[t / 3][(t % 3 + 2) % 3]);
                    zero |= u8::from(incircle(a, b, c, x) == 0.0) << k;
                }
            }
        }
        let node = Node {
            at,
            group: v as u32,
            out: u32::MAX,
        };
        (node, zero)
    });
    let cocircular: Vec<(u32, u32)> = (0..3 * nv)
        .filter(|&h| zero[h / 3] >> (h % 3) & 1 != 0)
        .map(|h| (h as u32 / 3, g.twin[h] / 3))
        .collect();
    if cocircular.is_empty() {
        return (nodes, None);
    }
    let mut sets = DisjointSets::new(nv);
    for &(u, w) in &cocircular {
        sets.union(u as usize, w as usize);
    }
    // the root is the group's least vertex
    let roots = sets.roots().into_iter().map(|r| r as u32).collect();
    (nodes, Some(roots))
}

/// The output vertices: the groups whose representative lies in the closed domain,
/// numbered in vertex order, each listing every site of its group; `nodes` learn their
/// output index and group.
fn output_vertices(d: &PointDiagram, nodes: &mut [Node], parent: Option<&[u32]>) -> Vec<Vertex> {
    let g = &d.graph;
    let nv = g.gens.len();
    let inv = 1.0 / d.scale;
    let site = |s: u32| Generator::Site(d.input[s as usize] as usize);
    let mut outs: Vec<u32> = Vec::new();
    for v in 0..nv {
        let rep = parent.map_or(v, |p| p[v] as usize);
        if rep == v && is_real(d, v) && d.domain.contains(nodes[v].at) {
            nodes[v].out = outs.len() as u32;
            outs.push(v as u32);
        }
    }
    let mut vertices = map_range(outs.len(), 1 << 12, |k| {
        let v = outs[k] as usize;
        let mut ids = g.gens[v].map(|s| d.input[s as usize]);
        ids.sort_unstable();
        Vertex {
            clearance: None,
            at: nodes[v].at * inv,
            sites: ids.map(|i| Generator::Site(i as usize)).into(),
        }
    });
    if let Some(parent) = parent {
        for v in 0..nv {
            let r = parent[v] as usize;
            if r != v {
                nodes[v] = Node {
                    group: r as u32,
                    ..nodes[r]
                };
                if nodes[r].out != u32::MAX {
                    let sites = &mut vertices[nodes[r].out as usize].sites;
                    sites.extend(g.gens[v].iter().map(|&s| site(s)));
                }
            }
        }
        for v in vertices.iter_mut() {
            v.sites.sort_unstable();
            v.sites.dedup();
        }
    }
    vertices
}

/// The edges between real sites, between distinct groups, clipped to the domain: their
/// half-edges first, so that the edges are written in place.
fn output_edges(d: &PointDiagram, nodes: &[Node]) -> Vec<Edge> {
    let g = &d.graph;
    let inv = 1.0 / d.scale;
    let site = |s: u32| Generator::Site(d.input[s as usize] as usize);
    let kept = filter_map_range(g.twin.len(), 1 << 12, |h| {
        let h = h as u32;
        let t = g.twin[h as usize];
        (h < t && clip(d, nodes, h, t).is_some()).then_some(h)
    });
    map_range(kept.len(), 1 << 12, |k| {
        let h = kept[k];
        let ((start, end), (from, to)) =
            clip(d, nodes, h, g.twin[h as usize]).expect("a kept edge");
        let (a, b) = (g.right(h), g.left(h));
        Edge {
            clearance: Vec::new(),
            sites_along: Vec::new(),
            sites: [site(b), site(a)],
            from,
            to,
            points: [start * inv, end * inv].into(),
            bisector: Vec::new(),
            parametric: Vec::new(),
        }
    })
}

/// Traces `c`'s cells from the graph's faces, along the same segments as the edges;
/// `false` (and no cells) when a face is inconsistent.
fn trace_cells(d: &PointDiagram, nodes: &[Node], c: &mut VoronoiComplex) -> bool {
    let g = &d.graph;
    let inv = 1.0 / d.scale;
    // The same segments as the edges, in the direction of each half-edge.
    let segment = |h: u32| {
        let t = g.twin[h as usize];
        let ((p, q), _) = clip(d, nodes, h.min(t), h.max(t))?;
        Some(if h < t {
            (p * inv, q * inv)
        } else {
            (q * inv, p * inv)
        })
    };
    let domain = Aabb::new(d.domain.min * inv, d.domain.max * inv);
    match face_cells(d, segment, domain) {
        Ok(cells) => {
            c.cells = cells;
            true
        }
        Err(Inconsistent) => false,
    }
}

/// The run's figures in `c.stats`.
fn record_stats(d: &PointDiagram, c: &mut VoronoiComplex) {
    let stat = |v: usize| serde_json::Value::from(v);
    c.stats.insert("sites".into(), stat(d.input.len()));
    c.stats
        .insert("duplicate_sites".into(), stat(d.duplicates.len()));
    c.stats
        .insert("skipped_sites".into(), stat(d.skipped.len()));
    c.stats
        .insert("topology_overrides".into(), stat(d.overrides));
    c.stats
        .insert("seed_fallbacks".into(), stat(d.seed_fallbacks));
    c.stats.insert("vertices".into(), stat(c.vertices.len()));
    c.stats.insert("edges".into(), stat(c.edges.len()));
}

/// The edge of half-edge `h` (`h < t = twin(h)`, from `u = h / 3` to `w = t / 3`) as
/// output: its segment clipped to the domain (scaled coordinates) and its end vertices'
/// output indices, or `None` when it separates a far generator, joins two vertices of
/// one group, or meets the domain in less than a segment.
#[allow(clippy::type_complexity)]
#[inline]
fn clip(
    d: &PointDiagram,
    nodes: &[Node],
    h: u32,
    t: u32,
) -> Option<((Point, Point), (Option<usize>, Option<usize>))> {
    let g = &d.graph;
    let (nu, nw) = (nodes[h as usize / 3], nodes[t as usize / 3]);
    if nu.group == nw.group {
        return None;
    }
    let (from, to) = (
        (nu.out != u32::MAX).then_some(nu.out as usize),
        (nw.out != u32::MAX).then_some(nw.out as usize),
    );
    if from.is_some() && to.is_some() {
        // Both ends are output, hence real: so are the edge's generators.
        return Some(((nu.at, nw.at), (from, to)));
    }
    let n = d.input.len() as u32;
    let (a, b) = (g.right(h), g.left(h));
    if a >= n || b >= n {
        return None;
    }
    // Clip on the bisector m + s·dir, dir = (a − b)⊥ (from u to w, b on the left):
    // parameters stay accurate when a vertex is very far away.
    let (pa, pb) = (d.pts[a as usize], d.pts[b as usize]);
    let (m, dir) = (pa.lerp(pb, 0.5), (pa - pb).perp());
    let param = |p: Point| (p - m).dot(dir) / dir.dot(dir);
    let (s0, s1) = d.domain.line_range(m, dir)?;
    let lo = if from.is_some() {
        param(nu.at)
    } else {
        param(nu.at).max(s0)
    };
    let hi = if to.is_some() {
        param(nw.at)
    } else {
        param(nw.at).min(s1)
    };
    if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let on_line = |s: f64| d.domain.clamp(m + dir * s);
    let ends = (
        if from.is_some() { nu.at } else { on_line(lo) },
        if to.is_some() { nw.at } else { on_line(hi) },
    );
    Some((ends, (from, to)))
}
