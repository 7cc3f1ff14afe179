//! `arachis doe analyze`: fit a linear, 2FI or quadratic model to one response of a design
//! table and print a Design-Expert-style ANOVA table (or, with `--json`, one JSON object).
//!
//! Factor columns may be coded, or actual with their levels given by `--levels`:
//! `NAME=LOW:HIGH` codes linearly, (x − centre)/half-range; `NAME=LOW:CENTRE:HIGH` or
//! `NAME=AXIAL_LOW:LOW:CENTRE:HIGH:AXIAL_HIGH` takes a coding table as a paper prints
//! it (levels code to −1, 0, +1 and ±α exactly, see `--alpha`).

use std::io::Write;
use std::path::PathBuf;

use anyhow::{bail, Context};
use serde::Serialize;

use crate::io::CsvTable;
use crate::stats::report::text_report;
use crate::stats::{analyze, read_design_table, Anova, FactorLevels, ModelOrder};

/// Arguments of `arachis doe analyze`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design table: CSV with a header row, one row per run (`#` lines are comments).
    pub file: PathBuf,
    /// Response column to analyse.
    #[arg(long)]
    pub response: String,
    /// Model to fit.
    #[arg(long, value_enum)]
    pub model: ModelArg,
    /// Factor columns, comma-separated; terms follow the columns' order in the file
    /// [default: every column left of the response except `run`].
    #[arg(long, value_delimiter = ',')]
    pub factors: Option<Vec<String>>,
    /// Actual levels of factors given in actual units, comma-separated:
    /// NAME=LOW:HIGH (coded linearly), or a printed coding table NAME=LOW:CENTRE:HIGH or
    /// NAME=AXIAL_LOW:LOW:CENTRE:HIGH:AXIAL_HIGH. Factors not listed must be coded.
    #[arg(long, value_delimiter = ',')]
    pub levels: Vec<String>,
    /// Coded axial distance α for five-level tables [default: the printed ratio
    /// (+α level − centre)/(high − centre)].
    #[arg(long)]
    pub alpha: Option<f64>,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// The `--model` choices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ModelArg {
    /// Intercept and main effects.
    Linear,
    /// Linear plus two-factor interactions.
    #[value(name = "2fi")]
    TwoFactorInteraction,
    /// 2FI plus squared terms.
    Quadratic,
}

impl From<ModelArg> for ModelOrder {
    fn from(m: ModelArg) -> Self {
        match m {
            ModelArg::Linear => Self::Linear,
            ModelArg::TwoFactorInteraction => Self::TwoFactorInteraction,
            ModelArg::Quadratic => Self::Quadratic,
        }
    }
}

/// A factor and the actual values its −1 and +1 stand for (`null` when read coded).
#[derive(Debug, Serialize)]
struct FactorJson {
    name: String,
    low: Option<f64>,
    high: Option<f64>,
}

/// The `--json` object.
#[derive(Debug, Serialize)]
struct AnalysisJson<'a> {
    response: &'a str,
    model_order: &'a str,
    factors: Vec<FactorJson>,
    #[serde(flatten)]
    anova: &'a Anova,
}

/// Runs `arachis doe analyze`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let table = CsvTable::read(&args.file)?;
    let levels = args
        .levels
        .iter()
        .map(|spec| parse_levels(spec, args.alpha))
        .collect::<anyhow::Result<Vec<_>>>()?;
    // A factor given twice was read at its first levels (issue 23).
    for (i, (name, _)) in levels.iter().enumerate() {
        if let Some(first) = levels[..i].iter().position(|(n, _)| n == name) {
            bail!(
                "--levels gives factor '{name}' twice ('{}' and '{}')",
                args.levels[first],
                args.levels[i]
            );
        }
    }
    let read = read_design_table(&table, &args.response, args.factors.as_deref(), &levels)?;
    let order = ModelOrder::from(args.model);
    let anova = analyze(&read.design, order).with_context(|| {
        format!(
            "{}: cannot analyse '{}' with the {} model",
            args.file.display(),
            args.response,
            order.label()
        )
    })?;
    let factors: Vec<FactorJson> = read
        .design
        .factor_names
        .iter()
        .zip(&read.levels)
        .map(|(name, l)| FactorJson {
            name: name.clone(),
            low: l.as_ref().map(|l| l.low),
            high: l.as_ref().map(|l| l.high),
        })
        .collect();
    let out = if args.json {
        let json = AnalysisJson {
            response: &args.response,
            model_order: order.label(),
            factors,
            anova: &anova,
        };
        serde_json::to_string_pretty(&json)? + "\n"
    } else {
        let mut out = format!(
            "File: {}\nRuns: {}\n",
            args.file.display(),
            read.design.runs.len()
        );
        for f in &factors {
            let line = match (f.low, f.high) {
                (Some(lo), Some(hi)) => {
                    format!("Factor {}: actual, -1 = {lo}, +1 = {hi}\n", f.name)
                }
                _ => format!("Factor {}: coded\n", f.name),
            };
            out.push_str(&line);
        }
        out.push('\n');
        out + &text_report(&anova, &args.response)
    };
    write_stdout(&out)
}

/// Writes `text` to standard output; a closed pipe (`| head`) is not an error.
fn write_stdout(text: &str) -> anyhow::Result<()> {
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(e).context("cannot write to standard output")
        }
        _ => Ok(()),
    }
}

/// Parses `NAME=v1:v2[:v3[:v4:v5]]`.
fn parse_levels(spec: &str, alpha: Option<f64>) -> anyhow::Result<(String, FactorLevels)> {
    let Some((name, values)) = spec.split_once('=') else {
        bail!("--levels '{spec}': expected NAME=LOW:HIGH");
    };
    let values = values
        .split(':')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .with_context(|| format!("--levels '{spec}': '{v}' is not a number"))
        })
        .collect::<anyhow::Result<Vec<f64>>>()?;
    let levels = match values.as_slice() {
        [low, high] => FactorLevels::new(*low, *high),
        _ => FactorLevels::with_printed_levels(&values, alpha),
    }
    .map_err(|reason| anyhow::anyhow!("--levels '{spec}': {reason}"))?;
    Ok((name.trim().to_owned(), levels))
}
