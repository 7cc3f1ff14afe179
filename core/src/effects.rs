//! Optional physical effects: a catalogue of terms that are **off** by default and that
//! calibration (and `arachis diagnose`) can switch on and vary.
//!
//! | effect | parameter (off value) | scope | term | formula |
//! |---|---|---|---|---|
//! | viscoelastic damping | relaxation time A, s (0) | material pair | [`ViscoelasticNormal`](crate::contact::ViscoelasticNormal) | Fn_v = −(4/3)E*·A·a·vn (Brilliantov et al. 1996) |
//! | SJKR cohesion | energy density k, J/m³ (0) | material pair | [`CohesionSjkr`](crate::contact::CohesionSjkr) | Fc = k·π·2R*α (LIGGGHTS sjkr) |
//! | hysteretic contact | plastic fraction λ (0) | material pair | [`HystereticNormal`](crate::contact::HystereticNormal) | unloading to a plastic set λ·α_max (after Walton & Braun 1986) |
//! | EPSD rolling resistance | rolling friction μr (0), damping ratio η_r | material pair | [`RollingEpsd`](crate::contact::RollingEpsd) | T = −k_r·θr − C_r·ω_r, \|k_r·θr\| ≤ μr·R*·Fn, k_r = 2.25·k_n·μr²R*² (Ai et al. 2011, type C) |
//! | full JKR cohesion | work of adhesion Γ, J/m² (0) | material pair | [`CohesionJkr`](crate::contact::CohesionJkr) | F = 4E*a³/(3R*) − √(8πΓE*a³), δ = a²/R* − √(2πΓa/E*); pull-off 1.5πΓR* (JKR 1971) |
//! | air drag | drag coefficient Cd (0), air density ρ, kg/m³ | world | [`AirDrag`] | F = −½ρ·Cd·πr²·\|v\|v |
//!
//! The EPSD form is an alternative to (or an addition to) the CDT rolling friction of
//! [`crate::pair::PairSpec::rolling_friction`]; set that to 0 to use EPSD alone. JKR replaces
//! the Hertz normal law and cannot be combined with the hysteretic contact.
//!
//! With every effect off the step is bit-identical to the plain Hertz–Mindlin law (the golden
//! digests in `testdata/digests` do not change): each term is guarded by its `on` flag.
//!
//! # Adding an effect of your own (worked example)
//!
//! Say contacts in a humid store gain a constant liquid-bridge pull F_b (N) while they touch.
//! 1. **The term.** A new file `contact/liquid_bridge.rs` with a struct holding its `on` flag
//!    and a pair constant in internal units, implementing [`crate::contact::ContactTerm`]:
//!    ```
//!    use arachis_core::contact::{ContactForce, ContactKinematics, ContactState, ContactTerm};
//!    use arachis_core::num::{Fx, Scalar, Vec3};
//!
//!    /// Constant bridge force. Off value: F_b = 0.
//!    #[derive(Clone, Copy, Default)]
//!    struct LiquidBridge<S> { on: bool, force_n: S }
//!
//!    impl<S: Scalar> LiquidBridge<S> {
//!        /// F_b in N (≥ 0); 0 is off.
//!        fn new(force_n: f64) -> Self { LiquidBridge { on: force_n > 0.0, force_n: S::from_f64(force_n) } }
//!    }
//!    impl<S: Scalar> ContactTerm<S> for LiquidBridge<S> {
//!        fn apply(&self, _: &ContactKinematics<S>, _: &mut ContactState<S>, out: &mut ContactForce<S>) {
//!            if self.on { out.normal -= self.force_n; } // attractive: reduces the push on j
//!        }
//!    }
//!
//!    // Unit test against theory: the force is exactly −F_b while in contact.
//!    let k = ContactKinematics { normal: Vec3::new(Fx::ZERO, Fx::ZERO, Fx::ONE),
//!        overlap: Fx::from_f64(0.01), contact_radius: Fx::from_f64(0.2), sqrt_a_mstar: Fx::ZERO,
//!        vn: Fx::ZERO, vt: Vec3::ZERO, dt: Fx::from_f64(1e-3), lever_i: Fx::ONE, lever_j: Fx::ZERO,
//!        r_star: Fx::ONE, w_rel: Vec3::ZERO, rolling_inertia: Fx::ZERO };
//!    let mut out = ContactForce::default();
//!    LiquidBridge::<Fx>::new(0.002).apply(&k, &mut ContactState::default(), &mut out);
//!    assert!((out.normal.to_f64() + 0.002).abs() < 1e-9);
//!    ```
//! 2. **Wire it in.** Add a field to [`crate::pair::PairParams`] initialised to its default
//!    (off) in `PairParams::new`, one `apply` line in `PairParams::evaluate` at the right stage
//!    (before the clip if it is part of the repulsive law, after it if it may attract), and a
//!    field to [`EffectSpec`] so [`crate::world::World::set_pair_effects`] can set it. Keep the `on` guard:
//!    that is what keeps the golden digests unchanged while the effect is off.
//! 3. **Make it calibratable.** In the host, add a field to `ModelParams` and an entry to
//!    the effect catalogue `CATALOGUE` (`host/src/diagnose/params.rs`): its name, unit, a
//!    finite-difference step and a typical scale (off value 0), and pass the field into
//!    [`EffectSpec`] where the cheap experiments build their world
//!    (`host/src/diagnose/experiment.rs`). `arachis diagnose` then tests it as a candidate
//!    and `arachis fit --with liquid_bridge` calibrates F_b with the base parameters. An
//!    effect is only testable if some experiment responds to it in a way the base
//!    parameters cannot mimic: hysteresis needed the `unload` experiment, since in a rebound
//!    it only lowers e, which the calibrated restitution absorbs.

use crate::error::SetupError;
use crate::material::finite;
pub use crate::step::air_drag::AirDrag;

/// Air density at 20 °C and 1 atm, kg/m³ (ISO 2533 standard atmosphere at sea level, 1.204).
pub const AIR_DENSITY_20C_KG_M3: f64 = 1.204;

/// The optional effects of one material pair. `Default` is all off.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EffectSpec {
    /// Viscoelastic dissipative relaxation time A, s (0 = off): velocity-dependent restitution.
    pub viscoelastic_time_s: f64,
    /// SJKR cohesion energy density k, J/m³ (0 = off).
    pub cohesion_energy_density_j_m3: f64,
    /// Hysteretic normal contact: plastic fraction λ ∈ [0, 1) (0 = off); e = √(1 − λ).
    pub plastic_fraction: f64,
    /// EPSD rolling resistance: rolling friction coefficient μr ≥ 0 (0 = off), limiting
    /// torque μr·R*·Fn (Ai et al. 2011 eq. (15)).
    pub epsd_rolling_friction: f64,
    /// EPSD rolling damping ratio η_r ≥ 0 (fraction of critical, Ai et al. 2011 eq. (14));
    /// only used while `epsd_rolling_friction` > 0. 0.3 is Ai et al.'s typical value.
    pub epsd_damping_ratio: f64,
    /// Full JKR cohesion: work of adhesion Γ, J/m² ≥ 0 (0 = off); pull-off force 1.5πΓR*.
    pub jkr_work_of_adhesion_j_m2: f64,
}

pub(crate) fn non_negative(x: f64, what: &'static str) -> Result<f64, SetupError> {
    let x = finite(x, what)?;
    if x < 0.0 {
        return Err(SetupError::NegativeEffectParameter { what, value: x });
    }
    Ok(x)
}

impl EffectSpec {
    /// Whether an effect that keeps per-contact history is on (hysteresis: α_max; EPSD
    /// rolling: θr; JKR: the neck flag). The world then needs an effect-history arena
    /// ([`crate::body::StorageLengths::with_effects`]).
    pub fn needs_history(&self) -> bool {
        self.plastic_fraction > 0.0
            || self.epsd_rolling_friction > 0.0
            || self.jkr_work_of_adhesion_j_m2 > 0.0
    }
}
