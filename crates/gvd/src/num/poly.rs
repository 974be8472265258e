//! Sparse polynomials in up to three variables `x`, `y`, `z` (power basis), with a parser.
//! STUB: the numerics helper replaces this file.

use crate::num::Interval;

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

impl std::fmt::Display for ParseError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} at position {}", self.message, self.position)
    }
}

impl Poly {
    /// Parses text such as `(x^2+y^2-1)^3 + 27*x^2*y^2`; `vars` lists the allowed
    /// variable names (a subset of `x`, `y`, `z`).
    pub fn parse(_text: &str, _vars: &[char]) -> Result<Poly, ParseError> {
        todo!()
    }
    pub fn eval(&self, _x: f64, _y: f64, _z: f64) -> f64 {
        todo!()
    }
    pub fn eval_interval(&self, _x: Interval, _y: Interval, _z: Interval) -> Interval {
        todo!()
    }
    /// The largest exponent of variable `var` (0 = x, 1 = y, 2 = z).
    pub fn degree_in(&self, _var: usize) -> u32 {
        todo!()
    }
}
