//! The point engine: the topology-oriented incremental Voronoi diagram of Euclidean
//! points (SI92; Imai 1996; Hel01).
//!
//! The diagram starts as G(3), the diagram of three far generators enclosing the sites
//! and the domain, and takes one site at a time (steps B1, B2, A2–A4 of the wiki page,
//! in `insert.rs`): the tree `T` of vertices that the new site's region swallows is
//! grown from a seed by the exact incircle sign `H < 0`, under the topological
//! conditions that keep `T` a tree (C4) and every old face's remainder connected (C5);
//! new vertices go on the edges leaving `T`, the new face cycle joins them, and `T` is
//! deleted. Every decision that could break the graph is a combinatorial one, so the
//! result is a valid planar graph for any input. The signs are exact (after an exact
//! power-of-two rescaling) as long as no products underflow, i.e. nonzero coordinate
//! differences exceed about 10^-70 times the largest coordinate; the graph is then the
//! exact Voronoi diagram.
//!
//! Sites are inserted in a biased randomized order along a Hilbert curve and located by
//! a walk from the previous site, which keeps the expected cost O(n log n).
//!
//! ```
//! use gvd::geom::{Aabb, Point};
//! let pts = [Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(0.0, 1.0)];
//! let d = gvd::internals::points_voronoi(&pts, Aabb::from_array([-1.0, -1.0, 2.0, 2.0])).unwrap();
//! assert_eq!(d.vertices.len(), 1);
//! assert_eq!(d.edges.len(), 3);
//! ```

mod cells;
pub(crate) mod graph;
mod insert;
pub(crate) mod order;
mod output;
pub(crate) mod predicates;

use crate::complex::VoronoiComplex;
use crate::control::Watch;
use crate::geom::{Aabb, Point};
use crate::Error;
use graph::{Graph, GHOST};
use insert::{Builder, Outcome};

/// A face of the graph: an input site, or one of the three far generators of G(3).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
pub enum Face {
    /// The input point with this index.
    Site(usize),
    /// Far generator 0, 1 or 2.
    Far(usize),
}

/// The Voronoi diagram of a set of points as a half-edge graph, before clipping.
///
/// Vertices have degree three; the three half-edges leaving vertex `v` are
/// `3v, 3v + 1, 3v + 2`. Vertex 0 is the vertex at infinity shared by the far
/// generators, so the graph is closed (`V − E + F = 2`) and every face is one cycle.
#[derive(Clone, Debug)]
pub struct PointDiagram {
    /// Sites in insertion order (scaled), then the three far generators.
    pub(crate) pts: Vec<Point>,
    /// The input index of each inserted-order site.
    pub(crate) input: Vec<u32>,
    pub(crate) graph: Graph,
    /// The domain, scaled.
    domain: Aabb,
    /// Internal coordinates are input coordinates times `scale` (a power of two).
    pub(crate) scale: f64,
    duplicates: Vec<(usize, usize)>,
    skipped: Vec<usize>,
    overrides: usize,
    seed_fallbacks: usize,
}

/// `2^e` for `−1022 ≤ e ≤ 1023`.
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

impl PointDiagram {
    /// Builds the diagram of `points`; `domain` is where the diagram will be reported
    /// (the far generators are placed so that no far face reaches it).
    ///
    /// Fails on non-finite coordinates, an empty or non-finite domain, or more than
    /// 700 million points. Coincident points are allowed: the one with the least index
    /// owns the cell (see [`duplicates`](Self::duplicates)).
    pub fn new(points: &[Point], domain: Aabb) -> Result<Self, Error> {
        Self::watched(points, domain, &Watch::default())
    }

    /// [`new`](Self::new), stopped early by `watch` (checked per inserted point).
    pub(crate) fn watched(points: &[Point], domain: Aabb, watch: &Watch) -> Result<Self, Error> {
        let d = domain.to_array();
        if d.iter().any(|v| !v.is_finite()) || !(d[0] <= d[2] && d[1] <= d[3]) {
            return Err(Error::scene(
                "domain",
                "must be finite with min <= max on both axes",
            ));
        }
        if let Some(i) = points
            .iter()
            .position(|p| !(p.x.is_finite() && p.y.is_finite()))
        {
            return Err(Error::site(i, "at", "coordinates must be finite"));
        }
        if points.len() > 700_000_000 {
            return Err(Error::scene(
                "sites",
                "more than 700 million points do not fit the 32-bit graph",
            ));
        }
        // Scale by a power of two (exact) so that the largest coordinate is about 1:
        // the exact predicates then neither overflow nor underflow for sane spreads.
        let m = points
            .iter()
            .flat_map(|p| [p.x.abs(), p.y.abs()])
            .chain(d.iter().map(|v| v.abs()))
            .fold(0.0f64, f64::max);
        let scale = if m > 0.0 {
            pow2(-(m.log2().ceil() as i32).clamp(-1000, 1000))
        } else {
            1.0
        };
        let sp = |p: Point| Point::new(p.x * scale, p.y * scale);
        let dom = Aabb::new(sp(domain.min), sp(domain.max));

        let scaled: Vec<Point> = points.iter().map(|&p| sp(p)).collect();
        let mut input = order::brio(&scaled);
        let n = points.len();
        let mut pts: Vec<Point> = input.iter().map(|&i| scaled[i as usize]).collect();
        drop(scaled);

        // Far generators: an equilateral triangle around everything, its inscribed
        // circle 16 times the extent, so every domain point is nearer to some site than
        // to any far generator.
        let (mut lo, mut hi) = (dom.min, dom.max);
        for p in &pts {
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        }
        let c = lo.lerp(hi, 0.5);
        let r = (hi.x - lo.x).max(hi.y - lo.y).max(pow2(-30));
        let l = 32.0 * r;
        let h = l * 3f64.sqrt() / 2.0;
        pts.push(c + Point::new(0.0, l));
        pts.push(c + Point::new(-h, -l / 2.0));
        pts.push(c + Point::new(h, -l / 2.0));
        let far = [n as u32, n as u32 + 1, n as u32 + 2];

        let mut b = Builder::new(&pts, far, n);
        let (mut duplicates, mut skipped) = (Vec::new(), Vec::new());
        watch.stage("points", Some(n as u64));
        for i in 0..n as u32 {
            if !watch.tick(1) {
                watch.check()?;
            }
            match b.insert(i) {
                Outcome::Inserted => {}
                Outcome::Duplicate(s) => {
                    // The copy with the least input index owns the cell.
                    let (i, s) = (i as usize, s as usize);
                    if input[i] < input[s] {
                        input.swap(i, s);
                    }
                    duplicates.push((input[i] as usize, s))
                }
                Outcome::Skipped => skipped.push(input[i as usize] as usize),
            }
        }
        for (_, s) in duplicates.iter_mut() {
            *s = input[*s] as usize;
        }
        let (graph, overrides, seed_fallbacks) = (b.graph, b.overrides, b.seed_fallbacks);
        Ok(PointDiagram {
            pts,
            input,
            graph,
            domain: dom,
            scale,
            duplicates,
            skipped,
            overrides,
            seed_fallbacks,
        })
    }

    /// The number of vertices, the vertex at infinity (0) included.
    pub fn vertex_count(&self) -> usize {
        self.graph.gens.len()
    }

    /// The number of half-edges (`3 ×` the vertex count).
    pub fn half_edge_count(&self) -> usize {
        self.graph.twin.len()
    }

    /// The opposite half-edge of `h`.
    pub fn twin(&self, h: usize) -> usize {
        self.graph.twin[h] as usize
    }

    /// The half-edge after `h` around its left face.
    pub fn next(&self, h: usize) -> usize {
        self.graph.next(h as u32) as usize
    }

    /// The half-edge before `h` around its left face.
    pub fn prev(&self, h: usize) -> usize {
        self.graph.prev(h as u32) as usize
    }

    /// The vertex `h` leaves.
    pub fn origin(&self, h: usize) -> usize {
        h / 3
    }

    /// Whether `v` is the vertex at infinity.
    pub fn is_at_infinity(&self, v: usize) -> bool {
        v == GHOST as usize
    }

    fn face(&self, s: u32) -> Face {
        match self.input.get(s as usize) {
            Some(&i) => Face::Site(i as usize),
            None => Face::Far(s as usize - self.input.len()),
        }
    }

    /// The face to the left of `h`.
    pub fn left(&self, h: usize) -> Face {
        self.face(self.graph.left(h as u32))
    }

    /// The generators of vertex `v`, counter-clockwise around its circle (clockwise for
    /// the vertex at infinity).
    pub fn generators(&self, v: usize) -> [Face; 3] {
        self.graph.gens[v].map(|s| self.face(s))
    }

    /// The three far generators of G(3), counter-clockwise, in input coordinates.
    pub fn far_generators(&self) -> [Point; 3] {
        let n = self.input.len();
        [0, 1, 2].map(|k| self.pts[n + k] * (1.0 / self.scale))
    }

    /// Input points that coincide with another one of smaller index, as
    /// `(point, point owning the cell)`.
    pub fn duplicates(&self) -> &[(usize, usize)] {
        &self.duplicates
    }

    /// Input points left out because no vertex was strictly in conflict with them:
    /// impossible with exact signs, so only when a coordinate spread overflowed the
    /// exact range. Empty in every tested case.
    pub fn skipped(&self) -> &[usize] {
        &self.skipped
    }

    /// The number of vertices with `H < 0` that C4 or C5 kept out of `T` (0 when the
    /// signs were exact), and the number of seeds not found on the nearest face.
    pub fn topology_counts(&self) -> (usize, usize) {
        (self.overrides, self.seed_fallbacks)
    }

    /// The diagram clipped to the domain (see [`points_voronoi`]).
    pub fn to_complex(&self) -> VoronoiComplex {
        output::to_complex(self, false).0
    }

    /// [`to_complex`](Self::to_complex) with `cells`: each site's face, a convex
    /// polygon, clipped to the domain (the complex's own edge segments, joined along the
    /// domain boundary with the corners the cell holds); one counter-clockwise ring per
    /// site whose cell meets the domain with positive area, sorted by site. The flag is
    /// `false` if some face could not be traced consistently (not expected with exact
    /// signs); `cells` is then left empty, for [`crate::complex::cells::build_cells`] to fill.
    pub fn to_complex_with_cells(&self) -> (VoronoiComplex, bool) {
        output::to_complex(self, true)
    }
}

/// The Voronoi diagram of `points` within `domain`, by topology-oriented incremental
/// insertion.
///
/// * vertices: the Voronoi vertices in the closed domain, each at the circumcentre of
///   its generators (computed in f64); 4+ exactly cocircular sites (incircle = 0) give
///   one vertex listing them all;
/// * edges: straight, clipped to the domain, `points = [start, end]`, `from`/`to` the
///   end vertices or `None` where the domain boundary cuts the edge; `sites[0]` lies to
///   the left of the direction `from → to`. Only edges that meet the domain with
///   positive length are listed;
/// * generators are `Generator::Site(i)` with `i` the input index; a point equal to one
///   of smaller index has no cell.
pub fn points_voronoi(points: &[Point], domain: Aabb) -> Result<VoronoiComplex, Error> {
    Ok(PointDiagram::new(points, domain)?.to_complex())
}

/// Gives every edge of `c`, a diagram of `points`, its bisector in offset-parameter
/// form ([`crate::complex::Edge::bisector`]): one piece, or two split at the midpoint
/// of the two sites.
pub fn add_point_bisectors(c: &mut VoronoiComplex, points: &[Point], domain: Aabb) {
    use super::bisector_form::{self, OffsetGen};
    let tol = 1e-12 * domain.longest_side();
    let forms = crate::par::map_range(c.edges.len(), 1 << 10, |k| {
        let e = &c.edges[k];
        let [a, b] = e.sites.map(|g| OffsetGen::point(points[g.site()]));
        bisector_form::pieces(a, b, &e.points, tol).unwrap_or_default()
    });
    for (e, form) in c.edges.iter_mut().zip(forms) {
        e.bisector = form;
    }
}
