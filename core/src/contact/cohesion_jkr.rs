//! Full JKR cohesion (Johnson, Kendall & Roberts, Proc. R. Soc. Lond. A 324 (1971) 301–313),
//! with the work of adhesion Γ (J/m², "surface energy" of the pair). In the form of Johnson,
//! *Contact Mechanics* (1985) §5.5, for contact radius a:
//!
//!   F(a) = 4E*a³/(3R*) − √(8πΓE*·a³),   δ(a) = a²/R* − √(2πΓa/E*),
//!
//! with δ the overlap and F the normal force (positive repulsive). Consequences used below:
//! - pull-off (largest tensile force, under force control) F_c = 1.5·π·Γ·R*, at
//!   a³ = 9πΓR*²/(8E*);
//! - the contact, once made, holds down to a negative overlap δ_min = −3·a_m²/R* with
//!   a_m³ = πΓR*²/(8E*), i.e. δ_min = −(3/4)(π²Γ²R*/E*²)^{1/3} (the JKR separation, under
//!   displacement control); at δ = 0 it still pulls with (8/9)F_c;
//! - bodies approaching snap into contact at δ = 0 (Thornton & Yin 1991's DEM form): the
//!   loading/unloading hysteresis dissipates energy.
//!
//! **Solving for a.** With x = √a the overlap relation is g(x) = x⁴ − cR*·x − R*δ = 0,
//! c = √(2πΓ/E*). g is convex, so Newton's method started right of the largest root falls
//! monotonically onto it; the start max(2x_m, (2R*δ)^{1/4}) is such a point (x_m³ = cR*/4,
//! where g′ = 0). x_m itself is a Newton cube root from a start above it. Both loops run a
//! bounded number of iterations and stop on the first non-decreasing step, in integer
//! arithmetic: deterministic, and accurate to the last few raw units except next to δ_min
//! (a double root, linear convergence), where the force is still within 1e-4 of F_c.
//!
//! **Pipeline.** The term runs right after [`super::HertzNormal`] and replaces its force by
//! the JKR repulsive part 4E*a³/(3R*); the adhesive part √(8πΓE*a³) goes into
//! [`ContactForce::attraction`] and is subtracted after friction and rolling, so (as with
//! SJKR) the Coulomb limit and rolling torque see the repulsive part only (Thornton's
//! Fn + 2F_c friction load is of the same kind).
//!
//! **Where it runs.** A pair whose other terms are the base law's takes the fused law
//! ([`super::fused::jkr`]: the same split of the force, in the fast arithmetic, with a
//! cheaper Newton start) while its overlap is positive; this term evaluates the neck held
//! beyond touching, and every contact of a pair with other optional effects.
//!
//! **Simplifications.** Sphere–sphere contacts hold to δ_min (the narrow phase keeps an
//! attached pair while its gap is below [`CohesionJkr::reach`]; the Verlet skin R_max/8 is far
//! larger than any JKR separation of interest, 7 µm for Γ = 0.1 J/m², E* = 10 MPa,
//! R* = 1 m). Wall contacts are detected only while they overlap, so against a wall the
//! contact breaks at δ = 0, where the pull is (8/9)F_c. While δ < 0, Hertz, the dampers and
//! the tangential spring see a zero contact radius: only the JKR force acts across the neck.

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// J/m² (= N/m) to N/mm.
const N_PER_MM_PER_J_M2: f64 = 1.0e-3;
/// Largest R*, mm, for which [`CohesionJkr::reach`] bounds the JKR separation (1 m).
pub const REACH_MAX_R_STAR_MM: f64 = 1000.0;
/// Newton iterations allowed (each loop stops earlier, on the first non-decreasing step;
/// next to the double root at δ_min convergence halves the error per step).
const MAX_NEWTON: usize = 48;

/// Full JKR cohesion. Off value: Γ = 0 (`on = false`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CohesionJkr<S> {
    /// Whether the term is active.
    pub on: bool,
    /// c = √(2πΓ/E*), √mm.
    pub c: S,
    /// (4/3)·E*, MPa.
    pub four_thirds_e_star: S,
    /// √(8πΓE*), N/mm^{3/2}: the adhesive force is this·a^{3/2}.
    pub adhesion_coef: S,
    /// Upper bound of the JKR separation |δ_min|, mm, for R* ≤ [`REACH_MAX_R_STAR_MM`]: the
    /// narrow phase keeps an attached sphere pair while its gap is below this.
    pub reach: S,
}

impl<S: Scalar> CohesionJkr<S> {
    /// Build from the work of adhesion Γ, J/m² (≥ 0), and E*, MPa.
    pub fn new(work_of_adhesion_j_m2: f64, e_star_mpa: f64) -> Self {
        let pi = core::f64::consts::PI;
        let g = work_of_adhesion_j_m2 * N_PER_MM_PER_J_M2;
        let reach =
            0.75 * libm::cbrt(pi * pi * g * g * REACH_MAX_R_STAR_MM / (e_star_mpa * e_star_mpa));
        CohesionJkr {
            on: work_of_adhesion_j_m2 > 0.0,
            c: S::from_f64(libm::sqrt(2.0 * pi * g / e_star_mpa)),
            four_thirds_e_star: S::from_f64(4.0 / 3.0 * e_star_mpa),
            adhesion_coef: S::from_f64(libm::sqrt(8.0 * pi * g * e_star_mpa)),
            reach: S::from_f64(reach),
        }
    }

    /// JKR normal force split as (repulsive 4E*a³/(3R*), adhesive √(8πΓE*a³)), N, at overlap
    /// `delta` (mm, may be negative) and R* `r_star` (mm); `None` beyond the separation
    /// (δ < δ_min): the contact has broken.
    pub fn force(&self, delta: S, r_star: S) -> Option<(S, S)> {
        let cr = self.c * r_star;
        let xm = cbrt(cr.mul_pow2(-2));
        let xm2 = xm * xm;
        let delta_min = -(xm2 * xm2).mul_int(3) / r_star;
        if delta < delta_min {
            return None;
        }
        let rd = r_star * delta;
        let mut x = xm.mul_int(2);
        if rd > S::ZERO {
            x = x.max(rd.mul_int(2).sqrt().sqrt());
        }
        let x = newton_from_right(x, cr, rd);
        let x3 = x * x * x;
        Some((
            self.four_thirds_e_star * (x3 * x3) / r_star,
            self.adhesion_coef * x3,
        ))
    }
}

/// The root of g(x) = x⁴ − `cr`·x − `rd` (module docs) by Newton's method from `x`, a point
/// right of it: g is convex there, so the iterates fall monotonically onto the root; the loop
/// stops on the first non-decreasing step (or after [`MAX_NEWTON`]).
#[inline(always)]
fn newton_from_right<S: Scalar>(x: S, cr: S, rd: S) -> S {
    newton_until(x, cr, rd, |_, _, _| false)
}

/// [`newton_from_right`]'s loop, which also stops before a step where `close(x, g, g′)`
/// says the root is near enough (the fused law's [`crate::contact::fused::jkr`]).
#[inline(always)]
pub(crate) fn newton_until<S: Scalar>(
    mut x: S,
    cr: S,
    rd: S,
    close: impl Fn(S, S, S) -> bool,
) -> S {
    for _ in 0..MAX_NEWTON {
        let x2 = x * x;
        let g = x2 * x2 - cr * x - rd;
        let gp = (x2 * x).mul_int(4) - cr;
        if g <= S::ZERO || gp <= S::ZERO || close(x, g, gp) {
            break;
        }
        let step = g / gp;
        if step <= S::ZERO {
            break;
        }
        x -= step;
    }
    x
}

/// Cube root of y ≥ 0 by Newton's method from above (t³ is convex for t > 0): the start
/// y^{1/4} (y < 1) or y^{1/2} (y ≥ 1) is ≥ y^{1/3}.
pub(crate) fn cbrt<S: Scalar>(y: S) -> S {
    if y <= S::ZERO {
        return S::ZERO;
    }
    let mut t = if y < S::ONE {
        y.sqrt().sqrt()
    } else {
        y.sqrt()
    };
    for _ in 0..MAX_NEWTON {
        let t2 = t * t;
        let step = (t2 * t - y) / t2.mul_int(3);
        if step <= S::ZERO {
            break;
        }
        t -= step;
    }
    t
}

impl<S: Scalar> ContactTerm<S> for CohesionJkr<S> {
    #[inline(always)]
    fn apply(
        &self,
        k: &ContactKinematics<S>,
        state: &mut ContactState<S>,
        out: &mut ContactForce<S>,
    ) {
        if !self.on {
            return;
        }
        // The Hertz term's force (zero across a neck, where the contact radius is zero).
        let hertz = self.four_thirds_e_star * (k.contact_radius * k.overlap);
        match self.force(k.overlap, k.r_star) {
            Some((rep, adh)) => {
                state.jkr_attached = true;
                out.normal += rep - hertz;
                out.attraction += adh;
            }
            None => {
                state.jkr_attached = false;
                out.normal -= hertz;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;
    use core::f64::consts::PI;

    // Γ 0.1 J/m², E* 10 MPa, R* 2 mm (two 4 mm spheres).
    const GAMMA: f64 = 0.1;
    const ES: f64 = 10.0;
    const R: f64 = 2.0;

    /// The analytic curve, parametrised by a (mm): (δ, F), Johnson 1985 §5.5.
    fn analytic(a: f64) -> (f64, f64) {
        let g = GAMMA * 1e-3;
        (
            a * a / R - (2.0 * PI * g * a / ES).sqrt(),
            4.0 * ES * a.powi(3) / (3.0 * R) - (8.0 * PI * g * ES * a.powi(3)).sqrt(),
        )
    }

    #[test]
    fn force_overlap_curve_matches_jkr() {
        // Along the stable branch (a from 1.01·a_m to 3·a_0), F from the term at the analytic
        // δ(a) equals the analytic F(a) within 2e-5·F_c. Next to the fold at a_m (δ_min),
        // dF/dδ is infinite, so the quantisation of δ itself (2.3e-10 mm) moves F by more:
        // at a = 1.0001·a_m within 5e-4·F_c.
        let t = CohesionJkr::<Fx>::new(GAMMA, ES);
        let g = GAMMA * 1e-3;
        let fc = 1.5 * PI * g * R;
        let a_m = (PI * g * R * R / (8.0 * ES)).cbrt();
        let a0 = (9.0 * PI * g * R * R / (2.0 * ES)).cbrt();
        let err = |a: f64| {
            let (d, f) = analytic(a);
            let (rep, adh) = t.force(Fx::from_f64(d), Fx::from_f64(R)).expect("attached");
            ((rep - adh).to_f64() - f).abs() / fc
        };
        let mut worst = 0.0f64;
        for i in 0..=200 {
            worst = worst.max(err(1.01 * a_m + (3.0 * a0 - 1.01 * a_m) * i as f64 / 200.0));
        }
        assert!(worst < 2e-5, "worst |ΔF|/F_c {worst:e}");
        let fold = err(1.0001 * a_m);
        assert!(fold < 5e-4, "at the fold |ΔF|/F_c {fold:e}");
        // At δ = 0 the pull is (8/9)·F_c.
        let (rep, adh) = t.force(Fx::ZERO, Fx::from_f64(R)).unwrap();
        assert!(((adh - rep).to_f64() / fc - 8.0 / 9.0).abs() < 1e-6);
    }

    #[test]
    fn pull_off_and_separation() {
        // Largest tensile force over the attached range = 1.5πΓR* (within 1e-5 relative, the
        // grid step); the contact breaks just beyond δ_min = −(3/4)(π²Γ²R*/E*²)^{1/3}.
        let t = CohesionJkr::<Fx>::new(GAMMA, ES);
        let g = GAMMA * 1e-3;
        let fc = 1.5 * PI * g * R;
        let d_min = -0.75 * (PI * PI * g * g * R / (ES * ES)).cbrt();
        let mut most = 0.0f64;
        for i in 0..=2000 {
            let d = d_min * (1.0 - i as f64 / 2000.0) * 0.999_999;
            let (rep, adh) = t.force(Fx::from_f64(d), Fx::from_f64(R)).unwrap();
            most = most.max((adh - rep).to_f64());
        }
        assert!((most / fc - 1.0).abs() < 1e-5, "{most} vs {fc}");
        assert!(t
            .force(Fx::from_f64(d_min * 1.0001), Fx::from_f64(R))
            .is_none());
        assert!(t
            .force(Fx::from_f64(d_min * 0.9999), Fx::from_f64(R))
            .is_some());
        assert!(t.reach.to_f64() >= -d_min);
    }
}
