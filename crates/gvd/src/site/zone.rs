//! Zone boundaries at the smooth joints of a curve cut into pieces.
//!
//! Where two pieces of one curve meet with a common tangent at `p`, the points whose
//! nearest point on both pieces is `p` form the normal line `p + s·n`, out to the centre
//! of curvature on each side where a piece bends towards it (`s = ρ = 1/|κ|`: beyond,
//! `p` stops being a local nearest point of that piece; on a side both bend away from,
//! without end). The diagram of the pieces has an edge there that the curve's diagram
//! has not; beyond the centre of curvature of a vertex of the curve, the same normal
//! carries the ridge that ends there.

use crate::geom::Point;

/// The zone boundary at a smooth joint of two pieces (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct ZoneEnd {
    /// The joint.
    pub at: Point,
    /// A unit normal of the curve there.
    normal: Point,
    /// How far the boundary reaches along `normal` and along `−normal`.
    reach: [f64; 2],
}

impl ZoneEnd {
    /// The zone boundary at `at` with unit normal `normal`, reaching `reach[0]` along it
    /// and `reach[1]` against it (`∞` for no end).
    pub fn new(at: Point, normal: Point, reach: [f64; 2]) -> Self {
        ZoneEnd { at, normal, reach }
    }

    /// The zone boundary at the joint `at` of pieces with unit tangent `tangent` there
    /// and signed curvatures `curvatures` (positive: bending to the left of the
    /// tangent): on each side, it ends at the nearest centre of curvature there.
    pub fn from_curvatures(at: Point, tangent: Point, curvatures: &[f64]) -> Self {
        let mut reach = [f64::INFINITY; 2];
        for &k in curvatures {
            let side = usize::from(k < 0.0);
            if k != 0.0 && k.is_finite() {
                reach[side] = reach[side].min(1.0 / k.abs());
            }
        }
        ZoneEnd::new(at, tangent.perp(), reach)
    }

    /// Whether `q` lies within `slop` of this zone boundary.
    pub fn zone_holds(&self, q: Point, slop: f64) -> bool {
        let d = q - self.at;
        let along = d.dot(self.normal);
        d.cross(self.normal).abs() <= slop && along <= self.reach[0] && -along <= self.reach[1]
    }

    /// The centres of curvature where the boundary ends (where a ridge ends if the joint
    /// is a vertex of the curve).
    pub fn centres(&self) -> impl Iterator<Item = Point> + '_ {
        [(1.0, self.reach[0]), (-1.0, self.reach[1])]
            .into_iter()
            .filter(|(_, r)| r.is_finite())
            .map(|(s, r)| self.at + self.normal * (s * r))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zone_ends_at_the_nearest_centre_on_each_side() {
        // tangent +x at the origin: left is +y; curvatures 2 and 0.5 to the left, none
        // to the right
        let z =
            ZoneEnd::from_curvatures(Point::new(0.0, 0.0), Point::new(1.0, 0.0), &[2.0, 0.5, 0.0]);
        assert!(z.zone_holds(Point::new(0.0, 0.4), 1e-12));
        assert!(!z.zone_holds(Point::new(0.0, 0.6), 1e-12));
        assert!(z.zone_holds(Point::new(0.0, -100.0), 1e-12));
        assert!(!z.zone_holds(Point::new(0.1, 0.1), 1e-3));
        let c: Vec<Point> = z.centres().collect();
        assert_eq!(c, vec![Point::new(0.0, 0.5)]);
    }
}
