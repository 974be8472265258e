//! Free-form sites as rational Bézier spans and corners (HREK07 §7): a B-spline is cut
//! into Bézier spans by knot insertion (Boehm's algorithm on homogeneous control points,
//! every knot of the curve's range raised to multiplicity `degree`, Farin02 ch. 10); the
//! spans are grouped into C1 pieces, split where the tangent direction jumps (corners).
//! Open curves get a corner at each end, except where two open sites join end to end:
//! a [`Joint`] where the tangent does not turn, and where it does one corner (in
//! `complex` and `medial_axis` modes; each site's own in `voronoi` mode); in those two
//! modes chains of joined sites that close up bound a region.

use crate::complex::{FeatureKind, Generator};
use crate::geom::bezier::RationalBezier;
use crate::geom::bspline::ends_meet;
use crate::geom::ring::{even_odd_contains, signed_area};
use crate::geom::{Aabb, Point};
use crate::num::bernstein::Bernstein1;
use crate::num::roots::{isolate, refine};
use crate::scene::{Mode, Scene, SiteKind};

/// Angle (radians) above which the tangent direction at a joint counts as a jump.
const CORNER_ANGLE: f64 = 1e-6;

/// Which side of a span (relative to its direction of parameterization) bisector points
/// may lie on: the orientation constraint (HREK07 eqs. 8–13).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Left of the tangent (`⟨P − C, N_L⟩ > 0`, `N_L = (−y', x')`).
    Left,
    /// Right of the tangent.
    Right,
    /// Either side (open curves).
    Both,
}

impl Side {
    /// True when the signed offset `s = ⟨P − C, N_L⟩` is on this side.
    pub fn admits(self, s: f64) -> bool {
        match self {
            Side::Left => s > 0.0,
            Side::Right => s < 0.0,
            Side::Both => true,
        }
    }
}

/// A C1 rational Bézier span of a site.
#[derive(Clone, Debug)]
pub struct Span {
    /// The span, parameter `t ∈ [0, 1]`.
    pub curve: RationalBezier,
    /// The site it belongs to.
    pub site: usize,
    /// Its C1 piece within the site (the format's `piece` feature index).
    pub piece: usize,
    /// The side where the diagram lies.
    pub side: Side,
    /// A box holding the span.
    pub bbox: Aabb,
}

/// A tangent discontinuity or an open end of a curve.
#[derive(Clone, Debug)]
pub struct Corner {
    /// Where it is.
    pub at: Point,
    /// The site it belongs to.
    pub site: usize,
    /// Its corner index within the site.
    pub index: usize,
    /// Unit tangent of the curve arriving at the corner (zero at an open start).
    pub tin: Point,
    /// Unit tangent of the curve leaving it (zero at an open end).
    pub tout: Point,
    /// The normal cone `{v : ⟨v, tin⟩ ≥ 0, ⟨v, tout⟩ ≤ 0}` of the corner reaches the
    /// side where the diagram lies (a convex corner seen from there); inactive corners
    /// are nearest to no point of that side and generate nothing.
    pub active: bool,
}

impl Corner {
    /// Whether `q` lies in each half-plane of the corner's normal cone, `⟨v, tin⟩ ≥ 0`
    /// and `⟨v, tout⟩ ≤ 0` with `v = q − at` (within `tol`); in both, the corner is the
    /// nearest point of its two spans (HREK07 §7.3, the bounding normals of a tangent
    /// discontinuity).
    pub fn halves(&self, q: Point, tol: f64) -> [bool; 2] {
        let v = q - self.at;
        [v.dot(self.tin) >= -tol, v.dot(self.tout) <= tol]
    }
}

/// A feature of the scene: a span or a corner, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Feature {
    /// `Pieces::spans[k]`.
    Span(usize),
    /// `Pieces::corners[k]`.
    Corner(usize),
}

/// Every free-form site cut into spans and corners.
#[derive(Clone, Debug, Default)]
pub struct Pieces {
    /// The spans.
    pub spans: Vec<Span>,
    /// The corners (active or not).
    pub corners: Vec<Corner>,
    /// Whether generators are features (`complex`, `medial_axis`) or whole sites.
    pub featured: bool,
    /// Where spans of two joined sites meet without a corner.
    pub joints: Vec<Joint>,
}

/// Two spans of different sites that meet end to end where the tangent turns by less
/// than the output resolves (no corner): near the common point `p` the edge of the two
/// lies along their common normal `p + s·n`, where both feet stay at `p` — a segment
/// in the plane that `F3` sees only as a corner `(t, r)` of its square.
#[derive(Clone, Copy, Debug)]
pub struct Joint {
    /// The common end point.
    pub at: Point,
    /// The two spans.
    pub spans: [usize; 2],
    /// Their parameters at `at` (0 or 1).
    pub feet: [f64; 2],
    /// The unit normal (the mean of the two) pointing to the side where the diagram
    /// lies; either way when `both`.
    pub normal: Point,
    /// The diagram lies on both sides (open chains).
    pub both: bool,
}

impl Pieces {
    /// The output generator of a feature.
    pub fn generator(&self, f: Feature) -> Generator {
        let (site, feature, index) = match f {
            Feature::Span(k) => (self.spans[k].site, FeatureKind::Piece, self.spans[k].piece),
            Feature::Corner(k) => (
                self.corners[k].site,
                FeatureKind::Corner,
                self.corners[k].index,
            ),
        };
        if self.featured {
            Generator::Feature {
                site,
                feature,
                index,
            }
        } else {
            Generator::Site(site)
        }
    }

    /// The site of a feature.
    pub fn site(&self, f: Feature) -> usize {
        match f {
            Feature::Span(k) => self.spans[k].site,
            Feature::Corner(k) => self.corners[k].site,
        }
    }
}

/// Refuses `medial_axis` mode where the curves bound no region (no curve is closed and
/// no chain closes up: every span's diagram lies on both its sides).
pub fn check_region(scene: &Scene, pieces: &Pieces) -> Result<(), crate::error::Error> {
    if scene.mode() == Mode::MedialAxis && pieces.spans.iter().all(|s| s.side == Side::Both) {
        return Err(crate::error::Error::scene(
            "mode",
            "'medial_axis' keeps the diagram inside the regions that closed curves bound, \
             and these curves bound none: no curve is closed and no chain of curves \
             joined end to end closes up",
        ));
    }
    Ok(())
}

/// The spans of one site (homogeneous Bézier control polygons) and whether it is closed,
/// or `None` when the site is not a free-form curve.
pub(crate) fn site_spans(kind: &SiteKind) -> Option<(Vec<RationalBezier>, bool)> {
    match kind {
        SiteKind::Bezier {
            control_points,
            weights,
        } => {
            let c = RationalBezier::new(control_points, weights.as_deref());
            let closed = control_points.first() == control_points.last();
            Some((vec![c], closed))
        }
        SiteKind::Bspline {
            degree,
            control_points,
            knots,
            weights,
            closed,
        } => {
            let h: Vec<[f64; 3]> = control_points
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let w = weights.as_ref().map_or(1.0, |w| w[i]);
                    [p.x * w, p.y * w, w]
                })
                .collect();
            let spans = bspline_to_bezier(*degree, &h, knots);
            let ends = spans
                .first()
                .zip(spans.last())
                .map(|(a, b)| (a.eval(0.0), b.eval(1.0)));
            // the scene's check refuses a `closed` flag on ends that do not meet
            let meets = ends.is_some_and(|(a, b)| ends_meet(a, b));
            Some((spans, *closed || meets))
        }
        _ => None,
    }
}

/// [`site_spans`] without the spans that are points next to the site's size (a
/// B-spline's repeated knots): the site's spans as the engines cut them.
pub(crate) fn solid_spans(kind: &SiteKind) -> Option<(Vec<RationalBezier>, bool)> {
    let (spans, closed) = site_spans(kind)?;
    let scale = spans
        .iter()
        .map(|c| c.control_box().longest_side())
        .fold(0.0, f64::max);
    let spans = spans
        .into_iter()
        .filter(|c| c.control_box().longest_side() > 1e-12 * scale)
        .flat_map(|c| balanced(c, 0))
        .collect();
    Some((spans, closed))
}

/// Most ratio of a span's largest weight to its smallest (see [`balanced`]).
const WEIGHT_RATIO: f64 = 16.0;

/// `c` if its weights are within [`WEIGHT_RATIO`] of each other, else its halves in
/// standard form ([`RationalBezier::standard_form`]), balanced in turn (`depth` halvings
/// so far; each about takes the square root of the ratio, and 10 bring 1e300 to 2). A
/// weight far above its neighbours gathers the parameter at one point of the curve (a
/// conic of weight 1e3 spends all but 1e-3 of it at its shoulder), and `F3`, of degree
/// 4 in the weights, loses the rest of the curve in its error bound.
fn balanced(c: RationalBezier, depth: usize) -> Vec<RationalBezier> {
    if c.weight_ratio() <= WEIGHT_RATIO || depth >= 10 {
        return vec![c];
    }
    let (l, r) = c.standard_form().split(0.5);
    let mut out = balanced(l.standard_form(), depth + 1);
    out.extend(balanced(r.standard_form(), depth + 1));
    out
}

/// Boehm knot insertion: `u` inserted once into `(knots, points)` of degree `p`, in
/// the span `knots[k] ≤ u < knots[k+1]` (`knots[k] < u ≤ knots[k+1]` with `left`, for
/// the end of the curve's range).
fn insert_knot(p: usize, knots: &mut Vec<f64>, points: &mut Vec<[f64; 3]>, u: f64, left: bool) {
    let Some(k) = (0..knots.len() - 1).rev().find(|&k| {
        if left {
            knots[k] < u && u <= knots[k + 1]
        } else {
            knots[k] <= u && u < knots[k + 1]
        }
    }) else {
        return;
    };
    if k < p || k >= points.len() {
        return;
    }
    let mut q = Vec::with_capacity(points.len() + 1);
    q.extend_from_slice(&points[..=k - p]);
    for i in k - p + 1..=k {
        let a = (u - knots[i]) / (knots[i + p] - knots[i]);
        q.push(std::array::from_fn(|c| {
            (1.0 - a) * points[i - 1][c] + a * points[i][c]
        }));
    }
    q.extend_from_slice(&points[k..]);
    *points = q;
    knots.insert(k + 1, u);
}

/// The Bézier spans of a B-spline of degree `p` over its range `[knots[p], knots[n]]`.
pub fn bspline_to_bezier(p: usize, points: &[[f64; 3]], knots: &[f64]) -> Vec<RationalBezier> {
    let n = points.len();
    let (a, b) = (knots[p], knots[n]);
    let mut values: Vec<f64> = knots
        .iter()
        .copied()
        .filter(|&u| a <= u && u <= b)
        .collect();
    values.dedup();
    let mut kn = knots.to_vec();
    let mut pts = points.to_vec();
    for &u in &values {
        let mult = kn.iter().filter(|&&x| x == u).count();
        // the end of the range is raised to multiplicity p as well, from its left
        for _ in mult..p {
            insert_knot(p, &mut kn, &mut pts, u, u == b);
        }
    }
    let mut out = Vec::new();
    for i in p..kn.len().saturating_sub(p + 1) {
        if kn[i] < kn[i + 1] && kn[i] >= a && kn[i + 1] <= b && i < pts.len() {
            out.push(RationalBezier::from_homogeneous(pts[i - p..=i].to_vec()));
        }
    }
    out
}

/// The unit vector along `v` (zero stays zero).
fn unit(v: Point) -> Point {
    let n = v.norm();
    if n > 0.0 {
        v * (1.0 / n)
    } else {
        v
    }
}

/// Ends of two open sites closer than this (relative to the domain's size) are joined.
pub const JOIN: f64 = 1e-12;

/// An end of an open site (`end` 0: its start, 1: its end) joined to an end of another.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Link {
    /// The other site.
    pub site: usize,
    /// Its end there.
    pub end: usize,
}

/// A site's spans: whether it is closed, its end points and unit end tangents.
struct SiteSpans {
    spans: Vec<RationalBezier>,
    closed: bool,
    at: [Point; 2],
    tangent: [Point; 2],
}

/// The links of open sites that meet end to end (each end meets exactly one end of
/// another site within `tol`): per site, at its start and its end.
fn links(sites: &[Option<SiteSpans>], tol: f64) -> Vec<[Option<Link>; 2]> {
    let ends: Vec<(usize, usize, Point)> = sites
        .iter()
        .enumerate()
        .filter_map(|(i, s)| s.as_ref().filter(|s| !s.closed).map(|s| (i, s)))
        .flat_map(|(i, s)| [(i, 0, s.at[0]), (i, 1, s.at[1])])
        .collect();
    link_ends(&ends, sites.len(), tol)
}

/// The links among the `ends` `(site, end, point)` of open sites (of `count` sites in
/// all): an end is joined where it meets exactly one end of another site within `tol`.
pub(crate) fn link_ends(
    ends: &[(usize, usize, Point)],
    count: usize,
    tol: f64,
) -> Vec<[Option<Link>; 2]> {
    let mut out = vec![[None, None]; count];
    for &(i, end, p) in ends {
        let mut meets = ends
            .iter()
            .filter(|&&(j, e, q)| (j, e) != (i, end) && q.dist(p) <= tol);
        if let (Some(&(j, e, _)), None) = (meets.next(), meets.next()) {
            if j != i {
                out[i][end] = Some(Link { site: j, end: e });
            }
        }
    }
    out
}

/// The side of each site where the diagram lies. The closed curves and the chains of
/// joined open sites that close up are loops, and their even-odd inside is the region
/// (a loop inside an odd number of others is a hole's boundary): in `medial_axis` mode
/// the diagram lies on each loop's side towards the region, in the other modes on its
/// side away from it, on the side of each site's own direction; `Both` for the rest,
/// and for the chains in `complex` mode (only a closed curve is a solid there).
fn sides(sites: &[Option<SiteSpans>], links: &[[Option<Link>; 2]], mode: Mode) -> Vec<Side> {
    let ring_of = |s: &SiteSpans, reversed: bool| {
        let mut v: Vec<Point> = s
            .spans
            .iter()
            .flat_map(|c| {
                let mut v = c.sample(16);
                v.pop();
                v
            })
            .collect();
        if reversed {
            v.reverse();
        }
        v
    };
    // each loop: its sites (with whether each runs against the loop) and its ring
    struct Loop {
        members: Vec<(usize, bool)>,
        ring: Vec<Point>,
    }
    let mut loops: Vec<Loop> = Vec::new();
    let mut seen = vec![false; sites.len()];
    for (i, s) in sites.iter().enumerate() {
        let Some(s) = s else { continue };
        if s.closed {
            loops.push(Loop {
                members: vec![(i, false)],
                ring: ring_of(s, false),
            });
            continue;
        }
        if seen[i] {
            continue;
        }
        // walk the chain from site i in its direction: (site, reversed)
        let mut chain = vec![(i, false)];
        let mut closed = false;
        while let Some(j) = {
            let &(k, reversed) = chain.last().unwrap();
            links[k][usize::from(!reversed)]
        } {
            if j.site == i {
                closed = true;
                break;
            }
            if chain.len() > sites.len() {
                break;
            }
            // entered at its start: along its direction
            chain.push((j.site, j.end == 1));
        }
        for &(k, _) in &chain {
            seen[k] = true;
        }
        if closed {
            let ring: Vec<Point> = chain
                .iter()
                .flat_map(|&(k, reversed)| ring_of(sites[k].as_ref().unwrap(), reversed))
                .collect();
            loops.push(Loop {
                members: chain,
                ring,
            });
        }
    }
    let mut out = vec![Side::Both; sites.len()];
    for (k, Loop { members, ring }) in loops.iter().enumerate() {
        let depth = loops
            .iter()
            .enumerate()
            .filter(|&(j, other)| j != k && even_odd_contains(&other.ring, ring[0]))
            .count();
        // the loop's inside is the region's near it when it is not a hole
        let inside_wanted = (depth % 2 == 0) == (mode == Mode::MedialAxis);
        let side = if (signed_area(ring) > 0.0) == inside_wanted {
            Side::Left
        } else {
            Side::Right
        };
        for &(site, reversed) in members {
            // in `complex` mode a chain of open sites bounds no solid: the diagram lies
            // on both of its sides (a closed curve is a solid, as a polygon is)
            let chain = !sites[site].as_ref().is_some_and(|s| s.closed);
            if chain && mode == Mode::Complex {
                continue;
            }
            out[site] = match (side, reversed) {
                (Side::Left, true) => Side::Right,
                (Side::Right, true) => Side::Left,
                (side, _) => side,
            };
        }
    }
    out
}

/// True when the unit tangents `a` (arriving) and `b` (leaving) turn by more than
/// `angle` (or one is missing).
fn turns(a: Point, b: Point, angle: f64) -> bool {
    a.dot(b) < angle.cos() || a.norm() == 0.0 || b.norm() == 0.0
}

/// Cuts every free-form site of the scene into spans and corners. Sites that are not
/// free-form curves are skipped (the caller refuses them). In `complex` and
/// `medial_axis` modes, open sites joined end to end are one curve: a joint is a corner
/// (one, with the two sites' tangents) only where the tangent turns, and a chain that
/// closes up bounds a region like a closed curve. In `voronoi` mode, sites joined end
/// to end without a turn meet at a joint, whose normal is their edge, and keep their
/// own corners where the tangent turns.
pub fn pieces(scene: &Scene) -> Pieces {
    let mode = scene.mode();
    let mut out = Pieces {
        featured: mode != Mode::Voronoi,
        ..Pieces::default()
    };
    let mut sites: Vec<Option<SiteSpans>> = scene
        .sites()
        .iter()
        .map(|s| {
            let (spans, closed) = solid_spans(&s.kind)?;
            // in complex and medial_axis modes a curve meets itself: cut the spans at
            // their curvature extrema, so that no span has a bisector with itself
            let spans: Vec<RationalBezier> = if mode == Mode::Voronoi {
                spans
            } else {
                spans.iter().flat_map(split_at_vertices).collect()
            };
            let (first, last) = (spans.first()?, spans.last()?);
            Some(SiteSpans {
                at: [first.eval(0.0), last.eval(1.0)],
                tangent: [unit(first.end_tangents().0), unit(last.end_tangents().1)],
                spans,
                closed,
            })
        })
        .collect();
    let mut links = links(&sites, JOIN * scene.domain().longest_side());
    if out.featured {
        grade(&mut sites, &links);
    }
    // a turn at a joint below `2 chord / diagonal` moves the edge along the mean normal
    // by less than `chord` anywhere in the domain: no corner there
    let diagonal = scene.domain().width().hypot(scene.domain().height());
    let joint_turn = (2.0 * super::chord(scene) / diagonal).max(CORNER_ANGLE);
    // a site's tangent at end `end` of site `l.site`, in the direction of a site whose
    // end `end` is linked there (reversed when both ends are starts, or both ends)
    let linked_tangent = |links: &[[Option<Link>; 2]], site: usize, end: usize| {
        let l = links[site][end]?;
        let t = sites[l.site].as_ref()?.tangent[l.end];
        Some(if l.end == end { t * -1.0 } else { t })
    };
    if !out.featured {
        // whole sites are the generators: two sites that meet end to end without a
        // turn are split by the common normal there (a joint, as in the other modes);
        // where the tangent turns, each keeps the corner at its end
        let smooth: Vec<[bool; 2]> = (0..sites.len())
            .map(|i| {
                [0, 1].map(|end| {
                    linked_tangent(&links, i, end).is_some_and(|t| {
                        let own = sites[i].as_ref().map_or(t, |s| s.tangent[end]);
                        !turns(own, t, joint_turn)
                    })
                })
            })
            .collect();
        for (ends, smooth) in links.iter_mut().zip(smooth) {
            for (l, smooth) in ends.iter_mut().zip(smooth) {
                if !smooth {
                    *l = None;
                }
            }
        }
    }
    // loops bound regions in `complex` and `medial_axis` modes only: in `voronoi` mode
    // the diagram lies on both sides of joined open sites
    let no_links = vec![[None, None]; sites.len()];
    let mut sides = sides(&sites, if out.featured { &links } else { &no_links }, mode);
    // a closed curve that crosses or touches itself or another (a loop with a cusp, a
    // curve through another) has no outside that is one side of each of its spans: the
    // lower envelope alone trims the bisectors then (`voronoi` mode; the other modes
    // refuse such curves)
    if mode == Mode::Voronoi && sites.iter().flatten().any(|s| s.closed) && scene.curves_meet() {
        sides.fill(Side::Both);
    }
    // per site: the indices of its first and last spans in `out.spans`
    let mut end_spans: Vec<[usize; 2]> = vec![[0, 0]; sites.len()];
    for (site, s) in sites.iter().enumerate() {
        let Some(SiteSpans { spans, closed, .. }) = s else {
            continue;
        };
        let (closed, side) = (*closed, sides[site]);
        let tangents: Vec<(Point, Point)> = spans
            .iter()
            .map(|c| {
                let (a, b) = c.end_tangents();
                (unit(a), unit(b))
            })
            .collect();
        let m = spans.len();
        // breaks[k]: a corner at the start of span k
        let mut breaks: Vec<bool> = (0..m)
            .map(|k| k > 0 && turns(tangents[k - 1].1, tangents[k].0, CORNER_ANGLE))
            .collect();
        let seam = closed && turns(tangents[m - 1].1, tangents[0].0, CORNER_ANGLE);
        breaks[0] = !closed || seam;
        // the corner at an open end (0: start, 1: end): free, or where the site joins
        // another (made by the lower site, in this site's direction: the other's
        // tangent is reversed when its end of the same kind meets this one)
        let open_end = |end: usize, index: usize| -> Option<Corner> {
            let zero = Point::new(0.0, 0.0);
            let own = if end == 0 {
                tangents[0].0
            } else {
                tangents[m - 1].1
            };
            let other = match links[site][end] {
                None => zero,
                Some(l) if l.site < site => return None,
                Some(_) => {
                    let t = linked_tangent(&links, site, end).unwrap_or(zero);
                    if !turns(own, t, joint_turn) {
                        return None;
                    }
                    t
                }
            };
            let (tin, tout) = if end == 0 { (other, own) } else { (own, other) };
            let at = if end == 0 {
                spans[0].eval(0.0)
            } else {
                spans[m - 1].eval(1.0)
            };
            Some(make_corner(at, site, index, tin, tout, side))
        };
        // pieces and corners, numbered like the format: from the seam when it is a
        // corner (or the curve is open), else from the first break
        let first = if closed && !seam {
            breaks.iter().position(|&b| b).unwrap_or(0)
        } else {
            0
        };
        let mut piece = 0usize;
        let mut corner = 0usize;
        end_spans[site] = [out.spans.len(), out.spans.len() + m - 1];
        for j in 0..m {
            let k = (first + j) % m;
            if j > 0 && breaks[k] {
                piece += 1;
            }
            if k == 0 && !closed {
                out.corners.extend(open_end(0, corner));
                corner += 1;
            } else if breaks[k] {
                out.corners.push(make_corner(
                    spans[k].eval(0.0),
                    site,
                    corner,
                    tangents[(k + m - 1) % m].1,
                    tangents[k].0,
                    side,
                ));
                corner += 1;
            }
            out.spans.push(Span {
                bbox: spans[k].control_box(),
                curve: spans[k].clone(),
                site,
                piece,
                side,
            });
        }
        if !closed {
            out.corners.extend(open_end(1, corner));
        }
    }
    for (i, ends) in links.iter().enumerate() {
        for (end, l) in ends.iter().enumerate() {
            let (Some(l), Some(own), Some(other)) =
                (*l, sites[i].as_ref(), linked_tangent(&links, i, end))
            else {
                continue;
            };
            if l.site < i || turns(own.tangent[end], other, joint_turn) {
                continue;
            }
            let n = unit(own.tangent[end] + other).perp();
            out.joints.push(Joint {
                at: own.at[end],
                spans: [end_spans[i][end], end_spans[l.site][l.end]],
                feet: [end as f64, l.end as f64],
                normal: if sides[i] == Side::Right { n * -1.0 } else { n },
                both: sides[i] == Side::Both,
            });
        }
    }
    out
}

/// With `H = (X, Y, W)` the homogeneous span, `κ = det(H, H', H'') W³ / |T|³`,
/// `T = (X'W − XW', Y'W − YW')` (Farin02): the numerator `det · W³` and `|T|²`, in
/// Bernstein form (`None` for a line, whose `κ` vanishes identically).
fn curvature_parts(c: &RationalBezier) -> Option<(Bernstein1, Bernstein1)> {
    if c.degree() < 2 {
        return None;
    }
    let h = c.homogeneous();
    let coord = |k: usize| Bernstein1::exact(h.iter().map(|p| p[k]).collect());
    let (x, y, w) = (coord(0), coord(1), coord(2));
    let d = |f: &Bernstein1| f.derivative();
    let (x1, y1, w1) = (d(&x), d(&y), d(&w));
    let (x2, y2, w2) = (d(&x1), d(&y1), d(&w1));
    let det = x
        .mul(&y1.mul(&w2).sub(&w1.mul(&y2)))
        .sub(&y.mul(&x1.mul(&w2).sub(&w1.mul(&x2))))
        .add(&w.mul(&x1.mul(&y2).sub(&y1.mul(&x2))));
    let tx = x1.mul(&w).sub(&x.mul(&w1));
    let ty = y1.mul(&w).sub(&y.mul(&w1));
    Some((det.mul(&w.mul(&w).mul(&w)), tx.mul(&tx).add(&ty.mul(&ty))))
}

/// The sign of `c`'s curvature where it is the same along the whole span (`+1`:
/// bending left, `−1`: right, `0`: a line), from the Bernstein coefficients of its
/// numerator ([`curvature_parts`]); `None` where they change sign.
pub fn bend(c: &RationalBezier) -> Option<f64> {
    let Some((k, _)) = curvature_parts(c) else {
        return Some(0.0);
    };
    let range = k.range();
    if range.lo > 0.0 {
        Some(1.0)
    } else if range.hi < 0.0 {
        Some(-1.0)
    } else if range.lo == 0.0 && range.hi == 0.0 {
        Some(0.0)
    } else {
        None
    }
}

/// `dκ/dt` of `c` up to a positive factor, in Bernstein form (`None` for a line): by
/// [`curvature_parts`], `κ'` has the sign of `2 (det · W³)' |T|² − 3 det · W³ (|T|²)'`.
pub fn curvature_trend(c: &RationalBezier) -> Option<Bernstein1> {
    let (k, t2) = curvature_parts(c)?;
    let d = |f: &Bernstein1| f.derivative();
    Some(d(&k).mul(&t2).scale(2.0).sub(&k.mul(&d(&t2)).scale(3.0)))
}

/// The parameters in `(0, 1)` where the curvature of `c` has an extremum (the curve's
/// vertices): the zeros of [`curvature_trend`], isolated in Bernstein form.
pub fn curvature_extrema(c: &RationalBezier) -> Vec<f64> {
    let Some(g) = curvature_trend(c) else {
        return Vec::new();
    };
    isolate(&g, 1e-12)
        .into_iter()
        .map(|r| {
            if r.certified {
                refine(&g, r.lo, r.hi)
            } else {
                0.5 * (r.lo + r.hi)
            }
        })
        .filter(|&t| t > 1e-6 && t < 1.0 - 1e-6)
        .collect()
}

/// Most ratio of the sizes of two spans that meet end to end (see [`graded`]).
const NEIGHBOUR_RATIO: f64 = 8.0;

/// `spans` (one curve's, in order; `closed` when the last meets the first) with every
/// span halved until it is at most [`NEIGHBOUR_RATIO`] times the size of the spans it
/// meets, and of the spans of other sites joined at its ends (`outside`: their sizes).
/// Sizes below `floor` count as `floor`, which bounds the halvings.
fn graded(
    mut spans: Vec<RationalBezier>,
    closed: bool,
    outside: [Option<f64>; 2],
    floor: f64,
) -> Vec<RationalBezier> {
    loop {
        let sizes: Vec<f64> = spans.iter().map(|c| span_size(c).max(floor)).collect();
        let n = sizes.len();
        let too_long = (0..n).find(|&k| {
            let before = match k {
                0 if closed => Some(sizes[n - 1]),
                0 => outside[0],
                _ => Some(sizes[k - 1]),
            };
            let after = match k + 1 {
                m if m < n => Some(sizes[m]),
                _ if closed => Some(sizes[0]),
                _ => outside[1],
            };
            [before, after]
                .into_iter()
                .flatten()
                .any(|b| sizes[k] > NEIGHBOUR_RATIO * b.max(floor))
        });
        let Some(k) = too_long else { return spans };
        let (l, r) = spans[k].split(0.5);
        spans[k] = r;
        spans.insert(k, l);
    }
}

/// The size of a span: its control box's longest side.
fn span_size(c: &RationalBezier) -> f64 {
    c.control_box().longest_side()
}

/// Grades the spans of every site, and across the joints of sites joined end to end
/// ([`graded`]), down to 1e-6 of the curves' extent. A ridge that ends at the joint of
/// two spans (a curvature extremum, or a joint of two sites) is a zero of `F3` of
/// fourth order at a corner of their square, and `F3`'s error bound is relative to its
/// largest coefficient: beside a span a thousand times longer, the ridge's last stretch
/// sinks below it, and the trace breaks it into pieces.
fn grade(sites: &mut [Option<SiteSpans>], links: &[[Option<Link>; 2]]) {
    let extent = sites
        .iter()
        .flatten()
        .flat_map(|s| &s.spans)
        .map(|c| c.control_box())
        .reduce(|a, b| a.union(&b))
        .map_or(0.0, |b| b.longest_side());
    let floor = 1e-6 * extent;
    let end_size = |sites: &[Option<SiteSpans>], link: Option<Link>| {
        let l = link?;
        let spans = &sites[l.site].as_ref()?.spans;
        let span = if l.end == 0 {
            spans.first()
        } else {
            spans.last()
        };
        span.map(span_size)
    };
    // a halving at a joint may make the span across it too long in turn: a few rounds
    for _ in 0..16 {
        let mut changed = false;
        for i in 0..sites.len() {
            let outside = links[i].map(|l| end_size(sites, l));
            let Some(s) = sites[i].as_mut() else { continue };
            let before = s.spans.len();
            s.spans = graded(std::mem::take(&mut s.spans), s.closed, outside, floor);
            changed |= s.spans.len() != before;
        }
        if !changed {
            break;
        }
    }
}

/// `c` cut at its curvature extrema.
fn split_at_vertices(c: &RationalBezier) -> Vec<RationalBezier> {
    let mut out = Vec::new();
    let mut rest = c.clone();
    let mut done = 0.0;
    for t in curvature_extrema(c) {
        let local = (t - done) / (1.0 - done);
        if local <= 1e-6 || local >= 1.0 - 1e-6 {
            continue;
        }
        let (l, r) = rest.split(local);
        out.push(l);
        rest = r;
        done = t;
    }
    out.push(rest);
    out
}

fn make_corner(
    at: Point,
    site: usize,
    index: usize,
    tin: Point,
    tout: Point,
    side: Side,
) -> Corner {
    // the cone's middle direction tin − tout; on the allowed side iff the curve turns
    // away from it (see the module docs of `freeform`)
    let turn = tin.cross(tout);
    let active = match side {
        Side::Both => true,
        Side::Left => turn < 0.0,
        Side::Right => turn > 0.0,
    };
    Corner {
        at,
        site,
        index,
        tin,
        tout,
        active,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_cubic_bspline_spans_match_de_boor() {
        // a uniform cubic B-spline: span k's Bézier points from de Boor's formula
        let p: Vec<[f64; 3]> = [[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0], [6.0, 1.0]]
            .iter()
            .map(|q| [q[0], q[1], 1.0])
            .collect();
        let knots: Vec<f64> = (0..9).map(f64::from).collect();
        let spans = bspline_to_bezier(3, &p, &knots);
        assert_eq!(spans.len(), 2);
        // uniform cubic: the curve at knot 3 is (P0 + 4 P1 + P2) / 6
        let want = Point::new((0.0 + 4.0 + 3.0) / 6.0, (0.0 + 8.0 + 3.0) / 6.0);
        assert!(spans[0].eval(0.0).dist(want) < 1e-12);
        assert!(spans[0].eval(1.0).dist(spans[1].eval(0.0)) < 1e-12);
        let want_end = Point::new((3.0 + 16.0 + 6.0) / 6.0, (3.0 + 0.0 + 1.0) / 6.0);
        assert!(spans[1].eval(1.0).dist(want_end) < 1e-12);
        // C1 at the joint
        assert!(spans[0].derivative(1.0).dist(spans[1].derivative(0.0)) < 1e-9);
    }

    #[test]
    fn curvature_extrema_of_an_ellipse_arc_are_its_vertices() {
        // the quarter ellipse x = 2 cos, y = sin from (2, 0) to (0, 1) as a rational
        // quadratic; as a half (through the vertex (0, 1)) it has one extremum there
        let q = RationalBezier::new(
            &[
                Point::new(2.0, 0.0),
                Point::new(2.0, 1.0),
                Point::new(0.0, 1.0),
            ],
            Some(&[1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0]),
        );
        assert!(curvature_extrema(&q).is_empty()); // the vertices are at its ends
        let half = RationalBezier::new(
            &[
                Point::new(2.0, 0.0),
                Point::new(2.0, 2.0),
                Point::new(-2.0, 2.0),
                Point::new(-2.0, 0.0),
            ],
            Some(&[1.0, 1.0 / 3.0, 1.0 / 3.0, 1.0]),
        );
        let e = curvature_extrema(&half);
        assert_eq!(e.len(), 1, "{e:?}");
        let p = half.eval(e[0]);
        assert!(p.dist(Point::new(0.0, 1.0)) < 1e-9, "{p:?}");
    }
}
