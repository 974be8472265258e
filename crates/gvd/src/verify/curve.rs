//! The checker's own distance to an algebraic curve `{f = 0} ∩ clip`, written apart from
//! the engine's `site/algebraic` (nothing shared but the polynomial type and intervals):
//! a quadtree over the clip box keeps the cells where the mean-value form
//! `f(c) + ∇f(B)·(B − c)` (natural interval extensions of the partials) may vanish,
//! down to a spacing of a quarter of epsilon; each kept cell contributes the crossings
//! of `f` along its lower and left sides (bisection) and its centre projected onto the
//! curve (gradient Newton). The distance at `q` starts from the nearest sample (a k-d
//! tree) and slides along the curve: step along the tangent to the projection of `q`,
//! project back onto `f = 0`, keep the best point.

use crate::geom::{Aabb, Point};
use crate::num::poly::Poly;
use crate::num::Interval;

/// Cells smaller than the clip box by this factor are not split (a floor on the work).
const MIN_CELL: f64 = 1.0 / 16384.0;

/// A densely sampled algebraic curve.
#[derive(Clone, Debug)]
pub(super) struct Curve {
    f: Poly,
    fx: Poly,
    fy: Poly,
    clip: Aabb,
    step: f64,
    /// samples in k-d order (see [`Curve::nearest_sample`])
    tree: Vec<Point>,
}

impl Curve {
    /// Samples `{f = 0} ∩ clip` at a spacing of about `spacing`.
    pub(super) fn new(f: &Poly, clip: Aabb, spacing: f64) -> Curve {
        let step = spacing.max(MIN_CELL * clip.longest_side());
        let mut c = Curve {
            fx: f.partial(0),
            fy: f.partial(1),
            f: f.clone(),
            clip,
            step,
            tree: Vec::new(),
        };
        let mut samples = Vec::new();
        let mut stack = vec![clip];
        while let Some(b) = stack.pop() {
            if !c.may_vanish(&b) {
                continue;
            }
            if b.longest_side() > step {
                let m = b.center();
                stack.push(Aabb::new(b.min, m));
                stack.push(Aabb::new(
                    Point::new(m.x, b.min.y),
                    Point::new(b.max.x, m.y),
                ));
                stack.push(Aabb::new(
                    Point::new(b.min.x, m.y),
                    Point::new(m.x, b.max.y),
                ));
                stack.push(Aabb::new(m, b.max));
                continue;
            }
            let [p00, p10, p11, p01] = b.corners();
            for (a, e) in [(p00, p10), (p00, p01), (p10, p11), (p01, p11)] {
                if let Some(p) = c.bisect(a, e) {
                    samples.push(p);
                }
            }
            if let Some(p) = c.project(b.center()) {
                if b.center().dist(p) <= b.longest_side() {
                    samples.push(p);
                }
            }
        }
        samples.retain(|p| clip.contains(*p));
        build_kd(&mut samples, 0);
        c.tree = samples;
        c
    }

    fn f_at(&self, p: Point) -> f64 {
        self.f.eval(p.x, p.y, 0.0)
    }

    fn grad(&self, p: Point) -> Point {
        Point::new(self.fx.eval(p.x, p.y, 0.0), self.fy.eval(p.x, p.y, 0.0))
    }

    /// The mean-value form of `f` over `b` may hold 0.
    fn may_vanish(&self, b: &Aabb) -> bool {
        let c = b.center();
        let z = Interval::point(0.0);
        let at = self
            .f
            .eval_interval(Interval::point(c.x), Interval::point(c.y), z);
        let gx = self.fx.eval_interval(b.x(), b.y(), z);
        let gy = self.fy.eval_interval(b.x(), b.y(), z);
        let v = at + gx * (b.x() - c.x) + gy * (b.y() - c.y);
        !v.excludes_zero()
    }

    /// The crossing of `f` on the segment `a`–`b` when its ends differ in sign
    /// (a crossing at `a` itself counts, one at `b` is left to the next cell).
    fn bisect(&self, a: Point, b: Point) -> Option<Point> {
        let (fa, fb) = (self.f_at(a), self.f_at(b));
        if fa == 0.0 {
            return Some(a);
        }
        if fb == 0.0 || (fa > 0.0) == (fb > 0.0) {
            return None;
        }
        let (mut lo, mut hi) = (a, b);
        for _ in 0..60 {
            let m = lo.lerp(hi, 0.5);
            if (self.f_at(m) > 0.0) == (fa > 0.0) {
                lo = m;
            } else {
                hi = m;
            }
        }
        Some(lo.lerp(hi, 0.5))
    }

    /// `p` moved onto `f = 0` by gradient Newton steps, if it converges.
    fn project(&self, mut p: Point) -> Option<Point> {
        for _ in 0..20 {
            let v = self.f_at(p);
            let g = self.grad(p);
            let g2 = g.dot(g);
            if v == 0.0 {
                return Some(p);
            }
            if !(g2 > 0.0 && g2.is_finite()) {
                return None;
            }
            let s = g * (v / g2);
            p = p - s;
            if s.norm() <= 1e-15 * (1.0 + p.norm()) {
                return Some(p);
            }
        }
        let g = self.grad(p).norm();
        (self.f_at(p).abs() <= 1e-9 * g * self.step).then_some(p)
    }

    /// The nearest point of the curve to `q` (`None`: no sample at all).
    pub(super) fn foot(&self, q: Point) -> Option<Point> {
        let mut best = self.nearest_sample(q)?;
        let mut p = best;
        for _ in 0..24 {
            let g = self.grad(p);
            let n = g.norm();
            if !(n > 0.0 && n.is_finite()) {
                break;
            }
            let t = Point::new(-g.y / n, g.x / n);
            let along = (q - p).dot(t).clamp(-self.step, self.step);
            let Some(next) = self.project(p + t * along) else {
                break;
            };
            if !self.clip.contains(next) {
                break;
            }
            p = next;
            if q.dist(p) < q.dist(best) {
                best = p;
            }
            if along.abs() <= 1e-13 * (1.0 + q.dist(p)) {
                break;
            }
        }
        Some(best)
    }

    /// The nearest sample to `q` (k-d tree search).
    fn nearest_sample(&self, q: Point) -> Option<Point> {
        let mut best = (f64::INFINITY, None);
        search_kd(&self.tree, 0, q, &mut best);
        best.1
    }
}

/// Something with a position in the plane, for the k-d tree.
pub(super) trait Located: Copy {
    fn at(&self) -> Point;
}

impl Located for Point {
    fn at(&self) -> Point {
        *self
    }
}

impl Located for (Point, f64) {
    fn at(&self) -> Point {
        self.0
    }
}

/// Orders `pts` as an implicit k-d tree: the median of the slice splits it, on `axis`.
pub(super) fn build_kd<T: Located>(pts: &mut [T], axis: usize) {
    if pts.len() <= 1 {
        return;
    }
    let mid = pts.len() / 2;
    let key = |p: &T| if axis == 0 { p.at().x } else { p.at().y };
    pts.select_nth_unstable_by(mid, |a, b| key(a).total_cmp(&key(b)));
    let (lo, hi) = pts.split_at_mut(mid);
    build_kd(lo, 1 - axis);
    build_kd(&mut hi[1..], 1 - axis);
}

/// The nearest item of a tree built by [`build_kd`] to `q`, improving on `best`.
pub(super) fn search_kd<T: Located>(pts: &[T], axis: usize, q: Point, best: &mut (f64, Option<T>)) {
    if pts.is_empty() {
        return;
    }
    let mid = pts.len() / 2;
    let p = pts[mid].at();
    let d = q.dist(p);
    if d < best.0 {
        *best = (d, Some(pts[mid]));
    }
    let delta = if axis == 0 { q.x - p.x } else { q.y - p.y };
    let (near, far) = if delta < 0.0 {
        (&pts[..mid], &pts[mid + 1..])
    } else {
        (&pts[mid + 1..], &pts[..mid])
    };
    search_kd(near, 1 - axis, q, best);
    if delta.abs() < best.0 {
        search_kd(far, 1 - axis, q, best);
    }
}
