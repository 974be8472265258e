//! The library's entry point: a scene in, its Voronoi complex out.

use crate::complex::VoronoiComplex;
use crate::error::Error;
use crate::geom::Aabb;
use crate::scene::Scene;
use crate::site::{FieldOptions, SiteField};
use crate::subdivision;

/// How to compute a diagram.
#[derive(Clone, Debug)]
pub struct Options {
    /// Boxes holding two or more sites are split until no longer than this (the
    /// "maximum admissible box size" of Emiris et al., for smoother curves); `None`
    /// lets the certificates decide alone.
    pub max_box: Option<f64>,
    /// Process independent boxes in parallel (same result either way).
    pub parallel: bool,
    /// Choices among equivalent distance fields (closed forms or the general paths).
    pub fields: FieldOptions,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            max_box: None,
            parallel: cfg!(feature = "parallel"),
            fields: FieldOptions::default(),
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

/// [`compute`], also returning the subdivision's leaves.
pub fn compute_with_boxes(scene: &Scene, options: &Options) -> Result<Computation, Error> {
    let fields = SiteField::for_scene_with(scene, &options.fields)?;
    let params = subdivision::Params {
        domain: scene.domain,
        epsilon: scene.epsilon,
        max_box: options.max_box,
        parallel: options.parallel,
    };
    let out = subdivision::run(&fields, &params);
    Ok(Computation {
        complex: out.complex,
        boxes: out.leaves.iter().map(|l| (l.aabb, l.sites.len())).collect(),
    })
}
