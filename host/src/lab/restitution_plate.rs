//! Coefficient of restitution from the 45° plate rig, seed 000 eqs. (13)–(18).
//!
//! A pod falls from rest through height h onto a steel plate inclined at 45°, arriving at
//! v₀ = √(2gh) (eq. (14)). It rebounds as a projectile with horizontal speed v_x and
//! downward speed v_y and lands on a sheet of paper. Landing at depth h₁ below the impact
//! point O at horizontal distance s₁, and (plate raised) at depth h₂, distance s₂, gives
//! two points of one parabola, h_i = v_y t_i + g t_i²/2 with s_i = v_x t_i (eq. (16)), hence
//!
//! ```text
//! v_x = √( g s₁ s₂ (s₁ − s₂) / (2 (h₁ s₂ − h₂ s₁)) )          eq. (15)
//! v_y = h₁ v_x / s₁ − g s₁ / (2 v_x)
//! e   = √(v_x² + v_y²) · cos(45° + arctan(v_y/v_x)) / (v₀ sin 45°)   eq. (18)
//! ```
//!
//! The v_y line is our solution of eq. (16): the printed eq. (15) for v_y,
//! (h₁v_x − g s₁)/(s₁ − 2v_x), is not dimensionally consistent (its numerator adds m²/s to
//! m²/s²), so it is a typesetting error. Eq. (18) is the plate-normal rebound speed over the
//! plate-normal impact speed; it equals (v_x − v_y)/v₀. Since v_x, v_y and v₀ all scale as
//! √g, e does not depend on the value of g.
//!
//! CSV columns (mm): `drop_height_mm` (h), `h1_mm`, `s1_mm`, `h2_mm`, `s2_mm`.
//!
//! ```
//! use arachis::lab::restitution_plate::{rebound_velocity, restitution_45};
//! // Two landing points of the parabola v_x = 1, v_y = 0.2 m/s (g = 9.81), v₀ = 2 m/s.
//! let g = 9.81;
//! let land = |t: f64| (0.2 * t + g * t * t / 2.0, t);
//! let ((h1, s1), (h2, s2)) = (land(0.3), land(0.2));
//! let (vx, vy) = rebound_velocity(h1, s1, h2, s2, g).unwrap();
//! assert!((vx - 1.0).abs() < 1e-12 && (vy - 0.2).abs() < 1e-12);
//! assert!((restitution_45(vx, vy, 2.0) - 0.4).abs() < 1e-12);
//! ```

use std::f64::consts::FRAC_PI_4;

use super::columns::{lines, positive, row_error};
use super::error::LabError;
use super::report::{LabReport, Quantity, Value};
use super::units::{M_PER_MM, STANDARD_GRAVITY};
use crate::io::CsvTable;

/// Column: fall height from release to the impact point O, mm.
pub const DROP_COLUMN: &str = "drop_height_mm";
/// Columns of the first landing point: depth below O and horizontal distance, mm.
pub const FIRST_COLUMNS: [&str; 2] = ["h1_mm", "s1_mm"];
/// Columns of the second landing point, mm.
pub const SECOND_COLUMNS: [&str; 2] = ["h2_mm", "s2_mm"];

/// Impact speed v₀ = √(2 g h) in m/s after a free fall of `h_m` (m) under `g` (m/s²).
/// Seed 000 eq. (14).
pub fn impact_speed(h_m: f64, g: f64) -> f64 {
    (2.0 * g * h_m).sqrt()
}

/// Rebound velocity (v_x horizontal, v_y downward), m/s, from two landing points of one
/// parabola: depths `h1`, `h2` (m) below the impact point at horizontal distances `s1`,
/// `s2` (m), gravity `g` (m/s²). Seed 000 eqs. (15)–(16). `None` when the points fit no
/// parabola through O with v_x > 0.
pub fn rebound_velocity(h1: f64, s1: f64, h2: f64, s2: f64, g: f64) -> Option<(f64, f64)> {
    let vx2 = g * s1 * s2 * (s1 - s2) / (2.0 * (h1 * s2 - h2 * s1));
    if !(vx2.is_finite() && vx2 > 0.0) {
        return None;
    }
    let vx = vx2.sqrt();
    Some((vx, h1 * vx / s1 - g * s1 / (2.0 * vx)))
}

/// Restitution on the 45° plate, seed 000 eq. (18): rebound speed normal to the plate over
/// impact speed `v0` normal to it; `vx` horizontal and `vy` downward rebound speeds (m/s).
pub fn restitution_45(vx: f64, vy: f64, v0: f64) -> f64 {
    (vx * vx + vy * vy).sqrt() * (FRAC_PI_4 + (vy / vx).atan()).cos() / (v0 * FRAC_PI_4.sin())
}

/// Restitution of every replicate in `table`.
pub fn analyze(table: &CsvTable) -> Result<LabReport, LabError> {
    let g = STANDARD_GRAVITY;
    let h = positive(table, DROP_COLUMN, "drop height")?;
    let h1 = positive(table, FIRST_COLUMNS[0], "landing depth")?;
    let s1 = positive(table, FIRST_COLUMNS[1], "landing distance")?;
    let h2 = positive(table, SECOND_COLUMNS[0], "landing depth")?;
    let s2 = positive(table, SECOND_COLUMNS[1], "landing distance")?;
    let all = [
        FIRST_COLUMNS[0],
        FIRST_COLUMNS[1],
        SECOND_COLUMNS[0],
        SECOND_COLUMNS[1],
    ];
    let (mut e, mut vx, mut vy, mut v0) = (vec![], vec![], vec![], vec![]);
    for i in 0..lines(table).len() {
        let (x, y) = rebound_velocity(
            h1[i] * M_PER_MM,
            s1[i] * M_PER_MM,
            h2[i] * M_PER_MM,
            s2[i] * M_PER_MM,
            g,
        )
        .ok_or_else(|| {
            row_error(
                table,
                i,
                &all,
                "the two landing points fit no rebound parabola (need s1 ≠ s2 and h1·s2 − h2·s1 of the sign of s1 − s2)".to_owned(),
            )
        })?;
        let speed = impact_speed(h[i] * M_PER_MM, g);
        let coefficient = restitution_45(x, y, speed);
        if coefficient <= 0.0 {
            return Err(row_error(
                table,
                i,
                &all,
                format!("the rebound (v_x {x:.3} m/s, v_y {y:.3} m/s down) points into the plate"),
            ));
        }
        e.push(coefficient);
        vx.push(x);
        vy.push(y);
        v0.push(speed);
    }
    let mut report = LabReport::new("restitution-plate", table);
    report.settings.push(Value::new("gravity", g, "m/s^2"));
    report.settings.push(Value::new("plate_angle", 45.0, "deg"));
    report
        .quantities
        .push(Quantity::new(table, "restitution", "1", &e)?);
    report
        .quantities
        .push(Quantity::new(table, "impact_speed", "m/s", &v0)?);
    report
        .quantities
        .push(Quantity::new(table, "rebound_vx", "m/s", &vx)?);
    report
        .quantities
        .push(Quantity::new(table, "rebound_vy_down", "m/s", &vy)?);
    report.notes.push(
        "v_y solved from eq. (16) as h1·v_x/s1 − g·s1/(2v_x); seed 000 eq. (15) prints a dimensionally inconsistent v_y".to_owned(),
    );
    Ok(report)
}
