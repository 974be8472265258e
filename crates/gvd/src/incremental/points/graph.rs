//! The half-edge graph of a Voronoi diagram of points.
//!
//! Every Voronoi vertex has degree three (a vertex where 4+ sites are cocircular is
//! kept as a tree of degree-3 vertices joined by zero-length edges, merged only on
//! output), so the three half-edges leaving vertex `v` are numbered `3v, 3v+1, 3v+2`
//! and only `twin` is stored; `next` and `prev` follow from the numbering.
//!
//! Vertex `v` lists its three generators `g[v] = [g0, g1, g2]` counter-clockwise around
//! the circle through them. Half-edge `3v+k` leaves `v` along the bisector of `g_k` and
//! `g_{k+1}` (indices mod 3), with face `g_{k+1}` on its left and `g_k` on its right.
//! With `twin(3v+k) = 3w+j`:
//!
//! * `next(3v+k) = 3w + (j+2) mod 3` (the next edge around the left face, leaving `w`),
//! * `prev(3v+k) = twin(3v + (k+1) mod 3)`.
//!
//! (This is the dual of a triangle-based Delaunay mesh: vertex = triangle, half-edge =
//! directed triangle side.) The graph lives on the sphere: vertex [`GHOST`] is the
//! vertex "at infinity" shared by the three far generators, so every face is one closed
//! cycle and `V − E + F = 2`.

/// The vertex at infinity of the initial diagram; it never enters the tree `T`.
pub(crate) const GHOST: u32 = 0;

/// Vertices (as generator triples) and the twin of every half-edge.
#[derive(Clone, Debug)]
pub(crate) struct Graph {
    pub(crate) gens: Vec<[u32; 3]>,
    pub(crate) twin: Vec<u32>,
}

impl Graph {
    /// The diagram G(3) of the three far generators `f0, f1, f2` (counter-clockwise):
    /// one finite vertex (their circumcentre) and the ghost vertex, joined by three
    /// edges.
    pub(crate) fn initial(f: [u32; 3]) -> Graph {
        Graph {
            gens: vec![[f[0], f[2], f[1]], f],
            // 3 = f0→f1 ↔ 2 = f1→f0, 4 = f1→f2 ↔ 1 = f2→f1, 5 = f2→f0 ↔ 0 = f0→f2.
            twin: vec![5, 4, 3, 2, 1, 0],
        }
    }

    #[inline]
    pub(crate) fn next(&self, h: u32) -> u32 {
        let t = self.twin[h as usize];
        t - t % 3 + (t % 3 + 2) % 3
    }

    #[inline]
    pub(crate) fn prev(&self, h: u32) -> u32 {
        self.twin[(h - h % 3 + (h % 3 + 1) % 3) as usize]
    }

    /// The generator whose face lies to the left of `h`.
    #[inline]
    pub(crate) fn left(&self, h: u32) -> u32 {
        self.gens[(h / 3) as usize][((h % 3 + 1) % 3) as usize]
    }

    /// The generator whose face lies to the right of `h`.
    #[inline]
    pub(crate) fn right(&self, h: u32) -> u32 {
        self.gens[(h / 3) as usize][(h % 3) as usize]
    }

    /// The half-edge leaving `v` with generator `s` on its left (`s` must be one of
    /// `v`'s generators).
    #[inline]
    pub(crate) fn leaving_with_left(&self, v: u32, s: u32) -> u32 {
        let g = self.gens[v as usize];
        let k = if g[1] == s {
            0
        } else if g[2] == s {
            1
        } else {
            2
        };
        3 * v + k
    }
}
