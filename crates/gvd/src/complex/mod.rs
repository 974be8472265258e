//! The output model shared by every algorithm family: a Voronoi complex of vertices,
//! edges and cells, as `../SCENE_FORMAT.md` ("Diagram") defines it.

pub(crate) mod cells;
pub mod prune;

use crate::geom::Point;
use serde::{Deserialize, Serialize};
/// The inline vectors of [`Vertex::sites`], [`Edge::points`] and [`Cell::rings`], re-exported for
/// callers that build diagrams.
pub use smallvec::{smallvec, SmallVec};
use std::collections::BTreeMap;

/// A feature of a site with features (corner, edge or curve piece), used as a generator
/// in `complex` and `medial_axis` modes.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FeatureKind {
    /// A corner of a polyline or polygon site.
    Corner,
    /// An edge of a polyline or polygon site.
    Edge,
    /// A piece of a curved site between its breaks.
    Piece,
}

/// A generator of the diagram: a whole site (written as its index) or one feature of it.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Generator {
    /// A whole site, by its index in the scene.
    Site(usize),
    /// A feature of a site: one of its corners, edges or pieces.
    Feature {
        /// The site's index in the scene.
        site: usize,
        /// What kind of feature.
        feature: FeatureKind,
        /// The feature's index within the site (corners and edges numbered across rings).
        index: usize,
    },
}

impl Generator {
    /// The index of the site this generator belongs to.
    pub fn site(&self) -> usize {
        match *self {
            Generator::Site(i) => i,
            Generator::Feature { site, .. } => site,
        }
    }
}

/// A Voronoi vertex: a point equidistant from its generators (three or more, or more
/// than three when near-degenerate vertices within epsilon are merged).
#[derive(Clone, PartialEq, Debug, Serialize, Deserialize)]
pub struct Vertex {
    /// Where the vertex is.
    pub at: Point,
    /// Usually three, stored inline.
    pub sites: SmallVec<[Generator; 3]>,
    /// The distance to the generators (the radius of the maximal empty disc centred
    /// here), when known and asked for ([`VoronoiComplex::add_clearances`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearance: Option<f64>,
}

/// A Voronoi edge: a polyline within epsilon of the bisector of its two generators,
/// from vertex `from` to vertex `to` (`None` where it ends on the domain boundary).
#[derive(Clone, PartialEq, Debug, Serialize, Deserialize)]
pub struct Edge {
    /// The two generators the edge separates.
    pub sites: [Generator; 2],
    /// The vertex the edge starts at (`None`: it starts on the domain boundary).
    pub from: Option<usize>,
    /// The vertex the edge ends at (`None`: it ends on the domain boundary).
    pub to: Option<usize>,
    /// Two for a straight edge, stored inline.
    pub points: SmallVec<[Point; 2]>,
    /// The exact bisector under `points`, piece by piece in their order (empty when not
    /// asked for, or when a piece has constant clearance; see [`BisectorPiece`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bisector: Vec<BisectorPiece>,
    /// The free-form engine's edge in parameter space, piece by piece in the order of
    /// `points` (empty for the other engines, and after pruning; see
    /// [`ParametricPiece`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub parametric: Vec<ParametricPiece>,
    /// The distance to the two generators at each of `points` (parallel to it), when
    /// known and asked for ([`VoronoiComplex::add_clearances`]); empty otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub clearance: Vec<f64>,
    /// Where the generators change along the edge: only on edges that pruning joined
    /// across a vertex of degree two ([`prune`]). `sites` are the generators from
    /// `points[0]`; each change's from `points[start]` on, in increasing `start`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sites_along: Vec<SitesChange>,
}

/// A change of an edge's generators ([`Edge::sites_along`]).
#[derive(Clone, Copy, PartialEq, Debug, Serialize, Deserialize)]
pub struct SitesChange {
    /// The index in the edge's `points` where the new generators take over.
    pub start: usize,
    /// The two generators from there on.
    pub sites: [Generator; 2],
}

/// One piece of an edge's bisector in Held's offset-parameter form (Hel01): with `t` the clearance (the distance to both
/// generators),
///
/// x(t) = x1 − x2 − x3·t + sign · x4 · √((x5 + x6·t)² − (x7 + x8·t)²),
///
/// and y(t) likewise from `y`, for `t` from `t[0]` (where the piece starts, in the
/// direction of the edge's `points`) to `t[1]`. Every bisector of points, lines and
/// circles has this form; a piece ends where the edge changes generators or the root
/// changes sign (at the apex, the point of least clearance).
#[derive(Clone, Copy, PartialEq, Debug, Serialize, Deserialize)]
pub struct BisectorPiece {
    /// The coefficients `x1..x8` of the `x` coordinate's offset-parameter form.
    pub x: [f64; 8],
    /// The coefficients `x1..x8` of the `y` coordinate's offset-parameter form.
    pub y: [f64; 8],
    /// +1 or −1: the branch of the root.
    pub sign: i8,
    /// The range of the clearance `t` over the piece.
    pub t: [f64; 2],
}

impl BisectorPiece {
    /// The point of clearance `t` (the root clamped at zero against rounding).
    pub fn at(&self, t: f64) -> Point {
        let coord = |c: &[f64; 8]| {
            let (u, v) = (c[4] + c[5] * t, c[6] + c[7] * t);
            let root = (u * u - v * v).max(0.0).sqrt();
            c[0] - c[1] - c[2] * t + f64::from(self.sign) * c[3] * root
        };
        Point::new(coord(&self.x), coord(&self.y))
    }
}

/// One piece of a free-form engine's edge in parameter space (HREK07): the two
/// generators' rational Bézier spans, and the foot parameters `(t, r)` on them where
/// the piece starts and ends (in the direction of the edge's `points`). Between them
/// `t` and `r` move monotonically along the zero set of the bisector function
/// `F3(t, r)`, and the edge's point is where the curves' normals at `t` and `r` meet
/// (eqs. 5–7): a user can evaluate it to any precision. A corner is a span of one
/// control point (its foot parameter `None`); a piece whose feet stay at one joint of
/// two spans is the common normal there.
#[derive(Clone, PartialEq, Debug, Serialize, Deserialize)]
pub struct ParametricPiece {
    /// Each generator's span as homogeneous control points `(w·x, w·y, w)`.
    pub curves: [Vec<[f64; 3]>; 2],
    /// The foot parameters on the two spans where the piece starts.
    pub from: [Option<f64>; 2],
    /// The foot parameters on the two spans where the piece ends.
    pub to: [Option<f64>; 2],
}

/// A site's cell clipped to the domain, as closed rings (last point not repeated).
#[derive(Clone, PartialEq, Debug, Serialize, Deserialize)]
pub struct Cell {
    /// The site (or generator index) whose cell this is.
    pub site: usize,
    /// Usually one (a cell with holes has more), stored inline.
    pub rings: SmallVec<[Vec<Point>; 1]>,
}

/// The Voronoi diagram (or complex, or medial axis) of a scene.
#[derive(Clone, PartialEq, Debug, Default, Serialize, Deserialize)]
pub struct VoronoiComplex {
    /// The Voronoi vertices.
    pub vertices: Vec<Vertex>,
    /// The edges, each a polyline within epsilon of its bisector.
    pub edges: Vec<Edge>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    /// The cells as rings, when computed.
    pub cells: Vec<Cell>,
    /// The user ids of the scene's sites by site index (`null` where a site has none),
    /// when any site has one: what [`crate::compute`] copies from the scene so that every
    /// writer can echo them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub site_ids: Vec<Option<String>>,
    /// Figures of the run: `seconds`, `boxes`, `uncertified_boxes`, ...
    #[serde(default)]
    pub stats: BTreeMap<String, serde_json::Value>,
}

impl VoronoiComplex {
    /// Multiplies every length by `s`: vertices, edge points, cells, and the offset
    /// forms (`x1, x2, x5, x7` and the clearances are lengths; `x3, x4, x6, x8` are
    /// ratios). With the inverse of [`crate::Scene::unit_scale`] it takes a diagram
    /// computed at unit scale back to the scene's.
    pub fn scale(&mut self, s: f64) {
        for v in &mut self.vertices {
            v.at = v.at * s;
            v.clearance = v.clearance.map(|r| r * s);
        }
        for e in &mut self.edges {
            e.points.iter_mut().for_each(|q| *q = *q * s);
            e.clearance.iter_mut().for_each(|r| *r *= s);
            for piece in &mut e.bisector {
                for coeffs in [&mut piece.x, &mut piece.y] {
                    for k in [0, 1, 4, 6] {
                        coeffs[k] *= s;
                    }
                }
                piece.t = piece.t.map(|t| t * s);
            }
            for piece in &mut e.parametric {
                for h in piece.curves.iter_mut().flatten() {
                    h[0] *= s;
                    h[1] *= s;
                }
            }
        }
        for cell in &mut self.cells {
            cell.rings.iter_mut().flatten().for_each(|q| *q = *q * s);
        }
    }

    /// Removes the vertices that no edge ends at, renumbering the edges' ends.
    pub fn drop_unused_vertices(&mut self) {
        let mut used = vec![false; self.vertices.len()];
        for e in &self.edges {
            for v in [e.from, e.to].into_iter().flatten() {
                used[v] = true;
            }
        }
        let mut renumbered = vec![usize::MAX; used.len()];
        let mut kept = 0;
        for (v, &u) in used.iter().enumerate() {
            if u {
                renumbered[v] = kept;
                kept += 1;
            }
        }
        let mut v = 0;
        self.vertices.retain(|_| {
            v += 1;
            used[v - 1]
        });
        for e in &mut self.edges {
            e.from = e.from.map(|v| renumbered[v]);
            e.to = e.to.map(|v| renumbered[v]);
        }
    }

    /// Checks the structural invariants every algorithm must keep: edge ends name
    /// existing vertices that list the edge's generators, edges have at least two
    /// points, and a loop with no vertex is closed. Returns the first violation.
    pub fn check_invariants(&self) -> Result<(), String> {
        for (k, e) in self.edges.iter().enumerate() {
            if e.points.len() < 2 {
                return Err(format!("edge {k} has fewer than two points"));
            }
            if e.sites[0] == e.sites[1] && matches!(e.sites[0], Generator::Site(_)) {
                return Err(format!(
                    "edge {k} separates site {} from itself",
                    e.sites[0].site()
                ));
            }
            if !e.clearance.is_empty() && e.clearance.len() != e.points.len() {
                return Err(format!(
                    "edge {k} has {} clearances for {} points",
                    e.clearance.len(),
                    e.points.len()
                ));
            }
            let mut start = 0;
            for change in &e.sites_along {
                if change.start <= start || change.start + 1 >= e.points.len() {
                    return Err(format!(
                        "edge {k}'s generators change at point {} out of order",
                        change.start
                    ));
                }
                start = change.start;
            }
            let last_sites = e.sites_along.last().map_or(e.sites, |c| c.sites);
            for (end, sites) in [(e.from, e.sites), (e.to, last_sites)] {
                let Some(end) = end else { continue };
                let Some(v) = self.vertices.get(end) else {
                    return Err(format!("edge {k} names vertex {end}, which does not exist"));
                };
                if !sites.iter().all(|g| v.sites.contains(g)) {
                    return Err(format!(
                        "edge {k} ends at vertex {end}, which does not list the edge's generators"
                    ));
                }
            }
            let closed = e.points.first() == e.points.last();
            if e.from.is_none() && e.to.is_none() && closed && e.points.len() < 3 {
                return Err(format!("edge {k} is a degenerate closed loop"));
            }
        }
        Ok(())
    }
}
