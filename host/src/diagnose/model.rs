//! The simulated side of a diagnosis: each experiment's rig, built from the study exactly
//! as a calibration builds it, and the parameters those rigs declare ([`Catalogue`]).
//!
//! Simulations run in parallel on this machine, or, with an [`Executor`] attached
//! ([`Model::with_executor`]), through it: stored in its run cache and replayed from it, or
//! run on a Slurm cluster. Either way a simulation is a pure function of its request, so
//! the numbers are the same.

use anyhow::{Context, Result};

use super::params::Catalogue;
use super::residuals::Experiment;
use rayon::prelude::*;

use crate::calibration::rig::response;
use crate::calibration::{BatchRun, Condition, Executor, ParameterValues, Rig, RunRequest};
use crate::rigs::kind::RigOptions;
use crate::study::Study;

/// The rigs of a study's experiments and their parameters.
pub struct Model<'a> {
    /// One rig per experiment, in the data's order.
    rigs: Vec<Box<dyn Rig + 'a>>,
    /// The rig each experiment runs (its name in the catalogue).
    names: Vec<String>,
    /// The quantity each experiment reads.
    quantities: Vec<String>,
    /// Where simulations run when not on this machine's threads alone.
    executor: Option<Executor>,
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
            executor: None,
            quantities: experiments.iter().map(|e| e.quantity.clone()).collect(),
            catalogue: Catalogue::of_rigs(experiments.iter().map(|e| e.rig.as_str())),
        })
    }

    /// This model with its simulations run through `executor` (module docs).
    pub fn with_executor(mut self, executor: Executor) -> Self {
        self.executor = Some(executor);
        self
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
    /// parallel or through the attached executor.
    pub fn simulate_all(&self, runs: &[(usize, &Condition, ParameterValues)]) -> Result<Vec<f64>> {
        let Some(executor) = &self.executor else {
            return runs
                .par_iter()
                .map(|(e, c, p)| self.simulate_here(*e, c, p))
                .collect();
        };
        let batch: Vec<BatchRun<'_>> = runs
            .iter()
            .map(|(e, c, p)| BatchRun {
                rig: self.rigs[*e].as_ref(),
                experiment: &self.names[*e],
                quantity: &self.quantities[*e],
                values: p.clone(),
                condition: c,
                replicate: 0,
            })
            .collect();
        Ok(executor
            .run_requests("diagnosis", &batch)?
            .into_iter()
            .map(|d| d.response)
            .collect())
    }

    /// One simulation on this thread.
    fn simulate_here(
        &self,
        experiment: usize,
        condition: &Condition,
        p: &ParameterValues,
    ) -> Result<f64> {
        let request = RunRequest {
            values: p,
            condition,
            replicate: 0,
        };
        let quantity = &self.quantities[experiment];
        let responses = self.rigs[experiment].run(&request)?;
        response(&responses, quantity).with_context(|| format!("experiment {}", experiment + 1))
    }
}
