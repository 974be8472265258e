//! Trimming a bisector branch to its part on the Voronoi diagram: the orientation
//! constraint (HREK07 eqs. 8–13; for a corner, its bounding normals, §7.3), the
//! curvature constraint (eqs. 22–23) and the lower envelope of the distance functions
//! (§6). The envelope is evaluated as a minimum-distance test at the branch's samples
//! (the "minimum distance" procedure of §7.3, applied to every bisector): a sample is on
//! the envelope when no feature is nearer than its clearance. Where the status changes
//! between samples the change is located by bisection along the branch's monotone
//! parameter: a change to "another feature is nearer" is a Voronoi vertex (eqs. 24–26),
//! a change to "outside the domain" an end on the boundary.

use super::bisector::{centre_of_curvature, local_foot, side_and_curvature};
use super::nearest::Features;
#[cfg(doc)]
use super::pieces::Corner;
use super::pieces::Feature;
use crate::control::Watch;
use crate::geom::{segment_distance, Aabb, Point};

/// A point of a bisector branch: where it is, its clearance, and the foot parameters on
/// the two features (spans only).
#[derive(Clone, Copy, Debug)]
pub struct Eval {
    /// The bisector point.
    pub p: Point,
    /// Its distance to both features.
    pub d: f64,
    /// Foot parameters on the first and second feature (`None` for corners).
    pub feet: [Option<f64>; 2],
    /// The feet are held at the spans' ends on a joint (its normal): one-sided minima,
    /// which the curvature constraint does not bound; the lower envelope still tests
    /// whether other points of the spans are nearer.
    pub at_ends: bool,
}

/// What a sample is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Status {
    Valid,
    /// Outside the domain (or not finite).
    Out,
    /// Fails the orientation or curvature constraint, or could not be evaluated.
    Bad,
    /// Outside an active corner's normal cone: which of its two half-planes
    /// ([`super::pieces::Corner::halves`]) hold the point.
    Cone([bool; 2]),
    /// This feature is nearer: the point is not on the envelope.
    Nearer(Feature),
}

#[derive(Clone, Copy, Debug)]
struct Sample {
    s: f64,
    e: Option<Eval>,
    status: Status,
}

/// How a trimmed run ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum End {
    /// At a Voronoi vertex, where this third feature becomes nearer.
    Vertex(Feature),
    /// On the domain's boundary.
    Boundary,
    /// Where a constraint or the branch itself ends (joins another run).
    Open,
}

/// A trimmed piece of a bisector: a polyline within epsilon of it.
#[derive(Clone, Debug)]
pub struct Run {
    /// The two features.
    pub pair: [Feature; 2],
    /// The polyline.
    pub points: Vec<Point>,
    /// How the first and the last point end.
    pub ends: [End; 2],
    /// The foot parameters on the two features at the first and the last point
    /// (`None` on a corner).
    pub feet: [[Option<f64>; 2]; 2],
}

/// What the trimming of one branch needs.
pub struct Trimmer<'a> {
    /// Distance queries.
    pub features: &'a Features<'a>,
    /// The domain.
    pub domain: Aabb,
    /// The scene's size, the unit of the tolerances: the domain's, but no more than
    /// four times the curves' extent.
    pub size: f64,
    /// Chord tolerance of the polylines.
    pub chord: f64,
    /// Longest step between samples (so that short runs are not stepped over).
    pub step: f64,
    /// Tolerance of the distance comparisons.
    pub tol: f64,
    /// Constraints switched on (for tests that switch one off).
    pub constraints: Constraints,
    /// Samples evaluated so far (a budget).
    pub samples: std::cell::Cell<usize>,
    /// Most samples allowed.
    pub max_samples: usize,
    /// The run's watch: a cancelled or timed-out run samples no more.
    pub watch: Watch,
}

/// Which trimming constraints apply.
#[derive(Clone, Copy, Debug)]
pub struct Constraints {
    /// The orientation constraint.
    pub orientation: bool,
    /// The curvature constraint.
    pub curvature: bool,
    /// The lower envelope.
    pub envelope: bool,
}

impl Default for Constraints {
    fn default() -> Self {
        Constraints {
            orientation: true,
            curvature: true,
            envelope: true,
        }
    }
}

impl Trimmer<'_> {
    fn status(&self, pair: [Feature; 2], e: Option<Eval>) -> Status {
        let Some(e) = e else { return Status::Bad };
        let slack = 1e-9 * self.domain.longest_side();
        if !(e.p.x.is_finite() && e.p.y.is_finite()) || self.domain.outside_distance(e.p) > slack {
            return Status::Out;
        }
        let pieces = self.features.pieces;
        for (k, f) in pair.iter().enumerate() {
            match *f {
                Feature::Span(i) => {
                    let Some(t) = e.feet[k] else {
                        return Status::Bad;
                    };
                    let span = &pieces.spans[i];
                    let (side, curv) = side_and_curvature(&span.curve, t, e.p);
                    if self.constraints.orientation && !span.side.admits(side) {
                        return Status::Bad;
                    }
                    if self.constraints.curvature && !e.at_ends && curv > 1.0 + 1e-9 {
                        return Status::Bad;
                    }
                }
                Feature::Corner(i) => {
                    let c = &pieces.corners[i];
                    if self.constraints.orientation {
                        if !c.active {
                            return Status::Bad;
                        }
                        let halves = c.halves(e.p, self.tol);
                        if halves != [true, true] {
                            return Status::Cone(halves);
                        }
                    }
                }
            }
        }
        if self.constraints.envelope {
            if let Some((h, _)) = self.features.nearest_below(e.p, e.d - self.tol) {
                return Status::Nearer(h);
            }
        }
        Status::Valid
    }

    /// Whether the chord from `pa` to `pb` about the bisector point `e` keeps, at its
    /// quarter points, nearest points on both spans of `pair` near `e`'s feet, as the
    /// bisector's own points have. Near the end of a ridge the points with two feet are
    /// a cusp between two branches of the evolute, which narrows like `σ^{3/2}` with
    /// the distance `σ` from the end: a chord within the chord tolerance can leave it,
    /// and its points then have one foot. Within the chord tolerance of the centre of
    /// curvature at `e`'s feet (the ridge's end) this is not asked, nor of chords
    /// shorter than a hundredth of it (which bounds the halving where it cannot hold).
    fn two_feet(&self, pair: [Feature; 2], e: &Eval, pa: Point, pb: Point) -> bool {
        let ([Feature::Span(a), Feature::Span(b)], [Some(t), Some(r)], false) =
            (pair, e.feet, e.at_ends)
        else {
            return true;
        };
        let spans = &self.features.pieces.spans;
        let (ca, cb) = (&spans[a].curve, &spans[b].curve);
        let end = centre_of_curvature(ca, t);
        let apart = ca.eval(t).dist(cb.eval(r));
        [0.25, 0.5, 0.75].into_iter().all(|s| {
            let q = pa + (pb - pa) * s;
            if end.is_some_and(|c| c.dist(q) <= self.chord) {
                return true;
            }
            match (local_foot(ca, t, q), local_foot(cb, r, q)) {
                (Some(t), Some(r)) => ca.eval(t).dist(cb.eval(r)) > 0.5 * apart,
                _ => false,
            }
        })
    }

    fn sample(&self, pair: [Feature; 2], eval: &dyn Fn(f64) -> Option<Eval>, s: f64) -> Sample {
        self.samples.set(self.samples.get() + 1);
        let e = eval(s);
        Sample {
            s,
            e,
            status: self.status(pair, e),
        }
    }

    fn exhausted(&self) -> bool {
        self.samples.get() >= self.max_samples || !self.watch.tick(0)
    }

    /// Samples strictly between `a` and `b` (in order), refined until valid stretches
    /// are within the chord tolerance and status changes are located. `coarse` is the
    /// coarse step of the whole bisector: invalid stretches are searched for valid ones
    /// down to a fixed fraction of it (halvings below a coarse step, not below the
    /// range given, which may be a thin slab by a singular point).
    fn refine(
        &self,
        pair: [Feature; 2],
        eval: &dyn Fn(f64) -> Option<Eval>,
        a: Sample,
        b: Sample,
        coarse: f64,
        out: &mut Vec<Sample>,
    ) {
        // wider than `k` halvings of the coarse step
        let wider = |k: i32| b.s - a.s > 1.5 * coarse * 0.5f64.powi(k);
        if !wider(48) || self.exhausted() || b.s - a.s <= 1e-15 * (1.0 + a.s.abs()) {
            return;
        }
        let (pa, pb) = (a.e.map(|e| e.p), b.e.map(|e| e.p));
        let valid = |x: &Sample| x.status == Status::Valid;
        let split = match (valid(&a), valid(&b)) {
            (true, true) => {
                let (pa, pb) = (pa.unwrap(), pb.unwrap());
                if pa.dist(pb) > self.step {
                    true
                } else {
                    let m = self.sample(pair, eval, 0.5 * (a.s + b.s));
                    // far from the chord, or (a parameterization far from uniform in the
                    // plane, near a singular corner) splitting the chord unevenly
                    let len = pa.dist(pb);
                    let far = m.e.is_none_or(|e| {
                        let share = e.p.dist(pa) / len;
                        segment_distance(e.p, pa, pb) > self.chord
                            || (len > self.chord && !(0.2..=0.8).contains(&share))
                            || (len > 1e-2 * self.chord && !self.two_feet(pair, &e, pa, pb))
                    });
                    if far || m.status != Status::Valid {
                        self.refine(pair, eval, a, m, coarse, out);
                        out.push(m);
                        self.refine(pair, eval, m, b, coarse, out);
                    }
                    return;
                }
            }
            (true, false) | (false, true) => {
                // locate the change to full precision, keeping a sample on each side
                let d = match (pa, pb) {
                    (Some(x), Some(y)) => x.dist(y),
                    _ => f64::INFINITY,
                };
                d > 1e-12 * self.size
            }
            (false, false) => {
                // a valid stretch may hide between two invalid samples: look when the
                // samples are inside and far apart, or straddle the domain, or leave a
                // corner's cone on its two sides (a thin cone, as of a slight corner,
                // lies between them), or, where whole sites are the generators, two
                // other sites are nearer on its two sides (a short edge between two
                // vertices, where the nearest third site changes; in the other modes
                // neighbouring pieces of one outline alternate so along most branches,
                // and are not searched between)
                match (pa, pb) {
                    (Some(x), Some(y))
                        if matches!((a.status, b.status),
                            (Status::Cone(u), Status::Cone(v)) if u != v) =>
                    {
                        x.dist(y) > 1e-12 * self.size && wider(48)
                    }
                    (Some(x), Some(y))
                        if matches!((a.status, b.status),
                            (Status::Nearer(u), Status::Nearer(v))
                                if !self.features.pieces.featured
                                    && self.features.pieces.site(u) != self.features.pieces.site(v)) =>
                    {
                        x.dist(y) > 1e-12 * self.size && wider(12)
                    }
                    (Some(x), Some(y)) => {
                        let near = |p: Point| self.domain.outside_distance(p) < self.step;
                        (near(x) || near(y)) && x.dist(y) > self.step && wider(24)
                    }
                    _ => wider(12),
                }
            }
        };
        if split {
            let m = self.sample(pair, eval, 0.5 * (a.s + b.s));
            self.refine(pair, eval, a, m, coarse, out);
            out.push(m);
            self.refine(pair, eval, m, b, coarse, out);
        }
    }

    /// The runs of the branch `s ↦ eval(s)`, `s ∈ [s0, s1]`, on the Voronoi diagram,
    /// from `initial` coarse samples; `whole` is the parameter length of the whole
    /// bisector the range is part of (`s1 − s0`, or `1` for a slab of a span's `t`).
    pub fn trim(
        &self,
        pair: [Feature; 2],
        eval: &dyn Fn(f64) -> Option<Eval>,
        (s0, s1): (f64, f64),
        initial: usize,
        whole: f64,
    ) -> Vec<Run> {
        let n = initial.max(2);
        let coarse_step = whole / n as f64;
        let coarse: Vec<Sample> = (0..=n)
            .map(|k| {
                let s = if k == n {
                    s1
                } else {
                    s0 + (s1 - s0) * k as f64 / n as f64
                };
                self.sample(pair, eval, s)
            })
            .collect();
        let mut all = vec![coarse[0]];
        for w in coarse.windows(2) {
            self.refine(pair, eval, w[0], w[1], coarse_step, &mut all);
            all.push(w[1]);
        }
        let mut runs = Vec::new();
        let mut k = 0;
        while k < all.len() {
            if all[k].status != Status::Valid {
                k += 1;
                continue;
            }
            let start = k;
            while k < all.len() && all[k].status == Status::Valid {
                k += 1;
            }
            let end_of = |neighbour: Option<&Sample>| match neighbour.map(|s| s.status) {
                None | Some(Status::Valid) | Some(Status::Bad) | Some(Status::Cone(_)) => End::Open,
                Some(Status::Out) => End::Boundary,
                Some(Status::Nearer(h)) => End::Vertex(h),
            };
            let before = if start > 0 { all.get(start - 1) } else { None };
            let ends = [end_of(before), end_of(all.get(k))];
            let evals: Vec<Eval> = all[start..k].iter().filter_map(|s| s.e).collect();
            if evals.len() < 2 {
                continue;
            }
            let mut points: Vec<Point> = evals.iter().map(|e| e.p).collect();
            for (i, end) in ends.iter().enumerate() {
                if *end == End::Boundary {
                    let j = if i == 0 { 0 } else { points.len() - 1 };
                    points[j] = self.domain.clamp(points[j]);
                }
            }
            let feet = [evals[0].feet, evals[evals.len() - 1].feet];
            runs.push(Run {
                pair,
                points,
                ends,
                feet,
            });
        }
        runs
    }
}
