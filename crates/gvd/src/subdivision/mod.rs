//! The subdivision engine (Emiris, Mantzaflaris, Mourrain 2013, Alg. 1 and 2), generic
//! over [`DistanceField`]: subdivide with the lower-envelope filter, cut the leaves'
//! sides into shared segments, find the label changes on them, resolve each leaf, stitch.

mod assemble;
mod budget;
mod featured;
mod filter;
mod locate;
mod resolve;
mod segments;
pub mod soft;
mod trace;
mod tree;

use crate::complex::VoronoiComplex;
use crate::control::Watch;
use crate::error::Error;
use crate::geom::Aabb;
use crate::scene::Scene;
use crate::site::{DistanceField, FieldOptions, SiteField};
pub(crate) use budget::Budget;
pub use budget::Limits;
use resolve::{LeafOutput, Port, PortId, Resolver, Tolerances};
use serde_json::json;
use std::time::Instant;

/// Parameters of a subdivision run.
#[derive(Clone, Copy, Debug)]
pub struct Params {
    /// The box the diagram is computed in.
    pub domain: Aabb,
    /// Output curves lie within this distance of the true diagram.
    pub epsilon: f64,
    /// Boxes that hold two or more sites are split until no longer than this.
    pub max_box: Option<f64>,
    /// Use rayon's thread pool (the result is the same either way).
    pub parallel: bool,
    /// The boxes and output points the run may use.
    pub limits: Limits,
}

/// The diagram and the leaves of the subdivision (for pictures and box counts): each
/// leaf's box and its number of sites.
pub struct Output {
    pub complex: VoronoiComplex,
    pub boxes: Vec<(Aabb, usize)>,
}

impl Params {
    /// The parameters of a run over `scene`'s domain at its epsilon.
    pub fn for_scene(scene: &Scene, max_box: Option<f64>, parallel: bool, limits: Limits) -> Self {
        Params {
            domain: scene.domain(),
            epsilon: scene.epsilon(),
            max_box,
            parallel,
            limits,
        }
    }
}

/// [`run`] over the fields of `scene` (as `field_options` choose them). A scene whose
/// field values would overflow or underflow f64 ([`Scene::unit_scale`]: coordinates
/// beyond about `2^±200` for distances, `2^±50` for lp4) is computed at an exact
/// power-of-two scale where its largest coordinate is about 1, and its diagram and
/// boxes scaled back (`stats.rescaled_by` gives the factor used): the same diagram,
/// scaled, as the scene at unit scale. `watch` stops the run early. In `medial_axis`
/// mode, and in `complex` mode with free-form curves, the diagram is that of the sites'
/// features ([`featured`], unscaled).
pub(crate) fn run_scene(
    scene: &Scene,
    field_options: &FieldOptions,
    params: &Params,
    watch: &Watch,
) -> Result<Output, Error> {
    if featured_mode(scene) {
        return featured::run(scene, field_options, params, watch);
    }
    let rounded = round_ellipses_as_circles(scene);
    let scene = rounded.as_ref().unwrap_or(scene);
    check_polynomial_precision(scene)?;
    let Some(s) = scene.unit_scale() else {
        check_field_range(scene)?;
        let fields = SiteField::for_scene_with(scene, field_options)?;
        let mut out = run_watched(&fields, params, watch)?;
        add_curve_stats(&fields, &mut out.complex);
        return Ok(out);
    };
    let scaled = scene.scaled(s);
    let fields = SiteField::for_scene_with(&scaled, field_options)?;
    let scaled_params = Params {
        domain: scaled.domain(),
        epsilon: scaled.epsilon(),
        max_box: params.max_box.map(|m| m * s),
        ..*params
    };
    let mut out = run_watched(&fields, &scaled_params, watch)?;
    out.scale_back(s);
    Ok(out)
}

impl Output {
    /// Brings the output of a run on the scene scaled by `s` back to the scene's
    /// coordinates: the diagram, the leaves and the lengths among the stats, and records
    /// `stats.rescaled_by`.
    fn scale_back(&mut self, s: f64) {
        self.complex.scale(1.0 / s);
        for (b, _) in &mut self.boxes {
            *b = Aabb::new(b.min * (1.0 / s), b.max * (1.0 / s));
        }
        let stats = &mut self.complex.stats;
        for key in ["resolution", "epsilon_floored_from"] {
            if let Some(v) = stats.get(key).and_then(|v| v.as_f64()) {
                stats.insert(key.into(), json!(v / s));
            }
        }
        stats.insert("rescaled_by".into(), json!(s));
    }
}

/// Records each algebraic curve's enclosure figures in `stats.algebraic`.
fn add_curve_stats(fields: &[SiteField], complex: &mut VoronoiComplex) {
    let curves: Vec<serde_json::Value> = fields
        .iter()
        .enumerate()
        .filter_map(|(i, f)| match f {
            SiteField::Algebraic(a) => {
                let mut s = a.stats();
                s["site"] = json!(i);
                Some(s)
            }
            _ => None,
        })
        .collect();
    if !curves.is_empty() {
        complex.stats.insert("algebraic".into(), json!(curves));
    }
}

/// Whether `scene` is computed by its features' fields ([`featured`]): in
/// `medial_axis` mode, and in `complex` mode when it has free-form curves (whose pieces
/// and corners are that mode's generators).
fn featured_mode(scene: &Scene) -> bool {
    use crate::scene::{Mode, SiteKind};
    let freeform = |k: &SiteKind| matches!(k, SiteKind::Bezier { .. } | SiteKind::Bspline { .. });
    match scene.mode() {
        Mode::MedialAxis => true,
        Mode::Complex => scene.sites().iter().any(|s| freeform(&s.kind)),
        Mode::Voronoi => false,
    }
}

/// `scene` with each nearly round ellipse (semi-axes `a`, `b` within `epsilon / 16`)
/// taken as the circle of radius `(a + b)/2`, whose distance differs from the
/// ellipse's by at most `|a − b|/2` (outside the site, where the diagram lies); `None`
/// when there is none. The ellipse's offset polynomial degenerates there: its leading
/// coefficient `(a² − b²)²` vanishes, and the bounds from it with it.
fn round_ellipses_as_circles(scene: &Scene) -> Option<Scene> {
    use crate::scene::SiteKind;
    let round = |kind: &SiteKind| match kind {
        SiteKind::Ellipse {
            center, semi_axes, ..
        } if (semi_axes[0] - semi_axes[1]).abs() <= scene.epsilon() / 16.0 => {
            Some(SiteKind::Circle {
                center: *center,
                radius: 0.5 * (semi_axes[0] + semi_axes[1]),
            })
        }
        _ => None,
    };
    if !scene.sites().iter().any(|s| round(&s.kind).is_some()) {
        return None;
    }
    let mut out = scene.clone();
    for site in out.sites_mut() {
        if let Some(circle) = round(&site.kind) {
            site.kind = circle;
        }
    }
    Some(out)
}

/// Refuses a `field` site whose polynomial f64 cannot evaluate over the domain to
/// within epsilon: a sum of terms `c·x^i·y^j` is computed with an error up to about
/// `(d + 1)·2^-52·Σ|c|·M^(i+j)` (`d` its degree, `M` the domain's largest coordinate),
/// and where the terms cancel (`(x+y+1)^24` reaches 5^24 at a corner and is 1 near
/// its bisectors) no box bound can certify anything: the subdivision would split to
/// its floor everywhere. That error is a worst case; refused is a bound beyond 64
/// epsilon (beside `(x−1)²+(y−1)²` at epsilon 1e-3 in `[-2, 2]²`, `(x+y+1)^18` at
/// bound 16 epsilon takes 27 boxes; `^20`, at 440, left 829 boxes uncertified in 3 s,
/// and `^22` ran past 20 s before this check).
fn check_polynomial_precision(scene: &Scene) -> Result<(), Error> {
    use crate::scene::SiteKind;
    let d = &scene.domain();
    let m = d.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (i, site) in scene.sites().iter().enumerate() {
        let SiteKind::Field { equation } = &site.kind else {
            continue;
        };
        let poly = &equation.poly();
        let size: f64 = poly
            .terms
            .iter()
            .map(|(e, c)| c.abs() * m.powi((e[0] + e[1]) as i32))
            .sum();
        let error = f64::from(poly.total_degree() + 1) * f64::EPSILON * size;
        if error.is_nan() || error > 64.0 * scene.epsilon() {
            return Err(Error::site(
                i,
                "equation",
                format!(
                    "f64 evaluates this polynomial over the domain only to about {error:.3e} (its terms reach {size:.3e} and cancel), coarser than epsilon {:e}; lower its degree or coefficients, or raise epsilon",
                    scene.epsilon()
                ),
            ));
        }
    }
    Ok(())
}

/// Refuses a scene whose field values overflow or underflow f64 over the domain (a
/// scene that [`run_scene`] could not rescale, as its sites' fields differ in degree):
/// a field of degree `k` takes values up to about `(2M)^k` (`M` the largest coordinate)
/// and varies on the scale of `L^k` (`L` the domain's size).
fn check_field_range(scene: &Scene) -> Result<(), Error> {
    let d = &scene.domain();
    let extent = d.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let size = d.longest_side().log2();
    for (i, site) in scene.sites().iter().enumerate() {
        let Some(k) = site.kind.field_degree() else {
            continue;
        };
        let reach = (2.0 * extent.max(site_extent(&site.kind))).log2();
        let k = f64::from(k);
        let what = if k * reach > 1000.0 {
            "overflow"
        } else if k * size < -1000.0 {
            "underflow"
        } else {
            continue;
        };
        return Err(Error::Site {
            site: i,
            field: "kind".into(),
            message: format!(
                "its field (of degree {k} in lengths) would {what} f64 over this domain, and the scene mixes fields of different degrees, so no rescaling keeps its diagram; give the scene at a scale nearer 1"
            ),
        });
    }
    Ok(())
}

/// The largest coordinate or length of a site's data, as far as it decides the size of
/// its field's values.
fn site_extent(kind: &crate::scene::SiteKind) -> f64 {
    use crate::scene::SiteKind;
    let m = |p: &crate::geom::Point| p.x.abs().max(p.y.abs());
    match kind {
        SiteKind::Point { at, .. } => m(at),
        SiteKind::Circle { center, radius } | SiteKind::Arc { center, radius, .. } => {
            m(center).max(*radius)
        }
        SiteKind::Ellipse {
            center, semi_axes, ..
        } => m(center).max(semi_axes[0]).max(semi_axes[1]),
        SiteKind::Segment { from, to } => m(from).max(m(to)),
        SiteKind::Polyline { points } => points.iter().map(m).fold(0.0, f64::max),
        SiteKind::Polygon { rings } => rings.iter().flatten().map(m).fold(0.0, f64::max),
        _ => 0.0,
    }
}

/// Computes the minimization diagram of `fields` over the domain, or
/// [`Error::Budget`] when it needs more boxes or points than `params.limits` allow.
///
/// The resolution is `params.epsilon`, floored where f64 or the box lattice cannot
/// resolve it (see `resolution`); `stats.resolution` gives the one used.
pub fn run<F: DistanceField>(fields: &[F], params: &Params) -> Result<Output, Error> {
    run_watched(fields, params, &Watch::default())
}

/// [`run`], stopped early by `watch` (a cancel flag or a time limit).
pub(crate) fn run_watched<F: DistanceField>(
    fields: &[F],
    params: &Params,
    watch: &Watch,
) -> Result<Output, Error> {
    let start = Instant::now();
    watch.stage("boxes", None);
    let lattice = tree::Lattice::new(&params.domain, params.max_box);
    let eps = params.epsilon.max(resolution(&params.domain, &lattice));
    let min_box = 0.5 * eps;
    let budget = Budget::new(&params.limits, fields.len(), watch);
    if let Some(m) = params.max_box {
        budget.check_max_box(m, &params.domain)?;
    }
    let tree_params = tree::Params {
        max_box: params.max_box,
        min_box,
        parallel: params.parallel,
        budget: &budget,
    };
    let tree::Leaves {
        leaves,
        states: leaf_states,
    } = tree::subdivide(fields, &lattice, &tree_params);
    budget.check(eps)?;
    let t_subdivide = start.elapsed().as_secs_f64();

    let boxes: Vec<tree::IBox> = leaves.iter().map(|l| l.ib).collect();
    let segs = segments::build(&boxes, &lattice);
    let scan_len = 0.125 * eps;
    let scan_one = |s: &segments::Segment| {
        let cands = match s.leaves {
            [Some(a), Some(b)] => intersect(&leaves[a as usize].sites, &leaves[b as usize].sites),
            [Some(a), None] | [None, Some(a)] => leaves[a as usize].sites.clone(),
            [None, None] => Vec::new(),
        };
        if cands.len() < 2 || budget.exhausted() {
            return Vec::new();
        }
        // the states over the side, narrowed from the smaller leaf's where it kept them
        let side = segments::segment_box(s.from, s.to);
        let from = s
            .leaves
            .iter()
            .flatten()
            .map(|&l| l as usize)
            .filter(|&l| !leaf_states[l].is_empty())
            .min_by(|&a, &b| {
                leaves[a]
                    .aabb
                    .longest_side()
                    .total_cmp(&leaves[b].aabb.longest_side())
            });
        let sites = cands
            .iter()
            .map(|&c| {
                let field = &fields[c as usize];
                let kept = from.and_then(|l| {
                    let k = leaves[l].sites.binary_search(&c).ok()?;
                    Some(&leaf_states[l][k])
                });
                let state = match kept {
                    Some(st) => field.restrict(st, &side),
                    None => field.state(&side),
                };
                (c, state)
            })
            .collect();
        segments::transitions(fields, sites, s.from, s.to, scan_len, budget.watch())
    };
    let transitions: Vec<Vec<segments::Transition>> =
        map(params.parallel, &segs.segments, scan_one);
    budget.check(eps)?;
    let t_scan = start.elapsed().as_secs_f64();

    let tol = Tolerances {
        trace: 0.25 * eps,
        min_box,
        scan: scan_len,
    };
    let leaf_ids: Vec<usize> = (0..leaves.len()).collect();
    let resolve_one = |&l: &usize| {
        let leaf = &leaves[l];
        let mut out = LeafOutput::default();
        if leaf.sites.len() < 2 {
            return out;
        }
        let mut ports = Vec::new();
        for &s in &segs.members[segs.rows[l]..segs.rows[l + 1]] {
            for (k, t) in transitions[s as usize].iter().enumerate() {
                ports.push(Port {
                    id: PortId::Segment {
                        segment: s,
                        index: k as u32,
                    },
                    at: t.at,
                    pair: t.pair,
                });
            }
        }
        if !budget.exhausted() {
            Resolver::new(fields, tol, &budget, l as u32).resolve_leaf(
                leaf,
                &leaf_states[l],
                ports,
                &mut out,
            );
        }
        out
    };
    let outputs: Vec<LeafOutput> = map(params.parallel, &leaf_ids, resolve_one);
    budget.check(eps)?;
    let t_resolve = start.elapsed().as_secs_f64();
    let uncertified: u32 = outputs.iter().map(|o| o.uncertified).sum();
    let local_splits: u32 = outputs.iter().map(|o| o.local_splits).sum();
    let mut complex = assemble::assemble(outputs, 0.5 * eps, 0.125 * eps);
    let t_assemble = start.elapsed().as_secs_f64();
    if !fields.is_empty() {
        let locator = locate::Locator::new(fields, &leaves, params.domain);
        complex.cells =
            crate::complex::cells::build_cells(&complex, &params.domain, &|q| locator.nearest(q));
    }

    let spanning = leaves.iter().filter(|l| l.sites.len() >= 2).count();
    let stats = &mut complex.stats;
    stats.insert("seconds".into(), json!(start.elapsed().as_secs_f64()));
    stats.insert("seconds_subdivision".into(), json!(t_subdivide));
    stats.insert("seconds_segments".into(), json!(t_scan - t_subdivide));
    stats.insert("seconds_leaves".into(), json!(t_resolve - t_scan));
    stats.insert(
        "seconds_cells".into(),
        json!(start.elapsed().as_secs_f64() - t_assemble),
    );
    stats.insert("engine".into(), json!("subdivision"));
    stats.insert("resolution".into(), json!(eps));
    if eps > params.epsilon {
        stats.insert("epsilon_floored_from".into(), json!(params.epsilon));
    }
    stats.insert("boxes".into(), json!(spanning));
    stats.insert("leaves".into(), json!(leaves.len()));
    stats.insert("uncertified_boxes".into(), json!(uncertified));
    stats.insert("local_splits".into(), json!(local_splits));
    let boxes = leaves.iter().map(|l| (l.aabb, l.sites.len())).collect();
    Ok(Output { complex, boxes })
}

/// The finest resolution a run over `domain` can give: a few hundred ulps of its largest
/// coordinate (below that f64 cannot tell points apart), and two of the lattice's
/// smallest boxes (below that no box can be split). A finer epsilon is floored here.
pub fn resolution(domain: &Aabb, lattice: &tree::Lattice) -> f64 {
    domain.f64_resolution().max(2.0 * lattice.smallest_box())
}

/// The sorted intersection of two sorted site lists.
fn intersect(a: &[u32], b: &[u32]) -> Vec<u32> {
    let (mut i, mut j, mut out) = (0, 0, Vec::new());
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                out.push(a[i]);
                i += 1;
                j += 1;
            }
        }
    }
    out
}

/// `items.map(f)` in order, on rayon's pool when asked.
fn map<T: Sync, R: Send>(parallel: bool, items: &[T], f: impl Fn(&T) -> R + Sync + Send) -> Vec<R> {
    #[cfg(feature = "parallel")]
    if parallel {
        use rayon::prelude::*;
        return items.par_iter().map(f).collect();
    }
    let _ = parallel;
    items.iter().map(f).collect()
}
