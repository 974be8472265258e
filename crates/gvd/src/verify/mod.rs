//! `gvd verify`: an independent brute-force checker of a diagram against its scene.
//!
//! It evaluates the sites' distance fields itself, straight from the [`Scene`] (see
//! `field.rs`), and never calls an algorithm that computes diagrams. The checks follow
//! the shared Python checker (`tools/README.md`), with tolerance `tol = slack · ε`:
//!
//! * **a. soundness** — every edge polyline is sampled at spacing ≤ ε/2 (its own points
//!   included); each sample moves onto the bisector of its generators `a`, `b` by up to 4
//!   Newton steps on `d_a − d_b` (each at most 4ε). `e_tie` = distance moved +
//!   `|d_a − d_b| / |∇(d_a − d_b)|`; if another site `k` is nearer there by an excess,
//!   `e_other = excess / |∇(d_min − d_k)|`. The sample error is `hypot(e_tie, e_other)`,
//!   at least its distance outside the domain or inside a closed site; good iff ≤ tol.
//! * **b. vertices** — Gauss–Newton from the vertex to the nearby point where its
//!   generators tie; error = distance to it + leftover spread / (2 max |∇d|), combined
//!   with `e_other`; every vertex must have error ≤ tol.
//! * **c. completeness** — the centres of an N × N grid are labelled with their nearest
//!   site; every crossing between differently labelled neighbours (bisection, split where
//!   a third site is nearer) needs an output edge with the same unordered pair within
//!   `R = 2·tol + h`, or a vertex within `R` listing both. Where a label's foot is a
//!   point that several sites contain (a shared segment end), any of them may name it
//!   (`SCENE_FORMAT.md`, "Shared points"): its corner there in the featured modes.
//! * **d. structure** — valid labels and `from`/`to` references, edge ends within tol of
//!   the vertex they name, which lists the edge's generators; null ends on the domain
//!   boundary unless the edge is a closed loop.
//!
//! Generators (`generators.rs`): whole sites in `voronoi` mode (a polyline or polygon
//! is the union of its segments, a polygon's inside masked: it belongs to no cell, and
//! an edge sample there counts its depth); in `complex` and `medial_axis` modes the
//! corners, edges and arc pieces of segments, polylines, polygons and arcs, each with
//! its own field. As in the Python checker, in those modes:
//!
//! * an edge between a corner and an edge/piece ending there is a zone boundary, not a
//!   Voronoi edge: its samples fail unless within `2·tol` of the corner; grid crossings
//!   between such a pair are skipped;
//! * an edge/piece is open: where its foot is an end corner the nearest generator is
//!   that corner (nearest-generator labels, crossings that passed a zone boundary), and
//!   an edge sample lying beyond an end of its edge/piece generator by more than tol
//!   fails ("label the corner");
//! * `medial_axis` mode keeps only the even-odd interior of the polygons and of chains
//!   of open sites that close up (`region.rs`): samples outside fail by their distance
//!   to it, grid nodes and crossings outside are skipped. A closed algebraic curve
//!   there is one generator for all the engine's pieces (cut at its vertices): edges and
//!   vertices are checked on its branches (local feet, `field.rs`), and its ridges'
//!   grid crossings are where the nearest foot jumps between neighbours.
//!
//! One deliberate difference: a crossing whose labels become a corner and its own edge
//! after that relabelling lies on a zone boundary and is skipped (the Python checker
//! reports it as missing; it arises where a corner's wedge is narrower than the grid).

mod completeness;
mod curve;
mod field;
mod generators;
mod nearest;
mod parametric;
mod region;
mod report;
mod soundness;
mod structure;
mod vertices;

pub use report::Report;

use crate::complex::{Generator, VoronoiComplex};
use crate::error::Error;
use crate::geom::Point;
use crate::scene::{Mode, Scene};
use field::Field;
use generators::Gens;
use nearest::Nearest;
use report::MAX_LIST;

/// How strict the checker is.
#[derive(Clone, Debug, PartialEq)]
pub struct VerifyOptions {
    /// The completeness grid is `grid × grid` nodes.
    pub grid: usize,
    /// Every distance test uses `tol = slack · epsilon`.
    pub slack: f64,
    /// The fraction of good edge samples needed to pass.
    pub min_sound: f64,
    /// The fraction of covered bisector crossings needed to pass.
    pub min_complete: f64,
}

impl Default for VerifyOptions {
    fn default() -> Self {
        VerifyOptions {
            grid: 512,
            slack: 1.0,
            min_sound: 1.0,
            min_complete: 1.0,
        }
    }
}

/// The largest completeness grid ([`VerifyOptions::grid`]): its labels and crossings take
/// some 16 bytes a node, 270 MB here.
pub const MAX_GRID: usize = 4096;

/// Checks `diagram` against `scene`. Refuses scenes the checker cannot evaluate:
/// ellipses in `medial_axis` mode. A diagram whose engine floored an epsilon finer than
/// f64 resolves (`stats.epsilon_floored_from`) is checked at its `stats.resolution`,
/// with a warning.
pub fn verify(
    scene: &Scene,
    diagram: &VoronoiComplex,
    opts: &VerifyOptions,
) -> Result<Report, Error> {
    if !(2..=MAX_GRID).contains(&opts.grid) {
        return Err(Error::InvalidOption {
            option: "grid".into(),
            message: format!(
                "the completeness grid must have 2 to {MAX_GRID} nodes a side, found {}",
                opts.grid
            ),
        });
    }
    if !(opts.slack.is_finite() && opts.slack > 0.0) {
        return Err(Error::InvalidOption {
            option: "slack".into(),
            message: format!("must be a finite number > 0, found {}", opts.slack),
        });
    }
    if let Some(eps) = floored_epsilon(scene, diagram) {
        let coarser = Scene::new(scene.domain(), eps, scene.mode(), scene.sites().to_vec())?;
        let mut report = check_scaled(&coarser, diagram, opts)?;
        report.warnings.push(format!(
            "checked at the diagram's resolution {eps:e}: the engine floored epsilon {:e}, finer than it resolves in this domain",
            scene.epsilon()
        ));
        return Ok(report);
    }
    check_scaled(scene, diagram, opts)
}

/// The resolution a diagram states it was computed at when its engine floored the
/// scene's epsilon (`stats.resolution` with `stats.epsilon_floored_from`); believed up
/// to 1e-9 of the domain, as such a floor comes from f64's resolution only.
fn floored_epsilon(scene: &Scene, diagram: &VoronoiComplex) -> Option<f64> {
    let stat = |key: &str| diagram.stats.get(key).and_then(|v| v.as_f64());
    let resolution = stat("resolution")?;
    let believed = resolution > scene.epsilon()
        && resolution <= 1e-9 * scene.domain().longest_side()
        && stat("epsilon_floored_from") == Some(scene.epsilon());
    believed.then_some(resolution)
}

/// [`check`], at a power-of-two scale near 1 for scenes whose fields share a degree
/// and would overflow or underflow (beyond 2^±200 for distances): exact, the same
/// diagram, as the engines compute them.
fn check_scaled(
    scene: &Scene,
    diagram: &VoronoiComplex,
    opts: &VerifyOptions,
) -> Result<Report, Error> {
    if let Some(s) = scene.unit_scale() {
        let mut scaled = diagram.clone();
        scaled.scale(s);
        let mut report = check(&scene.scaled(s), &scaled, opts, 1.0 / s)?;
        report.worst_edge_error /= s;
        return Ok(report);
    }
    check(scene, diagram, opts, 1.0)
}

/// [`verify`] of a scene at `1 / unit` times the caller's coordinates: messages give
/// lengths and locations times `unit`, in the caller's.
fn check(
    scene: &Scene,
    diagram: &VoronoiComplex,
    opts: &VerifyOptions,
    unit: f64,
) -> Result<Report, Error> {
    let gens = Gens::new(scene)?;
    let ck = Checker::new(scene, &gens, diagram, opts, unit);
    Ok(ck.run())
}

/// A point as `(x, y)` with 6 digits after the point, or 6 significant digits in
/// exponent form far from 1.
fn at(p: Point) -> String {
    let f = |v: f64| {
        if v == 0.0 || (1e-3..1e9).contains(&v.abs()) {
            format!("{v:.6}")
        } else {
            format!("{v:.5e}")
        }
    };
    format!("({}, {})", f(p.x), f(p.y))
}

/// An excess `d_a − d_b > 0` of one field over another as a length: the excess over
/// `|∇d_a − ∇d_b|` (first order), floored at `1e-12` of the larger gradient. Only the
/// ratio counts, so multiplying every field by one factor (a Möbius scale of 1e300)
/// leaves it alone; the gradients' norms are `hypot`s, whose squares would overflow.
fn excess_length(excess: f64, ga: Point, gb: Point) -> f64 {
    let floor = 1e-12 * ga.norm_wide().max(gb.norm_wide());
    excess / (ga - gb).norm_wide().max(floor).max(f64::MIN_POSITIVE)
}

fn finite(p: Point) -> bool {
    p.x.is_finite() && p.y.is_finite()
}

/// An edge that passed the structural parse.
struct GoodEdge {
    index: usize,
    a: usize,
    b: usize,
}

struct Checker<'a> {
    scene: &'a Scene,
    gens: &'a Gens,
    fields: &'a [Field],
    near: Nearest<'a>,
    diagram: &'a VoronoiComplex,
    opts: &'a VerifyOptions,
    tol: f64,
    scale: f64,
    /// valid edges with their generators
    edges: Vec<GoodEdge>,
    /// each vertex's generators (deduplicated), `None` if invalid
    vgens: Vec<Option<Vec<usize>>>,
    /// each vertex's curved generators listed more than once, with how often (that
    /// many branches of one curve tie there; where one is left, the vertex ends the
    /// curve's ridge at a centre of curvature)
    vtwice: Vec<Vec<(usize, usize)>>,
    /// `1e-12` of the scene's size (feet this close to a corner are at the corner)
    tiny: f64,
    errors: Vec<String>,
    warnings: Vec<String>,
    /// What lengths and locations are multiplied by in messages (1 unless the scene
    /// was rescaled for the check).
    unit: f64,
}

impl<'a> Checker<'a> {
    fn new(
        scene: &'a Scene,
        gens: &'a Gens,
        diagram: &'a VoronoiComplex,
        opts: &'a VerifyOptions,
        unit: f64,
    ) -> Self {
        let mut ck = Checker {
            unit,
            scene,
            gens,
            fields: &gens.fields,
            near: Nearest::new(gens, scene.domain()),
            diagram,
            opts,
            tol: opts.slack * scene.epsilon(),
            scale: scene.domain().longest_side(),
            edges: Vec::new(),
            vgens: Vec::new(),
            vtwice: Vec::new(),
            tiny: 1e-12 * scene.domain().longest_side(),
            errors: Vec::new(),
            warnings: Vec::new(),
        };
        ck.parse();
        ck
    }

    /// A label's generator, if the label is valid in the scene's mode.
    fn label(&self, g: &Generator) -> Result<usize, String> {
        self.gens.parse(g)
    }

    /// A location in messages, in the caller's coordinates.
    fn at(&self, p: Point) -> String {
        at(p * self.unit)
    }

    /// A generator's name in messages.
    fn name(&self, g: usize) -> String {
        self.gens.name(g)
    }

    fn run(mut self) -> Report {
        let mut problems = Vec::new();
        let spacing = self.sample_spacing();
        let (sound, worst_edge_error, sound_ok) = self.soundness(spacing, &mut problems);
        let (vok, vertices_ok) = self.vertices(&mut problems);
        let complete = self.completeness(&mut problems);
        self.structure();
        let structure_ok = self.errors.is_empty();
        let n = self.errors.len();
        problems.extend(
            self.errors
                .iter()
                .take(MAX_LIST)
                .map(|m| format!("structure: {m}")),
        );
        if n > MAX_LIST {
            problems.push(format!("structure: ... and {} more errors", n - MAX_LIST));
        }
        Report {
            sound,
            complete,
            vertices_ok: vok,
            worst_edge_error,
            problems,
            warnings: self.warnings,
            passed: sound_ok && vertices_ok && complete >= self.opts.min_complete && structure_ok,
        }
    }

    fn eval(&self, site: usize, q: Point) -> (f64, Point) {
        self.fields[site].eval(q)
    }

    /// How far another site intrudes at `q` beyond the nearer of `gens`, whose value
    /// there is `dmin` with gradient `gmin` (first order, in length units), and the
    /// intruder; a point inside a closed site counts its depth. An excess within the
    /// rounding of the two values (some ulps of `dmin` and of `q`'s coordinates) is
    /// none: divided by the gradients' small difference (two sites nearly in line with
    /// `q`) it would be rounding divided by rounding.
    fn intrusion(&self, q: Point, dmin: f64, gmin: Point, gens: &[usize]) -> (f64, usize) {
        let position = q.x.abs().max(q.y.abs()) * gmin.norm_wide();
        let rounding = 8.0 * f64::EPSILON * (dmin.abs() + position);
        match self.near.at(q) {
            None => (self.near.inside_depth(q), usize::MAX),
            Some(hit) if !gens.contains(&hit.gen) && dmin - hit.value > rounding => {
                let (_, gk) = self.eval(hit.gen, q);
                (excess_length(dmin - hit.value, gmin, gk), hit.gen)
            }
            Some(hit) => (0.0, hit.gen),
        }
    }

    /// Moves `q0` onto the bisector of `a` and `b` (up to 4 Newton steps on `d_a − d_b`,
    /// each at most 4ε). Returns `e_tie` (distance moved + residual, in length units),
    /// the projected point, and the smaller field there with its gradient.
    fn project(&self, q0: Point, a: usize, b: usize) -> (f64, Point, f64, Point) {
        let cap = 4.0 * self.scene.epsilon();
        let mut q = q0;
        let (mut va, mut ga) = self.eval(a, q);
        let (mut vb, mut gb) = self.eval(b, q);
        let mut far = None;
        for _ in 0..4 {
            let (d, g) = (
                field::difference(&self.fields[a], &self.fields[b], q),
                ga - gb,
            );
            let gn = g.norm_wide();
            if !d.is_finite() || gn <= 1e-12 * ga.norm_wide().max(gb.norm_wide()) {
                break;
            }
            let step = g * (1.0 / gn) * (-d / gn);
            let sl = step.norm();
            if sl > cap {
                far = Some((d.abs() / gn).max(cap));
                break;
            }
            if sl <= 1e-13 * self.scale {
                break;
            }
            q = q + step;
            (va, ga) = self.eval(a, q);
            (vb, gb) = self.eval(b, q);
        }
        let d = field::difference(&self.fields[a], &self.fields[b], q);
        let gn = (ga - gb).norm_wide();
        // Where both fields measure to the same point (a shared end's wedge, which
        // either site may name) they coincide: d and its gradient are rounding alone,
        // and their ratio means nothing (d in length units: over the fields' slope).
        let slope = ga.norm_wide().max(gb.norm_wide());
        let resid = if d.abs() <= 1e-12 * self.scale * slope {
            0.0
        } else {
            d.abs() / gn
        };
        let e_tie = far.unwrap_or(q.dist(q0) + resid);
        let e_tie = if e_tie.is_finite() {
            e_tie
        } else {
            f64::INFINITY
        };
        let (dmin, gmin) = if va <= vb { (va, ga) } else { (vb, gb) };
        if e_tie > 0.25 * self.tol {
            if let Some(s) = self.bracket(q0, a, b, ga + gb).filter(|&s| s < e_tie) {
                let (va, ga) = self.eval(a, q0);
                let (vb, gb) = self.eval(b, q0);
                let (dmin, gmin) = if va <= vb { (va, ga) } else { (vb, gb) };
                return (s, q0, dmin, gmin);
            }
        }
        (e_tie, q, dmin, gmin)
    }

    /// A certificate that the bisector of `a` and `b` passes within `s ≤ tol` of `q`:
    /// `d_a − d_b` changes sign (or vanishes) between `q − s·n` and `q + s·n`, for `n`
    /// perpendicular to `g` (the sum of the fields' gradients, along which both grow
    /// alike) or along `g` itself; the least such `s` among `tol·2⁻ᵏ`, `k ≤ 40`.
    /// Where the two fields are tangent along the bisector (the common normal of a
    /// tangent joint: `d_a − d_b` vanishes to second order across it), the first-order
    /// estimate `|d_a − d_b| / |∇(d_a − d_b)|` divides rounding by rounding on it.
    fn bracket(&self, q: Point, a: usize, b: usize, g: Point) -> Option<f64> {
        let len = g.norm_wide();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        let g = g * (1.0 / len);
        let diff = |x: Point| field::difference(&self.fields[a], &self.fields[b], x);
        let mut best = None;
        let mut s = self.tol;
        for _ in 0..=40 {
            let changes = [g.perp(), g].iter().any(|&n| {
                let (lo, hi) = (diff(q - n * s), diff(q + n * s));
                // signs compared, not a product: that of two values near 1e-300 (a
                // Möbius scale of 1e-300) underflows to 0, a "change" everywhere
                let changes = lo == 0.0 || hi == 0.0 || (lo < 0.0) != (hi < 0.0);
                lo.is_finite() && hi.is_finite() && changes
            });
            if !changes {
                break;
            }
            best = Some(s);
            s *= 0.5;
        }
        best
    }

    /// Whether `q` lies in the `medial_axis` region (always true in the other modes).
    fn in_region(&self, q: Point) -> bool {
        self.scene.mode() != Mode::MedialAxis
            || self.gens.region.as_ref().is_some_and(|r| r.contains(q))
    }
}

#[cfg(test)]
mod tests;
