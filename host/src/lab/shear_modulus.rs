//! Shear modulus from the elastic modulus and Poisson's ratio, seed 000 eq. (12):
//! G = E / (2(1 + μ)).
//!
//! CSV columns: `modulus_mpa` (apparent elastic modulus E, MPa) and `poisson` (μ, in
//! [0, 0.5]).
//!
//! ```
//! // Seed 000 §3.1.3: E = 8.43 MPa and μ = 0.386 give G = 3.04 MPa.
//! let g = arachis::lab::shear_modulus::shear_modulus(8.43e6, 0.386);
//! assert!((g / 1e6 - 3.04).abs() < 0.005);
//! ```

use super::columns::positive;
use super::error::LabError;
use super::report::{LabReport, Quantity};
use super::units::PA_PER_MPA;
use crate::io::CsvTable;

/// Column: elastic modulus E, MPa.
pub const MODULUS_COLUMN: &str = "modulus_mpa";
/// Column: Poisson's ratio μ.
pub const POISSON_COLUMN: &str = "poisson";

/// Upper bound of Poisson's ratio for an isotropic elastic solid (incompressible limit).
pub const POISSON_MAX: f64 = 0.5;

/// Shear modulus G = E/(2(1 + μ)) in Pa, from elastic modulus `e_pa` (Pa) and Poisson's
/// ratio `mu`. Seed 000 eq. (12).
pub fn shear_modulus(e_pa: f64, mu: f64) -> f64 {
    e_pa / (2.0 * (1.0 + mu))
}

/// Reads Poisson's ratio column `name`, each value in [0, 0.5].
pub fn poisson_column(table: &CsvTable, name: &str) -> Result<Vec<f64>, LabError> {
    Ok(table.f64_column_checked(name, |mu| {
        if (0.0..=POISSON_MAX).contains(&mu) {
            Ok(())
        } else {
            Err(format!(
                "Poisson's ratio must be in [0, {POISSON_MAX}], got {mu}"
            ))
        }
    })?)
}

/// Shear modulus of every replicate in `table`.
pub fn analyze(table: &CsvTable) -> Result<LabReport, LabError> {
    let e = positive(table, MODULUS_COLUMN, "elastic modulus")?;
    let mu = poisson_column(table, POISSON_COLUMN)?;
    let g: Vec<f64> = e
        .iter()
        .zip(&mu)
        .map(|(e, mu)| shear_modulus(e * PA_PER_MPA, *mu))
        .collect();
    let mut report = LabReport::new("shear-modulus", table);
    report
        .quantities
        .push(Quantity::new(table, "shear_modulus", "Pa", &g)?.shown_in("MPa", 1.0 / PA_PER_MPA));
    Ok(report)
}
