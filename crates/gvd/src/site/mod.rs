//! Sites as distance fields. The subdivision engine sees only the [`DistanceField`]
//! trait; each site family lives in its own file and [`SiteField`] dispatches to it.

mod euclidean;
mod polynomial;

pub use euclidean::EuclideanPoint;
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
    Euclidean(EuclideanPoint),
    Polynomial(PolynomialField),
}

/// The per-box state of a [`SiteField`].
#[derive(Clone, Debug)]
pub enum FieldState {
    None,
    Bernstein(Box<Bernstein2>),
}

impl SiteField {
    /// The distance field of site `index` of a scene, or an error when no field of the
    /// subdivision engine can represent it yet.
    pub fn from_site(index: usize, kind: &SiteKind) -> Result<SiteField, Error> {
        match kind {
            SiteKind::Point { at, metric } => Ok(match metric {
                Metric::Euclidean => SiteField::Euclidean(EuclideanPoint::new(*at)),
                _ => SiteField::Polynomial(PolynomialField::from_metric(*at, metric)),
            }),
            SiteKind::Field { equation } => Ok(SiteField::Polynomial(PolynomialField::new(
                equation.poly.clone(),
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
        scene
            .sites
            .iter()
            .enumerate()
            .map(|(i, s)| SiteField::from_site(i, &s.kind))
            .collect()
    }
}

impl DistanceField for SiteField {
    type State = FieldState;

    fn state(&self, b: &Aabb) -> FieldState {
        match self {
            SiteField::Euclidean(_) => FieldState::None,
            SiteField::Polynomial(f) => FieldState::Bernstein(Box::new(f.bernstein(b))),
        }
    }

    fn split(&self, s: &FieldState, b: &Aabb, axis: Axis, at: f64) -> (FieldState, FieldState) {
        match (self, s) {
            (SiteField::Polynomial(f), FieldState::Bernstein(bf)) => {
                let (l, r) = f.split(bf, b, axis, at);
                (
                    FieldState::Bernstein(Box::new(l)),
                    FieldState::Bernstein(Box::new(r)),
                )
            }
            _ => (FieldState::None, FieldState::None),
        }
    }

    fn bound(&self, s: &FieldState, b: &Aabb) -> Interval {
        match (self, s) {
            (SiteField::Euclidean(e), _) => e.bound(b),
            (SiteField::Polynomial(_), FieldState::Bernstein(bf)) => bf.range(),
            (SiteField::Polynomial(f), FieldState::None) => f.bernstein(b).range(),
        }
    }

    fn gradient_bound(&self, s: &FieldState, b: &Aabb) -> Option<[Interval; 2]> {
        match (self, s) {
            (SiteField::Euclidean(e), _) => e.gradient_bound(b),
            (SiteField::Polynomial(_), FieldState::Bernstein(bf)) => {
                Some(polynomial::gradient_bound(bf, b))
            }
            (SiteField::Polynomial(f), FieldState::None) => {
                Some(polynomial::gradient_bound(&f.bernstein(b), b))
            }
        }
    }

    fn value(&self, q: Point) -> f64 {
        match self {
            SiteField::Euclidean(e) => e.value(q),
            SiteField::Polynomial(f) => f.value(q),
        }
    }

    fn gradient(&self, q: Point) -> Point {
        match self {
            SiteField::Euclidean(e) => e.gradient(q),
            SiteField::Polynomial(f) => f.gradient(q),
        }
    }

    fn pair(&self, s: &FieldState, other: &SiteField, so: &FieldState, b: &Aabb) -> PairBound {
        match (self, other, s, so) {
            (SiteField::Euclidean(p), SiteField::Euclidean(q), _, _) => p.pair(q, b),
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
