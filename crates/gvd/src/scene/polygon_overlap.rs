//! Polygon sites whose insides overlap (SCENE_FORMAT.md: the sites of a scene are
//! disjoint; polygons may share corners and edges, their insides on either side).
//!
//! Two closed polygonal regions `A`, `B` overlap when a point of `A`'s boundary lies
//! strictly inside `B` (a boundary point is a limit of inside points, and an inside
//! neighbourhood of it then meets `A`'s inside), when their boundaries cross, or when
//! they run along one another with both insides on the same side. The witnesses tried,
//! all with exact orientation signs (Shewchuk97), so touching polygons are never refused:
//!
//! * pairs of edges of different polygons that cross at a point inside both, or lie on
//!   one line over a common piece and point the same way (every ring oriented with its
//!   region on the left: outer rings counter-clockwise, holes clockwise), tried within
//!   the cells of a grid of the edges;
//! * pairs of edges that touch, where one runs from the point they share into the
//!   other polygon's inside: the direction along it lies strictly left of the other's
//!   edge there, or strictly inside the other's angle at its corner there;
//! * every corner of each polygon, located in the other polygons whose boxes hold it,
//!   each through a slab index of its edges ([`RayCrossings`]).
//!
//! Complete: a boundary point of `A` strictly inside `B` lies on an edge of `A`, on a
//! piece between two consecutive points where that edge meets `B`'s boundary (or its
//! own ends). The edges do not cross there, so the whole piece is inside `B`: from its
//! start on `B`'s boundary (an end of the edge, or a corner of `B`) the edge runs into
//! `B`, or, if the piece touches `B` nowhere, its end corners are inside `B`. A polygon
//! inscribed in another, its corners on the other's sides, is found whatever its
//! coordinates.

use super::validate::{contact, on_segment, Contact};
use super::{Metric, Mode, Site, SiteKind};
use crate::error::Error;
use crate::geom::grid::{bounds_of_points, BucketGrid};
use crate::geom::predicates::orientation as orient;
use crate::geom::ring::{Location, RayCrossings};
use crate::geom::{Aabb, Point};
use std::cmp::Ordering;

/// An edge of a polygon site, `a → b` with the region on its left, and where it was
/// given: edge `index` of ring `ring` (from point `index` to the next).
#[derive(Clone, Copy)]
struct Edge {
    polygon: u32,
    ring: u32,
    index: u32,
    a: Point,
    b: Point,
    /// The positions (in the list of edges) of the ring's oriented edges that end at
    /// `a` and that start at `b`.
    before: u32,
    after: u32,
}

/// What shows two polygons' insides overlap.
enum Witness {
    /// Edge `e` of one crosses edge `f` of the other.
    Cross(Edge, Edge),
    /// Edges `e` and `f` run along one line the same way over a common piece.
    Along(Edge, Edge),
    /// Edge `e` runs into the inside of polygon `inside` from a point on its boundary.
    Enters(Edge, u32),
    /// Point `index` of ring `ring` of polygon `polygon` lies strictly inside polygon
    /// `inside`.
    Inside {
        polygon: u32,
        ring: u32,
        index: u32,
        inside: u32,
    },
}

/// Refuses two polygon sites whose insides overlap, naming the later site (its
/// `rings`) and the earlier one; of several such pairs, the one with the smallest
/// indices.
pub(crate) fn overlapping_polygons(sites: &[Site]) -> Result<(), Error> {
    let polygons = polygon_sites(sites);
    if polygons.len() < 2 {
        return Ok(());
    }
    let edges = oriented_edges(&polygons);
    let mut first: Option<((usize, usize), Witness)> = None;
    let mut note = |w: Witness| {
        let (p, q) = match &w {
            Witness::Cross(e, f) | Witness::Along(e, f) => (e.polygon, f.polygon),
            Witness::Enters(e, inside) => (e.polygon, *inside),
            Witness::Inside {
                polygon, inside, ..
            } => (*polygon, *inside),
        };
        let (i, j) = (polygons[p as usize].0, polygons[q as usize].0);
        let pair = (i.max(j), i.min(j));
        if first.as_ref().is_none_or(|(f, _)| pair < *f) {
            first = Some((pair, w));
        }
    };
    edge_contacts(&edges, &mut note);
    points_inside(&polygons, &edges, &mut note);
    let Some(((later, earlier), w)) = first else {
        return Ok(());
    };
    let site = |p: u32| polygons[p as usize].0;
    let how = match w {
        Witness::Cross(e, f) | Witness::Along(e, f) => {
            let (mine, theirs) = if site(e.polygon) == later {
                (e, f)
            } else {
                (f, e)
            };
            let (verb, tail) = if matches!(w, Witness::Cross(..)) {
                ("crosses", "")
            } else {
                ("lies along", ", both insides on one side")
            };
            format!(
                "edge {} of ring {} {verb} edge {} of ring {} of polygon site {earlier}{tail}",
                mine.index, mine.ring, theirs.index, theirs.ring
            )
        }
        Witness::Enters(e, _) => {
            let what = format!("edge {} of ring {}", e.index, e.ring);
            if site(e.polygon) == later {
                format!("{what} runs into the inside of polygon site {earlier} from its boundary")
            } else {
                format!("{what} of polygon site {earlier} runs into its inside from its boundary")
            }
        }
        Witness::Inside {
            polygon,
            ring,
            index,
            ..
        } => {
            let what = format!("point {index} of ring {ring}");
            if site(polygon) == later {
                format!("{what} lies inside polygon site {earlier}")
            } else {
                format!("{what} of polygon site {earlier} lies inside it")
            }
        }
    };
    Err(Error::site(
        later,
        "rings",
        format!(
            "its inside overlaps that of polygon site {earlier}: {how} (polygons may share \
             corners and edges, not insides)"
        ),
    ))
}

/// The edges of every ring, oriented with the polygon's region on their left.
fn oriented_edges(polygons: &[(usize, &[Vec<Point>])]) -> Vec<Edge> {
    let mut edges = Vec::new();
    for (p, (_, rings)) in polygons.iter().enumerate() {
        for (r, ring) in rings.iter().enumerate() {
            let forward = counter_clockwise(ring) == (r == 0);
            let (n, start) = (ring.len(), edges.len());
            for k in 0..n {
                let (a, b) = (ring[k], ring[(k + 1) % n]);
                // edge `k − 1` ends at point `k` and edge `k + 1` starts at point `k + 1`;
                // reversed, edge `k` runs from point `k + 1` to point `k`
                let (prev, next) = (start + (k + n - 1) % n, start + (k + 1) % n);
                let (a, b, before, after) = if forward {
                    (a, b, prev, next)
                } else {
                    (b, a, next, prev)
                };
                edges.push(Edge {
                    polygon: p as u32,
                    ring: r as u32,
                    index: k as u32,
                    a,
                    b,
                    before: before as u32,
                    after: after as u32,
                });
            }
        }
    }
    edges
}

/// Whether a simple ring runs counter-clockwise: its turn at its least point (by x,
/// then y), a corner of its convex hull where it cannot run straight (a ring that
/// turns back there is refused before).
fn counter_clockwise(ring: &[Point]) -> bool {
    let n = ring.len();
    let k = (0..n)
        .min_by(|&i, &j| (ring[i].x.total_cmp(&ring[j].x)).then(ring[i].y.total_cmp(&ring[j].y)))
        .unwrap_or(0);
    orient(ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n]) == Ordering::Greater
}

/// Edges of different polygons that cross, or run along one line the same way over a
/// common piece.
fn edge_contacts(edges: &[Edge], note: &mut impl FnMut(Witness)) {
    let grid = BucketGrid::of_ring_edges(edges.len(), |k| [edges[k].a, edges[k].b]);
    for bucket in grid.buckets() {
        for (x, &i) in bucket.iter().enumerate() {
            let e = edges[i as usize];
            for &j in &bucket[x + 1..] {
                let f = edges[j as usize];
                if e.polygon == f.polygon {
                    continue;
                }
                match contact(e.a, e.b, f.a, f.b) {
                    Contact::Cross => note(Witness::Cross(e, f)),
                    Contact::Touch if same_way_along(&e, &f) => note(Witness::Along(e, f)),
                    Contact::Touch if runs_into(&e, &f, edges) => {
                        note(Witness::Enters(e, f.polygon))
                    }
                    Contact::Touch if runs_into(&f, &e, edges) => {
                        note(Witness::Enters(f, e.polygon))
                    }
                    _ => {}
                }
            }
        }
    }
}

/// Whether `e`, from a point it shares with `f` (an end of either), runs into the inside
/// of `f`'s polygon (see [`enters`]).
fn runs_into(e: &Edge, f: &Edge, edges: &[Edge]) -> bool {
    let on = |g: &Edge, p: Point| orient(g.a, g.b, p) == Ordering::Equal && on_segment(g.a, g.b, p);
    [e.a, e.b, f.a, f.b].into_iter().any(|p| {
        on(e, p)
            && on(f, p)
            && [e.a, e.b]
                .into_iter()
                .any(|to| to != p && enters(p, to, f, edges))
    })
}

/// Whether the direction from `p`, a point of edge `f`, towards `to` points strictly
/// into the inside of `f`'s polygon (on its left, [`oriented_edges`]): left of `f` at a
/// point inside it; at a corner, left of both edges there where the ring turns left,
/// of either where it turns right (exact orientation signs: `p` lies on both lines).
fn enters(p: Point, to: Point, f: &Edge, edges: &[Edge]) -> bool {
    let left = |a: Point, b: Point| orient(a, b, to) == Ordering::Greater;
    let (into, out) = if p == f.a {
        (&edges[f.before as usize], f)
    } else if p == f.b {
        (f, &edges[f.after as usize])
    } else {
        return left(f.a, f.b);
    };
    let (u, v) = (into.a, out.b);
    match orient(u, p, v) {
        Ordering::Greater => left(u, p) && left(p, v),
        Ordering::Less => left(u, p) || left(p, v),
        Ordering::Equal => left(p, v),
    }
}

/// Whether `e` and `f` lie on one line, share a piece longer than a point, and point
/// the same way (exact: orientation signs and comparisons of coordinates).
fn same_way_along(e: &Edge, f: &Edge) -> bool {
    if orient(e.a, e.b, f.a) != Ordering::Equal || orient(e.a, e.b, f.b) != Ordering::Equal {
        return false;
    }
    // along x unless the line is vertical (then along y)
    let coord = |p: Point| if e.a.x != e.b.x { p.x } else { p.y };
    let (e0, e1, f0, f1) = (coord(e.a), coord(e.b), coord(f.a), coord(f.b));
    let common = e0.min(e1).max(f0.min(f1)) < e0.max(e1).min(f0.max(f1));
    common && (e0 < e1) == (f0 < f1)
}

/// The polygons' regions, for locating points strictly inside them: a grid of their
/// outer rings' boxes, and a slab index of each polygon's edges ([`RayCrossings`],
/// exact).
struct Regions {
    boxes: Vec<Aabb>,
    grid: BucketGrid,
    indices: Vec<RayCrossings>,
}

impl Regions {
    /// The regions of `polygons`, whose edges `edges` lists polygon by polygon.
    fn new(polygons: &[(usize, &[Vec<Point>])], edges: &[Edge]) -> Regions {
        let boxes: Vec<Aabb> = polygons
            .iter()
            .map(|(_, rings)| bounds_of_points(rings[0].iter().copied()))
            .collect();
        let extent = bounds_of_points(boxes.iter().flat_map(|b| [b.min, b.max]));
        let side = extent.longest_side() / (polygons.len() as f64).sqrt();
        let grid = BucketGrid::new(extent, side, 4096, boxes.len(), |k| boxes[k]);
        let mut indices: Vec<RayCrossings> = Vec::with_capacity(polygons.len());
        let mut start = 0;
        for p in 0..polygons.len() {
            let end = start + edges[start..].partition_point(|e| e.polygon == p as u32);
            indices.push(RayCrossings::new(
                edges[start..end].iter().map(|e| (e.a, e.b)).collect(),
            ));
            start = end;
        }
        Regions {
            boxes,
            grid,
            indices,
        }
    }

    /// Calls `f` with every polygon (its index in the list) that holds `q` strictly
    /// inside: not on its boundary, not in a hole.
    fn holding(&self, q: Point, mut f: impl FnMut(u32)) {
        for &p in self.grid.bucket(self.grid.cell_of(q)) {
            if self.boxes[p as usize].contains(q)
                && self.indices[p as usize].locate(q) == Location::Inside
            {
                f(p);
            }
        }
    }
}

/// Corners of each polygon that lie strictly inside another.
fn points_inside(
    polygons: &[(usize, &[Vec<Point>])],
    edges: &[Edge],
    note: &mut impl FnMut(Witness),
) {
    let regions = Regions::new(polygons, edges);
    for (p, (_, rings)) in polygons.iter().enumerate() {
        let polygon = p as u32;
        for (r, ring) in rings.iter().enumerate() {
            for (k, &a) in ring.iter().enumerate() {
                regions.holding(a, |inside| {
                    if inside != polygon {
                        note(Witness::Inside {
                            polygon,
                            ring: r as u32,
                            index: k as u32,
                            inside,
                        });
                    }
                });
            }
        }
    }
}

/// Refuses a point site strictly inside a polygon site (outside its holes), naming the
/// point's `at` and the first polygon that holds it, in the modes where polygons are
/// solid (`voronoi`, `complex`: their insides are part of the site; in `medial_axis`
/// mode the diagram is the one inside them, and points there are obstacles). There a point
/// whose field vanishes only at itself (Euclidean, lp) is never nearer than the
/// polygon, whose field is 0 on the whole region: its cell would be empty (reading a
/// polygon as its boundary instead would give it one inside). The location is exact
/// (orientation signs, Sunday01): a point on a polygon's boundary is a shared point,
/// accepted. Of several such points, the first in the scene.
pub(crate) fn points_inside_polygons(sites: &[Site], mode: Mode) -> Result<(), Error> {
    if mode == Mode::MedialAxis {
        return Ok(());
    }
    let polygons = polygon_sites(sites);
    let points: Vec<(usize, Point)> = sites
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.kind {
            SiteKind::Point {
                at,
                metric: Metric::Euclidean | Metric::Lp { .. },
            } => Some((i, *at)),
            _ => None,
        })
        .collect();
    if polygons.is_empty() || points.is_empty() {
        return Ok(());
    }
    let regions = Regions::new(&polygons, &oriented_edges(&polygons));
    for (i, at) in points {
        let mut holder: Option<usize> = None;
        regions.holding(at, |p| {
            let site = polygons[p as usize].0;
            holder = Some(holder.map_or(site, |h| h.min(site)));
        });
        if let Some(polygon) = holder {
            return Err(Error::site(
                i,
                "at",
                format!(
                    "lies inside polygon site {polygon}: in '{}' mode a polygon is solid (its \
                     inside is part of the site), so a point inside it has no cell; move the \
                     point out or onto the boundary (a shared point), or use mode \
                     'medial_axis' for the diagram inside the polygon",
                    mode.name()
                ),
            ));
        }
    }
    Ok(())
}

/// Refuses a site that reaches strictly inside a polygon site (outside its holes), as
/// seen at `samples(i)`, points along site `i`, naming the site and the first such
/// polygon: where a polygon is solid and a
/// subdivision field is its boundary's distance, a site inside it would have a cell
/// there. Points on a polygon's boundary touch it and pass.
pub(crate) fn sites_inside_polygons(
    sites: &[Site],
    samples: impl Fn(usize) -> Vec<Point>,
) -> Result<(), Error> {
    let polygons = polygon_sites(sites);
    if polygons.is_empty() {
        return Ok(());
    }
    let regions = Regions::new(&polygons, &oriented_edges(&polygons));
    for i in (0..sites.len()).filter(|&i| !matches!(sites[i].kind, SiteKind::Polygon { .. })) {
        let mut holder: Option<usize> = None;
        for q in samples(i) {
            regions.holding(q, |p| {
                let site = polygons[p as usize].0;
                holder = Some(holder.map_or(site, |h| h.min(site)));
            });
            if let Some(polygon) = holder {
                return Err(Error::Conflict {
                    site: i,
                    other: polygon,
                    message: format!(
                        "the first reaches inside the polygon near ({}, {}): a polygon is \
                         solid, and the sites of a scene must be disjoint",
                        q.x, q.y
                    ),
                });
            }
        }
    }
    Ok(())
}

/// The polygon sites, with their site indices.
fn polygon_sites(sites: &[Site]) -> Vec<(usize, &[Vec<Point>])> {
    sites
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.kind {
            SiteKind::Polygon { rings } => Some((i, rings.as_slice())),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygon(rings: &[&[[f64; 2]]]) -> Site {
        Site::new(SiteKind::Polygon {
            rings: rings
                .iter()
                .map(|r| r.iter().map(|&[x, y]| Point::new(x, y)).collect())
                .collect(),
        })
    }

    const SQUARE: &[[f64; 2]] = &[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    const BIG: &[[f64; 2]] = &[[-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]];

    /// The refusal's message, `None` when the two polygons are accepted.
    fn refusal(a: &[&[[f64; 2]]], b: &[&[[f64; 2]]]) -> Option<String> {
        let sites = [polygon(a), polygon(b)];
        overlapping_polygons(&sites).err().map(|e| {
            assert_eq!((e.site_index(), e.field()), (Some(1), Some("rings")), "{e}");
            e.to_string()
        })
    }

    #[test]
    fn overlapping_insides_are_refused() {
        let below = 1.0f64.next_down();
        let above = 1.0f64.next_up();
        let small: &[[f64; 2]] = &[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
        for (name, other, says) in [
            ("nested", small, "point 0 of ring 0 lies inside"),
            (
                "corner an ulp in",
                &[[-1.0, -1.0], [1.0, -1.0], [below, below], [-1.0, 1.0]][..],
                "lies along edge 0",
            ),
            (
                "clockwise copy, corner an ulp out",
                &[[-1.0, -1.0], [-1.0, 1.0], [above, above], [1.0, -1.0]],
                "both insides on one side",
            ),
            (
                "a half",
                &[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0]],
                "lies along",
            ),
            (
                "inscribed, corners on the sides",
                &[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]],
                "runs into the inside of polygon site 0",
            ),
            (
                "crossing",
                &[[-0.5, -2.0], [0.5, -2.0], [0.5, 2.0], [-0.5, 2.0]],
                "crosses",
            ),
            ("around", BIG, "of polygon site 0 lies inside it"),
        ] {
            let m = refusal(&[SQUARE], &[other]).unwrap_or_else(|| panic!("{name}: accepted"));
            assert!(m.contains(says), "{name}: {m}");
        }
        // inscribed at coordinates where no edge's midpoint rounds onto the edge
        let diamond: &[[f64; 2]] = &[[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];
        let (a, b) = (0.7, 1.0 - 0.7);
        let inscribed: &[[f64; 2]] = &[[a, -b], [0.6, 0.4], [-a, b], [-0.6, -0.4]];
        let m = refusal(&[diamond], &[inscribed]).expect("inscribed: accepted");
        assert!(m.contains("runs into the inside of polygon site 0"), "{m}");
        // from a corner where the other turns right (reflex), into its inside or not
        let l_shape: &[[f64; 2]] = &[
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ];
        let into: &[[f64; 2]] = &[[1.0, 1.0], [0.0, 0.5], [0.5, 0.0]];
        assert!(refusal(&[l_shape], &[into]).is_some_and(|m| m.contains("runs into")));
        for outside in [
            &[[1.0, 1.0], [2.0, 1.5], [1.5, 2.0]][..],
            &[[1.0, 1.0], [2.0, 1.0], [2.0, 2.0]],
        ] {
            assert_eq!(refusal(&[l_shape], &[outside]), None, "{outside:?}");
        }
        // an island as large as the hole it sits in, but turned: it overlaps the ring
        let turned: &[[f64; 2]] = &[[0.0, -1.5], [1.5, 0.0], [0.0, 1.5], [-1.5, 0.0]];
        assert!(refusal(&[BIG, SQUARE], &[turned]).is_some());
    }

    #[test]
    fn touching_polygons_and_islands_in_holes_are_accepted() {
        let reversed: Vec<[f64; 2]> = SQUARE.iter().rev().copied().collect();
        for (name, a, b) in [
            (
                "sharing an edge",
                &[SQUARE][..],
                &[&[[1.0, -1.0], [2.0, -1.0], [2.0, 1.0], [1.0, 1.0]][..]][..],
            ),
            (
                "sharing part of an edge",
                &[SQUARE],
                &[&[[1.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 2.0]][..]],
            ),
            (
                "sharing a corner",
                &[SQUARE],
                &[&[[1.0, 1.0], [2.0, 1.0], [2.0, 2.0]][..]],
            ),
            (
                "a corner on a side",
                &[SQUARE],
                &[&[[1.0, 0.0], [2.0, -1.0], [2.0, 1.0]][..]],
            ),
            (
                "an island in a hole",
                &[BIG, SQUARE],
                &[&[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]][..]],
            ),
            ("an island filling its hole", &[BIG, SQUARE], &[SQUARE]),
            ("the same, clockwise", &[BIG, SQUARE], &[&reversed[..]]),
            (
                "apart",
                &[SQUARE],
                &[&[[3.0, 3.0], [4.0, 3.0], [4.0, 4.0]][..]],
            ),
        ] {
            assert_eq!(refusal(a, b), None, "{name}");
        }
    }

    /// The refusal of `points` (Euclidean unless given) among the polygons `rings` in
    /// `mode`: the point's index and the message; `None` when accepted.
    fn point_refusal(
        polygons: &[&[&[[f64; 2]]]],
        points: &[([f64; 2], Metric)],
        mode: Mode,
    ) -> Option<(usize, String)> {
        let mut sites: Vec<Site> = polygons.iter().map(|p| polygon(p)).collect();
        sites.extend(points.iter().map(|([x, y], metric)| {
            Site::new(SiteKind::Point {
                at: Point::new(*x, *y),
                metric: metric.clone(),
            })
        }));
        points_inside_polygons(&sites, mode).err().map(|e| {
            assert_eq!(e.field(), Some("at"), "{e}");
            (e.site_index().unwrap(), e.to_string())
        })
    }

    #[test]
    fn points_inside_solid_polygons_are_refused() {
        let hole: &[[f64; 2]] = &[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
        let island: &[[f64; 2]] = &[[-0.25, -0.25], [0.25, -0.25], [0.25, 0.25], [-0.25, 0.25]];
        let below = 1.0f64.next_down();
        for mode in [Mode::Voronoi, Mode::Complex] {
            for (name, polygons, at, by) in [
                ("inside", &[&[SQUARE][..]][..], [0.2, 0.3], 0),
                ("an ulp inside a side", &[&[SQUARE][..]], [below, 0.3], 0),
                (
                    "in the ring around a hole",
                    &[&[BIG, hole][..]],
                    [1.0, 1.0],
                    0,
                ),
                (
                    "on an island in a hole",
                    &[&[BIG, hole][..], &[island]],
                    [0.1, 0.0],
                    1,
                ),
            ] {
                let (site, m) = point_refusal(
                    polygons,
                    &[([5.0, 5.0], Metric::Euclidean), (at, Metric::Euclidean)],
                    mode,
                )
                .unwrap_or_else(|| panic!("{name}: accepted"));
                assert_eq!(site, polygons.len() + 1, "{name}: {m}");
                assert!(
                    m.contains(&format!("inside polygon site {by}")),
                    "{name}: {m}"
                );
                assert!(m.contains(mode.name()), "{name}: {m}");
            }
            let lp = Metric::Lp { p: 4 };
            assert!(point_refusal(&[&[SQUARE]], &[([0.0, 0.0], lp)], mode).is_some());
        }
        // in medial_axis mode the diagram is the one inside: the point is an obstacle
        assert_eq!(
            point_refusal(
                &[&[SQUARE]],
                &[([0.2, 0.3], Metric::Euclidean)],
                Mode::MedialAxis
            ),
            None
        );
    }

    #[test]
    fn points_on_outside_or_in_holes_of_polygons_are_accepted() {
        let hole: &[[f64; 2]] = &[[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
        let above = 1.0f64.next_up();
        for (name, polygons, at) in [
            ("on a corner", &[&[SQUARE][..]][..], [1.0, 1.0]),
            ("on a side", &[&[SQUARE][..]], [1.0, 0.3]),
            ("an ulp outside a side", &[&[SQUARE][..]], [above, 0.3]),
            ("in a hole", &[&[BIG, hole][..]], [0.0, 0.0]),
            ("on a hole's side", &[&[BIG, hole][..]], [0.5, 0.1]),
            ("outside", &[&[SQUARE][..]], [3.0, 0.0]),
        ] {
            assert_eq!(
                point_refusal(polygons, &[(at, Metric::Euclidean)], Mode::Voronoi),
                None,
                "{name}"
            );
        }
        // a power point's field is negative around it: it may have a cell inside
        let power = Metric::Power { weight: 0.5 };
        assert_eq!(
            point_refusal(&[&[SQUARE]], &[([0.0, 0.0], power)], Mode::Voronoi),
            None
        );
    }
}
