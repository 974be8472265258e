//! The soft-predicate subdivision algorithm of Yap, Sharma and Lien (YSL12, §IV–VI)
//! for polygonal sets: the Voronoi complex of segments, polylines and polygons from
//! their corner and edge features ([`crate::site::polygonal`]), purely numerically.
//!
//! Three phases: subdivision and refinement ([`refine`]: boxes split until
//! `C = C0 ∧ C1 ∧ C2` holds ([`predicate`]), then candidate boxes balanced), and
//! construction ([`rounds`] over the leaves' [`quadtree`], which gives each leaf its
//! side segments; [`construct`]: via nodes on them, the Voronoi vertex test, arcs).
//! The stitching of arcs into edges is the generic engine's ([`super::assemble`]);
//! [`output`] names the generators per mode and clips to the domain.

pub mod construct;
pub mod output;
pub mod predicate;
pub mod quadtree;
pub mod refine;
pub mod rounds;

use super::budget::{Budget, Limits};
use super::tree::Lattice;
use super::Output;
use crate::complex::VoronoiComplex;
use crate::control::Watch;
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::scene::{Mode, Scene};
use crate::site::polygonal::Polygonal;
use construct::{Resolver, Tol};
use refine::{Ctx, Node};
use serde_json::json;
use std::time::Instant;

/// The filters of YSL12 ¶25, each a switch so that its effect can be measured (all on
/// by default: they change the number of boxes, not the diagram).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Filters {
    /// The zone filter: a feature belongs to a box only if its zone meets the box's
    /// influence disc (¶25(b)).
    pub zone: bool,
    /// With the zone filter, use the oriented zones Z*(f) (empty at concave corners)
    /// instead of the zones Z(f).
    pub oriented: bool,
    /// C1 also accepts a box of two edges (¶25(a)).
    pub two_edge: bool,
}

impl Default for Filters {
    fn default() -> Self {
        Filters {
            zone: true,
            oriented: true,
            two_edge: true,
        }
    }
}

/// The box the subdivision runs over: the domain grown by small, unequal fractions of
/// its size on each side, so that no box side falls on a line of symmetry of the
/// input (where a bisector could run along a side).
fn grown(d: &Aabb) -> Aabb {
    let (w, h) = (d.width(), d.height());
    Aabb::new(
        Point::new(d.min.x - w * 0.003_917, d.min.y - h * 0.002_731),
        Point::new(d.max.x + w * 0.001_373, d.max.y + h * 0.004_129),
    )
}

/// Computes the diagram of a polygonal scene by YSL12, or refuses a site it cannot
/// take; [`Error::Budget`] when the boxes or points run out, [`Error::Cancelled`] (or
/// the time limit's [`Error::Budget`]) when `watch` stops the run. A scene far from unit
/// size ([`Scene::unit_scale`]) is computed at an exact power-of-two scale and scaled
/// back, as the other engines do (its squared distances would underflow or overflow).
pub(crate) fn run_scene(
    scene: &Scene,
    filters: &Filters,
    limits: &Limits,
    watch: &Watch,
) -> Result<Output, Error> {
    let Some(s) = scene.unit_scale() else {
        return run_unit(scene, filters, limits, watch);
    };
    let mut out = run_unit(&scene.scaled(s), filters, limits, watch)?;
    out.scale_back(s);
    Ok(out)
}

/// [`run_scene`] on a scene near unit size.
fn run_unit(
    scene: &Scene,
    filters: &Filters,
    limits: &Limits,
    watch: &Watch,
) -> Result<Output, Error> {
    let start = Instant::now();
    watch.stage("boxes", None);
    let poly = Polygonal::new(scene)?;
    let domain = scene.domain();
    let root = grown(&domain);
    let lattice = Lattice::new(&root, None);
    let eps = scene.epsilon().max(super::resolution(&root, &lattice));
    let budget = Budget::new(limits, poly.features.len(), watch);
    let ctx = Ctx {
        poly: &poly,
        lattice: &lattice,
        filters,
        min_box: 0.5 * eps,
        budget: &budget,
    };
    let mut tree = ctx.subdivide();
    budget.check(eps)?;
    let t_subdivide = start.elapsed().as_secs_f64();
    let visited_subdivision = tree.leaf_count();
    let balance_splits = ctx.balance(&mut tree);
    budget.check(eps)?;
    let t_refine = start.elapsed().as_secs_f64();
    let tol = Tol {
        tie: 1e-9 * poly.scale,
        trace: 0.25 * eps,
        clear: (1e-3 * eps).max(64e-9 * poly.scale),
    };
    let resolver = Resolver {
        poly: &poly,
        tol,
        budget: &budget,
        by_sites: scene.mode() == Mode::Voronoi,
    };
    let constructed = rounds::construct(&ctx, &resolver, &mut tree, watch)?;
    budget.check(eps)?;
    let t_construct = start.elapsed().as_secs_f64();

    let leaves: Vec<&Node> = constructed
        .order
        .iter()
        .map(|&x| tree.leaf(x).expect("the order lists leaves"))
        .collect();
    let uncertified = constructed.output.uncertified;
    let mut complex =
        super::assemble::assemble(vec![constructed.output], 1e-12 * poly.scale, 0.125 * eps);
    output::name_features(&mut complex, &poly);
    let mut complex = output::clip(complex, &domain);
    if scene.mode() == Mode::Voronoi {
        complex = output::to_sites(complex);
        complex.cells = crate::complex::cells::site_cells(&complex, scene);
    }
    add_stats(
        &mut complex,
        &leaves,
        Stats {
            start,
            t_subdivide,
            t_refine,
            t_construct,
            eps,
            epsilon: scene.epsilon(),
            features: poly.features.len(),
            visited_subdivision,
            balance_splits,
            local_splits: constructed.local_splits,
            uncertified,
            rounds: constructed.rounds,
            filters: *filters,
        },
    );
    let boxes = leaves.iter().map(|n| (n.aabb, n.bs.set.len())).collect();
    Ok(Output { complex, boxes })
}

/// The figures of a run.
struct Stats {
    start: Instant,
    t_subdivide: f64,
    t_refine: f64,
    t_construct: f64,
    eps: f64,
    epsilon: f64,
    features: usize,
    visited_subdivision: usize,
    balance_splits: usize,
    local_splits: usize,
    uncertified: u32,
    rounds: usize,
    filters: Filters,
}

fn add_stats(complex: &mut VoronoiComplex, leaves: &[&Node], s: Stats) {
    let st = &mut complex.stats;
    st.insert("engine".into(), json!("subdivision"));
    st.insert("algorithm".into(), json!("soft predicates (YSL12)"));
    st.insert("seconds".into(), json!(s.start.elapsed().as_secs_f64()));
    st.insert("seconds_subdivision".into(), json!(s.t_subdivide));
    st.insert(
        "seconds_refinement".into(),
        json!(s.t_refine - s.t_subdivide),
    );
    st.insert(
        "seconds_construction".into(),
        json!(s.t_construct - s.t_refine),
    );
    st.insert("resolution".into(), json!(s.eps));
    if s.eps > s.epsilon {
        st.insert("epsilon_floored_from".into(), json!(s.epsilon));
    }
    st.insert("features".into(), json!(s.features));
    st.insert(
        "boxes".into(),
        json!(leaves.iter().filter(|n| n.candidate()).count()),
    );
    st.insert("leaves".into(), json!(leaves.len()));
    st.insert(
        "leaves_after_subdivision".into(),
        json!(s.visited_subdivision),
    );
    st.insert("balance_splits".into(), json!(s.balance_splits));
    st.insert("local_splits".into(), json!(s.local_splits));
    st.insert("uncertified_boxes".into(), json!(s.uncertified));
    st.insert("construction_rounds".into(), json!(s.rounds));
    st.insert(
        "filters".into(),
        json!({"zone": s.filters.zone, "oriented_zones": s.filters.oriented, "two_edge": s.filters.two_edge}),
    );
}
