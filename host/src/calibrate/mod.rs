//! `arachis calibrate`: seed 000's calibration plan end to end (issue 4 §4–§5).
//!
//! 1. [`screening`]: a Plackett–Burman design over every varied parameter (dummy columns
//!    kept for the error estimate), a first-order fit and ANOVA; factors with p < α pass
//!    (seed 000 §3.3, Tables 4–5).
//! 2. [`steepest_ascent`]: a path along the screening fit's gradient in the passed factors,
//!    toward the target; the others held at the study's values (seed 000 §3.4, Table 6).
//! 3. [`box_behnken`]: a Box–Behnken design around the best path point, a quadratic fit and
//!    ANOVA (seed 000 §3.5, Tables 7–9, eq. (22)).
//! 4. [`optimum`]: Derringer–Suich desirability with the measured angle as the target
//!    (seed 000 §3.6.1).
//! 5. [`validation`]: a simulation of the optimum and its relative error
//!    ψ = |ζ′ − ζ|/ζ × 100 % (seed 000 eq. (21), §3.6.2).
//!
//! Every simulation goes through a [`Simulator`] (the DEM rigs of `crate::experiments` via
//! [`DemExperiment`], or in tests [`Seed000Surrogate`]) and the [`run_cache`]: each finished run is
//! stored as `OUT/runs/<spec hash>.json` the moment it finishes, so an interrupted
//! calibration resumes where it stopped and, the simulator being deterministic, ends with
//! the same bits. Runs execute in parallel on a rayon pool of `jobs` threads; results are
//! put back in run order, never completion order, so the thread count cannot change the
//! output. [`report`] writes `calibration.json`, `report.md` and SVG figures, all atomically.

pub mod box_behnken;
pub mod dem;
pub mod error;
pub mod figures;
pub mod optimum;
pub mod progress;
pub mod report;
pub mod run_cache;
pub mod screening;
pub mod simulator;
pub mod steepest_ascent;
pub mod surrogate;
pub mod validation;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use serde::Serialize;

pub use dem::DemExperiment;
pub use error::CalibrateError;
pub use progress::Progress;
pub use run_cache::RunCache;
pub use simulator::{parameter_values, RunResult, SimulationError, Simulator};
pub use surrogate::Seed000Surrogate;

use crate::study::parameters::lookup;
use crate::study::{Experiment, Study};

/// Format tag of `calibration.json`.
pub const CALIBRATION_FORMAT: &str = "arachis-calibration-1";

/// Folder of stored runs inside the output folder.
pub const RUNS_DIR: &str = "runs";

/// How to run a calibration.
#[derive(Debug, Clone)]
pub struct CalibrateOptions {
    /// Run mode (a `[plan.modes]` key); `None` takes the plan's `mode`.
    pub mode: Option<String>,
    /// Worker threads; `None` uses every core.
    pub jobs: Option<usize>,
    /// The output folder (created if missing).
    pub out_dir: PathBuf,
    /// Progress display.
    pub progress: Progress,
}

/// A finished calibration and how much work it took.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Every number of the calibration (what `calibration.json` holds).
    pub calibration: Calibration,
    /// Runs simulated by this call.
    pub simulated: usize,
    /// Runs replayed from the run cache.
    pub replayed: usize,
}

/// The target the calibration aims at.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetInfo {
    /// The experiment.
    pub experiment: Experiment,
    /// The quantity.
    pub quantity: String,
    /// Its unit.
    pub unit: String,
    /// The measured mean, in `unit`.
    pub value: f64,
    /// The measurement's condition.
    pub condition: BTreeMap<String, f64>,
}

/// Every number of a calibration, as written to `calibration.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Calibration {
    /// [`CALIBRATION_FORMAT`].
    pub format: &'static str,
    /// The study's name.
    pub study: String,
    /// The run mode.
    pub mode: String,
    /// The simulator's id.
    pub simulator: String,
    /// The simulator in words.
    pub simulator_description: String,
    /// The target measurement.
    pub target: TargetInfo,
    /// Stage 1.
    pub screening: screening::Screening,
    /// Stage 2.
    pub steepest_ascent: steepest_ascent::SteepestAscent,
    /// Stage 3 and the response-surface fit.
    pub box_behnken: box_behnken::BoxBehnkenStage,
    /// Stage 4.
    pub optimum: optimum::Optimum,
    /// Stage 5.
    pub validation: validation::Validation,
}

/// One run a stage asks for.
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedRun {
    /// Coded settings (the stage's coding, one per design column).
    pub coded: Vec<f64>,
    /// The parameters this run sets (registry name → value in the parameter's unit); all
    /// others take their held values ([`Study::held_value`]).
    pub values: BTreeMap<String, f64>,
    /// 0 for the first run at these settings, 1 for the next, …: a replicate is the same
    /// point with the study's random seed advanced by this much, so replicated centre
    /// points are independent piles (pure error), not copies.
    pub replicate: u32,
}

/// One finished run as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunRecord {
    /// 1-based run number within the stage (standard order).
    pub run: usize,
    /// Coded settings.
    pub coded: Vec<f64>,
    /// The parameters the run set (registry name → value in the parameter's unit).
    pub actual: BTreeMap<String, f64>,
    /// Replicate index (see [`PlannedRun::replicate`]).
    pub replicate: u32,
    /// Hash of the run's full specification (its file under `runs/`).
    pub spec_hash: String,
    /// The response, in the target's unit.
    pub response: f64,
}

/// Replicate indices of `rows`: how many earlier rows have the same settings.
pub fn replicate_indices(rows: &[Vec<f64>]) -> Vec<u32> {
    rows.iter()
        .enumerate()
        .map(|(i, row)| rows[..i].iter().filter(|r| *r == row).count() as u32)
        .collect()
}

/// The runs of `design` (real factors `factors`, in design-column order), replicates
/// numbered by [`replicate_indices`].
pub fn planned_runs(
    factors: &[screening::FactorInfo],
    design: &crate::doe::Design,
) -> Vec<PlannedRun> {
    let replicates = replicate_indices(&design.coded);
    design
        .coded
        .iter()
        .zip(replicates)
        .enumerate()
        .map(|(i, (row, replicate))| PlannedRun {
            coded: row.clone(),
            values: factors
                .iter()
                .zip(design.actual_row(i))
                .map(|(f, v)| (f.name.clone(), v))
                .collect::<BTreeMap<_, _>>(),
            replicate,
        })
        .collect()
}

/// What the stages share: the study, the simulator, the cache and the worker pool.
pub struct Runner<'a> {
    study: &'a Study,
    simulator: &'a dyn Simulator,
    mode: String,
    cache: RunCache,
    pool: rayon::ThreadPool,
    progress: Progress,
    simulated: AtomicUsize,
    replayed: AtomicUsize,
}

impl<'a> Runner<'a> {
    /// A runner for `study` in `mode`, storing runs under `out_dir/runs` with `jobs` threads.
    pub fn new(
        study: &'a Study,
        simulator: &'a dyn Simulator,
        options: &CalibrateOptions,
    ) -> Result<Self, CalibrateError> {
        let mode = options
            .mode
            .clone()
            .unwrap_or_else(|| study.file().plan.mode.clone());
        if !study.file().plan.modes.contains_key(&mode) {
            let known: Vec<&String> = study.file().plan.modes.keys().collect();
            return Err(CalibrateError::Plan(format!(
                "no mode '{mode}' in [plan.modes] (the study has {known:?})"
            )));
        }
        let jobs = options.jobs.unwrap_or_else(|| {
            std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
        });
        if jobs == 0 {
            return Err(CalibrateError::Threads {
                jobs,
                reason: "at least one is needed".into(),
            });
        }
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(jobs)
            .build()
            .map_err(|e| CalibrateError::Threads {
                jobs,
                reason: e.to_string(),
            })?;
        let cache = RunCache::open(&options.out_dir.join(RUNS_DIR), simulator)?;
        Ok(Self {
            study,
            simulator,
            mode,
            cache,
            pool,
            progress: options.progress.clone(),
            simulated: AtomicUsize::new(0),
            replayed: AtomicUsize::new(0),
        })
    }

    /// The study.
    pub fn study(&self) -> &Study {
        self.study
    }

    /// The simulator.
    pub fn simulator(&self) -> &dyn Simulator {
        self.simulator
    }

    /// The run mode.
    pub fn mode(&self) -> &str {
        &self.mode
    }

    /// Runs the rayon pool's work (the desirability search uses it too).
    pub fn install<R: Send>(&self, work: impl FnOnce() -> R + Send) -> R {
        self.pool.install(work)
    }

    /// Runs simulated and replayed so far.
    pub fn counts(&self) -> (usize, usize) {
        (
            self.simulated.load(Ordering::Relaxed),
            self.replayed.load(Ordering::Relaxed),
        )
    }

    /// The full specification of `run` of `experiment` at `condition`.
    pub fn spec(
        &self,
        stage: &'static str,
        index: usize,
        experiment: Experiment,
        condition: &BTreeMap<String, f64>,
        run: &PlannedRun,
    ) -> Result<crate::study::RunSpec, CalibrateError> {
        for (name, value) in &run.values {
            let spec = lookup(name).ok_or_else(|| CalibrateError::Spec {
                stage,
                run: index + 1,
                reason: format!("unknown parameter '{name}'"),
            })?;
            let limits = self
                .study
                .file()
                .parameters
                .get(name)
                .map_or(spec.limits, |r| r.limits(spec));
            limits
                .check(*value)
                .map_err(|reason| CalibrateError::OutOfLimits {
                    stage,
                    run: index + 1,
                    parameter: name.clone(),
                    value: *value,
                    reason,
                })?;
        }
        let mut spec = self
            .study
            .run_spec(experiment, condition, &run.values, &self.mode)
            .map_err(|reason| CalibrateError::Spec {
                stage,
                run: index + 1,
                reason,
            })?;
        spec.simulation.random_seed = spec
            .simulation
            .random_seed
            .wrapping_add(u64::from(run.replicate));
        Ok(spec)
    }

    /// Simulates (or replays) every run of a stage in parallel and returns the records in
    /// run order. Each finished run is stored at once; the first failure (in run order among
    /// those that failed) stops the stage.
    pub fn run_batch(
        &self,
        stage: &'static str,
        experiment: Experiment,
        condition: &BTreeMap<String, f64>,
        runs: &[PlannedRun],
    ) -> Result<Vec<RunRecord>, CalibrateError> {
        let specs = runs
            .iter()
            .enumerate()
            .map(|(i, r)| self.spec(stage, i, experiment, condition, r))
            .collect::<Result<Vec<_>, _>>()?;
        let hashes: Vec<_> = specs.iter().map(|s| s.spec_hash()).collect();
        let mut results: Vec<Option<RunResult>> = specs
            .iter()
            .zip(&hashes)
            .map(|(s, h)| self.cache.load(s, *h))
            .collect();
        let missing: Vec<usize> = (0..runs.len()).filter(|&i| results[i].is_none()).collect();
        let replayed = runs.len() - missing.len();
        self.replayed.fetch_add(replayed, Ordering::Relaxed);
        let bar = self.progress.stage(stage, runs.len(), replayed);
        let outcome: Vec<Result<(usize, RunResult), CalibrateError>> = self.pool.install(|| {
            missing
                .par_iter()
                .map(|&i| {
                    let failed = |reason: String| CalibrateError::Simulation {
                        stage,
                        run: i + 1,
                        hash: hashes[i].to_string(),
                        reason,
                    };
                    let result = self
                        .simulator
                        .simulate(&specs[i])
                        .map_err(|e| failed(e.0))?;
                    if !result.response.is_finite() {
                        return Err(failed(format!(
                            "the response {} is not a finite number",
                            result.response
                        )));
                    }
                    self.cache.store(&specs[i], hashes[i], result)?;
                    self.simulated.fetch_add(1, Ordering::Relaxed);
                    bar.inc(1);
                    Ok((i, result))
                })
                .collect()
        });
        bar.finish_and_clear();
        for item in outcome {
            let (i, result) = item?;
            results[i] = Some(result);
        }
        Ok(runs
            .iter()
            .zip(results)
            .zip(&hashes)
            .enumerate()
            .map(|(i, ((run, result), hash))| RunRecord {
                run: i + 1,
                coded: run.coded.clone(),
                actual: run.values.clone(),
                replicate: run.replicate,
                spec_hash: hash.to_string(),
                response: result.expect("every run finished").response,
            })
            .collect())
    }
}

/// Runs the whole plan of `study` with `simulator`, writing the report folder to
/// `options.out_dir`. Returns the calibration even when validation misses its tolerance
/// (the report says so; [`validation::Validation::passed`] tells).
pub fn calibrate(
    study: &Study,
    simulator: &dyn Simulator,
    options: &CalibrateOptions,
) -> Result<Outcome, CalibrateError> {
    let runner = Runner::new(study, simulator, options)?;
    let target_m = study.target();
    let target = TargetInfo {
        experiment: target_m.experiment,
        quantity: target_m.quantity.clone(),
        unit: target_m.unit.clone(),
        value: target_m
            .mean()
            .ok_or_else(|| CalibrateError::Plan("the target measurement has no mean".into()))?,
        condition: target_m.condition.clone(),
    };
    let screening = screening::run(&runner, &target)?;
    let path = steepest_ascent::run(&runner, &target, &screening)?;
    let bbd = box_behnken::run(&runner, &target, &path)?;
    let optimum = optimum::run(&runner, &target, &screening, &bbd)?;
    let validation = validation::run(&runner, &optimum)?;
    let calibration = Calibration {
        format: CALIBRATION_FORMAT,
        study: study.file().study.name.clone(),
        mode: runner.mode().to_owned(),
        simulator: simulator.id(),
        simulator_description: simulator.description(),
        target,
        screening,
        steepest_ascent: path,
        box_behnken: bbd,
        optimum,
        validation,
    };
    report::write_all(&runner, &calibration, &options.out_dir)?;
    let (simulated, replayed) = runner.counts();
    Ok(Outcome {
        calibration,
        simulated,
        replayed,
    })
}
