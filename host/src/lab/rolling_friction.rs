//! Rolling friction by energy balance on an incline followed by a level run (seed 000
//! eq. (20); seed 001 eqs. (16)–(17)).
//!
//! A sample released from rest rolls a distance x down a plate inclined at α, then a
//! distance l along the level plate, and stops. The potential energy m g x sin α is spent
//! against rolling resistance f m g (x cos α + l), so
//!
//! ```text
//! f = x sin α / (x cos α + l)                       seed 001 eq. (17)
//! ```
//!
//! Seed 000 records the release height H₂ = x sin θ₂ instead of x and the level distance
//! S₂; the same balance gives f = H₂/(H₂ cot θ₂ + S₂). Seed 000 eq. (20) prints
//! H₂ cos θ₂ where the balance has H₂ cot θ₂ (the slope length is H₂/sin θ₂, not H₂): the
//! printed form equals the balance only at θ₂ = 90°. `--as-printed` reproduces it for
//! comparison with the paper's numbers.
//!
//! CSV columns: `angle_deg` (α, in (0°, 90°)), `level_mm` (l or S₂, mm, ≥ 0), and either
//! `slope_mm` (x, mm; seed 001) or `height_mm` (H₂, mm; seed 000).
//!
//! ```
//! use arachis::lab::rolling_friction::{from_height, from_slope};
//! // 100 mm down a 30° slope then 200 mm on the level.
//! let f = from_slope(0.1, 30f64.to_radians(), 0.2);
//! assert!((f - 0.05 / (0.1 * 3f64.sqrt() / 2.0 + 0.2)).abs() < 1e-12);
//! assert!((from_height(0.05, 30f64.to_radians(), 0.2) - f).abs() < 1e-12);
//! ```

use super::columns::{angle_deg, has, non_negative, positive};
use super::error::LabError;
use super::report::{LabReport, Quantity};
use crate::io::CsvTable;

/// Column: plate inclination α, degrees.
pub const ANGLE_COLUMN: &str = "angle_deg";
/// Column: rolling distance on the level plate (l, S₂), mm.
pub const LEVEL_COLUMN: &str = "level_mm";
/// Column: rolling distance down the slope x, mm (seed 001).
pub const SLOPE_COLUMN: &str = "slope_mm";
/// Column: release height H₂, mm (seed 000).
pub const HEIGHT_COLUMN: &str = "height_mm";

/// f = x sin α/(x cos α + l), dimensionless: slope distance `x`, level distance `l` (any one
/// length unit), inclination `alpha_rad` (rad). Seed 001 eq. (17).
pub fn from_slope(x: f64, alpha_rad: f64, l: f64) -> f64 {
    x * alpha_rad.sin() / (x * alpha_rad.cos() + l)
}

/// f = H/(H cot θ + S): release height `h`, level distance `s` (one length unit),
/// inclination `theta_rad`. The energy balance of seed 000 eq. (20) with the slope length
/// H/sin θ.
pub fn from_height(h: f64, theta_rad: f64, s: f64) -> f64 {
    h / (h / theta_rad.tan() + s)
}

/// Seed 000 eq. (20) exactly as printed, γ = H/(H cos θ + S); for comparison only.
pub fn from_height_as_printed(h: f64, theta_rad: f64, s: f64) -> f64 {
    h / (h * theta_rad.cos() + s)
}

/// Options of the rolling-friction analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RollingOptions {
    /// Use seed 000 eq. (20) as printed (H cos θ) instead of the energy balance (H cot θ).
    pub as_printed: bool,
}

/// Rolling friction of every replicate in `table`.
pub fn analyze(table: &CsvTable, options: RollingOptions) -> Result<LabReport, LabError> {
    // The open interval: at 0° nothing rolls, at 90° the slope is a wall.
    let alpha = angle_deg(
        table,
        ANGLE_COLUMN,
        f64::MIN_POSITIVE,
        90.0,
        "plate inclination",
    )?;
    let level = non_negative(table, LEVEL_COLUMN, "level rolling distance")?;
    let mut report = LabReport::new("rolling-friction", table);
    let f: Vec<f64> = if has(table, SLOPE_COLUMN) {
        let x = positive(table, SLOPE_COLUMN, "slope rolling distance")?;
        report
            .notes
            .push("seed 001 eq. (17): f = x sin α/(x cos α + l)".to_owned());
        (0..x.len())
            .map(|i| from_slope(x[i], alpha[i].to_radians(), level[i]))
            .collect()
    } else if has(table, HEIGHT_COLUMN) {
        let h = positive(table, HEIGHT_COLUMN, "release height")?;
        let formula: fn(f64, f64, f64) -> f64 = if options.as_printed {
            report.notes.push(
                "seed 000 eq. (20) as printed: γ = H/(H cos θ + S), not an energy balance unless θ = 90°".to_owned(),
            );
            from_height_as_printed
        } else {
            report.notes.push(
                "energy balance of seed 000 eq. (20) with slope length H/sin θ: γ = H/(H cot θ + S); the printed H cos θ is a typo (--as-printed uses it)".to_owned(),
            );
            from_height
        };
        (0..h.len())
            .map(|i| formula(h[i], alpha[i].to_radians(), level[i]))
            .collect()
    } else {
        return Err(LabError::Layout {
            path: table.path.clone(),
            reason: format!(
                "needs '{SLOPE_COLUMN}' (seed 001) or '{HEIGHT_COLUMN}' (seed 000) (columns: {})",
                table.headers.join(", ")
            ),
        });
    };
    report
        .quantities
        .push(Quantity::new(table, "rolling_friction", "1", &f)?);
    Ok(report)
}
