//! The free-form engine (HREK07): Voronoi diagrams of rational Bézier and B-spline
//! curves by bisectors in parameter space, without approximating the curves.
//!
//! Phases, one file each: the curves are cut into C1 rational Bézier spans and corners
//! ([`pieces`]); every pair of features that may share a Voronoi edge (a conservative
//! grid test, [`candidates`]) gets its bisector: for two spans the zero set of
//! `F3(t, r)` ([`bisector`]) split into monotone branches ([`trace`]), for a corner and
//! a span the rational point/curve bisector `B(t)` (eq. 29), for two corners their
//! perpendicular bisector, for two spans of joined sites meeting without a corner their
//! common normal at the joint; each branch is trimmed by the orientation and curvature
//! constraints and the lower envelope ([`trim`]); the runs are assembled into the
//! complex ([`assemble`]), those of two spans that stop by a corner generating nothing
//! (the curve convex there) ending at a vertex on it. Lines are spans of degree 1. Distances to the features are certified univariate root
//! isolations ([`nearest`]).
//!
//! A corner is *active* when its normal cone `{v : ⟨v, t_in⟩ ≥ 0, ⟨v, t_out⟩ ≤ 0}`
//! reaches the side of the curve where the diagram lies; the cone's middle direction
//! `t_in − t_out` is on the left of the arriving tangent iff `t_in × t_out < 0`.

mod assemble;
pub(crate) mod bisector;
mod candidates;
mod feet;
pub(crate) mod nearest;
pub(crate) mod pieces;
mod trace;
mod trim;

use crate::complex::cells;
use crate::complex::VoronoiComplex;
use crate::control::Watch;
use crate::error::Error;
use crate::geom::Point;
use crate::scene::{Scene, SiteKind};
pub(crate) use feet::with_feet;
use nearest::Features;
use pieces::Feature;
use trim::{Constraints, Eval, Run, Trimmer};

/// True when every site is a free-form curve (`bezier`, `bspline`).
pub fn supports(scene: &Scene) -> bool {
    !scene.sites().is_empty()
        && scene
            .sites()
            .iter()
            .all(|s| matches!(s.kind, SiteKind::Bezier { .. } | SiteKind::Bspline { .. }))
}

/// The chord tolerance of the output polylines: a quarter of the scene's epsilon.
fn chord(scene: &Scene) -> f64 {
    0.25 * scene.epsilon()
}

/// Most samples evaluated over all bisector branches of one scene.
const MAX_SAMPLES: usize = 4_000_000;

/// The Voronoi diagram of a scene of free-form curves.
pub fn compute(scene: &Scene, watch: &Watch) -> Result<VoronoiComplex, Error> {
    compute_with(scene, Constraints::default(), watch)
}

/// [`compute`] with some trimming constraints switched off (for tests); `watch` stops
/// the run early (checked per pair of pieces).
pub fn compute_with(
    scene: &Scene,
    constraints: Constraints,
    watch: &Watch,
) -> Result<VoronoiComplex, Error> {
    let start = std::time::Instant::now();
    if let Some((i, s)) = scene
        .sites()
        .iter()
        .enumerate()
        .find(|(_, s)| !matches!(s.kind, SiteKind::Bezier { .. } | SiteKind::Bspline { .. }))
    {
        return Err(Error::Unsupported {
            site: i,
            kind: s.kind.name().to_string(),
            message: "the freeform engine computes bezier and bspline curves only (so far)".into(),
        });
    }
    if let Some(s) = scene.unit_scale() {
        // far from unit size, squared distances overflow or underflow: compute at an
        // exact power-of-two scale and scale back
        let mut c = compute_with(&scene.scaled(s), constraints, watch)?;
        c.scale(1.0 / s);
        c.stats.insert("rescaled_by".into(), serde_json::json!(s));
        return Ok(c);
    }
    let pieces = pieces::pieces(scene);
    if pieces.spans.is_empty() {
        return Err(Error::scene("sites", "no free-form curve to compute"));
    }
    pieces::check_region(scene, &pieces)?;
    let features = Features::new(&pieces);
    let domain = scene.domain();
    // distances are compared, and run ends meet, relative to the domain, but no more
    // than four times the curves' extent: a domain far larger than the curves (±1e7
    // about a curve of size 2) would merge every run end into one vertex otherwise
    let extent = pieces
        .spans
        .iter()
        .map(|s| s.bbox)
        .reduce(|a, b| a.union(&b))
        .map_or(0.0, |b| b.longest_side());
    let size = domain.longest_side().min(4.0 * extent);
    let trimmer = Trimmer {
        features: &features,
        domain,
        size,
        chord: chord(scene),
        step: domain.longest_side() / 64.0,
        tol: 1e-9 * size,
        constraints,
        samples: std::cell::Cell::new(0),
        max_samples: MAX_SAMPLES,
        watch: watch.clone(),
    };
    let pairs = candidates::pairs(&features, &domain);
    let mut runs: Vec<Run> = Vec::new();
    let mut stats = trace::TraceStats::default();
    let mut branches = 0usize;
    let mut trace_seconds = 0.0;
    let forms = &features.forms;
    watch.stage("pairs", Some(pairs.len() as u64));
    for &[f, g] in &pairs {
        watch.tick(1);
        watch.check()?;
        match (f, g) {
            (Feature::Span(a), Feature::Span(b)) => {
                let (ca, cb) = (&pieces.spans[a].curve, &pieces.spans[b].curve);
                let f3 = bisector::f3(&forms[a], &forms[b]);
                let clock = std::time::Instant::now();
                let units = [ca, cb].map(|c| c.control_box().longest_side());
                let found = trace::branches(&f3, &bisector::shared_ends(ca, cb), units, &mut stats);
                trace_seconds += clock.elapsed().as_secs_f64();
                for br in found {
                    branches += 1;
                    let eval = |t: f64| -> Option<Eval> {
                        let r = trace::branch_at(&f3, &br, t)?;
                        if ca.eval(t).dist(cb.eval(r)) <= trimmer.tol {
                            // the feet meet (adjacent spans at a curvature extremum):
                            // the ridge ends at the centre of curvature
                            return bisector::ridge_end(ca, t, cb, r, trimmer.tol);
                        }
                        // two lines: parallel ones have parallel normals all along
                        let p = if ca.degree() == 1 && cb.degree() == 1 {
                            bisector::equidistant_on_normal(ca, t, cb, r)?
                        } else {
                            bisector::normals_meet(ca, t, cb, r)?
                        };
                        Some(Eval {
                            p,
                            d: 0.5 * (p.dist(ca.eval(t)) + p.dist(cb.eval(r))),
                            feet: [Some(t), Some(r)],
                            at_ends: false,
                        })
                    };
                    runs.extend(trimmer.trim([f, g], &eval, br.slab, 8, 1.0));
                }
            }
            (Feature::Corner(c), Feature::Span(b)) | (Feature::Span(b), Feature::Corner(c)) => {
                let p = pieces.corners[c].at;
                let cb = &pieces.spans[b].curve;
                branches += 1;
                let eval = |t: f64| -> Option<Eval> {
                    let q = bisector::point_curve(cb, t, p)?;
                    Some(Eval {
                        p: q,
                        d: q.dist(p),
                        feet: [None, Some(t)],
                        at_ends: false,
                    })
                };
                runs.extend(trimmer.trim(
                    [Feature::Corner(c), Feature::Span(b)],
                    &eval,
                    (0.0, 1.0),
                    32,
                    1.0,
                ));
            }
            (Feature::Corner(c0), Feature::Corner(c1)) => {
                let (p0, p1) = (pieces.corners[c0].at, pieces.corners[c1].at);
                let m = (p0 + p1) * 0.5;
                let dir = (p1 - p0).perp();
                let Some((s0, s1)) = domain.line_range(m, dir) else {
                    continue;
                };
                branches += 1;
                let eval = |s: f64| -> Option<Eval> {
                    let q = m + dir * s;
                    Some(Eval {
                        p: q,
                        d: q.dist(p0),
                        feet: [None, None],
                        at_ends: false,
                    })
                };
                runs.extend(trimmer.trim([f, g], &eval, (s0, s1), 16, s1 - s0));
            }
        }
    }
    // the edges along the common normals of joints without a corner
    for j in &pieces.joints {
        let Some((s0, s1)) = domain.line_range(j.at, j.normal) else {
            continue;
        };
        let s0 = if j.both { s0 } else { s0.max(0.0) };
        if s1 <= s0 {
            continue;
        }
        branches += 1;
        let eval = |s: f64| -> Option<Eval> {
            Some(Eval {
                p: j.at + j.normal * s,
                d: s.abs(),
                feet: j.feet.map(Some),
                at_ends: true,
            })
        };
        let pair = j.spans.map(Feature::Span);
        runs.extend(trimmer.trim(pair, &eval, (s0, s1), 16, s1 - s0));
    }
    watch.check()?;
    if trimmer.samples.get() >= MAX_SAMPLES {
        return Err(Error::Budget {
            what: "points".into(),
            limit: MAX_SAMPLES,
            message: format!(
                "the freeform engine evaluated {MAX_SAMPLES} bisector samples without finishing (a scene of many or very wiggly curves?)"
            ),
        });
    }
    assemble::reach_corners(&pieces, &mut runs, 1e-7 * size, trimmer.chord);
    let (mut complex, loose) = assemble::assemble(&pieces, runs, 1e-7 * size, trimmer.chord);
    if !pieces.featured {
        complex.cells = cells::build_cells(&complex, &domain, &|q: Point| {
            features.nearest(q).map_or(0, |(f, _)| pieces.site(f))
        });
    }
    let s = &mut complex.stats;
    s.insert("engine".into(), serde_json::json!("freeform"));
    s.insert("spans".into(), serde_json::json!(pieces.spans.len()));
    s.insert("corners".into(), serde_json::json!(features.active.len()));
    s.insert("pairs".into(), serde_json::json!(pairs.len()));
    s.insert("branches".into(), serde_json::json!(branches));
    s.insert("special_points".into(), serde_json::json!(stats.special));
    s.insert(
        "uncertified_special_points".into(),
        serde_json::json!(stats.uncertified),
    );
    s.insert("samples".into(), serde_json::json!(trimmer.samples.get()));
    s.insert("loose_ends".into(), serde_json::json!(loose));
    s.insert("seconds_trace".into(), serde_json::json!(trace_seconds));
    s.insert(
        "seconds".into(),
        serde_json::json!(start.elapsed().as_secs_f64()),
    );
    Ok(complex)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::ring::even_odd_contains;

    fn scene(name: &str) -> Scene {
        let path = format!("{}/tests/data/freeform/{name}", env!("CARGO_MANIFEST_DIR"));
        Scene::from_json(&std::fs::read_to_string(path).unwrap()).unwrap()
    }

    /// Edge points inside a closed site, and edge points not on the diagram: unequal
    /// distances to the edge's two sites, or a third site nearer, by more than epsilon
    /// (`voronoi` mode).
    fn faults(sc: &Scene, d: &VoronoiComplex) -> (usize, usize) {
        let pieces = pieces::pieces(sc);
        let features = Features::new(&pieces);
        let rings: Vec<Vec<Point>> = (0..sc.sites().len())
            .map(|i| {
                pieces
                    .spans
                    .iter()
                    .filter(|s| s.site == i)
                    .flat_map(|s| s.curve.sample(64))
                    .collect()
            })
            .collect();
        let (mut inside, mut nearer) = (0, 0);
        for e in &d.edges {
            for &q in &e.points {
                if rings.iter().any(|r| even_odd_contains(r, q)) {
                    inside += 1;
                }
                let site_distance = |i: usize| {
                    (0..pieces.spans.len())
                        .filter(|&k| pieces.spans[k].site == i)
                        .map(|k| features.span_distance(k, q).0)
                        .fold(f64::INFINITY, f64::min)
                };
                let (di, dj) = (
                    site_distance(e.sites[0].site()),
                    site_distance(e.sites[1].site()),
                );
                let best = features.nearest(q).map_or(f64::INFINITY, |(_, d)| d);
                if (di - dj).abs() > sc.epsilon() || best < di.min(dj) - sc.epsilon() {
                    nearer += 1;
                }
            }
        }
        (inside, nearer)
    }

    #[test]
    fn the_lower_envelope_leaves_only_nearest_points() {
        let sc = scene("freeform-nonconvex2-voronoi.json");
        assert_eq!(
            faults(&sc, &compute(&sc, &Watch::default()).unwrap()),
            (0, 0)
        );
    }
}
