//! The contact law, as composable terms (DESIGN §2, §6; seed 000 eqs. (1)–(7)).
//!
//! Each physical effect is a separate struct implementing [`ContactTerm`], with its own
//! parameters and an "off" value, held per material pair in [`crate::pair::PairParams`]:
//!
//! | stage | term | file | formula |
//! |---|---|---|---|
//! | normal | [`HertzNormal`] | `hertz_normal.rs` | Fn = (4/3)E*·a·α, a = √(R*α) (eq. 3) |
//! | normal | [`NormalDamping`] | `normal_damping.rs` | Fn_d = −2√(5/6)β√(Sn m*)·vn, Sn = 2E*a (eq. 4) |
//! | clip | [`clip_normal`] | `mod.rs` | Fn ← max(Fn, 0): **no attractive normal force** |
//! | tangential | [`MindlinTangential`] | `mindlin_tangential.rs` | Ft = −St·δt, St = 8G*a (eq. 5) |
//! | tangential | [`TangentialDamping`] | `tangential_damping.rs` | Ft_d = −2√(5/6)β√(St m*)·vt (eq. 6) |
//! | tangential | [`CoulombLimit`] | `coulomb.rs` | \|Ft\| ≤ μs·Fn, history rescaled |
//! | rolling | [`RollingCdt`] | `rolling_cdt.rs` | T = −μr·Fn·Ri·ω̂i (eq. 7, EDEM CDT) |
//! | rolling (LIGGGHTS convention) | [`RollingCdtLiggghts`] | `rolling_cdt_liggghts.rs` | T_j = −T_i = μr·F_el·R*·ŵ_t, ŵ the unit of ωi − ωj (LIGGGHTS `rolling_friction cdt`) |
//! | rolling (LIGGGHTS convention) | [`RollingEpsd2Liggghts`] | `rolling_epsd2_liggghts.rs` | M ← M + k_t·R*²·dt·ω_t, \|M\| ≤ μr·Fn·R*, T_j = −T_i = M (LIGGGHTS `rolling_friction epsd2`) |
//! | normal (optional) | [`ViscoelasticNormal`] | `viscoelastic_normal.rs` | Fn_v = −(4/3)E*·A·a·vn (Brilliantov 1996), before the clip |
//! | normal (optional) | [`CohesionJkr`] | `cohesion_jkr.rs` | replaces Hertz by 4E*a³/(3R*), a from δ = a²/R* − √(2πΓa/E*) (JKR 1971); adhesive part below |
//! | normal (optional) | [`HystereticNormal`] | `hysteretic_normal.rs` | unloading F_max((α−λα_max)/(α_max−λα_max))^{3/2} (after Walton & Braun 1986) |
//! | rolling (optional) | [`RollingEpsd`] | `rolling_epsd.rs` | T_j = k_r·θr + C_r·ω_r, \|k_r·θr\| ≤ μr·R*·Fn, k_r = 2.25·(2E*a)·μr²R*² (Ai et al. 2011 type C); T_i = −T_j |
//! | cohesion (optional) | [`CohesionSjkr`] | `cohesion_sjkr.rs` | Fc = −k·π·2R*α (SJKR), last, may attract |
//! | cohesion (optional) | [`CohesionJkr`] | `cohesion_jkr.rs` | Fc = −√(8πΓE*a³) (JKR adhesive part), last; pull-off 1.5πΓR*, holds to δ_min < 0 |
//!
//! The optional terms are off by default and switched per pair with
//! [`crate::world::World::set_pair_effects`]; [`crate::effects`] lists them (with air drag, a
//! body force) and shows, with a worked example, how to add an effect of your own.
//!
//! The terms run in that order, so a later effect (cohesion, another rolling law, bonds) is a
//! new struct added to the pair table at the right stage, without touching these.
//!
//! **Attractive force.** The total normal force (elastic + damping) is clipped at ≥ 0: the law
//! never pulls bodies together. With this clip the damping law does not return exactly the
//! input e (Thornton, Cummins & Cleary 2013); the restitution test measures the effective e.
//! The Coulomb limit and the rolling torque both use this clipped total normal force
//! (EDEM convention; LIGGGHTS uses the elastic part only for rolling).
//!
//! **Conventions.** Each pair reads rolling friction and the Coulomb limit as EDEM (the
//! default) or as LIGGGHTS 3.8 does ([`Conventions`], `convention.rs`); the differences, term
//! by term with their sources, are in `docs/conventions.md`.
//!
//! Sign conventions: body i and body j (or a wall, as j); `normal` is the unit vector from i
//! towards j; relative velocity is v_j − v_i at the contact point, so vn = v_rel·n > 0 when
//! separating. Forces in [`ContactForce`] act on j; i receives the opposite.

pub mod cohesion_jkr;
pub mod cohesion_sjkr;
pub mod convention;
pub mod coulomb;
pub mod fused;
pub mod hertz_normal;
pub mod history;
pub mod hysteretic_normal;
pub mod lanes;
pub mod mindlin_tangential;
pub mod normal_damping;
pub mod rolling_cdt;
pub mod rolling_cdt_liggghts;
pub mod rolling_epsd;
pub mod rolling_epsd2_liggghts;
pub mod tangential_damping;
pub mod viscoelastic_normal;

pub use cohesion_jkr::CohesionJkr;
pub use cohesion_sjkr::CohesionSjkr;
pub use convention::{Conventions, FrictionConvention, RollingConvention, UnknownConvention};
pub use coulomb::CoulombLimit;
pub use hertz_normal::HertzNormal;
pub use history::{ContactSlot, ContactState, EffectHistory, NeighbourEntry, WALL_PARTNER_FLAG};
pub use hysteretic_normal::HystereticNormal;
pub use mindlin_tangential::MindlinTangential;
pub use normal_damping::NormalDamping;
pub use rolling_cdt::RollingCdt;
pub use rolling_cdt_liggghts::RollingCdtLiggghts;
pub use rolling_epsd::RollingEpsd;
pub use rolling_epsd2_liggghts::RollingEpsd2Liggghts;
pub use tangential_damping::TangentialDamping;
pub use viscoelastic_normal::ViscoelasticNormal;

use crate::num::{Scalar, Vec3};

/// 2√(5/6): the damping prefactor of seed 000 eqs. (4) and (6).
pub const DAMPING_PREFACTOR: f64 = 1.825_741_858_350_553_7;

/// β = ln e / √(ln²e + π²) (seed 000 eq. (4)); β ≤ 0, and β = 0 for e = 1.
pub fn beta_from_restitution(e: f64) -> f64 {
    let l = libm::log(e);
    l / libm::sqrt(l * l + core::f64::consts::PI * core::f64::consts::PI)
}

/// Geometry and relative motion of one contact, from the narrow phase.
#[derive(Clone, Copy, Debug, Default)]
pub struct ContactKinematics<S> {
    /// Unit normal from body i towards body j (or the wall).
    pub normal: Vec3<S>,
    /// Normal overlap α, mm (> 0), seed 000 eq. (1).
    pub overlap: S,
    /// Contact radius a = √(R*·α), mm (DESIGN §2).
    pub contact_radius: S,
    /// √(a·m*), √(mm·g): shared by both damping terms (zero if no damping term is on).
    pub sqrt_a_mstar: S,
    /// Normal relative velocity vn = (v_j − v_i)·n, mm/ms (> 0 separating).
    pub vn: S,
    /// Tangential relative velocity, mm/ms.
    pub vt: Vec3<S>,
    /// Time step, ms.
    pub dt: S,
    /// Distance from body i's centre of mass to the contact point, mm.
    pub lever_i: S,
    /// Distance from body j's centre of mass to the contact point, mm (0 for a wall).
    pub lever_j: S,
    /// Effective radius R* = RiRj/(Ri+Rj), mm (wall: Ri); only set when a term needs it
    /// ([`crate::pair::PairParams::needs_r_star`]), zero otherwise.
    pub r_star: S,
    /// Relative angular velocity ωi − ωj, rad/ms (wall: ωi); only set when a term needs it
    /// ([`crate::pair::PairParams::needs_relative_spin`]), zero otherwise.
    pub w_rel: Vec3<S>,
    /// Equivalent rolling inertia I_r = [1/(Ii + mi·ri²) + 1/(Ij + mj·rj²)]⁻¹, g·mm²
    /// (Ai et al. 2011 eq. (14); wall: Ii + mi·ri²), ri the lever; only set when the EPSD
    /// rolling term is on, zero otherwise.
    pub rolling_inertia: S,
}

/// Force and rolling torque of one contact, accumulated by the terms.
#[derive(Clone, Copy, Debug, Default)]
pub struct ContactForce<S> {
    /// Normal force on j along `normal`, N (≥ 0 after [`clip_normal`]).
    pub normal: S,
    /// Tangential force on j, N.
    pub tangential: Vec3<S>,
    /// Tangential stiffness St of this step, N/mm (set by [`MindlinTangential`]; used by the
    /// Coulomb history rescale).
    pub tangential_stiffness: S,
    /// Rolling-resistance torque magnitude on body i, N·mm, acting along −ω̂i.
    pub roll_i: S,
    /// Rolling-resistance torque magnitude on body j, N·mm, acting along −ω̂j.
    pub roll_j: S,
    /// Rolling-resistance torque vector on body j, N·mm; i receives the opposite (EPSD and
    /// LIGGGHTS-convention terms).
    pub rolling_torque: Vec3<S>,
    /// Attractive normal force, N (≥ 0), subtracted from `normal` after friction and rolling
    /// (the adhesive part of JKR cohesion).
    pub attraction: S,
}

/// One piece of the contact law. Implementations add to `out` and may update `state`
/// (the contact history); each one has an "off" value in which it does nothing.
pub trait ContactTerm<S: Scalar> {
    /// Add this term's contribution.
    fn apply(
        &self,
        k: &ContactKinematics<S>,
        state: &mut ContactState<S>,
        out: &mut ContactForce<S>,
    );
}

/// Clip the total normal force at zero: the contact law is never attractive. An overflowed
/// force stays as it is (in fixed point its poison is the most negative integer, which the
/// clip would otherwise turn into a silent 0), so the step reports the overflow.
#[inline(always)]
pub fn clip_normal<S: Scalar>(out: &mut ContactForce<S>) {
    if out.normal < S::ZERO && out.normal.is_valid() {
        out.normal = S::ZERO;
    }
}

/// Kinematics for the terms' unit tests: normal +z, overlap `overlap_mm`, contact radius
/// `contact_radius_mm`, dt 1e-3 ms, lever 1 mm on side i; every velocity and the R*, spin
/// and inertia fields zero. Tests set what their term needs with struct-update syntax.
#[cfg(test)]
pub(crate) fn test_kinematics(
    overlap_mm: f64,
    contact_radius_mm: f64,
) -> ContactKinematics<crate::num::Fx> {
    use crate::num::Fx;
    ContactKinematics {
        normal: Vec3::new(Fx::ZERO, Fx::ZERO, Fx::ONE),
        overlap: Fx::from_f64(overlap_mm),
        contact_radius: Fx::from_f64(contact_radius_mm),
        sqrt_a_mstar: Fx::ZERO,
        vn: Fx::ZERO,
        vt: Vec3::ZERO,
        dt: Fx::from_f64(1e-3),
        lever_i: Fx::ONE,
        lever_j: Fx::ZERO,
        r_star: Fx::ZERO,
        w_rel: Vec3::ZERO,
        rolling_inertia: Fx::ZERO,
    }
}
