//! Bernstein forms over boxes. STUB: the numerics helper replaces this file.

use crate::geom::{Aabb, Axis};
use crate::num::poly::Poly;
use crate::num::Interval;

/// A bivariate polynomial in tensor Bernstein form over a box.
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein2 {
    pub deg: [usize; 2],
    pub coef: Vec<f64>,
    pub err: f64,
}

impl Bernstein2 {
    pub fn from_poly(_p: &Poly, _b: &Aabb) -> Self {
        todo!()
    }
    pub fn split(&self, _axis: Axis, _t: f64) -> (Self, Self) {
        todo!()
    }
    pub fn range(&self) -> Interval {
        todo!()
    }
    pub fn eval(&self, _u: f64, _v: f64) -> f64 {
        todo!()
    }
}
