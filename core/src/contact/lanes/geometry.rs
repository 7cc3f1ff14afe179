//! Contact geometry in lanes: unit normal (Q.30), overlap (block value) and lever lengths
//! (Q.25) from the centres' difference or the wall's normal and overlap (formats in
//! [`super`]).

use super::{LaneBatch, LENGTH_BITS, STATE};
use crate::num::lanes::{mul32, shr_round, Lanes, Mask, Soft, LANES};
use crate::{lanes, mask, sum3};

/// Fraction bits of the unit normal.
pub(super) const UNIT: i64 = 30;
/// Fraction bits of lever lengths and offsets.
pub(super) const LENGTH: i64 = 25;
/// Fraction bits of the squared distances (mm²) from which the overlap is taken.
const AREA: i64 = 43;
/// Low bits of a Q32.32 coordinate in the split square of [`square_q43`].
const LOW_BITS: i64 = 21;

/// What the geometry gives the law.
pub(super) struct Geometry {
    /// Unit normal from i towards j (or the wall), Q.30.
    pub n: [Lanes; 3],
    /// Overlap α, mm.
    pub alpha: Soft,
    /// Lever lengths Lᵢ = Rᵢ − α/2 and Lⱼ (0 for a wall), Q.25.
    pub len_i: Lanes,
    /// See `len_i`.
    pub len_j: Lanes,
    /// Whether the lane lies inside the envelope so far.
    pub ok: Mask,
}

/// x² of a Q32.32 raw x with |x| < 2^38, in Q.43 (mm²), exact to 2^-44: x = h·2^21 + l
/// with 0 ≤ l < 2^21, so x² = h²·2^42 + 2hl·2^21 + l², each product within 64 bits.
#[inline(always)]
fn square_q43(x: i64) -> i64 {
    let h = x >> LOW_BITS;
    let l = x & ((1 << LOW_BITS) - 1);
    // Q.64 → Q.43 divides by 2^21.
    (mul32(h, h) << LOW_BITS)
        .wrapping_add(mul32(h, l) << 1)
        .wrapping_add(shr_round(mul32(l, l), LOW_BITS))
}

/// The geometry of every lane of `b`.
#[inline(always)]
pub(super) fn geometry(b: &LaneBatch) -> Geometry {
    let reach_raw = 1i64 << (STATE + LENGTH_BITS);
    let rs: Lanes = lanes!(|l| b.r_i[l].wrapping_add(if b.wall[l] { 0 } else { b.r_j[l] }));
    let radii_in = mask!(|l| {
        (0 < b.r_i[l] && b.r_i[l] < reach_raw)
            && (b.wall[l] || (0 < b.r_j[l] && b.r_j[l] < reach_raw))
            && (b.d[0][l].unsigned_abs() | b.d[1][l].unsigned_abs() | b.d[2][l].unsigned_abs())
                < 2 * reach_raw as u64
    });
    // Spheres: (Rᵢ+Rⱼ)² − |d|², exact to 2^-43 mm².
    let d2: Lanes = lanes!(|l| sum3!(|k| square_q43(b.d[k][l])));
    let rs2: Lanes = lanes!(|l| square_q43(rs[l]));
    let gap: Lanes = lanes!(|l| rs2[l].wrapping_sub(d2[l]));
    let d2_soft = Soft::from_fixed(&d2, AREA);
    let inv_d = d2_soft.rsqrt();
    let dist = d2_soft.mul(&inv_d);
    let inv_sum = Soft::from_fixed(&rs, STATE).add(&dist).rsqrt();
    let alpha_spheres = Soft::from_fixed(&gap, AREA).mul(&inv_sum.mul(&inv_sum));
    // n̂ = d/|d| from d in Q.25 (below 2^31 for |d| < 2^6 mm).
    let mut n = [[0; LANES]; 3];
    let mut n_fits = [true; LANES];
    for (k, n_k) in n.iter_mut().enumerate() {
        let d25 = lanes!(|l| shr_round(b.d[k][l], STATE - LENGTH));
        let (v, fits) = inv_d.times_fixed(&d25, LENGTH, UNIT);
        for l in 0..LANES {
            n_k[l] = if b.wall[l] {
                shr_round(b.d[k][l], STATE - UNIT)
            } else {
                v[l]
            };
            n_fits[l] &= b.wall[l] || fits[l];
        }
    }
    let alpha = Soft::select(
        &b.wall,
        &Soft::from_fixed(&b.overlap, STATE),
        &alpha_spheres,
    );
    let (alpha25, alpha_fits) = alpha.to_fixed(LENGTH);
    let half = lanes!(|l| alpha25[l] >> 1);
    let len_i = lanes!(|l| shr_round(b.r_i[l], STATE - LENGTH).wrapping_sub(half[l]));
    let len_j = lanes!(|l| {
        if b.wall[l] {
            0
        } else {
            shr_round(b.r_j[l], STATE - LENGTH).wrapping_sub(half[l])
        }
    });
    let ok = mask!(|l| {
        // Spheres: touching, with centres at least (Rᵢ+Rⱼ)/2 apart (4·gap ≤ 3·(Rᵢ+Rⱼ)²).
        let spheres_in = gap[l] > 0 && gap[l] <= rs2[l] / 4 * 3 + rs2[l] % 4 * 3 / 4;
        radii_in[l]
            && n_fits[l]
            && alpha_fits[l]
            && (b.wall[l] || spheres_in)
            && alpha.m[l] > 0
            && len_i[l] > 0
            && len_j[l] >= 0
    });
    Geometry {
        n,
        alpha,
        len_i,
        len_j,
        ok,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_square_is_exact_to_its_last_place() {
        let mut x: u64 = 0x1234_5678_9ABC_DEF1;
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = (x >> 26) as i64 - (1 << 37); // |v| < 2^38
                                                  // v²/2^21 rounded; the split rounds only its last term, so it is off by at most 1.
            let exact = (v as i128 * v as i128 + (1 << 20)) >> 21;
            assert!((square_q43(v) as i128 - exact).abs() <= 1, "{v}");
        }
    }
}
