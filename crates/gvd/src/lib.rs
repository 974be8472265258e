//! # gvd — generalized Voronoi diagrams in the plane
//!
//! Reads a [`Scene`] (sites in a domain), computes its [`VoronoiComplex`] (vertices,
//! edges as polylines within epsilon, cells), and writes it as JSON or SVG.
//!
//! ```no_run
//! let scene = gvd::Scene::from_json(&std::fs::read_to_string("scene.json").unwrap()).unwrap();
//! let diagram = gvd::compute(&scene, &gvd::Options::default()).unwrap();
//! println!("{} vertices, {} edges", diagram.vertices.len(), diagram.edges.len());
//! ```

pub mod cells;
pub mod complex;
mod compute;
pub mod error;
pub mod geom;
pub mod incremental;
pub mod io;
pub mod num;
pub mod offset;
mod par;
pub mod scene;
pub mod site;
pub mod subdivision;
pub mod verify;

pub use complex::VoronoiComplex;
pub use compute::{compute, compute_with_boxes, Computation, Engine, Options};
pub use error::Error;
pub use scene::Scene;
