//! Sites as distance fields. The subdivision engine sees only the [`DistanceField`]
//! trait; each site family lives in its own file and [`SiteField`] dispatches to it.

pub mod algebraic;
mod circle;
mod ellipse;
mod euclidean;
pub mod implicit;
mod lp;
pub mod polygonal;
mod polynomial;

pub use algebraic::{AlgebraicField, AlgebraicState};
pub use circle::CircleField;
pub use ellipse::EllipseField;
pub use euclidean::EuclideanPoint;
pub use implicit::{ImplicitField, ImplicitState};
pub use lp::LpPoint;
pub use polynomial::PolynomialField;

use crate::error::Error;
use crate::geom::{Aabb, Axis, Point};
use crate::num::bernstein::Bernstein2;
use crate::num::Interval;
use crate::scene::{Metric, Scene, SiteKind};

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

    /// The field at `q`, as accurate as f64 allows.
    fn value(&self, q: Point) -> f64;

    /// The field's gradient at `q`.
    fn gradient(&self, q: Point) -> Point;

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
}

/// The per-box state of a [`SiteField`].
#[derive(Clone, Debug)]
pub enum FieldState {
    None,
    Bernstein(Bernstein2),
    Implicit(Box<ImplicitState>),
    Algebraic(Box<AlgebraicState>),
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
            other => Err(Error::Unsupported {
                site: index,
                kind: other.name().to_string(),
                message: "not supported yet by the subdivision engine".to_string(),
            }),
        }
    }

    /// The fields of every site of a scene.
    pub fn for_scene(scene: &Scene) -> Result<Vec<SiteField>, Error> {
        SiteField::for_scene_with(scene, &FieldOptions::default())
    }

    /// The fields of every site of a scene, with explicit choices.
    pub fn for_scene_with(scene: &Scene, options: &FieldOptions) -> Result<Vec<SiteField>, Error> {
        scene
            .sites()
            .iter()
            .enumerate()
            .map(|(i, s)| {
                SiteField::from_site_at(i, &s.kind, &scene.domain(), scene.epsilon(), options)
            })
            .collect()
    }
}

impl DistanceField for SiteField {
    type State = FieldState;

    fn state(&self, b: &Aabb) -> FieldState {
        match self {
            SiteField::Euclidean(_) | SiteField::Circle(_) | SiteField::Lp(_) => FieldState::None,
            SiteField::Polynomial(f) => FieldState::Bernstein(f.bernstein(b)),
            SiteField::Implicit(f) => FieldState::Implicit(Box::new(f.state(b))),
            SiteField::Ellipse(f) => FieldState::Implicit(Box::new(f.state(b))),
            SiteField::Algebraic(f) => FieldState::Algebraic(Box::new(f.state(b))),
        }
    }

    fn split(&self, s: &FieldState, b: &Aabb, axis: Axis, at: f64) -> (FieldState, FieldState) {
        match (self, s) {
            (SiteField::Polynomial(f), FieldState::Bernstein(bf)) => {
                let (l, r) = f.split(bf, b, axis, at);
                (FieldState::Bernstein(l), FieldState::Bernstein(r))
            }
            (SiteField::Implicit(f), FieldState::Implicit(st)) => {
                let (l, r) = f.split(st, b, axis, at);
                (
                    FieldState::Implicit(Box::new(l)),
                    FieldState::Implicit(Box::new(r)),
                )
            }
            (SiteField::Ellipse(f), FieldState::Implicit(st)) => {
                let (l, r) = f.split(st, b, axis, at);
                (
                    FieldState::Implicit(Box::new(l)),
                    FieldState::Implicit(Box::new(r)),
                )
            }
            (SiteField::Algebraic(f), FieldState::Algebraic(st)) => {
                let (l, r) = f.split(st, b, axis, at);
                (
                    FieldState::Algebraic(Box::new(l)),
                    FieldState::Algebraic(Box::new(r)),
                )
            }
            (SiteField::Implicit(_) | SiteField::Ellipse(_) | SiteField::Algebraic(_), _) => {
                let (lb, rb) = b.split(axis, at);
                (self.state(&lb), self.state(&rb))
            }
            _ => (FieldState::None, FieldState::None),
        }
    }

    fn bound(&self, s: &FieldState, b: &Aabb) -> Interval {
        match (self, s) {
            (SiteField::Euclidean(e), _) => e.bound(b),
            (SiteField::Lp(f), _) => f.bound(b),
            (SiteField::Circle(c), _) => c.bound(b),
            (SiteField::Polynomial(_), FieldState::Bernstein(bf)) => bf.range(),
            (SiteField::Polynomial(f), _) => f.bernstein(b).range(),
            (SiteField::Implicit(f), FieldState::Implicit(st)) => f.bound(st),
            (SiteField::Implicit(f), _) => f.bound(&f.state(b)),
            (SiteField::Ellipse(f), FieldState::Implicit(st)) => f.bound(st),
            (SiteField::Ellipse(f), _) => f.bound(&f.state(b)),
            (SiteField::Algebraic(f), FieldState::Algebraic(st)) => f.bound(st, b),
            (SiteField::Algebraic(f), _) => f.bound(&f.state(b), b),
        }
    }

    fn gradient_bound(&self, s: &FieldState, b: &Aabb) -> Option<[Interval; 2]> {
        match (self, s) {
            (SiteField::Euclidean(e), _) => e.gradient_bound(b),
            (SiteField::Lp(f), _) => Some(f.gradient_bound(b)),
            (SiteField::Polynomial(_), FieldState::Bernstein(bf)) => {
                Some(polynomial::gradient_bound(bf, b))
            }
            (SiteField::Polynomial(f), _) => Some(polynomial::gradient_bound(&f.bernstein(b), b)),
            (SiteField::Circle(c), _) => Some(c.gradient_bound(b)),
            (SiteField::Implicit(f), FieldState::Implicit(st)) => f.gradient_bound(st, b),
            (SiteField::Implicit(f), _) => f.gradient_bound(&f.state(b), b),
            (SiteField::Ellipse(f), FieldState::Implicit(st)) => f.gradient_bound(st, b),
            (SiteField::Ellipse(f), _) => f.gradient_bound(&f.state(b), b),
            (SiteField::Algebraic(f), FieldState::Algebraic(st)) => f.gradient_bound(st, b),
            (SiteField::Algebraic(f), _) => f.gradient_bound(&f.state(b), b),
        }
    }

    fn value(&self, q: Point) -> f64 {
        match self {
            SiteField::Euclidean(e) => e.value(q),
            SiteField::Lp(f) => f.value(q),
            SiteField::Polynomial(f) => f.value(q),
            SiteField::Circle(c) => c.value(q),
            SiteField::Implicit(f) => f.value(q),
            SiteField::Ellipse(f) => f.value(q),
            SiteField::Algebraic(f) => f.value(q),
        }
    }

    fn gradient(&self, q: Point) -> Point {
        match self {
            SiteField::Euclidean(e) => e.gradient(q),
            SiteField::Lp(f) => f.gradient(q),
            SiteField::Polynomial(f) => f.gradient(q),
            SiteField::Circle(c) => c.gradient(q),
            SiteField::Implicit(f) => f.gradient(q),
            SiteField::Ellipse(f) => f.gradient(q),
            SiteField::Algebraic(f) => f.gradient(q),
        }
    }

    fn pair(&self, s: &FieldState, other: &SiteField, so: &FieldState, b: &Aabb) -> PairBound {
        match (self, other, s, so) {
            (SiteField::Euclidean(p), SiteField::Euclidean(q), _, _) => p.pair(q, b),
            (SiteField::Lp(p), SiteField::Lp(q), _, _) if p.p == q.p => p.pair(q, b),
            (SiteField::Circle(p), SiteField::Circle(q), _, _) => {
                circle::pair((p.center, p.radius), (q.center, q.radius), b)
            }
            (SiteField::Circle(p), SiteField::Euclidean(q), _, _) => {
                circle::pair((p.center, p.radius), (q.at, 0.0), b)
            }
            (SiteField::Euclidean(p), SiteField::Circle(q), _, _) => {
                circle::pair((p.at, 0.0), (q.center, q.radius), b)
            }
            (
                SiteField::Polynomial(_),
                SiteField::Polynomial(_),
                FieldState::Bernstein(fa),
                FieldState::Bernstein(fb),
            ) => polynomial::pair(fa, fb, b),
            _ => bound_difference(self, s, other, so, b),
        }
    }
}
