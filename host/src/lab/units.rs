//! Unit conversions at the CSV boundary.
//!
//! The library's public functions take and return SI quantities. Bench sheets are written in
//! the units the instruments read (mm from calipers and texture analysers, g from balances,
//! mL from measuring cylinders, degrees from protractors), and every CSV column names its
//! unit in its header (`deformation_mm`, `mass_g`, …). These factors convert a column value
//! into SI by multiplication.

/// Metres per millimetre.
pub const M_PER_MM: f64 = 1e-3;
/// Square metres per square millimetre.
pub const M2_PER_MM2: f64 = 1e-6;
/// Kilograms per gram.
pub const KG_PER_G: f64 = 1e-3;
/// Cubic metres per millilitre.
pub const M3_PER_ML: f64 = 1e-6;
/// Pascals per megapascal.
pub const PA_PER_MPA: f64 = 1e6;
/// Standard gravity, m/s². Seed 000 takes 9.8 for its friction balance (eq. 19), where g
/// cancels; seed 001 §2.4.2 uses 9.81. The restitution analyses use this value.
pub const STANDARD_GRAVITY: f64 = 9.81;
