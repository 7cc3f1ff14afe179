//! How to build a campaign's rig anywhere: the study file, the simulator and the run mode
//! (or, for the passes of `arachis harvest`, the topology, machine and scalar,
//! [`HarvestRecipe`]), the same on the machine that plans the campaign and on every cluster
//! node that runs a piece of it. A [`RigRecipe`] is what a worker task carries instead of the rig itself.
//!
//! ```no_run
//! use arachis::cluster::{RigRecipe, Simulator};
//! use arachis::study::Study;
//! let recipe = RigRecipe::new("testdata/peanut-pods-saline/study.toml".as_ref(),
//!                             Simulator::Surrogate, None)?;
//! let study = recipe.load_study()?;
//! let rig = recipe.build(&study, "repose")?;
//! # Ok::<(), anyhow::Error>(())
//! ```

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::Context;
use serde::{Deserialize, Serialize};

use crate::calibration::{Rig, RigError};
use crate::harvest::Machine;
use crate::rigs::harvest_pass::HarvestPassRig;
use crate::rigs::kind::RigOptions;
use crate::rigs::pod_bench::PodBenchRig;
use crate::rigs::pod_world::{Experiment, ModeName};
use crate::rigs::repose_surrogate::{Seed000Surrogate, SurrogateRig};
use crate::study::Study;

/// Which simulator answers a campaign's runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Simulator {
    /// The study's DEM rig.
    Dem,
    /// Seed 000's closed-form surrogate of the repose rig: a test stand-in, NOT a DEM
    /// simulation.
    Surrogate,
}

/// The pull of seed 001's built-in pull-off study as `plant-calibrate` set it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShippedPull {
    /// Gripper speed, m/s.
    pub speed_m_s: f64,
    /// Pull direction from the stalk axis, degrees.
    pub angle_deg: f64,
}

/// The harvest's pass rig, as `arachis harvest` set it up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HarvestRecipe {
    /// The plant topology file, absolute (`None`: the shipped small plant).
    pub topology: Option<PathBuf>,
    /// The machine.
    pub machine: Machine,
    /// Whether the passes step in f64 (else fixed point).
    pub f64: bool,
}

impl HarvestRecipe {
    /// The pass rig.
    pub fn build(&self) -> anyhow::Result<HarvestPassRig> {
        let (text, name) = crate::plant::topology_text(self.topology.as_deref())
            .with_context(|| format!("cannot read the topology {:?}", self.topology))?;
        HarvestPassRig::new(&text, self.machine, self.f64).with_context(|| name)
    }
}

/// Everything besides a run's values that decides which rig simulates it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RigRecipe {
    /// The study file, as an absolute path (workers may start in another folder); for the
    /// built-in pull-off study, the path it is known by.
    pub study: PathBuf,
    /// Set when the study is seed 001's built-in pull-off study (`plant-calibrate`), with
    /// the pull its flags chose: the worker builds that study, not the file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shipped_pull_off: Option<ShippedPull>,
    /// Set for the passes of `arachis harvest`, which have no study (`study` is then
    /// empty): the worker builds this pass rig.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub harvest: Option<HarvestRecipe>,
    /// The simulator.
    pub simulator: Simulator,
    /// The run mode of a pod rig (`quick`, `full`), if the study has modes.
    pub mode: Option<String>,
    /// Whether the study was accepted with values outside their plausible ranges
    /// (`--allow-extreme`); the worker must accept it alike.
    #[serde(default)]
    pub allow_extreme: bool,
    /// Test hook: time each surrogate run sleeps, ms (0 in real use).
    #[serde(default)]
    pub surrogate_delay_ms: u64,
}

impl RigRecipe {
    /// The recipe of `study` (made absolute), `simulator` and `mode`.
    pub fn new(
        study: &Path,
        simulator: Simulator,
        mode: Option<ModeName>,
    ) -> std::io::Result<Self> {
        Ok(Self {
            study: std::path::absolute(study)?,
            shipped_pull_off: None,
            harvest: None,
            simulator,
            mode: mode.map(|m| m.as_str().to_owned()),
            allow_extreme: crate::plausible::extreme_allowed(),
            surrogate_delay_ms: 0,
        })
    }

    /// The recipe's study, loaded (or built, for the built-in pull-off study).
    pub fn load_study(&self) -> anyhow::Result<Study> {
        Ok(match self.shipped_pull_off {
            Some(pull) => {
                let mut study = Study::shipped_pull_off();
                study.set_pull(pull.speed_m_s, pull.angle_deg);
                study
            }
            None => Study::load(&self.study)?,
        })
    }

    /// The recipe of `arachis harvest`'s passes.
    pub fn for_harvest(harvest: HarvestRecipe) -> Self {
        Self {
            study: PathBuf::new(),
            shipped_pull_off: None,
            harvest: Some(harvest),
            simulator: Simulator::Dem,
            mode: None,
            allow_extreme: crate::plausible::extreme_allowed(),
            surrogate_delay_ms: 0,
        }
    }

    /// The run mode, parsed.
    fn mode(&self) -> Result<Option<ModeName>, RigError> {
        self.mode
            .as_deref()
            .map(|m| m.parse().map_err(|e| RigError(format!("mode '{m}': {e}"))))
            .transpose()
    }

    /// The rig of `experiment` in `study` (which must be the recipe's study, loaded), or
    /// the surrogate standing in for the repose rig.
    pub fn build<'a>(
        &self,
        study: &'a Study,
        experiment: &str,
    ) -> Result<Box<dyn Rig + 'a>, RigError> {
        let mode = self.mode()?;
        if self.simulator == Simulator::Dem {
            let options = RigOptions {
                mode,
                ..RigOptions::default()
            };
            return study.rig(experiment, &options);
        }
        let world = study
            .pod_world()
            .filter(|_| experiment == Experiment::Repose.name())
            .ok_or_else(|| {
                RigError(format!(
                    "{}: the surrogate stands in for seed 000's repose runs only, not \
                     {experiment}",
                    self.study.display()
                ))
            })?;
        Ok(Box::new(SurrogateRig {
            pod: PodBenchRig::new(
                world,
                crate::rigs::repose_cylinder::TEST,
                mode.unwrap_or(ModeName::Quick),
            ),
            surrogate: Seed000Surrogate::default(),
            delay: Duration::from_millis(self.surrogate_delay_ms),
        }))
    }
}
