//! Open circular arcs as generators, and their bisectors with points, segments and
//! other arcs in polar (offset-parameter) form about the arc's centre.
//!
//! An arc is `c + r·(cos θ, sin θ)` for `a0 < θ < a0 + span`; its distance at `x` is
//! `| |x − c| − r |` inside the open wedge `a0 < ∠(x − c) < a0 + span` and `+∞`
//! elsewhere (the endpoints are point generators of their own). Write
//! `x = c + ρ·u`, `u = (cos θ, sin θ)`, and `t` for the clearance. Every bisector with
//! an arc is then a conic with a focus at `c`:
//!
//! ```text
//! ρ(θ) = N / (M − w·u),   t = |ρ − r|,
//! ```
//!
//! * point `p`, `d = p − c`: `|x − p|² = (ρ − r)²` gives `N = r² − |d|²`, `M = 2r`,
//!   `w = 2d` (an ellipse inside the circle when `|d| < r`, else the branch of a
//!   hyperbola outside it; there is one curve, no choice);
//! * the line of a segment, `h(x) = (x − a)·n`, `h_c = h(c)`: `h(x) = s·(ρ − r)` with
//!   `s = ±1` gives `N = r + s·h_c`, `M = 1`, `w = s·n` (a parabola);
//! * a second arc `(c₂, r₂)`, `δ = c₂ − c`: `|x − c₂| − r₂ = s·(ρ − r)` with `s = ±1`,
//!   `k = r₂ − s·r`, gives `N = k² − |δ|²`, `M = −2sk`, `w = 2δ`, valid where
//!   `|x − c₂| = k + s·ρ ≥ 0` (a conic through inner/inner and outer/outer pieces
//!   for `s = 1`, mixed ones for `s = −1`).
//!
//! The sign `s` is that of the least residual `|F_s|` of the unsquared equation at
//! `near` (or at both ends of an edge; `F_s`, a difference of signed distances, is
//! zero exactly on the curve), among the candidates that are not empty (`ρ ≤ 0` at
//! every angle).
//!
//! When `N = 0` (a point on the circle, a line or circle tangent to it) the curve
//! degenerates to the ray from `c` in the direction `u*` with `w·u* = M`.
//!
//! The parameter of `x` is its polar angle about `c` minus `a0`, cut in the middle of
//! the angles outside the wedge: every edge of an arc's face lies in its wedge, so the
//! parameter is continuous between two vertices of one edge.

use super::geometry::{Bisector, Clearance};
use crate::geom::Point;
use std::f64::consts::{PI, TAU};

/// An open circular arc, counter-clockwise from `a0` over `span ∈ (0, 2π]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Arc {
    pub(crate) c: Point,
    pub(crate) r: f64,
    pub(crate) a0: f64,
    pub(crate) span: f64,
    /// The endpoints' point generators (start, end).
    pub(crate) ends: [u32; 2],
    /// The endpoints' coordinates (start, end).
    pub(crate) end_points: [Point; 2],
}

impl Arc {
    /// The arc of centre `c` and radius `r` from angle `start` counter-clockwise to
    /// `end` (radians; the span `end − start` is taken into `(0, 2π]`).
    pub(crate) fn new(c: Point, r: f64, start: f64, end: f64, ends: [u32; 2]) -> Arc {
        let mut span = (end - start).rem_euclid(TAU);
        if span <= 0.0 || !span.is_finite() {
            span = TAU;
        }
        let mut arc = Arc {
            c,
            r,
            a0: start,
            span,
            ends,
            end_points: [c; 2],
        };
        arc.end_points = [arc.point_at(0.0), arc.point_at(span)];
        arc
    }

    /// The polar angle of `x − c` relative to `a0`, in `[0, 2π)`.
    #[inline]
    pub(crate) fn rel_angle(&self, x: Point) -> f64 {
        let v = x - self.c;
        let a = (v.y.atan2(v.x) - self.a0).rem_euclid(TAU);
        if a >= TAU {
            0.0
        } else {
            a
        }
    }

    /// Whether `x` lies strictly inside the wedge (never the centre).
    #[inline]
    pub(crate) fn in_wedge(&self, x: Point) -> bool {
        let a = self.rel_angle(x);
        x != self.c && a > 0.0 && a < self.span
    }

    /// Distance to the open arc: `| |x − c| − r |` inside the wedge, `+∞` otherwise.
    #[inline]
    pub(crate) fn open_distance(&self, x: Point) -> f64 {
        if self.in_wedge(x) {
            (x.dist(self.c) - self.r).abs()
        } else {
            f64::INFINITY
        }
    }

    /// Whether `x`, at clearance `t` from its generators, is nearer to the open arc.
    #[inline]
    pub(crate) fn claims(&self, x: Point, t: f64) -> bool {
        self.in_wedge(x) && (x.dist(self.c) - self.r).abs() < t
    }

    /// The point at relative angle `a` and offset `h` (radius `r + h`).
    pub(crate) fn at(&self, a: f64, h: f64) -> Point {
        let th = self.a0 + a;
        self.c + Point::new(th.cos(), th.sin()) * (self.r + h)
    }

    /// The point of the circle at relative angle `a`.
    pub(crate) fn point_at(&self, a: f64) -> Point {
        self.at(a, 0.0)
    }

    /// The relative angle of `x` in `[lo, lo + 2π)`, `lo = −(2π − span)/2`: continuous
    /// across the wedge and a little beyond it.
    pub(crate) fn param(&self, x: Point) -> f64 {
        let lo = -0.5 * (TAU - self.span);
        let v = x - self.c;
        let a = (v.y.atan2(v.x) - self.a0 - lo).rem_euclid(TAU);
        lo + if a >= TAU { 0.0 } else { a }
    }
}

/// The conic `ρ(θ) = N / (M − w·u)` of focus `c`, parametrized by `θ − a0` for the
/// arc `(c, r, a0, span)`, where `k + s·ρ ≥ 0` (`|x − c₂| = k + s·ρ` for a second
/// arc; `k = 1, s = 0` otherwise); the clearance is `|ρ − r|`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Conic {
    arc: Arc,
    n: f64,
    m: f64,
    /// The validity condition `k + s·ρ ≥ 0`.
    valid: (f64, f64),
    /// `|w|` and `a0 − ∠w`: `M − w·u = (M − |w|) + 2|w|·sin²((s + a0 − ∠w)/2)`, which
    /// keeps the denominator accurate near the pole.
    wn: f64,
    phase: f64,
}

impl Conic {
    fn new(arc: &Arc, n: f64, m: f64, w: Point, valid: (f64, f64)) -> Conic {
        Conic {
            arc: *arc,
            n,
            m,
            valid,
            wn: w.norm(),
            phase: arc.a0 - w.y.atan2(w.x),
        }
    }

    /// `M − w·u` at parameter `s`.
    #[inline]
    fn denominator(&self, s: f64) -> f64 {
        let h = (0.5 * (s + self.phase)).sin();
        (self.m - self.wn) + 2.0 * self.wn * h * h
    }

    pub(crate) fn param(&self, x: Point) -> f64 {
        self.arc.param(x)
    }

    /// The point at parameter `s` and its clearance, if `ρ(s)` is finite and positive.
    pub(crate) fn point(&self, s: f64) -> Option<(Point, f64)> {
        let rho = self.n / self.denominator(s);
        if !(rho > 0.0 && rho.is_finite() && self.valid.0 + self.valid.1 * rho >= 0.0) {
            return None;
        }
        let th = self.arc.a0 + s;
        let x = self.arc.c + Point::new(th.cos(), th.sin()) * rho;
        Some((x, (rho - self.arc.r).abs()))
    }

    /// The clearance `| |x − c| − r |` of any point.
    pub(crate) fn clearance(&self, x: Point) -> f64 {
        (x.dist(self.arc.c) - self.arc.r).abs()
    }

    /// The angle `β ∈ (0, π)` of the tangent `dx/ds` in the frame `(u, u⊥)`: the
    /// tangent is `(ρ/(M − w·u))·((w·u⊥)·u + (M − w·u)·u⊥)` and `ρ/(M − w·u)` has the
    /// sign of `N`, so the tangent's angle is `θ + β`, `β` continuous along the curve.
    fn tangent_angle(&self, s: f64) -> f64 {
        // w·u⊥ = −|w|·sin(θ − ∠w).
        let wup = -self.wn * (s + self.phase).sin();
        let sign = if self.n < 0.0 { -1.0 } else { 1.0 };
        (sign * self.denominator(s)).atan2(sign * wup)
    }

    /// Points strictly between parameters `s0` and `s1` such that the polyline through
    /// `x(s0)`, them and `x(s1)` is within `tol` of the curve: a convex piece whose
    /// tangent turns by `ψ = Δs + Δβ`, `|ψ| < π/2`, lies within `(L/2)·tan(|ψ|/2)` of
    /// its chord `L`. `None` when that takes more than `max` points.
    pub(crate) fn interior_samples(
        &self,
        s0: f64,
        s1: f64,
        tol: f64,
        max: usize,
    ) -> Option<Vec<Point>> {
        const MAX_DEPTH: u32 = 40;
        let mut out = Vec::new();
        // (s_a, s_b, depth), left piece last so it is handled first.
        let mut stack = vec![(s0, s1, 0u32)];
        while let Some((a, b, depth)) = stack.pop() {
            let mid = 0.5 * (a + b);
            let flat = match (self.point(a), self.point(b)) {
                (Some((xa, _)), Some((xb, _))) => {
                    let turn = (b - a + self.tangent_angle(b) - self.tangent_angle(a)).abs();
                    turn < 0.5 * PI && 0.5 * xa.dist(xb) * (0.5 * turn).tan() <= tol
                }
                _ => true,
            };
            if out.len() + stack.len() >= max {
                return None;
            }
            if flat || depth >= MAX_DEPTH || mid == a || mid == b {
                if b != s1 {
                    if let Some((x, _)) = self.point(b) {
                        out.push(x);
                    }
                }
            } else {
                stack.push((mid, b, depth + 1));
                stack.push((a, mid, depth + 1));
            }
        }
        Some(out)
    }
}

/// A straight bisector through `origin` along `dir` (made unit); a chord if `dir`
/// is zero.
fn line(origin: Point, dir: Point, clearance: Clearance) -> Bisector {
    let len = dir.norm();
    if len > 0.0 && len.is_finite() {
        Bisector::Line {
            origin,
            dir: dir * (1.0 / len),
            clearance,
        }
    } else {
        Bisector::Chord { clearance }
    }
}

fn circle(arc: &Arc) -> Clearance {
    Clearance::Circle { c: arc.c, r: arc.r }
}

/// The conic `N / (M − w·u)`, or the ray from the focus it degenerates to when `N`
/// is zero within rounding (`scale` is the size of the terms of `N`).
fn conic_or_ray(arc: &Arc, n: f64, m: f64, w: Point, valid: (f64, f64), scale: f64) -> Bisector {
    if n.abs() > 1e-12 * scale {
        return Bisector::Conic(Conic::new(arc, n, m, w, valid));
    }
    if w.norm() > 0.0 {
        // The pole w·u* = M: N = 0 means |w| = |M| in every form, so u* = ±w/|w|.
        line(arc.c, w * m.signum(), circle(arc))
    } else {
        Bisector::Chord {
            clearance: circle(arc),
        }
    }
}

/// The bisector of point generator `id` at `p` and `arc`.
pub(crate) fn point_arc(id: u32, p: Point, arc: &Arc) -> Bisector {
    if arc.ends.contains(&id) {
        // The separator: the ray from the centre through the endpoint.
        return line(p, p - arc.c, Clearance::Point(p));
    }
    let d = p - arc.c;
    let (dd, rr) = (d.dot(d), arc.r * arc.r);
    if (rr - dd).abs() <= 1e-12 * (rr + dd) {
        // On the circle, outside the arc: the arc is nearer everywhere in its wedge.
        return Bisector::Chord {
            clearance: Clearance::Point(p),
        };
    }
    Bisector::Conic(Conic::new(arc, rr - dd, 2.0 * arc.r, d * 2.0, (1.0, 0.0)))
}

/// Whether a candidate has no point at all: `ρ = N/(M − w·u) ≤ 0` at every angle.
fn empty(b: &Bisector) -> bool {
    match b {
        Bisector::Conic(k) => {
            if k.n > 0.0 {
                k.m + k.wn <= 0.0
            } else {
                k.m - k.wn >= 0.0
            }
        }
        _ => false,
    }
}

/// Of the candidates for `s = +1` and `s = −1`, the one with the least sum of
/// residuals `|F_s(x)|` over the probes, unless it is empty. (Not the distance at
/// the probe's polar angle: near a tangency the right candidate is a thin conic
/// hugging a ray, with no point at an angle slightly off.)
fn choose(
    plus: Bisector,
    minus: Bisector,
    residual: impl Fn(f64, Point) -> f64,
    probes: &[Point],
) -> Bisector {
    let sum = |s: f64| probes.iter().map(|&x| residual(s, x).abs()).sum::<f64>();
    let size: f64 = probes.iter().map(|p| p.norm()).sum::<f64>() + f64::MIN_POSITIVE;
    let plus_wins = match (empty(&minus), empty(&plus)) {
        (true, false) => true,
        (false, true) => false,
        // Both curves pass through every probe (an edge whose two ends lie on the
        // sites, as the arc and the diameter of a half disc): the edge is the piece
        // of smaller clearance between them (the other runs out to infinity or
        // around the far side).
        _ if probes.len() >= 2 && sum(1.0).max(sum(-1.0)) <= 1e-9 * size => {
            let mid = |b: &Bisector| {
                let t = b.at_fraction(probes[0], probes[1], 0.5).1;
                if t.is_finite() {
                    t
                } else {
                    f64::INFINITY
                }
            };
            mid(&plus) <= mid(&minus)
        }
        _ => sum(1.0) <= sum(-1.0),
    };
    if plus_wins {
        plus
    } else {
        minus
    }
}

/// The bisector of the segment on the line through `a` with unit normal `n`, and
/// `arc`, through (or nearest to) the probes.
pub(crate) fn line_arc(a: Point, n: Point, arc: &Arc, probes: &[Point]) -> Bisector {
    let hc = (arc.c - a).dot(n);
    let scale = arc.r + hc.abs();
    let [plus, minus] =
        [1.0, -1.0].map(|s| conic_or_ray(arc, arc.r + s * hc, 1.0, n * s, (1.0, 0.0), scale));
    // F_s = h − s·(ρ − r).
    let f = |s: f64, x: Point| (x - a).dot(n) - s * (x.dist(arc.c) - arc.r);
    choose(plus, minus, f, probes)
}

/// The bisector of arcs `a` (the focus and parameter) and `b`, through (or nearest
/// to) the probes.
pub(crate) fn arc_arc(a: &Arc, b: &Arc, probes: &[Point]) -> Bisector {
    let delta = b.c - a.c;
    let dd = delta.dot(delta);
    let scale = a.r + b.r;
    if dd <= (1e-12 * scale).powi(2) && (a.r - b.r).abs() <= 1e-12 * scale {
        // Two arcs of one circle: they meet only at a shared endpoint's ray.
        for (k, e) in a.ends.iter().enumerate() {
            if b.ends.contains(e) {
                let p = a.end_points[k];
                return line(p, p - a.c, Clearance::Point(p));
            }
        }
        return Bisector::Chord {
            clearance: circle(a),
        };
    }
    let [plus, minus] = [1.0, -1.0].map(|s| {
        let k = b.r - s * a.r;
        conic_or_ray(a, k * k - dd, -2.0 * s * k, delta * 2.0, (k, s), k * k + dd)
    });
    // F_s = (ρ₂ − r₂) − s·(ρ − r).
    let f = |s: f64, x: Point| (x.dist(b.c) - b.r) - s * (x.dist(a.c) - a.r);
    choose(plus, minus, f, probes)
}

#[cfg(test)]
mod tests;
