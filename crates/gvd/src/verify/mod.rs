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
//!   to it, grid nodes and crossings outside are skipped.
//!
//! One deliberate difference: a crossing whose labels become a corner and its own edge
//! after that relabelling lies on a zone boundary and is skipped (the Python checker
//! reports it as missing; it arises where a corner's wedge is narrower than the grid).

mod curve;
mod field;
mod generators;
mod nearest;
mod region;

use crate::complex::{Generator, VoronoiComplex};
use crate::error::Error;
use crate::geom::{Aabb, Point};
use crate::par::map_range;
use crate::scene::{Mode, Scene};
use field::Field;
use generators::Gens;
use nearest::Nearest;
use std::collections::BTreeMap;

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

/// What the checker found.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The fraction of edge samples within tolerance of their bisector.
    pub sound: f64,
    /// The fraction of grid bisector crossings covered by an edge or vertex.
    pub complete: f64,
    /// `(good, total)` vertices.
    pub vertices_ok: (usize, usize),
    /// The largest edge sample error, in length units.
    pub worst_edge_error: f64,
    /// The worst offenders of each check, each naming the edge or vertex, its
    /// generators and a location.
    pub problems: Vec<String>,
    /// Findings that do not fail the diagram (unreferenced vertices, null ends on a site).
    pub warnings: Vec<String>,
    /// Whether all four checks passed.
    pub passed: bool,
}

impl Report {
    /// `sound=0.9993 complete=0.9981 vertices_ok=123/123 worst_edge_error=0.0012 PASS`,
    /// as the Python checker prints it.
    pub fn summary_line(&self) -> String {
        format!(
            "sound={:.4} complete={:.4} vertices_ok={}/{} worst_edge_error={} {}",
            self.sound,
            self.complete,
            self.vertices_ok.0,
            self.vertices_ok.1,
            fmt_g3(self.worst_edge_error),
            if self.passed { "PASS" } else { "FAIL" }
        )
    }
}

/// How many offenders each check lists.
const MAX_LIST: usize = 5;

/// The largest completeness grid ([`VerifyOptions::grid`]): its labels and crossings take
/// some 16 bytes a node, 270 MB here.
pub const MAX_GRID: usize = 4096;

/// Most edge samples the soundness check takes (some 24 bytes each): edges longer than
/// this many times ε/2 are sampled more coarsely, with a warning.
const MAX_SAMPLES: usize = 1 << 22;

/// Checks `diagram` against `scene`. Refuses scenes the checker cannot evaluate: site
/// kinds without a distance field here yet (Béziers, B-splines), and
/// ellipses in `medial_axis` mode.
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
    // Scenes whose fields share a degree and would overflow or underflow (beyond 2^±200
    // for distances) are checked at a power-of-two scale near 1 (exact, the same
    // diagram), as the engines compute them.
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

/// `x` with 3 significant digits, like Python's `{:.3g}`.
fn fmt_g3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x.is_nan() {
            "nan".into()
        } else if x.is_infinite() {
            "inf".into()
        } else {
            "0".into()
        };
    }
    let e = x.abs().log10().floor() as i32;
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if !(-4..3).contains(&e) {
        let m = x / 10f64.powi(e);
        // rounding may carry the mantissa to 10
        let (m, e) = if (m.abs() * 100.0).round() >= 1000.0 {
            (m / 10.0, e + 1)
        } else {
            (m, e)
        };
        format!(
            "{}e{}{:02}",
            trim(format!("{m:.2}")),
            if e < 0 { '-' } else { '+' },
            e.abs()
        )
    } else {
        trim(format!("{:.*}", (2 - e).max(0) as usize, x))
    }
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

/// Objects bucketed by a point in a uniform grid of cells (indices clamped, so objects
/// outside the grid land in its border cells).
struct Buckets {
    origin: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    start: Vec<usize>,
    ids: Vec<usize>,
}

impl Buckets {
    fn new(points: &[Point], area: Aabb, cell: f64) -> Self {
        let nx = ((area.width() / cell).ceil() as usize).clamp(1, 4096);
        let ny = ((area.height() / cell).ceil() as usize).clamp(1, 4096);
        let mut b = Buckets {
            origin: area.min,
            cell,
            nx,
            ny,
            start: vec![0; nx * ny + 1],
            ids: vec![0; points.len()],
        };
        let keys: Vec<usize> = points.iter().map(|&p| b.key(p)).collect();
        for &k in &keys {
            b.start[k + 1] += 1;
        }
        for k in 0..nx * ny {
            b.start[k + 1] += b.start[k];
        }
        let mut fill = b.start.clone();
        for (i, &k) in keys.iter().enumerate() {
            b.ids[fill[k]] = i;
            fill[k] += 1;
        }
        b
    }

    fn index(&self, p: Point) -> (usize, usize) {
        let f = |v: f64, n: usize| (v / self.cell).floor().clamp(0.0, (n - 1) as f64) as usize;
        (
            f(p.x - self.origin.x, self.nx),
            f(p.y - self.origin.y, self.ny),
        )
    }

    fn key(&self, p: Point) -> usize {
        let (i, j) = self.index(p);
        j * self.nx + i
    }

    /// The objects in the cells within `reach` cells of `p`'s cell.
    fn around(&self, p: Point, reach: usize) -> impl Iterator<Item = usize> + '_ {
        let (i, j) = self.index(p);
        let (i0, i1) = (i.saturating_sub(reach), (i + reach).min(self.nx - 1));
        let (j0, j1) = (j.saturating_sub(reach), (j + reach).min(self.ny - 1));
        (j0..=j1).flat_map(move |jj| {
            let row = jj * self.nx;
            self.ids[self.start[row + i0]..self.start[row + i1 + 1]]
                .iter()
                .copied()
        })
    }
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
    /// each vertex's curved generators listed more than once (two branches of one
    /// curve: with a single branch the vertex must be its centre of curvature)
    vtwice: Vec<Vec<usize>>,
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

    /// The structural parse: which edges and vertices can be checked at all.
    fn parse(&mut self) {
        let d = self.diagram;
        for (k, v) in d.vertices.iter().enumerate() {
            let gens: Result<Vec<usize>, String> = if !finite(v.at) {
                Err("'at' is not finite".into())
            } else if v.sites.is_empty() {
                Err("'sites' is empty".into())
            } else {
                v.sites.iter().map(|g| self.label(g)).collect()
            };
            match gens {
                Ok(mut g) => {
                    g.sort_unstable();
                    let mut twice: Vec<usize> = g
                        .windows(2)
                        .filter(|w| w[0] == w[1] && self.gens.curved[w[0]] && self.gens.featured)
                        .map(|w| w[0])
                        .collect();
                    twice.dedup();
                    g.dedup();
                    self.vgens.push(Some(g));
                    self.vtwice.push(twice);
                }
                Err(m) => {
                    self.errors.push(format!("vertex {k}: {m}"));
                    self.vgens.push(None);
                    self.vtwice.push(Vec::new());
                }
            }
        }
        for (k, e) in d.edges.iter().enumerate() {
            let parsed = if e.points.len() < 2 || !e.points.iter().all(|&p| finite(p)) {
                Err("'points' must be at least two finite points".to_string())
            } else {
                match (self.label(&e.sites[0]), self.label(&e.sites[1])) {
                    (Ok(a), Ok(b)) if a == b && !(self.gens.featured && self.gens.curved[a]) => {
                        Err(format!(
                            "both generators are {} (an edge separates two different generators)",
                            self.name(a)
                        ))
                    }
                    (Ok(a), Ok(b)) => Ok((a, b)),
                    (Err(m), _) | (_, Err(m)) => Err(m),
                }
            };
            match parsed {
                Ok((a, b)) => self.edges.push(GoodEdge { index: k, a, b }),
                Err(m) => self.errors.push(format!("edge {k}: {m}")),
            }
        }
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
    /// intruder; a point inside a closed site counts its depth.
    fn intrusion(&self, q: Point, dmin: f64, gmin: Point, gens: &[usize]) -> (f64, usize) {
        match self.near.at(q) {
            None => (self.near.inside_depth(q), usize::MAX),
            Some(hit) if !gens.contains(&hit.gen) && dmin > hit.value => {
                let (_, gk) = self.eval(hit.gen, q);
                ((dmin - hit.value) / (gmin - gk).norm().max(1e-12), hit.gen)
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
            let (d, g) = (va - vb, ga - gb);
            let gn = g.norm();
            if !d.is_finite() || gn <= 1e-12 {
                break;
            }
            let step = g * (-d / (gn * gn));
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
        let (d, gn) = (va - vb, (ga - gb).norm());
        let resid = if d != 0.0 { d.abs() / gn } else { 0.0 };
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
        let len = g.norm();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        let g = g * (1.0 / len);
        let diff = |x: Point| self.fields[a].value(x) - self.fields[b].value(x);
        let mut best = None;
        let mut s = self.tol;
        for _ in 0..=40 {
            let changes = [g.perp(), g].iter().any(|&n| {
                let (lo, hi) = (diff(q - n * s), diff(q + n * s));
                lo.is_finite() && hi.is_finite() && lo * hi <= 0.0
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

    /// The error of edge sample `q0` of the bisector of `a` and `b`, and why.
    fn sample_error(&self, q0: Point, a: usize, b: usize) -> (f64, &'static str) {
        let (e_tie, q, dmin, gmin) = if a == b {
            // two branches of one curve (an arc piece): an arc has a single branch
            // wherever its distance is differentiable, so the edge can only be its
            // centre, where a ridge ends
            let (va, ga) = self.eval(a, q0);
            let e = self.fields[a]
                .curvature_center()
                .map_or(f64::INFINITY, |c| c.dist(q0));
            (e, q0, va, ga)
        } else {
            self.project(q0, a, b)
        };
        let (e_other, _) = self.intrusion(q, dmin, gmin, &[a, b]);
        let mut e = e_tie.hypot(e_other);
        let mut why = if a == b && e_tie >= e_other {
            "no second branch of the generator nearby"
        } else if e_tie >= e_other {
            "not on the bisector of its generators"
        } else {
            "another generator is nearer"
        };
        let out = self.scene.domain().outside_distance(q0);
        if out > e {
            (e, why) = (out, "outside the domain");
        }
        if !self.in_region(q0) {
            let d = self
                .gens
                .region
                .as_ref()
                .map_or(f64::INFINITY, |r| r.boundary_distance(q0));
            if d > e {
                (e, why) = (d, "outside the medial-axis region");
            }
        }
        let inside = self.near.inside_depth(q0);
        if inside > e {
            (e, why) = (inside, "inside a closed site");
        }
        if self.gens.featured {
            // an edge/piece is an open feature: beyond its end (by more than the
            // tolerance) the nearest feature is the end corner, not the edge
            for g in [a, b] {
                let beyond = self.gens.beyond_end(g, q, self.tiny);
                if beyond > e {
                    (e, why) = (
                        beyond,
                        "the foot on an edge/piece generator is its end corner (label the corner)",
                    );
                }
            }
            // a corner and its own edge tie along a zone boundary, which is no Voronoi
            // edge (harmless right at the corner)
            if self.gens.zone_boundary(a, b) && self.fields[a].value(q0) > 2.0 * self.tol {
                return (
                    f64::INFINITY,
                    "zone boundary of a corner and its own edge (not a Voronoi edge)",
                );
            }
        }
        (e, why)
    }

    /// The spacing of check a's samples: ε/2, or the coarser spacing that keeps them
    /// within [`MAX_SAMPLES`] (with a warning saying so).
    fn sample_spacing(&mut self) -> f64 {
        let fine = self.scene.epsilon() / 2.0;
        let (mut length, mut chords) = (0.0, 0usize);
        for ge in &self.edges {
            let pts = &self.diagram.edges[ge.index].points;
            length += pts.windows(2).map(|w| w[1].dist(w[0])).sum::<f64>();
            chords += pts.len();
        }
        let room = MAX_SAMPLES.saturating_sub(chords).max(MAX_SAMPLES / 2) as f64;
        if !length.is_finite() || length / fine <= room {
            return fine;
        }
        let spacing = length / room;
        self.warnings.push(format!(
            "soundness: the edges are sampled every {} ({} eps), not every eps/2: at eps/2 they would take {} samples",
            fmt_g3(spacing * self.unit),
            fmt_g3(spacing / self.scene.epsilon()),
            fmt_g3(length / fine)
        ));
        spacing
    }

    /// Check a: returns (fraction good, worst error, pass).
    fn soundness(&self, spacing: f64, problems: &mut Vec<String>) -> (f64, f64, bool) {
        let mut samples: Vec<(Point, usize)> = Vec::new();
        for (g, ge) in self.edges.iter().enumerate() {
            let pts = &self.diagram.edges[ge.index].points;
            for w in pts.windows(2) {
                // At most 2^16 samples a chord: a length that overflows (coordinates
                // near f64's range) or a bogus diagram must not exhaust memory.
                let n = ((w[1].dist(w[0]) / spacing).ceil() as usize).clamp(1, 1 << 16);
                samples.extend((0..n).map(|j| (w[0].lerp(w[1], j as f64 / n as f64), g)));
            }
            samples.push((pts[pts.len() - 1], g));
        }
        let errs = map_range(samples.len(), 1, |i| {
            let (q, g) = samples[i];
            self.sample_error(q, self.edges[g].a, self.edges[g].b)
        });
        let good = errs.iter().filter(|e| e.0 <= self.tol).count();
        let worst = errs.iter().fold(0.0, |m: f64, e| m.max(e.0));
        // the worst sample of each bad edge
        let mut per_edge: BTreeMap<usize, (f64, usize, &str, usize)> = BTreeMap::new();
        for (i, &(e, why)) in errs.iter().enumerate() {
            if e > self.tol {
                let ent = per_edge.entry(samples[i].1).or_insert((e, i, why, 0));
                ent.3 += 1;
                if e > ent.0 {
                    (ent.0, ent.1, ent.2) = (e, i, why);
                }
            }
        }
        let mut bad: Vec<_> = per_edge.into_iter().collect();
        bad.sort_by(|x, y| y.1 .0.total_cmp(&x.1 .0));
        for &(g, (e, i, why, count)) in bad.iter().take(MAX_LIST) {
            let ge = &self.edges[g];
            problems.push(format!(
                "soundness: edge {} (sites {}, {}): {count} bad samples, worst {} ({} eps) at {}: {why}",
                ge.index,
                self.name(ge.a),
                self.name(ge.b),
                fmt_g3(e * self.unit),
                fmt_g3(e / self.scene.epsilon()),
                self.at(samples[i].0)
            ));
        }
        if bad.len() > MAX_LIST {
            problems.push(format!(
                "soundness: ... and {} more bad edges",
                bad.len() - MAX_LIST
            ));
        }
        let fraction = if samples.is_empty() {
            1.0
        } else {
            good as f64 / samples.len() as f64
        };
        let invalid = self.diagram.edges.len() - self.edges.len();
        (
            fraction,
            worst,
            fraction >= self.opts.min_sound && invalid == 0,
        )
    }

    /// One Gauss–Newton step towards `d_i(v + s) = t` for all generators `i` (unknowns
    /// `s`, `t`): solves `(JᵀJ + δI) x = −Jᵀr` with rows `J_i = (∇d_i, −1)` and
    /// `r_i = d_i − mean d`. Returns the step and the values and gradients at `v`.
    fn gauss_newton_step(&self, v: Point, gens: &[usize]) -> (Point, Vec<(f64, Point)>) {
        let ev: Vec<(f64, Point)> = gens.iter().map(|&g| self.eval(g, v)).collect();
        let mean = ev.iter().map(|e| e.0).sum::<f64>() / ev.len() as f64;
        let mut m = [[0.0f64; 3]; 3];
        let mut rhs = [0.0f64; 3];
        for &(val, g) in &ev {
            let j = [g.x, g.y, -1.0];
            for r in 0..3 {
                for c in 0..3 {
                    m[r][c] += j[r] * j[c];
                }
                rhs[r] -= j[r] * (val - mean);
            }
        }
        let reg = 1e-12 * (m[0][0] + m[1][1] + m[2][2]);
        for (r, row) in m.iter_mut().enumerate() {
            row[r] += reg;
        }
        let x = solve3(m, rhs).unwrap_or([0.0; 3]);
        let step = Point::new(x[0], x[1]);
        (if finite(step) { step } else { Point::default() }, ev)
    }

    /// The error of vertex `v` with generators `gens`, of which the curved `twice` are
    /// listed twice, and why.
    fn vertex_error(&self, v: Point, gens: &[usize], twice: &[usize]) -> (f64, String) {
        let cap = 4.0 * self.scene.epsilon();
        let mut pos = v;
        for _ in 0..6 {
            let (s, _) = self.gauss_newton_step(pos, gens);
            pos = pos + s * (cap / s.norm().max(1e-300)).min(1.0);
        }
        let (s, _) = self.gauss_newton_step(pos, gens);
        pos = pos + s;
        let (_, ev) = self.gauss_newton_step(pos, gens);
        let vmax = ev.iter().map(|e| e.0).fold(f64::NEG_INFINITY, f64::max);
        let (vmin, gmin) = ev
            .iter()
            .copied()
            .fold((f64::INFINITY, Point::default()), |m, e| {
                if e.0 < m.0 {
                    e
                } else {
                    m
                }
            });
        let gmax = ev.iter().map(|e| e.1.norm()).fold(0.0, f64::max);
        let spread = if (vmax - vmin).is_finite() {
            vmax - vmin
        } else {
            0.0
        };
        let mut e_tie = pos.dist(v) + spread / (2.0 * gmax).max(1e-12);
        // a curve listed twice with a single branch (an arc): the vertex ends a ridge,
        // so it must be the centre of curvature
        for &g in twice {
            let ec = self.fields[g]
                .curvature_center()
                .map_or(f64::INFINITY, |c| c.dist(v));
            e_tie = e_tie.max(ec);
        }
        let (e_other, who) = self.intrusion(pos, vmin, gmin, gens);
        let e = e_tie.hypot(e_other);
        let out = self.scene.domain().outside_distance(v);
        let why = if out >= e {
            "outside the domain".to_string()
        } else if e_tie >= e_other {
            "its generators are not tied".to_string()
        } else if who == usize::MAX {
            "inside a closed site".to_string()
        } else {
            format!("generator {} is nearer", self.name(who))
        };
        (e.max(out), why)
    }

    /// Check b: returns ((good, total), pass).
    fn vertices(&self, problems: &mut Vec<String>) -> ((usize, usize), bool) {
        let vs = &self.diagram.vertices;
        let errs = map_range(vs.len(), 1, |k| {
            self.vgens[k]
                .as_ref()
                .map(|g| self.vertex_error(vs[k].at, g, &self.vtwice[k]))
        });
        let mut bad: Vec<(usize, f64, &str)> = Vec::new();
        let mut ok = 0;
        for (k, e) in errs.iter().enumerate() {
            match e {
                Some((e, _)) if *e <= self.tol => ok += 1,
                Some((e, why)) => bad.push((k, *e, why)),
                None => {}
            }
        }
        bad.sort_by(|x, y| y.1.total_cmp(&x.1));
        for &(k, e, why) in bad.iter().take(MAX_LIST) {
            problems.push(format!(
                "vertices: vertex {k} (sites [{}]) at {}: error {} ({} eps): {why}",
                self.vgens[k]
                    .as_deref()
                    .unwrap_or(&[])
                    .iter()
                    .map(|&g| self.name(g))
                    .collect::<Vec<_>>()
                    .join(", "),
                self.at(vs[k].at),
                fmt_g3(e * self.unit),
                fmt_g3(e / self.scene.epsilon())
            ));
        }
        if bad.len() > MAX_LIST {
            problems.push(format!(
                "vertices: ... and {} more bad vertices",
                bad.len() - MAX_LIST
            ));
        }
        ((ok, vs.len()), ok == vs.len())
    }

    /// The crossings of the bisectors between the nearest generators `a` at `qa` and
    /// `b` at `qb`: bisection of `d_a − d_b` (14 steps, then linear interpolation);
    /// where a third generator is
    /// nearer at the crossing, both halves are searched again (depth ≤ 4). An edge or
    /// piece whose foot at the crossing is its end corner, beyond it by more than the
    /// last bracket, becomes that corner (the bisection crossed the corner's zone
    /// boundary). Crossings in ties of coincident
    /// feet, inside closed sites and outside the medial-axis region are skipped.
    fn crossings(
        &self,
        qa: Point,
        qb: Point,
        a: usize,
        b: usize,
        depth: u32,
        out: &mut Vec<(Point, usize, usize)>,
    ) {
        let (mut lo, mut hi) = (0.0, 1.0);
        let (mut d_lo, mut d_hi) = (f64::NAN, f64::NAN);
        for _ in 0..14 {
            let mid = 0.5 * (lo + hi);
            let q = qa.lerp(qb, mid);
            let (va, vb) = (self.fields[a].value(q), self.fields[b].value(q));
            if va <= vb {
                (lo, d_lo) = (mid, va - vb);
            } else {
                (hi, d_hi) = (mid, va - vb);
            }
        }
        // The tie inside the last bracket by linear interpolation of d_a − d_b (as the
        // Python checker does): the bracket's middle can be half a bracket off, enough
        // to separate the feet at a tie through one point (a shared end's wedge).
        let frac = d_lo / (d_lo - d_hi);
        let t = if frac.is_finite() {
            lo + frac.clamp(0.0, 1.0) * (hi - lo)
        } else {
            0.5 * (lo + hi)
        };
        let x = qa.lerp(qb, t);
        let (da, ga) = self.eval(a, x);
        let (db, gb) = self.eval(b, x);
        // The crossing is known within the last bracket: only beyond a corner by more
        // than that did the bisection cross the corner's zone boundary (a tangent
        // joint's crossing lies on the boundary, on either side by rounding).
        let bracket = qa.dist(qb) * (hi - lo);
        let (a, b) = if self.gens.featured {
            (
                self.gens.corner_if_at_end(a, x, self.tiny, bracket),
                self.gens.corner_if_at_end(b, x, self.tiny, bracket),
            )
        } else {
            (a, b)
        };
        // after the relabelling, a corner and its own edge: the crossing lies on that
        // corner's zone boundary, which is no Voronoi edge (the Python checker keeps
        // these; they arise where a corner's wedge is narrower than the grid)
        if self.gens.featured && self.gens.zone_boundary(a, b) {
            return;
        }
        let Some(hit) = self.near.at(x) else {
            return;
        };
        let (dmin, gmin) = if da <= db { (da, ga) } else { (db, gb) };
        let k = hit.gen;
        if k != a && k != b && depth < 4 {
            let (_, gk) = self.eval(k, x);
            if (dmin - hit.value) / (gmin - gk).norm().max(1e-12) > 1e-9 * self.scale {
                self.crossings(qa, x, a, k, depth + 1, out);
                self.crossings(x, qb, k, b, depth + 1, out);
                return;
            }
        }
        let tie = match (self.fields[a].foot(x), self.fields[b].foot(x)) {
            (Some(fa), Some(fb)) => fa.dist(fb) <= 1e-7 * self.scale,
            _ => false,
        };
        if !tie && self.in_region(x) {
            out.push((x, a, b));
        }
    }

    /// `g` and the generators that may name its region at `x` instead: where `g`'s foot
    /// from `x` is a point that other sites share (see [`generators::SharedPoints`]),
    /// their generators there that tie with `g` at `x`.
    fn owners(&self, g: usize, x: Point) -> Vec<usize> {
        let mut out = vec![g];
        let Some(foot) = self.fields[g].foot(x) else {
            return out;
        };
        let shared = &self.gens.shared;
        let owners = shared.owners_at(foot);
        if owners.is_empty() {
            return out;
        }
        let (site, dg) = (self.gens.labels[g].site(), self.fields[g].value(x));
        for (h, other) in owners {
            let tie = (self.fields[h].value(x) - dg).abs() <= 2.0 * shared.radius();
            if other != site && tie && !out.contains(&h) {
                out.push(h);
            }
        }
        out
    }

    /// Check c: returns the fraction of covered crossings.
    fn completeness(&self, problems: &mut Vec<String>) -> f64 {
        let dom = self.scene.domain();
        let n = self.opts.grid;
        let (hx, hy) = (dom.width() / n as f64, dom.height() / n as f64);
        let r = 2.0 * self.tol + hx.max(hy);
        let node = |i: usize, j: usize| {
            Point::new(
                dom.min.x + (i as f64 + 0.5) * hx,
                dom.min.y + (j as f64 + 0.5) * hy,
            )
        };
        let labels = map_range(n * n, 1, |k| {
            let q = node(k % n, k / n);
            if self.in_region(q) {
                self.near.at(q).map(|h| h.gen)
            } else {
                None
            }
        });
        let mut pairs = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let Some(a) = labels[j * n + i] else { continue };
                for (di, dj) in [(1, 0), (0, 1)] {
                    if i + di < n && j + dj < n {
                        if let Some(b) = labels[(j + dj) * n + i + di] {
                            if a != b && !self.gens.zone_boundary(a, b) {
                                pairs.push((node(i, j), node(i + di, j + dj), a, b));
                            }
                        }
                    }
                }
            }
        }
        let found = map_range(pairs.len(), 1, |p| {
            let (qa, qb, a, b) = pairs[p];
            let mut out = Vec::new();
            self.crossings(qa, qb, a, b, 0, &mut out);
            out
        });
        let crossings: Vec<(Point, usize, usize)> = found.into_iter().flatten().collect();
        // the output edges as pieces of length ≤ R, bucketed by their midpoints
        let mut pieces: Vec<(Point, Point, (usize, usize))> = Vec::new();
        for ge in &self.edges {
            let key = (ge.a.min(ge.b), ge.a.max(ge.b));
            for w in self.diagram.edges[ge.index].points.windows(2) {
                let m = ((w[1].dist(w[0]) / r).ceil() as usize).clamp(1, 1 << 16);
                pieces.extend((0..m).map(|j| {
                    let t = |j: usize| j as f64 / m as f64;
                    (w[0].lerp(w[1], t(j)), w[0].lerp(w[1], t(j + 1)), key)
                }));
            }
        }
        let mids: Vec<Point> = pieces.iter().map(|p| p.0.lerp(p.1, 0.5)).collect();
        let pb = Buckets::new(&mids, dom, r);
        let vat: Vec<Point> = self.diagram.vertices.iter().map(|v| v.at).collect();
        let vb = Buckets::new(&vat, dom, r);
        let covered_by = |x: Point, a: usize, b: usize| {
            let key = (a.min(b), a.max(b));
            // a piece's midpoint lies within R + R/2 of x: at most 2 cells away
            pb.around(x, 2).any(|p| {
                pieces[p].2 == key
                    && crate::geom::segment_distance(x, pieces[p].0, pieces[p].1) <= r
            }) || vb.around(x, 1).any(|v| {
                vat[v].dist(x) <= r
                    && self.vgens[v]
                        .as_ref()
                        .is_some_and(|g| g.contains(&a) && g.contains(&b))
            })
        };
        let covered = map_range(crossings.len(), 1, |c| {
            let (x, a, b) = crossings[c];
            covered_by(x, a, b) || {
                // either label may be another owner of a shared point
                let (oa, ob) = (self.owners(a, x), self.owners(b, x));
                (oa.len() > 1 || ob.len() > 1)
                    && oa.iter().any(|&a2| {
                        ob.iter()
                            .any(|&b2| a2 != b2 && (a2, b2) != (a, b) && covered_by(x, a2, b2))
                    })
            }
        });
        let mut missing: BTreeMap<(usize, usize), (usize, Point)> = BTreeMap::new();
        for (c, &ok) in covered.iter().enumerate() {
            if !ok {
                let (x, a, b) = crossings[c];
                missing.entry((a.min(b), a.max(b))).or_insert((0, x)).0 += 1;
            }
        }
        let mut miss: Vec<_> = missing.into_iter().collect();
        miss.sort_by_key(|m| std::cmp::Reverse(m.1 .0));
        for &((a, b), (count, x)) in miss.iter().take(MAX_LIST) {
            problems.push(format!(
                "completeness: no edge between sites {} and {} near {} ({count} crossings uncovered)",
                self.name(a),
                self.name(b),
                self.at(x)
            ));
        }
        if miss.len() > MAX_LIST {
            problems.push(format!(
                "completeness: ... and {} more missing pairs",
                miss.len() - MAX_LIST
            ));
        }
        let good = covered.iter().filter(|&&c| c).count();
        if crossings.is_empty() {
            1.0
        } else {
            good as f64 / crossings.len() as f64
        }
    }

    /// Check d: the edge ends (the labels were checked by `parse`).
    fn structure(&mut self) {
        let d = self.diagram;
        let dom = self.scene.domain();
        let nv = d.vertices.len();
        let mut degree = vec![0usize; nv];
        let mut errors = Vec::new();
        let mut warnings = Vec::new();
        let mut edge_gens = vec![None; d.edges.len()];
        for g in &self.edges {
            edge_gens[g.index] = Some([g.a, g.b]);
        }
        for (k, e) in d.edges.iter().enumerate() {
            if e.points.is_empty() {
                continue;
            }
            let gens = edge_gens[k];
            let (first, last) = (e.points[0], e.points[e.points.len() - 1]);
            let is_loop = e.from.is_none()
                && e.to.is_none()
                && e.points.len() > 2
                && first.dist(last) <= self.tol;
            for (name, end, p) in [("from", e.from, first), ("to", e.to, last)] {
                match end {
                    Some(v) if v >= nv => errors.push(format!(
                        "edge {k}: '{name}' = {v} is not a vertex index or null"
                    )),
                    Some(v) => {
                        degree[v] += 1;
                        let dv = p.dist(d.vertices[v].at);
                        if dv > self.tol {
                            errors.push(format!(
                                "edge {k}: '{name}' end {} is {} ({} eps) from vertex {v} at {}",
                                self.at(p),
                                fmt_g3(dv * self.unit),
                                fmt_g3(dv / self.scene.epsilon()),
                                self.at(d.vertices[v].at)
                            ));
                        }
                        if let (Some(g), Some(vg)) = (gens, &self.vgens[v]) {
                            for s in g.iter().filter(|s| !vg.contains(s)) {
                                errors.push(format!(
                                    "edge {k}: vertex {v} ('{name}') does not list its generator {}",
                                    self.name(*s)
                                ));
                            }
                        }
                    }
                    None if is_loop => {}
                    None => {
                        let db = (p.x - dom.min.x)
                            .abs()
                            .min((p.x - dom.max.x).abs())
                            .min((p.y - dom.min.y).abs())
                            .min((p.y - dom.max.y).abs());
                        if db <= self.tol {
                            continue;
                        }
                        let on_site = self
                            .near
                            .at_unmasked(p)
                            .is_none_or(|h| self.fields[h.gen].distance_to_site(p) <= self.tol);
                        if on_site {
                            warnings.push(format!(
                                "edge {k}: null '{name}' end {} ends on a site, not on the domain boundary",
                                self.at(p)
                            ));
                        } else {
                            errors.push(format!(
                                "edge {k}: null '{name}' end {} is not on the domain boundary ({} away) and not a closed loop",
                                self.at(p),
                                fmt_g3(db * self.unit)
                            ));
                        }
                    }
                }
            }
        }
        let iso = degree.iter().filter(|&&g| g == 0).count();
        if iso > 0 {
            warnings.push(format!("{iso} vertices are not referenced by any edge"));
        }
        self.errors.extend(errors);
        self.warnings.extend(warnings);
    }
}

/// Solves the 3 × 3 system `m x = b` by Gaussian elimination with partial pivoting.
fn solve3(mut m: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    for c in 0..3 {
        let p = (c..3).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        if m[p][c] == 0.0 {
            return None;
        }
        m.swap(c, p);
        b.swap(c, p);
        let (pivot, rows) = m.split_at_mut(c + 1);
        let pivot = pivot[c];
        for (r, row) in rows.iter_mut().enumerate() {
            let f = row[c] / pivot[c];
            for (x, p) in row.iter_mut().zip(pivot).skip(c) {
                *x -= f * p;
            }
            b[c + 1 + r] -= f * b[c];
        }
    }
    let mut x = [0.0; 3];
    for r in (0..3).rev() {
        let s: f64 = (r + 1..3).map(|k| m[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / m[r][r];
    }
    Some(x)
}

#[cfg(test)]
mod tests;
