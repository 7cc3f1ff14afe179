//! Static friction by the tilting-plate method: μs = tan θ at the angle θ where the sample
//! starts to slide (seed 000 eq. (19), seed 001 eq. (1)).
//!
//! CSV column: `angle_deg` (critical inclination θ, degrees, in [0°, 90°)).
//!
//! ```
//! let mu = arachis::lab::static_friction::static_friction(30.0_f64.to_radians());
//! assert!((mu - 0.57735).abs() < 1e-5);
//! ```

use super::columns::angle_deg;
use super::error::LabError;
use super::report::{LabReport, Quantity};
use crate::io::CsvTable;

/// Column: critical inclination angle θ, degrees.
pub const ANGLE_COLUMN: &str = "angle_deg";

/// A tilting plate stands between flat (0°) and vertical (90°, where tan θ is infinite).
pub const MAX_TILT_DEG: f64 = 90.0;

/// Static friction coefficient μs = tan θ (dimensionless) at critical angle `theta_rad`
/// (rad). Seed 000 eq. (19): F_f = μ mg cos θ balances mg sin θ.
pub fn static_friction(theta_rad: f64) -> f64 {
    theta_rad.tan()
}

/// Static friction of every replicate in `table`.
pub fn analyze(table: &CsvTable) -> Result<LabReport, LabError> {
    let theta = angle_deg(table, ANGLE_COLUMN, 0.0, MAX_TILT_DEG, "tilt angle")?;
    let mu: Vec<f64> = theta
        .iter()
        .map(|t| static_friction(t.to_radians()))
        .collect();
    let mut report = LabReport::new("static-friction", table);
    report
        .quantities
        .push(Quantity::new(table, "static_friction", "1", &mu)?);
    Ok(report)
}
