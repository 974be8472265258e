//! The library's entry point: a scene in, its Voronoi complex out.

use crate::cells;
use crate::complex::VoronoiComplex;
use crate::error::Error;
use crate::geom::Aabb;
use crate::geom::{Point, PointGrid};
use crate::incremental;
use crate::scene::Scene;
use crate::scene::{Metric, Mode, SiteKind};
use crate::site::{FieldOptions, SiteField};
use crate::subdivision;

/// Which algorithm family computes the diagram.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Engine {
    /// The incremental engine where it applies (scenes of Euclidean points only), the
    /// subdivision engine otherwise.
    #[default]
    Auto,
    /// Subdivision over distance fields (Emiris et al. 2013): every supported site kind.
    Subdivision,
    /// Topology-oriented incremental construction: Euclidean points, segments,
    /// polylines and polygons.
    Incremental,
}

/// How to compute a diagram.
#[derive(Clone, Debug)]
pub struct Options {
    /// Which algorithm family to use.
    pub engine: Engine,
    /// Boxes holding two or more sites are split until no longer than this (the
    /// "maximum admissible box size" of Emiris et al., for smoother curves); `None`
    /// lets the certificates decide alone.
    pub max_box: Option<f64>,
    /// Process independent boxes in parallel (same result either way).
    pub parallel: bool,
    /// Choices among equivalent distance fields (closed forms or the general paths).
    pub fields: FieldOptions,
    /// Give every edge of the incremental engine its exact bisector in
    /// offset-parameter form ([`crate::complex::Edge::bisector`]).
    pub bisectors: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            engine: Engine::Auto,
            max_box: None,
            parallel: cfg!(feature = "parallel"),
            fields: FieldOptions::default(),
            bisectors: false,
        }
    }
}

/// A computed diagram with the subdivision boxes that span it (each with its number of
/// surviving sites), for pictures and box counts.
pub struct Computation {
    pub complex: VoronoiComplex,
    pub boxes: Vec<(Aabb, usize)>,
}

/// Computes the Voronoi diagram of a scene.
pub fn compute(scene: &Scene, options: &Options) -> Result<VoronoiComplex, Error> {
    compute_with_boxes(scene, options).map(|c| c.complex)
}

/// [`compute`], also returning the subdivision's leaves (none for the incremental engine).
pub fn compute_with_boxes(scene: &Scene, options: &Options) -> Result<Computation, Error> {
    let points = euclidean_points(scene);
    match (options.engine, points) {
        (Engine::Auto | Engine::Incremental, Some(points)) => {
            return timed_incremental(|| {
                let diagram = incremental::PointDiagram::new(&points, scene.domain)?;
                let (mut complex, traced) = diagram.to_complex_with_cells();
                drop(diagram);
                if !traced {
                    // Not expected with exact signs: the generic cells from the edges.
                    let grid = PointGrid::new(&points);
                    complex.cells = cells::build_cells(&complex, &scene.domain, &|q| {
                        grid.nearest(q).unwrap_or(0)
                    });
                    complex
                        .stats
                        .insert("cells_from_edges".into(), serde_json::json!(true));
                }
                if options.bisectors {
                    incremental::add_point_bisectors(&mut complex, &points, scene.domain);
                }
                Ok(complex)
            });
        }
        (Engine::Auto | Engine::Incremental, None) if incremental::linear::supports(scene) => {
            return timed_incremental(|| {
                incremental::linear::linear_voronoi(scene, options.bisectors)
            });
        }
        (Engine::Incremental, None) => {
            let (site, kind) = scene
                .sites
                .iter()
                .enumerate()
                .find(|(_, s)| !incremental::linear::supports_site(&s.kind))
                .map(|(i, s)| (i, s.kind.name().to_string()))
                .unwrap_or((0, "point".into()));
            return Err(Error::Unsupported {
                site,
                kind,
                message: "the incremental engine computes Euclidean points, segments, arcs short of a full circle, polylines and polygons (so far)".into(),
            });
        }
        _ => {}
    }
    if scene.mode == Mode::MedialAxis {
        if let Some(i) = scene
            .sites
            .iter()
            .position(|s| matches!(s.kind, SiteKind::Algebraic { .. }))
        {
            return Err(Error::Unsupported {
                site: i,
                kind: "algebraic".into(),
                message: "medial_axis mode is not computed for algebraic curves yet".into(),
            });
        }
    }
    let fields = SiteField::for_scene_with(scene, &options.fields)?;
    let params = subdivision::Params {
        domain: scene.domain,
        epsilon: scene.epsilon,
        max_box: options.max_box,
        parallel: options.parallel,
    };
    let mut out = subdivision::run(&fields, &params);
    let curves: Vec<serde_json::Value> = fields
        .iter()
        .enumerate()
        .filter_map(|(i, f)| match f {
            SiteField::Algebraic(a) => {
                let mut s = a.stats();
                s["site"] = serde_json::json!(i);
                Some(s)
            }
            _ => None,
        })
        .collect();
    if !curves.is_empty() {
        out.complex
            .stats
            .insert("algebraic".into(), serde_json::json!(curves));
    }
    Ok(Computation {
        complex: out.complex,
        boxes: out.leaves.iter().map(|l| (l.aabb, l.sites.len())).collect(),
    })
}

/// Runs an incremental computation and records its time and engine in `stats`.
fn timed_incremental(
    run: impl FnOnce() -> Result<VoronoiComplex, Error>,
) -> Result<Computation, Error> {
    let start = std::time::Instant::now();
    let mut complex = run()?;
    let stats = &mut complex.stats;
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
        .sites
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
