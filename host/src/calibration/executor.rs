//! Where the engine's runs execute: a batch of a stage's runs is checked, looked up in the
//! run cache, and the missing ones are simulated in parallel on a rayon pool of `jobs`
//! threads. Results go back in run order, never completion order, so the thread count
//! cannot change a number; each finished run is stored the moment it finishes, so an
//! interrupted calibration resumes where it stopped.
//!
//! This is the one place that spreads rig runs over cores: a setting of how each run is
//! executed (threads per run, say) belongs here and nowhere else. An executor may instead
//! hand a stage's missing runs to a [`Remote`] backend (a Slurm cluster, `crate::cluster`),
//! which simulates them elsewhere and stores them in the same run cache; the stage then
//! replays them from the cache, so the numbers cannot depend on where a run ran.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use serde::Serialize;

use super::error::CalibrateError;
use super::factor::Factor;
use super::objective::Objective;
use super::progress::Progress;
use super::rig::{response, Condition, ParameterValues, Responses, Rig, RunRequest};
use super::run_cache::RunCache;
use super::spec_hash::SpecHash;

/// One run a stage asks for.
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedRun {
    /// Coded settings (the stage's coding, one per design column).
    pub coded: Vec<f64>,
    /// The factors this run sets (name → value in the factor's unit); every other factor
    /// takes its held value.
    pub values: ParameterValues,
    /// Replicate index ([`RunRequest::replicate`]).
    pub replicate: u32,
}

/// One finished run; serialised as `calibration.json` lists it (the factors' values as
/// `actual`, without the rig's other responses).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunRecord {
    /// 1-based run number within the stage (standard order).
    pub run: usize,
    /// Coded settings.
    pub coded: Vec<f64>,
    /// The factors the run set (name → value).
    #[serde(rename = "actual")]
    pub values: ParameterValues,
    /// Replicate index.
    pub replicate: u32,
    /// Hash of the run's specification (its file under `runs/`).
    pub spec_hash: SpecHash,
    /// The objective's quantity, in its unit.
    pub response: f64,
    /// Every response the rig returned.
    #[serde(skip)]
    pub responses: Responses,
}

/// Replicate indices of `rows`: how many earlier rows have the same settings.
pub fn replicate_indices(rows: &[Vec<f64>]) -> Vec<u32> {
    rows.iter()
        .enumerate()
        .map(|(i, row)| rows[..i].iter().filter(|r| *r == row).count() as u32)
        .collect()
}

/// One run of [`Executor::run_requests`]: a rig, the response read from it, and the request.
#[derive(Clone)]
pub struct BatchRun<'a> {
    /// The rig.
    pub rig: &'a dyn Rig,
    /// The study experiment (rig name) it belongs to: how a remote worker builds the rig.
    pub experiment: &'a str,
    /// The response read from it.
    pub quantity: &'a str,
    /// Every parameter the run sets.
    pub values: ParameterValues,
    /// The measurement's condition.
    pub condition: &'a Condition,
    /// Replicate index.
    pub replicate: u32,
}

impl BatchRun<'_> {
    /// The rig's request.
    pub fn request(&self) -> RunRequest<'_> {
        RunRequest {
            values: &self.values,
            condition: self.condition,
            replicate: self.replicate,
        }
    }
}

/// A run of [`Executor::run_requests`], finished or replayed.
#[derive(Debug, Clone, PartialEq)]
pub struct FinishedRun {
    /// Hash of its specification.
    pub spec_hash: SpecHash,
    /// The response asked for.
    pub response: f64,
    /// Every response of the rig.
    pub responses: Responses,
}

/// One run a stage hands to a [`Remote`] backend: what a worker elsewhere needs to
/// simulate it, besides the recipe of the rig (which the backend holds).
#[derive(Debug, Clone, Copy)]
pub struct RemoteRun<'a> {
    /// The stage.
    pub stage: &'static str,
    /// 1-based run number within the stage.
    pub run: usize,
    /// Hash of the run's specification (its file in the run cache).
    pub spec_hash: SpecHash,
    /// The specification itself.
    pub spec: &'a serde_json::Value,
    /// The rig's [`Rig::id`], stored with the run.
    pub rig_id: &'a str,
    /// The study experiment whose rig runs it ([`Objective::experiment`]).
    pub experiment: &'a str,
    /// The response the stage reads ([`Objective::quantity`]).
    pub quantity: &'a str,
    /// The run itself.
    pub request: RunRequest<'a>,
}

/// Somewhere else to simulate runs: it returns once every run it was given is stored in
/// `cache` (as [`RunCache::store`] writes it), or with the error that stopped it.
pub trait Remote: Send + Sync {
    /// Simulates `runs` elsewhere, storing each in `cache`; `bar` counts finished runs.
    fn run_all(
        &self,
        runs: &[RemoteRun<'_>],
        cache: &RunCache,
        bar: &indicatif::ProgressBar,
    ) -> Result<(), CalibrateError>;
}

/// Runs batches of runs; counts what it simulated and replayed.
pub struct Executor {
    cache: Option<RunCache>,
    remote: Option<Box<dyn Remote>>,
    pool: rayon::ThreadPool,
    progress: Progress,
    simulated: AtomicUsize,
    replayed: AtomicUsize,
}

impl Executor {
    /// An executor with `jobs` threads (`None`: every core), storing runs in `cache_dir`
    /// when given.
    pub fn new(
        jobs: Option<usize>,
        cache_dir: Option<&Path>,
        progress: Progress,
    ) -> Result<Self, CalibrateError> {
        let jobs = jobs.unwrap_or_else(|| {
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
        let cache = cache_dir.map(RunCache::open).transpose()?;
        Ok(Self {
            cache,
            remote: None,
            pool,
            progress,
            simulated: AtomicUsize::new(0),
            replayed: AtomicUsize::new(0),
        })
    }

    /// This executor with its stages' missing runs simulated by `remote` instead of on the
    /// local pool; refused without a run cache, where the remote runs are stored.
    pub fn with_remote(mut self, remote: Box<dyn Remote>) -> Result<Self, CalibrateError> {
        if self.cache.is_none() {
            return Err(CalibrateError::Plan(
                "a remote executor needs a run cache to collect its runs in".into(),
            ));
        }
        self.remote = Some(remote);
        Ok(self)
    }

    /// Runs `work` on the pool (the desirability search uses it too).
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

    /// Every factor's value for `run`: the run's settings, the held values elsewhere.
    pub fn full_values(factors: &[Factor], run: &PlannedRun) -> ParameterValues {
        let mut values: ParameterValues =
            factors.iter().map(|f| (f.name.clone(), f.held)).collect();
        values.extend(run.values.iter().map(|(k, v)| (k.clone(), *v)));
        values
    }

    /// Every factor's value for run `index` of `stage`, each checked against its factor's
    /// limits.
    pub fn checked_values(
        stage: &'static str,
        index: usize,
        factors: &[Factor],
        run: &PlannedRun,
    ) -> Result<ParameterValues, CalibrateError> {
        let values = Self::full_values(factors, run);
        for f in factors {
            let value = values[&f.name];
            f.admitted
                .check(value)
                .map_err(|reason| CalibrateError::OutOfLimits {
                    stage,
                    run: index + 1,
                    parameter: f.name.clone(),
                    value,
                    reason,
                })?;
        }
        Ok(values)
    }

    /// Simulates (or replays) every run of a stage in parallel and returns the records in
    /// run order. Each finished run is stored at once; the first failure (in run order
    /// among those that failed) stops the stage.
    pub fn run_batch(
        &self,
        stage: &'static str,
        objective: &Objective<'_>,
        factors: &[Factor],
        runs: &[PlannedRun],
    ) -> Result<Vec<RunRecord>, CalibrateError> {
        let values = runs
            .iter()
            .enumerate()
            .map(|(i, r)| Self::checked_values(stage, i, factors, r))
            .collect::<Result<Vec<_>, _>>()?;
        let batch: Vec<BatchRun<'_>> = runs
            .iter()
            .zip(values)
            .map(|(run, values)| BatchRun {
                rig: objective.rig,
                experiment: &objective.experiment,
                quantity: &objective.quantity,
                values,
                condition: &objective.condition,
                replicate: run.replicate,
            })
            .collect();
        let done = self.run_requests(stage, &batch)?;
        Ok(runs
            .iter()
            .zip(done)
            .enumerate()
            .map(|(i, (run, d))| RunRecord {
                run: i + 1,
                coded: run.coded.clone(),
                values: run.values.clone(),
                replicate: run.replicate,
                spec_hash: d.spec_hash,
                response: d.response,
                responses: d.responses,
            })
            .collect())
    }

    /// Simulates (or replays) any runs, each on its own rig and condition, in parallel (or
    /// on the remote backend), and returns them in order. A diagnosis asks for its
    /// predictions and finite differences this way.
    pub fn run_requests(
        &self,
        stage: &'static str,
        batch: &[BatchRun<'_>],
    ) -> Result<Vec<FinishedRun>, CalibrateError> {
        let specs = batch
            .iter()
            .enumerate()
            .map(|(i, b)| {
                b.rig
                    .specification(&b.request())
                    .map_err(|e| CalibrateError::Spec {
                        stage,
                        run: i + 1,
                        reason: e.0,
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let hashes: Vec<SpecHash> = specs.iter().map(SpecHash::of).collect();
        let rig_ids: Vec<String> = batch.iter().map(|b| b.rig.id()).collect();
        let load = |i: usize| {
            self.cache
                .as_ref()
                .and_then(|c| c.load(&specs[i], hashes[i], &rig_ids[i], batch[i].quantity))
        };
        let mut results: Vec<Option<Responses>> = (0..batch.len()).map(load).collect();
        let missing: Vec<usize> = (0..batch.len()).filter(|&i| results[i].is_none()).collect();
        let replayed = batch.len() - missing.len();
        self.replayed.fetch_add(replayed, Ordering::Relaxed);
        let bar = self.progress.stage(stage, batch.len(), replayed);
        let failed = |i: usize, reason: String| CalibrateError::Simulation {
            stage,
            run: i + 1,
            hash: hashes[i].to_string(),
            reason,
        };
        if let Some(remote) = &self.remote {
            let remote_runs: Vec<RemoteRun<'_>> = missing
                .iter()
                .map(|&i| RemoteRun {
                    stage,
                    run: i + 1,
                    spec_hash: hashes[i],
                    spec: &specs[i],
                    rig_id: &rig_ids[i],
                    experiment: batch[i].experiment,
                    quantity: batch[i].quantity,
                    request: batch[i].request(),
                })
                .collect();
            let cache = self.cache.as_ref().expect("a remote executor has a cache");
            remote.run_all(&remote_runs, cache, &bar)?;
            for &i in &missing {
                results[i] = Some(load(i).ok_or_else(|| {
                    failed(
                        i,
                        format!(
                            "the remote executor finished without a valid stored run {}",
                            cache.path(hashes[i]).display()
                        ),
                    )
                })?);
            }
            self.simulated.fetch_add(missing.len(), Ordering::Relaxed);
        } else {
            // The runs of a stage share the cores: each steps on its share of the threads.
            let in_flight = self.pool.current_num_threads().min(missing.len()).max(1);
            let threads_per_run = (crate::stepping::default_threads() / in_flight).max(1);
            let outcome: Vec<Result<(usize, Responses), CalibrateError>> =
                self.pool.install(|| {
                    missing
                        .par_iter()
                        .map(|&i| {
                            let b = &batch[i];
                            let responses = crate::stepping::with_threads(threads_per_run, || {
                                b.rig.run(&b.request())
                            })
                            .map_err(|e| failed(i, e.0))?;
                            response(&responses, b.quantity).map_err(|e| failed(i, e.0))?;
                            if let Some(cache) = &self.cache {
                                cache.store(&specs[i], hashes[i], &rig_ids[i], &responses)?;
                            }
                            self.simulated.fetch_add(1, Ordering::Relaxed);
                            bar.inc(1);
                            Ok((i, responses))
                        })
                        .collect()
                });
            for item in outcome {
                let (i, responses) = item?;
                results[i] = Some(responses);
            }
        }
        bar.finish_and_clear();
        results
            .into_iter()
            .enumerate()
            .map(|(i, responses)| {
                let responses = responses.expect("every run finished");
                let value = response(&responses, batch[i].quantity).map_err(|e| failed(i, e.0))?;
                Ok(FinishedRun {
                    spec_hash: hashes[i],
                    response: value,
                    responses,
                })
            })
            .collect()
    }
}
