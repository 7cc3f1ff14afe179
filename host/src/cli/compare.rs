//! `arachis compare STUDY`: simulate each measured experiment at each condition with the
//! current calibration; print the standardised residuals and a lack-of-fit test per
//! experiment; with `--plots DIR`, write one SVG per experiment (measured vs simulated against
//! the condition).
//!
//! ```text
//! arachis compare testdata/diagnosis-tutorial/measured.toml --plots out/
//! ```

use std::path::PathBuf;

use anyhow::{Context, Result};

use crate::diagnose::model::Model;
use crate::diagnose::plot::plot_experiment;
use crate::diagnose::residuals::{lack_of_fit, Dataset};
use crate::diagnose::sensitivity::predict;
use crate::study::Study;

/// Arguments of `arachis compare`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Study file with measurements at several conditions, replicated (e.g. a [diagnosis]
    /// study).
    pub study: PathBuf,
    /// Directory for the SVG plots (created if missing); no plots without it.
    #[arg(long)]
    pub plots: Option<PathBuf>,
    /// Where the simulations run, and the run cache that keeps them.
    #[command(flatten)]
    pub runs: super::runs_args::RunsArgs,
    /// Simulated replicates per prediction of a random rig.
    #[command(flatten)]
    pub prediction: super::runs_args::PredictionArgs,
}

/// Runs `arachis compare`.
pub fn run(args: Args) -> Result<()> {
    let study = Study::load(&args.study)?;
    let data = Dataset::new(&study)?;
    let model = args.runs.attach(
        args.prediction
            .apply(Model::new(&study, &data.experiments)?),
        &study,
    )?;
    let pred = predict(&data, &model, &study.current_values())?;
    print!("{}", report(&data, &pred)?);
    if let Some(dir) = &args.plots {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        for (ei, e) in data.experiments.iter().enumerate() {
            let path = dir.join(format!("compare-{}-{}.svg", ei + 1, e.rig));
            plot_experiment(
                &data,
                ei,
                &pred,
                None,
                &format!("{}: measured vs simulated", e.rig),
                &path,
            )?;
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}

/// The comparison table and lack-of-fit lines.
pub fn report(data: &Dataset, pred: &[f64]) -> Result<String> {
    use std::fmt::Write;
    let mut s = String::new();
    let r = data.standardised(pred);
    let lof = lack_of_fit(data, pred)?;
    for (ei, e) in data.experiments.iter().enumerate() {
        let axis = if e.condition.1.is_empty() {
            "(one condition)"
        } else {
            e.condition.1.as_str()
        };
        writeln!(
            s,
            "experiment {} {}: {} vs {axis}",
            ei + 1,
            e.rig,
            e.observable_label
        )?;
        writeln!(
            s,
            "  condition      n   measured mean  ± SE         simulated       std. residual"
        )?;
        for (i, o) in data
            .obs
            .iter()
            .enumerate()
            .filter(|(_, o)| o.experiment == ei)
        {
            let at = if o.x.is_nan() {
                "-".to_owned()
            } else {
                format!("{:.6}", o.x)
            };
            writeln!(
                s,
                "  {at:<12} {:>3}   {:<14.6} {:<12.3e} {:<15.6} {:+8.2}{}",
                o.n,
                o.mean,
                o.se_mean,
                pred[i],
                r[i],
                if r[i].abs() > 3.0 {
                    "  <-- beyond 3 SE"
                } else {
                    ""
                }
            )?;
        }
        let l = &lof[ei];
        writeln!(
            s,
            "  lack of fit: sum r^2 = {:.2} over {} conditions, F = {:.2} on ({}, {}) df, p = {:.3e}{}",
            l.chi2,
            l.conditions,
            l.chi2 / l.conditions as f64,
            l.conditions,
            l.df_pe,
            l.p_value,
            if l.p_value < 0.05 { "  -> the model misses something here" } else { "" }
        )?;
        writeln!(
            s,
            "  replicate RMS of (measured - simulated) = {:.4e}, pure-error SD = {:.4e}",
            l.rms, l.sd
        )?;
    }
    Ok(s)
}
