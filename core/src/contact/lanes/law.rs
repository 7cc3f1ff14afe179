//! The law in lanes: contact velocity, Hertz and Mindlin forces with damping, the Coulomb
//! limit, torques and CDT rolling magnitudes (formats in [`super`]; the same law as
//! [`crate::contact::fused::evaluate`]).

use super::geometry::{geometry, LENGTH, UNIT};
use super::{
    LaneBatch, LaneLoads, DELTA_BITS, FORCE_BITS, LENGTH_BITS, MASS_BITS, SPEED_BITS, SPIN_BITS,
    STATE, TIMESTEP_BITS,
};
use crate::num::lanes::{any, bit_length, mul32, mul_sub_shr, shr_round, Lanes, Mask, Soft, LANES};
use crate::{lanes, mask, sum3, xyz};

/// Fraction bits of velocities.
const SPEED: i64 = 23;
/// Fraction bits of angular velocities.
const SPIN: i64 = 24;
/// Fraction bits of the history in products.
const HISTORY: i64 = 27;
/// Fraction bits of the time step.
const TIME: i64 = 34;
/// Vectors narrowed for a product keep their largest component below 2^NARROW.
const NARROW: i64 = 30;

/// The raw Q32.32 bound 2^bits.
#[inline(always)]
const fn bound(bits: i64) -> u64 {
    1 << (STATE + bits)
}

/// |x| | |y| | |z| of lane `l` (below 2^k iff every component is).
#[inline(always)]
fn magnitude(v: &[Lanes; 3], l: usize) -> u64 {
    v[0][l].unsigned_abs() | v[1][l].unsigned_abs() | v[2][l].unsigned_abs()
}

/// The right shift that brings every component of `v` (and `extra`) below 2^NARROW.
#[inline(always)]
fn narrowing(v: &[Lanes; 3], extra: &Lanes) -> Lanes {
    lanes!(|l| (bit_length((magnitude(v, l) | extra[l].unsigned_abs()) as i64) - NARROW).max(0))
}

/// `v` shifted right by `s` per lane, rounded.
#[inline(always)]
fn narrowed(v: &[Lanes; 3], s: &Lanes) -> [Lanes; 3] {
    xyz!(|k| lanes!(|l| shr_round(v[k][l], s[l])))
}

/// a × b of narrow vectors, each product shifted right by `s` (rounded).
#[inline(always)]
fn cross_shr(a: &[Lanes; 3], b: &[Lanes; 3], s: &Lanes) -> [Lanes; 3] {
    [
        lanes!(|l| mul_sub_shr(a[1][l], b[2][l], a[2][l], b[1][l], s[l])),
        lanes!(|l| mul_sub_shr(a[2][l], b[0][l], a[0][l], b[2][l], s[l])),
        lanes!(|l| mul_sub_shr(a[0][l], b[1][l], a[1][l], b[0][l], s[l])),
    ]
}

/// The rolling lever from a body's centre of mass to the contact point: |o ± n̂L| for a clump
/// sphere (Q.25 arm, squared in Q.48), L for a single one.
#[inline(always)]
fn lever(n: &[Lanes; 3], len: &Lanes, o: &[Lanes; 3], clump: &Mask, sign: i64) -> Soft {
    if !any(clump) {
        return Soft::from_fixed(len, LENGTH);
    }
    let arm: [Lanes; 3] = xyz!(|k| lanes!(|l| shr_round(
        o[k][l].wrapping_add(sign * shr_round(mul32(n[k][l], len[l]), UNIT)),
        1
    )));
    let arm2: Lanes = lanes!(|l| sum3!(|k| mul32(arm[k][l], arm[k][l])));
    Soft::select(
        clump,
        &Soft::from_fixed(&arm2, 2 * (LENGTH - 1)).sqrt(),
        &Soft::from_fixed(len, LENGTH),
    )
}

/// Evaluate the law on every lane of `b` with time step `dt` (raw Q32.32 ms).
#[inline(always)]
pub(super) fn evaluate(b: &LaneBatch, dt: i64) -> LaneLoads {
    let g = geometry(b);
    let n = g.n;
    let inputs_in = mask!(|l| {
        magnitude(&b.v, l) < bound(SPEED_BITS)
            && (magnitude(&b.spin_i, l) | magnitude(&b.spin_j, l)) < bound(SPIN_BITS)
            && magnitude(&b.delta, l) < bound(DELTA_BITS)
            && (magnitude(&b.offset_i, l) | magnitude(&b.offset_j, l)) < bound(LENGTH_BITS)
            && 0 < b.m_star[l]
            && (b.m_star[l] as u64) < bound(MASS_BITS)
            && 0 < b.r_star[l]
            && (b.r_star[l] as u64) < bound(LENGTH_BITS)
            && 0 < dt
            && (dt as u64) < bound(TIMESTEP_BITS)
    });

    // Contact velocity v − (Lᵢωᵢ + Lⱼωⱼ) × n̂ (Q.23), and its normal and tangential parts.
    let spin_part: [Lanes; 3] = xyz!(|k| {
        lanes!(|l| {
            let wi = shr_round(b.spin_i[k][l], STATE - SPIN);
            let wj = shr_round(b.spin_j[k][l], STATE - SPIN);
            shr_round(
                mul32(wi, g.len_i[l]).wrapping_add(mul32(wj, g.len_j[l])),
                SPIN + LENGTH - SPEED,
            )
        })
    });
    let spin_in = mask!(|l| magnitude(&spin_part, l) < 1 << (SPEED + SPEED_BITS));
    let to_unit = [UNIT; LANES];
    let turn = cross_shr(&spin_part, &n, &to_unit);
    let vc: [Lanes; 3] =
        xyz!(|k| lanes!(|l| shr_round(b.v[k][l], STATE - SPEED).wrapping_sub(turn[k][l])));
    let vn: Lanes = lanes!(|l| shr_round(sum3!(|k| mul32(vc[k][l], n[k][l])), UNIT));
    let vt: [Lanes; 3] =
        xyz!(|k| lanes!(|l| vc[k][l].wrapping_sub(shr_round(mul32(n[k][l], vn[l]), UNIT))));

    // a = √(R*α), √(a·m*).
    let a = Soft::from_fixed(&b.r_star, STATE).mul(&g.alpha).sqrt();
    let root_am = a.mul(&Soft::from_fixed(&b.m_star, STATE)).sqrt();

    // Normal force: Hertz (4/3)E*·a·α minus damping, clipped at zero (eqs. (3), (4)).
    let hertz = Soft::from_fixed(&b.kn, STATE).mul(&a.mul(&g.alpha));
    let damp_n = Soft::from_fixed(&b.cn, STATE)
        .mul(&root_am)
        .mul_fixed(&vn, SPEED);
    let f_n = hertz.sub(&damp_n);
    let f_n = Soft::select(&f_n.positive(), &f_n, &Soft::ZERO);

    // History projected on the tangent plane plus vt·dt (Q.32 kept, Q.27 in products).
    let d27: [Lanes; 3] = xyz!(|k| lanes!(|l| shr_round(b.delta[k][l], STATE - HISTORY)));
    let dn: Lanes = lanes!(|l| shr_round(sum3!(|k| mul32(d27[k][l], n[k][l])), UNIT));
    let dt34 = dt << (TIME - STATE);
    let to_state = UNIT + HISTORY - STATE;
    let mut d1: [Lanes; 3] = xyz!(|k| {
        lanes!(|l| {
            b.delta[k][l]
                .wrapping_sub(shr_round(mul32(n[k][l], dn[l]), to_state))
                .wrapping_add(shr_round(mul32(vt[k][l], dt34), SPEED + TIME - STATE))
        })
    });
    let history_in = mask!(|l| magnitude(&d1, l) < bound(DELTA_BITS));

    // Tangential force: −(St·δt + damping·vt), St = 8G*·a.
    let st = Soft::from_fixed(&b.kt, STATE).mul(&a);
    let damp_t = Soft::from_fixed(&b.ct, STATE).mul(&root_am);
    let d1_27: [Lanes; 3] = xyz!(|k| lanes!(|l| shr_round(d1[k][l], STATE - HISTORY)));
    let mut tangential_fits = [true; LANES];
    let mut f_t: [Lanes; 3] = [[0; LANES]; 3];
    for k in 0..3 {
        let (spring, s_fits) = st.times_fixed(&d1_27[k], HISTORY, STATE);
        let (damp, d_fits) = damp_t.times_fixed(&vt[k], SPEED, STATE);
        for l in 0..LANES {
            f_t[k][l] = spring[l].wrapping_add(damp[l]).wrapping_neg();
            tangential_fits[l] &= s_fits[l] & d_fits[l];
        }
    }
    let normal_in = f_n.below(FORCE_BITS);
    let forces_in =
        mask!(|l| normal_in[l] && magnitude(&f_t, l) < bound(FORCE_BITS) && tangential_fits[l]);

    // Coulomb limit |Ft| ≤ μs·Fn; when the spring alone exceeds it, the history is rescaled
    // so that St|δt| = μs·Fn.
    let limit = Soft::from_fixed(&b.mu, STATE).mul(&f_n);
    let (limit32, _) = limit.to_fixed(STATE);
    let s = narrowing(&f_t, &limit32);
    let ft_n = narrowed(&f_t, &s);
    let f2: Lanes = lanes!(|l| sum3!(|k| mul32(ft_n[k][l], ft_n[k][l])));
    let sliding = mask!(|l| {
        let lim = shr_round(limit32[l], s[l]);
        f2[l] > mul32(lim, lim)
    });
    if any(&sliding) {
        // |Ft| from f2 (in Q.(64 − 2s)), the ratio μs·Fn/|Ft| ≤ 1.
        let f2_soft = Soft::from_fixed(&f2, 0).mul_pow_lanes(&lanes!(|l| 2 * s[l] - 2 * STATE));
        let ratio = limit.mul(&f2_soft.rsqrt());
        let dd: Lanes = lanes!(|l| sum3!(|k| mul32(d1_27[k][l], d1_27[k][l])));
        let stretch2 = st.mul(&st).mul(&Soft::from_fixed(&dd, 2 * HISTORY));
        let overstretched = stretch2.greater(&limit.mul(&limit));
        let ratio_d = limit.mul(&stretch2.rsqrt());
        for k in 0..3 {
            let x_frac = lanes!(|l| STATE - s[l]);
            let (scaled, _) = ratio.times_fixed_lanes(&ft_n[k], &x_frac, STATE);
            let (scaled_d, _) = ratio_d.times_fixed(&d1_27[k], HISTORY, STATE);
            for l in 0..LANES {
                // Branch-free, so that the lanes stay in one vector.
                let free = limit.m[l] > 0;
                let capped = if free { scaled[l] } else { 0 };
                let rescaled = if overstretched[l] {
                    scaled_d[l]
                } else {
                    d1[k][l]
                };
                let history = if free { rescaled } else { 0 };
                f_t[k][l] = if sliding[l] { capped } else { f_t[k][l] };
                d1[k][l] = if sliding[l] { history } else { d1[k][l] };
            }
        }
    }

    // Loads: force on j, torques about each centre of mass, CDT rolling magnitudes (eq. (7)).
    let mut force = [[0; LANES]; 3];
    for k in 0..3 {
        let (along, _) = f_n.times_fixed(&n[k], UNIT, STATE);
        force[k] = lanes!(|l| along[l].wrapping_add(f_t[k][l]));
    }
    let s_t = narrowing(&f_t, &[0; LANES]);
    let ft_t = narrowed(&f_t, &s_t);
    // τ = n̂ × Ft in Q.(30 − s), below 2^31.
    let tau = cross_shr(&n, &ft_t, &[STATE; LANES]);
    let lever_shift = lanes!(|l| UNIT - s_t[l] + LENGTH - STATE);
    let mut torque_i: [Lanes; 3] =
        xyz!(|k| lanes!(|l| shr_round(mul32(tau[k][l], g.len_i[l]), lever_shift[l])));
    let mut torque_j: [Lanes; 3] = xyz!(|k| {
        lanes!(|l| shr_round(mul32(tau[k][l], g.len_j[l]), lever_shift[l]).wrapping_neg())
    });
    // o × F for clump spheres (zero for single spheres: skipped when the batch has none).
    let o_i: [Lanes; 3] = xyz!(|k| lanes!(|l| shr_round(b.offset_i[k][l], STATE - LENGTH)));
    let o_j: [Lanes; 3] = xyz!(|k| lanes!(|l| shr_round(b.offset_j[k][l], STATE - LENGTH)));
    let clumps = any(&b.clump_i) || any(&b.clump_j);
    if clumps {
        let s_f = narrowing(&force, &[0; LANES]);
        let f_narrow = narrowed(&force, &s_f);
        let offset_shift = lanes!(|l| LENGTH - s_f[l]);
        let t_i = cross_shr(&o_i, &f_narrow, &offset_shift);
        let t_j = cross_shr(&o_j, &f_narrow, &offset_shift);
        for k in 0..3 {
            for l in 0..LANES {
                torque_i[k][l] = torque_i[k][l].wrapping_add(t_i[k][l]);
                torque_j[k][l] = torque_j[k][l].wrapping_add(t_j[k][l]);
            }
        }
    }
    let t = Soft::from_fixed(&b.mu_r, STATE).mul(&f_n);
    let (roll_i, _) = t
        .mul(&lever(&n, &g.len_i, &o_i, &b.clump_i, 1))
        .to_fixed(STATE);
    let (roll_j, _) = t
        .mul(&lever(&n, &g.len_j, &o_j, &b.clump_j, -1))
        .to_fixed(STATE);

    let ok = mask!(|l| g.ok[l] && inputs_in[l] && spin_in[l] && history_in[l] && forces_in[l]);
    LaneLoads {
        ok,
        force,
        torque_i,
        torque_j,
        roll_i,
        roll_j,
        delta: d1,
    }
}
