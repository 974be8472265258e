//! The distance from a point to the curve: a best-first search of the enclosure for the
//! nearest chord or sample, then Newton's method on the foot-point system
//! `f(p) = 0`, `(p − q) × ∇f(p) = 0` (the Lagrange conditions of `min |p − q|` on the
//! curve) from there. The answer is the least of the refined foot and the samples met
//! (all points of the curve to f64 accuracy), so it is never above a true distance to a
//! point of the curve by more than f64 rounding.

use super::dense::Jet;
use super::enclosure::{Enclosure, NONE};
use super::holds_no_foot;
use crate::geom::{segment_foot, Aabb, Point};

/// The distance to the curve and a nearest point of it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Nearest {
    pub dist: f64,
    pub foot: Point,
}

/// The nearest point of the curve to `q`, searched in the enclosure nodes `from` (and
/// their descendants), which must hold every point of the curve that can be nearest to
/// `q`; `reach` bounds how far Newton's method may move from its start (a few leaf
/// sizes). `None` when those nodes hold no sample.
pub(super) fn nearest(
    e: &Enclosure,
    jet: &Jet,
    clip: &Aabb,
    q: Point,
    from: &[u32],
    reach: f64,
) -> Option<Nearest> {
    // depth-first, nearer node first
    let mut stack: Vec<(f64, u32)> = Vec::with_capacity(96 + from.len());
    stack.extend(
        from.iter()
            .map(|&n| (box_distance(q, &e.nodes[n as usize].bbox), n)),
    );
    stack.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
    let mut sample = (f64::INFINITY, q);
    let mut chord = (f64::INFINITY, q);
    let at_q = Aabb::new(q, q);
    while let Some((lo, n)) = stack.pop() {
        let node = &e.nodes[n as usize];
        if lo > sample.0.min(chord.0) || holds_no_foot(clip, &at_q, &node.bbox, &node.normal) {
            continue;
        }
        if node.leaf == NONE {
            let mut kids: [(f64, u32); 2] = [(f64::INFINITY, NONE); 2];
            for (k, &c) in e.children(n).iter().enumerate().take(2) {
                kids[k] = (box_distance(q, &e.nodes[c as usize].bbox), c);
            }
            if kids[0].0 < kids[1].0 {
                kids.swap(0, 1);
            }
            for kid in kids {
                if kid.1 != NONE && kid.0 <= sample.0.min(chord.0) {
                    stack.push(kid);
                }
            }
            continue;
        }
        let leaf = &e.leaves[node.leaf as usize];
        for &s in &leaf.samples {
            let d = q.dist(s);
            if d < sample.0 {
                sample = (d, s);
            }
        }
        if let Some((a, b)) = leaf.chord {
            let p = segment_foot(q, a, b);
            let d = q.dist(p);
            if d < chord.0 {
                chord = (d, p);
            }
        }
    }
    if !sample.0.is_finite() {
        return None;
    }
    let start = if chord.0 < sample.0 {
        chord.1
    } else {
        sample.1
    };
    let mut best = Nearest {
        dist: sample.0,
        foot: sample.1,
    };
    if let Some(p) = foot_newton(jet, clip, q, start, reach) {
        let d = q.dist(p);
        if d < best.dist {
            best = Nearest { dist: d, foot: p };
        }
    }
    Some(best)
}

/// The distance from `q` to the box `b` (0 inside).
fn box_distance(q: Point, b: &Aabb) -> f64 {
    let dx = (b.min.x - q.x).max(q.x - b.max.x).max(0.0);
    let dy = (b.min.y - q.y).max(q.y - b.max.y).max(0.0);
    (dx * dx + dy * dy).sqrt()
}

/// Newton's method on the foot-point system from `start`; `None` when it leaves the
/// clip box or moves farther than `reach`, or ends off the curve.
fn foot_newton(jet: &Jet, clip: &Aabb, q: Point, start: Point, reach: f64) -> Option<Point> {
    let mut p = start;
    let scale = q.x.abs().max(q.y.abs()).max(p.x.abs()).max(p.y.abs()) + reach;
    for _ in 0..32 {
        let (x, y) = (p.x, p.y);
        let f = jet.f.eval(x, y);
        let (fx, fy) = (jet.fx.eval(x, y), jet.fy.eval(x, y));
        let (fxx, fxy, fyy) = (jet.fxx.eval(x, y), jet.fxy.eval(x, y), jet.fyy.eval(x, y));
        let r = p - q;
        let g = r.x * fy - r.y * fx;
        let (j11, j12) = (fx, fy);
        let j21 = fy + r.x * fxy - r.y * fxx;
        let j22 = r.x * fyy - fx - r.y * fxy;
        let det = j11 * j22 - j12 * j21;
        if !(det.is_finite() && det != 0.0) {
            break;
        }
        let step = Point::new((j22 * f - j12 * g) / det, (j11 * g - j21 * f) / det);
        let next = p - step;
        if !(next.x.is_finite() && next.y.is_finite()) || next.dist(start) > reach {
            return None;
        }
        p = next;
        if step.norm() <= 4.0 * f64::EPSILON * scale {
            break;
        }
    }
    let level = 1e3 * f64::EPSILON * jet.f.magnitude(p.x, p.y);
    (clip.contains(p) && jet.f.eval(p.x, p.y).abs() <= level).then_some(p)
}
