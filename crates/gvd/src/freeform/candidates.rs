//! The pairs of features that may share a Voronoi edge inside the domain, by a
//! conservative grid test: if `P` is equidistant (`D`) from features `a`, `b` and no
//! feature is nearer, then at the grid point `q` of its cell (`|P − q| ≤ ρ`)
//! `dist(q, a) ≤ D + ρ ≤ min_k dist(q, k) + 2ρ`. With lower bounds `ℓ` (the sampled
//! distance minus half the longest sample step) and upper bounds `u` (the sampled
//! distance) of the distances, `a` and `b` are candidates at `q` when
//! `ℓ(q, a) ≤ min_k u(q, k) + 2ρ`. Every pair on the diagram is found.

use super::nearest::Features;
use super::pieces::{Feature, JOIN};
use crate::geom::{Aabb, Point};
use std::collections::BTreeSet;

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

/// The candidate pairs (each once, first < second), excluding pairs that never bound an
/// edge: two features of one site in `voronoi` mode, a corner and the spans that end at
/// it.
pub fn pairs(features: &Features, domain: &Aabb) -> Vec<[Feature; 2]> {
    let pieces = features.pieces;
    // (feature, samples, half the longest step, box)
    let mut sampled: Vec<(Feature, Vec<Point>, f64, Aabb)> = Vec::new();
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
        sampled.push((Feature::Span(k), pts, slack, s.bbox));
    }
    for &k in &features.active {
        let p = pieces.corners[k].at;
        sampled.push((Feature::Corner(k), vec![p], 0.0, Aabb::new(p, p)));
    }
    let (dx, dy) = (domain.width() / GRID as f64, domain.height() / GRID as f64);
    let rho = 0.5 * dx.hypot(dy);
    let join = JOIN * domain.longest_side();
    // the nearest sample by squared distance, one square root (no `hypot` per sample)
    let dist = |q: Point, pts: &[Point]| least_dist2(q, pts).sqrt();
    let mut out: BTreeSet<[Feature; 2]> = BTreeSet::new();
    let mut near: Vec<usize> = Vec::new();
    // per feature at the current grid point: (distance to its box unless above the
    // nearest sample found before it, sampled distance if already computed)
    let mut known: Vec<(Option<f64>, Option<f64>)> = Vec::with_capacity(sampled.len());
    for i in 0..GRID {
        for j in 0..GRID {
            let q = Point::new(
                domain.min.x + (i as f64 + 0.5) * dx,
                domain.min.y + (j as f64 + 0.5) * dy,
            );
            known.clear();
            let mut upper = f64::INFINITY;
            for (_, pts, _, b) in &sampled {
                let outside = outside_unless_above(b, q, upper);
                let mut sampled_distance = None;
                if outside.is_some_and(|o| o < upper) {
                    let d = dist(q, pts);
                    sampled_distance = Some(d);
                    upper = upper.min(d);
                }
                known.push((outside, sampled_distance));
            }
            near.clear();
            let bound = upper + 2.0 * rho;
            for (k, ((_, pts, slack, b), &(outside, d))) in sampled.iter().zip(&known).enumerate() {
                let outside = outside.or_else(|| outside_unless_above(b, q, bound));
                if outside.is_some_and(|o| o <= bound)
                    && d.unwrap_or_else(|| dist(q, pts)) - slack <= bound
                {
                    near.push(k);
                }
            }
            for x in 0..near.len() {
                for y in x + 1..near.len() {
                    let (f, g) = (sampled[near[x]].0, sampled[near[y]].0);
                    if keep(features, f, g, join) {
                        out.insert(if f < g { [f, g] } else { [g, f] });
                    }
                }
            }
        }
    }
    out.into_iter().collect()
}

fn keep(features: &Features, f: Feature, g: Feature, join: f64) -> bool {
    let pieces = features.pieces;
    let (sf, sg) = (pieces.site(f), pieces.site(g));
    if !pieces.featured {
        return sf != sg;
    }
    // a corner and the spans that end at it (its own, or those of a site joined there)
    // meet only at the corner
    let touches = |c: usize, s: usize| {
        let (c, s) = (&pieces.corners[c], &pieces.spans[s].curve);
        c.at.dist(s.eval(0.0)) <= join || c.at.dist(s.eval(1.0)) <= join
    };
    match (f, g) {
        (Feature::Corner(c), Feature::Span(s)) | (Feature::Span(s), Feature::Corner(c)) => {
            !touches(c, s)
        }
        _ => true,
    }
}
