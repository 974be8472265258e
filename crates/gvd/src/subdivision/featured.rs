//! `complex` and `medial_axis` modes over distance fields where curves have features
//! (SYMW11's problem, the medial axis of regions bounded by closed algebraic curves;
//! HREK07's free-form curves by their pieces and corners). The diagram is that of the
//! sites' pieces ([`FeatureFields`]: each curve cut into arcs with no ridge of their
//! own), kept where it belongs to the mode's diagram ([`FeatureFields::keeps`]: inside
//! the regions in `medial_axis` mode, off the solid side of closed free-form curves in
//! `complex` mode), and rid of the zone boundaries between pieces: the edges of a
//! corner and the pieces ending at it, and the points whose nearest point on two pieces
//! of one generator is their shared smooth end (within the resolution of the normal
//! there, up to the centre of curvature: [`ZoneEnd`](crate::site::zone::ZoneEnd); where
//! two sites join smoothly, that normal separates two generators and stays). What remains are the
//! points whose distance is reached at two distinct points of different features or of
//! one feature: the features' diagram, ridges included. Pieces are named by the
//! generators they belong to (a ridge of one piece lists it twice).

use super::{run_watched, trace, Output, Params};
use crate::complex::prune::keep_passing;
use crate::complex::{Edge, Generator, Vertex, VoronoiComplex};
use crate::control::Watch;
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::scene::Scene;
use crate::site::featured::{FeatureFields, Keep};
use crate::site::{DistanceField, FieldOptions, SiteField};
use serde_json::json;

/// Ends of two pieces within this fraction of the domain's size are their shared end
/// (each piece computes it to about 1e-15 of its box).
const SHARED_END: f64 = 1e-9;

/// Computes the diagram of `scene`'s features (mode `complex` or `medial_axis`, sites
/// the subdivision engine takes, among them algebraic and free-form curves).
pub(crate) fn run(
    scene: &Scene,
    field_options: &FieldOptions,
    params: &Params,
    watch: &Watch,
) -> Result<Output, Error> {
    let m = FeatureFields::for_scene(scene, field_options)?;
    // the medial axis of curves lies inside them: no need to subdivide the rest
    let near_curves = m.region_box.and_then(|b| {
        let margin = 2.0 * params.epsilon;
        let grown = Aabb::new(
            b.min - Point::new(margin, margin),
            b.max + Point::new(margin, margin),
        );
        params.domain.intersection(&grown)
    });
    let params = &Params {
        domain: near_curves.unwrap_or(params.domain),
        ..*params
    };
    let mut out = run_watched(&m.fields, params, watch)?;
    let size = params.domain.longest_side();
    let resolution = out
        .complex
        .stats
        .get("resolution")
        .and_then(|v| v.as_f64())
        .unwrap_or(params.epsilon);
    let on_curve = 1e-9 * size;
    let passes = |e: &Edge, q: Point| {
        let [a, b] = e.sites.map(|g| g.site());
        m.keeps(a, q, on_curve)
            && m.keeps(b, q, on_curve)
            && !m.zone_neighbours[a].contains(&b)
            && !(m.generators[a] == m.generators[b]
                && m.ends[a].iter().any(|end| {
                    m.ends[b]
                        .iter()
                        .any(|other| end.at.dist(other.at) <= SHARED_END * size)
                        && end.zone_holds(q, resolution)
                }))
    };
    keep_passing(&mut out.complex, &passes, resolution / 4.0, &|_, _| None);
    snap_ends(&mut out.complex, &m, resolution);
    follow_ridges(&mut out.complex, &m, params.epsilon / 8.0, size);
    name_generators(&mut out.complex, &m);
    split_at_changes(&mut out.complex);
    out.complex.cells.clear();
    out.complex
        .stats
        .insert("feature_fields".into(), json!(m.fields.len()));
    Ok(out)
}

/// Moves each end of the diagram (a vertex of degree one) within `tol` of where such
/// an end truly lies to there. A ridge ends at a centre of curvature of a piece end:
/// the cut on the zone boundary lies on the simplified polyline, up to a fraction of
/// the resolution aside, and near a vertex of the curve the nearest point is flat to
/// fourth order, so that much aside puts the foot, and its centre of curvature, several
/// resolutions away. An edge that reaches a corner ends there, and its end lists the
/// corner (the subdivision stops a box short of it). Edges left without length (a
/// stub at a corner, shorter than the cut's tolerance) go.
fn snap_ends(complex: &mut VoronoiComplex, m: &FeatureFields, tol: f64) {
    let mut degree = vec![0usize; complex.vertices.len()];
    for e in &complex.edges {
        for v in [e.from, e.to].into_iter().flatten() {
            degree[v] += 1;
        }
    }
    let centres = m
        .ends
        .iter()
        .flatten()
        .flat_map(|e| e.centres())
        .map(|c| (c, None));
    let corners = m
        .fields
        .iter()
        .enumerate()
        .filter_map(|(k, f)| match (f, &m.keep[k]) {
            (SiteField::Euclidean(p), Keep::Corner { .. }) => Some((p.at, Some(k))),
            _ => None,
        });
    let targets: Vec<(Point, Option<usize>)> = centres.chain(corners).collect();
    for (v, vertex) in complex.vertices.iter_mut().enumerate() {
        if degree[v] != 1 {
            continue;
        }
        let nearest = targets
            .iter()
            .min_by(|a, b| a.0.dist(vertex.at).total_cmp(&b.0.dist(vertex.at)));
        if let Some(&(at, corner)) = nearest.filter(|t| t.0.dist(vertex.at) <= tol) {
            vertex.at = at;
            if let Some(g) = corner.map(Generator::Site) {
                if !vertex.sites.contains(&g) {
                    vertex.sites.push(g);
                }
            }
        }
    }
    for e in &mut complex.edges {
        let mut points = e.points.to_vec();
        if let (Some(v), Some(first)) = (e.from, points.first_mut()) {
            *first = complex.vertices[v].at;
        }
        if let (Some(v), Some(last)) = (e.to, points.last_mut()) {
            *last = complex.vertices[v].at;
        }
        e.points = points.into();
    }
    complex
        .edges
        .retain(|e| e.points.iter().any(|&p| p != e.points[0]));
    complex.drop_unused_vertices();
}

/// Keeps each ridge among the points with two nearest points on its curve. A ridge of
/// two pieces of one curve ends at the centre of curvature of their joint, and near
/// that end the points with two nearest points are a cusp between two branches of the
/// evolute, narrowing like `σ^{3/2}` with the distance `σ` from the end: a chord within
/// the chord tolerance can leave it, and its points then have one nearest point, on one
/// piece, while their nearest point on the other is the joint. Such chords are halved,
/// their midpoints moved onto the bisector ([`trace::project`]), down to a hundredth of
/// `chord` and at most [`RIDGE_HALVINGS`] times; within `chord` of the end it is not
/// asked.
fn follow_ridges(complex: &mut VoronoiComplex, m: &FeatureFields, chord: f64, size: f64) {
    // the joint two fields of one generator share, with its centres of curvature
    let joint = |[a, b]: [usize; 2]| {
        if a == b || m.generators[a] != m.generators[b] {
            return None;
        }
        let end = m.ends[a].iter().find(|end| {
            m.ends[b]
                .iter()
                .any(|other| end.at.dist(other.at) <= SHARED_END * size)
        })?;
        Some((end.at, end.centres().collect::<Vec<_>>()))
    };
    let foot_at = |k: usize, q: Point, at: Point| {
        let field = &m.fields[k];
        (q - field.gradient(q) * field.value(q)).dist(at) <= SHARED_END * size
    };
    for e in complex.edges.iter_mut().filter(|e| e.points.len() >= 2) {
        let mut pair = e.sites.map(|g| g.site());
        let mut changes = e.sites_along.iter_mut().peekable();
        let mut points = Vec::with_capacity(e.points.len());
        points.push(e.points[0]);
        for (i, w) in e.points.windows(2).enumerate() {
            while let Some(change) = changes.next_if(|c| c.start <= i) {
                pair = change.sites.map(|g| g.site());
                change.start = points.len() - 1;
            }
            if let Some((at, centres)) = joint(pair) {
                let one_foot = |p: Point, q: Point| {
                    [0.25, 0.5, 0.75].into_iter().any(|s| {
                        let x = p + (q - p) * s;
                        centres.iter().all(|c| c.dist(x) > chord)
                            && pair.iter().any(|&k| foot_at(k, x, at))
                    })
                };
                let [a, b] = pair.map(|k| k as u32);
                halve(w[0], w[1], RIDGE_HALVINGS, &mut points, &|p, q| {
                    let len = p.dist(q);
                    if len <= 1e-2 * chord || !one_foot(p, q) {
                        return None;
                    }
                    let normal = (q - p).perp() * (1.0 / len);
                    trace::project(&m.fields, a, b, (p + q) * 0.5, normal, 0.5 * len)
                });
            }
            points.push(w[1]);
        }
        for change in changes {
            change.start = points.len() - 1;
        }
        e.points = points.into();
    }
}

/// The most halvings of one chord of a ridge ([`follow_ridges`]; the deep concavity's
/// axis needs two).
const RIDGE_HALVINGS: u32 = 8;

/// Pushes onto `out` the points strictly between `p` and `q` that `split` asks for: where
/// it gives a point for a chord, the chord is halved there and each half asked again,
/// `depth` times at most.
fn halve(
    p: Point,
    q: Point,
    depth: u32,
    out: &mut Vec<Point>,
    split: &dyn Fn(Point, Point) -> Option<Point>,
) {
    if depth == 0 {
        return;
    }
    if let Some(m) = split(p, q) {
        halve(p, m, depth - 1, out, split);
        out.push(m);
        halve(m, q, depth - 1, out, split);
    }
}

/// Replaces each generator (a field's index) by the generator it stands for, and drops
/// the generator changes along an edge that no longer change anything.
fn name_generators(complex: &mut VoronoiComplex, m: &FeatureFields) {
    let name = |g: &mut Generator| *g = m.generators[g.site()];
    for v in &mut complex.vertices {
        v.sites.iter_mut().for_each(name);
    }
    for e in &mut complex.edges {
        e.sites.iter_mut().for_each(name);
        let mut last = e.sites;
        e.sites_along.retain_mut(|c| {
            c.sites.iter_mut().for_each(name);
            let changes = c.sites != last;
            last = c.sites;
            changes
        });
    }
}

/// Splits each edge where its generators change (where a zone boundary left the
/// diagram): there the two pairs meet at a vertex of the three generators, as where a
/// corner's zone ends along an edge.
fn split_at_changes(complex: &mut VoronoiComplex) {
    let mut edges = Vec::with_capacity(complex.edges.len());
    for e in std::mem::take(&mut complex.edges) {
        if e.sites_along.is_empty() {
            edges.push(e);
            continue;
        }
        let (mut from, mut start, mut sites) = (e.from, 0, e.sites);
        for change in &e.sites_along {
            let mut generators: smallvec::SmallVec<[Generator; 3]> = sites.into_iter().collect();
            generators.extend(change.sites.into_iter().filter(|g| !sites.contains(g)));
            complex.vertices.push(Vertex {
                at: e.points[change.start],
                sites: generators,
                clearance: None,
            });
            let to = Some(complex.vertices.len() - 1);
            edges.push(part(&e, sites, from, to, start..change.start + 1));
            (from, start, sites) = (to, change.start, change.sites);
        }
        edges.push(part(&e, sites, from, e.to, start..e.points.len()));
    }
    complex.edges = edges;
}

/// The points `range` of `e` as an edge of `sites` from `from` to `to`.
fn part(
    e: &Edge,
    sites: [Generator; 2],
    from: Option<usize>,
    to: Option<usize>,
    range: std::ops::Range<usize>,
) -> Edge {
    Edge {
        sites,
        from,
        to,
        points: e.points[range].into(),
        bisector: Vec::new(),
        parametric: Vec::new(),
        clearance: Vec::new(),
        sites_along: Vec::new(),
    }
}
