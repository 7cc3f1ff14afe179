//! `arachis diagnose STUDY`: rank the optional effects that are off by how much of the misfit
//! each could explain (projected one-sided score test, Bonferroni over the candidates; see
//! `diagnose::score`), say which are not identifiable or not distinguishable, and propose the
//! measurement that best separates the top two.
//!
//! ```text
//! arachis diagnose testdata/diagnosis-tutorial/measured.toml
//! ```

use std::path::PathBuf;

use anyhow::Result;

use crate::calibration::ParameterValues;
use crate::diagnose::model::Model;
use crate::diagnose::params::ParamInfo;
use crate::diagnose::prospect;
use crate::diagnose::residuals::{lack_of_fit, Dataset, Experiment};
use crate::diagnose::scatter::{differences, lost_in_scatter, ScatteredDifference, CONFIDENCE};
use crate::diagnose::score::{rank, Ranking, Status, FAMILY_ALPHA, IDENTIFIABLE_FRACTION};
use crate::diagnose::sensitivity::Linearisation;
use crate::diagnose::separate::{identify, propose, Search};
use crate::rigs::kind::{RigKind, RigOptions};
use crate::study::Study;

/// Replicates assumed for a proposed extra measurement.
const PROPOSAL_REPLICATES: usize = 4;
/// Width of the effect column of the ranking table, characters (the one-sphere effects' names).
const EFFECT_COLUMN: usize = 14;
/// A proposed measurement must raise the separation by this much (standard errors) to be
/// worth making.
const MIN_SEPARATION_GAIN: f64 = 0.01;

/// After the rigs a study could still measure, when no effect is identifiable.
const IDENTIFY_HINT: &str = "`--consider RIG=SD` (the replicate SD you expect of it) has \
     the tool look for the measurement that makes candidate effects identifiable";
/// After the rigs a study could still measure, when two effects are indistinguishable.
const CONSIDER_HINT: &str =
    "`--consider RIG=SD` (the replicate SD you expect of it) has the search try one";

/// What to do when finite differences are lost in the placements' scatter.
const MORE_PLACEMENTS: &str =
    "simulate more placements (--replicates: the SE falls as 1/sqrt(N)) or larger piles";

/// Arguments of `arachis diagnose`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Study file with replicated measurements at several conditions (e.g. a [diagnosis]
    /// study).
    pub study: PathBuf,
    /// Skip the search for the measurement that separates the top two effects.
    #[arg(long)]
    pub no_proposal: bool,
    /// Also search a rig not yet measured, RIG=SD: SD is the replicate SD you expect of its
    /// measurement, in the unit of its first quantity (e.g. `--consider drum=0.7` for a
    /// dynamic angle of repose good to 0.7°). Repeatable.
    #[arg(long, value_name = "RIG=SD", value_parser = crate::diagnose::prospect::parse)]
    pub consider: Vec<(String, f64)>,
    /// Where the simulations run, and the run cache that keeps them.
    #[command(flatten)]
    pub runs: super::runs_args::RunsArgs,
    /// Simulated replicates per prediction of a random rig.
    #[command(flatten)]
    pub prediction: super::runs_args::PredictionArgs,
}

/// The finite differences of replicated rigs with their standard errors (`diagnose::scatter`),
/// each flagged when it is within its scatter.
fn write_scatter(
    s: &mut String,
    data: &Dataset,
    differences: &[ScatteredDifference],
) -> Result<()> {
    use std::fmt::Write;
    let within = differences.iter().filter(|d| d.within_scatter()).count();
    writeln!(
        s,
        "\nfinite differences against the placements' scatter (paired over {} placements; \
         {within} of {} within the scatter: |t| below Student's {:.0} % quantile, {:.2}):",
        differences[0].placements,
        differences.len(),
        100.0 * CONFIDENCE,
        differences[0].threshold()
    )?;
    let w = differences
        .iter()
        .map(|d| d.param.name.chars().count())
        .max()
        .unwrap_or(0);
    for d in differences {
        let o = &data.obs[d.obs];
        let at: Vec<String> = o
            .condition
            .iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect();
        writeln!(
            s,
            "  {:<w$} {} at {}: {:+.3e} ± {:.3e} per {} (t {:+.2}){}",
            d.param.name,
            data.experiments[o.experiment].rig,
            at.join(", "),
            d.value,
            d.se,
            d.param.unit,
            d.t(),
            if d.within_scatter() {
                "  within the scatter"
            } else {
                ""
            }
        )?;
    }
    Ok(())
}

/// Runs `arachis diagnose`.
pub fn run(args: Args) -> Result<()> {
    use std::fmt::Write;
    let study = Study::load(&args.study)?;
    let data = Dataset::new(&study)?;
    let model = args.runs.attach(
        args.prediction
            .apply(Model::new(&study, &data.experiments)?),
        &study,
    )?;
    let current = study.current_values();
    let lin = Linearisation::new(&data, &model, &current)?;
    // Rigs not yet measured that the proposal may name (checked before any output).
    let options = RigOptions {
        mode: study.plan_mode()?,
        ..RigOptions::default()
    };
    let calibrated: Vec<&str> = lin.calibrated.iter().map(|p| p.key).collect();
    let considered = args
        .consider
        .iter()
        .map(|(rig, sd)| {
            prospect::prospect(&study, &data.experiments, &calibrated, (rig, *sd), &options)
        })
        .collect::<Result<Vec<_>>>()?;
    let not_considered = prospect::unmeasured(
        &study,
        &data.experiments,
        &considered,
        &calibrated,
        &options,
    );
    let lof = lack_of_fit(&data, &lin.predictions)?;
    let mut s = String::new();
    writeln!(s, "lack of fit at the current calibration:")?;
    for l in &lof {
        writeln!(
            s,
            "  {:<8} sum r^2 {:>8.2} over {} conditions, p = {:.3e}",
            data.experiments[l.experiment].rig, l.chi2, l.conditions, l.p_value
        )?;
    }
    let r = rank(&data, &lin)?;
    writeln!(
        s,
        "\ncandidate effects (one-sided score test, projected off {}; Bonferroni over {} tested, family alpha {FAMILY_ALPHA}):",
        lin.calibrated.iter().map(|p| p.name).collect::<Vec<_>>().join(", "),
        r.tested
    )?;
    // Names up to 14 characters (the one-sphere effects) keep the table as it always was;
    // longer ones (`pod-pod.cohesion_j_m3`) widen the column.
    let w = r
        .candidates
        .iter()
        .map(|c| c.effect.name.chars().count())
        .max()
        .unwrap_or(0)
        .max(EFFECT_COLUMN);
    writeln!(
        s,
        "  rank {:<w$} z       p         p(adj)    estimate ± SE                 identifiable  verdict",
        "effect"
    )?;
    for (k, c) in r.candidates.iter().enumerate() {
        let verdict = match c.status {
            Status::Tested { claimed: true } => "MISSING: explains the misfit".to_string(),
            Status::Tested { claimed: false } => "not needed by these data".to_string(),
            Status::NotIdentifiable => format!(
                "NOT IDENTIFIABLE: the calibration absorbs it (< {:.0} % of its signature left); measure more conditions",
                100.0 * IDENTIFIABLE_FRACTION
            ),
            Status::NoSensitivity => "no measured experiment responds to it".to_string(),
        };
        if let Status::Tested { .. } = c.status {
            writeln!(
                s,
                "  {:<4} {:<w$} {:+7.2} {:<9.2e} {:<9.2e} {:+.3e} ± {:.3e} {:<5} {:<12.2} {}",
                k + 1,
                c.effect.name,
                c.z,
                c.p_value,
                c.p_adjusted,
                c.estimate,
                c.std_error,
                c.effect.unit,
                c.identifiable_fraction,
                verdict
            )?;
        } else {
            writeln!(
                s,
                "  -    {:<w$} {:>7} {:<9} {:<9} {:<29} {:<12.2} {}",
                c.effect.name, "-", "-", "-", "-", c.identifiable_fraction, verdict
            )?;
        }
    }
    for (a, b, cos) in &r.indistinguishable {
        writeln!(
            s,
            "  NOT DISTINGUISHABLE: {a} and {b} explain the same misfit with these data (cosine {cos:.3})"
        )?;
    }
    let scattered = differences(&lin, |obs| model.replicates_of(data.obs[obs].experiment));
    if !scattered.is_empty() {
        write_scatter(&mut s, &data, &scattered)?;
    }
    match r.top() {
        Some(t) if r.any_claimed() => {
            // The effects the data cannot tell from the top one share its verdict.
            let twins: Vec<&str> = r
                .indistinguishable
                .iter()
                .filter_map(|&(a, b, _)| match t.effect.name {
                    n if n == a => Some(b),
                    n if n == b => Some(a),
                    _ => None,
                })
                .collect();
            if twins.is_empty() {
                writeln!(
                    s,
                    "\nverdict: the model lacks an effect; best candidate '{}' (try: arachis fit STUDY --with {})",
                    t.effect.name, t.effect.name
                )?
            } else {
                writeln!(
                    s,
                    "\nverdict: the model lacks an effect, but these data cannot tell '{}' from '{}'",
                    t.effect.name,
                    twins.join("' or '")
                )?
            }
        }
        Some(_) => writeln!(
            s,
            "\nverdict: no missing effect can be claimed at family alpha {FAMILY_ALPHA}"
        )?,
        None => {
            writeln!(
                s,
                "\nverdict: no candidate effect is identifiable with these data; measure more conditions"
            )?;
            if let Some(h) = prospect::hint(&not_considered, IDENTIFY_HINT) {
                writeln!(s, "{h}")?;
            }
        }
    }
    let lost = |name: &str| lost_in_scatter(&scattered, name);
    if !r.candidates.is_empty() && r.candidates.iter().all(|c| lost(c.effect.name)) {
        writeln!(
            s,
            "warning: every candidate's finite differences lie within the placements' scatter, \
             so these data say nothing of them yet; {MORE_PLACEMENTS}"
        )?;
    } else if let Some(t) = r.top().filter(|t| lost(t.effect.name)) {
        writeln!(
            s,
            "warning: every finite difference of '{}' lies within the placements' scatter, \
             so its rank is not evidence; {MORE_PLACEMENTS}",
            t.effect.name
        )?;
    }
    if !data.priors.is_empty() {
        writeln!(
            s,
            "bench priors (each one more observation of its parameter in the score test):"
        )?;
        let current = study.current_values();
        for prior in &data.priors {
            let v = crate::diagnose::params::value(prior.param, &current);
            writeln!(
                s,
                "  {:<16} calibration {v:.5e}, bench {:.5e} ± {:.2e} {}: {:+.1} SD",
                prior.param.name,
                prior.mean,
                prior.sd,
                prior.param.unit,
                prior.z(v)
            )?;
        }
    }
    print!("{s}");
    write_proposals(
        &args,
        &study,
        (&data, &model, &lin, &current),
        &r,
        &Prospects {
            considered,
            not_considered,
        },
    )
}

/// The rigs not yet measured: those `--consider` named, and the others the study could
/// measure.
struct Prospects {
    /// The rigs `--consider` named, as experiments with the stated SD.
    considered: Vec<Experiment>,
    /// Rigs the study could measure that were neither measured nor named.
    not_considered: Vec<&'static RigKind>,
}

/// The proposed measurement: the one that separates the top two candidates, or, when none
/// is identifiable and `--consider` asks, those that would make candidates identifiable.
fn write_proposals(
    args: &Args,
    study: &Study,
    (data, model, lin, current): (&Dataset, &Model<'_>, &Linearisation, &ParameterValues),
    r: &Ranking,
    prospects: &Prospects,
) -> Result<()> {
    let (considered, not_considered) = (&prospects.considered, &prospects.not_considered);
    let tested: Vec<_> = r
        .candidates
        .iter()
        .filter(|c| matches!(c.status, Status::Tested { .. }))
        .collect();
    // The data's experiments, then the rigs the user asked to consider, each simulated by
    // its own rig (the ranking's model knows only the measured ones).
    let experiments: Vec<_> = data.experiments.iter().chain(considered).cloned().collect();
    let measured = data.experiments.len();
    let extended;
    let searched = if considered.is_empty() {
        model
    } else {
        extended = args.runs.attach(
            args.prediction.apply(Model::new(study, &experiments)?),
            study,
        )?;
        &extended
    };
    let noise_sd = |ei: usize| match ei.checked_sub(measured) {
        None => data.pure_error.get(ei).map(|p| p.sd),
        Some(k) => considered.get(k).and_then(|e| e.noise_sd),
    };
    let search = Search {
        experiments: &experiments,
        model: searched,
        noise_sd: &noise_sd,
        replicates: PROPOSAL_REPLICATES,
    };
    // Where the measurement was: " (not measured yet; …)" for a considered rig.
    let measure = |experiment: usize, condition: f64| {
        let e = &experiments[experiment];
        let unmeasured = match experiment.checked_sub(measured) {
            Some(_) => format!(
                " (not measured yet; replicate SD {} assumed, from --consider)",
                e.noise_sd.unwrap_or(f64::NAN)
            ),
            None => String::new(),
        };
        format!(
            "measure {} at {} = {condition:.4} ({PROPOSAL_REPLICATES} replicates){unmeasured}",
            e.rig, e.condition.1
        )
    };
    // A proposal computed from differences lost in the placements' scatter rests on noise.
    let noise_warning = |noisy: &[&ParamInfo]| {
        if !noisy.is_empty() {
            let names: Vec<&str> = noisy.iter().map(|e| e.name).collect();
            println!(
                "  warning: there, the finite differences of {} lie within the placements' \
                 scatter, so this proposal may rest on noise; {MORE_PLACEMENTS}",
                names.join(" and ")
            );
        }
    };
    // A separating measurement only helps when there is something to tell apart: a claimed
    // effect or an indistinguishable pair.
    let proposing = !args.no_proposal;
    if proposing && tested.len() >= 2 && (r.any_claimed() || !r.indistinguishable.is_empty()) {
        let (a, b) = (tested[0], tested[1]);
        if let Some(p) = propose(
            data,
            &search,
            lin,
            current,
            (a.effect, a.estimate),
            (b.effect, b.estimate),
        )? {
            let stuck = p.separation_after - p.separation_now < MIN_SEPARATION_GAIN;
            if stuck {
                println!(
                    "to tell '{}' from '{}' apart: no measurement in the rigs' search ranges \
                     would separate them further (separation {:.2} standard errors)",
                    a.effect.name, b.effect.name, p.separation_now
                );
            } else {
                println!(
                    "to tell '{}' from '{}' apart: {}; separation {:.2} -> {:.2} standard errors",
                    a.effect.name,
                    b.effect.name,
                    measure(p.experiment, p.condition),
                    p.separation_now,
                    p.separation_after
                );
                noise_warning(&p.noisy);
            }
            // Where the measured rigs leave effects indistinguishable, another rig may do
            // better than any new condition of theirs.
            if stuck || !r.indistinguishable.is_empty() {
                if let Some(h) = prospect::hint(not_considered, CONSIDER_HINT) {
                    println!("{h}");
                }
            }
        }
    } else if proposing && tested.is_empty() && !considered.is_empty() {
        // Nothing identifiable: which measurement would make candidates identifiable. Only
        // when asked for with --consider, since the search simulates every rig's grid of
        // conditions (minutes per condition for a pile).
        let found = identify(data, &search, lin, current)?;
        if found.is_empty() {
            println!(
                "no measurement in the searched rigs' ranges would make a candidate effect \
                 identifiable"
            );
        }
        for (k, i) in found.iter().enumerate() {
            let named: Vec<String> = i
                .identifiable
                .iter()
                .map(|(e, share)| format!("{} ({:.0} % left)", e.name, 100.0 * share))
                .collect();
            println!(
                "to make {} identifiable: {}",
                if k == 0 {
                    format!("the most candidates ({})", named.join(", "))
                } else {
                    named.join(", ")
                },
                measure(i.experiment, i.condition),
            );
            noise_warning(&i.noisy);
        }
    } else if !considered.is_empty() {
        println!(
            "note: --consider was not used: there is no proposal to make (--no-proposal, or \
             no two candidate effects to separate)"
        );
    }
    Ok(())
}
