//! Apparent elastic modulus of a convex body squeezed between two flat plates, by the
//! Hertz method of ASAE S368.4 (seed 000 eqs. (9)–(11); seed 001 eqs. (19)–(22)).
//!
//! ```text
//! E = 0.338 F (1 − μ²) / D^(3/2) · [K_U (1/R_U + 1/R′_U)^(1/3) + K_L (1/R_L + 1/R′_L)^(1/3)]^(3/2)
//! ```
//!
//! F is the force, D the total deformation (both contacts), μ Poisson's ratio, R and R′ the
//! principal radii of curvature at the upper (U) and lower (L) plate contacts, and K(θ) the
//! Hertz coefficient with cos θ from the radii ([`super::hertz_k`]). The formula is
//! homogeneous: seed 000 feeds it N and mm and reads MPa; this API takes N and m and
//! returns Pa. When the two contacts are alike, eq. (11) replaces the bracket by
//! 2K(1/R + 1/R′)^(1/3).
//!
//! Seed 001's variant takes the radii from the pod's thickness H and length L:
//! R = H/2 and R′ = (H² + (L/2)²)/(2H) (seed 001 eqs. (21)–(22)), the same at both plates.
//!
//! CSV columns: `force_n` (F, N), `deformation_mm` (D, mm, > 0), and either
//! `upper_r1_mm`, `upper_r2_mm` (principal radii at the upper contact, mm, either order)
//! with optional `lower_r1_mm`, `lower_r2_mm` (else eq. (11)), or `length_mm`,
//! `thickness_mm` (seed 001). Poisson's ratio comes from `--poisson` or a `poisson` column.
//!
//! ```
//! use arachis::lab::hertz_modulus::{apparent_modulus_eq11, KMethod};
//! // A sphere (R = R' = 10 mm): 20 N, 0.5 mm total deformation, μ = 0.386. Classical Hertz
//! // for two equal sphere-plate contacts gives E = (3/4)F(1 − μ²)/(√R (D/2)^(3/2)); eq. (11)
//! // differs only by the rounding of 0.337618 to 0.338.
//! let (f, d, mu, r) = (20.0, 0.5e-3, 0.386, 10e-3);
//! let e = apparent_modulus_eq11(f, d, mu, r, r, KMethod::Elliptic).unwrap();
//! let hertz = 0.75 * f * (1.0 - mu * mu) / (r.sqrt() * (d / 2.0_f64).powf(1.5));
//! assert!((e.modulus_pa / (hertz * 0.338 / 0.337618) - 1.0).abs() < 1e-5);
//! ```

use super::columns::{has, positive};
use super::error::LabError;
use super::hertz_k::{cos_theta, k_elliptic, k_table};
use super::report::{LabReport, Quantity, Value};
use super::shear_modulus::{poisson_column, shear_modulus, POISSON_MAX};
use super::units::{M_PER_MM, PA_PER_MPA};
use crate::io::CsvTable;

/// The constant of ASAE S368.4 eq. (9) as printed; Hertz's exact value is
/// 3/(2√2·π) = 0.337618 (see [`super::hertz_k`]). We use the printed value so that results
/// agree with the standard and the seeds.
pub const ASAE_CONSTANT: f64 = 0.338;

/// Column: compression force F, N.
pub const FORCE_COLUMN: &str = "force_n";
/// Column: total deformation D, mm.
pub const DEFORMATION_COLUMN: &str = "deformation_mm";
/// Columns: principal radii at the upper contact, mm.
pub const UPPER_COLUMNS: [&str; 2] = ["upper_r1_mm", "upper_r2_mm"];
/// Columns: principal radii at the lower contact, mm (optional).
pub const LOWER_COLUMNS: [&str; 2] = ["lower_r1_mm", "lower_r2_mm"];
/// Column (seed 001 variant): pod length L, mm.
pub const LENGTH_COLUMN: &str = "length_mm";
/// Column (seed 001 variant): pod thickness H, mm.
pub const THICKNESS_COLUMN: &str = "thickness_mm";
/// Column: Poisson's ratio, used when `--poisson` is not given.
pub const POISSON_COLUMN: &str = "poisson";

/// How K(θ) is obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum KMethod {
    /// Hertz's elliptic-integral solution: any θ in (0°, 90°].
    #[default]
    Elliptic,
    /// Linear interpolation in seed 000 Table 2: θ in [50°, 85°] only.
    Table,
}

/// One plate contact: its θ and K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactShape {
    /// Auxiliary angle θ, degrees.
    pub theta_deg: f64,
    /// Hertz coefficient K(θ), dimensionless.
    pub k: f64,
}

/// θ and K for principal radii `r1`, `r2` (any one length unit); `None` when `method` has no
/// K for that θ (outside the table).
pub fn contact_shape(r1: f64, r2: f64, method: KMethod) -> Option<ContactShape> {
    let theta_deg = cos_theta(r1, r2).acos().to_degrees();
    let k = match method {
        KMethod::Elliptic => k_elliptic(theta_deg.to_radians())?,
        KMethod::Table => k_table(theta_deg)?,
    };
    Some(ContactShape { theta_deg, k })
}

/// Apparent modulus E (Pa) by seed 000 eq. (9): force `force_n` (N), total deformation
/// `deformation_m` (m), Poisson's ratio `mu`, and each contact's K with its principal radii
/// (m) as `(k, r1, r2)`.
pub fn apparent_modulus(
    force_n: f64,
    deformation_m: f64,
    mu: f64,
    contacts: &[(f64, f64, f64)],
) -> f64 {
    let bracket: f64 = contacts
        .iter()
        .map(|&(k, r1, r2)| k * (1.0 / r1 + 1.0 / r2).cbrt())
        .sum();
    ASAE_CONSTANT * force_n * (1.0 - mu * mu) / deformation_m.powf(1.5) * bracket.powf(1.5)
}

/// Result of eq. (11): the modulus and the shape of the (identical) contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eq11 {
    /// Apparent elastic modulus, Pa.
    pub modulus_pa: f64,
    /// θ and K of each contact.
    pub shape: ContactShape,
}

/// Apparent modulus (Pa) by seed 000 eq. (11), the same radii `r1`, `r2` (m) at both plates;
/// `None` when `method` has no K for their θ.
pub fn apparent_modulus_eq11(
    force_n: f64,
    deformation_m: f64,
    mu: f64,
    r1: f64,
    r2: f64,
    method: KMethod,
) -> Option<Eq11> {
    let shape = contact_shape(r1, r2, method)?;
    let contact = (shape.k, r1, r2);
    Some(Eq11 {
        modulus_pa: apparent_modulus(force_n, deformation_m, mu, &[contact, contact]),
        shape,
    })
}

/// Seed 001 eqs. (21)–(22): (R, R′) = (H/2, (H² + (L/2)²)/(2H)) from pod length `length` and
/// thickness `thickness` (any one length unit; the radii come out in it).
pub fn seed001_radii(length: f64, thickness: f64) -> (f64, f64) {
    let r = thickness / 2.0;
    let r_prime = (thickness.powi(2) + (length / 2.0).powi(2)) / (2.0 * thickness);
    (r, r_prime)
}

/// Options of the Hertz analysis.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HertzOptions {
    /// Poisson's ratio for every replicate; when `None` the `poisson` column is used.
    pub poisson: Option<f64>,
    /// How K(θ) is obtained.
    pub k_method: KMethod,
}

/// Radii (m) of each contact for every row, and the columns they came from.
struct Geometry {
    upper: Vec<(f64, f64)>,
    lower: Option<Vec<(f64, f64)>>,
    upper_columns: Vec<&'static str>,
    lower_columns: Vec<&'static str>,
    note: &'static str,
}

fn radii_pair(table: &CsvTable, cols: [&str; 2]) -> Result<Vec<(f64, f64)>, LabError> {
    let a = positive(table, cols[0], "radius of curvature")?;
    let b = positive(table, cols[1], "radius of curvature")?;
    Ok(a.iter()
        .zip(&b)
        .map(|(a, b)| (a * M_PER_MM, b * M_PER_MM))
        .collect())
}

fn geometry(table: &CsvTable) -> Result<Geometry, LabError> {
    if has(table, UPPER_COLUMNS[0]) || has(table, UPPER_COLUMNS[1]) {
        let upper = radii_pair(table, UPPER_COLUMNS)?;
        let lower_present = has(table, LOWER_COLUMNS[0]) || has(table, LOWER_COLUMNS[1]);
        let lower = if lower_present {
            Some(radii_pair(table, LOWER_COLUMNS)?)
        } else {
            None
        };
        Ok(Geometry {
            upper,
            lower_columns: if lower_present {
                LOWER_COLUMNS.to_vec()
            } else {
                UPPER_COLUMNS.to_vec()
            },
            lower,
            upper_columns: UPPER_COLUMNS.to_vec(),
            note: if lower_present {
                "seed 000 eq. (9): upper and lower contacts from their own radii"
            } else {
                "seed 000 eq. (11): lower contact taken equal to the upper one"
            },
        })
    } else if has(table, LENGTH_COLUMN) && has(table, THICKNESS_COLUMN) {
        let l = positive(table, LENGTH_COLUMN, "pod length")?;
        let h = positive(table, THICKNESS_COLUMN, "pod thickness")?;
        let upper = l
            .iter()
            .zip(&h)
            .map(|(l, h)| seed001_radii(l * M_PER_MM, h * M_PER_MM))
            .collect();
        Ok(Geometry {
            upper,
            lower: None,
            upper_columns: vec![LENGTH_COLUMN, THICKNESS_COLUMN],
            lower_columns: vec![LENGTH_COLUMN, THICKNESS_COLUMN],
            note: "seed 001 eqs. (21)–(22): R = H/2, R' = (H^2 + (L/2)^2)/(2H) at both plates",
        })
    } else {
        Err(LabError::Layout {
            path: table.path.clone(),
            reason: format!(
                "needs the contact radii '{}', '{}' (optionally '{}', '{}') or the pod size '{}', '{}' (columns: {})",
                UPPER_COLUMNS[0],
                UPPER_COLUMNS[1],
                LOWER_COLUMNS[0],
                LOWER_COLUMNS[1],
                LENGTH_COLUMN,
                THICKNESS_COLUMN,
                table.headers.join(", ")
            ),
        })
    }
}

/// Poisson's ratio per row: the option if given, else the `poisson` column.
pub fn poisson_per_row(table: &CsvTable, option: Option<f64>) -> Result<Vec<f64>, LabError> {
    match option {
        Some(mu) if (0.0..=POISSON_MAX).contains(&mu) => Ok(vec![mu; table.rows.len()]),
        Some(mu) => Err(LabError::Option {
            option: "poisson".into(),
            reason: format!("Poisson's ratio must be in [0, {POISSON_MAX}], got {mu}"),
        }),
        None if has(table, POISSON_COLUMN) => poisson_column(table, POISSON_COLUMN),
        None => Err(LabError::Layout {
            path: table.path.clone(),
            reason: format!("needs Poisson's ratio: give --poisson or a '{POISSON_COLUMN}' column"),
        }),
    }
}

/// Apparent elastic modulus (and G by eq. (12)) of every replicate in `table`.
pub fn analyze(table: &CsvTable, options: HertzOptions) -> Result<LabReport, LabError> {
    let force = positive(table, FORCE_COLUMN, "compression force")?;
    let deformation = positive(table, DEFORMATION_COLUMN, "deformation")?;
    let geo = geometry(table)?;
    let mu = poisson_per_row(table, options.poisson)?;
    let shape_of = |i: usize, (r1, r2): (f64, f64), cols: &[&str]| {
        contact_shape(r1, r2, options.k_method).ok_or_else(|| {
            let theta = cos_theta(r1, r2).acos().to_degrees();
            let reason = match options.k_method {
                KMethod::Table => format!(
                    "θ = {theta:.2}° is outside seed 000 Table 2 (50°–85°); use --k-from elliptic"
                ),
                // Only θ = 0 (one radius negligible against the other) has no K.
                KMethod::Elliptic => format!(
                    "θ = {theta:.2}°: the radii describe a line contact, outside Hertz's point-contact solution"
                ),
            };
            super::columns::row_error(table, i, cols, reason)
        })
    };
    let n = table.rows.len();
    let (mut e, mut g, mut th_u, mut k_u, mut th_l, mut k_l) =
        (vec![], vec![], vec![], vec![], vec![], vec![]);
    for i in 0..n {
        let upper = shape_of(i, geo.upper[i], &geo.upper_columns)?;
        let lower_radii = geo.lower.as_ref().map_or(geo.upper[i], |l| l[i]);
        let lower = shape_of(i, lower_radii, &geo.lower_columns)?;
        let contacts = [
            (upper.k, geo.upper[i].0, geo.upper[i].1),
            (lower.k, lower_radii.0, lower_radii.1),
        ];
        let modulus = apparent_modulus(force[i], deformation[i] * M_PER_MM, mu[i], &contacts);
        e.push(modulus);
        g.push(shear_modulus(modulus, mu[i]));
        th_u.push(upper.theta_deg);
        k_u.push(upper.k);
        th_l.push(lower.theta_deg);
        k_l.push(lower.k);
    }
    let mut report = LabReport::new("hertz-modulus", table);
    if let Some(mu) = options.poisson {
        report.settings.push(Value::new("poisson", mu, "1"));
    }
    report.notes.push(
        match options.k_method {
            KMethod::Elliptic => "K(θ) from Hertz's elliptic-integral solution",
            KMethod::Table => "K(θ) interpolated in seed 000 Table 2",
        }
        .to_owned(),
    );
    let mpa = 1.0 / PA_PER_MPA;
    report
        .quantities
        .push(Quantity::new(table, "apparent_modulus", "Pa", &e)?.shown_in("MPa", mpa));
    report
        .quantities
        .push(Quantity::new(table, "shear_modulus", "Pa", &g)?.shown_in("MPa", mpa));
    report
        .quantities
        .push(Quantity::new(table, "theta_upper", "deg", &th_u)?);
    report
        .quantities
        .push(Quantity::new(table, "k_upper", "1", &k_u)?);
    if geo.lower.is_some() {
        report
            .quantities
            .push(Quantity::new(table, "theta_lower", "deg", &th_l)?);
        report
            .quantities
            .push(Quantity::new(table, "k_lower", "1", &k_l)?);
    }
    report.notes.push(geo.note.to_owned());
    report.notes.push(
        "cos θ = |1/R − 1/R'|/(1/R + 1/R') per contact (ASAE S368.4, seed 001 eq. (20)); seed 000 eq. (10) as printed also divides by the other contact's curvatures".to_owned(),
    );
    Ok(report)
}
