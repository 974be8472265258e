//! A closed smooth curve `{f = 0}` inside its clip box, cut into pieces for its medial
//! axis (SYMW11 compute it from curve pixels; here from certified pieces).
//!
//! An arc whose curvature is strictly monotone has nested osculating circles
//! (Tait–Kneser; GTT13), so no disc touches it twice from one side: every point of
//! the medial axis has its two nearest points on two different such arcs. The curve is
//! cut at its *vertices*, the zeros of `dκ/ds`: with `T = (−f_y, f_x)`, `G = |∇f|²` and
//! `N = f_xx f_y² − 2 f_xy f_x f_y + f_yy f_x²` (so `κ = N / G^{3/2}`),
//! `dκ/ds ∝ V = 2 G (∇N · T) − 3 N (∇G · T)`, and the vertices are the solutions of
//! `f = V = 0`, isolated by the certified solver. Each vertex gets a cut line (across
//! the curve: vertical where the tangent is nearer horizontal), the clip box is cut along
//! them into cells, and each cell is halved until every box either misses the curve or
//! holds one arc: `∇f · u > 0` over an enclosure of the curve in the box for some `u`
//! (the curve is a graph over `u⊥` there, with no closed loop) and the box's sides have
//! exactly two certified crossings. Those boxes are the pieces' clip boxes; pieces of
//! one curve meet at shared crossings, each such point the end of a zone boundary (the
//! normal there) that the diagram of the pieces has and the medial axis has not.

use super::dense::Jet;
use super::enclosure::{Enclosure, NONE};
use super::{AlgebraicField, Special};
use crate::error::Error;
use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::Bernstein2;
use crate::num::poly::Poly;
use crate::num::roots::{self, SystemOptions};
use crate::site::zone::ZoneEnd;

/// Deepest halving of a cell before the curve is declared too close to a cell's corner.
const MAX_DEPTH: u32 = 40;
/// Where a box is split along its longer side (relative): off the dyadic points, through
/// which curves with simple coefficients (`x² + y² − 1` through `(1, 0)`) often pass.
const SPLIT_AT: f64 = 0.512_345_678_9;

/// The pieces of a closed curve and the region it bounds.
pub struct Pieces {
    /// The pieces' distance fields, one arc of monotone curvature each.
    pub fields: Vec<AlgebraicField>,
    /// The two ends of each piece (where it crosses its clip box's sides), with the
    /// zone boundary of the piece next to it there.
    pub ends: Vec<[ZoneEnd; 2]>,
    /// The region inside the curve.
    pub region: Region,
}

/// The region a closed smooth curve bounds by the even-odd rule: `f` changes sign across
/// each of its branches, so a point is inside where `f` has the sign other than the one
/// it has on the clip box's sides (outside every branch).
pub struct Region {
    f: Poly,
    outside: f64,
}

impl Region {
    /// Whether `q` is inside (f64 evaluation of `f`: for points away from the curve).
    pub fn contains(&self, q: Point) -> bool {
        self.f.eval(q.x, q.y, 0.0) * self.outside < 0.0
    }
}

/// Cuts site `site`'s curve `{f = 0} ∩ clip` into [`Pieces`] with enclosure leaves no
/// longer than `resolution`. Refuses a curve that meets its clip box's sides (not
/// closed there), one with singular points (cusps, nodes, isolated points), and one
/// whose vertices are not isolated (a circle, whose curvature is constant).
pub fn pieces(site: usize, f: &Poly, clip: Aabb, resolution: f64) -> Result<Pieces, Error> {
    let refuse = |message: String| Error::Unsupported {
        site,
        kind: "algebraic".into(),
        message: format!("medial_axis mode: {message}"),
    };
    let form = Bernstein2::from_poly(f, &clip);
    for (axis, at) in [(Axis::X, 0), (Axis::X, 1), (Axis::Y, 0), (Axis::Y, 1)] {
        if !roots::isolate(&form.edge(axis, at), 1e-12).is_empty() {
            return Err(refuse(
                "the curve reaches its clip box's sides: the medial axis is computed \
                 inside curves closed within their clip box"
                    .into(),
            ));
        }
    }
    let outside = if f.eval(clip.min.x, clip.min.y, 0.0) > 0.0 {
        1.0
    } else {
        -1.0
    };
    let whole = AlgebraicField::new(site, f, clip, resolution)?;
    let Special {
        singular_points,
        singular_clusters,
        ..
    } = whole.special;
    if singular_points + singular_clusters > 0 {
        return Err(refuse(format!(
            "the curve has {} singular point(s) (f = ∂f/∂x = ∂f/∂y = 0: a cusp, node or \
             isolated point); the medial axis is computed inside smooth curves",
            singular_points + singular_clusters
        )));
    }
    let opts = SystemOptions {
        min_size: 1e-9 * clip.longest_side(),
        max_boxes: 1 << 16,
        noise: None,
        units: [1.0, 1.0],
    };
    let jet = Jet::new(f);
    let mut cuts = [vec![clip.min.x, clip.max.x], vec![clip.min.y, clip.max.y]];
    for root in roots::solve_system(f, &curvature_derivative(f), &[], &clip, &opts) {
        let p = root.point;
        if !root.certified {
            return Err(refuse(format!(
                "the curve's vertices (zeros of dκ/ds) could not be isolated near ({}, {}): \
                 its curvature is constant along an arc (a circle?) or has a degenerate \
                 extremum there",
                p.x, p.y
            )));
        }
        let (gx, gy) = (jet.fx.eval(p.x, p.y), jet.fy.eval(p.x, p.y));
        if gy.abs() >= gx.abs() {
            cuts[0].push(p.x);
        } else {
            cuts[1].push(p.y);
        }
    }
    for c in &mut cuts {
        c.sort_by(f64::total_cmp);
        c.dedup();
    }
    let mut boxes = Vec::new();
    for x in cuts[0].windows(2) {
        for y in cuts[1].windows(2) {
            let cell = Aabb::new(Point::new(x[0], y[0]), Point::new(x[1], y[1]));
            arcs(f, &jet, cell, 0, &mut boxes).map_err(|at| {
                refuse(format!(
                    "the curve could not be cut into single arcs near ({}, {}) (it passes \
                     within rounding of a cut's corner)",
                    at.x, at.y
                ))
            })?;
        }
    }
    let fields = boxes
        .iter()
        .map(|b| AlgebraicField::new(site, f, b.0, resolution))
        .collect::<Result<_, _>>()?;
    let end = |at: Point| end(&jet, outside, at);
    Ok(Pieces {
        fields,
        ends: boxes.into_iter().map(|b| b.1.map(end)).collect(),
        region: Region {
            f: f.clone(),
            outside,
        },
    })
}

/// Appends to `out` the boxes, halved from `b`, that each hold one arc of the curve
/// (see the module docs), with the arc's ends; `Err` with a point where halving reached
/// [`MAX_DEPTH`].
fn arcs(
    f: &Poly,
    jet: &Jet,
    b: Aabb,
    depth: u32,
    out: &mut Vec<(Aabb, [Point; 2])>,
) -> Result<(), Point> {
    let form = Bernstein2::from_poly(f, &b);
    if form.range().excludes_zero() {
        return Ok(());
    }
    if let Some(&[p, q]) = crossings(&form, &b).as_deref() {
        if turns_less_than_half(f, jet, &b) {
            out.push((b, [p, q]));
            return Ok(());
        }
    }
    if depth >= MAX_DEPTH {
        return Err(b.center());
    }
    let (axis, at) = if b.width() >= b.height() {
        (Axis::X, b.min.x + SPLIT_AT * b.width())
    } else {
        (Axis::Y, b.min.y + SPLIT_AT * b.height())
    };
    let (lo, hi) = b.split(axis, at);
    arcs(f, jet, lo, depth + 1, out)?;
    arcs(f, jet, hi, depth + 1, out)
}

/// True when some direction `u` has `∇f · u > 0` over every leaf of an enclosure of the
/// curve in `b` (interval bounds), `u` the mean of the leaves' gradients: then the
/// coordinate along `u⊥` is strictly monotone along the curve there, which so has no
/// closed loop and is one arc per two crossings of `b`'s sides.
fn turns_less_than_half(f: &Poly, jet: &Jet, b: &Aabb) -> bool {
    let Some(e) = Enclosure::build(f, jet, b, b.longest_side() / 64.0) else {
        return false;
    };
    let leaves = || e.nodes.iter().filter(|n| n.leaf != NONE);
    let mut u = Point::new(0.0, 0.0);
    for n in leaves() {
        if let Some(g) = n.unit_normal {
            u = u + Point::new(g[0].mid(), g[1].mid());
        }
    }
    leaves().all(|n| (n.normal[0].scale(u.x) + n.normal[1].scale(u.y)).lo > 0.0)
}

/// The points where the curve crosses the sides of `b` (`form` is `f` over it), when
/// every one is certified (simple, away from the corners); `None` otherwise.
fn crossings(form: &Bernstein2, b: &Aabb) -> Option<Vec<Point>> {
    let [dx, dy] = form.deg;
    let corners = [0, dy, dx * (dy + 1), dx * (dy + 1) + dy];
    if corners.iter().any(|&k| form.coef[k].abs() <= form.err) {
        return None;
    }
    let mut out = Vec::new();
    for (axis, at) in [(Axis::X, 0), (Axis::X, 1), (Axis::Y, 0), (Axis::Y, 1)] {
        let side = form.edge(axis, at);
        for r in roots::isolate(&side, 1e-12) {
            if !r.certified {
                return None;
            }
            let t = roots::refine(&side, r.lo, r.hi);
            let u = at as f64;
            out.push(match axis {
                Axis::X => b.at(u, t),
                Axis::Y => b.at(t, u),
            });
        }
    }
    Some(out)
}

/// The end `at` of a piece, its inward normal `−s ∇f/|∇f|` (`s` the sign of `f`
/// outside) and its radius of curvature towards it: the curvature vector of `{f = 0}`
/// is `−(tᵀ H t / |∇f|) ∇f/|∇f|` (`t` the unit tangent, `H` the Hessian of `f`), so the
/// curvature towards the inside is `κ = s·tᵀ H t / |∇f|`.
fn end(jet: &Jet, outside: f64, at: Point) -> ZoneEnd {
    let (x, y) = (at.x, at.y);
    let g = Point::new(jet.fx.eval(x, y), jet.fy.eval(x, y));
    let unit = g * (1.0 / g.norm());
    let t = unit.perp();
    let bend = t.x * t.x * jet.fxx.eval(x, y)
        + 2.0 * t.x * t.y * jet.fxy.eval(x, y)
        + t.y * t.y * jet.fyy.eval(x, y);
    let kappa = outside * bend / g.norm();
    let focal = if kappa > 0.0 {
        1.0 / kappa
    } else {
        f64::INFINITY
    };
    // outside the region the zone boundary does not matter: no end there
    ZoneEnd::new(at, unit * -outside, [focal, f64::INFINITY])
}

/// `V = 2 G (∇N · T) − 3 N (∇G · T)`, which has the sign of `dκ/ds` along
/// `T = (−f_y, f_x)` on the curve (module docs).
fn curvature_derivative(f: &Poly) -> Poly {
    let (fx, fy) = (f.partial(0), f.partial(1));
    let (fxx, fxy, fyy) = (fx.partial(0), fx.partial(1), fy.partial(1));
    let n = fxx
        .mul(&fy.mul(&fy))
        .sub(&fxy.mul(&fx).mul(&fy).scale(2.0))
        .add(&fyy.mul(&fx.mul(&fx)));
    let g = fx.mul(&fx).add(&fy.mul(&fy));
    let along = |h: &Poly| h.partial(1).mul(&fx).sub(&h.partial(0).mul(&fy));
    g.mul(&along(&n))
        .scale(2.0)
        .sub(&n.mul(&along(&g)).scale(3.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(text: &str) -> Poly {
        Poly::parse(text, &['x', 'y']).unwrap()
    }

    #[test]
    fn the_ellipse_has_its_four_vertices() {
        let f = poly("x^2/4 + y^2 - 1");
        let clip = Aabb::new(Point::new(-3.0, -2.0), Point::new(3.0, 2.0));
        let v = curvature_derivative(&f);
        let opts = SystemOptions::for_domain(&clip);
        let mut found: Vec<Point> = roots::solve_system(&f, &v, &[], &clip, &opts)
            .into_iter()
            .inspect(|r| assert!(r.certified))
            .map(|r| r.point)
            .collect();
        found.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        let expected = [(-2.0, 0.0), (0.0, -1.0), (0.0, 1.0), (2.0, 0.0)];
        assert_eq!(found.len(), 4, "{found:?}");
        for (p, e) in found.iter().zip(expected) {
            assert!(p.dist(Point::new(e.0, e.1)) < 1e-9, "{p:?} vs {e:?}");
        }
    }

    #[test]
    fn pieces_of_the_ellipse_are_single_arcs_meeting_at_the_vertices() {
        let f = poly("x^2/4 + y^2 - 1");
        let clip = Aabb::new(Point::new(-3.0, -2.0), Point::new(3.0, 2.0));
        let p = pieces(0, &f, clip, 1e-3).unwrap();
        assert!(p.fields.len() >= 4);
        assert!(p.region.contains(Point::new(1.9, 0.0)));
        assert!(!p.region.contains(Point::new(2.1, 0.0)));
        for vertex in [(2.0, 0.0), (0.0, 1.0)] {
            let at = Point::new(vertex.0, vertex.1);
            let ends = p
                .fields
                .iter()
                .filter(|a| {
                    let c = a.clip;
                    (c.min.x == at.x || c.max.x == at.x || c.min.y == at.y || c.max.y == at.y)
                        && c.min.x <= at.x
                        && at.x <= c.max.x
                        && c.min.y <= at.y
                        && at.y <= c.max.y
                })
                .count();
            assert_eq!(ends, 2, "two pieces end at the vertex {at:?}");
        }
    }

    #[test]
    fn a_circle_and_an_open_curve_are_refused() {
        let clip = Aabb::new(Point::new(-2.0, -2.0), Point::new(2.0, 2.0));
        let circle = pieces(3, &poly("x^2 + y^2 - 1"), clip, 1e-3).err().unwrap();
        assert!(circle.to_string().contains("constant"), "{circle}");
        let open = pieces(1, &poly("y - x^2"), clip, 1e-3).err().unwrap();
        assert!(open.to_string().contains("clip box"), "{open}");
    }
}
