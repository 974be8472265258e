//! The fields of a scene in `complex` and `medial_axis` modes, where a curve's
//! features are the generators and the diagram includes a curve's ridges (two nearest
//! points on one generator). The subdivision engine only separates fields, so each
//! curve is cut into pieces with no ridge of their own, and the diagram of the pieces
//! is cut back afterwards (`subdivision::featured`): an arc whose curvature is
//! monotone and whose tangent turns by less than half a turn has nested osculating
//! circles (Tait–Kneser; GTT13), so no disc touches it twice from one side.
//!
//! * **Algebraic curves** (`medial_axis` mode): arcs between the curve's vertices
//!   ([`algebraic::medial`]); the regions they bound by the sign of `f`.
//! * **Free-form curves**: the spans and corners of the free-form engine
//!   ([`crate::freeform::pieces`]: cut at tangent discontinuities and curvature
//!   extrema). Spans of one piece are joined into *runs* while `dκ/dt` keeps its sign
//!   and the control polygons' directions stay within half a turn; each run is a
//!   [`FreeformField`]. Each corner is a point field, placed before the runs: in the
//!   wedge of its normal cone both runs that end there are exactly as far as the corner,
//!   and they give way to it there ([`FreeformField::only_ends_at`]). Which side of a
//!   curve belongs to the diagram is the free-form engine's orientation constraint
//!   (HREK07 eqs. 8–13), read at a point's nearest point on a run.
//! * **Other sites** keep their whole field.
//!
//! Where two pieces meet smoothly their [`ZoneEnd`] says where their edge is a zone
//! boundary; a corner and the runs ending at it are *zone neighbours*, whose edges are
//! all zone boundaries.

use super::algebraic::{self, medial::Region};
use super::zone::ZoneEnd;
use super::{EuclideanPoint, FieldOptions, FreeformField, SiteField};
use crate::complex::{FeatureKind, Generator};
use crate::error::Error;
use crate::freeform::pieces::{self, curvature_trend, Side, Span};
use crate::geom::bezier::RationalBezier;
use crate::geom::{Aabb, Point};
use crate::scene::{Mode, Scene, SiteKind};
use std::ops::Range;

/// The widest spread of the control polygons' directions along one run (which holds
/// the tangent's, Farin02): within half a turn, with a margin.
const MAX_RUN_TURN: f64 = 0.9 * std::f64::consts::PI;

/// The fields of a scene's pieces, with what the diagram of the pieces needs to become
/// the scene's (see the module docs).
pub struct FeatureFields {
    /// The fields.
    pub fields: Vec<SiteField>,
    /// The generator each field stands for.
    pub generators: Vec<Generator>,
    /// The zone boundaries at the ends of each field's piece (none for a whole site).
    pub ends: Vec<Vec<ZoneEnd>>,
    /// For each field, the fields whose edges with it are zone boundaries.
    pub zone_neighbours: Vec<Vec<usize>>,
    /// Where each field's edges belong to the diagram.
    pub keep: Vec<Keep>,
    /// The regions the algebraic curves bound.
    pub regions: Vec<Region>,
    /// In `medial_axis` mode with free-form curves (then the only sites), a box holding
    /// every curve, and so the region they bound.
    pub region_box: Option<Aabb>,
}

/// Where the points of a field's edges belong to the diagram.
pub enum Keep {
    /// Everywhere.
    Everywhere,
    /// Inside an odd number of the algebraic curves' regions.
    InRegions,
    /// On the side of a free-form run where the diagram lies, read at the point's
    /// nearest point; where that is the run's end at a corner (`corners`, at the start
    /// and the end: whether the corner is active), where the corner says.
    Side {
        side: Side,
        corners: [Option<bool>; 2],
    },
    /// A corner: where it is active (its normal cone reaches the diagram's side).
    Corner { active: bool },
}

impl FeatureFields {
    /// The fields of `scene` (mode `complex` or `medial_axis`).
    pub fn for_scene(scene: &Scene, options: &FieldOptions) -> Result<FeatureFields, Error> {
        let mut out = FeatureFields {
            fields: Vec::new(),
            generators: Vec::new(),
            ends: Vec::new(),
            zone_neighbours: Vec::new(),
            keep: Vec::new(),
            regions: Vec::new(),
            region_box: None,
        };
        let medial = scene.mode() == Mode::MedialAxis;
        let freeform = scene.sites().iter().position(|s| is_freeform(&s.kind));
        if let Some(curve) = freeform {
            check_mixed(scene, curve)?;
            out.add_freeform(scene)?;
        }
        super::refuse_whole_linear_sites(scene)?;
        for (i, s) in scene.sites().iter().enumerate() {
            match &s.kind {
                k if is_freeform(k) => {}
                SiteKind::Algebraic { equation, clip } if medial => {
                    let clip = clip.unwrap_or(scene.domain());
                    let pieces =
                        algebraic::medial::pieces(i, equation.poly(), clip, scene.epsilon())?;
                    for (field, ends) in pieces.fields.into_iter().zip(pieces.ends) {
                        out.push(
                            SiteField::Algebraic(Box::new(field)),
                            piece(i, 0),
                            ends.to_vec(),
                            Keep::InRegions,
                        );
                    }
                    out.regions.push(pieces.region);
                }
                kind => {
                    let field = SiteField::from_site_at(
                        i,
                        kind,
                        &scene.domain(),
                        scene.epsilon(),
                        options,
                    )?;
                    let keep = if medial {
                        Keep::InRegions
                    } else {
                        Keep::Everywhere
                    };
                    out.push(field, Generator::Site(i), Vec::new(), keep);
                }
            }
        }
        Ok(out)
    }

    /// Whether the point `q` of an edge of field `k` lies where the diagram does;
    /// points within `slop` of a free-form curve belong to both its sides.
    pub fn keeps(&self, k: usize, q: Point, slop: f64) -> bool {
        match &self.keep[k] {
            Keep::Everywhere => true,
            Keep::InRegions => self.regions.iter().filter(|r| r.contains(q)).count() % 2 == 1,
            Keep::Corner { active } => *active,
            Keep::Side { side, corners } => {
                let SiteField::Freeform(f) = &self.fields[k] else {
                    return true;
                };
                let Some((foot, tangent, end)) = f.foot(q) else {
                    return true;
                };
                if q.dist(foot) <= slop {
                    return true;
                }
                match end.and_then(|e| corners[e]) {
                    Some(active) => active,
                    None => side.admits((q - foot).dot(tangent.perp())),
                }
            }
        }
    }

    fn push(&mut self, field: SiteField, generator: Generator, ends: Vec<ZoneEnd>, keep: Keep) {
        self.fields.push(field);
        self.generators.push(generator);
        self.ends.push(ends);
        self.zone_neighbours.push(Vec::new());
        self.keep.push(keep);
    }

    /// The corners and runs of the scene's free-form curves (see the module docs).
    fn add_freeform(&mut self, scene: &Scene) -> Result<(), Error> {
        let cut = pieces::pieces(scene);
        pieces::check_region(scene, &cut)?;
        let tol = pieces::JOIN * scene.domain().longest_side();
        if scene.mode() == Mode::MedialAxis {
            self.region_box = cut.spans.iter().map(|s| s.bbox).reduce(|a, b| a.union(&b));
        }
        let first_corner = self.fields.len();
        for c in &cut.corners {
            let corner = Generator::Feature {
                site: c.site,
                feature: FeatureKind::Corner,
                index: c.index,
            };
            let keep = Keep::Corner { active: c.active };
            self.push(
                SiteField::Euclidean(EuclideanPoint::new(c.at)),
                corner,
                Vec::new(),
                keep,
            );
        }
        let corner_at = |p: Point| {
            cut.corners
                .iter()
                .position(|c| c.at.dist(p) <= tol)
                .map(|k| first_corner + k)
        };
        let mut run_ends: Vec<(usize, [RunEnd; 2])> = Vec::new();
        for run in runs(&cut.spans, tol) {
            let spans: Vec<RationalBezier> = cut.spans[run.clone()]
                .iter()
                .map(|s| s.curve.clone())
                .collect();
            let first = &cut.spans[run.start];
            let ends = [
                RunEnd::of(&spans[0], 0.0),
                RunEnd::of(&spans[spans.len() - 1], 1.0),
            ];
            let field = FreeformField::new(first.site, spans, scene.epsilon())?;
            let k = self.fields.len();
            let corners = ends.map(|e| corner_at(e.at));
            for c in corners.iter().flatten() {
                self.zone_neighbours[*c].push(k);
            }
            let keep = Keep::Side {
                side: first.side,
                corners: corners
                    .map(|c| c.map(|c| matches!(self.keep[c], Keep::Corner { active: true }))),
            };
            self.push(
                SiteField::Freeform(Box::new(field)),
                piece(first.site, first.piece),
                Vec::new(),
                keep,
            );
            self.zone_neighbours[k].extend(corners.iter().flatten());
            run_ends.push((k, ends));
        }
        // runs that meet without a corner: the zone boundary of their smooth joint
        for (i, &(a, ends_a)) in run_ends.iter().enumerate() {
            for ea in ends_a {
                if corner_at(ea.at).is_some() {
                    continue;
                }
                for &(b, ends_b) in &run_ends[i + 1..] {
                    for eb in ends_b.iter().filter(|eb| eb.at.dist(ea.at) <= tol) {
                        // the other run's curvature, seen along this run's tangent
                        let kb = if eb.tangent.dot(ea.tangent) >= 0.0 {
                            eb.curvature
                        } else {
                            -eb.curvature
                        };
                        let zone = ZoneEnd::from_curvatures(ea.at, ea.tangent, &[ea.curvature, kb]);
                        self.ends[a].push(zone);
                        self.ends[b].push(zone);
                    }
                }
            }
        }
        Ok(())
    }
}

/// The output generator of piece `index` of site `site`.
fn piece(site: usize, index: usize) -> Generator {
    Generator::Feature {
        site,
        feature: FeatureKind::Piece,
        index,
    }
}

fn is_freeform(kind: &SiteKind) -> bool {
    matches!(kind, SiteKind::Bezier { .. } | SiteKind::Bspline { .. })
}

/// Refuses, beside free-form curves (`curve`: the first), sites whose features this
/// engine does not name (segments, polylines, polygons, arcs) and, in `medial_axis`
/// mode, every other kind (the region is then the free-form curves').
fn check_mixed(scene: &Scene, curve: usize) -> Result<(), Error> {
    let medial = scene.mode() == Mode::MedialAxis;
    let refused = |k: &SiteKind| !is_freeform(k) && (medial || super::is_linear_or_circular(k));
    match scene.sites().iter().position(|s| refused(&s.kind)) {
        None => Ok(()),
        Some(i) => Err(Error::Unsupported {
            site: i,
            kind: scene.sites()[i].kind.name().to_string(),
            message: format!(
                "the subdivision engine computes free-form curves (site {curve}) in mode '{}' \
                 only beside {}: use --engine freeform for curves alone",
                scene.mode().name(),
                if medial {
                    "other free-form curves"
                } else {
                    "points, circles, ellipses, fields and algebraic curves"
                }
            ),
        }),
    }
}

/// An end of a run: the point, the unit tangent along the run and the signed curvature
/// (positive: bending left).
#[derive(Clone, Copy)]
struct RunEnd {
    at: Point,
    tangent: Point,
    curvature: f64,
}

impl RunEnd {
    fn of(c: &RationalBezier, t: f64) -> RunEnd {
        let [_, d1, d2] = c.derivatives(t);
        let speed = d1.norm();
        let (tin, tout) = c.end_tangents();
        let along = if speed > 0.0 {
            d1
        } else if t < 0.5 {
            tin
        } else {
            tout
        };
        let curvature = if speed > 0.0 {
            d1.cross(d2) / (speed * speed * speed)
        } else {
            0.0
        };
        RunEnd {
            at: c.eval(t),
            tangent: along * (1.0 / along.norm()),
            curvature: if curvature.is_finite() {
                curvature
            } else {
                0.0
            },
        }
    }
}

/// The runs of `spans` (see the module docs): consecutive spans of one site and piece
/// that meet (within `tol`), whose control polygons' directions spread by at most
/// [`MAX_RUN_TURN`], and where `dκ/dt` keeps its sign or the diagram lies on the run's
/// convex side only (its curvature keeps a sign that bends it away from that side: no
/// disc there touches it twice, whatever its curvature does).
fn runs(spans: &[Span], tol: f64) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut run = Run::default();
    for (k, s) in spans.iter().enumerate() {
        let next = run.clone().extended(s);
        let joins = k > start && {
            let prev = &spans[k - 1];
            prev.site == s.site
                && prev.piece == s.piece
                && prev.curve.eval(1.0).dist(s.curve.eval(0.0)) <= tol
                && next.turn.spread() <= MAX_RUN_TURN
                && (next.monotone || next.convex_towards(s.side))
        };
        if k > start && !joins {
            out.push(start..k);
            start = k;
            run = Run::default().extended(s);
        } else {
            run = next;
        }
    }
    if start < spans.len() {
        out.push(start..spans.len());
    }
    out
}

/// What [`runs`] knows of a run of spans.
#[derive(Clone)]
struct Run {
    /// The sign of `dκ/dt` so far (0: none yet) and whether it kept it.
    trend: f64,
    monotone: bool,
    /// The sign of the curvature along the whole run (0: lines only), if it keeps one.
    bend: Option<f64>,
    turn: Turn,
}

impl Default for Run {
    fn default() -> Self {
        Run {
            trend: 0.0,
            monotone: true,
            bend: Some(0.0),
            turn: Turn::default(),
        }
    }
}

impl Run {
    fn extended(mut self, s: &Span) -> Run {
        let trend = curvature_trend(&s.curve).map_or(0.0, |g| g.eval(0.5).signum());
        self.monotone &= trend * self.trend >= 0.0;
        if self.trend == 0.0 {
            self.trend = trend;
        }
        self.bend = match (self.bend, pieces::bend(&s.curve)) {
            (Some(a), Some(b)) if a * b >= 0.0 => Some(if a != 0.0 { a } else { b }),
            _ => None,
        };
        self.turn = self.turn.extended(&s.curve);
        self
    }

    /// Whether the diagram lies on the run's convex side only.
    fn convex_towards(&self, side: Side) -> bool {
        match (side, self.bend) {
            (Side::Right, Some(b)) => b >= 0.0,
            (Side::Left, Some(b)) => b <= 0.0,
            _ => false,
        }
    }
}

/// The directions of a chain of control polygons' edges, unwrapped: the last one and
/// the least and greatest angle turned from the first.
#[derive(Clone, Default)]
struct Turn {
    last: Option<Point>,
    angle: f64,
    least: f64,
    most: f64,
}

impl Turn {
    fn extended(mut self, c: &RationalBezier) -> Turn {
        for w in c.control_points().windows(2) {
            let d = w[1] - w[0];
            if d.norm() == 0.0 {
                continue;
            }
            if let Some(last) = self.last {
                self.angle += last.cross(d).atan2(last.dot(d));
                self.least = self.least.min(self.angle);
                self.most = self.most.max(self.angle);
            }
            self.last = Some(d);
        }
        self
    }

    fn spread(&self) -> f64 {
        self.most - self.least
    }
}
