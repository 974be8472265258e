//! `medial_axis` mode over distance fields (SYMW11's problem: the medial axis of regions
//! bounded by closed algebraic curves). The diagram is that of the sites' pieces
//! ([`MedialFields`]: each closed curve cut at its vertices into arcs with no ridge of
//! their own), restricted to the regions the curves bound (even-odd), and rid of the
//! zone boundaries between pieces of one site: the points whose nearest point on both
//! pieces is their shared end (within the resolution of the normal there, up to the
//! centre of curvature: [`End`](crate::site::algebraic::medial::End)). What remains are the points whose distance to the
//! curve is reached at two distinct points, the medial axis. A curve's generator is its
//! one C1 piece (a ridge lists it twice, as does a ridge's end at a centre of curvature).

use super::{run_watched, Output, Params};
use crate::complex::prune::keep_passing;
use crate::complex::{Edge, FeatureKind, Generator, VoronoiComplex};
use crate::control::Watch;
use crate::error::Error;
use crate::geom::Point;
use crate::scene::Scene;
use crate::site::{FieldOptions, MedialFields};
use serde_json::json;

/// Ends of two pieces within this fraction of the domain's size are their shared end
/// (each piece computes it to about 1e-15 of its box).
const SHARED_END: f64 = 1e-9;

/// Computes the medial axis of `scene` (mode `medial_axis`, sites the subdivision
/// engine takes, among them algebraic curves).
pub(crate) fn run(
    scene: &Scene,
    field_options: &FieldOptions,
    params: &Params,
    watch: &Watch,
) -> Result<Output, Error> {
    let m = MedialFields::for_scene(scene, field_options)?;
    let mut out = run_watched(&m.fields, params, watch)?;
    let size = params.domain.longest_side();
    let resolution = out
        .complex
        .stats
        .get("resolution")
        .and_then(|v| v.as_f64())
        .unwrap_or(params.epsilon);
    let inside = |q: Point| m.regions.iter().filter(|r| r.contains(q)).count() % 2 == 1;
    let passes = |e: &Edge, q: Point| {
        let [a, b] = e.sites.map(|g| g.site());
        inside(q)
            && !m.ends[a].iter().any(|end| {
                m.ends[b]
                    .iter()
                    .any(|other| end.at.dist(other.at) <= SHARED_END * size)
                    && end.zone_holds(q, resolution)
            })
    };
    keep_passing(&mut out.complex, &passes, resolution / 4.0, &|_, _| None);
    snap_ridge_ends(&mut out.complex, &m, resolution);
    name_sites(&mut out.complex, &m);
    out.complex.cells.clear();
    out.complex
        .stats
        .insert("medial_pieces".into(), json!(m.fields.len()));
    Ok(out)
}

/// Moves each ridge end (a vertex of degree one) within `tol` of a centre of curvature
/// of a piece end to that centre, where the ridge truly ends. The cut on the zone
/// boundary lies on the simplified polyline, up to a fraction of the resolution aside;
/// near a vertex of the curve the nearest point is flat to fourth order, so that much
/// aside puts the foot, and its centre of curvature, several resolutions away.
fn snap_ridge_ends(complex: &mut VoronoiComplex, m: &MedialFields, tol: f64) {
    let mut degree = vec![0usize; complex.vertices.len()];
    for e in &complex.edges {
        for v in [e.from, e.to].into_iter().flatten() {
            degree[v] += 1;
        }
    }
    let centres: Vec<Point> = m.ends.iter().flatten().filter_map(|e| e.centre()).collect();
    for (v, vertex) in complex.vertices.iter_mut().enumerate() {
        if degree[v] != 1 {
            continue;
        }
        let nearest = centres
            .iter()
            .copied()
            .min_by(|a, b| a.dist(vertex.at).total_cmp(&b.dist(vertex.at)));
        if let Some(c) = nearest.filter(|c| c.dist(vertex.at) <= tol) {
            vertex.at = c;
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
}

/// Replaces each generator (a field's index) by what it stands for: a piece of an
/// algebraic curve by the curve's one piece (`{"site": i, "feature": "piece", "index":
/// 0}`: a smooth curve is one C1 piece), another field by its site; and drops the
/// generator changes along an edge that no longer change anything.
fn name_sites(complex: &mut VoronoiComplex, m: &MedialFields) {
    let site = |g: &mut Generator| {
        let k = g.site();
        *g = if m.ends[k].is_empty() {
            Generator::Site(m.owners[k])
        } else {
            Generator::Feature {
                site: m.owners[k],
                feature: FeatureKind::Piece,
                index: 0,
            }
        };
    };
    for v in &mut complex.vertices {
        v.sites.iter_mut().for_each(site);
    }
    for e in &mut complex.edges {
        e.sites.iter_mut().for_each(site);
        let mut last = e.sites;
        e.sites_along.retain_mut(|c| {
            c.sites.iter_mut().for_each(site);
            let changes = c.sites != last;
            last = c.sites;
            changes
        });
    }
}
