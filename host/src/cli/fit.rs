//! `arachis fit STUDY --with EFFECT`: recalibrate the base parameters with the effect on and
//! report the error before and after, the nested-model tests (likelihood ratio and F), AIC,
//! AICc, BIC, the leave-one-condition-out error, and the parameters with standard errors.
//! `--out FILE` writes the study with the new calibration (for the next `compare`).
//!
//! ```text
//! arachis fit testdata/diagnosis-tutorial/measured.toml --with viscoelastic --out fitted.toml
//! ```

use std::path::PathBuf;

use anyhow::{Context, Result};

use crate::diagnose::fit::{compare_with, residual_count, ONE_SIDED_CONFIDENCE};
use crate::diagnose::model::Model;
use crate::diagnose::params::value;
use crate::diagnose::plot::plot_experiment;
use crate::diagnose::residuals::{experiments, lack_of_fit, Dataset};
use crate::diagnose::sensitivity::predict;
use crate::io::atomic::write_string_atomic;
use crate::rigs::single_sphere::ModelParams;
use crate::study::Study;

/// A fitted base parameter this many bench SDs from its bench value is a conflict.
const PRIOR_CONFLICT_SD: f64 = 3.0;

/// Significance level of the nested-model tests in the verdict.
const NESTED_ALPHA: f64 = 0.05;

/// Arguments of `arachis fit`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Study file with replicated measurements at several conditions (e.g. a [diagnosis]
    /// study).
    pub study: PathBuf,
    /// The effect to switch on and fit (viscoelastic, cohesion, drag).
    #[arg(long = "with")]
    pub with: String,
    /// Skip the leave-one-condition-out refits (one refit per condition and model).
    #[arg(long)]
    pub no_loco: bool,
    /// Write the study with the fitted calibration here (a [diagnosis] study).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Directory for SVG plots of measured vs before/after.
    #[arg(long)]
    pub plots: Option<PathBuf>,
    /// Where the simulations run, and the run cache that keeps them.
    #[command(flatten)]
    pub runs: super::runs_args::RunsArgs,
    /// Simulated replicates per prediction of a random rig.
    #[command(flatten)]
    pub prediction: super::runs_args::PredictionArgs,
}

/// Runs `arachis fit`.
pub fn run(args: Args) -> Result<()> {
    use std::fmt::Write;
    if let Some(dir) = &args.plots {
        // Refused before the fit runs, naming the path (it once ran the whole fit, then said
        // "File exists (os error 17)").
        anyhow::ensure!(
            !dir.exists() || dir.is_dir(),
            "--plots {}: is a file; --plots names a folder for the SVG plots",
            dir.display()
        );
    }
    let study = Study::load(&args.study)?;
    let model = args.runs.attach(
        args.prediction
            .apply(Model::new(&study, &experiments(&study))?),
        &study,
    )?;
    let eff = model.catalogue.effect(&args.with)?;
    let data = Dataset::new(&study)?;
    let current = study.current_values();
    let c = compare_with(&data, &model, &current, eff, !args.no_loco)?;
    let mut s = String::new();
    let before = predict(&data, &model, &current)?;
    let rows = [
        ("current calibration", &before, c.sse_current, None),
        (
            "base refit, effect off",
            &c.without.predictions,
            c.without.sse,
            Some(&c.without),
        ),
        (
            "base refit + effect",
            &c.with.predictions,
            c.with.sse,
            Some(&c.with),
        ),
    ];
    writeln!(s, "error (SSE = sum of standardised residuals^2 over {} conditions; replicate RMS / pure-error SD per experiment):", c.n)?;
    for (name, pred, sse, _) in &rows {
        let lof = lack_of_fit(&data, pred)?;
        let per: Vec<String> = lof
            .iter()
            .map(|l| format!("{} {:.3}", data.experiments[l.experiment].rig, l.rms / l.sd))
            .collect();
        writeln!(
            s,
            "  {name:<24} SSE {sse:>9.2}   RMS/SD: {}",
            per.join(", ")
        )?;
    }
    for (name, _, _, fit) in &rows[1..] {
        let f = fit.expect("fitted rows");
        writeln!(
            s,
            "parameters, {name} ({} Gauss-Newton iterations):",
            f.iterations
        )?;
        for (k, p) in f.free.iter().enumerate() {
            let v = value(p, &f.params);
            match f.one_sided_interval(k) {
                Some((lo, hi)) => writeln!(
                    s,
                    "  {:<16} {v:.5e} {} at its {} limit; one-sided {:.0} % interval [{lo:.5e}, {hi:.5e}]",
                    p.name,
                    p.unit,
                    if Some(lo) == f.on_end[k] { "lower" } else { "upper" },
                    100.0 * ONE_SIDED_CONFIDENCE
                )?,
                None => writeln!(
                    s,
                    "  {:<16} {v:.5e} ± {:.2e} {}",
                    p.name, f.std_errors[k], p.unit
                )?,
            }
        }
    }
    if !data.priors.is_empty() {
        writeln!(
            s,
            "bench priors (distance of the fitted value from the bench value, in bench SDs; beyond {PRIOR_CONFLICT_SD} is a conflict):"
        )?;
        for (k, prior) in data.priors.iter().enumerate() {
            let at = |f: &crate::diagnose::fit::FitResult| {
                let z = f.prior_z[k].1;
                let v = value(prior.param, &f.params);
                let verdict = if z.abs() > PRIOR_CONFLICT_SD {
                    format!(
                        ": the calibration fits the data only {:.1} SD {} the bench value",
                        z.abs(),
                        if z < 0.0 { "below" } else { "above" }
                    )
                } else {
                    String::new()
                };
                format!("{v:.5e} ({z:+.1} SD{verdict})")
            };
            writeln!(
                s,
                "  {:<16} bench {:.5e} ± {:.2e} {}\n    effect off: {}\n    effect on:  {}",
                prior.param.name,
                prior.mean,
                prior.sd,
                prior.param.unit,
                at(&c.without),
                at(&c.with)
            )?;
        }
    }
    writeln!(s, "nested-model test ({} on vs off):", eff.name)?;
    writeln!(
        s,
        "  likelihood ratio  {:.2} ~ chi2(1), p = {:.3e}",
        c.lr, c.lr_p
    )?;
    writeln!(
        s,
        "  F                 {:.2} ~ F(1, {}), p = {:.3e}",
        c.f,
        residual_count(&data, &c.with.free) - c.with.k(),
        c.f_p
    )?;
    let n = c.n;
    writeln!(
        s,
        "information criteria (lower is better):  off      on       difference"
    )?;
    let (a0, a1) = (c.without.aic(), c.with.aic());
    let (ac0, ac1) = (c.without.aicc(n), c.with.aicc(n));
    let (b0, b1) = (c.without.bic(n), c.with.bic(n));
    writeln!(
        s,
        "  AIC                                   {a0:<8.2} {a1:<8.2} {:+.2}",
        a1 - a0
    )?;
    writeln!(
        s,
        "  AICc                                  {ac0:<8.2} {ac1:<8.2} {:+.2}",
        ac1 - ac0
    )?;
    writeln!(
        s,
        "  BIC                                   {b0:<8.2} {b1:<8.2} {:+.2}",
        b1 - b0
    )?;
    if let Some((l0, l1)) = c.loco {
        writeln!(
            s,
            "leave-one-condition-out RMS standardised prediction error: off {l0:.3}, on {l1:.3}"
        )?;
    }
    let agree = c.lr_p < NESTED_ALPHA
        && (c.f_p.is_nan() || c.f_p < NESTED_ALPHA)
        && ac1 < ac0
        && b1 < b0
        && c.loco.is_none_or(|(l0, l1)| l1 < l0);
    writeln!(
        s,
        "verdict: {}",
        if agree {
            format!(
                "accept '{}': the nested tests, AICc, BIC{} agree",
                eff.name,
                if c.loco.is_some() {
                    " and held-out error"
                } else {
                    ""
                }
            )
        } else {
            format!(
                "do not accept '{}': the criteria do not all agree",
                eff.name
            )
        }
    )?;
    print!("{s}");
    if let Some(dir) = &args.plots {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the plot folder {}", dir.display()))?;
        for (ei, e) in data.experiments.iter().enumerate() {
            let path = dir.join(format!("fit-{}-{}.svg", ei + 1, e.rig));
            plot_experiment(
                &data,
                ei,
                &before,
                Some((&format!("with {}", eff.name), &c.with.predictions)),
                &format!("{}: before (red) and after fitting {}", e.rig, eff.name),
                &path,
            )?;
            println!("wrote {}", path.display());
        }
    }
    if let Some(out) = &args.out {
        let mut section = study.file().diagnosis.clone().with_context(|| {
            format!(
                "--out writes a [diagnosis] study's calibration, and {} has no [diagnosis]",
                args.study.display()
            )
        })?;
        section.calibration = ModelParams::from_values(&c.with.params)?;
        write_string_atomic(out, &section.to_toml()?)?;
        println!(
            "wrote {} (calibration: {})",
            out.display(),
            model
                .catalogue
                .0
                .iter()
                .map(|p| format!("{} {:.5e}", p.name, value(p, &c.with.params)))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(())
}
