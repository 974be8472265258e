//! Reconstruction inside one leaf (Emiris et al. 2013, §2.3): from the label changes on
//! the leaf's boundary ("ports") and its certificate, join the ports by bisector arcs and
//! place the Voronoi vertex. A leaf whose ports do not fit a certified pattern is split
//! locally (new ports on the split line) until they do, or until the resolution cut-off,
//! where all its ports meet at one vertex of the labels present (a near-degenerate vertex
//! of higher degree, reported as uncertified).

use super::budget::Budget;
use super::filter::{self, Certificate};
use super::segments::{label, transitions_of};
use super::trace;
use super::tree::Leaf;
use crate::geom::{Aabb, Axis, Point};
use crate::site::DistanceField;
use smallvec::{smallvec, SmallVec};

/// Ports this many ulps (of the split coordinate or the box) from a split are taken to
/// be at its corner: a root of a bisector through the corner, rounded.
const CORNER_ULPS: f64 = 8.0;

/// Identifies a port globally: a transition on a shared segment, or one on a split line
/// inside a leaf.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum PortId {
    Segment { segment: u32, index: u32 },
    Inner { leaf: u32, index: u32 },
}

/// A label change on a box boundary: the bisector of `pair` crosses the boundary at `at`.
#[derive(Clone, Copy, Debug)]
pub struct Port {
    pub id: PortId,
    pub at: Point,
    pub pair: [u32; 2],
}

/// One end of a piece: a port, or a vertex of this leaf's output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum End {
    Port(PortId),
    Vertex(u32),
}

/// The points of a piece: inline for a straight piece (two points), as most are.
pub type PiecePoints = SmallVec<[Point; 2]>;

/// A bisector arc inside the leaf between two ends, as a polyline.
#[derive(Clone, Debug)]
pub struct Piece {
    pub pair: [u32; 2],
    pub ends: [End; 2],
    pub points: PiecePoints,
}

/// A Voronoi vertex found in the leaf, with its generators (sorted).
#[derive(Clone, Debug)]
pub struct FoundVertex {
    pub at: Point,
    pub sites: Vec<u32>,
}

/// What a leaf contributes to the diagram.
#[derive(Clone, Debug, Default)]
pub struct LeafOutput {
    pub pieces: Vec<Piece>,
    pub vertices: Vec<FoundVertex>,
    pub uncertified: u32,
    pub local_splits: u32,
}

/// Tolerances of the reconstruction.
#[derive(Clone, Copy, Debug)]
pub struct Tolerances {
    /// Maximum distance of a traced chord from the bisector.
    pub trace: f64,
    /// Boxes this small are not split again.
    pub min_box: f64,
    /// Label changes along a segment are isolated to this length.
    pub scan: f64,
}

pub struct Resolver<'a, F> {
    pub fields: &'a [F],
    pub tol: Tolerances,
    /// Local splits take boxes from it, traced polylines take points.
    pub budget: &'a Budget,
    pub leaf: u32,
    next_inner: u32,
}

impl<'a, F: DistanceField> Resolver<'a, F> {
    pub fn new(fields: &'a [F], tol: Tolerances, budget: &'a Budget, leaf: u32) -> Self {
        Resolver {
            fields,
            tol,
            budget,
            leaf,
            next_inner: 0,
        }
    }

    /// Resolves a leaf of the subdivision, using the certificate it stopped with and the
    /// states of its sites where the subdivision kept them (`kept`, else empty).
    pub fn resolve_leaf(
        &mut self,
        leaf: &Leaf,
        kept: &[F::State],
        ports: Vec<Port>,
        out: &mut LeafOutput,
    ) {
        if let Certificate::Monotone { over_y } = leaf.certificate {
            self.join_monotone(&leaf.aabb, &ports, over_y, out);
        } else {
            let kept = (kept.len() == leaf.sites.len()).then_some(kept);
            self.resolve(leaf.aabb, &leaf.sites, kept, ports, out);
        }
    }

    /// Resolves the box `b` with candidate sites `sites` (sorted), their states over `b`
    /// if known, and boundary `ports`.
    pub fn resolve(
        &mut self,
        b: Aabb,
        sites: &[u32],
        kept: Option<&[F::State]>,
        ports: Vec<Port>,
        out: &mut LeafOutput,
    ) {
        if sites.len() <= 1 {
            return;
        }
        let mut envelope = None;
        if ports.is_empty() {
            let e = self.envelope(&b, sites, kept);
            if self.no_island(&b, &e) {
                return;
            }
            envelope = Some(e);
        }
        if !self.budget.take_box() {
            return;
        }
        if b.longest_side() <= self.tol.min_box {
            self.fallback(b, sites, &ports, out);
            return;
        }
        let envelope = envelope.unwrap_or_else(|| self.envelope(&b, sites, kept));
        let active = &envelope.sites;
        let ids: Vec<u32> = active.iter().map(|s| s.0).collect();
        let labels_known = ports.iter().all(|p| p.pair.iter().all(|l| ids.contains(l)));
        if labels_known {
            match filter::certify(self.fields, &b, &envelope) {
                Certificate::Monotone { over_y } => {
                    self.join_monotone(&b, &ports, over_y, out);
                    return;
                }
                Certificate::SingleVertex if self.try_vertex(&b, active, &ports, out) => return,
                _ => {}
            }
            if active.len() <= 1 && ports.is_empty() {
                return;
            }
        }
        self.split(b, &ids, ports, out);
    }

    /// The lower envelope over `b` of `sites`, with their states `kept` or built afresh.
    fn envelope(
        &self,
        b: &Aabb,
        sites: &[u32],
        kept: Option<&[F::State]>,
    ) -> filter::Envelope<F::State> {
        let states: Vec<(u32, F::State)> = match kept {
            Some(kept) => sites.iter().copied().zip(kept.iter().cloned()).collect(),
            None => sites
                .iter()
                .map(|&s| (s, self.fields[s as usize].state(b)))
                .collect(),
        };
        filter::lower_envelope(self.fields, b, states)
    }

    /// With no port, a cell can still lie wholly inside the box (an island); it cannot
    /// when the box holds two sites whose bisector is monotone.
    fn no_island(&self, b: &Aabb, envelope: &filter::Envelope<F::State>) -> bool {
        envelope.sites.len() <= 1
            || matches!(
                filter::certify(self.fields, b, envelope),
                Certificate::Monotone { .. }
            )
    }

    /// Two sites with a monotone bisector: its arcs are graphs over one axis with disjoint
    /// ranges, so the ports sorted along that axis pair up consecutively.
    fn join_monotone(&self, b: &Aabb, ports: &[Port], over_y: bool, out: &mut LeafOutput) {
        let mut sorted: Vec<&Port> = ports.iter().collect();
        sorted.sort_by(|p, q| {
            let (a, b) = if over_y {
                (p.at.y, q.at.y)
            } else {
                (p.at.x, q.at.x)
            };
            a.total_cmp(&b)
        });
        for pq in sorted.chunks(2) {
            if let [p, q] = pq {
                let pair = ordered(p.pair);
                let points = trace::trace_graph(
                    self.fields,
                    pair[0],
                    pair[1],
                    p.at,
                    q.at,
                    over_y,
                    b,
                    self.tol.trace,
                    self.budget,
                );
                out.pieces.push(Piece {
                    pair,
                    ends: [End::Port(p.id), End::Port(q.id)],
                    points: points.into(),
                });
            }
        }
    }

    /// Three sites with at most one vertex: if Newton finds it and each pair crosses the
    /// boundary once, the three ports meet there; with no vertex, each pair must have
    /// an even number of ports and a monotone bisector. Returns false when neither holds.
    fn try_vertex(
        &self,
        b: &Aabb,
        active: &[(u32, F::State)],
        ports: &[Port],
        out: &mut LeafOutput,
    ) -> bool {
        let s = [active[0].0, active[1].0, active[2].0];
        let count = |x: u32, y: u32| ports.iter().filter(|p| same_pair(p.pair, x, y)).count();
        let counts = [count(s[0], s[1]), count(s[0], s[2]), count(s[1], s[2])];
        if let Some(v) = trace::vertex(self.fields, s, b) {
            if counts != [1, 1, 1] {
                return false;
            }
            let vi = out.vertices.len() as u32;
            out.vertices.push(FoundVertex {
                at: v,
                sites: sorted3(s),
            });
            for p in ports {
                let pair = ordered(p.pair);
                let i = |x: u32| active.iter().position(|a| a.0 == x).unwrap_or(0);
                let pb = filter::pair(self.fields, active, i(pair[0]), i(pair[1]), b);
                let points = match filter::monotone(&pb) {
                    Some(over_y) => trace::trace_graph(
                        self.fields,
                        pair[0],
                        pair[1],
                        p.at,
                        v,
                        over_y,
                        b,
                        self.tol.trace,
                        self.budget,
                    ),
                    None => trace::trace(
                        self.fields,
                        pair[0],
                        pair[1],
                        p.at,
                        v,
                        self.tol.trace,
                        self.budget,
                    ),
                };
                out.pieces.push(Piece {
                    pair,
                    ends: [End::Port(p.id), End::Vertex(vi)],
                    points: points.into(),
                });
            }
            return true;
        }
        let pairs = [(0, 1), (0, 2), (1, 2)];
        let mut plan = Vec::new();
        for (k, &(i, j)) in pairs.iter().enumerate() {
            if counts[k] == 0 {
                continue;
            }
            let p = filter::pair(self.fields, active, i, j, b);
            match filter::monotone(&p) {
                Some(over_y) if counts[k] % 2 == 0 => plan.push((s[i], s[j], over_y)),
                _ => return false,
            }
        }
        for (x, y, over_y) in plan {
            let mine: Vec<Port> = ports
                .iter()
                .filter(|p| same_pair(p.pair, x, y))
                .copied()
                .collect();
            self.join_monotone(b, &mine, over_y, out);
        }
        true
    }

    /// Splits the box in halves along its longer side, scans the split line for label
    /// changes (new inner ports) and resolves both halves.
    fn split(&mut self, b: Aabb, sites: &[u32], ports: Vec<Port>, out: &mut LeafOutput) {
        out.local_splits += 1;
        let axis = if b.width() >= b.height() {
            Axis::X
        } else {
            Axis::Y
        };
        let mid = b.center().coord(axis);
        let (lo, hi) = b.split(axis, mid);
        let (p0, p1) = match axis {
            Axis::X => (Point::new(mid, b.min.y), Point::new(mid, b.max.y)),
            Axis::Y => (Point::new(b.min.x, mid), Point::new(b.max.x, mid)),
        };
        let inner: Vec<Port> = transitions_of(
            self.fields,
            sites,
            p0,
            p1,
            self.tol.scan,
            self.budget.watch(),
        )
        .into_iter()
        .map(|t| {
            let id = PortId::Inner {
                leaf: self.leaf,
                index: self.next_inner,
            };
            self.next_inner += 1;
            Port {
                id,
                at: t.at,
                pair: t.pair,
            }
        })
        .collect();
        let (mut lower, mut upper): (Vec<Port>, Vec<Port>) = ports
            .into_iter()
            .partition(|p| self.goes_lower(&b, sites, p, axis, mid));
        lower.extend_from_slice(&inner);
        upper.extend(inner);
        self.resolve(lo, sites, None, lower, out);
        self.resolve(hi, sites, None, upper, out);
    }

    /// Whether port `p` of box `b` (with sites `sites`) belongs to the lower half when
    /// `b` is split at `mid` along `axis`. A port at the split (a corner of both halves,
    /// to within the rounding of its root: a bisector through the corner, tied there)
    /// goes to the half whose side holds the label change: every side runs towards
    /// greater coordinates with `pair[0]` before `pair[1]`, and the scan of the split
    /// line sees the corner's label, so the change lies below the corner when that label
    /// is `pair[1]` and above it when it is `pair[0]`; both halves' boundaries then agree
    /// with the split line's ports. A port exactly at a corner labelled by a third site
    /// goes to the half its bisector enters: the one its tangent, pointed into `b`,
    /// leans towards.
    fn goes_lower(&self, b: &Aabb, sites: &[u32], p: &Port, axis: Axis, mid: f64) -> bool {
        let at = p.at.coord(axis);
        let rounding = CORNER_ULPS * f64::EPSILON * mid.abs().max(b.longest_side());
        if (at - mid).abs() <= rounding {
            let corner = match axis {
                Axis::X => Point::new(mid, p.at.y),
                Axis::Y => Point::new(p.at.x, mid),
            };
            let corner = label(self.fields, sites, corner);
            if corner == p.pair[1] {
                return true;
            }
            if corner == p.pair[0] {
                return false;
            }
        }
        if at != mid {
            return at < mid;
        }
        let [f, g] = p.pair.map(|s| &self.fields[s as usize]);
        let normal = f.gradient(p.at) - g.gradient(p.at);
        let tangent = Point::new(-normal.y, normal.x);
        // the box's side the port lies on, across the split line
        let (along, across, low_side) = match axis {
            Axis::X => (tangent.x, tangent.y, p.at.y <= b.center().y),
            Axis::Y => (tangent.y, tangent.x, p.at.x <= b.center().x),
        };
        let inward = if low_side { across } else { -across };
        if inward == 0.0 || along == 0.0 {
            return true;
        }
        (along < 0.0) == (inward > 0.0)
    }

    /// At the resolution cut-off: one vertex at the box centre joins all ports when three
    /// or more labels meet; with two labels the ports pair up around the boundary so that
    /// the centre's label stays connected.
    fn fallback(&self, b: Aabb, sites: &[u32], ports: &[Port], out: &mut LeafOutput) {
        if ports.is_empty() {
            return;
        }
        out.uncertified += 1;
        let mut labels: Vec<u32> = ports.iter().flat_map(|p| p.pair).collect();
        labels.sort_unstable();
        labels.dedup();
        let c = b.center();
        let mut cyc: Vec<&Port> = ports.iter().collect();
        cyc.sort_by(|p, q| perimeter(&b, p.at).total_cmp(&perimeter(&b, q.at)));
        if labels.len() >= 3 {
            // bisectors that only pass through (a cell thinner than the box between two
            // others) pair up without crossing; a vertex is needed only when they cannot
            if let Some(matching) = noncrossing_matching(&cyc) {
                for (i, j) in matching {
                    let (p, q) = (cyc[i], cyc[j]);
                    out.pieces.push(Piece {
                        pair: ordered(p.pair),
                        ends: [End::Port(p.id), End::Port(q.id)],
                        points: smallvec![p.at, q.at],
                    });
                }
                return;
            }
        }
        if labels.len() >= 3 || ports.len() % 2 == 1 {
            let vi = out.vertices.len() as u32;
            out.vertices.push(FoundVertex {
                at: c,
                sites: labels,
            });
            for p in ports {
                out.pieces.push(Piece {
                    pair: ordered(p.pair),
                    ends: [End::Port(p.id), End::Vertex(vi)],
                    points: smallvec![p.at, c],
                });
            }
            return;
        }
        let centre = label(self.fields, sites, c);
        // the arc after cyc[0] (towards cyc[1]) has label `after`: pairing (0,1),(2,3)...
        // cuts those arcs off from the centre, so they must not carry the centre's label
        let after = label(self.fields, sites, arc_point(&b, cyc[0].at, cyc[1].at));
        let shift = usize::from(after == centre);
        let n = cyc.len();
        for k in (0..n).step_by(2) {
            let (p, q) = (cyc[(k + shift) % n], cyc[(k + shift + 1) % n]);
            out.pieces.push(Piece {
                pair: ordered(p.pair),
                ends: [End::Port(p.id), End::Port(q.id)],
                points: smallvec![p.at, q.at],
            });
        }
    }
}

/// Pairs ports of the same bisector that are adjacent in the cyclic order, repeatedly
/// (cancellation of equal neighbours in a cyclic word); the pairs found this way never
/// cross. `None` when some port is left over.
fn noncrossing_matching(cyc: &[&Port]) -> Option<Vec<(usize, usize)>> {
    let mut stack: Vec<usize> = Vec::new();
    let mut pairs = Vec::new();
    let key = |k: usize| ordered(cyc[k].pair);
    for k in 0..cyc.len() {
        match stack.last() {
            Some(&t) if key(t) == key(k) => {
                stack.pop();
                pairs.push((t, k));
            }
            _ => stack.push(k),
        }
    }
    // what is left may still cancel across the wrap-around
    while stack.len() >= 2 && key(stack[0]) == key(stack[stack.len() - 1]) {
        let (first, last) = (stack.remove(0), stack.pop().unwrap_or(0));
        pairs.push((first, last));
    }
    stack.is_empty().then_some(pairs)
}

fn same_pair(p: [u32; 2], x: u32, y: u32) -> bool {
    (p[0] == x && p[1] == y) || (p[0] == y && p[1] == x)
}

fn ordered(p: [u32; 2]) -> [u32; 2] {
    [p[0].min(p[1]), p[0].max(p[1])]
}

fn sorted3(mut s: [u32; 3]) -> Vec<u32> {
    s.sort_unstable();
    s.to_vec()
}

/// The arc-length position of a boundary point, counter-clockwise from `b.min`.
fn perimeter(b: &Aabb, p: Point) -> f64 {
    let (w, h) = (b.width(), b.height());
    let d = [
        (p.y - b.min.y).abs(),
        (p.x - b.max.x).abs(),
        (p.y - b.max.y).abs(),
        (p.x - b.min.x).abs(),
    ];
    let side = (0..4).min_by(|&i, &j| d[i].total_cmp(&d[j])).unwrap_or(0);
    match side {
        0 => p.x - b.min.x,
        1 => w + (p.y - b.min.y),
        2 => w + h + (b.max.x - p.x),
        _ => 2.0 * w + h + (b.max.y - p.y),
    }
}

/// A boundary point between `p` and `q`, counter-clockwise from `p`.
fn arc_point(b: &Aabb, p: Point, q: Point) -> Point {
    let (w, h) = (b.width(), b.height());
    let total = 2.0 * (w + h);
    let (s, t) = (perimeter(b, p), perimeter(b, q));
    let t = if t < s { t + total } else { t };
    let m = (0.5 * (s + t)) % total;
    if m < w {
        Point::new(b.min.x + m, b.min.y)
    } else if m < w + h {
        Point::new(b.max.x, b.min.y + (m - w))
    } else if m < 2.0 * w + h {
        Point::new(b.max.x - (m - w - h), b.max.y)
    } else {
        Point::new(b.min.x, b.max.y - (m - 2.0 * w - h))
    }
}
