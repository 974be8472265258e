//! The certified enclosure of a curve `{f = 0} ∩ clip`: a quadtree over the clip box in
//! which a box is dropped only when the Bernstein range of `f` over it excludes 0
//! (convex-hull property; tighter than the modified affine arithmetic of Shou et al.
//! 2011, §2). Every point of the curve lies in a leaf; the leaves stop at `leaf_size`.
//!
//! **Witnesses.** A leaf side whose two corners have certified opposite signs of `f`
//! holds a point of the curve (continuity). The crossing is refined by the Illinois
//! method and kept with a certified bracket: a short piece of the side at whose ends
//! interval evaluations of `f` have opposite signs. Brackets give the rigorous upper
//! bounds of the distance; their refined points are the leaf's *samples* (points of the
//! curve to f64 accuracy), and two crossings of one leaf make its *chord*, along which
//! the nearest-point search looks first.
//!
//! Node boxes are the hulls of their leaves, grown by a margin covering the rounding of
//! the split coordinates (children's Bernstein forms stand for the exact halves).

use super::dense::Jet;
use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::Bernstein2;
use crate::num::interval::{round_down, round_up};
use crate::num::Interval;

pub(super) use crate::site::curve_tree::NONE;

/// A certified point of the curve: it lies on the segment `a`–`b`; `p` is its f64
/// refinement.
#[derive(Clone, Copy, Debug)]
pub(super) struct Witness {
    pub a: Point,
    pub b: Point,
    pub p: Point,
}

/// A node of the enclosure.
#[derive(Clone, Debug)]
pub(super) struct Node {
    /// Holds every point of the curve under this node.
    pub bbox: Aabb,
    /// Children: `kids[first..first + count]` (no children: a leaf).
    pub first: u32,
    pub count: u32,
    /// A witness under this node ([`NONE`] if none).
    pub witness: u32,
    /// For a leaf, its index in [`Enclosure::leaves`] ([`NONE`] otherwise).
    pub leaf: u32,
    /// A componentwise enclosure of `∇f` over the node's box.
    pub normal: [Interval; 2],
    /// The unit vectors `∇f/|∇f|` over `normal` (`None` where it may hold 0).
    pub unit_normal: Option<[Interval; 2]>,
}

/// What a leaf knows of the curve inside it.
#[derive(Clone, Debug, Default)]
pub(super) struct Leaf {
    /// Points of the curve (f64 accuracy).
    pub samples: Vec<Point>,
    /// Two crossings of the leaf's sides, when it has exactly two.
    pub chord: Option<(Point, Point)>,
    /// A thin region holding every point of the curve in the leaf, where `f` is
    /// monotone across the curve's direction.
    pub strip: Option<Strip>,
}

/// The points within `half_width` of the segment `a`–`b`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Strip {
    pub a: Point,
    pub b: Point,
    pub half_width: f64,
}

/// The enclosure tree; the root is the last node.
#[derive(Clone, Debug, Default)]
pub(super) struct Enclosure {
    pub nodes: Vec<Node>,
    pub kids: Vec<u32>,
    pub leaves: Vec<Leaf>,
    pub witnesses: Vec<Witness>,
    pub margin: f64,
}

/// Deepest refinement below the clip box.
const MAX_DEPTH: u32 = 40;
/// Most boxes an enclosure may visit: bounded work where f64 cannot resolve the curve
/// over its clip box (a tiny curve in a huge domain keeps every box near it undecided).
pub(super) const MAX_BOXES: usize = 1 << 20;

impl Enclosure {
    /// The enclosure of `{f = 0} ∩ clip` with leaves no longer than `leaf_size`, or
    /// `None` when it needs more than [`MAX_BOXES`] boxes.
    pub(super) fn build(
        f: &crate::num::poly::Poly,
        jet: &Jet,
        clip: &Aabb,
        leaf_size: f64,
    ) -> Option<Self> {
        let magnitude = clip
            .min
            .x
            .abs()
            .max(clip.max.x.abs())
            .max(clip.min.y.abs())
            .max(clip.max.y.abs())
            .max(clip.longest_side());
        let mut e = Enclosure {
            margin: 64.0 * f64::EPSILON * magnitude,
            ..Default::default()
        };
        let builder = Builder {
            f,
            jet,
            leaf_size,
            boxes: std::cell::Cell::new(0),
        };
        let form = Bernstein2::from_poly(f, clip);
        builder.node(&mut e, *clip, &form, 0);
        (builder.boxes.get() <= MAX_BOXES).then_some(e)
    }

    pub(super) fn root(&self) -> Option<u32> {
        self.nodes.len().checked_sub(1).map(|r| r as u32)
    }

    pub(super) fn children(&self, n: u32) -> &[u32] {
        let node = &self.nodes[n as usize];
        &self.kids[node.first as usize..(node.first + node.count) as usize]
    }

    /// The leaf whose box holds `p`, if any (the first found).
    pub(super) fn leaf_at(&self, p: Point) -> Option<u32> {
        let mut stack = vec![self.root()?];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if !node.bbox.contains(p) {
                continue;
            }
            if node.leaf != NONE {
                return Some(node.leaf);
            }
            stack.extend_from_slice(self.children(n));
        }
        None
    }

    /// Adds a point of the curve to the leaf holding it (value searches only).
    pub(super) fn add_sample(&mut self, p: Point) -> bool {
        match self.leaf_at(p) {
            Some(l) => {
                self.leaves[l as usize].samples.push(p);
                true
            }
            None => false,
        }
    }

    /// Adds `w` as a witness of the leaf holding its point and of every ancestor that
    /// has none.
    pub(super) fn add_witness(&mut self, w: Witness) {
        let id = self.witnesses.len() as u32;
        let Some(root) = self.root() else { return };
        let mut path = Vec::new();
        let mut stack = vec![(root, 0usize)];
        // depth-first for the path to a leaf holding w.p
        while let Some((n, depth)) = stack.pop() {
            path.truncate(depth);
            let node = &self.nodes[n as usize];
            if !node.bbox.contains(w.p) {
                continue;
            }
            path.push(n);
            if node.leaf != NONE {
                self.witnesses.push(w);
                for &m in &path {
                    if self.nodes[m as usize].witness == NONE {
                        self.nodes[m as usize].witness = id;
                    }
                }
                return;
            }
            for &c in self.children(n) {
                stack.push((c, depth + 1));
            }
        }
    }
}

struct Builder<'a> {
    f: &'a crate::num::poly::Poly,
    jet: &'a Jet,
    leaf_size: f64,
    /// Boxes visited, against [`MAX_BOXES`].
    boxes: std::cell::Cell<usize>,
}

impl Builder<'_> {
    fn node(&self, e: &mut Enclosure, b: Aabb, form: &Bernstein2, depth: u32) -> Option<u32> {
        self.boxes.set(self.boxes.get() + 1);
        if self.boxes.get() > MAX_BOXES || form.range().excludes_zero() {
            return None;
        }
        if b.longest_side() <= self.leaf_size || depth >= MAX_DEPTH {
            return Some(self.leaf(e, b, form));
        }
        let axis = if b.width() >= b.height() {
            Axis::X
        } else {
            Axis::Y
        };
        let at = match axis {
            Axis::X => b.min.x + 0.5 * b.width(),
            Axis::Y => b.min.y + 0.5 * b.height(),
        };
        let (lb, ub) = b.split(axis, at);
        let (lf, uf) = form.split(axis, 0.5);
        let kids: Vec<u32> = [(lb, lf), (ub, uf)]
            .into_iter()
            .filter_map(|(hb, hf)| self.node(e, hb, &hf, depth + 1))
            .collect();
        if kids.is_empty() {
            return None;
        }
        let mut bbox = e.nodes[kids[0] as usize].bbox;
        let mut normal = e.nodes[kids[0] as usize].normal;
        let centre = b.center();
        let mut witness = (f64::INFINITY, NONE);
        for &k in &kids {
            let n = &e.nodes[k as usize];
            bbox = hull(&bbox, &n.bbox);
            normal = [normal[0].hull(n.normal[0]), normal[1].hull(n.normal[1])];
            if n.witness != NONE {
                let d = e.witnesses[n.witness as usize].p.dist(centre);
                if d < witness.0 {
                    witness = (d, n.witness);
                }
            }
        }
        let first = e.kids.len() as u32;
        e.kids.extend_from_slice(&kids);
        e.nodes.push(Node {
            bbox,
            first,
            count: kids.len() as u32,
            witness: witness.1,
            leaf: NONE,
            unit_normal: crate::site::curve_tree::direction(normal[0], normal[1]),
            normal,
        });
        Some(e.nodes.len() as u32 - 1)
    }

    /// A leaf: its crossings (witnesses), samples and chord.
    fn leaf(&self, e: &mut Enclosure, b: Aabb, form: &Bernstein2) -> u32 {
        let [dx, dy] = form.deg;
        let c = &form.coef;
        let sign = |v: f64| {
            if v > form.err {
                1
            } else if v < -form.err {
                -1
            } else {
                0
            }
        };
        let [p00, p10, p11, p01] = b.corners();
        let s00 = sign(c[0]);
        let s10 = sign(c[dx * (dy + 1)]);
        let s01 = sign(c[dy]);
        let s11 = sign(c[dx * (dy + 1) + dy]);
        let mut leaf = Leaf::default();
        let mut witness = NONE;
        for (p, sp, q, sq) in [
            (p00, s00, p10, s10),
            (p10, s10, p11, s11),
            (p01, s01, p11, s11),
            (p00, s00, p01, s01),
        ] {
            if sp * sq >= 0 {
                continue;
            }
            if let Some(w) = self.crossing(p, q) {
                if witness == NONE {
                    witness = e.witnesses.len() as u32;
                }
                e.witnesses.push(w);
                leaf.samples.push(w.p);
            }
        }
        if leaf.samples.len() == 2 {
            leaf.chord = Some((leaf.samples[0], leaf.samples[1]));
        }
        if leaf.samples.is_empty() {
            // no crossing on the sides (a small loop, a tangency, an isolated point, a
            // curve along a side, or no curve at all): the centre projected onto the
            // curve, if it lands inside; a witness where f is exactly 0 there
            if let Some(p) = project(self.jet, b.center(), &b) {
                leaf.samples.push(p);
                if exact_zero(self.f, p) {
                    witness = e.witnesses.len() as u32;
                    e.witnesses.push(Witness { a: p, b: p, p });
                }
            }
        }
        // a corner where f vanishes to rounding (the curve ends there on a clip corner,
        // or passes a corner exactly) has no sign change beside it: a sample of its own,
        // and a witness where f is exactly 0 there
        for (p, sp) in [(p00, s00), (p10, s10), (p11, s11), (p01, s01)] {
            let level = 1e3 * f64::EPSILON * self.jet.f.magnitude(p.x, p.y);
            if sp == 0 && self.jet.f.eval(p.x, p.y).abs() <= level {
                leaf.samples.push(p);
                if exact_zero(self.f, p) {
                    if witness == NONE {
                        witness = e.witnesses.len() as u32;
                    }
                    e.witnesses.push(Witness { a: p, b: p, p });
                }
            }
        }
        let grow = e.margin;
        let bbox = Aabb::new(
            Point::new(b.min.x - grow, b.min.y - grow),
            Point::new(b.max.x + grow, b.max.y + grow),
        );
        let normal = gradient_bound(form, &b);
        leaf.strip = leaf
            .samples
            .first()
            .and_then(|&p| self.strip(p, &normal, &b, grow));
        e.leaves.push(leaf);
        e.nodes.push(Node {
            bbox,
            first: 0,
            count: 0,
            witness,
            leaf: e.leaves.len() as u32 - 1,
            unit_normal: crate::site::curve_tree::direction(normal[0], normal[1]),
            normal,
        });
        e.nodes.len() as u32 - 1
    }

    /// The strip about the line through `p` (a point of the curve in a leaf with box
    /// `b`, its points within `slack` of it, and gradient enclosure `g`) across which
    /// `f` is monotone. With `n` the mean direction of `∇f`, `u ⊥ n`, and a point
    /// `p + αu + βn` of the curve in the box, the mean value theorem gives `0 ∈ f(p) + α·(g·u) + β·(g·n)`, so
    /// `|β| ≤ (|f(p)| + |α|·max|g·u|) / min|g·n|`: about `κ·side²` for curvature `κ`.
    /// `None` where `g·n` may vanish or the strip is no thinner than the box.
    fn strip(&self, p: Point, g: &[Interval; 2], b: &Aabb, slack: f64) -> Option<Strip> {
        let mid = Point::new(g[0].mid(), g[1].mid());
        let len = mid.norm();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        let n = mid * (1.0 / len);
        let u = n.perp();
        let across = g[0].scale(n.x) + g[1].scale(n.y);
        let along = (g[0].scale(u.x) + g[1].scale(u.y)).mag();
        let least = if across.lo > 0.0 {
            across.lo
        } else if across.hi < 0.0 {
            -across.hi
        } else {
            return None;
        };
        let residual = self
            .f
            .eval_interval(
                Interval::point(p.x),
                Interval::point(p.y),
                Interval::point(0.0),
            )
            .mag();
        // the range of α over the box (the curve's points lie in it, to the margin)
        let (mut first, mut last) = (f64::INFINITY, f64::NEG_INFINITY);
        for c in b.corners() {
            let alpha = (c - p).dot(u);
            first = first.min(alpha);
            last = last.max(alpha);
        }
        let widen = 1e-12 * (last - first) + 2.0 * slack;
        let (first, last) = (first - widen, last + widen);
        let reach = first.abs().max(last.abs());
        let half_width = round_up((residual + reach * along) / least * (1.0 + 1e-12) + 4.0 * slack);
        (half_width.is_finite() && half_width < 0.25 * b.longest_side()).then(|| Strip {
            a: p + u * first,
            b: p + u * last,
            half_width,
        })
    }

    /// The crossing of the curve with the segment `p`–`q` whose ends have opposite
    /// signs: refined by the Illinois method, bracketed by interval evaluations.
    fn crossing(&self, p: Point, q: Point) -> Option<Witness> {
        let at = |t: f64| if t >= 1.0 { q } else { p.lerp(q, t) };
        let g = |t: f64| {
            let r = at(t);
            self.jet.f.eval(r.x, r.y)
        };
        let (mut a, mut b) = (0.0f64, 1.0f64);
        let (mut ga, mut gb) = (g(a), g(b));
        if ga == 0.0 || gb == 0.0 || (ga > 0.0) == (gb > 0.0) {
            // f64 disagrees with the certified corner signs: the whole side is the bracket
            return opposite(self.f, p, q).then_some(Witness {
                a: p,
                b: q,
                p: p.lerp(q, 0.5),
            });
        }
        let mut side = 0i8;
        for _ in 0..80 {
            let t = if (ga - gb).abs() > 0.0 {
                (a * gb - b * ga) / (gb - ga)
            } else {
                0.5 * (a + b)
            };
            let t = if t > a && t < b { t } else { 0.5 * (a + b) };
            if t <= a || t >= b {
                break;
            }
            let gt = g(t);
            if gt == 0.0 {
                a = t;
                b = t;
                break;
            }
            if (gt > 0.0) == (ga > 0.0) {
                a = t;
                ga = gt;
                if side == -1 {
                    gb *= 0.5;
                }
                side = -1;
            } else {
                b = t;
                gb = gt;
                if side == 1 {
                    ga *= 0.5;
                }
                side = 1;
            }
            if b - a <= 1e-15 {
                break;
            }
        }
        let t = 0.5 * (a + b);
        let point = at(t);
        // a certified bracket, widening from the refined point to the whole side
        for delta in [1e-12, 1e-9, 1e-6, 1e-3] {
            let (lo, hi) = ((t - delta).max(0.0), (t + delta).min(1.0));
            let (pa, pb) = (at(lo), at(hi));
            if opposite(self.f, pa, pb) {
                return Some(Witness {
                    a: pa,
                    b: pb,
                    p: point,
                });
            }
        }
        opposite(self.f, p, q).then_some(Witness {
            a: p,
            b: q,
            p: point,
        })
    }
}

/// True when interval evaluations of `f` at `a` and `b` have certified opposite signs.
pub(super) fn opposite(f: &crate::num::poly::Poly, a: Point, b: Point) -> bool {
    let at = |p: Point| {
        f.eval_interval(
            Interval::point(p.x),
            Interval::point(p.y),
            Interval::point(0.0),
        )
    };
    let (fa, fb) = (at(a), at(b));
    (fa.lo > 0.0 && fb.hi < 0.0) || (fa.hi < 0.0 && fb.lo > 0.0)
}

/// True when `f(p) = 0` exactly because every term has a vanishing factor (`x = 0` or
/// `y = 0`, e.g. the curve `y` along a clip side `y = 0`), where no sign change can show
/// the curve.
fn exact_zero(f: &crate::num::poly::Poly, p: Point) -> bool {
    f.terms
        .iter()
        .all(|&(e, c)| c == 0.0 || (e[0] > 0 && p.x == 0.0) || (e[1] > 0 && p.y == 0.0))
}

/// `p` moved onto the curve by Newton steps along the gradient, if it lands in `within`
/// with `f` at rounding level.
pub(super) fn project(jet: &Jet, mut p: Point, within: &Aabb) -> Option<Point> {
    for _ in 0..12 {
        let v = jet.f.eval(p.x, p.y);
        let (gx, gy) = (jet.fx.eval(p.x, p.y), jet.fy.eval(p.x, p.y));
        let g2 = gx * gx + gy * gy;
        if v == 0.0 || !(g2 > 0.0 && g2.is_finite()) {
            break;
        }
        p = Point::new(p.x - v * gx / g2, p.y - v * gy / g2);
    }
    let level = 1e3 * f64::EPSILON * jet.f.magnitude(p.x, p.y);
    (within.contains(p) && jet.f.eval(p.x, p.y).abs() <= level).then_some(p)
}

/// A componentwise enclosure of `∇f` over box `b`, from the Bernstein form of `f` over
/// `b`: `(∂f/∂u / width, ∂f/∂v / height)` in the form's relative coordinates, widened
/// for the rounding of the box's sides.
fn gradient_bound(form: &Bernstein2, b: &Aabb) -> [Interval; 2] {
    let widen = |i: Interval| {
        let slack = 1e-14 * i.mag();
        Interval::new(round_down(i.lo - slack), round_up(i.hi + slack))
    };
    [
        widen(form.derivative(Axis::X).range().scale(1.0 / b.width())),
        widen(form.derivative(Axis::Y).range().scale(1.0 / b.height())),
    ]
}

/// The smallest box holding both.
pub(super) fn hull(a: &Aabb, b: &Aabb) -> Aabb {
    Aabb::new(
        Point::new(a.min.x.min(b.min.x), a.min.y.min(b.min.y)),
        Point::new(a.max.x.max(b.max.x), a.max.y.max(b.max.y)),
    )
}
