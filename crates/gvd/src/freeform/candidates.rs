//! The pairs of features that may share a Voronoi edge inside the domain, by a
//! conservative grid test: if `P` is equidistant (`D`) from features `a`, `b` and no
//! feature is nearer, then at the grid point `q` of its cell (`|P − q| ≤ ρ`)
//! `dist(q, a) ≤ D + ρ ≤ min_k dist(q, k) + 2ρ`. With lower bounds `ℓ` (the sampled
//! distance minus half the longest sample step) and upper bounds `u` (the sampled
//! distance) of the distances, `a` and `b` are candidates at `q` when
//! `ℓ(q, a) ≤ min_k u(q, k) + 2ρ`. Every pair on the diagram is found.

use super::nearest::Features;
use super::pieces::{Feature, JOIN};
use crate::geom::grid::bounds_of_points;
use crate::geom::{Aabb, Point};

/// Grid points per side.
const GRID: usize = 96;
/// Samples per span.
const SAMPLES: usize = 32;

/// `b.outside_distance(q)`, or `None` when it is certainly above `bound`: its larger
/// component is, by more than the rounding of `hypot` (spared then).
fn outside_unless_above(b: &Aabb, q: Point, bound: f64) -> Option<f64> {
    let dx = (b.min.x - q.x).max(q.x - b.max.x).max(0.0);
    let dy = (b.min.y - q.y).max(q.y - b.max.y).max(0.0);
    if dx.max(dy) > bound * (1.0 + 4.0 * f64::EPSILON) {
        return None;
    }
    Some(b.outside_distance(q))
}

/// The least squared distance from `q` to `pts` (`∞` for none; NaNs skipped, as by
/// `f64::min`), in four independent lanes: a plain comparison per sample instead of
/// `f64::min`'s NaN handling, the same least value (a minimum does not round).
fn least_dist2(q: Point, pts: &[Point]) -> f64 {
    let less = |m: f64, d: f64| if d < m { d } else { m };
    let mut lanes = [f64::INFINITY; 4];
    let mut chunks = pts.chunks_exact(4);
    for chunk in &mut chunks {
        for (m, p) in lanes.iter_mut().zip(chunk) {
            *m = less(*m, p.dist2(q));
        }
    }
    let rest = chunks.remainder().iter().map(|p| p.dist2(q));
    lanes.into_iter().chain(rest).fold(f64::INFINITY, less)
}

/// A feature's samples with what the grid test needs of them.
struct Sampled {
    feature: Feature,
    pts: Vec<Point>,
    /// Half the longest step: the curve is within it of a sample.
    slack: f64,
    /// The control box (the curve lies in it).
    bbox: Aabb,
    /// The samples' bounding box.
    hull: Aabb,
}

/// Grid points per side of a block: the features that cannot matter anywhere in a
/// block are set aside once for its points.
const BLOCK: usize = 4;

/// Relative slack over the rounding of the distances compared below (a few ulps).
const ROUNDING: f64 = 1e-12;

/// A lower bound of every sampled distance (`least_dist2(q, pts).sqrt()`) from a point
/// of `rect` to samples in `hull`: the exact distance between the boxes is below the
/// exact distances, and those are within a few ulps of the computed ones.
fn below_sampled(hull: &Aabb, rect: &Aabb) -> f64 {
    let dx = (hull.min.x - rect.max.x)
        .max(rect.min.x - hull.max.x)
        .max(0.0);
    let dy = (hull.min.y - rect.max.y)
        .max(rect.min.y - hull.max.y)
        .max(0.0);
    dx.hypot(dy) * (1.0 - ROUNDING)
}

/// The candidate pairs (each once, first < second), excluding pairs that never bound an
/// edge: two features of one site in `voronoi` mode, a corner and the spans that end at
/// it.
///
/// At each grid point the test needs the least sampled distance over all features
/// (`upper`) and, per feature, its control box's distance and its sampled distance. The
/// grid is walked in blocks of [`BLOCK`]² points: a feature whose samples are farther
/// from the whole block than `upper` can be anywhere in it (the least sampled distance
/// at the block's centre plus the centre's distance to its points: sampled distances are
/// 1-Lipschitz) by more than `2ρ` and its slack is neither nearest nor near at any of its
/// points, and is left out there; the others are taken nearest first, and a feature
/// whose samples' box is no nearer than the least distance found so far is not sampled
/// for `upper`. The decisions are those of every feature at every point.
pub fn pairs(features: &Features, domain: &Aabb) -> Vec<[Feature; 2]> {
    let pieces = features.pieces;
    let mut sampled: Vec<Sampled> = Vec::new();
    for (k, s) in pieces.spans.iter().enumerate() {
        let pts = s.curve.sample(SAMPLES);
        // the curve between samples stays within half an arc step of them; the arc is
        // bounded by the control polygon's length per step
        let poly: f64 = s
            .curve
            .control_points()
            .windows(2)
            .map(|w| w[0].dist(w[1]))
            .sum();
        let step = pts.windows(2).map(|w| w[0].dist(w[1])).fold(0.0, f64::max);
        let slack = 0.5 * step.max(poly / SAMPLES as f64 * 2.0);
        let hull = bounds_of_points(pts.iter().copied());
        sampled.push(Sampled {
            feature: Feature::Span(k),
            pts,
            slack,
            bbox: s.bbox,
            hull,
        });
    }
    for &k in &features.active {
        let p = pieces.corners[k].at;
        sampled.push(Sampled {
            feature: Feature::Corner(k),
            pts: vec![p],
            slack: 0.0,
            bbox: Aabb::new(p, p),
            hull: Aabb::new(p, p),
        });
    }
    let (dx, dy) = (domain.width() / GRID as f64, domain.height() / GRID as f64);
    let rho = 0.5 * dx.hypot(dy);
    let join = JOIN * domain.longest_side();
    let grid_point = |i: usize, j: usize| {
        Point::new(
            domain.min.x + (i as f64 + 0.5) * dx,
            domain.min.y + (j as f64 + 0.5) * dy,
        )
    };
    // the nearest sample by squared distance, one square root (no `hypot` per sample)
    let dist = |q: Point, pts: &[Point]| least_dist2(q, pts).sqrt();
    let n = sampled.len();
    // per pair of features: whether it is kept, once decided
    let mut kept: Vec<Option<bool>> = vec![None; n * n];
    let mut out: Vec<[Feature; 2]> = Vec::new();
    // the block's features, nearest first: (lower bound at the centre, index)
    let mut order: Vec<(f64, usize)> = Vec::with_capacity(n);
    let mut distance: Vec<Option<f64>> = Vec::with_capacity(n);
    let mut near: Vec<usize> = Vec::new();
    for bi in (0..GRID).step_by(BLOCK) {
        for bj in (0..GRID).step_by(BLOCK) {
            let (ei, ej) = ((bi + BLOCK).min(GRID), (bj + BLOCK).min(GRID));
            let rect = Aabb::new(grid_point(bi, bj), grid_point(ei - 1, ej - 1));
            let centre = rect.center();
            let reach = 0.5 * rect.width().hypot(rect.height());
            order.clear();
            order.extend((0..n).map(|k| {
                (
                    below_sampled(&sampled[k].hull, &Aabb::new(centre, centre)),
                    k,
                )
            }));
            order.sort_by(|a, b| a.0.total_cmp(&b.0));
            // the least sampled distance at the centre, then a bound of `upper` over
            // the block
            let mut at_centre = f64::INFINITY;
            for &(lower, k) in &order {
                if lower >= at_centre {
                    break;
                }
                at_centre = at_centre.min(dist(centre, &sampled[k].pts));
            }
            let most = (at_centre + reach) * (1.0 + ROUNDING);
            order.retain(|&(_, k)| {
                let s = &sampled[k];
                below_sampled(&s.hull, &rect) <= (most + 2.0 * rho + s.slack) * (1.0 + ROUNDING)
            });
            for i in bi..ei {
                for j in bj..ej {
                    let q = grid_point(i, j);
                    distance.clear();
                    distance.resize(order.len(), None);
                    let mut upper = f64::INFINITY;
                    for (d, &(_, k)) in distance.iter_mut().zip(&order) {
                        let s = &sampled[k];
                        if s.hull.outside_distance(q) * (1.0 - ROUNDING) >= upper {
                            continue;
                        }
                        let dk = dist(q, &s.pts);
                        *d = Some(dk);
                        upper = upper.min(dk);
                    }
                    near.clear();
                    let bound = upper + 2.0 * rho;
                    for (d, &(_, k)) in distance.iter().zip(&order) {
                        let s = &sampled[k];
                        if outside_unless_above(&s.bbox, q, bound).is_some_and(|o| o <= bound)
                            && d.unwrap_or_else(|| dist(q, &s.pts)) - s.slack <= bound
                        {
                            near.push(k);
                        }
                    }
                    for x in 0..near.len() {
                        for y in x + 1..near.len() {
                            let (a, b) = (near[x].min(near[y]), near[x].max(near[y]));
                            let (f, g) = (sampled[a].feature, sampled[b].feature);
                            let decided = &mut kept[a * n + b];
                            if decided.is_none() {
                                let keep = keep(features, f, g, join);
                                if keep {
                                    out.push(if f < g { [f, g] } else { [g, f] });
                                }
                                *decided = Some(keep);
                            }
                        }
                    }
                }
            }
        }
    }
    out.sort();
    out
}

fn keep(features: &Features, f: Feature, g: Feature, join: f64) -> bool {
    let pieces = features.pieces;
    let (sf, sg) = (pieces.site(f), pieces.site(g));
    let touches = |c: usize, s: usize| {
        let (c, s) = (&pieces.corners[c], &pieces.spans[s].curve);
        c.at.dist(s.eval(0.0)) <= join || c.at.dist(s.eval(1.0)) <= join
    };
    if !pieces.featured {
        // a site's corner at an end of another site's span is a point of that site,
        // never strictly nearer than it: the two tie in the corner's normal cone, and
        // their bisector only bounds that tie (SCENE_FORMAT.md: either site may name a
        // shared end's region), as at a corner of two straight sites, where it is empty
        return sf != sg
            && match (f, g) {
                (Feature::Corner(c), Feature::Span(s)) | (Feature::Span(s), Feature::Corner(c)) => {
                    !touches(c, s)
                }
                _ => true,
            };
    }
    // a corner and the spans that end at it (its own, or those of a site joined there)
    // meet only at the corner
    match (f, g) {
        (Feature::Corner(c), Feature::Span(s)) | (Feature::Span(s), Feature::Corner(c)) => {
            !touches(c, s)
        }
        _ => true,
    }
}
