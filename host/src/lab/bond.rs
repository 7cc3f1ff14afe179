//! Bond parameters for the Hertz–Mindlin-with-bonding model, seed 001 §2.4.1
//! (eqs. (26)–(28)); DESIGN §2 end.
//!
//! - Hertz normal stiffness coefficient of two spheres a, b:
//!   K_n = (4/3) [(1 − ν_a²)/E_a + (1 − ν_b²)/E_b]⁻¹ ((r_a + r_b)/(r_a r_b))^(−1/2), in
//!   N/m^(3/2) (the Hertz law F = K_n δ^(3/2)).
//! - Tangential stiffness K_s = (1/2 … 2/3) K_n: seed 001 prints "(1 2 2 3) K_n", which we
//!   read as the usual range K_s/K_n ∈ [1/2, 2/3]; both ends are reported.
//! - Critical normal stress σ = F/(πR²) from the critical force F on a compression surface
//!   of radius R (eq. (27)).
//! - Critical tangential stress τ = σ tan φ + c, Mohr–Coulomb with internal friction angle
//!   φ and cohesion c (eq. (28)).
//!
//! CSV columns: `force_n` (critical force F, N) and `radius_mm` (R, mm). The friction angle,
//! cohesion and the two particles for K_n are options.
//!
//! ```
//! use arachis::lab::bond::{critical_normal_stress, critical_tangential_stress, normal_stiffness};
//! let sigma = critical_normal_stress(12.74, 1.1e-3);
//! assert!((sigma - 12.74 / (std::f64::consts::PI * 1.21e-6)).abs() < 1e-6);
//! assert_eq!(critical_tangential_stress(1e5, 45f64.to_radians(), 2e4), 1e5 * 45f64.to_radians().tan() + 2e4);
//! // Two equal spheres (E = 1 MPa, ν = 0, r = 1 m): (4/3)(1/2 MPa)(1/2)^(1/2)·… = (4/3)·5e5·√0.5.
//! let kn = normal_stiffness((1e6, 0.0, 1.0), (1e6, 0.0, 1.0));
//! assert!((kn - 4.0 / 3.0 * 5e5 * 0.5f64.sqrt()).abs() < 1e-6);
//! ```

use std::f64::consts::PI;

use super::columns::positive;
use super::error::LabError;
use super::report::{LabReport, Quantity, Value};
use super::units::{M_PER_MM, PA_PER_MPA};
use crate::io::CsvTable;

/// Column: critical force F, N.
pub const FORCE_COLUMN: &str = "force_n";
/// Column: radius R of the compression (bond) surface, mm.
pub const RADIUS_COLUMN: &str = "radius_mm";

/// Lower end of the K_s/K_n range of seed 001 eq. (26).
pub const KS_RATIO_LOW: f64 = 1.0 / 2.0;
/// Upper end of the K_s/K_n range of seed 001 eq. (26).
pub const KS_RATIO_HIGH: f64 = 2.0 / 3.0;

/// Hertz normal stiffness coefficient K_n (N/m^(3/2)) of particles `a` and `b`, each given
/// as (E in Pa, Poisson's ratio, radius in m). Seed 001 eq. (26).
pub fn normal_stiffness(a: (f64, f64, f64), b: (f64, f64, f64)) -> f64 {
    let (ea, nua, ra) = a;
    let (eb, nub, rb) = b;
    let e_star = 1.0 / ((1.0 - nua * nua) / ea + (1.0 - nub * nub) / eb);
    4.0 / 3.0 * e_star * ((ra + rb) / (ra * rb)).powf(-0.5)
}

/// Critical normal stress σ = F/(πR²) in Pa from force `force_n` (N) and surface radius
/// `radius_m` (m). Seed 001 eq. (27).
pub fn critical_normal_stress(force_n: f64, radius_m: f64) -> f64 {
    force_n / (PI * radius_m * radius_m)
}

/// Critical tangential stress τ = σ tan φ + c in Pa from σ (Pa), internal friction angle
/// `phi_rad` (rad) and cohesion `cohesion_pa` (Pa). Seed 001 eq. (28).
pub fn critical_tangential_stress(sigma_pa: f64, phi_rad: f64, cohesion_pa: f64) -> f64 {
    sigma_pa * phi_rad.tan() + cohesion_pa
}

/// One particle at a bond end: (E in Pa, Poisson's ratio, radius in m).
pub type Particle = (f64, f64, f64);

/// Options of the bond analysis.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BondOptions {
    /// Internal friction angle φ, degrees, in [0°, 90°); τ is reported when given.
    pub friction_angle_deg: Option<f64>,
    /// Cohesion c, Pa, ≥ 0.
    pub cohesion_pa: f64,
    /// The two particles at the bond ends, for K_n and K_s.
    pub particles: Option<(Particle, Particle)>,
}

fn option_error(option: &str, reason: String) -> LabError {
    LabError::Option {
        option: option.to_owned(),
        reason,
    }
}

fn check_particle(p: Particle, side: &str) -> Result<(), LabError> {
    let (e, nu, r) = p;
    if e.is_nan() || e <= 0.0 {
        return Err(option_error(
            &format!("modulus-{side}-mpa"),
            format!("must be positive, got {e}"),
        ));
    }
    if !(0.0..=0.5).contains(&nu) {
        return Err(option_error(
            &format!("poisson-{side}"),
            format!("must be in [0, 0.5], got {nu}"),
        ));
    }
    if r.is_nan() || r <= 0.0 {
        return Err(option_error(
            &format!("radius-{side}-mm"),
            format!("must be positive, got {r}"),
        ));
    }
    Ok(())
}

/// σ (and τ, K_n, K_s when their settings are given) for every replicate in `table`.
pub fn analyze(table: &CsvTable, options: BondOptions) -> Result<LabReport, LabError> {
    let force = positive(table, FORCE_COLUMN, "critical force")?;
    let radius = positive(table, RADIUS_COLUMN, "surface radius")?;
    if options.cohesion_pa.is_nan() || options.cohesion_pa < 0.0 {
        return Err(option_error(
            "cohesion-pa",
            format!("must not be negative, got {}", options.cohesion_pa),
        ));
    }
    let sigma: Vec<f64> = force
        .iter()
        .zip(&radius)
        .map(|(f, r)| critical_normal_stress(*f, r * M_PER_MM))
        .collect();
    let mut report = LabReport::new("bond", table);
    let mpa = 1.0 / PA_PER_MPA;
    report
        .quantities
        .push(Quantity::new(table, "critical_normal_stress", "Pa", &sigma)?.shown_in("MPa", mpa));
    if let Some(phi) = options.friction_angle_deg {
        if !(0.0..90.0).contains(&phi) {
            return Err(option_error(
                "friction-angle-deg",
                format!("must be in [0°, 90°), got {phi}°"),
            ));
        }
        report
            .settings
            .push(Value::new("friction_angle", phi, "deg"));
        report
            .settings
            .push(Value::new("cohesion", options.cohesion_pa, "Pa"));
        let tau: Vec<f64> = sigma
            .iter()
            .map(|s| critical_tangential_stress(*s, phi.to_radians(), options.cohesion_pa))
            .collect();
        report.quantities.push(
            Quantity::new(table, "critical_tangential_stress", "Pa", &tau)?.shown_in("MPa", mpa),
        );
    } else {
        report
            .notes
            .push("give --friction-angle-deg (and --cohesion-pa) for τ = σ tan φ + c".to_owned());
    }
    if let Some((a, b)) = options.particles {
        check_particle(a, "a")?;
        check_particle(b, "b")?;
        let kn = normal_stiffness(a, b);
        report
            .derived
            .push(Value::new("normal_stiffness_kn", kn, "N/m^1.5"));
        report.derived.push(Value::new(
            "tangential_stiffness_ks_low",
            KS_RATIO_LOW * kn,
            "N/m^1.5",
        ));
        report.derived.push(Value::new(
            "tangential_stiffness_ks_high",
            KS_RATIO_HIGH * kn,
            "N/m^1.5",
        ));
        report
            .notes
            .push("K_s = (1/2 … 2/3) K_n: our reading of seed 001 eq. (26) as printed".to_owned());
    }
    Ok(report)
}
