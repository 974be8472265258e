//! The checker's generators: what the diagram's labels name, each with its own field.
//!
//! In `voronoi` mode a generator is a whole site: a polyline's field is the distance to
//! the union of its segments, a polygon's the distance to its rings (its inside is
//! masked, see `region.rs`). In `complex` and `medial_axis` modes sites with features are
//! split as `SCENE_FORMAT.md` and the Python checker number them:
//!
//! * `segment`: corner 0 = `from`, corner 1 = `to`, edge 0;
//! * `polyline`: corners 0..n−1, edge k from corner k to corner k+1;
//! * `polygon`: corners numbered across the rings (ring 0 first), edge k from corner k
//!   to the next corner of its ring, a ring's last edge closing it;
//! * `arc`: corner 0 = start, corner 1 = end, piece 0 (a full circle: piece 0 only);
//! * `bezier`, `bspline`: pieces between tangent discontinuities in parameter order,
//!   corner k at the start of piece k (an open curve's last corner at its end; a
//!   closed curve without corners is one piece).
//!
//! A corner's field is the distance to its point, an edge's the distance to its closed
//! segment, a piece's the distance to its arc. Other sites stay whole generators.
//!
//! An edge or piece is an *open* feature: where its foot is an end corner, the nearest
//! feature is that corner. Each edge/piece records its ends (corner position, unit
//! tangent into the feature, corner generator) for the rules built on this
//! ([`Gens::end_corner`], [`Gens::beyond_end`], [`Gens::corner_if_at_end`],
//! [`Gens::zone_boundary`]).

use super::field::Field;
use super::parametric::{spline_site, SplineSite};
use super::region::{boundary_segments, medial_region, Region};
use crate::complex::{FeatureKind, Generator};
use crate::error::Error;
use crate::geom::grid::SparseGrid;
use crate::geom::Point;
use crate::scene::{Mode, Scene, SiteKind};
use std::collections::HashMap;
use std::f64::consts::TAU;

/// An end of an edge or piece generator.
#[derive(Clone, Copy, Debug)]
pub(super) struct End {
    /// the end corner's position
    pub at: Point,
    /// the unit tangent at the end, pointing into the feature
    pub into: Point,
    /// the corner's generator
    pub corner: usize,
}

/// A region whose inside belongs to no diagram (`voronoi` and `complex` modes).
#[derive(Clone, Debug)]
pub(super) enum Mask {
    /// an ellipse: the inside of generator `gen`'s field
    Ellipse { gen: usize },
    /// a polygon's even-odd inside
    Polygon { region: Region },
}

/// Feature kinds as lookup keys: edges and pieces are the same thing.
fn kind_key(k: Option<FeatureKind>) -> u8 {
    match k {
        None => 0,
        Some(FeatureKind::Corner) => 1,
        Some(FeatureKind::Edge) | Some(FeatureKind::Piece) => 2,
    }
}

/// The generator table of a scene.
pub(super) struct Gens {
    /// each generator's field
    pub fields: Vec<Field>,
    /// each generator's label, as the diagram writes it
    pub labels: Vec<Generator>,
    /// the ends of each edge/piece generator (empty for the others)
    pub ends: Vec<Vec<End>>,
    /// curved generators (arc pieces; ellipses), which may bound an edge on both sides
    /// in `complex` and `medial_axis` modes
    pub curved: Vec<bool>,
    /// for a corner generator, the edge/piece generators it ends
    pub corner_of: Vec<Vec<usize>>,
    /// `complex` or `medial_axis` mode
    pub featured: bool,
    /// closed sites whose insides are masked (empty in `medial_axis` mode)
    pub masks: Vec<Mask>,
    /// the medial-axis region (`medial_axis` mode only)
    pub region: Option<Region>,
    /// the points that several sites contain, with their owners
    pub shared: SharedPoints,
    lookup: HashMap<(usize, u8, usize), usize>,
}

/// The points that several sites contain (segments sharing an end, a point site at a
/// segment's end), each with the generator that names it for each of those sites: its
/// corner there in `complex` and `medial_axis` modes, the site itself in `voronoi`
/// mode. `SCENE_FORMAT.md` ("Shared points") leaves open which of them owns the region
/// of points nearest to the shared point, so a diagram may name any. Points within
/// `radius` of each other are one point (an arc's computed end may miss a segment's by
/// an ulp).
pub(super) struct SharedPoints {
    radius: f64,
    /// owners at their points
    owners: SparseGrid<(usize, usize)>,
}

/// A site's point, the generator naming it, and the site.
impl SharedPoints {
    fn new(radius: f64) -> SharedPoints {
        SharedPoints {
            radius,
            owners: SparseGrid::new(radius),
        }
    }

    /// The owners `(generator, site)` within `radius` of `p`.
    fn near(&self, p: Point) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.owners.near(p).map(|e| e.1)
    }

    /// The owners of the shared point at `p` (none if no shared point is there).
    pub(super) fn owners_at(&self, p: Point) -> Vec<(usize, usize)> {
        let owners: Vec<(usize, usize)> = self.near(p).collect();
        let first = owners.first().map(|o| o.1);
        if owners.iter().all(|o| Some(o.1) == first) {
            return Vec::new();
        }
        owners
    }

    /// Within what the shared points are matched.
    pub(super) fn radius(&self) -> f64 {
        self.radius
    }
}

/// The points of a site that another site may share: a Euclidean point site's point,
/// the corners of segments, polylines and polygons (in their numbering), an arc's ends.
fn site_points(kind: &SiteKind) -> Vec<Point> {
    match kind {
        SiteKind::Point {
            at,
            metric: crate::scene::Metric::Euclidean,
        } => vec![*at],
        SiteKind::Segment { from, to } => vec![*from, *to],
        SiteKind::Polyline { points } => points.clone(),
        SiteKind::Polygon { rings } => rings.iter().flatten().copied().collect(),
        &SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => {
            let sweep = crate::geom::arc::sweep(start_angle, end_angle);
            if sweep >= TAU {
                return Vec::new();
            }
            let at = |a: f64| center + Point::new(a.cos(), a.sin()) * radius;
            vec![at(start_angle), at(start_angle + sweep)]
        }
        _ => Vec::new(),
    }
}

impl Gens {
    /// Builds the generators of `scene`, or refuses what the checker cannot evaluate.
    pub(super) fn new(scene: &Scene) -> Result<Gens, Error> {
        let featured = scene.mode() != Mode::Voronoi;
        let h = 1e-6 * scene.domain().longest_side();
        let (scale, spacing) = (scene.domain().longest_side(), 0.25 * scene.epsilon());
        let mut g = Gens {
            fields: Vec::new(),
            labels: Vec::new(),
            ends: Vec::new(),
            curved: Vec::new(),
            corner_of: Vec::new(),
            featured,
            masks: Vec::new(),
            region: None,
            shared: SharedPoints::new(1e-9 * scene.domain().longest_side()),
            lookup: HashMap::new(),
        };
        for (i, site) in scene.sites().iter().enumerate() {
            let kind = &site.kind;
            if scene.mode() == Mode::MedialAxis && matches!(kind, SiteKind::Ellipse { .. }) {
                return Err(Error::Unsupported {
                    site: i,
                    kind: kind.name().to_string(),
                    message: "the checker cannot evaluate an ellipse's medial axis yet".into(),
                });
            }
            if featured {
                match kind {
                    SiteKind::Segment { from, to } => g.add_chain(i, &[*from, *to]),
                    SiteKind::Polyline { points } => g.add_chain(i, points),
                    SiteKind::Polygon { rings } => {
                        let mut base = 0;
                        let corners: Vec<usize> = rings
                            .iter()
                            .flatten()
                            .enumerate()
                            .map(|(k, &p)| g.push(Field::Euclid { p }, i, Some((0, k)), false))
                            .collect();
                        for ring in rings {
                            let n = ring.len();
                            for k in 0..n {
                                let (c0, c1) = (corners[base + k], corners[base + (k + 1) % n]);
                                g.add_segment(i, base + k, ring[k], ring[(k + 1) % n], c0, c1);
                            }
                            base += n;
                        }
                    }
                    SiteKind::Arc {
                        center,
                        radius,
                        start_angle,
                        end_angle,
                    } => g.add_arc(i, *center, *radius, *start_angle, *end_angle),
                    SiteKind::Bezier { .. } | SiteKind::Bspline { .. } => {
                        if let Some(spline) = spline_site(kind, scale, spacing) {
                            g.add_spline(i, spline);
                        }
                    }
                    other => {
                        let f = Field::of_site(i, other, h, scene)?;
                        let curved = match f {
                            Field::Ellipse { .. } => true,
                            Field::Curve(_) => scene.mode() == Mode::MedialAxis,
                            _ => false,
                        };
                        g.push(f, i, None, curved);
                    }
                }
            } else {
                let f = Field::of_site(i, kind, h, scene)?;
                let curved = matches!(f, Field::Arc { .. } | Field::Ellipse { .. });
                g.push(f, i, None, curved);
            }
            if scene.mode() != Mode::MedialAxis {
                match kind {
                    SiteKind::Polygon { rings } => g.masks.push(Mask::Polygon {
                        region: Region::new(super::field::ring_segments(rings)),
                    }),
                    SiteKind::Ellipse { .. } => g.masks.push(Mask::Ellipse {
                        gen: g.fields.len() - 1,
                    }),
                    SiteKind::Bezier { .. } | SiteKind::Bspline { .. }
                        if spline_site(kind, scale, spacing).is_some_and(|c| c.closed) =>
                    {
                        g.masks.push(Mask::Polygon {
                            region: Region::new(boundary_segments(kind, 0.0, spacing, scale)),
                        });
                    }
                    _ => {}
                }
            }
        }
        if scene.mode() == Mode::MedialAxis {
            // the algebraic sites' own samples bound the region too (not sampled again)
            let curves = g
                .fields
                .iter()
                .filter_map(|f| match f {
                    Field::Curve(c) => Some((**c).clone()),
                    _ => None,
                })
                .collect();
            let r = medial_region(scene, curves);
            g.region = (!r.is_empty()).then_some(r);
        }
        g.find_shared_points(scene);
        Ok(g)
    }

    /// Fills [`Gens::shared`] with the points of more than one site.
    fn find_shared_points(&mut self, scene: &Scene) {
        let mut all = SharedPoints::new(self.shared.radius);
        for (i, site) in scene.sites().iter().enumerate() {
            let whole = self.lookup.get(&(i, 0, 0)).copied();
            for (k, p) in site_points(&site.kind).into_iter().enumerate() {
                let corner = self
                    .lookup
                    .get(&(i, kind_key(Some(FeatureKind::Corner)), k));
                if let Some(g) = whole.or(corner.copied()) {
                    all.owners.insert(p, (g, i));
                }
            }
        }
        for &(p, (g, site)) in all.owners.items() {
            if all.near(p).any(|(_, other)| other != site) {
                self.shared.owners.insert(p, (g, site));
            }
        }
    }

    /// Adds a generator: `feature` is `None` for a whole site, else `(kind, index)` with
    /// kind 0 = corner, 1 = edge, 2 = piece.
    fn push(&mut self, f: Field, site: usize, feature: Option<(u8, usize)>, curved: bool) -> usize {
        let id = self.fields.len();
        let (label, key) = match feature {
            None => (Generator::Site(site), (site, 0, 0)),
            Some((k, index)) => {
                let feature =
                    [FeatureKind::Corner, FeatureKind::Edge, FeatureKind::Piece][k as usize];
                (
                    Generator::Feature {
                        site,
                        feature,
                        index,
                    },
                    (site, kind_key(Some(feature)), index),
                )
            }
        };
        self.fields.push(f);
        self.labels.push(label);
        self.ends.push(Vec::new());
        self.curved.push(curved);
        self.corner_of.push(Vec::new());
        self.lookup.insert(key, id);
        id
    }

    /// Corners and edges of an open chain of points.
    fn add_chain(&mut self, site: usize, pts: &[Point]) {
        let corners: Vec<usize> = pts
            .iter()
            .enumerate()
            .map(|(k, &p)| self.push(Field::Euclid { p }, site, Some((0, k)), false))
            .collect();
        for k in 0..pts.len().saturating_sub(1) {
            self.add_segment(site, k, pts[k], pts[k + 1], corners[k], corners[k + 1]);
        }
    }

    /// Edge `index` of `site` from corner `c0` at `a` to corner `c1` at `b`.
    fn add_segment(&mut self, site: usize, index: usize, a: Point, b: Point, c0: usize, c1: usize) {
        let e = self.push(Field::Segment { a, b }, site, Some((1, index)), false);
        let d = b - a;
        let u = d * (1.0 / d.norm().max(1e-300));
        self.set_ends(e, [(a, u, c0), (b, u * -1.0, c1)]);
    }

    /// An arc's corners and piece (a full circle: its piece only).
    fn add_arc(&mut self, site: usize, c: Point, r: f64, start: f64, end: f64) {
        let sweep = crate::geom::arc::sweep(start, end);
        let f = Field::Arc { c, r, start, sweep };
        if sweep >= TAU {
            self.push(f, site, Some((2, 0)), true);
            return;
        }
        let at = |a: f64| c + Point::new(a.cos(), a.sin()) * r;
        let tangent = |a: f64| Point::new(-a.sin(), a.cos());
        let (p0, p1) = (at(start), at(start + sweep));
        let c0 = self.push(Field::Euclid { p: p0 }, site, Some((0, 0)), false);
        let c1 = self.push(Field::Euclid { p: p1 }, site, Some((0, 1)), false);
        let e = self.push(f, site, Some((2, 0)), true);
        let t1 = tangent(start + sweep);
        self.set_ends(e, [(p0, tangent(start), c0), (p1, t1 * -1.0, c1)]);
    }

    /// A free-form curve's corners and pieces (SCENE_FORMAT.md numbering): piece `k`
    /// runs from corner `k` to the next corner (wrapping on a closed curve).
    fn add_spline(&mut self, site: usize, spline: SplineSite) {
        let corners: Vec<usize> = spline
            .corners
            .iter()
            .enumerate()
            .map(|(k, &p)| self.push(Field::Euclid { p }, site, Some((0, k)), false))
            .collect();
        let n = corners.len();
        for (k, piece) in spline.pieces.into_iter().enumerate() {
            let [(p0, t0), (p1, t1)] = piece.ends();
            let e = self.push(Field::Pieces(vec![piece]), site, Some((2, k)), true);
            if n > 0 {
                self.set_ends(e, [(p0, t0, corners[k]), (p1, t1, corners[(k + 1) % n])]);
            }
        }
    }

    fn set_ends(&mut self, e: usize, ends: [(Point, Point, usize); 2]) {
        for (at, into, corner) in ends {
            self.ends[e].push(End { at, into, corner });
            self.corner_of[corner].push(e);
        }
    }

    /// The generator a diagram label names, or why it is not valid in this mode.
    pub(super) fn parse(&self, g: &Generator) -> Result<usize, String> {
        // a piece of a closed smooth curve in `medial_axis` mode: the whole curve, whose
        // branches the checks compare
        if let Generator::Feature {
            site,
            feature: FeatureKind::Piece,
            ..
        } = *g
        {
            if let Some(whole) = self.whole_curve(site) {
                return Ok(whole);
            }
        }
        match *g {
            Generator::Site(i) => self.lookup.get(&(i, 0, 0)).copied().ok_or_else(|| {
                if self.lookup.keys().any(|k| k.0 == i) {
                    format!("site {i} has features in this mode; label a corner, edge or piece")
                } else {
                    format!("site {i} does not exist")
                }
            }),
            Generator::Feature { site, .. } if !self.featured => Err(format!(
                "feature generators of site {site} are not valid in voronoi mode"
            )),
            Generator::Feature {
                site,
                feature,
                index,
            } => self
                .lookup
                .get(&(site, kind_key(Some(feature)), index))
                .copied()
                .ok_or_else(|| {
                    if self.lookup.contains_key(&(site, 0, 0)) {
                        format!("site {site} has no features; use {site}")
                    } else {
                        format!("no feature {feature:?} {index} on site {site}")
                    }
                }),
        }
    }

    /// Whether generator `g` is a whole curve standing for its pieces
    /// ([`whole_curve`](Self::whole_curve)).
    pub(super) fn whole_curve_field(&self, g: usize) -> bool {
        self.whole_curve(self.labels[g].site()) == Some(g)
    }

    /// The generator of site `site` when it is one curved field for the whole site in
    /// a featured mode (an algebraic curve in `medial_axis` mode).
    fn whole_curve(&self, site: usize) -> Option<usize> {
        let g = *self.lookup.get(&(site, 0, 0))?;
        (self.featured && self.curved[g] && matches!(self.fields[g], Field::Curve(_))).then_some(g)
    }

    /// A generator's name in messages: `3`, or `3:corner1` / `3:edge0` / `3:piece0`.
    pub(super) fn name(&self, g: usize) -> String {
        match self.labels.get(g) {
            Some(Generator::Site(i)) => i.to_string(),
            Some(Generator::Feature {
                site,
                feature,
                index,
            }) => format!("{site}:{}{index}", format!("{feature:?}").to_lowercase()),
            None => "none".into(),
        }
    }

    /// Whether `a` and `b` are a corner and an edge/piece ending there: their common
    /// boundary is a zone boundary, not a Voronoi edge.
    pub(super) fn zone_boundary(&self, a: usize, b: usize) -> bool {
        self.corner_of[a].contains(&b) || self.corner_of[b].contains(&a)
    }

    /// The end of edge/piece `g` that is its foot from `q`, if any (within `tiny`).
    fn end_at_foot(&self, g: usize, q: Point, tiny: f64) -> Option<End> {
        let ends = &self.ends[g];
        if ends.is_empty() {
            return None;
        }
        let foot = self.fields[g].foot(q)?;
        ends.iter().copied().find(|e| foot.dist(e.at) <= tiny)
    }

    /// The label of the nearest generator `g` at `q`: the end corner where the foot on
    /// an edge/piece is that corner (the Python checker's `_label`).
    pub(super) fn end_corner(&self, g: usize, q: Point, tiny: f64) -> usize {
        self.end_at_foot(g, q, tiny).map_or(g, |e| e.corner)
    }

    /// How far `q` lies beyond an end corner of edge/piece `g` whose foot from `q` is
    /// that corner (0 otherwise): such a point should name the corner.
    pub(super) fn beyond_end(&self, g: usize, q: Point, tiny: f64) -> f64 {
        self.end_at_foot(g, q, tiny)
            .map_or(0.0, |e| (-(q - e.at).dot(e.into)).max(0.0))
    }

    /// `g`, or its end corner where the foot from `x` is that corner (within `tiny`) and
    /// `x` lies beyond it by more than `tiny` and `margin` (a bisection crossed the
    /// corner's zone boundary).
    pub(super) fn corner_if_at_end(&self, g: usize, x: Point, tiny: f64, margin: f64) -> usize {
        match self.end_at_foot(g, x, tiny) {
            Some(e) if (x - e.at).dot(e.into) < -tiny.max(margin) => e.corner,
            _ => g,
        }
    }
}
