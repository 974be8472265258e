//! Check a (soundness): edge samples moved onto their generators' bisector, the
//! distance moved and any nearer site's excess within tolerance.

use super::field::{ridge_error, Branch, Field};
use super::report::{fmt_g3, MAX_LIST};
use super::Checker;
use crate::geom::Point;
use crate::par::map_range;
use std::collections::BTreeMap;

impl Checker<'_> {
    /// The error of edge sample `q0` of the bisector of `a` and `b`, and why.
    pub(super) fn sample_error(&self, q0: Point, a: usize, b: usize) -> (f64, &'static str) {
        let (e_tie, q, dmin, gmin) = if a == b {
            // two branches of one curved feature: its ridge, which ends at a centre of
            // curvature (an arc has a single branch, so only its centre qualifies)
            let branches = self.fields[a].branches(q0, 2.0 * self.tol);
            let mut e = ridge_error(q0, &branches, 2);
            if e > self.tol {
                if let Some(nearest) = branches.first() {
                    e = e.min(self.ridge_nearby(a, q0, nearest));
                }
            }
            let (va, ga) = branches
                .first()
                .map_or_else(|| self.eval(a, q0), |b| (b.value, b.gradient(q0)));
            (e, q0, va, ga)
        } else {
            self.project(q0, a, b)
        };
        let (e_other, _) = self.intrusion(q, dmin, gmin, &[a, b]);
        let mut e = e_tie.hypot(e_other);
        let mut why = if a == b && e_tie >= e_other {
            "no second branch of the generator nearby"
        } else if e_tie >= e_other {
            "not on the bisector of its generators"
        } else {
            "another generator is nearer"
        };
        let out = self.scene.domain().outside_distance(q0);
        if out > e {
            (e, why) = (out, "outside the domain");
        }
        if !self.in_region(q0) {
            let d = self
                .gens
                .region
                .as_ref()
                .map_or(f64::INFINITY, |r| r.boundary_distance(q0));
            if d > e {
                (e, why) = (d, "outside the medial-axis region");
            }
        }
        let inside = self.near.inside_depth(q0);
        if inside > e {
            (e, why) = (inside, "inside a closed site");
        }
        if self.gens.featured {
            // an edge/piece is an open feature: beyond its end (by more than the
            // tolerance) the nearest feature is the end corner, not the edge
            for g in [a, b] {
                let beyond = self.gens.beyond_end(g, q, self.tiny);
                if beyond > e {
                    (e, why) = (
                        beyond,
                        "the foot on an edge/piece generator is its end corner (label the corner)",
                    );
                }
            }
            // a corner and its own edge tie along a zone boundary, which is no Voronoi
            // edge (harmless right at the corner)
            if self.gens.zone_boundary(a, b) && self.fields[a].value(q0) > 2.0 * self.tol {
                return (
                    f64::INFINITY,
                    "zone boundary of a corner and its own edge (not a Voronoi edge)",
                );
            }
        }
        (e, why)
    }

    /// How far `q` is from the ridge of free-form feature `a` (where two branches of
    /// its distance tie), searched over the ridge points `C(t) + R(t)·n(t)` whose feet
    /// lie within `8·tol` along the curve of `q`'s nearest foot `C(t_f)` (steps of
    /// `tol / 2`), `R(t)` the radius of the largest empty disc touching there (see
    /// [`Parametric::ridge_point`]). Where the ridge's two branches merge (towards
    /// its end at a centre of curvature), points just off it see a single branch,
    /// whose tie the first-order estimate cannot measure; and near the end the normal
    /// through `q`'s own foot meets the ridge at a grazing angle.
    ///
    /// [`Parametric::ridge_point`]: super::parametric::Parametric::ridge_point
    fn ridge_nearby(&self, a: usize, q: Point, nearest: &Branch) -> f64 {
        let (Field::Pieces(pieces), Some((k, t_f))) = (&self.fields[a], nearest.param) else {
            return f64::INFINITY;
        };
        let piece = &pieces[k];
        let (t0, t1) = piece.range();
        let step = 0.5 * self.tol / piece.speed(t_f).max(1e-300);
        let side = piece.side_of(q, t_f);
        let d = nearest.value;
        let radii = (d - 4.0 * self.tol, d + 4.0 * self.tol);
        let rounding = 1e-12 * self.scale;
        (-16..=16)
            .map(|j| t_f + j as f64 * step)
            .filter(|t| (t0..=t1).contains(t))
            .filter_map(|t| piece.ridge_point(t, side, radii, rounding))
            .fold(f64::INFINITY, |best, m| best.min(m.dist(q)))
    }

    /// The spacing of check a's samples: ε/2, or the coarser spacing that keeps them
    /// within [`MAX_SAMPLES`] (with a warning saying so).
    pub(super) fn sample_spacing(&mut self) -> f64 {
        let fine = self.scene.epsilon() / 2.0;
        let (mut length, mut chords) = (0.0, 0usize);
        for ge in &self.edges {
            let pts = &self.diagram.edges[ge.index].points;
            length += pts.windows(2).map(|w| w[1].dist(w[0])).sum::<f64>();
            chords += pts.len();
        }
        let room = MAX_SAMPLES.saturating_sub(chords).max(MAX_SAMPLES / 2) as f64;
        if !length.is_finite() || length / fine <= room {
            return fine;
        }
        let spacing = length / room;
        self.warnings.push(format!(
            "soundness: the edges are sampled every {} ({} eps), not every eps/2: at eps/2 they would take {} samples",
            fmt_g3(spacing * self.unit),
            fmt_g3(spacing / self.scene.epsilon()),
            fmt_g3(length / fine)
        ));
        spacing
    }

    /// Check a: returns (fraction good, worst error, pass).
    pub(super) fn soundness(&self, spacing: f64, problems: &mut Vec<String>) -> (f64, f64, bool) {
        let mut samples: Vec<(Point, usize)> = Vec::new();
        for (g, ge) in self.edges.iter().enumerate() {
            let pts = &self.diagram.edges[ge.index].points;
            for w in pts.windows(2) {
                // At most 2^16 samples a chord: a length that overflows (coordinates
                // near f64's range) or a bogus diagram must not exhaust memory.
                let n = ((w[1].dist(w[0]) / spacing).ceil() as usize).clamp(1, 1 << 16);
                samples.extend((0..n).map(|j| (w[0].lerp(w[1], j as f64 / n as f64), g)));
            }
            samples.push((pts[pts.len() - 1], g));
        }
        let errs = map_range(samples.len(), 1, |i| {
            let (q, g) = samples[i];
            self.sample_error(q, self.edges[g].a, self.edges[g].b)
        });
        let good = errs.iter().filter(|e| e.0 <= self.tol).count();
        let worst = errs.iter().fold(0.0, |m: f64, e| m.max(e.0));
        // the worst sample of each bad edge
        let mut per_edge: BTreeMap<usize, (f64, usize, &str, usize)> = BTreeMap::new();
        for (i, &(e, why)) in errs.iter().enumerate() {
            if e > self.tol {
                let ent = per_edge.entry(samples[i].1).or_insert((e, i, why, 0));
                ent.3 += 1;
                if e > ent.0 {
                    (ent.0, ent.1, ent.2) = (e, i, why);
                }
            }
        }
        let mut bad: Vec<_> = per_edge.into_iter().collect();
        bad.sort_by(|x, y| y.1 .0.total_cmp(&x.1 .0));
        for &(g, (e, i, why, count)) in bad.iter().take(MAX_LIST) {
            let ge = &self.edges[g];
            problems.push(format!(
                "soundness: edge {} (sites {}, {}): {count} bad samples, worst {} ({} eps) at {}: {why}",
                ge.index,
                self.name(ge.a),
                self.name(ge.b),
                fmt_g3(e * self.unit),
                fmt_g3(e / self.scene.epsilon()),
                self.at(samples[i].0)
            ));
        }
        if bad.len() > MAX_LIST {
            problems.push(format!(
                "soundness: ... and {} more bad edges",
                bad.len() - MAX_LIST
            ));
        }
        let fraction = if samples.is_empty() {
            1.0
        } else {
            good as f64 / samples.len() as f64
        };
        let invalid = self.diagram.edges.len() - self.edges.len();
        (
            fraction,
            worst,
            fraction >= self.opts.min_sound && invalid == 0,
        )
    }
}

/// Most edge samples the soundness check takes (some 24 bytes each): edges longer than
/// this many times ε/2 are sampled more coarsely, with a warning.
pub(super) const MAX_SAMPLES: usize = 1 << 22;
