//! Generators (points, open segments and open arcs), their distances, and the
//! bisector of two generators between two of its points, in offset-parameter form.
//!
//! Every bisector of points and segments is a line or a parabola (the wiki page's
//! "line/line" and "point/line" forms). A point `x(u)` of the parabola of focus `p` and
//! the line through `a` with unit direction `d` and unit normal `n` is, with
//! `u = (x − a)·d` the foot parameter, `u_p = (p − a)·d` and `h_p = (p − a)·n ≠ 0`,
//!
//! ```text
//! x(u) = a + u·d + σ·t(u)·n,   t(u) = ((u − u_p)² + h_p²) / (2|h_p|),   σ = sign h_p,
//! ```
//!
//! where `t(u)` is the offset parameter (the clearance, equal distance to `p` and to the
//! line). Lines (point/point, segment/segment, and the separator of a segment and its
//! own endpoint) are straight between any two of their points. Bisectors with an arc
//! are conics with a focus at its centre, in polar form (`arc.rs`).

pub(crate) use super::arc::{Arc, Conic};
use crate::geom::predicates::segment_anchor;
use crate::geom::{Aabb, Point};
use crate::incremental::ANCHOR_SPAN;

/// A generator of the segment diagram.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub(crate) enum Gen {
    /// A point: an input point or a segment endpoint (deduplicated), or one of the far
    /// generators (index at least the number of real points).
    Point(u32),
    /// The open segment with this index.
    Segment(u32),
    /// The open arc with this index.
    Arc(u32),
}

/// A segment from `a` to `b` as its supporting line: `o + u·d` for
/// `feet[0] < u < feet[1]`, unit normal `n` (`d` turned counter-clockwise).
///
/// Feet and offsets are measured from `o`: the end `a`, unless it lies far out
/// (`segment_anchor`); then the segment's point nearest to the origin (an end, or a
/// point within an ulp of the segment): from an end 1e15 away, `x − a` would round
/// every point of a domain 4 wide to 0.125, and the bisectors with the segment with it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Line {
    pub(crate) a: Point,
    /// The end `a + len·d`, as given (not recomputed).
    pub(crate) b: Point,
    pub(crate) d: Point,
    pub(crate) n: Point,
    pub(crate) len: f64,
    /// The origin of the feet and offsets, on the segment.
    pub(crate) o: Point,
    /// The feet of `a` and `b`.
    pub(crate) feet: [f64; 2],
    /// The length, or the domain's largest coordinate where that is smaller: the scale
    /// of [`is_beside`](Self::is_beside)'s tolerance.
    size: f64,
    /// The endpoints' point generators.
    pub(crate) ends: [u32; 2],
}

impl Line {
    /// The segment, measured from `a`.
    #[cfg(test)]
    pub(crate) fn new(a: Point, b: Point, ends: [u32; 2]) -> Line {
        Line::anchored(a, b, ends, f64::INFINITY)
    }

    /// The segment, measured from `a` if it lies within `reach` of the origin.
    pub(crate) fn anchored(a: Point, b: Point, ends: [u32; 2], reach: f64) -> Line {
        let v = b - a;
        let len = v.norm();
        let d = v * (1.0 / len);
        let (o, lambda) = segment_anchor(a, b, reach);
        // An end's own foot is 0; the other's, `±len`. From a point inside, each is
        // measured from it: `len − λ·len` would round to an ulp of a far end's.
        let feet = if lambda == 0.0 {
            [0.0, len]
        } else if lambda == 1.0 {
            [-len, 0.0]
        } else {
            [(a - o).dot(d), (b - o).dot(d)]
        };
        Line {
            a,
            b,
            d,
            n: d.perp(),
            len,
            o,
            feet,
            size: len.min(reach / ANCHOR_SPAN),
            ends,
        }
    }

    /// The foot parameter and signed offset of `x`.
    #[inline]
    pub(crate) fn coords(&self, x: Point) -> (f64, f64) {
        let r = x - self.o;
        (r.dot(self.d), r.dot(self.n))
    }

    /// `|x − p|² − h²` for `x` of foot `u` and offset `h`: `(u − u_p)² + h_p·(h_p − 2h)`
    /// with `p`'s own (an end's exactly: `h_p = 0`). Far from the segment, where the
    /// squares of `|x − p|` and `h` agree to their rounding, this keeps the difference.
    pub(crate) fn excess(&self, (u, h): (f64, f64), p: Point) -> f64 {
        let (up, hp) = if p == self.a {
            (self.feet[0], 0.0)
        } else if p == self.b {
            (self.feet[1], 0.0)
        } else {
            self.coords(p)
        };
        (u - up) * (u - up) + hp * (hp - 2.0 * h)
    }

    /// Whether a point of foot `u` and offset `h` ([`coords`](Self::coords)) lies off
    /// the line by more than rounding (`1e-12` of the scale): not `1e-12` of the length
    /// of a segment 1e15 long, which took a point 1.16 from it for one on its line.
    #[inline]
    pub(crate) fn is_beside(&self, u: f64, h: f64) -> bool {
        h.abs() > 1e-12 * (self.size + u.abs())
    }

    /// Distance to the open segment: `|offset|` when the foot is strictly inside,
    /// `+∞` otherwise (the endpoints are generators of their own).
    #[inline]
    pub(crate) fn open_distance(&self, x: Point) -> f64 {
        let (u, h) = self.coords(x);
        if u > self.feet[0] && u < self.feet[1] {
            h.abs()
        } else {
            f64::INFINITY
        }
    }

    /// Whether `x`, at clearance `t` from its generators, is nearer to the open
    /// segment (its foot strictly inside and `|offset| < t`).
    #[inline]
    pub(crate) fn claims(&self, x: Point, t: f64) -> bool {
        let (u, h) = self.coords(x);
        u > self.feet[0] && u < self.feet[1] && h.abs() < t
    }

    pub(crate) fn at(&self, u: f64, h: f64) -> Point {
        self.o + self.d * u + self.n * h
    }

    /// The common end of `self` and `other` (a point generator ending both), with the
    /// unit directions away from it along each.
    fn common_end(&self, other: &Line) -> Option<(Point, Point, Point)> {
        let away = |l: &Line, p: u32| {
            if l.ends[0] == p {
                Some((l.a, l.d))
            } else if l.ends[1] == p {
                Some((l.b, l.d * -1.0))
            } else {
                None
            }
        };
        self.ends.iter().find_map(|&p| {
            let (at, a1) = away(self, p)?;
            let (_, a2) = away(other, p)?;
            Some((at, a1, a2))
        })
    }
}

fn unit(v: Point) -> Point {
    v * (1.0 / v.norm())
}

/// The shape of the bisector of two generators.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Bisector {
    /// The line `origin + s·dir` (unit `dir`), parametrized by `s`.
    Line {
        origin: Point,
        dir: Point,
        clearance: Clearance,
    },
    /// The parabola of focus `p` (at foot `up`, offset `hp` of `line`) and directrix
    /// `line`, parametrized by the foot `u`.
    Parabola {
        line: Line,
        p: Point,
        up: f64,
        hp: f64,
    },
    /// A point on the line of a segment (outside it) and that segment: the bisector
    /// has no piece where the segment is the nearer; kept straight between vertices.
    /// Likewise a point on an arc's circle (outside the arc) and that arc.
    Chord { clearance: Clearance },
    /// A conic with a focus at an arc's centre, parametrized by the polar angle about
    /// it relative to the arc's start (see `arc.rs`).
    Conic(Conic),
}

/// How to measure the clearance (common distance) of a point on a straight bisector.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Clearance {
    Point(Point),
    Line(Line),
    /// The distance `| |x − c| − r |` to a circle.
    Circle {
        c: Point,
        r: f64,
    },
}

impl Clearance {
    fn at(&self, x: Point) -> f64 {
        match self {
            Clearance::Point(p) => x.dist(*p),
            Clearance::Line(l) => l.coords(x).1.abs(),
            Clearance::Circle { c, r } => (x.dist(*c) - r).abs(),
        }
    }
}

/// Where the ray `p + s·dir` (unit `dir`, `s > 0`) from point generator `p` meets the
/// bisector of `p` and `other`: a point on the ray is at clearance `s` from `p`, so
///
/// * another point `q`: `s² = |p + s·dir − q|²` gives `s = |q − p|² / (2 dir·(q − p))`;
/// * a segment's line (`p` at signed offset `h_p`, `σ = sign h_p`): the offset
///   `h_p + s·(n·dir)` equals `σ·s` on the parabola, so `s = |h_p| / (1 − σ n·dir)`.
///
/// `None` when the ray misses the bisector, for an arc, and when `p` is an end of the
/// segment or lies on its line (the bisector is then not a parabola).
pub(crate) fn ray_exit(id: u32, p: Point, dir: Point, other: Shape) -> Option<f64> {
    let s = match other {
        Shape::Point(_, q) => {
            let v = q - p;
            v.dot(v) / (2.0 * dir.dot(v))
        }
        Shape::Segment(l) => {
            let (up, hp) = l.coords(p);
            if l.ends.contains(&id) || !l.is_beside(up, hp) {
                return None;
            }
            hp.abs() / (1.0 - l.n.dot(dir) * hp.signum())
        }
        Shape::Arc(_) => return None,
    };
    (s > 0.0 && s.is_finite()).then_some(s)
}

/// Half the brackets around a closed form's guess that [`Bisector::boundary_near`]
/// refines, narrowest first, as fractions of the parameter range: the narrow one is
/// wider than the guess's rounding on most edges, the wide one on nearly all.
const GUESS_BRACKETS: [f64; 2] = [1.0 / (1u64 << 40) as f64, 1.0 / (1u64 << 24) as f64];

/// Below this `|a₁ + a₂|` (about the bend in radians) a joint of two segments is
/// straight enough that their bisector is taken through the joint along its normal:
/// the crossing of their lines divides rounding by `|a₁ + a₂|`, `1e-12` of the
/// scene's size at this bend.
const STRAIGHT_JOINT: f64 = 1e-4;

/// A generator's geometry, for bisectors.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Shape<'a> {
    Point(u32, Point),
    Segment(&'a Line),
    Arc(&'a Arc),
}

impl Bisector {
    /// The bisector of two generators; `near` (a point of the wanted piece) chooses
    /// between the two angle bisectors of two segments' lines, and between the two
    /// conics of an arc and a segment or another arc (a point on a curved piece, not a
    /// chord's midpoint, when the piece bends much).
    pub(crate) fn of(a: Shape, b: Shape, near: Point) -> Bisector {
        Bisector::through(a, b, &[near])
    }

    /// The bisector of two generators through both ends `from` and `to` of an edge
    /// (vertices, exactly on it): unlike a chord's midpoint, they tell the two conics
    /// of an arc and a segment or arc apart wherever the clearance is not zero at both.
    pub(crate) fn of_edge(a: Shape, b: Shape, from: Point, to: Point) -> Bisector {
        match (a, b) {
            (Shape::Arc(_), _) | (_, Shape::Arc(_)) => Bisector::through(a, b, &[from, to]),
            _ => Bisector::of(a, b, from.lerp(to, 0.5)),
        }
    }

    /// Whether the bisector of `a` and `b` is a [`Bisector::Line`] (see `through`):
    /// two points, two segments, or a segment and one of its ends (the separator).
    /// Polylines of these need not build it.
    pub(crate) fn is_line(a: Shape, b: Shape) -> bool {
        match (a, b) {
            (Shape::Point(..), Shape::Point(..)) | (Shape::Segment(_), Shape::Segment(_)) => true,
            (Shape::Point(id, _), Shape::Segment(l)) | (Shape::Segment(l), Shape::Point(id, _)) => {
                l.ends.contains(&id)
            }
            _ => false,
        }
    }

    /// The bisector nearest to the probes (one for the straight choices).
    fn through(a: Shape, b: Shape, probes: &[Point]) -> Bisector {
        let near = probes[0];
        match (a, b) {
            (Shape::Point(id, p), Shape::Arc(arc)) | (Shape::Arc(arc), Shape::Point(id, p)) => {
                super::arc::point_arc(id, p, arc)
            }
            (Shape::Segment(l), Shape::Arc(arc)) | (Shape::Arc(arc), Shape::Segment(l)) => {
                super::arc::line_arc(l.o, l.n, arc, probes)
            }
            (Shape::Arc(a1), Shape::Arc(a2)) => super::arc::arc_arc(a1, a2, probes),
            (Shape::Point(_, p), Shape::Point(_, q)) => Bisector::Line {
                origin: p.lerp(q, 0.5),
                dir: unit((q - p).perp()),
                clearance: Clearance::Point(p),
            },
            (Shape::Point(id, p), Shape::Segment(l)) | (Shape::Segment(l), Shape::Point(id, p)) => {
                if l.ends.contains(&id) {
                    // The separator: the normal through the endpoint.
                    return Bisector::Line {
                        origin: p,
                        dir: l.n,
                        clearance: Clearance::Point(p),
                    };
                }
                let (up, hp) = l.coords(p);
                if l.is_beside(up, hp) {
                    Bisector::Parabola {
                        line: *l,
                        p,
                        up,
                        hp,
                    }
                } else {
                    Bisector::Chord {
                        clearance: Clearance::Point(p),
                    }
                }
            }
            (Shape::Segment(l1), Shape::Segment(l2)) => {
                // Segments with a common end `p` (directions `a₁`, `a₂` away from it):
                // of the two angle bisectors of their lines only the inner one, along
                // `a₁ + a₂`, has both feet inside the segments (on the other,
                // `(x − p)·a₁` and `(x − p)·a₂` have opposite signs). Below, its normal
                // `n₁ ∓ n₂` has length `|a₁ + a₂|`: at a (nearly) straight joint it
                // vanishes, and the only candidate left would be the common line.
                // There the inner bisector is the line through `p` along `(a₁ − a₂)⊥`
                // (the common normal at `p`), well conditioned at any bend.
                if let Some((p, a1, a2)) = l1.common_end(l2) {
                    if (a1 + a2).norm() < STRAIGHT_JOINT {
                        return Bisector::Line {
                            origin: p,
                            dir: unit((a1 - a2).perp()),
                            clearance: Clearance::Line(*l1),
                        };
                    }
                }
                // Points with n1·(x − a1) = ±n2·(x − a2): the line with normal n1 ∓ n2
                // through the lines' crossing (or midway, for parallel lines); take the
                // one nearer to `near`.
                let mut best: Option<(f64, Bisector)> = None;
                for sign in [1.0, -1.0] {
                    let normal = l1.n - l2.n * sign;
                    let len = normal.norm();
                    if len < 1e-9 {
                        continue;
                    }
                    let normal = normal * (1.0 / len);
                    let c = (l1.n.dot(l1.o) - sign * l2.n.dot(l2.o)) / len;
                    let miss = (normal.dot(near) - c).abs();
                    if best.as_ref().is_none_or(|(m, _)| miss < *m) {
                        let line = Bisector::Line {
                            origin: normal * c,
                            dir: normal.perp(),
                            clearance: Clearance::Line(*l1),
                        };
                        best = Some((miss, line));
                    }
                }
                best.map(|(_, b)| b).unwrap_or(Bisector::Chord {
                    clearance: Clearance::Line(*l1),
                })
            }
        }
    }

    /// The parameter of `x`: along the line, or the foot `u` on the parabola's
    /// directrix.
    fn param(&self, x: Point) -> f64 {
        match self {
            Bisector::Line { origin, dir, .. } => (x - *origin).dot(*dir),
            Bisector::Parabola { line, .. } => line.coords(x).0,
            Bisector::Conic(conic) => conic.param(x),
            Bisector::Chord { .. } => unreachable!("chords use the chord parameter"),
        }
    }

    /// The point with parameter `s` (see [`param`]; for chords `λ ∈ [0, 1]` from
    /// `from` to `to`) and its clearance.
    fn point(&self, from: Point, to: Point, s: f64) -> (Point, f64) {
        match self {
            Bisector::Line {
                origin,
                dir,
                clearance,
            } => {
                let x = *origin + *dir * s;
                (x, clearance.at(x))
            }
            Bisector::Parabola { line, up, hp, .. } => {
                let t = ((s - up) * (s - up) + hp * hp) / (2.0 * hp.abs());
                (line.at(s, t.copysign(*hp)), t)
            }
            Bisector::Chord { clearance } => {
                let x = from.lerp(to, s);
                (x, clearance.at(x))
            }
            Bisector::Conic(conic) => conic.point(s).unwrap_or_else(|| {
                // Off the curve (only through rounding between two of its points):
                // the chord.
                let (s0, s1) = (conic.param(from), conic.param(to));
                let lambda = if s1 != s0 { (s - s0) / (s1 - s0) } else { 0.5 };
                let x = from.lerp(to, lambda.clamp(0.0, 1.0));
                (x, conic.clearance(x))
            }),
        }
    }

    /// The point at fraction `λ` of the parameter range from `from` to `to`, and its
    /// clearance.
    pub(crate) fn at_fraction(&self, from: Point, to: Point, lambda: f64) -> (Point, f64) {
        let (s0, s1) = self.range(from, to);
        self.point(from, to, s0 + (s1 - s0) * lambda)
    }

    /// The fraction of the parameter range from `from` to `to` at `x` (a point of the
    /// bisector); NaN for chords.
    pub(crate) fn fraction(&self, from: Point, to: Point, x: Point) -> f64 {
        match self {
            Bisector::Chord { .. } => f64::NAN,
            _ => {
                let (s0, s1) = self.range(from, to);
                (self.param(x) - s0) / (s1 - s0)
            }
        }
    }

    fn range(&self, from: Point, to: Point) -> (f64, f64) {
        match self {
            Bisector::Chord { .. } => (0.0, 1.0),
            _ => (self.param(from), self.param(to)),
        }
    }

    /// The last point of the bisector from `from` (inside the new region) towards
    /// `to` that is still `inside`, by bisection to full precision, with its clearance;
    /// `to` itself when `to` is inside too (rounding at a tie).
    pub(crate) fn boundary(
        &self,
        from: Point,
        to: Point,
        inside: impl Fn(Point, f64) -> bool,
    ) -> (Point, f64) {
        let (mut lo, mut hi) = self.range(from, to);
        let end = self.point(from, to, hi);
        if inside(end.0, end.1) {
            return end;
        }
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if mid == lo || mid == hi {
                break;
            }
            let (x, t) = self.point(from, to, mid);
            if inside(x, t) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        self.point(from, to, 0.5 * (lo + hi))
    }

    /// [`boundary`](Self::boundary) from a close guess (a fraction of the parameter
    /// range): the bisection runs in the first bracket of [`GUESS_BRACKETS`] around it
    /// whose ends are inside and outside, which takes far fewer steps (`None` when
    /// none is).
    pub(crate) fn boundary_near(
        &self,
        from: Point,
        to: Point,
        guess: f64,
        inside: impl Fn(Point, f64) -> bool,
    ) -> Option<(Point, f64)> {
        let (s0, s1) = self.range(from, to);
        let at = |lambda: f64| self.point(from, to, s0 + (s1 - s0) * lambda.clamp(0.0, 1.0));
        if !guess.is_finite() {
            return None;
        }
        GUESS_BRACKETS.iter().find_map(|&half| {
            let (lo, hi) = (at(guess - half), at(guess + half));
            (inside(lo.0, lo.1) && !inside(hi.0, hi.1)).then(|| self.boundary(lo.0, hi.0, &inside))
        })
    }

    /// Appends to `out` a polyline from `from` to `to` within `tol` of the bisector;
    /// where that takes more than `max` interior points, within `tol` wherever it can
    /// meet the box `visible` (the domain; a curved part beyond it is then one chord,
    /// which stays outside it); `false` (with the chord appended) when even that takes
    /// more.
    pub(crate) fn polyline(
        &self,
        from: Point,
        to: Point,
        tol: f64,
        visible: &Aabb,
        max: usize,
        out: &mut Vec<Point>,
    ) -> bool {
        out.push(from);
        match self {
            Bisector::Line { .. } | Bisector::Chord { .. } => {}
            Bisector::Parabola { line, up, hp, .. } => {
                let (u0, u1) = self.range(from, to);
                // Chord sagitta over a step Δu is at most Δu²·κ/8 with curvature
                // κ ≤ 1/|h_p|. The apex (u = u_p) is always a vertex of the polyline:
                // a chord across it could touch the focus on a parabola narrower
                // than `tol`.
                let step = (8.0 * tol * hp.abs()).sqrt();
                let pieces = |v0: f64, v1: f64| {
                    let apex = (up - v0) * (up - v1) < 0.0;
                    let stops = if apex {
                        vec![v0, *up, v1]
                    } else {
                        vec![v0, v1]
                    };
                    let n: f64 = stops
                        .windows(2)
                        .map(|w| ((w[1] - w[0]).abs() / step).ceil())
                        .sum();
                    (stops, n)
                };
                let (mut stops, mut n) = pieces(u0, u1);
                let mut v0 = u0;
                if n > max as f64 {
                    // Too long to draw whole (an edge to a vertex 1e15 away): only feet
                    // within those of the box's corners can belong to points of the
                    // box, and along a chord the foot is linear, so beyond them one
                    // chord leads to each end, with no point in the box.
                    let feet = visible.corners().map(|c| line.coords(c).0);
                    let lo = feet.iter().copied().fold(f64::INFINITY, f64::min);
                    let hi = feet.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    if u0.max(u1) < lo || u0.min(u1) > hi {
                        out.push(to);
                        return true;
                    }
                    v0 = u0.clamp(lo, hi);
                    (stops, n) = pieces(v0, u1.clamp(lo, hi));
                    if n > max as f64 {
                        out.push(to);
                        return false;
                    }
                }
                if v0 != u0 {
                    out.push(self.point(from, to, v0).0);
                }
                for w in stops.windows(2) {
                    let n = ((w[1] - w[0]).abs() / step).ceil().max(1.0) as usize;
                    for k in 1..n {
                        let u = w[0] + (w[1] - w[0]) * k as f64 / n as f64;
                        out.push(self.point(from, to, u).0);
                    }
                    if w[1] != u1 {
                        out.push(self.point(from, to, w[1]).0);
                    }
                }
            }
            Bisector::Conic(conic) => {
                let (s0, s1) = self.range(from, to);
                match conic.interior_samples(s0, s1, tol, max) {
                    Some(samples) => out.extend(samples),
                    None => {
                        out.push(to);
                        return false;
                    }
                }
            }
        }
        out.push(to);
        true
    }
}

/// Random inputs for the engine's unit tests.
#[cfg(test)]
pub(crate) mod testing {
    use super::*;

    /// Uniform numbers in [0, 1) from a xorshift generator.
    pub(crate) fn rng(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A bisector of kind `case % 3`: points `p` and `q`, point `p` and segment
    /// `other`, segments `third` and `other`.
    pub(crate) fn linear_bisector(
        case: usize,
        p: Point,
        q: Point,
        other: &Line,
        third: &Line,
    ) -> Bisector {
        match case % 3 {
            0 => Bisector::of(Shape::Point(2, p), Shape::Point(3, q), p),
            1 => Bisector::of(Shape::Point(2, p), Shape::Segment(other), p),
            _ => Bisector::of(Shape::Segment(third), Shape::Segment(other), p),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::testing::rng;
    use super::*;

    /// Two segments with a common end, at random angles and at straight and nearly
    /// straight joints (bends down to 1e-12 rad): their bisector goes through the end,
    /// and along it both feet are on the segments (on one side at least), with equal
    /// distances to the two segments there (computed here from the ends). At a
    /// straight joint their common line would fail this: its points have one foot off
    /// one segment.
    #[test]
    fn segments_with_a_common_end_meet_on_their_inner_bisector() {
        let mut rnd = rng(0x7a3c_19e5_d00d_f00d);
        let seg_dist = |x: Point, a: Point, b: Point| {
            let d = b - a;
            let u = (x - a).dot(d) / d.dot(d);
            // Closed, to rounding: at a straight joint the feet are at the end.
            (u > -1e-9 && u < 1.0 + 1e-9).then(|| (d.cross(x - a) / d.norm()).abs())
        };
        for case in 0..2000 {
            let p = Point::new(rnd() * 100.0, rnd() * 100.0);
            let a1 = std::f64::consts::TAU * rnd();
            let bend = match case % 4 {
                0 => 0.0,
                1 => 1e-12,
                2 => 1.5e-10 * (rnd() - 0.5),
                _ => 6.0 * rnd() - 3.0,
            };
            let a2 = a1 + std::f64::consts::PI + bend;
            let (q1, q2) = (
                p + Point::new(a1.cos(), a1.sin()) * (1.0 + 50.0 * rnd()),
                p + Point::new(a2.cos(), a2.sin()) * (1.0 + 50.0 * rnd()),
            );
            // Either segment may start or end at the common point 7.
            let l1 = if case % 3 == 0 {
                Line::new(q1, p, [3, 7])
            } else {
                Line::new(p, q1, [7, 3])
            };
            let l2 = if case % 5 < 2 {
                Line::new(q2, p, [4, 7])
            } else {
                Line::new(p, q2, [7, 4])
            };
            // An edge's middle, near the inner bisector (which of the two lines it
            // is nearer to chooses the bisector at a real bend).
            let inner = Point::new(a1.cos() + a2.cos(), a1.sin() + a2.sin());
            let near = p + inner * (rnd() / inner.norm().max(1e-300)) + Point::new(1e-9, 0.0);
            let bis = Bisector::of(Shape::Segment(&l1), Shape::Segment(&l2), near);
            let Bisector::Line { origin, dir, .. } = bis else {
                panic!("case {case}: {bis:?}");
            };
            let off = dir.cross(p - origin).abs();
            assert!(off <= 1e-12 * 100.0, "case {case}: {off} from the end");
            let mut inside = 0;
            for s in [-0.5, -0.1, 0.1, 0.5] {
                let (x, t) = bis.point(p, p, (p - origin).dot(dir) + s);
                if let (Some(d1), Some(d2)) = (seg_dist(x, q1, p), seg_dist(x, q2, p)) {
                    assert!((d1 - d2).abs() <= 1e-9, "case {case}: {d1} vs {d2}");
                    assert!((t - d1).abs() <= 1e-9, "case {case}: clearance {t} vs {d1}");
                    inside += 1;
                }
            }
            assert!(inside >= 2, "case {case}: no point with both feet inside");
        }
    }

    /// The closed form of `ray_exit` against bisection on the ray of the sign of
    /// `|x − p| − d(x, other)` (the distance to another point, or to a segment's line),
    /// for random points, segments and directions.
    #[test]
    fn ray_exit_matches_bisection() {
        let mut rnd = rng(0x51f1_5e55_0ddb_a11d);
        let mut checked = 0;
        for case in 0..2000 {
            let mut point = || Point::new(rnd(), rnd());
            let (p, q) = (point(), point());
            let line = Line::new(point(), point(), [1, 2]);
            let a = std::f64::consts::TAU * rnd();
            let dir = Point::new(a.cos(), a.sin());
            let (shape, other): (Shape, Box<dyn Fn(Point) -> f64>) = if case % 2 == 0 {
                (Shape::Point(1, q), Box::new(move |x: Point| x.dist(q)))
            } else {
                (
                    Shape::Segment(&line),
                    Box::new(move |x: Point| line.coords(x).1.abs()),
                )
            };
            let f = |s: f64| {
                let x = p + dir * s;
                x.dist(p) - other(x)
            };
            let exit = ray_exit(0, p, dir, shape);
            // Nearer to p at the start; the ray meets the bisector if it ends nearer to
            // the other generator within a long reach.
            let reach = 1e4;
            if f(reach) <= 0.0 {
                assert!(
                    exit.is_none_or(|s| s > 0.5 * reach),
                    "case {case}: {exit:?}"
                );
                continue;
            }
            let s = exit.unwrap_or_else(|| panic!("case {case}: no exit"));
            let (mut lo, mut hi) = (0.0, reach);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if f(mid) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            assert!(
                (s - lo).abs() <= 1e-9 * (1.0 + lo),
                "case {case}: {s} vs {lo}"
            );
            checked += 1;
        }
        assert!(checked > 1000, "{checked}");
    }
}
