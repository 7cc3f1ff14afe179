//! Time-step helpers: the Rayleigh time (DESIGN §2) and the stable bound the world enforces.
//!
//! T_R = π R √(ρ/G) / (0.1631 ν + 0.8766). Seed 000 runs at 20 % of T_R, seed 001 at 6.5 %.
//! The world refuses any dt above [`MAX_RAYLEIGH_FRACTION`] × T_R of its smallest sphere.
//!
//! ```
//! use arachis_core::timestep::rayleigh_time_s;
//! // DESIGN §8 bed: R = 4 mm pod (ρ 582 kg/m³, E 8.43 MPa, ν 0.386) → T_R ≈ 1.85e-4 s.
//! let t = rayleigh_time_s(0.004, 582.0, 8.43e6, 0.386);
//! assert!((t - 1.85e-4).abs() < 0.01e-4);
//! ```

use core::f64::consts::PI;

/// Coefficient of ν in the Rayleigh denominator (DESIGN §2).
pub const RAYLEIGH_NU_COEF: f64 = 0.1631;
/// Constant of the Rayleigh denominator (DESIGN §2).
pub const RAYLEIGH_CONST: f64 = 0.8766;
/// Largest accepted dt as a fraction of the smallest Rayleigh time. 0.4 is the upper end of the
/// usual 20–40 % recommendation for Hertzian DEM: above it the explicit scheme resolves a
/// contact with too few steps.
pub const MAX_RAYLEIGH_FRACTION: f64 = 0.4;

/// Rayleigh time T_R = πR√(ρ/G)/(0.1631ν + 0.8766), s, with G = E/(2(1+ν)).
///
/// `radius_m` in m, `density_kg_m3` in kg/m³, `youngs_modulus_pa` in Pa.
pub fn rayleigh_time_s(
    radius_m: f64,
    density_kg_m3: f64,
    youngs_modulus_pa: f64,
    poisson: f64,
) -> f64 {
    let g = youngs_modulus_pa / (2.0 * (1.0 + poisson));
    PI * radius_m * libm::sqrt(density_kg_m3 / g) / (RAYLEIGH_NU_COEF * poisson + RAYLEIGH_CONST)
}

/// The largest dt (s) the world accepts for a given smallest Rayleigh time (s).
pub fn max_stable_dt_s(min_rayleigh_time_s: f64) -> f64 {
    MAX_RAYLEIGH_FRACTION * min_rayleigh_time_s
}
