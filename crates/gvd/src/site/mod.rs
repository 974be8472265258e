//! Sites as distance fields. The subdivision engine sees only the [`DistanceField`]
//! trait; each site family lives in its own file and [`SiteField`] dispatches to it.

pub mod algebraic;
mod circle;
mod curve_tree;
mod ellipse;
mod euclidean;
pub mod featured;
mod freeform;
pub mod implicit;
mod lp;
pub mod polygonal;
mod polynomial;
pub mod zone;

pub use algebraic::AlgebraicField;
pub use circle::CircleField;
pub use curve_tree::CurveState;
pub use ellipse::EllipseField;
pub use euclidean::EuclideanPoint;
pub use freeform::FreeformField;
pub use implicit::{ImplicitField, ImplicitState};
pub use lp::LpPoint;
pub use polynomial::PolynomialField;

use crate::error::Error;
use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::Bernstein2;
use crate::num::Interval;
use crate::scene::{Metric, Mode, Scene, SiteKind};

/// Bounds over a box of a function `h` whose zero set and sign are those of
/// `f_a − f_b` (it may be `f_a − f_b` itself or any sign-equivalent form, e.g. the
/// difference of squared Euclidean distances).
#[derive(Clone, Copy, Debug)]
pub struct PairBound {
    /// An enclosure of `h` over the box.
    pub value: Interval,
    /// An enclosure of `∇h` over the box, when the fields can bound their gradients.
    pub gradient: Option<[Interval; 2]>,
}

/// What the subdivision engine needs from a site: a conservative bound of its field over
/// a box, its value and gradient at a point, and optional per-box state that children
/// inherit (split, never recomputed from scratch).
pub trait DistanceField: Send + Sync {
    /// Per-box state (e.g. Bernstein coefficients over the box).
    type State: Clone + Send + Sync;

    /// The state for box `b`, computed from scratch.
    fn state(&self, b: &Aabb) -> Self::State;

    /// The states of the two halves of `b` split at coordinate `at` along `axis`.
    fn split(&self, s: &Self::State, b: &Aabb, axis: Axis, at: f64) -> (Self::State, Self::State);

    /// An enclosure of the field over `b`.
    fn bound(&self, s: &Self::State, b: &Aabb) -> Interval;

    /// An enclosure of the field's gradient over `b`, if the field can give one.
    fn gradient_bound(&self, s: &Self::State, b: &Aabb) -> Option<[Interval; 2]>;

    /// Whether [`restrict`](Self::restrict) narrows a state more cheaply than
    /// [`state`](Self::state) builds one; the engine then keeps the states of its leaves
    /// for the scan of their sides.
    fn restricts(&self) -> bool {
        false
    }

    /// The state over `to`, a box inside the one `s` was made for (by default afresh).
    fn restrict(&self, _s: &Self::State, to: &Aabb) -> Self::State {
        self.state(to)
    }

    /// The field at `q`, as accurate as f64 allows.
    fn value(&self, q: Point) -> f64;

    /// The field at `q`, a point of the box that `s` was made for; fields whose state
    /// narrows the search for the value override it (by default [`value`](Self::value)).
    fn value_in(&self, _s: &Self::State, q: Point) -> f64 {
        self.value(q)
    }

    /// The field's gradient at `q`.
    fn gradient(&self, q: Point) -> Point;

    /// The exact order of this field's and `other`'s values at `q`, where the two can be
    /// compared without rounding (two Euclidean points); `None` by default, when only
    /// the f64 values can tell.
    fn exact_cmp(&self, _other: &Self, _q: Point) -> Option<std::cmp::Ordering> {
        None
    }

    /// True when `other` is nowhere nearer than this site over `b` (ties allowed), known
    /// from what the two sites are rather than from bounds: say a curve `other` lies
    /// outside the region this curve bounds, and `b` is inside that region. The filter
    /// then drops `other` where no bound of the difference can, as where the
    /// difference has a double zero (the common normal of two tangent curves). False
    /// by default.
    fn occludes(&self, _s: &Self::State, _other: &Self, _so: &Self::State, _b: &Aabb) -> bool {
        false
    }

    /// Bounds of `f_self − f_other` (or of a sign-equivalent function) over `b`. The
    /// default subtracts the two field bounds; implementations override it where the
    /// difference is much tighter than that (the difference of two quadrics is linear).
    fn pair(&self, s: &Self::State, other: &Self, so: &Self::State, b: &Aabb) -> PairBound {
        bound_difference(self, s, other, so, b)
    }
}

/// `f_a − f_b` bounded by subtracting the two fields' own bounds (and gradient bounds).
pub fn bound_difference<F: DistanceField + ?Sized>(
    a: &F,
    sa: &F::State,
    b: &F,
    sb: &F::State,
    bx: &Aabb,
) -> PairBound {
    let gradient = match (a.gradient_bound(sa, bx), b.gradient_bound(sb, bx)) {
        (Some(g), Some(h)) => Some([g[0] - h[0], g[1] - h[1]]),
        _ => None,
    };
    PairBound {
        value: a.bound(sa, bx) - b.bound(sb, bx),
        gradient,
    }
}

/// A site's distance field, one variant per family.
#[derive(Clone, Debug)]
pub enum SiteField {
    /// A Euclidean point by its closed form.
    Euclidean(EuclideanPoint),
    /// A polynomial field in x and y (point metrics and `field` sites).
    Polynomial(PolynomialField),
    /// An lp point by its closed form (exact separable bounds).
    Lp(LpPoint),
    /// A circle by its closed form `|q − c| − r`.
    Circle(CircleField),
    /// An implicit field (§3): `implicit_field` sites, and circles on the implicit path.
    Implicit(Box<ImplicitField>),
    /// An ellipse: implicit box bounds, closed-form point values.
    Ellipse(Box<EllipseField>),
    /// An algebraic curve: its own [`DistanceField`], delegated to.
    Algebraic(Box<AlgebraicField>),
    /// A Bézier or B-spline curve by its tree of sub-spans.
    Freeform(Box<FreeformField>),
}

/// The per-box state of a [`SiteField`]: its family's own state (large ones boxed).
#[derive(Clone, Debug)]
pub enum FieldState {
    Euclidean(()),
    Polynomial(Bernstein2),
    Lp(()),
    Circle(()),
    Implicit(Box<ImplicitState>),
    Ellipse(Box<ImplicitState>),
    Algebraic(Box<CurveState>),
    Freeform(Box<CurveState>),
}

/// Choices among equivalent fields for a site kind.
#[derive(Clone, Copy, Debug, Default)]
pub struct FieldOptions {
    /// Circles through the implicit path (Bernstein forms of `|q − c|² − w²`) instead of
    /// their closed form (the default, faster: see `gvd bench implicit`).
    pub implicit_circles: bool,
    /// lp points through their Bernstein forms (the paper's path) instead of their
    /// closed form (the default, faster and tighter: see `gvd bench emiris-table1`).
    pub bernstein_lp: bool,
}

impl SiteField {
    /// The distance field of site `index` of a scene, or an error when no field of the
    /// subdivision engine can represent it yet (default [`FieldOptions`]).
    pub fn from_site(index: usize, kind: &SiteKind, domain: &Aabb) -> Result<SiteField, Error> {
        SiteField::from_site_with(index, kind, domain, &FieldOptions::default())
    }

    /// [`SiteField::from_site`] with explicit choices.
    pub fn from_site_with(
        index: usize,
        kind: &SiteKind,
        domain: &Aabb,
        options: &FieldOptions,
    ) -> Result<SiteField, Error> {
        SiteField::from_site_at(index, kind, domain, 1e-3 * domain.longest_side(), options)
    }

    /// [`SiteField::from_site_with`] at the scene's resolution `epsilon` (curves are
    /// enclosed to it).
    fn from_site_at(
        index: usize,
        kind: &SiteKind,
        domain: &Aabb,
        epsilon: f64,
        options: &FieldOptions,
    ) -> Result<SiteField, Error> {
        match kind {
            SiteKind::Algebraic { equation, clip } => Ok(SiteField::Algebraic(Box::new(
                AlgebraicField::new(index, equation.poly(), clip.unwrap_or(*domain), epsilon)?,
            ))),
            SiteKind::Circle { center, radius } => Ok(if options.implicit_circles {
                SiteField::Implicit(Box::new(ImplicitField::circle(*center, *radius)))
            } else {
                SiteField::Circle(CircleField::new(*center, *radius))
            }),
            SiteKind::Ellipse {
                center,
                semi_axes,
                rotation,
            } => Ok(SiteField::Ellipse(Box::new(EllipseField::new(
                *center, *semi_axes, *rotation,
            )))),
            SiteKind::ImplicitField { equation } => Ok(SiteField::Implicit(Box::new(
                ImplicitField::new(index, equation.poly(), domain)?,
            ))),
            SiteKind::Point { at, metric } => Ok(match metric {
                Metric::Euclidean => SiteField::Euclidean(EuclideanPoint::new(*at)),
                Metric::Lp { p } if !options.bernstein_lp => SiteField::Lp(LpPoint::new(*at, *p)),
                _ => SiteField::Polynomial(PolynomialField::from_metric(*at, metric)),
            }),
            SiteKind::Field { equation } => Ok(SiteField::Polynomial(PolynomialField::new(
                equation.poly().clone(),
            ))),
            SiteKind::Bezier { .. }
            | SiteKind::Bspline { .. }
            | SiteKind::Segment { .. }
            | SiteKind::Polyline { .. }
            | SiteKind::Polygon { .. }
            | SiteKind::Arc { .. } => {
                let spans = freeform::curve_spans(kind).unwrap_or_default();
                Ok(SiteField::Freeform(Box::new(FreeformField::new(
                    index, spans, epsilon,
                )?)))
            }
        }
    }

    /// The fields of every site of a scene.
    pub fn for_scene(scene: &Scene) -> Result<Vec<SiteField>, Error> {
        SiteField::for_scene_with(scene, &FieldOptions::default())
    }

    /// The fields of every site of a scene, with explicit choices.
    /// Algebraic curves learn on which side of each other they lie.
    /// Segments, polylines, polygons and arcs are whole sites: `voronoi` mode only.
    pub fn for_scene_with(scene: &Scene, options: &FieldOptions) -> Result<Vec<SiteField>, Error> {
        refuse_whole_linear_sites(scene)?;
        refuse_shared_ends(scene)?;
        scene.refuse_sites_inside_polygons(|i| {
            site_samples(&scene.sites()[i].kind, scene.epsilon())
        })?;
        let mut fields = scene
            .sites()
            .iter()
            .enumerate()
            .map(|(i, s)| {
                SiteField::from_site_at(i, &s.kind, &scene.domain(), scene.epsilon(), options)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut curves: Vec<&mut AlgebraicField> = fields
            .iter_mut()
            .filter_map(|f| match f {
                SiteField::Algebraic(a) => Some(a.as_mut()),
                _ => None,
            })
            .collect();
        AlgebraicField::find_sides(&mut curves);
        Ok(fields)
    }
}

/// Refuses segments, polylines, polygons and arcs outside `voronoi` mode: their fields
/// are whole sites, and the other modes' generators are their ends, edges and corners.
pub(crate) fn refuse_whole_linear_sites(scene: &Scene) -> Result<(), Error> {
    if scene.mode() == Mode::Voronoi {
        return Ok(());
    }
    match scene
        .sites()
        .iter()
        .position(|s| is_linear_or_circular(&s.kind))
    {
        None => Ok(()),
        Some(i) => Err(Error::Unsupported {
            site: i,
            kind: scene.sites()[i].kind.name().to_string(),
            message: format!(
                "the subdivision engine computes segments, polylines, polygons and arcs \
                 beside other kinds in 'voronoi' mode only, not in '{}' (the incremental \
                 engine computes them alone in every mode)",
                scene.mode().name()
            ),
        }),
    }
}

/// Refuses a segment, polyline, polygon or arc that shares a point (an end, a corner)
/// with another site: around it both distances are the distance to that point, a tie
/// over a whole wedge, which these fields do not resolve into one owner.
fn refuse_shared_ends(scene: &Scene) -> Result<(), Error> {
    let corners = |kind: &SiteKind| -> Vec<Point> {
        match kind {
            SiteKind::Point { at, .. } => vec![*at],
            SiteKind::Segment { from, to } => vec![*from, *to],
            SiteKind::Polyline { points } => points.clone(),
            SiteKind::Polygon { rings } => rings.concat(),
            // curves and arcs: the end control points of their spans (an arc's are its
            // own ends, bit for bit; evaluating at 1 may round off the last one)
            kind => freeform::curve_spans(kind)
                .and_then(|spans| {
                    let first = *spans.first()?.control_points().first()?;
                    let last = *spans.last()?.control_points().last()?;
                    Some(vec![first, last])
                })
                .unwrap_or_default(),
        }
    };
    let mut owner: std::collections::HashMap<(u64, u64), usize> = Default::default();
    for (i, site) in scene.sites().iter().enumerate() {
        for p in corners(&site.kind) {
            let key = ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits());
            match owner.get(&key) {
                Some(&j)
                    if j != i
                        && (is_linear_or_circular(&site.kind)
                            || is_linear_or_circular(&scene.sites()[j].kind)) =>
                {
                    return Err(Error::Conflict {
                        site: j,
                        other: i,
                        message: format!(
                            "they share the point ({}, {}), which the subdivision engine \
                             does not resolve beside segments, polylines, polygons and arcs \
                             yet (the incremental engine computes such shared ends)",
                            p.x, p.y
                        ),
                    });
                }
                _ => {
                    owner.entry(key).or_insert(i);
                }
            }
        }
    }
    Ok(())
}

/// Most points [`site_samples`] takes along one site.
const MAX_SITE_SAMPLES: usize = 1 << 20;

/// Points along a site, `spacing` apart or closer (up to [`MAX_SITE_SAMPLES`]): the
/// point itself, points of a circle or an ellipse, of each span of a curve; none for
/// algebraic curves and fields.
fn site_samples(kind: &SiteKind, spacing: f64) -> Vec<Point> {
    let count = |length: f64| ((length / spacing).ceil() as usize).clamp(2, MAX_SITE_SAMPLES);
    let around = |n: usize, at: &dyn Fn(f64) -> Point| -> Vec<Point> {
        (0..n)
            .map(|k| at(std::f64::consts::TAU * k as f64 / n as f64))
            .collect()
    };
    match kind {
        SiteKind::Point { at, .. } => vec![*at],
        SiteKind::Circle { center, radius } => {
            around(count(std::f64::consts::TAU * radius), &|a: f64| {
                *center + Point::new(a.cos(), a.sin()) * *radius
            })
        }
        SiteKind::Ellipse {
            center,
            semi_axes,
            rotation,
        } => {
            let (s, c) = rotation.sin_cos();
            around(
                count(std::f64::consts::TAU * semi_axes[0].max(semi_axes[1])),
                &|a: f64| {
                    let (x, y) = (semi_axes[0] * a.cos(), semi_axes[1] * a.sin());
                    *center + Point::new(c * x - s * y, s * x + c * y)
                },
            )
        }
        _ => {
            let spans = freeform::curve_spans(kind).unwrap_or_default();
            let per_span = MAX_SITE_SAMPLES / spans.len().max(1);
            spans
                .iter()
                .flat_map(|span| {
                    let hull: f64 = span
                        .control_points()
                        .windows(2)
                        .map(|w| w[0].dist(w[1]))
                        .sum();
                    span.sample(count(hull).min(per_span.max(2)))
                })
                .collect()
        }
    }
}

/// Whether a site is a segment, polyline, polygon or arc: a field of the subdivision
/// engine as a curve of straight and circular spans.
pub fn is_linear_or_circular(kind: &SiteKind) -> bool {
    matches!(
        kind,
        SiteKind::Segment { .. }
            | SiteKind::Polyline { .. }
            | SiteKind::Polygon { .. }
            | SiteKind::Arc { .. }
    )
}

/// [`DistanceField`] for [`SiteField`], delegating to each family: `$variant` names
/// both a [`SiteField`] and its [`FieldState`]. A state of another family (never made
/// by the engine) is replaced by a fresh one for the box.
macro_rules! delegate_to_families {
    ($($variant:ident),* $(,)?) => {
        impl DistanceField for SiteField {
            type State = FieldState;

            fn state(&self, b: &Aabb) -> FieldState {
                match self {
                    $(SiteField::$variant(f) => FieldState::$variant(f.state(b).into()),)*
                }
            }

            fn split(&self, s: &FieldState, b: &Aabb, axis: Axis, at: f64) -> (FieldState, FieldState) {
                match self {
                    $(SiteField::$variant(f) => {
                        let (l, r) = match s {
                            FieldState::$variant(s) => f.split(s, b, axis, at),
                            _ => f.split(&f.state(b), b, axis, at),
                        };
                        (FieldState::$variant(l.into()), FieldState::$variant(r.into()))
                    })*
                }
            }

            fn bound(&self, s: &FieldState, b: &Aabb) -> Interval {
                match self {
                    $(SiteField::$variant(f) => match s {
                        FieldState::$variant(s) => f.bound(s, b),
                        _ => f.bound(&f.state(b), b),
                    },)*
                }
            }

            fn gradient_bound(&self, s: &FieldState, b: &Aabb) -> Option<[Interval; 2]> {
                match self {
                    $(SiteField::$variant(f) => match s {
                        FieldState::$variant(s) => f.gradient_bound(s, b),
                        _ => f.gradient_bound(&f.state(b), b),
                    },)*
                }
            }

            fn restricts(&self) -> bool {
                match self {
                    $(SiteField::$variant(f) => f.restricts(),)*
                }
            }

            fn restrict(&self, s: &FieldState, to: &Aabb) -> FieldState {
                match (self, s) {
                    $((SiteField::$variant(f), FieldState::$variant(s)) => {
                        FieldState::$variant(f.restrict(s, to).into())
                    })*
                    _ => self.state(to),
                }
            }

            fn value(&self, q: Point) -> f64 {
                match self {
                    $(SiteField::$variant(f) => f.value(q),)*
                }
            }

            fn value_in(&self, s: &FieldState, q: Point) -> f64 {
                match (self, s) {
                    $((SiteField::$variant(f), FieldState::$variant(s)) => f.value_in(s, q),)*
                    _ => self.value(q),
                }
            }

            fn gradient(&self, q: Point) -> Point {
                match self {
                    $(SiteField::$variant(f) => f.gradient(q),)*
                }
            }

            /// One family's own pair bound; across families, a point and a circle by
            /// the circles' form, a point and a free-form curve by the mean value form
            /// (`curve_tree::pair_with_point`), else the difference of the two bounds.
            fn pair(&self, s: &FieldState, other: &SiteField, so: &FieldState, b: &Aabb) -> PairBound {
                match (self, other, s, so) {
                    $((
                        SiteField::$variant(p),
                        SiteField::$variant(q),
                        FieldState::$variant(s),
                        FieldState::$variant(so),
                    ) => p.pair(s, q, so, b),)*
                    (SiteField::Circle(p), SiteField::Euclidean(q), _, _) => {
                        circle::pair((p.center, p.radius), (q.at, 0.0), b)
                    }
                    (SiteField::Euclidean(p), SiteField::Circle(q), _, _) => {
                        circle::pair((p.at, 0.0), (q.center, q.radius), b)
                    }
                    (SiteField::Euclidean(p), SiteField::Freeform(q), _, FieldState::Freeform(so)) => {
                        curve_tree::pair_with_point(p.at, q.as_ref(), so, b)
                    }
                    (SiteField::Freeform(p), SiteField::Euclidean(q), FieldState::Freeform(s), _) => {
                        let h = curve_tree::pair_with_point(q.at, p.as_ref(), s, b);
                        PairBound {
                            value: -h.value,
                            gradient: h.gradient.map(|g| [-g[0], -g[1]]),
                        }
                    }
                    _ => bound_difference(self, s, other, so, b),
                }
            }

            /// Two Euclidean points exactly (`EuclideanPoint::exact_cmp`); other pairs by
            /// their f64 values only.
            fn exact_cmp(&self, other: &SiteField, q: Point) -> Option<std::cmp::Ordering> {
                match (self, other) {
                    (SiteField::Euclidean(p), SiteField::Euclidean(o)) => p.exact_cmp(o, q),
                    _ => None,
                }
            }

            /// Algebraic curves by the sides they lie on (`algebraic::occlusion`); a
            /// free-form curve whose only possible nearest points over `b` are its ends at
            /// a point of `self` (a corner's point, or another curve's end: a joint), by
            /// `self` (`FreeformField::only_ends_at`).
            fn occludes(&self, _s: &FieldState, other: &SiteField, so: &FieldState, b: &Aabb) -> bool {
                match (self, other, so) {
                    (SiteField::Algebraic(p), SiteField::Algebraic(q), _) => p.occludes_over(q, b),
                    (SiteField::Euclidean(p), SiteField::Freeform(f), FieldState::Freeform(s)) => {
                        f.only_ends_at(s, b, p.at)
                    }
                    (SiteField::Freeform(a), SiteField::Freeform(f), FieldState::Freeform(s)) => {
                        a.ends().into_iter().any(|e| f.only_ends_at(s, b, e))
                    }
                    _ => false,
                }
            }
        }
    };
}

delegate_to_families!(Euclidean, Polynomial, Lp, Circle, Implicit, Ellipse, Algebraic, Freeform);
