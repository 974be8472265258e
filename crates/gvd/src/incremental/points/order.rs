//! Insertion order: a biased randomized insertion order (BRIO, Amenta–Choi–Rote 2003)
//! whose rounds are sorted along a Hilbert curve.
//!
//! A site enters round `r` with probability `2^-(r+1)` (counted from the last round),
//! so each round is a random sample about twice the size of the one before it; the
//! expected total work stays O(n log n) as for a random order, while the walk from the
//! last inserted site to the next one is short because consecutive sites are
//! neighbours on the curve. Rounds alternate the curve's direction so that a round
//! starts near where the previous one ended.

use crate::geom::Point;

/// Bits per coordinate of the Hilbert grid.
const HILBERT_BITS: u32 = 22;
/// Number of BRIO rounds (the earliest ones hold ~n/2^ROUNDS sites).
const ROUNDS: u32 = 24;

/// SplitMix64: a fixed, well-mixed hash of the site index (the order is reproducible).
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The index of cell `(x, y)` along the Hilbert curve of the `2^HILBERT_BITS` grid.
fn hilbert(mut x: u32, mut y: u32) -> u64 {
    let mut d = 0u64;
    let mut s = 1u32 << (HILBERT_BITS - 1);
    while s > 0 {
        let rx = u32::from(x & s != 0);
        let ry = u32::from(y & s != 0);
        d += u64::from(s) * u64::from(s) * u64::from((3 * rx) ^ ry);
        if ry == 0 {
            if rx == 1 {
                let mask = (1u32 << HILBERT_BITS) - 1;
                x = !x & mask;
                y = !y & mask;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s >>= 1;
    }
    d
}

/// The BRIO order of `points` (finite coordinates), as indices into `points`.
pub(crate) fn brio(points: &[Point]) -> Vec<u32> {
    let (mut lo, mut hi) = (
        Point::new(f64::MAX, f64::MAX),
        Point::new(f64::MIN, f64::MIN),
    );
    for p in points {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let side = ((1u64 << HILBERT_BITS) - 1) as f64;
    let scale = |v: f64, l: f64, h: f64| -> u32 {
        if h > l {
            (((v - l) / (h - l)) * side).clamp(0.0, side) as u32
        } else {
            0
        }
    };
    let full = (1u64 << (2 * HILBERT_BITS)) - 1;
    let mut keys: Vec<(u64, u32)> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            // Round 0 is the smallest sample; the last round holds about half the sites.
            let round = ROUNDS - mix(i as u64).leading_zeros().min(ROUNDS);
            let h = hilbert(scale(p.x, lo.x, hi.x), scale(p.y, lo.y, hi.y));
            let h = if round % 2 == 1 { full - h } else { h };
            ((u64::from(round) << (2 * HILBERT_BITS)) | h, i as u32)
        })
        .collect();
    keys.sort_unstable();
    keys.into_iter().map(|(_, i)| i).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hilbert_is_a_bijection_on_a_small_grid_prefix() {
        // On the curve, consecutive indices are 4-neighbour cells: check the first 4096.
        let mut cells = vec![(0u32, 0u32); 4096];
        for x in 0..64 {
            for y in 0..64 {
                let d = hilbert(x, y);
                assert!(d < 4096, "({x}, {y}) -> {d}");
                cells[d as usize] = (x, y);
            }
        }
        for w in cells.windows(2) {
            let (a, b) = (w[0], w[1]);
            assert_eq!(a.0.abs_diff(b.0) + a.1.abs_diff(b.1), 1, "{a:?} {b:?}");
        }
    }

    #[test]
    fn brio_is_a_permutation() {
        let pts: Vec<Point> = (0..1000)
            .map(|i| Point::new((i * 7 % 31) as f64, (i % 17) as f64))
            .collect();
        let mut o = brio(&pts);
        o.sort_unstable();
        assert!(o.iter().enumerate().all(|(i, &j)| i as u32 == j));
    }
}
