//! Tangent (G1) joints in the segment engine's raw diagram.
//!
//! A point `P` that ends exactly two features `F₁`, `F₂` (segments or arcs) whose
//! tangents there agree is a tangent joint: their normals at `P` are one line `N`.
//! Every point `x` of `N` (up to the centres of curvature on the concave side) has
//! its foot on both features at `P`, so `d(x, F₁) = d(x, F₂) = d(x, P) = |x − P|`,
//! and on either side of `N` one feature is strictly nearer than `P`. So `P`'s face
//! has zero area and `N` is an edge between `F₁` and `F₂`, with `P` on it (a vertex
//! where the edge touches the sites).
//!
//! The engine leaves `P`'s face as a sliver along `N`: one side is a chain of
//! separators `P/F₁`, the other of separators `P/F₂`, and at each end of the sliver
//! (a tip, where a third generator `X` ties with the three) the two sides are joined
//! by edges `P/X` of zero length up to rounding. The first feature inserted at `P`
//! gave its side a vertex at `P` (clearance 0). [`collapse`] turns the sliver into
//! the edge `F₁/F₂`: the side through `P`'s vertex is relabelled, the other side is
//! dropped, and the tip edges are contracted.

use super::{ArcSpec, Gen, RawEdge, RawVertex};
use crate::geom::Point;
use rustc_hash::FxHashMap;
use smallvec::SmallVec;

/// How far from opposite two features' directions away from a shared end may be
/// (the sine of the angle between their normals) for a tangent joint: within
/// rounding of the ends' and tangents' coordinates.
const TANGENT_TOL: f64 = 1e-9;

/// A tangent joint: its two features, where it is, and the unit normal there (the
/// direction of the edge between the features).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Joint {
    features: [Gen; 2],
    at: Point,
    normal: Point,
}

impl Joint {
    /// The foot of `q` on the joint's normal.
    pub(crate) fn onto(&self, q: Point) -> Point {
        self.at + self.normal * (q - self.at).dot(self.normal)
    }
}

/// Per point generator, the features ending there with their unit directions away
/// from it (beyond the end, along the tangent).
fn ends_at(
    points: &[Point],
    segments: &[[u32; 2]],
    arcs: &[ArcSpec],
) -> Vec<SmallVec<[(Gen, Point); 2]>> {
    let mut at: Vec<SmallVec<[(Gen, Point); 2]>> = vec![SmallVec::new(); points.len()];
    for (k, &[a, b]) in segments.iter().enumerate() {
        let d = points[b as usize] - points[a as usize];
        let d = d * (1.0 / d.norm());
        at[a as usize].push((Gen::Segment(k as u32), d * -1.0));
        at[b as usize].push((Gen::Segment(k as u32), d));
    }
    for (k, arc) in arcs.iter().enumerate() {
        // The counter-clockwise tangent, backwards at the start, forwards at the end.
        for (end, angle, sign) in [(0, arc.start, -1.0), (1, arc.start + arc.span, 1.0)] {
            let tangent = Point::new(-angle.sin(), angle.cos()) * sign;
            at[arc.ends[end] as usize].push((Gen::Arc(k as u32), tangent));
        }
    }
    at
}

/// The tangent joints: each point generator that ends exactly two features whose
/// unit directions away from it `a₁`, `a₂` satisfy `|a₁ + a₂| ≤ TANGENT_TOL`, with
/// those two features.
pub(crate) fn tangent_joints(
    points: &[Point],
    segments: &[[u32; 2]],
    arcs: &[ArcSpec],
) -> FxHashMap<u32, Joint> {
    (0u32..)
        .zip(ends_at(points, segments, arcs))
        .filter_map(|(p, f)| match f[..] {
            [(f1, a1), (f2, a2)] if (a1 + a2).norm() <= TANGENT_TOL => {
                let here = points[p as usize];
                // The normal from an arc's centre (exact where the joint is axis-aligned
                // at exact coordinates), else the segment's perpendicular.
                let normal = [f1, f2]
                    .iter()
                    .find_map(|&f| match f {
                        Gen::Arc(k) => Some(here - arcs[k as usize].c),
                        _ => None,
                    })
                    .unwrap_or(a1.perp());
                let joint = Joint {
                    features: [f1, f2],
                    at: here,
                    normal: normal * (1.0 / normal.norm()),
                };
                Some((p, joint))
            }
            _ => None,
        })
        .collect()
}

/// How near two features' directions away from a shared end may be for a cusp
/// ([`find_cusp`]): near cusps a few 1e-9 apart gave the same wrong diagrams as exact
/// ones (their ties hold to rounding), from 1e-8 on they pass `gvd verify`.
const CUSP_TOL: f64 = 1e-7;

/// The first cusp: a point generator and two features that leave it in one direction
/// (`|a₁ − a₂| ≤ CUSP_TOL`; an arc and a segment or another arc, tangent there and
/// turning back). Their separators at the point lie on one line, their common normal,
/// and the second feature inserted is as near as the point all along the first one's
/// separator there (nearer to second order on one side): its region's boundary runs
/// along an old edge, which the conflict tree cannot express, and the engine's diagram
/// was wrong there (edges 0.2–0.3 off beside arcs of radius 0.25).
pub(crate) fn find_cusp(
    points: &[Point],
    segments: &[[u32; 2]],
    arcs: &[ArcSpec],
) -> Option<(u32, Gen, Gen)> {
    (0u32..)
        .zip(ends_at(points, segments, arcs))
        .find_map(|(p, f)| {
            f.iter().enumerate().find_map(|(i, &(f1, a1))| {
                f[i + 1..]
                    .iter()
                    .find(|&&(_, a2)| (a1 - a2).norm() <= CUSP_TOL)
                    .map(|&(f2, _)| (p, f1, f2))
            })
        })
}

/// Collapses the sliver of every tangent joint (see the module doc) in the raw
/// diagram: the separators `P/F` on the side of `P`'s vertex become edges `F₁/F₂`
/// and their vertices list both features, the other side's separators and the tip
/// edges `P/X` are removed. Returns the tips' vertex pairs, to be merged. A joint
/// without a vertex at `P` on either side, or with a tip edge longer than `tip_tol`
/// (by `length`), is left as it is.
pub(crate) fn collapse(
    joints: &FxHashMap<u32, Joint>,
    tip_tol: f64,
    vertices: &mut [RawVertex],
    edges: &mut Vec<RawEdge>,
    length: impl Fn(&RawEdge) -> f64,
) -> Vec<[usize; 2]> {
    if joints.is_empty() {
        return Vec::new();
    }
    // The joint an edge belongs to, and the feature across it (`None` for a tip).
    let role = |e: &RawEdge| -> Option<(u32, Option<usize>)> {
        let (p, other) = match e.gens {
            [Gen::Point(p), o] if joints.contains_key(&p) => (p, o),
            [o, Gen::Point(p)] if joints.contains_key(&p) => (p, o),
            _ => return None,
        };
        Some((p, joints[&p].features.iter().position(|&f| f == other)))
    };
    // The side through P's vertex, per joint; none where a tip edge is longer than
    // `tip_tol` (it is zero up to rounding): then the face is no sliver and stays.
    let mut keep: FxHashMap<u32, usize> = FxHashMap::default();
    for e in edges.iter() {
        if let Some((p, Some(side))) = role(e) {
            if e.ends.iter().any(|&v| vertices[v].t == 0.0) {
                keep.insert(p, side);
            }
        }
    }
    for e in edges.iter() {
        if let Some((p, None)) = role(e) {
            if length(e) > tip_tol {
                keep.remove(&p);
            }
        }
    }
    let mut merges = Vec::new();
    edges.retain_mut(|e| {
        let Some((p, side)) = role(e) else {
            return true;
        };
        let Some(&kept) = keep.get(&p) else {
            return true;
        };
        match side {
            Some(s) if s == kept => {
                let features = joints[&p].features;
                e.gens = features;
                for v in e.ends {
                    for f in features {
                        if !vertices[v].gens.contains(&f) {
                            vertices[v].gens.push(f);
                        }
                    }
                }
                true
            }
            Some(_) => false,
            None => {
                merges.push(e.ends);
                false
            }
        }
    });
    onto_normals(joints, vertices, edges);
    merges
}

/// Puts every edge between a joint's two features that leaves the joint's own vertex
/// (clearance 0 at the joint), with its end vertices, on the joint's normal, where it
/// lies: the engine's points are on that line only up to rounding. The edge's polyline
/// is projected onto the normal when it is drawn ([`RawEdge::on_normal`]).
fn onto_normals(joints: &FxHashMap<u32, Joint>, vertices: &mut [RawVertex], edges: &mut [RawEdge]) {
    let by_pair: FxHashMap<[Gen; 2], (u32, &Joint)> = joints
        .iter()
        .flat_map(|(&p, j)| {
            let [a, b] = j.features;
            [([a, b], (p, j)), ([b, a], (p, j))]
        })
        .collect();
    for e in edges {
        let Some(&(p, joint)) = by_pair.get(&e.gens) else {
            continue;
        };
        let at_joint = |v: usize| vertices[v].t == 0.0 && vertices[v].at == joint.at;
        if e.ends.iter().any(|&v| at_joint(v)) {
            e.on_normal = Some(p);
            // The far end too: a vertex of the two features (and a third generator)
            // on the normal, which the polyline's ends are taken from.
            for v in e.ends {
                vertices[v].at = joint.onto(vertices[v].at);
            }
        }
    }
}
