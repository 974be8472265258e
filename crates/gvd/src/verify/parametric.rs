//! The checker's own distance to a piece `C([t0, t1])` of a Bézier or B-spline curve,
//! written apart from the free-form engine (nothing shared but the curve's evaluation,
//! `geom::bspline`): the piece is sampled until consecutive samples are at most `S`
//! apart (`S`: the spacing asked for, or 1/64 of the piece's extent if larger). The
//! foot of `q` lies within `S` of a sample, so that sample is at most `d_min + S` from
//! `q`, `d_min` the distance to the nearest sample: Newton steps on
//! `(C(t) − q) · C'(t) = 0` within `[t0, t1]` start from every such sample, and the best
//! point met is the foot.

use crate::geom::bspline::RationalBspline;
use crate::geom::grid::bounds_of_points;
use crate::geom::{Aabb, Point};
use crate::scene::SiteKind;

/// Chords halve at most this many times when a piece is sampled (a floor on the work).
const MAX_DEPTH: u32 = 18;

/// A sampled curve piece.
#[derive(Clone, Debug)]
pub(super) struct Parametric {
    curve: RationalBspline,
    t0: f64,
    t1: f64,
    /// `(point, parameter)` samples in parameter order, at most `spacing` apart
    samples: Vec<(Point, f64)>,
    spacing: f64,
    /// a box that holds the piece: its samples' box grown by the spacing
    bounds: Aabb,
}

impl Parametric {
    /// The piece `C([t0, t1])`, its samples at most `spacing` (or 1/64 of its extent)
    /// apart, or `2^-18` of the parameter range.
    pub(super) fn new(curve: RationalBspline, t0: f64, t1: f64, spacing: f64) -> Parametric {
        let mut piece = Parametric {
            curve,
            t0,
            t1,
            samples: Vec::new(),
            spacing,
            bounds: Aabb::new(Point::default(), Point::default()),
        };
        let coarse = piece.sampled(f64::INFINITY);
        let extent = {
            let b = bounds_of_points(coarse.iter().map(|s| s.0));
            b.min.dist(b.max)
        };
        piece.spacing = spacing.max(extent / 64.0);
        piece.samples = piece.sampled(piece.spacing);
        // consecutive samples are at most `spacing` apart, so the piece between them
        // stays within `spacing` of either
        let b = bounds_of_points(piece.samples.iter().map(|s| s.0));
        let grow = Point::new(piece.spacing, piece.spacing);
        piece.bounds = Aabb::new(b.min - grow, b.max + grow);
        piece
    }

    /// Samples in parameter order, at most `spacing` apart (16 at least).
    fn sampled(&self, spacing: f64) -> Vec<(Point, f64)> {
        let (t0, t1) = (self.t0, self.t1);
        let mut samples = vec![(self.at(t0), t0)];
        let n = 16;
        for k in 0..n {
            let a = t0 + (t1 - t0) * k as f64 / n as f64;
            let b = if k + 1 == n {
                t1
            } else {
                t0 + (t1 - t0) * (k + 1) as f64 / n as f64
            };
            sample(&|t| self.at(t), a, b, spacing, MAX_DEPTH, &mut samples);
        }
        samples
    }

    /// A box that holds the piece.
    pub(super) fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The curve's own parameter for `t`: beyond the end of its domain (the piece of a
    /// closed curve that runs over the seam) it wraps around.
    fn wrapped(&self, t: f64) -> f64 {
        let (lo, hi) = self.curve.domain();
        if t > hi {
            t - (hi - lo)
        } else {
            t
        }
    }

    /// The point at parameter `t`.
    pub(super) fn at(&self, t: f64) -> Point {
        self.curve.eval(self.wrapped(t))
    }

    fn derivative(&self, t: f64) -> Point {
        self.curve.derivative(self.wrapped(t))
    }

    /// The piece as a polyline in parameter order, vertices at most `spacing` apart.
    pub(super) fn outline(&self, spacing: f64) -> Vec<Point> {
        self.sampled(spacing).into_iter().map(|s| s.0).collect()
    }

    /// The piece's two ends, each with its unit tangent pointing into the piece.
    pub(super) fn ends(&self) -> [(Point, Point); 2] {
        [
            (self.at(self.t0), self.tangent(self.t0)),
            (self.at(self.t1), self.tangent(self.t1) * -1.0),
        ]
    }

    /// The unit tangent at `t` (zero where the derivative vanishes).
    fn tangent(&self, t: f64) -> Point {
        let d = self.derivative(t);
        let n = d.norm();
        if n > 0.0 {
            d * (1.0 / n)
        } else {
            d
        }
    }

    /// The nearest point of the piece to `q`.
    pub(super) fn foot(&self, q: Point) -> Point {
        self.local_feet(q, 0.0)
            .first()
            .map_or_else(|| self.at(self.t0), |f| f.1)
    }

    /// The distinct local minima of the distance from `q` along the piece whose
    /// distances are within `slack` of the least, nearest first, as `(distance, foot,
    /// parameter)`: Newton from every sample within reach (`d_min + spacing + slack`,
    /// `d_min` the nearest sample's distance) that is a local minimum of the sampled
    /// distance, or next to one. (A foot `t*` between samples `j` and `j + 1`, the only
    /// critical point of the distance from `t_{j−1}` to `t_{j+2}`, makes the nearer of
    /// the two a local minimum of the samples and the other its neighbour.) Two feet are
    /// one minimum unless the distance rises between them, on either way round if the
    /// piece is a loop (where the distance is flat, Newton stops at points about the
    /// square root of rounding apart).
    pub(super) fn local_feet(&self, q: Point, slack: f64) -> Vec<(f64, Point, f64)> {
        let dist: Vec<f64> = self.samples.iter().map(|s| q.dist(s.0)).collect();
        let reach = dist.iter().fold(f64::INFINITY, |a, &b| a.min(b)) + self.spacing + slack;
        let extent = self.bounds.min.dist(self.bounds.max);
        let loop_range = (self.at(self.t0).dist(self.at(self.t1)) <= 1e-12 * extent)
            .then_some(self.t1 - self.t0);
        let rises_between = |a: &(f64, Point, f64), b: &(f64, Point, f64)| {
            let floor = a.0.max(b.0) + 1e-13 * (extent + a.0);
            let mid = 0.5 * (a.2 + b.2);
            let rises = |t: f64| q.dist(self.at(t)) > floor;
            let across = |range: f64| {
                let t = mid + 0.5 * range;
                rises(if t > self.t1 { t - range } else { t })
            };
            rises(mid) && loop_range.is_none_or(across)
        };
        let local_min = |k: usize| {
            let before = k.checked_sub(1).map_or(f64::INFINITY, |j| dist[j]);
            let after = dist.get(k + 1).copied().unwrap_or(f64::INFINITY);
            dist[k] <= before && dist[k] <= after
        };
        let mut feet: Vec<(f64, Point, f64)> = Vec::new();
        for (k, &(p, t)) in self.samples.iter().enumerate() {
            let start = local_min(k)
                || k.checked_sub(1).is_some_and(local_min)
                || (k + 1 < dist.len() && local_min(k + 1));
            if dist[k] <= reach && start {
                let found = self.descend(q, p, t);
                match feet.iter_mut().find(|f| !rises_between(f, &found)) {
                    Some(f) if found.0 < f.0 => *f = found,
                    Some(_) => {}
                    None => feet.push(found),
                }
            }
        }
        feet.sort_by(|a, b| a.0.total_cmp(&b.0));
        if let Some(least) = feet.first().map(|f| f.0) {
            feet.retain(|f| f.0 <= least + slack);
        }
        feet
    }

    /// The ridge point over the foot at parameter `t`: `C(t) + R·n`, `n` the unit
    /// normal on the `side` (±1) of the left normal, `R` the radius of the largest
    /// disc on that side touching the piece at `C(t)` that holds no point of it
    /// (discs along a normal are nested, so bisection finds `R`), if `R` lies within
    /// `radii`. `rounding` is the slack of the "holds no point" test.
    pub(super) fn ridge_point(
        &self,
        t: f64,
        side: f64,
        radii: (f64, f64),
        rounding: f64,
    ) -> Option<Point> {
        let d = self.derivative(t);
        let speed = d.norm();
        if !(speed > 0.0 && speed.is_finite()) {
            return None;
        }
        let (foot, n) = (self.at(t), d.perp() * (side / speed));
        let empty = |r: f64| {
            let x = foot + n * r;
            x.dist(self.foot(x)) >= r - rounding
        };
        let (mut lo, mut hi) = (radii.0.max(0.0), radii.1);
        if !empty(lo) || empty(hi) {
            return None;
        }
        for _ in 0..12 {
            let mid = 0.5 * (lo + hi);
            if empty(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(foot + n * (0.5 * (lo + hi)))
    }

    /// The left normal's side (±1) of `q` at parameter `t`.
    pub(super) fn side_of(&self, q: Point, t: f64) -> f64 {
        if (q - self.at(t)).dot(self.derivative(t).perp()) >= 0.0 {
            1.0
        } else {
            -1.0
        }
    }

    /// The speed `|C'(t)|`.
    pub(super) fn speed(&self, t: f64) -> f64 {
        self.derivative(t).norm()
    }

    /// The parameter range `(t0, t1)`.
    pub(super) fn range(&self) -> (f64, f64) {
        (self.t0, self.t1)
    }

    /// The centre of curvature at parameter `t`, `C + N / κ` with
    /// `κ = (C' × C'') / |C'|³` and `N` the left normal (`C''` by central differences
    /// of `C'`); `None` where the piece is straight or singular there.
    pub(super) fn curvature_center(&self, t: f64) -> Option<Point> {
        let h = 1e-6 * (self.t1 - self.t0);
        let (a, b) = ((t - h).max(self.t0), (t + h).min(self.t1));
        let d = self.derivative(t);
        let second = (self.derivative(b) - self.derivative(a)) * (1.0 / (b - a));
        let speed = d.norm();
        let kappa = d.cross(second) / speed.powi(3);
        let center = self.at(t) + d.perp() * (1.0 / (speed * kappa));
        (kappa != 0.0 && center.x.is_finite() && center.y.is_finite()).then_some(center)
    }

    /// Newton on `φ(t) = (C(t) − q) · C'(t) = 0` from sample `(p, t)`, with
    /// `φ' = |C'|² + (C − q) · C''` (`C''` by central differences of `C'`; `|C'|²` alone,
    /// the Gauss–Newton step, where that is not positive): the nearest point met, as
    /// `(distance, point, parameter)`.
    fn descend(&self, q: Point, mut p: Point, mut t: f64) -> (f64, Point, f64) {
        let mut best = (q.dist(p), p, t);
        let h = 1e-6 * (self.t1 - self.t0);
        for _ in 0..32 {
            let d = self.derivative(t);
            let dd = d.dot(d);
            if !(dd > 0.0 && dd.is_finite()) {
                break;
            }
            let second = (self.derivative(t + h) - self.derivative(t - h)) * (0.5 / h);
            let slope = dd + (p - q).dot(second);
            let slope = if slope > 0.0 && slope.is_finite() {
                slope
            } else {
                dd
            };
            let next = (t - (p - q).dot(d) / slope).clamp(self.t0, self.t1);
            let moved = (next - t).abs();
            t = next;
            p = self.at(t);
            if q.dist(p) < best.0 {
                best = (q.dist(p), p, t);
            }
            if moved <= 1e-10 * (self.t1 - self.t0) {
                break;
            }
        }
        best
    }
}

/// Appends the samples of `(a, b]`, halving it while its chord exceeds `spacing`.
fn sample(
    eval: &impl Fn(f64) -> Point,
    a: f64,
    b: f64,
    spacing: f64,
    depth: u32,
    out: &mut Vec<(Point, f64)>,
) {
    let (pa, pb) = (eval(a), eval(b));
    let m = 0.5 * (a + b);
    // the midpoint too: a chord can be short where the piece loops
    let pm = eval(m);
    if depth > 0 && (pa.dist(pm) > spacing || pm.dist(pb) > spacing) {
        sample(eval, a, m, spacing, depth - 1, out);
        sample(eval, m, b, spacing, depth - 1, out);
    } else {
        out.push((pm, m));
        out.push((pb, b));
    }
}

/// A `bezier` or `bspline` site split as SCENE_FORMAT.md numbers its features: pieces
/// between tangent discontinuities in parameter order, corner `k` at the start of
/// piece `k` (an open curve's last corner at its end; a closed curve without corners
/// is one periodic piece).
pub(super) struct SplineSite {
    pub pieces: Vec<Parametric>,
    pub corners: Vec<Point>,
    pub closed: bool,
}

/// The pieces and corners of a free-form site (`None` for other kinds). A Bézier curve
/// is closed when its ends are within `1e-9 · scale`; samples are `spacing` apart.
pub(super) fn spline_site(kind: &SiteKind, scale: f64, spacing: f64) -> Option<SplineSite> {
    let (curve, closed) = match kind {
        SiteKind::Bezier {
            control_points,
            weights,
        } => {
            let c = RationalBspline::bezier(control_points, weights.as_deref());
            let (lo, hi) = c.domain();
            let closed = c.eval(lo).dist(c.eval(hi)) <= 1e-9 * scale;
            (c, closed)
        }
        SiteKind::Bspline {
            degree,
            control_points,
            knots,
            weights,
            closed,
        } => (
            RationalBspline::new(*degree, control_points, knots, weights.as_deref()),
            *closed,
        ),
        _ => return None,
    };
    let (lo, hi) = curve.domain();
    let breaks = curve.tangent_breaks();
    let seam = closed && curve.seam_turns();
    let (ranges, corner_t): (Vec<(f64, f64)>, Vec<f64>) = if closed && !seam {
        if breaks.is_empty() {
            (vec![(lo, hi)], Vec::new())
        } else {
            // pieces from break to break, the last one over the seam (wrapping)
            let mut r: Vec<(f64, f64)> = breaks.windows(2).map(|w| (w[0], w[1])).collect();
            r.push((breaks[breaks.len() - 1], breaks[0] + (hi - lo)));
            (r, breaks.clone())
        }
    } else {
        let cuts: Vec<f64> = std::iter::once(lo)
            .chain(breaks.iter().copied())
            .chain(std::iter::once(hi))
            .collect();
        let ranges = cuts.windows(2).map(|w| (w[0], w[1])).collect();
        let corners = if closed {
            cuts[..cuts.len() - 1].to_vec()
        } else {
            cuts
        };
        (ranges, corners)
    };
    Some(SplineSite {
        pieces: ranges
            .iter()
            .map(|&(a, b)| Parametric::new(curve.clone(), a, b, spacing))
            .collect(),
        corners: corner_t.iter().map(|&t| curve.eval(t)).collect(),
        closed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn foot_on_a_nurbs_quarter_circle_is_radial() {
        // the unit quarter circle as a rational quadratic (weights 1, 1/√2, 1)
        let pts = [
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        ];
        let w = [1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0];
        let piece = Parametric::new(RationalBspline::bezier(&pts, Some(&w)), 0.0, 1.0, 0.01);
        for k in 1..20 {
            let a = std::f64::consts::FRAC_PI_2 * k as f64 / 20.0;
            let q = Point::new(a.cos(), a.sin()) * 2.5;
            let f = piece.foot(q);
            // the distance is exact to rounding; the foot itself only to about the
            // square root of it, as the distance is flat to second order there
            assert!((f.norm() - 1.0).abs() < 1e-12);
            assert!((q.dist(f) - 1.5).abs() < 1e-12, "{f:?} for {q:?}");
            assert!(f.dist(q * 0.4) < 1e-7, "{f:?} for {q:?}");
        }
        // beyond the ends the foot is the end
        assert!(piece.foot(Point::new(2.0, -1.0)).dist(pts[0]) < 1e-12);
    }
}
