//! Materials: Young's modulus, Poisson ratio, density, and the EDEM/LIGGGHTS shear modulus
//! convention G = E/(2(1+ν)) (DESIGN §2).
//!
//! ```
//! use arachis_core::material::MaterialSpec;
//! // Peanut pod, seed 000 §3.1: E = 8.43 MPa, ν = 0.386, ρ = 582.36 kg/m³.
//! let pod = MaterialSpec { youngs_modulus_pa: 8.43e6, poisson: 0.386, density_kg_m3: 582.36 };
//! let m = pod.validate().unwrap();
//! assert!((m.shear_modulus_mpa() - 3.04).abs() < 0.01); // seed 000 reports G = 3.04 MPa
//! ```

use crate::error::SetupError;
use crate::units::{DENSITY_KG_M3_TO_G_MM3, STRESS_PA_TO_MPA};

/// Largest number of materials in one world.
pub const MAX_MATERIALS: usize = 8;

/// Index of a material in the world's material table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct MaterialId(pub u16);

/// A material as given by the user, in SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialSpec {
    /// Young's modulus E, Pa (> 0).
    pub youngs_modulus_pa: f64,
    /// Poisson ratio ν, dimensionless, in (−1, 0.5) (or (−1, 1) through
    /// [`PoissonRange::ContactModel`]).
    pub poisson: f64,
    /// Density ρ, kg/m³ (> 0).
    pub density_kg_m3: f64,
}

/// A validated material, in internal units (MPa, g/mm³).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Young's modulus, MPa.
    pub youngs_modulus_mpa: f64,
    /// Poisson ratio.
    pub poisson: f64,
    /// Density, g/mm³.
    pub density_g_mm3: f64,
}

pub(crate) fn finite(x: f64, what: &'static str) -> Result<f64, SetupError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(SetupError::NonFinite { what })
    }
}

/// Which Poisson ratios a material may have.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PoissonRange {
    /// ν ∈ (−1, 0.5): an isotropic elastic solid (finite bulk modulus). The default.
    #[default]
    Isotropic,
    /// ν ∈ (−1, 1): as far as the Hertz–Mindlin terms stay positive. 1 − ν² > 0 keeps
    /// E* = [(1−νᵢ²)/Eᵢ + (1−νⱼ²)/Eⱼ]⁻¹ positive and (2 − ν)(1 + ν) > 0 keeps G* (DESIGN §2)
    /// positive; the Rayleigh denominator 0.1631ν + 0.8766 stays positive too. Seed 000
    /// Table 3 screens ν up to 0.586, so a calibration must be able to ask for it knowingly.
    ContactModel,
}

impl PoissonRange {
    /// True when `nu` lies in the range (open bounds).
    pub fn contains(self, nu: f64) -> bool {
        match self {
            PoissonRange::Isotropic => nu > -1.0 && nu < 0.5,
            PoissonRange::ContactModel => nu > -1.0 && nu < 1.0,
        }
    }
}

impl MaterialSpec {
    /// Check ranges and convert to internal units; ν must lie in (−1, 0.5)
    /// ([`PoissonRange::Isotropic`]).
    pub fn validate(&self) -> Result<Material, SetupError> {
        self.validate_with(PoissonRange::Isotropic)
    }

    /// Like [`MaterialSpec::validate`], with the Poisson ratio checked against `range`.
    pub fn validate_with(&self, range: PoissonRange) -> Result<Material, SetupError> {
        let e = finite(self.youngs_modulus_pa, "Young's modulus")?;
        let nu = finite(self.poisson, "Poisson ratio")?;
        let rho = finite(self.density_kg_m3, "density")?;
        if e <= 0.0 {
            return Err(SetupError::NonPositiveYoungsModulus {
                youngs_modulus_pa: e,
            });
        }
        if !range.contains(nu) {
            return Err(SetupError::PoissonOutOfRange { nu });
        }
        if rho <= 0.0 {
            return Err(SetupError::NonPositiveDensity { density_kg_m3: rho });
        }
        Ok(Material {
            youngs_modulus_mpa: e * STRESS_PA_TO_MPA,
            poisson: nu,
            density_g_mm3: rho * DENSITY_KG_M3_TO_G_MM3,
        })
    }
}

impl Material {
    /// Shear modulus G = E/(2(1+ν)), MPa (EDEM/LIGGGHTS convention, DESIGN §2).
    pub fn shear_modulus_mpa(&self) -> f64 {
        self.youngs_modulus_mpa / (2.0 * (1.0 + self.poisson))
    }
    /// (1−ν²)/E, 1/MPa: this material's share of 1/E* (DESIGN §2).
    pub fn inv_e_star_part(&self) -> f64 {
        (1.0 - self.poisson * self.poisson) / self.youngs_modulus_mpa
    }
    /// 2(2−ν)(1+ν)/E, 1/MPa: this material's share of 1/G* (DESIGN §2).
    pub fn inv_g_star_part(&self) -> f64 {
        2.0 * (2.0 - self.poisson) * (1.0 + self.poisson) / self.youngs_modulus_mpa
    }
}
