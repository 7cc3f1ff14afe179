//! The model's parameters as the diagnosis loop sees them: the **base** parameters that the
//! current calibration sets (and that calibration may re-fit), and the catalogue of optional
//! **effects**, each with its off value (0), unit and finite-difference step. The effects map
//! onto the core's [`arachis_core::effects`] switches.

use anyhow::{bail, Result};
use serde::{Deserialize, Serialize};

/// Every parameter the cheap experiments depend on (SI units in the names).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelParams {
    /// Pod–steel coefficient of restitution e ∈ (0, 1] (seed 000 eq. (4)).
    pub restitution: f64,
    /// Pod Young's modulus, Pa.
    pub youngs_modulus_pa: f64,
    /// Effect: viscoelastic relaxation time A, s (0 = off).
    #[serde(default)]
    pub viscoelastic_time_s: f64,
    /// Effect: SJKR cohesion energy density k, J/m³ (0 = off).
    #[serde(default)]
    pub cohesion_j_m3: f64,
    /// Effect: air-drag coefficient Cd (0 = off).
    #[serde(default)]
    pub drag_coefficient: f64,
    /// Effect: hysteretic normal contact, plastic fraction λ ∈ [0, 1) (0 = off). Not written
    /// when 0, so study files from before the effect existed are reproduced byte for byte.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub plastic_fraction: f64,
}

/// serde helper: skip an effect parameter that is off.
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// Which kind of parameter an entry is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// Set by the current calibration; the fit may move it.
    Base,
    /// An optional effect, off (0) unless switched on.
    Effect,
}

/// One parameter: name, unit, role, finite-difference step and accessors.
#[derive(Clone, Copy, Debug)]
pub struct ParamInfo {
    /// Name used on the command line and in study files.
    pub name: &'static str,
    /// Unit, for reports.
    pub unit: &'static str,
    /// Base or effect.
    pub role: Role,
    /// Finite-difference step (absolute, in the parameter's unit). Chosen so that the change
    /// of each observable is far above the fixed-point resolution of the simulation, and
    /// small enough to stay in the linear range.
    pub fd_step: f64,
    /// Typical magnitude, used to scale the fit's parameter vector to order one.
    pub scale: f64,
    /// One-line description.
    pub about: &'static str,
    get: fn(&ModelParams) -> f64,
    set: fn(&mut ModelParams, f64),
}

impl ParamInfo {
    /// The parameter's value in `p`.
    pub fn get(&self, p: &ModelParams) -> f64 {
        (self.get)(p)
    }
    /// Set the parameter in `p`.
    pub fn set(&self, p: &mut ModelParams, v: f64) {
        (self.set)(p, v)
    }
}

/// The parameter catalogue: base parameters first, then the candidate effects.
pub const CATALOGUE: [ParamInfo; 6] = [
    ParamInfo {
        name: "restitution",
        unit: "-",
        role: Role::Base,
        fd_step: 0.01,
        scale: 0.5,
        about: "pod-steel coefficient of restitution (constant-e damping, seed 000 eq. 4)",
        get: |p| p.restitution,
        set: |p, v| p.restitution = v,
    },
    ParamInfo {
        name: "youngs_modulus",
        unit: "Pa",
        role: Role::Base,
        fd_step: 2.0e5,
        scale: 1.0e7,
        about: "pod Young's modulus (Hertz stiffness, seed 000 eq. 3)",
        get: |p| p.youngs_modulus_pa,
        set: |p, v| p.youngs_modulus_pa = v,
    },
    ParamInfo {
        name: "viscoelastic",
        unit: "s",
        role: Role::Effect,
        fd_step: 2.0e-6,
        scale: 1.0e-5,
        about: "viscoelastic damping, restitution falls with impact speed (Brilliantov 1996)",
        get: |p| p.viscoelastic_time_s,
        set: |p, v| p.viscoelastic_time_s = v,
    },
    ParamInfo {
        name: "cohesion",
        unit: "J/m^3",
        role: Role::Effect,
        fd_step: 2.0e3,
        scale: 1.0e4,
        about: "SJKR cohesion, attraction k x contact area (LIGGGHTS sjkr)",
        get: |p| p.cohesion_j_m3,
        set: |p, v| p.cohesion_j_m3 = v,
    },
    ParamInfo {
        name: "drag",
        unit: "-",
        role: Role::Effect,
        fd_step: 0.05,
        scale: 0.5,
        about: "air drag coefficient Cd, F = -0.5 rho Cd A |v| v",
        get: |p| p.drag_coefficient,
        set: |p, v| p.drag_coefficient = v,
    },
    ParamInfo {
        name: "hysteretic",
        unit: "-",
        role: Role::Effect,
        fd_step: 0.02,
        scale: 0.1,
        about: "hysteretic (plastic) normal contact, plastic fraction of the peak overlap (Walton & Braun 1986)",
        get: |p| p.plastic_fraction,
        set: |p, v| p.plastic_fraction = v,
    },
];

/// Look a parameter up by name; the error lists the known names.
pub fn param(name: &str) -> Result<&'static ParamInfo> {
    match CATALOGUE.iter().find(|p| p.name == name) {
        Some(p) => Ok(p),
        None => bail!(
            "unknown parameter or effect '{name}'; known: {}",
            CATALOGUE
                .iter()
                .map(|p| p.name)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// Look an effect up by name (refuses base parameters).
pub fn effect(name: &str) -> Result<&'static ParamInfo> {
    let p = param(name)?;
    if p.role != Role::Effect {
        bail!(
            "'{name}' is a base parameter, not an optional effect; effects: {}",
            effects().map(|p| p.name).collect::<Vec<_>>().join(", ")
        );
    }
    Ok(p)
}

/// The base parameters.
pub fn base() -> impl Iterator<Item = &'static ParamInfo> {
    CATALOGUE.iter().filter(|p| p.role == Role::Base)
}

/// The candidate effects.
pub fn effects() -> impl Iterator<Item = &'static ParamInfo> {
    CATALOGUE.iter().filter(|p| p.role == Role::Effect)
}

impl ModelParams {
    /// Check ranges: e ∈ (0, 1], E > 0, effects ≥ 0, all finite.
    pub fn validate(&self) -> Result<()> {
        for p in CATALOGUE.iter() {
            let v = p.get(self);
            if !v.is_finite() {
                bail!("{} = {v} is not a finite number", p.name);
            }
            if p.role == Role::Effect && v < 0.0 {
                bail!("effect {} = {v} {} must be >= 0 (0 is off)", p.name, p.unit);
            }
        }
        if !(self.restitution > 0.0 && self.restitution <= 1.0) {
            bail!("restitution = {} must be in (0, 1]", self.restitution);
        }
        if self.plastic_fraction >= 1.0 {
            bail!("hysteretic = {} must be < 1", self.plastic_fraction);
        }
        if self.youngs_modulus_pa <= 0.0 {
            bail!("youngs_modulus = {} Pa must be > 0", self.youngs_modulus_pa);
        }
        Ok(())
    }
}
