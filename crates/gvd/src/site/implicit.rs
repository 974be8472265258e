//! Implicit distance fields (Emiris, Mantzaflaris, Mourrain 2013, §3): the field at `q`
//! is the smallest non-negative root `z` of a polynomial `g(x, y, z)`, and 0 where
//! `g(q, ·)` has no non-negative root (the point is inside the site).
//!
//! Per box the site carries the trivariate Bernstein form of `g` over box × `T`, where
//! `T` is a `z`-interval that holds the smallest root of every point of the box (at the
//! start: `[0, R]` with `R` a Fujiwara/Cauchy-type bound of the roots of `g(D, z)` as a
//! polynomial in `z` with interval coefficients). The field bound is §3.1's: from the
//! z-envelopes `m_g(z) ≤ g ≤ M_g(z)` (min and max of the coefficients over `x, y`),
//! * the smallest root is at least the first root of the envelope that keeps the sign
//!   `g` has at the bottom of `T` (`g(q, T.lo) > 0` for all `q`: `m_g`; `< 0`: `M_g`);
//! * it is at most the first point where the *other* envelope is certified to have the
//!   opposite sign — and finding such a point proves a root exists for every `q`.
//!
//! The bound found is itself an enclosure of the smallest root, so `T` is narrowed to it
//! (two de Casteljau splits in `z`) whenever that tightens the form; children inherit
//! the form split in `x` or `y`, refreshed from the power basis when the inherited error
//! dominates.
//!
//! Two exact reductions keep degrees low: a `g` even in `z` is handled in `t = z²`
//! (`z = √t` is monotone), and a constant `shift` is added to the root (a circle of
//! radius `r` is `|q − c|² − w²` with `w = z + r`, so its field `|q − c| − r` keeps its
//! negative values inside the circle, as the Apollonius diagram needs). A closed site
//! (an ellipse) may give an `inside` polynomial: where it is negative the field is 0.

use super::DistanceField;
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::num::bernstein::{Bernstein1, Bernstein2, Bernstein3};
use crate::num::interval::{round_down, round_up};
use crate::num::poly::Poly;
use crate::num::roots;
use crate::num::Interval;

/// Relative precision of the envelope root searches.
const ROOT_WIDTH: f64 = 1e-5;
/// A form inherited by splitting is converted afresh when its error exceeds this
/// fraction of its coefficients' spread.
const REFRESH: f64 = 1e-4;
/// Depth of the search for a certified sign change of an envelope.
const SIGN_DEPTH: u32 = 18;
/// Depth and work of the search along `z` (pieces of `T`).
const Z_DEPTH: u32 = 10;
const Z_PIECES: u32 = 64;

/// A field given implicitly by `g(x, y, z)`.
#[derive(Clone, Debug)]
pub struct ImplicitField {
    /// The polynomial is in coordinates local to this point.
    origin: Point,
    /// `g` in local `x, y` and `t` (`t = z`, or `t = z²` when `squared`).
    g: Poly,
    /// `g = Σ_k coef[k](x, y) t^k`.
    coef: Vec<Poly>,
    gx: Poly,
    gy: Poly,
    gt: Poly,
    squared: bool,
    shift: f64,
    /// Where this is negative (local coordinates) the field is 0.
    inside: Option<Poly>,
    /// The field is a Euclidean distance: its gradient has norm at most 1; and `g` has a
    /// non-negative root everywhere with `g(q, 0) ≥ 0` (circles, ellipses).
    lipschitz: bool,
}

/// Where a box lies against the `inside` region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    Outside,
    Inside,
    Mixed,
}

/// The per-box state of an implicit field.
#[derive(Clone, Debug)]
pub struct ImplicitState {
    /// `g` over box × `t` (`None`: no root bound over this box, or the box is inside).
    form: Option<Bernstein3>,
    t: Interval,
    /// Every point of the box has a root in `t` (certified).
    exists: bool,
    /// `g` provably has no root in `t` anywhere in the box.
    rootless: bool,
    /// An enclosure of the smallest root (in `t`) where it exists.
    root: Interval,
    side: Side,
    /// The field bound over the box.
    bound: Interval,
}

impl ImplicitField {
    /// The field of a user-given `g(x, y, z)` (global coordinates) over `domain`;
    /// refused when `g` does not involve `z` or its roots cannot be bounded anywhere in
    /// the domain.
    pub fn new(site: usize, g: &Poly, domain: &Aabb) -> Result<Self, Error> {
        if g.degree_in(2) == 0 {
            return Err(Error::site(
                site,
                "equation",
                "an implicit field must involve z (its value is a root in z)",
            ));
        }
        let f = ImplicitField::build(Point::new(0.0, 0.0), g.clone(), 0.0, None, false);
        // the roots must be boundable somewhere: try the domain and a grid of sub-boxes
        let n = 16;
        let mut any = false;
        'grid: for i in 0..n {
            for j in 0..n {
                let sub = Aabb::new(
                    domain.at(i as f64 / n as f64, j as f64 / n as f64),
                    domain.at((i + 1) as f64 / n as f64, (j + 1) as f64 / n as f64),
                );
                if f.root_bound(&f.local(&sub)).is_some() {
                    any = true;
                    break 'grid;
                }
            }
        }
        if !any {
            return Err(Error::site(
                site,
                "equation",
                "the field has no finite value in the domain: the coefficient of the \
                 highest power of z vanishes throughout, so its roots cannot be bounded",
            ));
        }
        Ok(f)
    }

    /// A circle of radius `r ≥ 0` about `c` through the implicit path:
    /// `g = (x − cx)² + (y − cy)² − w²`, `w = z + r ≥ 0`, field `w − r`.
    pub fn circle(c: Point, r: f64) -> Self {
        let x = Poly::var(0);
        let y = Poly::var(1);
        let w = Poly::var(2);
        let g = x.mul(&x).add(&y.mul(&y)).sub(&w.mul(&w));
        ImplicitField::build(c, g, -r, None, true)
    }

    /// A field from `g` in coordinates local to `origin`, with a shift of the root and
    /// an optional inside region (both local); `lipschitz` when it is a true distance.
    pub fn local_field(
        origin: Point,
        g: Poly,
        shift: f64,
        inside: Option<Poly>,
        lipschitz: bool,
    ) -> Self {
        ImplicitField::build(origin, g, shift, inside, lipschitz)
    }

    fn build(origin: Point, g: Poly, shift: f64, inside: Option<Poly>, lipschitz: bool) -> Self {
        let squared = g.terms.iter().all(|t| t.0[2] % 2 == 0);
        let g = if squared {
            Poly::from_terms(
                g.terms
                    .iter()
                    .map(|&(e, c)| ([e[0], e[1], e[2] / 2], c))
                    .collect(),
            )
        } else {
            g
        };
        let n = g.degree_in(2) as usize;
        let mut coef = vec![Vec::new(); n + 1];
        for &(e, c) in &g.terms {
            coef[e[2] as usize].push(([e[0], e[1], 0], c));
        }
        let coef = coef.into_iter().map(Poly::from_terms).collect();
        ImplicitField {
            origin,
            gx: g.partial(0),
            gy: g.partial(1),
            gt: g.partial(2),
            g,
            coef,
            squared,
            shift,
            inside,
            lipschitz,
        }
    }

    /// Whether the polynomial is handled in `t = z²`.
    pub fn is_squared(&self) -> bool {
        self.squared
    }

    /// The degree in `t`.
    pub fn degree_t(&self) -> usize {
        self.coef.len() - 1
    }

    fn local(&self, b: &Aabb) -> Aabb {
        Aabb::new(b.min - self.origin, b.max - self.origin)
    }

    /// A bound `R` of every real root `t ≥ 0` of `g(q, t)` for `q` in the (local) box:
    /// Fujiwara's `2 max_k (|c_k| / |c_n|)^{1/(n−k)}` with interval coefficients.
    fn root_bound(&self, lb: &Aabb) -> Option<f64> {
        let z = Interval::point(0.0);
        let c: Vec<Interval> = self
            .coef
            .iter()
            .map(|p| p.eval_interval(lb.x(), lb.y(), z))
            .collect();
        let n = c.len() - 1;
        let lead = c[n];
        if !lead.excludes_zero() {
            return None;
        }
        let mig = lead.lo.abs().min(lead.hi.abs());
        let mut r: f64 = 0.0;
        for (k, ck) in c.iter().enumerate().take(n) {
            let q = round_up(ck.mag() / mig);
            let root = round_up(q.powf(1.0 / (n - k) as f64) * (1.0 + 1e-12));
            r = r.max(root);
        }
        let r = round_up(2.0 * r) + f64::MIN_POSITIVE;
        r.is_finite().then_some(r)
    }

    fn side(&self, lb: &Aabb) -> Side {
        match &self.inside {
            None => Side::Outside,
            Some(p) => {
                let r = Bernstein2::from_poly(p, lb).range();
                if r.lo > 0.0 {
                    Side::Outside
                } else if r.hi < 0.0 {
                    Side::Inside
                } else {
                    Side::Mixed
                }
            }
        }
    }

    fn inside_state(&self) -> ImplicitState {
        ImplicitState {
            form: None,
            t: Interval::point(0.0),
            exists: false,
            rootless: false,
            root: Interval::point(0.0),
            side: Side::Inside,
            bound: Interval::point(0.0),
        }
    }

    fn unbounded_state(&self, side: Side) -> ImplicitState {
        ImplicitState {
            form: None,
            t: Interval::new(0.0, f64::INFINITY),
            exists: false,
            rootless: false,
            root: Interval::new(0.0, f64::INFINITY),
            side,
            bound: Interval::new(self.shift.min(0.0), f64::INFINITY),
        }
    }

    /// Analyses `form` over box × `t`, narrowing `t` to the root enclosure while that
    /// shrinks it markedly (splitting in `z`), and caches the field bound.
    fn settle(
        &self,
        mut form: Bernstein3,
        mut t: Interval,
        mut exists: bool,
        side: Side,
        lb: &Aabb,
    ) -> ImplicitState {
        // a distance field first narrows T by its certified centre root (cheap, 1-D),
        // so that the §3.1 search below starts from a tight z-interval
        let mut lip = None;
        if self.lipschitz {
            if let Some(l) = self.lipschitz_root(lb, t) {
                let r = Interval::new(t.lo.max(l.lo), t.hi.min(l.hi));
                if r.lo <= r.hi {
                    lip = Some(r);
                    if r.width() < 0.7 * t.width() {
                        form = self.restrict(form, t, r, lb);
                        t = r;
                    }
                }
            }
        }
        let mut rounds = 0;
        loop {
            // distance fields have g(q, 0) ≥ 0 and no root below T.lo: g(q, T.lo) ≥ 0
            let info = analyse(&form, self.lipschitz);
            let Some((ulo, uhi, found)) = info else {
                // no root in t for any point of the box: the field is 0 there
                let mut s = ImplicitState {
                    form: Some(form),
                    t,
                    exists: false,
                    rootless: true,
                    root: Interval::point(0.0),
                    side,
                    bound: Interval::point(0.0),
                };
                s.bound = self.value_bound(&s);
                return s;
            };
            exists |= found;
            let w = t.width();
            let mut root = Interval::new(
                round_down(t.lo + ulo * w).max(t.lo),
                round_up(t.lo + uhi * w).min(t.hi),
            );
            if let Some(l) = lip {
                let r = Interval::new(root.lo.max(l.lo), root.hi.min(l.hi));
                if r.lo <= r.hi {
                    root = r;
                }
            }
            rounds += 1;
            if rounds <= 2 && w > 0.0 && root.width() < 0.7 * w {
                form = self.restrict(form, t, root, lb);
                t = root;
                continue;
            }
            let mut s = ImplicitState {
                form: Some(form),
                t,
                exists: exists || self.lipschitz,
                rootless: false,
                root,
                side,
                bound: Interval::point(0.0),
            };
            s.bound = self.value_bound(&s);
            return s;
        }
    }

    /// The form over box × `r` from the form over box × `t` (`r ⊆ t`): two de Casteljau
    /// splits in z, or a fresh conversion when the inherited error dominates.
    fn restrict(&self, form: Bernstein3, t: Interval, r: Interval, lb: &Aabb) -> Bernstein3 {
        let w = t.width();
        if w <= 0.0 {
            return form;
        }
        let ulo = ((r.lo - t.lo) / w).clamp(0.0, 1.0);
        let uhi = ((r.hi - t.lo) / w).clamp(ulo, 1.0);
        let mut f = form;
        if ulo > 0.0 {
            f = f.split(2, ulo).1;
        }
        if uhi < 1.0 && ulo < 1.0 {
            let rel = ((uhi - ulo) / (1.0 - ulo)).clamp(0.0, 1.0);
            f = f.split(2, rel).0;
        }
        if f.err > REFRESH * coef_spread(&f) {
            Bernstein3::from_poly(&self.g, lb, r)
        } else {
            f
        }
    }

    /// For a 1-Lipschitz root (a Euclidean distance to a curve, on both sides of it): an
    /// enclosure of the smallest root over the (local) box from a certified enclosure at
    /// the box's centre, found by the same §3.1 analysis on `g(centre, t)` over `root`
    /// (interval coefficients), widened by the half-diagonal.
    fn lipschitz_root(&self, lb: &Aabb, root: Interval) -> Option<Interval> {
        if root.width() <= 0.0 {
            return None;
        }
        let c = lb.center();
        let (px, py, p0) = (
            Interval::point(c.x),
            Interval::point(c.y),
            Interval::point(0.0),
        );
        let ck: Vec<Interval> = self
            .coef
            .iter()
            .map(|p| p.eval_interval(px, py, p0))
            .collect();
        let mids: Vec<f64> = ck.iter().map(|i| i.mid()).collect();
        let top = root.lo.abs().max(root.hi.abs());
        let mut extra = 0.0;
        for (k, i) in ck.iter().enumerate() {
            let rad = round_up((i.hi - i.mid()).max(i.mid() - i.lo));
            extra = round_up(extra + rad * round_up(top.powi(k as i32)) * (1.0 + 1e-12));
        }
        let f1 = Bernstein1::from_poly_1d(&mids, root);
        let err = round_up(f1.err + extra);
        if !err.is_finite() {
            return None;
        }
        let n = f1.coef.len() - 1;
        let b3 = Bernstein3 {
            deg: [0, 0, n],
            coef: f1.coef,
            err,
        };
        let (ulo, uhi, found) = analyse(&b3, true)?;
        if !found {
            return None;
        }
        let w = root.width();
        let tc = Interval::new(
            round_down(root.lo + ulo * w).max(root.lo),
            round_up(root.lo + uhi * w).min(root.hi),
        );
        let zc = if self.squared { tc.sqrt() } else { tc };
        let hd = round_up(0.5 * lb.width().hypot(lb.height()) * (1.0 + 1e-12));
        let z = Interval::new(round_down(zc.lo - hd).max(0.0), round_up(zc.hi + hd));
        Some(if self.squared { z.sqr() } else { z })
    }

    /// The field bound of a settled state.
    fn value_bound(&self, s: &ImplicitState) -> Interval {
        if s.side == Side::Inside || s.rootless {
            return Interval::point(0.0);
        }
        let root = if self.squared { s.root.sqrt() } else { s.root };
        // slack for the relative ↔ absolute mapping of z (a few ulps of |T|)
        let slack = 1e-12 * (s.t.hi.abs() + s.t.lo.abs()) + f64::MIN_POSITIVE;
        let mut v = (root + Interval::new(-slack, slack)) + self.shift;
        if !s.exists || s.side == Side::Mixed {
            v = v.hull(Interval::point(0.0));
        }
        v
    }

    /// The smallest non-negative root in `t` of `g(q, t)`, if any.
    pub fn root_at(&self, q: Point) -> Option<f64> {
        let u = q - self.origin;
        let c: Vec<f64> = self.coef.iter().map(|p| p.eval(u.x, u.y, 0.0)).collect();
        smallest_nonneg_root(&c)
    }

    /// Central differences of the value (where `g_z` vanishes).
    fn finite_difference(&self, q: Point) -> Point {
        let h = 1e-7 * (1.0 + q.x.abs().max(q.y.abs()));
        let dx = Point::new(h, 0.0);
        let dy = Point::new(0.0, h);
        let d = Point::new(
            (self.value(q + dx) - self.value(q - dx)) / (2.0 * h),
            (self.value(q + dy) - self.value(q - dy)) / (2.0 * h),
        );
        if d.x.is_finite() && d.y.is_finite() {
            d
        } else {
            Point::new(0.0, 0.0)
        }
    }
}

impl DistanceField for ImplicitField {
    type State = ImplicitState;

    /// The state of box `b` from scratch.
    fn state(&self, b: &Aabb) -> ImplicitState {
        let lb = self.local(b);
        let side = self.side(&lb);
        if side == Side::Inside {
            return self.inside_state();
        }
        let Some(r) = self.root_bound(&lb) else {
            return self.unbounded_state(side);
        };
        let t = Interval::new(0.0, r);
        let form = Bernstein3::from_poly(&self.g, &lb, t);
        self.settle(form, t, false, side, &lb)
    }

    /// The halves of a state split at `at` along `axis`.
    fn split(
        &self,
        s: &ImplicitState,
        b: &Aabb,
        axis: crate::geom::Axis,
        at: f64,
    ) -> (ImplicitState, ImplicitState) {
        let (lb, rb) = b.split(axis, at);
        let Some(form) = &s.form else {
            if s.side == Side::Inside {
                return (s.clone(), s.clone());
            }
            return (self.state(&lb), self.state(&rb));
        };
        let (ax, len, from) = match axis {
            crate::geom::Axis::X => (0, b.width(), b.min.x),
            crate::geom::Axis::Y => (1, b.height(), b.min.y),
        };
        if len <= 0.0 {
            return (self.state(&lb), self.state(&rb));
        }
        let rel = ((at - from) / len).clamp(0.0, 1.0);
        let (fl, fr) = form.split(ax, rel);
        let child = |f: Bernstein3, cb: &Aabb| {
            let llb = self.local(cb);
            let side = if s.side == Side::Mixed {
                self.side(&llb)
            } else {
                s.side
            };
            if side == Side::Inside {
                return self.inside_state();
            }
            if s.rootless {
                // no root in t over the parent: none over the child either
                return ImplicitState {
                    form: Some(f),
                    side,
                    ..s.clone()
                };
            }
            let f = if f.err > REFRESH * coef_spread(&f) {
                Bernstein3::from_poly(&self.g, &llb, s.t)
            } else {
                f
            };
            self.settle(f, s.t, s.exists, side, &llb)
        };
        (child(fl, &lb), child(fr, &rb))
    }

    fn bound(&self, s: &ImplicitState, _: &Aabb) -> Interval {
        s.bound
    }

    /// `∇f = −∇_xy g / g_z` over the box, from the derivative forms over box × `T`.
    fn gradient_bound(&self, s: &ImplicitState, b: &Aabb) -> Option<[Interval; 2]> {
        let zero = Interval::point(0.0);
        let unit = Interval::new(-1.0, 1.0);
        let fallback = || self.lipschitz.then_some([unit, unit]);
        if s.side == Side::Inside || s.rootless {
            return Some([zero, zero]);
        }
        let Some(form) = &s.form else {
            return fallback();
        };
        let tw = s.t.width();
        let (w, h) = (b.width(), b.height());
        if tw <= 0.0 {
            return fallback();
        }
        let gt = form.derivative(2).range().scale(1.0 / tw);
        let per = |axis: usize, len: f64| -> Option<Interval> {
            if len <= 0.0 {
                return None;
            }
            let ga = form.derivative(axis).range().scale(1.0 / len);
            let dt = (-ga).div(gt)?;
            if self.squared {
                // dz/dx = (dt/dx) / (2 √t)
                let z2 = s.root.sqrt().scale(2.0);
                dt.div(z2)
            } else {
                Some(dt)
            }
        };
        let mut g = [zero, zero];
        for (k, len) in [(0usize, w), (1usize, h)] {
            g[k] = match per(k, len) {
                Some(v) => v,
                None if self.lipschitz => unit,
                None => Interval::new(f64::NEG_INFINITY, f64::INFINITY),
            };
            if !s.exists || s.side == Side::Mixed {
                g[k] = g[k].hull(zero);
            }
            if self.lipschitz {
                g[k] = Interval::new(g[k].lo.max(-1.0), g[k].hi.min(1.0));
            }
        }
        Some(g)
    }

    fn value(&self, q: Point) -> f64 {
        if let Some(p) = &self.inside {
            let u = q - self.origin;
            if p.eval(u.x, u.y, 0.0) < 0.0 {
                return 0.0;
            }
        }
        match self.root_at(q) {
            None => 0.0,
            Some(t) => {
                let z = if self.squared { t.max(0.0).sqrt() } else { t };
                z + self.shift
            }
        }
    }

    fn gradient(&self, q: Point) -> Point {
        if let Some(p) = &self.inside {
            let u = q - self.origin;
            if p.eval(u.x, u.y, 0.0) < 0.0 {
                return Point::new(0.0, 0.0);
            }
        }
        let Some(t) = self.root_at(q) else {
            return Point::new(0.0, 0.0);
        };
        let u = q - self.origin;
        let gt = self.gt.eval(u.x, u.y, t);
        let gx = self.gx.eval(u.x, u.y, t);
        let gy = self.gy.eval(u.x, u.y, t);
        let mut d = Point::new(-gx / gt, -gy / gt);
        if self.squared {
            let z = t.max(0.0).sqrt();
            d = d * (0.5 / z);
        }
        if d.x.is_finite() && d.y.is_finite() {
            d
        } else {
            self.finite_difference(q)
        }
    }
}

/// The largest distance between two coefficients (the scale of the form's values).
fn coef_spread(f: &Bernstein3) -> f64 {
    let (lo, hi) = f
        .coef
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &c| {
            (l.min(c), h.max(c))
        });
    (hi - lo).max(f64::MIN_POSITIVE)
}

/// §3.1 on a form over box × `T` (relative `u ∈ [0,1]` along `T`): `None` when no point
/// of the box has a root in `T`; else `(lo, hi, found)` with every smallest root in
/// `[lo, hi]` and `found` when a root is proved for every point of the box.
///
/// `nonneg_bottom`: `g ≥ 0` is known at the bottom of `T` for every point (a weak sign,
/// enough for the upper bound). The search splits `T` (de Casteljau in `z`) from the
/// bottom up: a piece where the envelope that keeps the bottom sign cannot vanish is
/// skipped; the first piece where it can gives the lower bound; the first point where the
/// other envelope is certified to have the opposite sign gives the upper bound. Splitting
/// tightens both envelopes (the z control polygon converges to the polynomial).
fn analyse(form: &Bernstein3, nonneg_bottom: bool) -> Option<(f64, f64, bool)> {
    let (m, big) = form.z_envelopes();
    let sign0 = if m.coef[0] > 0.0 || nonneg_bottom {
        1.0
    } else if big.coef[0] < 0.0 {
        -1.0
    } else {
        return Some((0.0, 1.0, false));
    };
    // envelopes of σ·g: `low` keeps the bottom sign, `high` must turn non-positive
    let oriented = |f: &Bernstein3| {
        let (m, big) = f.z_envelopes();
        if sign0 > 0.0 {
            (m, big)
        } else {
            let neg = |b: Bernstein1| Bernstein1 {
                coef: b.coef.iter().map(|c| -c).collect(),
                err: b.err,
            };
            (neg(big), neg(m))
        }
    };
    let mut lower: Option<f64> = None;
    let mut stack = vec![(form.clone(), 0.0f64, 1.0f64, 0u32)];
    let mut pieces = 0;
    while let Some((f, lo, hi, depth)) = stack.pop() {
        pieces += 1;
        let (low, high) = oriented(&f);
        if low.coef.iter().all(|&c| c > 0.0) {
            continue; // σ·g > 0 on the whole piece for every point
        }
        let w = hi - lo;
        if lower.is_none() {
            // where `low ≤ 0` already at the piece's bottom nothing is excluded; else
            // `low > 0` up to its first root (none: positive on the whole piece)
            let r = if low.coef[0] > 0.0 {
                match roots::first_root(&low, ROOT_WIDTH) {
                    Some(r) => r,
                    None => continue,
                }
            } else {
                0.0
            };
            lower = Some(lo + r * w);
        }
        if let Some(u) = first_nonpositive(&high) {
            let l = lower.unwrap_or(lo);
            return Some((l, (lo + u * w).max(l), true));
        }
        if depth < Z_DEPTH && pieces < Z_PIECES {
            let (a, b) = f.split(2, 0.5);
            let mid = lo + 0.5 * w;
            stack.push((b, mid, hi, depth + 1));
            stack.push((a, lo, mid, depth + 1));
        }
    }
    lower.map(|l| (l, 1.0, false))
}

/// The first `u ∈ [0, 1]` (to about `2^-SIGN_DEPTH`) at which `b ≤ 0` is certified, by a
/// depth-first search from the left; `None` when no such point is found.
fn first_nonpositive(b: &Bernstein1) -> Option<f64> {
    let mut stack = vec![(b.clone(), 0.0f64, 1.0f64, 0u32)];
    let mut pieces = 0;
    while let Some((f, lo, hi, depth)) = stack.pop() {
        pieces += 1;
        if pieces > 4096 {
            return None;
        }
        let err = f.err;
        if f.coef.iter().all(|&c| c > err) {
            continue; // positive on the whole piece
        }
        if f.coef[0] + err <= 0.0 {
            return Some(lo);
        }
        let last = f.coef[f.coef.len() - 1];
        if depth >= SIGN_DEPTH {
            if last + err <= 0.0 {
                return Some(hi);
            }
            continue;
        }
        let (l, r) = f.split(0.5);
        let mid = 0.5 * (lo + hi);
        stack.push((r, mid, hi, depth + 1));
        stack.push((l, lo, mid, depth + 1));
    }
    None
}

/// The smallest real root `t ≥ 0` of `Σ c[k] t^k` (`Some(0)` for the zero polynomial,
/// `None` when there is none): closed forms up to degree 2, certified Bernstein
/// isolation on `[0, R]` above, then refinement.
pub fn smallest_nonneg_root(c: &[f64]) -> Option<f64> {
    if c.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let mut n = c.len();
    while n > 0 && c[n - 1] == 0.0 {
        n -= 1;
    }
    if n == 0 || c[0] == 0.0 {
        return Some(0.0);
    }
    let c = &c[..n];
    match n - 1 {
        0 => None,
        1 => {
            let r = -c[0] / c[1];
            (r >= 0.0).then_some(r)
        }
        2 => {
            let (a, b, cc) = (c[2], c[1], c[0]);
            let mut disc = b * b - 4.0 * a * cc;
            if disc < 0.0 {
                if disc >= -1e-14 * (b * b + (4.0 * a * cc).abs()) {
                    disc = 0.0;
                } else {
                    return None;
                }
            }
            let sq = disc.sqrt();
            let q = -0.5 * (b + if b >= 0.0 { sq } else { -sq });
            let (r1, r2) = if q != 0.0 {
                (q / a, cc / q)
            } else {
                (-b / (2.0 * a), -b / (2.0 * a))
            };
            let (s, l) = (r1.min(r2), r1.max(r2));
            if s >= 0.0 {
                Some(s)
            } else if l >= 0.0 {
                Some(l)
            } else {
                None
            }
        }
        _ => general_root(c),
    }
}

fn horner(c: &[f64], t: f64) -> (f64, f64) {
    let (mut p, mut d) = (0.0, 0.0);
    for &a in c.iter().rev() {
        d = d * t + p;
        p = p * t + a;
    }
    (p, d)
}

fn general_root(c: &[f64]) -> Option<f64> {
    let n = c.len() - 1;
    let lead = c[n].abs();
    let mut r: f64 = 0.0;
    for (k, ck) in c.iter().enumerate().take(n) {
        r = r.max((ck.abs() / lead).powf(1.0 / (n - k) as f64));
    }
    let big = (2.0 * r * (1.0 + 1e-9)).max(f64::MIN_POSITIVE);
    if !big.is_finite() {
        return None;
    }
    let b = Bernstein1::from_poly_1d(c, Interval::new(0.0, big));
    let scale = |t: f64| -> f64 {
        c.iter()
            .enumerate()
            .map(|(k, a)| a.abs() * t.powi(k as i32))
            .sum()
    };
    for iv in roots::isolate(&b, 1e-15) {
        let (lo, hi) = (iv.lo * big, iv.hi * big);
        let (plo, _) = horner(c, lo);
        let (phi, _) = horner(c, hi);
        let t = if plo == 0.0 {
            lo
        } else if phi == 0.0 {
            hi
        } else if (plo > 0.0) != (phi > 0.0) {
            bisect(c, lo, hi, plo)
        } else if iv.certified {
            // one root proved, but the end signs are within rounding: refine on the form
            roots::refine(&b, iv.lo, iv.hi) * big
        } else {
            // no sign change: a (near-)double root or nothing
            let mid = 0.5 * (lo + hi);
            let (pm, _) = horner(c, mid);
            if pm.abs() <= 1e-10 * scale(mid) {
                mid
            } else {
                continue;
            }
        };
        return Some(polish(c, t, lo, hi).max(0.0));
    }
    None
}

fn bisect(c: &[f64], mut lo: f64, mut hi: f64, mut plo: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let (pm, _) = horner(c, mid);
        if pm == 0.0 {
            return mid;
        }
        if (pm > 0.0) == (plo > 0.0) {
            lo = mid;
            plo = pm;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// A few Newton steps kept inside `[lo, hi]`, keeping the best iterate.
fn polish(c: &[f64], mut t: f64, lo: f64, hi: f64) -> f64 {
    let (mut best, mut best_p) = (t, horner(c, t).0.abs());
    for _ in 0..4 {
        let (p, d) = horner(c, t);
        if d == 0.0 || !d.is_finite() {
            break;
        }
        let next = t - p / d;
        if !(lo..=hi).contains(&next) {
            break;
        }
        t = next;
        let pn = horner(c, t).0.abs();
        if pn < best_p {
            best = t;
            best_p = pn;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_of_small_polynomials() {
        assert_eq!(smallest_nonneg_root(&[-1.0, 1.0]), Some(1.0));
        assert_eq!(smallest_nonneg_root(&[1.0, 1.0]), None);
        assert_eq!(smallest_nonneg_root(&[0.0, 1.0, 1.0]), Some(0.0));
        // (t − 1)(t − 2)(t − 3)
        let r = smallest_nonneg_root(&[-6.0, 11.0, -6.0, 1.0]).unwrap();
        assert!((r - 1.0).abs() < 1e-14, "{r}");
        // (t + 1)(t − 0.25)(t − 5)(t² + 1)
        let mut c = vec![0.0; 6];
        // (t + 1)(t − 0.25)(t − 5) = t³ − 4.25 t² − 4 t + 1.25, times (t² + 1)
        let cubic = [1.25, -4.0, -4.25, 1.0];
        for (i, a) in cubic.iter().enumerate() {
            c[i] += a;
            c[i + 2] += a;
        }
        let r = smallest_nonneg_root(&c).unwrap();
        assert!((r - 0.25).abs() < 1e-13, "{r}");
        // no non-negative root: (t + 1)(t + 2)(t + 3)
        assert_eq!(smallest_nonneg_root(&[6.0, 11.0, 6.0, 1.0]), None);
        // double root at 0.5: (t − 0.5)² (t + 1)
        let r = smallest_nonneg_root(&[0.25, -0.75, 0.0, 1.0]).unwrap();
        assert!((r - 0.5).abs() < 1e-6, "{r}");
    }
}
