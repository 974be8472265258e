//! Occlusion between two algebraic curves: when a curve `B` lies on one side of another
//! curve `A`, `σ·f_A ≥ 0` on `B` (`σ = ±1`), then `A` is at least as near as `B` at
//! every point `q` of `A`'s clip box with `σ·f_A(q) < 0`. The segment from `q` to its
//! nearest point `β` of `B` stays in the (convex) clip box and `f_A` changes sign on it,
//! so it meets `A` at some `z`: `d_A(q) ≤ |q − z| ≤ |q − β| = d_B(q)`.
//!
//! This proves `d_A ≤ d_B` where the difference has a double zero and no interval bound
//! can: along the common normal of two tangent curves (Shou et al. 2011, examples 3 and
//! 4, whose circles touch), where the feet on both curves are the contact point.
//!
//! **The side of `B`.** Every enclosure leaf of `B` is searched with Bernstein forms: a
//! box is settled when `f_B` has no zero in it, when `σ·f_A > 0` on it, or when
//! `g = σ·f_A − λ·f_B > 0` on it (`g = σ·f_A` on `B`; `λ` cancels the gradient of `g`
//! at the box's centre, so `g` is second order across `B` and the boxes left close in
//! on the contact points instead of on a band along `B`). Boxes left at
//! [`CONTACT_SIZE`] are *contacts*: `B` may cross to the other side of `A` only inside
//! them, so the argument above holds up to their width. Exact tangency cannot be
//! certified in f64; the contacts are counted in the site's `stats` instead.

use super::AlgebraicField;
use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::Bernstein2;

/// The side of site `other` with respect to a curve.
#[derive(Clone, Debug)]
pub(super) struct Side {
    /// The other site's index.
    pub site: usize,
    /// `σ`: `σ·f ≥ 0` on the other curve outside the contacts.
    pub sign: f64,
    /// Boxes where the other curve may cross to the side `σ·f < 0`.
    pub contacts: Vec<Aabb>,
}

/// Contact boxes are this small beside the clip box.
const CONTACT_SIZE: f64 = 1e-8;
/// Most contact boxes per pair: more means the curves run together over a stretch
/// (they overlap or cross), and the pair is left to the distance bounds.
const MAX_CONTACTS: usize = 64;
/// Most boxes searched per pair, and over all pairs of a scene (bounded work; pairs
/// left unsearched get no side, and their boxes are decided by the bounds alone).
const MAX_BOXES: usize = 1 << 16;
pub(super) const MAX_SCENE_BOXES: usize = 1 << 21;

/// The side of curve `b` with respect to curve `a` (`None`: `b` leaves `a`'s clip box,
/// crosses `a`, or the search ran out of work); `spent` counts the boxes searched.
pub(super) fn side(a: &AlgebraicField, b: &AlgebraicField, spent: &mut usize) -> Option<Side> {
    if !a.clip.contains_box(&b.clip) {
        return None;
    }
    // the sign of `f_a` where it is largest on `b`'s certified points
    let sign = b
        .enclosure
        .witnesses
        .iter()
        .map(|w| a.jet.f.eval(w.p.x, w.p.y))
        .max_by(|u, v| u.abs().total_cmp(&v.abs()))
        .filter(|v| *v != 0.0)?
        .signum();
    let min_size = CONTACT_SIZE * a.clip.longest_side().max(b.clip.longest_side());
    let mut contacts = Vec::new();
    // every point of `b` lies in its clip box and in the nodes of its enclosure, which
    // are searched from the root down; below a leaf, its box is split in quarters
    let mut work: Vec<(Aabb, u32)> = b
        .enclosure
        .root()
        .and_then(|r| Some((b.enclosure.nodes[r as usize].bbox.intersection(&b.clip)?, r)))
        .into_iter()
        .collect();
    let mut boxes = 0;
    while let Some((k, node)) = work.pop() {
        boxes += 1;
        *spent += 1;
        if boxes > MAX_BOXES || *spent > MAX_SCENE_BOXES {
            return None;
        }
        let fb = Bernstein2::from_poly(&b.poly, &k);
        if fb.range().excludes_zero() {
            continue;
        }
        let fa = Bernstein2::from_poly(&a.poly, &k);
        let range = fa.range();
        let (lo, hi) = if sign > 0.0 {
            (range.lo, range.hi)
        } else {
            (-range.hi, -range.lo)
        };
        if lo > 0.0 {
            continue;
        }
        if node != super::NONE && !b.enclosure.children(node).is_empty() {
            work.extend(b.enclosure.children(node).iter().filter_map(|&c| {
                let bbox = b.enclosure.nodes[c as usize].bbox.intersection(&b.clip)?;
                Some((bbox, c))
            }));
            continue;
        }
        if hi < 0.0 && crosses(b, &k) {
            return None; // `b` runs on the other side of `a`
        }
        if second_order_positive(a, b, &fa, &fb, sign, &k) {
            continue;
        }
        if k.longest_side() <= min_size {
            contacts.push(k);
            if contacts.len() > MAX_CONTACTS {
                return None;
            }
            continue;
        }
        let (l, r) = k.split(Axis::X, k.center().x);
        for h in [l, r] {
            let (lo, hi) = h.split(Axis::Y, h.center().y);
            work.extend([(lo, super::NONE), (hi, super::NONE)]);
        }
    }
    Some(Side {
        site: b.site,
        sign,
        contacts: crate::geom::clusters(contacts),
    })
}

/// True when `g = σ·f_a − λ·f_b > 0` over `k`, with `λ` making `∇g = 0` at the box's
/// centre (least squares): then `σ·f_a > 0` at every point of `b` in `k`.
fn second_order_positive(
    a: &AlgebraicField,
    b: &AlgebraicField,
    fa: &Bernstein2,
    fb: &Bernstein2,
    sign: f64,
    k: &Aabb,
) -> bool {
    let c = k.center();
    let ga = Point::new(a.jet.fx.eval(c.x, c.y), a.jet.fy.eval(c.x, c.y)) * sign;
    let gb = Point::new(b.jet.fx.eval(c.x, c.y), b.jet.fy.eval(c.x, c.y));
    let norm = gb.x * gb.x + gb.y * gb.y;
    if norm.is_nan() || norm <= 0.0 {
        return false;
    }
    let lambda = (ga.x * gb.x + ga.y * gb.y) / norm;
    let constant = |v: f64| Bernstein2 {
        deg: [0, 0],
        coef: vec![v],
        err: 0.0,
    };
    let g = fa.mul(&constant(sign)).sub(&fb.mul(&constant(lambda)));
    g.range().lo > 0.0
}

/// True when `f_b` has opposite signs, beyond rounding, at two corners of `k`: the
/// curve `b` passes through `k`.
fn crosses(b: &AlgebraicField, k: &Aabb) -> bool {
    let values = k.corners().map(|c| {
        let v = b.jet.f.eval(c.x, c.y);
        let level = 1e3 * f64::EPSILON * b.jet.f.magnitude(c.x, c.y);
        if v.abs() > level {
            v.signum()
        } else {
            0.0
        }
    });
    values.contains(&1.0) && values.contains(&-1.0)
}
