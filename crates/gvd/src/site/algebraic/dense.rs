//! A bivariate polynomial as a dense coefficient table, for fast f64 evaluation of the
//! curve's polynomial and its derivatives (nested Horner), with a magnitude bound for
//! rounding-level tests.

use crate::num::poly::Poly;

/// `Σ c_ij xⁱ yʲ` with `c_ij` at `i·(dy + 1) + j`.
#[derive(Clone, Debug)]
pub(super) struct Dense {
    dx: usize,
    dy: usize,
    coef: Vec<f64>,
    abs: Vec<f64>,
}

impl Dense {
    /// The terms of `p` in `x` and `y` (terms in `z` are dropped).
    pub(super) fn new(p: &Poly) -> Self {
        let (dx, dy) = (p.degree_in(0) as usize, p.degree_in(1) as usize);
        let mut coef = vec![0.0; (dx + 1) * (dy + 1)];
        for &(e, c) in p.terms.iter().filter(|t| t.0[2] == 0) {
            coef[e[0] as usize * (dy + 1) + e[1] as usize] += c;
        }
        let abs = coef.iter().map(|c| c.abs()).collect();
        Dense { dx, dy, coef, abs }
    }

    fn horner(&self, coef: &[f64], x: f64, y: f64) -> f64 {
        let mut acc = 0.0;
        for i in (0..=self.dx).rev() {
            let row = &coef[i * (self.dy + 1)..(i + 1) * (self.dy + 1)];
            let r = row.iter().rev().fold(0.0, |a, &c| a * y + c);
            acc = acc * x + r;
        }
        acc
    }

    pub(super) fn eval(&self, x: f64, y: f64) -> f64 {
        self.horner(&self.coef, x, y)
    }

    /// `Σ |c_ij| |x|ⁱ |y|ʲ`: the scale of the rounding errors of [`Dense::eval`].
    pub(super) fn magnitude(&self, x: f64, y: f64) -> f64 {
        self.horner(&self.abs, x.abs(), y.abs())
    }
}

/// The curve's polynomial with its first and second partial derivatives.
#[derive(Clone, Debug)]
pub(super) struct Jet {
    pub f: Dense,
    pub fx: Dense,
    pub fy: Dense,
    pub fxx: Dense,
    pub fxy: Dense,
    pub fyy: Dense,
}

impl Jet {
    pub(super) fn new(p: &Poly) -> Self {
        let (px, py) = (p.partial(0), p.partial(1));
        Jet {
            f: Dense::new(p),
            fxx: Dense::new(&px.partial(0)),
            fxy: Dense::new(&px.partial(1)),
            fyy: Dense::new(&py.partial(1)),
            fx: Dense::new(&px),
            fy: Dense::new(&py),
        }
    }
}
