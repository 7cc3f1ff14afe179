//! The fused base law for Q32.32 fixed point with **narrow products** (issue 16): the law of
//! [`super::fixed`] for a pair without JKR cohesion, in which every product whose operands
//! have a bounded range is a 64-bit product of narrowed operands instead of a 128-bit one.
//!
//! The Q32.32 kernel forms about 55 products per contact, each a 64 × 64 → 128-bit multiply,
//! a rounding add with carry and a double shift, and each ties up two registers, so the
//! kernel spills. Here the contact's motion (velocities, spins, levers, history) is narrowed
//! once into formats whose products fit an `i64`, and the loads are computed in a scale of
//! the contact's own: its normal and tangential forces are shifted right by the same k bits
//! ([`force_shift`]) so that they hold at most [`FORCE_LANE_BITS`] bits. About a dozen
//! products of the stiffness chain stay 128-bit, where a stiffness of any size meets an
//! overlap or a history.
//!
//! ## Formats and error budget
//! Inputs and outputs are raw Q32.32 (internal units: mm, g, ms, N), inside the envelope of
//! [`super::fixed`] (the same bounds; a contact outside returns `None`).
//!
//! | quantity | bound | format | resolution |
//! |---|---|---|---|
//! | centre distance, overlap α, levers Lᵢ, Lⱼ | < 2^5 mm | Q.32 (exact, as [`super::fixed`]) | 2.3e-10 mm |
//! | levers and clump offsets in products | < 2^5 mm | Q.26 | 1.5e-8 mm |
//! | unit normal n̂ | 1 | Q.30 | 9.3e-10 |
//! | ωᵢ, ωⱼ | < 2^6 rad/ms | Q.24 | 6e-8 rad/ms |
//! | centre velocity difference, contact velocity, vn, vt | < 2^5, < 2^6.3 mm/ms | Q.24 | 6e-8 m/s |
//! | history δt in its projection | < 2^3 mm | Q.27 | 7.5e-9 mm |
//! | history δt, kept and in the spring | < 2^3 mm | Q.32 | 2.3e-10 mm |
//! | time step | < 2^-3 ms | Q.34 | 5.8e-11 ms |
//! | a, √(a·m*), Fn, St·δt, damping | as [`super::fixed`] | Q.32, 128-bit products | 2.3e-10 |
//! | μs, μr | < 4 | Q.30 | 9.3e-10 |
//! | Fn, Ft in the loads | < 2^13 N | Q.(32 − k), below 2^29 | 2^-29 of the larger |
//!
//! What the formats cost against the Q32.32 kernel:
//! - a contact velocity off by up to 2^-25 mm/ms moves the damping forces by their
//!   coefficient times that (about 1e-9 N on a settled pod, whose weight is 2.2e-2 N) and
//!   the history by vt's error times dt (2^-25 mm/ms × 0.02 ms ≈ 6e-10 mm a step);
//! - the history's projection on the normal is off by up to about 2^-27 mm, along the normal,
//!   which the next step's projection removes again;
//! - levers and offsets to 1.5e-8 mm change torques by that much of their force;
//! - loads in the contact's scale are good to 2^-29 of its larger force (k = 0, no loss, for
//!   every force below 2^-3 N, which holds for nearly every contact of a pod bed).
//!
//! The test below states the budget contact by contact against the f64 law, as the Q32.32
//! kernel's test does, with these terms added.
//!
//! ```
//! use arachis_core::contact::fused::{narrow, FusedContact, FusedPair, Geometry};
//! use arachis_core::num::{FxFast, Scalar, Vec3};
//! // Pod on a steel plate, 0.02 mm overlap, at rest: the Hertz force (4/3)E*·√(R*α)·α.
//! let p = FusedPair::<f64> { eligible: true, four_thirds_e_star: 13.2, normal_damping: 0.0,
//!     eight_g_star: 48.0, tangential_damping: 0.0, friction: 0.589, rolling_friction: 0.0,
//!     jkr: false, jkr_c: 0.0, jkr_adhesion: 0.0 };
//! let c = FusedContact {
//!     geometry: Geometry::Wall { normal: Vec3::new(0.0, 0.0, 1.0), overlap: 0.02 },
//!     r_i: 4.0, r_star: 4.0, m_star: 0.156, v_centres: Vec3::ZERO, spin_i: Vec3::ZERO,
//!     spin_j: Vec3::ZERO, offset_i: None, offset_j: None, dt: 0.02 };
//! let to = |x: f64| FxFast::from_f64(x);
//! let mut delta = Vec3::ZERO;
//! let load = narrow::evaluate(&c.map(to), &p.map(to), &mut delta).unwrap();
//! let hertz = 13.2 * (4.0f64 * 0.02).sqrt() * 0.02;
//! assert!((load.force.z.to_f64() - hertz).abs() < 1e-8 * hertz);
//! ```

use super::fixed::{
    fx, geometry, magnitude, mul_wide, raw3, scale_by_ratio, scale_to_length, shr, sqrt_coarse,
    CONTACT_RADIUS_RAW, DELTA_RAW, FORCE_RAW, MASS_RAW, OFFSET_RAW, REACH_RAW, SPEED_RAW, SPIN_RAW,
    STATE, TIMESTEP_RAW, UNIT,
};
use super::{FusedContact, FusedLoad, FusedPair};
use crate::num::{FxFast, Vec3};

/// Fraction bits of levers and clump offsets in products (Q.26: below 2^31 for 2^5 mm).
const LENGTH: u32 = 26;
/// Fraction bits of velocities and spins in products (Q.24: a contact velocity below 2^6.3
/// mm/ms stays below 2^30.3, and three of its products with the Q.30 normal below 2^62).
const SPEED: u32 = 24;
/// Fraction bits of the history in its projection on the normal (Q.27: below 2^30 for
/// 2^3 mm).
const HISTORY: u32 = 27;
/// Fraction bits of the time step (Q.34: below 2^31 for 2^-3 ms).
const TIMESTEP: u32 = 34;
/// Fraction bits of the friction coefficients (Q.30: below 2^32 for μ < 4).
const FRICTION: u32 = 30;
/// Bits by which μr·Fn is narrowed further before it meets a clump's lever.
const ROLL_NARROWING: u32 = 2;
/// Bits of the normal and tangential forces in the contact's own scale: below 2^29, so that
/// |Ft|² sums three squares below 2^58 and (μs·Fn)² stays below 2^62.
pub const FORCE_LANE_BITS: u32 = 29;

/// `x` shifted right by `k` bits, rounded to nearest (ties up); `x` itself for k = 0.
#[inline(always)]
fn shr_var(x: i64, k: u32) -> i64 {
    (x + ((1i64 << k) >> 1)) >> k
}

/// The shift k that brings every force of the contact below 2^[`FORCE_LANE_BITS`]: the
/// magnitude `m` (|Fn| | |Ft,x| | |Ft,y| | |Ft,z|, below 2^45 inside the envelope) has
/// 64 − lz bits.
#[inline(always)]
pub fn force_shift(m: u64) -> u32 {
    (64 - m.leading_zeros()).saturating_sub(FORCE_LANE_BITS)
}

/// a × b for narrow operands, each component a 64-bit difference of products rounded and
/// shifted right by s.
#[inline(always)]
fn cross_narrow(a: [i64; 3], b: [i64; 3], s: u32) -> [i64; 3] {
    [
        shr(a[1] * b[2] - a[2] * b[1], s),
        shr(a[2] * b[0] - a[0] * b[2], s),
        shr(a[0] * b[1] - a[1] * b[0], s),
    ]
}

/// The rolling lever in Q.26 (see [`super::fixed`]): `len26` for a single sphere,
/// |o + sign·n̂·len| for a clump sphere at offset `o26` (components below 2^5 mm, so the
/// lever is below 2^6.4 mm).
#[inline(always)]
fn lever26(n30: [i64; 3], len26: i64, offset26: Option<[i64; 3]>, sign: i64) -> i64 {
    match offset26 {
        Some(o) => {
            let arm: [i64; 3] = each3!(|k| o[k] + sign * shr(n30[k] * len26, UNIT));
            // The root of a Q.52 square is the Q.26 length (the integer root of the raw value).
            sqrt_coarse(arm.iter().map(|&x| (x as i128 * x as i128) as u128).sum())
        }
        None => len26,
    }
}

/// Evaluate the fused law of a pair without JKR cohesion (module docs) on raw Q32.32
/// integers; `None` outside the envelope. `delta` (mm) is updated only on success.
#[inline(always)]
pub fn evaluate(
    c: &FusedContact<FxFast>,
    p: &FusedPair<FxFast>,
    delta: &mut Vec3<FxFast>,
) -> Option<FusedLoad<FxFast>> {
    let (kn, kt) = (p.four_thirds_e_star.raw(), p.eight_g_star.raw());
    let (cn, ct) = (p.normal_damping.raw(), p.tangential_damping.raw());
    let (n30, alpha, li, lj) = geometry(c, false)?;
    let (v, wi, wj, d0) = (
        raw3(c.v_centres),
        raw3(c.spin_i),
        raw3(c.spin_j),
        raw3(*delta),
    );
    let (m_star, dt, r_star) = (c.m_star.raw(), c.dt.raw(), c.r_star.raw());
    let offsets_in = c.offset_i.is_none_or(|o| magnitude(raw3(o)) < OFFSET_RAW)
        & c.offset_j.is_none_or(|o| magnitude(raw3(o)) < OFFSET_RAW);
    let inputs_in = (alpha > 0)
        & (li > 0)
        & (r_star > 0)
        & (r_star < REACH_RAW)
        & (magnitude(v) < SPEED_RAW)
        & ((magnitude(wi) | magnitude(wj)) < SPIN_RAW)
        & (magnitude(d0) < DELTA_RAW)
        & (m_star > 0)
        & (m_star < MASS_RAW)
        & (dt > 0)
        & (dt < TIMESTEP_RAW)
        & offsets_in;
    if !inputs_in {
        return None;
    }
    // Narrow the motion once: levers Q.26 (< 2^31), spins and velocities Q.24 (< 2^30).
    let (li26, lj26) = (shr(li, STATE - LENGTH), shr(lj, STATE - LENGTH));
    let to_speed = |x: [i64; 3]| x.map(|c| shr(c, STATE - SPEED));
    let (v24, wi24, wj24) = (to_speed(v), to_speed(wi), to_speed(wj));
    // Spin velocity Lᵢωᵢ + Lⱼωⱼ (Q.24): each product below 2^61, their sum below 2^62.
    let spin: [i64; 3] = if li26 == lj26 {
        each3!(|k| shr((wi24[k] + wj24[k]) * li26, LENGTH))
    } else {
        each3!(|k| shr(wi24[k] * li26 + wj24[k] * lj26, LENGTH))
    };
    if magnitude(spin) >= (SPEED_RAW >> (STATE - SPEED)) {
        return None;
    }
    // Contact velocity v − (Lᵢωᵢ + Lⱼωⱼ) × n̂ and its normal and tangential parts (Q.24).
    let turn = cross_narrow(spin, n30, UNIT);
    let vc: [i64; 3] = each3!(|k| v24[k] - turn[k]);
    let vn = shr(vc[0] * n30[0] + vc[1] * n30[1] + vc[2] * n30[2], UNIT);
    let vt: [i64; 3] = each3!(|k| vc[k] - shr(n30[k] * vn, UNIT));

    // Contact radius a = √(R*α) and √(a·m*) (Q.32), as in the Q32.32 kernel.
    let a = sqrt_coarse(r_star as u128 * alpha as u128);
    if a >= CONTACT_RADIUS_RAW {
        return None;
    }
    let root_am = sqrt_coarse(a as u128 * m_star as u128);

    // Normal force: Hertz (4/3)E*·a·α minus damping, clipped at zero (eqs. (3), (4)).
    let elastic = mul_wide(mul_wide(kn, a, STATE), alpha, STATE);
    let mut f_n = elastic - mul_wide(mul_wide(cn, root_am, STATE), vn, SPEED);
    if f_n < 0 {
        f_n = 0;
    }
    if f_n as u64 >= FORCE_RAW {
        return None;
    }

    // Tangential: history projected on the tangent plane plus vt·dt (Q.32), spring, damping.
    let d27 = d0.map(|x| shr(x, STATE - HISTORY));
    let dn = shr(d27[0] * n30[0] + d27[1] * n30[1] + d27[2] * n30[2], UNIT);
    let dt34 = dt << (TIMESTEP - STATE);
    let mut d1: [i64; 3] = each3!(|k| d0[k] - shr(n30[k] * dn, UNIT + HISTORY - STATE)
        + shr(vt[k] * dt34, SPEED + TIMESTEP - STATE));
    if magnitude(d1) >= DELTA_RAW {
        return None;
    }
    let st = mul_wide(kt, a, STATE);
    let spring: [i64; 3] = each3!(|k| mul_wide(st, d1[k], STATE));
    let damp_t = mul_wide(ct, root_am, STATE);
    let mut f_t: [i64; 3] = each3!(|k| -(spring[k] + mul_wide(damp_t, vt[k], SPEED)));
    if magnitude(f_t) >= FORCE_RAW {
        return None;
    }

    // The contact's scale: forces shifted right by k bits hold at most FORCE_LANE_BITS.
    let k = force_shift(f_n as u64 | magnitude(f_t));
    let fn_k = shr_var(f_n, k);
    let mut ft_k = f_t.map(|x| shr_var(x, k));
    let mu = shr(p.friction.raw(), STATE - FRICTION);
    let limit_k = shr(mu * fn_k, FRICTION);

    // Coulomb limit |Ft| ≤ μs·Fn; when the spring alone exceeds it, the history is rescaled so
    // that St|δt| = μs·Fn (the rare sliding contact pays for the Q32.32 roots and products).
    let f2 = ft_k[0] * ft_k[0] + ft_k[1] * ft_k[1] + ft_k[2] * ft_k[2];
    if f2 > limit_k * limit_k {
        let limit = mul_wide(p.friction.raw(), f_n, STATE);
        if limit <= 0 {
            f_t = [0; 3];
            d1 = [0; 3];
        } else {
            let f2: i128 = f_t.iter().map(|&x| x as i128 * x as i128).sum();
            f_t = scale_to_length(f_t, f2 as u128, limit);
            let s2: i128 = spring.iter().map(|&x| x as i128 * x as i128).sum();
            if s2 > limit as i128 * limit as i128 {
                d1 = scale_by_ratio(d1, limit, s2 as u128);
            }
        }
        ft_k = f_t.map(|x| shr_var(x, k));
    }

    // Loads: force on j, torques about each centre of mass, CDT rolling magnitudes (eq. (7)),
    // in the contact's scale (each product below 2^62), then back to Q.32.
    let normal_k: [i64; 3] = each3!(|k| shr(n30[k] * fn_k, UNIT));
    let force: [i64; 3] = each3!(|j| (normal_k[j] << k) + f_t[j]);
    let tau = cross_narrow(n30, ft_k, UNIT);
    let mut torque_i: [i64; 3] = each3!(|j| shr(tau[j] * li26, LENGTH) << k);
    let mut torque_j: [i64; 3] = if li26 == lj26 {
        torque_i.map(|x| -x)
    } else {
        each3!(|j| -(shr(tau[j] * lj26, LENGTH) << k))
    };
    let force_k: [i64; 3] = each3!(|j| normal_k[j] + ft_k[j]);
    let offset26 = |o: Vec3<FxFast>| raw3(o).map(|x| shr(x, STATE - LENGTH));
    let (oi, oj) = (c.offset_i.map(offset26), c.offset_j.map(offset26));
    if let Some(o) = oi {
        let t = cross_narrow(o, force_k, LENGTH);
        torque_i = each3!(|j| torque_i[j] + (t[j] << k));
    }
    if let Some(o) = oj {
        let t = cross_narrow(o, force_k, LENGTH);
        torque_j = each3!(|j| torque_j[j] + (t[j] << k));
    }
    let (mut roll_i, mut roll_j) = (0, 0);
    let mu_r = shr(p.rolling_friction.raw(), STATE - FRICTION);
    if mu_r != 0 {
        // μr·Fn two bits narrower (below 2^29): a clump's lever reaches 2^6.4 mm (2^32.4 in
        // Q.26), and their product must stay below 2^63.
        let t = shr(mu_r * fn_k, FRICTION + ROLL_NARROWING);
        roll_i = shr(t * lever26(n30, li26, oi, 1), LENGTH - ROLL_NARROWING) << k;
        if let super::Geometry::Spheres { .. } = c.geometry {
            roll_j = shr(t * lever26(n30, lj26, oj, -1), LENGTH - ROLL_NARROWING) << k;
        }
    }
    *delta = fx(d1);
    Some(FusedLoad {
        force: fx(force),
        torque_i: fx(torque_i),
        torque_j: fx(torque_j),
        roll_i: FxFast::from_raw(roll_i),
        roll_j: FxFast::from_raw(roll_j),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::fused::random_contacts::{agreement, test_pairs, Extra, LEVER_MM};
    use crate::contact::fused::Geometry;

    /// One unit of Q.24 (the velocities' format), mm/ms.
    const SPEED_UNIT: f64 = 1.0 / (1u64 << SPEED) as f64;
    /// One unit of Q.26 (the levers' format), mm.
    const LENGTH_UNIT: f64 = 1.0 / (1u64 << LENGTH) as f64;
    /// One unit of Q.27 (the history's format in its projection), mm.
    const HISTORY_UNIT: f64 = 1.0 / (1u64 << HISTORY) as f64;
    /// The loads' relative resolution in the contact's scale, 2^-29.
    const SCALE_UNIT: f64 = 1.0 / (1u64 << FORCE_LANE_BITS) as f64;

    /// What the narrow formats add to the Q32.32 budget (module docs), for one contact:
    /// - the contact velocity is off by half a unit of Q.24 from each rounding on its way (v,
    ///   the spin product, the turn, vn, vt: 3 units) plus ωᵢ's and ωⱼ's rounding times their
    ///   levers and the levers' rounding times the spins;
    /// - the forces move by the damping coefficients times that, and by the tangential
    ///   stiffness times the history's error: the velocity's times dt, plus the projection's
    ///   (a few units of Q.27, along the normal), and a sliding history by μs times the force's
    ///   error over the stiffness;
    /// - torques, and rolling torques with μr, move by the force's error times the longest
    ///   lever, by the levers' and offsets' rounding (Q.26) times the force, and by the scale's
    ///   resolution.
    fn narrow_budget(
        p: &FusedPair<f64>,
        c: &FusedContact<f64>,
        alpha: f64,
        want: &FusedLoad<f64>,
    ) -> Extra {
        let r_j = match c.geometry {
            Geometry::Spheres { r_j, .. } => r_j,
            Geometry::Wall { .. } => 0.0,
        };
        let spin = |w: Vec3<f64>| w.x.abs().max(w.y.abs()).max(w.z.abs());
        let v_err = SPEED_UNIT * (3.0 + 0.5 * (c.r_i + r_j))
            + LENGTH_UNIT * (spin(c.spin_i) + spin(c.spin_j));
        let root_am = libm::sqrt(libm::sqrt(c.r_star * alpha) * c.m_star);
        let st = p.eight_g_star * libm::sqrt(c.r_star * alpha);
        let history = v_err * c.dt + 4.0 * HISTORY_UNIT;
        let force = (p.normal_damping + p.tangential_damping) * root_am * v_err + st * history;
        // A sliding contact's history is μs·Fn/St: the normal force's error over St.
        let sliding = p.friction * force / st;
        let f = want
            .force
            .x
            .abs()
            .max(want.force.y.abs())
            .max(want.force.z.abs());
        Extra {
            force,
            torque: LEVER_MM * force + (2.0 * LENGTH_UNIT + LEVER_MM * SCALE_UNIT) * 2.0 * f,
            roll: p.rolling_friction
                * (LEVER_MM * force + f * (2.0 * LENGTH_UNIT + LEVER_MM * SCALE_UNIT * 4.0)),
            history: history + sliding,
        }
    }

    /// This kernel against the f64 law on 200 000 random contacts (spheres and walls, single
    /// and clump spheres, soft and stiff pairs) inside the Q32.32 budget plus the narrow
    /// formats' own ([`narrow_budget`]), and in nearly every case inside the envelope.
    #[test]
    fn agrees_with_the_f64_law_inside_its_error_budget() {
        let inside = agreement(
            &test_pairs(),
            0x2545_F491_4F6C_DD1D,
            evaluate,
            narrow_budget,
        );
        assert!(
            inside > 190_000,
            "only {inside} contacts inside the envelope"
        );
    }

    /// The contact's scale: forces below 2^29 raw are not shifted (k = 0), a force of
    /// 2^45 − 1 raw (just under 8 kN) is shifted by 16, and the shift never leaves more than
    /// 29 bits.
    #[test]
    fn the_force_shift_keeps_29_bits() {
        assert_eq!(force_shift(0), 0);
        assert_eq!(force_shift((1 << 29) - 1), 0);
        assert_eq!(force_shift(1 << 29), 1);
        assert_eq!(force_shift((1 << 45) - 1), 16);
        for bits in 0..45 {
            let m = (1u64 << bits) | 1;
            assert!(m >> force_shift(m) < 1 << FORCE_LANE_BITS, "{bits}");
        }
    }
}
