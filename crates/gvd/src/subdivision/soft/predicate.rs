//! The soft predicates of one box (YSL12 ¶17–18): its clearance, its conservative
//! feature set φ̃(B), and the termination predicate C = C0 ∧ C1 ∧ C2.

use super::Filters;
use crate::geom::{Aabb, Point};
use crate::site::polygonal::{Polygonal, Shape};
use smallvec::SmallVec;

/// A sorted list of features.
pub type FeatureSet = SmallVec<[u32; 4]>;

/// Parents with at most this many features keep their distances on the stack.
const STACK_DISTANCES: usize = 32;

/// What one box knows: `φ̃(B)` and `Cl(m_B)`.
#[derive(Clone, Debug)]
pub struct BoxSet {
    /// φ̃(B), sorted (inline up to four features, as most leaves hold).
    pub set: FeatureSet,
    /// The clearance of the box's centre (0 in the material).
    pub clearance: f64,
}

/// `r_B`: half the box's diagonal.
pub fn radius(b: &Aabb) -> f64 {
    0.5 * b.width().hypot(b.height())
}

/// φ̃(B) from the parent's set (the distributional property, Lemma 3(iii)): the
/// features `f` with `Sep(m_B, f) ≤ Cl(m_B) + 2 r_B` (4) whose zone (Z*, Z or none,
/// per the filters) meets the disc of radius `r_B` about `m_B` (which holds `B`).
/// Conservative (Lemma 3(i)): a point `q ∈ B` with nearest feature `f` has
/// `q ∈ Z*(f) ∩ B` and `Sep(m_B, f) ≤ r_B + Cl(q) ≤ Cl(m_B) + 2 r_B`. `Cl(m_B)` is the
/// least distance over the parent's set, which holds `m_B`'s nearest feature.
///
/// The zone is tested against the box, not against the influence disc `D(B)` as
/// ¶17 words it: `D(B)` reaches past a nearest corner into the zones of the corner's
/// own edges, which would then belong to every box on a corner's bisectors, and
/// Lemma 3(ii) (convergence) would fail.
pub fn feature_set(poly: &Polygonal, parent: &[u32], b: &Aabb, filters: &Filters) -> BoxSet {
    let m = b.center();
    let r = radius(b);
    let (mut on_stack, mut on_heap) = ([0.0; STACK_DISTANCES], Vec::new());
    let dists: &mut [f64] = if parent.len() <= STACK_DISTANCES {
        &mut on_stack[..parent.len()]
    } else {
        on_heap.resize(parent.len(), 0.0);
        &mut on_heap
    };
    for (d, &f) in dists.iter_mut().zip(parent) {
        *d = poly.features[f as usize].distance(m);
    }
    let nearest = dists.iter().copied().fold(f64::INFINITY, f64::min);
    let clearance = if nearest.is_finite() && poly.free(m) {
        nearest
    } else {
        0.0
    };
    let reach = clearance + 2.0 * r;
    let set = parent
        .iter()
        .zip(dists.iter())
        .filter(|(&f, &d)| {
            let feat = &poly.features[f as usize];
            d <= reach
                && (!filters.zone
                    || if filters.oriented {
                        feat.oriented_zone.distance(m) <= r
                    } else {
                        feat.zone.distance(m) <= r
                    })
        })
        .map(|(&f, _)| f)
        .collect();
    BoxSet { set, clearance }
}

/// `C(B) = C0 ∧ C1 ∧ C2` (YSL12 ¶18): at most three features; where the box is not
/// free of features (`Cl(m_B) < r_B`) the set is inseparable (or, with the filter of
/// ¶25(a), two edges); and no special parabola meets a special box.
pub fn holds(poly: &Polygonal, bs: &BoxSet, b: &Aabb, filters: &Filters) -> bool {
    let set = &bs.set;
    if set.len() > 3 {
        return false;
    }
    let r = radius(b);
    if bs.clearance < r {
        let two_edges = set.len() == 2 && set.iter().all(|&f| poly.features[f as usize].is_edge());
        if !(poly.inseparable(set) || (filters.two_edge && two_edges)) {
            return false;
        }
        return true;
    }
    c2(poly, set, b)
}

/// C2: a box is `(f, g)`-special when its four corners are labelled by the edge `g`,
/// it is free of features, and the corner `f` with `g` is a parabola generator (`f`
/// strictly on `g`'s free side, not an end of `g`). The paper then bounds `Cl(m_B)` by
/// `3 r_B² / (2 α)`; here the question that bound answers — can the parabola of `f`
/// and `g` enter `B` between its corners? — is decided exactly: `h(q) = |q − f|² −
/// s_g(q)²` is convex (its Hessian `2 u uᵀ` has rank one), with no critical point, so
/// its least value over `B` lies on a side, where it is a quadratic in one variable.
/// C2 holds when that least value is positive.
fn c2(poly: &Polygonal, set: &[u32], b: &Aabb) -> bool {
    for &g in set {
        let Shape::Edge(a, e) = poly.features[g as usize].shape else {
            continue;
        };
        let side = poly.features[g as usize].side.unwrap_or((e - a).perp());
        for &f in set {
            let Shape::Corner(c) = poly.features[f as usize].shape else {
                continue;
            };
            if poly.features[g as usize].links.contains(&f) {
                continue;
            }
            let n = side * (1.0 / side.norm());
            let cy = (c - a).dot(n);
            let oriented = poly.features[g as usize].side.is_some();
            if cy.abs() <= 1e-12 * poly.scale || (oriented && cy < 0.0) {
                continue;
            }
            if !b.corners().iter().all(|&q| label(poly, set, q) == Some(g)) {
                continue;
            }
            if least_on_boundary(c, a, n, b) <= 0.0 {
                return false;
            }
        }
    }
    true
}

/// λ(q): the nearest feature of `set` whose oriented zone holds `q` (ties to the
/// lower index).
pub fn label(poly: &Polygonal, set: &[u32], q: Point) -> Option<u32> {
    let tol = 1e-12 * poly.scale;
    set.iter()
        .filter(|&&f| poly.features[f as usize].oriented_zone.contains(q, tol))
        .map(|&f| (f, poly.features[f as usize].distance(q)))
        .min_by(|x, y| x.1.total_cmp(&y.1).then(x.0.cmp(&y.0)))
        .map(|x| x.0)
}

/// The least of `|q − c|² − (n·(q − a))²` over the sides of `b`.
fn least_on_boundary(c: Point, a: Point, n: Point, b: &Aabb) -> f64 {
    let k = b.corners();
    let mut least = f64::INFINITY;
    for i in 0..4 {
        let (p, d) = (k[i], k[(i + 1) % 4] - k[i]);
        let (w, s0, s1) = (p - c, n.dot(p - a), n.dot(d));
        let qa = d.dot(d) - s1 * s1;
        let qb = 2.0 * (w.dot(d) - s0 * s1);
        let qc = w.dot(w) - s0 * s0;
        let at = |t: f64| (qa * t + qb) * t + qc;
        least = least.min(at(0.0)).min(at(1.0));
        if qa > 0.0 {
            let t = -qb / (2.0 * qa);
            if (0.0..=1.0).contains(&t) {
                least = least.min(at(t));
            }
        }
    }
    least
}
