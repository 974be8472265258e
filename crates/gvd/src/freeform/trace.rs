//! The zero set of `F3(t, r)` over `[0, 1]²` split into t- and r-monotone branches
//! (HREK07 §4). The special points are the edge points (roots of `F3` on the four sides,
//! by univariate isolation) and the turning points `F3 = ∂F3/∂t = 0`, `F3 = ∂F3/∂r = 0`
//! (and singular points among them) by the certified 2-D solver `solve_system`. Their
//! `t` values cut the square into slabs; inside a slab the zero set is a fixed number of
//! disjoint monotone graphs `r = gₖ(t)` (no turning, crossing or edge point inside), so
//! the `k`-th root of `F3(t, ·)` belongs to branch `k` at every `t` of the slab — the
//! vertical-line connectivity of Keyser et al. (cited in HREK07 §4). A branch's ends are
//! joined to the nearest root (or special point) on the slab's sides.

use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::{Bernstein1, Bernstein2};
use crate::num::roots::{isolate, refine_by_newton, solve_systems, RootInterval, SystemOptions};

/// Special points closer than this in `t` share a slab side.
const SAME_T: f64 = 1e-10;

/// One monotone branch of the zero set inside a slab.
#[derive(Clone, Debug)]
pub struct Branch {
    /// The slab `[t0, t1]`.
    pub slab: (f64, f64),
    /// Which root of `F3(t, ·)` (in increasing `r`) inside the slab.
    pub index: usize,
    /// How many roots the slab has.
    pub count: usize,
    /// `r` at the slab's sides (the nodes the branch ends at), if found.
    pub ends: (Option<f64>, Option<f64>),
}

/// The roots in `r` of `F3(t, ·)`, sorted (uncertified clusters by their midpoints).
pub fn roots_at(f: &Bernstein2, t: f64) -> Vec<f64> {
    column_roots(&f.restrict(Axis::X, t))
        .into_iter()
        .map(|(r, _)| r)
        .collect()
}

/// The roots of `col`, sorted, each with whether it is an uncertified cluster that
/// reaches a side of the square.
fn column_roots(col: &Bernstein1) -> Vec<(f64, bool)> {
    isolate(col, 1e-13)
        .iter()
        .map(|root| {
            let at_side = !root.certified && (root.lo <= 0.0 || root.hi >= 1.0);
            (root_in(col, root), at_side)
        })
        .collect()
}

/// The root of `col` in `root`: refined when certified, else the cluster's midpoint.
fn root_in(col: &Bernstein1, root: &RootInterval) -> f64 {
    if root.certified {
        refine_by_newton(col, root.lo, root.hi)
    } else {
        0.5 * (root.lo + root.hi)
    }
}

/// The `r` of branch `b` at `t` inside its slab (`None` when the root count differs,
/// which only rounding near a special point causes). Only the branch's own root is
/// refined when the count is right.
pub fn branch_at(f: &Bernstein2, b: &Branch, t: f64) -> Option<f64> {
    if t <= b.slab.0 {
        return b.ends.0;
    }
    if t >= b.slab.1 {
        return b.ends.1;
    }
    let col = f.restrict(Axis::X, t);
    let found = isolate(&col, 1e-13);
    if found.len() == b.count {
        return Some(root_in(&col, &found[b.index]));
    }
    counted(column_roots(&col), b.count).map(|roots| roots[b.index])
}

/// The roots of `F3(t, ·)` when there are `count` of them.
fn roots_counted(f: &Bernstein2, t: f64, count: usize) -> Option<Vec<f64>> {
    counted(column_roots(&f.restrict(Axis::X, t)), count)
}

/// The roots when there are `count` of them. A root just outside the square (near a
/// singular corner, where `F3` vanishes to high order and sinks below its error bound)
/// can show as an uncertified cluster at a side: those are dropped before giving up.
fn counted(mut roots: Vec<(f64, bool)>, count: usize) -> Option<Vec<f64>> {
    if roots.len() != count {
        roots.retain(|&(r, at_side)| !at_side && r > 1e-7 && r < 1.0 - 1e-7);
    }
    (roots.len() == count).then(|| roots.into_iter().map(|(r, _)| r).collect())
}

/// How the work went: the number of uncertified special clusters.
#[derive(Clone, Copy, Debug, Default)]
pub struct TraceStats {
    /// Special points found (edge points and turning points).
    pub special: usize,
    /// Of which uncertified clusters of the 2-D solver.
    pub uncertified: usize,
}

/// Half the side of the box left out around a shared end of two spans: a power of two,
/// so that the domains left are halved exactly in f64 (the 2-D solver then splits its
/// Bernstein forms instead of converting them again).
const CORNER_BOX: f64 = 1.0 / 1024.0;

/// `b` minus the box `e`, as up to four boxes.
fn subtract(b: &Aabb, e: &Aabb) -> Vec<Aabb> {
    let (x0, x1) = (e.min.x.max(b.min.x), e.max.x.min(b.max.x));
    let (y0, y1) = (e.min.y.max(b.min.y), e.max.y.min(b.max.y));
    if x0 >= x1 || y0 >= y1 {
        return vec![*b];
    }
    let mut out = Vec::new();
    let mut push = |a: [f64; 4]| {
        if a[0] < a[2] && a[1] < a[3] {
            out.push(Aabb::from_array(a));
        }
    };
    push([b.min.x, b.min.y, x0, b.max.y]);
    push([x1, b.min.y, b.max.x, b.max.y]);
    push([x0, b.min.y, x1, y0]);
    push([x0, y1, x1, b.max.y]);
    out
}

/// The monotone branches of `F3 = 0` over `[0, 1]²`. `shared` lists the corners of
/// the square where the two spans share an end point: `F3` vanishes to second order
/// there (both `C₀ − C₁` and the tangents' cross product vanish), a singular point the
/// 2-D solver cannot certify, so the turning points are sought outside a box of side
/// [`CORNER_BOX`] around it and the corner itself cuts the slabs. Near such a corner
/// `F3` and its partials fall below the error bound of `F3`'s form along whole strips
/// (to fourth order at a smooth joint, and along the whole side of a short span beside
/// a long one): the solver leaves boxes where both are lost in it unresolved instead of
/// splitting them to its minimum size, and splits boxes across their longer side in
/// `units`, the two spans' sizes, so that they stay about square on the curves.
pub fn branches(
    f: &Bernstein2,
    shared: &[Point],
    units: [f64; 2],
    stats: &mut TraceStats,
) -> Vec<Branch> {
    if f.range().excludes_zero() {
        return Vec::new();
    }
    let mut special: Vec<Point> = Vec::new();
    // edge points on the sides r = 0 and r = 1 (t = 0, 1 are slab sides anyway)
    for at in [0, 1] {
        let side = f.edge(Axis::Y, at);
        for root in isolate(&side, 1e-13) {
            special.push(Point::new(root_in(&side, &root), at as f64));
        }
    }
    // turning points
    let poly = f.to_poly();
    let mut domains = vec![Aabb::from_array([0.0, 0.0, 1.0, 1.0])];
    for c in shared {
        let h = Point::new(CORNER_BOX, CORNER_BOX);
        let e = Aabb::new(*c - h, *c + h);
        domains = domains.iter().flat_map(|b| subtract(b, &e)).collect();
        special.push(*c);
    }
    // the clusters around a shared corner's box are not worth fine boxes
    let (min_size, max_boxes) = if shared.is_empty() {
        (1e-7, 1 << 12)
    } else {
        (1e-5, 1 << 10)
    };
    // the turning points in t and in r, in one subdivision: F3's form over [0, 1]² is
    // known to within its error bound, its partial derivatives (in the square's
    // coordinates, differences of neighbouring coefficients times the degree) to within
    // 2n times it
    let partials = [poly.partial(0), poly.partial(1)];
    let opts = [0, 1].map(|axis| SystemOptions {
        min_size,
        max_boxes,
        noise: Some([f.err, 2.0 * f.deg[axis] as f64 * f.err]),
        units,
    });
    let mut turning: [Vec<Point>; 2] = Default::default();
    for d in &domains {
        for (found, roots) in turning
            .iter_mut()
            .zip(solve_systems(&poly, &partials, &[], d, &opts))
        {
            for root in roots {
                if !root.certified {
                    stats.uncertified += 1;
                }
                found.push(root.point);
            }
        }
    }
    special.extend(turning.into_iter().flatten());
    stats.special += special.len();
    let mut cuts: Vec<f64> = special.iter().map(|p| p.x.clamp(0.0, 1.0)).collect();
    cuts.push(0.0);
    cuts.push(1.0);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < SAME_T);
    // the nodes on each cut (the side of one or two slabs): the roots there and the
    // special points on it
    let nodes: Vec<Vec<f64>> = cuts
        .iter()
        .map(|&t| {
            let mut nodes = roots_at(f, t);
            nodes.extend(
                special
                    .iter()
                    .filter(|p| (p.x - t).abs() < SAME_T * 10.0)
                    .map(|p| p.y),
            );
            nodes
        })
        .collect();
    let mut out = Vec::new();
    for (w, n) in cuts.windows(2).zip(nodes.windows(2)) {
        let (t0, t1) = (w[0], w[1]);
        if t1 - t0 < SAME_T {
            continue;
        }
        let mid = roots_at(f, 0.5 * (t0 + t1));
        let count = mid.len();
        let (n0, n1) = (&n[0], &n[1]);
        // a branch's end: the node nearest to its root just inside the slab
        let inner = |t: f64| roots_counted(f, t, count);
        let h = 1e-7 * (t1 - t0);
        let (near0, near1) = (inner(t0 + h), inner(t1 - h));
        for (index, &r_mid) in mid.iter().enumerate() {
            let pick = |nodes: &[f64], near: &Option<Vec<f64>>| {
                let r = near.as_ref().map_or(r_mid, |v| v[index]);
                nodes
                    .iter()
                    .copied()
                    .min_by(|a, b| (a - r).abs().total_cmp(&(b - r).abs()))
                    .filter(|n| (n - r).abs() < 5e-2)
            };
            out.push(Branch {
                slab: (t0, t1),
                index,
                count,
                ends: (pick(n0, &near0), pick(n1, &near1)),
            });
        }
    }
    out
}
