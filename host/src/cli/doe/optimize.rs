//! `arachis doe optimize`: numerical optimisation of fitted surfaces by desirability.
//!
//! ```text
//! arachis doe optimize fit.json --goal angle_deg=target:31.06 [--goal ...] [--solutions 100] [--json]
//! ```
//!
//! Each FIT.json is the output of `arachis doe analyze --json` (see
//! [`crate::optimize::FitFile`]); all must share the same factors. A goal is
//! `RESPONSE=KIND[:ARGS][@IMPORTANCE]` with KIND
//! - `target:T` or `target:T:LOW:HIGH`,
//! - `max`, `max:LOW:HIGH`, `min`, `min:LOW:HIGH`,
//! - `range:LOW:HIGH`,
//!
//! and IMPORTANCE the weight rᵢ in D = (Π dᵢ^rᵢ)^(1/Σrᵢ) (default 1; Design-Expert offers 1
//! to 5). Limits default to the response's predicted range over the coded box. Solutions are
//! printed best first, in coded and actual units, with the predicted responses.

use std::path::PathBuf;

use anyhow::{bail, Context};
use serde_json::json;

use crate::doe::design_csv::format_significant;
use crate::optimize::{
    goal_with_default_limits, optimise_desirability, surface_range, FitFile, Goal, GoalKind,
    ResponseSurface, SearchOptions, MAX_SOLUTIONS,
};

/// Significant digits of printed factor levels and predictions.
const PRINTED_DIGITS: usize = 6;

/// Arguments of `arachis doe optimize`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Fit files written by `arachis doe analyze --json`, one per response.
    #[arg(required = true)]
    pub fits: Vec<PathBuf>,
    /// A goal `RESPONSE=KIND[:ARGS][@IMPORTANCE]`, e.g. `angle_deg=target:31.06`; repeatable.
    #[arg(long = "goal", required = true)]
    pub goals: Vec<String>,
    /// Most distinct solutions to report (1 to 100).
    #[arg(long, default_value_t = MAX_SOLUTIONS)]
    pub solutions: usize,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// A goal as given on the command line, before its default limits are known.
#[derive(Debug, Clone, PartialEq)]
pub struct GoalSpec {
    /// The response it applies to.
    pub response: String,
    /// What the response should do.
    pub kind: GoalKind,
    /// Explicit limits, if given.
    pub limits: Option<(f64, f64)>,
    /// Importance rᵢ.
    pub importance: f64,
}

/// Parses `RESPONSE=KIND[:ARGS][@IMPORTANCE]`.
pub fn parse_goal(text: &str) -> anyhow::Result<GoalSpec> {
    let context = || format!("goal '{text}'");
    let (response, rest) = text.split_once('=').with_context(|| {
        format!(
            "{}: expected RESPONSE=KIND, e.g. angle_deg=target:31.06",
            context()
        )
    })?;
    let response = response.trim();
    if response.is_empty() {
        bail!("{}: the response name is empty", context());
    }
    let (spec, importance) = match rest.split_once('@') {
        Some((s, r)) => {
            let r: f64 = r
                .trim()
                .parse()
                .with_context(|| format!("{}: importance '{r}' is not a number", context()))?;
            if !(r.is_finite() && r > 0.0) {
                bail!("{}: importance {r} must be positive", context());
            }
            (s, r)
        }
        None => (rest, 1.0),
    };
    let parts: Vec<&str> = spec.split(':').map(str::trim).collect();
    let numbers = parts[1..]
        .iter()
        .map(|p| {
            p.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .with_context(|| format!("{}: '{p}' is not a number", context()))
        })
        .collect::<anyhow::Result<Vec<f64>>>()?;
    let limits_from = |n: &[f64]| -> anyhow::Result<Option<(f64, f64)>> {
        match n {
            [] => Ok(None),
            [low, high] => Ok(Some((*low, *high))),
            _ => bail!("{}: give both limits LOW:HIGH or none", context()),
        }
    };
    let (kind, limits) = match parts[0].to_ascii_lowercase().as_str() {
        "target" => match numbers.split_first() {
            Some((t, rest)) => (GoalKind::Target(*t), limits_from(rest)?),
            None => bail!("{}: target needs a value, e.g. target:31.06", context()),
        },
        "max" | "maximise" | "maximize" => (GoalKind::Maximise, limits_from(&numbers)?),
        "min" | "minimise" | "minimize" => (GoalKind::Minimise, limits_from(&numbers)?),
        "range" | "in-range" => match limits_from(&numbers)? {
            Some(l) => (GoalKind::InRange, Some(l)),
            None => bail!("{}: range needs LOW:HIGH", context()),
        },
        other => bail!(
            "{}: unknown goal '{other}' (expected target, max, min or range)",
            context()
        ),
    };
    Ok(GoalSpec {
        response: response.to_owned(),
        kind,
        limits,
        importance,
    })
}

/// Runs `arachis doe optimize`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if !(1..=MAX_SOLUTIONS).contains(&args.solutions) {
        bail!(
            "--solutions {}: between 1 and {MAX_SOLUTIONS} solutions can be listed",
            args.solutions
        );
    }
    let fits: Vec<FitFile> = args
        .fits
        .iter()
        .map(|p| FitFile::read(p))
        .collect::<Result<_, _>>()?;
    let first = &fits[0];
    let names: Vec<&str> = first.factors.iter().map(|f| f.name.as_str()).collect();
    for fit in &fits[1..] {
        let other: Vec<&str> = fit.factors.iter().map(|f| f.name.as_str()).collect();
        if other != names {
            bail!(
                "{}: factors {} differ from {} in {}",
                fit.path.display(),
                other.join(", "),
                names.join(", "),
                first.path.display()
            );
        }
        if fits.iter().filter(|f| f.response == fit.response).count() > 1 {
            bail!("response '{}' is given by two fit files", fit.response);
        }
    }
    let dims = names.len();
    let specs: Vec<GoalSpec> = args
        .goals
        .iter()
        .map(|g| parse_goal(g))
        .collect::<anyhow::Result<_>>()?;
    let mut goals: Vec<(usize, Goal, (f64, f64))> = Vec::new();
    for spec in &specs {
        let Some(index) = fits.iter().position(|f| f.response == spec.response) else {
            bail!(
                "goal for '{}': no fit file has this response (responses: {})",
                spec.response,
                fits.iter()
                    .map(|f| f.response.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        };
        if goals.iter().any(|(i, _, _)| *i == index) {
            bail!("two goals for response '{}'", spec.response);
        }
        let range = surface_range(&fits[index].model, dims)?;
        let goal = goal_with_default_limits(spec.kind, spec.limits, range)
            .with_context(|| format!("goal for '{}'", spec.response))?
            .with_importance(spec.importance)?;
        goals.push((index, goal, range));
    }
    let responses: Vec<(&dyn ResponseSurface, Goal)> = goals
        .iter()
        .map(|(i, g, _)| (&fits[*i].model as &dyn ResponseSurface, *g))
        .collect();
    let solutions = optimise_desirability(
        &responses,
        dims,
        &SearchOptions::for_solutions(args.solutions),
    )?;
    let predict_all = |x: &[f64]| -> Vec<f64> { fits.iter().map(|f| f.model.predict(x)).collect() };

    if args.json {
        let goals_json: Vec<_> = goals
            .iter()
            .map(|(i, g, range)| {
                json!({
                    "response": fits[*i].response,
                    "goal": goal_name(g.kind),
                    "target": match g.kind { GoalKind::Target(t) => Some(t), _ => None },
                    "low": g.low,
                    "high": g.high,
                    "importance": g.importance,
                    "predicted_range": [range.0, range.1],
                })
            })
            .collect();
        let solutions_json: Vec<_> = solutions
            .iter()
            .enumerate()
            .map(|(rank, s)| {
                let coded: serde_json::Map<_, _> = names
                    .iter()
                    .zip(&s.coded)
                    .map(|(n, x)| ((*n).to_owned(), json!(x)))
                    .collect();
                let actual: serde_json::Map<_, _> = first
                    .factors
                    .iter()
                    .zip(&s.coded)
                    .map(|(f, &x)| (f.name.clone(), json!(f.to_actual(x))))
                    .collect();
                let predicted: serde_json::Map<_, _> = fits
                    .iter()
                    .zip(predict_all(&s.coded))
                    .map(|(f, y)| (f.response.clone(), json!(y)))
                    .collect();
                json!({
                    "rank": rank + 1,
                    "desirability": s.desirability,
                    "coded": coded,
                    "actual": actual,
                    "predicted": predicted,
                })
            })
            .collect();
        let out = json!({ "goals": goals_json, "solutions": solutions_json });
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }

    for (i, g, range) in &goals {
        let target = match g.kind {
            GoalKind::Target(t) => format!(" {}", format_significant(t, PRINTED_DIGITS)),
            _ => String::new(),
        };
        println!(
            "# goal: {} {}{}, limits {} to {}, importance {} (predicted range over the box {} to {})",
            fits[*i].response,
            goal_name(g.kind),
            target,
            format_significant(g.low, PRINTED_DIGITS),
            format_significant(g.high, PRINTED_DIGITS),
            g.importance,
            format_significant(range.0, PRINTED_DIGITS),
            format_significant(range.1, PRINTED_DIGITS),
        );
    }
    println!("# {} distinct solution(s), best first", solutions.len());
    let mut header = vec!["rank".to_owned(), "desirability".to_owned()];
    header.extend(names.iter().map(|n| format!("{n}_coded")));
    header.extend(
        first
            .factors
            .iter()
            .filter(|f| f.levels.is_some())
            .map(|f| f.name.clone()),
    );
    header.extend(fits.iter().map(|f| f.response.clone()));
    println!("{}", header.join(","));
    for (rank, s) in solutions.iter().enumerate() {
        let mut cells = vec![(rank + 1).to_string(), format!("{:.4}", s.desirability)];
        cells.extend(s.coded.iter().map(|x| format!("{x:.4}")));
        cells.extend(
            first
                .factors
                .iter()
                .zip(&s.coded)
                .filter_map(|(f, &x)| f.to_actual(x))
                .map(|v| format_significant(v, PRINTED_DIGITS)),
        );
        cells.extend(
            predict_all(&s.coded)
                .into_iter()
                .map(|y| format_significant(y, PRINTED_DIGITS)),
        );
        println!("{}", cells.join(","));
    }
    Ok(())
}

fn goal_name(kind: GoalKind) -> &'static str {
    match kind {
        GoalKind::Maximise => "maximise",
        GoalKind::Minimise => "minimise",
        GoalKind::Target(_) => "target",
        GoalKind::InRange => "in range",
    }
}
