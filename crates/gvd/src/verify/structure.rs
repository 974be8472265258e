//! Check d (structure): valid labels and references, edge ends at the vertices they
//! name, null ends on the domain boundary; and the parse of the diagram the other
//! checks read.

use super::report::fmt_g3;
use super::{finite, Checker, GoodEdge};

impl Checker<'_> {
    /// The structural parse: which edges and vertices can be checked at all.
    pub(super) fn parse(&mut self) {
        let d = self.diagram;
        for (k, v) in d.vertices.iter().enumerate() {
            let gens: Result<Vec<usize>, String> = if !finite(v.at) {
                Err("'at' is not finite".into())
            } else if v.sites.is_empty() {
                Err("'sites' is empty".into())
            } else {
                v.sites.iter().map(|g| self.label(g)).collect()
            };
            match gens {
                Ok(mut g) => {
                    g.sort_unstable();
                    let mut twice: Vec<(usize, usize)> = Vec::new();
                    for w in g.windows(2) {
                        if w[0] == w[1] && self.gens.curved[w[0]] && self.gens.featured {
                            match twice.last_mut() {
                                Some(last) if last.0 == w[0] => last.1 += 1,
                                _ => twice.push((w[0], 2)),
                            }
                        }
                    }
                    g.dedup();
                    self.vgens.push(Some(g));
                    self.vtwice.push(twice);
                }
                Err(m) => {
                    self.errors.push(format!("vertex {k}: {m}"));
                    self.vgens.push(None);
                    self.vtwice.push(Vec::new());
                }
            }
        }
        for (k, e) in d.edges.iter().enumerate() {
            let parsed = if e.points.len() < 2 || !e.points.iter().all(|&p| finite(p)) {
                Err("'points' must be at least two finite points".to_string())
            } else {
                match (self.label(&e.sites[0]), self.label(&e.sites[1])) {
                    (Ok(a), Ok(b)) if a == b && !(self.gens.featured && self.gens.curved[a]) => {
                        Err(format!(
                            "both generators are {} (an edge separates two different generators)",
                            self.name(a)
                        ))
                    }
                    (Ok(a), Ok(b)) => Ok((a, b)),
                    (Err(m), _) | (_, Err(m)) => Err(m),
                }
            };
            match parsed {
                Ok((a, b)) => self.edges.push(GoodEdge { index: k, a, b }),
                Err(m) => self.errors.push(format!("edge {k}: {m}")),
            }
        }
    }

    /// Check d: the edge ends (the labels were checked by `parse`).
    pub(super) fn structure(&mut self) {
        let d = self.diagram;
        let dom = self.scene.domain();
        let nv = d.vertices.len();
        let mut degree = vec![0usize; nv];
        let mut errors = Vec::new();
        let mut warnings = Vec::new();
        let mut edge_gens = vec![None; d.edges.len()];
        for g in &self.edges {
            edge_gens[g.index] = Some([g.a, g.b]);
        }
        for (k, e) in d.edges.iter().enumerate() {
            if e.points.is_empty() {
                continue;
            }
            let gens = edge_gens[k];
            let (first, last) = (e.points[0], e.points[e.points.len() - 1]);
            let is_loop = e.from.is_none()
                && e.to.is_none()
                && e.points.len() > 2
                && first.dist(last) <= self.tol;
            for (name, end, p) in [("from", e.from, first), ("to", e.to, last)] {
                match end {
                    Some(v) if v >= nv => errors.push(format!(
                        "edge {k}: '{name}' = {v} is not a vertex index or null"
                    )),
                    Some(v) => {
                        degree[v] += 1;
                        let dv = p.dist(d.vertices[v].at);
                        if dv > self.tol {
                            errors.push(format!(
                                "edge {k}: '{name}' end {} is {} ({} eps) from vertex {v} at {}",
                                self.at(p),
                                fmt_g3(dv * self.unit),
                                fmt_g3(dv / self.scene.epsilon()),
                                self.at(d.vertices[v].at)
                            ));
                        }
                        if let (Some(g), Some(vg)) = (gens, &self.vgens[v]) {
                            for s in g.iter().filter(|s| !vg.contains(s)) {
                                errors.push(format!(
                                    "edge {k}: vertex {v} ('{name}') does not list its generator {}",
                                    self.name(*s)
                                ));
                            }
                        }
                    }
                    None if is_loop => {}
                    None => {
                        let db = (p.x - dom.min.x)
                            .abs()
                            .min((p.x - dom.max.x).abs())
                            .min((p.y - dom.min.y).abs())
                            .min((p.y - dom.max.y).abs());
                        if db <= self.tol {
                            continue;
                        }
                        let on_site = self
                            .near
                            .at_unmasked(p)
                            .is_none_or(|h| self.fields[h.gen].distance_to_site(p) <= self.tol);
                        if on_site {
                            warnings.push(format!(
                                "edge {k}: null '{name}' end {} ends on a site, not on the domain boundary",
                                self.at(p)
                            ));
                        } else {
                            errors.push(format!(
                                "edge {k}: null '{name}' end {} is not on the domain boundary ({} away) and not a closed loop",
                                self.at(p),
                                fmt_g3(db * self.unit)
                            ));
                        }
                    }
                }
            }
        }
        let iso = degree.iter().filter(|&&g| g == 0).count();
        if iso > 0 {
            warnings.push(format!("{iso} vertices are not referenced by any edge"));
        }
        self.errors.extend(errors);
        self.warnings.extend(warnings);
    }
}
