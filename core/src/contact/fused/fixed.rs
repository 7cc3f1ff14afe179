//! The fused base law for Q32.32 fixed point, written on the raw integers: the law of
//! [`super`] for [`FxFast`].
//!
//! The generic law runs every product through the scalar type: a 128-bit multiply, a
//! rounding add with carry and a shift, then a conversion back, with the state of each
//! [`FxFast`] kept in its own variable. Here the same products are written on `i64` and
//! `i128` directly, so that chains such as a dot product round once; the three roots come from
//! one 64-bit reciprocal-root routine ([`rsqrt_q30`]: a table and two Newton steps, integer
//! multiplications only) instead of the exact 128-bit roots; and the envelope is tested with a
//! few comparisons of magnitudes (`|x| | |y| | |z|`, one test per vector).
//!
//! Precision (every quantity is Q.32 unless stated): the centre distance is the correctly
//! rounded root of the exact |d|² (one reciprocal root, one residual step and an exact
//! finish), so the overlap is as exact as in the checked terms; the normal is Q.30 (2^-30);
//! a = √(R*α) and √(a·m*), which only scale stiffness and damping, are good to about 2^-28.
//! The test below compares 200 000 random contacts with the f64 law: every load agrees within
//! 2e-6 of its size plus what the Q.32 rounding of the overlap and the history moves it by.
//!
//! Every bound of the envelope is checked before the product it protects; the kernel returns
//! `None` outside it, and the caller falls back to the checked terms.

use super::jkr::Neck;
use super::{FusedContact, FusedLoad, FusedPair, Geometry};
use crate::num::fixed::{isqrt_round_u128, nearest_root};
use crate::num::fixed_fast::rsqrt_q30;
use crate::num::{FxFast, Vec3};

/// Fraction bits of the state and lengths (Q.32).
const STATE: u32 = 32;
/// Fraction bits of the unit normal (Q.30).
const UNIT: u32 = 30;

/// Raw bounds of the envelope (Q.32): sum of radii < 2^5 mm, …
const REACH_RAW: i64 = 1 << (STATE + 5);
/// … centre velocity difference and spin velocity < 2^5 mm/ms, …
const SPEED_RAW: u64 = 1 << (STATE + 5);
/// … angular velocity < 2^6 rad/ms, …
const SPIN_RAW: u64 = 1 << (STATE + 6);
/// … history < 2^3 mm, …
const DELTA_RAW: u64 = 1 << (STATE + 3);
/// … contact radius a < 2^4 mm, …
const CONTACT_RADIUS_RAW: i64 = 1 << (STATE + 4);
/// … effective mass < 2^10 g, …
const MASS_RAW: i64 = 1 << (STATE + 10);
/// … time step < 2^-3 ms ([`MAX_TIMESTEP_S`]), …
const TIMESTEP_RAW: i64 = 1 << (STATE - 3);
/// The time step below which this kernel takes a world's contacts, s: 2^-3 ms. A world that
/// steps as long or longer sends every contact to the checked terms (the same law, about
/// twice the cost of a step; `host/src/field/settle.rs` measured it on a settling bed).
pub const MAX_TIMESTEP_S: f64 = 1.25e-4;
/// … clump offsets < 2^5 mm, …
const OFFSET_RAW: u64 = 1 << (STATE + 5);
/// … normal and tangential force components < 2^13 N.
const FORCE_RAW: u64 = 1 << (STATE + 13);

/// (x + 2^(s−1)) >> s: rounded to nearest, ties up (s ≥ 1).
#[inline(always)]
fn shr(x: i64, s: u32) -> i64 {
    (x + (1 << (s - 1))) >> s
}

/// a·b rounded and shifted right by s (1 ≤ s ≤ 64), with a 128-bit product; the result must
/// fit an i64 (the envelope's bounds). Public for the benches that compare other
/// arithmetic with the kernel's (`benches/benches/exact_lanes.rs`), as are [`dot_wide`],
/// [`mul_sub_wide`] and [`sqrt_coarse`].
#[inline(always)]
pub fn mul_wide(a: i64, b: i64, s: u32) -> i64 {
    ((a as i128 * b as i128 + (1i128 << (s - 1))) >> s) as i64
}

/// Half a unit of Q.32, for rounding a 128-bit Q.64 sum.
const HALF_UNIT: i128 = 1 << (STATE - 1);

/// a·b rounded to nearest and shifted right by s (a dot product), 128-bit.
#[inline(always)]
pub fn dot_wide(a: [i64; 3], b: [i64; 3], s: u32) -> i64 {
    ((a[0] as i128 * b[0] as i128
        + a[1] as i128 * b[1] as i128
        + a[2] as i128 * b[2] as i128
        + (1i128 << (s - 1)))
        >> s) as i64
}

/// (a·b − c·d) rounded and shifted right by s, 128-bit.
#[inline(always)]
pub fn mul_sub_wide(a: i64, b: i64, c: i64, d: i64, s: u32) -> i64 {
    ((a as i128 * b as i128 - c as i128 * d as i128 + (1i128 << (s - 1))) >> s) as i64
}

/// `[e(0), e(1), e(2)]` for an expression `e` in the component index: `each3!(|k| e)`.
/// A macro, not a function taking a closure: LLVM kept several such closures out of line
/// in the contact loop (13 call sites), and every call spilled the caller-saved registers
/// of the whole scan around it.
macro_rules! each3 {
    (|$k:ident| $e:expr) => {
        [
            {
                let $k = 0usize;
                $e
            },
            {
                let $k = 1usize;
                $e
            },
            {
                let $k = 2usize;
                $e
            },
        ]
    };
}

/// Largest |component| bound: |x| | |y| | |z| (below 2^k iff every component is).
#[inline(always)]
fn magnitude(v: [i64; 3]) -> u64 {
    v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs()
}

/// A nonzero v as x·2^s with x ∈ [2^62, 2^64) and s even: (x, s).
#[inline(always)]
fn normalise(v: u128) -> (u64, i32) {
    // s = (bits − 64) rounded up to even, so that the root's exponent s/2 is whole; the two
    // halves are handled apart because a variable 128-bit shift costs a dozen instructions.
    let high = (v >> 64) as u64;
    if high == 0 {
        let low = v as u64;
        let k = low.leading_zeros() & !1;
        (low.wrapping_shl(k), -(k as i32))
    } else {
        let s = (65 - high.leading_zeros() as i32) & !1;
        ((v >> s) as u64, s)
    }
}

/// 2^s·x for a signed shift s (right shifts rounded).
#[inline(always)]
fn scale_pow2(x: i64, s: i32) -> i64 {
    if s >= 0 {
        x << s
    } else {
        shr(x, (-s) as u32)
    }
}

/// √v of a u128 holding Q.64, in Q.32, to about 2^-28 relative (0 for v = 0). Public, as
/// [`mul_wide`] is, for `benches/benches/exact_lanes.rs`.
#[inline(always)]
pub fn sqrt_coarse(v: u128) -> i64 {
    if v == 0 {
        return 0;
    }
    let (x, s) = normalise(v);
    // √x = x·(1/√x) = (x/2^32)·y/2^30 with y = 2^30/√(x/2^64); √v = √x·2^(s/2), in Q.32
    // (v is Q.64): the same integer.
    let root_x = ((x >> 32) * rsqrt_q30(x)) >> 30;
    scale_pow2(root_x as i64, s / 2)
}

/// `v·target/√v2` for v2 = |u|² (Q.64) of some vector u: `v` rescaled by the ratio of
/// `target` (Q.32, < 2^47) to |u|, through one reciprocal root (good to about 2^-28).
#[inline(always)]
fn scale_by_ratio(v: [i64; 3], target: i64, v2: u128) -> [i64; 3] {
    let (x, s) = normalise(v2);
    let y = rsqrt_q30(x) as i128;
    // 1/√v2 = y·2^(−62 − s/2) (v2 in raw units squared); v·target < 2^93, times y < 2^124.
    let sh = 62 + s / 2;
    let sh = sh.clamp(1, 126) as u32;
    each3!(|k| ((v[k] as i128 * target as i128 * y + (1i128 << (sh - 1))) >> sh) as i64)
}

/// `v` rescaled to length `target` (Q.32), where v2 = |v|² (Q.64).
#[inline(always)]
fn scale_to_length(v: [i64; 3], v2: u128, target: i64) -> [i64; 3] {
    scale_by_ratio(v, target, v2)
}

/// Centre distance |d| (Q.32, correctly rounded) and the unit normal d/|d| (Q.30) from one
/// reciprocal root: y ≈ 1/√|d|² to 2^-28 gives the normal at once and a distance within a
/// few hundred units, which one residual step and [`nearest_root`] make exact.
#[inline(always)]
fn distance_and_normal(d: [i64; 3], d2: u128) -> Option<(i64, [i64; 3])> {
    let (x, s) = normalise(d2);
    let y = rsqrt_q30(x);
    // √d2 = √x·2^(s/2) ≈ (x/2^32)·y/2^30 · 2^(s/2).
    let r0 = scale_pow2((((x >> 32) * y) >> 30) as i64, s / 2);
    // r ← r + (d2 − r²)/(2√d2), with 1/(2√d2) = y·2^(−63 − s/2).
    let res = d2 as i128 - r0 as i128 * r0 as i128;
    let sh = 63 + s / 2;
    let step = if sh < 127 { (res * y as i128) >> sh } else { 0 };
    let r1 = r0 + step as i64;
    let res1 = d2 as i128 - r1 as i128 * r1 as i128;
    let dist = match i64::try_from(res1).ok().and_then(|e| nearest_root(e, r1)) {
        Some(r) => r,
        None => isqrt_round_u128(d2) as i64,
    };
    // n = d/√d2 = d·y·2^(−62 − s/2); in Q.30 from d in Q.26: (d26·y) >> (26 + s/2).
    let sh_n = 26 + s / 2;
    if !(1..=62).contains(&sh_n) {
        return None;
    }
    let n = each3!(|k| shr(shr(d[k], STATE - 26) * y as i64, sh_n as u32));
    Some((dist, n))
}

/// The raw integers of a vector.
#[inline(always)]
fn raw3(v: Vec3<FxFast>) -> [i64; 3] {
    [v.x.raw(), v.y.raw(), v.z.raw()]
}

/// A vector of raw integers.
#[inline(always)]
fn fx(v: [i64; 3]) -> Vec3<FxFast> {
    Vec3::new(
        FxFast::from_raw(v[0]),
        FxFast::from_raw(v[1]),
        FxFast::from_raw(v[2]),
    )
}

/// a × b, each component one 128-bit difference of products rounded and shifted right by s.
#[inline(always)]
fn cross_wide(a: [i64; 3], b: [i64; 3], s: u32) -> [i64; 3] {
    [
        mul_sub_wide(a[1], b[2], a[2], b[1], s),
        mul_sub_wide(a[2], b[0], a[0], b[2], s),
        mul_sub_wide(a[0], b[1], a[1], b[0], s),
    ]
}

/// The rolling lever from a body's centre of mass to the contact point (Q.32): `len` for a
/// single sphere, |o + sign·n̂·len| for a clump sphere whose centre lies at `offset`.
#[inline(always)]
fn lever(n30: [i64; 3], len: i64, offset: Option<Vec3<FxFast>>, sign: i64) -> i64 {
    match offset {
        Some(o) => {
            let o = raw3(o);
            let arm: [i64; 3] = each3!(|k| o[k] + sign * mul_wide(n30[k], len, UNIT));
            sqrt_coarse(arm.iter().map(|&x| (x as i128 * x as i128) as u128).sum())
        }
        None => len,
    }
}

/// Evaluate the fused law (module docs of [`super`]) on raw integers; `None` outside the
/// envelope. `delta` (mm) is updated only on success.
#[inline(always)]
pub fn evaluate(
    c: &FusedContact<FxFast>,
    p: &FusedPair<FxFast>,
    delta: &mut Vec3<FxFast>,
) -> Option<FusedLoad<FxFast>> {
    let mut no_root = FxFast::from_raw(0);
    evaluate_jkr(c, p, delta, &mut no_root)
}

/// [`evaluate`] with JKR's root x = √a (√mm): in, the last step's (0: none); out, this
/// step's; like `delta`, updated only on success ([`super::evaluate_fast_jkr`]).
///
/// A JKR pair with a last root (attached) is also evaluated apart (δ ≤ 0), across its neck,
/// as the checked terms evaluate it: the JKR force alone (no contact radius, so no Hertz
/// force, damping or tangential stiffness; the history is carried as on contact), its
/// repulsive part loading the rolling friction. Past the JKR separation the contact breaks:
/// zero loads, and the history and root come back zero ([`super::jkr::attached_force`]). The
/// caller gives a neck only within the pair's reach (rs + [`crate::contact::CohesionJkr::reach`]).
#[inline(always)]
pub fn evaluate_jkr(
    c: &FusedContact<FxFast>,
    p: &FusedPair<FxFast>,
    delta: &mut Vec3<FxFast>,
    jkr_root: &mut FxFast,
) -> Option<FusedLoad<FxFast>> {
    // A JKR contact attached at its last step (it has a root) may hold beyond touching.
    let attached = p.jkr && jkr_root.raw() > 0;
    let (kn, kt) = (p.four_thirds_e_star.raw(), p.eight_g_star.raw());
    let (cn, ct) = (p.normal_damping.raw(), p.tangential_damping.raw());
    let ri = c.r_i.raw();

    // Geometry: normal (Q.30), overlap and levers (Q.32).
    let (n30, alpha, li, lj) = match c.geometry {
        Geometry::Spheres { d, r_j, .. } => {
            let rj = r_j.raw();
            let d = raw3(d);
            if !((0..REACH_RAW).contains(&ri)
                && (0..REACH_RAW).contains(&rj)
                && magnitude(d) < REACH_RAW as u64)
            {
                return None;
            }
            let rs = ri + rj;
            let d2: u128 = d.iter().map(|&x| (x as i128 * x as i128) as u128).sum();
            let rs2 = rs as u128 * rs as u128;
            // Touching, or held across a JKR neck, with an overlap of at most half the reach
            // (centres not too close).
            if !((d2 < rs2 || attached) && 4 * d2 >= rs2 && d2 != 0) {
                return None;
            }
            let (dist, n) = distance_and_normal(d, d2)?;
            let alpha = rs - dist;
            let half = alpha >> 1;
            (n, alpha, ri - half, rj - half)
        }
        Geometry::Wall { normal, overlap } => {
            let alpha = overlap.raw();
            if !((1..REACH_RAW).contains(&alpha) && (0..REACH_RAW).contains(&ri)) {
                return None;
            }
            (
                raw3(normal).map(|x| shr(x, STATE - UNIT)),
                alpha,
                ri - (alpha >> 1),
                0,
            )
        }
    };
    // Apart or just touching (α ≤ 0; a wall contact always overlaps): held across a neck.
    let neck = attached && alpha <= 0;
    let (v, wi, wj, d0) = (
        raw3(c.v_centres),
        raw3(c.spin_i),
        raw3(c.spin_j),
        raw3(*delta),
    );
    let (m_star, dt, r_star) = (c.m_star.raw(), c.dt.raw(), c.r_star.raw());
    let offsets_in = c.offset_i.is_none_or(|o| magnitude(raw3(o)) < OFFSET_RAW)
        & c.offset_j.is_none_or(|o| magnitude(raw3(o)) < OFFSET_RAW);
    let inputs_in = ((alpha > 0) | neck)
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
    // Contact velocity v − (Lᵢωᵢ + Lⱼωⱼ) × n̂ (Q.32), and its normal and tangential parts.
    // These products stay 128-bit: a stiff, damped contact turns a velocity error of 1e-7
    // into a force error of 1e-5 of its force.
    let spin: [i64; 3] = if li == lj {
        each3!(|k| mul_wide(wi[k] + wj[k], li, STATE))
    } else {
        each3!(|k| {
            ((wi[k] as i128 * li as i128 + wj[k] as i128 * lj as i128 + HALF_UNIT) >> STATE) as i64
        })
    };
    if magnitude(spin) >= SPEED_RAW {
        return None;
    }
    let vc = [
        v[0] - mul_sub_wide(spin[1], n30[2], spin[2], n30[1], UNIT),
        v[1] - mul_sub_wide(spin[2], n30[0], spin[0], n30[2], UNIT),
        v[2] - mul_sub_wide(spin[0], n30[1], spin[1], n30[0], UNIT),
    ];
    let vn = dot_wide(vc, n30, UNIT);
    let vt: [i64; 3] = each3!(|k| vc[k] - mul_wide(n30[k], vn, UNIT));

    // Contact radius a = √(R*α) and √(a·m*) (Q.32); a neck has none, so no Hertz force,
    // damping or tangential stiffness, as in the checked terms.
    let a = if neck {
        0
    } else {
        sqrt_coarse(r_star as u128 * alpha as u128)
    };
    if a >= CONTACT_RADIUS_RAW {
        return None;
    }
    let root_am = sqrt_coarse(a as u128 * m_star as u128);

    // Normal force: Hertz (4/3)E*·a·α minus damping, clipped at zero (eqs. (3), (4)).
    // JKR's repulsive force replaces Hertz's; its adhesion is subtracted from the force last
    // ([`super::jkr`], the generic law's order).
    let (elastic, attraction, root) = if p.jkr {
        let held = super::jkr::attached_force(
            FxFast::from_raw(alpha),
            c.r_star,
            p.jkr_c,
            p.four_thirds_e_star,
            p.jkr_adhesion,
            *jkr_root,
        )?;
        let Neck::Held(rep, adh, root) = held else {
            // A neck beyond the JKR separation: it breaks, with no force and no history.
            *delta = Vec3::ZERO;
            *jkr_root = FxFast::from_raw(0);
            return Some(FusedLoad::default());
        };
        (rep.raw(), adh.raw(), root)
    } else {
        (mul_wide(mul_wide(kn, a, STATE), alpha, STATE), 0, *jkr_root)
    };
    let mut f_n = elastic - mul_wide(mul_wide(cn, root_am, STATE), vn, STATE);
    if f_n < 0 {
        f_n = 0;
    }
    if f_n as u64 >= FORCE_RAW {
        return None;
    }

    // Tangential: history projected on the tangent plane plus vt·dt, spring and damping.
    let dn = dot_wide(d0, n30, UNIT);
    let mut d1: [i64; 3] =
        each3!(|k| d0[k] - mul_wide(n30[k], dn, UNIT) + mul_wide(vt[k], dt, STATE));
    if magnitude(d1) >= DELTA_RAW {
        return None;
    }
    let st = mul_wide(kt, a, STATE);
    let spring: [i64; 3] = each3!(|k| mul_wide(st, d1[k], STATE));
    let damp_t = mul_wide(ct, root_am, STATE);
    let mut f_t: [i64; 3] = each3!(|k| -(spring[k] + mul_wide(damp_t, vt[k], STATE)));
    if magnitude(f_t) >= FORCE_RAW {
        return None;
    }

    // Coulomb limit |Ft| ≤ μs·Fn; when the spring alone exceeds it, the history is rescaled so
    // that St|δt| = μs·Fn (the rare sliding contact pays for exact roots and divisions).
    let limit = mul_wide(p.friction.raw(), f_n, STATE);
    let f2: i128 = f_t.iter().map(|&x| x as i128 * x as i128).sum();
    if f2 > limit as i128 * limit as i128 {
        if limit <= 0 {
            f_t = [0; 3];
            d1 = [0; 3];
        } else {
            f_t = scale_to_length(f_t, f2 as u128, limit);
            let s2: i128 = spring.iter().map(|&x| x as i128 * x as i128).sum();
            if s2 > limit as i128 * limit as i128 {
                // δt·μs·Fn/(St|δt|) = δt·limit/|spring|.
                d1 = scale_by_ratio(d1, limit, s2 as u128);
            }
        }
    }

    // Loads: force on j, torques about each centre of mass, CDT rolling magnitudes (eq. (7)).
    let force: [i64; 3] = each3!(|k| mul_wide(n30[k], f_n - attraction, UNIT) + f_t[k]);
    let tau = cross_wide(n30, f_t, UNIT);
    let mut torque_i: [i64; 3] = each3!(|k| mul_wide(tau[k], li, STATE));
    let mut torque_j: [i64; 3] = if li == lj {
        torque_i.map(|x| -x)
    } else {
        each3!(|k| -mul_wide(tau[k], lj, STATE))
    };
    if let Some(o) = c.offset_i {
        let t = cross_wide(raw3(o), force, STATE);
        torque_i = each3!(|k| torque_i[k] + t[k]);
    }
    if let Some(o) = c.offset_j {
        let t = cross_wide(raw3(o), force, STATE);
        torque_j = each3!(|k| torque_j[k] + t[k]);
    }
    let (mut roll_i, mut roll_j) = (0, 0);
    let mu_r = p.rolling_friction.raw();
    if mu_r != 0 {
        let t = mul_wide(mu_r, f_n, STATE);
        roll_i = mul_wide(t, lever(n30, li, c.offset_i, 1), STATE);
        if let Geometry::Spheres { .. } = c.geometry {
            roll_j = mul_wide(t, lever(n30, lj, c.offset_j, -1), STATE);
        }
    }
    *delta = fx(d1);
    *jkr_root = root;
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

    #[test]
    fn the_published_time_step_bound_is_the_envelopes() {
        use crate::num::Fx;
        use crate::units::TIME_S_TO_MS;
        let bound_ms = Fx::from_f64(MAX_TIMESTEP_S * TIME_S_TO_MS);
        assert_eq!(bound_ms.raw(), TIMESTEP_RAW);
    }
    use crate::contact::fused::evaluate as evaluate_f64;
    use crate::contact::fused::random_contacts::{contact, jkr_pairs, test_pairs, Stream};
    use crate::num::Scalar;

    /// Absolute part of the tolerance on forces (N) and history (mm): a dozen Q32.32 units of
    /// rounding in a chain of products.
    const FORCE_ABS: f64 = 3e-9;
    /// One unit of a Q.32 force, N.
    const FORCE_UNIT_N: f64 = 2.33e-10;
    /// The longest lever of the random contacts (sphere radius plus clump offset), mm.
    const LEVER_MM: f64 = 24.0;
    /// The same on torques (N·mm): the force's rounding times the longest lever.
    const TORQUE_ABS: f64 = LEVER_MM * FORCE_ABS;
    /// The Q32.32 overlap is rounded (to within a unit, 2^-32 mm, with the distance's own
    /// rounding) in both this kernel and the checked terms, where the f64 law has it
    /// exact: an error of the fixed-point format, not of the kernel.
    const OVERLAP_ROUNDING_MM: f64 = 2.0 * 2.33e-10;
    /// The Q32.32 history is rounded in every step's projection and increment (up to eight units
    /// of 2^-32 mm) in both this kernel and the checked terms.
    const HISTORY_ROUNDING_MM: f64 = 8.0 * 2.33e-10;
    /// Relative tolerance: the kernel's own error budget (module docs), a few 1e-7, with
    /// margin.
    const RELATIVE: f64 = 2e-6;

    /// Units of Q.32 to which fixed point evaluates JKR's g(x) (three rounded terms): x is
    /// off by up to this many units over g′(x) ([`super::super::jkr`]'s tests).
    const JKR_G_UNITS: f64 = 4.0;

    /// This kernel against the f64 law on 200 000 random contacts (spheres and walls,
    /// single and clump spheres, soft and stiff pairs): every force, torque, rolling torque and
    /// new history component agrees within [`RELATIVE`] of the largest component of its vector,
    /// plus what the Q.32 rounding of the overlap and the history ([`OVERLAP_ROUNDING_MM`],
    /// [`HISTORY_ROUNDING_MM`]) moves it by, plus [`FORCE_ABS`] or [`TORQUE_ABS`].
    #[test]
    fn agrees_with_the_f64_law_inside_its_error_budget() {
        let inside = agreement(&test_pairs(), 0x2545_F491_4F6C_DD1D);
        // Nearly every random contact lies inside the envelope.
        assert!(
            inside > 190_000,
            "only {inside} contacts inside the envelope"
        );
    }

    /// The same with JKR cohesion on the pairs (sticky soil on soil and on steel): the budget
    /// adds what the Q.32 Newton root of JKR's contact radius moves the normal force by
    /// ([`JKR_G_UNITS`]).
    #[test]
    fn with_jkr_agrees_with_the_f64_law_inside_its_error_budget() {
        let inside = agreement(&jkr_pairs(), 0x2545_F491_4F6C_DD1D);
        assert!(
            inside > 190_000,
            "only {inside} contacts inside the envelope"
        );
    }

    /// Check 200 000 random contacts of `pairs` (see above); returns how many lay inside the
    /// envelope.
    fn agreement(pairs: &[(FusedPair<f64>, bool); 3], seed: u64) -> usize {
        let mut s = Stream(seed);
        let mut inside = 0;
        for k in 0..200_000 {
            let (p, stiff) = pairs[k % 3];
            let (c, delta0) = contact(&mut s, k % 4 == 0, k % 5 == 0, stiff);
            let mut d_ref = delta0;
            let Some(want) = evaluate_f64(&c, &p, &mut d_ref) else {
                continue;
            };
            let to = |x: f64| FxFast::from_f64(x);
            let mut d_fix = delta0.map(to);
            let Some(got) = evaluate(&c.map(to), &p.map(to), &mut d_fix) else {
                continue;
            };
            inside += 1;
            // Loads scale at most as α^1.5 (Hertz), so the Q.32 overlap's rounding moves them
            // by at most 1.5·δα/α of themselves.
            let alpha = match c.geometry {
                Geometry::Spheres { d, r_j, .. } => c.r_i + r_j - d.norm(),
                Geometry::Wall { overlap, .. } => overlap,
            };
            let rel = RELATIVE + 1.5 * OVERLAP_ROUNDING_MM / alpha;
            // The Q.32 history's rounding times the tangential stiffness 8G*·a.
            let st = p.eight_g_star * libm::sqrt(c.r_star * alpha);
            let history_abs = st * HISTORY_ROUNDING_MM;
            let jkr_abs = jkr_normal_error(&p, &c, alpha);
            let (force_abs, torque_abs) = (
                FORCE_ABS + history_abs + jkr_abs,
                TORQUE_ABS + LEVER_MM * (history_abs + jkr_abs),
            );
            let check = |name: &str, g: Vec3<FxFast>, w: Vec3<f64>, abs: f64| {
                let scale = w.x.abs().max(w.y.abs()).max(w.z.abs());
                let err = (g.map(|x| x.to_f64()) - w).map(|x| x.abs());
                let e = err.x.max(err.y).max(err.z);
                let tol = rel * scale + abs;
                assert!(
                    e <= tol,
                    "{name} off by {e:e} (tolerance {tol:e}) in case {k}: {g:?} vs {w:?}; {c:?}; α {alpha:e}, JKR {jkr_abs:e}"
                );
            };
            let roll = |g: FxFast, w: f64| g.to_f64() - w;
            check("force", got.force, want.force, force_abs);
            check("torque i", got.torque_i, want.torque_i, torque_abs);
            check("torque j", got.torque_j, want.torque_j, torque_abs);
            // A sliding contact's history is μs·Fn/St: the Q.32 limit's rounding over St.
            check(
                "history",
                d_fix,
                d_ref,
                FORCE_ABS + (2.0 * FORCE_UNIT_N + p.friction * jkr_abs) / st,
            );
            for (g, w) in [(got.roll_i, want.roll_i), (got.roll_j, want.roll_j)] {
                assert!(
                    roll(g, w).abs() <= rel * w.abs() + torque_abs,
                    "rolling off in case {k}"
                );
            }
        }
        inside
    }

    /// How far fixed point's normal force may lie from f64's beyond the base budget with JKR
    /// on, N (zero without JKR), in absolute terms: what matters where JKR's repulsive force,
    /// large even at a vanishing overlap, nearly cancels the normal damping (Fn, and with it
    /// the Coulomb limit, is then a small difference of two large terms).
    /// - JKR: x = √a off by [`JKR_G_UNITS`]·2^-32/g′(x), plus where the Newton loop stops
    ///   (2^-[`crate::contact::fused::jkr::NEWTON_STOP_BITS`] of x), moves the repulsive force
    ///   (∝ x⁶) six times and the adhesive (∝ x³) three times its relative error.
    /// - Damping: ∝ √(√(R*α)·m*), so the overlap's rounding moves it by a quarter of
    ///   [`OVERLAP_ROUNDING_MM`]/α of itself, and the coarse roots by 2^-27.
    fn jkr_normal_error(p: &FusedPair<f64>, c: &FusedContact<f64>, alpha: f64) -> f64 {
        if !p.jkr {
            return 0.0;
        }
        let (k, a) = (p.four_thirds_e_star, p.jkr_adhesion);
        let (rep, adh, _) = crate::contact::fused::jkr::force(alpha, c.r_star, p.jkr_c, k, a, 0.0)
            .expect("f64 has no envelope");
        let x3 = adh / a;
        let slope = 4.0 * x3 - p.jkr_c * c.r_star;
        // The root's conditioning, and where either Newton loop may stop.
        let dx_x = JKR_G_UNITS * 2f64.powi(-32) / slope / libm::cbrt(x3)
            + 2f64.powi(-crate::contact::fused::jkr::NEWTON_STOP_BITS);
        // The normal contact velocity, as the law forms it (levers Rᵢ − α/2, Rⱼ − α/2).
        let (n, r_j) = match c.geometry {
            Geometry::Spheres { d, r_j, .. } => (d.scale(1.0 / d.norm()), r_j),
            Geometry::Wall { normal, .. } => (normal, alpha),
        };
        let spin = c.spin_i.scale(c.r_i - alpha / 2.0) + c.spin_j.scale(r_j - alpha / 2.0);
        let vn = (c.v_centres - spin.cross(n)).dot(n);
        let root_am = libm::sqrt(libm::sqrt(c.r_star * alpha) * c.m_star);
        let damping = (p.normal_damping * root_am * vn).abs();
        let damping_abs = damping * (0.25 * OVERLAP_ROUNDING_MM / alpha + 2f64.powi(-27));
        (6.0 * rep + 3.0 * adh) * dx_x + damping_abs
    }

    /// A pod–pod pair with JKR (Γ 2 J/m², seed 000's coefficients) held apart across its
    /// neck, δ from 0.1 to 0.9 of the JKR separation δ_min (Johnson 1985 §5.5), on a tilted
    /// axis with sliding and spinning spheres: the force on j is n̂ times the checked term's
    /// JKR force, repulsive minus adhesive (within 2e-6 of their sum plus a few Q.32 units,
    /// the root's budget); no tangential force, so no torque about the centres; the rolling
    /// torque is μr times the repulsive force times the lever Rᵢ − δ/2; the history is carried
    /// as on contact (projected, plus vt·dt, within a dozen units). Past δ_min the contact
    /// breaks (no load, history and root zero); a pair with no last root is not attached and
    /// is left to the terms.
    #[test]
    fn a_neck_carries_the_jkr_force_alone_and_breaks_past_the_separation() {
        use crate::contact::fused::random_contacts::{sticky, POD};
        use crate::contact::CohesionJkr;
        use crate::num::Fx;
        let gamma = 2.0;
        let pp = sticky(POD, POD, 0.335, 0.854, 0.346, gamma);
        let p = pp.fused.map(FxFast::from_f64);
        let term = CohesionJkr::<Fx>::new(gamma, pp.e_star_mpa);
        let (r, r_star, m_star, dt) = (4.0, 2.0, 0.08, 1e-3);
        let g = gamma * 1e-3;
        let d_min = -0.75
            * libm::cbrt(core::f64::consts::PI.powi(2) * g * g * r_star / pp.e_star_mpa.powi(2));
        let n = Vec3::new(0.6, 0.0, 0.8);
        let (v, wi, wj) = (
            Vec3::new(0.01, -0.02, 0.003),
            Vec3::new(0.0, 0.05, -0.01),
            Vec3::new(0.02, 0.0, 0.01),
        );
        let d0 = Vec3::new(1e-4, 2e-4, -0.75e-4);
        let fx = FxFast::from_f64;
        let at = |delta: f64, root: FxFast| {
            let c = FusedContact {
                geometry: Geometry::Spheres {
                    d: n.scale(2.0 * r - delta).map(fx),
                    d2: fx((2.0 * r - delta).powi(2)),
                    r_j: fx(r),
                },
                r_i: fx(r),
                r_star: fx(r_star),
                m_star: fx(m_star),
                v_centres: v.map(fx),
                spin_i: wi.map(fx),
                spin_j: wj.map(fx),
                offset_i: None,
                offset_j: None,
                dt: fx(dt),
            };
            let (mut hist, mut root) = (d0.map(fx), root);
            evaluate_jkr(&c, &p, &mut hist, &mut root).map(|l| (l, hist, root))
        };
        let unit = 2.33e-10;
        for k in 1..=9 {
            let delta = d_min * k as f64 / 10.0;
            let Some(Neck::Held(_, _, last)) = super::super::jkr::attached_force(
                fx(delta),
                fx(r_star),
                p.jkr_c,
                p.four_thirds_e_star,
                p.jkr_adhesion,
                FxFast::ZERO,
            ) else {
                panic!("broken at {delta}");
            };
            let (load, hist, root) = at(delta, last).expect("a neck in the envelope");
            assert!(root > FxFast::ZERO, "still attached at {delta}");
            let (rep, adh) = term
                .force(Fx::from_f64(delta), Fx::from_f64(r_star))
                .expect("held");
            let (rep, adh) = (rep.to_f64(), adh.to_f64());
            let want = n.scale(rep - adh);
            let tol = 2e-6 * (rep + adh) + 8.0 * unit;
            let err = load.force.map(|x| x.to_f64()) - want;
            assert!(
                err.x.abs().max(err.y.abs()).max(err.z.abs()) <= tol,
                "force at δ {delta}: {:?} vs {want:?}",
                load.force
            );
            assert_eq!((load.torque_i, load.torque_j), (Vec3::ZERO, Vec3::ZERO));
            let lever = r - delta / 2.0;
            let roll = 0.346 * rep * lever;
            assert!((load.roll_i.to_f64() - roll).abs() <= 2e-6 * roll + 8.0 * unit * lever);
            assert_eq!(load.roll_i, load.roll_j);
            let vc = v - (wi.scale(lever) + wj.scale(lever)).cross(n);
            let vt = vc - n.scale(vc.dot(n));
            let want_hist = d0 - n.scale(d0.dot(n)) + vt.scale(dt);
            let e = hist.map(|x| x.to_f64()) - want_hist;
            assert!(
                e.x.abs().max(e.y.abs()).max(e.z.abs()) <= 12.0 * unit,
                "history at δ {delta}"
            );
        }
        let near = match super::super::jkr::attached_force(
            fx(0.9 * d_min),
            fx(r_star),
            p.jkr_c,
            p.four_thirds_e_star,
            p.jkr_adhesion,
            FxFast::ZERO,
        ) {
            Some(Neck::Held(_, _, x)) => x,
            other => panic!("{other:?}"),
        };
        let (load, hist, root) = at(1.001 * d_min, near).expect("a broken neck is evaluated");
        assert_eq!(
            (load, hist, root),
            (FusedLoad::default(), Vec3::ZERO, FxFast::ZERO)
        );
        assert!(
            at(0.5 * d_min, FxFast::ZERO).is_none(),
            "no last root: not attached"
        );
    }
}
