//! Where a new segment claims a bisector piece: the piece from `from` to `to` splits
//! into intervals of its fraction `λ ∈ [0, 1]`, each wholly claimed or wholly not.
//!
//! Along a line or parabola bisector the point `x(λ)` and everything the claim of
//! segment `s` (foot `f`, signed offset `h`, `0 < f < len` and `|h| < t`) depends on is
//! polynomial in `λ` of degree at most two:
//!
//! * parabolas: `x`, `t`, `f` and `h` are quadratics; `|h| < t` changes where
//!   `t − h` or `t + h` vanishes;
//! * lines (and chords): `x`, `f` and `h` are linear and `t²` is quadratic; `|h| < t`
//!   changes where `h² − t²` vanishes.
//!
//! So the claim can only change at roots of a few quadratics, each interpolated from
//! three samples; every interval between consecutive roots is then tested at its middle
//! with the exact predicate. This finds claimed or unclaimed intervals of any width,
//! such as the needle a point next to the segment keeps (the parabola around it is
//! about `√(δ·y)` wide at distance `y`, for the point's distance `δ` to the segment),
//! which samples at fixed fractions miss.

use super::geometry::{Bisector, Line};
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

/// The maximal claimed and unclaimed intervals of the bisector piece from `from` to
/// `to`, in order from `from`.
pub(crate) fn claimed_pieces(bis: &Bisector, from: Point, to: Point, line: &Line) -> Vec<Piece> {
    let sample = |lambda: f64| {
        let (x, t) = bis.at_fraction(from, to, lambda);
        let (f, h) = line.coords(x);
        (f, h, t)
    };
    let s = [sample(0.0), sample(0.5), sample(1.0)];
    let quad = |value: &dyn Fn((f64, f64, f64)) -> f64| interpolate(s.map(value));
    let mut breaks = Fractions::default();
    let mut extrema = Fractions::default();
    let mut add_roots = |c: [f64; 3]| {
        for r in quadratic_roots(c).into_iter().flatten() {
            if r > 0.0 && r < 1.0 {
                breaks.push(r);
            }
        }
        // Two roots closer than rounding can resolve (a piece narrower than about
        // 1e-8 of the edge) leave no break: the extremum between them is tested too.
        let top = -c[1] / (2.0 * c[2]);
        if top > 0.0 && top < 1.0 {
            extrema.push(top);
        }
    };
    add_roots(quad(&|(f, _, _)| f));
    add_roots(quad(&|(f, _, _)| f - line.len));
    match bis {
        Bisector::Conic(_) => return sampled_pieces(bis, from, to, |x, t| line.claims(x, t)),
        Bisector::Parabola { .. } => {
            add_roots(quad(&|(_, h, t)| t - h));
            add_roots(quad(&|(_, h, t)| t + h));
        }
        Bisector::Line { .. } | Bisector::Chord { .. } => {
            add_roots(quad(&|(_, h, t)| h * h - t * t));
        }
    }
    for &top in extrema.as_slice() {
        breaks.push(top);
    }
    breaks.push(0.0);
    breaks.push(1.0);
    let breaks = breaks.sorted_distinct();
    let extrema = extrema.as_slice();

    let claims_at = |lambda: f64| {
        let (x, t) = bis.at_fraction(from, to, lambda);
        line.claims(x, t)
    };
    let mut pieces: Vec<Piece> = Vec::with_capacity(breaks.len);
    let mut push = |lo: f64, hi: f64, claimed: bool| match pieces.last_mut() {
        Some(last) if last.claimed == claimed => last.hi = hi,
        _ => pieces.push(Piece { lo, hi, claimed }),
    };
    for w in breaks.as_slice().windows(2) {
        if extrema.contains(&w[0]) {
            // Zero-width when the claim there differs from the pieces on both sides.
            push(w[0], w[0], claims_at(w[0]));
        }
        push(w[0], w[1], claims_at(0.5 * (w[0] + w[1])));
    }
    pieces
}

/// A few fractions (breaks of a bisector piece: at most two roots of each of four
/// quadratics, their extrema, and the two ends), without allocating.
#[derive(Default)]
struct Fractions {
    values: [f64; 16],
    len: usize,
}

impl Fractions {
    fn push(&mut self, x: f64) {
        self.values[self.len] = x;
        self.len += 1;
    }

    fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    /// The fractions in increasing order, equal ones once.
    fn sorted_distinct(mut self) -> Fractions {
        let v = &mut self.values[..self.len];
        v.sort_by(f64::total_cmp);
        let mut n = 0;
        for k in 0..v.len() {
            if n == 0 || v[k] != v[n - 1] {
                v[n] = v[k];
                n += 1;
            }
        }
        self.len = n;
        self
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
) -> Vec<Piece> {
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
    pieces
}

/// The coefficients `[c0, c1, c2]` of the quadratic through `(0, y0)`, `(½, y½)`,
/// `(1, y1)`.
fn interpolate([y0, yh, y1]: [f64; 3]) -> [f64; 3] {
    [y0, 4.0 * yh - 3.0 * y0 - y1, 2.0 * (y0 + y1) - 4.0 * yh]
}

/// The real roots of `c0 + c1·λ + c2·λ²` (a leading coefficient negligible against the
/// others makes it linear), by the cancellation-free formula.
fn quadratic_roots([c0, c1, c2]: [f64; 3]) -> [Option<f64>; 2] {
    let scale = c0.abs().max(c1.abs()).max(c2.abs());
    if scale == 0.0 || !scale.is_finite() {
        return [None, None];
    }
    if c2.abs() <= 1e-12 * scale {
        return [(c1 != 0.0).then(|| -c0 / c1), None];
    }
    let disc = c1 * c1 - 4.0 * c2 * c0;
    if disc < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (c1 + disc.sqrt().copysign(c1));
    if q == 0.0 {
        return [Some(0.0), None];
    }
    [Some(q / c2), Some(c0 / q)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::incremental::segments::geometry::Shape;

    #[test]
    fn roots_of_quadratics() {
        let roots = |c| quadratic_roots(c).into_iter().flatten().collect::<Vec<_>>();
        let mut r = roots([2.0, -3.0, 1.0]);
        r.sort_by(f64::total_cmp);
        assert_eq!(r, vec![1.0, 2.0]);
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
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut rnd = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut point = || Point::new(rnd(), rnd());
        let line = Line::new(Point::new(0.3, 0.4), Point::new(0.7, 0.55), [0, 1]);
        let mut checked = 0;
        for case in 0..300 {
            let (p, q) = (point(), point());
            let other = Line::new(point(), point(), [4, 5]);
            let third = Line::new(point(), point(), [6, 7]);
            let bis = match case % 3 {
                0 => Bisector::of(Shape::Point(2, p), Shape::Point(3, q), p),
                1 => Bisector::of(Shape::Point(2, p), Shape::Segment(&other), p),
                _ => Bisector::of(Shape::Segment(&third), Shape::Segment(&other), p),
            };
            let (from, to) = (point(), point());
            // Project the ends onto the bisector through its own parametrization.
            let (a, _) = bis.at_fraction(from, to, 0.0);
            let (b, _) = bis.at_fraction(from, to, 1.0);
            if !(a.x.is_finite() && b.x.is_finite()) || a.dist(b) > 10.0 {
                continue;
            }
            let pieces = claimed_pieces(&bis, a, b, &line);
            for piece in &pieces {
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
}
