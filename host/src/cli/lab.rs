//! `arachis lab <test> FILE.csv [--json]`: bench-test analysis.
//!
//! Each test reads one CSV of replicates (a header row, one replicate per row, `#` starts a
//! comment line; column headers carry their units) and prints the replicate summary of each
//! derived quantity as a table, or as one JSON object with `--json` (SI units, stated in
//! each record). `--help` on a test lists its columns.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Subcommand;

use crate::io::CsvTable;
use crate::lab::{
    bond, density, hertz_modulus, poisson, restitution_camera, restitution_plate, rolling_friction,
    shear_modulus, static_friction, tensile_modulus, LabReport,
};

/// Arguments of `arachis lab`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The bench test to analyse.
    #[command(subcommand)]
    pub test: LabTest,
    /// Print one JSON object (SI units) instead of the table.
    #[arg(long, global = true)]
    pub json: bool,
}

/// A CSV file of replicates.
#[derive(Debug, clap::Args)]
pub struct FileArg {
    /// CSV file, one replicate per row.
    pub file: PathBuf,
}

/// Options of `lab hertz-modulus`.
#[derive(Debug, clap::Args)]
pub struct HertzArgs {
    /// CSV file, one replicate per row.
    pub file: PathBuf,
    /// Poisson's ratio for every replicate (else the `poisson` column).
    #[arg(long)]
    pub poisson: Option<f64>,
    /// Where K(θ) comes from: Hertz's elliptic-integral solution (any θ) or seed 000
    /// Table 2 (50°–85°, interpolated).
    #[arg(long, value_enum, default_value_t = hertz_modulus::KMethod::Elliptic)]
    pub k_from: hertz_modulus::KMethod,
}

/// Options of `lab restitution-camera`.
#[derive(Debug, clap::Args)]
pub struct CameraArgs {
    /// CSV file, one replicate per row.
    pub file: PathBuf,
    /// Inclination α of the collision plate, degrees in [0, 90); above 0 the normal and
    /// tangential restitution are reported too.
    #[arg(long, default_value_t = 0.0)]
    pub plate_angle_deg: f64,
}

/// Options of `lab rolling-friction`.
#[derive(Debug, clap::Args)]
pub struct RollingArgs {
    /// CSV file, one replicate per row.
    pub file: PathBuf,
    /// With `height_mm`: use seed 000 eq. (20) exactly as printed (H cos θ) instead of the
    /// energy balance (H cot θ).
    #[arg(long)]
    pub as_printed: bool,
}

/// Options of `lab bond`.
#[derive(Debug, clap::Args)]
pub struct BondArgs {
    /// CSV file, one replicate per row.
    pub file: PathBuf,
    /// Internal friction angle φ, degrees: reports τ = σ tan φ + c.
    #[arg(long)]
    pub friction_angle_deg: Option<f64>,
    /// Cohesion c, Pa (with --friction-angle-deg).
    #[arg(long, default_value_t = 0.0)]
    pub cohesion_pa: f64,
    /// Elastic modulus of particle a, MPa (with the other particle options: K_n, K_s).
    #[arg(long, requires_all = ["poisson_a", "radius_a_mm", "modulus_b_mpa", "poisson_b", "radius_b_mm"])]
    pub modulus_a_mpa: Option<f64>,
    /// Poisson's ratio of particle a.
    #[arg(long, requires = "modulus_a_mpa")]
    pub poisson_a: Option<f64>,
    /// Radius of particle a, mm.
    #[arg(long, requires = "modulus_a_mpa")]
    pub radius_a_mm: Option<f64>,
    /// Elastic modulus of particle b, MPa.
    #[arg(long, requires = "modulus_a_mpa")]
    pub modulus_b_mpa: Option<f64>,
    /// Poisson's ratio of particle b.
    #[arg(long, requires = "modulus_a_mpa")]
    pub poisson_b: Option<f64>,
    /// Radius of particle b, mm.
    #[arg(long, requires = "modulus_a_mpa")]
    pub radius_b_mm: Option<f64>,
}

/// The `lab` subcommands: the CSV analyses, and the repose angle from a photograph.
#[derive(Debug, Subcommand)]
pub enum LabTest {
    /// A bench test whose replicates come as a CSV file.
    #[command(flatten)]
    Csv(Test),
    /// Repose (stacking) angle from a side photograph of a pile (seed 000 §3.6.1).
    Repose(super::lab_repose::Args),
    /// Repose angle of a pile of spheres from its final positions (another engine's dump),
    /// photographed as the repose rig photographs its own.
    ReposePile(super::lab_repose_pile::Args),
}

/// The bench tests analysed from a CSV file of replicates.
#[derive(Debug, Subcommand)]
pub enum Test {
    /// Density by displacement, ρ = m/ΔV (seed 000 §2.5.1).
    #[command(
        after_help = "CSV columns:\n  mass_g     pod mass, g (> 0)\n  volume_ml  rise of the water level with the pod held just under, mL (> 0)"
    )]
    Density(FileArg),
    /// Poisson's ratio, μ = (W'y/Wy)/(W'x/Wx) (seed 000 eq. 8).
    #[command(
        after_help = "CSV columns:\n  length_mm                  axial length Wx, mm (> 0)\n  width_mm                   transverse width Wy, mm (> 0)\n  axial_deformation_mm       axial deformation W'x, mm (> 0)\n  transverse_deformation_mm  transverse deformation W'y, mm (>= 0)"
    )]
    Poisson(FileArg),
    /// Apparent elastic modulus by ASAE S368.4 Hertz contact (seed 000 eqs. 9-11, seed 001
    /// eqs. 19-22), with G = E/(2(1+μ)).
    #[command(
        after_help = "CSV columns:\n  force_n         compression force F, N (> 0)\n  deformation_mm  total deformation D, mm (> 0)\nthen either the contact radii (seed 000)\n  upper_r1_mm, upper_r2_mm  principal radii of curvature at the upper plate, mm (either order)\n  lower_r1_mm, lower_r2_mm  optional; without them the lower contact equals the upper (eq. 11)\nor the pod size (seed 001: R = H/2, R' = (H^2 + (L/2)^2)/(2H))\n  length_mm, thickness_mm   pod length L and thickness H, mm\nand, unless --poisson is given,\n  poisson         Poisson's ratio, in [0, 0.5]"
    )]
    HertzModulus(HertzArgs),
    /// Shear modulus G = E/(2(1+μ)) (seed 000 eq. 12).
    #[command(
        after_help = "CSV columns:\n  modulus_mpa  elastic modulus E, MPa (> 0)\n  poisson      Poisson's ratio, in [0, 0.5]"
    )]
    ShearModulus(FileArg),
    /// Tensile modulus E2 = F·L/(A·ΔL) (seed 001 eq. 23).
    #[command(
        after_help = "CSV columns:\n  force_n        tensile force F, N (> 0)\n  length_mm      effective specimen length L, mm (> 0)\n  elongation_mm  elongation ΔL, mm (> 0)\n  area_mm2       cross-section A, mm² (> 0), or instead\n  diameter_mm    specimen diameter D, mm (A = πD²/4)"
    )]
    TensileModulus(FileArg),
    /// Restitution from the 45° plate rig (seed 000 eqs. 13-18).
    #[command(
        after_help = "CSV columns (mm, all > 0):\n  drop_height_mm  free-fall height h from release to the impact point O\n  h1_mm, s1_mm    first landing point: depth below O, horizontal distance from O\n  h2_mm, s2_mm    second landing point (plate at another height)"
    )]
    RestitutionPlate(FileArg),
    /// Restitution from 3-D high-speed-camera coordinates (seed 001 eqs. 2-12), with the
    /// rotational-energy share (eqs. 13-15).
    #[command(
        after_help = "CSV columns (Z up):\n  za_mm, z0_mm, ta_s         height at the start of the fall, height at impact (mm), fall time (s)\n  x0_mm, y0_mm               impact point X, Y, mm\n  xn_mm, yn_mm, zn_mm, tn_s  position after the rebound time tn (mm, s)\noptional, all together, for the rotational share (ellipsoid L/2, W/2, H/2):\n  mass_g                     pod mass, g\n  length_mm, width_mm, thickness_mm  pod L, W, H, mm\n  wx_rad_s, wy_rad_s, wz_rad_s       angular velocity about the width, thickness, length axes, rad/s"
    )]
    RestitutionCamera(CameraArgs),
    /// Static friction μs = tan θ on a tilting plate (seed 000 eq. 19, seed 001 eq. 1).
    #[command(
        after_help = "CSV columns:\n  angle_deg  critical tilt angle θ, degrees, in [0, 90)"
    )]
    StaticFriction(FileArg),
    /// Rolling friction by energy balance (seed 000 eq. 20, seed 001 eq. 17).
    #[command(
        after_help = "CSV columns:\n  angle_deg  plate inclination, degrees, in (0, 90)\n  level_mm   rolling distance on the level plate (l, S2), mm (>= 0)\nand either\n  slope_mm   rolling distance down the slope x, mm (seed 001: f = x sin α/(x cos α + l))\nor\n  height_mm  release height H2, mm (seed 000: γ = H/(H cot θ + S))"
    )]
    RollingFriction(RollingArgs),
    /// Bond parameters: σ = F/(πR²), τ = σ tan φ + c, Hertz K_n and K_s (seed 001
    /// eqs. 26-28).
    #[command(
        after_help = "CSV columns:\n  force_n    critical force F, N (> 0)\n  radius_mm  radius R of the compression (bond) surface, mm (> 0)"
    )]
    Bond(BondArgs),
}

fn read(path: &Path) -> anyhow::Result<CsvTable> {
    Ok(CsvTable::read(path)?)
}

/// Runs the chosen analysis on its file.
pub fn analyze(test: Test) -> anyhow::Result<LabReport> {
    Ok(match test {
        Test::Density(a) => density::analyze(&read(&a.file)?)?,
        Test::Poisson(a) => poisson::analyze(&read(&a.file)?)?,
        Test::HertzModulus(a) => hertz_modulus::analyze(
            &read(&a.file)?,
            hertz_modulus::HertzOptions {
                poisson: a.poisson,
                k_method: a.k_from,
            },
        )?,
        Test::ShearModulus(a) => shear_modulus::analyze(&read(&a.file)?)?,
        Test::TensileModulus(a) => tensile_modulus::analyze(&read(&a.file)?)?,
        Test::RestitutionPlate(a) => restitution_plate::analyze(&read(&a.file)?)?,
        Test::RestitutionCamera(a) => restitution_camera::analyze(
            &read(&a.file)?,
            restitution_camera::CameraOptions {
                plate_angle_deg: a.plate_angle_deg,
            },
        )?,
        Test::StaticFriction(a) => static_friction::analyze(&read(&a.file)?)?,
        Test::RollingFriction(a) => rolling_friction::analyze(
            &read(&a.file)?,
            rolling_friction::RollingOptions {
                as_printed: a.as_printed,
            },
        )?,
        Test::Bond(a) => {
            let particles = match (
                a.modulus_a_mpa,
                a.poisson_a,
                a.radius_a_mm,
                a.modulus_b_mpa,
                a.poisson_b,
                a.radius_b_mm,
            ) {
                (Some(ea), Some(nua), Some(ra), Some(eb), Some(nub), Some(rb)) => {
                    use crate::lab::units::{M_PER_MM, PA_PER_MPA};
                    Some((
                        (ea * PA_PER_MPA, nua, ra * M_PER_MM),
                        (eb * PA_PER_MPA, nub, rb * M_PER_MM),
                    ))
                }
                _ => None,
            };
            bond::analyze(
                &read(&a.file)?,
                bond::BondOptions {
                    friction_angle_deg: a.friction_angle_deg,
                    cohesion_pa: a.cohesion_pa,
                    particles,
                },
            )?
        }
    })
}

/// Runs `arachis lab`: prints the table, or one JSON object with `--json`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let test = match args.test {
        LabTest::Csv(test) => test,
        LabTest::Repose(photo) => return super::lab_repose::run(photo, args.json),
        LabTest::ReposePile(pile) => return super::lab_repose_pile::run(pile, args.json),
    };
    let report = analyze(test)?;
    let text = if args.json {
        format!("{}\n", serde_json::to_string(&report)?)
    } else {
        report.to_table()
    };
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        // A closed pipe (`| head`) is the reader's choice, not an error.
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.into()),
        _ => Ok(()),
    }
}
