//! What the insertion needs to know of the site it inserts: an open segment (and,
//! the same way, an open arc), with its two endpoints already in the diagram.

use super::geometry::{Arc, Bisector, Line};
use super::pieces::{arc_pieces, claimed_pieces, Pieces};
use crate::geom::Point;

pub(crate) trait NewSite {
    /// The point generators of its two ends.
    fn ends(&self) -> [u32; 2];
    /// Distance to the open site: `+∞` where the foot is not inside it (the endpoints
    /// are generators of their own).
    fn open_distance(&self, x: Point) -> f64;
    /// Whether `x`, at clearance `t` from its generators, is nearer to the open site.
    fn claims(&self, x: Point, t: f64) -> bool {
        self.open_distance(x) < t
    }
    /// The unit direction at end `k` pointing away from the site, along its tangent.
    fn away(&self, k: usize) -> Point;
    /// A signed function of `x` vanishing on the site's supporting curve.
    fn side(&self, x: Point) -> f64;
    /// The claimed and unclaimed intervals of a bisector piece (see `pieces.rs`).
    fn pieces(&self, bis: &Bisector, from: Point, to: Point) -> Pieces;
}

impl NewSite for Line {
    fn ends(&self) -> [u32; 2] {
        self.ends
    }
    fn open_distance(&self, x: Point) -> f64 {
        Line::open_distance(self, x)
    }
    fn claims(&self, x: Point, t: f64) -> bool {
        Line::claims(self, x, t)
    }
    fn away(&self, k: usize) -> Point {
        if k == 0 {
            self.d * -1.0
        } else {
            self.d
        }
    }
    fn side(&self, x: Point) -> f64 {
        self.coords(x).1
    }
    fn pieces(&self, bis: &Bisector, from: Point, to: Point) -> Pieces {
        claimed_pieces(bis, from, to, self)
    }
}

impl NewSite for Arc {
    fn ends(&self) -> [u32; 2] {
        self.ends
    }
    fn open_distance(&self, x: Point) -> f64 {
        Arc::open_distance(self, x)
    }
    fn claims(&self, x: Point, t: f64) -> bool {
        Arc::claims(self, x, t)
    }
    /// Backwards along the counter-clockwise tangent at the start, forwards at the end.
    fn away(&self, k: usize) -> Point {
        let a = self.a0 + if k == 0 { 0.0 } else { self.span };
        let tangent = Point::new(-a.sin(), a.cos());
        if k == 0 {
            tangent * -1.0
        } else {
            tangent
        }
    }
    fn side(&self, x: Point) -> f64 {
        x.dist(self.c) - self.r
    }
    fn pieces(&self, bis: &Bisector, from: Point, to: Point) -> Pieces {
        arc_pieces(bis, from, to, self)
    }
}
