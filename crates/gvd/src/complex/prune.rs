//! Pruning the medial axis of the branches that small boundary details give it.
//!
//! A point `q` of an edge with generators `g1, g2` has two nearest boundary points, the
//! feet `f1, f2` (the generators' nearest points). Two criteria judge it:
//! * the λ-medial axis (CL05): `q` stays when its nearest boundary points do not fit in
//!   a disc of radius below λ, i.e. `|f1 − f2| / 2 ≥ λ`;
//! * the object angle (FLM03): `q` stays when the feet subtend `∠f1 q f2 ≥ θ`.
//!
//! With both set a point stays when it passes both. Each edge keeps the runs of its
//! polyline that pass, with the ends of a run located by bisection to within epsilon/4
//! between a point that passes and one that does not. The graph is then mended: a cut
//! end becomes a vertex of degree one (its two generators the edge's), vertices left with
//! no edge go (an isolated point of the pruned set is dropped), and every vertex of
//! degree two is merged away, joining its two edges into one; the joined edge's
//! generators change where the vertex was ([`Edge::sites_along`]).

use super::{Edge, Generator, SitesChange, Vertex, VoronoiComplex};
use crate::clearance::{with_feet, Feet};
use crate::error::Error;
use crate::geom::Point;
use crate::scene::{Mode, Scene};

/// Which points of the medial axis to keep (`Options::prune`); the default keeps all.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pruning {
    /// The λ-medial axis (CL05): keep the points whose two nearest boundary points are at
    /// least `2λ` apart (a length of the scene, finite and > 0).
    pub lambda: Option<f64>,
    /// The object angle θ (FLM03), in radians in (0, π]: keep the points whose two
    /// nearest boundary points subtend at least θ there.
    pub object_angle: Option<f64>,
}

impl Pruning {
    /// Whether any criterion is set.
    pub fn is_on(&self) -> bool {
        self.lambda.is_some() || self.object_angle.is_some()
    }

    /// Refuses a λ that is not a finite length > 0 or an angle outside (0, π].
    pub fn check(&self) -> Result<(), Error> {
        let invalid = |option: &str, message: String| Error::InvalidOption {
            option: option.into(),
            message,
        };
        if let Some(l) = self.lambda.filter(|l| !(l.is_finite() && *l > 0.0)) {
            return Err(invalid(
                "prune.lambda",
                format!("must be a finite length > 0, found {l}"),
            ));
        }
        if let Some(t) = self
            .object_angle
            .filter(|t| !(*t > 0.0 && *t <= std::f64::consts::PI))
        {
            return Err(invalid(
                "prune.object_angle",
                format!("must be an angle in (0, π] radians, found {t}"),
            ));
        }
        Ok(())
    }

    /// Whether the point `q` with feet `f1, f2` passes every criterion set. A point on
    /// the boundary (`q` at a foot) subtends no angle.
    fn keeps(&self, q: Point, f1: Point, f2: Point) -> bool {
        let wide = self.lambda.is_none_or(|l| f1.dist(f2) >= 2.0 * l);
        let open = self.object_angle.is_none_or(|theta| {
            let (a, b) = (f1 - q, f2 - q);
            a.norm() > 0.0 && b.norm() > 0.0 && a.cross(b).atan2(a.dot(b)).abs() >= theta
        });
        wide && open
    }
}

/// What [`prune`] did, for `stats.pruning`.
#[derive(Debug, PartialEq, Eq)]
pub struct PruneCounts {
    /// Edges and vertices before.
    pub edges_before: usize,
    /// Vertices before.
    pub vertices_before: usize,
    /// New vertices of degree one where a branch was cut.
    pub cut_ends: usize,
    /// Vertices of degree two merged away.
    pub merged_vertices: usize,
}

/// A run of an edge's polyline that passes, with whether each end was cut.
struct Run {
    points: Vec<Point>,
    cut_start: bool,
    cut_end: bool,
}

/// Prunes `complex` (computed from `scene`) by `pruning`, in place; see the module
/// notes. Clearances, where the edges carry them, are computed for the new points.
/// Refuses generators whose nearest points are not known here (point metrics other than
/// Euclidean, ellipses, fields, algebraic curves), naming the site, and
/// edges with exact bisector pieces, which it would not cut; drops the free-form
/// engine's parameter-space pieces.
pub fn prune(
    complex: &mut VoronoiComplex,
    scene: &Scene,
    pruning: &Pruning,
) -> Result<PruneCounts, Error> {
    pruning.check()?;
    with_feet(scene, |feet| prune_with(complex, scene, feet, pruning))
}

/// [`prune`] with the feet of `scene`'s generators.
pub(crate) fn prune_with(
    complex: &mut VoronoiComplex,
    scene: &Scene,
    feet: &Feet,
    pruning: &Pruning,
) -> Result<PruneCounts, Error> {
    check_feet_known(complex, scene, feet)?;
    if complex.edges.iter().any(|e| !e.bisector.is_empty()) {
        return Err(Error::InvalidOption {
            option: "prune".into(),
            message: "pruning does not cut exact bisector pieces: compute without them".into(),
        });
    }
    let counts_before = (complex.edges.len(), complex.vertices.len());
    // the free-form engine's parameter-space pieces describe the uncut edges
    for e in &mut complex.edges {
        e.parametric.clear();
    }
    let with_clearance = scene.mode() != Mode::Voronoi;
    let clearance = |sites: &[Generator; 2], q: Point| {
        Some(feet.generators_clearance(sites, q)).filter(|r| with_clearance && r.is_finite())
    };
    let passes = |e: &Edge, q: Point| {
        let f = e.sites.map(|g| feet.foot(&g, q).unwrap_or(q));
        pruning.keeps(q, f[0], f[1])
    };
    let (cut_ends, merged_vertices) =
        keep_passing(complex, &passes, scene.epsilon() / 4.0, &clearance);
    Ok(PruneCounts {
        edges_before: counts_before.0,
        vertices_before: counts_before.1,
        cut_ends,
        merged_vertices,
    })
}

/// Keeps the runs of each edge's polyline whose points pass (`passes(edge, q)`), and
/// mends the graph as the module notes say: each cut end becomes a vertex of degree one
/// listing the edge's generators, with `clearance(generators, point)`; the clearances of
/// the kept points are recomputed where the edge carried them; vertices left with no
/// edge go, and those of degree two are merged away. Returns the numbers of cut ends and
/// of merged vertices.
pub(crate) fn keep_passing(
    complex: &mut VoronoiComplex,
    passes: &dyn Fn(&Edge, Point) -> bool,
    tolerance: f64,
    clearance: &dyn Fn(&[Generator; 2], Point) -> Option<f64>,
) -> (usize, usize) {
    let mut vertices = std::mem::take(&mut complex.vertices);
    let mut edges = Vec::with_capacity(complex.edges.len());
    let mut cut_ends = 0;
    for e in std::mem::take(&mut complex.edges) {
        for run in passing_runs(&e, &|q| passes(&e, q), tolerance) {
            let mut end_vertex = |cut: bool, at: Point, old: Option<usize>| {
                if !cut {
                    return old;
                }
                cut_ends += 1;
                vertices.push(Vertex {
                    at,
                    sites: e.sites.iter().copied().collect(),
                    clearance: clearance(&e.sites, at),
                });
                Some(vertices.len() - 1)
            };
            let from = end_vertex(run.cut_start, run.points[0], e.from);
            let to = end_vertex(
                run.cut_end,
                *run.points.last().unwrap_or(&run.points[0]),
                e.to,
            );
            let radii = if e.clearance.is_empty() {
                Vec::new()
            } else {
                run.points
                    .iter()
                    .map(|&q| clearance(&e.sites, q).unwrap_or(f64::NAN))
                    .collect()
            };
            edges.push(Edge {
                sites: e.sites,
                from,
                to,
                points: run.points.into(),
                bisector: Vec::new(),
                parametric: Vec::new(),
                clearance: radii,
                sites_along: Vec::new(),
            });
        }
    }
    let merged_vertices = merge_degree_two(&mut edges, vertices.len());
    complex.edges = edges;
    complex.vertices = vertices;
    complex.drop_unused_vertices();
    (cut_ends, merged_vertices)
}

/// Refuses a generator whose feet are not known, naming its site.
fn check_feet_known(complex: &VoronoiComplex, scene: &Scene, feet: &Feet) -> Result<(), Error> {
    for e in &complex.edges {
        let Some(&q) = e.points.first() else { continue };
        if let Some(g) = e.sites.iter().find(|g| feet.foot(g, q).is_none()) {
            let site = g.site();
            let kind = scene
                .sites()
                .get(site)
                .map_or("unknown", |s| s.kind.name())
                .to_string();
            return Err(Error::Unsupported {
                site,
                kind,
                message: "pruning needs each generator's nearest points, known here for \
                          Euclidean points, circles, segments, arcs, polylines, polygons, \
                          Bézier and B-spline curves"
                    .into(),
            });
        }
    }
    Ok(())
}

/// The maximal runs of `e`'s polyline whose points pass, each end between a passing and a
/// failing point located by bisection to within `tolerance` (on the passing side). A
/// closed loop with no vertex whose first point passes joins its last run to its first.
fn passing_runs(e: &Edge, passes: &dyn Fn(Point) -> bool, tolerance: f64) -> Vec<Run> {
    let points = &e.points;
    let flags: Vec<bool> = points.iter().map(|&q| passes(q)).collect();
    if flags.iter().all(|&f| f) {
        return vec![Run {
            points: points.to_vec(),
            cut_start: false,
            cut_end: false,
        }];
    }
    let mut runs = Vec::new();
    let mut current: Option<Run> = flags[0].then(|| Run {
        points: vec![points[0]],
        cut_start: false,
        cut_end: false,
    });
    for k in 1..points.len() {
        let (a, b) = (points[k - 1], points[k]);
        match (flags[k - 1], flags[k]) {
            (true, true) => push_distinct(current.as_mut(), b),
            (true, false) => {
                let mut run = current.take().expect("a passing point opened a run");
                push_distinct(Some(&mut run), boundary(a, b, passes, tolerance));
                run.cut_end = true;
                runs.push(run);
            }
            (false, true) => {
                let mut run = Run {
                    points: vec![boundary(b, a, passes, tolerance)],
                    cut_start: true,
                    cut_end: false,
                };
                push_distinct(Some(&mut run), b);
                current = Some(run);
            }
            (false, false) => {}
        }
    }
    runs.extend(current);
    let closed_loop = e.from.is_none() && e.to.is_none() && points.first() == points.last();
    if closed_loop && flags[0] && runs.len() > 1 {
        let first = runs.remove(0);
        let last = runs.last_mut().expect("two runs or more");
        last.points.extend_from_slice(&first.points[1..]);
        last.cut_end = first.cut_end;
    }
    runs.retain(|r| r.points.len() >= 2);
    runs
}

/// Appends `q` to the run unless it repeats the run's last point.
fn push_distinct(run: Option<&mut Run>, q: Point) {
    if let Some(run) = run {
        if run.points.last() != Some(&q) {
            run.points.push(q);
        }
    }
}

/// Between `inside` (which passes) and `outside` (which does not), a point that passes
/// within `tolerance` of where passing stops, by bisection.
fn boundary(
    mut inside: Point,
    mut outside: Point,
    passes: &dyn Fn(Point) -> bool,
    tolerance: f64,
) -> Point {
    for _ in 0..64 {
        if inside.dist(outside) <= tolerance {
            break;
        }
        let middle = inside.lerp(outside, 0.5);
        if passes(middle) {
            inside = middle;
        } else {
            outside = middle;
        }
    }
    inside
}

/// Merges away every vertex of degree two (of `vertex_count`), joining its two edges;
/// returns how many. A loop through its only vertex becomes a closed loop with no
/// vertex. Joined edges are left as empty placeholders, then removed.
fn merge_degree_two(edges: &mut Vec<Edge>, vertex_count: usize) -> usize {
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); vertex_count];
    for (k, e) in edges.iter().enumerate() {
        for v in [e.from, e.to].into_iter().flatten() {
            incident[v].push(k);
        }
    }
    let mut merged = 0;
    let mut alive = vec![true; edges.len()];
    for v in 0..vertex_count {
        let [a, b] = incident[v][..] else { continue };
        merged += 1;
        if a == b {
            let e = &mut edges[a];
            (e.from, e.to) = (None, None);
            incident[v].clear();
            continue;
        }
        // Orient a to end at v and b to start there, then append b to a.
        if edges[a].to != Some(v) {
            reverse(&mut edges[a]);
        }
        if edges[b].from != Some(v) {
            reverse(&mut edges[b]);
        }
        let sites = edges[b].sites;
        let tail = std::mem::replace(&mut edges[b], placeholder(sites));
        alive[b] = false;
        let far_end = tail.to;
        append(&mut edges[a], tail);
        incident[v].clear();
        if let Some(w) = far_end {
            for slot in incident[w].iter_mut().filter(|k| **k == b) {
                *slot = a;
            }
        }
    }
    let mut k = 0;
    edges.retain(|_| {
        k += 1;
        alive[k - 1]
    });
    merged
}

/// `e` run the other way: its points, clearances, ends and generator changes.
fn reverse(e: &mut Edge) {
    let n = e.points.len();
    let mut pieces: Vec<(usize, [Generator; 2])> = std::iter::once((0, e.sites))
        .chain(e.sites_along.iter().map(|c| (c.start, c.sites)))
        .collect();
    // A piece from point s to the next piece's start t runs from n−1−t to n−1−s reversed.
    let ends: Vec<usize> = pieces.iter().skip(1).map(|p| p.0).chain([n - 1]).collect();
    for (piece, end) in pieces.iter_mut().zip(ends) {
        piece.0 = n - 1 - end;
    }
    pieces.reverse();
    e.sites = pieces[0].1;
    e.sites_along = pieces[1..]
        .iter()
        .map(|&(start, sites)| SitesChange { start, sites })
        .collect();
    e.points.reverse();
    e.clearance.reverse();
    (e.from, e.to) = (e.to, e.from);
}

/// Appends `tail` (which starts where `head` ends) to `head`.
fn append(head: &mut Edge, tail: Edge) {
    let offset = head.points.len() - 1;
    head.sites_along.push(SitesChange {
        start: offset,
        sites: tail.sites,
    });
    head.sites_along
        .extend(tail.sites_along.iter().map(|c| SitesChange {
            start: c.start + offset,
            sites: c.sites,
        }));
    head.points.extend_from_slice(&tail.points[1..]);
    if !head.clearance.is_empty() && !tail.clearance.is_empty() {
        head.clearance.extend_from_slice(&tail.clearance[1..]);
    } else {
        head.clearance.clear();
    }
    head.to = tail.to;
}

/// An empty edge left where a joined edge was, removed afterwards.
fn placeholder(sites: [Generator; 2]) -> Edge {
    Edge {
        sites,
        from: None,
        to: None,
        points: Default::default(),
        bisector: Vec::new(),
        parametric: Vec::new(),
        clearance: Vec::new(),
        sites_along: Vec::new(),
    }
}
