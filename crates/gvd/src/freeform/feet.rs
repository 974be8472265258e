//! The nearest points of free-form generators, for the clearances and the pruning of a
//! diagram ([`crate::clearance`]): a whole `bezier` or `bspline` site, one of its C1
//! pieces or one of its corners, by the certified foot-point search of [`nearest`].

use super::nearest::Features;
use super::pieces::pieces;
use crate::complex::{FeatureKind, Generator};
use crate::geom::Point;
use crate::scene::Scene;

/// Runs `work` with the foot lookup of `scene`'s free-form generators, built once: for a
/// generator and a point `q`, the generator's nearest point to `q` (`None` for a
/// generator that is not free-form).
pub(crate) fn with_feet<R>(
    scene: &Scene,
    work: impl FnOnce(&dyn Fn(&Generator, Point) -> Option<Point>) -> R,
) -> R {
    let pieces = pieces(scene);
    let features = Features::new(&pieces);
    let foot = |g: &Generator, q: Point| -> Option<Point> {
        let (site, feature, index) = match *g {
            Generator::Site(site) => (site, None, 0),
            Generator::Feature {
                site,
                feature,
                index,
            } => (site, Some(feature), index),
        };
        if feature == Some(FeatureKind::Corner) {
            let corner = pieces
                .corners
                .iter()
                .find(|c| c.site == site && c.index == index);
            return corner.map(|c| c.at);
        }
        let mut best: Option<(f64, Point)> = None;
        for (k, span) in pieces.spans.iter().enumerate() {
            let wanted = span.site == site && (feature.is_none() || span.piece == index);
            if !wanted || best.is_some_and(|b| features.farther(k, q, b.0)) {
                continue;
            }
            let (d, t) = features.span_distance(k, q);
            if best.is_none_or(|b| d < b.0) {
                best = Some((d, span.curve.eval(t)));
            }
        }
        best.map(|b| b.1)
    };
    work(&foot)
}
