//! Free-form curves that cross or touch (SCENE_FORMAT.md). In `complex` and
//! `medial_axis` modes both engines cut the curves into pieces and corners and take
//! them to bound regions (`freeform::pieces`): curves may meet only end to end, where
//! consecutive spans of a site meet, at the seam of a closed curve and where two open
//! sites are joined. A crossing or a touch anywhere else leaves the regions and the
//! pieces' sides undefined, and the diagram was wrong (loose edge ends, edges outside
//! the region), so such scenes are refused. `voronoi` mode takes them.
//!
//! The spans are halved (de Casteljau, Farin02 ch. 5) until every pair of parts is
//! certified to meet nowhere but at a common end. A part lies in the convex hull of its
//! control points (weights positive), so:
//!
//! * two parts are *apart* when along some axis the control points of one lie more
//!   than `gap` beyond the other's (axes: x, y, the normals of both control polygons'
//!   edges and end-to-end chords, the line between their centroids);
//! * two parts with a common end `p` meet only there when the other control points of
//!   each, seen from `p`, lie in angular sectors narrower than π that share no
//!   direction: each hull lies in its sector's cone from `p`;
//! * a part does not meet itself when the differences of its consecutive control
//!   points lie in an open half-plane `⟨v, d⟩ > 0`: then `⟨P(t), d⟩ − c` has Bernstein
//!   coefficients with at most one sign change for every `c` (times positive weights),
//!   so by variation diminishing each value is taken once, and the part is injective.
//!
//! Two parts within `gap` that none of these separate are a contact. `gap` is `2^-30`
//! of the curves' extent, some 1e-9, where the free-form engine's feet meet.

use super::{Mode, Site};
use crate::error::Error;
use crate::freeform::pieces::{link_ends, solid_spans, JOIN};
use crate::geom::bezier::RationalBezier;
use crate::geom::{Aabb, Point};
use std::f64::consts::{PI, TAU};

/// The contact distance, relative to the curves' extent.
const GAP: f64 = 1.0 / (1u64 << 30) as f64;
/// Angles (radians) within this are taken as equal by the sector tests.
const ANGLE_MARGIN: f64 = 1e-9;
/// Most pairs of parts tried over a scene.
const MAX_PAIRS: usize = 1 << 21;
/// Most halvings of one span (below `gap` long before, for curves within the domain).
const MAX_DEPTH: u32 = 80;

/// A piece of a span: its site, its control points (projected), and the vertices at its
/// two ends: ends that meet share a vertex, every other end has one of its own.
#[derive(Clone)]
struct Part {
    curve: RationalBezier,
    points: Vec<Point>,
    site: usize,
    ends: [u32; 2],
    depth: u32,
}

impl Part {
    fn new(curve: RationalBezier, site: usize, ends: [u32; 2], depth: u32) -> Part {
        Part {
            points: curve.control_points(),
            curve,
            site,
            ends,
            depth,
        }
    }

    fn size(&self) -> f64 {
        bounds(&self.points).longest_side()
    }

    /// The two halves, meeting at the new vertex `middle`.
    fn halves(&self, middle: u32) -> [Part; 2] {
        let (l, r) = self.curve.split(0.5);
        let d = self.depth + 1;
        [
            Part::new(l, self.site, [self.ends[0], middle], d),
            Part::new(r, self.site, [middle, self.ends[1]], d),
        ]
    }

    /// The control point at end `e` (0: start, 1: end).
    fn end_point(&self, e: usize) -> Point {
        self.points[if e == 0 { 0 } else { self.points.len() - 1 }]
    }
}

fn bounds(points: &[Point]) -> Aabb {
    let mut b = Aabb::from_array([f64::INFINITY, f64::INFINITY, -f64::INFINITY, -f64::INFINITY]);
    for p in points {
        b.min.x = b.min.x.min(p.x);
        b.min.y = b.min.y.min(p.y);
        b.max.x = b.max.x.max(p.x);
        b.max.y = b.max.y.max(p.y);
    }
    b
}

/// The angular sector `(start, width)` holding the directions of `vectors` (zero
/// vectors skipped), when it is narrower than π; `Some((0, 0))` for none at all.
fn sector(vectors: impl Iterator<Item = Point>) -> Option<(f64, f64)> {
    let mut angles: Vec<f64> = vectors
        .filter(|v| v.x != 0.0 || v.y != 0.0)
        .map(|v| v.y.atan2(v.x))
        .collect();
    if angles.is_empty() {
        return Some((0.0, 0.0));
    }
    angles.sort_by(f64::total_cmp);
    // the widest gap between neighbouring directions (circularly) is outside the sector
    let n = angles.len();
    let (gap, after) = (0..n)
        .map(|k| {
            let next = if k + 1 < n {
                angles[k + 1]
            } else {
                angles[0] + TAU
            };
            (next - angles[k], (k + 1) % n)
        })
        .fold((-1.0, 0), |best, g| if g.0 > best.0 { g } else { best });
    let width = TAU - gap;
    (width < PI - ANGLE_MARGIN).then_some((angles[after], width))
}

/// Whether the sectors `a` and `b` share no direction (with the margin).
fn sectors_apart(a: (f64, f64), b: (f64, f64)) -> bool {
    let ahead = |from: f64, to: f64| (to - from).rem_euclid(TAU);
    ahead(a.0, b.0) > a.1 + ANGLE_MARGIN && ahead(b.0, a.0) > b.1 + ANGLE_MARGIN
}

/// The part is injective: its control polygon's steps lie in an open half-plane.
fn monotone(x: &Part) -> bool {
    sector(x.points.windows(2).map(|w| w[1] - w[0])).is_some()
}

/// Some axis separates the control points of `x` and `y` by more than `gap`.
fn apart(x: &Part, y: &Part, gap: f64) -> bool {
    let centroid = |p: &[Point]| {
        let s = p.iter().fold(Point::new(0.0, 0.0), |s, &q| s + q);
        s * (1.0 / p.len() as f64)
    };
    let steps = |p: &[Point]| {
        let chord = p[p.len() - 1] - p[0];
        p.windows(2)
            .map(|w| (w[1] - w[0]).perp())
            .chain([chord.perp()])
            .collect::<Vec<_>>()
    };
    let mut axes = vec![Point::new(1.0, 0.0), Point::new(0.0, 1.0)];
    axes.push(centroid(&y.points) - centroid(&x.points));
    axes.extend(steps(&x.points));
    axes.extend(steps(&y.points));
    axes.into_iter().any(|u| {
        let n = u.norm();
        if n == 0.0 || !n.is_finite() {
            return false;
        }
        let u = u * (1.0 / n);
        let range = |p: &[Point]| {
            p.iter()
                .fold((f64::INFINITY, -f64::INFINITY), |(lo, hi), q| {
                    let s = q.dot(u);
                    (lo.min(s), hi.max(s))
                })
        };
        let ((xl, xh), (yl, yh)) = (range(&x.points), range(&y.points));
        yl - xh > gap || xl - yh > gap
    })
}

/// `x` and `y` share exactly one end vertex and meet nowhere else (their hulls lie in
/// cones from it that share no direction). The apex is `x`'s end; `y`'s own end there
/// (the same point, or within the joining tolerance) is left out.
fn meet_only_at_common_end(x: &Part, y: &Part) -> bool {
    let common: Vec<(usize, usize)> = (0..2)
        .flat_map(|a| (0..2).map(move |b| (a, b)))
        .filter(|&(a, b)| x.ends[a] == y.ends[b])
        .collect();
    let &[(a, b)] = common.as_slice() else {
        return false;
    };
    let apex = x.end_point(a);
    let others = |p: &Part, e: usize| {
        let skip = if e == 0 { 0 } else { p.points.len() - 1 };
        p.points
            .iter()
            .enumerate()
            .filter(move |&(i, _)| i != skip)
            .map(move |(_, &q)| q - apex)
            .collect::<Vec<_>>()
    };
    match (
        sector(others(x, a).into_iter()),
        sector(others(y, b).into_iter()),
    ) {
        (Some(sx), Some(sy)) => sectors_apart(sx, sy),
        _ => false,
    }
}

/// What the search found: a contact of two sites near a point, or too much work.
enum Found {
    Contact(usize, usize, Point),
    Budget(usize, usize),
}

/// Refuses free-form curves that cross or touch other than end to end, in `complex`
/// and `medial_axis` modes (see the module docs); the later site's `control_points`
/// is named, with the earlier site.
pub(crate) fn crossing_curves(domain: &Aabb, mode: Mode, sites: &[Site]) -> Result<(), Error> {
    if mode == Mode::Voronoi {
        return Ok(());
    }
    match first_contact(domain, sites) {
        None => Ok(()),
        Some((Found::Contact(a, b, p), unit)) => {
            let (earlier, later) = (a.min(b), a.max(b));
            let (x, y) = (p.x / unit, p.y / unit);
            let what = if a == b {
                "the curve crosses or touches itself".to_string()
            } else {
                format!("it crosses or touches site {earlier}")
            };
            Err(Error::site(
                later,
                "control_points",
                format!(
                    "{what} near ({x:.4e}, {y:.4e}); in 'complex' and 'medial_axis' modes \
                     curves bound regions and may meet only end to end (mode 'voronoi' \
                     takes crossing curves)"
                ),
            ))
        }
        Some((Found::Budget(a, b), _)) => Err(Error::site(
            a.max(b),
            "control_points",
            format!(
                "it runs so close to site {} that {MAX_PAIRS} pairs of its pieces did not \
                 show where they meet; in 'complex' and 'medial_axis' modes curves may meet \
                 only end to end",
                a.min(b)
            ),
        )),
    }
}

/// True when some free-form curves cross or touch other than end to end, or may (the
/// search's budget ran out): then closed curves do not bound regions whose outside is
/// one side of each span.
pub(crate) fn curves_meet(domain: &Aabb, sites: &[Site]) -> bool {
    first_contact(domain, sites).is_some()
}

/// The first contact of the scene's free-form curves other than end to end, and the
/// power of two the search scaled them by (`None`: they meet only end to end).
fn first_contact(domain: &Aabb, sites: &[Site]) -> Option<(Found, f64)> {
    let curves: Vec<(usize, Vec<RationalBezier>, bool)> = sites
        .iter()
        .enumerate()
        .filter_map(|(i, s)| solid_spans(&s.kind).map(|(spans, closed)| (i, spans, closed)))
        .filter(|(_, spans, _)| !spans.is_empty())
        .collect();
    if curves.is_empty() {
        return None;
    }
    // the open ends joined as the engines join them (`pieces::links`)
    let ends: Vec<(usize, usize, Point)> = curves
        .iter()
        .filter(|(_, _, closed)| !closed)
        .flat_map(|(i, spans, _)| {
            [
                (*i, 0, spans[0].eval(0.0)),
                (*i, 1, spans[spans.len() - 1].eval(1.0)),
            ]
        })
        .collect();
    let links = link_ends(&ends, sites.len(), JOIN * domain.longest_side());
    // vertices: span k of a site starts at its vertex k; the last span ends at the
    // site's vertex `m` (its own, or the first's when closed); a linked end takes the
    // vertex of the lower site's end
    let mut first_vertex = vec![0u32; sites.len()];
    let mut next = 0u32;
    for (i, spans, _) in &curves {
        first_vertex[*i] = next;
        next += spans.len() as u32 + 1;
    }
    let vertex_of_end = |site: usize, end: usize, m: usize, closed: bool| -> u32 {
        let own = |site: usize, end: usize, m: usize| {
            first_vertex[site] + if end == 0 { 0 } else { m as u32 }
        };
        if closed {
            return own(site, 0, m);
        }
        match links[site][end] {
            Some(l) if l.site < site => {
                let lm = curves
                    .iter()
                    .find(|c| c.0 == l.site)
                    .map_or(0, |c| c.1.len());
                own(l.site, l.end, lm)
            }
            _ => own(site, end, m),
        }
    };
    // scale to unit size by a power of two (exact) so that products neither overflow
    // nor underflow
    let extent = bounds(
        &curves
            .iter()
            .flat_map(|(_, spans, _)| spans.iter().flat_map(|c| c.control_points()))
            .collect::<Vec<_>>(),
    )
    .longest_side();
    let unit = if extent > 0.0 && extent.is_finite() {
        (-extent.log2().round()).exp2()
    } else {
        1.0
    };
    let mut parts: Vec<Part> = Vec::new();
    for (i, spans, closed) in &curves {
        let m = spans.len();
        for (k, c) in spans.iter().enumerate() {
            let start = if k == 0 {
                vertex_of_end(*i, 0, m, *closed)
            } else {
                first_vertex[*i] + k as u32
            };
            let end = if k + 1 == m {
                vertex_of_end(*i, 1, m, *closed)
            } else {
                first_vertex[*i] + k as u32 + 1
            };
            let h = c
                .homogeneous()
                .iter()
                .map(|h| [h[0] * unit, h[1] * unit, h[2]])
                .collect();
            parts.push(Part::new(
                RationalBezier::from_homogeneous(h),
                *i,
                [start, end],
                0,
            ));
        }
    }
    let gap = GAP * extent * unit;
    search(&parts, gap, next).map(|found| (found, unit))
}

/// Halves parts until every pair, and every part with itself, is certified; the first
/// contact (or the budget's end) is returned. `vertices`: the next free vertex number.
fn search(parts: &[Part], gap: f64, mut vertices: u32) -> Option<Found> {
    enum Task {
        Alone(Part),
        Pair(Part, Part),
    }
    let mut tasks: Vec<Task> = parts.iter().cloned().map(Task::Alone).collect();
    let boxes: Vec<Aabb> = parts.iter().map(|p| bounds(&p.points)).collect();
    for i in 0..parts.len() {
        for j in i + 1..parts.len() {
            let (a, b) = (&boxes[i], &boxes[j]);
            let overlap = a.min.x - gap <= b.max.x
                && b.min.x - gap <= a.max.x
                && a.min.y - gap <= b.max.y
                && b.min.y - gap <= a.max.y;
            if overlap {
                tasks.push(Task::Pair(parts[i].clone(), parts[j].clone()));
            }
        }
    }
    let mut tried = 0usize;
    while let Some(task) = tasks.pop() {
        tried += 1;
        match task {
            Task::Alone(x) => {
                if monotone(&x) {
                    continue;
                }
                if x.size() <= gap || x.depth >= MAX_DEPTH {
                    return Some(Found::Contact(x.site, x.site, x.curve.eval(0.5)));
                }
                if tried > MAX_PAIRS {
                    return Some(Found::Budget(x.site, x.site));
                }
                let [l, r] = x.halves(vertices);
                vertices += 1;
                tasks.push(Task::Pair(l.clone(), r.clone()));
                tasks.push(Task::Alone(l));
                tasks.push(Task::Alone(r));
            }
            Task::Pair(x, y) => {
                if apart(&x, &y, gap) || meet_only_at_common_end(&x, &y) {
                    continue;
                }
                let (sx, sy) = (x.size(), y.size());
                let stuck = x.depth.max(y.depth) >= MAX_DEPTH;
                if (sx <= gap && sy <= gap) || stuck {
                    return Some(Found::Contact(x.site, y.site, x.curve.eval(0.5)));
                }
                if tried > MAX_PAIRS {
                    return Some(Found::Budget(x.site, y.site));
                }
                let (big, other) = if sx >= sy { (x, y) } else { (y, x) };
                let halves = big.halves(vertices);
                vertices += 1;
                for h in halves {
                    tasks.push(Task::Pair(h, other.clone()));
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bezier(points: &[[f64; 2]]) -> Site {
        Site::bezier(points.iter().copied(), None)
    }

    fn check(sites: &[Site]) -> Result<(), Error> {
        let domain = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
        crossing_curves(&domain, Mode::MedialAxis, sites)
    }

    #[test]
    fn sectors() {
        let s = sector([Point::new(1.0, 0.0), Point::new(0.0, 1.0)].into_iter()).unwrap();
        assert!((s.1 - PI / 2.0).abs() < 1e-15);
        assert!(sector([Point::new(1.0, 0.0), Point::new(-1.0, 0.0)].into_iter()).is_none());
        let left = sector([Point::new(-1.0, 0.1), Point::new(-1.0, -0.1)].into_iter()).unwrap();
        assert!(sectors_apart(s, left));
        let wide = sector([Point::new(1.0, -0.1), Point::new(-0.1, 1.0)].into_iter()).unwrap();
        assert!(!sectors_apart(s, wide));
    }

    #[test]
    fn a_lens_of_two_arches_passes_and_a_crossing_is_found() {
        let upper = bezier(&[[-1.0, 0.0], [-0.5, 1.0], [0.5, 1.0], [1.0, 0.0]]);
        let lower = bezier(&[[1.0, 0.0], [0.5, -1.0], [-0.5, -1.0], [-1.0, 0.0]]);
        check(&[upper.clone(), lower]).unwrap();
        // the lower arch bulging through the upper one
        let through = bezier(&[[1.0, 0.0], [0.5, 2.0], [-0.5, -1.0], [-1.0, 0.0]]);
        let e = check(&[upper, through]).unwrap_err();
        assert_eq!(e.site_index(), Some(1));
        assert_eq!(e.field(), Some("control_points"));
        assert!(e.to_string().contains("crosses or touches site 0"), "{e}");
    }

    #[test]
    fn a_loop_in_one_span_is_found() {
        // a cubic whose control polygon crosses itself makes a loop
        let looped = bezier(&[[0.0, 0.0], [2.0, 1.0], [0.0, 1.0], [2.0, 0.0]]);
        let close = bezier(&[[2.0, 0.0], [2.0, -1.0], [0.0, -1.0], [0.0, 0.0]]);
        let e = check(&[looped, close]).unwrap_err();
        assert!(e.to_string().contains("crosses or touches itself"), "{e}");
    }

    #[test]
    fn a_cusp_at_a_joint_is_a_touch() {
        // the second curve leaves the common end back along the first's tangent there
        let a = bezier(&[[0.0, 0.0], [0.5, 0.5], [1.0, 0.0]]);
        let b = bezier(&[[1.0, 0.0], [0.75, 0.25], [0.5, 1.0]]);
        assert!(check(&[a.clone(), b]).is_err());
        // a corner of a few degrees passes
        let c = bezier(&[[1.0, 0.0], [0.75, 0.3], [0.5, 1.0]]);
        check(&[a, c]).unwrap();
    }
}
