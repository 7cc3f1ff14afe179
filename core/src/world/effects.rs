//! The world's API for optional effects ([`crate::effects`]): per material pair, and air
//! drag for the whole world.

use super::World;
use crate::contact::{
    CohesionJkr, CohesionSjkr, HystereticNormal, RollingEpsd, ViscoelasticNormal,
};
use crate::effects::{non_negative, AirDrag, EffectSpec};
use crate::error::{CapacityKind, SetupError};
use crate::material::MaterialId;
use crate::num::Scalar;

impl<S: Scalar> World<'_, S> {
    /// Switch the optional effects of the (already set) pair `a`–`b` (symmetric).
    /// Errors: unknown material, pair not yet set, negative or non-finite parameters, a
    /// constant outside the fixed-point range, EPSD on a pair already in LIGGGHTS' `epsd2`
    /// rolling convention (two rolling springs), or an effect that keeps history in a world
    /// without an effect-history arena ([`crate::body::StorageLengths::with_effects`]).
    pub fn set_pair_effects(
        &mut self,
        a: MaterialId,
        b: MaterialId,
        spec: EffectSpec,
    ) -> Result<(), SetupError> {
        let tau = non_negative(spec.viscoelastic_time_s, "viscoelastic relaxation time")?;
        let k = non_negative(spec.cohesion_energy_density_j_m3, "cohesion energy density")?;
        let lambda = non_negative(spec.plastic_fraction, "plastic fraction")?;
        if lambda >= 1.0 {
            return Err(SetupError::NotRepresentable {
                what: "plastic fraction (must be < 1)",
                value: lambda,
            });
        }
        let mu_r = non_negative(spec.epsd_rolling_friction, "EPSD rolling friction")?;
        let eta_r = non_negative(spec.epsd_damping_ratio, "EPSD rolling damping ratio")?;
        let gamma = non_negative(spec.jkr_work_of_adhesion_j_m2, "JKR work of adhesion")?;
        if gamma > 0.0 && lambda > 0.0 {
            return Err(SetupError::IncompatibleEffects {
                a: "JKR cohesion",
                b: "hysteretic normal contact",
            });
        }
        if spec.needs_history() && !self.list.has_effect_history() {
            return Err(SetupError::Capacity {
                kind: CapacityKind::EffectHistory,
                capacity: 0,
            });
        }
        let (ia, ib) = (a.0 as usize, b.0 as usize);
        if ia >= self.materials.len() || ib >= self.materials.len() {
            return Err(SetupError::UnknownMaterial { id: a.0.max(b.0) });
        }
        let mut p = self.pairs[ia][ib];
        if !p.defined {
            return Err(SetupError::UnknownMaterial { id: b.0 });
        }
        if mu_r > 0.0 && p.rolling_epsd2.on {
            return Err(SetupError::IncompatibleEffects {
                a: "EPSD rolling resistance",
                b: "the liggghts-epsd2 rolling convention",
            });
        }
        p.viscoelastic = ViscoelasticNormal::new(tau, p.e_star_mpa);
        p.cohesion = CohesionSjkr::new(k);
        p.hysteretic = HystereticNormal::new(lambda, p.e_star_mpa);
        p.rolling_epsd = RollingEpsd::new(mu_r, eta_r, p.e_star_mpa);
        p.jkr = CohesionJkr::new(gamma, p.e_star_mpa);
        for v in [
            p.viscoelastic.coef,
            p.cohesion.coef,
            p.rolling_epsd.stiffness_coef,
            p.rolling_epsd.two_damping_ratio,
            p.jkr.c,
            p.jkr.adhesion_coef,
            p.jkr.reach,
        ] {
            if !v.is_valid() {
                return Err(SetupError::NotRepresentable {
                    what: "effect constant",
                    value: v.to_f64(),
                });
            }
        }
        p.fuse();
        self.pairs[ia][ib] = p;
        self.pairs[ib][ia] = p;
        Ok(())
    }

    /// Switch air drag on (Cd > 0) or off (Cd = 0) for all bodies: air density ρ (kg/m³,
    /// e.g. [`crate::effects::AIR_DENSITY_20C_KG_M3`]) and drag coefficient Cd (≈ 0.47 for a sphere at
    /// Re 10³–10⁵).
    pub fn set_air_drag(
        &mut self,
        air_density_kg_m3: f64,
        drag_coefficient: f64,
    ) -> Result<(), SetupError> {
        let rho = non_negative(air_density_kg_m3, "air density")?;
        let cd = non_negative(drag_coefficient, "drag coefficient")?;
        let d = AirDrag::<S>::new(rho, cd);
        if !d.coef.is_valid() {
            return Err(SetupError::NotRepresentable {
                what: "drag constant",
                value: 0.5 * rho * cd,
            });
        }
        self.air_drag = d;
        Ok(())
    }

    /// The air-drag settings.
    pub fn air_drag(&self) -> &AirDrag<S> {
        &self.air_drag
    }
}
