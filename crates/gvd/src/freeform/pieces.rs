//! Free-form sites as rational Bézier spans and corners (HREK07 §7): a B-spline is cut
//! into Bézier spans by knot insertion (Boehm's algorithm on homogeneous control points,
//! every knot of the curve's range raised to multiplicity `degree`, Farin02 ch. 10); the
//! spans are grouped into C1 pieces, split where the tangent direction jumps (corners).
//! Open curves get a corner at each end.

use crate::complex::{FeatureKind, Generator};
use crate::geom::bezier::RationalBezier;
use crate::geom::ring::signed_area;
use crate::geom::{Aabb, Point};
use crate::num::bernstein::Bernstein1;
use crate::num::roots::{isolate, refine};
use crate::scene::{Mode, Scene, SiteKind};

/// Angle (radians) above which the tangent direction at a joint counts as a jump.
const CORNER_ANGLE: f64 = 1e-6;

/// Which side of a span (relative to its direction of parameterization) bisector points
/// may lie on: the orientation constraint (HREK07 eqs. 8–13).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Left of the tangent (`⟨P − C, N_L⟩ > 0`, `N_L = (−y', x')`).
    Left,
    /// Right of the tangent.
    Right,
    /// Either side (open curves).
    Both,
}

impl Side {
    /// True when the signed offset `s = ⟨P − C, N_L⟩` is on this side.
    pub fn admits(self, s: f64) -> bool {
        match self {
            Side::Left => s > 0.0,
            Side::Right => s < 0.0,
            Side::Both => true,
        }
    }
}

/// A C1 rational Bézier span of a site.
#[derive(Clone, Debug)]
pub struct Span {
    /// The span, parameter `t ∈ [0, 1]`.
    pub curve: RationalBezier,
    /// The site it belongs to.
    pub site: usize,
    /// Its C1 piece within the site (the format's `piece` feature index).
    pub piece: usize,
    /// The side where the diagram lies.
    pub side: Side,
    /// A box holding the span.
    pub bbox: Aabb,
}

/// A tangent discontinuity or an open end of a curve.
#[derive(Clone, Debug)]
pub struct Corner {
    /// Where it is.
    pub at: Point,
    /// The site it belongs to.
    pub site: usize,
    /// Its corner index within the site.
    pub index: usize,
    /// Unit tangent of the curve arriving at the corner (zero at an open start).
    pub tin: Point,
    /// Unit tangent of the curve leaving it (zero at an open end).
    pub tout: Point,
    /// The normal cone `{v : ⟨v, tin⟩ ≥ 0, ⟨v, tout⟩ ≤ 0}` of the corner reaches the
    /// side where the diagram lies (a convex corner seen from there); inactive corners
    /// are nearest to no point of that side and generate nothing.
    pub active: bool,
}

impl Corner {
    /// True when `q` lies in the corner's normal cone (within `tol`): the points for
    /// which the corner is the nearest point of its two spans (HREK07 §7.3, the bounding
    /// normals of a tangent discontinuity).
    pub fn sees(&self, q: Point, tol: f64) -> bool {
        let v = q - self.at;
        v.dot(self.tin) >= -tol && v.dot(self.tout) <= tol
    }
}

/// A feature of the scene: a span or a corner, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Feature {
    /// `Pieces::spans[k]`.
    Span(usize),
    /// `Pieces::corners[k]`.
    Corner(usize),
}

/// Every free-form site cut into spans and corners.
#[derive(Clone, Debug, Default)]
pub struct Pieces {
    /// The spans.
    pub spans: Vec<Span>,
    /// The corners (active or not).
    pub corners: Vec<Corner>,
    /// Whether generators are features (`complex`, `medial_axis`) or whole sites.
    pub featured: bool,
}

impl Pieces {
    /// The output generator of a feature.
    pub fn generator(&self, f: Feature) -> Generator {
        let (site, feature, index) = match f {
            Feature::Span(k) => (self.spans[k].site, FeatureKind::Piece, self.spans[k].piece),
            Feature::Corner(k) => (
                self.corners[k].site,
                FeatureKind::Corner,
                self.corners[k].index,
            ),
        };
        if self.featured {
            Generator::Feature {
                site,
                feature,
                index,
            }
        } else {
            Generator::Site(site)
        }
    }

    /// The site of a feature.
    pub fn site(&self, f: Feature) -> usize {
        match f {
            Feature::Span(k) => self.spans[k].site,
            Feature::Corner(k) => self.corners[k].site,
        }
    }
}

/// The spans of one site (homogeneous Bézier control polygons) and whether it is closed,
/// or `None` when the site is not a free-form curve.
fn site_spans(kind: &SiteKind) -> Option<(Vec<RationalBezier>, bool)> {
    match kind {
        SiteKind::Bezier {
            control_points,
            weights,
        } => {
            let c = RationalBezier::new(control_points, weights.as_deref());
            let closed = control_points.first() == control_points.last();
            Some((vec![c], closed))
        }
        SiteKind::Bspline {
            degree,
            control_points,
            knots,
            weights,
            closed,
        } => {
            let h: Vec<[f64; 3]> = control_points
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let w = weights.as_ref().map_or(1.0, |w| w[i]);
                    [p.x * w, p.y * w, w]
                })
                .collect();
            let spans = bspline_to_bezier(*degree, &h, knots);
            let ends = spans
                .first()
                .zip(spans.last())
                .map(|(a, b)| (a.eval(0.0), b.eval(1.0)));
            let meets = ends.is_some_and(|(a, b)| a.dist(b) <= 1e-9 * (1.0 + a.norm()));
            Some((spans, *closed || meets))
        }
        _ => None,
    }
}

/// Boehm knot insertion: `u` inserted once into `(knots, points)` of degree `p`, in
/// the span `knots[k] ≤ u < knots[k+1]` (`knots[k] < u ≤ knots[k+1]` with `left`, for
/// the end of the curve's range).
fn insert_knot(p: usize, knots: &mut Vec<f64>, points: &mut Vec<[f64; 3]>, u: f64, left: bool) {
    let Some(k) = (0..knots.len() - 1).rev().find(|&k| {
        if left {
            knots[k] < u && u <= knots[k + 1]
        } else {
            knots[k] <= u && u < knots[k + 1]
        }
    }) else {
        return;
    };
    if k < p || k >= points.len() {
        return;
    }
    let mut q = Vec::with_capacity(points.len() + 1);
    q.extend_from_slice(&points[..=k - p]);
    for i in k - p + 1..=k {
        let a = (u - knots[i]) / (knots[i + p] - knots[i]);
        q.push(std::array::from_fn(|c| {
            (1.0 - a) * points[i - 1][c] + a * points[i][c]
        }));
    }
    q.extend_from_slice(&points[k..]);
    *points = q;
    knots.insert(k + 1, u);
}

/// The Bézier spans of a B-spline of degree `p` over its range `[knots[p], knots[n]]`.
pub fn bspline_to_bezier(p: usize, points: &[[f64; 3]], knots: &[f64]) -> Vec<RationalBezier> {
    let n = points.len();
    let (a, b) = (knots[p], knots[n]);
    let mut values: Vec<f64> = knots
        .iter()
        .copied()
        .filter(|&u| a <= u && u <= b)
        .collect();
    values.dedup();
    let mut kn = knots.to_vec();
    let mut pts = points.to_vec();
    for &u in &values {
        let mult = kn.iter().filter(|&&x| x == u).count();
        // the end of the range is raised to multiplicity p as well, from its left
        for _ in mult..p {
            insert_knot(p, &mut kn, &mut pts, u, u == b);
        }
    }
    let mut out = Vec::new();
    for i in p..kn.len().saturating_sub(p + 1) {
        if kn[i] < kn[i + 1] && kn[i] >= a && kn[i + 1] <= b && i < pts.len() {
            out.push(RationalBezier::from_homogeneous(pts[i - p..=i].to_vec()));
        }
    }
    out
}

/// The unit vector along `v` (zero stays zero).
fn unit(v: Point) -> Point {
    let n = v.norm();
    if n > 0.0 {
        v * (1.0 / n)
    } else {
        v
    }
}

/// Cuts every free-form site of the scene into spans and corners. Sites that are not
/// free-form curves are skipped (the caller refuses them).
pub fn pieces(scene: &Scene) -> Pieces {
    let mode = scene.mode();
    let mut out = Pieces {
        featured: mode != Mode::Voronoi,
        ..Pieces::default()
    };
    for (site, s) in scene.sites().iter().enumerate() {
        let Some((spans, closed)) = site_spans(&s.kind) else {
            continue;
        };
        let scale = spans
            .iter()
            .map(|c| c.control_box().longest_side())
            .fold(0.0, f64::max);
        let spans: Vec<RationalBezier> = spans
            .into_iter()
            .filter(|c| c.control_box().longest_side() > 1e-12 * scale)
            .collect();
        if spans.is_empty() {
            continue;
        }
        // in complex and medial_axis modes a curve meets itself: cut the spans at their
        // curvature extrema, so that no span has a bisector with itself
        let spans = if mode == Mode::Voronoi {
            spans
        } else {
            spans.iter().flat_map(split_at_vertices).collect()
        };
        let tangents: Vec<(Point, Point)> = spans
            .iter()
            .map(|c| {
                let (a, b) = c.end_tangents();
                (unit(a), unit(b))
            })
            .collect();
        let jump = |a: Point, b: Point| {
            a.dot(b) < (CORNER_ANGLE).cos() || a.norm() == 0.0 || b.norm() == 0.0
        };
        let m = spans.len();
        // breaks[k]: a corner at the start of span k
        let mut breaks: Vec<bool> = (0..m)
            .map(|k| k > 0 && jump(tangents[k - 1].1, tangents[k].0))
            .collect();
        let seam = closed && jump(tangents[m - 1].1, tangents[0].0);
        breaks[0] = !closed || seam;
        // the side where the diagram lies: outside a closed curve (inside in medial_axis)
        let side = if closed {
            let ring: Vec<Point> = spans
                .iter()
                .flat_map(|c| {
                    let mut v = c.sample(16);
                    v.pop();
                    v
                })
                .collect();
            let ccw = signed_area(&ring) > 0.0;
            let inside_left = ccw;
            let want_inside = mode == Mode::MedialAxis;
            if inside_left == want_inside {
                Side::Left
            } else {
                Side::Right
            }
        } else {
            Side::Both
        };
        // pieces and corners, numbered like the format: from the seam when it is a
        // corner (or the curve is open), else from the first break
        let first = if closed && !seam {
            breaks.iter().position(|&b| b).unwrap_or(0)
        } else {
            0
        };
        let mut piece = 0usize;
        let mut corner = 0usize;
        for j in 0..m {
            let k = (first + j) % m;
            if j > 0 && breaks[k] {
                piece += 1;
            }
            if breaks[k] {
                let tin = if !closed && k == 0 {
                    Point::new(0.0, 0.0)
                } else {
                    tangents[(k + m - 1) % m].1
                };
                let tout = tangents[k].0;
                out.corners.push(make_corner(
                    spans[k].eval(0.0),
                    site,
                    corner,
                    tin,
                    tout,
                    side,
                ));
                corner += 1;
            }
            out.spans.push(Span {
                bbox: spans[k].control_box(),
                curve: spans[k].clone(),
                site,
                piece,
                side,
            });
        }
        if !closed {
            let end = spans[m - 1].eval(1.0);
            out.corners.push(make_corner(
                end,
                site,
                corner,
                tangents[m - 1].1,
                Point::new(0.0, 0.0),
                side,
            ));
        }
    }
    out
}

/// The parameters in `(0, 1)` where the curvature of `c` has an extremum (the curve's
/// vertices): with `H = (X, Y, W)`, `κ = det(H, H', H'') W³ / |T|³`, `T = (X'W − XW',
/// Y'W − YW')` (Farin02), so `κ' = 0` where
/// `2 (det · W³)' |T|² − 3 det · W³ (|T|²)' = 0`, a polynomial isolated in Bernstein form.
pub fn curvature_extrema(c: &RationalBezier) -> Vec<f64> {
    let h = c.homogeneous();
    let coord = |k: usize| Bernstein1::exact(h.iter().map(|p| p[k]).collect());
    let (x, y, w) = (coord(0), coord(1), coord(2));
    let d = |f: &Bernstein1| f.derivative();
    let (x1, y1, w1) = (d(&x), d(&y), d(&w));
    let (x2, y2, w2) = (d(&x1), d(&y1), d(&w1));
    let det = x
        .mul(&y1.mul(&w2).sub(&w1.mul(&y2)))
        .sub(&y.mul(&x1.mul(&w2).sub(&w1.mul(&x2))))
        .add(&w.mul(&x1.mul(&y2).sub(&y1.mul(&x2))));
    let tx = x1.mul(&w).sub(&x.mul(&w1));
    let ty = y1.mul(&w).sub(&y.mul(&w1));
    let t2 = tx.mul(&tx).add(&ty.mul(&ty));
    let k = det.mul(&w.mul(&w).mul(&w));
    let g = d(&k).mul(&t2).scale(2.0).sub(&k.mul(&d(&t2)).scale(3.0));
    isolate(&g, 1e-12)
        .into_iter()
        .map(|r| {
            if r.certified {
                refine(&g, r.lo, r.hi)
            } else {
                0.5 * (r.lo + r.hi)
            }
        })
        .filter(|&t| t > 1e-6 && t < 1.0 - 1e-6)
        .collect()
}

/// `c` cut at its curvature extrema.
fn split_at_vertices(c: &RationalBezier) -> Vec<RationalBezier> {
    let mut out = Vec::new();
    let mut rest = c.clone();
    let mut done = 0.0;
    for t in curvature_extrema(c) {
        let local = (t - done) / (1.0 - done);
        if local <= 1e-6 || local >= 1.0 - 1e-6 {
            continue;
        }
        let (l, r) = rest.split(local);
        out.push(l);
        rest = r;
        done = t;
    }
    out.push(rest);
    out
}

fn make_corner(
    at: Point,
    site: usize,
    index: usize,
    tin: Point,
    tout: Point,
    side: Side,
) -> Corner {
    // the cone's middle direction tin − tout; on the allowed side iff the curve turns
    // away from it (see the module docs of `freeform`)
    let turn = tin.cross(tout);
    let active = match side {
        Side::Both => true,
        Side::Left => turn < 0.0,
        Side::Right => turn > 0.0,
    };
    Corner {
        at,
        site,
        index,
        tin,
        tout,
        active,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_cubic_bspline_spans_match_de_boor() {
        // a uniform cubic B-spline: span k's Bézier points from de Boor's formula
        let p: Vec<[f64; 3]> = [[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0], [6.0, 1.0]]
            .iter()
            .map(|q| [q[0], q[1], 1.0])
            .collect();
        let knots: Vec<f64> = (0..9).map(f64::from).collect();
        let spans = bspline_to_bezier(3, &p, &knots);
        assert_eq!(spans.len(), 2);
        // uniform cubic: the curve at knot 3 is (P0 + 4 P1 + P2) / 6
        let want = Point::new((0.0 + 4.0 + 3.0) / 6.0, (0.0 + 8.0 + 3.0) / 6.0);
        assert!(spans[0].eval(0.0).dist(want) < 1e-12);
        assert!(spans[0].eval(1.0).dist(spans[1].eval(0.0)) < 1e-12);
        let want_end = Point::new((3.0 + 16.0 + 6.0) / 6.0, (3.0 + 0.0 + 1.0) / 6.0);
        assert!(spans[1].eval(1.0).dist(want_end) < 1e-12);
        // C1 at the joint
        assert!(spans[0].derivative(1.0).dist(spans[1].derivative(0.0)) < 1e-9);
    }

    #[test]
    fn curvature_extrema_of_an_ellipse_arc_are_its_vertices() {
        // the quarter ellipse x = 2 cos, y = sin from (2, 0) to (0, 1) as a rational
        // quadratic; as a half (through the vertex (0, 1)) it has one extremum there
        let q = RationalBezier::new(
            &[
                Point::new(2.0, 0.0),
                Point::new(2.0, 1.0),
                Point::new(0.0, 1.0),
            ],
            Some(&[1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0]),
        );
        assert!(curvature_extrema(&q).is_empty()); // the vertices are at its ends
        let half = RationalBezier::new(
            &[
                Point::new(2.0, 0.0),
                Point::new(2.0, 2.0),
                Point::new(-2.0, 2.0),
                Point::new(-2.0, 0.0),
            ],
            Some(&[1.0, 1.0 / 3.0, 1.0 / 3.0, 1.0]),
        );
        let e = curvature_extrema(&half);
        assert_eq!(e.len(), 1, "{e:?}");
        let p = half.eval(e[0]);
        assert!(p.dist(Point::new(0.0, 1.0)) < 1e-9, "{p:?}");
    }
}
