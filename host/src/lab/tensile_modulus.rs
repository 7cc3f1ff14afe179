//! Tensile elastic modulus from a pull test, seed 001 eq. (23): E₂ = F·L / (A·ΔL).
//!
//! CSV columns: `force_n` (tensile force F, N), `length_mm` (effective specimen length L,
//! mm), `elongation_mm` (ΔL, mm, > 0), and the cross-section as either `area_mm2` (A, mm²)
//! or `diameter_mm` (A = πD²/4).
//!
//! ```
//! // 10 N on a 20 mm specimen of 3 mm² section stretching 0.5 mm: 133.3 MPa.
//! let e2 = arachis::lab::tensile_modulus::tensile_modulus(10.0, 20e-3, 3e-6, 0.5e-3);
//! assert!((e2 - 1.0e7 * 40.0 / 3.0).abs() < 1.0);
//! ```

use std::f64::consts::PI;

use super::columns::{has, positive};
use super::error::LabError;
use super::report::{LabReport, Quantity};
use super::units::{M2_PER_MM2, M_PER_MM, PA_PER_MPA};
use crate::io::CsvTable;

/// Column: tensile force F, N.
pub const FORCE_COLUMN: &str = "force_n";
/// Column: effective specimen length L, mm.
pub const LENGTH_COLUMN: &str = "length_mm";
/// Column: elongation ΔL, mm.
pub const ELONGATION_COLUMN: &str = "elongation_mm";
/// Column: cross-sectional area A, mm².
pub const AREA_COLUMN: &str = "area_mm2";
/// Column (alternative to area): specimen diameter D, mm.
pub const DIAMETER_COLUMN: &str = "diameter_mm";

/// Tensile modulus E₂ = F·L/(A·ΔL) in Pa from force `force_n` (N), length `length_m` (m),
/// area `area_m2` (m²) and elongation `elongation_m` (m). Seed 001 eq. (23).
pub fn tensile_modulus(force_n: f64, length_m: f64, area_m2: f64, elongation_m: f64) -> f64 {
    force_n * length_m / (area_m2 * elongation_m)
}

/// Tensile modulus of every replicate in `table`.
pub fn analyze(table: &CsvTable) -> Result<LabReport, LabError> {
    let force = positive(table, FORCE_COLUMN, "tensile force")?;
    let length = positive(table, LENGTH_COLUMN, "specimen length")?;
    let elongation = positive(table, ELONGATION_COLUMN, "elongation")?;
    let area_m2: Vec<f64> = if has(table, AREA_COLUMN) {
        positive(table, AREA_COLUMN, "cross-sectional area")?
            .iter()
            .map(|a| a * M2_PER_MM2)
            .collect()
    } else if has(table, DIAMETER_COLUMN) {
        positive(table, DIAMETER_COLUMN, "diameter")?
            .iter()
            .map(|d| PI * (d * M_PER_MM).powi(2) / 4.0)
            .collect()
    } else {
        return Err(LabError::Layout {
            path: table.path.clone(),
            reason: format!(
                "needs a cross-section column, '{AREA_COLUMN}' or '{DIAMETER_COLUMN}' (columns: {})",
                table.headers.join(", ")
            ),
        });
    };
    let e2: Vec<f64> = (0..force.len())
        .map(|i| {
            tensile_modulus(
                force[i],
                length[i] * M_PER_MM,
                area_m2[i],
                elongation[i] * M_PER_MM,
            )
        })
        .collect();
    let mut report = LabReport::new("tensile-modulus", table);
    report.quantities.push(
        Quantity::new(table, "tensile_modulus", "Pa", &e2)?.shown_in("MPa", 1.0 / PA_PER_MPA),
    );
    Ok(report)
}
