//! Coefficient of restitution from 3-D high-speed-camera coordinates, seed 001 eqs. (2)–(12),
//! with the rotational-energy share of eqs. (13)–(15).
//!
//! The camera sees the pod against a reference wall (Y, Z) and in a mirror (X, Z); Z is up.
//! Before impact the pod falls from height Z_a to the impact height Z₀ in time t_a; the
//! mean speed over that interval is the speed at its middle, so the impact speed is
//! v₁ = (Z_a − Z₀)/t_a + g t_a/2 (eq. (4)). After impact it reaches (X_n, Y_n, Z_n) in time
//! t_n from (X₀, Y₀, Z₀), so v_x = (X_n − X₀)/t_n, v_y = (Y_n − Y₀)/t_n and
//! v_z = (Z_n − Z₀)/t_n + g t_n/2 (eqs. (9)–(11)); e = |v₂|/v₁ (eqs. (2), (12)).
//!
//! On a plate inclined at α (about X), seed 001 eq. (7) turns the axes:
//! Y′ = Y cos α + Z sin α, Z′ = Z cos α − Y sin α, and eq. (8) splits e into a normal
//! part e_n = v′_z/(v₁ cos α) and a tangential part e_t = √(v_x² + v′_y²)/(v₁ sin α). Seed
//! 001 prints eq. (8) with sin α and cos α exchanged, which with its own eq. (7) would give
//! e_n = ∞ on a level plate; we follow eq. (7).
//!
//! CSV columns: `za_mm`, `z0_mm`, `ta_s` (fall), `x0_mm`, `y0_mm`, `xn_mm`, `yn_mm`, `zn_mm`,
//! `tn_s` (rebound). Optional, all together, for the rotational share: `mass_g`,
//! `length_mm`, `width_mm`, `thickness_mm`, `wx_rad_s`, `wy_rad_s`, `wz_rad_s` (angular
//! velocity about the pod's width, thickness and length axes).
//!
//! ```
//! use arachis::lab::restitution_camera::{impact_speed, rebound_velocity};
//! let g: f64 = 9.81;
//! // A fall of 0.5 m from rest takes t = √(2·0.5/g); v₁ = g t.
//! let t = (1.0 / g).sqrt();
//! assert!((impact_speed(0.5, 0.0, t, g) - g * t).abs() < 1e-12);
//! // Rebound straight up at 1 m/s, seen 0.05 s later.
//! let tn = 0.05;
//! let v = rebound_velocity([0.0; 3], [0.0, 0.0, tn - g * tn * tn / 2.0], tn, g);
//! assert!((v[2] - 1.0).abs() < 1e-12);
//! ```

use super::columns::{has, positive, row_error};
use super::error::LabError;
use super::report::{LabReport, Quantity, Value};
use super::rotation_energy::{
    ellipsoid_inertia, rotational_energy, rotational_share, translational_energy,
};
use super::units::{KG_PER_G, M_PER_MM, STANDARD_GRAVITY};
use crate::io::CsvTable;

/// Fall columns: start height Z_a (mm), impact height Z₀ (mm), fall time t_a (s).
pub const FALL_COLUMNS: [&str; 3] = ["za_mm", "z0_mm", "ta_s"];
/// Impact-point columns X₀, Y₀ (mm); Z₀ is in [`FALL_COLUMNS`].
pub const IMPACT_COLUMNS: [&str; 2] = ["x0_mm", "y0_mm"];
/// Rebound columns: X_n, Y_n, Z_n (mm) and t_n (s).
pub const REBOUND_COLUMNS: [&str; 4] = ["xn_mm", "yn_mm", "zn_mm", "tn_s"];
/// Optional columns for the rotational share.
pub const ROTATION_COLUMNS: [&str; 7] = [
    "mass_g",
    "length_mm",
    "width_mm",
    "thickness_mm",
    "wx_rad_s",
    "wy_rad_s",
    "wz_rad_s",
];

/// Largest plate inclination accepted: at 90° the plate is a wall the pod cannot fall onto.
pub const MAX_PLATE_ANGLE_DEG: f64 = 90.0;

/// Impact speed v₁ (m/s) after falling from height `za` to `z0` (m) in `ta` (s) under `g`
/// (m/s²). Seed 001 eq. (4).
pub fn impact_speed(za: f64, z0: f64, ta: f64, g: f64) -> f64 {
    (za - z0) / ta + 0.5 * g * ta
}

/// Rebound velocity (v_x, v_y, v_z) in m/s, Z up, from the impact position `p0` and the
/// position `pn` (m) a time `tn` (s) later. Seed 001 eqs. (9)–(11).
pub fn rebound_velocity(p0: [f64; 3], pn: [f64; 3], tn: f64, g: f64) -> [f64; 3] {
    [
        (pn[0] - p0[0]) / tn,
        (pn[1] - p0[1]) / tn,
        (pn[2] - p0[2]) / tn + 0.5 * g * tn,
    ]
}

/// Normal and tangential restitution (e_n, e_t) on a plate inclined at `alpha_rad`, from
/// the rebound velocity `v` (m/s, level-frame axes) and the vertical impact speed `v1`
/// (m/s). e_t is `None` on a level plate, where the impact has no tangential part.
/// Seed 001 eqs. (7)–(8).
pub fn normal_tangential(v: [f64; 3], v1: f64, alpha_rad: f64) -> (f64, Option<f64>) {
    let (s, c) = alpha_rad.sin_cos();
    let vy_t = v[1] * c + v[2] * s;
    let vz_t = v[2] * c - v[1] * s;
    let e_n = vz_t / (v1 * c);
    let e_t = (alpha_rad > 0.0).then(|| (v[0] * v[0] + vy_t * vy_t).sqrt() / (v1 * s));
    (e_n, e_t)
}

/// Options of the camera analysis.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CameraOptions {
    /// Plate inclination α, degrees, in [0°, 90°).
    pub plate_angle_deg: f64,
}

/// Restitution (and, with the optional columns, rotational share) of every replicate.
pub fn analyze(table: &CsvTable, options: CameraOptions) -> Result<LabReport, LabError> {
    let alpha = options.plate_angle_deg;
    if !(0.0..MAX_PLATE_ANGLE_DEG).contains(&alpha) {
        return Err(LabError::Option {
            option: "plate-angle-deg".into(),
            reason: format!("plate inclination must be in [0°, 90°), got {alpha}°"),
        });
    }
    let g = STANDARD_GRAVITY;
    let num = |name: &str| {
        table
            .f64_column(name)
            .map(|v| v.iter().map(|x| x * M_PER_MM).collect::<Vec<_>>())
    };
    let (za, z0) = (num(FALL_COLUMNS[0])?, num(FALL_COLUMNS[1])?);
    let ta = positive(table, FALL_COLUMNS[2], "fall time")?;
    let (x0, y0) = (num(IMPACT_COLUMNS[0])?, num(IMPACT_COLUMNS[1])?);
    let (xn, yn, zn) = (
        num(REBOUND_COLUMNS[0])?,
        num(REBOUND_COLUMNS[1])?,
        num(REBOUND_COLUMNS[2])?,
    );
    let tn = positive(table, REBOUND_COLUMNS[3], "rebound time")?;
    let rotation = ROTATION_COLUMNS.iter().any(|c| has(table, c));
    let rot = if rotation {
        let m = positive(table, ROTATION_COLUMNS[0], "mass")?;
        let l = positive(table, ROTATION_COLUMNS[1], "pod length")?;
        let w = positive(table, ROTATION_COLUMNS[2], "pod width")?;
        let h = positive(table, ROTATION_COLUMNS[3], "pod thickness")?;
        let wx = table.f64_column(ROTATION_COLUMNS[4])?;
        let wy = table.f64_column(ROTATION_COLUMNS[5])?;
        let wz = table.f64_column(ROTATION_COLUMNS[6])?;
        Some((m, l, w, h, wx, wy, wz))
    } else {
        None
    };
    // Fall height must be non-negative; checked on the raw column so the line is named.
    non_negative_fall(table, &za, &z0)?;
    let mut e = vec![];
    let (mut en, mut et, mut v1s, mut er, mut eta) = (vec![], vec![], vec![], vec![], vec![]);
    for i in 0..table.rows.len() {
        let v1 = impact_speed(za[i], z0[i], ta[i], g);
        if v1 <= 0.0 {
            return Err(row_error(
                table,
                i,
                &FALL_COLUMNS,
                format!("impact speed {v1:.4} m/s is not positive"),
            ));
        }
        let v = rebound_velocity([x0[i], y0[i], z0[i]], [xn[i], yn[i], zn[i]], tn[i], g);
        let v2 = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        e.push(v2 / v1);
        let (n, t) = normal_tangential(v, v1, alpha.to_radians());
        en.push(n);
        if let Some(t) = t {
            et.push(t);
        }
        v1s.push(v1);
        if let Some((m, l, w, h, wx, wy, wz)) = &rot {
            let mass = m[i] * KG_PER_G;
            let inertia =
                ellipsoid_inertia(mass, l[i] * M_PER_MM, w[i] * M_PER_MM, h[i] * M_PER_MM);
            let rotational = rotational_energy(inertia, [wx[i], wy[i], wz[i]]);
            er.push(rotational);
            eta.push(rotational_share(rotational, translational_energy(mass, v)));
        }
    }
    let mut report = LabReport::new("restitution-camera", table);
    report.settings.push(Value::new("gravity", g, "m/s^2"));
    report
        .settings
        .push(Value::new("plate_angle", alpha, "deg"));
    report
        .quantities
        .push(Quantity::new(table, "restitution", "1", &e)?);
    report
        .quantities
        .push(Quantity::new(table, "restitution_normal", "1", &en)?);
    if !et.is_empty() {
        report
            .quantities
            .push(Quantity::new(table, "restitution_tangential", "1", &et)?);
    }
    report
        .quantities
        .push(Quantity::new(table, "impact_speed", "m/s", &v1s)?);
    if rotation {
        report
            .quantities
            .push(Quantity::new(table, "rotational_energy", "J", &er)?);
        report
            .quantities
            .push(Quantity::new(table, "rotational_share", "1", &eta)?.shown_in("%", 100.0));
    }
    if alpha > 0.0 {
        report.notes.push(
            "e_n, e_t follow seed 001 eq. (7)'s rotation; its eq. (8) prints sin α and cos α exchanged".to_owned(),
        );
    }
    Ok(report)
}

/// Rejects a row whose start height Z_a is below the impact height Z₀.
fn non_negative_fall(table: &CsvTable, za: &[f64], z0: &[f64]) -> Result<(), LabError> {
    for i in 0..za.len() {
        if za[i] < z0[i] {
            return Err(row_error(
                table,
                i,
                &FALL_COLUMNS[..2],
                format!(
                    "start height {} mm is below the impact height {} mm",
                    za[i] / M_PER_MM,
                    z0[i] / M_PER_MM
                ),
            ));
        }
    }
    Ok(())
}
