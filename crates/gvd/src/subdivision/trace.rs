//! Bisector tracing inside a box, and the Voronoi vertex solver.

use super::budget::Budget;
use crate::geom::{segment_distance, Aabb, Point};
use crate::site::DistanceField;

/// `f_a(q) − f_b(q)`.
#[inline]
pub fn diff<F: DistanceField>(fields: &[F], a: u32, b: u32, q: Point) -> f64 {
    fields[a as usize].value(q) - fields[b as usize].value(q)
}

/// Moves `m` along the unit normal `n` onto the bisector `f_a = f_b`, to the sign change
/// nearest `m` within distance `reach`; `None` when there is none.
pub fn project<F: DistanceField>(
    fields: &[F],
    a: u32,
    b: u32,
    m: Point,
    n: Point,
    reach: f64,
) -> Option<Point> {
    let h0 = diff(fields, a, b, m);
    if h0 == 0.0 {
        return Some(m);
    }
    let mut found = None;
    'search: for frac in [1.0 / 64.0, 1.0 / 16.0, 0.25, 0.5, 1.0] {
        for sign in [1.0, -1.0] {
            let t = sign * frac * reach;
            let h = diff(fields, a, b, m + n * t);
            if (h > 0.0) != (h0 > 0.0) || h == 0.0 {
                found = Some(t);
                break 'search;
            }
        }
    }
    let t1 = found?;
    let h1 = diff(fields, a, b, m + n * t1);
    if h1 == 0.0 {
        return Some(m + n * t1);
    }
    let (lo, hi, hl, hh) = if t1 > 0.0 {
        (0.0, t1, h0, h1)
    } else {
        (t1, 0.0, h1, h0)
    };
    let t = illinois(|t| diff(fields, a, b, m + n * t), lo, hi, hl, hh);
    Some(m + n * t)
}

/// A polyline from `p` to `q` (both on the bisector of `a` and `b`) whose points lie on
/// the bisector and whose chords stay within `tol` of it: chords are halved until their
/// midpoint and quarter points project onto the curve within `tol`. Each point takes one
/// from `budget`; once it is out, the chords left are kept as they are.
#[allow(clippy::too_many_arguments)]
pub fn trace<F: DistanceField>(
    fields: &[F],
    a: u32,
    b: u32,
    p: Point,
    q: Point,
    tol: f64,
    budget: &Budget,
) -> Vec<Point> {
    let mut out = vec![p];
    chord(fields, a, b, p, q, (tol, budget), 0, &mut out);
    out
}

#[allow(clippy::too_many_arguments)]
fn chord<F: DistanceField>(
    fields: &[F],
    a: u32,
    b: u32,
    p: Point,
    q: Point,
    (tol, budget): (f64, &Budget),
    depth: u32,
    out: &mut Vec<Point>,
) {
    let d = q - p;
    let len = d.norm();
    if len <= tol || depth >= 24 || !budget.take_point() {
        out.push(q);
        return;
    }
    let n = d.perp() * (1.0 / len);
    let reach = len;
    let mid = project(fields, a, b, p.lerp(q, 0.5), n, reach);
    let Some(m) = mid else {
        out.push(q);
        return;
    };
    let off = |t: f64| {
        project(fields, a, b, p.lerp(q, t), n, reach).map_or(0.0, |r| (r - p.lerp(q, t)).norm())
    };
    if (m - p.lerp(q, 0.5)).norm() <= tol && off(0.25) <= tol && off(0.75) <= tol {
        out.push(q);
        return;
    }
    chord(fields, a, b, p, m, (tol, budget), depth + 1, out);
    chord(fields, a, b, m, q, (tol, budget), depth + 1, out);
}

/// The point of `bx` where `f_a = f_b = f_c`, by Newton's method from the box centre;
/// `None` when it does not converge inside the box.
pub fn vertex<F: DistanceField>(fields: &[F], s: [u32; 3], bx: &Aabb) -> Option<Point> {
    let mut q = bx.center();
    let scale = bx.longest_side();
    let mut converged = false;
    for _ in 0..40 {
        let fa = fields[s[0] as usize].value(q);
        let r1 = fa - fields[s[1] as usize].value(q);
        let r2 = fa - fields[s[2] as usize].value(q);
        let ga = fields[s[0] as usize].gradient(q);
        let j1 = ga - fields[s[1] as usize].gradient(q);
        let j2 = ga - fields[s[2] as usize].gradient(q);
        let det = j1.cross(j2);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        // solve [j1; j2] Δ = −(r1, r2)
        let dx = (-r1 * j2.y + r2 * j1.y) / det;
        let dy = (-r2 * j1.x + r1 * j2.x) / det;
        let step = Point::new(dx, dy);
        q = q + step;
        if !q.x.is_finite() || bx.outside_distance(q) > scale {
            return None;
        }
        if step.norm() <= 1e-14 * (scale + q.norm()) {
            converged = true;
            break;
        }
    }
    (converged && bx.contains(q)).then_some(q)
}

/// A polyline from `p` to `q` along a bisector that is a graph over one axis in `bx`
/// (`over_y`: `x = g(y)`; else `y = g(x)`), certified by a gradient component that never
/// vanishes. Each point is the unique root of `f_a − f_b` on the box's cross-section,
/// found by bisection; the parameter interval is halved until chords stay within `tol`
/// (or `budget` runs out of points).
#[allow(clippy::too_many_arguments)]
pub fn trace_graph<F: DistanceField>(
    fields: &[F],
    a: u32,
    b: u32,
    p: Point,
    q: Point,
    over_y: bool,
    bx: &Aabb,
    tol: f64,
    budget: &Budget,
) -> Vec<Point> {
    let mut out = vec![p];
    graph_chord(fields, (a, b), p, q, over_y, bx, (tol, budget), 0, &mut out);
    out
}

#[allow(clippy::too_many_arguments)]
fn graph_chord<F: DistanceField>(
    fields: &[F],
    ab: (u32, u32),
    p: Point,
    q: Point,
    over_y: bool,
    bx: &Aabb,
    (tol, budget): (f64, &Budget),
    depth: u32,
    out: &mut Vec<Point>,
) {
    let param = |r: Point| if over_y { r.y } else { r.x };
    if p.dist(q) <= tol || depth >= 30 || !budget.take_point() {
        out.push(q);
        return;
    }
    let on_curve = |f: f64| {
        let t = param(p) + f * (param(q) - param(p));
        cross_section_root(fields, ab, t, over_y, bx)
    };
    let Some(m) = on_curve(0.5) else {
        out.push(q);
        return;
    };
    // the chord is kept when the curve's points at 1/4, 1/2 and 3/4 of the parameter
    // range lie within tol of it
    let near = |r: Option<Point>| r.is_none_or(|r| segment_distance(r, p, q) <= tol);
    if segment_distance(m, p, q) <= tol && near(on_curve(0.25)) && near(on_curve(0.75)) {
        out.push(q);
        return;
    }
    graph_chord(fields, ab, p, m, over_y, bx, (tol, budget), depth + 1, out);
    graph_chord(fields, ab, m, q, over_y, bx, (tol, budget), depth + 1, out);
}

/// The root of `f_a − f_b` on the line `y = t` (`over_y`) or `x = t` across the box.
fn cross_section_root<F: DistanceField>(
    fields: &[F],
    (a, b): (u32, u32),
    t: f64,
    over_y: bool,
    bx: &Aabb,
) -> Option<Point> {
    let at = |s: f64| {
        if over_y {
            Point::new(s, t)
        } else {
            Point::new(t, s)
        }
    };
    let (lo, hi) = if over_y {
        (bx.min.x, bx.max.x)
    } else {
        (bx.min.y, bx.max.y)
    };
    let h_lo = diff(fields, a, b, at(lo));
    let h_hi = diff(fields, a, b, at(hi));
    if h_lo == 0.0 {
        return Some(at(lo));
    }
    if h_hi == 0.0 {
        return Some(at(hi));
    }
    if (h_lo > 0.0) == (h_hi > 0.0) {
        return None;
    }
    Some(at(illinois(
        |s| diff(fields, a, b, at(s)),
        lo,
        hi,
        h_lo,
        h_hi,
    )))
}

/// The root of `h` in `[lo, hi]` (with `h(lo)`, `h(hi)` of opposite signs) by the Illinois
/// variant of regula falsi: superlinear on smooth functions, and every step keeps a
/// bracket, falling back to bisection when the interpolant stalls.
pub fn illinois(
    h: impl Fn(f64) -> f64,
    mut lo: f64,
    mut hi: f64,
    mut h_lo: f64,
    mut h_hi: f64,
) -> f64 {
    let mut side = 0i8;
    for _ in 0..100 {
        let width = hi - lo;
        if width <= 4.0 * f64::EPSILON * (lo.abs().max(hi.abs())) {
            break;
        }
        let mut s = (lo * h_hi - hi * h_lo) / (h_hi - h_lo);
        if !(s > lo && s < hi) {
            s = 0.5 * (lo + hi);
        }
        let hs = h(s);
        if hs == 0.0 {
            return s;
        }
        if (hs > 0.0) == (h_lo > 0.0) {
            lo = s;
            h_lo = hs;
            if side == -1 {
                h_hi *= 0.5;
            }
            side = -1;
        } else {
            hi = s;
            h_hi = hs;
            if side == 1 {
                h_lo *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (lo + hi)
}
