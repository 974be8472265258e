//! The topology-oriented incremental engine (SI92; Imai 1996; Hel01, keys in
//! `docs/REFERENCES.md`): sites go in one at a time, each insertion a combinatorial
//! update of a planar graph under exact (or filtered) signs, so the result is always a
//! valid graph.
//!
//! * `points/`: the point engine, the exact Voronoi diagram of Euclidean points.
//! * `segments_arcs/`: the segment-and-arc engine, built on the points' graph, with its
//!   tangent joints.
//! * `scene_adapter/`: scenes of points, segments, arcs, polylines and polygons turned
//!   into the engines' generators, and their raw graph into the scene mode's
//!   [`crate::complex::VoronoiComplex`].
//! * `bisector_form.rs`: bisectors in Held's offset-parameter form (`--bisectors`).

mod bisector_form;
mod points;
mod scene_adapter;
pub(crate) mod segments_arcs;

pub use points::{add_point_bisectors, points_voronoi, Face, PointDiagram};

use crate::geom::Aabb;

/// How far from the origin (in either coordinate) a segment's end may lie and still be
/// the origin of its line's coordinates ([`crate::geom::predicates::segment_anchor`]):
/// `2^20` times the domain's largest coordinate, so that points of the domain keep all
/// but 20 bits of their precision.
fn anchor_reach(domain: &Aabb) -> f64 {
    let largest = domain.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    ANCHOR_SPAN * largest
}

/// [`anchor_reach`] over the domain's largest coordinate.
const ANCHOR_SPAN: f64 = (1u64 << 20) as f64;
pub use scene_adapter::{scene_voronoi, supports, supports_site};
