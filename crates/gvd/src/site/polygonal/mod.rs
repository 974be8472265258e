//! Polygonal sites as features (YSL12 §IV): segments, polylines and polygons split
//! into corners (points) and edges (open segments), each with its zone `Z(f)` and
//! oriented zone `Z*(f)` ([`zones`]), and the geometry the soft-predicate engine asks
//! of them ([`bisector`]): distances, the bisector of two features, its crossings with
//! a box side, and the points equidistant from three features.
//!
//! Features are numbered as the incremental engine and `docs/SCENE_FORMAT.md` number
//! them: corner `k` is a site's `k`-th point (across rings), edge `k` runs from corner
//! `k` to the next one of its ring or chain. Corners at the same point (shared
//! endpoints of segment sites) are one feature with several owners.

pub mod bisector;
pub mod zones;

use crate::complex::{FeatureKind, Generator};
use crate::error::Error;
use crate::geom::ring::{even_odd_contains, signed_area};
use crate::geom::{segment_distance, Aabb, Point};
use crate::scene::{Mode, Scene, SiteKind};
use smallvec::{smallvec, SmallVec};
use std::collections::HashMap;
pub use zones::Zone;

/// The shape of a feature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A corner: a point.
    Corner(Point),
    /// An edge: the open segment between two corners.
    Edge(Point, Point),
}

/// One corner or edge, with its zones and neighbours.
#[derive(Clone, Debug)]
pub struct Feature {
    /// Where it is.
    pub shape: Shape,
    /// The oriented zone `Z*(f)`: on the free side only (polygons), empty at concave
    /// corners.
    pub oriented_zone: Zone,
    /// The zone `Z(f)`, on both sides.
    pub zone: Zone,
    /// For an edge, the unit normal of its free side (polygon edges); `None` for
    /// edges of segments and polylines, free on both sides.
    pub side: Option<Point>,
    /// Its names as generators (`complex` mode): the first names it, the others own
    /// the same point (shared endpoints).
    pub owners: SmallVec<[Generator; 1]>,
    /// A corner's incident edges; an edge's two end corners (feature indices).
    pub links: SmallVec<[u32; 2]>,
    /// A corner whose two edges are collinear: a zone boundary between them.
    pub flat: bool,
}

impl Feature {
    /// Whether the feature is an edge.
    pub fn is_edge(&self) -> bool {
        matches!(self.shape, Shape::Edge(..))
    }

    /// `Sep(q, f)`, the distance from `q` to the closed feature.
    pub fn distance(&self, q: Point) -> f64 {
        match self.shape {
            Shape::Corner(c) => q.dist(c),
            Shape::Edge(a, b) => segment_distance(q, a, b),
        }
    }
}

/// The features of a scene's polygonal sites, and the material they bound.
#[derive(Clone, Debug)]
pub struct Polygonal {
    /// All features, corners and edges of every site.
    pub features: Vec<Feature>,
    /// The rings of each polygon site, with their bounding box (the material test).
    polygons: Vec<(Aabb, Vec<Vec<Point>>)>,
    /// `medial_axis` mode: the free space is the polygons' inside.
    inside: bool,
    /// The size of the scene (for relative tolerances).
    pub scale: f64,
}

/// Whether the scene has sites and all are polygonal (segment, polyline, polygon).
pub fn supports(scene: &Scene) -> bool {
    !scene.sites().is_empty()
        && scene.sites().iter().all(|s| {
            matches!(
                s.kind,
                SiteKind::Segment { .. } | SiteKind::Polyline { .. } | SiteKind::Polygon { .. }
            )
        })
}

/// Builds corner features, merging those at the same point.
struct Builder {
    features: Vec<Feature>,
    corners: HashMap<(u64, u64), u32>,
    /// Per corner feature: whether some owner's oriented zone is empty.
    concave: Vec<bool>,
}

impl Builder {
    fn corner(&mut self, at: Point, owner: Generator) -> u32 {
        let key = (at.x.to_bits(), at.y.to_bits());
        if let Some(&f) = self.corners.get(&key) {
            self.features[f as usize].owners.push(owner);
            return f;
        }
        let f = self.features.len() as u32;
        self.features.push(Feature {
            shape: Shape::Corner(at),
            oriented_zone: Zone::Plane,
            zone: Zone::Plane,
            side: None,
            owners: smallvec![owner],
            links: SmallVec::new(),
            flat: false,
        });
        self.concave.push(false);
        self.corners.insert(key, f);
        f
    }

    /// The edge from corner `ca` to corner `cb` with free side `side` (unit normal).
    fn edge(&mut self, ca: u32, cb: u32, owner: Generator, side: Option<Point>) {
        let (Shape::Corner(a), Shape::Corner(b)) = (
            self.features[ca as usize].shape,
            self.features[cb as usize].shape,
        ) else {
            return;
        };
        let len = a.dist(b);
        let u = (b - a) * (1.0 / len);
        let f = self.features.len() as u32;
        self.features.push(Feature {
            shape: Shape::Edge(a, b),
            oriented_zone: Zone::Strip { a, u, len, side },
            zone: Zone::Strip {
                a,
                u,
                len,
                side: None,
            },
            side,
            owners: smallvec![owner],
            links: smallvec![ca, cb],
            flat: false,
        });
        self.concave.push(false);
        self.features[ca as usize].links.push(f);
        self.features[cb as usize].links.push(f);
    }
}

fn feature(site: usize, feature: FeatureKind, index: usize) -> Generator {
    Generator::Feature {
        site,
        feature,
        index,
    }
}

impl Polygonal {
    /// The features of `scene`, whose sites must all be polygonal; in `medial_axis`
    /// mode all must be polygons, and the free space is their inside.
    pub fn new(scene: &Scene) -> Result<Self, Error> {
        let inside = scene.mode() == Mode::MedialAxis;
        let mut b = Builder {
            features: Vec::new(),
            corners: HashMap::new(),
            concave: Vec::new(),
        };
        let mut polygons = Vec::new();
        for (i, site) in scene.sites().iter().enumerate() {
            match &site.kind {
                SiteKind::Segment { from, to } if !inside => {
                    let ca = b.corner(*from, feature(i, FeatureKind::Corner, 0));
                    let cb = b.corner(*to, feature(i, FeatureKind::Corner, 1));
                    b.edge(ca, cb, feature(i, FeatureKind::Edge, 0), None);
                }
                SiteKind::Polyline { points } if !inside => {
                    let cs: Vec<u32> = points
                        .iter()
                        .enumerate()
                        .map(|(k, p)| b.corner(*p, feature(i, FeatureKind::Corner, k)))
                        .collect();
                    for (k, w) in cs.windows(2).enumerate() {
                        b.edge(w[0], w[1], feature(i, FeatureKind::Edge, k), None);
                    }
                }
                SiteKind::Polygon { rings } => {
                    let mut base = 0;
                    for (r, ring) in rings.iter().enumerate() {
                        add_ring(&mut b, i, base, ring, r == 0, inside);
                        base += ring.len();
                    }
                    let mut bbox = Aabb::new(rings[0][0], rings[0][0]);
                    for p in rings.iter().flatten() {
                        bbox = Aabb::new(
                            Point::new(bbox.min.x.min(p.x), bbox.min.y.min(p.y)),
                            Point::new(bbox.max.x.max(p.x), bbox.max.y.max(p.y)),
                        );
                    }
                    polygons.push((bbox, rings.clone()));
                }
                other => {
                    return Err(Error::Unsupported {
                        site: i,
                        kind: other.name().to_string(),
                        message: if inside {
                            "the soft-predicate engine computes the medial axis of polygons only"
                                .into()
                        } else {
                            "the soft-predicate engine computes segments, polylines and polygons"
                                .into()
                        },
                    })
                }
            }
        }
        finish_corner_zones(&mut b);
        check_conflicts(&b.features, &scene.domain())?;
        let d = scene.domain();
        let scale = d
            .width()
            .max(d.height())
            .max(d.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs())));
        Ok(Polygonal {
            features: b.features,
            polygons,
            inside,
            scale,
        })
    }

    /// Whether `q` lies in the free space (outside the polygons, or inside them in
    /// `medial_axis` mode); points on the boundary may go either way.
    pub fn free(&self, q: Point) -> bool {
        let in_any = self.polygons.iter().any(|(bbox, rings)| {
            bbox.contains(q)
                && rings
                    .iter()
                    .fold(false, |acc, ring| acc ^ even_odd_contains(ring, q))
        });
        in_any == self.inside
    }

    /// Whether two features never carry a Voronoi curve between them: a corner and
    /// its own edge, or two edges through a flat corner (their zones only touch
    /// along a normal, where the corner ties with both).
    pub fn zone_boundary(&self, f: u32, g: u32) -> bool {
        let (ff, fg) = (&self.features[f as usize], &self.features[g as usize]);
        match (ff.is_edge(), fg.is_edge()) {
            (false, true) => fg.links.contains(&f),
            (true, false) => ff.links.contains(&g),
            (true, true) => ff
                .links
                .iter()
                .any(|c| fg.links.contains(c) && self.features[*c as usize].flat),
            (false, false) => false,
        }
    }

    /// The corner two edges share, if any.
    pub fn shared_corner(&self, f: u32, g: u32) -> Option<u32> {
        let (ff, fg) = (&self.features[f as usize], &self.features[g as usize]);
        if !(ff.is_edge() && fg.is_edge()) {
            return None;
        }
        ff.links.iter().copied().find(|c| fg.links.contains(c))
    }

    /// The flat corner two collinear edges share, if any.
    pub fn flat_corner(&self, f: u32, g: u32) -> Option<u32> {
        self.shared_corner(f, g)
            .filter(|&c| self.features[c as usize].flat)
    }

    /// Inseparability (YSL12 ¶17): at most one feature, or a corner with only edges
    /// incident to it (the corner may be absent from the set when its oriented zone is
    /// empty because it is flat: two collinear edges).
    pub fn inseparable(&self, set: &[u32]) -> bool {
        if set.len() <= 1 {
            return true;
        }
        let star = |c: u32| {
            set.iter().all(|&g| {
                g == c || {
                    let fg = &self.features[g as usize];
                    fg.is_edge() && fg.links.contains(&c)
                }
            })
        };
        if set
            .iter()
            .any(|&c| !self.features[c as usize].is_edge() && star(c))
        {
            return true;
        }
        // two edges through a flat corner
        let first = &self.features[set[0] as usize];
        first.is_edge()
            && first
                .links
                .iter()
                .any(|&c| self.features[c as usize].flat && star(c))
    }
}

/// Adds one ring of polygon site `site` (its corners numbered from `base`); `outer`:
/// the first ring. The material lies on the left of a counter-clockwise outer ring
/// and on the right of a counter-clockwise hole; in `medial_axis` mode (`inside`)
/// material and free space trade places.
fn add_ring(b: &mut Builder, site: usize, base: usize, ring: &[Point], outer: bool, inside: bool) {
    let ccw = signed_area(ring) > 0.0;
    let material_left = outer == ccw;
    let free_right = material_left != inside;
    let n = ring.len();
    let cs: Vec<u32> = ring
        .iter()
        .enumerate()
        .map(|(k, p)| b.corner(*p, feature(site, FeatureKind::Corner, base + k)))
        .collect();
    for k in 0..n {
        let (a, c) = (ring[k], ring[(k + 1) % n]);
        let u = (c - a) * (1.0 / a.dist(c));
        let right = Point::new(u.y, -u.x);
        let side = if free_right { right } else { right * -1.0 };
        b.edge(
            cs[k],
            cs[(k + 1) % n],
            feature(site, FeatureKind::Edge, base + k),
            Some(side),
        );
    }
    // a corner's cone lies on the free side iff the ring turns towards the material
    for k in 0..n {
        let (p, c, q) = (ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n]);
        let (u, v) = ((c - p) * (1.0 / p.dist(c)), (q - c) * (1.0 / c.dist(q)));
        let turn = u.cross(v);
        let f = cs[k] as usize;
        if turn.abs() <= 1e-12 && u.dot(v) > 0.0 {
            b.features[f].flat = true;
            b.concave[f] = true;
        } else if (turn > 0.0) != free_right {
            b.concave[f] = true;
        }
    }
}

/// Sets each corner's zones from its incident edges: the cone of the half-planes
/// behind the corner (Z), empty where some owner's cone lies in the material (Z*).
fn finish_corner_zones(b: &mut Builder) {
    for f in 0..b.features.len() {
        let Shape::Corner(c) = b.features[f].shape else {
            continue;
        };
        let dirs: SmallVec<[Point; 2]> = b.features[f]
            .links
            .iter()
            .filter_map(|&e| match b.features[e as usize].shape {
                Shape::Edge(a, z) => {
                    let other = if a == c { z } else { a };
                    Some((other - c) * (1.0 / other.dist(c)))
                }
                Shape::Corner(_) => None,
            })
            .collect();
        let cone = if dirs.is_empty() {
            Zone::Plane
        } else {
            Zone::Cone { c, dirs }
        };
        let two_collinear = {
            let l = &b.features[f].links;
            l.len() == 2 && {
                let d: Vec<Point> = l
                    .iter()
                    .filter_map(|&e| match b.features[e as usize].shape {
                        Shape::Edge(a, z) => Some(if a == c { z - c } else { a - c }),
                        _ => None,
                    })
                    .collect();
                d.len() == 2
                    && d[0].cross(d[1]).abs() <= 1e-12 * d[0].norm() * d[1].norm()
                    && d[0].dot(d[1]) < 0.0
            }
        };
        if two_collinear {
            b.features[f].flat = true;
            b.concave[f] = true;
        }
        b.features[f].oriented_zone = if b.concave[f] {
            Zone::Empty
        } else {
            cone.clone()
        };
        b.features[f].zone = cone;
    }
}

/// Refuses edges that cross, overlap or touch away from a shared corner (the
/// incremental engine's check, `incremental/segments_arcs/crossings.rs`, with its
/// resolution): features are a boundary complex only for non-crossing sites.
fn check_conflicts(features: &[Feature], domain: &Aabb) -> Result<(), Error> {
    use crate::incremental::segments_arcs::{
        check_sites_beside_tolerance, find_conflict, Conflict, NEAR_TOUCH,
    };
    let mut index = vec![u32::MAX; features.len()];
    let mut points = Vec::new();
    for (f, feat) in features.iter().enumerate() {
        if let Shape::Corner(p) = feat.shape {
            index[f] = points.len() as u32;
            points.push(p);
        }
    }
    let edges: Vec<usize> = (0..features.len())
        .filter(|&f| features[f].is_edge())
        .collect();
    let segments: Vec<[u32; 2]> = edges
        .iter()
        .map(|&e| {
            [
                index[features[e].links[0] as usize],
                index[features[e].links[1] as usize],
            ]
        })
        .collect();
    check_sites_beside_tolerance(points.iter().copied(), domain)?;
    let near =
        NEAR_TOUCH * crate::geom::grid::bounds_of_points(points.iter().copied()).longest_side();
    let Some(c) = find_conflict(&points, &segments, &[], near) else {
        return Ok(());
    };
    let site = |k: usize| features[edges[k]].owners[0].site();
    let (i, j, what) = match c {
        Conflict::Cross(i, j) => (i, j, "edges cross"),
        Conflict::Overlap(i, j) => (i, j, "edges overlap"),
        Conflict::Touch(i, j) => (
            i,
            j,
            "an endpoint touches the inside of another edge (split it there)",
        ),
        Conflict::PointOn(i, _) => (i, i, "a point lies inside an edge"),
        Conflict::NearlyOn(i, j, _) => (
            i,
            j.unwrap_or(i),
            "a corner lies within 4e-12 of the scene's size of an edge's inside without \
             touching it exactly: make it touch exactly or move it apart",
        ),
    };
    let (a, b) = (site(i), site(j));
    Err(Error::Conflict {
        site: a.min(b),
        other: a.max(b),
        message: if a == b {
            format!("{what} within site {a}")
        } else {
            what.to_string()
        },
    })
}
