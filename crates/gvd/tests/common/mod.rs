//! Brute-force distances of points, segments, arcs, polylines and polygons, computed
//! directly from the scene's definitions (no code shared with the engines), for the
//! integration tests of the incremental engine.
#![allow(dead_code)] // each test file uses its own subset

use gvd::complex::{FeatureKind, Generator};
use gvd::geom::Point;
use gvd::scene::{Mode, SiteKind};
use gvd::Scene;

/// The distance from `q` to the closed segment `[a, b]` (to `a` when `a = b`).
pub fn seg_dist(q: Point, a: Point, b: Point) -> f64 {
    let d = b - a;
    if d.dot(d) == 0.0 {
        return q.dist(a);
    }
    let t = ((q - a).dot(d) / d.dot(d)).clamp(0.0, 1.0);
    q.dist(a + d * t)
}

/// Corners and edges of a site with features, as (corner points, edges as corner
/// index pairs); an arc has its two ends as corners and no edges.
pub fn features(kind: &SiteKind) -> (Vec<Point>, Vec<(usize, usize)>) {
    match kind {
        SiteKind::Point { at, .. } => (vec![*at], vec![]),
        SiteKind::Segment { from, to } => (vec![*from, *to], vec![(0, 1)]),
        SiteKind::Polyline { points } => (
            points.clone(),
            (1..points.len()).map(|k| (k - 1, k)).collect(),
        ),
        SiteKind::Polygon { rings } => {
            let (mut pts, mut edges) = (Vec::new(), Vec::new());
            for ring in rings {
                let base = pts.len();
                for k in 0..ring.len() {
                    edges.push((base + k, base + (k + 1) % ring.len()));
                }
                pts.extend_from_slice(ring);
            }
            (pts, edges)
        }
        &SiteKind::Arc {
            center,
            radius,
            start_angle,
            end_angle,
        } => (
            arc_ends(center, radius, start_angle, end_angle).to_vec(),
            vec![],
        ),
        _ => panic!("not a linear site or an arc"),
    }
}

pub fn inside_polygon(q: Point, rings: &[Vec<Point>]) -> bool {
    let mut inside = false;
    for ring in rings {
        for k in 0..ring.len() {
            let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
            if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x) {
                inside = !inside;
            }
        }
    }
    inside
}

/// The ends of the arc of centre `c` and radius `r` from angle `start` to `end`,
/// computed as the scene's reader does (the end at `start` plus the counter-clockwise
/// span), so that another site can name the same point bit for bit.
pub fn arc_ends(c: Point, r: f64, start: f64, end: f64) -> [Point; 2] {
    let span = (end - start).rem_euclid(std::f64::consts::TAU);
    [start, start + span].map(|a| c + Point::new(a.cos(), a.sin()) * r)
}

/// The distance from `q` to that arc, counter-clockwise from `start` to `end`: to its
/// circle where the ray from `c` through `q` meets the arc, else to the nearer end.
pub fn arc_dist(q: Point, c: Point, r: f64, start: f64, end: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let span = (end - start).rem_euclid(tau);
    let angle = ((q.y - c.y).atan2(q.x - c.x) - start).rem_euclid(tau);
    if angle <= span {
        (q.dist(c) - r).abs()
    } else {
        let [a, b] = arc_ends(c, r, start, end);
        q.dist(a).min(q.dist(b))
    }
}

/// The distance from `q` to generator `g` of the scene.
pub fn dist(s: &Scene, g: &Generator, q: Point) -> f64 {
    if let SiteKind::Arc {
        center,
        radius,
        start_angle,
        end_angle,
    } = s.sites()[g.site()].kind
    {
        return match *g {
            Generator::Feature {
                feature: FeatureKind::Corner,
                index,
                ..
            } => q.dist(arc_ends(center, radius, start_angle, end_angle)[index]),
            _ => arc_dist(q, center, radius, start_angle, end_angle),
        };
    }
    match *g {
        Generator::Site(i) => {
            let kind = &s.sites()[i].kind;
            if let SiteKind::Polygon { rings } = kind {
                if inside_polygon(q, rings) {
                    return 0.0;
                }
            }
            let (pts, edges) = features(kind);
            let corners = pts.iter().map(|p| q.dist(*p));
            let sides = edges.iter().map(|&(a, b)| seg_dist(q, pts[a], pts[b]));
            corners.chain(sides).fold(f64::INFINITY, f64::min)
        }
        Generator::Feature {
            site,
            feature,
            index,
        } => {
            let (pts, edges) = features(&s.sites()[site].kind);
            match feature {
                FeatureKind::Corner => q.dist(pts[index]),
                _ => {
                    let (a, b) = edges[index];
                    seg_dist(q, pts[a], pts[b])
                }
            }
        }
    }
}

/// Every generator of the scene in its mode.
pub fn generators(s: &Scene) -> Vec<Generator> {
    let mut out = Vec::new();
    for (i, site) in s.sites().iter().enumerate() {
        match (&site.kind, s.mode()) {
            (SiteKind::Point { .. }, _) | (_, Mode::Voronoi) => out.push(Generator::Site(i)),
            (kind, _) => {
                let (pts, edges) = features(kind);
                for k in 0..pts.len() {
                    out.push(Generator::Feature {
                        site: i,
                        feature: FeatureKind::Corner,
                        index: k,
                    });
                }
                for k in 0..edges.len() {
                    out.push(Generator::Feature {
                        site: i,
                        feature: FeatureKind::Edge,
                        index: k,
                    });
                }
                if let SiteKind::Arc { .. } = kind {
                    out.push(Generator::Feature {
                        site: i,
                        feature: FeatureKind::Piece,
                        index: 0,
                    });
                }
            }
        }
    }
    out
}

/// The site pairs of a diagram's edges, each sorted, as a sorted list without repeats.
pub fn edge_pairs(d: &gvd::VoronoiComplex) -> Vec<[usize; 2]> {
    let mut pairs: Vec<[usize; 2]> = d
        .edges
        .iter()
        .map(|e| {
            let (a, b) = (e.sites[0].site(), e.sites[1].site());
            [a.min(b), a.max(b)]
        })
        .collect();
    pairs.sort();
    pairs.dedup();
    pairs
}
