//! Circular arcs: one model and one full-circle rule for every module.
//!
//! An arc runs counter-clockwise from `start_angle` to `end_angle` (radians). Its sweep
//! is `(end − start) mod 2π`; a sweep within [`FULL_TURN_TOLERANCE`] of 0 or of 2π is
//! the full circle (the rule of the format's reference checker; a start equal to the end
//! is refused when the scene is read).

use super::Point;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Sweeps within this many radians of a whole turn are the full circle.
pub const FULL_TURN_TOLERANCE: f64 = 1e-12;

/// The counter-clockwise angle from `start` to `end` in `(0, 2π)`, or `None` for the full
/// circle.
pub fn partial_sweep(start: f64, end: f64) -> Option<f64> {
    let sweep = (end - start).rem_euclid(TAU);
    (sweep > FULL_TURN_TOLERANCE && sweep < TAU - FULL_TURN_TOLERANCE).then_some(sweep)
}

/// The counter-clockwise angle from `start` to `end` in `(0, 2π]`: `2π` for the full
/// circle.
pub fn sweep(start: f64, end: f64) -> f64 {
    partial_sweep(start, end).unwrap_or(TAU)
}

/// Whether the ray from `q` towards +x crosses the counter-clockwise arc of the circle
/// `(center, radius)` from `ends[0]` (at angle `start`) through `sweep` to `ends[1]` an
/// odd number of times. The arc is cut into y-monotone pieces at its top and bottom;
/// a piece counts under the even-odd rule of `ring::even_odd_contains` (one end strictly
/// above `q`, the other not, its crossing right of `q`), so arcs and segments that share
/// ends count consistently. `ends` are the arc's end points as the caller's other
/// boundary pieces know them.
pub fn ray_crosses_odd(
    center: Point,
    radius: f64,
    start: f64,
    sweep: f64,
    ends: [Point; 2],
    q: Point,
) -> bool {
    let at = |a: f64| center + Point::new(a.cos(), a.sin()) * radius;
    // the angles of the top and bottom within the sweep, in order
    let first = ((start - FRAC_PI_2) / PI).floor() + 1.0;
    let mut cuts = vec![(start, ends[0])];
    let mut k = first;
    while FRAC_PI_2 + k * PI < start + sweep {
        let a = FRAC_PI_2 + k * PI;
        cuts.push((a, at(a)));
        k += 1.0;
    }
    cuts.push((start + sweep, ends[1]));
    let mut odd = false;
    for w in cuts.windows(2) {
        let ((a0, p0), (a1, p1)) = (w[0], w[1]);
        if (p0.y > q.y) != (p1.y > q.y) {
            let dy = q.y - center.y;
            let half = (radius * radius - dy * dy).max(0.0).sqrt();
            let x = center.x + half.copysign((0.5 * (a0 + a1)).cos());
            odd ^= q.x < x;
        }
    }
    odd
}

/// An arc of a circle: centre, radius, start angle and counter-clockwise sweep in
/// `(0, 2π]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    /// The circle's centre.
    pub center: Point,
    /// The circle's radius.
    pub radius: f64,
    /// The angle of the first end, in radians.
    pub start: f64,
    /// The counter-clockwise angle swept, in `(0, 2π]`.
    pub sweep: f64,
}

impl Arc {
    /// The arc from `start_angle` to `end_angle` (the format's fields).
    pub fn from_angles(center: Point, radius: f64, start_angle: f64, end_angle: f64) -> Arc {
        Arc {
            center,
            radius,
            start: start_angle,
            sweep: sweep(start_angle, end_angle),
        }
    }

    /// Whether the arc is the whole circle.
    pub fn is_full(&self) -> bool {
        self.sweep >= TAU
    }

    /// The point at angle `theta` on the arc's circle.
    pub fn at_angle(&self, theta: f64) -> Point {
        let (s, c) = theta.sin_cos();
        Point::new(
            self.center.x + self.radius * c,
            self.center.y + self.radius * s,
        )
    }

    /// The arc's two ends (equal for a full circle).
    pub fn ends(&self) -> [Point; 2] {
        [
            self.at_angle(self.start),
            self.at_angle(self.start + self.sweep),
        ]
    }

    /// Whether the direction `theta` from the centre falls within the closed arc.
    pub fn spans(&self, theta: f64) -> bool {
        self.is_full() || (theta - self.start).rem_euclid(TAU) <= self.sweep
    }

    /// The arc as rational quadratic Bézier spans of at most a quarter turn each, exact
    /// (Farin02, §13.5): a span of sweep `θ` has its ends on the circle, its middle
    /// control point where their tangents meet, at `r / cos(θ/2)` from the centre, with
    /// weight `cos(θ/2)`. The first and last ends are [`ends`](Self::ends), bit for bit.
    pub fn bezier_spans(&self) -> Vec<super::bezier::RationalBezier> {
        let count = (self.sweep / FRAC_PI_2).ceil().max(1.0);
        let step = self.sweep / count;
        let weight = (0.5 * step).cos();
        let [first, last] = self.ends();
        (0..count as usize)
            .map(|k| {
                let a = self.start + k as f64 * step;
                let from = if k == 0 { first } else { self.at_angle(a) };
                let to = if k + 1 == count as usize {
                    last
                } else {
                    self.at_angle(a + step)
                };
                let (s, c) = (a + 0.5 * step).sin_cos();
                let middle = self.center + Point::new(c, s) * (self.radius / weight);
                super::bezier::RationalBezier::new(&[from, middle, to], Some(&[1.0, weight, 1.0]))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::geom::ring::even_odd_contains;
    use proptest::prelude::*;

    proptest! {
        /// The ray test agrees with the even-odd rule on a fine polyline of the arc,
        /// closed by its chord, away from the arc and the chord.
        #[test]
        fn ray_test_matches_a_fine_polyline(start in -7.0..7.0f64, sweep in 0.01..6.2f64,
                                            qx in -2.0..2.0f64, qy in -2.0..2.0f64) {
            let (c, r) = (Point::new(0.1, -0.2), 1.3);
            let at = |a: f64| c + Point::new(a.cos(), a.sin()) * r;
            let n = 20_000;
            let ring: Vec<Point> = (0..=n).map(|k| at(start + sweep * k as f64 / n as f64)).collect();
            let q = Point::new(qx, qy);
            let chord = crate::geom::segment_distance(q, ring[0], ring[n]);
            prop_assume!((q.dist(c) - r).abs() > 1e-3 && chord > 1e-3);
            let ends = [ring[0], ring[n]];
            let chord_crosses = (ends[1].y > q.y) != (ends[0].y > q.y)
                && q.x < ends[1].x + (q.y - ends[1].y) * (ends[0].x - ends[1].x) / (ends[0].y - ends[1].y);
            let ours = ray_crosses_odd(c, r, start, sweep, ends, q) ^ chord_crosses;
            prop_assert_eq!(ours, even_odd_contains(&ring, q));
        }
    }
    use super::*;

    #[test]
    fn whole_turns_are_full_circles_and_nothing_else_is() {
        assert_eq!(partial_sweep(0.0, TAU), None);
        assert_eq!(partial_sweep(1.0, 1.0 + TAU), None);
        assert_eq!(partial_sweep(0.0, -TAU), None);
        assert_eq!(partial_sweep(0.0, 2.0 * TAU), None);
        assert_eq!(partial_sweep(0.0, 1e-13), None);
        assert_eq!(partial_sweep(0.0, TAU - 1e-13), None);
        // more than a turn but not a whole number of turns: the remainder
        let s = partial_sweep(0.0, 7.0).unwrap();
        assert!((s - (7.0 - TAU)).abs() < 1e-15);
        // clockwise input runs the other way round
        let s = partial_sweep(0.0, -1.0).unwrap();
        assert!((s - (TAU - 1.0)).abs() < 1e-15);
        assert_eq!(sweep(0.0, TAU), TAU);
        assert_eq!(sweep(0.0, 1.5), 1.5);
    }

    #[test]
    fn bezier_spans_lie_on_the_circle_and_share_the_arc_ends() {
        for (start, end) in [(0.3, 0.4), (0.0, 3.0), (-2.0, 4.0), (1.0, 1.0 + TAU)] {
            let a = Arc::from_angles(Point::new(0.5, -1.5), 2.0, start, end);
            let spans = a.bezier_spans();
            assert_eq!(spans.len(), (a.sweep / (TAU / 4.0)).ceil() as usize);
            for (k, s) in spans.iter().enumerate() {
                for i in 0..=16 {
                    let t = f64::from(i) / 16.0;
                    let p = s.eval(t);
                    assert!((p.dist(a.center) - a.radius).abs() < 1e-14, "{p:?}");
                    // the angle grows along the arc, within the span's share of the sweep
                    let turned = (p - a.center).y.atan2((p - a.center).x) - a.start;
                    let share = a.sweep / spans.len() as f64;
                    let along = (turned - k as f64 * share).rem_euclid(TAU);
                    assert!(along <= share + 1e-12 || along >= TAU - 1e-12, "{along}");
                }
            }
            let [p, q] = a.ends();
            assert_eq!(spans[0].eval(0.0), p);
            assert_eq!(spans.last().unwrap().eval(1.0), q);
        }
    }

    #[test]
    fn spans_wraps_through_zero() {
        let a = Arc::from_angles(Point::new(0.0, 0.0), 1.0, 3.0 * TAU / 4.0, TAU / 4.0);
        assert!((a.sweep - TAU / 2.0).abs() < 1e-15);
        assert!(a.spans(0.0));
        assert!(!a.spans(TAU / 2.0));
        let [p, q] = a.ends();
        assert!(p.dist(Point::new(0.0, -1.0)) < 1e-15);
        assert!(q.dist(Point::new(0.0, 1.0)) < 1e-15);
    }
}
