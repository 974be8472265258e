//! Check a (soundness): edge samples moved onto their generators' bisector, the
//! distance moved and any nearer site's excess within tolerance.

use super::report::{fmt_g3, MAX_LIST};
use super::Checker;
use crate::geom::Point;
use crate::par::map_range;
use std::collections::BTreeMap;

impl Checker<'_> {
    /// The error of edge sample `q0` of the bisector of `a` and `b`, and why.
    pub(super) fn sample_error(&self, q0: Point, a: usize, b: usize) -> (f64, &'static str) {
        let (e_tie, q, dmin, gmin) = if a == b {
            // two branches of one curve (an arc piece): an arc has a single branch
            // wherever its distance is differentiable, so the edge can only be its
            // centre, where a ridge ends
            let (va, ga) = self.eval(a, q0);
            let e = self.fields[a]
                .curvature_center()
                .map_or(f64::INFINITY, |c| c.dist(q0));
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
