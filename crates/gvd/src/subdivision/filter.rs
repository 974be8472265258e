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

/// Keeps the sites that may be nearest somewhere in `b` (their order is kept).
pub fn lower_envelope<F: DistanceField>(
    fields: &[F],
    b: &Aabb,
    mut sites: Vec<(u32, F::State)>,
) -> Vec<(u32, F::State)> {
    if sites.len() <= 1 {
        return sites;
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
        let dominated: Vec<bool> = (0..sites.len())
            .map(|a| a != best && pair(fields, &sites, a, best, b).value.lo > 0.0)
            .collect();
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
    sites
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
pub fn certify<F: DistanceField>(fields: &[F], b: &Aabb, sites: &[(u32, F::State)]) -> Certificate {
    match sites.len() {
        2 => match monotone(&pair(fields, sites, 0, 1, b)) {
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
