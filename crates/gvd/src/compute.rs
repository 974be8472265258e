//! The library's entry point: a scene in, its Voronoi complex out.

use crate::clearance::{with_feet, Feet};
use crate::complex::cells;
use crate::complex::prune::{prune_with, Pruning};
use crate::complex::VoronoiComplex;
use crate::control::{Control, Watch};
use crate::error::Error;
use crate::geom::Aabb;
use crate::geom::{Point, PointGrid};
use crate::incremental;
use crate::scene::Scene;
use crate::scene::{Metric, Mode, SiteKind};
use crate::site::FieldOptions;
use crate::subdivision;

/// Which algorithm family computes the diagram.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Engine {
    /// The incremental engine where it applies (scenes of Euclidean points only), the
    /// subdivision engine otherwise.
    #[default]
    Auto,
    /// Subdivision: over distance fields (EMM13) for every supported site kind, by
    /// soft predicates over corner and edge features (YSL12) for scenes of segments,
    /// polylines and polygons.
    Subdivision,
    /// Topology-oriented incremental construction: Euclidean points, segments,
    /// polylines and polygons.
    Incremental,
    /// Bisectors in parameter space (HREK07): scenes of `bezier` and `bspline` curves.
    Freeform,
}

/// How to compute a diagram: the engine, and each engine's own knobs.
#[derive(Clone, Debug)]
pub struct Options {
    /// Which algorithm family to use.
    pub engine: Engine,
    /// Work in parallel (same result either way).
    pub parallel: bool,
    /// Knobs of the subdivision engine.
    pub subdivision: SubdivisionOptions,
    /// Knobs of the incremental engine.
    pub incremental: IncrementalOptions,
    /// Stopping and watching the run from outside: a cancel flag, a time limit, a
    /// progress callback (none by default). Every engine heeds it.
    pub control: Control,
    /// Pruning of the medial axis (λ-medial axis, object angle; none by default), after
    /// the clearances and the largest inscribed circle are taken: see
    /// [`crate::complex::prune`].
    pub prune: Pruning,
}

/// Knobs of the subdivision engine (EMM13).
#[derive(Clone, Debug, Default)]
pub struct SubdivisionOptions {
    /// Boxes holding two or more sites are split until no longer than this (the
    /// "maximum admissible box size" of (EMM13), for smoother curves); `None` lets the
    /// certificates decide alone.
    pub max_box: Option<f64>,
    /// Choices among equivalent distance fields (closed forms or the general paths).
    pub fields: FieldOptions,
    /// The boxes and output points the subdivision engine may use (defaults grow with
    /// the number of sites); running out gives [`Error::Budget`].
    pub limits: subdivision::Limits,
    /// The filters of the soft-predicate algorithm (YSL12), which computes scenes of
    /// segments, polylines and polygons.
    pub soft: subdivision::soft::Filters,
}

/// Knobs of the incremental engine (SI92, Hel01).
#[derive(Clone, Debug, Default)]
pub struct IncrementalOptions {
    /// Give every edge its exact bisector in offset-parameter form
    /// ([`crate::complex::Edge::bisector`]).
    pub bisectors: bool,
    /// Refuse segments (and polyline and polygon edges) that cross, overlap, repeat
    /// one another or touch another's inside, and point sites inside a segment, naming
    /// the two sites, instead of cutting them into pieces that meet at shared ends
    /// (the default: the pieces of a site stay that site's generators, and `stats`
    /// counts the cuts as `split_crossings`, `split_touches` and `merged_duplicates`).
    pub strict: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            engine: Engine::Auto,
            parallel: cfg!(feature = "parallel"),
            subdivision: SubdivisionOptions::default(),
            incremental: IncrementalOptions::default(),
            control: Control::default(),
            prune: Pruning::default(),
        }
    }
}

/// A computed diagram with the subdivision boxes that span it (each with its number of
/// surviving sites), for pictures and box counts.
pub struct Computation {
    /// The diagram.
    pub complex: VoronoiComplex,
    /// The subdivision's leaves, each with its number of surviving sites.
    pub boxes: Vec<(Aabb, usize)>,
}

/// Computes the Voronoi diagram of a scene.
pub fn compute(scene: &Scene, options: &Options) -> Result<VoronoiComplex, Error> {
    compute_with_boxes(scene, options).map(|c| c.complex)
}

/// [`compute`], also returning the subdivision's leaves (none for the incremental engine).
/// The diagram carries the sites' user ids ([`VoronoiComplex::site_ids`]) when any site
/// has one, and in `complex` and `medial_axis` modes the clearance of its vertices and
/// edge points ([`VoronoiComplex::add_clearances`]; not in `voronoi` mode, whose
/// diagrams of millions of points would grow by a number per point for little use);
/// in `medial_axis` mode also `stats.max_inscribed_circle`
/// ([`VoronoiComplex::max_inscribed_circle`]). Then, when `options.prune` sets a
/// criterion, the diagram is pruned ([`crate::complex::prune::prune`]) and
/// `stats.pruning` says how.
pub fn compute_with_boxes(scene: &Scene, options: &Options) -> Result<Computation, Error> {
    options.prune.check()?;
    if options.prune.is_on() && options.incremental.bisectors {
        return Err(Error::InvalidOption {
            option: "prune".into(),
            message: "pruning does not cut exact bisector pieces: leave out the bisectors".into(),
        });
    }
    let mut out = run_engine(scene, options)?;
    if scene.mode() != Mode::Voronoi || options.prune.is_on() {
        // the feet are built once: the free-form curves' take a search structure
        with_feet(scene, |feet| {
            add_clearances_and_prune(&mut out.complex, scene, &options.prune, feet)
        })?;
    }
    if scene.sites().iter().any(|s| s.id.is_some()) {
        out.complex.site_ids = scene.sites().iter().map(|s| s.id.clone()).collect();
    }
    Ok(out)
}

/// The clearances outside `voronoi` mode, the maximum inscribed circle in `medial_axis`
/// mode, then the pruning when `pruning` sets a criterion ([`compute_with_boxes`]).
fn add_clearances_and_prune(
    complex: &mut VoronoiComplex,
    scene: &Scene,
    pruning: &Pruning,
    feet: &Feet,
) -> Result<(), Error> {
    if scene.mode() != Mode::Voronoi {
        complex.store_clearances(feet);
    }
    if scene.mode() == Mode::MedialAxis {
        if let Some((center, radius)) = complex.max_inscribed_circle() {
            complex.stats.insert(
                "max_inscribed_circle".into(),
                serde_json::json!({ "center": [center.x, center.y], "radius": radius }),
            );
        }
    }
    if pruning.is_on() {
        let counts = prune_with(complex, scene, feet, pruning)?;
        let stats = serde_json::json!({
            "lambda": pruning.lambda,
            "object_angle_degrees": pruning.object_angle.map(f64::to_degrees),
            "edges_before": counts.edges_before,
            "vertices_before": counts.vertices_before,
            "cut_ends": counts.cut_ends,
            "merged_vertices": counts.merged_vertices,
        });
        complex.stats.insert("pruning".into(), stats);
    }
    Ok(())
}

/// The engine the options and the scene choose, run.
fn run_engine(scene: &Scene, options: &Options) -> Result<Computation, Error> {
    let watch = Watch::start(&options.control)?;
    check_medial_axis(scene)?;
    scene.refuse_points_inside_polygons()?;
    scene.refuse_crossing_curves()?;
    if options.engine == Engine::Freeform
        || (options.engine == Engine::Auto && crate::freeform::supports(scene))
    {
        let complex = crate::freeform::compute(scene, &watch)?;
        return Ok(Computation {
            complex,
            boxes: Vec::new(),
        });
    }
    let points = euclidean_points(scene);
    match (options.engine, points) {
        (Engine::Auto | Engine::Incremental, Some(points)) => {
            return timed_incremental(scene, || {
                let diagram = incremental::PointDiagram::watched(&points, scene.domain(), &watch)?;
                let (mut complex, traced) = diagram.to_complex_with_cells();
                drop(diagram);
                if !traced {
                    // Not expected with exact signs: the generic cells from the edges.
                    let grid = PointGrid::new(&points);
                    complex.cells = cells::build_cells(&complex, &scene.domain(), &|q| {
                        grid.nearest(q).unwrap_or(0)
                    });
                    complex
                        .stats
                        .insert("cells_from_edges".into(), serde_json::json!(true));
                }
                if options.incremental.bisectors {
                    incremental::add_point_bisectors(&mut complex, &points, scene.domain());
                }
                Ok(complex)
            });
        }
        (Engine::Auto | Engine::Incremental, None) if incremental::supports(scene) => {
            return timed_incremental(scene, || {
                incremental::scene_voronoi(
                    scene,
                    &options.incremental,
                    &options.subdivision.limits,
                    &watch,
                )
            });
        }
        (Engine::Incremental, None) => {
            let (site, kind) = scene
                .sites()
                .iter()
                .enumerate()
                .find(|(_, s)| !incremental::supports_site(&s.kind))
                .map(|(i, s)| (i, s.kind.name().to_string()))
                .unwrap_or((0, "point".into()));
            return Err(Error::Unsupported {
                site,
                kind,
                message: "the incremental engine computes Euclidean points, segments, arcs short of a full circle, polylines and polygons (so far)".into(),
            });
        }
        (Engine::Auto, None) => check_one_engine_takes_all(scene)?,
        _ => {}
    }
    scene.refuse_repeated_segments()?;
    if options.engine == Engine::Subdivision && crate::site::polygonal::supports(scene) {
        let out = subdivision::soft::run_scene(
            scene,
            &options.subdivision.soft,
            &options.subdivision.limits,
            &watch,
        )?;
        return Ok(Computation {
            complex: out.complex,
            boxes: out.boxes,
        });
    }
    scene.refuse_near_coincident_points()?;
    let params = subdivision::Params::for_scene(
        scene,
        options.subdivision.max_box,
        options.parallel,
        options.subdivision.limits,
    );
    let out = subdivision::run_scene(scene, &options.subdivision.fields, &params, &watch)?;
    Ok(Computation {
        complex: out.complex,
        boxes: out.boxes,
    })
}

/// Whether the subdivision engine has a distance field for sites of this kind in this
/// mode (segments, polylines, polygons and arcs as whole sites: `voronoi` mode only).
fn subdivision_supports(kind: &SiteKind, mode: Mode) -> bool {
    mode == Mode::Voronoi || !crate::site::is_linear_or_circular(kind)
}

/// With `Engine::Auto` on a scene the incremental engine cannot take: refuses, naming
/// the real cause, a site that no engine computes, or a mix of kinds that no single
/// engine computes (instead of the first site the subdivision engine lacks).
fn check_one_engine_takes_all(scene: &Scene) -> Result<(), Error> {
    let sites = scene.sites();
    let Some(lacking) = sites
        .iter()
        .position(|s| !subdivision_supports(&s.kind, scene.mode()))
    else {
        return Ok(());
    };
    let unsupported = |i: usize, message: String| Error::Unsupported {
        site: i,
        kind: sites[i].kind.name().to_string(),
        message,
    };
    let other = sites
        .iter()
        .position(|s| !incremental::supports_site(&s.kind))
        .unwrap_or(0);
    Err(unsupported(
        lacking,
        format!(
            "the incremental engine takes this site but not site {other} (kind '{}'); \
             the subdivision engine takes both in 'voronoi' mode only: no engine \
             computes the two in one scene in mode '{}' yet",
            sites[other].kind.name(),
            scene.mode().name()
        ),
    ))
}

/// Refuses `medial_axis` mode where it has no meaning or no engine. The mode keeps the
/// complex inside the regions that closed sites bound: a scene of sites that bound none
/// (points, segments, open arcs, polylines, fields) has an empty medial axis, refused
/// rather than written as an empty diagram (or as the Voronoi diagram the point and
/// subdivision engines would give). Circles, ellipses and full-circle arcs bound
/// regions, but no engine computes the medial axis inside them yet. Polygons, curves,
/// algebraic curves and the open sites that may close up in chains (segments,
/// polylines, arcs: the engine refuses them when they do not) pass on.
fn check_medial_axis(scene: &Scene) -> Result<(), Error> {
    if scene.mode() != Mode::MedialAxis {
        return Ok(());
    }
    let round = |kind: &SiteKind| match kind {
        SiteKind::Circle { .. } | SiteKind::Ellipse { .. } => true,
        SiteKind::Arc {
            start_angle,
            end_angle,
            ..
        } => crate::geom::arc::sweep(*start_angle, *end_angle) == std::f64::consts::TAU,
        _ => false,
    };
    let may_bound = |kind: &SiteKind| {
        matches!(
            kind,
            SiteKind::Polygon { .. }
                | SiteKind::Segment { .. }
                | SiteKind::Polyline { .. }
                | SiteKind::Arc { .. }
                | SiteKind::Bezier { .. }
                | SiteKind::Bspline { .. }
                | SiteKind::Algebraic { .. }
        )
    };
    if let Some(i) = scene.sites().iter().position(|s| round(&s.kind)) {
        return Err(Error::Unsupported {
            site: i,
            kind: scene.sites()[i].kind.name().to_string(),
            message: "the medial axis inside circles, ellipses and full-circle arcs is not computed yet (mode 'medial_axis' takes polygons)".into(),
        });
    }
    if scene.sites().iter().any(|s| may_bound(&s.kind)) {
        return Ok(());
    }
    Err(Error::scene(
        "mode",
        "'medial_axis' keeps the diagram inside the regions that closed sites bound \
         (polygons, closed curves, chains of segments and arcs that close up), and this \
         scene has none: its medial axis is empty; use mode 'voronoi' or 'complex'",
    ))
}

/// Runs an incremental computation and records its time and engine in `stats`, and, for
/// an epsilon finer than f64 resolves over the domain ([`Aabb::f64_resolution`]), the
/// resolution the diagram has (`resolution`, `epsilon_floored_from`, as the subdivision
/// engine reports its floor).
fn timed_incremental(
    scene: &Scene,
    run: impl FnOnce() -> Result<VoronoiComplex, Error>,
) -> Result<Computation, Error> {
    let start = std::time::Instant::now();
    let mut complex = run()?;
    let stats = &mut complex.stats;
    let floor = scene.domain().f64_resolution();
    if scene.epsilon() < floor {
        stats.insert("resolution".into(), serde_json::json!(floor));
        stats.insert(
            "epsilon_floored_from".into(),
            serde_json::json!(scene.epsilon()),
        );
    }
    stats.insert(
        "seconds".into(),
        serde_json::json!(start.elapsed().as_secs_f64()),
    );
    stats.insert("engine".into(), serde_json::json!("incremental"));
    Ok(Computation {
        complex,
        boxes: Vec::new(),
    })
}

/// The sites' positions when every site is a Euclidean point.
fn euclidean_points(scene: &Scene) -> Option<Vec<Point>> {
    scene
        .sites()
        .iter()
        .map(|s| match s.kind {
            SiteKind::Point {
                at,
                metric: Metric::Euclidean,
            } => Some(at),
            _ => None,
        })
        .collect()
}
