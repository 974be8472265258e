//! The subdivision phase (Emiris et al. 2013, Alg. 1): split the domain, keep in each box
//! only the sites that may reach the lower envelope there, and stop where at most three
//! sites remain and a certificate holds, or at the resolution cut-off.
//!
//! Boxes live on an integer lattice so that neighbouring boxes share exact coordinates:
//! the domain is a grid of `n[0] × n[1]` root cells (of side at most the maximum box
//! size, when one is asked for), each cell subdivided dyadically below that.

use super::budget::Budget;
use super::filter::{self, Certificate};
use crate::geom::{Aabb, Axis, Point};
use crate::site::DistanceField;

/// Bits of dyadic refinement available below a root cell.
const CELL_BITS: u32 = 40;

/// Maps integer lattice coordinates to the plane.
#[derive(Clone, Copy, Debug)]
pub struct Lattice {
    pub origin: Point,
    pub cell: [f64; 2],
    pub cells: [u64; 2],
}

impl Lattice {
    /// A lattice over `domain` whose root cells have sides at most `max_cell`
    /// (or one roughly square cell per unit of aspect ratio when `None`).
    pub fn new(domain: &Aabb, max_cell: Option<f64>) -> Self {
        let (w, h) = (domain.width(), domain.height());
        let count = |len: f64, other: f64| -> u64 {
            let n = match max_cell {
                Some(m) if m > 0.0 => (len / m * (1.0 - 1e-12)).ceil(),
                _ => (len / other).round(),
            };
            n.clamp(1.0, (1u64 << 20) as f64) as u64
        };
        let cells = [count(w, h), count(h, w)];
        Lattice {
            origin: domain.min,
            cell: [w / cells[0] as f64, h / cells[1] as f64],
            cells,
        }
    }

    /// The longest side of the smallest box the lattice can hold.
    pub fn smallest_box(&self) -> f64 {
        self.cell[0].max(self.cell[1]) / (1u64 << CELL_BITS) as f64
    }

    /// The plane coordinate along `axis` of lattice coordinate `v`.
    pub fn coord(&self, axis: usize, v: u64) -> f64 {
        let whole = (v >> CELL_BITS) as f64;
        let frac = (v & ((1u64 << CELL_BITS) - 1)) as f64 / (1u64 << CELL_BITS) as f64;
        let o = if axis == 0 {
            self.origin.x
        } else {
            self.origin.y
        };
        o + (whole + frac) * self.cell[axis]
    }

    /// The point at lattice coordinates `(x, y)`.
    pub fn point(&self, x: u64, y: u64) -> Point {
        Point::new(self.coord(0, x), self.coord(1, y))
    }

    /// The box of the whole domain in lattice coordinates.
    pub fn root(&self) -> IBox {
        IBox {
            lo: [0, 0],
            hi: [self.cells[0] << CELL_BITS, self.cells[1] << CELL_BITS],
        }
    }

    pub fn aabb(&self, ib: &IBox) -> Aabb {
        Aabb::new(
            self.point(ib.lo[0], ib.lo[1]),
            self.point(ib.hi[0], ib.hi[1]),
        )
    }
}

/// A box in lattice coordinates: `[lo[0], hi[0]] × [lo[1], hi[1]]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IBox {
    pub lo: [u64; 2],
    pub hi: [u64; 2],
}

impl IBox {
    /// Splits along `axis` at a root-cell line when the box spans several cells, else
    /// in halves; `None` when the lattice has no room left.
    fn split(&self, axis: usize) -> Option<(IBox, IBox, u64)> {
        let (a, b) = (self.lo[axis], self.hi[axis]);
        let (ca, cb) = (a >> CELL_BITS, b >> CELL_BITS);
        let mid = if cb - ca >= 2 && a & ((1 << CELL_BITS) - 1) == 0 {
            ((ca + cb) / 2) << CELL_BITS
        } else if b - a >= 2 {
            a + (b - a) / 2
        } else {
            return None;
        };
        let (mut l, mut r) = (*self, *self);
        l.hi[axis] = mid;
        r.lo[axis] = mid;
        Some((l, r, mid))
    }
}

/// A leaf of the subdivision: its box and the sites that survived the filter there.
#[derive(Clone, Debug)]
pub struct Leaf {
    pub ib: IBox,
    pub aabb: Aabb,
    pub sites: Vec<u32>,
    /// What the certificate proved when the box stopped (`None`: one site, or stopped at
    /// the resolution cut-off or the lattice's limit).
    pub certificate: Certificate,
}

/// Parameters of the subdivision phase.
#[derive(Clone, Copy)]
pub struct Params<'a> {
    /// Boxes holding two or more sites are split until their longest side is at most this.
    pub max_box: Option<f64>,
    /// The resolution cut-off: boxes this small are not split.
    pub min_box: f64,
    /// Process independent subtrees on rayon's thread pool (same result either way).
    pub parallel: bool,
    /// Each box visited takes one; once it is out no box is split again (the leaves are
    /// then incomplete, and the caller reports the exhausted budget, not a diagram).
    pub budget: &'a Budget,
}

/// The leaves of the subdivision, and the states of their sites where a leaf holds two
/// or more sites whose fields [restrict](DistanceField::restricts) (else empty).
pub struct Leaves<S> {
    pub leaves: Vec<Leaf>,
    pub states: Vec<Vec<S>>,
}

/// Runs Alg. 1 and returns the leaves in a deterministic order (depth-first, lower child
/// first), whatever the number of threads.
pub fn subdivide<F: DistanceField>(
    fields: &[F],
    lattice: &Lattice,
    params: &Params,
) -> Leaves<F::State> {
    let root = lattice.root();
    let aabb = lattice.aabb(&root);
    let sites: Vec<(u32, F::State)> = fields
        .iter()
        .enumerate()
        .map(|(i, f)| (i as u32, f.state(&aabb)))
        .collect();
    let mut out = Leaves {
        leaves: Vec::new(),
        states: Vec::new(),
    };
    recurse(fields, lattice, params, root, aabb, sites, &mut out);
    out
}

fn recurse<F: DistanceField>(
    fields: &[F],
    lattice: &Lattice,
    params: &Params,
    ib: IBox,
    aabb: Aabb,
    sites: Vec<(u32, F::State)>,
    out: &mut Leaves<F::State>,
) {
    if !params.budget.take_box() {
        return;
    }
    let envelope = filter::lower_envelope(fields, &aabb, sites);
    let size = aabb.longest_side();
    let mut leaf = |sites: Vec<(u32, F::State)>, certificate: Certificate| {
        out.leaves.push(Leaf {
            ib,
            aabb,
            sites: sites.iter().map(|s| s.0).collect(),
            certificate,
        });
        let keep = sites.len() >= 2 && sites.iter().any(|s| fields[s.0 as usize].restricts());
        out.states.push(if keep {
            sites.into_iter().map(|s| s.1).collect()
        } else {
            Vec::new()
        });
    };
    if envelope.sites.len() <= 1 {
        leaf(envelope.sites, Certificate::None);
        return;
    }
    let too_big = params.max_box.is_some_and(|m| size > m * (1.0 + 1e-9));
    if !too_big {
        let certificate = filter::certify(fields, &aabb, &envelope);
        if certificate != Certificate::None {
            leaf(envelope.sites, certificate);
            return;
        }
    }
    let sites = envelope.sites;
    let axis = if aabb.width() >= aabb.height() { 0 } else { 1 };
    let split = if size <= params.min_box && !too_big {
        None
    } else {
        ib.split(axis)
    };
    let Some((li, ri, mid)) = split else {
        leaf(sites, Certificate::None);
        return;
    };
    let at = lattice.point(mid, mid);
    let (ax, at) = if axis == 0 {
        (Axis::X, at.x)
    } else {
        (Axis::Y, at.y)
    };
    let (la, ra) = aabb.split(ax, at);
    let mut left = Vec::with_capacity(sites.len());
    let mut right = Vec::with_capacity(sites.len());
    for (i, s) in &sites {
        let (l, r) = fields[*i as usize].split(s, &aabb, ax, at);
        left.push((*i, l));
        right.push((*i, r));
    }
    drop(sites);
    let fork = params.parallel && (left.len() >= 16 || size > params.min_box * 64.0);
    #[cfg(not(feature = "parallel"))]
    let _ = fork; // one thread: the subtrees run in turn below
    #[cfg(feature = "parallel")]
    if fork {
        let mut rout = Leaves {
            leaves: Vec::new(),
            states: Vec::new(),
        };
        rayon::join(
            || recurse(fields, lattice, params, li, la, left, out),
            || recurse(fields, lattice, params, ri, ra, right, &mut rout),
        );
        out.leaves.append(&mut rout.leaves);
        out.states.append(&mut rout.states);
        return;
    }
    recurse(fields, lattice, params, li, la, left, out);
    recurse(fields, lattice, params, ri, ra, right, out);
}
