//! Cells from edges: the faces of the planar subdivision that a complex's edge
//! polylines and the domain boundary form, each labelled with the site it belongs to.

use super::{Cell, VoronoiComplex};
use crate::geom::grid::{bounds_of_points, BucketGrid};
use crate::geom::ring::{even_odd_contains, signed_area};
use crate::geom::{Aabb, Point};
use crate::offset::feature::{Features, Shape};
use crate::scene::Scene;
use std::cmp::Ordering;
use std::collections::BTreeMap;
use std::f64::consts::TAU;

/// Angles closer than this (radians) are ties, broken by the polylines' later points.
const ANGLE_TIE: f64 = 1e-10;

/// How far from a node (in units of the merge tolerance, 1e-10 of the domain) an edge's
/// direction is taken: 1e-7 of the domain.
const DEPARTURE_REACH: f64 = 1e3;

/// The cells of the subdivision formed by `complex`'s edges and `domain`'s boundary.
///
/// Edge ends without a vertex are snapped onto the boundary; closed loops without a
/// vertex become islands (an inner ring and a clockwise hole in the surrounding cell).
/// Each face goes to the site `label` returns just inside it, chosen among the
/// generators of its edges. Returns one [`Cell`] per site with a face, sorted by site,
/// outer rings counter-clockwise first, then clockwise holes. Inconsistent input
/// (unknown vertex, non-finite point, degenerate loop) is skipped, never a panic.
pub fn build_cells(
    complex: &VoronoiComplex,
    domain: &Aabb,
    label: &(dyn Fn(Point) -> usize + Sync),
) -> Vec<Cell> {
    let (w, h) = (domain.width(), domain.height());
    if !(w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite()) {
        return Vec::new();
    }
    let tol = 1e-10 * domain.longest_side();
    let mut g = Graph::new(complex, domain, tol);
    let mut faces = Vec::new();
    for (k, e) in complex.edges.iter().enumerate() {
        if e.points.len() < 2
            || e.points
                .iter()
                .any(|p| !(p.x.is_finite() && p.y.is_finite()))
        {
            continue;
        }
        let sites = [e.sites[0].site(), e.sites[1].site()];
        let (first, last) = (e.points[0], e.points[e.points.len() - 1]);
        // A loop: closed, or its ends nearer each other than to the boundary.
        let gap = first.dist(last);
        let closed = gap <= tol || gap < g.boundary_dist(first).min(g.boundary_dist(last));
        if e.from.is_none() && e.to.is_none() && e.points.len() > 2 && closed {
            faces.extend(island(&e.points, domain, tol, sites));
            continue;
        }
        let (Some(u), Some(v)) = (g.end_node(e.from, first), g.end_node(e.to, last)) else {
            continue;
        };
        g.edges.push((u, v, k));
    }
    faces.extend(g.faces(complex));

    #[cfg(feature = "parallel")]
    let votes: Vec<Option<usize>> = {
        use rayon::prelude::*;
        faces.par_iter().map(|f| vote(f, label)).collect()
    };
    #[cfg(not(feature = "parallel"))]
    let votes: Vec<Option<usize>> = faces.iter().map(|f| vote(f, label)).collect();
    let mut holes_biggest: Option<(f64, usize)> = None;
    let mut sited: Vec<(usize, Face)> = Vec::new();
    let mut plain = Vec::new();
    for (f, site) in faces.into_iter().zip(votes) {
        match site {
            Some(s) => {
                if f.area < 0.0 && holes_biggest.is_none_or(|(a, _)| -f.area > a) {
                    holes_biggest = Some((-f.area, s));
                }
                sited.push((s, f));
            }
            None => plain.push(f),
        }
    }
    // A face bounded by the domain alone is the whole domain, possibly with islands:
    // the biggest hole is an outermost one, and its left side is this face.
    let whole = holes_biggest.map_or_else(|| label(domain.center()), |(_, s)| s);
    sited.extend(plain.into_iter().map(|f| (whole, f)));

    let mut by_site: BTreeMap<usize, Vec<Face>> = BTreeMap::new();
    for (s, f) in sited {
        by_site.entry(s).or_default().push(f);
    }
    by_site
        .into_iter()
        .filter(|(_, fs)| fs.iter().any(|f| f.area > 0.0))
        .map(|(site, mut fs)| {
            fs.sort_by_key(|f| f.area < 0.0);
            Cell {
                site,
                rings: fs.into_iter().map(|f| f.ring).collect(),
            }
        })
        .collect()
}

/// The cells of a `voronoi`-mode diagram of Euclidean points, segments, arcs, polylines
/// and polygons: [`build_cells`] with each face given to its nearest site, found among
/// the sites' corners, edges and arcs bucketed about one per grid cell. A polygon's
/// inside is part of its cell (a point inside it is nearer to its boundary than to any
/// other site, which lies outside). Arcs' cells are bounded by the edges' polylines,
/// within epsilon of the true curves. Empty for scenes of other kinds.
pub(crate) fn site_cells(complex: &VoronoiComplex, scene: &Scene) -> Vec<Cell> {
    let Ok(features) = Features::of_scene(scene) else {
        return Vec::new();
    };
    let (shapes, site_of) = (&features.shapes, features.sites_of_shapes());
    if shapes.is_empty() {
        return Vec::new();
    }
    let domain = scene.domain();
    let boxes: Vec<Aabb> = shapes.iter().map(Shape::bounds).collect();
    let corners = boxes.iter().flat_map(|b| [b.min, b.max]);
    let extent = bounds_of_points(corners.chain([domain.min, domain.max]));
    let n = ((shapes.len() as f64).sqrt().ceil() as usize).clamp(1, 1024);
    let side = (extent.width() * extent.height() / (n * n) as f64).sqrt();
    let side = side.max(extent.longest_side() / 1024.0);
    let grid = BucketGrid::new(extent, side, 1024, shapes.len(), |k| boxes[k]);
    build_cells(complex, &domain, &|q| {
        grid.nearest_by(q, |k| shapes[k as usize].distance(q))
            .map_or(0, |(_, k)| site_of[k as usize])
    })
}

/// A closed face boundary: `ring[i] → ring[i + 1]` lies on an edge of those generator
/// sites (`None` on the domain boundary). Positive area: counter-clockwise outer ring.
struct Face {
    ring: Vec<Point>,
    sites: Vec<Option<[usize; 2]>>,
    area: f64,
}

impl Face {
    fn new(ring: Vec<Point>, sites: Vec<Option<[usize; 2]>>) -> Option<Face> {
        let area = signed_area(&ring);
        (ring.len() >= 3 && area != 0.0 && area.is_finite()).then_some(Face { ring, sites, area })
    }
}

/// The inside ring and the surrounding face's hole of a closed loop edge.
fn island(points: &[Point], domain: &Aabb, tol: f64, sites: [usize; 2]) -> Vec<Face> {
    let mut ring = dedup(points.iter().map(|&p| domain.clamp(p)), tol);
    while ring.len() > 1 && ring[ring.len() - 1].dist(ring[0]) <= tol {
        ring.pop();
    }
    if signed_area(&ring) < 0.0 {
        ring.reverse();
    }
    let mut hole = ring.clone();
    hole.reverse();
    let n = ring.len();
    [ring, hole]
        .into_iter()
        .filter_map(|r| Face::new(r, vec![Some(sites); n]))
        .collect()
}

/// The site of a face: `label` at points just left of its longest edge segments (and
/// inside the face), counted only when it names one of the segment's generators; the
/// most frequent wins (else `label` a hair left of the longest). `None` for a face with
/// no edge segment.
fn vote(f: &Face, label: &(dyn Fn(Point) -> usize + Sync)) -> Option<usize> {
    let n = f.ring.len();
    let mut segs: Vec<(f64, usize, [usize; 2])> = (0..n)
        .filter_map(|i| f.sites[i].map(|s| (f.ring[i].dist(f.ring[(i + 1) % n]), i, s)))
        .collect();
    if segs.is_empty() {
        return None;
    }
    segs.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut votes: Vec<(usize, usize)> = Vec::new();
    let mut fallback = None;
    for &(_, i, sites) in segs.iter().take(8) {
        let (p, q) = (f.ring[i], f.ring[(i + 1) % n]);
        let mid = p.lerp(q, 0.5);
        fallback.get_or_insert_with(|| label(mid + (q - p).perp() * 1e-3));
        let inside = [0.25, 0.02]
            .into_iter()
            .map(|t| mid + (q - p).perp() * t)
            .find(|&x| even_odd_contains(&f.ring, x) == (f.area > 0.0));
        let Some(s) = inside.map(label).filter(|s| sites.contains(s)) else {
            continue;
        };
        match votes.iter_mut().find(|v| v.0 == s) {
            Some(v) => v.1 += 1,
            None => votes.push((s, 1)),
        }
        if votes.iter().map(|v| v.1).sum::<usize>() >= 3 {
            break;
        }
    }
    // The first best by count: `max_by_key` would keep the last.
    let best = votes.iter().fold(None::<(usize, usize)>, |b, &v| match b {
        Some(b) if b.1 >= v.1 => Some(b),
        _ => Some(v),
    });
    best.map(|b| b.0).or(fallback)
}

/// A graph node: a Voronoi vertex, a domain corner or a boundary hit point.
struct Node {
    at: Point,
    /// Position along the boundary (counter-clockwise from `domain.min`), if on it.
    t: Option<f64>,
    /// Union-find parent.
    parent: usize,
}

/// One direction of an edge or boundary piece: a polyline from node `from`.
struct HalfEdge {
    from: usize,
    points: Vec<Point>,
    sites: Option<[usize; 2]>,
    /// Traversed clockwise along the domain boundary (the outside face).
    outside: bool,
}

struct Graph<'a> {
    domain: &'a Aabb,
    tol: f64,
    /// The number of vertex nodes; the four corners follow them.
    nv: usize,
    nodes: Vec<Node>,
    /// Open edges as `(from node, to node, edge index)`.
    edges: Vec<(usize, usize, usize)>,
}

impl<'a> Graph<'a> {
    /// Vertex nodes first (index = vertex index), then the four corners.
    fn new(complex: &VoronoiComplex, domain: &'a Aabb, tol: f64) -> Graph<'a> {
        let mut g = Graph {
            domain,
            tol,
            nv: complex.vertices.len(),
            nodes: Vec::new(),
            edges: Vec::new(),
        };
        for v in &complex.vertices {
            let at = domain.clamp(v.at);
            if g.boundary_dist(at) <= tol {
                let at = g.snap(at);
                let t = g.boundary_t(at);
                g.push(at, t);
            } else {
                g.push(at, None);
            }
        }
        let (a, b) = (domain.min, domain.max);
        for c in [a, Point::new(b.x, a.y), b, Point::new(a.x, b.y)] {
            let t = g.boundary_t(c);
            g.push(c, t);
        }
        g
    }

    fn push(&mut self, at: Point, t: Option<f64>) -> usize {
        let parent = self.nodes.len();
        self.nodes.push(Node { at, t, parent });
        parent
    }

    /// The node an edge end names: its vertex, or a new boundary point snapped from `p`.
    /// `None` for a vertex that does not exist or is not finite.
    fn end_node(&mut self, vertex: Option<usize>, p: Point) -> Option<usize> {
        match vertex {
            Some(v) => {
                let at = self.nodes.get(v).filter(|_| v < self.nv)?.at;
                (at.x.is_finite() && at.y.is_finite()).then_some(v)
            }
            None => {
                let at = self.snap(self.domain.clamp(p));
                let t = self.boundary_t(at);
                Some(self.push(at, t))
            }
        }
    }

    fn boundary_dist(&self, p: Point) -> f64 {
        let (a, b) = (self.domain.min, self.domain.max);
        (p.x - a.x).min(b.x - p.x).min(p.y - a.y).min(b.y - p.y)
    }

    /// The nearest boundary point to `p` (inside the domain).
    fn snap(&self, p: Point) -> Point {
        let (a, b) = (self.domain.min, self.domain.max);
        let d = [p.y - a.y, b.x - p.x, b.y - p.y, p.x - a.x];
        let side = (0..4).fold(0, |m, i| if d[i] < d[m] { i } else { m });
        match side {
            0 => Point::new(p.x, a.y),
            1 => Point::new(b.x, p.y),
            2 => Point::new(p.x, b.y),
            _ => Point::new(a.x, p.y),
        }
    }

    /// Counter-clockwise boundary position of a point on the boundary (positions within
    /// `tol` of the full perimeter wrap to 0).
    fn boundary_t(&self, p: Point) -> Option<f64> {
        let (a, b) = (self.domain.min, self.domain.max);
        let (w, h) = (self.domain.width(), self.domain.height());
        let t = if p.y == a.y {
            p.x - a.x
        } else if p.x == b.x {
            w + p.y - a.y
        } else if p.y == b.y {
            w + h + b.x - p.x
        } else if p.x == a.x {
            2.0 * w + h + b.y - p.y
        } else {
            return None;
        };
        Some(if t >= 2.0 * (w + h) - self.tol {
            0.0
        } else {
            t
        })
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.nodes[i].parent != i {
            let gp = self.nodes[self.nodes[i].parent].parent;
            self.nodes[i].parent = gp;
            i = gp;
        }
        i
    }

    /// Corners outrank boundary points, which outrank vertices, as merged nodes' roots.
    fn rank(&self, i: usize) -> u8 {
        if (self.nv..self.nv + 4).contains(&i) {
            2
        } else {
            u8::from(self.nodes[i].t.is_some())
        }
    }

    fn union(&mut self, i: usize, j: usize) {
        let (ri, rj) = (self.find(i), self.find(j));
        if ri != rj {
            let (root, child) = if self.rank(rj) > self.rank(ri) {
                (rj, ri)
            } else {
                (ri, rj)
            };
            self.nodes[child].parent = root;
        }
    }

    /// The polyline of edge `k` between the merged nodes `u` and `v`: interior points
    /// clamped to the domain, points closer than `tol` dropped.
    fn polyline(&self, complex: &VoronoiComplex, k: usize, u: usize, v: usize) -> Vec<Point> {
        let pts = &complex.edges[k].points;
        let inner = pts[1..pts.len() - 1].iter().map(|&p| self.domain.clamp(p));
        let mut out = dedup(std::iter::once(self.nodes[u].at).chain(inner), self.tol);
        let end = self.nodes[v].at;
        if out.len() > 1 && out[out.len() - 1].dist(end) <= self.tol {
            out.pop();
        }
        out.push(end);
        out
    }

    /// The faces of the subdivision, except the outside of the domain.
    fn faces(mut self, complex: &VoronoiComplex) -> Vec<Face> {
        let on = self.merge_close_nodes(complex);
        let half = self.half_edges(complex, &on);
        walk_faces(&half, self.nodes.len(), DEPARTURE_REACH * self.tol)
    }

    /// Merges the ends of edges shorter than `tol`, then boundary points closer than it;
    /// returns the boundary nodes by their position `t` along the boundary.
    fn merge_close_nodes(&mut self, complex: &VoronoiComplex) -> Vec<(f64, usize)> {
        for (u, v, k) in self.edges.clone() {
            let pts = &complex.edges[k].points;
            let len: f64 = pts.windows(2).map(|w| w[0].dist(w[1])).sum();
            if len <= self.tol {
                self.union(u, v);
            }
        }
        let mut on: Vec<(f64, usize)> = (0..self.nodes.len())
            .filter_map(|i| self.nodes[i].t.map(|t| (t, i)))
            .collect();
        on.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for k in 1..on.len() {
            if on[k].0 - on[k - 1].0 <= self.tol {
                self.union(on[k - 1].1, on[k].1);
            }
        }
        for i in 0..self.nodes.len() {
            let r = self.find(i);
            self.nodes[i].at = self.nodes[r].at;
        }
        on
    }

    /// The half-edges: both directions of each edge between merged nodes, and of each
    /// piece of the domain boundary between consecutive boundary nodes (the outer one
    /// marked `outside`).
    fn half_edges(&mut self, complex: &VoronoiComplex, on: &[(f64, usize)]) -> Vec<HalfEdge> {
        let mut half: Vec<HalfEdge> = Vec::new();
        for (u, v, k) in self.edges.clone() {
            let (u, v) = (self.find(u), self.find(v));
            let points = self.polyline(complex, k, u, v);
            if points.len() < 2 + usize::from(u == v) {
                continue;
            }
            let e = &complex.edges[k];
            let sites = Some([e.sites[0].site(), e.sites[1].site()]);
            let mut back = points.clone();
            back.reverse();
            half.push(HalfEdge {
                from: u,
                points,
                sites,
                outside: false,
            });
            half.push(HalfEdge {
                from: v,
                points: back,
                sites,
                outside: false,
            });
        }
        let mut ring: Vec<usize> = Vec::new();
        for &(_, i) in on {
            let r = self.find(i);
            if ring.last() != Some(&r) && ring.first() != Some(&r) {
                ring.push(r);
            }
        }
        for k in 0..ring.len() {
            let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
            let (pa, pb) = (self.nodes[a].at, self.nodes[b].at);
            if a != b {
                half.push(HalfEdge {
                    from: a,
                    points: vec![pa, pb],
                    sites: None,
                    outside: false,
                });
                half.push(HalfEdge {
                    from: b,
                    points: vec![pb, pa],
                    sites: None,
                    outside: true,
                });
            }
        }
        half
    }
}

/// The faces traced by the half-edges (twins `h` and `h ^ 1`) leaving `nodes` nodes:
/// each face is the cycle of next half-edges, turning clockwise at each node, that never
/// runs outside the domain.
fn walk_faces(half: &[HalfEdge], nodes: usize, reach: f64) -> Vec<Face> {
    // Outgoing half-edges around each node, counter-clockwise.
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); nodes];
    for (h, he) in half.iter().enumerate() {
        out[he.from].push(h);
    }
    let mut pos = vec![0; half.len()];
    for list in &mut out {
        sort_around(list, half, reach);
        for (i, &h) in list.iter().enumerate() {
            pos[h] = i;
        }
    }
    let next = |h: usize| {
        let t = h ^ 1;
        let list = &out[half[t].from];
        list[(pos[t] + list.len() - 1) % list.len()]
    };

    let mut seen = vec![false; half.len()];
    let mut faces = Vec::new();
    for start in 0..half.len() {
        let (mut ring, mut sites, mut outside) = (Vec::new(), Vec::new(), false);
        let mut h = start;
        while !seen[h] {
            seen[h] = true;
            let he = &half[h];
            outside |= he.outside;
            ring.extend_from_slice(&he.points[..he.points.len() - 1]);
            sites.extend(std::iter::repeat_n(he.sites, he.points.len() - 1));
            h = next(h);
        }
        if h == start && !outside {
            faces.extend(Face::new(ring, sites));
        }
    }
    faces
}

/// Sorts half-edges leaving one node counter-clockwise by the direction from the node
/// to their first point farther than `reach` (their last point if none is): a first
/// step shorter than that may double back (a vertex moved by a merge within epsilon
/// leaves such a spur), which would swap the order of edges and run faces together.
/// Near ties are ordered by their later points.
fn sort_around(list: &mut [usize], half: &[HalfEdge], reach: f64) {
    let angle = |h: usize| {
        let points = &half[h].points;
        let o = points[0];
        let far = points[1..].iter().find(|p| p.dist(o) > reach);
        let d = *far.unwrap_or(&points[points.len() - 1]) - o;
        let a = (d.y + 0.0).atan2(d.x);
        let a = if a < 0.0 { a + TAU } else { a };
        if a > TAU - ANGLE_TIE {
            a - TAU
        } else {
            a
        }
    };
    list.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)).then(a.cmp(&b)));
    let mut i = 0;
    while i < list.len() {
        let mut j = i + 1;
        while j < list.len() && angle(list[j]) - angle(list[j - 1]) <= ANGLE_TIE {
            j += 1;
        }
        // Insertion sort: never panics on a comparison that is not a total order.
        for k in i + 1..j {
            let mut m = k;
            while m > i && tie_order(&half[list[m - 1]], &half[list[m]]) == Ordering::Greater {
                list.swap(m - 1, m);
                m -= 1;
            }
        }
        i = j;
    }
}

/// Orders two half-edges leaving the same node in the same direction: counter-clockwise
/// by the first pair of later points that are not aligned as seen from the node.
fn tie_order(a: &HalfEdge, b: &HalfEdge) -> Ordering {
    let o = a.points[0];
    let (la, lb) = (a.points.len(), b.points.len());
    for k in 1..la.max(lb) {
        let da = a.points[k.min(la - 1)] - o;
        let db = b.points[k.min(lb - 1)] - o;
        let c = da.cross(db);
        if c.abs() > 1e-13 * da.norm() * db.norm() {
            return if c > 0.0 {
                Ordering::Less
            } else {
                Ordering::Greater
            };
        }
    }
    Ordering::Equal
}

/// The points farther than `tol` from the previous one kept.
fn dedup(points: impl Iterator<Item = Point>, tol: f64) -> Vec<Point> {
    let mut out: Vec<Point> = Vec::new();
    for p in points {
        if out.last().is_none_or(|q| q.dist(p) > tol) {
            out.push(p);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::{smallvec, Edge, Generator, Vertex};
    use crate::scene::{Metric, Mode, Scene, Site, SiteKind};

    const SQUARE: Aabb = Aabb::new(Point::new(-1.0, -1.0), Point::new(1.0, 1.0));

    fn area(c: &Cell) -> f64 {
        c.rings.iter().map(|r| signed_area(r)).sum()
    }

    fn nearest(sites: &[Point]) -> impl Fn(Point) -> usize + Sync + '_ {
        |p| {
            (0..sites.len()).fold(0, |m, i| {
                if p.dist(sites[i]) < p.dist(sites[m]) {
                    i
                } else {
                    m
                }
            })
        }
    }

    /// A straight edge with `n` points.
    fn edge(sites: [usize; 2], ends: [Option<usize>; 2], a: Point, b: Point, n: usize) -> Edge {
        Edge {
            clearance: Vec::new(),
            sites_along: Vec::new(),
            sites: sites.map(Generator::Site),
            from: ends[0],
            bisector: Vec::new(),
            parametric: Vec::new(),
            to: ends[1],
            points: (0..n)
                .map(|i| a.lerp(b, i as f64 / (n - 1) as f64))
                .collect(),
        }
    }

    fn vertex(at: Point, sites: &[usize]) -> Vertex {
        Vertex {
            clearance: None,
            at,
            sites: sites.iter().map(|&s| Generator::Site(s)).collect(),
        }
    }

    /// Where the ray from `o` along `d` leaves the domain.
    fn exit(o: Point, d: Point, b: &Aabb) -> Point {
        let t = |o: f64, d: f64, lo: f64, hi: f64| {
            if d > 0.0 {
                (hi - o) / d
            } else if d < 0.0 {
                (lo - o) / d
            } else {
                f64::INFINITY
            }
        };
        o + d * t(o.x, d.x, b.min.x, b.max.x).min(t(o.y, d.y, b.min.y, b.max.y))
    }

    /// The exact Euclidean Voronoi cell of `sites[i]` clipped to the domain
    /// (Sutherland–Hodgman against each bisector's half-plane).
    fn exact_cell(sites: &[Point], i: usize, b: &Aabb) -> f64 {
        let mut poly = vec![
            b.min,
            Point::new(b.max.x, b.min.y),
            b.max,
            Point::new(b.min.x, b.max.y),
        ];
        for &sj in sites.iter().filter(|&&sj| sj != sites[i]) {
            let si = sites[i];
            let f = |p: Point| (p - si).dot(p - si) - (p - sj).dot(p - sj);
            let mut next = Vec::new();
            for k in 0..poly.len() {
                let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
                if f(p) <= 0.0 {
                    next.push(p);
                }
                if (f(p) < 0.0) != (f(q) < 0.0) && f(p) != f(q) {
                    next.push(p.lerp(q, f(p) / (f(p) - f(q))));
                }
            }
            poly = next;
        }
        signed_area(&poly)
    }

    fn complex(vertices: Vec<Vertex>, edges: Vec<Edge>) -> VoronoiComplex {
        VoronoiComplex {
            vertices,
            edges,
            ..Default::default()
        }
    }

    /// Every cell's area against the exact clipped cell, outer rings counter-clockwise.
    fn check_exact(cells: &[Cell], sites: &[Point]) {
        assert_eq!(
            cells.iter().map(|c| c.site).collect::<Vec<_>>(),
            (0..sites.len()).collect::<Vec<_>>()
        );
        for c in cells {
            let want = exact_cell(sites, c.site, &SQUARE);
            assert!(
                (area(c) - want).abs() < 1e-12,
                "site {}: {} vs {want}",
                c.site,
                area(c)
            );
            assert!(signed_area(&c.rings[0]) > 0.0);
            assert_ne!(c.rings[0].first(), c.rings[0].last());
        }
        let total: f64 = cells.iter().map(area).sum();
        assert!((total - 4.0).abs() < 1e-12);
    }

    #[test]
    fn two_points_split_the_domain() {
        let sites = [Point::new(-0.5, 0.0), Point::new(0.5, 0.3)];
        let m = sites[0].lerp(sites[1], 0.5);
        let d = (sites[1] - sites[0]).perp();
        let (a, b) = (exit(m, d * -1.0, &SQUARE), exit(m, d, &SQUARE));
        let c = complex(vec![], vec![edge([0, 1], [None, None], a, b, 25)]);
        check_exact(&build_cells(&c, &SQUARE, &nearest(&sites)), &sites);
    }

    #[test]
    fn three_points_meet_at_a_vertex() {
        let sites = [
            Point::new(0.0, 0.6),
            Point::new(-0.6, -0.3),
            Point::new(0.5, -0.4),
        ];
        // The circumcentre: equidistant from the three sites.
        let (a, b, c) = (sites[0], sites[1], sites[2]);
        let (ab, ac) = (b - a, c - a);
        let den = 2.0 * ab.cross(ac);
        let o = a + Point::new(
            ac.y * ab.dot(ab) - ab.y * ac.dot(ac),
            ab.x * ac.dot(ac) - ac.x * ab.dot(ab),
        ) * (1.0 / den);
        let mut edges = Vec::new();
        for (i, j, k) in [(0, 1, 2), (1, 2, 0), (0, 2, 1)] {
            let d = (sites[j] - sites[i]).perp();
            let d = if d.dot(sites[i] - sites[k]) > 0.0 {
                d
            } else {
                d * -1.0
            };
            let end = exit(o, d, &SQUARE);
            // Alternate orientations: vertex first, then boundary first.
            edges.push(if i == 1 {
                edge([i, j], [None, Some(0)], end, o, 9)
            } else {
                edge([i, j], [Some(0), None], o, end, 9)
            });
        }
        let c = complex(vec![vertex(o, &[0, 1, 2])], edges);
        check_exact(&build_cells(&c, &SQUARE, &nearest(&sites)), &sites);
    }

    #[test]
    fn four_cells_meet_at_a_degree_four_vertex() {
        let o = Point::new(0.0, 0.0);
        let sites = [
            Point::new(0.5, 0.5),
            Point::new(-0.5, 0.5),
            Point::new(-0.5, -0.5),
            Point::new(0.5, -0.5),
        ];
        let axes = [
            (0, 1, Point::new(0.0, 1.0)),
            (1, 2, Point::new(-1.0, 0.0)),
            (2, 3, Point::new(0.0, -1.0)),
            (0, 3, Point::new(1.0, 0.0)),
        ];
        let edges = axes
            .iter()
            .map(|&(i, j, p)| edge([i, j], [Some(0), None], o, p, 5))
            .collect();
        let c = complex(vec![vertex(o, &[0, 1, 2, 3])], edges);
        check_exact(&build_cells(&c, &SQUARE, &nearest(&sites)), &sites);
    }

    #[test]
    fn edges_ending_at_the_domain_corners() {
        let o = Point::new(0.0, 0.0);
        let sites = [
            Point::new(0.5, 0.0),
            Point::new(0.0, 0.5),
            Point::new(-0.5, 0.0),
            Point::new(0.0, -0.5),
        ];
        let diagonals = [
            (0, 1, SQUARE.max),
            (1, 2, Point::new(-1.0, 1.0)),
            (2, 3, SQUARE.min),
            (0, 3, Point::new(1.0, -1.0)),
        ];
        let edges = diagonals
            .iter()
            .map(|&(i, j, p)| edge([i, j], [None, Some(0)], p, o, 7))
            .collect();
        let c = complex(vec![vertex(o, &[0, 1, 2, 3])], edges);
        let cells = build_cells(&c, &SQUARE, &nearest(&sites));
        check_exact(&cells, &sites);
        // One ring each: 6 points out to a corner, the corner beyond, 6 points back.
        assert!(cells
            .iter()
            .all(|c| c.rings.len() == 1 && c.rings[0].len() == 13));
    }

    #[test]
    fn nested_islands_make_holes_in_the_surrounding_cells() {
        let centre = Point::new(0.2, -0.1);
        let circle = |r: f64, n: usize| -> Vec<Point> {
            (0..=n)
                .map(|k| {
                    let a = TAU * (k % n) as f64 / n as f64;
                    centre + Point::new(a.cos(), a.sin()) * r
                })
                .collect()
        };
        let (outer, inner) = (circle(0.4, 100), circle(0.2, 60));
        let mut reversed = inner.clone();
        reversed.reverse();
        // Not closed by a repeated point: its ends are nearer each other than the boundary.
        reversed.pop();
        let loops = [([0, 1], outer.clone()), ([1, 2], reversed)];
        let edges = loops
            .into_iter()
            .map(|(s, points)| Edge {
                clearance: Vec::new(),
                sites_along: Vec::new(),
                sites: s.map(Generator::Site),
                from: None,
                bisector: Vec::new(),
                parametric: Vec::new(),
                to: None,
                points: points.into(),
            })
            .collect();
        let label = |p: Point| match p.dist(centre) {
            d if d < 0.2 => 2,
            d if d < 0.4 => 1,
            _ => 0,
        };
        let cells = build_cells(&complex(vec![], edges), &SQUARE, &label);
        let (a_out, a_in) = (signed_area(&outer[1..]), signed_area(&inner[1..]));
        let areas: Vec<f64> = cells.iter().map(area).collect();
        assert_eq!(
            cells
                .iter()
                .map(|c| (c.site, c.rings.len()))
                .collect::<Vec<_>>(),
            [(0, 2), (1, 2), (2, 1)]
        );
        for (got, want) in areas.iter().zip([4.0 - a_out, a_out - a_in, a_in]) {
            assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        }
        assert!(cells.iter().all(|c| signed_area(&c.rings[0]) > 0.0));
        assert!(signed_area(&cells[0].rings[1]) < 0.0);
    }

    #[test]
    fn no_edges_make_one_cell() {
        let cells = build_cells(&VoronoiComplex::default(), &SQUARE, &|p: Point| {
            if p.x == 0.0 {
                7
            } else {
                3
            }
        });
        assert_eq!(cells.len(), 1);
        assert_eq!(cells[0].site, 7);
        assert_eq!(area(&cells[0]), 4.0);
    }

    #[test]
    fn vertex_on_the_boundary_with_nearly_coincident_hit_points() {
        let sites = [
            Point::new(-0.5, 0.0),
            Point::new(0.5, 0.0),
            Point::new(0.0, -2.118),
        ];
        let v = Point::new(0.0, -1.0 + 1e-13);
        let edges = vec![
            edge([0, 1], [Some(0), None], v, Point::new(0.0, 1.0), 10),
            edge([0, 2], [Some(0), None], v, Point::new(-2e-13, -1.0), 2),
            edge([1, 2], [Some(0), None], v, Point::new(2e-13, -1.0), 2),
        ];
        let cells = build_cells(
            &complex(vec![vertex(v, &[0, 1, 2])], edges),
            &SQUARE,
            &nearest(&sites),
        );
        assert_eq!(cells.len(), 2);
        assert!(cells.iter().all(|c| (area(c) - 2.0).abs() < 1e-9));
    }

    #[test]
    fn inconsistent_input_is_skipped() {
        let mut c = complex(
            vec![],
            vec![edge(
                [0, 1],
                [None, None],
                Point::new(0.0, -1.0),
                Point::new(0.0, 1.0),
                3,
            )],
        );
        c.edges.push(edge(
            [0, 1],
            [Some(5), None],
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            2,
        ));
        c.edges.push(Edge {
            points: smallvec![Point::new(f64::NAN, 0.0); 3],
            ..c.edges[0].clone()
        });
        c.edges.push(Edge {
            points: smallvec![],
            ..c.edges[0].clone()
        });
        let cells = build_cells(&c, &SQUARE, &|p: Point| usize::from(p.x > 0.0));
        assert_eq!(cells.iter().map(area).collect::<Vec<_>>(), [2.0, 2.0]);
    }

    #[test]
    fn random_points_tile_the_domain() {
        let domain = Aabb::new(Point::new(-1.0, -0.5), Point::new(2.0, 1.5));
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        // A few sites outside the domain too.
        let sites: Vec<Point> = (0..50)
            .map(|_| domain.at(uniform() * 1.1 - 0.05, uniform() * 1.1 - 0.05))
            .collect();
        let scene = Scene::new(
            domain,
            1e-4,
            Mode::Voronoi,
            sites
                .iter()
                .map(|&at| Site {
                    id: None,
                    kind: SiteKind::Point {
                        at,
                        metric: Metric::Euclidean,
                    },
                })
                .collect(),
        )
        .expect("a valid scene");
        let diagram = crate::compute(&scene, &crate::Options::default()).unwrap();
        let cells = build_cells(&diagram, &domain, &nearest(&sites));
        let total: f64 = cells.iter().map(area).sum();
        let whole = domain.width() * domain.height();
        assert!((total - whole).abs() < 1e-6 * whole, "{total} vs {whole}");
        for (i, &s) in sites
            .iter()
            .enumerate()
            .filter(|&(_, &s)| domain.contains(s))
        {
            let c = cells
                .iter()
                .find(|c| c.site == i)
                .unwrap_or_else(|| panic!("no cell for site {i}"));
            assert!(
                c.rings.iter().filter(|r| even_odd_contains(r, s)).count() % 2 == 1,
                "site {i} outside its cell"
            );
            let want = exact_cell(&sites, i, &domain);
            assert!(
                (area(c) - want).abs() < 1e-2 * want,
                "site {i}: {} vs {want}",
                area(c)
            );
        }
    }
}
