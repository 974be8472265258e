//! Geometric validation of sites with exact orientation predicates: simple polygon rings,
//! holes inside the outer ring, duplicate point sites; and the checks against hostile
//! input: identical sites of any kind, overlapping circles and ellipses, numbers f64
//! cannot resolve at the scene's epsilon.

use super::{Metric, Site, SiteKind};
use crate::error::Error;
use crate::geom::grid::{bounds_of_points, BucketGrid};
use crate::geom::predicates::orientation as orient;
use crate::geom::ring::winding_number;
use crate::geom::{Aabb, Point};
use std::cmp::Ordering;

/// Whether `p`, known to be collinear with segment `ab`, lies on the closed segment.
pub(super) fn on_segment(a: Point, b: Point, p: Point) -> bool {
    a.x.min(b.x) <= p.x && p.x <= a.x.max(b.x) && a.y.min(b.y) <= p.y && p.y <= a.y.max(b.y)
}

/// How two closed segments meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Contact {
    None,
    /// They cross at a single point interior to both.
    Cross,
    /// They share at least one point, an endpoint of one of them or a collinear overlap.
    Touch,
}

pub(super) fn contact(a: Point, b: Point, c: Point, d: Point) -> Contact {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    let opposite = |p: Ordering, q: Ordering| p != Ordering::Equal && q == p.reverse();
    if opposite(o1, o2) && opposite(o3, o4) {
        return Contact::Cross;
    }
    let touches = (o1 == Ordering::Equal && on_segment(a, b, c))
        || (o2 == Ordering::Equal && on_segment(a, b, d))
        || (o3 == Ordering::Equal && on_segment(c, d, a))
        || (o4 == Ordering::Equal && on_segment(c, d, b));
    if touches {
        Contact::Touch
    } else {
        Contact::None
    }
}

/// An edge of a polygon: ring index, edge index in the ring, endpoints.
struct Edge {
    ring: usize,
    index: usize,
    a: Point,
    b: Point,
}

/// Checks that polygon rings (outer ring first, then holes) bound a proper region: each ring
/// has at least 3 distinct points and no zero-length edge, no ring meets itself or another
/// ring (not even touching), every hole lies inside the outer ring and outside the other
/// holes. The message names the ring and edges at fault.
pub(super) fn check_rings(rings: &[Vec<Point>]) -> Result<(), String> {
    if rings.is_empty() {
        return Err("a polygon needs at least one ring (its outer boundary)".into());
    }
    for (r, ring) in rings.iter().enumerate() {
        if distinct_count(ring) < 3 {
            return Err(format!("ring {r} has fewer than 3 distinct points"));
        }
        let n = ring.len();
        for i in 0..n {
            let j = (i + 1) % n;
            if ring[i] == ring[j] {
                return Err(format!(
                    "ring {r}: points {i} and {j} coincide (zero-length edge; rings are closed implicitly, do not repeat the first point)"
                ));
            }
        }
        for i in 0..n {
            let (prev, here, next) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            if orient(prev, here, next) == Ordering::Equal && (prev - here).dot(next - here) > 0.0 {
                return Err(format!(
                    "ring {r} is self-intersecting: edges {} and {i} overlap (the ring turns back at point {i})",
                    (i + n - 1) % n
                ));
            }
        }
    }
    check_crossings(rings)?;
    let outer = &rings[0];
    for (h, hole) in rings.iter().enumerate().skip(1) {
        if winding_number(outer, hole[0]) == 0 {
            return Err(format!("hole ring {h} lies outside the outer ring 0"));
        }
        for (g, other) in rings.iter().enumerate().skip(1) {
            if g != h && winding_number(other, hole[0]) != 0 {
                return Err(format!("hole ring {h} lies inside hole ring {g}"));
            }
        }
    }
    Ok(())
}

fn distinct_count(ring: &[Point]) -> usize {
    let mut pts: Vec<(f64, f64)> = ring.iter().map(|p| (p.x, p.y)).collect();
    pts.sort_by(|p, q| p.partial_cmp(q).unwrap_or(Ordering::Equal));
    pts.dedup();
    pts.len()
}

/// Any contact between edges of the rings other than the shared corner of two edges
/// adjacent in one ring (adjacent overlaps are checked by the caller). Pairs are tried
/// within the cells of a grid that holds each edge in the cells it passes through, so
/// long spiky rings cost about as much as round ones; of several contacts the message
/// names the first pair in ring and edge order.
fn check_crossings(rings: &[Vec<Point>]) -> Result<(), String> {
    let edges: Vec<Edge> = rings
        .iter()
        .enumerate()
        .flat_map(|(ring, pts)| {
            (0..pts.len()).map(move |index| Edge {
                ring,
                index,
                a: pts[index],
                b: pts[(index + 1) % pts.len()],
            })
        })
        .collect();
    let grid = BucketGrid::of_ring_edges(edges.len(), |k| [edges[k].a, edges[k].b]);
    let mut first: Option<(&Edge, &Edge, Contact)> = None;
    for bucket in grid.buckets() {
        for (x, &i) in bucket.iter().enumerate() {
            for &j in &bucket[x + 1..] {
                // buckets list items in increasing order, which is ring and edge order
                let (e, f) = (&edges[i as usize], &edges[j as usize]);
                if first.is_some_and(|(e0, f0, _)| {
                    (e0.ring, e0.index, f0.ring, f0.index) <= (e.ring, e.index, f.ring, f.index)
                }) {
                    continue;
                }
                let c = contact(e.a, e.b, f.a, f.b);
                if c == Contact::None {
                    continue;
                }
                if e.ring == f.ring {
                    let last = rings[e.ring].len() - 1;
                    let adjacent = f.index == e.index + 1 || (e.index == 0 && f.index == last);
                    if adjacent && c == Contact::Touch {
                        continue;
                    }
                }
                first = Some((e, f, c));
            }
        }
    }
    match first {
        None => Ok(()),
        Some((e, f, c)) if e.ring == f.ring => {
            let how = if c == Contact::Cross {
                "cross"
            } else {
                "touch"
            };
            Err(format!(
                "ring {} is self-intersecting: edges {} and {} {how}",
                e.ring, e.index, f.index
            ))
        }
        Some((e, f, _)) => Err(format!(
            "rings {} and {} intersect: edge {} of ring {} meets edge {} of ring {}",
            e.ring, f.ring, e.index, e.ring, f.index, f.ring
        )),
    }
}

/// The first point site that repeats an earlier one (same location and same metric), as
/// `(later, earlier)` site indices.
pub(super) fn duplicate_point(sites: &[Site]) -> Option<(usize, usize)> {
    // Sorted by location (then index), equal locations are runs: no hashing and no
    // allocation per point, which counts at a million points.
    let key = |p: Point| ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits());
    let mut points: Vec<((u64, u64), usize)> = sites
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.kind {
            SiteKind::Point { at, .. } => Some((key(*at), i)),
            _ => None,
        })
        .collect();
    points.sort_unstable();
    let metric = |i: usize| match &sites[i].kind {
        SiteKind::Point { metric, .. } => Some(metric),
        _ => None,
    };
    let mut first: Option<(usize, usize)> = None;
    for run in points.chunk_by(|a, b| a.0 == b.0).filter(|r| r.len() > 1) {
        // The earliest point of the run repeating an earlier one of the same metric.
        for (k, &(_, i)) in run.iter().enumerate().skip(1) {
            if first.is_some_and(|(f, _)| f < i) {
                break;
            }
            if let Some(&(_, j)) = run[..k].iter().find(|&&(_, j)| metric(j) == metric(i)) {
                first = Some((i, j));
                break;
            }
        }
    }
    first
}

/// The first site (not a point: [`duplicate_point`] takes those; segments only with
/// `segments`) identical to an earlier one: same kind and same data (equations
/// compared as polynomials, so `x^2+y^2` repeats `y^2 + x^2`). Two identical sites tie
/// everywhere: their bisector is the whole plane. The segment engine merges repeated
/// segments (their common points may be named by either), the other engines do not.
pub(crate) fn duplicate_site(sites: &[Site], segments: bool) -> Result<(), Error> {
    use std::hash::{Hash, Hasher};
    let key = |kind: &SiteKind| {
        let mut h = std::hash::DefaultHasher::new();
        kind.name().hash(&mut h);
        match equation_of(kind) {
            Some(poly) => format!("{poly:?}").hash(&mut h),
            None => first_numbers(kind)
                .map(|x| (x + 0.0).to_bits())
                .hash(&mut h),
        }
        h.finish()
    };
    let mut keyed: Vec<(u64, usize)> = sites
        .iter()
        .enumerate()
        .filter(|(_, s)| match s.kind {
            SiteKind::Point { .. } => false,
            SiteKind::Segment { .. } => segments,
            _ => true,
        })
        .map(|(i, s)| (key(&s.kind), i))
        .collect();
    keyed.sort_unstable();
    let same = |a: &SiteKind, b: &SiteKind| match (a, b) {
        (
            SiteKind::Algebraic {
                equation: e,
                clip: c,
            },
            SiteKind::Algebraic {
                equation: f,
                clip: d,
            },
        ) => e.poly == f.poly && c == d,
        _ => match (equation_of(a), equation_of(b)) {
            (Some(p), Some(q)) => a.name() == b.name() && p == q,
            _ => a == b,
        },
    };
    let mut first: Option<(usize, usize)> = None;
    for run in keyed.chunk_by(|a, b| a.0 == b.0).filter(|r| r.len() > 1) {
        for (k, &(_, i)) in run.iter().enumerate().skip(1) {
            let earlier = run[..k]
                .iter()
                .find(|&&(_, j)| same(&sites[j].kind, &sites[i].kind));
            if let Some(&(_, j)) = earlier {
                if first.is_none_or(|(f, _)| i < f) {
                    first = Some((i, j));
                }
                break;
            }
        }
    }
    match first {
        None => Ok(()),
        Some((i, j)) => Err(Error::site(
            i,
            defining_field(&sites[i].kind),
            format!(
                "identical to site {j} (a duplicate {}: the two tie everywhere)",
                sites[i].kind.name()
            ),
        )),
    }
}

/// The polynomial of a site given by an equation.
fn equation_of(kind: &SiteKind) -> Option<&crate::num::poly::Poly> {
    match kind {
        SiteKind::Algebraic { equation, .. }
        | SiteKind::Field { equation }
        | SiteKind::ImplicitField { equation } => Some(&equation.poly),
        _ => None,
    }
}

/// A few of the numbers that define a site (for grouping candidates of duplicates).
fn first_numbers(kind: &SiteKind) -> [f64; 3] {
    let p = |q: &Point, r: f64| [q.x, q.y, r];
    match kind {
        SiteKind::Point { at, .. } => p(at, 0.0),
        SiteKind::Circle { center, radius } | SiteKind::Arc { center, radius, .. } => {
            p(center, *radius)
        }
        SiteKind::Ellipse {
            center, semi_axes, ..
        } => p(center, semi_axes[0]),
        SiteKind::Segment { from, to } => p(from, to.x),
        SiteKind::Polyline { points } => points.first().map_or([0.0; 3], |q| p(q, 0.0)),
        SiteKind::Polygon { rings } => rings
            .first()
            .and_then(|r| r.first())
            .map_or([0.0; 3], |q| p(q, 0.0)),
        SiteKind::Bezier { control_points, .. } | SiteKind::Bspline { control_points, .. } => {
            control_points.first().map_or([0.0; 3], |q| p(q, 0.0))
        }
        SiteKind::Algebraic { .. } | SiteKind::Field { .. } | SiteKind::ImplicitField { .. } => {
            [0.0; 3]
        }
    }
}

/// The field a message about the whole site names.
fn defining_field(kind: &SiteKind) -> &'static str {
    match kind {
        SiteKind::Point { .. } => "at",
        SiteKind::Circle { .. } | SiteKind::Ellipse { .. } | SiteKind::Arc { .. } => "center",
        SiteKind::Segment { .. } => "from",
        SiteKind::Polyline { .. } => "points",
        SiteKind::Polygon { .. } => "rings",
        SiteKind::Bezier { .. } | SiteKind::Bspline { .. } => "control_points",
        SiteKind::Algebraic { .. } | SiteKind::Field { .. } | SiteKind::ImplicitField { .. } => {
            "equation"
        }
    }
}

/// Refuses two point sites of one metric (Euclidean ones only with `euclidean`: the
/// exact engine computes those), or two free-form curves alike but for control points
/// (and a B-spline's `closed`, which does not change its points), closer than f64 can
/// separate at the scene's epsilon: the bisector of sites `δ` apart in a domain of size
/// `D` is placed only to about `D²·2^-52/δ` (the fields' rounding over the slope of
/// their difference), epsilon taken at least 1e-9 of `D`. Two lp points one ulp apart
/// otherwise give a bisector anywhere in their cell.
pub(crate) fn near_coincident_sites(
    domain: &Aabb,
    epsilon: f64,
    sites: &[Site],
    euclidean: bool,
) -> Result<(), Error> {
    let side = domain.longest_side();
    let closest = side * (side / epsilon.max(1e-9 * side)) * f64::EPSILON;
    // each candidate by a point of it: a point site's, a curve's first control point
    let anchored: Vec<(usize, Point)> = sites
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.kind {
            SiteKind::Point { at, metric } if euclidean || *metric != Metric::Euclidean => {
                Some((i, *at))
            }
            SiteKind::Bezier { control_points, .. } | SiteKind::Bspline { control_points, .. } => {
                control_points.first().map(|&p| (i, p))
            }
            _ => None,
        })
        .collect();
    if anchored.len() < 2 {
        return Ok(());
    }
    let extent = bounds_of_points(anchored.iter().map(|a| a.1));
    // about 16 cells per candidate (at least 64, at most 4096 along an axis): a finer
    // grid costs more to allocate than its buckets save
    let per_axis = (4.0 * (anchored.len() as f64).sqrt())
        .ceil()
        .clamp(64.0, 4096.0);
    let cell = closest.max(extent.longest_side() / per_axis);
    let grid = BucketGrid::new(extent, cell, per_axis as usize, anchored.len(), |k| {
        Aabb::new(anchored[k].1, anchored[k].1)
    });
    // how far apart two control polygons alike in all else are (their farthest pair)
    let apart = |p: &[Point], q: &[Point]| {
        (p.len() == q.len()).then(|| p.iter().zip(q).map(|(a, b)| a.dist(*b)).fold(0.0, f64::max))
    };
    let distance = |a: &SiteKind, b: &SiteKind| match (a, b) {
        (SiteKind::Point { at: p, metric: m }, SiteKind::Point { at: q, metric: n }) => {
            (m == n).then(|| p.dist(*q))
        }
        (
            SiteKind::Bezier {
                control_points: p,
                weights: w,
            },
            SiteKind::Bezier {
                control_points: q,
                weights: v,
            },
        ) if w == v => apart(p, q),
        (
            SiteKind::Bspline {
                degree: d,
                control_points: p,
                knots: k,
                weights: w,
                ..
            },
            SiteKind::Bspline {
                degree: e,
                control_points: q,
                knots: l,
                weights: v,
                ..
            },
        ) if (d, k, w) == (e, l, v) => apart(p, q),
        _ => None,
    };
    for (k, &(i, p)) in anchored.iter().enumerate() {
        // the earliest site too near (whatever the grid's cells)
        let mut near: Option<(usize, f64)> = None;
        grid.any_around(p, 1, |j| {
            let earlier = anchored[j as usize].0;
            let d = distance(&sites[i].kind, &sites[earlier].kind);
            if let Some(d) = d.filter(|&d| (j as usize) < k && d < closest) {
                if near.is_none_or(|(e, _)| earlier < e) {
                    near = Some((earlier, d));
                }
            }
            false
        });
        if let Some((j, d)) = near {
            let alike = match (&sites[i].kind, &sites[j].kind) {
                (SiteKind::Point { .. }, _) => "of the same metric",
                (SiteKind::Bspline { closed: c, .. }, SiteKind::Bspline { closed: f, .. })
                    if c != f =>
                {
                    "alike but for its control points and `closed` (a curve whose ends meet is closed all the same)"
                }
                _ => "alike but for its control points",
            };
            return Err(Error::site(
                i,
                defining_field(&sites[i].kind),
                format!(
                    "{d:.3e} from site {j} {alike}: at epsilon {epsilon:e} f64 places their bisector only if they are at least {closest:.3e} apart; merge them or move them apart"
                ),
            ));
        }
    }
    Ok(())
}

/// How much coarser than epsilon f64 may resolve a scene's numbers. A coordinate or a
/// length `x` is known to `|x|·2^-52` (its ulp); an epsilon somewhat finer than that is
/// floored by the engines (the subdivision reports `epsilon_floored_from`), but a number
/// whose ulp exceeds `COARSEST` epsilons leaves nothing the diagram could resolve: a
/// segment end at 1e308 with epsilon 1e-3 keeps nothing of the segment's direction
/// inside a unit domain.
const COARSEST: f64 = 64.0;

/// Checks that epsilon is finer than the domain (a coarser one leaves nothing to
/// resolve: an empty diagram), and so is the floor the engines put on it
/// ([`Aabb::f64_resolution`]: a domain a few dozen ulps wide far from the origin is
/// refused, naming `domain`), and that f64 can resolve the scene at it: the domain's coordinates, each
/// site's coordinates, radii and semi-axes, arc angles (times the radius), and the
/// weights of the quadratic metrics (a power weight `w` enters as `w²`, the others as
/// they are, against the field's slope of about the domain's size). Names the site and
/// field of the first number too large.
pub(crate) fn check_precision(domain: &Aabb, epsilon: f64, sites: &[Site]) -> Result<(), Error> {
    let side = domain.longest_side();
    if epsilon >= side {
        return Err(Error::scene(
            "epsilon",
            format!(
                "epsilon {epsilon:e} is not finer than the domain ({side:e} on its longest side): the diagram would resolve nothing in it; give a smaller epsilon or a larger domain"
            ),
        ));
    }
    let ulp = |x: f64| x.abs() * f64::EPSILON;
    let limit = COARSEST * epsilon;
    let extent = domain.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // the engines floor a finer epsilon to this; a floor not finer than the domain is,
    // like such an epsilon, a diagram that resolves nothing (an empty one, or edges
    // rounded to a grid of a few dozen steps)
    let floor = domain.f64_resolution();
    if floor >= side {
        return Err(Error::scene(
            "domain",
            format!(
                "the domain is only {side:e} wide at coordinates up to {extent:e}, where f64 spaces numbers {:e} apart: the engines resolve a diagram there only to {floor:.3e}, not finer than the domain; translate the scene (domain and sites) nearer the origin, or enlarge the domain",
                extent.next_up() - extent
            ),
        ));
    }
    if ulp(extent) > limit {
        return Err(Error::scene(
            "epsilon",
            format!(
                "epsilon {epsilon:e} is far finer than f64 resolves in this domain (coordinates up to {extent:e} are spaced {:e}); the finest epsilon accepted here is {:e}",
                ulp(extent),
                ulp(extent) / COARSEST
            ),
        ));
    }
    // a field value `v` is resolved to ulp(v), a position to that over the field's slope
    let slope = side;
    for (i, site) in sites.iter().enumerate() {
        let too_coarse = |field: &str, what: &str, x: f64, resolved: f64| {
            Error::site(
                i,
                field,
                format!(
                    "{what} {x:e} is too large for epsilon {epsilon:e}: f64 resolves it only to {resolved:.3e}; move the site nearer the domain, or raise epsilon"
                ),
            )
        };
        let check = |field: &str, x: f64| {
            if ulp(x) > limit {
                Err(too_coarse(field, "coordinate or length", x, ulp(x)))
            } else {
                Ok(())
            }
        };
        let point = |field: &str, p: &Point| check(field, p.x).and_then(|_| check(field, p.y));
        let points = |field: &str, ps: &[Point]| ps.iter().try_for_each(|p| point(field, p));
        match &site.kind {
            SiteKind::Point { at, metric } => {
                point("at", at)?;
                let weight = match metric {
                    Metric::Power { weight } => weight * weight,
                    Metric::Anisotropic { weight, .. } | Metric::Moebius { weight, .. } => *weight,
                    Metric::Euclidean | Metric::Lp { .. } => 0.0,
                };
                if ulp(weight) > limit * slope {
                    return Err(too_coarse(
                        "metric.weight",
                        "the weight's contribution to the field",
                        weight,
                        ulp(weight) / slope,
                    ));
                }
            }
            SiteKind::Circle { center, radius } => {
                point("center", center)?;
                check("radius", *radius)?;
            }
            SiteKind::Ellipse {
                center, semi_axes, ..
            } => {
                point("center", center)?;
                check("semi_axes", semi_axes[0])?;
                check("semi_axes", semi_axes[1])?;
            }
            SiteKind::Segment { from, to } => {
                point("from", from)?;
                point("to", to)?;
            }
            SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => {
                point("center", center)?;
                check("radius", *radius)?;
                for (field, angle) in [("start_angle", start_angle), ("end_angle", end_angle)] {
                    if ulp(*angle) * radius > limit {
                        return Err(too_coarse(field, "angle", *angle, ulp(*angle) * radius));
                    }
                }
            }
            SiteKind::Polyline { points: ps } => points("points", ps)?,
            SiteKind::Polygon { rings } => rings.iter().try_for_each(|r| points("rings", r))?,
            SiteKind::Bezier { control_points, .. } | SiteKind::Bspline { control_points, .. } => {
                points("control_points", control_points)?
            }
            SiteKind::Algebraic { .. }
            | SiteKind::Field { .. }
            | SiteKind::ImplicitField { .. } => {}
        }
    }
    Ok(())
}

/// A disk or a filled ellipse: `center + R(rotation)·(a cos t, b sin t)` bounds it.
#[derive(Clone, Copy)]
struct Oval {
    center: Point,
    axes: [f64; 2],
    rotation: f64,
}

impl Oval {
    fn of(kind: &SiteKind) -> Option<Oval> {
        match kind {
            SiteKind::Circle { center, radius } if *radius > 0.0 => Some(Oval {
                center: *center,
                axes: [*radius, *radius],
                rotation: 0.0,
            }),
            SiteKind::Ellipse {
                center,
                semi_axes,
                rotation,
            } => Some(Oval {
                center: *center,
                axes: *semi_axes,
                rotation: *rotation,
            }),
            _ => None,
        }
    }

    fn boundary(&self, t: f64) -> Point {
        let (s, c) = self.rotation.sin_cos();
        let (u, v) = (self.axes[0] * t.cos(), self.axes[1] * t.sin());
        self.center + Point::new(c * u - s * v, s * u + c * v)
    }

    /// `(u/a)² + (v/b)² − 1` in the oval's frame: negative strictly inside.
    fn level(&self, q: Point) -> f64 {
        let (s, c) = self.rotation.sin_cos();
        let d = q - self.center;
        let (u, v) = (c * d.x + s * d.y, -s * d.x + c * d.y);
        (u / self.axes[0]).powi(2) + (v / self.axes[1]).powi(2) - 1.0
    }

    fn reach(&self) -> f64 {
        self.axes[0].max(self.axes[1])
    }

    /// Whether a point of `self`'s boundary lies strictly inside `other`: 1024 samples
    /// of the parameter, each local minimum of `other.level` refined by golden-section
    /// search (the level is a trigonometric polynomial of degree 2 in `t`: at most two
    /// minima, each found unless narrower than the sampling, which the caller covers by
    /// testing both ways).
    fn enters(&self, other: &Oval) -> bool {
        const N: usize = 1024;
        let tau = std::f64::consts::TAU;
        let g = |t: f64| other.level(self.boundary(t));
        let vals: Vec<f64> = (0..N).map(|k| g(tau * k as f64 / N as f64)).collect();
        (0..N).any(|k| {
            let (prev, here, next) = (vals[(k + N - 1) % N], vals[k], vals[(k + 1) % N]);
            if here < 0.0 {
                return true;
            }
            if here > prev || here > next {
                return false;
            }
            let (mut lo, mut hi) = (
                tau * (k as f64 - 1.0) / N as f64,
                tau * (k as f64 + 1.0) / N as f64,
            );
            let r = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..60 {
                let (m1, m2) = (hi - r * (hi - lo), lo + r * (hi - lo));
                if g(m1) < 0.0 || g(m2) < 0.0 {
                    return true;
                }
                if g(m1) < g(m2) {
                    hi = m2;
                } else {
                    lo = m1;
                }
            }
            false
        })
    }

    /// Whether the two interiors meet: a boundary point of one strictly inside the
    /// other, or one's centre inside the other (containment). Touching is allowed, also
    /// where the data of tangent circles rounds to a penetration of `1e-12` relative.
    /// The centres' distance is a `hypot`: its square overflows near 1e154.
    fn overlaps(&self, other: &Oval) -> bool {
        let gap = self.center - other.center;
        let gap = gap.x.hypot(gap.y);
        if gap >= self.reach() + other.reach() {
            return false;
        }
        if self.axes[0] == self.axes[1] && other.axes[0] == other.axes[1] {
            let touch = self.axes[0] + other.axes[0];
            return gap < touch * (1.0 - 1e-12);
        }
        other.level(self.center) < 0.0
            || self.level(other.center) < 0.0
            || self.enters(other)
            || other.enters(self)
    }
}

/// Refuses circles and ellipses whose interiors meet (the format's sites are disjoint:
/// inside two sites at once both fields are negative and the diagram is not defined
/// there). Pairs are swept in order of their leftmost reach.
pub(crate) fn overlapping_ovals(sites: &[Site]) -> Result<(), Error> {
    let mut ovals: Vec<(usize, Oval)> = sites
        .iter()
        .enumerate()
        .filter_map(|(i, s)| Oval::of(&s.kind).map(|o| (i, o)))
        .collect();
    ovals.sort_by(|a, b| (a.1.center.x - a.1.reach()).total_cmp(&(b.1.center.x - b.1.reach())));
    for (k, (i, a)) in ovals.iter().enumerate() {
        for (j, b) in &ovals[k + 1..] {
            if b.center.x - b.reach() > a.center.x + a.reach() {
                break;
            }
            if a.overlaps(b) {
                let (site, other) = ((*i).max(*j), (*i).min(*j));
                return Err(Error::Conflict {
                    site,
                    other,
                    message: "their interiors overlap (the sites of a scene must be disjoint)"
                        .into(),
                });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ring(pts: &[[f64; 2]]) -> Vec<Point> {
        pts.iter().map(|&p| Point::from(p)).collect()
    }

    #[test]
    fn simple_rings_pass() {
        let square = ring(&[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]]);
        let hole = ring(&[[1.0, 1.0], [2.0, 1.0], [1.0, 2.0]]);
        let hole2 = ring(&[[3.0, 3.0], [3.5, 3.0], [3.5, 3.5]]);
        assert_eq!(check_rings(std::slice::from_ref(&square)), Ok(()));
        assert_eq!(check_rings(&[square, hole, hole2]), Ok(()));
        // A non-convex ring with collinear consecutive points going forward is fine.
        let l = ring(&[
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ]);
        assert_eq!(check_rings(&[l]), Ok(()));
    }

    #[test]
    fn bad_rings_are_refused() {
        let msg = |rings: &[Vec<Point>]| check_rings(rings).unwrap_err();
        assert!(
            msg(&[ring(&[[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]])]).contains("fewer than 3 distinct")
        );
        let bowtie = ring(&[[-1.0, -1.0], [1.0, 1.0], [1.0, -0.5], [-1.0, 1.0]]);
        assert!(msg(&[bowtie]).contains("edges 0 and 2 cross"));
        let repeated = ring(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]);
        assert!(msg(&[repeated]).contains("zero-length edge"));
        let flat = ring(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]);
        assert!(msg(&[flat]).contains("overlap"));
        // A corner touching a non-adjacent edge.
        let pinched = ring(&[[0.0, 0.0], [4.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]);
        assert!(msg(&[pinched]).contains("touch"));
        let square = ring(&[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]]);
        let outside = ring(&[[5.0, 5.0], [6.0, 5.0], [5.0, 6.0]]);
        assert!(msg(&[square.clone(), outside]).contains("outside the outer ring"));
        let crossing = ring(&[[3.0, 3.0], [5.0, 3.0], [3.0, 5.0]]);
        assert!(msg(&[square.clone(), crossing]).contains("rings 0 and 1 intersect"));
        let big = ring(&[[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]]);
        let small = ring(&[[1.5, 1.5], [2.0, 1.5], [1.5, 2.0]]);
        assert!(msg(&[square, big, small]).contains("hole ring 2 lies inside hole ring 1"));
        assert!(msg(&[]).contains("at least one ring"));
    }
}
