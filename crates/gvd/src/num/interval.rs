//! Closed f64 intervals with outward rounding.
//!
//! Every arithmetic result is widened by one ulp on each side (`next_down` / `next_up`),
//! which encloses the exact result of the operation on the exact operands: round-to-
//! nearest is off by at most half an ulp. All rounding goes through [`round_down`] and
//! [`round_up`], so a faster directed-rounding successor can be swapped in at one place.

use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

/// Rounds a computed lower end down so that it encloses the exact value.
#[inline]
pub fn round_down(x: f64) -> f64 {
    x.next_down()
}

/// Rounds a computed upper end up so that it encloses the exact value.
#[inline]
pub fn round_up(x: f64) -> f64 {
    x.next_up()
}

/// A closed interval `[lo, hi]` of reals, `lo <= hi` (or empty-free by construction).
#[derive(Clone, Copy, PartialEq, Debug, Default)]
pub struct Interval {
    /// The lower end.
    pub lo: f64,
    /// The upper end.
    pub hi: f64,
}

impl Interval {
    /// The interval `[lo, hi]`; the caller guarantees `lo <= hi`.
    #[inline]
    pub const fn new(lo: f64, hi: f64) -> Self {
        Interval { lo, hi }
    }

    /// The degenerate interval `[x, x]`.
    #[inline]
    pub const fn point(x: f64) -> Self {
        Interval { lo: x, hi: x }
    }

    /// The smallest interval holding both `a` and `b`, in either order.
    #[inline]
    pub fn hull_of(a: f64, b: f64) -> Self {
        Interval::new(a.min(b), a.max(b))
    }

    /// The smallest interval holding `self` and `other`.
    #[inline]
    pub fn hull(self, other: Interval) -> Self {
        Interval::new(self.lo.min(other.lo), self.hi.max(other.hi))
    }

    #[inline]
    /// `hi − lo`.
    pub fn width(self) -> f64 {
        self.hi - self.lo
    }

    #[inline]
    /// The midpoint.
    pub fn mid(self) -> f64 {
        0.5 * (self.lo + self.hi)
    }

    #[inline]
    /// Whether `x` lies in the closed interval.
    pub fn contains(self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }

    /// True when every element is strictly positive or every element strictly negative.
    #[inline]
    pub fn excludes_zero(self) -> bool {
        self.lo > 0.0 || self.hi < 0.0
    }

    /// The largest absolute value in the interval.
    #[inline]
    pub fn mag(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// `self²`, tight (non-negative even when the interval straddles zero).
    #[inline]
    pub fn sqr(self) -> Self {
        let (a, b) = (self.lo.abs(), self.hi.abs());
        let (small, large) = if a < b { (a, b) } else { (b, a) };
        let lo = if self.lo <= 0.0 && self.hi >= 0.0 {
            0.0
        } else {
            round_down(small * small).max(0.0)
        };
        Interval::new(lo, round_up(large * large))
    }

    /// `self^n` for a non-negative integer `n`, tight for even and odd `n`: the end
    /// values' powers (monotone pieces), each widened by its rounding error.
    pub fn powi(self, n: u32) -> Self {
        match n {
            0 => Interval::point(1.0),
            1 => self,
            _ if n % 2 == 0 => {
                let (a, b) = (self.lo.abs(), self.hi.abs());
                let (small, large) = if a < b { (a, b) } else { (b, a) };
                let lo = if self.lo <= 0.0 && self.hi >= 0.0 {
                    0.0
                } else {
                    pow_enclosure(small, n).0.max(0.0)
                };
                Interval::new(lo, pow_enclosure(large, n).1)
            }
            _ => Interval::new(pow_enclosure(self.lo, n).0, pow_enclosure(self.hi, n).1),
        }
    }

    /// `sqrt(self)` for `self.lo >= 0` (negative parts are clamped to zero).
    #[inline]
    pub fn sqrt(self) -> Self {
        Interval::new(
            round_down(self.lo.max(0.0).sqrt()).max(0.0),
            round_up(self.hi.max(0.0).sqrt()),
        )
    }

    /// `self / d` for a divisor interval that excludes zero (`None` otherwise).
    #[allow(clippy::should_implement_trait)] // partial: `None` when d holds 0
    pub fn div(self, d: Interval) -> Option<Self> {
        if !d.excludes_zero() {
            return None;
        }
        let q = [
            self.lo / d.lo,
            self.lo / d.hi,
            self.hi / d.lo,
            self.hi / d.hi,
        ];
        let lo = q[0].min(q[1]).min(q[2]).min(q[3]);
        let hi = q[0].max(q[1]).max(q[2]).max(q[3]);
        Some(Interval::new(round_down(lo), round_up(hi)))
    }

    /// `self * k` for a scalar `k`.
    #[inline]
    pub fn scale(self, k: f64) -> Self {
        let (a, b) = (self.lo * k, self.hi * k);
        Interval::new(round_down(a.min(b)), round_up(a.max(b)))
    }
}

/// An enclosure of `x^n`: squaring multiplies at most `2·log2(n)` times, each off by
/// half an ulp, far inside the `2n` ulps allowed here; the absolute term covers
/// subnormals.
fn pow_enclosure(x: f64, n: u32) -> (f64, f64) {
    let r = ipow(x, n);
    let e = r.abs() * (2.0 * n as f64 * f64::EPSILON) + f64::MIN_POSITIVE;
    (round_down(r - e), round_up(r + e))
}

/// `x^n` by repeated squaring.
#[inline]
pub fn ipow(mut x: f64, mut n: u32) -> f64 {
    let mut r = 1.0;
    while n > 0 {
        if n & 1 == 1 {
            r *= x;
        }
        x *= x;
        n >>= 1;
    }
    r
}

impl Add for Interval {
    type Output = Interval;
    #[inline]
    fn add(self, o: Interval) -> Interval {
        Interval::new(round_down(self.lo + o.lo), round_up(self.hi + o.hi))
    }
}

impl Sub for Interval {
    type Output = Interval;
    #[inline]
    fn sub(self, o: Interval) -> Interval {
        Interval::new(round_down(self.lo - o.hi), round_up(self.hi - o.lo))
    }
}

impl Neg for Interval {
    type Output = Interval;
    #[inline]
    fn neg(self) -> Interval {
        Interval::new(-self.hi, -self.lo)
    }
}

impl Mul for Interval {
    type Output = Interval;
    #[inline]
    fn mul(self, o: Interval) -> Interval {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        let lo = p[0].min(p[1]).min(p[2]).min(p[3]);
        let hi = p[0].max(p[1]).max(p[2]).max(p[3]);
        Interval::new(round_down(lo), round_up(hi))
    }
}

impl Add<f64> for Interval {
    type Output = Interval;
    #[inline]
    fn add(self, k: f64) -> Interval {
        self + Interval::point(k)
    }
}

impl Sub<f64> for Interval {
    type Output = Interval;
    #[inline]
    fn sub(self, k: f64) -> Interval {
        self - Interval::point(k)
    }
}

impl fmt::Display for Interval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "[{}, {}]", self.lo, self.hi)
    }
}

/// A box's coordinate ranges as intervals (here, so that `geom` needs nothing of `num`).
impl crate::geom::Aabb {
    /// The box's range of `x`.
    #[inline]
    pub fn x(&self) -> Interval {
        Interval::new(self.min.x, self.max.x)
    }
    /// The box's range of `y`.
    #[inline]
    pub fn y(&self) -> Interval {
        Interval::new(self.min.y, self.max.y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn products_enclose_samples(a in -1e3..1e3f64, b in 0.0..1e3f64, c in -1e3..1e3f64, d in 0.0..1e3f64, s in 0.0..1.0f64, t in 0.0..1.0f64) {
            let x = Interval::new(a, a + b);
            let y = Interval::new(c, c + d);
            let (u, v) = (a + s * b, c + t * d);
            prop_assert!((x * y).contains(u * v));
            prop_assert!((x + y).contains(u + v));
            prop_assert!((x - y).contains(u - v));
            prop_assert!(x.sqr().contains(u * u));
            prop_assert!(x.powi(3).contains(u * u * u));
            prop_assert!(x.powi(4).contains(u * u * u * u));
            let u7 = (1..7).fold(u, |acc, _| acc * u);
            let slack = 1e-14 * u7.abs();
            let p7 = x.powi(7);
            prop_assert!(p7.lo - slack <= u7 && u7 <= p7.hi + slack);
            prop_assert!(x.powi(8).lo <= (u7 * u).abs() * (1.0 + 1e-14));
        }
    }

    #[test]
    fn square_of_straddling_interval_starts_at_zero() {
        let s = Interval::new(-1.0, 2.0).sqr();
        assert_eq!(s.lo, 0.0);
        assert!(s.hi >= 4.0);
    }
}
