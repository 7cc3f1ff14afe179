//! The simulated side of a diagnosis: each experiment's rig, built from the study exactly
//! as a calibration builds it, and the parameters those rigs declare ([`Catalogue`]).
//!
//! Simulations run in parallel on this machine, or, with an [`Executor`] attached
//! ([`Model::with_executor`]), through it: stored in its run cache and replayed from it, or
//! run on a Slurm cluster. Either way a simulation is a pure function of its request, so
//! the numbers are the same.
//!
//! A rig with a random placement (a pod pile: `RigKind::random`) scatters from one
//! placement to the next. Its prediction is the mean of [`Model::with_replicates`]
//! simulations (replicates 0…n−1 of the run request, [`DEFAULT_RANDOM_REPLICATES`] unless
//! set), and every parameter set is simulated at the same placements: common random
//! numbers, so a finite difference compares like with like and the placement's share of
//! the scatter cancels as far as the runs stay correlated. A deterministic rig runs once.

use anyhow::{Context, Result};

use super::params::Catalogue;
use super::residuals::Experiment;
use rayon::prelude::*;

use crate::calibration::rig::response;
use crate::calibration::{
    BatchRun, Condition, Executor, ParameterValues, Progress, Rig, RunRequest,
};
use crate::rigs::kind::RigOptions;
use crate::study::Study;

/// Simulated replicates per prediction of a rig with a random placement, unless set
/// ([`Model::with_replicates`]).
pub const DEFAULT_RANDOM_REPLICATES: u32 = 4;

/// The prediction from one run's replicates: their mean, summed in replicate order.
pub fn replicate_mean(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, v| m + v / values.len() as f64)
}

/// The rigs of a study's experiments and their parameters.
pub struct Model<'a> {
    /// One rig per experiment, in the data's order.
    rigs: Vec<Box<dyn Rig + 'a>>,
    /// The rig each experiment runs (its name in the catalogue).
    names: Vec<String>,
    /// The quantity each experiment reads.
    quantities: Vec<String>,
    /// Whether each experiment's rig places its particles at random (module docs).
    random: Vec<bool>,
    /// Simulated replicates per prediction of a random rig.
    replicates: u32,
    /// Where simulations run when not on this machine's threads alone.
    executor: Option<Executor>,
    /// The progress bar of simulations run here (an executor draws its own).
    progress: Progress,
    /// Every parameter the rigs declare.
    pub catalogue: Catalogue,
}

impl<'a> Model<'a> {
    /// The rigs of `experiments` over `study` (a pod rig in the study's default mode).
    pub fn new(study: &'a Study, experiments: &[Experiment]) -> Result<Self> {
        let options = RigOptions {
            mode: study.plan_mode()?,
            ..RigOptions::default()
        };
        let rigs = experiments
            .iter()
            .map(|e| study.rig(&e.rig, &options))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            rigs,
            names: experiments.iter().map(|e| e.rig.clone()).collect(),
            random: experiments
                .iter()
                .map(|e| crate::rigs::catalogue::find(&e.rig).is_some_and(|k| k.random))
                .collect(),
            replicates: DEFAULT_RANDOM_REPLICATES,
            executor: None,
            progress: Progress::hidden(),
            quantities: experiments.iter().map(|e| e.quantity.clone()).collect(),
            catalogue: Catalogue::of_rigs(experiments.iter().map(|e| e.rig.as_str())),
        })
    }

    /// This model with its simulations run through `executor` (module docs).
    pub fn with_executor(mut self, executor: Executor) -> Self {
        self.executor = Some(executor);
        self
    }

    /// This model with a progress bar over the simulations it runs on this machine (drawn on
    /// a terminal only; a batch through an executor has the executor's bar).
    pub fn with_progress(mut self, progress: Progress) -> Self {
        self.progress = progress;
        self
    }

    /// This model with `n` ≥ 1 simulated replicates per prediction of a random rig.
    pub fn with_replicates(mut self, n: u32) -> Self {
        self.replicates = n.max(1);
        self
    }

    /// Simulated replicates per prediction of experiment `experiment`.
    pub fn replicates_of(&self, experiment: usize) -> u32 {
        if self.random[experiment] {
            self.replicates
        } else {
            1
        }
    }

    /// The simulated quantity of experiment `experiment` at `condition` with parameters `p`.
    pub fn simulate(
        &self,
        experiment: usize,
        condition: &Condition,
        p: &ParameterValues,
    ) -> Result<f64> {
        Ok(self.simulate_all(&[(experiment, condition, p.clone())])?[0])
    }

    /// The simulated quantity of each (experiment, condition, parameters), in order, run in
    /// parallel or through the attached executor: the mean over the experiment's replicates
    /// ([`Model::replicates_of`]; the same placements for every run).
    pub fn simulate_all(&self, runs: &[(usize, &Condition, ParameterValues)]) -> Result<Vec<f64>> {
        Ok(self
            .simulate_replicates(runs)?
            .iter()
            .map(|each| replicate_mean(each))
            .collect())
    }

    /// Every replicate of each (experiment, condition, parameters), in order: run k's values,
    /// replicate 0 first.
    pub fn simulate_replicates(
        &self,
        runs: &[(usize, &Condition, ParameterValues)],
    ) -> Result<Vec<Vec<f64>>> {
        // Every simulation of every run, replicates of one run adjacent.
        let each: Vec<(usize, u32)> = runs
            .iter()
            .enumerate()
            .flat_map(|(k, (e, _, _))| (0..self.replicates_of(*e)).map(move |rep| (k, rep)))
            .collect();
        let values: Vec<f64> = match &self.executor {
            None => {
                let bar = self.progress.stage("diagnosis", each.len(), 0);
                let values = each
                    .par_iter()
                    .map(|&(k, rep)| {
                        let (e, c, p) = &runs[k];
                        let v = self.simulate_here(*e, c, p, rep);
                        bar.inc(1);
                        v
                    })
                    .collect::<Result<_>>()?;
                bar.finish_and_clear();
                values
            }
            Some(executor) => {
                let batch: Vec<BatchRun<'_>> = each
                    .iter()
                    .map(|&(k, rep)| {
                        let (e, c, p) = &runs[k];
                        BatchRun {
                            rig: self.rigs[*e].as_ref(),
                            experiment: &self.names[*e],
                            quantity: &self.quantities[*e],
                            values: p.clone(),
                            condition: c,
                            replicate: rep,
                        }
                    })
                    .collect();
                executor
                    .run_requests("diagnosis", &batch)?
                    .into_iter()
                    .map(|d| d.response)
                    .collect()
            }
        };
        let mut out: Vec<Vec<f64>> = vec![Vec::new(); runs.len()];
        for (&(k, _), v) in each.iter().zip(values) {
            out[k].push(v);
        }
        Ok(out)
    }

    /// One simulation (replicate `replicate`) on this thread.
    fn simulate_here(
        &self,
        experiment: usize,
        condition: &Condition,
        p: &ParameterValues,
        replicate: u32,
    ) -> Result<f64> {
        let request = RunRequest {
            values: p,
            condition,
            replicate,
        };
        let quantity = &self.quantities[experiment];
        let responses = self.rigs[experiment].run(&request)?;
        response(&responses, quantity).with_context(|| format!("experiment {}", experiment + 1))
    }
}
