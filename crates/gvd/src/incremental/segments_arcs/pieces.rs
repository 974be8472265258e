//! Where a new segment claims a bisector piece: the piece from `from` to `to` splits
//! into intervals of its fraction `λ ∈ [0, 1]`, each wholly claimed or wholly not.
//!
//! Along a line or parabola bisector the point `x(λ)` and everything the claim of
//! segment `s` (foot `f`, signed offset `h`, `f` between the ends' feet and `|h| < t`) depends on is
//! polynomial in `λ` of degree at most two:
//!
//! * parabolas: `x`, `t`, `f` and `h` are quadratics; `|h| < t` changes where
//!   `t − h` or `t + h` vanishes;
//! * lines (and chords): `x`, `f` and `h` are linear and `t²` is quadratic; `|h| < t`
//!   changes where `h² − t²` vanishes (not for a chord along an arc's circle, whose
//!   clearance is the distance to the circle: those pieces are not exact).
//!
//! So the claim can only change at roots of a few quadratics, each interpolated from
//! three samples (expanded about either end of the piece); every interval between consecutive roots is then tested at its middle
//! with the exact predicate. This finds claimed or unclaimed intervals of any width,
//! such as the needle a point next to the segment keeps (the parabola around it is
//! about `√(δ·y)` wide at distance `y`, for the point's distance `δ` to the segment),
//! which samples at fixed fractions miss.

use super::geometry::{Arc, Bisector, Clearance, Line};
use crate::geom::Point;

/// An interval of fractions, claimed by the segment or not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Piece {
    pub(crate) lo: f64,
    pub(crate) hi: f64,
    pub(crate) claimed: bool,
}

impl Piece {
    pub(crate) fn mid(&self) -> f64 {
        0.5 * (self.lo + self.hi)
    }
}

/// The pieces of a bisector, in order, and whether their ends are the roots of the
/// quadratics (to rounding) rather than a sampling's midpoints.
#[derive(Debug)]
pub(crate) struct Pieces {
    list: Vec<Piece>,
    pub(crate) exact: bool,
}

impl std::ops::Deref for Pieces {
    type Target = [Piece];
    fn deref(&self) -> &[Piece] {
        &self.list
    }
}

/// The maximal claimed and unclaimed intervals of the bisector piece from `from` to
/// `to`, in order from `from`, for a new segment `line`.
pub(crate) fn claimed_pieces(bis: &Bisector, from: Point, to: Point, line: &Line) -> Pieces {
    let claims = |x: Point, t: f64| line.claims(x, t);
    if let Bisector::Conic(_) = bis {
        return sampled_pieces(bis, from, to, claims);
    }
    let sample = |lambda: f64| {
        let (x, t) = bis.at_fraction(from, to, lambda);
        let (f, h) = line.coords(x);
        (f, h, t)
    };
    let s = [sample(0.0), sample(0.5), sample(1.0)];
    let quad = |value: &dyn Fn((f64, f64, f64)) -> f64| s.map(value);
    let [foot, end] = line.feet.map(|u| quad(&|(f, ..)| f - u));
    match *bis {
        Bisector::Parabola { p, .. } => {
            // `t ∓ h` as `(t² − h²)/(t ± h)`, a sum without cancellation, with
            // `t² − h²` from the focus (`Line::excess`): far out, `t` and `|h|` agree
            // to their rounding while that difference stays exact in the focus's terms.
            // (only where the difference lost half its bits: `FAR_END`)
            let minus = |(f, h, t): (f64, f64, f64)| {
                let direct = t - h;
                if h > 0.0 && FAR_END * direct.abs() < t {
                    line.excess((f, h), p) / (t + h)
                } else {
                    direct
                }
            };
            let plus = |(f, h, t): (f64, f64, f64)| {
                let direct = t + h;
                if h < 0.0 && FAR_END * direct.abs() < t {
                    line.excess((f, h), p) / (t - h)
                } else {
                    direct
                }
            };
            let quads = [foot, end, quad(&minus), quad(&plus)];
            pieces_between_roots(bis, from, to, &quads, claims)
        }
        _ => {
            let quads = [foot, end, quad(&|(_, h, t)| h * h - t * t)];
            let mut pieces = pieces_between_roots(bis, from, to, &quads, claims);
            // A chord's clearance to a circle is not polynomial: the roots are only
            // where the middles tell the claim.
            if let Bisector::Chord {
                clearance: Clearance::Circle { .. },
            } = bis
            {
                pieces.exact = false;
            }
            pieces
        }
    }
}

/// The same for a new arc `(c, r)` with wedge `a0 < ∠(x − c) < a0 + span`, exact on
/// straight bisectors whose clearance is the distance to a point or a line:
///
/// * the wedge's sides `(x − c) × e_k = 0` are linear in `λ`;
/// * `|x − c| = r ± t`: with a point's clearance `t² = |x − p|²`, `D = |x − c|² − t² −
///   r²` is linear and the condition is `D² − 4r²t² = 0`, a quadratic; with a line's
///   signed offset `t = ±h`, `|x − c|² − (r ± h)² = 0` are two quadratics.
///
/// Conics and parabolas are sampled.
pub(crate) fn arc_pieces(bis: &Bisector, from: Point, to: Point, arc: &Arc) -> Pieces {
    let claims = |x: Point, t: f64| arc.claims(x, t);
    let clearance = match bis {
        Bisector::Line { clearance, .. } | Bisector::Chord { clearance } => *clearance,
        _ => return sampled_pieces(bis, from, to, claims),
    };
    let sides = [arc.a0, arc.a0 + arc.span].map(|a| Point::new(a.cos(), a.sin()));
    let x = [0.0, 0.5, 1.0].map(|l| bis.at_fraction(from, to, l));
    let [s0, s1] = sides.map(|e| x.map(|(q, _)| e.cross(q - arc.c)));
    let r = arc.r;
    match clearance {
        Clearance::Point(p) => {
            let circle = x.map(|(q, _)| {
                let t2 = q.dist2(p);
                let d = q.dist2(arc.c) - t2 - r * r;
                d * d - 4.0 * r * r * t2
            });
            pieces_between_roots(bis, from, to, &[s0, s1, circle], claims)
        }
        Clearance::Line(l) => {
            let [c0, c1] = [1.0, -1.0].map(|sign| {
                x.map(|(q, _)| {
                    let h = l.coords(q).1;
                    q.dist2(arc.c) - (r + sign * h) * (r + sign * h)
                })
            });
            pieces_between_roots(bis, from, to, &[s0, s1, c0, c1], claims)
        }
        Clearance::Circle { .. } => sampled_pieces(bis, from, to, claims),
    }
}

/// At most four quadratics: up to two roots and an extremum each from either end, and
/// both ends.
const MAX_BREAKS: usize = 4 * 3 * 2 + 2;

/// How much larger than the value at `λ = 1` the one at `λ = 0` must be for the roots
/// to be taken from the expansion about `λ = 1` too: beyond it, half the bits of the
/// value there are lost in the coefficients about `λ = 0`.
const FAR_END: f64 = (1u64 << 26) as f64;

/// Pieces split at the roots in `(0, 1)` of the (at most four) quadratics given by
/// their values at `λ = 0, ½, 1` (`quads`), each tested at its middle with `claims`.
///
/// The roots come from the expansion about `λ = 0`, and also from the one about
/// `λ = 1` (the values reversed, for `μ = 1 − λ`) where the value at 0 is far larger
/// ([`FAR_END`]): on an edge from a vertex 1e15 away, the claim's margin there is some
/// 1e30 times the one at a root beside the domain, which only the expansion about the
/// near end keeps. The two copies of a root split off a sliver whose middle the
/// predicate tests like any piece: the claim changes at the copy it bears out.
fn pieces_between_roots(
    bis: &Bisector,
    from: Point,
    to: Point,
    quads: &[[f64; 3]],
    claims: impl Fn(Point, f64) -> bool,
) -> Pieces {
    let mut breaks = [0.0f64; MAX_BREAKS];
    let mut extrema = [f64::NAN; 8];
    let mut n = 0;
    for (k, &[y0, yh, y1]) in quads.iter().enumerate() {
        let far = y0.abs() > FAR_END * y1.abs();
        let ends = if far { 2 } else { 1 };
        for (end, values) in [[y0, yh, y1], [y1, yh, y0]]
            .into_iter()
            .enumerate()
            .take(ends)
        {
            let at = |m: f64| if end == 0 { m } else { 1.0 - m };
            let c = interpolate(values);
            let (roots, count) = quadratic_roots(c);
            for &r in &roots[..count] {
                if r > 0.0 && r < 1.0 {
                    breaks[n] = at(r);
                    n += 1;
                }
            }
            // Two roots closer than rounding can resolve (a piece narrower than about
            // 1e-8 of the edge) leave no break: the extremum between them is tested too.
            let top = -c[1] / (2.0 * c[2]);
            if top > 0.0 && top < 1.0 {
                extrema[2 * k + end] = at(top);
                breaks[n] = at(top);
                n += 1;
            }
        }
    }
    breaks[n] = 0.0;
    breaks[n + 1] = 1.0;
    let breaks = &mut breaks[..n + 2];
    breaks.sort_unstable_by(f64::total_cmp);
    let mut m = 1;
    for k in 1..breaks.len() {
        if breaks[k] != breaks[m - 1] {
            breaks[m] = breaks[k];
            m += 1;
        }
    }
    let breaks = &breaks[..m];

    let claims_at = |lambda: f64| {
        let (x, t) = bis.at_fraction(from, to, lambda);
        claims(x, t)
    };
    let mut pieces: Vec<Piece> = Vec::with_capacity(breaks.len() + 2);
    let mut push = |lo: f64, hi: f64, claimed: bool| match pieces.last_mut() {
        Some(last) if last.claimed == claimed => last.hi = hi,
        _ => pieces.push(Piece { lo, hi, claimed }),
    };
    for w in breaks.windows(2) {
        if extrema.contains(&w[0]) {
            // Zero-width when the claim there differs from the pieces on both sides.
            push(w[0], w[0], claims_at(w[0]));
        }
        push(w[0], w[1], claims_at(0.5 * (w[0] + w[1])));
    }
    Pieces {
        list: pieces,
        exact: true,
    }
}

/// Fractions sampled where the claim is not polynomial in the fraction (conics of
/// arcs): pieces narrower than a sample's spacing can be missed.
const SAMPLES: usize = 64;

/// The claimed and unclaimed intervals of a bisector piece by samples: each interval
/// between consecutive samples whose claims differ is split at the middle.
pub(crate) fn sampled_pieces(
    bis: &Bisector,
    from: Point,
    to: Point,
    claims: impl Fn(Point, f64) -> bool,
) -> Pieces {
    let claim_at = |lambda: f64| {
        let (x, t) = bis.at_fraction(from, to, lambda);
        claims(x, t)
    };
    let mut pieces: Vec<Piece> = Vec::new();
    for k in 0..SAMPLES {
        let (lo, hi) = (k as f64 / SAMPLES as f64, (k + 1) as f64 / SAMPLES as f64);
        let claimed = claim_at(0.5 * (lo + hi));
        match pieces.last_mut() {
            Some(last) if last.claimed == claimed => last.hi = hi,
            _ => pieces.push(Piece { lo, hi, claimed }),
        }
    }
    Pieces {
        list: pieces,
        exact: false,
    }
}

/// The coefficients `[c0, c1, c2]` of the quadratic through `(0, y0)`, `(½, y½)`,
/// `(1, y1)`.
fn interpolate([y0, yh, y1]: [f64; 3]) -> [f64; 3] {
    [y0, 4.0 * yh - 3.0 * y0 - y1, 2.0 * (y0 + y1) - 4.0 * yh]
}

/// The real roots of `c0 + c1·λ + c2·λ²` (a leading coefficient negligible against the
/// others makes it linear), by the cancellation-free formula: the first `count` of the
/// pair.
fn quadratic_roots([c0, c1, c2]: [f64; 3]) -> ([f64; 2], usize) {
    let scale = c0.abs().max(c1.abs()).max(c2.abs());
    if scale == 0.0 || !scale.is_finite() {
        return ([0.0; 2], 0);
    }
    if c2.abs() <= 1e-12 * scale {
        return if c1 != 0.0 {
            ([-c0 / c1, 0.0], 1)
        } else {
            ([0.0; 2], 0)
        };
    }
    let disc = c1 * c1 - 4.0 * c2 * c0;
    if disc < 0.0 {
        return ([0.0; 2], 0);
    }
    let q = -0.5 * (c1 + disc.sqrt().copysign(c1));
    if q == 0.0 {
        return ([0.0; 2], 1);
    }
    ([q / c2, c0 / q], 2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::incremental::segments_arcs::geometry::testing::{linear_bisector, rng};
    use crate::incremental::segments_arcs::geometry::Shape;

    #[test]
    fn roots_of_quadratics() {
        let roots = |c| {
            let (r, n) = quadratic_roots(c);
            let mut r = r[..n].to_vec();
            r.sort_by(f64::total_cmp);
            r
        };
        assert_eq!(roots([2.0, -3.0, 1.0]), vec![1.0, 2.0]);
        assert_eq!(roots([1.0, 0.0, 1.0]), Vec::<f64>::new());
        assert_eq!(roots([-1.0, 2.0, 0.0]), vec![0.5]);
    }

    /// A point 1e-7 from the segment keeps a needle about 1e-4 wide around it; the
    /// bisector of that point and another one crosses the needle in the middle of an
    /// otherwise claimed edge.
    #[test]
    fn finds_a_needle_in_a_claimed_edge() {
        let line = Line::new(Point::new(0.0, 0.0), Point::new(1.0, 0.0), [0, 1]);
        let p = Point::new(0.5, 1e-7);
        let q = Point::new(0.5, 0.02);
        let bis = Bisector::of(Shape::Point(2, p), Shape::Point(3, q), p.lerp(q, 0.5));
        let (from, to) = (Point::new(0.3, 0.01), Point::new(0.7, 0.01));
        let pieces = claimed_pieces(&bis, from, to, &line);
        assert_eq!(pieces.len(), 3, "{pieces:?}");
        assert!(pieces[0].claimed && !pieces[1].claimed && pieces[2].claimed);
        let needle = pieces[1];
        assert!(needle.hi - needle.lo < 2e-3, "{needle:?}");
        let (x, t) = bis.at_fraction(from, to, needle.mid());
        assert!((x.x - 0.5).abs() < 1e-4 && !line.claims(x, t));
    }

    /// On random point/point, point/segment and segment/segment bisectors, dense samples
    /// inside each piece agree with its claim.
    #[test]
    fn pieces_agree_with_dense_samples() {
        let mut rnd = rng(0x2545_f491_4f6c_dd1du64);
        let mut point = || Point::new(rnd(), rnd());
        let line = Line::new(Point::new(0.3, 0.4), Point::new(0.7, 0.55), [0, 1]);
        let mut checked = 0;
        for case in 0..300 {
            let (p, q) = (point(), point());
            let other = Line::new(point(), point(), [4, 5]);
            let third = Line::new(point(), point(), [6, 7]);
            let bis = linear_bisector(case, p, q, &other, &third);
            let (from, to) = (point(), point());
            // Project the ends onto the bisector through its own parametrization.
            let (a, _) = bis.at_fraction(from, to, 0.0);
            let (b, _) = bis.at_fraction(from, to, 1.0);
            if !(a.x.is_finite() && b.x.is_finite()) || a.dist(b) > 10.0 {
                continue;
            }
            let pieces = claimed_pieces(&bis, a, b, &line);
            for piece in pieces.iter() {
                for k in 1..200 {
                    let lambda = piece.lo + (piece.hi - piece.lo) * k as f64 / 200.0;
                    let (x, t) = bis.at_fraction(a, b, lambda);
                    let margin = (line.coords(x).1.abs() - t).abs();
                    if margin > 1e-9 {
                        assert_eq!(
                            line.claims(x, t),
                            piece.claimed,
                            "case {case}: {pieces:?} at {lambda}"
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 10_000, "{checked}");
    }

    /// The same for a new arc, on point/point and segment/segment bisectors (exact
    /// roots).
    #[test]
    fn arc_pieces_agree_with_dense_samples() {
        let mut rnd = rng(0x9e37_79b9_7f4a_7c15u64);
        let mut checked = 0;
        for case in 0..300 {
            let arc = Arc::new(
                Point::new(0.5, 0.5),
                0.1 + 0.3 * rnd(),
                6.0 * rnd(),
                6.0 * rnd(),
                [0, 1],
            );
            let mut point = || Point::new(rnd(), rnd());
            let (p, q) = (point(), point());
            let other = Line::new(point(), point(), [4, 5]);
            let third = Line::new(point(), point(), [6, 7]);
            let bis = if case % 2 == 0 {
                Bisector::of(Shape::Point(2, p), Shape::Point(3, q), p)
            } else {
                Bisector::of(Shape::Segment(&third), Shape::Segment(&other), p)
            };
            let (from, to) = (point(), point());
            let (a, _) = bis.at_fraction(from, to, 0.0);
            let (b, _) = bis.at_fraction(from, to, 1.0);
            if !(a.x.is_finite() && b.x.is_finite()) || a.dist(b) > 10.0 {
                continue;
            }
            let pieces = arc_pieces(&bis, a, b, &arc);
            for piece in pieces.iter() {
                for k in 1..200 {
                    let lambda = piece.lo + (piece.hi - piece.lo) * k as f64 / 200.0;
                    let (x, t) = bis.at_fraction(a, b, lambda);
                    let margin = ((x.dist(arc.c) - arc.r).abs() - t).abs();
                    let v = x - arc.c;
                    let rel = (v.y.atan2(v.x) - arc.a0).rem_euclid(std::f64::consts::TAU);
                    let wedge_margin = rel.min((rel - arc.span).abs());
                    if margin > 1e-9 && wedge_margin > 1e-9 {
                        assert_eq!(
                            arc.claims(x, t),
                            piece.claimed,
                            "case {case}: {pieces:?} at {lambda}"
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 10_000, "{checked}");
    }
}
