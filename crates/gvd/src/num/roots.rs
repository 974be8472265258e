//! Certified real root isolation: univariate Bernstein forms on `[0, 1]` ([`isolate`]),
//! and square systems of two bivariate polynomials over a box ([`solve_system`],
//! subdivision with Bernstein exclusion and the Krawczyk test; its own section below).
//!
//! **Univariate.** //! Subdivision (at midpoints, or at `3/8`, `5/8` when the midpoint value is within
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

use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::{Bernstein1, Bernstein2};
use crate::num::poly::Poly;
use crate::num::Interval;

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

/// The forms of the pieces done with, whose allocations the next splits reuse.
#[derive(Default)]
struct Spare(Vec<Bernstein1>);

impl Spare {
    fn take(&mut self) -> Bernstein1 {
        self.0
            .pop()
            .unwrap_or_else(|| Bernstein1::exact(Vec::new()))
    }

    fn keep(&mut self, p: Piece) {
        self.0.push(p.f);
    }
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
    /// as the ends stay exact. `None` when the piece is too short to split exactly. The
    /// values at `3/8`, `5/8` are those the splits there would give (the same de Casteljau
    /// steps): only the split taken is formed.
    fn split(&self, spare: &mut Spare) -> Option<(Piece, Piece)> {
        let len = self.hi - self.lo;
        if len & 1 != 0 {
            return None;
        }
        let near_zero = |value: f64, err: f64| value.abs() <= err;
        let (mut l, mut r) = (spare.take(), spare.take());
        self.f.split_into(0.5, &mut l, &mut r);
        let mut at = self.lo + len / 2;
        if near_zero(r.coef[0], r.err) && len & 7 == 0 {
            let err = r.err;
            if let Some(k) = [3, 5]
                .into_iter()
                .find(|&k| !near_zero(self.f.eval(k as f64 / 8.0), err))
            {
                self.f.split_into(k as f64 / 8.0, &mut l, &mut r);
                at = self.lo + len / 8 * k;
            }
        }
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
    let mut spare = Spare::default();
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
            Verdict::Unknown if p.hi - p.lo <= min_len => emit(p.lo, p.hi, false),
            Verdict::Unknown => match p.split(&mut spare) {
                Some((l, r)) => {
                    stack.push(r);
                    stack.push(l);
                }
                None => emit(p.lo, p.hi, false),
            },
        }
        spare.keep(p);
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
    let mut spare = Spare::default();
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
            Verdict::Excluded => {}
            Verdict::Flat => return Some(end(&p)),
            _ if pieces > MAX_PIECES || p.hi - p.lo <= min_len => return Some(end(&p)),
            _ => match p.split(&mut spare) {
                Some((l, r)) => {
                    let (near, far) = if from_right { (r, l) } else { (l, r) };
                    stack.push(far);
                    stack.push(near);
                }
                None => return Some(end(&p)),
            },
        }
        spare.keep(p);
    }
    None
}

/// The values of `b` at `lo` and `hi` when they change sign; else the answer of the
/// refinements: an end where `b` is zero, or the end with the smaller `|b|`.
fn bracket(b: &Bernstein1, lo: f64, hi: f64) -> Result<(f64, f64), f64> {
    let (flo, fhi) = (b.eval(lo), b.eval(hi));
    if flo == 0.0 {
        return Err(lo);
    }
    if fhi == 0.0 {
        return Err(hi);
    }
    if (flo > 0.0) == (fhi > 0.0) || flo.is_nan() || fhi.is_nan() {
        return Err(if flo.abs() <= fhi.abs() { lo } else { hi });
    }
    Ok((flo, fhi))
}

/// Refines a root bracketed by a sign change of `b` on `[lo, hi]` by bisection to full
/// f64 precision (f64 evaluation, not certified). Without a sign change at the ends,
/// returns the end with the smaller `|b|`.
pub fn refine(b: &Bernstein1, mut lo: f64, mut hi: f64) -> f64 {
    let (mut flo, _) = match bracket(b, lo, hi) {
        Ok(values) => values,
        Err(end) => return end,
    };
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

/// The root bracketed by a sign change of `b` on `[lo, hi]`, as [`refine`] finds it, by
/// Newton's method kept inside the bracket (Press et al., `rtsafe`): each value's sign
/// narrows the bracket, and a step that would leave it, or that would not at least halve
/// the step before last, is a bisection instead. At a simple root it converges
/// quadratically, a handful of evaluations against bisection's fifty; it stops where a
/// step no longer moves the iterate (within rounding of the root) or the bracket is two
/// adjacent floats. Not certified; without a sign change at the ends, as [`refine`].
pub fn refine_by_newton(b: &Bernstein1, mut lo: f64, mut hi: f64) -> f64 {
    let (_, fhi) = match bracket(b, lo, hi) {
        Ok(values) => values,
        Err(end) => return end,
    };
    let rising = fhi > 0.0;
    let mut x = 0.5 * (lo + hi);
    let (mut step, mut step_before) = (hi - lo, hi - lo);
    for _ in 0..256 {
        let (f, slope) = b.value_and_slope(x);
        if f == 0.0 || f.is_nan() {
            return x;
        }
        if (f > 0.0) == rising {
            hi = x;
        } else {
            lo = x;
        }
        let newton = x - f / slope;
        if newton == x {
            // the step is below rounding: `x` is the root to within an ulp (the step
            // would otherwise fall on the bracket's end `x` and bisect the bracket on)
            return x;
        }
        let next = if newton > lo && newton < hi && (2.0 * f).abs() <= (step_before * slope).abs() {
            newton
        } else {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                return x;
            }
            mid
        };
        (step_before, step) = (step, next - x);
        if next == x {
            return x;
        }
        x = next;
    }
    x
}

// ---------------------------------------------------------------------------------------
// Square systems of two bivariate polynomials: subdivision + Krawczyk.

/// Options of [`solve_system`].
#[derive(Clone, Copy, Debug)]
pub struct SystemOptions {
    /// Boxes whose longest side is at most this are not split further: what survives
    /// there is reported as an uncertified cluster.
    pub min_size: f64,
    /// Largest number of boxes examined; the boxes left unexplored when it is reached
    /// are reported as uncertified clusters, so every call terminates quickly.
    pub max_boxes: usize,
    /// How far `f` and `g` themselves may be from the exact system (e.g. the rounding in
    /// forming them), if known: a box over which both stay within that of 0 cannot be
    /// decided at this precision and is reported unresolved without being split (no
    /// sub-box could be excluded by their ranges either).
    pub noise: Option<[f64; 2]>,
    /// Units of the two variables: a box is split across the side longest in these
    /// (e.g. the lengths of two curves each variable parameterizes, so that boxes are
    /// about square in the plane of the curves).
    pub units: [f64; 2],
}

impl SystemOptions {
    /// `min_size` a millionth of the domain's longest side, at most `2¹⁶` boxes.
    pub fn for_domain(domain: &Aabb) -> Self {
        SystemOptions {
            min_size: 1e-6 * domain.longest_side(),
            max_boxes: 1 << 16,
            noise: None,
            units: [1.0, 1.0],
        }
    }
}

/// A region of the plane holding solutions of a system (see [`solve_system`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SystemRoot {
    /// Every solution this entry stands for lies in this box.
    pub enclosure: Aabb,
    /// True: exactly one solution in `enclosure`, a simple one (nonsingular Jacobian),
    /// proved by the Krawczyk test. False: a cluster of boxes that could be neither
    /// excluded nor certified (no solution, several, or a singular one such as a
    /// tangency); the cluster is the hull of the boxes.
    pub certified: bool,
    /// The solution refined by Newton's method (certified roots), or the point of the
    /// cluster with the smallest residual found (f64, not certified).
    pub point: Point,
}

/// A box of [`solve_systems`]: the forms over `b` of `f` and the side conditions, and
/// per system the form of its `g` (`None` once that system is done with the box).
struct SystemBox {
    b: Aabb,
    shared: Vec<Bernstein2>,
    own: Vec<Option<Bernstein2>>,
}

/// One system `f = g = 0` of [`solve_systems`]: its `g`, Jacobian and findings.
struct Run<'a> {
    g: &'a Poly,
    opts: SystemOptions,
    jacobian: [Poly; 4],
    /// (uniqueness region, enclosure K, refined point)
    certified: Vec<(Aabb, Aabb, Point)>,
    unresolved: Vec<Aabb>,
    boxes: usize,
}

/// Solves `f = g = 0` in `domain`, with optional `side` conditions (polynomials that
/// must also vanish at the solutions sought, used only to exclude boxes: e.g. `f` for
/// the singular points `f = f_x = f_y = 0`, solved as the square system `f_x = f_y = 0`).
///
/// Subdivision in halves along the longer side (in [`SystemOptions::units`]). A box is
/// **excluded** when the Bernstein range of one polynomial over it excludes 0
/// (convex-hull property; the forms
/// are computed over the domain from `Poly`, and a box's halves get them by de Casteljau
/// at `1/2` when its midpoint is exact in f64, else from `Poly` again, so they always
/// stand for the f64 box, with rounding in their error bounds). A box is
/// **certified** by the Krawczyk operator
/// `K(X) = m − Y·F(m) + (I − Y·J(X))·(X − m)` with `m` the centre, `J(X)` an interval
/// Jacobian (ranges of the derivatives of the Bernstein forms of `f` and `g` over `X`)
/// and `Y ≈ J(m)⁻¹`:
/// `K(X) ⊂ int X` proves a unique, simple root in `X` (Krawczyk 1969; Moore), and
/// `K(X) ∩ X = ∅` proves none. The test runs on `X` inflated by a quarter around its
/// centre, so roots on a box side are certified too; duplicates found from neighbouring
/// boxes are merged (a certified enclosure inside another's uniqueness region is the
/// same root). A certified enclosure is then contracted (`X ← K(X) ∩ X`) and dropped
/// when a side condition excludes 0 over it; otherwise the side conditions are not
/// decided there (their zero is a measure-zero condition no interval test proves).
/// Boxes reaching `min_size` unresolved, or where both polynomials are lost in their
/// noise ([`SystemOptions::noise`]), are merged into clusters of touching boxes.
/// No solution is ever lost: a box is dropped only when excluded.
pub fn solve_system(
    f: &Poly,
    g: &Poly,
    side: &[Poly],
    domain: &Aabb,
    opts: &SystemOptions,
) -> Vec<SystemRoot> {
    solve_systems(
        f,
        std::slice::from_ref(g),
        side,
        domain,
        std::slice::from_ref(opts),
    )
    .pop()
    .unwrap_or_default()
}

/// [`solve_system`] for `f = g = 0` with each `g` of `gs` and its options in `opts`, in
/// one subdivision: the forms of `f` and of the side conditions are split once for all
/// the systems (and `f`'s over a box's Krawczyk region converted once), each system
/// following its own boxes in the same order, so that every answer is the one
/// [`solve_system`] gives. The systems' boxes are split alike: their options must have
/// the same [`SystemOptions::units`].
pub fn solve_systems(
    f: &Poly,
    gs: &[Poly],
    side: &[Poly],
    domain: &Aabb,
    opts: &[SystemOptions],
) -> Vec<Vec<SystemRoot>> {
    assert_eq!(gs.len(), opts.len(), "one set of options per system");
    let Some(first) = opts.first() else {
        return Vec::new();
    };
    assert!(
        opts.iter().all(|o| o.units == first.units),
        "the systems must split their boxes alike"
    );
    let (fx, fy) = (f.partial(0), f.partial(1));
    let mut runs: Vec<Run> = gs
        .iter()
        .zip(opts)
        .map(|(g, &opts)| Run {
            g,
            opts,
            jacobian: [fx.clone(), fy.clone(), g.partial(0), g.partial(1)],
            certified: Vec::new(),
            unresolved: Vec::new(),
            boxes: 0,
        })
        .collect();
    let shared: Vec<&Poly> = std::iter::once(f).chain(side).collect();
    let make = |b: Aabb, live: &[bool]| SystemBox {
        shared: shared
            .iter()
            .map(|p| Bernstein2::from_poly(p, &b))
            .collect(),
        own: gs
            .iter()
            .zip(live)
            .map(|(g, &l)| l.then(|| Bernstein2::from_poly(g, &b)))
            .collect(),
        b,
    };
    let units = if first.units.iter().all(|u| u.is_finite() && *u > 0.0) {
        first.units
    } else {
        [1.0, 1.0]
    };
    let mut stack = vec![make(*domain, &vec![true; gs.len()])];
    let mut split_for = vec![false; gs.len()];
    while let Some(sb) = stack.pop() {
        let excluded = sb.shared.iter().any(|form| form.range().excludes_zero());
        let axis = if sb.b.width() * units[0] >= sb.b.height() * units[1] {
            Axis::X
        } else {
            Axis::Y
        };
        let ends = match axis {
            Axis::X => (sb.b.min.x, sb.b.max.x),
            Axis::Y => (sb.b.min.y, sb.b.max.y),
        };
        let at = 0.5 * (ends.0 + ends.1);
        let x = inflate(&sb.b, 0.25);
        // `f`'s form over `x`, converted at most once for all the systems
        let mut f_over_x: Option<Bernstein2> = None;
        for ((run, own), split) in runs.iter_mut().zip(&sb.own).zip(&mut split_for) {
            *split = false;
            let Some(g_form) = own else { continue };
            run.boxes += 1;
            if excluded || g_form.range().excludes_zero() {
                continue;
            }
            let forms = [&sb.shared[0], g_form];
            if run.boxes > run.opts.max_boxes || below_noise(forms, run.opts.noise) {
                run.unresolved.push(sb.b);
                continue;
            }
            let system = [f, run.g];
            let outcome = if may_contract(forms, &sb.b) {
                krawczyk(
                    system,
                    &run.jacobian,
                    &x,
                    Some((forms, &sb.b)),
                    &mut f_over_x,
                )
            } else {
                Krawczyk::Unknown
            };
            match outcome {
                Krawczyk::Unique { region, enclosure } => {
                    let enclosure = contract(system, &run.jacobian, enclosure);
                    let excluded = side
                        .iter()
                        .any(|p| Bernstein2::from_poly(p, &enclosure).range().excludes_zero());
                    if !excluded && enclosure.intersection(&sb.b).is_some() {
                        let p = newton_refine(system, &run.jacobian, &enclosure);
                        run.certified.push((region, enclosure, p));
                    }
                    continue;
                }
                Krawczyk::NoRoot => continue,
                Krawczyk::Unknown => {}
            }
            if sb.b.longest_side() <= run.opts.min_size || !(ends.0 < at && at < ends.1) {
                // too small, or no room left in f64
                run.unresolved.push(sb.b);
                continue;
            }
            *split = true;
        }
        if !split_for.contains(&true) {
            continue;
        }
        let (lo, hi) = sb.b.split(axis, at);
        if exact_midpoint(ends.0, ends.1) {
            let (l, h): (Vec<_>, Vec<_>) = sb.shared.iter().map(|f| f.split(axis, 0.5)).unzip();
            let (mut own_l, mut own_h) = (Vec::new(), Vec::new());
            for (own, &split) in sb.own.iter().zip(&split_for) {
                let halves = own.as_ref().filter(|_| split).map(|g| g.split(axis, 0.5));
                let (gl, gh) = halves.unzip();
                own_l.push(gl);
                own_h.push(gh);
            }
            stack.push(SystemBox {
                b: hi,
                shared: h,
                own: own_h,
            });
            stack.push(SystemBox {
                b: lo,
                shared: l,
                own: own_l,
            });
        } else {
            stack.push(make(hi, &split_for));
            stack.push(make(lo, &split_for));
        }
    }
    runs.into_iter().map(|run| run.roots(f)).collect()
}

impl Run<'_> {
    /// The certified roots without duplicates, then the clusters of unresolved boxes.
    fn roots(self, f: &Poly) -> Vec<SystemRoot> {
        let system = [f, self.g];
        let mut out: Vec<SystemRoot> = Vec::new();
        for (k, &(_, enclosure, point)) in self.certified.iter().enumerate() {
            let duplicate = self.certified[..k].iter().any(|(region, e, p)| {
                region.contains_box(&enclosure) || (e.contains(point) && enclosure.contains(*p))
            });
            if !duplicate {
                out.push(SystemRoot {
                    enclosure,
                    certified: true,
                    point,
                });
            }
        }
        for cluster in crate::geom::clusters(self.unresolved) {
            let point = best_point(system, &self.jacobian, &cluster);
            out.push(SystemRoot {
                enclosure: cluster,
                certified: false,
                point,
            });
        }
        out
    }
}

/// True when `f` and `g` (the first two forms) are both within `noise` (plus their own
/// rounding) of 0 over the whole box: see [`SystemOptions::noise`].
fn below_noise(forms: [&Bernstein2; 2], noise: Option<[f64; 2]>) -> bool {
    noise.is_some_and(|noise| {
        forms
            .iter()
            .zip(noise)
            .all(|(form, n)| form.within_of_zero(n))
    })
}

/// A cheap screen before the Krawczyk test over `X ⊇ b`, from the forms of `f` and `g`
/// over `b` (no conversion from `Poly`): with `J(b)` the Bernstein ranges of the
/// Jacobian and `Y` the inverse of its midpoint, `K(X) ⊂ int X` needs about
/// `Σ_c |δ_rc − (Y J)_rc| rad_c < rad_r` for both rows, which the wider `J(X)` only
/// makes harder. A box failing it is split without the test: that costs boxes, never
/// roots.
fn may_contract(forms: [&Bernstein2; 2], b: &Aabb) -> bool {
    let (w, h) = (b.width(), b.height());
    if !(w > 0.0 && h > 0.0) {
        return true;
    }
    let partial = |k: usize, axis: Axis, len: f64| {
        let r = forms[k].derivative_range(axis);
        Interval::new(r.lo / len, r.hi / len)
    };
    let j = [
        partial(0, Axis::X, w),
        partial(0, Axis::Y, h),
        partial(1, Axis::X, w),
        partial(1, Axis::Y, h),
    ];
    let jm = j.map(|i| i.mid());
    let det = jm[0] * jm[3] - jm[1] * jm[2];
    if !(det.is_finite() && det != 0.0) {
        return false;
    }
    let y = [jm[3] / det, -jm[1] / det, -jm[2] / det, jm[0] / det];
    let rad = [0.5 * w, 0.5 * h];
    (0..2).all(|r| {
        let spread: f64 = (0..2)
            .map(|c| {
                let yj =
                    j[c] * Interval::point(y[2 * r]) + j[2 + c] * Interval::point(y[2 * r + 1]);
                let delta = if r == c { 1.0 } else { 0.0 };
                (Interval::point(delta) - yj).mag() * rad[c]
            })
            .sum();
        spread < rad[r]
    })
}

/// True when `(a + b) / 2` is the exact midpoint of `[a, b]`: the sum rounds to
/// nothing (Knuth's TwoSum error term vanishes) and stays finite.
fn exact_midpoint(a: f64, b: f64) -> bool {
    let s = a + b;
    let bb = s - a;
    s.is_finite() && (a - (s - bb)) + (b - bb) == 0.0
}

enum Krawczyk {
    /// A unique simple root in `region`, lying in `enclosure ⊂ region`.
    Unique {
        region: Aabb,
        enclosure: Aabb,
    },
    NoRoot,
    Unknown,
}

/// The Krawczyk test of the system over `x` (see [`solve_system`]). With `screen`, the
/// forms of `f` and `g` over a box `b ⊆ x`, first, without converting anything, the
/// operator with the Jacobian's inner intervals from those forms ([`inner_jacobian`]):
/// that image lies inside the test's own `K(X)` (interval arithmetic is inclusion
/// monotone), so when it already sticks out of `int X` and meets `X`, `K(X)` does too and
/// the test can only answer `Unknown`: it is not run.
fn krawczyk(
    system: [&Poly; 2],
    jacobian: &[Poly; 4],
    x: &Aabb,
    screen: Option<([&Bernstein2; 2], &Aabb)>,
    f_over_x: &mut Option<Bernstein2>,
) -> Krawczyk {
    let Some(centre) = KrawczykCentre::new(system, jacobian, x) else {
        return Krawczyk::Unknown;
    };
    let undecided = |k: &Aabb| !strictly_inside(k, x) && k.intersection(x).is_some();
    let inner = screen.and_then(|(forms, b)| centre.image(x, &inner_jacobian(forms, b)?));
    if inner.is_some_and(|k| undecided(&k)) {
        return Krawczyk::Unknown;
    }
    let Some(kb) =
        interval_jacobian(system, jacobian, x, f_over_x).and_then(|j| centre.image(x, &j))
    else {
        return Krawczyk::Unknown;
    };
    if strictly_inside(&kb, x) {
        Krawczyk::Unique {
            region: *x,
            enclosure: kb,
        }
    } else if kb.intersection(x).is_none() {
        Krawczyk::NoRoot
    } else {
        Krawczyk::Unknown
    }
}

/// True when `k` lies in the interior of `x`.
fn strictly_inside(k: &Aabb, x: &Aabb) -> bool {
    k.min.x > x.min.x && k.max.x < x.max.x && k.min.y > x.min.y && k.max.y < x.max.y
}

/// Shrinks the enclosure of a certified root: every root in `X` lies in `K(X) ∩ X`,
/// iterated while it at least halves.
fn contract(system: [&Poly; 2], jacobian: &[Poly; 4], mut x: Aabb) -> Aabb {
    for _ in 0..64 {
        let image = krawczyk_image(system, jacobian, &x, &mut None);
        let Some(k) = image.and_then(|k| k.intersection(&x)) else {
            break;
        };
        let shrunk = k.longest_side() <= 0.5 * x.longest_side();
        x = k;
        if !shrunk {
            break;
        }
    }
    x
}

/// What the Krawczyk operator over a box needs besides the interval Jacobian: the
/// centre `m`, `F(m)` enclosed, `Y ≈ J(m)⁻¹`.
struct KrawczykCentre {
    m: Point,
    fm: [Interval; 2],
    y: [Interval; 4],
}

impl KrawczykCentre {
    /// `None` where the Jacobian at the centre is singular (or not finite).
    fn new(system: [&Poly; 2], jacobian: &[Poly; 4], x: &Aabb) -> Option<Self> {
        let m = x.center();
        let (mx, my) = (Interval::point(m.x), Interval::point(m.y));
        let zero = Interval::point(0.0);
        let fm = [
            system[0].eval_interval(mx, my, zero),
            system[1].eval_interval(mx, my, zero),
        ];
        let jm: Vec<f64> = jacobian.iter().map(|p| p.eval(m.x, m.y, 0.0)).collect();
        let det = jm[0] * jm[3] - jm[1] * jm[2];
        if !(det.is_finite() && det != 0.0) {
            return None;
        }
        let y = [jm[3] / det, -jm[1] / det, -jm[2] / det, jm[0] / det].map(Interval::point);
        Some(KrawczykCentre { m, fm, y })
    }

    /// `K(X)` with the interval Jacobian `j` as a box; `None` where something is not
    /// finite.
    fn image(&self, x: &Aabb, j: &[Interval; 4]) -> Option<Aabb> {
        let finite = |i: &Interval| i.lo.is_finite() && i.hi.is_finite();
        if !self.fm.iter().chain(j).all(finite) {
            return None;
        }
        let (m, y) = (self.m, &self.y);
        let zero = Interval::point(0.0);
        let d = [x.x() - m.x, x.y() - m.y];
        let one = Interval::point(1.0);
        // row r of K: m_r − (Y F(m))_r + Σ_c (δ_rc − (Y J)_rc) d_c
        let mut k = [zero; 2];
        for (r, kr) in k.iter_mut().enumerate() {
            let yf = y[2 * r] * self.fm[0] + y[2 * r + 1] * self.fm[1];
            let mut acc = Interval::point(if r == 0 { m.x } else { m.y }) - yf;
            for (c, dc) in d.iter().enumerate() {
                let yj = y[2 * r] * j[c] + y[2 * r + 1] * j[2 + c];
                let delta = if r == c { one } else { zero };
                acc = acc + (delta - yj) * *dc;
            }
            *kr = acc;
        }
        k.iter()
            .all(finite)
            .then(|| Aabb::new(Point::new(k[0].lo, k[1].lo), Point::new(k[0].hi, k[1].hi)))
    }
}

/// The Krawczyk image `K(X)` as a box; `None` where it cannot be formed (a singular
/// Jacobian at the centre, or overflow). `f_over_x` holds `f`'s form over `x` once made.
fn krawczyk_image(
    system: [&Poly; 2],
    jacobian: &[Poly; 4],
    x: &Aabb,
    f_over_x: &mut Option<Bernstein2>,
) -> Option<Aabb> {
    let centre = KrawczykCentre::new(system, jacobian, x)?;
    let j = interval_jacobian(system, jacobian, x, f_over_x)?;
    centre.image(x, &j)
}

/// Intervals inside the enclosures of `f_x, f_y, g_x, g_y` that [`interval_jacobian`]
/// gives over any box holding `b`, from `forms`, those of `f` and `g` over `b`: the inner
/// intervals of their derivatives' coefficient hulls ([`CoefficientHull::inner`](crate::num::bernstein::CoefficientHull::inner)) divided
/// by `b`'s sides, rounded inward. `None` when one is empty or `b` is flat.
fn inner_jacobian(forms: [&Bernstein2; 2], b: &Aabb) -> Option<[Interval; 4]> {
    let sides = [
        Interval::point(b.max.x) - Interval::point(b.min.x),
        Interval::point(b.max.y) - Interval::point(b.min.y),
    ];
    if !sides.iter().all(|s| s.lo > 0.0 && s.hi.is_finite()) {
        return None;
    }
    let mut j = [Interval::point(0.0); 4];
    for (row, form) in forms.into_iter().enumerate() {
        for (col, (axis, side)) in [Axis::X, Axis::Y].into_iter().zip(sides).enumerate() {
            let h = form.derivative_hull(axis)?.inner()?;
            // h.lo / s at most lo, h.hi / s at least hi for every s in `side`
            let lo = Interval::point(h.lo).div(side)?.hi;
            let hi = Interval::point(h.hi).div(side)?.lo;
            // (a NaN passes here and is refused by the image's finiteness test)
            if lo > hi {
                return None;
            }
            j[2 * row + col] = Interval::new(lo, hi);
        }
    }
    Some(j)
}

/// Enclosures of `f_x, f_y, g_x, g_y` over `x`: the ranges of the derivatives of the
/// Bernstein forms of `f` and `g` over `x` (differences of neighbouring coefficients
/// times the degree: `∂/∂u` in the box's relative coordinate `u = (x − x₀)/(x₁ − x₀)`),
/// divided by the box's width or height (two conversions from `Poly` instead of four).
/// A box of zero width or height has no derivative along it in its forms: there the
/// partial derivatives in `jacobian` are converted instead. `None` when a side's length
/// is not a positive finite number. `f_over_x` holds `f`'s form over `x` once made.
fn interval_jacobian(
    system: [&Poly; 2],
    jacobian: &[Poly; 4],
    x: &Aabb,
    f_over_x: &mut Option<Bernstein2>,
) -> Option<[Interval; 4]> {
    if !(x.width() > 0.0 && x.height() > 0.0) {
        return Some(std::array::from_fn(|k| {
            Bernstein2::from_poly(&jacobian[k], x).range()
        }));
    }
    // the exact side lengths, enclosed
    let sides = [
        Interval::point(x.max.x) - Interval::point(x.min.x),
        Interval::point(x.max.y) - Interval::point(x.min.y),
    ];
    if !sides.iter().all(|s| s.hi.is_finite()) {
        return None;
    }
    let mut j = [Interval::point(0.0); 4];
    let g_over_x = Bernstein2::from_poly(system[1], x);
    let f_over_x = &*f_over_x.get_or_insert_with(|| Bernstein2::from_poly(system[0], x));
    for (row, form) in [f_over_x, &g_over_x].into_iter().enumerate() {
        for (col, (axis, side)) in [Axis::X, Axis::Y].into_iter().zip(sides).enumerate() {
            j[2 * row + col] = form.derivative_range(axis).div(side)?;
        }
    }
    Some(j)
}

/// One Newton step for the system at `p`; `None` where the Jacobian is singular.
fn newton_step(system: [&Poly; 2], jacobian: &[Poly; 4], p: Point) -> Option<Point> {
    let f = [system[0].eval(p.x, p.y, 0.0), system[1].eval(p.x, p.y, 0.0)];
    let j: Vec<f64> = jacobian.iter().map(|q| q.eval(p.x, p.y, 0.0)).collect();
    let det = j[0] * j[3] - j[1] * j[2];
    if !(det.is_finite() && det != 0.0) {
        return None;
    }
    let dx = (j[3] * f[0] - j[1] * f[1]) / det;
    let dy = (j[0] * f[1] - j[2] * f[0]) / det;
    Some(Point::new(p.x - dx, p.y - dy))
}

/// Newton's method from the centre of `enclosure`, kept inside it (f64, not certified;
/// the certificate is the enclosure).
fn newton_refine(system: [&Poly; 2], jacobian: &[Poly; 4], enclosure: &Aabb) -> Point {
    let mut p = enclosure.center();
    for _ in 0..60 {
        let Some(next) = newton_step(system, jacobian, p) else {
            break;
        };
        let next = enclosure.clamp(next);
        if next == p {
            break;
        }
        p = next;
    }
    p
}

/// The point of a cluster with the smallest residual among its centre and the Newton
/// iterates from it that stay inside.
fn best_point(system: [&Poly; 2], jacobian: &[Poly; 4], cluster: &Aabb) -> Point {
    let residual =
        |p: Point| system[0].eval(p.x, p.y, 0.0).abs() + system[1].eval(p.x, p.y, 0.0).abs();
    let mut p = cluster.center();
    let mut best = (residual(p), p);
    for _ in 0..30 {
        match newton_step(system, jacobian, p) {
            Some(next) if cluster.contains(next) => p = next,
            _ => break,
        }
        let r = residual(p);
        if r < best.0 {
            best = (r, p);
        }
    }
    best.1
}

/// `b` grown by `frac` of its sides on each side.
fn inflate(b: &Aabb, frac: f64) -> Aabb {
    let (dx, dy) = (frac * b.width(), frac * b.height());
    Aabb::new(
        Point::new(b.min.x - dx, b.min.y - dy),
        Point::new(b.max.x + dx, b.max.y + dy),
    )
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
            // Newton's method in the bracket lands within rounding of bisection's root
            let y = refine_by_newton(&b, iv.lo, iv.hi);
            assert!((y - x).abs() <= 4.0 * f64::EPSILON, "{y} vs {x}");
        }
        // without a sign change, the end nearer to zero, as bisection
        assert_eq!(refine_by_newton(&b, 0.3, 0.4), refine(&b, 0.3, 0.4));
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

#[cfg(test)]
mod system_tests {
    use super::*;

    fn poly(s: &str) -> Poly {
        Poly::parse(s, &['x', 'y']).unwrap()
    }

    /// The boxes of a 6 × 6 grid over `[-1, 1]²` and their quarters.
    fn boxes() -> Vec<Aabb> {
        let mut out = Vec::new();
        for i in 0..6 {
            for j in 0..6 {
                let (x, y) = (-1.0 + i as f64 / 3.0, -1.0 + j as f64 / 3.0);
                let b = Aabb::from_array([x, y, x + 1.0 / 3.0, y + 1.0 / 3.0]);
                let (l, h) = b.split(Axis::X, b.center().x);
                out.extend([b, l, h]);
                out.extend([l, h].iter().flat_map(|q| {
                    let (a, c) = q.split(Axis::Y, q.center().y);
                    [a, c]
                }));
            }
        }
        out
    }

    #[test]
    fn inner_jacobian_lies_inside_the_jacobian_over_a_larger_box() {
        let (f, g) = (
            poly("x^3*y - 2*x*y^2 + y^3 - 0.3*x + 0.1"),
            poly("x^2 + y^2 - x*y^3 - 0.5"),
        );
        let jacobian = [f.partial(0), f.partial(1), g.partial(0), g.partial(1)];
        let mut checked = 0;
        for b in boxes() {
            let forms = [Bernstein2::from_poly(&f, &b), Bernstein2::from_poly(&g, &b)];
            let Some(inner) = inner_jacobian([&forms[0], &forms[1]], &b) else {
                continue;
            };
            checked += 1;
            let x = inflate(&b, 0.25);
            let outer = interval_jacobian([&f, &g], &jacobian, &x, &mut None).unwrap();
            for (i, o) in inner.iter().zip(&outer) {
                assert!(o.lo <= i.lo && i.hi <= o.hi, "{b:?}: {i} not in {o}");
            }
        }
        assert!(checked > 100, "only {checked} boxes had inner intervals");
    }

    #[test]
    fn the_krawczyk_screen_answers_unknown_only_where_the_test_does() {
        let (f, g) = (poly("x^2 + y^2 - 0.5"), poly("x*y - 0.2 + 0.1*x^3"));
        let jacobian = [f.partial(0), f.partial(1), g.partial(0), g.partial(1)];
        let (mut screened, mut decided) = (0, 0);
        for b in boxes() {
            let forms = [Bernstein2::from_poly(&f, &b), Bernstein2::from_poly(&g, &b)];
            let x = inflate(&b, 0.25);
            let full = krawczyk([&f, &g], &jacobian, &x, None, &mut None);
            let with = krawczyk(
                [&f, &g],
                &jacobian,
                &x,
                Some(([&forms[0], &forms[1]], &b)),
                &mut None,
            );
            let same = match (&full, &with) {
                (
                    Krawczyk::Unique {
                        region: r0,
                        enclosure: e0,
                    },
                    Krawczyk::Unique {
                        region: r1,
                        enclosure: e1,
                    },
                ) => r0 == r1 && e0 == e1,
                (Krawczyk::NoRoot, Krawczyk::NoRoot) | (Krawczyk::Unknown, Krawczyk::Unknown) => {
                    true
                }
                _ => false,
            };
            assert!(same, "{b:?}");
            if matches!(full, Krawczyk::Unknown) {
                let centre = KrawczykCentre::new([&f, &g], &jacobian, &x).unwrap();
                let inner =
                    inner_jacobian([&forms[0], &forms[1]], &b).and_then(|j| centre.image(&x, &j));
                screened += inner
                    .is_some_and(|k| !strictly_inside(&k, &x) && k.intersection(&x).is_some())
                    as usize;
            } else {
                decided += 1;
            }
        }
        // the screen does spare tests, and the others still decide boxes
        assert!(
            screened > 20 && decided > 20,
            "{screened} screened, {decided} decided"
        );
    }

    fn solve(f: &str, g: &str, d: [f64; 4]) -> Vec<SystemRoot> {
        let domain = Aabb::from_array(d);
        solve_system(
            &poly(f),
            &poly(g),
            &[],
            &domain,
            &SystemOptions::for_domain(&domain),
        )
    }

    /// Every expected root lies in exactly one certified enclosure, whose point is at it.
    fn assert_certified(roots: &[SystemRoot], expected: &[Point]) {
        assert_eq!(roots.len(), expected.len(), "{roots:?}");
        for e in expected {
            let holding: Vec<_> = roots.iter().filter(|r| r.enclosure.contains(*e)).collect();
            assert_eq!(holding.len(), 1, "{e:?} in {roots:?}");
            assert!(holding[0].certified, "{holding:?}");
            assert!(holding[0].point.dist(*e) < 1e-12, "{holding:?} vs {e:?}");
            assert!(holding[0].enclosure.longest_side() < 1e-3);
        }
    }

    #[test]
    fn circle_and_line() {
        let (x, y) = (2.0 / 5f64.sqrt(), 1.0 / 5f64.sqrt());
        let roots = solve("x^2 + y^2 - 1", "y - x/2", [-2.0, -2.0, 2.0, 2.0]);
        assert_certified(&roots, &[Point::new(x, y), Point::new(-x, -y)]);
    }

    #[test]
    fn two_conics_meet_four_times() {
        let t = 2.0 / 5f64.sqrt();
        let roots = solve("x^2/4 + y^2 - 1", "x^2 + y^2/4 - 1", [-3.0, -3.0, 3.0, 3.0]);
        let expected = [(t, t), (-t, t), (t, -t), (-t, -t)].map(|(x, y)| Point::new(x, y));
        assert_certified(&roots, &expected);
    }

    #[test]
    fn roots_on_box_sides_are_found_once() {
        // the roots (±1, 0) lie on the split line x = 0 ± 1 of a [−1, 1] box's halves,
        // and on the domain's sides
        let roots = solve("x^2 - 1", "y", [-1.0, -1.0, 1.0, 1.0]);
        assert_certified(&roots, &[Point::new(1.0, 0.0), Point::new(-1.0, 0.0)]);
        let roots = solve("x^2 + y^2 - 1", "x - y", [-2.0, -2.0, 2.0, 2.0]);
        let s = 0.5f64.sqrt();
        assert_certified(&roots, &[Point::new(s, s), Point::new(-s, -s)]);
    }

    #[test]
    fn boxes_lost_in_the_noise_are_left_whole() {
        let domain = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
        let opts = |noise| SystemOptions {
            noise,
            ..SystemOptions::for_domain(&domain)
        };
        let s = 0.5f64.sqrt();
        let expected = [Point::new(s, s), Point::new(-s, -s)];
        let (f, g) = (poly("x^2 + y^2 - 1"), poly("x - y"));
        // far above the noise: the same certified roots as without it
        let roots = solve_system(&f, &g, &[], &domain, &opts(Some([1e-9, 1e-9])));
        assert_certified(&roots, &expected);
        // scaled below it: the domain, unsplit, as one cluster holding both roots
        let (tiny_f, tiny_g) = (f.scale(1e-20), g.scale(1e-20));
        let roots = solve_system(&tiny_f, &tiny_g, &[], &domain, &opts(Some([1e-18, 1e-18])));
        assert_eq!(roots.len(), 1, "{roots:?}");
        assert!(
            !roots[0].certified && roots[0].enclosure == domain,
            "{roots:?}"
        );
        // scaling alone changes nothing, nor does one polynomial alone in the noise
        let roots = solve_system(&tiny_f, &tiny_g, &[], &domain, &opts(None));
        assert_certified(&roots, &expected);
        let roots = solve_system(&tiny_f, &g, &[], &domain, &opts(Some([1e-18, 1e-18])));
        assert_certified(&roots, &expected);
    }

    #[test]
    fn units_change_the_splits_not_the_roots() {
        let domain = Aabb::from_array([-3.0, -3.0, 3.0, 3.0]);
        let (f, g) = (poly("x^2/4 + y^2 - 1"), poly("x^2 + y^2/4 - 1"));
        let t = 2.0 / 5f64.sqrt();
        let expected = [(t, t), (-t, t), (t, -t), (-t, -t)].map(|(x, y)| Point::new(x, y));
        // (units of zero fall back to equal ones)
        for units in [[1.0, 1e-3], [50.0, 1.0], [0.0, 1.0]] {
            let opts = SystemOptions {
                units,
                ..SystemOptions::for_domain(&domain)
            };
            assert_certified(&solve_system(&f, &g, &[], &domain, &opts), &expected);
        }
    }

    #[test]
    fn systems_sharing_f_get_the_answers_of_separate_calls() {
        // a curve's turning points in x and in y, and the nodal cubic's with a noise
        // floor and a small budget (uncertified clusters too)
        let cases = [
            ("x^2/4 + y^2 - 1", [-3.0, -3.0, 3.0, 3.0], None, 1 << 16),
            (
                "y^2 - x^2*(x + 1)",
                [-2.0, -2.0, 2.0, 2.0],
                Some([1e-9, 1e-8]),
                300,
            ),
        ];
        for (f, d, noise, max_boxes) in cases {
            let (f, domain) = (poly(f), Aabb::from_array(d));
            let gs = [f.partial(0), f.partial(1)];
            let opts = [1.0, 2.0].map(|k| SystemOptions {
                noise: noise.map(|[a, b]| [a, k * b]),
                max_boxes,
                units: [1.0, 3.0],
                ..SystemOptions::for_domain(&domain)
            });
            let together = solve_systems(&f, &gs, &[], &domain, &opts);
            for ((g, o), found) in gs.iter().zip(&opts).zip(&together) {
                assert_eq!(found, &solve_system(&f, g, &[], &domain, o));
                assert!(!found.is_empty());
            }
        }
    }

    #[test]
    fn tangency_is_an_uncertified_cluster() {
        // the line y = 1 touches the unit circle at (0, 1): a double root
        let roots = solve("x^2 + y^2 - 1", "y - 1", [-2.0, -2.0, 2.0, 2.0]);
        assert!(!roots.is_empty());
        assert!(roots.iter().all(|r| !r.certified), "{roots:?}");
        let at = Point::new(0.0, 1.0);
        let holding: Vec<_> = roots.iter().filter(|r| r.enclosure.contains(at)).collect();
        assert_eq!(holding.len(), 1, "{roots:?}");
        assert!(holding[0].enclosure.longest_side() < 1e-3, "{holding:?}");
        // nothing far from the tangency survives
        for r in &roots {
            assert!(r.enclosure.center().dist(at) < 1e-2, "{r:?}");
        }
    }

    #[test]
    fn no_root_and_side_conditions() {
        assert!(solve("x^2 + y^2 + 1", "x - y", [-2.0, -2.0, 2.0, 2.0]).is_empty());
        // singular points of the node y² − x²(x + 1) = 0: f_x = f_y = 0 at (0, 0) and
        // (−2/3, 0); only the first is on the curve
        let f = poly("y^2 - x^2*(x + 1)");
        let domain = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
        let roots = solve_system(
            &f.partial(0),
            &f.partial(1),
            std::slice::from_ref(&f),
            &domain,
            &SystemOptions::for_domain(&domain),
        );
        assert_certified(&roots, &[Point::new(0.0, 0.0)]);
    }

    #[test]
    fn budget_bounds_the_work() {
        // f = g: a whole curve of solutions, reported as clusters within the budget
        let domain = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
        let f = poly("x^2 + y^2 - 1");
        let opts = SystemOptions {
            min_size: 1e-9,
            max_boxes: 2000,
            noise: None,
            units: [1.0, 1.0],
        };
        let roots = solve_system(&f, &f, &[], &domain, &opts);
        assert!(!roots.is_empty() && roots.iter().all(|r| !r.certified));
        let on = Point::new(0.6, 0.8);
        assert!(roots.iter().any(|r| r.enclosure.contains(on)));
    }
}
