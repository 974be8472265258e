//! # gvd — generalized Voronoi diagrams in the plane
//!
//! Build a [`Scene`] (sites in a domain, checked as they are added), compute its
//! [`VoronoiComplex`] (vertices with their generators, edges as polylines within
//! epsilon, cells), check it independently with [`verify()`], derive offsets with
//! [`offset()`], and write it with [`io`].
//!
//! ```
//! use gvd::{compute, Mode, Options, Scene, Site};
//!
//! let scene = Scene::new(
//!     gvd::Aabb::from_array([-2.0, -2.0, 2.0, 2.0]),
//!     1e-3,
//!     Mode::Voronoi,
//!     vec![
//!         Site::point([1.5, 1.5]),
//!         Site::point([-1.5, 1.0]),
//!         Site::polygon([[[-1.0, -1.0], [0.0, -1.0], [0.0, 0.0]]]),
//!         Site::arc([1.0, -1.0], 0.5, 0.0, std::f64::consts::PI),
//!     ],
//! )?;
//! let diagram = compute(&scene, &Options::default())?;
//! assert!(gvd::verify(&scene, &diagram, &gvd::VerifyOptions::default())?.passed);
//! println!("{} vertices, {} edges", diagram.vertices.len(), diagram.edges.len());
//! # Ok::<(), gvd::Error>(())
//! ```
//!
//! Scenes also come from JSON ([`Scene::from_json`], the format of
//! `docs/SCENE_FORMAT.md`). The papers are cited by key; see `docs/REFERENCES.md`.

#![warn(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links)]
#![warn(clippy::print_stdout, clippy::print_stderr)]

mod clearance;
pub mod complex;
mod compute;
mod control;
mod disjoint_sets;
mod error;
mod freeform;
pub mod geom;
mod incremental;
pub mod io;
mod num;
pub mod offset;
mod par;
pub mod scene;
mod site;
mod subdivision;
pub mod verify;

pub use complex::prune::Pruning;
pub use complex::VoronoiComplex;
pub use compute::{
    compute, compute_with_boxes, Computation, Engine, IncrementalOptions, Options,
    SubdivisionOptions,
};
pub use control::{Control, Progress, ProgressFn};
pub use error::Error;
pub use geom::{Aabb, Point};
pub use offset::{offset, offset_scene, Offset};
pub use scene::{Metric, Mode, Scene, SceneBuilder, Site, SiteKind};
pub use site::FieldOptions;
pub use subdivision::soft::Filters as SoftFilters;
pub use subdivision::Limits;
pub use verify::{verify, Report, VerifyOptions};

/// Engine entry points and numerics for benchmarks and engine-level tests. No
/// stability promise: use [`compute`] in applications.
pub mod internals {
    pub use crate::complex::cells::build_cells;
    pub use crate::incremental::{points_voronoi, Face, PointDiagram};
    pub use crate::num::bernstein::{Bernstein1, Bernstein2, Bernstein3};
    pub use crate::num::poly::Poly;
    pub use crate::num::roots;
    pub use crate::num::Interval;
    pub use crate::site::{AlgebraicField, DistanceField, SiteField};
    pub use crate::subdivision::{run as subdivide, Params as SubdivisionParams};
}
