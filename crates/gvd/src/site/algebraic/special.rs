//! Special points of a curve: its singular points (`f = f_x = f_y = 0`: cusps, nodes,
//! isolated points), found by the certified solver of `num::roots` on the square system
//! `f_x = f_y = 0` with `f` as a side condition; and its contacts with the clip box's
//! sides that no sign change shows (tangencies), found by univariate isolation on each
//! side. Both become samples of the leaves holding them, so that distances near them
//! are right even where no side of a leaf sees the curve cross.

use super::dense::Jet;
use super::enclosure::{project, Enclosure, Witness};
use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::Bernstein2;
use crate::num::poly::Poly;
use crate::num::roots::{self, SystemOptions};

/// What the special-point analysis found.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Special {
    /// Certified simple critical points of `f` where `f` could not be excluded: nodes
    /// (self-crossings) and isolated points.
    pub singular_points: usize,
    /// Uncertified clusters of `f = f_x = f_y = 0` (cusps, tacnodes, higher
    /// singularities).
    pub singular_clusters: usize,
    /// Points where the curve touches a side of the clip box without crossing it.
    pub clip_contacts: usize,
    /// The size of the largest singular cluster (a non-isolated singular set when large).
    pub largest_cluster: f64,
}

/// Finds the special points of `{f = 0} ∩ clip` and adds them to the enclosure as
/// samples. A certified critical point where `f` vanishes to rounding level and no
/// certified crossing exists anywhere (a curve made of isolated points) becomes a
/// witness: the one place a witness rests on `f(p) = 0` to rounding rather than on a
/// sign change.
pub(super) fn analyse(f: &Poly, jet: &Jet, clip: &Aabb, e: &mut Enclosure) -> Special {
    let mut out = Special::default();
    let (fx, fy) = (f.partial(0), f.partial(1));
    let opts = SystemOptions {
        min_size: 1e-9 * clip.longest_side(),
        max_boxes: 1 << 15,
        noise: None,
        units: [1.0, 1.0],
    };
    let level = |p: Point| 1e3 * f64::EPSILON * jet.f.magnitude(p.x, p.y);
    let mut isolated = Vec::new();
    for root in roots::solve_system(&fx, &fy, std::slice::from_ref(f), clip, &opts) {
        let p = clip.clamp(root.point);
        if root.certified {
            out.singular_points += 1;
            if jet.f.eval(p.x, p.y).abs() <= level(p) {
                isolated.push(p);
            }
        } else {
            out.singular_clusters += 1;
            out.largest_cluster = out.largest_cluster.max(root.enclosure.longest_side());
        }
        let p = if jet.f.eval(p.x, p.y).abs() <= level(p) {
            Some(p)
        } else {
            project(jet, p, &root.enclosure)
        };
        if let Some(p) = p {
            e.add_sample(p);
        }
    }
    if e.witnesses.is_empty() {
        for p in isolated {
            e.add_witness(Witness { a: p, b: p, p });
        }
    }
    let form = Bernstein2::from_poly(f, clip);
    for (axis, at) in [(Axis::X, 0), (Axis::X, 1), (Axis::Y, 0), (Axis::Y, 1)] {
        let side = form.edge(axis, at);
        for r in roots::isolate(&side, 1e-12) {
            if r.certified {
                continue; // a crossing: the leaves' sides see it
            }
            let t = roots::refine(&side, r.lo, r.hi);
            let p = match (axis, at) {
                (Axis::X, 0) => clip.at(0.0, t),
                (Axis::X, _) => clip.at(1.0, t),
                (Axis::Y, 0) => clip.at(t, 0.0),
                (Axis::Y, _) => clip.at(t, 1.0),
            };
            if jet.f.eval(p.x, p.y).abs() <= level(p) && e.add_sample(p) {
                out.clip_contacts += 1;
            }
        }
    }
    out
}
