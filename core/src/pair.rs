//! Material-pair parameters: the contact terms of [`crate::contact`] with their constants
//! precomputed at set-up (E*, G*, damping factors), one entry per unordered material pair.
//!
//! ```
//! use arachis_core::pair::PairSpec;
//! // Pod–pod, seed 000 §3.6.2: e 0.335, μs 0.854, μr 0.346.
//! let p = PairSpec::hertz_mindlin(0.335, 0.854, 0.346);
//! assert!(p.validate().is_ok());
//! ```

use crate::contact::fused::jkr::{JKR_ADHESION_BITS, JKR_C_BITS};
use crate::contact::fused::{
    FusedPair, DAMPING_BITS, FRICTION_BITS, NORMAL_STIFFNESS_BITS, TANGENTIAL_STIFFNESS_BITS,
};
use crate::contact::{
    CohesionJkr, CohesionSjkr, HystereticNormal, RollingEpsd, ViscoelasticNormal,
};
use crate::contact::{
    ContactForce, ContactKinematics, ContactState, ContactTerm, Conventions, CoulombLimit,
    FrictionConvention, HertzNormal, MindlinTangential, NormalDamping, RollingCdt,
    RollingCdtLiggghts, RollingConvention, RollingEpsd2Liggghts, TangentialDamping,
};
use crate::error::SetupError;
use crate::material::{finite, Material};
use crate::num::{Envelope, Scalar};

/// Which terms a pair uses. Each switch turns one term to its "off" value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TermSwitches {
    /// Hertz elastic normal force (seed 000 eq. 3).
    pub hertz_normal: bool,
    /// Normal damping (eq. 4).
    pub normal_damping: bool,
    /// Mindlin tangential spring with history (eq. 5).
    pub mindlin_tangential: bool,
    /// Tangential damping (eq. 6).
    pub tangential_damping: bool,
    /// Coulomb limit |Ft| ≤ μs Fn.
    pub coulomb_limit: bool,
    /// CDT rolling friction (eq. 7).
    pub rolling_cdt: bool,
}

impl TermSwitches {
    /// Every term of EDEM's Hertz–Mindlin (no slip) with CDT rolling friction.
    pub const ALL: TermSwitches = TermSwitches {
        hertz_normal: true,
        normal_damping: true,
        mindlin_tangential: true,
        tangential_damping: true,
        coulomb_limit: true,
        rolling_cdt: true,
    };
}

/// Pair interaction as given by the user.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairSpec {
    /// Coefficient of restitution e ∈ (0, 1] (sets β of eqs. (4), (6)).
    pub restitution: f64,
    /// Sliding (static) friction coefficient μs ≥ 0.
    pub friction: f64,
    /// Rolling friction coefficient μr ≥ 0.
    pub rolling_friction: f64,
    /// Which terms are on.
    pub terms: TermSwitches,
    /// Which engine's reading of rolling friction and the Coulomb limit
    /// ([`crate::contact::convention`]); EDEM's by default.
    pub conventions: Conventions,
}

impl PairSpec {
    /// Hertz–Mindlin (no slip) + CDT rolling friction, all terms on.
    pub fn hertz_mindlin(restitution: f64, friction: f64, rolling_friction: f64) -> Self {
        PairSpec {
            restitution,
            friction,
            rolling_friction,
            terms: TermSwitches::ALL,
            conventions: Conventions::EDEM,
        }
    }

    /// The same pair in other conventions.
    pub fn with_conventions(self, conventions: Conventions) -> Self {
        PairSpec {
            conventions,
            ..self
        }
    }

    /// `true` when the pair keeps per-contact state beyond δt, so a world using it needs an
    /// effect-history arena ([`crate::body::StorageLengths::with_effects`]): LIGGGHTS' `epsd2`
    /// rolling convention with rolling friction on.
    pub fn needs_effect_history(&self) -> bool {
        self.conventions.rolling == RollingConvention::LiggghtsEpsd2
            && self.terms.rolling_cdt
            && self.rolling_friction > 0.0
    }

    /// Check e ∈ (0, 1], μs ≥ 0, μr ≥ 0, all finite.
    pub fn validate(&self) -> Result<(), SetupError> {
        let e = finite(self.restitution, "restitution")?;
        let mu = finite(self.friction, "sliding friction")?;
        let mur = finite(self.rolling_friction, "rolling friction")?;
        if !(e > 0.0 && e <= 1.0) {
            return Err(SetupError::RestitutionOutOfRange { e });
        }
        if mu < 0.0 {
            return Err(SetupError::NegativeFriction {
                what: "sliding",
                value: mu,
            });
        }
        if mur < 0.0 {
            return Err(SetupError::NegativeFriction {
                what: "rolling",
                value: mur,
            });
        }
        Ok(())
    }
}

/// Precomputed pair constants: one struct per contact term, in pipeline order.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairParams<S> {
    /// `false` until [`crate::world::World::set_pair`] is called for this pair.
    pub defined: bool,
    /// E*, MPa (kept for reports).
    pub e_star_mpa: f64,
    /// G*, MPa (kept for reports).
    pub g_star_mpa: f64,
    /// Hertz normal term.
    pub hertz: HertzNormal<S>,
    /// Normal damping term.
    pub normal_damping: NormalDamping<S>,
    /// Mindlin tangential spring.
    pub tangential: MindlinTangential<S>,
    /// Tangential damping.
    pub tangential_damping: TangentialDamping<S>,
    /// Coulomb limit.
    pub coulomb: CoulombLimit<S>,
    /// CDT rolling friction in EDEM's convention.
    pub rolling: RollingCdt<S>,
    /// CDT rolling friction in LIGGGHTS' convention (off unless the pair asks for it).
    pub rolling_liggghts: RollingCdtLiggghts<S>,
    /// EPSD2 rolling resistance in LIGGGHTS' convention (off unless the pair asks for it).
    pub rolling_epsd2: RollingEpsd2Liggghts<S>,
    /// Optional effect: viscoelastic normal damping (off by default; [`crate::effects`]).
    pub viscoelastic: ViscoelasticNormal<S>,
    /// Optional effect: SJKR cohesion (off by default; [`crate::effects`]).
    pub cohesion: CohesionSjkr<S>,
    /// Optional effect: hysteretic (plastic) normal contact (off by default).
    pub hysteretic: HystereticNormal<S>,
    /// Optional effect: EPSD rolling resistance (off by default).
    pub rolling_epsd: RollingEpsd<S>,
    /// Optional effect: full JKR cohesion (off by default).
    pub jkr: CohesionJkr<S>,
    /// The constants of the fused base law ([`crate::contact::fused`]), and whether the pair
    /// may use it; kept up to date by [`PairParams::fuse`].
    pub fused: FusedPair<S>,
}

impl<S: Scalar> PairParams<S> {
    /// Precompute from two materials and a validated spec.
    pub fn new(a: &Material, b: &Material, spec: &PairSpec) -> Self {
        let e_star = 1.0 / (a.inv_e_star_part() + b.inv_e_star_part());
        let g_star = 1.0 / (a.inv_g_star_part() + b.inv_g_star_part());
        let t = spec.terms;
        let mut p = PairParams {
            defined: true,
            e_star_mpa: e_star,
            g_star_mpa: g_star,
            hertz: HertzNormal::new(e_star),
            normal_damping: NormalDamping::new(spec.restitution, e_star),
            tangential: MindlinTangential::new(g_star),
            tangential_damping: TangentialDamping::new(spec.restitution, g_star),
            coulomb: CoulombLimit::new(spec.friction),
            rolling: RollingCdt::new(spec.rolling_friction),
            rolling_liggghts: RollingCdtLiggghts::new(spec.rolling_friction, e_star),
            rolling_epsd2: RollingEpsd2Liggghts::new(spec.rolling_friction, g_star),
            viscoelastic: ViscoelasticNormal::default(),
            cohesion: CohesionSjkr::default(),
            hysteretic: HystereticNormal::default(),
            rolling_epsd: RollingEpsd::default(),
            jkr: CohesionJkr::default(),
            fused: FusedPair::default(),
        };
        p.hertz.on &= t.hertz_normal;
        p.normal_damping.on &= t.normal_damping;
        p.tangential.on &= t.mindlin_tangential;
        p.tangential_damping.on &= t.tangential_damping && t.mindlin_tangential;
        p.coulomb.on &= t.coulomb_limit && t.mindlin_tangential;
        p.rolling.on &= t.rolling_cdt;
        p.rolling_liggghts.on &= t.rolling_cdt;
        p.rolling_epsd2.on &= t.rolling_cdt;
        // Exactly one reading of the rolling friction stays on.
        let rolling = spec.conventions.rolling;
        p.rolling.on &= rolling == RollingConvention::Edem;
        p.rolling_liggghts.on &= rolling == RollingConvention::LiggghtsCdt;
        p.rolling_epsd2.on &= rolling == RollingConvention::LiggghtsEpsd2;
        p.coulomb.spring_only = spec.conventions.friction == FrictionConvention::Liggghts;
        p.fuse();
        p
    }

    /// Set [`PairParams::fused`] from the terms: the fused law applies to a defined pair with
    /// no optional effect but JKR cohesion, EDEM's conventions, the Hertz, Mindlin and
    /// Coulomb terms on (damping and rolling may be off: their factors are then zero) and
    /// constants inside the fused law's envelope. A pair in LIGGGHTS' conventions takes the
    /// terms.
    pub fn fuse(&mut self) {
        let on = |on: bool, x: S| if on { x } else { S::ZERO };
        let f = FusedPair {
            eligible: false,
            four_thirds_e_star: self.hertz.four_thirds_e_star,
            normal_damping: on(self.normal_damping.on, self.normal_damping.coef),
            eight_g_star: self.tangential.eight_g_star,
            tangential_damping: on(self.tangential_damping.on, self.tangential_damping.coef),
            friction: self.coulomb.mu,
            rolling_friction: on(self.rolling.on, self.rolling.mu_r),
            jkr: self.jkr.on,
            jkr_c: on(self.jkr.on, self.jkr.c),
            jkr_adhesion: on(self.jkr.on, self.jkr.adhesion_coef),
        };
        // JKR is the one optional effect the fused law carries ([`crate::contact::fused::jkr`]).
        let no_effects = !(self.viscoelastic.on
            | self.cohesion.on
            | self.hysteretic.on
            | self.rolling_epsd.on
            | self.rolling_liggghts.on
            | self.rolling_epsd2.on
            | self.coulomb.spring_only);
        let base_on = self.hertz.on & self.tangential.on & self.coulomb.on;
        let to_fx = |x: S| crate::num::Fx::from_f64(x.to_f64());
        let in_range = to_fx(f.four_thirds_e_star).within(NORMAL_STIFFNESS_BITS)
            & to_fx(f.eight_g_star).within(TANGENTIAL_STIFFNESS_BITS)
            & to_fx(f.normal_damping).within(DAMPING_BITS)
            & to_fx(f.tangential_damping).within(DAMPING_BITS)
            & to_fx(f.friction).within(FRICTION_BITS)
            & to_fx(f.rolling_friction).within(FRICTION_BITS)
            & to_fx(f.jkr_c).within(JKR_C_BITS)
            & to_fx(f.jkr_adhesion).within(JKR_ADHESION_BITS);
        self.fused = FusedPair {
            eligible: self.defined & no_effects & base_on & in_range,
            ..f
        };
    }

    /// `true` when contacts of this pair keep history (tangential spring, hysteresis, EPSD
    /// rolling angle, EPSD2 rolling torque or JKR neck).
    #[inline(always)]
    pub fn keeps_history(&self) -> bool {
        self.tangential.on | self.hysteretic.on | self.needs_effect_history()
    }

    /// `true` when contacts of this pair keep state beyond δt, in the effect-history arena
    /// ([`crate::body::StorageLengths::with_effects`]).
    #[inline(always)]
    pub fn needs_effect_history(&self) -> bool {
        self.hysteretic.on | self.rolling_epsd.on | self.rolling_epsd2.on | self.jkr.on
    }

    /// `true` when a term needs R* in [`ContactKinematics::r_star`] (EPSD rolling,
    /// LIGGGHTS-convention rolling, JKR).
    #[inline(always)]
    pub fn needs_r_star(&self) -> bool {
        self.needs_relative_spin() | self.jkr.on
    }

    /// `true` when a term needs the relative spin [`ContactKinematics::w_rel`] and adds a
    /// torque vector ([`ContactForce::rolling_torque`]): EPSD or LIGGGHTS-convention rolling.
    #[inline(always)]
    pub fn needs_relative_spin(&self) -> bool {
        self.rolling_epsd.on | self.rolling_liggghts.on | self.rolling_epsd2.on
    }

    /// `true` when a damping term needs √(a·m*).
    #[inline(always)]
    pub fn needs_damping(&self) -> bool {
        self.normal_damping.on | self.tangential_damping.on
    }

    /// Run all terms in pipeline order (normal → clip → tangential → rolling → cohesion).
    #[inline(always)]
    pub fn evaluate(
        &self,
        k: &ContactKinematics<S>,
        state: &mut ContactState<S>,
    ) -> ContactForce<S> {
        let mut out = ContactForce::default();
        self.hertz.apply(k, state, &mut out);
        self.jkr.apply(k, state, &mut out);
        self.hysteretic.apply(k, state, &mut out);
        self.normal_damping.apply(k, state, &mut out);
        self.viscoelastic.apply(k, state, &mut out);
        crate::contact::clip_normal(&mut out);
        self.tangential.apply(k, state, &mut out);
        self.tangential_damping.apply(k, state, &mut out);
        self.coulomb.apply(k, state, &mut out);
        self.rolling.apply(k, state, &mut out);
        self.rolling_liggghts.apply(k, state, &mut out);
        self.rolling_epsd2.apply(k, state, &mut out);
        self.rolling_epsd.apply(k, state, &mut out);
        self.cohesion.apply(k, state, &mut out);
        if self.jkr.on {
            out.normal -= out.attraction;
        }
        out
    }
}
