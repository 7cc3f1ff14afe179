//! The pull-off simulator of the plant calibration: one factor setting in, one detachment
//! force out, from the core's virtual tensile test ([`PullOff`], Q32.32 fixed point, so the
//! same setting gives the same bits on any machine and thread count).
//!
//! [`PullOffArenas`] owns the storage the core borrows (the core never allocates); the
//! `arachis pulloff` command uses it too. [`PullOffSimulator::run_batch`] simulates a
//! stage's runs on the rayon pool and returns them in run order, never completion order.

use arachis_core::prelude::*;
use arachis_core::scenario::pull_off::{PullOff, PullOffResult};
use arachis_core::scenario::ScenarioError;
use rayon::prelude::*;
use serde::Serialize;

use super::error::PlantCalibrationError;
use super::factors::TABLE5;
use crate::arena::{OwnedBonds, OwnedStorage};
use crate::calibrate::Progress;

/// Step budget of one pull: 50 ms of pulling at dt 5e-7 s, 5 mm at 0.1 m/s, about 20 times
/// the junction's stretch at break in the seed's ranges.
pub const MAX_STEPS: u64 = 100_000;

/// Owned arenas of one pull-off world.
pub struct PullOffArenas<S: Scalar> {
    storage: OwnedStorage<S>,
    bonds: OwnedBonds<S>,
}

impl<S: Scalar> PullOffArenas<S> {
    /// Arenas sized for `rig`.
    pub fn new(rig: &PullOff) -> Self {
        Self {
            storage: OwnedStorage::new(rig.storage_lengths()),
            bonds: OwnedBonds::new(rig.bond_capacity()),
        }
    }

    /// The world of `rig` over these arenas.
    pub fn world(&mut self, rig: &PullOff) -> Result<World<'_, S>, ScenarioError> {
        rig.build(self.storage.storage(), self.bonds.storage())
    }
}

/// What one calibration run observed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PullOutcome {
    /// Detachment force, N: the largest pull force before the junction broke.
    pub detachment_force_n: f64,
    /// σc·πRb² of the run's junction, N: the force at which an axial pull must break it
    /// (the criterion in pure tension; an independent check of the simulation).
    pub predicted_axial_n: f64,
}

/// The pull-off rig with every screening factor settable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PullOffSimulator {
    /// The rig before the factors are applied (its pull speed and angle are the test's
    /// conditions).
    pub base: PullOff,
}

impl PullOffSimulator {
    /// The rig with the nine factors of [`TABLE5`] set to `values` (SI).
    pub fn rig(&self, values: &[f64; 9]) -> Result<PullOff, PlantCalibrationError> {
        let mut rig = self.base;
        for (f, &v) in TABLE5.iter().zip(values) {
            f.check(v).map_err(PlantCalibrationError::Plan)?;
            f.apply(&mut rig, v);
        }
        Ok(rig)
    }

    /// Pulls once at `values`. Fails if the junction does not break within [`MAX_STEPS`]
    /// or a stalk bond breaks first (then the junction's force was never measured).
    pub fn pull(&self, values: &[f64; 9]) -> Result<PullOutcome, PlantCalibrationError> {
        let rig = self.rig(values)?;
        let failed = |reason: String| PlantCalibrationError::Simulation {
            values: values.to_vec(),
            reason,
        };
        let mut arenas = PullOffArenas::<Fx>::new(&rig);
        let mut world = arenas.world(&rig).map_err(|e| failed(e.to_string()))?;
        let r: PullOffResult = rig
            .run(&mut world, MAX_STEPS, |_, _| {})
            .map_err(|e| failed(e.to_string()))?;
        if r.stalk_broke_first {
            return Err(failed("a stalk bond broke before the junction".into()));
        }
        if r.break_step.is_none() {
            return Err(failed(format!(
                "the junction held for {MAX_STEPS} steps (peak {} N)",
                r.detachment_force_n
            )));
        }
        Ok(PullOutcome {
            detachment_force_n: r.detachment_force_n,
            predicted_axial_n: rig.predicted_axial_detachment_n(),
        })
    }

    /// Pulls at every setting of `runs` in parallel with a progress bar named `stage`;
    /// results in run order.
    pub fn run_batch(
        &self,
        stage: &str,
        runs: &[[f64; 9]],
        progress: &Progress,
    ) -> Result<Vec<PullOutcome>, PlantCalibrationError> {
        let bar = progress.stage(stage, runs.len(), 0);
        let out = runs
            .par_iter()
            .map(|v| {
                let r = self.pull(v);
                bar.inc(1);
                r
            })
            .collect::<Result<Vec<_>, _>>();
        bar.finish_and_clear();
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unphysical_settings_are_refused_before_simulating() {
        let sim = PullOffSimulator {
            base: PullOff::default(),
        };
        let mut v = TABLE5.map(|f| f.centre());
        v[2] = 1.5;
        let err = sim.pull(&v).unwrap_err().to_string();
        assert!(err.contains("x3"), "{err}");
    }
}
