//! Internal units (DESIGN §4): **millimetre, gram, millisecond**.
//!
//! Derived units are then force in N (g·mm/ms²), stress/modulus in MPa (N/mm²), velocity in
//! m/s (mm/ms), energy in mJ (N·mm), torque in N·mm, angular velocity in rad/ms, inertia in
//! g·mm², density in g/mm³ and acceleration in mm/ms². In these units the working quantities of
//! a peanut-pod simulation sit between ~1e-4 and ~1e5, well inside Q32.32 (resolution 2.3e-10,
//! range ±2.1e9); see the magnitude table in the crate docs.
//!
//! The public set-up API takes SI values (`_m`, `_kg`, `_s`, `_pa` suffixes) and converts with
//! the factors below; state accessors return internal units unless their name says `_si`.

/// Metres → millimetres.
pub const LENGTH_M_TO_MM: f64 = 1.0e3;
/// Kilograms → grams.
pub const MASS_KG_TO_G: f64 = 1.0e3;
/// Seconds → milliseconds.
pub const TIME_S_TO_MS: f64 = 1.0e3;
/// m/s → mm/ms (identical).
pub const VELOCITY_M_S_TO_MM_MS: f64 = 1.0;
/// rad/s → rad/ms.
pub const ANGULAR_VELOCITY_RAD_S_TO_RAD_MS: f64 = 1.0e-3;
/// m/s² → mm/ms².
pub const ACCELERATION_M_S2_TO_MM_MS2: f64 = 1.0e-3;
/// Pa → MPa (N/mm²).
pub const STRESS_PA_TO_MPA: f64 = 1.0e-6;
/// kg/m³ → g/mm³.
pub const DENSITY_KG_M3_TO_G_MM3: f64 = 1.0e-6;
/// N → N (g·mm/ms² is exactly one newton).
pub const FORCE_N_TO_INTERNAL: f64 = 1.0;
/// J → mJ (N·mm).
pub const ENERGY_J_TO_MJ: f64 = 1.0e3;
/// N·m → N·mm.
pub const TORQUE_NM_TO_NMM: f64 = 1.0e3;
/// kg·m² → g·mm².
pub const INERTIA_KG_M2_TO_G_MM2: f64 = 1.0e9;
/// Standard gravity, m/s² (used by examples and tests; the world's gravity is set explicitly).
pub const STANDARD_GRAVITY_M_S2: f64 = 9.81;
