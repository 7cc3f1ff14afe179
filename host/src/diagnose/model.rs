//! The simulated side of a diagnosis: each experiment's rig, built from the study exactly
//! as a calibration builds it, and the parameters those rigs declare ([`Catalogue`]).

use anyhow::{Context, Result};

use super::params::Catalogue;
use super::residuals::Experiment;
use crate::calibration::rig::response;
use crate::calibration::{Condition, ParameterValues, Rig, RunRequest};
use crate::rigs::kind::RigOptions;
use crate::study::Study;

/// The rigs of a study's experiments and their parameters.
pub struct Model<'a> {
    /// One rig per experiment, in the data's order.
    rigs: Vec<Box<dyn Rig + 'a>>,
    /// The quantity each experiment reads.
    quantities: Vec<String>,
    /// Every parameter the rigs declare.
    pub catalogue: Catalogue,
}

impl<'a> Model<'a> {
    /// The rigs of `experiments` over `study` (a pod rig in the study's default mode).
    pub fn new(study: &'a Study, experiments: &[Experiment]) -> Result<Self> {
        let mode = study
            .file()
            .plan
            .as_ref()
            .and_then(|p| p.mode.as_deref())
            .map(str::parse)
            .transpose()?;
        let options = RigOptions {
            mode,
            ..RigOptions::default()
        };
        let rigs = experiments
            .iter()
            .map(|e| study.rig(&e.rig, &options))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            rigs,
            quantities: experiments.iter().map(|e| e.quantity.clone()).collect(),
            catalogue: Catalogue::of_rigs(experiments.iter().map(|e| e.rig.as_str())),
        })
    }

    /// The simulated quantity of experiment `experiment` at `condition` with parameters `p`.
    pub fn simulate(
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
