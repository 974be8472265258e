//! The lower-envelope filter (Emiris et al. 2013, §2.2) and the box certificates.
//!
//! Over a box `D`, `U_D = min_i max f_i(D)` bounds the lower envelope from above; a site
//! whose field is bounded below by more than `U_D` has no point of its cell in `D`. When
//! few sites remain, each pair is compared directly through a bound of `f_a − f_b`, which
//! is much tighter than the two separate bounds.

use crate::geom::Aabb;
use crate::num::Interval;
use crate::site::{DistanceField, PairBound};

/// Sites left after the first filter below which the pairwise test runs (it is
/// quadratic in their number).
const PAIRWISE_LIMIT: usize = 6;

/// The sites that may be nearest somewhere in a box, and, when two remain and the
/// filter compared them, its bound of `f_first − f_second` (to be reused by the
/// certificates rather than computed again).
pub struct Envelope<S> {
    pub sites: Vec<(u32, S)>,
    pub pair: Option<PairBound>,
}

impl<S> Envelope<S> {
    /// The bound of `f_first − f_second` of the two sites left: the filter's own, or
    /// computed now.
    pub fn pair_of_two<F: DistanceField<State = S>>(&self, fields: &[F], b: &Aabb) -> PairBound {
        self.pair
            .unwrap_or_else(|| pair(fields, &self.sites, 0, 1, b))
    }
}

/// Keeps the sites that may be nearest somewhere in `b` (their order is kept).
pub fn lower_envelope<F: DistanceField>(
    fields: &[F],
    b: &Aabb,
    mut sites: Vec<(u32, F::State)>,
) -> Envelope<F::State> {
    if sites.len() <= 1 {
        return Envelope { sites, pair: None };
    }
    let bounds: Vec<Interval> = sites
        .iter()
        .map(|(i, s)| fields[*i as usize].bound(s, b))
        .collect();
    let upper = bounds.iter().map(|r| r.hi).fold(f64::INFINITY, f64::min);
    let mut k = 0;
    sites.retain(|_| {
        k += 1;
        bounds[k - 1].lo <= upper
    });
    let mut kept_pair = None;
    if sites.len() > 1 && sites.len() <= PAIRWISE_LIMIT {
        // the site with the least upper bound dominates most others; test against it first
        let best = (0..sites.len())
            .min_by(|&a, &c| {
                let (ia, ic) = (sites[a].0 as usize, sites[c].0 as usize);
                let (ua, uc) = (
                    kept_upper(fields, &sites[a], b, ia),
                    kept_upper(fields, &sites[c], b, ic),
                );
                ua.total_cmp(&uc)
            })
            .unwrap_or(0);
        let against_best: Vec<Option<PairBound>> = (0..sites.len())
            .map(|a| (a != best).then(|| pair(fields, &sites, a, best, b)))
            .collect();
        let (ib, sb) = &sites[best];
        let dominated: Vec<bool> = against_best
            .iter()
            .zip(&sites)
            .map(|(p, (ia, sa))| {
                p.as_ref().is_some_and(|p| {
                    p.value.lo > 0.0
                        || fields[*ib as usize].occludes(sb, &fields[*ia as usize], sa, b)
                })
            })
            .collect();
        if dominated.iter().filter(|d| !**d).count() == 2 {
            // the two left are `best` and one other, compared above
            let other = (0..sites.len()).find(|&a| a != best && !dominated[a]);
            kept_pair = other.and_then(|a| {
                let p = against_best[a]?;
                // f_a − f_best, as f_first − f_second
                Some(if a < best { p } else { negated(p) })
            });
        }
        let mut k = 0;
        sites.retain(|_| {
            k += 1;
            !dominated[k - 1]
        });
        if sites.len() > 2 {
            let dominated: Vec<bool> = (0..sites.len())
                .map(|a| {
                    (0..sites.len()).any(|c| c != a && pair(fields, &sites, a, c, b).value.lo > 0.0)
                })
                .collect();
            let mut k = 0;
            sites.retain(|_| {
                k += 1;
                !dominated[k - 1]
            });
        }
    }
    Envelope {
        sites,
        pair: kept_pair,
    }
}

/// The bound of `−h` from that of `h` (exact: intervals negate without rounding).
fn negated(p: PairBound) -> PairBound {
    PairBound {
        value: -p.value,
        gradient: p.gradient.map(|g| [-g[0], -g[1]]),
    }
}

fn kept_upper<F: DistanceField>(fields: &[F], site: &(u32, F::State), b: &Aabb, i: usize) -> f64 {
    fields[i].bound(&site.1, b).hi
}

/// Bounds of `f_a − f_c` (or a sign-equivalent function) for sites at positions `a`, `c`.
pub fn pair<F: DistanceField>(
    fields: &[F],
    sites: &[(u32, F::State)],
    a: usize,
    c: usize,
    b: &Aabb,
) -> PairBound {
    let (ia, sa) = &sites[a];
    let (ic, sc) = &sites[c];
    fields[*ia as usize].pair(sa, &fields[*ic as usize], sc, b)
}

/// What a box's certificate proves about the diagram inside it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Certificate {
    None,
    /// Two sites whose bisector has a gradient component that never vanishes: the
    /// bisector is a graph over the other axis, crossing the box in simple arcs.
    Monotone {
        over_y: bool,
    },
    /// Three sites whose bisector system has a nonsingular interval Jacobian: at most
    /// one Voronoi vertex in the box.
    SingleVertex,
}

/// The monotonicity certificate of a pair bound: `∂h/∂x ≠ 0` makes the zero set a graph
/// `x = g(y)` (sorted by y), `∂h/∂y ≠ 0` a graph `y = g(x)`. When both hold, the axis
/// whose component is larger in magnitude wins, so that sorting along the other axis is
/// well conditioned (a bisector of slope 1e-16 is a graph over y, but a useless one).
pub fn monotone(p: &PairBound) -> Option<bool> {
    let g = p.gradient?;
    let least = |i: Interval| {
        if i.excludes_zero() {
            i.lo.abs().min(i.hi.abs())
        } else {
            0.0
        }
    };
    let (mx, my) = (least(g[0]), least(g[1]));
    if mx == 0.0 && my == 0.0 {
        None
    } else {
        Some(mx >= my)
    }
}

/// Tests the certificate for a box with two or three sites.
pub fn certify<F: DistanceField>(fields: &[F], b: &Aabb, env: &Envelope<F::State>) -> Certificate {
    let sites = &env.sites;
    match sites.len() {
        2 => match monotone(&env.pair_of_two(fields, b)) {
            Some(over_y) => Certificate::Monotone { over_y },
            None => Certificate::None,
        },
        3 => {
            let (Some(g1), Some(g2)) = (
                pair(fields, sites, 0, 1, b).gradient,
                pair(fields, sites, 0, 2, b).gradient,
            ) else {
                return Certificate::None;
            };
            let det = g1[0] * g2[1] - g1[1] * g2[0];
            if det.excludes_zero() {
                Certificate::SingleVertex
            } else {
                Certificate::None
            }
        }
        _ => Certificate::None,
    }
}
