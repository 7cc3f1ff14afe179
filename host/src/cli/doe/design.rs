//! `arachis doe design`: writes a design matrix as CSV, with coded and actual columns.
//!
//! ```text
//! arachis doe design --type bbd --factors x3:0.327:0.340,x4:0.848:0.858,x5:0.332:0.350 \
//!     --center 5 --out bbd.csv
//! ```
//!
//! The CSV has `run`, `std_order`, `point`, the coded columns `<name>_coded` and the actual
//! columns `<name>`, rows in standard order; comment lines give each factor's unit and levels
//! (see [`crate::doe::design_csv`]). The file is written atomically: on any error no file is
//! left behind.

use crate::count_limits::{count, MAX_CENTRE_POINTS, MAX_DESIGN_POINTS};
use std::path::PathBuf;

use anyhow::{bail, Context};

use crate::doe::{
    box_behnken, central_composite, design_to_csv, fractional_factorial, full_factorial,
    plackett_burman, steepest_ascent, Alpha, Design, Factor, PlackettBurmanRuns,
};
use crate::io::write_string_atomic;

/// Centre points of a Box–Behnken or central composite design when `--center` is not given
/// (seed 000 Table 8 and seed 001 Table 10 both use 5).
const DEFAULT_RSM_CENTRE_POINTS: usize = 5;
/// Default step of a steepest-ascent path, coded units of the leading factor.
const DEFAULT_PATH_STEP: f64 = 0.5;
/// Default number of points of a steepest-ascent path (seed 000 Table 6 and seed 001 Table 8).
const DEFAULT_PATH_POINTS: usize = 5;

/// The kinds of design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DesignType {
    /// Plackett–Burman, 12 runs (up to 11 factors; unused columns are dummies).
    Pb12,
    /// Plackett–Burman, 20 runs (up to 19 factors).
    Pb20,
    /// Two-level full factorial.
    Factorial,
    /// Two-level fractional factorial (needs `--generators`).
    Fractional,
    /// Box–Behnken (3 to 7 factors).
    Bbd,
    /// Central composite (2 to 10 factors; `--alpha`).
    Ccd,
    /// Path of steepest ascent (needs `--coefficients`).
    Steepest,
}

/// Arguments of `arachis doe design`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Kind of design.
    #[arg(long = "type", value_enum)]
    pub design_type: DesignType,
    /// Factors as `name:low:high[:unit]`, comma-separated; low and high are the actual
    /// levels of coded −1 and +1.
    #[arg(
        long,
        value_delimiter = ',',
        required = true,
        allow_hyphen_values = true
    )]
    pub factors: Vec<String>,
    /// Number of centre points (default 0 for pb/factorial designs, 5 for bbd/ccd; at most
    /// `count_limits::MAX_CENTRE_POINTS`).
    #[arg(long, value_parser = count::<usize>(0, MAX_CENTRE_POINTS))]
    pub center: Option<usize>,
    /// Axial distance of a ccd: rotatable, face, spherical, or a number such as 1.414.
    #[arg(long, allow_hyphen_values = true)]
    pub alpha: Option<String>,
    /// Generators of a fractional factorial, e.g. `D=ABC,E=-ABD` (letters A, B, … skip I).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub generators: Vec<String>,
    /// Names of the dummy columns of a Plackett–Burman design, comma-separated.
    #[arg(long, value_delimiter = ',')]
    pub dummy_names: Vec<String>,
    /// Options of a steepest-ascent path (boxed to keep the command-line enum small).
    #[command(flatten)]
    pub path: Box<PathArgs>,
    /// Output CSV file (written atomically); standard output when absent.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Options of `--type steepest`.
#[derive(Debug, clap::Args)]
pub struct PathArgs {
    /// Steepest ascent: first-order coefficients in coded units, one per factor.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub coefficients: Vec<f64>,
    /// Steepest ascent: coded starting point, one value per factor (default the centre).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub origin: Vec<f64>,
    /// Steepest ascent: coded step of the factor with the largest coefficient.
    #[arg(long)]
    pub step: Option<f64>,
    /// Steepest ascent: number of points, origin included (at most
    /// `count_limits::MAX_DESIGN_POINTS`).
    #[arg(long, value_parser = count::<usize>(1, MAX_DESIGN_POINTS))]
    pub points: Option<usize>,
}

/// Rejects options that do not apply to the chosen design, so a typo is not silently ignored.
fn check_applicable(args: &Args) -> anyhow::Result<()> {
    let t = args.design_type;
    let only = |given: bool, option: &str, types: &[DesignType], names: &str| {
        if given && !types.contains(&t) {
            bail!("{option} applies to {names} designs only");
        }
        Ok(())
    };
    only(args.alpha.is_some(), "--alpha", &[DesignType::Ccd], "ccd")?;
    only(
        !args.generators.is_empty(),
        "--generators",
        &[DesignType::Fractional],
        "fractional",
    )?;
    only(
        !args.dummy_names.is_empty(),
        "--dummy-names",
        &[DesignType::Pb12, DesignType::Pb20],
        "pb12/pb20",
    )?;
    let path_option = !args.path.coefficients.is_empty()
        || !args.path.origin.is_empty()
        || args.path.step.is_some()
        || args.path.points.is_some();
    only(
        path_option,
        "--coefficients/--origin/--step/--points",
        &[DesignType::Steepest],
        "steepest",
    )?;
    only(
        args.center.is_some(),
        "--center",
        &[
            DesignType::Pb12,
            DesignType::Pb20,
            DesignType::Factorial,
            DesignType::Fractional,
            DesignType::Bbd,
            DesignType::Ccd,
        ],
        "pb/factorial/bbd/ccd",
    )?;
    Ok(())
}

/// Builds the design the arguments ask for.
pub fn build(args: &Args) -> anyhow::Result<Design> {
    check_applicable(args)?;
    let factors: Vec<Factor> = args
        .factors
        .iter()
        .map(|s| Factor::parse(s))
        .collect::<Result<_, _>>()?;
    let centre = args.center.unwrap_or(0);
    let design = match args.design_type {
        DesignType::Pb12 | DesignType::Pb20 => {
            let runs = if args.design_type == DesignType::Pb12 {
                PlackettBurmanRuns::Twelve
            } else {
                PlackettBurmanRuns::Twenty
            };
            let d = plackett_burman(runs, &factors, centre)?;
            if args.dummy_names.is_empty() {
                d
            } else {
                let names: Vec<&str> = args.dummy_names.iter().map(String::as_str).collect();
                d.with_dummy_names(&names)?
            }
        }
        DesignType::Factorial => full_factorial(&factors, centre)?,
        DesignType::Fractional => {
            if args.generators.is_empty() {
                bail!("a fractional design needs --generators, e.g. --generators D=ABC");
            }
            let g: Vec<&str> = args.generators.iter().map(String::as_str).collect();
            fractional_factorial(&factors, &g, centre)?
        }
        DesignType::Bbd => box_behnken(&factors, args.center.unwrap_or(DEFAULT_RSM_CENTRE_POINTS))?,
        DesignType::Ccd => {
            let alpha = match &args.alpha {
                Some(a) => Alpha::parse(a)?,
                None => Alpha::Rotatable,
            };
            central_composite(
                &factors,
                alpha,
                args.center.unwrap_or(DEFAULT_RSM_CENTRE_POINTS),
            )?
        }
        DesignType::Steepest => {
            if args.path.coefficients.is_empty() {
                bail!("a steepest-ascent path needs --coefficients, one per factor");
            }
            let origin = if args.path.origin.is_empty() {
                vec![0.0; factors.len()]
            } else {
                args.path.origin.clone()
            };
            steepest_ascent(
                &factors,
                &args.path.coefficients,
                &origin,
                args.path.step.unwrap_or(DEFAULT_PATH_STEP),
                args.path.points.unwrap_or(DEFAULT_PATH_POINTS),
            )?
        }
    };
    Ok(design)
}

/// Runs `arachis doe design`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let design = build(&args)?;
    let csv = design_to_csv(&design);
    match &args.out {
        Some(path) => write_string_atomic(path, &csv)
            .with_context(|| format!("writing the design to {}", path.display())),
        None => {
            print!("{csv}");
            Ok(())
        }
    }
}
