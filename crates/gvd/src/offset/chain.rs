//! Joining oriented pieces end to start into curves.

use super::{Curve, Primitive};
use crate::geom::Point;
use std::collections::{HashMap, VecDeque};

/// A kept piece of a level curve, oriented with its feature on the left.
pub(super) struct Piece {
    pub(super) primitive: Primitive,
    pub(super) start: Point,
    pub(super) end: Point,
}

/// Pieces' end points bucketed in square cells of side `tol`.
struct Buckets {
    tol: f64,
    map: HashMap<(i64, i64), Vec<usize>>,
}

impl Buckets {
    fn new(points: impl Iterator<Item = Point>, tol: f64) -> Buckets {
        let mut b = Buckets {
            tol,
            map: HashMap::new(),
        };
        for (k, p) in points.enumerate() {
            b.map.entry(b.key(p)).or_default().push(k);
        }
        b
    }

    fn key(&self, p: Point) -> (i64, i64) {
        (
            (p.x / self.tol).floor() as i64,
            (p.y / self.tol).floor() as i64,
        )
    }

    /// The unused piece whose bucketed point is nearest to `p`, within `tol`.
    fn nearest(&self, p: Point, at: impl Fn(usize) -> Point, used: &[bool]) -> Option<usize> {
        let (i, j) = self.key(p);
        let mut best: Option<(f64, usize)> = None;
        for di in -1..=1 {
            for dj in -1..=1 {
                let key = (i.saturating_add(di), j.saturating_add(dj));
                for &k in self.map.get(&key).into_iter().flatten() {
                    let d = at(k).dist(p);
                    if !used[k] && d <= self.tol && best.is_none_or(|(bd, _)| d < bd) {
                        best = Some((d, k));
                    }
                }
            }
        }
        best.map(|(_, k)| k)
    }
}

/// Chains pieces whose ends meet within `tol` (an end joins the nearest unused start)
/// into curves; a curve is closed when its last end meets its first start.
pub(super) fn chain(pieces: Vec<Piece>, tol: f64) -> Vec<Curve> {
    let starts = Buckets::new(pieces.iter().map(|p| p.start), tol);
    let ends = Buckets::new(pieces.iter().map(|p| p.end), tol);
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
            let next = starts.nearest(last.end, |k| pieces[k].start, &used);
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
            while let Some(k) = ends.nearest(pieces[run[0]].start, |k| pieces[k].end, &used) {
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
