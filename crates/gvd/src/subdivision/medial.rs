//! `medial_axis` mode over distance fields (SYMW11's problem: the medial axis of regions
//! bounded by closed algebraic curves). The diagram is that of the sites' pieces
//! ([`MedialFields`]: each closed curve cut at its vertices into arcs with no ridge of
//! their own), restricted to the regions the curves bound (even-odd), and rid of the
//! zone boundaries between pieces of one site: the points whose nearest point on both
//! pieces is their shared end. What remains are the points whose distance to the curve
//! is reached at two distinct points, the medial axis. Its generators are
//! the sites (a ridge of one curve lists that curve twice, as does a ridge's end at a
//! centre of curvature).

use super::{run_watched, Output, Params};
use crate::complex::prune::keep_passing;
use crate::complex::{Edge, Generator, VoronoiComplex};
use crate::control::Watch;
use crate::error::Error;
use crate::geom::Point;
use crate::scene::Scene;
use crate::site::{DistanceField, FieldOptions, MedialFields};
use serde_json::json;

/// Ends of two pieces within this fraction of the domain's size are their shared end
/// (each piece computes it to about 1e-15 of its box).
const SHARED_END: f64 = 1e-9;

/// A point `q` lies on the zone boundary of two pieces that share the end `e` where both
/// are no nearer than `e`, to this fraction of the domain's size: `min(d_a, d_b) ≥
/// |q − e| − τ`. Beside a ridge's end at the centre of curvature of a vertex, with feet
/// `±s` from it, the ridge's points are nearer by about `κ's²` than `e`, so the ridge is cut
/// about `√τ` (3e-5 of the domain) short of its end; the distances come from feet
/// refined by Newton's method (or samples where the distance is flat), far below `τ`.
const ZONE: f64 = 1e-9;

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
    let inside = |q: Point| m.regions.iter().filter(|r| r.contains(q)).count() % 2 == 1;
    let passes = |e: &Edge, q: Point| {
        if !inside(q) {
            return false;
        }
        let [a, b] = e.sites.map(|g| g.site());
        if m.owners[a] != m.owners[b] {
            return true;
        }
        let near = m.fields[a].value(q).min(m.fields[b].value(q)) + ZONE * size;
        !m.ends[a].iter().any(|&end| {
            m.ends[b].iter().any(|&other| end.dist(other) <= SHARED_END * size)
                && near >= q.dist(end)
        })
    };
    let resolution = out.complex.stats["resolution"].as_f64().unwrap_or(params.epsilon);
    keep_passing(&mut out.complex, &passes, resolution / 4.0, &|_, _| None);
    name_sites(&mut out.complex, &m.owners);
    out.complex.cells.clear();
    out.complex
        .stats
        .insert("medial_pieces".into(), json!(m.fields.len()));
    Ok(out)
}

/// Replaces each generator (a field's index) by its site's, dropping the generator
/// changes along an edge that no longer change anything.
fn name_sites(complex: &mut VoronoiComplex, owners: &[usize]) {
    let site = |g: &mut Generator| *g = Generator::Site(owners[g.site()]);
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
