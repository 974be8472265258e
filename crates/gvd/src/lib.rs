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

pub mod complex;
pub mod error;
pub mod geom;
pub mod num;
pub mod scene;

pub use complex::VoronoiComplex;
pub use error::Error;
pub use scene::Scene;
