//! Certified real root isolation for univariate Bernstein forms on `[0, 1]`.
//!
//! Subdivision (at midpoints, or at `3/8`, `5/8` when the midpoint value is within
//! rounding of zero; piece ends are exact fixed-point numbers) with two tests on the
//! coefficients `b_i` of a piece, each counted as `+` (`b_i > err`), `−` (`b_i < −err`)
//! or unknown (`|b_i| ≤ err`, the exact coefficient may be zero or of either sign):
//! * exclusion: all known and of one sign ⇒ `f ≠ 0` on the closed piece (convex hull);
//! * Descartes' rule of signs: all known with exactly one sign variation ⇒ exactly one
//!   root in the open piece, and none at its ends (`b_0 = f(lo)`, `b_n = f(hi)` ≠ 0).
//!
//! A piece whose coefficients are all unknown is indistinguishable from zero and is
//! reported at once as uncertified; so is any piece narrower than `min_width` (at least
//! `2⁻⁴⁹`). The work is capped at [`MAX_PIECES`] pieces, after which the unexplored
//! pieces are reported as uncertified, so every call terminates quickly. No root is ever
//! missed: a piece is dropped only by the exclusion test.

use crate::num::bernstein::Bernstein1;

/// Largest number of pieces one call examines.
pub const MAX_PIECES: usize = 1 << 16;

/// Piece ends are exact fixed-point numbers `k / ONE`, so every split parameter handed
/// to de Casteljau (`1/2`, `3/8`, `5/8`) matches the piece ends exactly.
const ONE: u64 = 1 << 62;
const SCALE: f64 = ONE as f64;

/// Smallest usable width, in units of `1 / ONE` (`2⁻⁴⁹`; smaller requests are raised).
const MIN_UNITS: u64 = 1 << 13;

/// A parameter interval `[lo, hi] ⊆ [0, 1]` holding roots.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RootInterval {
    /// The left end.
    pub lo: f64,
    /// The right end.
    pub hi: f64,
    /// True when exactly one root (simple, in the open interval) is proved; false when
    /// the interval may hold any number of roots, including none.
    pub certified: bool,
}

enum Verdict {
    /// No root on the closed piece.
    Excluded,
    /// Exactly one root, in the open piece.
    One,
    /// Every coefficient within `err` of zero.
    Flat,
    Unknown,
}

fn classify(b: &Bernstein1) -> Verdict {
    let (mut last, mut changes, mut unknown) = (0i8, 0, 0);
    for &c in &b.coef {
        let s = if c > b.err {
            1
        } else if c < -b.err {
            -1
        } else {
            0
        };
        if s == 0 {
            unknown += 1;
            continue;
        }
        if last != 0 && s != last {
            changes += 1;
        }
        last = s;
    }
    match (unknown, changes) {
        (u, _) if u == b.coef.len() => Verdict::Flat,
        (0, 0) => Verdict::Excluded,
        (0, 1) => Verdict::One,
        _ => Verdict::Unknown,
    }
}

/// A piece of `[0, 1]`: the form over it and its exact ends in units of `1 / ONE`.
struct Piece {
    f: Bernstein1,
    lo: u64,
    hi: u64,
}

impl Piece {
    fn whole(b: &Bernstein1) -> Self {
        Piece {
            f: b.clone(),
            lo: 0,
            hi: ONE,
        }
    }

    /// Splits at the midpoint, or at `3/8` / `5/8` of the piece when the value at the
    /// midpoint is within `err` of zero (a root there could never be certified), as long
    /// as the ends stay exact. `None` when the piece is too short to split exactly.
    fn split(&self) -> Option<(Piece, Piece)> {
        let len = self.hi - self.lo;
        if len & 1 != 0 {
            return None;
        }
        let near_zero = |r: &Bernstein1| r.coef[0].abs() <= r.err;
        let mut halves = self.f.split(0.5);
        let mut at = self.lo + len / 2;
        if near_zero(&halves.1) && len & 7 == 0 {
            for k in [3, 5] {
                let parts = self.f.split(k as f64 / 8.0);
                if !near_zero(&parts.1) {
                    halves = parts;
                    at = self.lo + len / 8 * k;
                    break;
                }
            }
        }
        let (l, r) = halves;
        Some((
            Piece {
                f: l,
                lo: self.lo,
                hi: at,
            },
            Piece {
                f: r,
                lo: at,
                hi: self.hi,
            },
        ))
    }
}

/// `k / ONE` rounded down (`up = false`) or up to an f64.
fn to_f64(k: u64, up: bool) -> f64 {
    let x = k as f64 / SCALE; // division by a power of two is exact
    let back = (x * SCALE) as u64;
    match (back.cmp(&k), up) {
        (std::cmp::Ordering::Greater, false) => x.next_down(),
        (std::cmp::Ordering::Less, true) => x.next_up(),
        _ => x,
    }
}

fn min_units(min_width: f64) -> u64 {
    if min_width * SCALE > MIN_UNITS as f64 {
        (min_width * SCALE).min(SCALE) as u64
    } else {
        MIN_UNITS
    }
}

/// Isolates the real roots of `b` in `[0, 1]`: sorted, disjoint intervals (relative
/// parameters, ends rounded outward to f64) whose union holds every root. Certified
/// intervals hold exactly one root; adjacent uncertified ones are merged (clusters,
/// multiple roots, near-zero stretches).
pub fn isolate(b: &Bernstein1, min_width: f64) -> Vec<RootInterval> {
    let min_len = min_units(min_width);
    let mut out: Vec<(u64, u64, bool)> = Vec::new();
    let mut emit = |lo: u64, hi: u64, certified: bool| match out.last_mut() {
        Some(last) if !last.2 && !certified && last.1 == lo => last.1 = hi,
        _ => out.push((lo, hi, certified)),
    };
    // depth-first, left piece on top: pieces come off the stack left to right
    let mut stack = vec![Piece::whole(b)];
    let mut pieces = 0;
    while let Some(p) = stack.pop() {
        pieces += 1;
        if pieces > MAX_PIECES {
            emit(p.lo, p.hi, false);
            continue;
        }
        match classify(&p.f) {
            Verdict::Excluded => {}
            Verdict::One => emit(p.lo, p.hi, true),
            Verdict::Flat => emit(p.lo, p.hi, false),
            Verdict::Unknown => match p.split() {
                Some((l, r)) if p.hi - p.lo > min_len => {
                    stack.push(r);
                    stack.push(l);
                }
                _ => emit(p.lo, p.hi, false),
            },
        }
    }
    out.into_iter()
        .map(|(lo, hi, certified)| RootInterval {
            lo: to_f64(lo, false),
            hi: to_f64(hi, true),
            certified,
        })
        .collect()
}

/// A value `≤` the smallest root of `b` in `[0, 1]` (`None`: provably no root), within
/// about `min_width` of it: the left end of the leftmost piece that cannot be excluded.
pub fn first_root(b: &Bernstein1, min_width: f64) -> Option<f64> {
    extreme_root(b, min_width, false)
}

/// A value `≥` the largest root of `b` in `[0, 1]` (`None`: provably no root).
pub fn last_root(b: &Bernstein1, min_width: f64) -> Option<f64> {
    extreme_root(b, min_width, true)
}

/// Depth-first search from the left (or right, when `from_right`) for the first piece
/// that is not excluded and cannot usefully be split further.
fn extreme_root(b: &Bernstein1, min_width: f64, from_right: bool) -> Option<f64> {
    let min_len = min_units(min_width);
    let mut stack = vec![Piece::whole(b)];
    let mut pieces = 0;
    let end = |p: &Piece| {
        if from_right {
            to_f64(p.hi, true)
        } else {
            to_f64(p.lo, false)
        }
    };
    while let Some(p) = stack.pop() {
        pieces += 1;
        match classify(&p.f) {
            Verdict::Excluded => continue,
            Verdict::Flat => return Some(end(&p)),
            _ if pieces > MAX_PIECES || p.hi - p.lo <= min_len => return Some(end(&p)),
            _ => match p.split() {
                Some((l, r)) => {
                    let (near, far) = if from_right { (r, l) } else { (l, r) };
                    stack.push(far);
                    stack.push(near);
                }
                None => return Some(end(&p)),
            },
        }
    }
    None
}

/// Refines a root bracketed by a sign change of `b` on `[lo, hi]` by bisection to full
/// f64 precision (f64 evaluation, not certified). Without a sign change at the ends,
/// returns the end with the smaller `|b|`.
pub fn refine(b: &Bernstein1, mut lo: f64, mut hi: f64) -> f64 {
    let (mut flo, fhi) = (b.eval(lo), b.eval(hi));
    if flo == 0.0 {
        return lo;
    }
    if fhi == 0.0 {
        return hi;
    }
    if (flo > 0.0) == (fhi > 0.0) || flo.is_nan() || fhi.is_nan() {
        return if flo.abs() <= fhi.abs() { lo } else { hi };
    }
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return if flo.abs() <= b.eval(hi).abs() {
                lo
            } else {
                hi
            };
        }
        let fm = b.eval(mid);
        if fm == 0.0 {
            return mid;
        }
        if (fm > 0.0) == (flo > 0.0) {
            lo = mid;
            flo = fm;
        } else {
            hi = mid;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::poly::Poly;
    use crate::num::Interval;
    use proptest::prelude::*;

    /// The power coefficients of `c · Π (t − r_i)`.
    fn from_roots(roots: &[f64], c: f64) -> Vec<f64> {
        let mut p = vec![c];
        for &r in roots {
            let mut q = vec![0.0; p.len() + 1];
            for (i, &a) in p.iter().enumerate() {
                q[i + 1] += a;
                q[i] -= r * a;
            }
            p = q;
        }
        p
    }

    fn unit() -> Interval {
        Interval::new(0.0, 1.0)
    }

    #[test]
    fn isolates_known_simple_roots() {
        let roots = [0.1, 0.25, 0.5, 0.8, 0.95];
        let b = Bernstein1::from_poly_1d(&from_roots(&roots, 3.0), unit());
        let iso = isolate(&b, 1e-9);
        assert_eq!(iso.len(), roots.len(), "{iso:?}");
        for (r, iv) in roots.iter().zip(&iso) {
            assert!(iv.certified && iv.lo < *r && *r < iv.hi, "{r} {iv:?}");
            let x = refine(&b, iv.lo, iv.hi);
            assert!((x - r).abs() < 1e-12, "{x} vs {r}");
        }
        let first = first_root(&b, 1e-6).unwrap();
        assert!(first <= 0.1 && first > 0.1 - 2e-6, "{first}");
        let last = last_root(&b, 1e-6).unwrap();
        assert!((0.95..0.95 + 2e-6).contains(&last), "{last}");
    }

    #[test]
    fn handles_double_roots_endpoints_and_no_roots() {
        // (t − 0.3)² (t − 0.7): a double and a simple root
        let b = Bernstein1::from_poly_1d(&from_roots(&[0.3, 0.3, 0.7], 1.0), unit());
        let iso = isolate(&b, 1e-10);
        assert!(
            iso.iter()
                .any(|i| !i.certified && i.lo <= 0.3 && 0.3 <= i.hi),
            "{iso:?}"
        );
        assert!(
            iso.iter().any(|i| i.certified && i.lo < 0.7 && 0.7 < i.hi),
            "{iso:?}"
        );
        assert!(iso.len() <= 3, "{iso:?}");
        // roots at the ends and at the first split point
        let b = Bernstein1::from_poly_1d(&from_roots(&[0.0, 0.5, 1.0], 1.0), unit());
        let iso = isolate(&b, 1e-8);
        for r in [0.0, 0.5, 1.0] {
            assert!(iso.iter().any(|i| i.lo <= r && r <= i.hi), "{r}: {iso:?}");
        }
        assert_eq!(first_root(&b, 1e-8), Some(0.0));
        assert_eq!(last_root(&b, 1e-8), Some(1.0));
        // t² + 1 has no real roots
        let b = Bernstein1::from_poly_1d(&[1.0, 0.0, 1.0], unit());
        assert!(isolate(&b, 1e-8).is_empty());
        assert_eq!(first_root(&b, 1e-8), None);
        // the zero polynomial: one uncertified interval, at once
        let z = Bernstein1 {
            coef: vec![0.0; 4],
            err: 0.0,
        };
        assert_eq!(
            isolate(&z, 0.0),
            vec![RootInterval {
                lo: 0.0,
                hi: 1.0,
                certified: false
            }]
        );
    }

    #[test]
    fn a_high_multiplicity_root_terminates_quickly() {
        let b = Bernstein1::from_poly_1d(&from_roots(&[0.4; 7], 1.0), unit());
        let iso = isolate(&b, 0.0);
        assert_eq!(iso.len(), 1, "{iso:?}");
        assert!(iso[0].lo <= 0.4 && 0.4 <= iso[0].hi);
    }

    proptest! {
        #[test]
        fn never_misses_a_root(
            roots in proptest::collection::vec(prop_oneof![-0.2..1.2f64, Just(0.5), Just(0.25), Just(0.375), Just(0.0)], 1..8),
            c in prop_oneof![-5.0..-0.1f64, 0.1..5.0f64],
            a in prop_oneof![Just(0.0), -1.0..0.5f64],
            w in prop_oneof![Just(1.0), 0.1..2.0f64],
        ) {
            let dom = Interval::new(a, a + w);
            let power = from_roots(&roots, c);
            let b = Bernstein1::from_poly_1d(&power, dom);
            let iso = isolate(&b, 1e-9);
            for pair in iso.windows(2) {
                prop_assert!(pair[0].hi <= pair[1].lo);
            }
            // the exact polynomial's sign, where certain, at world point t
            let p = Poly::from_terms(power.iter().enumerate().map(|(i, &c)| ([i as u32, 0, 0], c)).collect());
            let sign = |t: f64| {
                let v = p.eval_interval(Interval::point(t), Interval::point(0.0), Interval::point(0.0));
                if v.lo > 0.0 { 1 } else if v.hi < 0.0 { -1 } else { 0 }
            };
            let mut ts: Vec<f64> = roots.iter().flat_map(|&r| [r - 1e-6, r + 1e-6]).chain([a, a + w]).filter(|t| dom.contains(*t)).collect();
            ts.sort_by(f64::total_cmp);
            let rel = |t: f64| (t - a) / w;
            let covered = |u0: f64, u1: f64| iso.iter().any(|i| i.lo <= u1 + 1e-12 && u0 - 1e-12 <= i.hi);
            let mut first_bracket = None;
            let mut last_bracket = None;
            for pair in ts.windows(2) {
                let (sa, sb) = (sign(pair[0]), sign(pair[1]));
                if sa * sb < 0 {
                    let (u0, u1) = (rel(pair[0]), rel(pair[1]));
                    prop_assert!(covered(u0, u1), "sign change in [{}, {}] missed: {:?}", u0, u1, iso);
                    first_bracket.get_or_insert(u1);
                    last_bracket = Some(u0);
                }
            }
            for i in iso.iter().filter(|i| i.certified) {
                let (sa, sb) = (sign(a + i.lo * w), sign(a + i.hi * w));
                prop_assert!(sa * sb <= 0, "certified interval without a sign change: {:?}", i);
            }
            if let Some(u1) = first_bracket {
                prop_assert!(first_root(&b, 1e-6).is_some_and(|f| f <= u1 + 1e-12));
                prop_assert!(last_root(&b, 1e-6).is_some_and(|l| l >= last_bracket.unwrap() - 1e-12));
            }
            if iso.is_empty() {
                prop_assert!(first_root(&b, 1e-9).is_none() && last_root(&b, 1e-9).is_none());
            }
        }

        #[test]
        fn sign_changes_are_found_in_random_polynomials(c in proptest::collection::vec(-10.0..10.0f64, 2..9), s in proptest::collection::vec(0.0..=1.0f64, 2..20)) {
            // any sampled sign change must lie inside the union of the reported intervals
            let b = Bernstein1 { coef: c, err: 0.0 };
            let iso = isolate(&b, 1e-9);
            let mut s = s;
            s.sort_by(f64::total_cmp);
            for w in s.windows(2) {
                let (fa, fb) = (b.eval(w[0]), b.eval(w[1]));
                if fa.abs() > 1e-9 && fb.abs() > 1e-9 && (fa > 0.0) != (fb > 0.0) {
                    prop_assert!(iso.iter().any(|i| i.hi >= w[0] && i.lo <= w[1]), "{:?} between {} and {}", iso, w[0], w[1]);
                }
            }
        }
    }
}
