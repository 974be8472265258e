//! Joining oriented pieces end to start into curves.

use super::{Curve, Primitive};
use crate::geom::grid::{bounds_of_points, BucketGrid};
use crate::geom::{Aabb, Point};
use std::collections::VecDeque;

/// A kept piece of a level curve, oriented with its feature on the left.
pub(super) struct Piece {
    pub(super) primitive: Primitive,
    pub(super) start: Point,
    pub(super) end: Point,
}

/// Pieces' end points bucketed in the shared grid, in cells at least `tol` wide.
struct Ends {
    points: Vec<Point>,
    tol: f64,
    grid: BucketGrid,
}

impl Ends {
    fn new(points: Vec<Point>, tol: f64) -> Ends {
        let extent = bounds_of_points(points.iter().copied());
        let fit = extent.longest_side() / (2.0 * points.len() as f64).sqrt();
        let grid = BucketGrid::new(extent, tol.max(fit), 4096, points.len(), |k| {
            Aabb::new(points[k], points[k])
        });
        Ends { points, tol, grid }
    }

    /// The unused piece whose end point is nearest to `p` within `tol` (the first
    /// piece among equals).
    fn nearest(&self, p: Point, used: &[bool]) -> Option<usize> {
        let reach = Point::new(self.tol, self.tol);
        let mut best: Option<(f64, usize)> = None;
        self.grid
            .for_each_in(&Aabb::new(p - reach, p + reach), |_, k| {
                let (d, k) = (self.points[k as usize].dist(p), k as usize);
                if !used[k] && d <= self.tol && best.is_none_or(|(bd, bk)| (d, k) < (bd, bk)) {
                    best = Some((d, k));
                }
            });
        best.map(|(_, k)| k)
    }
}

/// Chains pieces whose ends meet within `tol` (an end joins the nearest unused start)
/// into curves; a curve is closed when its last end meets its first start.
pub(super) fn chain(pieces: Vec<Piece>, tol: f64) -> Vec<Curve> {
    let starts = Ends::new(pieces.iter().map(|p| p.start).collect(), tol);
    let ends = Ends::new(pieces.iter().map(|p| p.end).collect(), tol);
    let mut used = vec![false; pieces.len()];
    let mut curves = Vec::new();
    for seed in 0..pieces.len() {
        if used[seed] {
            continue;
        }
        used[seed] = true;
        let mut run = VecDeque::from([seed]);
        let mut closed = false;
        loop {
            let (first, last) = (&pieces[run[0]], &pieces[run[run.len() - 1]]);
            let next = starts.nearest(last.end, &used);
            // close unless another piece starts nearer to the last end than the first
            let gap = last.end.dist(first.start);
            let may_close = gap <= tol && (run.len() > 1 || is_long_arc(&first.primitive));
            if may_close && next.is_none_or(|k| gap <= pieces[k].start.dist(last.end)) {
                closed = true;
                break;
            }
            let Some(k) = next else {
                break;
            };
            used[k] = true;
            run.push_back(k);
        }
        if !closed {
            while let Some(k) = ends.nearest(pieces[run[0]].start, &used) {
                used[k] = true;
                run.push_front(k);
            }
        }
        curves.push(Curve {
            closed,
            primitives: run.iter().map(|&k| pieces[k].primitive.clone()).collect(),
        });
    }
    curves
}

/// An arc of more than half a turn: a lone piece whose ends meet closes on itself.
fn is_long_arc(p: &Primitive) -> bool {
    match p {
        Primitive::Arc {
            start_angle,
            end_angle,
            ..
        } => (end_angle - start_angle).abs() > std::f64::consts::PI,
        Primitive::Line { .. } => false,
    }
}
