//! Scenes of Euclidean points, segments, arcs, polylines and polygons through the
//! segment engine: sites become point, segment and arc generators, and the engine's raw
//! graph becomes the [`VoronoiComplex`] of the scene's mode.
//!
//! * Generators: every distinct point (point sites, segment and arc ends, chain
//!   corners), every segment, polyline edge and polygon edge of positive length, and
//!   every arc short of a full circle.
//! * Labels: in `voronoi` mode a generator is its site; in `complex` and
//!   `medial_axis` modes a corner, an edge or a piece (an arc's inside) feature (a
//!   point site stays a site). A point shared by several sites is named by the first
//!   of them in the scene; vertices there list all of them.
//! * Edges between a corner and a segment ending there (the zone boundaries, or
//!   separators) and edges between two parts of one site in `voronoi` mode are left
//!   out; edges then run through the vertices that join only two labels, away from
//!   the sites. At a tangent joint the end's face has zero area: its two sides of
//!   separators become one edge between the two features (`joints.rs`). Edges inside
//!   polygons are left out in `voronoi` and `complex` modes (the inside is part of the
//!   site) and kept only there in `medial_axis` mode. Everything is clipped to the
//!   domain.

mod assembly;
mod phases;

use super::bisector_form::{self, OffsetGen};
use super::segments_arcs::{
    check_sites_beside_tolerance, find_arc_conflict, find_conflict, joints, split_segments,
    ArcConflict, ArcSpec, Conflict, Gen, SegmentDiagram, Split, NEAR_TOUCH,
};
use crate::complex::{BisectorPiece, FeatureKind, Generator, VoronoiComplex};
use crate::compute::IncrementalOptions;
use crate::control::Watch;
use crate::geom::arc::{partial_sweep, ray_crosses_odd};
use crate::geom::grid::SparseGrid;
use crate::geom::ring::RayCrossings;
use crate::geom::Point;
use crate::scene::{Metric, Mode, Scene, SiteKind};
use crate::subdivision::{Budget, Limits};
use crate::Error;
use assembly::{assemble, Stretch};
use phases::Phases;
use rustc_hash::FxHashMap;
use std::sync::OnceLock;

/// Whether every site is a Euclidean point, a segment, an arc short of a full circle, a
/// polyline or a polygon.
pub fn supports(scene: &Scene) -> bool {
    scene.sites().iter().all(|s| supports_site(&s.kind))
}

/// Whether a site of this kind goes through the segment engine.
pub fn supports_site(kind: &SiteKind) -> bool {
    match kind {
        SiteKind::Arc {
            start_angle,
            end_angle,
            ..
        } => partial_sweep(*start_angle, *end_angle).is_some(),
        kind => matches!(
            kind,
            SiteKind::Point {
                metric: Metric::Euclidean,
                ..
            } | SiteKind::Segment { .. }
                | SiteKind::Polyline { .. }
                | SiteKind::Polygon { .. }
        ),
    }
}

/// What a point generator is of a site.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    /// The site is this point.
    Point,
    /// Corner `k` of the site (a segment's end, an arc's end, a chain's corner).
    Corner(usize),
    /// A point inside edge `k` of the site where it was cut (`split.rs`).
    Inside(usize),
}

/// A site and what a point generator is of it.
type Owner = (usize, Part);

/// The generators of a scene and what they stand for.
struct Generators {
    points: Vec<Point>,
    /// Per point generator: (site, what the point is of it), the first site in the
    /// scene that has the point, which names it on edges.
    point_owner: Vec<Owner>,
    /// The other sites' corners and point sites at a shared point (vertices there list
    /// them all: they are one point).
    also: FxHashMap<u32, Vec<Owner>>,
    segments: Vec<[u32; 2]>,
    /// Per segment generator: (site, edge index).
    segment_owner: Vec<(usize, usize)>,
    arcs: Vec<ArcSpec>,
    /// Per arc generator: its site.
    arc_owner: Vec<usize>,
    /// Point generators that are point sites and no segment's end.
    lonely: Vec<u32>,
    /// Closed rings of polygon sites (for insides).
    rings: Vec<Vec<Point>>,
    /// The rings' edges, and the loops' segments, indexed for even-odd tests (built on
    /// first use).
    ring_crossings: OnceLock<RayCrossings>,
    loop_crossings: OnceLock<RayCrossings>,
    /// In `medial_axis` mode, the segment and arc generators of open sites (segments,
    /// polylines, arcs) that close up into loops: they bound regions too.
    loop_segments: Vec<u32>,
    loop_arcs: Vec<u32>,
    /// The first point generator that is a computed crossing point (`split.rs`), if any:
    /// they are numbered last.
    first_crossing_point: Option<u32>,
    /// The site of `point_owner` and of `segment_owner`, compactly.
    point_site: Vec<u32>,
    segment_site: Vec<u32>,
    /// Where segments' lines may be measured from their first end (`anchor_reach`).
    reach: f64,
}

/// Room for every point of every site of `scene` (shared ones counted once each).
fn room(scene: &Scene) -> usize {
    scene
        .sites()
        .iter()
        .map(|s| match &s.kind {
            SiteKind::Polyline { points } => points.len(),
            SiteKind::Polygon { rings } => rings.iter().map(Vec::len).sum(),
            SiteKind::Point { .. } => 1,
            _ => 2,
        })
        .sum()
}

/// [`Generators`] under construction, with the index of its points by their bits.
struct GeneratorBuilder {
    g: Generators,
    index: FxHashMap<(u64, u64), u32>,
    /// Scratch: a chain's point ids.
    ids: Vec<u32>,
}

impl GeneratorBuilder {
    fn with_room(most: usize) -> GeneratorBuilder {
        let g = Generators {
            points: Vec::with_capacity(most),
            point_owner: Vec::with_capacity(most),
            also: FxHashMap::default(),
            segments: Vec::with_capacity(most),
            segment_owner: Vec::with_capacity(most),
            arcs: Vec::new(),
            arc_owner: Vec::new(),
            lonely: Vec::new(),
            rings: Vec::new(),
            ring_crossings: OnceLock::new(),
            loop_crossings: OnceLock::new(),
            loop_segments: Vec::new(),
            loop_arcs: Vec::new(),
            first_crossing_point: None,
            point_site: Vec::new(),
            segment_site: Vec::new(),
            reach: f64::INFINITY,
        };
        let mut index = FxHashMap::default();
        index.reserve(most);
        GeneratorBuilder {
            g,
            index,
            ids: Vec::new(),
        }
    }

    /// The point generator at `p` (a new one, or `owner` shares an existing one).
    fn point(&mut self, p: Point, owner: Owner) -> u32 {
        // −0.0 and 0.0 are the same point.
        let key = ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits());
        match self.index.get(&key) {
            Some(&id) => {
                self.g.share(id, owner);
                id
            }
            None => {
                self.g.points.push(p);
                self.g.point_owner.push(owner);
                let id = self.g.points.len() as u32 - 1;
                self.index.insert(key, id);
                id
            }
        }
    }

    /// The corners of a chain of site `site` (numbered from `corner0`) and its edges of
    /// positive length; `closed` joins the last corner to the first.
    fn chain(&mut self, site: usize, corner0: usize, pts: &[Point], closed: bool) {
        let mut ids = std::mem::take(&mut self.ids);
        ids.clear();
        for (k, &p) in pts.iter().enumerate() {
            ids.push(self.point(p, (site, Part::Corner(corner0 + k))));
        }
        let n = ids.len();
        let edges = if closed { n } else { n - 1 };
        for k in 0..edges {
            let (a, b) = (ids[k], ids[(k + 1) % n]);
            if a != b {
                self.g.segments.push([a, b]);
                self.g.segment_owner.push((site, corner0 + k));
            }
        }
        self.ids = ids;
    }

    /// The arcs, their ends snapped onto the points within `snap_tol`: an arc's ends are
    /// computed (centre + radius · direction), so they may miss a segment's or another
    /// arc's end by an ulp. A point shared by several sites is named by the first of
    /// them in the scene.
    fn arcs(&mut self, arc_sites: Vec<(usize, ArcSpec)>, snap_tol: f64) {
        let mut snap = Snap::new(snap_tol);
        if !arc_sites.is_empty() {
            snap.insert_all(&self.g.points);
        }
        for (i, mut arc) in arc_sites {
            arc.ends = [0, 1].map(|k| {
                let end = arc.end_point(k);
                match snap.find(end) {
                    Some(id) => {
                        self.g.share(id, (i, Part::Corner(k)));
                        id
                    }
                    None => {
                        let id = self.point(end, (i, Part::Corner(k)));
                        snap.insert(end, id);
                        id
                    }
                }
            });
            self.g.arcs.push(arc);
            self.g.arc_owner.push(i);
        }
    }

    /// Point sites, last, so that a corner keeps its feature label; a point site on a
    /// corner is the same generator.
    fn point_sites(&mut self, sites: Vec<(usize, Point)>) {
        for (i, at) in sites {
            let before = self.g.points.len();
            let id = self.point(at, (i, Part::Point));
            if id as usize == before {
                self.g.lonely.push(id);
            }
        }
    }
}

impl Generators {
    /// The generators of `scene`'s points, segments, polylines, polygons and arcs: each
    /// distinct point once (chain corners first, then arc ends snapped onto them, then
    /// point sites), each edge of positive length, each arc short of a full circle.
    fn of(scene: &Scene) -> Generators {
        let mut b = GeneratorBuilder::with_room(room(scene));
        let mut points_sites = Vec::new();
        let mut arc_sites = Vec::new();
        for (i, site) in scene.sites().iter().enumerate() {
            match &site.kind {
                SiteKind::Point { at, .. } => points_sites.push((i, *at)),
                SiteKind::Segment { from, to } => b.chain(i, 0, &[*from, *to], false),
                SiteKind::Polyline { points } => b.chain(i, 0, points, false),
                &SiteKind::Arc {
                    center,
                    radius,
                    start_angle,
                    end_angle,
                } => {
                    if let Some(span) = partial_sweep(start_angle, end_angle) {
                        let arc = ArcSpec {
                            c: center,
                            r: radius,
                            start: start_angle,
                            span,
                            ends: [0, 0],
                        };
                        arc_sites.push((i, arc));
                    }
                }
                SiteKind::Polygon { rings } => {
                    let mut corner = 0;
                    for ring in rings {
                        b.chain(i, corner, ring, true);
                        corner += ring.len();
                        b.g.rings.push(ring.clone());
                    }
                }
                _ => {}
            }
        }
        b.arcs(arc_sites, 1e-12 * scene.domain().longest_side());
        b.point_sites(points_sites);
        b.g
    }

    /// The compact site tables and, in `medial_axis` mode, the loops: once the
    /// generators are final (after any cuts).
    fn finish(&mut self, scene: &Scene) {
        self.reach = super::anchor_reach(&scene.domain());
        self.point_site = self.point_owner.iter().map(|o| o.0 as u32).collect();
        self.segment_site = self.segment_owner.iter().map(|o| o.0 as u32).collect();
        if scene.mode() == Mode::MedialAxis {
            self.find_loops(scene);
        }
    }

    /// The segments replaced by their pieces `cut`: the computed crossing points become
    /// point generators, named by the first site whose edge they are inside, and every
    /// point inside an edge is also owned by that edge's site.
    fn apply_split(&mut self, cut: Split) {
        let first_new = self.points.len() as u32;
        if !cut.new_points.is_empty() {
            self.first_crossing_point = Some(first_new);
        }
        let inside_owner = |seg: u32, owners: &[(usize, usize)]| {
            let (site, edge) = owners[seg as usize];
            (site, Part::Inside(edge))
        };
        self.points.extend(&cut.new_points);
        let mut named = vec![false; cut.new_points.len()];
        // `inside` is sorted by point, then segment: a new point's first entry is the
        // earliest segment, of the earliest site.
        self.point_owner
            .resize(self.points.len(), (usize::MAX, Part::Point));
        for &(p, seg) in &cut.inside {
            let owner = inside_owner(seg, &self.segment_owner);
            match p.checked_sub(first_new) {
                Some(k) if !named[k as usize] => {
                    named[k as usize] = true;
                    self.point_owner[p as usize] = owner;
                }
                _ => self.share(p, owner),
            }
        }
        // a point site that cut a segment is an end of its pieces now
        self.lonely
            .retain(|p| cut.inside.binary_search_by_key(p, |&(q, _)| q).is_err());
        self.segment_owner = cut
            .origin
            .iter()
            .map(|&o| self.segment_owner[o as usize])
            .collect();
        self.segments = cut.pieces;
    }

    /// The segment and arc generators of open sites that lie on closed loops: the
    /// 2-core of the graph they make on the point generators (generators with an end
    /// that no other one shares are peeled off until none is left).
    fn find_loops(&mut self, scene: &Scene) {
        let open_segments: Vec<u32> = (0..self.segments.len() as u32)
            .filter(|&k| {
                let site = self.segment_owner[k as usize].0;
                !matches!(scene.sites()[site].kind, SiteKind::Polygon { .. })
            })
            .collect();
        let ends = |e: usize| -> [u32; 2] {
            if e < open_segments.len() {
                self.segments[open_segments[e] as usize]
            } else {
                self.arcs[e - open_segments.len()].ends
            }
        };
        let count = open_segments.len() + self.arcs.len();
        let mut degree = vec![0u32; self.points.len()];
        let mut at: FxHashMap<u32, Vec<usize>> = FxHashMap::default();
        for e in 0..count {
            for p in ends(e) {
                degree[p as usize] += 1;
                at.entry(p).or_default().push(e);
            }
        }
        let mut alive = vec![true; count];
        let mut free: Vec<u32> = (0..self.points.len() as u32)
            .filter(|&p| degree[p as usize] == 1)
            .collect();
        while let Some(p) = free.pop() {
            for &e in at.get(&p).into_iter().flatten() {
                if alive[e] {
                    alive[e] = false;
                    for q in ends(e) {
                        degree[q as usize] -= 1;
                        if degree[q as usize] == 1 {
                            free.push(q);
                        }
                    }
                }
            }
        }
        self.loop_segments = (0..open_segments.len())
            .filter(|&e| alive[e])
            .map(|e| open_segments[e])
            .collect();
        self.loop_arcs = (open_segments.len()..count)
            .filter(|&e| alive[e])
            .map(|e| (e - open_segments.len()) as u32)
            .collect();
    }

    /// Another owner of point `p`: it names the point if its site comes first.
    fn share(&mut self, p: u32, owner: Owner) {
        let name = &mut self.point_owner[p as usize];
        if *name == owner {
            return;
        }
        let other = if owner.0 < name.0 {
            std::mem::replace(name, owner)
        } else {
            owner
        };
        let also = self.also.entry(p).or_default();
        if !also.contains(&other) {
            also.push(other);
        }
    }

    fn point_label(&self, p: u32, mode: Mode) -> Generator {
        owner_label(self.point_owner[p as usize], mode)
    }

    /// How many labels generator `x` has at a vertex.
    fn label_count(&self, x: Gen) -> usize {
        match x {
            Gen::Point(p) => 1 + self.also.get(&p).map_or(0, Vec::len),
            _ => 1,
        }
    }

    /// The labels of point `p`'s other owners.
    fn also_labels(&self, p: u32, mode: Mode) -> impl Iterator<Item = Generator> + '_ {
        let also = self.also.get(&p).map_or(&[][..], |v| &v[..]);
        also.iter().map(move |&o| owner_label(o, mode))
    }

    fn label(&self, g: Gen, mode: Mode) -> Generator {
        match g {
            Gen::Point(p) => self.point_label(p, mode),
            Gen::Segment(s) => {
                let (site, k) = self.segment_owner[s as usize];
                match mode {
                    Mode::Voronoi => Generator::Site(site),
                    _ => Generator::Feature {
                        site,
                        feature: FeatureKind::Edge,
                        index: k,
                    },
                }
            }
            Gen::Arc(a) => {
                let site = self.arc_owner[a as usize];
                match mode {
                    Mode::Voronoi => Generator::Site(site),
                    _ => Generator::Feature {
                        site,
                        feature: FeatureKind::Piece,
                        index: 0,
                    },
                }
            }
        }
    }

    /// Generator `gen` grown towards `side`; `None` for a far (frame) point.
    fn offset_gen(&self, gen: Gen, side: Point) -> Option<OffsetGen> {
        match gen {
            Gen::Point(p) => self.points.get(p as usize).map(|&c| OffsetGen::point(c)),
            Gen::Segment(s) => {
                let [a, b] = self.segments[s as usize].map(|p| self.points[p as usize]);
                OffsetGen::line(a, b, side, self.reach)
            }
            Gen::Arc(a) => {
                let arc = &self.arcs[a as usize];
                Some(OffsetGen::circle(arc.c, arc.r, side))
            }
        }
    }

    /// The exact bisector under `piece`, a clipped part of a chain whose segment `j`
    /// lies on the chain's segment `first + j`: stretch by stretch, in order. Empty
    /// when some stretch has no offset form (constant clearance).
    fn bisector(
        &self,
        piece: &[Point],
        first: usize,
        stretches: &[Stretch],
        tol: f64,
    ) -> Vec<BisectorPiece> {
        let segments = piece.len() - 1;
        let mut out = Vec::new();
        for (k, st) in stretches.iter().enumerate() {
            let end = stretches.get(k + 1).map_or(usize::MAX, |n| n.start);
            // This stretch's segments of the piece: j with start <= first + j < end.
            let lo = st.start.saturating_sub(first);
            let hi = end.saturating_sub(first).min(segments);
            if lo >= hi {
                continue;
            }
            for pts in self.sides(&piece[lo..=hi], st.gens) {
                // A point off both generators tells the side each one grows towards.
                let mid = if pts.len() == 2 {
                    pts[0].lerp(pts[1], 0.5)
                } else {
                    pts[pts.len() / 2]
                };
                let [Some(a), Some(b)] = st.gens.map(|g| self.offset_gen(g, mid)) else {
                    return Vec::new();
                };
                // Two features with a common end whose own bisector has constant
                // clearance (two arcs of one circle, two collinear segments) meet along
                // the normal at that end: the bisector of the end and either feature.
                let joint = || {
                    let end = self.common_end(st.gens[0], st.gens[1])?;
                    let end = OffsetGen::point(self.points[end as usize]);
                    bisector_form::pieces(end, a, &pts, tol)
                };
                match bisector_form::pieces(a, b, &pts, tol).or_else(joint) {
                    Some(p) => out.extend(p),
                    None => return Vec::new(),
                }
            }
        }
        out
    }

    /// `pts` cut where they cross the supporting line of a segment among `gens`, the
    /// crossing point ending one run and starting the next. A bisector crosses that
    /// line only through the segment's end (where the clearance is 0), as along the
    /// common normal at a nearly straight joint; on each side the line is grown
    /// towards that side, so one offset form cannot hold both.
    fn sides(&self, pts: &[Point], gens: [Gen; 2]) -> Vec<Vec<Point>> {
        let lines: Vec<[Point; 2]> = gens
            .iter()
            .filter_map(|&g| match g {
                Gen::Segment(s) => Some(self.segments[s as usize].map(|p| self.points[p as usize])),
                _ => None,
            })
            .collect();
        let side = |x: Point| {
            lines
                .iter()
                .map(|&[a, b]| (b - a).cross(x - a))
                .collect::<Vec<_>>()
        };
        let mut runs = Vec::new();
        let mut run = vec![pts[0]];
        let mut prev = side(pts[0]);
        // the last side not on the line, per line (a point may lie on it exactly)
        let mut was = prev.clone();
        for &x in &pts[1..] {
            let now = side(x);
            // the first line the step leaves for its other side, at its fraction of
            // the step (0: from a point on the line)
            let cut = (0..lines.len())
                .filter(|&i| was[i] * now[i] < 0.0)
                .map(|i| prev[i] / (prev[i] - now[i]))
                .min_by(f64::total_cmp);
            if let Some(f) = cut {
                let at = run[run.len() - 1].lerp(x, f);
                if f > 0.0 {
                    run.push(at);
                }
                runs.push(std::mem::replace(&mut run, vec![at]));
            }
            run.push(x);
            for i in 0..lines.len() {
                if now[i] != 0.0 {
                    was[i] = now[i];
                }
            }
            prev = now;
        }
        runs.push(run);
        runs
    }

    /// The point generator that ends both `a` and `b` (segments or arcs), if any.
    fn common_end(&self, a: Gen, b: Gen) -> Option<u32> {
        let ends = |g: Gen| match g {
            Gen::Segment(s) => Some(self.segments[s as usize]),
            Gen::Arc(a) => Some(self.arcs[a as usize].ends),
            Gen::Point(_) => None,
        };
        let (ea, eb) = (ends(a)?, ends(b)?);
        ea.into_iter().find(|p| eb.contains(p))
    }

    /// Whether an edge between generators `a` and `b` is drawn in `mode`: they have
    /// different labels (of different sites in `voronoi` mode), and in the other modes
    /// it is not a zone boundary between a segment or an arc and one of its ends. In
    /// `voronoi` mode such a boundary is drawn when another site names the end (they
    /// share it): it bounds that site's share of the end's region, where the distances
    /// to both sites tie, and without it their cells would run together.
    fn shown(&self, a: Gen, b: Gen, mode: Mode) -> bool {
        match mode {
            Mode::Voronoi => self.site(a) != self.site(b),
            _ => self.label(a, mode) != self.label(b, mode) && !self.is_separator(a, b),
        }
    }

    /// The site that names generator `g` (a compact table: this is asked per edge).
    fn site(&self, g: Gen) -> u32 {
        match g {
            Gen::Point(p) => self.point_site[p as usize],
            Gen::Segment(s) => self.segment_site[s as usize],
            Gen::Arc(a) => self.arc_owner[a as usize] as u32,
        }
    }

    /// Whether `a` and `b` are a segment and one of its own ends.
    fn is_separator(&self, a: Gen, b: Gen) -> bool {
        match (a, b) {
            (Gen::Point(p), Gen::Segment(s)) | (Gen::Segment(s), Gen::Point(p)) => {
                self.segments[s as usize].contains(&p)
            }
            (Gen::Point(p), Gen::Arc(a)) | (Gen::Arc(a), Gen::Point(p)) => {
                self.arcs[a as usize].ends.contains(&p)
            }
            _ => false,
        }
    }

    /// Even-odd inside test against all polygon rings (boundary excluded).
    fn inside_polygons(&self, q: Point) -> bool {
        let index = self.ring_crossings.get_or_init(|| {
            RayCrossings::new(
                self.rings
                    .iter()
                    .flat_map(|r| (0..r.len()).map(move |k| (r[k], r[(k + 1) % r.len()])))
                    .collect(),
            )
        });
        index.odd(q)
    }

    /// Whether `q` lies in the `medial_axis` region: the even-odd interior of the
    /// polygons' rings and of the loops of open sites together.
    fn inside_region(&self, q: Point) -> bool {
        let loop_segments = self.loop_crossings.get_or_init(|| {
            RayCrossings::new(
                self.loop_segments
                    .iter()
                    .map(|&k| {
                        let [a, b] = self.segments[k as usize].map(|p| self.points[p as usize]);
                        (a, b)
                    })
                    .collect(),
            )
        });
        let arc_crosses = |&k: &u32| {
            let arc = &self.arcs[k as usize];
            let ends = arc.ends.map(|p| self.points[p as usize]);
            ray_crosses_odd(arc.c, arc.r, arc.start, arc.span, ends, q)
        };
        let arcs = self.loop_arcs.iter().filter(|k| arc_crosses(k)).count();
        self.inside_polygons(q) ^ loop_segments.odd(q) ^ (arcs % 2 == 1)
    }
}

/// The label of a point owned by `(site, part)`: in `complex` and `medial_axis` modes a
/// corner is a corner feature and a cut inside an edge is that edge (the point lies on
/// it), and a point site stays its site.
fn owner_label((site, part): Owner, mode: Mode) -> Generator {
    let feature = |feature, index| Generator::Feature {
        site,
        feature,
        index,
    };
    match (mode, part) {
        (Mode::Voronoi, _) | (_, Part::Point) => Generator::Site(site),
        (_, Part::Corner(k)) => feature(FeatureKind::Corner, k),
        (_, Part::Inside(k)) => feature(FeatureKind::Edge, k),
    }
}

/// Points within `tol` of each other, by the shared sparse grid of cell `tol`.
struct Snap(SparseGrid<u32>);

impl Snap {
    fn new(tol: f64) -> Snap {
        Snap(SparseGrid::new(tol))
    }

    fn insert_all(&mut self, points: &[Point]) {
        for (id, &p) in points.iter().enumerate() {
            self.insert(p, id as u32);
        }
    }

    fn insert(&mut self, p: Point, id: u32) {
        self.0.insert(p, id);
    }

    /// The nearest point within `tol` of `p` (the first found among equals).
    fn find(&self, p: Point) -> Option<u32> {
        let mut best: Option<(f64, u32)> = None;
        for &(q, id) in self.0.near(p) {
            let d = q.dist(p);
            if best.is_none_or(|(b, _)| d < b) {
                best = Some((d, id));
            }
        }
        best.map(|(_, id)| id)
    }
}

/// Cuts the segments of `g` where they cross, overlap or touch inside (`split.rs`),
/// returning how many crossing points, cuts at input points and merged pieces that
/// took; or, with `strict` and in `medial_axis` mode (where the regions that crossing
/// sites bound are not defined), refuses the first such contact, naming its sites.
/// (Polygons whose insides overlap, crossing ones among them, are refused by the
/// [`Scene`].)
fn cut_or_refuse(
    g: &mut Generators,
    scene: &Scene,
    strict: bool,
    near: f64,
) -> Result<Option<[usize; 3]>, Error> {
    let medial = scene.mode() == Mode::MedialAxis;
    if strict || medial {
        let why = if strict {
            " (strict: such input is refused, not split)"
        } else {
            " (in mode 'medial_axis' segments are not split there: the regions that \
             crossing or overlapping sites bound are not defined; use mode 'voronoi' or \
             'complex')"
        };
        return match find_conflict(&g.points, &g.segments, &g.lonely, near) {
            Some(c) => Err(conflict_error(g, c, why)),
            None => Ok(None),
        };
    }
    let cut = split_segments(&g.points, &g.segments, &g.lonely, near, 0.25 * near)
        .map_err(|c| conflict_error(g, c, ""))?;
    let counts = [cut.crossings, cut.touches, cut.merged];
    g.apply_split(cut);
    Ok(Some(counts))
}

fn arc_conflict_error(g: &Generators, c: ArcConflict) -> Error {
    let (a, b, what) = match c {
        ArcConflict::Segment(i, j) => (
            g.arc_owner[i],
            g.segment_owner[j].0,
            "an arc crosses or touches a segment away from a shared endpoint",
        ),
        ArcConflict::Arc(i, j) => (
            g.arc_owner[i],
            g.arc_owner[j],
            "arcs cross, touch or overlap away from a shared endpoint",
        ),
        ArcConflict::Point(i, p) => (g.arc_owner[i], g.point_owner[p].0, "a point lies on an arc"),
    };
    Error::Conflict {
        site: a.min(b),
        other: a.max(b),
        message: what.to_string(),
    }
}

/// The refusal of a cusp: `features` leave point generator `p` in one direction.
fn cusp_error(g: &Generators, p: u32, features: [Gen; 2]) -> Error {
    let [a, b] = features.map(|f| match f {
        Gen::Segment(k) => g.segment_owner[k as usize].0,
        Gen::Arc(k) => g.arc_owner[k as usize],
        Gen::Point(k) => g.point_owner[k as usize].0,
    });
    let at = g.points[p as usize];
    let message = format!(
        "a cusp at ({:?}, {:?}): two edges leave it in the same direction (within 1e-7 \
         rad), which the incremental engine does not resolve yet",
        at.x, at.y
    );
    Error::Conflict {
        site: a.min(b),
        other: a.max(b),
        message,
    }
}

/// The refusal of conflict `c`, its message followed by `why` (why it was not cut).
fn conflict_error(g: &Generators, c: Conflict, why: &str) -> Error {
    let seg_site = |s: usize| g.segment_owner[s].0;
    let (a, b, what) = match c {
        Conflict::Cross(i, j) => (seg_site(i), seg_site(j), "segments cross"),
        Conflict::Overlap(i, j) => (seg_site(i), seg_site(j), "segments overlap"),
        Conflict::Touch(i, j) => (
            seg_site(i),
            seg_site(j),
            "an endpoint touches the inside of another segment (split it there)",
        ),
        Conflict::PointOn(i, p) => (
            seg_site(i),
            g.point_owner[p].0,
            "a point lies inside a segment",
        ),
        Conflict::NearlyOn(i, j, p) => (
            seg_site(i),
            j.map_or(g.point_owner[p].0, seg_site),
            "an end or a point lies within 4e-12 of the domain's size of a segment's inside \
             without touching it exactly, closer than the segment engine resolves: make it \
             touch exactly (split the segment there) or move it apart",
        ),
    };
    let message = if a == b {
        format!("{what} within site {a}{why}")
    } else {
        format!("{what}{why}")
    };
    Error::Conflict {
        site: a.min(b),
        other: a.max(b),
        message,
    }
}

/// The diagram of a scene of Euclidean points, segments, arcs, polylines and polygons;
/// with `options.bisectors`, every edge also carries its exact bisector in
/// offset-parameter form ([`Edge::bisector`]). Segments and chain edges that cross,
/// overlap or touch inside are cut into pieces first (`split.rs`; counted in `stats`),
/// except with `options.strict` and in `medial_axis` mode, where they are refused.
/// `watch` stops the construction early; the polylines drawn hold at most the points
/// `limits` allow ([`Error::Budget`] beyond).
pub fn scene_voronoi(
    scene: &Scene,
    options: &IncrementalOptions,
    limits: &Limits,
    watch: &Watch,
) -> Result<VoronoiComplex, Error> {
    if let Some(s) = scene.unit_scale() {
        let mut c = scene_voronoi(&scene.scaled(s), options, limits, watch)?;
        c.scale(1.0 / s);
        return Ok(c);
    }
    let mut phases = Phases::default();
    let mut g = Generators::of(scene);
    let near = NEAR_TOUCH * scene.domain().longest_side();
    if !g.segments.is_empty() || !g.arcs.is_empty() {
        check_sites_beside_tolerance(g.points.iter().copied(), &scene.domain())?;
    }
    // (no cuts in `medial_axis` mode: its loops are those of the input)
    let cuts = cut_or_refuse(&mut g, scene, options.strict, near)?;
    g.finish(scene);
    let bounds_nothing = g.rings.is_empty() && g.loop_segments.is_empty() && g.loop_arcs.is_empty();
    if scene.mode() == Mode::MedialAxis && bounds_nothing {
        return Err(Error::scene(
            "mode",
            "'medial_axis' keeps the diagram inside the regions that closed sites bound, and \
             no polygon is given and no chain of segments, polylines and arcs closes up (their \
             ends must meet exactly): the medial axis is empty; use mode 'voronoi' or 'complex'",
        ));
    }
    let scale = scene.domain().longest_side();
    if let Some(c) = find_arc_conflict(&g.points, &g.segments, &g.arcs, &g.lonely, scale) {
        return Err(arc_conflict_error(&g, c));
    }
    if let Some((p, f1, f2)) = joints::find_cusp(&g.points, &g.segments, &g.arcs) {
        return Err(cusp_error(&g, p, [f1, f2]));
    }
    phases.end("input");
    let budget = Budget::new(limits, scene.sites().len(), watch);
    let mut diagram = SegmentDiagram::new(&g.points, &g.segments, &g.arcs, scene.domain(), budget)?;
    if let Some(first) = g.first_crossing_point {
        diagram.snap_vertices_to_points(first, 0.25 * near);
    }
    phases.end("construction");
    let mut complex = assemble(&g, scene, &diagram, options.bisectors, &mut phases)?;
    diagram.budget.check(scene.epsilon())?;
    phases.end("assembly");
    if scene.mode() == Mode::Voronoi {
        complex.cells = crate::complex::cells::site_cells(&complex, scene);
        phases.end("cells");
    }
    complex.stats.insert(
        "topology_overrides".into(),
        serde_json::json!(diagram.overrides),
    );
    if let Some([crossings, touches, merged]) = cuts.filter(|c| c.iter().any(|&n| n > 0)) {
        for (key, n) in [
            ("split_crossings", crossings),
            ("split_touches", touches),
            ("merged_duplicates", merged),
        ] {
            complex.stats.insert(key.into(), serde_json::json!(n));
        }
    }
    phases.record(&mut complex.stats);
    Ok(complex)
}
