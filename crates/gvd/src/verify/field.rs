//! The checker's own distance fields, evaluated directly from the scene's definitions
//! (`SCENE_FORMAT.md`, "Site kinds" and "Point metrics"). Nothing here is shared with
//! the algorithms.

use super::curve::Curve;
use super::parametric::{spline_site, Parametric};
use crate::error::Error;
use crate::geom::Point;
use crate::num::poly::Poly;
use crate::scene::{Metric, Scene, SiteKind};
use std::f64::consts::TAU;

/// One site's distance field, prepared for evaluation.
#[derive(Clone, Debug)]
pub(super) enum Field {
    /// `|q − p|`
    Euclid { p: Point },
    /// `(x − px)^p + (y − py)^p`, `p` even
    Lp { p: Point, exp: i32 },
    /// `(q − p)ᵀ M (q − p) − w`
    Aniso { p: Point, m: [[f64; 2]; 2], w: f64 },
    /// `s |q − p|² − w` (power: `s = 1`, `w = weight²`; Möbius: `s = v`)
    Scaled { p: Point, s: f64, w: f64 },
    /// `|q − c| − r`
    Circle { c: Point, r: f64 },
    /// distance to the closed segment `[a, b]`
    Segment { a: Point, b: Point },
    /// distance to the union of closed segments (a polyline, or a polygon's rings: the
    /// inside of a polygon is handled by the closed-site masks, see `region.rs`), with
    /// the bounding box `lo`–`hi` of the segments
    Chain {
        segs: Vec<(Point, Point)>,
        lo: Point,
        hi: Point,
    },
    /// distance to the arc of radius `r` about `c` from angle `start`, sweeping `sweep`
    /// counter-clockwise (`sweep ≥ 2π`: the full circle)
    Arc {
        c: Point,
        r: f64,
        start: f64,
        sweep: f64,
    },
    /// distance to the ellipse curve `c + R(θ) (a cos t, b sin t)` from outside, 0 inside
    Ellipse { c: Point, a: f64, b: f64, rot: f64 },
    /// an explicit polynomial field `f(x, y)`
    Poly { f: Poly, h: f64 },
    /// the smallest non-negative root `z` of `g(x, y, z)`, 0 if none
    Implicit { g: Poly, h: f64 },
    /// distance to the algebraic curve `{f = 0} ∩ clip`, densely sampled
    Curve(Box<Curve>),
    /// distance to the union of free-form curve pieces, densely sampled
    Pieces(Vec<Parametric>),
}

/// One branch of a curved feature's distance at a point: a local minimum along it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Branch {
    /// the distance to the foot
    pub value: f64,
    /// the nearest point of this branch
    pub foot: Point,
    /// the centre of curvature at the foot, where the curve bends
    pub center: Option<Point>,
    /// for a free-form field: the piece (its index in the field) and the foot's parameter
    pub param: Option<(usize, f64)>,
}

impl Branch {
    /// The unit vector from the foot towards `q`: the gradient of this branch's distance.
    pub(super) fn gradient(&self, q: Point) -> Point {
        let d = q - self.foot;
        let n = d.norm();
        if n > 0.0 {
            d * (1.0 / n)
        } else {
            d
        }
    }
}

/// How far `q` is from a point where the `m` nearest `branches` of one curved feature
/// tie (first order: their values' spread over the least difference of their unit
/// gradients), or, for `m = 2`, from the centre of curvature at the nearest foot,
/// where such a ridge ends as its two branches merge. Infinite where neither applies.
pub(super) fn ridge_error(q: Point, branches: &[Branch], m: usize) -> f64 {
    let mut e = f64::INFINITY;
    if m >= 2 && branches.len() >= m {
        let near = &branches[..m];
        let spread = near[m - 1].value - near[0].value;
        let mut separation = f64::INFINITY;
        for (i, a) in near.iter().enumerate() {
            for b in &near[i + 1..] {
                separation = separation.min(a.gradient(q).dist(b.gradient(q)));
            }
        }
        e = spread / separation.max(1e-12);
    }
    if m == 2 {
        if let Some(c) = branches.first().and_then(|b| b.center) {
            e = e.min(c.dist(q));
        }
    }
    e
}

/// How far the field can drop near its anchor: `field(q) ≥ lower(|q − anchor|)`,
/// non-decreasing in the distance, for the nearest-site search.
#[derive(Clone, Copy, Debug)]
pub(super) enum Bound {
    /// `k · r^e − w` (clamped below by `floor`)
    Pow { k: f64, e: i32, w: f64, floor: f64 },
    /// no bound: evaluate always
    None,
}

impl Bound {
    pub(super) fn lower(self, r: f64) -> f64 {
        match self {
            Bound::Pow { k, e, w, floor } => (k * r.powi(e) - w).max(floor),
            Bound::None => f64::NEG_INFINITY,
        }
    }
}

impl Field {
    /// The field of the whole site `site` (index `i`), or `Unsupported` for a kind the
    /// checker cannot evaluate. `h` is the step of the central differences; the scene
    /// gives algebraic curves their default clip box and sampling resolution.
    pub(super) fn of_site(
        i: usize,
        site: &SiteKind,
        h: f64,
        scene: &Scene,
    ) -> Result<Field, Error> {
        Ok(match site {
            SiteKind::Point { at, metric } => match *metric {
                Metric::Euclidean => Field::Euclid { p: *at },
                Metric::Lp { p } => Field::Lp {
                    p: *at,
                    exp: p as i32,
                },
                Metric::Anisotropic { matrix, weight } => Field::Aniso {
                    p: *at,
                    m: matrix,
                    w: weight,
                },
                Metric::Power { weight } => Field::Scaled {
                    p: *at,
                    s: 1.0,
                    w: weight * weight,
                },
                Metric::Moebius { scale, weight } => Field::Scaled {
                    p: *at,
                    s: scale,
                    w: weight,
                },
            },
            SiteKind::Circle { center, radius } => Field::Circle {
                c: *center,
                r: *radius,
            },
            SiteKind::Segment { from, to } => Field::Segment { a: *from, b: *to },
            SiteKind::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => Field::Arc {
                c: *center,
                r: *radius,
                start: *start_angle,
                sweep: crate::geom::arc::sweep(*start_angle, *end_angle),
            },
            SiteKind::Polyline { points } => {
                Field::chain(points.windows(2).map(|w| (w[0], w[1])).collect())
            }
            SiteKind::Polygon { rings } => Field::chain(ring_segments(rings)),
            SiteKind::Ellipse {
                center,
                semi_axes,
                rotation,
            } => Field::Ellipse {
                c: *center,
                a: semi_axes[0],
                b: semi_axes[1],
                rot: *rotation,
            },
            SiteKind::Field { equation } => Field::Poly {
                f: equation.poly().clone(),
                h,
            },
            SiteKind::ImplicitField { equation } => Field::Implicit {
                g: equation.poly().clone(),
                h,
            },
            SiteKind::Algebraic { equation, clip } => {
                let clip = clip.unwrap_or(scene.domain());
                let curve = Curve::new(equation.poly(), clip, 0.25 * scene.epsilon());
                if curve.foot(clip.center()).is_none() {
                    return Err(Error::Unsupported {
                        site: i,
                        kind: site.name().to_string(),
                        message: "the checker finds no point of the curve in its clip box".into(),
                    });
                }
                Field::Curve(Box::new(curve))
            }
            SiteKind::Bezier { .. } | SiteKind::Bspline { .. } => {
                let scale = scene.domain().longest_side();
                let spline = spline_site(site, scale, 0.25 * scene.epsilon());
                Field::Pieces(spline.map(|s| s.pieces).unwrap_or_default())
            }
        })
    }

    /// The distance field of a union of segments.
    pub(super) fn chain(segs: Vec<(Point, Point)>) -> Field {
        let (lo, hi) = bounds(&segs);
        Field::Chain { segs, lo, hi }
    }

    /// The branches at `q` of a curved feature's distance whose values are within
    /// `slack` of the least, nearest first: an arc has one (about its centre), a
    /// free-form piece and an algebraic curve one per distinct local minimum along it
    /// (with the centre of curvature at its foot); other fields have none. Two branches tie on the
    /// feature's own ridge (its self-bisector), which ends at a centre of curvature.
    pub(super) fn branches(&self, q: Point, slack: f64) -> Vec<Branch> {
        match *self {
            Field::Arc { c, .. } => match self.foot(q) {
                Some(foot) => vec![Branch {
                    value: q.dist(foot),
                    foot,
                    center: Some(c),
                    param: None,
                }],
                None => Vec::new(),
            },
            Field::Pieces(ref pieces) => {
                let mut all: Vec<Branch> = pieces
                    .iter()
                    .enumerate()
                    .flat_map(|(k, p)| {
                        p.local_feet(q, slack)
                            .into_iter()
                            .map(move |(value, foot, t)| Branch {
                                value,
                                foot,
                                center: p.curvature_center(t),
                                param: Some((k, t)),
                            })
                    })
                    .collect();
                all.sort_by(|a, b| a.value.total_cmp(&b.value));
                if let Some(least) = all.first().map(|b| b.value) {
                    all.retain(|b| b.value <= least + slack);
                }
                all
            }
            Field::Curve(ref c) => c
                .local_feet(q, slack)
                .into_iter()
                .map(|(value, foot)| Branch {
                    value,
                    foot,
                    center: c.curvature_center(foot),
                    param: None,
                })
                .collect(),
            _ => Vec::new(),
        }
    }

    /// The anchor and lower bound used by the nearest-site search.
    pub(super) fn bound(&self) -> (Point, Bound) {
        let radial = |p: Point, rho: f64| {
            let b = Bound::Pow {
                k: 1.0,
                e: 1,
                w: rho,
                floor: 0.0,
            };
            (p, b)
        };
        match *self {
            Field::Euclid { p } => radial(p, 0.0),
            // x^p + y^p ≥ 2 ((x² + y²)/2)^(p/2) = 2^(1 − p/2) r^p (power means)
            Field::Lp { p, exp } => (
                p,
                Bound::Pow {
                    k: 2f64.powf(1.0 - exp as f64 / 2.0),
                    e: exp,
                    w: 0.0,
                    floor: 0.0,
                },
            ),
            // (q − p)ᵀ M (q − p) ≥ λ_min r²
            Field::Aniso { p, m, w } => {
                let tr = 0.5 * (m[0][0] + m[1][1]);
                let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
                let lmin = (tr - (tr * tr - det).max(0.0).sqrt()).max(0.0);
                let b = Bound::Pow {
                    k: lmin * (1.0 - 1e-12),
                    e: 2,
                    w,
                    floor: -w,
                };
                (p, b)
            }
            Field::Scaled { p, s, w } => (
                p,
                Bound::Pow {
                    k: s,
                    e: 2,
                    w,
                    floor: -w,
                },
            ),
            Field::Circle { c, r } => (
                c,
                Bound::Pow {
                    k: 1.0,
                    e: 1,
                    w: r,
                    floor: -r,
                },
            ),
            Field::Segment { a, b } => radial(a.lerp(b, 0.5), 0.5 * a.dist(b)),
            Field::Chain { lo, hi, .. } => radial(lo.lerp(hi, 0.5), 0.5 * lo.dist(hi)),
            Field::Arc { c, r, .. } => radial(c, r),
            Field::Ellipse { c, a, b, .. } => radial(c, a.max(b)),
            Field::Pieces(ref pieces) if !pieces.is_empty() => {
                let (lo, hi) = pieces.iter().map(|p| p.bounds()).fold(
                    (pieces[0].bounds().min, pieces[0].bounds().max),
                    |(lo, hi), b| {
                        (
                            Point::new(lo.x.min(b.min.x), lo.y.min(b.min.y)),
                            Point::new(hi.x.max(b.max.x), hi.y.max(b.max.y)),
                        )
                    },
                );
                radial(lo.lerp(hi, 0.5), 0.5 * lo.dist(hi))
            }
            Field::Poly { .. } | Field::Implicit { .. } | Field::Curve(_) | Field::Pieces(_) => {
                (Point::default(), Bound::None)
            }
        }
    }

    /// `(f, r)` with the field at `q` equal to `|q − f| − r` for the fields that are a
    /// Euclidean distance computed in closed form (`f` a point site's point, a circle's
    /// centre, the foot on a segment, chain or arc); `None` for the others.
    fn foot_and_radius(&self, q: Point) -> Option<(Point, f64)> {
        match *self {
            Field::Euclid { p } => Some((p, 0.0)),
            Field::Circle { c, r } => Some((c, r)),
            Field::Segment { .. } | Field::Chain { .. } | Field::Arc { .. } => {
                self.foot(q).map(|f| (f, 0.0))
            }
            _ => None,
        }
    }

    /// The field at `q`.
    pub(super) fn value(&self, q: Point) -> f64 {
        match *self {
            Field::Euclid { p } => q.dist(p),
            Field::Lp { p, exp } => (q.x - p.x).powi(exp) + (q.y - p.y).powi(exp),
            Field::Aniso { p, m, w } => {
                let d = q - p;
                m[0][0] * d.x * d.x + (m[0][1] + m[1][0]) * d.x * d.y + m[1][1] * d.y * d.y - w
            }
            Field::Scaled { p, s, w } => {
                let d = q - p;
                s * d.dot(d) - w
            }
            Field::Circle { c, r } => q.dist(c) - r,
            Field::Segment { a, b } => q.dist(crate::geom::segment_foot(q, a, b)),
            Field::Arc { .. } | Field::Chain { .. } | Field::Curve(_) | Field::Pieces(_) => {
                q.dist(self.foot(q).unwrap_or(q))
            }
            Field::Ellipse { .. } if self.inside(q) => 0.0,
            Field::Ellipse { .. } => q.dist(self.foot(q).unwrap_or(q)),
            Field::Poly { ref f, .. } => f.eval(q.x, q.y, 0.0),
            Field::Implicit { ref g, .. } => smallest_nonneg_root(&z_coeffs(g, q)),
        }
    }

    /// The field and its gradient at `q` (analytic where simple, else central
    /// differences).
    pub(super) fn eval(&self, q: Point) -> (f64, Point) {
        let unit = |v: Point| {
            let n = v.norm();
            if n > 0.0 {
                v * (1.0 / n)
            } else {
                Point::default()
            }
        };
        match *self {
            Field::Euclid { p } => (q.dist(p), unit(q - p)),
            Field::Lp { p, exp } => {
                let d = q - p;
                let g = Point::new(
                    exp as f64 * d.x.powi(exp - 1),
                    exp as f64 * d.y.powi(exp - 1),
                );
                (self.value(q), g)
            }
            Field::Aniso { p, m, .. } => {
                let d = q - p;
                let g = Point::new(
                    2.0 * m[0][0] * d.x + (m[0][1] + m[1][0]) * d.y,
                    (m[0][1] + m[1][0]) * d.x + 2.0 * m[1][1] * d.y,
                );
                (self.value(q), g)
            }
            Field::Scaled { p, s, .. } => (self.value(q), (q - p) * (2.0 * s)),
            Field::Circle { c, .. } => (self.value(q), unit(q - c)),
            Field::Segment { .. }
            | Field::Chain { .. }
            | Field::Arc { .. }
            | Field::Ellipse { .. }
            | Field::Curve(_)
            | Field::Pieces(_) => match self.foot(q) {
                Some(f) if !self.inside(q) => (q.dist(f), unit(q - f)),
                _ => (0.0, Point::default()),
            },
            Field::Poly { h, .. } | Field::Implicit { h, .. } => {
                let dx = Point::new(h, 0.0);
                let dy = Point::new(0.0, h);
                let g = Point::new(
                    (self.value(q + dx) - self.value(q - dx)) / (2.0 * h),
                    (self.value(q + dy) - self.value(q - dy)) / (2.0 * h),
                );
                (self.value(q), g)
            }
        }
    }

    /// The nearest point of a geometric site (points: the point itself), if any.
    pub(super) fn foot(&self, q: Point) -> Option<Point> {
        match *self {
            Field::Euclid { p }
            | Field::Lp { p, .. }
            | Field::Aniso { p, .. }
            | Field::Scaled { p, .. } => Some(p),
            Field::Circle { c, r } => {
                let d = q - c;
                let n = d.norm();
                Some(if n > 0.0 { c + d * (r / n) } else { c })
            }
            Field::Segment { a, b } => Some(crate::geom::segment_foot(q, a, b)),
            Field::Chain { ref segs, .. } => segs
                .iter()
                .map(|&(a, b)| crate::geom::segment_foot(q, a, b))
                .min_by(|f, g| q.dist(*f).total_cmp(&q.dist(*g))),
            Field::Arc { c, r, start, sweep } => {
                let d = q - c;
                let t = (d.y.atan2(d.x) - start).rem_euclid(TAU);
                let n = d.norm();
                if (t <= sweep || sweep >= TAU) && n > 0.0 {
                    return Some(c + d * (r / n));
                }
                let at = |a: f64| c + Point::new(a.cos(), a.sin()) * r;
                let (p0, p1) = (at(start), at(start + sweep));
                Some(if q.dist(p0) <= q.dist(p1) { p0 } else { p1 })
            }
            Field::Ellipse { c, a, b, rot } => {
                let (s, co) = rot.sin_cos();
                let d = q - c;
                let local = Point::new(co * d.x + s * d.y, -s * d.x + co * d.y);
                let f = ellipse_foot(a, b, local);
                Some(c + Point::new(co * f.x - s * f.y, s * f.x + co * f.y))
            }
            Field::Curve(ref c) => c.foot(q),
            Field::Pieces(ref pieces) => {
                // pieces whose box lies farther than the best foot so far are skipped
                let mut best: Option<Point> = None;
                for p in pieces {
                    let d = best.map_or(f64::INFINITY, |f| q.dist(f));
                    if p.bounds().outside_distance(q) < d {
                        let f = p.foot(q);
                        if q.dist(f) < d {
                            best = Some(f);
                        }
                    }
                }
                best
            }
            Field::Poly { .. } | Field::Implicit { .. } => None,
        }
    }

    /// Whether `q` lies strictly inside a closed site (an ellipse).
    pub(super) fn inside(&self, q: Point) -> bool {
        self.inside_depth(q) > 0.0
    }

    /// A lower bound on the distance from `q` to the boundary of the closed site that
    /// contains it (0 outside). For an ellipse with `s² = (x/a)² + (y/b)² < 1` this is
    /// `(1 − s) min(a, b)`: by convexity `E ⊇ sE + (1 − s) B(0, min(a, b))`.
    pub(super) fn inside_depth(&self, q: Point) -> f64 {
        match *self {
            Field::Ellipse { c, a, b, rot } => {
                let (s, co) = rot.sin_cos();
                let d = q - c;
                let (x, y) = (co * d.x + s * d.y, -s * d.x + co * d.y);
                let r = ((x / a).powi(2) + (y / b).powi(2)).sqrt();
                ((1.0 - r) * a.min(b)).max(0.0)
            }
            _ => 0.0,
        }
    }

    /// A Euclidean distance from `q` to the site itself, in length units (for point
    /// fields: to the point; for field sites: `|f| / |∇f|`).
    pub(super) fn distance_to_site(&self, q: Point) -> f64 {
        match *self {
            Field::Circle { .. } | Field::Poly { .. } | Field::Implicit { .. } => {
                let (v, g) = self.eval(q);
                if matches!(self, Field::Circle { .. }) {
                    v.abs()
                } else {
                    v.abs() / g.norm().max(1e-300)
                }
            }
            _ => self.foot(q).map_or(f64::INFINITY, |f| q.dist(f)),
        }
    }
}

/// `d_a − d_b` at `q`, the quantity whose zero is the bisector of `a` and `b`.
///
/// Where both fields are Euclidean distances to a foot (less a radius: a circle), far
/// from two nearby feet `f_a`, `f_b`, the two distances agree to many digits: their
/// difference in f64 is the rounding of each (an ulp of `|q − f|`, 1.9e-9 at 1e7),
/// which the gradients' small difference (about `|f_a − f_b| / |q − f|`, 3e-10 for
/// feet 0.01 apart seen from 1e7) turns into an error of position of some units. The
/// identity `|q − f_a| − |q − f_b| = (f_b − f_a)·((q − f_a) + (q − f_b)) / (|q − f_a| +
/// |q − f_b|)` takes the difference from the feet's difference instead, with an error
/// of some ulps of the feet over the distance (position errors some 1e-5 there). The
/// feet are exact for points and ends, and off by rounding along a segment or an arc,
/// which changes the distance only to second order.
pub(super) fn difference(a: &Field, b: &Field, q: Point) -> f64 {
    match (a.foot_and_radius(q), b.foot_and_radius(q)) {
        (Some((fa, ra)), Some((fb, rb))) => {
            let (da, db) = (q - fa, q - fb);
            let sum = da.norm() + db.norm();
            let apart = if sum > 0.0 {
                (fb - fa).dot(da + db) / sum
            } else {
                0.0
            };
            apart - (ra - rb)
        }
        _ => a.value(q) - b.value(q),
    }
}

/// The boundary segments of a polygon's rings (each ring closed).
pub(super) fn ring_segments(rings: &[Vec<Point>]) -> Vec<(Point, Point)> {
    rings
        .iter()
        .flat_map(|r| (0..r.len()).map(move |k| (r[k], r[(k + 1) % r.len()])))
        .collect()
}

/// The nearest point of the axis-aligned ellipse `(x/a)² + (y/b)² = 1` to an outside
/// point `q`. By symmetry take `q` in the first quadrant and `a ≥ b` (else swap the
/// axes). The foot is `(a² x / (t + a²), b² y / (t + b²))` where `t ≥ 0` is the root of
/// `F(t) = (a x / (t + a²))² + (b y / (t + b²))² − 1` (Eberly). `F` is convex and
/// decreasing for `t > −b²` with `F(0) ≥ 0` outside, so Newton from `t = 0` increases
/// monotonically to the root: no safeguard is needed. (On the angle parameter the
/// stationary equation can have several roots in the quadrant when `q` lies inside the
/// evolute.) For an inside point it returns the radial projection onto the curve.
fn ellipse_foot(a: f64, b: f64, q: Point) -> Point {
    if a < b {
        let f = ellipse_foot(b, a, Point::new(q.y, q.x));
        return Point::new(f.y, f.x);
    }
    let (x, y) = (q.x.abs(), q.y.abs());
    let s = ((x / a).powi(2) + (y / b).powi(2)).sqrt();
    if s <= 1.0 {
        return if s > 0.0 {
            q * (1.0 / s)
        } else {
            Point::new(a, 0.0)
        };
    }
    let (a2, b2) = (a * a, b * b);
    let mut t = 0.0f64;
    for _ in 0..200 {
        let (u, v) = (a * x / (t + a2), b * y / (t + b2));
        let f = u * u + v * v - 1.0;
        let df = -2.0 * (u * u / (t + a2) + v * v / (t + b2));
        let step = -f / df;
        if step.is_nan() || step <= 0.0 || t + step == t {
            break;
        }
        t += step;
    }
    Point::new(
        (a2 * x / (t + a2)).copysign(q.x),
        (b2 * y / (t + b2)).copysign(q.y),
    )
}

/// The coefficients `c_k` of `g(x, y, z) = Σ c_k z^k` at `q = (x, y)`.
fn z_coeffs(g: &Poly, q: Point) -> Vec<f64> {
    let deg = g.terms.iter().map(|t| t.0[2]).max().unwrap_or(0) as usize;
    let mut c = vec![0.0; deg + 1];
    for &([i, j, k], coef) in &g.terms {
        c[k as usize] += coef * q.x.powi(i as i32) * q.y.powi(j as i32);
    }
    c
}

/// `Σ c_k t^k` by Horner's rule.
fn horner(c: &[f64], t: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * t + ck)
}

/// The smallest non-negative real root of `Σ c_k z^k`, or 0 if there is none (the point
/// is inside the site). Degrees ≤ 2 in closed form; higher degrees by isolating the
/// roots between the derivative's roots on `[0, B]`, `B = 1 + max |c_k / c_n|`
/// (Cauchy), each monotone piece solved by safeguarded Newton.
fn smallest_nonneg_root(c: &[f64]) -> f64 {
    let scale = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut n = c.len();
    while n > 0 && c[n - 1].abs() <= 1e-14 * scale {
        n -= 1;
    }
    let c = &c[..n];
    let root = match n {
        0 | 1 => None,
        2 => Some(-c[0] / c[1]).filter(|z| *z >= 0.0),
        3 => {
            let (a, b, cc) = (c[2], c[1], c[0]);
            let disc = b * b - 4.0 * a * cc;
            if disc < 0.0 {
                None
            } else {
                // numerically stable pair of roots
                let qq = -0.5 * (b + disc.sqrt().copysign(b));
                let r1 = qq / a;
                let r2 = if qq != 0.0 { cc / qq } else { r1 };
                [r1.min(r2), r1.max(r2)].into_iter().find(|z| *z >= 0.0)
            }
        }
        _ => {
            let bound = 1.0
                + c[..n - 1]
                    .iter()
                    .fold(0.0f64, |m, v| m.max((v / c[n - 1]).abs()));
            real_roots(c, 0.0, bound).into_iter().next()
        }
    };
    root.unwrap_or(0.0)
}

/// The real roots of `Σ c_k t^k` in `[lo, hi]`, ascending: between consecutive roots of
/// the derivative the polynomial is monotone, so each piece holds at most one root; a
/// critical point where the polynomial vanishes (to rounding) is a multiple root.
fn real_roots(c: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    if c.len() <= 1 {
        return Vec::new();
    }
    if c.len() == 2 {
        let z = -c[0] / c[1];
        return if (lo..=hi).contains(&z) {
            vec![z]
        } else {
            Vec::new()
        };
    }
    let d: Vec<f64> = c
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, ck)| k as f64 * ck)
        .collect();
    let mut knots = vec![lo];
    knots.extend(real_roots(&d, lo, hi));
    knots.push(hi);
    let noise = |t: f64| {
        1e-12
            * c.iter()
                .rev()
                .fold(0.0, |acc: f64, &ck| acc * t.abs() + ck.abs())
    };
    let mut roots: Vec<f64> = Vec::new();
    for w in knots.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (fa, fb) = (horner(c, a), horner(c, b));
        if fa.abs() <= noise(a) {
            if roots.last().is_none_or(|r| *r < a) {
                roots.push(a);
            }
            continue;
        }
        if fa * fb > 0.0 {
            continue;
        }
        let (mut l, mut h) = if fa < 0.0 { (a, b) } else { (b, a) };
        let mut t = 0.5 * (a + b);
        for _ in 0..200 {
            let f = horner(c, t);
            if f == 0.0 {
                break;
            }
            if f < 0.0 {
                l = t;
            } else {
                h = t;
            }
            let df = horner(&d, t);
            // converged: keep t (the check must come before t moves, or a bisection
            // step taken beside a converged Newton iterate would be returned)
            if (f / df).abs() <= 1e-16 * t.abs() {
                break;
            }
            let nt = t - f / df;
            let (mn, mx) = (l.min(h), l.max(h));
            t = if df != 0.0 && nt > mn && nt < mx {
                nt
            } else {
                0.5 * (l + h)
            };
            if (mx - mn) <= 1e-15 * mx.abs().max(1e-300) {
                break;
            }
        }
        roots.push(t);
    }
    if horner(c, hi).abs() <= noise(hi) && roots.last().is_none_or(|r| *r < hi) {
        roots.push(hi);
    }
    roots
}

/// The corners `(lo, hi)` of the box around segments' ends (infinite when empty).
pub(super) fn bounds(segs: &[(Point, Point)]) -> (Point, Point) {
    let (mut lo, mut hi) = (
        Point::new(f64::INFINITY, f64::INFINITY),
        Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for &(a, b) in segs {
        for p in [a, b] {
            lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
            hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    #[test]
    fn cubic_root_is_not_a_bisection_midpoint() {
        // z³ + z² = r²: this input once returned half the root (a bisection step taken
        // after Newton had converged)
        let c = [1.9970599999999998, 0.0, -1.0, -1.0];
        let z = smallest_nonneg_root(&c);
        assert!((c[0] - z * z - z * z * z).abs() < 1e-12, "{z}");
    }

    use super::*;

    #[test]
    fn roots_of_cubic_and_quadratic() {
        // (z − 1)(z − 2)(z + 3) = z³ − 7z + 6
        assert!((smallest_nonneg_root(&[6.0, -7.0, 0.0, 1.0]) - 1.0).abs() < 1e-12);
        // (z − 0.5)² double root
        assert!((smallest_nonneg_root(&[0.25, -1.0, 1.0]) - 0.5).abs() < 1e-7);
        // z² + 1: none
        assert_eq!(smallest_nonneg_root(&[1.0, 0.0, 1.0]), 0.0);
        // (z − 0.3)²(z − 2)(z + 1): quartic with a double root
        let c = [-0.18, 1.11, -1.31, -1.6, 1.0];
        assert!(
            (smallest_nonneg_root(&c) - 0.3).abs() < 1e-6,
            "{}",
            smallest_nonneg_root(&c)
        );
    }

    #[test]
    fn ellipse_and_arc_distances() {
        let e = Field::Ellipse {
            c: Point::new(1.0, 0.0),
            a: 2.0,
            b: 1.0,
            rot: std::f64::consts::FRAC_PI_2,
        };
        // rotated by 90°: the major axis is vertical
        assert!((e.value(Point::new(1.0, 3.0)) - 1.0).abs() < 1e-12);
        assert!((e.value(Point::new(3.0, 0.0)) - 1.0).abs() < 1e-12);
        assert_eq!(e.value(Point::new(1.2, 0.3)), 0.0);
        // an elongated ellipse seen from inside its evolute: the nearest foot is the
        // co-vertex side, at distance 0.5 (the angle equation has several roots there)
        let long = Field::Ellipse {
            c: Point::default(),
            a: 3.0,
            b: 1.0,
            rot: 0.0,
        };
        assert!((long.value(Point::new(0.0, 1.5)) - 0.5).abs() < 1e-12);
        let q = Point::new(0.4, 1.5);
        let brute = (0..200_000)
            .map(|k| {
                let t = k as f64 * TAU / 200_000.0;
                q.dist(Point::new(3.0 * t.cos(), t.sin()))
            })
            .fold(f64::INFINITY, f64::min);
        // sampling overestimates by O(Δt²)
        let v = long.value(q);
        assert!(v <= brute && brute - v < 1e-8, "{v} {brute}");
        let arc = Field::Arc {
            c: Point::default(),
            r: 1.0,
            start: 0.0,
            sweep: std::f64::consts::FRAC_PI_2,
        };
        assert!((arc.value(Point::new(2.0, 2.0)) - (8f64.sqrt() - 1.0)).abs() < 1e-12);
        assert!((arc.value(Point::new(0.0, -1.0)) - 2f64.sqrt()).abs() < 1e-12);
    }
}
