//! Bond sets: the parameters shared by a group of bonds (e.g. all pod–stalk bonds), given in
//! SI ([`BondSetSpec`]), validated and converted once into internal units ([`BondParams`]).
//!
//! Seed 001 Table 4 start values for the pod–stalk junction: Kn = Kt = 5e5 N/m³,
//! σc = τc = 1e5 Pa, Rb = 1.1 mm; the calibrated junction has Kt = 4.738e5 N/m³ and
//! τc = 9.350e5 Pa (seed 001 §3.2).

use super::error::BondError;
use crate::material::finite;
use crate::num::quantise::quantise;
use crate::num::Scalar;
use crate::units::{LENGTH_M_TO_MM, STRESS_PA_TO_MPA};
use core::f64::consts::PI;

/// Largest number of bond sets in one world.
pub const MAX_BOND_SETS: usize = 16;

/// N/m³ → N/mm³ (stiffness per unit area: a stress per length).
pub const STIFFNESS_N_M3_TO_N_MM3: f64 = 1.0e-9;

/// Index of a bond set in the world's bond-set table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct BondSetId(pub u16);

/// A bond set as given by the user (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BondSetSpec {
    /// Free tag the host uses to name the set (e.g. 1 = pod–stalk, 2 = stalk–stem); it is
    /// copied into every break record.
    pub tag: u16,
    /// Normal stiffness per unit area Kn, N/m³ (> 0).
    pub normal_stiffness_n_m3: f64,
    /// Tangential stiffness per unit area Kt, N/m³ (> 0).
    pub tangential_stiffness_n_m3: f64,
    /// Normal critical stress σc, Pa (> 0).
    pub normal_strength_pa: f64,
    /// Tangential critical stress τc, Pa (> 0).
    pub tangential_strength_pa: f64,
    /// Bond radius Rb, m (> 0).
    pub radius_m: f64,
}

impl BondSetSpec {
    /// Seed 001 Table 4 start values of the pod–stalk junction (Kn = Kt = 5e5 N/m³,
    /// σc = τc = 1e5 Pa, Rb = 1.1 mm) with the given tag.
    pub const fn seed_001_table_4(tag: u16) -> Self {
        BondSetSpec {
            tag,
            normal_stiffness_n_m3: 5.0e5,
            tangential_stiffness_n_m3: 5.0e5,
            normal_strength_pa: 1.0e5,
            tangential_strength_pa: 1.0e5,
            radius_m: 1.1e-3,
        }
    }

    /// Check ranges and convert to internal units.
    pub fn validate<S: Scalar>(&self) -> Result<BondParams<S>, BondError> {
        let kn = positive(self.normal_stiffness_n_m3, "normal stiffness per unit area")?;
        let kt = positive(
            self.tangential_stiffness_n_m3,
            "tangential stiffness per unit area",
        )?;
        let sc = positive(self.normal_strength_pa, "normal critical stress")?;
        let tc = positive(self.tangential_strength_pa, "tangential critical stress")?;
        let rb_m = finite(self.radius_m, "bond radius")?;
        if rb_m <= 0.0 {
            return Err(BondError::NonPositiveBondRadius { radius_m: rb_m });
        }
        let rb = rb_m * LENGTH_M_TO_MM;
        let kn = kn * STIFFNESS_N_M3_TO_N_MM3;
        let kt = kt * STIFFNESS_N_M3_TO_N_MM3;
        // A = πRb², J = πRb⁴/2, I = J/2 (seed 001 §2.4.1; Potyondy & Cundall eq. (9)).
        let area = PI * rb * rb;
        let polar = PI * rb * rb * rb * rb / 2.0;
        let inertia = polar / 2.0;
        let q = |x: f64, what: &'static str| quantise::<S>(x, what).map_err(BondError::Setup);
        Ok(BondParams {
            tag: self.tag,
            radius: q(rb, "bond radius (mm)")?,
            kn_area: q(kn * area, "Kn·A (N/mm)")?,
            kt_area: q(kt * area, "Kt·A (N/mm)")?,
            kt_polar: q(kt * polar, "Kt·J (N·mm)")?,
            kn_inertia: q(kn * inertia, "Kn·J/2 (N·mm)")?,
            inv_area: q(1.0 / area, "1/A (1/mm²)")?,
            rb_over_inertia: q(rb / inertia, "Rb/(J/2) (1/mm³)")?,
            rb_over_polar: q(rb / polar, "Rb/J (1/mm³)")?,
            normal_strength: q(sc * STRESS_PA_TO_MPA, "normal critical stress (MPa)")?,
            tangential_strength: q(tc * STRESS_PA_TO_MPA, "tangential critical stress (MPa)")?,
            kn_area_f64: kn * area,
            kt_area_f64: kt * area,
            rot_stiffness_f64: (kn * inertia).max(kt * polar),
        })
    }
}

fn positive(x: f64, what: &'static str) -> Result<f64, BondError> {
    let x = finite(x, what).map_err(BondError::Setup)?;
    if x <= 0.0 {
        return Err(BondError::NonPositive { what, value: x });
    }
    Ok(x)
}

/// A validated bond set in internal units (mm, N, MPa). Products with the section constants
/// are precomputed so that the step does no division.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BondParams<S> {
    /// The host's tag of the set.
    pub tag: u16,
    /// Bond radius Rb, mm.
    pub radius: S,
    /// Kn·A, N/mm (axial stiffness).
    pub kn_area: S,
    /// Kt·A, N/mm (shear stiffness).
    pub kt_area: S,
    /// Kt·J, N·mm per rad (twisting stiffness).
    pub kt_polar: S,
    /// Kn·J/2, N·mm per rad (bending stiffness).
    pub kn_inertia: S,
    /// 1/A, 1/mm².
    pub inv_area: S,
    /// Rb/I = 2Rb/J, 1/mm³ (bending stress per moment).
    pub rb_over_inertia: S,
    /// Rb/J, 1/mm³ (torsional shear stress per moment).
    pub rb_over_polar: S,
    /// σc, MPa.
    pub normal_strength: S,
    /// τc, MPa.
    pub tangential_strength: S,
    /// Kn·A in f64 (set-up only: stable time step).
    pub(crate) kn_area_f64: f64,
    /// Kt·A in f64 (set-up only).
    pub(crate) kt_area_f64: f64,
    /// max(Kn·J/2, Kt·J) in f64, N·mm (set-up only).
    pub(crate) rot_stiffness_f64: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;

    #[test]
    fn section_constants_of_seed_table_4() {
        let p: BondParams<f64> = BondSetSpec::seed_001_table_4(1).validate().unwrap();
        // A = π·1.1² = 3.8013 mm², Kn = 5e-4 N/mm³ → Kn·A = 1.9007e-3 N/mm.
        assert!((p.kn_area - 5e-4 * PI * 1.21).abs() < 1e-15);
        assert!((p.rb_over_polar * PI * 1.1f64.powi(4) / 2.0 - 1.1).abs() < 1e-12);
        assert!((p.normal_strength - 0.1).abs() < 1e-15);
        let q: BondParams<Fx> = BondSetSpec::seed_001_table_4(1).validate().unwrap();
        assert!((q.kn_area.to_f64() / p.kn_area - 1.0).abs() < 1e-6);
    }

    #[test]
    fn bad_values_are_typed_errors() {
        let ok = BondSetSpec::seed_001_table_4(0);
        let r = |s: BondSetSpec| s.validate::<Fx>().unwrap_err();
        assert!(matches!(
            r(BondSetSpec {
                radius_m: 0.0,
                ..ok
            }),
            BondError::NonPositiveBondRadius { .. }
        ));
        assert!(matches!(
            r(BondSetSpec {
                normal_stiffness_n_m3: -1.0,
                ..ok
            }),
            BondError::NonPositive { .. }
        ));
        assert!(matches!(
            r(BondSetSpec {
                radius_m: f64::NAN,
                ..ok
            }),
            BondError::Setup(crate::error::SetupError::NonFinite { .. })
        ));
    }
}
