//! The offset data model (`SCENE_FORMAT.md`, "Offsets"): curves of lines and circular
//! arcs at one distance from the sites, as the algorithm in `offset/` returns them and
//! the writers in `io/` draw them.

use crate::geom::Point;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One primitive of an offset curve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Primitive {
    /// The segment from `from` to `to`.
    Line {
        /// The first end.
        from: Point,
        /// The last end.
        to: Point,
    },
    /// The arc of the circle `|x − center| = radius` from `start_angle` to `end_angle`
    /// (radians, `start_angle` in `[0, 2π)`, `|end_angle − start_angle| ≤ 2π`):
    /// counter-clockwise when `start_angle < end_angle`, clockwise (the inner side of an
    /// arc site) when `end_angle < start_angle`.
    Arc {
        /// The circle's centre.
        center: Point,
        /// The circle's radius.
        radius: f64,
        /// The angle of the first end (radians).
        start_angle: f64,
        /// The angle of the last end (below `start_angle` for a clockwise arc).
        end_angle: f64,
    },
}

impl Primitive {
    /// The point at relative position `t ∈ [0, 1]` along the primitive.
    pub fn point_at(&self, t: f64) -> Point {
        match *self {
            Primitive::Line { from, to } => from.lerp(to, t),
            Primitive::Arc {
                center,
                radius,
                start_angle,
                end_angle,
            } => {
                let a = start_angle + (end_angle - start_angle) * t;
                center + Point::new(a.cos(), a.sin()) * radius
            }
        }
    }

    /// The first point.
    pub fn start(&self) -> Point {
        self.point_at(0.0)
    }

    /// The last point.
    pub fn end(&self) -> Point {
        self.point_at(1.0)
    }
}

/// A connected offset curve: primitives end to start, oriented with the sites on the
/// left (counter-clockwise around a site, clockwise around a pocket's outer ring).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Curve {
    /// Whether the last primitive ends where the first starts (else both ends lie on
    /// the domain's boundary).
    pub closed: bool,
    /// The pieces, end to end.
    pub primitives: Vec<Primitive>,
}

impl Curve {
    /// The curve as points within `tolerance` of it (arcs as chords whose sagitta
    /// `r (1 − cos(θ/2))` stays below `tolerance`), from its start to its end; a closed
    /// curve repeats its first point last.
    pub fn polyline(&self, tolerance: f64) -> Vec<Point> {
        let mut out = Vec::new();
        for p in &self.primitives {
            match *p {
                Primitive::Line { from, .. } => out.push(from),
                Primitive::Arc {
                    radius,
                    start_angle,
                    end_angle,
                    ..
                } => {
                    let sweep = (end_angle - start_angle).abs();
                    let step = if tolerance > 0.0 && tolerance < radius {
                        2.0 * (1.0 - tolerance / radius).acos()
                    } else {
                        sweep
                    };
                    let n = (sweep / step.max(1e-6)).ceil().clamp(1.0, 65536.0) as usize;
                    out.extend((0..n).map(|k| p.point_at(k as f64 / n as f64)));
                }
            }
        }
        if let Some(last) = self.primitives.last() {
            out.push(last.end());
        }
        out
    }
}

/// The offset curves of a scene at one distance.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Offset {
    /// The offset distance.
    pub distance: f64,
    /// The offset curves.
    pub curves: Vec<Curve>,
    /// Figures of the run: `seconds`, `features`, `crossings`, `fallbacks`, ...
    #[serde(default)]
    pub stats: BTreeMap<String, serde_json::Value>,
}

impl Offset {
    /// Compact JSON (`SCENE_FORMAT.md`, "Offsets").
    pub fn to_json(&self) -> String {
        // serializing plain data to a string cannot fail
        serde_json::to_string(self).unwrap_or_default()
    }
}
