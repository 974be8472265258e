//! Check b (vertices): each vertex near a point where its generators tie, found by
//! Gauss–Newton, and no other site nearer.

use super::field::{ridge_error, Field};
use super::report::{fmt_g3, MAX_LIST};
use super::{finite, Checker};
use crate::geom::Point;
use crate::par::map_range;

impl Checker<'_> {
    /// One Gauss–Newton step towards `d_i(v + s) = t` for all generators `i` (unknowns
    /// `s`, `t`): solves `(JᵀJ + δI) x = −Jᵀr` with rows `J_i = (∇d_i, −1)` and
    /// `r_i = d_i − mean d`. Returns the step and the values and gradients at `v`.
    /// The fields are divided by a power of two near their largest gradient first (the
    /// same step, as the tie does not change when every field is multiplied by one
    /// factor): `JᵀJ` would overflow with gradients beyond 1e154 (a Möbius scale of
    /// 1e300) and underflow with tiny ones.
    pub(super) fn gauss_newton_step(&self, v: Point, gens: &[usize]) -> (Point, Vec<(f64, Point)>) {
        let ev: Vec<(f64, Point)> = gens.iter().map(|&g| self.eval(g, v)).collect();
        let mean = ev.iter().map(|e| e.0).sum::<f64>() / ev.len() as f64;
        let largest = ev
            .iter()
            .fold(0.0f64, |m, e| m.max(e.1.x.abs()).max(e.1.y.abs()));
        let unit = if largest > 0.0 && largest.is_finite() {
            2f64.powi(-(largest.log2().round() as i32))
        } else {
            1.0
        };
        let mut m = [[0.0f64; 3]; 3];
        let mut rhs = [0.0f64; 3];
        for &(val, g) in &ev {
            let j = [g.x * unit, g.y * unit, -1.0];
            for r in 0..3 {
                for c in 0..3 {
                    m[r][c] += j[r] * j[c];
                }
                rhs[r] -= j[r] * ((val - mean) * unit);
            }
        }
        let reg = 1e-12 * (m[0][0] + m[1][1] + m[2][2]);
        for (r, row) in m.iter_mut().enumerate() {
            row[r] += reg;
        }
        let x = solve3(m, rhs).unwrap_or([0.0; 3]);
        let step = Point::new(x[0], x[1]);
        (if finite(step) { step } else { Point::default() }, ev)
    }

    /// The error of vertex `v` with generators `gens`, of which the curved features
    /// `twice` are listed more than once (as `(generator, times)`), and why.
    pub(super) fn vertex_error(
        &self,
        v: Point,
        gens: &[usize],
        twice: &[(usize, usize)],
    ) -> (f64, String) {
        let cap = 4.0 * self.scene.epsilon();
        let mut pos = v;
        for _ in 0..6 {
            let (s, _) = self.gauss_newton_step(pos, gens);
            pos = pos + s * (cap / s.norm().max(1e-300)).min(1.0);
        }
        let (s, _) = self.gauss_newton_step(pos, gens);
        pos = pos + s;
        let (_, ev) = self.gauss_newton_step(pos, gens);
        let vmax = ev.iter().map(|e| e.0).fold(f64::NEG_INFINITY, f64::max);
        let (vmin, gmin) = ev
            .iter()
            .copied()
            .fold((f64::INFINITY, Point::default()), |m, e| {
                if e.0 < m.0 {
                    e
                } else {
                    m
                }
            });
        let gmax = ev.iter().map(|e| e.1.norm_wide()).fold(0.0, f64::max);
        let spread = if (vmax - vmin).is_finite() {
            vmax - vmin
        } else {
            0.0
        };
        let mut e_tie = pos.dist(v) + spread / (2.0 * gmax).max(f64::MIN_POSITIVE);
        // a curved feature listed m times: m of its branches tie there (where only
        // one is left, the vertex ends the feature's ridge at a centre of curvature)
        for &(g, m) in twice {
            let branches = self.fields[g].branches(v, 2.0 * self.tol);
            // a whole algebraic curve stands for the engine's pieces, cut at its
            // vertices: a foot on a cut is listed by both pieces there, so m pieces have
            // m/2 to m distinct feet, and all those found must tie
            let m = if matches!(self.fields[g], Field::Curve(_)) {
                branches.len().min(m).max(m.div_ceil(2)).max(2)
            } else {
                m
            };
            e_tie = e_tie.max(ridge_error(v, &branches, m));
        }
        let (e_other, who) = self.intrusion(pos, vmin, gmin, gens);
        let e = e_tie.hypot(e_other);
        let out = self.scene.domain().outside_distance(v);
        let why = if out >= e {
            "outside the domain".to_string()
        } else if e_tie >= e_other {
            "its generators are not tied".to_string()
        } else if who == usize::MAX {
            "inside a closed site".to_string()
        } else {
            format!("generator {} is nearer", self.name(who))
        };
        (e.max(out), why)
    }

    /// Check b: returns ((good, total), pass).
    pub(super) fn vertices(&self, problems: &mut Vec<String>) -> ((usize, usize), bool) {
        let vs = &self.diagram.vertices;
        let errs = map_range(vs.len(), 1, |k| {
            self.vgens[k]
                .as_ref()
                .map(|g| self.vertex_error(vs[k].at, g, &self.vtwice[k]))
        });
        let mut bad: Vec<(usize, f64, &str)> = Vec::new();
        let mut ok = 0;
        for (k, e) in errs.iter().enumerate() {
            match e {
                Some((e, _)) if *e <= self.tol => ok += 1,
                Some((e, why)) => bad.push((k, *e, why)),
                None => {}
            }
        }
        bad.sort_by(|x, y| y.1.total_cmp(&x.1));
        for &(k, e, why) in bad.iter().take(MAX_LIST) {
            problems.push(format!(
                "vertices: vertex {k} (sites [{}]) at {}: error {} ({} eps): {why}",
                self.vgens[k]
                    .as_deref()
                    .unwrap_or(&[])
                    .iter()
                    .map(|&g| self.name(g))
                    .collect::<Vec<_>>()
                    .join(", "),
                self.at(vs[k].at),
                fmt_g3(e * self.unit),
                fmt_g3(e / self.scene.epsilon())
            ));
        }
        if bad.len() > MAX_LIST {
            problems.push(format!(
                "vertices: ... and {} more bad vertices",
                bad.len() - MAX_LIST
            ));
        }
        ((ok, vs.len()), ok == vs.len())
    }
}

/// Solves the 3 × 3 system `m x = b` by Gaussian elimination with partial pivoting.
pub(super) fn solve3(mut m: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    for c in 0..3 {
        let p = (c..3).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        if m[p][c] == 0.0 {
            return None;
        }
        m.swap(c, p);
        b.swap(c, p);
        let (pivot, rows) = m.split_at_mut(c + 1);
        let pivot = pivot[c];
        for (r, row) in rows.iter_mut().enumerate() {
            let f = row[c] / pivot[c];
            for (x, p) in row.iter_mut().zip(pivot).skip(c) {
                *x -= f * p;
            }
            b[c + 1 + r] -= f * b[c];
        }
    }
    let mut x = [0.0; 3];
    for r in (0..3).rev() {
        let s: f64 = (r + 1..3).map(|k| m[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / m[r][r];
    }
    Some(x)
}
