//! Sparse polynomials in up to three variables `x`, `y`, `z` (power basis), with a parser.
//!
//! A [`Poly`] is `Σ c · x^i y^j z^k` with f64 coefficients. The polynomial *is* its f64
//! coefficients: parsing `(x - 0.1)^3` expands with rounding, and every later bound
//! (e.g. [`Poly::eval_interval`], the Bernstein forms) is rigorous for the expanded form.

use crate::num::Interval;
use std::collections::HashMap;
use std::fmt;

/// A sparse polynomial in `x`, `y`, `z`: a sum of `coef · x^i y^j z^k`.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Poly {
    /// `(exponents [i, j, k], coefficient)`, sorted by exponents, no zero coefficients.
    pub terms: Vec<([u32; 3], f64)>,
}

/// Why an equation failed to parse, with the byte position of the problem.
#[derive(Clone, Debug, PartialEq)]
pub struct ParseError {
    pub position: usize,
    pub message: String,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} at position {}", self.message, self.position)
    }
}

impl std::error::Error for ParseError {}

/// Largest exponent accepted after `^`.
pub const MAX_EXPONENT: u32 = 64;
/// Largest number of terms an expansion may reach while parsing.
pub const MAX_TERMS: usize = 100_000;
/// Largest degree in one variable an expansion may reach while parsing.
pub const MAX_DEGREE: u32 = 1024;
/// Largest number of term-by-term products one multiplication may need while parsing.
const MAX_PRODUCT_WORK: usize = 60_000_000;
/// Deepest nesting of parentheses / unary signs accepted by the parser.
const MAX_DEPTH: usize = 200;

const VAR_NAMES: [char; 3] = ['x', 'y', 'z'];
/// The highest degree per variable up to which [`Poly::eval`] and [`Poly::eval_interval`]
/// tabulate the powers of the point once (above it, each term takes its own powers).
const TABULATED: usize = 32;

impl Poly {
    /// The zero polynomial.
    pub fn zero() -> Poly {
        Poly { terms: Vec::new() }
    }

    /// The constant polynomial `c`.
    pub fn constant(c: f64) -> Poly {
        Poly::from_terms(vec![([0, 0, 0], c)])
    }

    /// The variable with index `i` (0 = x, 1 = y, 2 = z).
    pub fn var(i: usize) -> Poly {
        assert!(i < 3, "variable index {i} out of range");
        let mut e = [0; 3];
        e[i] = 1;
        Poly::from_terms(vec![(e, 1.0)])
    }

    /// Normalises arbitrary terms: sorts, merges equal exponents, drops zero coefficients.
    pub fn from_terms(mut terms: Vec<([u32; 3], f64)>) -> Poly {
        terms.sort_unstable_by_key(|a| a.0);
        let mut out: Vec<([u32; 3], f64)> = Vec::with_capacity(terms.len());
        for (e, c) in terms {
            match out.last_mut() {
                Some(last) if last.0 == e => last.1 += c,
                _ => out.push((e, c)),
            }
        }
        out.retain(|t| t.1 != 0.0);
        Poly { terms: out }
    }

    /// Whether every coefficient is zero.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// Parses text such as `(x^2+y^2-1)^3 + 27*x^2*y^2`; `vars` lists the allowed
    /// variable names (a subset of `x`, `y`, `z`; `x` is variable 0, `y` 1, `z` 2).
    ///
    /// Grammar: `+ - * ^`, `/` by a nonzero constant (`1/4*y`; the quotient is rounded
    /// to f64), unary signs, parentheses, decimal numbers (`1.5`, `2e-3`, `.5`),
    /// whitespace anywhere; `^` takes a non-negative integer literal ≤ 64. The
    /// result is expanded; expansions beyond 100 000 terms or degree 1024 in a variable and
    /// non-finite coefficients are errors (the parser never panics and its work is bounded).
    pub fn parse(text: &str, vars: &[char]) -> Result<Poly, ParseError> {
        let mut p = Parser {
            s: text.as_bytes(),
            pos: 0,
            vars,
            depth: 0,
        };
        let poly = p.expr()?;
        p.skip_ws();
        if p.pos < p.s.len() {
            return Err(p.unexpected());
        }
        if poly.terms.iter().any(|t| !t.1.is_finite()) {
            return Err(p.err_at(0, "coefficient overflow (not a finite number)"));
        }
        Ok(poly)
    }

    /// `p(x, y, z)` in f64, summing `c · x^i y^j z^k` term by term (the powers looked up
    /// in a table made once per call, up to degree `TABULATED`).
    pub fn eval(&self, x: f64, y: f64, z: f64) -> f64 {
        match self.power_tables([x, y, z], powu) {
            Some([px, py, pz]) => self
                .terms
                .iter()
                .map(|&(e, c)| c * px[e[0] as usize] * py[e[1] as usize] * pz[e[2] as usize])
                .sum(),
            None => self
                .terms
                .iter()
                .map(|&(e, c)| c * powu(x, e[0]) * powu(y, e[1]) * powu(z, e[2]))
                .sum(),
        }
    }

    /// A rigorous enclosure of `p` over the box `x × y × z` (outward-rounded).
    pub fn eval_interval(&self, x: Interval, y: Interval, z: Interval) -> Interval {
        let tables = self.power_tables([x, y, z], Interval::powi);
        let mut acc = Interval::point(0.0);
        for &(e, c) in &self.terms {
            let m = match &tables {
                Some([px, py, pz]) => px[e[0] as usize] * py[e[1] as usize] * pz[e[2] as usize],
                None => x.powi(e[0]) * y.powi(e[1]) * z.powi(e[2]),
            };
            acc = acc + m * Interval::point(c);
        }
        acc
    }

    /// Per variable, `pow(v, k)` for `k` up to its degree, or `None` when a degree is
    /// above [`TABULATED`].
    fn power_tables<T: Copy + Default>(
        &self,
        at: [T; 3],
        pow: impl Fn(T, u32) -> T,
    ) -> Option<[[T; TABULATED + 1]; 3]> {
        let mut deg = [0u32; 3];
        for (e, _) in &self.terms {
            for (d, &k) in deg.iter_mut().zip(e) {
                *d = (*d).max(k);
            }
        }
        if deg.iter().any(|&d| d as usize > TABULATED) {
            return None;
        }
        let mut tables = [[T::default(); TABULATED + 1]; 3];
        for ((table, &d), &v) in tables.iter_mut().zip(&deg).zip(&at) {
            for (k, slot) in table.iter_mut().enumerate().take(d as usize + 1) {
                *slot = pow(v, k as u32);
            }
        }
        Some(tables)
    }

    /// The largest exponent of variable `var` (0 = x, 1 = y, 2 = z).
    pub fn degree_in(&self, var: usize) -> u32 {
        self.terms.iter().map(|t| t.0[var]).max().unwrap_or(0)
    }

    /// The largest `i + j + k` over the terms (0 for the zero polynomial).
    pub fn total_degree(&self) -> u32 {
        self.terms
            .iter()
            .map(|t| t.0[0] + t.0[1] + t.0[2])
            .max()
            .unwrap_or(0)
    }

    /// `∂p/∂var`.
    pub fn partial(&self, var: usize) -> Poly {
        let terms = self
            .terms
            .iter()
            .filter(|t| t.0[var] > 0)
            .map(|&(mut e, c)| {
                let k = e[var];
                e[var] -= 1;
                (e, c * f64::from(k))
            })
            .collect();
        Poly::from_terms(terms)
    }

    /// The sum.
    pub fn add(&self, o: &Poly) -> Poly {
        self.merge(o, 1.0)
    }

    /// The difference.
    pub fn sub(&self, o: &Poly) -> Poly {
        self.merge(o, -1.0)
    }

    /// The negation.
    pub fn neg(&self) -> Poly {
        self.scale(-1.0)
    }

    /// `k · p`.
    pub fn scale(&self, k: f64) -> Poly {
        Poly::from_terms(self.terms.iter().map(|&(e, c)| (e, c * k)).collect())
    }

    /// `p · q`. Panics only on exponent overflow (beyond `u32`); see [`Poly::parse`] for
    /// the checked version used on untrusted input.
    pub fn mul(&self, o: &Poly) -> Poly {
        self.checked_mul(o, usize::MAX, usize::MAX)
            .expect("exponent overflow in Poly::mul")
    }

    /// `p^n` by repeated squaring.
    pub fn pow(&self, n: u32) -> Poly {
        self.checked_pow(n, usize::MAX, usize::MAX)
            .expect("exponent overflow in Poly::pow")
    }

    /// `self + s · o` merged in one pass over the two sorted term lists.
    fn merge(&self, o: &Poly, s: f64) -> Poly {
        let (a, b) = (&self.terms, &o.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() || j < b.len() {
            let t = if j == b.len() || (i < a.len() && a[i].0 < b[j].0) {
                i += 1;
                a[i - 1]
            } else if i == a.len() || b[j].0 < a[i].0 {
                j += 1;
                (b[j - 1].0, s * b[j - 1].1)
            } else {
                i += 1;
                j += 1;
                (a[i - 1].0, a[i - 1].1 + s * b[j - 1].1)
            };
            if t.1 != 0.0 {
                out.push(t);
            }
        }
        Poly { terms: out }
    }

    /// `p · q`, or `Err(message)` on exponent overflow (beyond [`MAX_DEGREE`] when
    /// `max_terms` is finite), on more than `max_terms` result
    /// terms (estimated before multiplying), or more than `max_work` term products.
    fn checked_mul(&self, o: &Poly, max_terms: usize, max_work: usize) -> Result<Poly, String> {
        let max_degree = if max_terms == usize::MAX {
            u64::from(u32::MAX)
        } else {
            u64::from(MAX_DEGREE)
        };
        let work = self.terms.len().saturating_mul(o.terms.len());
        if work > max_work {
            return Err("expansion too large".into());
        }
        let mut bound = 1usize;
        for v in 0..3 {
            let d = u64::from(self.degree_in(v)) + u64::from(o.degree_in(v));
            if d > max_degree {
                return Err(format!("degree {d} exceeds the maximum {max_degree}"));
            }
            bound = bound.saturating_mul(d as usize + 1);
        }
        if work.min(bound) > max_terms {
            return Err(format!("expansion exceeds {max_terms} terms"));
        }
        let mut acc: HashMap<[u32; 3], f64> = HashMap::with_capacity(work.min(bound));
        for &(ea, ca) in &self.terms {
            for &(eb, cb) in &o.terms {
                let e = [ea[0] + eb[0], ea[1] + eb[1], ea[2] + eb[2]];
                *acc.entry(e).or_insert(0.0) += ca * cb;
            }
        }
        Ok(Poly::from_terms(acc.into_iter().collect()))
    }

    fn checked_pow(&self, mut n: u32, max_terms: usize, max_work: usize) -> Result<Poly, String> {
        let mut result = Poly::constant(1.0);
        let mut base = self.clone();
        loop {
            if n & 1 == 1 {
                result = result.checked_mul(&base, max_terms, max_work)?;
            }
            n >>= 1;
            if n == 0 {
                return Ok(result);
            }
            base = base.checked_mul(&base, max_terms, max_work)?;
        }
    }
}

/// `x^n` by repeated squaring.
#[inline]
fn powu(x: f64, n: u32) -> f64 {
    match n {
        0 => 1.0,
        1 => x,
        2 => x * x,
        _ => x.powi(n as i32),
    }
}

impl fmt::Display for Poly {
    /// A parseable form such as `2*x^2*y - 0.5*z + 1` (highest exponents first); f64
    /// coefficients are written so that they parse back to the same value.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.terms.is_empty() {
            return write!(f, "0");
        }
        for (n, &(e, c)) in self.terms.iter().rev().enumerate() {
            let a = c.abs();
            match (n, c < 0.0) {
                (0, true) => write!(f, "-")?,
                (0, false) => {}
                (_, true) => write!(f, " - ")?,
                (_, false) => write!(f, " + ")?,
            }
            let mut first = true;
            if a != 1.0 || e == [0, 0, 0] {
                if a != 0.0 && !(1e-5..1e16).contains(&a) {
                    write!(f, "{a:e}")?;
                } else {
                    write!(f, "{a}")?;
                }
                first = false;
            }
            for (v, &k) in e.iter().enumerate() {
                if k == 0 {
                    continue;
                }
                if !first {
                    write!(f, "*")?;
                }
                first = false;
                write!(f, "{}", VAR_NAMES[v])?;
                if k > 1 {
                    write!(f, "^{k}")?;
                }
            }
        }
        Ok(())
    }
}

/// Recursive-descent parser: `expr := term (± term)*`, `term := unary ((*|/) unary)*`,
/// `unary := ± unary | power`, `power := primary (^ integer)?`,
/// `primary := number | variable | ( expr )`.
struct Parser<'a> {
    s: &'a [u8],
    pos: usize,
    vars: &'a [char],
    depth: usize,
}

impl Parser<'_> {
    fn err_at(&self, position: usize, message: impl Into<String>) -> ParseError {
        ParseError {
            position,
            message: message.into(),
        }
    }

    fn unexpected(&self) -> ParseError {
        match self.s.get(self.pos) {
            None => self.err_at(self.pos, "unexpected end of input"),
            Some(&b) => {
                let ch = String::from_utf8_lossy(&self.s[self.pos..])
                    .chars()
                    .next()
                    .unwrap_or(b as char);
                self.err_at(self.pos, format!("unexpected '{ch}'"))
            }
        }
    }

    fn skip_ws(&mut self) {
        while self.pos < self.s.len() && self.s[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.s.get(self.pos).copied()
    }

    fn op(&self, at: usize, r: Result<Poly, String>) -> Result<Poly, ParseError> {
        r.map_err(|m| self.err_at(at, m))
    }

    fn expr(&mut self) -> Result<Poly, ParseError> {
        let mut acc = self.term()?;
        while let Some(c @ (b'+' | b'-')) = self.peek() {
            self.pos += 1;
            let rhs = self.term()?;
            acc = if c == b'+' {
                acc.add(&rhs)
            } else {
                acc.sub(&rhs)
            };
        }
        Ok(acc)
    }

    fn term(&mut self) -> Result<Poly, ParseError> {
        let mut acc = self.unary()?;
        while let Some(c @ (b'*' | b'/')) = self.peek() {
            let at = self.pos;
            self.pos += 1;
            let rhs = self.unary()?;
            acc = if c == b'*' {
                self.op(at, acc.checked_mul(&rhs, MAX_TERMS, MAX_PRODUCT_WORK))?
            } else {
                match rhs.terms.as_slice() {
                    [([0, 0, 0], d)] => acc.scale(1.0 / d),
                    [] => return Err(self.err_at(at, "division by zero")),
                    _ => return Err(self.err_at(at, "division only by a constant")),
                }
            };
        }
        Ok(acc)
    }

    fn unary(&mut self) -> Result<Poly, ParseError> {
        match self.peek() {
            Some(c @ (b'+' | b'-')) => {
                self.pos += 1;
                self.enter()?;
                let p = self.unary()?;
                self.depth -= 1;
                Ok(if c == b'-' { p.neg() } else { p })
            }
            _ => self.power(),
        }
    }

    fn enter(&mut self) -> Result<(), ParseError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            Err(self.err_at(self.pos, "expression nested too deeply"))
        } else {
            Ok(())
        }
    }

    fn power(&mut self) -> Result<Poly, ParseError> {
        let base = self.primary()?;
        if self.peek() != Some(b'^') {
            return Ok(base);
        }
        let at = self.pos;
        self.pos += 1;
        self.skip_ws();
        let start = self.pos;
        while self.pos < self.s.len() && self.s[self.pos].is_ascii_digit() {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.err_at(start, "expected a non-negative integer exponent"));
        }
        if matches!(self.s.get(self.pos), Some(b'.' | b'e' | b'E')) {
            return Err(self.err_at(start, "exponent must be a non-negative integer"));
        }
        let digits = std::str::from_utf8(&self.s[start..self.pos]).unwrap_or("");
        let n = match digits.parse::<u32>() {
            Ok(n) if n <= MAX_EXPONENT => n,
            _ => {
                return Err(self.err_at(
                    start,
                    format!(
                        "exponent {} exceeds the maximum {MAX_EXPONENT}",
                        excerpt(digits)
                    ),
                ))
            }
        };
        if self.peek() == Some(b'^') {
            return Err(self.err_at(self.pos, "chained '^' is ambiguous: use parentheses"));
        }
        self.op(at, base.checked_pow(n, MAX_TERMS, MAX_PRODUCT_WORK))
    }

    fn primary(&mut self) -> Result<Poly, ParseError> {
        let Some(c) = self.peek() else {
            return Err(self.unexpected());
        };
        let start = self.pos;
        if c == b'(' {
            self.pos += 1;
            self.enter()?;
            let p = self.expr()?;
            self.depth -= 1;
            if self.peek() != Some(b')') {
                return Err(match self.s.get(self.pos) {
                    None => self.err_at(start, "unclosed '('"),
                    Some(_) => self.unexpected(),
                });
            }
            self.pos += 1;
            Ok(p)
        } else if c.is_ascii_digit() || c == b'.' {
            self.number()
        } else if c.is_ascii_alphabetic() || c == b'_' {
            while self.pos < self.s.len()
                && (self.s[self.pos].is_ascii_alphanumeric() || self.s[self.pos] == b'_')
            {
                self.pos += 1;
            }
            let name = std::str::from_utf8(&self.s[start..self.pos]).unwrap_or("?");
            let mut chars = name.chars();
            if let (Some(ch), None) = (chars.next(), chars.next()) {
                if let Some(i) = VAR_NAMES.iter().position(|&v| v == ch) {
                    if self.vars.contains(&ch) {
                        return Ok(Poly::var(i));
                    }
                }
            }
            let allowed: String = self.vars.iter().map(|c| format!("'{c}' ")).collect();
            Err(self.err_at(
                start,
                format!(
                    "unknown variable '{name}' (allowed: {})",
                    allowed.trim_end()
                ),
            ))
        } else {
            Err(self.unexpected())
        }
    }

    fn number(&mut self) -> Result<Poly, ParseError> {
        let start = self.pos;
        let digits = |p: &mut Self| {
            let s = p.pos;
            while p.pos < p.s.len() && p.s[p.pos].is_ascii_digit() {
                p.pos += 1;
            }
            p.pos - s
        };
        let mut n = digits(self);
        if self.s.get(self.pos) == Some(&b'.') {
            self.pos += 1;
            n += digits(self);
        }
        if n == 0 {
            return Err(self.err_at(start, "malformed number"));
        }
        if matches!(self.s.get(self.pos), Some(b'e' | b'E')) {
            self.pos += 1;
            if matches!(self.s.get(self.pos), Some(b'+' | b'-')) {
                self.pos += 1;
            }
            if digits(self) == 0 {
                return Err(self.err_at(start, "malformed number exponent"));
            }
        }
        let text = std::str::from_utf8(&self.s[start..self.pos]).unwrap_or("");
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Poly::constant(v)),
            _ => Err(self.err_at(start, format!("number '{}' is out of range", excerpt(text)))),
        }
    }
}

/// At most 40 bytes of a run of ASCII digits and signs, for messages (`…` marks a cut).
fn excerpt(text: &str) -> String {
    match text.get(..40) {
        Some(head) if head.len() < text.len() => format!("{head}… ({} characters)", text.len()),
        _ => text.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const XY: &[char] = &['x', 'y'];
    const XYZ: &[char] = &['x', 'y', 'z'];

    #[test]
    fn parses_and_evaluates_the_brief_examples() {
        let p = Poly::parse("(x^2+y^2-1)^3 + 27*x^2*y^2", XY).unwrap();
        let f = |x: f64, y: f64| (x * x + y * y - 1.0).powi(3) + 27.0 * x * x * y * y;
        for &(x, y) in &[(0.3, -0.7), (1.5, 2.0), (-0.2, 0.1)] {
            assert!((p.eval(x, y, 0.0) - f(x, y)).abs() < 1e-12 * (1.0 + f(x, y).abs()));
        }
        assert_eq!(p.degree_in(0), 6);
        assert_eq!(p.total_degree(), 6);

        let q = Poly::parse("(x - 1.5)^4 + (y + 0.25)^4", XY).unwrap();
        let g = |x: f64, y: f64| (x - 1.5f64).powi(4) + (y + 0.25f64).powi(4);
        assert!((q.eval(0.5, -1.0, 0.0) - g(0.5, -1.0)).abs() < 1e-12);

        let r = Poly::parse(" (x-1)^2 + y^2 - (z+0.5)^2 ", XYZ).unwrap();
        let h = |x: f64, y: f64, z: f64| (x - 1.0).powi(2) + y * y - (z + 0.5).powi(2);
        assert!((r.eval(0.25, 2.0, -3.0) - h(0.25, 2.0, -3.0)).abs() < 1e-12);

        let q = Poly::parse("1/4*y + (x - 1/2)^2 - 1/4", XY).unwrap();
        assert_eq!(q, Poly::parse("0.25*y + (x - 0.5)^2 - 0.25", XY).unwrap());
        assert_eq!(
            Poly::parse("x/2/2", XY).unwrap(),
            Poly::parse("0.25*x", XY).unwrap()
        );

        let n = Poly::parse("-2e-3*x + .5 - -x*3", XY).unwrap();
        assert!((n.eval(2.0, 0.0, 0.0) - (-4e-3 + 0.5 + 6.0)).abs() < 1e-15);
    }

    #[test]
    fn rejects_malformed_input() {
        let e = Poly::parse("x^", XY).unwrap_err();
        assert_eq!(e.position, 2);
        assert!(Poly::parse("x**2", XY).is_err());
        let e = Poly::parse("x + q", XY).unwrap_err();
        assert!(e.message.contains("'q'"), "{e}");
        assert_eq!(e.position, 4);
        let e = Poly::parse("x + z", XY).unwrap_err();
        assert!(e.message.contains("'z'"), "{e}");
        let e = Poly::parse("2^100", XY).unwrap_err();
        assert!(e.message.contains("exponent"), "{e}");
        for bad in [
            "",
            "(x",
            "x)",
            "2x",
            "x/y",
            "1/0",
            "x/(y-y)",
            "1/(1e-320*1e-10)",
            "x^2.5",
            "x^-1",
            "x^2^2",
            "1e",
            "1e999",
            "+",
            "xy",
            "x $ y",
        ] {
            assert!(Poly::parse(bad, XY).is_err(), "accepted {bad:?}");
        }
    }

    #[test]
    fn refuses_huge_expansions_quickly() {
        let t = std::time::Instant::now();
        let e = Poly::parse("(x+y+z+1)^64*(x+y+z+2)^64", XYZ).unwrap_err();
        assert!(e.message.contains("expansion"), "{e}");
        assert!(Poly::parse("((((x^64)^64)^64)^64)^64", XY).is_err());
        assert!(Poly::parse(&"(".repeat(100_000), XY).is_err());
        assert!(Poly::parse(&"-".repeat(100_000), XY).is_err());
        assert!(Poly::parse("10^64^1", XY).is_err());
        assert!(Poly::parse("(1e300*x)^2", XY).is_err());
        assert!(t.elapsed().as_secs_f64() < 5.0);
        // big but allowed
        let p = Poly::parse("(x+y+z+1)^20", XYZ).unwrap();
        assert_eq!(p.terms.len(), 1771);
    }

    #[test]
    fn algebra_and_derivatives() {
        let x = Poly::var(0);
        let y = Poly::var(1);
        let p = x
            .mul(&x)
            .mul(&y)
            .scale(3.0)
            .add(&y.pow(3))
            .sub(&Poly::constant(2.0));
        assert_eq!(p.to_string(), "3*x^2*y + y^3 - 2");
        assert_eq!(p.partial(0).to_string(), "6*x*y");
        assert_eq!(p.partial(1).to_string(), "3*x^2 + 3*y^2");
        assert!(p.sub(&p).is_zero());
        assert_eq!(p.neg().add(&p), Poly::zero());
        assert_eq!(Poly::zero().to_string(), "0");
    }

    fn poly_strategy(nvars: usize, max_deg: u32) -> impl Strategy<Value = Poly> {
        proptest::collection::vec(
            (0..=max_deg, 0..=max_deg, 0..=max_deg, -10.0..10.0f64),
            1..12,
        )
        .prop_map(move |ts| {
            Poly::from_terms(
                ts.into_iter()
                    .map(|(i, j, k, c)| {
                        let e = [
                            i,
                            if nvars > 1 { j } else { 0 },
                            if nvars > 2 { k } else { 0 },
                        ];
                        (e, c)
                    })
                    .collect(),
            )
        })
    }

    proptest! {
        #[test]
        fn display_round_trips(p in poly_strategy(3, 8), tiny in 1e-300..1e-20f64, big in 1e17..1e30f64) {
            let p = p.add(&Poly::var(2).scale(tiny)).add(&Poly::constant(big));
            let q = Poly::parse(&p.to_string(), XYZ).unwrap();
            prop_assert_eq!(p, q);
        }

        #[test]
        fn interval_eval_encloses_points(p in poly_strategy(3, 6), x in -3.0..3.0f64, y in -3.0..3.0f64, z in -3.0..3.0f64, w in 0.0..0.5f64, s in 0.0..1.0f64) {
            let b = |c: f64| Interval::new(c, c + w);
            let r = p.eval_interval(b(x), b(y), b(z));
            let pt = |c: f64| Interval::point(c + s * w);
            let v = p.eval_interval(pt(x), pt(y), pt(z));
            prop_assert!(r.lo <= v.hi && v.lo <= r.hi);
            // f64 eval sits within rounding of the enclosure
            let e = p.eval(x + s * w, y + s * w, z + s * w);
            let slack = 1e-12 * (1.0 + r.mag());
            prop_assert!(r.lo - slack <= e && e <= r.hi + slack);
        }

        #[test]
        fn mul_and_sub_match_eval(p in poly_strategy(3, 4), q in poly_strategy(3, 4), x in -2.0..2.0f64, y in -2.0..2.0f64, z in -2.0..2.0f64) {
            let (a, b) = (p.eval(x, y, z), q.eval(x, y, z));
            let tol = 1e-9 * (1.0 + a.abs() + b.abs()).powi(2);
            prop_assert!((p.mul(&q).eval(x, y, z) - a * b).abs() < tol);
            prop_assert!((p.sub(&q).eval(x, y, z) - (a - b)).abs() < tol);
            prop_assert!((p.add(&q).eval(x, y, z) - (a + b)).abs() < tol);
        }

        #[test]
        fn partial_matches_finite_difference(p in poly_strategy(3, 5), x in -1.5..1.5f64, y in -1.5..1.5f64, z in -1.5..1.5f64, v in 0usize..3) {
            let h = 1e-6;
            let mut a = [x, y, z];
            let mut b = a;
            a[v] -= h;
            b[v] += h;
            let fd = (p.eval(b[0], b[1], b[2]) - p.eval(a[0], a[1], a[2])) / (2.0 * h);
            let d = p.partial(v).eval(x, y, z);
            let scale: f64 = p.terms.iter().map(|t| t.1.abs()).sum::<f64>() * 1.5f64.powi(15);
            prop_assert!((fd - d).abs() <= 1e-5 * scale, "{} vs {}", fd, d);
        }
    }
}
