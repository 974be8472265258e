//! From trimmed runs to a `VoronoiComplex`: run ends that meet (within a small
//! tolerance) are clustered; a cluster where three or more generators meet is a Voronoi
//! vertex, a cluster of two runs of the same two generators is an inner joint (where a
//! foot moves from one span to the next, or a slab side), and the runs are chained
//! through the joints into edges. A run end of two generators that meets nothing
//! within the tolerance, nor the boundary, joins the nearest cluster within the chord
//! tolerance: the two parameterizations of one edge (a joint's normal, a branch of
//! `F3`), or the several runs that locate one degenerate vertex, meet only up to the
//! slivers next to a singular corner of `F3` that neither traces.

use super::pieces::{Feature, Pieces};
use super::trim::{End, Run};
use crate::complex::{Edge, Generator, ParametricPiece, SmallVec, Vertex, VoronoiComplex};
use crate::disjoint_sets::DisjointSets;
use crate::geom::grid::bounds_of_points;
use crate::geom::{segment_distance, Aabb, Point};
use std::collections::HashMap;

/// Ends the runs of two spans that stop (within `snap`) short of a corner where
/// both spans end and that generates nothing (inactive: the curve is convex there, seen
/// from the diagram's side) at that corner, a vertex of the corner and the two spans:
/// the bisector of the two spans reaches the corner along its angle bisector (HREK07
/// §7), but `F3` is singular at that corner of its square and the trace stops near it.
pub fn reach_corners(pieces: &Pieces, runs: &mut [Run], tol: f64, snap: f64) {
    let ends_at = |k: usize, p: Point| {
        let c = &pieces.spans[k].curve;
        c.eval(0.0).dist(p) <= tol || c.eval(1.0).dist(p) <= tol
    };
    for r in runs.iter_mut() {
        let [Feature::Span(a), Feature::Span(b)] = r.pair else {
            continue;
        };
        for which in [0, 1] {
            // (past the corner the samples are outside, or nearer to one of the two)
            let open = match r.ends[which] {
                End::Open => true,
                End::Vertex(h) => r.pair.contains(&h),
                End::Boundary => false,
            };
            if !open {
                continue;
            }
            let at = if which == 0 {
                r.points[0]
            } else {
                *r.points.last().unwrap()
            };
            let Some(k) = (0..pieces.corners.len()).find(|&k| {
                let c = &pieces.corners[k];
                !c.active && c.at.dist(at) <= snap && ends_at(a, c.at) && ends_at(b, c.at)
            }) else {
                continue;
            };
            let c = pieces.corners[k].at;
            if at.dist(c) <= tol {
                let i = if which == 0 { 0 } else { r.points.len() - 1 };
                r.points[i] = c;
            } else if which == 0 {
                r.points.insert(0, c);
            } else {
                r.points.push(c);
            }
            r.ends[which] = End::Vertex(Feature::Corner(k));
            // both feet now at the spans' ends on the corner
            let end_param = |s: usize| {
                let c0 = pieces.spans[s].curve.eval(0.0);
                Some(if c0.dist(c) <= snap { 0.0 } else { 1.0 })
            };
            r.feet[which] = [end_param(a), end_param(b)];
        }
    }
}

/// The complex of the runs, their ends clustered within `tol` (lone ends within
/// `snap`); also returns the number of loose run ends (ends that meet nothing and are
/// not on the boundary).
pub fn assemble(pieces: &Pieces, runs: Vec<Run>, tol: f64, snap: f64) -> (VoronoiComplex, usize) {
    let gens = |r: &Run| generators(pieces, r);
    let runs = &without_doubles(pieces, runs, snap);
    // cluster the run ends on a grid of cells of size `tol`
    let mut ends: Vec<(Point, usize, usize)> = Vec::new(); // point, run, which end
    for (k, r) in runs.iter().enumerate() {
        ends.push((r.points[0], k, 0));
        ends.push((*r.points.last().unwrap(), k, 1));
    }
    let cell = |p: Point| ((p.x / tol).floor() as i64, (p.y / tol).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut cluster_of = vec![usize::MAX; ends.len()];
    let mut clusters: Vec<Vec<usize>> = Vec::new();
    for (i, &(p, _, _)) in ends.iter().enumerate() {
        let (cx, cy) = cell(p);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = grid.get(&(cx + dx, cy + dy)) {
                    for &j in list {
                        if ends[j].0.dist(p) <= tol {
                            found = Some(cluster_of[j]);
                            break 'search;
                        }
                    }
                }
            }
        }
        let c = found.unwrap_or_else(|| {
            clusters.push(Vec::new());
            clusters.len() - 1
        });
        cluster_of[i] = c;
        clusters[c].push(i);
        grid.entry((cx, cy)).or_default().push(i);
    }
    for c in 0..clusters.len() {
        let [i] = clusters[c][..] else { continue };
        let (p, k, which) = ends[i];
        // (a ridge, one generator with itself, ends alone at a centre of curvature)
        let g = gens(&runs[k]);
        if runs[k].ends[which] == End::Boundary || g[0] == g[1] {
            continue;
        }
        let nearest = (0..ends.len())
            .filter(|&j| cluster_of[j] != c && ends[j].1 != k)
            .map(|j| (ends[j].0.dist(p), cluster_of[j]))
            .filter(|&(d, _)| d <= snap)
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, to)) = nearest {
            clusters[c].clear();
            clusters[to].push(i);
            cluster_of[i] = to;
        }
    }
    // a stub between two runs of the same two generators is no edge: a run of those
    // two, no longer than the snap, whose other end is in the same cluster (a sliver
    // of a near tie between two spans of one site leaving a cusp together, or where
    // both feet pass span ends at once) or meets nothing but such slivers (a piece of
    // a bisector past a joint's centre of curvature, beside its normal); it would make
    // a vertex of two generators
    let mut used = vec![false; runs.len()];
    let short = |k: usize| length(&runs[k].points) <= snap;
    let sliver = |k: usize| cluster_of[2 * k] == cluster_of[2 * k + 1] && short(k);
    // the cluster holds end `i` and slivers only
    let lone = |clusters: &[Vec<usize>], i: usize| {
        clusters[cluster_of[i]]
            .iter()
            .all(|&j| j == i || sliver(ends[j].1))
    };
    let stub = |clusters: &[Vec<usize>], i: usize| {
        let k = ends[i].1;
        short(k) && (sliver(k) || lone(clusters, i ^ 1))
    };
    for c in 0..clusters.len() {
        let (stubs, through): (Vec<usize>, Vec<usize>) =
            clusters[c].iter().partition(|&&i| stub(&clusters, i));
        let joint = match through[..] {
            [a, b] => {
                let g = gens(&runs[ends[a].1]);
                g == gens(&runs[ends[b].1]) && stubs.iter().all(|&i| gens(&runs[ends[i].1]) == g)
            }
            _ => false,
        };
        if joint && !stubs.is_empty() {
            clusters[c] = through;
            for i in stubs {
                used[ends[i].1] = true;
                // the stub's other end, and the slivers left alone with it
                let other = cluster_of[i ^ 1];
                if other != c {
                    for j in std::mem::take(&mut clusters[other]) {
                        used[ends[j].1] = true;
                    }
                }
            }
        }
    }
    // a cluster's generators and whether it is a vertex
    let mut complex = VoronoiComplex::default();
    let mut vertex_of = vec![None; clusters.len()];
    let mut boundary = vec![false; clusters.len()];
    let mut loose = 0;
    for (c, members) in clusters.iter().enumerate() {
        let mut g: Vec<Generator> = Vec::new();
        let mut third = false;
        for &i in members {
            let (_, k, which) = ends[i];
            let r = &runs[k];
            g.extend(gens(r));
            match r.ends[which] {
                End::Vertex(h) => {
                    g.push(pieces.generator(h));
                    third = true;
                }
                End::Boundary => boundary[c] = true,
                End::Open => {}
            }
        }
        g.sort();
        g.dedup();
        // the end of a ridge (an edge between two parts of one generator) at a centre of
        // curvature: a vertex listing that generator twice
        let ridge_end = members.len() == 1 && !boundary[c] && !third && g.len() == 1;
        // two edges of different pairs meeting (an edge whose generators change where it
        // crosses a zone boundary, as at the normal of a span at the corner it ends at):
        // a vertex of degree two
        let change = members.len() == 2 && !boundary[c] && {
            let (_, k0, _) = ends[members[0]];
            let (_, k1, _) = ends[members[1]];
            gens(&runs[k0]) != gens(&runs[k1])
        };
        if ridge_end || change || g.len() >= 3 || (members.len() >= 3 && !boundary[c]) {
            // (several runs of one generator's ridge meeting, as near a centre of
            // curvature: that generator, twice)
            if g.len() == 1 {
                g.push(g[0]);
            }
            let at = members
                .iter()
                .map(|&i| ends[i].0)
                .fold(Point::new(0.0, 0.0), |a, p| a + p)
                * (1.0 / members.len() as f64);
            vertex_of[c] = Some(complex.vertices.len());
            complex.vertices.push(Vertex {
                clearance: None,
                at,
                sites: SmallVec::from_vec(g),
            });
        } else if members.len() == 1 && !boundary[c] && !third {
            loose += 1;
        }
    }
    // chain runs through joints (clusters of exactly two run ends, not vertices)
    let other_end = |c: usize, i: usize| clusters[c].iter().copied().find(|&j| j != i);
    for start in 0..runs.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let g = gens(&runs[start]);
        // walk backwards from the start's first end to find the chain's beginning
        let mut chain: Vec<(usize, bool)> = vec![(start, false)]; // run, reversed
        for dir in [0usize, 1] {
            let (mut k, mut which) = (start, dir);
            loop {
                let i = 2 * k + which;
                let c = cluster_of[i];
                if vertex_of[c].is_some() || boundary[c] || clusters[c].len() != 2 {
                    break;
                }
                let Some(j) = other_end(c, i) else { break };
                let (_, kn, wn) = ends[j];
                if used[kn] || gens(&runs[kn]) != g {
                    break;
                }
                used[kn] = true;
                // entering run kn at end wn; continue from its other end
                let reversed = if dir == 1 { wn == 1 } else { wn == 0 };
                if dir == 1 {
                    chain.push((kn, reversed));
                } else {
                    chain.insert(0, (kn, reversed));
                }
                k = kn;
                which = 1 - wn;
            }
        }
        let mut points: Vec<Point> = Vec::new();
        for &(k, rev) in &chain {
            let mut p = runs[k].points.clone();
            if rev {
                p.reverse();
            }
            if points
                .last()
                .is_some_and(|q| p.first().is_some_and(|f| q.dist(*f) <= tol))
            {
                p.remove(0);
            }
            points.extend(p);
        }
        let (k0, rev0) = chain[0];
        let (k1, rev1) = *chain.last().unwrap();
        let first_end = 2 * k0 + usize::from(rev0);
        let last_end = 2 * k1 + usize::from(!rev1);
        let (c0, c1) = (cluster_of[first_end], cluster_of[last_end]);
        let (from, to) = (vertex_of[c0], vertex_of[c1]);
        if let Some(v) = from {
            points[0] = complex.vertices[v].at;
        }
        if let Some(v) = to {
            *points.last_mut().unwrap() = complex.vertices[v].at;
        }
        let closed = from.is_none() && to.is_none() && c0 == c1 && chain.len() > 1;
        if closed {
            let first = points[0];
            *points.last_mut().unwrap() = first;
        }
        // a run from a vertex back to it no longer than the snap (ε/4) is no edge:
        // degenerate meetings (a centre of curvature of two spans) leave thousands
        if points.len() < 2 || (from.is_some() && from == to && length(&points) <= snap) {
            continue;
        }
        let parametric = chain
            .iter()
            .map(|&(k, rev)| parametric_piece(pieces, &runs[k], rev))
            .collect();
        complex.edges.push(Edge {
            clearance: Vec::new(),
            sites_along: Vec::new(),
            sites: g,
            from,
            to,
            points: SmallVec::from_vec(points),
            bisector: Vec::new(),
            parametric,
        });
    }
    merge_close_vertices(&mut complex, snap);
    (complex, loose)
}

/// The two generators of a run, sorted.
fn generators(pieces: &Pieces, r: &Run) -> [Generator; 2] {
    let mut g = [pieces.generator(r.pair[0]), pieces.generator(r.pair[1])];
    g.sort();
    g
}

/// `runs` without those that only trace again, within `snap`, a part of a longer run of
/// the same two generators: where a joint's normal passes its centre of curvature, the
/// distance to the curve is flat across the normal, and the branch of `F3` beside it
/// runs along the normal for a stretch longer than `snap`, a loose end inside an edge.
fn without_doubles(pieces: &Pieces, runs: Vec<Run>, snap: f64) -> Vec<Run> {
    let lengths: Vec<f64> = runs.iter().map(|r| length(&r.points)).collect();
    let boxes: Vec<Aabb> = runs
        .iter()
        .map(|r| bounds_of_points(r.points.iter().copied()))
        .collect();
    // box `a` inside box `b` grown by `snap`
    let inside = |a: &Aabb, b: &Aabb| {
        a.min.x >= b.min.x - snap
            && a.min.y >= b.min.y - snap
            && a.max.x <= b.max.x + snap
            && a.max.y <= b.max.y + snap
    };
    let pairs: Vec<[Generator; 2]> = runs.iter().map(|r| generators(pieces, r)).collect();
    let mut by_pair: HashMap<[Generator; 2], Vec<usize>> = HashMap::new();
    for (k, pair) in pairs.iter().enumerate() {
        by_pair.entry(*pair).or_default().push(k);
    }
    let traced_again = |k: usize| {
        lengths[k] > snap
            && by_pair[&pairs[k]].iter().any(|&j| {
                j != k
                    && lengths[j] > lengths[k]
                    && inside(&boxes[k], &boxes[j])
                    && runs[k].points.iter().all(|&q| {
                        runs[j]
                            .points
                            .windows(2)
                            .any(|w| segment_distance(q, w[0], w[1]) <= snap)
                    })
            })
    };
    let doubled: Vec<bool> = (0..runs.len()).map(traced_again).collect();
    runs.into_iter()
        .zip(doubled)
        .filter_map(|(r, d)| (!d).then_some(r))
        .collect()
}

/// The length of a polyline.
fn length(points: &[Point]) -> f64 {
    points.windows(2).map(|w| w[0].dist(w[1])).sum()
}

/// Run `r` in parameter space, in the order of the edge's generators (sorted), its end
/// feet swapped when it runs against the edge.
fn parametric_piece(pieces: &Pieces, r: &Run, reversed: bool) -> ParametricPiece {
    let curve = |f: Feature| match f {
        Feature::Span(k) => pieces.spans[k].curve.homogeneous().to_vec(),
        Feature::Corner(k) => {
            let p = pieces.corners[k].at;
            vec![[p.x, p.y, 1.0]]
        }
    };
    let [from, to] = if reversed {
        [r.feet[1], r.feet[0]]
    } else {
        r.feet
    };
    let mut piece = ParametricPiece {
        curves: r.pair.map(curve),
        from,
        to,
    };
    if pieces.generator(r.pair[0]) > pieces.generator(r.pair[1]) {
        piece.curves.swap(0, 1);
        piece.from.swap(0, 1);
        piece.to.swap(0, 1);
    }
    piece
}

/// Merges the vertices closer than `snap`, or joined by an edge no longer than it (a
/// degenerate meeting of four or more generators comes out as vertices a rounding
/// apart, some joined by tiny edges), into one that lists the generators of all,
/// dropping those edges; a vertex left without an edge (the end of a run from a vertex
/// back to it) goes too.
fn merge_close_vertices(complex: &mut VoronoiComplex, snap: f64) {
    let short = |e: &Edge| length(&e.points) <= snap;
    let mut sets = DisjointSets::new(complex.vertices.len());
    for e in &complex.edges {
        if let (Some(a), Some(b)) = (e.from, e.to) {
            if a != b && short(e) {
                sets.union(a, b);
            }
        }
    }
    let mut by_x: Vec<usize> = (0..complex.vertices.len()).collect();
    by_x.sort_by(|&a, &b| {
        complex.vertices[a]
            .at
            .x
            .total_cmp(&complex.vertices[b].at.x)
    });
    for (k, &a) in by_x.iter().enumerate() {
        let p = complex.vertices[a].at;
        for &b in &by_x[k + 1..] {
            let q = complex.vertices[b].at;
            if q.x - p.x > snap {
                break;
            }
            if p.dist(q) <= snap {
                sets.union(a, b);
            }
        }
    }
    for v in 0..complex.vertices.len() {
        let r = sets.find(v);
        if r != v {
            let merged = complex.vertices[v].sites.clone();
            let sites = &mut complex.vertices[r].sites;
            for g in merged {
                if !sites.contains(&g) {
                    sites.push(g);
                }
            }
            sites.sort();
        }
    }
    complex
        .edges
        .retain(|e| !(e.from.is_some() && e.to.is_some() && e.from != e.to && short(e)));
    for e in &mut complex.edges {
        for end in [&mut e.from, &mut e.to] {
            *end = end.map(|v| sets.find(v));
        }
        if let Some(v) = e.from {
            e.points[0] = complex.vertices[v].at;
        }
        if let Some(v) = e.to {
            *e.points.last_mut().expect("two points or more") = complex.vertices[v].at;
        }
    }
    complex.drop_unused_vertices();
}
