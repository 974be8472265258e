//! Point insertion by the topology-oriented incremental method (Sugihara–Iri 1992):
//! for a new site `p`,
//!
//! * **B1** find the site `s` nearest to `p` (greedy walk over neighbouring faces from
//!   the last inserted site) and, among the vertices `Q` of the face of `s`, the seed with
//!   the least `H(Q, p)` (the power `|p − o|² − r²` of `p` for `Q`'s circle), kept only
//!   if its exact sign is negative;
//! * **B2** grow the tree `T` breadth-first: a neighbour `w` of `T` joins when
//!   `H(w, p) < 0` (exact incircle sign) and
//!   **C4** `w` is adjacent to no other vertex of `T` (`T` stays a tree) and
//!   **C5** `w`'s third face — the one not along the edge by which `w` was reached — has
//!   no vertex in `T` yet (every old face keeps a single connected remaining part;
//!   as tested here C5 implies C4, since a second neighbour of `w` in `T` would lie on
//!   that third face, but both are checked as on the wiki page);
//! * **A2–A4** put one new vertex on every edge leaving `T`, join them by the new face
//!   cycle of `p`, and delete `T` (whose slots the new vertices reuse).
//!
//! With exact signs the conditions never overrule `H`; when they do (the coordinates
//! overflowed the exact range) the topology wins and the count is reported.

use super::graph::{Graph, GHOST};
use super::predicates::{incircle, power_estimate};
use crate::geom::Point;

/// What happened to one site.
pub(crate) enum Outcome {
    Inserted,
    /// The site coincides with an already inserted one (internal index given).
    Duplicate(u32),
    /// No vertex of the diagram is strictly in conflict with the site (only possible
    /// when exact arithmetic overflowed); it is treated like a duplicate of the site.
    Skipped,
}

/// The insertion state: the graph, each site's face entry, and scratch marks.
pub(crate) struct Builder<'a> {
    pub(crate) pts: &'a [Point],
    pub(crate) graph: Graph,
    /// A vertex on each inserted site's face (`u32::MAX` before insertion).
    pub(crate) face_vertex: Vec<u32>,
    /// Vertex marks: `2r` = in `T`, `2r + 1` = decided out, during insertion round `r`.
    vmark: Vec<u32>,
    /// Site marks: `r` = the face is incident to `T` in round `r`.
    smark: Vec<u32>,
    /// The new vertex whose new-face edge starts at each boundary site (scratch).
    start: Vec<u32>,
    round: u32,
    tree: Vec<u32>,
    boundary: Vec<(u32, u32, u32)>,
    last: u32,
    /// Vertices with `H < 0` kept out of `T` by C4 or C5.
    pub(crate) overrides: usize,
    /// Insertions whose seed was not on the nearest face found (exhaustive search).
    pub(crate) seed_fallbacks: usize,
    /// Test only: replace every sign by a coin flip, to check that the topological
    /// conditions alone keep the graph valid.
    #[cfg(test)]
    pub(crate) chaos: Option<std::cell::Cell<u64>>,
}

#[inline]
fn d2(a: Point, b: Point) -> f64 {
    (a - b).dot(a - b)
}

impl<'a> Builder<'a> {
    /// The diagram of the three far generators `far` (counter-clockwise), which are the
    /// last three entries of `pts`.
    pub(crate) fn new(pts: &'a [Point], far: [u32; 3], capacity: usize) -> Self {
        let mut face_vertex = vec![u32::MAX; pts.len()];
        for f in far {
            face_vertex[f as usize] = 1;
        }
        let mut graph = Graph::initial(far);
        graph.gens.reserve(2 * capacity);
        graph.twin.reserve(6 * capacity);
        Builder {
            pts,
            graph,
            face_vertex,
            vmark: Vec::with_capacity(2 * capacity + 2),
            smark: vec![0; pts.len()],
            start: vec![0; pts.len()],
            round: 0,
            tree: Vec::new(),
            boundary: Vec::new(),
            last: far[0],
            overrides: 0,
            seed_fallbacks: 0,
            #[cfg(test)]
            chaos: None,
        }
    }

    #[inline]
    fn pos(&self, s: u32) -> Point {
        self.pts[s as usize]
    }

    /// B1, first half: the site nearest to `p` by a greedy walk over neighbouring faces
    /// (on a Voronoi diagram a face with no nearer neighbour is the nearest).
    fn nearest(&self, p: Point) -> u32 {
        let g = &self.graph;
        let mut s = self.last;
        let mut ds = d2(self.pos(s), p);
        loop {
            let h0 = g.leaving_with_left(self.face_vertex[s as usize], s);
            let (mut h, mut best, mut bd) = (h0, s, ds);
            loop {
                let t = g.right(h);
                let dt = d2(self.pos(t), p);
                if dt < bd {
                    best = t;
                    bd = dt;
                }
                h = g.next(h);
                if h == h0 {
                    break;
                }
            }
            if best == s {
                return s;
            }
            s = best;
            ds = bd;
        }
    }

    #[inline]
    fn conflict(&self, v: u32, p: Point) -> bool {
        #[cfg(test)]
        if let Some(state) = &self.chaos {
            let x = state
                .get()
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1);
            state.set(x);
            return v != GHOST && (x >> 40) % 3 != 0;
        }
        let [a, b, c] = self.graph.gens[v as usize];
        v != GHOST && incircle(self.pos(a), self.pos(b), self.pos(c), p) > 0.0
    }

    #[inline]
    fn power(&self, v: u32, p: Point) -> f64 {
        let [a, b, c] = self.graph.gens[v as usize];
        power_estimate(self.pos(a), self.pos(b), self.pos(c), p)
    }

    /// B1, second half: the vertex of `s`'s face with the least `H`, if its exact sign
    /// is negative; else any vertex in conflict on the faces around `s`, then anywhere.
    fn seed(&mut self, s: u32, p: Point) -> Option<u32> {
        let g = &self.graph;
        let h0 = g.leaving_with_left(self.face_vertex[s as usize], s);
        let (mut h, mut best, mut bh) = (h0, GHOST, f64::INFINITY);
        loop {
            let v = h / 3;
            if v != GHOST {
                let e = self.power(v, p);
                if e < bh || best == GHOST {
                    best = v;
                    bh = e;
                }
            }
            h = g.next(h);
            if h == h0 {
                break;
            }
        }
        if best != GHOST && self.conflict(best, p) {
            return Some(best);
        }
        // `s` was nearest only up to rounding: look on the faces of `s` and of its
        // neighbours, then (never seen in practice) everywhere.
        self.seed_fallbacks += 1;
        let mut h = h0;
        loop {
            let t = self.graph.right(h);
            let k0 = self
                .graph
                .leaving_with_left(self.face_vertex[t as usize], t);
            let mut k = k0;
            loop {
                if self.conflict(k / 3, p) {
                    return Some(k / 3);
                }
                k = self.graph.next(k);
                if k == k0 {
                    break;
                }
            }
            h = self.graph.next(h);
            if h == h0 {
                break;
            }
        }
        (1..self.graph.gens.len() as u32).find(|&v| self.conflict(v, p))
    }

    /// Inserts site `i` (an index into `pts`).
    pub(crate) fn insert(&mut self, i: u32) -> Outcome {
        let p = self.pos(i);
        let s = self.nearest(p);
        if self.pos(s) == p {
            return Outcome::Duplicate(s);
        }
        let Some(seed) = self.seed(s, p) else {
            return Outcome::Skipped;
        };
        self.round += 1;
        let (r, rin, rout) = (self.round, 2 * self.round, 2 * self.round + 1);
        self.vmark.resize(self.graph.gens.len(), 0);
        self.grow(seed, p, r, rin, rout);
        self.replace_tree(i, rin);
        self.last = i;
        Outcome::Inserted
    }

    /// B2: grows `T` from `seed` under `H < 0`, C4 and C5.
    fn grow(&mut self, seed: u32, p: Point, r: u32, rin: u32, rout: u32) {
        self.tree.clear();
        self.tree.push(seed);
        self.vmark[seed as usize] = rin;
        for s in self.graph.gens[seed as usize] {
            self.smark[s as usize] = r;
        }
        let mut next = 0;
        while next < self.tree.len() {
            let u = self.tree[next];
            next += 1;
            for k in 0..3 {
                let t = self.graph.twin[(3 * u + k) as usize];
                let w = t / 3;
                let m = self.vmark[w as usize];
                if w == GHOST || m == rin || m == rout {
                    continue;
                }
                self.vmark[w as usize] = rout;
                if !self.conflict(w, p) {
                    continue;
                }
                let j = t % 3;
                let tw = &self.graph.twin;
                let n1 = tw[(3 * w + (j + 1) % 3) as usize] / 3;
                let n2 = tw[(3 * w + (j + 2) % 3) as usize] / 3;
                let third = self.graph.gens[w as usize][((j + 2) % 3) as usize];
                if self.vmark[n1 as usize] == rin
                    || self.vmark[n2 as usize] == rin
                    || self.smark[third as usize] == r
                {
                    self.overrides += 1;
                    continue;
                }
                self.vmark[w as usize] = rin;
                self.smark[third as usize] = r;
                self.tree.push(w);
            }
        }
    }

    /// A2–A4: one new vertex `(a, b, p)` per edge leaving `T` (dual to the side `a → b`
    /// of a vertex of `T`), linked into the face cycle of `p`; `T`'s slots are reused.
    fn replace_tree(&mut self, p: u32, rin: u32) {
        self.boundary.clear();
        for &u in &self.tree {
            let g = self.graph.gens[u as usize];
            for k in 0..3 {
                let o = self.graph.twin[(3 * u + k) as usize];
                if self.vmark[(o / 3) as usize] != rin {
                    self.boundary
                        .push((g[k as usize], g[((k + 1) % 3) as usize], o));
                }
            }
        }
        // A tree of k degree-3 vertices has k + 2 leaving edges: k reused slots, 2 new.
        for idx in 0..self.boundary.len() {
            let (a, b, o) = self.boundary[idx];
            let t = match self.tree.get(idx) {
                Some(&t) => t,
                None => {
                    let t = self.graph.gens.len() as u32;
                    self.graph.gens.push([0; 3]);
                    self.graph.twin.extend_from_slice(&[0; 3]);
                    t
                }
            };
            self.graph.gens[t as usize] = [a, b, p];
            self.graph.twin[(3 * t) as usize] = o;
            self.graph.twin[o as usize] = 3 * t;
            self.start[a as usize] = t;
            self.face_vertex[a as usize] = t;
            self.boundary[idx].2 = t;
        }
        for &(_, b, t) in &self.boundary {
            // Side b → p of (a, b, p) is twin to side p → b of (b, c, p).
            let t2 = self.start[b as usize];
            self.graph.twin[(3 * t + 1) as usize] = 3 * t2 + 2;
            self.graph.twin[(3 * t2 + 2) as usize] = 3 * t + 1;
        }
        if let Some(&(_, _, t)) = self.boundary.first() {
            self.face_vertex[p as usize] = t;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks twins, next/prev, one cycle per face, Euler; returns the face count.
    fn check(g: &Graph) -> usize {
        let nh = g.twin.len() as u32;
        let mut count = std::collections::HashMap::new();
        for h in 0..nh {
            let t = g.twin[h as usize];
            assert!(t < nh && t != h && g.twin[t as usize] == h);
            assert_eq!(g.next(g.prev(h)), h);
            assert_eq!(g.left(g.next(h)), g.left(h));
            assert_eq!(g.left(t), g.right(h));
            assert_ne!(g.left(h), g.right(h));
            *count.entry(g.left(h)).or_insert(0usize) += 1;
        }
        let mut seen = std::collections::HashSet::new();
        for h0 in 0..nh {
            if !seen.insert(g.left(h0)) {
                continue;
            }
            let (mut h, mut len) = (h0, 0);
            loop {
                len += 1;
                h = g.next(h);
                if h == h0 || len > nh as usize {
                    break;
                }
            }
            assert_eq!(
                len,
                count[&g.left(h0)],
                "face {} is not one cycle",
                g.left(h0)
            );
            assert!(len >= 3);
        }
        let (v, e, f) = (g.gens.len(), g.twin.len() / 2, count.len());
        assert_eq!(v + f, e + 2, "Euler");
        f
    }

    /// With every `H` sign replaced by a coin flip, C4 and C5 alone still yield a valid
    /// planar graph after every insertion (the topology-oriented guarantee).
    #[test]
    fn topology_alone_keeps_the_graph_valid() {
        let n = 300;
        let mut pts: Vec<Point> = (0..n)
            .map(|i| {
                Point::new(
                    ((i * 37) % 101) as f64 / 101.0,
                    ((i * 61) % 89) as f64 / 89.0,
                )
            })
            .collect();
        pts.extend([
            Point::new(0.5, 40.0),
            Point::new(-40.0, -20.0),
            Point::new(40.0, -20.0),
        ]);
        for seed in 1..20u64 {
            let mut b = Builder::new(&pts, [n, n + 1, n + 2], n as usize);
            b.chaos = Some(std::cell::Cell::new(seed));
            let mut inserted = 0;
            for i in 0..n {
                if let Outcome::Inserted = b.insert(i) {
                    inserted += 1;
                }
                if i % 50 == 0 {
                    check(&b.graph);
                }
            }
            assert_eq!(check(&b.graph), inserted + 3);
        }
    }
}
