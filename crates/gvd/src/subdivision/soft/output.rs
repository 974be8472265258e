//! From the assembled graph of feature indices to the scene's diagram: generators
//! named as features (`complex`, `medial_axis`) or merged into sites (`voronoi`),
//! and everything clipped to the scene's domain (the subdivision runs over a slightly
//! larger, off-centre box, so that no box side lies on a symmetry line of the input).

use crate::complex::{Edge, Generator, Vertex, VoronoiComplex};
use crate::geom::{Aabb, Point};
use crate::site::polygonal::Polygonal;

/// Names the generators: a feature index becomes the feature's owners (the first on
/// edges; all of them at vertices, where shared endpoints count for every site).
pub fn name_features(c: &mut VoronoiComplex, poly: &Polygonal) {
    let owners = |g: &Generator| match *g {
        Generator::Site(f) => poly.features[f].owners.clone(),
        other => smallvec::smallvec![other],
    };
    for v in &mut c.vertices {
        let mut sites: Vec<Generator> = v.sites.iter().flat_map(owners).collect();
        sites.sort_unstable();
        sites.dedup();
        v.sites = sites.into();
    }
    for e in &mut c.edges {
        e.sites = [owners(&e.sites[0])[0], owners(&e.sites[1])[0]];
    }
}

/// `voronoi` mode: generators become sites; edges between two features of one site
/// are dropped, and chains through vertices left with two edges and fewer than three
/// sites are joined into one edge.
pub fn to_sites(c: VoronoiComplex) -> VoronoiComplex {
    let site = |g: &Generator| Generator::Site(g.site());
    let edges: Vec<Edge> = c
        .edges
        .into_iter()
        .map(|mut e| {
            e.sites = [site(&e.sites[0]), site(&e.sites[1])];
            e
        })
        .filter(|e| e.sites[0] != e.sites[1])
        .collect();
    let vertices: Vec<Vertex> = c
        .vertices
        .into_iter()
        .map(|mut v| {
            let mut s: Vec<Generator> = v.sites.iter().map(site).collect();
            s.sort_unstable();
            s.dedup();
            v.sites = s.into();
            v
        })
        .collect();
    // join edges through vertices of two edges and fewer than three sites
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); vertices.len()];
    for (k, e) in edges.iter().enumerate() {
        for v in [e.from, e.to].into_iter().flatten() {
            incident[v].push(k);
        }
    }
    let through =
        |v: Option<usize>| v.filter(|&v| incident[v].len() == 2 && vertices[v].sites.len() < 3);
    let mut used = vec![false; edges.len()];
    let mut out: Vec<Edge> = Vec::with_capacity(edges.len());
    let walk = |k: usize, forward: bool, used: &mut Vec<bool>, closed: bool| {
        let flip = |e: &Edge, fwd: bool| {
            let mut e = e.clone();
            if !fwd {
                e.points.reverse();
                std::mem::swap(&mut e.from, &mut e.to);
            }
            e
        };
        let mut chain = flip(&edges[k], forward);
        used[k] = true;
        while let Some(v) = through(chain.to) {
            let Some(&next) = incident[v].iter().find(|&&j| !used[j]) else {
                break;
            };
            used[next] = true;
            let e = flip(&edges[next], edges[next].from == Some(v));
            chain.points.extend(e.points.iter().skip(1).copied());
            chain.to = e.to;
        }
        if closed {
            chain.from = None;
            chain.to = None;
        }
        chain
    };
    for k in 0..edges.len() {
        for forward in [true, false] {
            let start = if forward { edges[k].from } else { edges[k].to };
            if !used[k] && through(start).is_none() {
                out.push(walk(k, forward, &mut used, false));
            }
        }
    }
    for k in 0..edges.len() {
        if !used[k] {
            out.push(walk(k, true, &mut used, true));
        }
    }
    // the vertices joined through are no longer ends: dropped below
    let edges = out;
    drop_unused(vertices, edges, c.stats)
}

/// Keeps the vertices that some edge ends at, renumbered.
fn drop_unused(
    vertices: Vec<Vertex>,
    mut edges: Vec<Edge>,
    stats: std::collections::BTreeMap<String, serde_json::Value>,
) -> VoronoiComplex {
    let mut used = vec![false; vertices.len()];
    for e in &edges {
        for v in [e.from, e.to].into_iter().flatten() {
            used[v] = true;
        }
    }
    let mut index = vec![usize::MAX; vertices.len()];
    let mut kept = Vec::new();
    for (v, vx) in vertices.into_iter().enumerate() {
        if used[v] {
            index[v] = kept.len();
            kept.push(vx);
        }
    }
    for e in &mut edges {
        e.from = e.from.map(|v| index[v]);
        e.to = e.to.map(|v| index[v]);
    }
    VoronoiComplex {
        vertices: kept,
        edges,
        stats,
        ..Default::default()
    }
}

/// The complex inside the domain `d`: edges cut where they leave it (those ends become
/// boundary ends), vertices outside dropped.
pub fn clip(c: VoronoiComplex, d: &Aabb) -> VoronoiComplex {
    let inside = |p: Point| d.outside_distance(p) == 0.0;
    let mut edges = Vec::new();
    for e in c.edges {
        let mut run: Vec<Point> = Vec::new();
        let mut run_from = if e.points.first().is_some_and(|&p| inside(p)) {
            e.from.filter(|&v| inside(c.vertices[v].at))
        } else {
            None
        };
        let n = e.points.len();
        for k in 0..n.saturating_sub(1) {
            let (a, b) = (e.points[k], e.points[k + 1]);
            let Some((t0, t1)) = d.segment_range(a, b) else {
                continue;
            };
            let (p, q) = (a.lerp(b, t0), a.lerp(b, t1));
            if run.is_empty() || t0 > 0.0 {
                if run.len() >= 2 {
                    edges.push(Edge {
                        clearance: Vec::new(),
                        sites_along: Vec::new(),
                        sites: e.sites,
                        from: run_from,
                        to: None,
                        points: std::mem::take(&mut run).into(),
                        bisector: Vec::new(),
                        parametric: Vec::new(),
                    });
                }
                run.clear();
                if t0 > 0.0 {
                    run_from = None;
                }
                run.push(p);
            }
            run.push(q);
            if t1 < 1.0 {
                if run.len() >= 2 {
                    edges.push(Edge {
                        clearance: Vec::new(),
                        sites_along: Vec::new(),
                        sites: e.sites,
                        from: run_from,
                        to: None,
                        points: std::mem::take(&mut run).into(),
                        bisector: Vec::new(),
                        parametric: Vec::new(),
                    });
                }
                run.clear();
                run_from = None;
            }
        }
        if run.len() >= 2 {
            let to = e.to.filter(|&v| inside(c.vertices[v].at));
            let closed = e.from.is_none() && e.to.is_none() && run_from.is_none();
            edges.push(Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites: e.sites,
                from: run_from,
                to: if closed { None } else { to },
                points: run.into(),
                bisector: Vec::new(),
                parametric: Vec::new(),
            });
        }
    }
    drop_unused(c.vertices, edges, c.stats)
}
