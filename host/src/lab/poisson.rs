//! Poisson's ratio from a compression test, seed 000 eq. (8).
//!
//! μ = |ε_y / ε_x| = (W′_y / W_y) / (W′_x / W_x): the transverse strain over the axial
//! strain, each a deformation over its original dimension. Deformations are entered as
//! magnitudes (the sign convention of compression versus expansion is the user's), so a
//! negative deformation is rejected as a data-entry error.
//!
//! Seed 001 eq. (18) prints the ratio of the two *deformations* (L₁ − L₂)/(W₁ − W₂) while its
//! text speaks of the ratio of *strains*; we follow the text (strains), which is also seed
//! 000's eq. (8).
//!
//! CSV columns (all mm): `length_mm` (W_x, axial length), `width_mm` (W_y, transverse
//! width), `axial_deformation_mm` (W′_x, > 0), `transverse_deformation_mm` (W′_y, ≥ 0).
//!
//! ```
//! // 0.5 mm of 34 mm axially, 0.104 mm of 18.3 mm transversely: μ ≈ 0.386.
//! let mu = arachis::lab::poisson::poisson_ratio(34e-3, 18.3e-3, 0.5e-3, 0.10386e-3);
//! assert!((mu - 0.386).abs() < 5e-4);
//! ```

use super::columns::{non_negative, positive};
use super::error::LabError;
use super::report::{LabReport, Quantity};
use crate::io::CsvTable;

/// Column: axial (loading-direction) length W_x, mm.
pub const LENGTH_COLUMN: &str = "length_mm";
/// Column: transverse width W_y, mm.
pub const WIDTH_COLUMN: &str = "width_mm";
/// Column: axial deformation W′_x (magnitude), mm.
pub const AXIAL_COLUMN: &str = "axial_deformation_mm";
/// Column: transverse deformation W′_y (magnitude), mm.
pub const TRANSVERSE_COLUMN: &str = "transverse_deformation_mm";

/// Poisson's ratio μ = (W′_y/W_y)/(W′_x/W_x), dimensionless, seed 000 eq. (8). Lengths in
/// any one unit (m in this API): axial length `wx`, transverse width `wy`, axial
/// deformation `dx`, transverse deformation `dy`.
pub fn poisson_ratio(wx: f64, wy: f64, dx: f64, dy: f64) -> f64 {
    (dy / wy) / (dx / wx)
}

/// Poisson's ratio of every replicate in `table`.
pub fn analyze(table: &CsvTable) -> Result<LabReport, LabError> {
    let wx = positive(table, LENGTH_COLUMN, "axial length")?;
    let wy = positive(table, WIDTH_COLUMN, "transverse width")?;
    let dx = positive(table, AXIAL_COLUMN, "axial deformation")?;
    let dy = non_negative(table, TRANSVERSE_COLUMN, "transverse deformation")?;
    // The mm → m factor cancels in each strain, so the mm values go in as they are.
    let mu: Vec<f64> = (0..wx.len())
        .map(|i| poisson_ratio(wx[i], wy[i], dx[i], dy[i]))
        .collect();
    let mut report = LabReport::new("poisson", table);
    report
        .quantities
        .push(Quantity::new(table, "poisson_ratio", "1", &mu)?);
    Ok(report)
}
