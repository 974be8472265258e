//! A general half-edge graph (vertices of any degree, faces of any generator), made
//! from the points' degree-3 graph and then edited by segment insertions.

use super::geometry::Gen;
use crate::geom::Point;
use crate::incremental::points::predicates::circumcenter;
use crate::incremental::points::PointDiagram;

pub(crate) const NONE: u32 = u32::MAX;

#[derive(Clone, Copy, Debug)]
pub(crate) struct Vertex {
    pub(crate) at: Point,
    /// Clearance: the common distance to the vertex's generators.
    pub(crate) t: f64,
    /// One half-edge leaving the vertex.
    pub(crate) out: u32,
    pub(crate) alive: bool,
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct HalfEdge {
    pub(crate) origin: u32,
    pub(crate) twin: u32,
    pub(crate) next: u32,
    pub(crate) prev: u32,
    /// The face on the left.
    pub(crate) face: u32,
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Face {
    pub(crate) gen: Gen,
    /// One half-edge of the face's boundary cycle.
    pub(crate) edge: u32,
}

#[derive(Clone, Debug, Default)]
pub(crate) struct Graph {
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) edges: Vec<HalfEdge>,
    pub(crate) faces: Vec<Face>,
}

/// The vertex at infinity (vertex 0 of the point graph): never in a conflict tree.
pub(crate) const GHOST: u32 = 0;

impl Graph {
    /// The general graph of a point diagram; face `s` is the point graph's generator
    /// `s` (inserted order, far generators last), in the diagram's scaled coordinates.
    pub(crate) fn from_points(d: &PointDiagram) -> Graph {
        let g = &d.graph;
        let nv = g.gens.len();
        let vertices = (0..nv)
            .map(|v| {
                let [a, b, c] = g.gens[v].map(|s| d.pts[s as usize]);
                let (at, t) = if v == GHOST as usize {
                    (Point::default(), f64::INFINITY)
                } else {
                    let at = circumcenter(a, b, c);
                    (at, at.dist(a))
                };
                Vertex {
                    at,
                    t,
                    out: 3 * v as u32,
                    alive: true,
                }
            })
            .collect();
        let mut faces = vec![
            Face {
                gen: Gen::Point(0),
                edge: NONE,
            };
            d.pts.len()
        ];
        let edges = (0..g.twin.len() as u32)
            .map(|h| {
                let face = g.left(h);
                let f = &mut faces[face as usize];
                f.gen = Gen::Point(face);
                f.edge = h;
                HalfEdge {
                    origin: h / 3,
                    twin: g.twin[h as usize],
                    next: g.next(h),
                    prev: g.prev(h),
                    face,
                }
            })
            .collect();
        Graph {
            vertices,
            edges,
            faces,
        }
    }

    #[inline]
    pub(crate) fn target(&self, h: u32) -> u32 {
        self.edges[self.edges[h as usize].twin as usize].origin
    }

    /// The half-edges leaving `v`, counter-clockwise.
    pub(crate) fn outgoing(&self, v: u32) -> impl Iterator<Item = u32> + '_ {
        let start = self.vertices[v as usize].out;
        let mut h = start;
        let mut done = false;
        std::iter::from_fn(move || {
            if done {
                return None;
            }
            let cur = h;
            // Next counter-clockwise: the twin of the previous edge of cur's face.
            h = self.edges[self.edges[cur as usize].prev as usize].twin;
            done = h == start;
            Some(cur)
        })
    }

    /// The half-edges of face `f`'s boundary cycle.
    pub(crate) fn cycle(&self, f: u32) -> impl Iterator<Item = u32> + '_ {
        let start = self.faces[f as usize].edge;
        let mut h = start;
        let mut done = start == NONE;
        std::iter::from_fn(move || {
            if done {
                return None;
            }
            let cur = h;
            h = self.edges[cur as usize].next;
            done = h == start;
            Some(cur)
        })
    }

    pub(crate) fn add_vertex(&mut self, at: Point, t: f64) -> u32 {
        self.vertices.push(Vertex {
            at,
            t,
            out: NONE,
            alive: true,
        });
        self.vertices.len() as u32 - 1
    }

    /// Adds an edge `a → b` with `left` on its left and `right` on its right; returns
    /// the half-edge `a → b` (its twin is the next index). Links are set by the caller.
    pub(crate) fn add_edge(&mut self, a: u32, b: u32, left: u32, right: u32) -> u32 {
        let h = self.edges.len() as u32;
        self.edges.push(HalfEdge {
            origin: a,
            twin: h + 1,
            next: NONE,
            prev: NONE,
            face: left,
        });
        self.edges.push(HalfEdge {
            origin: b,
            twin: h,
            next: NONE,
            prev: NONE,
            face: right,
        });
        h
    }

    pub(crate) fn link(&mut self, a: u32, b: u32) {
        self.edges[a as usize].next = b;
        self.edges[b as usize].prev = a;
    }
}

impl Graph {
    /// The half-edge invariants at half-edge `h` (none if either end is dead): twins
    /// pair up, `next`/`prev` are inverse, a face's cycle keeps its face, and
    /// consecutive half-edges meet at a vertex. `alive` holds each vertex's flag (a
    /// compact copy, kinder to the cache).
    pub(crate) fn check_edge(&self, h: usize, alive: &[bool]) -> Result<(), String> {
        let alive = |h: usize| {
            let e = &self.edges[h];
            alive[e.origin as usize] && alive[self.edges[e.twin as usize].origin as usize]
        };
        if !alive(h) {
            return Ok(());
        }
        let e = &self.edges[h];
        if self.edges[e.twin as usize].twin as usize != h {
            return Err(format!("twin of twin of {h}"));
        }
        if e.next == NONE || self.edges[e.next as usize].prev as usize != h {
            return Err(format!("prev of next of {h}"));
        }
        if !alive(e.next as usize) {
            return Err(format!("next of {h} is dead"));
        }
        if self.edges[e.next as usize].face != e.face {
            return Err(format!("next of {h} changes face"));
        }
        if self.edges[e.next as usize].origin != self.target(h as u32) {
            return Err(format!("next of {h} does not start where {h} ends"));
        }
        Ok(())
    }

    /// Whether live vertex `v`'s outgoing half-edge leaves it.
    pub(crate) fn check_vertex(&self, v: usize) -> Result<(), String> {
        let out = self.vertices[v].out;
        if out == NONE || self.edges[out as usize].origin as usize != v {
            return Err(format!("vertex {v} has a wrong outgoing half-edge"));
        }
        Ok(())
    }
}

impl Graph {
    /// Puts a vertex of degree two at `at` (clearance `t`) on the edge of `h`
    /// (`a → b`): `h` becomes `a → x`, a new half-edge `x → b` follows it; returns `x`.
    pub(crate) fn split_edge(&mut self, h: u32, at: Point, t: f64) -> u32 {
        let x = self.add_vertex(at, t);
        let tw = self.edges[h as usize].twin;
        let b = self.edges[tw as usize].origin;
        let (left, right) = (self.edges[h as usize].face, self.edges[tw as usize].face);
        let h2 = self.add_edge(x, b, left, right);
        let t2 = h2 + 1;
        // Pair h ↔ tw (now x → a) and h2 ↔ t2.
        self.edges[tw as usize].origin = x;
        let after = self.edges[h as usize].next;
        self.link(h2, after);
        self.link(h, h2);
        let before = self.edges[tw as usize].prev;
        self.link(before, t2);
        self.link(t2, tw);
        self.vertices[x as usize].out = h2;
        if self.vertices[b as usize].out == tw {
            self.vertices[b as usize].out = t2;
        }
        x
    }
}
