//! `arachis synth STUDY --hidden EFFECT=VALUE --noise SIGMA --seed N --out FILE`: write a
//! measurement set generated with a hidden effect (deterministic given the seed). STUDY may be
//! a template (points with `replicates = n`) or a measured study (its replicate counts are
//! kept). `--noise` is one SD for every experiment or `KIND=SIGMA` per kind (repeatable);
//! without it each experiment's `noise_sd` is used. The hidden effect is not written.
//!
//! ```text
//! arachis synth testdata/diagnosis-tutorial/template.toml --hidden viscoelastic=1.3e-5 \
//!     --seed 7 --out measured.toml
//! ```

use std::path::PathBuf;

use anyhow::{anyhow, Context, Result};

use crate::diagnose::model::Model;
use crate::diagnose::residuals::experiments;
use crate::diagnose::synth::{add_noise, truths, truths_from_csv, NoiseSpec};
use crate::io::atomic::write_string_atomic;
use crate::study::Study;

/// Replicates per point when a template point gives none.
const DEFAULT_REPLICATES: usize = 4;

/// Arguments of `arachis synth`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Study or template file.
    pub study: PathBuf,
    /// Hidden effect, EFFECT=VALUE (repeatable; none = the calibrated model itself).
    #[arg(long, conflicts_with = "truth")]
    pub hidden: Vec<String>,
    /// True values from a CSV file (experiment,condition,truth) instead of this model's, e.g.
    /// made by another engine (scripts/liggghts-diagnosis-truth.py); every point needs a row.
    #[arg(long)]
    pub truth: Option<PathBuf>,
    /// Noise SD: SIGMA for all experiments or RIG=SIGMA (repeatable).
    #[arg(long, allow_hyphen_values = true)]
    pub noise: Vec<String>,
    /// Seed of the noise stream.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output study file.
    #[arg(long)]
    pub out: PathBuf,
}

fn number(s: &str, what: &str) -> Result<f64> {
    s.trim()
        .parse::<f64>()
        .map_err(|_| anyhow!("{what}: '{s}' is not a number"))
}

/// Runs `arachis synth`.
pub fn run(args: Args) -> Result<()> {
    let study = Study::load(&args.study)?;
    let series = study.series();
    let model = Model::new(&study, &experiments(&study))?;
    let mut hidden = Vec::new();
    for (i, h) in args.hidden.iter().enumerate() {
        let (name, value) = h
            .split_once('=')
            .ok_or_else(|| anyhow!("--hidden '{h}': expected EFFECT=VALUE"))?;
        // An effect given twice was hidden at its last value (issue 23).
        if let Some(first) = args.hidden[..i].iter().find(|g| {
            g.split_once('=')
                .is_some_and(|(n, _)| n.trim() == name.trim())
        }) {
            anyhow::bail!(
                "--hidden gives '{}' twice ('{first}' and '{h}')",
                name.trim()
            );
        }
        hidden.push((
            model.catalogue.effect(name.trim())?,
            number(value, "--hidden")?,
        ));
    }
    let mut noise = NoiseSpec::default();
    for n in &args.noise {
        match n.split_once('=') {
            None if noise.all.is_some() => {
                anyhow::bail!("--noise gives the SD for every experiment twice ('{n}' again)")
            }
            Some((rig, _)) if noise.per_rig.iter().any(|(r, _)| r == rig.trim()) => {
                anyhow::bail!("--noise gives '{}' twice ('{n}' again)", rig.trim())
            }
            None => noise.all = Some(number(n, "--noise")?),
            Some((rig, v)) => {
                let rig = rig.trim();
                if !series.iter().any(|s| s.experiment == rig) {
                    let known: Vec<&str> = series.iter().map(|s| s.experiment.as_str()).collect();
                    anyhow::bail!(
                        "--noise '{n}': the study measures no '{rig}' (it measures {})",
                        known.join(", ")
                    );
                }
                noise.per_rig.push((rig.to_owned(), number(v, "--noise")?));
            }
        }
    }
    let truth = match &args.truth {
        Some(path) => truths_from_csv(path, &series)?,
        None => {
            truths(&model, &series, &study.current_values(), &hidden)
                .context("simulating the truth")?
                .1
        }
    };
    let values = add_noise(&series, &truth, &noise, args.seed, DEFAULT_REPLICATES)?;
    // The SDs drawn with are what the written study states (`--noise` overrides the study's).
    let sds = series
        .iter()
        .map(|s| noise.sd(&s.experiment, s.noise_sd))
        .collect::<anyhow::Result<Vec<f64>>>()?;
    let text = format!(
        "# Synthetic measurements written by `arachis synth` (seed {}); the hidden effect is not recorded here.\n{}",
        args.seed,
        study
            .toml_with_replicates(&values, Some(&sds))
            .map_err(|e| anyhow!("{}: {e}", args.study.display()))?
    );
    // What is written must load as a measured study.
    let written = Study::from_toml(&text, &args.out)?;
    crate::diagnose::residuals::Dataset::new(&written)?;
    write_string_atomic(&args.out, &text)?;
    println!("wrote {}", args.out.display());
    Ok(())
}
