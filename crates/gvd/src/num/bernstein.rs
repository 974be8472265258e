//! Bernstein forms in 1, 2 and 3 variables over boxes, with certified error bounds.
//!
//! A form of degree `(n₀, n₁, n₂)` stands for
//! `f(u, v, w) = Σ b_ijk · B_i^{n₀}(u) B_j^{n₁}(v) B_k^{n₂}(w)`, `B_i^n(u) = C(n,i) uⁱ(1−u)ⁿ⁻ⁱ`,
//! in relative coordinates `(u, v, w) ∈ [0,1]³` of the box it was made for.
//!
//! **Error model.** Each form carries `err ≥ 0` with the invariant: the exact Bernstein
//! coefficients `β` of the exact polynomial (at this degree, over this box) satisfy
//! `|β_ijk − b_ijk| ≤ err` for every index. Since the basis is non-negative and sums to
//! one, `min b − err ≤ f ≤ max b + err` on the box ([`Bernstein2::range`]). Every
//! operation (conversion, de Casteljau, elevation, difference, product, derivative)
//! grows `err` by a bound of its own f64 rounding, so the invariant survives any chain
//! of operations. Evaluation ([`Bernstein2::eval`]) is plain f64 and not certified.
//!
//! Split parameters must lie in `[0, 1]`; the children stand for the exact sub-boxes
//! `[0, t]` and `[t, 1]` of the parent's relative coordinate at the f64 value `t`.

use crate::geom::{Aabb, Axis};
use crate::num::interval::{round_down, round_up};
use crate::num::poly::Poly;
use crate::num::Interval;

const EPS: f64 = f64::EPSILON;
/// Absolute slack per operation covering underflow to subnormals.
const TINY: f64 = f64::MIN_POSITIVE;

/// A univariate polynomial in Bernstein form over `[0, 1]` (a relative parameter).
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein1 {
    /// `b_0 … b_n`; the degree is `coef.len() − 1`.
    pub coef: Vec<f64>,
    /// Coefficient-wise error bound (see the module docs).
    pub err: f64,
}

/// A bivariate polynomial in tensor Bernstein form over a box; coefficient `(i, j)` is at
/// `i·(deg[1]+1) + j` (`i` along x / `u`, `j` along y / `v`).
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein2 {
    /// The degrees in x and y.
    pub deg: [usize; 2],
    /// The coefficients, x-major.
    pub coef: Vec<f64>,
    /// A bound on the rounding error of every coefficient.
    pub err: f64,
}

/// A trivariate polynomial in tensor Bernstein form over box × z-interval; coefficient
/// `(i, j, k)` is at `(i·(deg[1]+1) + j)·(deg[2]+1) + k`.
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein3 {
    /// The degrees in x, y and z.
    pub deg: [usize; 3],
    /// The coefficients, x-major.
    pub coef: Vec<f64>,
    /// A bound on the rounding error of every coefficient.
    pub err: f64,
}

// ---------------------------------------------------------------------------------------
// Shared tensor core: every form is handled as a 3-D tensor (unused axes have degree 0).

struct Form {
    deg: [usize; 3],
    coef: Vec<f64>,
    err: f64,
}

#[derive(Clone, Copy)]
struct View<'a> {
    deg: [usize; 3],
    coef: &'a [f64],
    err: f64,
}

/// `(outer, n, inner)`: the coefficient of index `i` along `axis` in line `(o, q)` is at
/// `(o·(n+1) + i)·inner + q`.
#[inline]
fn layout(deg: [usize; 3], axis: usize) -> (usize, usize, usize) {
    let outer = deg[..axis].iter().map(|d| d + 1).product();
    let inner = deg[axis + 1..].iter().map(|d| d + 1).product();
    (outer, deg[axis], inner)
}

#[inline]
fn len_of(deg: [usize; 3]) -> usize {
    (deg[0] + 1) * (deg[1] + 1) * (deg[2] + 1)
}

/// The largest `|c_i|` (NaNs skipped), four lanes at a time.
#[inline]
fn max_abs(c: &[f64]) -> f64 {
    let mut lanes = [0.0f64; 4];
    let mut chunks = c.chunks_exact(4);
    for ch in &mut chunks {
        for (m, &x) in lanes.iter_mut().zip(ch) {
            // a NaN compares false and is skipped, as by `f64::max`
            if x.abs() > *m {
                *m = x.abs();
            }
        }
    }
    for &x in chunks.remainder() {
        if x.abs() > lanes[0] {
            lanes[0] = x.abs();
        }
    }
    lanes.into_iter().fold(0.0, f64::max)
}

/// `err` grown by `k` unit roundoffs of magnitude `m + err`, plus an underflow slack.
#[inline]
fn grown(err: f64, m: f64, k: f64) -> f64 {
    round_up(err + k * EPS * (m + err) + TINY)
}

/// Pascal's row `C(n, 0..=n)` in f64 (exact while the values stay below 2⁵³; otherwise
/// each entry carries a relative error below `n` unit roundoffs).
fn binomials(n: usize) -> Vec<f64> {
    let mut row = vec![1.0; n + 1];
    for r in 1..n {
        for k in (1..=r).rev() {
            row[k] += row[k - 1];
        }
    }
    row
}

/// For `i ≤ d`: the Bernstein coefficients of degree `d` over `[a, b]` of `x^i` (row `i`
/// of the first table) and the sums of the absolute values of their summands (second).
fn monomial_table(d: usize, a: f64, b: f64) -> (Vec<f64>, Vec<f64>) {
    let n = d + 1;
    let pow = |x: f64| {
        let mut v = vec![1.0; n];
        for k in 1..n {
            v[k] = v[k - 1] * x;
        }
        v
    };
    let (pa, pb) = (pow(a), pow(b));
    let rows: Vec<Vec<f64>> = (0..=d).map(binomials).collect();
    let choose = |r: usize, k: usize| if k > r { 0.0 } else { rows[r][k] };
    let mut value = vec![0.0; n * n];
    let mut magnitude = vec![0.0; n * n];
    for i in 0..n {
        for k in 0..n {
            let (mut v, mut m) = (0.0, 0.0);
            for t in 0..=i.min(k) {
                if i - t > d - k {
                    continue;
                }
                let w = choose(k, t) * choose(d - k, i - t) * pa[i - t] * pb[t];
                v += w;
                m += w.abs();
            }
            let c = choose(d, i);
            value[i * n + k] = v / c;
            magnitude[i * n + k] = m / c;
        }
    }
    (value, magnitude)
}

/// `min b − err`, `max b + err`, outward-rounded; the whole line if anything is NaN/∞.
fn range_of(coef: &[f64], err: f64) -> Interval {
    let (lo, hi, nan) = min_max(coef.iter().copied());
    interval_of(lo, hi, nan, err)
}

/// The smallest and largest of `values` (`∞`, `−∞` when empty), and whether one is NaN.
#[inline]
fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64, bool) {
    let (mut lo, mut hi, mut nan) = (f64::INFINITY, f64::NEG_INFINITY, false);
    for c in values {
        if c < lo {
            lo = c;
        }
        if c > hi {
            hi = c;
        }
        nan |= c.is_nan();
    }
    (lo, hi, nan)
}

/// `[lo − err, hi + err]`, outward-rounded; the whole line if `nan` or not finite.
#[inline]
fn interval_of(lo: f64, hi: f64, nan: bool, err: f64) -> Interval {
    let r = Interval::new(lo, hi) + Interval::new(-err, err);
    if nan || !(r.lo.is_finite() && r.hi.is_finite()) {
        Interval::new(f64::NEG_INFINITY, f64::INFINITY)
    } else {
        r
    }
}

/// de Casteljau value of a 1-D coefficient slice at `t` (may overwrite the slice). Up to
/// degree 11 through fixed-size copies the compiler unrolls (the same operations).
#[inline]
fn casteljau_value(c: &mut [f64], t: f64) -> f64 {
    macro_rules! fixed {
        ($($n:literal)*) => {
            match c.len() {
                $($n => casteljau_fixed::<$n>(c.try_into().expect("length checked"), t),)*
                _ => casteljau_slice(c, t),
            }
        };
    }
    fixed!(2 3 4 5 6 7 8 9 10 11 12)
}

#[inline]
fn casteljau_slice(c: &mut [f64], t: f64) -> f64 {
    let n = c.len();
    for r in 1..n {
        for i in 0..n - r {
            c[i] += t * (c[i + 1] - c[i]);
        }
    }
    c[0]
}

#[inline]
fn casteljau_fixed<const N: usize>(mut c: [f64; N], t: f64) -> f64 {
    for r in 1..N {
        for i in 0..N - r {
            c[i] += t * (c[i + 1] - c[i]);
        }
    }
    c[0]
}

/// de Casteljau at `t` on consecutive lines of `len` coefficients: `right` (holding the
/// coefficients) becomes the upper parts, `left` (a copy) the lower ones. Up to 12
/// coefficients through fixed-size copies the compiler unrolls (the same operations).
#[inline]
fn split_lines(left: &mut [f64], right: &mut [f64], len: usize, t: f64) {
    macro_rules! fixed {
        ($($n:literal)*) => {
            match len {
                $($n => split_lines_fixed::<$n>(left, right, t),)*
                _ => {
                    for (l, r) in left.chunks_exact_mut(len).zip(right.chunks_exact_mut(len)) {
                        for k in 1..len {
                            for i in 0..len - k {
                                r[i] += t * (r[i + 1] - r[i]);
                            }
                            l[k] = r[0];
                        }
                    }
                }
            }
        };
    }
    fixed!(2 3 4 5 6 7 8 9 10 11 12)
}

#[inline]
fn split_lines_fixed<const N: usize>(left: &mut [f64], right: &mut [f64], t: f64) {
    for (l, r) in left.chunks_exact_mut(N).zip(right.chunks_exact_mut(N)) {
        let mut c: [f64; N] = (&*r).try_into().expect("chunk of N");
        for (k, lower) in l.iter_mut().enumerate().skip(1) {
            for i in 0..N - k {
                c[i] += t * (c[i + 1] - c[i]);
            }
            *lower = c[0];
        }
        r.copy_from_slice(&c);
    }
}

impl View<'_> {
    fn range(self) -> Interval {
        range_of(self.coef, self.err)
    }

    fn eval(self, p: [f64; 3]) -> f64 {
        let mut buf = self.coef.to_vec();
        let mut len = buf.len();
        for axis in (0..3).rev() {
            let n1 = self.deg[axis] + 1;
            let rows = len / n1;
            for r in 0..rows {
                let v = casteljau_value(&mut buf[r * n1..(r + 1) * n1], p[axis]);
                buf[r] = v;
            }
            len = rows;
        }
        buf[0]
    }

    /// de Casteljau subdivision along `axis` at `t ∈ [0, 1]`: `(lower, upper)`.
    ///
    /// Each level is a convex combination `a + t(b − a)` (rounding ≤ 2.5 ε·max|b| per
    /// level), so `err` grows by `4·n·ε·(max|b| + err)`.
    fn split(self, axis: usize, t: f64) -> (Form, Form) {
        debug_assert!(
            (0.0..=1.0).contains(&t),
            "split parameter {t} outside [0, 1]"
        );
        let (outer, n, inner) = layout(self.deg, axis);
        let mut right = self.coef.to_vec();
        let mut left = right.clone();
        if n > 0 && inner == 1 {
            split_lines(&mut left, &mut right, n + 1, t);
        } else if n > 0 {
            for o in 0..outer {
                let base = o * (n + 1) * inner;
                let line = &mut right[base..base + (n + 1) * inner];
                for r in 1..=n {
                    // rows of `inner` coefficients, combined element by element
                    for i in 0..=n - r {
                        let (a, b) = line.split_at_mut((i + 1) * inner);
                        for (x, &y) in a[i * inner..].iter_mut().zip(&b[..inner]) {
                            *x += t * (y - *x);
                        }
                    }
                    left[base + r * inner..base + (r + 1) * inner].copy_from_slice(&line[..inner]);
                }
            }
        }
        let err = if n > 0 {
            grown(self.err, max_abs(self.coef), 4.0 * n as f64)
        } else {
            self.err
        };
        let form = |coef| Form {
            deg: self.deg,
            coef,
            err,
        };
        (form(left), form(right))
    }

    /// `∂f/∂(relative coordinate of axis)`: coefficients `n·(b_{i+1} − b_i)`, degree
    /// `n − 1` (the zero form of degree 0 when `n = 0`).
    fn derivative(self, axis: usize) -> Form {
        let (outer, n, inner) = layout(self.deg, axis);
        let mut deg = self.deg;
        if n == 0 {
            return Form {
                deg,
                coef: vec![0.0; self.coef.len()],
                err: 0.0,
            };
        }
        deg[axis] = n - 1;
        let nf = n as f64;
        let mut coef = Vec::with_capacity(outer * n * inner);
        for o in 0..outer {
            let base = o * (n + 1) * inner;
            for i in 0..n {
                let (a, b) = (base + i * inner, base + (i + 1) * inner);
                for q in 0..inner {
                    coef.push(nf * (self.coef[b + q] - self.coef[a + q]));
                }
            }
        }
        // exact differences are within 2·err; rounding of n·fl(b − a) is ≤ 2.01·u·n·2M
        let m = max_abs(self.coef);
        let err = round_up(2.0 * nf * self.err + 3.0 * nf * EPS * (m + self.err) + TINY);
        Form { deg, coef, err }
    }

    /// `self.derivative(axis).range()` without forming the derivative.
    fn derivative_range(self, axis: usize) -> Interval {
        let (_, n, _) = layout(self.deg, axis);
        if n == 0 {
            return self.derivative(axis).view().range();
        }
        self.derivative_hull(axis).range()
    }

    /// The least and largest coefficient of `self.derivative(axis)` and its error bound,
    /// without forming it (degree `n ≥ 1` along `axis`).
    fn derivative_hull(self, axis: usize) -> CoefficientHull {
        let (outer, n, inner) = layout(self.deg, axis);
        let nf = n as f64;
        let stride = (n + 1) * inner;
        let (mut lo, mut hi, mut nan) = (f64::INFINITY, f64::NEG_INFINITY, false);
        for line in self.coef.chunks_exact(stride).take(outer) {
            let (l, h, x) = min_max(line.iter().zip(&line[inner..]).map(|(&a, &b)| nf * (b - a)));
            lo = if l < lo { l } else { lo };
            hi = if h > hi { h } else { hi };
            nan |= x;
        }
        let m = max_abs(self.coef);
        let err = round_up(2.0 * nf * self.err + 3.0 * nf * EPS * (m + self.err) + TINY);
        CoefficientHull { lo, hi, nan, err }
    }

    /// Degree elevation to `to ≥ deg` (per axis):
    /// `b'_k = Σ_j C(n,j) C(r,k−j) / C(n+r,k) · b_j`, axis by axis.
    fn elevate(self, to: [usize; 3]) -> Form {
        let mut form = Form {
            deg: self.deg,
            coef: self.coef.to_vec(),
            err: self.err,
        };
        for (axis, &target) in to.iter().enumerate() {
            assert!(
                target >= form.deg[axis],
                "cannot lower a degree by elevation"
            );
            if target > form.deg[axis] {
                form = form.view().elevate_axis(axis, target);
            }
        }
        form
    }

    fn elevate_axis(self, axis: usize, target: usize) -> Form {
        let (outer, n, inner) = layout(self.deg, axis);
        let r = target - n;
        let (cn, cr, ct) = (binomials(n), binomials(r), binomials(target));
        let mut deg = self.deg;
        deg[axis] = target;
        let mut coef = vec![0.0; outer * (target + 1) * inner];
        for k in 0..=target {
            for j in k.saturating_sub(r)..=k.min(n) {
                let w = cn[j] * cr[k - j] / ct[k];
                for o in 0..outer {
                    let src = (o * (n + 1) + j) * inner;
                    let dst = (o * (target + 1) + k) * inner;
                    for q in 0..inner {
                        coef[dst + q] += w * self.coef[src + q];
                    }
                }
            }
        }
        // weights: relative error ≤ (2·target + 3)u; sums of ≤ n+1 terms
        let k = (3 * target + 6) as f64;
        let err = grown(self.err, max_abs(self.coef), k);
        Form { deg, coef, err }
    }

    /// `self ± o` after elevating both to the common degree.
    fn add(self, o: View, sign: f64) -> Form {
        let to = [0, 1, 2].map(|a| self.deg[a].max(o.deg[a]));
        let a = self.elevate(to);
        let b = o.elevate(to);
        let coef: Vec<f64> = a
            .coef
            .iter()
            .zip(&b.coef)
            .map(|(x, y)| x + sign * y)
            .collect();
        let m = max_abs(&a.coef) + max_abs(&b.coef);
        let err = round_up(a.err + b.err + EPS * m + TINY);
        Form { deg: to, coef, err }
    }

    /// The product: `γ_K = Σ_{I+J=K} Π_axis C(m,i)C(n,j)/C(m+n,k) · a_I b_J`.
    fn mul(self, o: View) -> Form {
        let (da, db) = (self.deg, o.deg);
        let deg = [0, 1, 2].map(|a| da[a] + db[a]);
        let scaled = |v: View| {
            let c = v.deg.map(binomials);
            let mut out = v.coef.to_vec();
            let mut idx = 0;
            for i in 0..=v.deg[0] {
                for j in 0..=v.deg[1] {
                    for k in 0..=v.deg[2] {
                        out[idx] *= c[0][i] * c[1][j] * c[2][k];
                        idx += 1;
                    }
                }
            }
            out
        };
        let (sa, sb) = (scaled(self), scaled(o));
        let mut coef = vec![0.0; len_of(deg)];
        let (ny, nz) = (deg[1] + 1, deg[2] + 1);
        let mut ia = 0;
        for i0 in 0..=da[0] {
            for i1 in 0..=da[1] {
                for i2 in 0..=da[2] {
                    let x = sa[ia];
                    ia += 1;
                    let mut ib = 0;
                    for j0 in 0..=db[0] {
                        for j1 in 0..=db[1] {
                            let row = ((i0 + j0) * ny + i1 + j1) * nz + i2;
                            for (j2, &y) in sb[ib..ib + db[2] + 1].iter().enumerate() {
                                coef[row + j2] += x * y;
                            }
                            ib += db[2] + 1;
                        }
                    }
                }
            }
        }
        let c = deg.map(binomials);
        let mut idx = 0;
        for i in 0..=deg[0] {
            for j in 0..=deg[1] {
                for k in 0..=deg[2] {
                    coef[idx] /= c[0][i] * c[1][j] * c[2][k];
                    idx += 1;
                }
            }
        }
        let (ma, mb) = (max_abs(self.coef), max_abs(o.coef));
        let (ea, eb) = (self.err, o.err);
        // terms per sum, binomial products (3 axes, 3 factors each) and the division
        let terms: usize = (0..3).map(|a| da[a].min(db[a]) + 1).product();
        let k = (terms + 6 * (deg[0] + deg[1] + deg[2]) + 16) as f64;
        let prop = ma * eb + mb * ea + ea * eb;
        let err = round_up(prop * (1.0 + k * EPS) + k * EPS * ma * mb + TINY);
        Form { deg, coef, err }
    }
}

/// The least (`lo`) and largest (`hi`) computed coefficient of a form, whether one is
/// NaN, and the form's error bound `err`: every exact coefficient `β_k` is within `err`
/// of its computed value.
#[derive(Clone, Copy, Debug)]
pub struct CoefficientHull {
    lo: f64,
    hi: f64,
    nan: bool,
    err: f64,
}

impl CoefficientHull {
    /// `[lo − err, hi + err]`, outward-rounded: it holds every exact coefficient, so the
    /// polynomial's values over the box.
    pub fn range(&self) -> Interval {
        interval_of(self.lo, self.hi, self.nan, self.err)
    }

    /// `[lo + err, hi − err]`, inward-rounded, when not empty: inside the hull of the
    /// exact coefficients (their least is at most `lo + err`, their largest at least
    /// `hi − err`). Bernstein coefficients over a sub-box are convex combinations of
    /// those over the box, so this lies inside the range of the polynomial's form over
    /// any box holding this one, however that form was computed.
    pub fn inner(&self) -> Option<Interval> {
        let (lo, hi) = (round_up(self.lo + self.err), round_down(self.hi - self.err));
        (!self.nan && lo.is_finite() && hi.is_finite() && lo <= hi).then(|| Interval::new(lo, hi))
    }
}

impl Form {
    fn view(&self) -> View<'_> {
        View {
            deg: self.deg,
            coef: &self.coef,
            err: self.err,
        }
    }
}

/// A coefficient of the power → Bernstein conversion: its f64 value and an interval
/// enclosing the exact one, carried through the same operations in one pass.
#[derive(Clone, Copy)]
struct Tracked {
    value: f64,
    enclosure: Interval,
}

impl Tracked {
    fn of(x: f64) -> Self {
        Tracked {
            value: x,
            enclosure: Interval::point(x),
        }
    }

    /// `self / d` for a positive integer `d`.
    fn over(self, d: Self) -> Self {
        Tracked {
            value: self.value / d.value,
            enclosure: self
                .enclosure
                .div(d.enclosure)
                .expect("binomials are positive"),
        }
    }

    /// `self · k` (the interval's product with the point `k`, as `Mul` forms it).
    fn times(self, k: f64) -> Self {
        Tracked {
            value: self.value * k,
            enclosure: self.enclosure.scale(k),
        }
    }
}

impl std::ops::Add for Tracked {
    type Output = Tracked;
    fn add(self, o: Tracked) -> Tracked {
        Tracked {
            value: self.value + o.value,
            enclosure: self.enclosure + o.enclosure,
        }
    }
}

impl std::ops::Mul for Tracked {
    type Output = Tracked;
    fn mul(self, o: Tracked) -> Tracked {
        Tracked {
            value: self.value * o.value,
            enclosure: self.enclosure * o.enclosure,
        }
    }
}

/// Power basis → Bernstein basis over `doms`, in place on the dense tensor `c` of degree
/// `deg`. Per axis with domain `[a, b]`: Taylor shift to `x = a + s`, scale `s = h·u`
/// (`h = b − a`), divide by `C(n, j)` and take the binomial transform
/// `b_i = Σ_{j≤i} C(i, j) d_j`. The lines along the axis are gathered into rows (row `i`
/// holds every line's `i`-th coefficient) and each step runs across a row: the same
/// operations on each coefficient as line by line, independent ones side by side.
fn power_to_bernstein(deg: [usize; 3], c: &mut [Tracked], doms: [Interval; 3]) {
    let mut rows: Vec<Tracked> = Vec::new();
    for (axis, &dom) in doms.iter().enumerate() {
        let (outer, n, inner) = layout(deg, axis);
        if n == 0 {
            continue;
        }
        let h = Tracked::of(dom.hi) + Tracked::of(-dom.lo);
        let mut pascal = vec![Tracked::of(1.0); n + 1];
        for r in 1..n {
            for k in (1..=r).rev() {
                pascal[k] = pascal[k] + pascal[k - 1];
            }
        }
        // line (o, q) is row position o·inner + q; its i-th coefficient at
        // (o·(n+1) + i)·inner + q of the tensor
        let lines = outer * inner;
        let at = |i: usize, l: usize| ((l / inner) * (n + 1) + i) * inner + l % inner;
        rows.clear();
        rows.extend(
            (0..=n)
                .flat_map(|i| (0..lines).map(move |l| (i, l)))
                .map(|(i, l)| c[at(i, l)]),
        );
        if dom.lo != 0.0 {
            for i in 0..n {
                // row j ← row j + lo · row j+1
                for j in (i..n).rev() {
                    let (low, high) = rows.split_at_mut((j + 1) * lines);
                    for (x, &y) in low[j * lines..].iter_mut().zip(&high[..lines]) {
                        *x = *x + y.times(dom.lo);
                    }
                }
            }
        }
        let mut hp = Tracked::of(1.0);
        for (row, &p) in rows.chunks_exact_mut(lines).zip(&pascal) {
            for x in row {
                *x = (*x * hp).over(p);
            }
            hp = hp * h;
        }
        // row i ← row i + row i−1
        for s in 1..=n {
            for i in (s..=n).rev() {
                let (low, high) = rows.split_at_mut(i * lines);
                for (x, &y) in high[..lines].iter_mut().zip(&low[(i - 1) * lines..]) {
                    *x = *x + y;
                }
            }
        }
        for (k, &x) in rows.iter().enumerate() {
            c[at(k / lines, k % lines)] = x;
        }
    }
}

/// The Bernstein form of the power tensor `pow` over `doms`: coefficients from the f64
/// conversion, `err` = the largest distance from a coefficient to the far end of its
/// interval-arithmetic enclosure.
fn from_power(deg: [usize; 3], pow: &[f64], doms: [Interval; 3]) -> Form {
    let mut both: Vec<Tracked> = pow.iter().map(|&x| Tracked::of(x)).collect();
    power_to_bernstein(deg, &mut both, doms);
    let coef: Vec<f64> = both.iter().map(|t| t.value).collect();
    let mut err: f64 = 0.0;
    for (&c, t) in coef.iter().zip(&both) {
        let e = t.enclosure;
        let r = round_up((e.hi - c).max(c - e.lo));
        err = if r.is_nan() {
            f64::INFINITY
        } else {
            err.max(r)
        };
    }
    Form { deg, coef, err }
}

/// The dense tensor of `p`'s power coefficients, keeping variables `< nvars`
/// (terms in the other variables are dropped, i.e. those variables are set to 0).
fn power_tensor(p: &Poly, nvars: usize) -> ([usize; 3], Vec<f64>) {
    let mut deg = [0; 3];
    for (v, d) in deg.iter_mut().enumerate().take(nvars) {
        *d = p.degree_in(v) as usize;
    }
    let mut t = vec![0.0; len_of(deg)];
    for &(e, c) in &p.terms {
        if e[nvars..].iter().any(|&k| k > 0) {
            continue;
        }
        let e = e.map(|k| k as usize);
        let idx = (e[0] * (deg[1] + 1) + e[1]) * (deg[2] + 1) + e[2];
        t[idx] = c;
    }
    (deg, t)
}

fn axis_index(a: Axis) -> usize {
    match a {
        Axis::X => 0,
        Axis::Y => 1,
    }
}

// ---------------------------------------------------------------------------------------

impl Bernstein1 {
    fn view(&self) -> View<'_> {
        View {
            deg: [self.coef.len() - 1, 0, 0],
            coef: &self.coef,
            err: self.err,
        }
    }

    fn from_form(f: Form) -> Self {
        Bernstein1 {
            coef: f.coef,
            err: f.err,
        }
    }

    /// The degree `n` (`coef.len() − 1`).
    pub fn degree(&self) -> usize {
        self.coef.len() - 1
    }

    /// The exact form with coefficients `coef` (error bound 0).
    pub fn exact(coef: Vec<f64>) -> Self {
        Bernstein1 { coef, err: 0.0 }
    }

    /// The constant `c` (degree 0, exact).
    pub fn constant(c: f64) -> Self {
        Self::exact(vec![c])
    }

    /// The form times the constant `k`.
    pub fn scale(&self, k: f64) -> Self {
        let m = max_abs(&self.coef);
        Bernstein1 {
            coef: self.coef.iter().map(|c| c * k).collect(),
            err: grown(self.err * k.abs(), m * k.abs(), 1.0),
        }
    }

    /// The Bernstein form over `[0,1]` of `p(t) = Σ power[k] tᵏ` restricted to
    /// `t ∈ interval` (relative parameter `u = (t − lo)/(hi − lo)`).
    pub fn from_poly_1d(power: &[f64], interval: Interval) -> Self {
        let pow = if power.is_empty() { &[0.0][..] } else { power };
        let deg = [pow.len() - 1, 0, 0];
        let dom = Interval::point(0.0);
        Self::from_form(from_power(deg, pow, [interval, dom, dom]))
    }

    /// de Casteljau at `t ∈ [0,1]`: the forms over `[0, t]` and `[t, 1]`.
    pub fn split(&self, t: f64) -> (Self, Self) {
        let (mut lower, mut upper) = (Self::exact(Vec::new()), Self::exact(Vec::new()));
        self.split_into(t, &mut lower, &mut upper);
        (lower, upper)
    }

    /// [`Self::split`] into `lower` and `upper`, reusing their allocations: each level
    /// is a convex combination (rounding ≤ 2.5 ε·max|b|), so `err` grows by
    /// `4·n·ε·(max|b| + err)`.
    pub fn split_into(&self, t: f64, lower: &mut Self, upper: &mut Self) {
        debug_assert!(
            (0.0..=1.0).contains(&t),
            "split parameter {t} outside [0, 1]"
        );
        for part in [&mut *lower, &mut *upper] {
            part.coef.clear();
            part.coef.extend_from_slice(&self.coef);
        }
        let n = self.degree();
        let err = if n > 0 {
            split_lines(&mut lower.coef, &mut upper.coef, n + 1, t);
            grown(self.err, max_abs(&self.coef), 4.0 * n as f64)
        } else {
            self.err
        };
        lower.err = err;
        upper.err = err;
    }

    /// A certified enclosure of the exact polynomial over `[0, 1]`.
    pub fn range(&self) -> Interval {
        self.view().range()
    }

    /// The value at `u` (f64 de Casteljau, not certified).
    pub fn eval(&self, u: f64) -> f64 {
        let mut buf = [0.0; 16];
        match buf.get_mut(..self.coef.len()) {
            Some(b) => {
                b.copy_from_slice(&self.coef);
                casteljau_value(b, u)
            }
            None => casteljau_value(&mut self.coef.clone(), u),
        }
    }

    /// The value and the slope `df/du` at `u` from one de Casteljau triangle: the last
    /// level's two points `p₀`, `p₁` give `f = p₀ + u (p₁ − p₀)` (the same steps as
    /// [`Self::eval`]) and `f' = n (p₁ − p₀)` (f64, not certified).
    pub fn value_and_slope(&self, u: f64) -> (f64, f64) {
        let n = self.degree();
        if n == 0 {
            return (self.coef[0], 0.0);
        }
        let mut buf = [0.0; 16];
        let mut heap;
        let c: &mut [f64] = match buf.get_mut(..self.coef.len()) {
            Some(b) => b,
            None => {
                heap = self.coef.clone();
                &mut heap
            }
        };
        c.copy_from_slice(&self.coef);
        for r in 1..n {
            for i in 0..=n - r {
                c[i] += u * (c[i + 1] - c[i]);
            }
        }
        let d = c[1] - c[0];
        (c[0] + u * d, n as f64 * d)
    }

    /// `df/du` (relative parameter; divide by the interval's width for world units).
    pub fn derivative(&self) -> Self {
        Self::from_form(self.view().derivative(0))
    }

    /// The same polynomial at degree `to ≥ degree()`.
    pub fn elevate(&self, to: usize) -> Self {
        Self::from_form(self.view().elevate([to, 0, 0]))
    }

    /// The sum.
    pub fn add(&self, o: &Self) -> Self {
        Self::from_form(self.view().add(o.view(), 1.0))
    }

    /// The difference.
    pub fn sub(&self, o: &Self) -> Self {
        Self::from_form(self.view().add(o.view(), -1.0))
    }

    /// The product (degrees add).
    pub fn mul(&self, o: &Self) -> Self {
        Self::from_form(self.view().mul(o.view()))
    }
}

impl Bernstein2 {
    fn view(&self) -> View<'_> {
        View {
            deg: [self.deg[0], self.deg[1], 0],
            coef: &self.coef,
            err: self.err,
        }
    }

    fn from_form(f: Form) -> Self {
        Bernstein2 {
            deg: [f.deg[0], f.deg[1]],
            coef: f.coef,
            err: f.err,
        }
    }

    /// The Bernstein form of `p(x, y)` over `b` (terms containing `z` are dropped, i.e.
    /// `z = 0`), degrees `(deg_x p, deg_y p)`.
    pub fn from_poly(p: &Poly, b: &Aabb) -> Self {
        let mut deg = [p.degree_in(0) as usize, p.degree_in(1) as usize];
        // a box of zero width or height (a segment) needs no degree along that axis
        if b.width() == 0.0 {
            deg[0] = 0;
        }
        if b.height() == 0.0 {
            deg[1] = 0;
        }
        let terms = p.terms.iter().filter(|(e, _)| e[2] == 0).count();
        if deg[0] < p.degree_in(0) as usize
            || deg[1] < p.degree_in(1) as usize
            || terms * 4 <= (deg[0] + 1) * (deg[1] + 1)
        {
            return Self::from_sparse(p, b, deg);
        }
        let (deg, pow) = power_tensor(p, 2);
        Self::from_form(from_power(deg, &pow, [b.x(), b.y(), Interval::point(0.0)]))
    }

    /// Enclosures of `h = self − o` and of its two partial derivatives with respect to the
    /// relative coordinates, computed coefficient by coefficient without forming `h`
    /// (both forms must be over the same box; unequal degrees go through [`Self::sub`]).
    pub fn difference_bounds(&self, o: &Self) -> (Interval, [Interval; 2]) {
        if self.deg != o.deg {
            let h = self.sub(o);
            return (
                h.range(),
                [h.derivative(Axis::X).range(), h.derivative(Axis::Y).range()],
            );
        }
        let [dx, dy] = self.deg;
        let ny = dy + 1;
        let h = |k: usize| self.coef[k] - o.coef[k];
        let m = max_abs(&self.coef) + max_abs(&o.coef);
        let err = round_up(self.err + o.err + EPS * m + TINY);
        let mut value = (f64::INFINITY, f64::NEG_INFINITY);
        let mut grad = [(f64::INFINITY, f64::NEG_INFINITY); 2];
        let mut nan = false;
        for i in 0..=dx {
            for j in 0..=dy {
                let v = h(i * ny + j);
                nan |= v.is_nan();
                value = (value.0.min(v), value.1.max(v));
                if i < dx {
                    let d = dx as f64 * (h((i + 1) * ny + j) - v);
                    grad[0] = (grad[0].0.min(d), grad[0].1.max(d));
                }
                if j < dy {
                    let d = dy as f64 * (h(i * ny + j + 1) - v);
                    grad[1] = (grad[1].0.min(d), grad[1].1.max(d));
                }
            }
        }
        let whole = Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        if nan || !err.is_finite() {
            return (whole, [whole, whole]);
        }
        let widen = |(lo, hi): (f64, f64), e: f64| {
            if lo > hi {
                Interval::point(0.0) // degree 0 along this axis: the derivative is 0
            } else {
                Interval::new(round_down(lo - e), round_up(hi + e))
            }
        };
        // a derivative coefficient n·(h_{i+1} − h_i) is within 2n·err plus its rounding
        let derr =
            |n: usize| round_up(2.0 * n as f64 * err + 4.0 * n as f64 * EPS * (m + err) + TINY);
        (
            widen(value, err),
            [widen(grad[0], derr(dx)), widen(grad[1], derr(dy))],
        )
    }

    /// The conversion of a sparse polynomial by blossoming: over `[a, b]` at degree `d`,
    /// the k-th Bernstein coefficient of `x^i` is its blossom at (a^(d−k), b^k),
    /// `Σ_m C(k,m) C(d−k,i−m) a^(i−m) b^m / C(d,i)`; a tensor coefficient is the sum over
    /// the terms of `c · β_i[k] · γ_j[l]`. The error bound counts every rounding against
    /// the sum of the absolute values of the summands.
    /// An axis whose interval is a point gets degree 0: there `x^i` is the constant `a^i`.
    fn from_sparse(p: &Poly, b: &Aabb, deg: [usize; 2]) -> Self {
        let table = |d: usize, full: u32, a: f64, b: f64| {
            if d == 0 && full > 0 {
                let v: Vec<f64> = (0..=full as i32).map(|i| a.powi(i)).collect();
                let m = v.iter().map(|x| x.abs()).collect();
                (v, m)
            } else {
                monomial_table(d, a, b)
            }
        };
        let ux = table(deg[0], p.degree_in(0), b.min.x, b.max.x);
        let uy = table(deg[1], p.degree_in(1), b.min.y, b.max.y);
        let (nx, ny) = (deg[0] + 1, deg[1] + 1);
        let mut coef = vec![0.0; nx * ny];
        let mut magnitude = vec![0.0f64; nx * ny];
        for &(e, c) in p.terms.iter().filter(|(e, _)| e[2] == 0) {
            let (i, j) = (e[0] as usize, e[1] as usize);
            for k in 0..nx {
                let (bx, mx) = (ux.0[i * nx + k], ux.1[i * nx + k]);
                for l in 0..ny {
                    let (by, my) = (uy.0[j * ny + l], uy.1[j * ny + l]);
                    coef[k * ny + l] += c * bx * by;
                    magnitude[k * ny + l] += c.abs() * mx * my;
                }
            }
        }
        let full = (p.degree_in(0) + p.degree_in(1)) as usize;
        let rounding = (4 * full + 16 + 2 * p.terms.len()) as f64 * EPS;
        let worst = magnitude.iter().fold(0.0f64, |m, &x| m.max(x));
        let err = round_up(worst * rounding + TINY);
        if !err.is_finite() || coef.iter().any(|c| !c.is_finite()) {
            return Bernstein2 {
                deg,
                coef,
                err: f64::INFINITY,
            };
        }
        Bernstein2 { deg, coef, err }
    }

    /// de Casteljau along `axis` at relative `t ∈ [0,1]`: the lower and upper parts.
    pub fn split(&self, axis: Axis, t: f64) -> (Self, Self) {
        let (l, r) = self.view().split(axis_index(axis), t);
        (Self::from_form(l), Self::from_form(r))
    }

    /// A certified enclosure of the exact polynomial over the box.
    pub fn range(&self) -> Interval {
        self.view().range()
    }

    /// True when every coefficient is within the error bound plus `slack` of 0. Then so
    /// is every coefficient of a sub-box's form (de Casteljau splits take convex
    /// combinations), so neither this range nor a sub-box's excludes 0 by more than
    /// `slack`.
    pub fn within_of_zero(&self, slack: f64) -> bool {
        let bound = self.err + slack;
        self.coef.iter().all(|c| c.abs() <= bound)
    }

    /// The value at relative `(u, v)` (f64 de Casteljau, not certified).
    pub fn eval(&self, u: f64, v: f64) -> f64 {
        self.view().eval([u, v, 0.0])
    }

    /// `∂f/∂u` or `∂f/∂v` in relative coordinates: divide by the box's width (X) or
    /// height (Y) for world units.
    pub fn derivative(&self, axis: Axis) -> Self {
        Self::from_form(self.view().derivative(axis_index(axis)))
    }

    /// The range of `self.derivative(axis)` (the same enclosure, without forming it).
    pub fn derivative_range(&self, axis: Axis) -> Interval {
        self.view().derivative_range(axis_index(axis))
    }

    /// The coefficient hull of `self.derivative(axis)` (without forming it); `None` for
    /// degree 0 along `axis`.
    pub fn derivative_hull(&self, axis: Axis) -> Option<CoefficientHull> {
        (self.deg[axis_index(axis)] > 0).then(|| self.view().derivative_hull(axis_index(axis)))
    }

    /// The same polynomial at degrees `to ≥ deg`.
    pub fn elevate(&self, to: [usize; 2]) -> Self {
        Self::from_form(self.view().elevate([to[0], to[1], 0]))
    }

    /// The sum.
    pub fn add(&self, o: &Self) -> Self {
        Self::from_form(self.view().add(o.view(), 1.0))
    }

    /// The difference.
    pub fn sub(&self, o: &Self) -> Self {
        Self::from_form(self.view().add(o.view(), -1.0))
    }

    /// The product (degrees add).
    pub fn mul(&self, o: &Self) -> Self {
        Self::from_form(self.view().mul(o.view()))
    }

    /// The tensor product `f(u, v) = a(u) · b(v)` of two univariate forms (degrees
    /// `(deg a, deg b)`): the product of `a` and `b` seen as forms in different
    /// variables.
    pub fn tensor(a: &Bernstein1, b: &Bernstein1) -> Self {
        let va = View {
            deg: [a.degree(), 0, 0],
            coef: &a.coef,
            err: a.err,
        };
        let vb = View {
            deg: [0, b.degree(), 0],
            coef: &b.coef,
            err: b.err,
        };
        Self::from_form(va.mul(vb))
    }

    /// The restriction to the line where the `axis` coordinate is `t ∈ [0, 1]`, as a
    /// form in the other relative coordinate (de Casteljau split, then the side:
    /// certified like [`Self::split`]).
    pub fn restrict(&self, axis: Axis, t: f64) -> Bernstein1 {
        if t >= 1.0 {
            return self.edge(axis, 1);
        }
        // the upper part's lower side: each line along `axis` evaluated at `t` by the
        // same de Casteljau steps as the split, without forming either part
        let (_, n, inner) = layout([self.deg[0], self.deg[1], 0], axis_index(axis));
        let mut line = vec![0.0; n + 1];
        let lines = self.coef.len() / (n + 1);
        let coef = (0..lines)
            .map(|k| {
                let (o, q) = (k / inner, k % inner);
                for (i, x) in line.iter_mut().enumerate() {
                    *x = self.coef[(o * (n + 1) + i) * inner + q];
                }
                casteljau_value(&mut line, t)
            })
            .collect();
        let err = if n > 0 {
            grown(self.err, max_abs(&self.coef), 4.0 * n as f64)
        } else {
            self.err
        };
        Bernstein1 { coef, err }
    }

    /// The polynomial in the power basis of the relative coordinates `(u, v)` (variables
    /// `x`, `y` of [`Poly`]): `B_i^n(u) = Σ_k C(n,i) C(n−i,k−i) (−1)^(k−i) u^k`. Plain
    /// f64 (not certified); for the 2-D solver over `[0, 1]²`.
    pub fn to_poly(&self) -> Poly {
        let [dx, dy] = self.deg;
        let power = |n: usize| -> Vec<Vec<f64>> {
            let c: Vec<Vec<f64>> = (0..=n).map(binomials).collect();
            (0..=n)
                .map(|i| {
                    (0..=n)
                        .map(|k| {
                            if k < i {
                                0.0
                            } else {
                                let sign = if (k - i) % 2 == 0 { 1.0 } else { -1.0 };
                                c[n][i] * c[n - i][k - i] * sign
                            }
                        })
                        .collect()
                })
                .collect()
        };
        let (px, py) = (power(dx), power(dy));
        let mut acc = vec![0.0; (dx + 1) * (dy + 1)];
        for (i, row) in px.iter().enumerate() {
            for (j, col) in py.iter().enumerate() {
                let b = self.coef[i * (dy + 1) + j];
                if b == 0.0 {
                    continue;
                }
                for k in i..=dx {
                    for l in j..=dy {
                        acc[k * (dy + 1) + l] += b * row[k] * col[l];
                    }
                }
            }
        }
        let mut terms = Vec::new();
        for k in 0..=dx {
            for l in 0..=dy {
                let c = acc[k * (dy + 1) + l];
                if c != 0.0 {
                    terms.push(([k as u32, l as u32, 0], c));
                }
            }
        }
        Poly::from_terms(terms)
    }

    /// The restriction to the box side where the `axis` coordinate is `at` (0: lower
    /// side, 1: upper side), as a form in the other relative coordinate. Exact: the
    /// side's coefficients are a subset of the box's.
    pub fn edge(&self, axis: Axis, at: usize) -> Bernstein1 {
        assert!(at <= 1, "edge side must be 0 or 1");
        let [dx, dy] = self.deg;
        let coef = match axis {
            Axis::X => {
                let i = at * dx;
                self.coef[i * (dy + 1)..(i + 1) * (dy + 1)].to_vec()
            }
            Axis::Y => (0..=dx)
                .map(|i| self.coef[i * (dy + 1) + at * dy])
                .collect(),
        };
        Bernstein1 {
            coef,
            err: self.err,
        }
    }
}

impl Bernstein3 {
    fn view(&self) -> View<'_> {
        View {
            deg: self.deg,
            coef: &self.coef,
            err: self.err,
        }
    }

    fn from_form(f: Form) -> Self {
        Bernstein3 {
            deg: f.deg,
            coef: f.coef,
            err: f.err,
        }
    }

    /// The Bernstein form of `p(x, y, z)` over `b × z`.
    pub fn from_poly(p: &Poly, b: &Aabb, z: Interval) -> Self {
        let (deg, pow) = power_tensor(p, 3);
        Self::from_form(from_power(deg, &pow, [b.x(), b.y(), z]))
    }

    /// de Casteljau along axis `0` (x), `1` (y) or `2` (z) at relative `t ∈ [0,1]`.
    pub fn split(&self, axis: usize, t: f64) -> (Self, Self) {
        let (l, r) = self.view().split(axis, t);
        (Self::from_form(l), Self::from_form(r))
    }

    /// A certified enclosure of the exact polynomial over box × z-interval.
    pub fn range(&self) -> Interval {
        self.view().range()
    }

    /// The value at relative `(u, v, w)` (f64 de Casteljau, not certified).
    pub fn eval(&self, u: f64, v: f64, w: f64) -> f64 {
        self.view().eval([u, v, w])
    }

    /// The derivative along relative axis `0..3`; divide by that side's length for world
    /// units.
    pub fn derivative(&self, axis: usize) -> Self {
        Self::from_form(self.view().derivative(axis))
    }

    /// The same polynomial at degrees `to ≥ deg`.
    pub fn elevate(&self, to: [usize; 3]) -> Self {
        Self::from_form(self.view().elevate(to))
    }

    /// The sum.
    pub fn add(&self, o: &Self) -> Self {
        Self::from_form(self.view().add(o.view(), 1.0))
    }

    /// The difference.
    pub fn sub(&self, o: &Self) -> Self {
        Self::from_form(self.view().add(o.view(), -1.0))
    }

    /// The product (degrees add).
    pub fn mul(&self, o: &Self) -> Self {
        Self::from_form(self.view().mul(o.view()))
    }

    /// Emiris et al. §3.1: `m_g(w) = Σ_k (min_ij γ_ijk − err) B_k(w)` and
    /// `M_g(w) = Σ_k (max_ij γ_ijk + err) B_k(w)`, so that
    /// `m_g(w) ≤ g(u, v, w) ≤ M_g(w)` on the whole box. The coefficients are rounded
    /// outward and returned *exact* (`err = 0`): the envelopes are certified bounds.
    pub fn z_envelopes(&self) -> (Bernstein1, Bernstein1) {
        let nz = self.deg[2] + 1;
        let mut lo = vec![f64::INFINITY; nz];
        let mut hi = vec![f64::NEG_INFINITY; nz];
        for (idx, &c) in self.coef.iter().enumerate() {
            let k = idx % nz;
            if c.is_nan() {
                lo[k] = f64::NEG_INFINITY;
                hi[k] = f64::INFINITY;
            }
            lo[k] = lo[k].min(c);
            hi[k] = hi[k].max(c);
        }
        let e = Interval::new(-self.err, self.err);
        let env = |v: Vec<f64>, lower: bool| Bernstein1 {
            coef: v
                .into_iter()
                .map(|c| {
                    let r = Interval::point(c) + e;
                    if lower {
                        r.lo
                    } else {
                        r.hi
                    }
                })
                .collect(),
            err: 0.0,
        };
        (env(lo, true), env(hi, false))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point;
    use proptest::prelude::*;

    fn poly_strategy(nvars: usize, max_deg: u32) -> impl Strategy<Value = Poly> {
        proptest::collection::vec(
            (0..=max_deg, 0..=max_deg, 0..=max_deg, -10.0..10.0f64),
            1..10,
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

    #[test]
    fn tensor_restrict_and_power_basis_agree_with_evaluation() {
        let a = Bernstein1::exact(vec![1.0, -2.0, 0.5, 3.0]);
        let b = Bernstein1::exact(vec![0.25, 2.0, -1.0]);
        let f = Bernstein2::tensor(&a, &b).add(&Bernstein2::tensor(&b, &a.scale(0.5)));
        let p = f.to_poly();
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.2), (0.9, 1.0)] {
            let want = a.eval(u) * b.eval(v) + 0.5 * b.eval(u) * a.eval(v);
            assert!((f.eval(u, v) - want).abs() < 1e-12);
            assert!((p.eval(u, v, 0.0) - want).abs() < 1e-12);
            assert!((f.restrict(Axis::X, u).eval(v) - want).abs() < 1e-12);
            assert!((f.restrict(Axis::Y, v).eval(u) - want).abs() < 1e-12);
        }
        assert_eq!(
            Bernstein1::constant(2.0).mul(&a).eval(0.4),
            2.0 * a.eval(0.4)
        );
    }

    proptest! {
        /// The restriction is the upper part's lower side, bit for bit (coefficients and
        /// error bound), whichever axis and degrees.
        #[test]
        fn restrict_is_the_side_of_the_split(p in poly_strategy(2, 6), t in 0.0..1.0f64, along_x: bool) {
            let b = Aabb::new(Point::new(-0.5, 0.25), Point::new(1.5, 2.0));
            let f = Bernstein2::from_poly(&p, &b);
            let axis = if along_x { Axis::X } else { Axis::Y };
            let (_, upper) = f.split(axis, t);
            prop_assert_eq!(f.restrict(axis, t), upper.edge(axis, 0));
        }

        #[test]
        fn sparse_and_dense_conversions_agree(p in poly_strategy(2, 8), x0 in -3.0..3.0f64, y0 in -3.0..3.0f64,
                                             w in 0.001..2.0f64, h in 0.001..2.0f64) {
            let b = Aabb::new(Point::new(x0, y0), Point::new(x0 + w, y0 + h));
            let deg = [p.degree_in(0) as usize, p.degree_in(1) as usize];
            let sparse = Bernstein2::from_sparse(&p, &b, deg);
            let (d, pow) = power_tensor(&p, 2);
            let dense = Bernstein2::from_form(from_power(d, &pow, [b.x(), b.y(), Interval::point(0.0)]));
            prop_assert_eq!(sparse.deg, dense.deg);
            for (s, t) in sparse.coef.iter().zip(&dense.coef) {
                prop_assert!((s - t).abs() <= sparse.err + dense.err, "{} vs {}", s, t);
            }
        }
    }

    proptest! {
        #[test]
        fn difference_bounds_match_the_formed_difference(p in poly_strategy(2, 6), q in poly_strategy(2, 6), x0 in -3.0..3.0f64, y0 in -3.0..3.0f64,
                                                          w in 0.001..2.0f64, h in 0.001..2.0f64, u in 0.0..=1.0f64, v in 0.0..=1.0f64) {
            let b = Aabb::new(Point::new(x0, y0), Point::new(x0 + w, y0 + h));
            let (fp, fq) = (Bernstein2::from_poly(&p, &b), Bernstein2::from_poly(&q, &b));
            let (value, grad) = fp.difference_bounds(&fq);
            let at = b.at(u, v);
            let exact = p.eval(at.x, at.y, 0.0) - q.eval(at.x, at.y, 0.0);
            let slack = 1e-9 * (1.0 + exact.abs());
            prop_assert!(value.lo - slack <= exact && exact <= value.hi + slack);
            let d = p.sub(&q);
            let gx = d.partial(0).eval(at.x, at.y, 0.0) * w;
            let gy = d.partial(1).eval(at.x, at.y, 0.0) * h;
            prop_assert!(grad[0].lo - 1e-9 * (1.0 + gx.abs()) <= gx && gx <= grad[0].hi + 1e-9 * (1.0 + gx.abs()));
            prop_assert!(grad[1].lo - 1e-9 * (1.0 + gy.abs()) <= gy && gy <= grad[1].hi + 1e-9 * (1.0 + gy.abs()));
        }
    }

    proptest! {
        #[test]
        fn segment_boxes_enclose_values(p in poly_strategy(2, 8), x0 in -3.0..3.0f64, y0 in -3.0..3.0f64,
                                        w in 0.001..2.0f64, u in 0.0..=1.0f64, vertical in any::<bool>()) {
            let b = if vertical {
                Aabb::new(Point::new(x0, y0), Point::new(x0, y0 + w))
            } else {
                Aabb::new(Point::new(x0, y0), Point::new(x0 + w, y0))
            };
            let f = Bernstein2::from_poly(&p, &b);
            prop_assert!(f.deg[usize::from(!vertical)] == 0);
            let q = b.at(u, u);
            let exact = p.eval(q.x, q.y, 0.0);
            let r = f.range();
            prop_assert!(r.lo <= exact + 1e-12 * exact.abs() && exact - 1e-12 * exact.abs() <= r.hi);
        }
    }

    /// A relative coordinate, often exactly at a side (where values equal coefficients).
    fn rel() -> impl Strategy<Value = f64> {
        prop_oneof![Just(0.0), Just(1.0), 0.0..=1.0f64]
    }

    fn box_strategy() -> impl Strategy<Value = Aabb> {
        (-3.0..3.0f64, -3.0..3.0f64, 1e-3..2.0f64, 1e-3..2.0f64)
            .prop_map(|(x, y, w, h)| Aabb::new(Point::new(x, y), Point::new(x + w, y + h)))
    }

    fn ival() -> impl Strategy<Value = Interval> {
        (-3.0..3.0f64, 1e-3..2.0f64).prop_map(|(a, w)| Interval::new(a, a + w))
    }

    /// A rigorous enclosure of the exact polynomial's value at an f64 point.
    fn exact(p: &Poly, x: f64, y: f64, z: f64) -> Interval {
        p.eval_interval(Interval::point(x), Interval::point(y), Interval::point(z))
    }

    fn meets(a: Interval, b: Interval) -> bool {
        a.lo <= b.hi && b.lo <= a.hi
    }

    fn coef_scale(p: &Poly) -> f64 {
        p.terms.iter().map(|t| t.1.abs()).sum::<f64>() * 5.0f64.powi(24)
    }

    #[test]
    fn simple_forms_are_tight() {
        let p = Poly::parse("x^2 - 2*x*y", &['x', 'y']).unwrap();
        let b = Bernstein2::from_poly(&p, &Aabb::from_array([0.0, 0.0, 1.0, 1.0]));
        assert_eq!(b.deg, [2, 1]);
        // x² − 2xy over [0,1]²: coefficients (i,j) = x²: [0, 0, 1]; −2xy: [0,0;0,−1;0,−2]
        assert_eq!(b.coef, vec![0.0, 0.0, 0.0, -1.0, 1.0, -1.0]);
        let r = b.range();
        assert!(r.lo >= -1.0 - 1e-12 && r.hi <= 1.0 + 1e-12 && r.contains(-1.0));
        assert!(b.err < 1e-14);
        let e = b.edge(Axis::X, 1); // x = 1: 1 − 2y
        assert_eq!(e.coef, vec![1.0, -1.0]);
        let e = b.edge(Axis::Y, 0); // y = 0: x²
        assert_eq!(e.coef, vec![0.0, 0.0, 1.0]);
        let d = b.derivative(Axis::X); // 2x − 2y over relative coords
        assert!((d.eval(0.75, 0.25) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn conversion_error_is_accounted_for() {
        // huge power coefficients, tiny values: f64 conversion error dominates
        let p = Poly::parse("(x - 1000.1)^4 + (y + 999.95)^3", &['x', 'y']).unwrap();
        let bx = Aabb::from_array([1000.0, -1000.0, 1000.2, -999.9]);
        let mut b = Bernstein2::from_poly(&p, &bx);
        assert!(b.err > 1e-6, "err {} should reflect cancellation", b.err);
        let check = |b: &Bernstein2, bx: &Aabb| {
            for i in 0..=4 {
                for j in 0..=4 {
                    let (u, v) = (i as f64 / 4.0, j as f64 / 4.0);
                    let q = bx.at(u, v);
                    assert!(meets(b.range(), exact(&p, q.x, q.y, 0.0)));
                }
            }
        };
        check(&b, &bx);
        let mut bx = bx;
        for k in 0..30 {
            let axis = if k % 2 == 0 { Axis::X } else { Axis::Y };
            let at = match axis {
                Axis::X => 0.5 * (bx.min.x + bx.max.x),
                Axis::Y => 0.5 * (bx.min.y + bx.max.y),
            };
            let (l, _) = b.split(axis, 0.5);
            b = l;
            bx = bx.split(axis, at).0;
            check(&b, &bx);
        }
    }

    #[test]
    fn lower_envelopes_bound_a_cone() {
        let p = Poly::parse("(x-1)^2 + y^2 - (z+0.5)^2", &['x', 'y', 'z']).unwrap();
        let b = Aabb::from_array([0.5, -0.5, 1.25, 0.25]);
        let z = Interval::new(-1.0, 0.5);
        let g = Bernstein3::from_poly(&p, &b, z);
        let (m, mm) = g.z_envelopes();
        assert_eq!(m.err, 0.0);
        for s in 0..=20 {
            let w = s as f64 / 20.0;
            for (u, v) in [(0.0, 0.0), (0.3, 0.9), (1.0, 0.5), (0.6, 0.1)] {
                let pt = b.at(u, v);
                let val = exact(&p, pt.x, pt.y, z.lo + w * z.width());
                assert!(m.eval(w) <= val.hi + 1e-12 && val.lo - 1e-12 <= mm.eval(w));
            }
        }
    }

    proptest! {
        #[test]
        fn range_encloses_samples_1d(c in proptest::collection::vec(-10.0..10.0f64, 1..10), dom in ival(), s in proptest::collection::vec(rel(), 8)) {
            let p = Poly::from_terms(c.iter().enumerate().map(|(i, &c)| ([i as u32, 0, 0], c)).collect());
            let b = Bernstein1::from_poly_1d(&c, dom);
            let r = b.range();
            for &u in &s {
                let x = dom.lo + u * dom.width();
                let v = exact(&p, x, 0.0, 0.0);
                prop_assert!(meets(r, v), "{} not in {}", v, r);
                prop_assert!((b.eval((x - dom.lo) / dom.width()) - p.eval(x, 0.0, 0.0)).abs() <= 1e-9 * coef_scale(&p));
            }
        }

        #[test]
        fn range_encloses_samples_2d(p in poly_strategy(2, 8), bx in box_strategy(), s in proptest::collection::vec((rel(), rel()), 8)) {
            let b = Bernstein2::from_poly(&p, &bx);
            let r = b.range();
            for &(u, v) in &s {
                let q = bx.at(u, v);
                let val = exact(&p, q.x, q.y, 0.0);
                prop_assert!(meets(r, val), "{} not in {}", val, r);
            }
            // corner values are exact coefficients: the enclosure is not vacuous
            let corner = exact(&p, bx.min.x, bx.min.y, 0.0);
            prop_assert!((b.coef[0] - corner.mid()).abs() <= b.err + corner.width() + 1e-300);
        }

        #[test]
        fn range_encloses_samples_3d(p in poly_strategy(3, 8), bx in box_strategy(), z in ival(), s in proptest::collection::vec((rel(), rel(), rel()), 8)) {
            let b = Bernstein3::from_poly(&p, &bx, z);
            let r = b.range();
            let (m, mm) = b.z_envelopes();
            for &(u, v, w) in &s {
                let q = bx.at(u, v);
                let zz = z.lo + w * z.width();
                let val = exact(&p, q.x, q.y, zz);
                prop_assert!(meets(r, val), "{} not in {}", val, r);
                prop_assert!(m.range().lo <= val.hi && val.lo <= mm.range().hi);
            }
        }

        #[test]
        fn split_children_reproduce_the_parent(p in poly_strategy(2, 6), bx in box_strategy(), t in 0.0..=1.0f64, u in 0.0..=1.0f64, v in 0.0..=1.0f64, x_axis in any::<bool>()) {
            let b = Bernstein2::from_poly(&p, &bx);
            let axis = if x_axis { Axis::X } else { Axis::Y };
            let (lo, hi) = b.split(axis, t);
            let tol = 1e-10 * (1.0 + max_abs(&b.coef));
            let (ul, uh) = (t * u, t + (1.0 - t) * u);
            let (pl, ph) = if x_axis { (b.eval(ul, v), b.eval(uh, v)) } else { (b.eval(v, ul), b.eval(v, uh)) };
            let (cl, ch) = if x_axis { (lo.eval(u, v), hi.eval(u, v)) } else { (lo.eval(v, u), hi.eval(v, u)) };
            prop_assert!((pl - cl).abs() <= tol, "{} vs {}", pl, cl);
            prop_assert!((ph - ch).abs() <= tol, "{} vs {}", ph, ch);
            // children ranges still enclose the exact values
            let q = if x_axis { bx.at(ul, v) } else { bx.at(v, ul) };
            prop_assert!(meets(lo.range(), exact(&p, q.x, q.y, 0.0)));
            prop_assert!(lo.err >= b.err && hi.err >= b.err);
        }

        #[test]
        fn split_3d_and_1d(p in poly_strategy(3, 4), bx in box_strategy(), z in ival(), t in 0.0..=1.0f64, w in proptest::array::uniform3(0.0..=1.0f64), axis in 0usize..3) {
            let b = Bernstein3::from_poly(&p, &bx, z);
            let (lo, hi) = b.split(axis, t);
            let mut wl = w;
            let mut wh = w;
            wl[axis] = t * w[axis];
            wh[axis] = t + (1.0 - t) * w[axis];
            let tol = 1e-10 * (1.0 + max_abs(&b.coef));
            prop_assert!((lo.eval(w[0], w[1], w[2]) - b.eval(wl[0], wl[1], wl[2])).abs() <= tol);
            prop_assert!((hi.eval(w[0], w[1], w[2]) - b.eval(wh[0], wh[1], wh[2])).abs() <= tol);
            let e = Bernstein1 { coef: b.coef[..b.deg[2] + 1].to_vec(), err: 0.0 };
            let (el, eh) = e.split(t);
            prop_assert!((el.eval(w[0]) - e.eval(t * w[0])).abs() <= tol);
            prop_assert!((eh.eval(w[0]) - e.eval(t + (1.0 - t) * w[0])).abs() <= tol);
        }

        #[test]
        fn derivative_matches_finite_differences(p in poly_strategy(2, 6), bx in box_strategy(), u in 0.01..0.99f64, v in 0.01..0.99f64, x_axis in any::<bool>()) {
            let b = Bernstein2::from_poly(&p, &bx);
            let h = 1e-6;
            let (d, fd, world) = if x_axis {
                let q = bx.at(u, v);
                (b.derivative(Axis::X).eval(u, v), (b.eval(u + h, v) - b.eval(u - h, v)) / (2.0 * h), p.partial(0).eval(q.x, q.y, 0.0) * bx.width())
            } else {
                let q = bx.at(u, v);
                (b.derivative(Axis::Y).eval(u, v), (b.eval(u, v + h) - b.eval(u, v - h)) / (2.0 * h), p.partial(1).eval(q.x, q.y, 0.0) * bx.height())
            };
            let scale = 1.0 + max_abs(&b.coef);
            prop_assert!((d - fd).abs() <= 1e-5 * scale, "{} vs {}", d, fd);
            prop_assert!((d - world).abs() <= 1e-9 * coef_scale(&p), "{} vs {}", d, world);
            let dr = b.derivative(if x_axis { Axis::X } else { Axis::Y }).range();
            let q = bx.at(u, v);
            let exact_d = p.partial(if x_axis { 0 } else { 1 }).eval_interval(Interval::point(q.x), Interval::point(q.y), Interval::point(0.0));
            let side = if x_axis { bx.width() } else { bx.height() };
            prop_assert!(meets(dr, exact_d.scale(side)));
        }

        #[test]
        fn mul_add_sub_match_eval(p in poly_strategy(2, 4), q in poly_strategy(2, 4), bx in box_strategy(), u in 0.0..=1.0f64, v in 0.0..=1.0f64) {
            let (a, b) = (Bernstein2::from_poly(&p, &bx), Bernstein2::from_poly(&q, &bx));
            let pt = bx.at(u, v);
            let (pa, pb) = (exact(&p, pt.x, pt.y, 0.0), exact(&q, pt.x, pt.y, 0.0));
            let prod = a.mul(&b);
            prop_assert!(meets(prod.range(), pa * pb));
            let direct = Bernstein2::from_poly(&p.mul(&q), &bx);
            let tol = 1e-9 * (1.0 + max_abs(&direct.coef));
            prop_assert!((prod.eval(u, v) - direct.eval(u, v)).abs() <= tol);
            prop_assert_eq!(prod.deg, [a.deg[0] + b.deg[0], a.deg[1] + b.deg[1]]);
            let diff = a.sub(&b);
            prop_assert!((diff.eval(u, v) - (a.eval(u, v) - b.eval(u, v))).abs() <= tol);
            prop_assert!(meets(diff.range(), pa - pb));
            let sum = a.add(&b);
            prop_assert!(meets(sum.range(), pa + pb));
            let el = a.elevate([a.deg[0] + 2, a.deg[1] + 1]);
            prop_assert!((el.eval(u, v) - a.eval(u, v)).abs() <= tol);
            prop_assert!(meets(el.range(), pa));
        }

        #[test]
        fn products_1d_and_3d(c in proptest::collection::vec(-5.0..5.0f64, 1..6), d in proptest::collection::vec(-5.0..5.0f64, 1..6), dom in ival(), u in 0.0..=1.0f64, p in poly_strategy(3, 3), q in poly_strategy(3, 3), bx in box_strategy(), z in ival()) {
            let (a, b) = (Bernstein1::from_poly_1d(&c, dom), Bernstein1::from_poly_1d(&d, dom));
            let tol = 1e-9 * (1.0 + max_abs(&a.coef)) * (1.0 + max_abs(&b.coef));
            prop_assert!((a.mul(&b).eval(u) - a.eval(u) * b.eval(u)).abs() <= tol);
            prop_assert!((a.sub(&b).eval(u) - (a.eval(u) - b.eval(u))).abs() <= tol);
            prop_assert!((a.derivative().eval(u) - (a.eval((u + 1e-6).min(1.0)) - a.eval((u - 1e-6).max(0.0))) / ((u + 1e-6).min(1.0) - (u - 1e-6).max(0.0))).abs() <= 1e-4 * (1.0 + max_abs(&a.coef)));
            let (g, h) = (Bernstein3::from_poly(&p, &bx, z), Bernstein3::from_poly(&q, &bx, z));
            let tol = 1e-9 * (1.0 + max_abs(&g.coef)) * (1.0 + max_abs(&h.coef));
            prop_assert!((g.mul(&h).eval(u, 0.5, 1.0 - u) - g.eval(u, 0.5, 1.0 - u) * h.eval(u, 0.5, 1.0 - u)).abs() <= tol);
            prop_assert!((g.add(&h).eval(u, 0.5, 0.3) - (g.eval(u, 0.5, 0.3) + h.eval(u, 0.5, 0.3))).abs() <= tol);
            let dz = g.derivative(2);
            let fd = (g.eval(0.3, u, 0.5 + 1e-6) - g.eval(0.3, u, 0.5 - 1e-6)) / 2e-6;
            prop_assert!((dz.eval(0.3, u, 0.5) - fd).abs() <= 1e-4 * (1.0 + max_abs(&g.coef)));
        }
    }
}
