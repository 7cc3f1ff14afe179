//! JKR cohesion inside the fused law: the normal force of a contact of a pair with JKR
//! cohesion, touching (overlap δ > 0, [`force`]) or held across a neck (δ ≤ 0, [`attached_force`]),
//! split as the checked term [`crate::contact::CohesionJkr`] splits it (Johnson, *Contact
//! Mechanics* (1985) §5.5):
//!
//!   repulsive 4E*a³/(3R*), adhesive √(8πΓE*·a³),  a the root of δ = a²/R* − √(2πΓa/E*).
//!
//! The term's algorithm with a cheaper start: with x = √a, Newton's method on the convex
//! g(x) = x⁴ − cR*·x − R*δ (c = √(2πΓ/E*)) from a point right of its root, stopping on the
//! first non-decreasing step. The term starts from max(2x_m, (2R*δ)^{1/4}) (x_m³ = cR*/4,
//! where g′ = 0), which costs a cube root (a Newton loop of its own) and lies far from the
//! root of a compressed contact; here the start is the contact's root at its last step (kept
//! in its effect history: one or two Newton steps then converge), else one Newton step from
//! Hertz's root (R*δ)^{1/4} ([`start`]). The repulsive force is formed at the root as
//! (4/3)E*·x²·(δ + c·x), without the term's division by R* ([`split`]). Every operation is the
//! fast arithmetic ([`Envelope`]), whose roots are the coarse ones (2^-28): the force differs
//! from the term's in the last bits, and the contact is the fused law's (module docs of
//! [`super`]).
//!
//! Envelope (fixed point): δ < 2^[`super::REACH_BITS`] mm and R* < 2^[`super::LENGTH_BITS`] mm
//! (checked by the caller), c < 2^[`JKR_C_BITS`] √mm and √(8πΓE*) < 2^[`JKR_ADHESION_BITS`]
//! (checked when the pair is fused). Then cR* < 2^9, R*δ < 2^11 and x_m < 2^2.4, and the root
//! lies below the term's start, 2^3.4. A start is a point right of the root: the term's start,
//! a point below 2^4 taken as it is (the last root is used only below 2^4), or a Newton step
//! from a point p below 2^4 taken only up to 2p; so the start and every iterate x < 2^5:
//! x⁴ < 2^20, cR*·x < 2^14 and 4x³ < 2^17. At the root, a³ = x⁶ < 2^20.4 and the adhesive
//! force is below 2^26.2 N. The products that can leave the range, (4/3)E*·x² (< 2^29), its
//! product with δ + c·x (< 2^10) and the adhesive one, are tested exactly
//! ([`Envelope::mul_within`]). A Newton quotient that overflows next to x_m is the poison,
//! which is negative and ends the loop. A neck's overlap lies between δ_min and 0, far inside
//! the bound on |δ|.
//!
//! ```
//! use arachis_core::contact::fused::jkr::force;
//! // Γ 0.1 J/m², E* 10 MPa, R* 2 mm: at δ = 0.01 mm the pair pushes back less than Hertz.
//! let (g, es, r, delta) = (0.1e-3, 10.0, 2.0, 0.01);
//! let pi = core::f64::consts::PI;
//! let (c, adhesion) = ((2.0 * pi * g / es).sqrt(), (8.0 * pi * g * es).sqrt());
//! let (rep, adh, x) = force(delta, r, c, 4.0 / 3.0 * es, adhesion, 0.0).unwrap();
//! let hertz = 4.0 / 3.0 * es * (r * delta).sqrt() * delta;
//! assert!(rep - adh < hertz && rep > hertz);
//! // Started from that root, the next step finds the same force.
//! let (rep2, _, _) = force(delta, r, c, 4.0 / 3.0 * es, adhesion, x).unwrap();
//! assert!((rep2 - rep).abs() < 1e-12 * rep);
//! ```

use super::{FORCE_BITS, PRODUCT_BITS};
use crate::contact::cohesion_jkr::{cbrt, newton_until};
use crate::num::Envelope;

/// JKR's c = √(2πΓ/E*) below 2^JKR_C_BITS √mm for the fused law (Γ = 1 J/m² with
/// E* = 0.4 MPa is c ≈ 0.13).
pub const JKR_C_BITS: i32 = 4;
/// √(8πΓE*) below 2^JKR_ADHESION_BITS N/mm^{3/2} for the fused law (Γ = 1 J/m² on steel,
/// E* ≈ 1.1e5 MPa, is ≈ 53).
pub const JKR_ADHESION_BITS: i32 = 16;

/// Whether the fast arithmetic's magnitude tests apply (fixed point only, as in [`super`]).
#[inline(always)]
fn bounded<T: Envelope>() -> bool {
    T::Q32_32
}

/// The JKR normal force (repulsive, adhesive), N, of a touching contact, and the root x = √a
/// (√mm) it found: overlap `delta` (mm, > 0), R* `r_star` (mm, > 0), the pair's c (√mm),
/// (4/3)E* `kn` (MPa) and √(8πΓE*) `adhesion` (N/mm^{3/2}); `last_root`, the root of the
/// contact's last step (0: none), is where Newton's method starts if it can ([`start`]).
/// `None` outside the envelope (module docs).
#[inline(always)]
pub fn force<T: Envelope>(
    delta: T,
    r_star: T,
    c: T,
    kn: T,
    adhesion: T,
    last_root: T,
) -> Option<(T, T, T)> {
    match attached_force(delta, r_star, c, kn, adhesion, last_root)? {
        Neck::Held(rep, adh, x) => Some((rep, adh, x)),
        Neck::Broken => None,
    }
}

/// What [`attached_force`] finds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Neck<T> {
    /// The contact holds: (repulsive, adhesive) N and the root x = √a, √mm, as [`force`]
    /// gives them.
    Held(T, T, T),
    /// The overlap is below the JKR separation δ_min = −3x_m⁴/R*: the contact has broken.
    Broken,
}

/// The JKR force of an attached contact, touching (as [`force`], whose arguments it takes)
/// or held across its neck at `delta` ≤ 0 mm (`last_root` > 0, the root of its last step):
/// [`Neck::Held`] while g(x) = x⁴ − cR*·x − R*δ has a root (always, for δ > 0),
/// [`Neck::Broken`] beyond δ_min, where it has none. The test needs no cube root: started
/// right of the largest root, Newton's iterates stay right of it, where g′ > 0 and a step
/// is shorter than x; without a root they run past the fold x_m (g′ ≤ 0) or step further
/// than x (next to the fold). The checked term ([`crate::contact::CohesionJkr::force`])
/// compares δ with its δ_min instead; the two can differ only within a few units of δ_min.
/// `None` outside the envelope.
#[inline(always)]
pub fn attached_force<T: Envelope>(
    delta: T,
    r_star: T,
    c: T,
    kn: T,
    adhesion: T,
    last_root: T,
) -> Option<Neck<T>> {
    let cr = c * r_star;
    let rd = r_star * delta;
    let x = newton_to_precision(start(cr, rd, last_root), cr, rd);
    if rd <= T::ZERO {
        let x2 = x * x;
        let g = x2 * x2 - cr * x - rd;
        let gp = (x2 * x).mul_int(4) - cr;
        if gp <= T::ZERO || g > x * gp {
            return Some(Neck::Broken);
        }
    }
    let (rep, adh, x) = split(x, delta, c, kn, adhesion)?;
    Some(Neck::Held(rep, adh, x))
}

/// The force split at the root x = √a: repulsive (4/3)E*·a³/R* = (4/3)E*·x²·(δ + c·x), since
/// the root has a²/R* = δ + c·√a (g(x) = 0 over R*), which needs no division and carries x's
/// relative error at most four times (x⁶/R* six times); adhesive √(8πΓE*)·x³.
#[inline(always)]
fn split<T: Envelope>(x: T, delta: T, c: T, kn: T, adhesion: T) -> Option<(T, T, T)> {
    let (k_a, k_in) = kn.mul_within(x * x, PRODUCT_BITS);
    let (rep, rep_in) = k_a.mul_within(delta + c * x, FORCE_BITS);
    let (adh, adh_in) = adhesion.mul_within(x * x * x, FORCE_BITS);
    if bounded::<T>() && !(k_in & rep_in & adh_in) {
        return None;
    }
    Some((rep, adh, x))
}

/// A Newton start right of the root of g(x) = x⁴ − cR*·x − R*δ (`cr` = cR*, `rd` = R*δ > 0),
/// the first of these that applies:
/// - the last step's root `last` (> 0): a contact's overlap changes little in a step, so it
///   lies next to the new root; taken as it is where g(last) ≥ 0, else after one Newton step;
/// - one Newton step from Hertz's root h = (R*δ)^{1/4}, where g(h) = −cR*·h < 0, close to the
///   root on a compressed contact, with no cube root;
/// - the checked term's start max(2x_m, (2R*δ)^{1/4}), x_m³ = cR*/4 (an overlap small beside
///   the adhesion, h near x_m).
///
/// A Newton step from a point p left of the root (g(p) < 0, g′(p) > 0) lands right of it,
/// since g is convex; it is taken only when it moves right by at most p, so that the start
/// stays below 2p.
#[inline(always)]
fn start<T: Envelope>(cr: T, rd: T, last: T) -> T {
    // The last root, where it is inside the iterates' bound (module docs).
    if last > T::ZERO && (!bounded::<T>() || last.within(LAST_ROOT_BITS)) {
        if let Some(x) = step_right(last, cr, rd) {
            return x;
        }
    }
    // 2x_m, right of every root (a cube root: only where the starts above do not apply).
    let twice_fold = || cbrt(cr.mul_pow2(-2)).mul_int(2);
    if rd <= T::ZERO {
        // A neck without a usable last root: no Hertz root at δ ≤ 0.
        return twice_fold();
    }
    let h = rd.sqrt().sqrt();
    if let Some(x) = step_right(h, cr, rd) {
        return x;
    }
    twice_fold().max(rd.mul_int(2).sqrt().sqrt())
}

/// Newton's method on g from `x`, a point right of its root, as the checked term's loop
/// ([`crate::contact::cohesion_jkr`]) runs it, but it also stops once the next step would move
/// x by at most 2^-[`NEWTON_STOP_BITS`] of itself: g ≤ 2^-k·x·g′, tested before the division
/// the step costs. Why: from the last step's root the first step already lands that close
/// (Newton's error squares), and the term's loop spent one or two more 128-bit divisions
/// finding that the root had not moved. Since g is convex the iterates stay right of the
/// root, so the root lies within that fraction below the x returned; a₃ = x⁶ is then off by
/// at most 6·2^-k of itself, the adhesive force (∝ x³) by 3·2^-k.
#[inline(always)]
fn newton_to_precision<T: Envelope>(x: T, cr: T, rd: T) -> T {
    // x·g′ < 2^5·2^17 inside the envelope (module docs).
    newton_until(x, cr, rd, |x, g, gp| {
        g <= (x * gp).mul_pow2(-NEWTON_STOP_BITS)
    })
}

/// The Newton loop stops once its step would be below 2^-NEWTON_STOP_BITS of x
/// ([`newton_to_precision`]): the repulsive force is then within 6·2^-24 = 3.6e-7 of itself.
pub const NEWTON_STOP_BITS: i32 = 24;

/// Iterates below 2^LAST_ROOT_BITS √mm: a last root beyond (none is, module docs) is not
/// used as a start.
const LAST_ROOT_BITS: i32 = 4;

/// `p` itself if g(p) ≥ 0 (right of the root, or on it), else the Newton step from `p` if
/// g′(p) > 0 and it moves right by at most `p` (module docs of [`start`]); `None` otherwise
/// (in fixed point a quotient that overflowed is the poison, which is refused too).
#[inline(always)]
fn step_right<T: Envelope>(p: T, cr: T, rd: T) -> Option<T> {
    let p3 = p * p * p;
    let g = p3 * p - cr * p - rd;
    let slope = p3.mul_int(4) - cr;
    if slope <= T::ZERO {
        return None;
    }
    if g >= T::ZERO {
        return Some(p);
    }
    let step = g / slope;
    (step < T::ZERO && step + p >= T::ZERO).then(|| p - step)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::CohesionJkr;
    use crate::num::{Fx, FxFast, Scalar};
    use core::f64::consts::PI;

    /// Relative tolerance against the analytic curve: x converges to a few units of its last
    /// place (Q.32), which a³ carries to about 1e-8; the Q.32 quantisation of δ moves a by
    /// δq/(2δ) at most (2.3e-10 mm over δ ≥ 1e-5 mm), so 1e-5 with margin.
    const CURVE_RELATIVE: f64 = 1e-5;
    /// Relative tolerance of fixed point against f64 on the same inputs, besides the root's
    /// conditioning ([`G_UNITS`]): the coarse roots (2^-28) move only the Newton start, and
    /// the products round to Q.32.
    const RELATIVE: f64 = 1e-6;
    /// Units of Q.32 (2^-32) to which fixed point evaluates g(x) = x⁴ − cR*·x − R*δ (three
    /// rounded terms): Newton stops where g is zero to within them, so x is off by up to
    /// G_UNITS·2^-32/g′(x), which a³ = x⁶ carries sixfold and x³ threefold. On a small soft
    /// contact (δ 1e-4 mm, g′ 2e-3) that is 1e-5 of the force.
    const G_UNITS: f64 = 4.0;
    /// Absolute part, N: a dozen Q32.32 units.
    const ABSOLUTE_N: f64 = 3e-9;

    /// The pair constants as the checked term quantises them: (c, (4/3)E*, √(8πΓE*)).
    fn constants(gamma: f64, es: f64) -> (Fx, Fx, Fx) {
        let t = CohesionJkr::<Fx>::new(gamma, es);
        (t.c, t.four_thirds_e_star, t.adhesion_coef)
    }

    /// Along the touching part of the stable branch (a from where δ = 0 up to 3a₀), the fast
    /// force at the analytic δ(a) against the analytic split 4E*a³/(3R*), √(8πΓE*a³) (Johnson
    /// 1985 §5.5), in fixed point and in f64, for Γ 0.1–2 J/m², E* 1–1000 MPa, R* 0.5–20 mm.
    #[test]
    fn matches_the_analytic_jkr_curve() {
        let mut n = 0;
        for &gamma in &[0.1, 2.0] {
            for &es in &[1.0, 10.0, 1000.0] {
                let (c, kn, adhesion) = constants(gamma, es);
                let g = gamma * 1e-3;
                for &r in &[0.5, 4.0, 20.0] {
                    // δ(a) = a²/R − √(2πΓa/E*) is zero at a_z = (2πΓR²/E*)^{1/3}.
                    let a_z = libm::cbrt(2.0 * PI * g * r * r / es);
                    let a0 = libm::cbrt(9.0 * PI * g * r * r / (2.0 * es));
                    for k in 1..=60 {
                        let a = a_z * (1.0 + 1e-3) + (3.0 * a0 - a_z) * k as f64 / 60.0;
                        let delta = a * a / r - libm::sqrt(2.0 * PI * g * a / es);
                        if delta < 1e-5 {
                            continue;
                        }
                        let rep = 4.0 * es * a * a * a / (3.0 * r);
                        let adh = libm::sqrt(8.0 * PI * g * es * a * a * a);
                        let fx = |x: f64| FxFast::from_f64(x);
                        let zero = FxFast::ZERO;
                        let got =
                            force(fx(delta), fx(r), c.into(), kn.into(), adhesion.into(), zero)
                                .expect("inside the envelope");
                        let got64 =
                            force(delta, r, c.to_f64(), kn.to_f64(), adhesion.to_f64(), 0.0)
                                .expect("f64 has no envelope");
                        for (name, g, w) in [
                            ("repulsive", got.0.to_f64(), rep),
                            ("adhesive", got.1.to_f64(), adh),
                            ("repulsive f64", got64.0, rep),
                            ("adhesive f64", got64.1, adh),
                        ] {
                            assert!(
                                (g - w).abs() <= CURVE_RELATIVE * w + ABSOLUTE_N,
                                "{name}: Γ {gamma} E* {es} R* {r} a {a}: {g} vs {w}"
                            );
                        }
                        n += 1;
                    }
                }
            }
        }
        assert!(n > 500, "only {n} points");
    }

    /// Fixed point against f64 on the same quantised inputs over a grid of pairs and
    /// overlaps (δ from 1e-6 to 5 % of R*), started cold and from the roots of a last step
    /// 0.1 % more and less compressed; and the checked term's split (forces above 1e-3 N),
    /// whose own x⁶ is one more Q.32 rounding.
    #[test]
    fn fixed_point_agrees_with_f64_and_the_checked_term() {
        let mut n = 0;
        for &gamma in &[0.01, 0.1, 2.0] {
            for &es in &[1.0, 10.0, 1000.0] {
                let term = CohesionJkr::<Fx>::new(gamma, es);
                let (c, kn, adhesion) = constants(gamma, es);
                for &r in &[0.5, 2.0, 4.0, 20.0] {
                    for k in 0..40 {
                        let delta = r * 1e-6 * libm::pow(5e4, k as f64 / 39.0);
                        let (d, rs) = (Fx::from_f64(delta), Fx::from_f64(r));
                        let fast = |d: Fx, last: FxFast| {
                            force::<FxFast>(
                                d.into(),
                                rs.into(),
                                c.into(),
                                kn.into(),
                                adhesion.into(),
                                last,
                            )
                        };
                        let Some(cold) = fast(d, FxFast::ZERO) else {
                            continue;
                        };
                        // Warm starts: the roots of a last step 0.1 % more and less compressed.
                        let last =
                            |f: f64| fast(Fx::from_f64(delta * f), FxFast::ZERO).map(|g| g.2);
                        let warm = [last(1.001), last(0.999)].map(|x| {
                            x.and_then(|x| fast(d, x))
                                .expect("a warm start in the envelope")
                        });
                        let want = force(
                            d.to_f64(),
                            rs.to_f64(),
                            c.to_f64(),
                            kn.to_f64(),
                            adhesion.to_f64(),
                            0.0,
                        )
                        .expect("f64 has no envelope");
                        let (rep, adh) = term.force(d, rs).expect("touching: attached");
                        // The root's conditioning (G_UNITS), from f64's x³ = adhesive/√(8πΓE*).
                        let x3 = want.1 / adhesion.to_f64();
                        let x = libm::cbrt(x3);
                        let slope = 4.0 * x3 - c.to_f64() * rs.to_f64();
                        // And where either Newton loop may stop ([`NEWTON_STOP_BITS`]).
                        let dx_x =
                            G_UNITS * 2f64.powi(-32) / slope / x + 2f64.powi(-NEWTON_STOP_BITS);
                        for got in [cold, warm[0], warm[1]] {
                            for (g, w, power) in
                                [(got.0.to_f64(), want.0, 6.0), (got.1.to_f64(), want.1, 3.0)]
                            {
                                assert!(
                                    (g - w).abs() <= (RELATIVE + power * dx_x) * w + ABSOLUTE_N,
                                    "Γ {gamma} E* {es} R* {r} δ {delta}: {g} vs f64 {w}"
                                );
                            }
                        }
                        for (w, checked, power) in
                            [(want.0, rep.to_f64(), 6.0), (want.1, adh.to_f64(), 3.0)]
                        {
                            // The term rounds x⁶ itself to Q.32: a unit of it times
                            // (4/3)E*/R* more.
                            let x6_unit = kn.to_f64() * 2f64.powi(-32) / rs.to_f64();
                            if w > 1e-3 {
                                assert!(
                                    (checked - w).abs()
                                        <= (CURVE_RELATIVE + power * dx_x) * w + x6_unit,
                                    "Γ {gamma} E* {es} R* {r} δ {delta}: term {checked} vs {w}"
                                );
                            }
                        }
                        n += 1;
                    }
                }
            }
        }
        assert!(n > 1000, "only {n} contacts inside the envelope");
    }

    /// Across a neck, δ from 0 down to the JKR separation δ_min = −(3/4)(π²Γ²R*/E*²)^{1/3}
    /// (Johnson 1985 §5.5), the neck's force against the checked term's at the same quantised
    /// δ, started from the root of a step 0.1 % less stretched: within the root's
    /// conditioning ([`G_UNITS`] over g′, which vanishes at the fold, so the check stops
    /// 1 % short of it) and the Newton stop, six and three times over. At 1.0001·δ_min the
    /// neck has broken, at 0.9999·δ_min it holds, as the term says.
    #[test]
    fn a_neck_holds_as_the_checked_term_and_breaks_at_the_jkr_separation() {
        let mut n = 0;
        for &gamma in &[0.1, 2.0] {
            for &es in &[1.0, 10.0, 1000.0] {
                let term = CohesionJkr::<Fx>::new(gamma, es);
                let (c, kn, adhesion) = constants(gamma, es);
                let g = gamma * 1e-3;
                for &r in &[0.5, 4.0, 20.0] {
                    let d_min = -0.75 * libm::cbrt(PI * PI * g * g * r / (es * es));
                    let rs = Fx::from_f64(r);
                    let neck = |d: f64, last: FxFast| {
                        attached_force::<FxFast>(
                            Fx::from_f64(d).into(),
                            rs.into(),
                            c.into(),
                            kn.into(),
                            adhesion.into(),
                            last,
                        )
                        .expect("inside the envelope")
                    };
                    let root_at = |d: f64| match neck(d, FxFast::ZERO) {
                        Neck::Held(_, _, x) => x,
                        Neck::Broken => panic!("broken at {d} (δ_min {d_min})"),
                    };
                    for k in 0..=40 {
                        let delta = 0.99 * d_min * k as f64 / 40.0;
                        let last = root_at(delta * 0.999);
                        let Neck::Held(rep, adh, _) = neck(delta, last) else {
                            panic!("Γ {gamma} E* {es} R* {r}: broken at δ {delta}, δ_min {d_min}");
                        };
                        let (want_rep, want_adh) =
                            term.force(Fx::from_f64(delta), rs).expect("the term holds");
                        let x3 = want_adh.to_f64() / adhesion.to_f64();
                        let slope = 4.0 * x3 - c.to_f64() * r;
                        let dx_x = G_UNITS * 2f64.powi(-32) / slope / libm::cbrt(x3)
                            + 2f64.powi(-NEWTON_STOP_BITS);
                        let x6_unit = kn.to_f64() * 2f64.powi(-32) / r;
                        for (name, got, want, power) in [
                            ("repulsive", rep.to_f64(), want_rep.to_f64(), 6.0),
                            ("adhesive", adh.to_f64(), want_adh.to_f64(), 3.0),
                        ] {
                            let tol = (RELATIVE + power * dx_x) * want + x6_unit + ABSOLUTE_N;
                            assert!(
                                (got - want).abs() <= tol,
                                "{name}: Γ {gamma} E* {es} R* {r} δ {delta}: {got} vs term {want}"
                            );
                        }
                        n += 1;
                    }
                    let near = root_at(0.99 * d_min);
                    assert_eq!(
                        neck(1.0001 * d_min, near),
                        Neck::Broken,
                        "Γ {gamma} E* {es} R* {r}"
                    );
                    assert!(term.force(Fx::from_f64(1.0001 * d_min), rs).is_none());
                    assert!(matches!(neck(0.9999 * d_min, near), Neck::Held(..)));
                    assert!(term.force(Fx::from_f64(0.9999 * d_min), rs).is_some());
                }
            }
        }
        assert!(n > 500, "only {n} necks");
    }
}
