//! Work limits of a subdivision run: the boxes it may visit and the polyline points it
//! may write. A run that reaches a limit stops early and reports it as
//! [`Error::Budget`], so that a scene finer than the limits allow (an epsilon near
//! f64's resolution, nearly degenerate sites) ends in seconds instead of exhausting the
//! memory. Counters are atomic: parallel subtrees draw on the same budget. The run's
//! [`Watch`] is ticked with every box and point taken, so a cancel flag or a time limit
//! stops the run as a spent budget does.

use crate::control::Watch;
use crate::error::Error;
use crate::geom::Aabb;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};

/// Boxes a run may visit by default, on top of [`BOXES_PER_SITE`] per site. The
/// corpus's subdivision runs visit at most a few tens per site.
pub const BASE_BOXES: usize = 1 << 21;
/// Boxes allowed per site on top of [`BASE_BOXES`].
pub const BOXES_PER_SITE: usize = 64;
/// Output polyline points a run may write by default, on top of [`POINTS_PER_SITE`] per
/// site (some 40 bytes each in JSON, about as many again in the cells: some 50 MB).
pub const BASE_POINTS: usize = 1 << 19;
/// Output points allowed per site on top of [`BASE_POINTS`].
pub const POINTS_PER_SITE: usize = 256;

/// The limits of one run; `None` fields take the defaults above for the scene's size.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Limits {
    /// Boxes the subdivision and the leaves' local splits may visit.
    pub max_boxes: Option<usize>,
    /// Points the traced bisector polylines may hold in all (subdivision engines; the
    /// curved edges of the incremental engine).
    pub max_points: Option<usize>,
}

/// What ran out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Exhausted {
    Boxes,
    Points,
}

/// The counters of one run against its limits.
pub struct Budget {
    max_boxes: usize,
    max_points: usize,
    boxes: AtomicUsize,
    points: AtomicUsize,
    out_of_boxes: AtomicBool,
    out_of_points: AtomicBool,
    watch: Watch,
}

impl Budget {
    /// The budget of a run over `sites` sites, stopped early by `watch`.
    pub fn new(limits: &Limits, sites: usize, watch: &Watch) -> Self {
        let boxes = BASE_BOXES.saturating_add(BOXES_PER_SITE.saturating_mul(sites));
        let points = BASE_POINTS.saturating_add(POINTS_PER_SITE.saturating_mul(sites));
        Budget {
            max_boxes: limits.max_boxes.unwrap_or(boxes),
            max_points: limits.max_points.unwrap_or(points),
            boxes: AtomicUsize::new(0),
            points: AtomicUsize::new(0),
            out_of_boxes: AtomicBool::new(false),
            out_of_points: AtomicBool::new(false),
            watch: watch.clone(),
        }
    }

    /// Refuses at once a maximum box size `max_box` that is not a finite length > 0, or
    /// that needs more boxes over `domain` than the budget holds.
    pub fn check_max_box(&self, max_box: f64, domain: &Aabb) -> Result<(), Error> {
        if !(max_box.is_finite() && max_box > 0.0) {
            return Err(Error::InvalidOption {
                option: "max_box".into(),
                message: format!("must be a finite length > 0, found {max_box}"),
            });
        }
        let boxes = (domain.width() / max_box).ceil() * (domain.height() / max_box).ceil();
        if boxes > self.max_boxes as f64 {
            return Err(Error::Budget {
                what: "boxes".into(),
                limit: self.max_boxes,
                message: format!(
                    "a maximum box size of {max_box:e} needs at least {boxes:.3e} boxes over the \
                     domain ({:e} × {:e}), more than the {} allowed; raise --max-box (or --max-boxes)",
                    domain.width(),
                    domain.height(),
                    self.max_boxes
                ),
            });
        }
        Ok(())
    }

    /// Takes one box; `false` once the boxes have run out.
    pub fn take_box(&self) -> bool {
        self.watch.tick(1) && Self::take(&self.boxes, self.max_boxes, &self.out_of_boxes)
    }

    /// Takes one output point; `false` once the points have run out.
    pub fn take_point(&self) -> bool {
        self.watch.tick(0) && Self::take(&self.points, self.max_points, &self.out_of_points)
    }

    /// Takes `n` output points at once (a polyline drawn whole); `false` once the
    /// points have run out.
    pub fn take_points(&self, n: usize) -> bool {
        if !self.watch.tick(0) || self.out_of_points.load(Relaxed) {
            return false;
        }
        if self.points.fetch_add(n, Relaxed).saturating_add(n) > self.max_points {
            self.out_of_points.store(true, Relaxed);
            return false;
        }
        true
    }

    /// The output points not yet taken.
    pub fn points_left(&self) -> usize {
        self.max_points.saturating_sub(self.points.load(Relaxed))
    }

    /// Marks the points as run out (a polyline needed more than [`points_left`](Self::points_left)).
    pub fn run_out_of_points(&self) {
        self.out_of_points.store(true, Relaxed);
    }

    /// The run's watch.
    pub fn watch(&self) -> &Watch {
        &self.watch
    }

    /// Whether either limit was reached or the run was stopped (its work is then
    /// incomplete).
    pub fn exhausted(&self) -> bool {
        self.which().is_some() || self.watch.stopped()
    }

    fn take(count: &AtomicUsize, max: usize, out: &AtomicBool) -> bool {
        if out.load(Relaxed) {
            return false;
        }
        if count.fetch_add(1, Relaxed) >= max {
            out.store(true, Relaxed);
            return false;
        }
        true
    }

    fn which(&self) -> Option<Exhausted> {
        if self.out_of_boxes.load(Relaxed) {
            Some(Exhausted::Boxes)
        } else if self.out_of_points.load(Relaxed) {
            Some(Exhausted::Points)
        } else {
            None
        }
    }

    /// `Ok` when no limit was reached and the run was not stopped, else the error
    /// telling which, at which epsilon.
    pub fn check(&self, epsilon: f64) -> Result<(), Error> {
        self.watch.check()?;
        match self.which() {
            None => Ok(()),
            Some(Exhausted::Boxes) => Err(Error::Budget {
                what: "boxes".into(),
                limit: self.max_boxes,
                message: format!(
                    "the subdivision needs more than {} boxes at epsilon {epsilon:e} \
                     (sites nearly coincide, or epsilon is too fine for the scene); \
                     raise --max-boxes (Options::limits) or epsilon",
                    self.max_boxes
                ),
            }),
            Some(Exhausted::Points) => Err(Error::Budget {
                what: "points".into(),
                limit: self.max_points,
                message: format!(
                    "the diagram needs more than {} polyline points at epsilon {epsilon:e}; \
                     raise --max-points (Options::limits) or epsilon",
                    self.max_points
                ),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_budget_runs_out_after_its_limit_and_says_which() {
        let limits = Limits {
            max_boxes: Some(3),
            max_points: Some(1),
        };
        let b = Budget::new(&limits, 10, &Watch::default());
        assert!((0..3).all(|_| b.take_box()));
        assert!(b.check(1e-3).is_ok());
        assert!(!b.take_box());
        assert!(b.take_point());
        let e = b.check(1e-3).unwrap_err().to_string();
        assert!(e.contains("more than 3 boxes at epsilon 1e-3"), "{e}");
        assert!(!b.take_point());
    }

    #[test]
    fn a_max_box_is_refused_when_absurd_or_beyond_the_budget() {
        let b = Budget::new(&Limits::default(), 2, &Watch::default());
        let domain = Aabb::from_array([-2.0, -2.0, 2.0, 2.0]);
        assert!(b.check_max_box(0.1, &domain).is_ok());
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = b.check_max_box(bad, &domain).unwrap_err().to_string();
            assert!(e.contains("finite length > 0"), "{e}");
        }
        let e = b.check_max_box(1e-6, &domain).unwrap_err().to_string();
        assert!(e.contains("1.600e13 boxes"), "{e}");
    }

    #[test]
    fn defaults_grow_with_the_sites() {
        let b = Budget::new(&Limits::default(), 1000, &Watch::default());
        assert_eq!(b.max_boxes, BASE_BOXES + 64_000);
        assert_eq!(b.max_points, BASE_POINTS + 256_000);
    }
}
