//! Density by displacement, seed 000 §2.5.1.
//!
//! A pod is weighed, then pressed just under the water surface in a measuring cylinder with
//! a rigid rod (pods float, so plain drainage does not work); the rise of the water level is
//! the pod's volume. ρ = m / ΔV.
//!
//! CSV columns: `mass_g` (pod mass, g) and `volume_ml` (rise of the water level, mL).
//!
//! ```
//! // 2.277 g displacing 3.91 mL: ≈ 582 kg/m³, seed 000's pod density.
//! let rho = arachis::lab::density::density(2.277e-3, 3.91e-6);
//! assert!((rho - 582.35).abs() < 0.01);
//! ```

use super::columns::{positive, row_error};
use super::error::LabError;
use super::report::{LabReport, Quantity};
use super::units::{KG_PER_G, M3_PER_ML};
use crate::io::CsvTable;
use crate::plausible::DENSITY_KG_M3;

/// Column: pod mass, g.
pub const MASS_COLUMN: &str = "mass_g";
/// Column: rise of the water level when the pod is held just under the surface, mL.
pub const VOLUME_COLUMN: &str = "volume_ml";

/// Density ρ = m / V in kg/m³, from mass `mass_kg` (kg) and displaced volume `volume_m3`
/// (m³). Seed 000 §2.5.1.
pub fn density(mass_kg: f64, volume_m3: f64) -> f64 {
    mass_kg / volume_m3
}

/// Density of every replicate in `table` (columns [`MASS_COLUMN`], [`VOLUME_COLUMN`]). A
/// replicate whose density lies outside [`DENSITY_KG_M3`] (a typo such as a mass of 1e300 g)
/// is refused with its line, unless `--allow-extreme`.
pub fn analyze(table: &CsvTable) -> Result<LabReport, LabError> {
    let mass = positive(table, MASS_COLUMN, "mass")?;
    let volume = positive(table, VOLUME_COLUMN, "displaced volume")?;
    let rho: Vec<f64> = mass
        .iter()
        .zip(&volume)
        .map(|(m, v)| density(m * KG_PER_G, v * M3_PER_ML))
        .collect();
    for (row, &r) in rho.iter().enumerate() {
        DENSITY_KG_M3.check(r).map_err(|reason| {
            let reason = format!("density {reason}");
            row_error(table, row, &[MASS_COLUMN, VOLUME_COLUMN], reason)
        })?;
    }
    let mut report = LabReport::new("density", table);
    report
        .quantities
        .push(Quantity::new(table, "density", "kg/m^3", &rho)?);
    Ok(report)
}
