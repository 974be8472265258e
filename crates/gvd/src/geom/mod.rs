//! Plane geometry: points, axis-aligned boxes, and the shared geometric modules
//! (exact predicates, arcs, rings, rational Bézier and B-spline curves, bucket grids).

pub mod arc;
pub mod bezier;
pub mod bspline;
pub(crate) mod grid;
mod nearest;
pub mod predicates;
pub mod ring;

pub use nearest::PointGrid;
use serde::{Deserialize, Serialize};
use std::ops::{Add, Mul, Sub};

/// A point (or vector) in the plane.
#[derive(Clone, Copy, PartialEq, Debug, Default, Serialize, Deserialize)]
#[serde(from = "[f64; 2]", into = "[f64; 2]")]
pub struct Point {
    /// The x coordinate.
    pub x: f64,
    /// The y coordinate.
    pub y: f64,
}

impl From<[f64; 2]> for Point {
    fn from(a: [f64; 2]) -> Self {
        Point { x: a[0], y: a[1] }
    }
}

impl From<Point> for [f64; 2] {
    fn from(p: Point) -> Self {
        [p.x, p.y]
    }
}

impl Point {
    #[inline]
    /// The point `(x, y)`.
    pub const fn new(x: f64, y: f64) -> Self {
        Point { x, y }
    }
    #[inline]
    /// The dot product.
    pub fn dot(self, o: Point) -> f64 {
        self.x * o.x + self.y * o.y
    }
    /// The z-component of the cross product `self × o`.
    #[inline]
    pub fn cross(self, o: Point) -> f64 {
        self.x * o.y - self.y * o.x
    }
    /// `sqrt(x² + y²)` (not `hypot`: several times faster, exact enough far below 1e150).
    #[inline]
    pub fn norm(self) -> f64 {
        (self.x * self.x + self.y * self.y).sqrt()
    }
    /// `hypot(x, y)`: slower than [`Point::norm`], but right where `x²` overflows
    /// (beyond 1e154) or underflows, as the gradients of quadratic fields with large
    /// or small factors do.
    #[inline]
    pub fn norm_wide(self) -> f64 {
        self.x.hypot(self.y)
    }
    #[inline]
    /// The Euclidean distance to `o`.
    pub fn dist(self, o: Point) -> f64 {
        (self - o).norm()
    }
    /// The squared distance.
    #[inline]
    pub fn dist2(self, o: Point) -> f64 {
        let d = self - o;
        d.dot(d)
    }
    /// The vector rotated by +90°.
    #[inline]
    pub fn perp(self) -> Point {
        Point::new(-self.y, self.x)
    }
    #[inline]
    /// The point `self + t (o − self)`.
    pub fn lerp(self, o: Point, t: f64) -> Point {
        Point::new(self.x + (o.x - self.x) * t, self.y + (o.y - self.y) * t)
    }
    #[inline]
    /// The coordinate along `axis`.
    pub fn coord(self, axis: Axis) -> f64 {
        match axis {
            Axis::X => self.x,
            Axis::Y => self.y,
        }
    }
}

impl Add for Point {
    type Output = Point;
    #[inline]
    fn add(self, o: Point) -> Point {
        Point::new(self.x + o.x, self.y + o.y)
    }
}

impl Sub for Point {
    type Output = Point;
    #[inline]
    fn sub(self, o: Point) -> Point {
        Point::new(self.x - o.x, self.y - o.y)
    }
}

impl Mul<f64> for Point {
    type Output = Point;
    #[inline]
    fn mul(self, k: f64) -> Point {
        Point::new(self.x * k, self.y * k)
    }
}

/// The hulls of the connected groups of touching (closed) boxes; quadratic, for the few
/// boxes a certified search leaves unresolved.
pub fn clusters(boxes: Vec<Aabb>) -> Vec<Aabb> {
    let n = boxes.len();
    let mut sets = crate::disjoint_sets::DisjointSets::new(n);
    for i in 0..n {
        for j in i + 1..n {
            if boxes[i].intersection(&boxes[j]).is_some() {
                sets.union(i, j);
            }
        }
    }
    let mut hulls: Vec<(usize, Aabb)> = Vec::new();
    for (i, b) in boxes.iter().enumerate() {
        let r = sets.find(i);
        match hulls.iter_mut().find(|h| h.0 == r) {
            Some(h) => h.1 = h.1.union(b),
            None => hulls.push((r, *b)),
        }
    }
    hulls.into_iter().map(|h| h.1).collect()
}

/// The point of the closed segment `[a, b]` nearest to `q`: `a + t·(b − a)` with
/// `t = (q − a)·(b − a) / |b − a|²` clamped to `[0, 1]`, and the end itself, exactly,
/// where `t` is clamped (`a + 1·(b − a)` may miss `b` by an ulp: then two segments
/// sharing that end measured from two points an ulp apart). Past the middle, where `a`
/// lies more than `2^20` times farther out than `b` and `q`, it is measured from `b`
/// the same way: from the far end of a segment 1e15 long, the foot of a point beside
/// the near end would round to an ulp of 1e15.
pub fn segment_foot(q: Point, a: Point, b: Point) -> Point {
    let ab = b - a;
    let l2 = ab.dot(ab);
    let t = if l2 > 0.0 { (q - a).dot(ab) / l2 } else { 0.0 };
    let size = |p: Point| p.x.abs().max(p.y.abs());
    if t <= 0.0 {
        a
    } else if t >= 1.0 {
        b
    } else if t <= 0.5 || size(a) <= (1u64 << 20) as f64 * size(b).max(size(q)) {
        a.lerp(b, t)
    } else {
        let s = (q - b).dot(ab) / -l2;
        if s <= 0.0 {
            b
        } else {
            b.lerp(a, s)
        }
    }
}

/// The distance from `q` to the closed segment `[a, b]`.
pub fn segment_distance(q: Point, a: Point, b: Point) -> f64 {
    q.dist(segment_foot(q, a, b))
}

/// A coordinate axis.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Axis {
    /// The x axis.
    X,
    /// The y axis.
    Y,
}

/// A closed axis-aligned box `[min.x, max.x] × [min.y, max.y]`.
#[derive(Clone, Copy, PartialEq, Debug)]
pub struct Aabb {
    /// The lower-left corner.
    pub min: Point,
    /// The upper-right corner.
    pub max: Point,
}

impl Aabb {
    #[inline]
    /// The box between two corners (`min ≤ max` componentwise).
    pub const fn new(min: Point, max: Point) -> Self {
        Aabb { min, max }
    }
    /// From `[xmin, ymin, xmax, ymax]`.
    pub fn from_array(a: [f64; 4]) -> Self {
        Aabb::new(Point::new(a[0], a[1]), Point::new(a[2], a[3]))
    }
    /// `[xmin, ymin, xmax, ymax]`.
    pub fn to_array(self) -> [f64; 4] {
        [self.min.x, self.min.y, self.max.x, self.max.y]
    }
    #[inline]
    /// The extent along x.
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }
    #[inline]
    /// The extent along y.
    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }
    #[inline]
    /// The larger of width and height.
    pub fn longest_side(&self) -> f64 {
        self.width().max(self.height())
    }
    #[inline]
    /// The centre.
    pub fn center(&self) -> Point {
        self.min.lerp(self.max, 0.5)
    }
    #[inline]
    /// Whether `p` lies in the closed box.
    pub fn contains(&self, p: Point) -> bool {
        self.min.x <= p.x && p.x <= self.max.x && self.min.y <= p.y && p.y <= self.max.y
    }
    /// The point at relative coordinates `(u, v) ∈ [0,1]²`.
    #[inline]
    pub fn at(&self, u: f64, v: f64) -> Point {
        Point::new(
            self.min.x + u * (self.max.x - self.min.x),
            self.min.y + v * (self.max.y - self.min.y),
        )
    }
    /// Splits at coordinate `at` along `axis` into the lower and the upper part.
    pub fn split(&self, axis: Axis, at: f64) -> (Aabb, Aabb) {
        match axis {
            Axis::X => (
                Aabb::new(self.min, Point::new(at, self.max.y)),
                Aabb::new(Point::new(at, self.min.y), self.max),
            ),
            Axis::Y => (
                Aabb::new(self.min, Point::new(self.max.x, at)),
                Aabb::new(Point::new(self.min.x, at), self.max),
            ),
        }
    }
    /// The common part of two boxes, if they meet.
    pub fn intersection(&self, o: &Aabb) -> Option<Aabb> {
        let b = Aabb::new(
            Point::new(self.min.x.max(o.min.x), self.min.y.max(o.min.y)),
            Point::new(self.max.x.min(o.max.x), self.max.y.min(o.max.y)),
        );
        (b.min.x <= b.max.x && b.min.y <= b.max.y).then_some(b)
    }
    /// True when `o` lies in this box (closed).
    pub fn contains_box(&self, o: &Aabb) -> bool {
        self.contains(o.min) && self.contains(o.max)
    }
    /// The least box holding both.
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb::new(
            Point::new(self.min.x.min(o.min.x), self.min.y.min(o.min.y)),
            Point::new(self.max.x.max(o.max.x), self.max.y.max(o.max.y)),
        )
    }
    /// The four corners, counter-clockwise from `min`.
    pub fn corners(&self) -> [Point; 4] {
        [
            self.min,
            Point::new(self.max.x, self.min.y),
            self.max,
            Point::new(self.min.x, self.max.y),
        ]
    }
    /// `p` moved into the box (removes the rounding of a computed boundary point).
    #[inline]
    pub fn clamp(&self, p: Point) -> Point {
        Point::new(
            p.x.clamp(self.min.x, self.max.x),
            p.y.clamp(self.min.y, self.max.y),
        )
    }
    /// Liang–Barsky on a whole line: the range of `s` for which `m + s·dir` lies in the
    /// box, if any.
    pub fn line_range(&self, m: Point, dir: Point) -> Option<(f64, f64)> {
        let (mut s0, mut s1) = (f64::NEG_INFINITY, f64::INFINITY);
        for (den, num) in [
            (-dir.x, m.x - self.min.x),
            (dir.x, self.max.x - m.x),
            (-dir.y, m.y - self.min.y),
            (dir.y, self.max.y - m.y),
        ] {
            if den == 0.0 {
                if num < 0.0 {
                    return None;
                }
            } else if den < 0.0 {
                s0 = s0.max(num / den);
            } else {
                s1 = s1.min(num / den);
            }
        }
        (s0 <= s1).then_some((s0, s1))
    }

    /// The range of `t ∈ [0, 1]` for which `a + t (b − a)` lies in the box, if any.
    pub fn segment_range(&self, a: Point, b: Point) -> Option<(f64, f64)> {
        let (t0, t1) = self.line_range(a, b - a)?;
        let (t0, t1) = (t0.max(0.0), t1.min(1.0));
        (t0 <= t1).then_some((t0, t1))
    }

    /// The part of the segment `[a, b]` in the box, if any: its two ends, and whether
    /// each was cut (is not `a`, resp. `b`, itself). A cut point is measured from the
    /// segment's end nearer to it, so it carries the rounding of its distance from that
    /// end, not of the segment's length: a segment from a vertex 1e15 away cut at a unit
    /// box lands within ulps of 1, not of 1e15 (`a + t (b − a)` with `t` near 1 would
    /// round to multiples of 0.125 there).
    pub fn segment_part(&self, a: Point, b: Point) -> Option<([Point; 2], [bool; 2])> {
        let (t0, t1) = self.segment_range(a, b)?;
        // `[r0, r1]` of the reversed segment, `r = 1 − t`, for the cuts nearer to `b`
        let back = || self.segment_range(b, a);
        let start = if t0 == 0.0 {
            a
        } else if t0 <= 0.5 {
            a.lerp(b, t0)
        } else {
            back().map_or(a.lerp(b, t0), |(_, r1)| b.lerp(a, r1))
        };
        let end = if t1 == 1.0 {
            b
        } else if t1 >= 0.5 {
            back().map_or(a.lerp(b, t1), |(r0, _)| b.lerp(a, r0))
        } else {
            a.lerp(b, t1)
        };
        Some(([start, end], [t0 > 0.0, t1 < 1.0]))
    }

    /// The finest distance a computation in f64 resolves over the box: a thousand ulps
    /// of its largest coordinate (below that f64 cannot tell points apart).
    pub fn f64_resolution(&self) -> f64 {
        let magnitude = self.to_array().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        1024.0 * f64::EPSILON * magnitude
    }

    /// The distance from `p` to the box boundary when `p` lies outside, else 0.
    pub fn outside_distance(&self, p: Point) -> f64 {
        let dx = (self.min.x - p.x).max(p.x - self.max.x).max(0.0);
        let dy = (self.min.y - p.y).max(p.y - self.max.y).max(0.0);
        // `hypot` of a zero and `v` is `v`: the common case costs no `hypot`
        if dx == 0.0 {
            dy
        } else if dy == 0.0 {
            dx
        } else {
            dx.hypot(dy)
        }
    }

    /// The distance between the box and the segment `[a, b]` (0 where they meet): for
    /// disjoint convex sets it is attained at a vertex of one of them.
    pub fn segment_distance(&self, a: Point, b: Point) -> f64 {
        if self.segment_range(a, b).is_some() {
            return 0.0;
        }
        // one square root of the least square (squares overflow beyond 1e154: then
        // each distance on its own, without overflow)
        let outside2 = |p: Point| {
            let dx = (self.min.x - p.x).max(p.x - self.max.x).max(0.0);
            let dy = (self.min.y - p.y).max(p.y - self.max.y).max(0.0);
            dx * dx + dy * dy
        };
        let least = self
            .corners()
            .iter()
            .map(|&c| c.dist2(segment_foot(c, a, b)))
            .fold(outside2(a).min(outside2(b)), f64::min);
        if least.is_finite() {
            return least.sqrt();
        }
        self.corners()
            .iter()
            .map(|&c| segment_distance(c, a, b))
            .fold(
                self.outside_distance(a).min(self.outside_distance(b)),
                f64::min,
            )
    }
}
