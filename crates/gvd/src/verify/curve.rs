//! The checker's own distance to an algebraic curve `{f = 0} ∩ clip`, written apart from
//! the engine's `site/algebraic` (nothing shared but the polynomial type and intervals):
//! a quadtree over the clip box keeps the cells where the mean-value form
//! `f(c) + ∇f(B)·(B − c)` (natural interval extensions of the partials) may vanish,
//! down to a spacing of a quarter of epsilon; each kept cell contributes the crossings
//! of `f` along its lower and left sides (bisection) and its centre projected onto the
//! curve (gradient Newton). The distance at `q` starts from the nearest sample (a k-d
//! tree) and slides along the curve: step along the tangent to the projection of `q`,
//! project back onto `f = 0`, keep the best point.
//!
//! For medial axes the curve also gives every local minimum of the distance from a
//! point (its *branches*, [`Curve::local_feet`]), the centre of curvature at a foot, and
//! the region it encloses (where `f` has the other sign than at the clip box's corner,
//! which a closed curve does not reach).

use crate::geom::{Aabb, Point};
use crate::num::poly::Poly;
use crate::num::Interval;
use std::collections::HashMap;

/// Cells smaller than the clip box by this factor are not split (a floor on the work).
const MIN_CELL: f64 = 1.0 / 16384.0;

/// A densely sampled algebraic curve.
#[derive(Clone, Debug)]
pub(super) struct Curve {
    f: Poly,
    fx: Poly,
    fy: Poly,
    fxx: Poly,
    fxy: Poly,
    fyy: Poly,
    clip: Aabb,
    step: f64,
    /// the sign of `f` at the clip box's lower left corner: `f > 0` there
    outside_positive: bool,
    /// samples in k-d order (see [`Curve::nearest_sample`])
    tree: Vec<Point>,
}

impl Curve {
    /// Samples `{f = 0} ∩ clip` at a spacing of about `spacing`.
    pub(super) fn new(f: &Poly, clip: Aabb, spacing: f64) -> Curve {
        let step = spacing.max(MIN_CELL * clip.longest_side());
        let (fx, fy) = (f.partial(0), f.partial(1));
        let mut c = Curve {
            fxx: fx.partial(0),
            fxy: fx.partial(1),
            fyy: fy.partial(1),
            fx,
            fy,
            f: f.clone(),
            clip,
            step,
            outside_positive: f.eval(clip.min.x, clip.min.y, 0.0) > 0.0,
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

    /// Whether `q` lies in the region the curve encloses: inside the clip box, where
    /// `f` has the other sign than at the box's corner (even-odd over nested loops).
    pub(super) fn encloses(&self, q: Point) -> bool {
        let v = self.f_at(q);
        self.clip.contains(q) && v != 0.0 && (v > 0.0) != self.outside_positive
    }

    /// The centre of curvature at the curve point `p`, `p − n/κ` with `n = ∇f/|∇f|` and
    /// `κ = (f_xx f_y² − 2 f_xy f_x f_y + f_yy f_x²) / |∇f|³` (`None` where flat).
    pub(super) fn curvature_center(&self, p: Point) -> Option<Point> {
        let g = self.grad(p);
        let n = g.norm();
        let at = |h: &Poly| h.eval(p.x, p.y, 0.0);
        let num =
            at(&self.fxx) * g.y * g.y - 2.0 * at(&self.fxy) * g.x * g.y + at(&self.fyy) * g.x * g.x;
        let kappa = num / (n * n * n);
        (kappa.is_finite() && kappa != 0.0).then(|| p - g * (1.0 / (n * kappa)))
    }

    /// Every local minimum of the distance from `q` along the curve within `slack` of
    /// the least, nearest first, as `(distance, foot)`. The samples within reach are
    /// taken nearest first; one with no sample taken before within three sample
    /// spacings starts a new basin, and a slide from it finds that basin's foot (feet
    /// within two spacings are one).
    pub(super) fn local_feet(&self, q: Point, slack: f64) -> Vec<(f64, Point)> {
        let Some(least) = self.foot(q) else {
            return Vec::new();
        };
        let reach = q.dist(least) + slack + 2.0 * self.step;
        let mut near = Vec::new();
        within_kd(&self.tree, 0, q, reach, &mut near);
        near.sort_by(|a, b| q.dist(*a).total_cmp(&q.dist(*b)));
        let cell = 3.0 * self.step;
        let key = |p: Point| ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64);
        let mut taken: HashMap<(i64, i64), Vec<Point>> = HashMap::new();
        let mut feet: Vec<(f64, Point)> = vec![(q.dist(least), least)];
        for p in near {
            let (kx, ky) = key(p);
            let joined = (-1..=1).any(|i| {
                (-1..=1).any(|j| {
                    taken
                        .get(&(kx + i, ky + j))
                        .is_some_and(|v| v.iter().any(|t| t.dist(p) <= cell))
                })
            });
            taken.entry((kx, ky)).or_default().push(p);
            if joined {
                continue;
            }
            let foot = self.slide(q, p);
            if feet.iter().all(|f| f.1.dist(foot) > 2.0 * self.step) {
                feet.push((q.dist(foot), foot));
            }
        }
        feet.sort_by(|a, b| a.0.total_cmp(&b.0));
        let best = feet[0].0;
        feet.retain(|f| f.0 <= best + slack);
        feet
    }

    /// The nearest point of the curve to `q` (`None`: no sample at all).
    pub(super) fn foot(&self, q: Point) -> Option<Point> {
        Some(self.slide(q, self.nearest_sample(q)?))
    }

    /// The local foot of `q` reached from the curve point `start`: Newton steps on the
    /// foot condition `(q − p)·t = 0` along the tangent `t` (at most a sample spacing
    /// each), back onto the curve, keeping the nearest point met. The condition's
    /// derivative along the curve is `−(1 + κ (q − p)·n)`, which goes to 0 as `q`
    /// nears the centre of curvature (there a plain step converges slowly); it is
    /// floored at 1/8.
    pub(super) fn slide(&self, q: Point, start: Point) -> Point {
        let mut best = start;
        let mut p = best;
        for _ in 0..48 {
            let g = self.grad(p);
            let n = g.norm();
            if !(n > 0.0 && n.is_finite()) {
                break;
            }
            let t = Point::new(-g.y / n, g.x / n);
            let slope = self
                .curvature_center(p)
                .map_or(1.0, |c| 1.0 - (q - p).dot(c - p) / (c - p).dot(c - p));
            let along = ((q - p).dot(t) / slope.max(0.125)).clamp(-self.step, self.step);
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
        best
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

/// The items of a tree built by [`build_kd`] within `r` of `q`.
fn within_kd<T: Located>(pts: &[T], axis: usize, q: Point, r: f64, out: &mut Vec<Point>) {
    if pts.is_empty() {
        return;
    }
    let mid = pts.len() / 2;
    let p = pts[mid].at();
    if q.dist(p) <= r {
        out.push(p);
    }
    let delta = if axis == 0 { q.x - p.x } else { q.y - p.y };
    if delta - r <= 0.0 {
        within_kd(&pts[..mid], 1 - axis, q, r, out);
    }
    if delta + r >= 0.0 {
        within_kd(&pts[mid + 1..], 1 - axis, q, r, out);
    }
}
