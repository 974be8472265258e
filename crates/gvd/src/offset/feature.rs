//! The scene's features — point sites, corners, edges and arcs — with their exact
//! Euclidean distances, the generators that name them, the regions polygons bound, and a
//! uniform grid that finds the features near a point.

use crate::complex::{FeatureKind, Generator};
use crate::error::Error;
use crate::geom::grid::{bounds_of_points, BucketGrid};
use crate::geom::ring::even_odd_contains;
use crate::geom::{segment_distance, Aabb, Point};
use crate::scene::{Metric, Scene, SiteKind};
use std::collections::HashMap;
use std::f64::consts::TAU;
use std::ops::Range;

/// One feature: a point (a point site or a corner), a closed edge `[a, b]` or a closed
/// circular arc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Shape {
    Point(Point),
    /// An edge with the indices of the corner features at `a` and at `b`.
    Edge {
        a: Point,
        b: Point,
        corners: [usize; 2],
    },
    /// The arc of the circle `(center, radius)` from angle `start` (as the scene gives
    /// it) counter-clockwise over `span` (in `(0, 2π)`), with the indices of the corner
    /// features at its start and at its end.
    Arc {
        center: Point,
        radius: f64,
        start: f64,
        span: f64,
        corners: [usize; 2],
    },
}

impl Shape {
    /// The Euclidean distance from `q` to the closed feature: `|q − p|` for a point,
    /// `|q − foot|` for an edge, the foot clamped to `[a, b]`; for an arc, the distance
    /// to its circle when the direction of `q` from the centre is within the span, else
    /// to the nearer end.
    pub(crate) fn distance(&self, q: Point) -> f64 {
        match *self {
            Shape::Point(p) => q.dist(p),
            Shape::Edge { a, b, .. } => segment_distance(q, a, b),
            Shape::Arc {
                center,
                radius,
                start,
                span,
                ..
            } => {
                let v = q - center;
                if (v.y.atan2(v.x) - start).rem_euclid(TAU) <= span {
                    (v.norm() - radius).abs()
                } else {
                    let [e0, e1] = arc_ends(center, radius, start, span);
                    q.dist(e0).min(q.dist(e1))
                }
            }
        }
    }

    pub(crate) fn bounds(&self) -> Aabb {
        match *self {
            Shape::Point(p) => Aabb::new(p, p),
            Shape::Edge { a, b, .. } => Aabb::new(
                Point::new(a.x.min(b.x), a.y.min(b.y)),
                Point::new(a.x.max(b.x), a.y.max(b.y)),
            ),
            // the whole circle's box: a little more than needed
            Shape::Arc { center, radius, .. } => Aabb::new(
                center - Point::new(radius, radius),
                center + Point::new(radius, radius),
            ),
        }
    }
}

/// The start and end points of an arc, computed as the diagram computes its end
/// generators (so that an end shared with another site is the same point).
pub(super) fn arc_ends(center: Point, radius: f64, start: f64, span: f64) -> [Point; 2] {
    [start, start + span].map(|a| center + Point::new(a.cos(), a.sin()) * radius)
}

/// Where a site's features sit in the list: corners `start..start + corners` (for a
/// point site, its one point), then its edges (an arc's one piece).
struct SiteFeatures {
    start: usize,
    corners: usize,
    edges: usize,
    /// What the generators call the features after the corners: edges, or an arc's piece.
    kind: FeatureKind,
}

/// Every feature of a scene, in site order.
pub(crate) struct Features {
    pub(crate) shapes: Vec<Shape>,
    /// Per feature, the feature that stands for it: the first point feature at the same
    /// place for a point (corners shared by sites, point sites on corners are one
    /// point, as in the diagram), itself otherwise.
    pub(super) canonical: Vec<usize>,
    /// Point features by the bits of their coordinates.
    points: HashMap<(u64, u64), usize>,
    sites: Vec<SiteFeatures>,
    /// The rings of every polygon site (outer ring first, then holes).
    polygons: Vec<Vec<Vec<Point>>>,
}

impl Features {
    /// The features of Euclidean points, segments, arcs, polylines and polygons
    /// (numbered as `SCENE_FORMAT.md` numbers corners, edges and pieces); other site
    /// kinds, and full-circle arcs, are refused.
    pub(crate) fn of_scene(scene: &Scene) -> Result<Features, Error> {
        let mut f = Features {
            shapes: Vec::new(),
            canonical: Vec::new(),
            points: HashMap::new(),
            sites: Vec::new(),
            polygons: Vec::new(),
        };
        for (i, site) in scene.sites().iter().enumerate() {
            match &site.kind {
                SiteKind::Point {
                    at,
                    metric: Metric::Euclidean,
                } => f.push_chain(&[*at], &[]),
                SiteKind::Segment { from, to } => f.push_chain(&[*from, *to], &[(0, 1)]),
                SiteKind::Polyline { points } => {
                    let edges: Vec<_> = (1..points.len()).map(|k| (k - 1, k)).collect();
                    f.push_chain(points, &edges);
                }
                SiteKind::Polygon { rings } => {
                    let (corners, edges) = ring_chain(rings);
                    f.push_chain(&corners, &edges);
                    f.polygons.push(rings.clone());
                }
                &SiteKind::Arc {
                    center,
                    radius,
                    start_angle,
                    end_angle,
                } => {
                    let Some(span) = crate::geom::arc::partial_sweep(start_angle, end_angle) else {
                        return Err(Error::Unsupported {
                            site: i,
                            kind: "arc".into(),
                            message: "offsets are computed for arcs short of a full circle".into(),
                        });
                    };
                    f.push_arc(center, radius, start_angle, span);
                }
                other => {
                    return Err(Error::Unsupported {
                        site: i,
                        kind: other.name().to_string(),
                        message: "offsets are computed for Euclidean points, segments, \
                                  arcs, polylines and polygons (so far)"
                            .into(),
                    })
                }
            }
        }
        Ok(f)
    }

    /// Appends one point feature, standing for the first point feature at its place.
    fn push_point(&mut self, p: Point) {
        let k = self.shapes.len();
        // −0.0 and 0.0 are the same point
        let key = ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits());
        self.canonical.push(*self.points.entry(key).or_insert(k));
        self.shapes.push(Shape::Point(p));
    }

    /// Appends one feature that stands for itself.
    fn push_shape(&mut self, s: Shape) {
        self.canonical.push(self.shapes.len());
        self.shapes.push(s);
    }

    /// Appends one site's corners and its edges (pairs of corner numbers).
    fn push_chain(&mut self, corners: &[Point], edges: &[(usize, usize)]) {
        let start = self.shapes.len();
        for &p in corners {
            self.push_point(p);
        }
        for &(i, j) in edges {
            self.push_shape(Shape::Edge {
                a: corners[i],
                b: corners[j],
                corners: [start + i, start + j],
            });
        }
        self.sites.push(SiteFeatures {
            start,
            corners: corners.len(),
            edges: edges.len(),
            kind: FeatureKind::Edge,
        });
    }

    /// Appends an arc site: its start and end corners, then its piece.
    fn push_arc(&mut self, center: Point, radius: f64, start: f64, span: f64) {
        let first = self.shapes.len();
        for p in arc_ends(center, radius, start, span) {
            self.push_point(p);
        }
        self.push_shape(Shape::Arc {
            center,
            radius,
            start,
            span,
            corners: [first, first + 1],
        });
        self.sites.push(SiteFeatures {
            start: first,
            corners: 2,
            edges: 1,
            kind: FeatureKind::Piece,
        });
    }

    /// The site of each feature, in the features' order.
    pub(crate) fn sites_of_shapes(&self) -> Vec<usize> {
        let mut out = Vec::with_capacity(self.shapes.len());
        for (i, s) in self.sites.iter().enumerate() {
            out.resize(s.start + s.corners + s.edges, i);
        }
        out
    }

    /// The features a generator stands for: a whole site (all its features) or one
    /// corner or edge; `None` for a generator the scene does not have.
    pub(super) fn of_generator(&self, g: &Generator) -> Option<Range<usize>> {
        let s = self.sites.get(g.site())?;
        match *g {
            Generator::Site(_) => Some(s.start..s.start + s.corners + s.edges),
            Generator::Feature { feature, index, .. } => {
                let k = match feature {
                    FeatureKind::Corner if index < s.corners => s.start + index,
                    FeatureKind::Edge | FeatureKind::Piece
                        if feature == s.kind && index < s.edges =>
                    {
                        s.start + s.corners + index
                    }
                    _ => return None,
                };
                Some(k..k + 1)
            }
        }
    }

    /// Whether `q` lies inside a polygon site (inside its outer ring, outside its holes):
    /// the even-odd rule over all of the polygon's rings.
    pub(super) fn inside_region(&self, q: Point) -> bool {
        self.polygons
            .iter()
            .any(|rings| rings.iter().filter(|r| even_odd_contains(r, q)).count() % 2 == 1)
    }
}

/// A polygon's corners numbered across its rings, and its edges: edge k goes from
/// corner k to the next corner of the same ring.
fn ring_chain(rings: &[Vec<Point>]) -> (Vec<Point>, Vec<(usize, usize)>) {
    let mut corners = Vec::new();
    let mut edges = Vec::new();
    for ring in rings {
        let (o, n) = (corners.len(), ring.len());
        corners.extend_from_slice(ring);
        edges.extend((0..n).map(|k| (o + k, o + (k + 1) % n)));
    }
    (corners, edges)
}

/// Features bucketed by their bounding boxes in the shared grid.
pub(super) struct Grid(BucketGrid);

impl Grid {
    /// A grid whose cells are at least `reach` wide (queries of radius `reach` then look
    /// at a few cells) and at most 256 along the longer side.
    pub(super) fn new(shapes: &[Shape], reach: f64) -> Grid {
        let boxes: Vec<Aabb> = shapes.iter().map(Shape::bounds).collect();
        let extent = bounds_of_points(boxes.iter().flat_map(|b| [b.min, b.max]));
        let side = if shapes.is_empty() {
            0.0
        } else {
            extent.longest_side()
        };
        let cell = reach.max(side / 256.0).max(f64::MIN_POSITIVE);
        Grid(BucketGrid::new(extent, cell, 257, boxes.len(), |k| {
            boxes[k]
        }))
    }

    /// Whether `pred` holds for some feature whose bounding box may meet the disk of
    /// radius `r` around `q` (features may be visited more than once).
    pub(super) fn any_near(&self, q: Point, r: f64, mut pred: impl FnMut(usize) -> bool) -> bool {
        let reach = Point::new(r, r);
        self.0
            .any_in(&Aabb::new(q - reach, q + reach), |k| pred(k as usize))
    }
}
