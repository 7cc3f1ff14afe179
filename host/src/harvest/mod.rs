//! The virtual harvest of issue 6 (seed 001 §3.3): generated plants pass through a picking
//! drum; pods come off when their bonds break; the loss rate of each replicate is compared
//! with the field losses of seed 001 Table 12 by the pooled t-test of [`crate::stats`].
//!
//! A replicate is [`HarvestConfig::plants`] plants of one topology, each with its own random
//! layout ([`pass::PlantLayout`]: yaw about the stem, lateral offset, drum phase) drawn from a
//! ChaCha8 stream seeded with `seed + replicate`; its loss rate is the pooled count of lost
//! pods over all its pods ([`accounting`]). Passes run in parallel (rayon), each in its own
//! world, so results do not depend on the thread count.
//!
//! Simplifications (stated, not hidden):
//! - seed 001 does not describe its harvester or its settings; [`machine::Machine`] is our
//!   stand-in (a toothed drum under plants clamped by the stem top), with typical, not
//!   seed-given, speeds;
//! - each plant passes the drum alone, in its own world: no plant–plant entanglement, no
//!   soil, no digging stage (pods lost in the soil before picking are not modelled);
//! - the drum is a ring of steel spheres (teeth) on an invisible axle; the housing is two
//!   infinite side planes; the collector is a horizontal plane under the drum, and free pods
//!   are classified when they cross it (or, at the end, by their ballistic landing point,
//!   ignoring further collisions);
//! - the plant is the shipped small topology unless another is given (a few pods per plant,
//!   much shorter than seed 001's 764 mm stem and 108 mm stalks, to stay affordable), so the
//!   loss rate of one replicate moves in steps of 1/(pods per replicate);
//! - pods are rigid clumps: none can break, so damaged pods are not a category.

pub mod accounting;
pub mod machine;
pub mod pass;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::Serialize;

use crate::plant::PlantModel;
use crate::stats::{pooled_t_test, PooledTTest};
use crate::vtk::ParticleFrame;
pub use accounting::{Fate, Tally};
pub use machine::{Machine, SEED001_FIELD_LOSS_PERCENT};
pub use pass::{run_pass, PassResult, PlantLayout, Progress};

/// Errors of the virtual harvest.
#[derive(Debug, thiserror::Error)]
pub enum HarvestError {
    /// A machine or run parameter is out of range.
    #[error("harvest parameter {name} {why}")]
    BadParameter {
        /// Parameter name.
        name: &'static str,
        /// What is wrong.
        why: String,
    },
    /// The plant cannot be used.
    #[error("plant: {0}")]
    Plant(String),
    /// The core refused the set-up.
    #[error("simulation set-up: {0}")]
    Core(String),
    /// A step failed.
    #[error("simulation step failed at t = {time_s} s: {what}")]
    Step {
        /// Simulated time, s.
        time_s: f64,
        /// The core's message.
        what: String,
    },
    /// The t-test could not be computed.
    #[error("t-test: {0}")]
    Stats(String),
}

/// What to run.
#[derive(Debug, Clone)]
pub struct HarvestConfig {
    /// The machine.
    pub machine: Machine,
    /// Plants per replicate.
    pub plants: u32,
    /// Replicates (each with its own layouts).
    pub replicates: u32,
    /// Seed of the first replicate (replicate r uses seed + r).
    pub seed: u64,
    /// Field loss rates to compare with, % (default: seed 001 Table 12).
    pub field_loss_percent: Vec<f64>,
    /// Steps between VTK frames (`None`: no frames).
    pub frame_every: Option<u64>,
}

impl Default for HarvestConfig {
    fn default() -> Self {
        HarvestConfig {
            machine: Machine::default(),
            plants: 4,
            replicates: 4,
            seed: 1,
            field_loss_percent: SEED001_FIELD_LOSS_PERCENT.to_vec(),
            frame_every: None,
        }
    }
}

/// One replicate's result.
#[derive(Debug, Clone, Serialize)]
pub struct Replicate {
    /// Its seed.
    pub seed: u64,
    /// Pod counts.
    pub tally: Tally,
    /// Loss rate, %.
    pub loss_percent: f64,
    /// Pod–stalk junction bonds broken.
    pub junction_breaks: u64,
    /// All bonds broken.
    pub bond_breaks: u64,
    /// The plant layouts.
    pub layouts: Vec<PlantLayout>,
    /// Digests of the passes (hex), for determinism checks.
    pub digests: Vec<String>,
}

/// The whole harvest.
#[derive(Debug, Clone, Serialize)]
pub struct HarvestOutcome {
    /// Replicates in order.
    pub replicates: Vec<Replicate>,
    /// Steps run over all passes.
    pub steps: u64,
    /// Time step, s.
    pub dt_s: f64,
    /// Simulated time of one pass, s.
    pub pass_time_s: f64,
    /// Pooled t-test of the simulated against the field loss rates (None if < 2 replicates).
    pub t_test: Option<PooledTTest>,
    /// Frames of each pass, replicate-major (empty without frames).
    #[serde(skip)]
    pub frames: Vec<Vec<ParticleFrame>>,
}

/// Run the harvest. `progress` hears from every pass (from worker threads).
pub fn run_harvest<S: arachis_core::num::Scalar>(
    config: &HarvestConfig,
    model: &PlantModel,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<HarvestOutcome, HarvestError> {
    let passes = plan_passes(config)?;
    // The passes share the cores: each steps on its share of the threads.
    let in_flight = rayon::current_num_threads().min(passes.len()).max(1);
    let threads_per_pass = (crate::stepping::default_threads() / in_flight).max(1);
    let results: Vec<PassResult> = passes
        .par_iter()
        .map(|pass| {
            crate::stepping::with_threads(threads_per_pass, || {
                run_pass::<S>(
                    &config.machine,
                    model,
                    &pass.layout,
                    config.frame_every,
                    progress,
                )
            })
        })
        .collect::<Result<_, _>>()?;
    assemble(config, &passes, results)
}

/// One plant pass of a harvest: its replicate, that replicate's seed and the plant's layout.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedPass {
    /// Replicate index.
    pub replicate: usize,
    /// The replicate's seed.
    pub seed: u64,
    /// The plant's layout.
    pub layout: PlantLayout,
}

/// Every pass of `config`, replicate by replicate (replicate r draws its plants' layouts
/// from the seed + r), after checking the configuration.
pub fn plan_passes(config: &HarvestConfig) -> Result<Vec<PlannedPass>, HarvestError> {
    config.machine.check()?;
    if config.plants == 0 {
        return Err(HarvestError::BadParameter {
            name: "plants",
            why: "must be at least 1".to_owned(),
        });
    }
    if config.replicates == 0 {
        return Err(HarvestError::BadParameter {
            name: "replicates",
            why: "must be at least 1".to_owned(),
        });
    }
    if config
        .field_loss_percent
        .iter()
        .any(|v| !(v.is_finite() && (0.0..=100.0).contains(v)))
    {
        return Err(HarvestError::BadParameter {
            name: "field_loss_percent",
            why: "values must be percentages in [0, 100]".to_owned(),
        });
    }
    if config.frame_every == Some(0) {
        return Err(HarvestError::BadParameter {
            name: "frame_every",
            why: "must be at least 1".to_owned(),
        });
    }
    let mut passes = Vec::new();
    for r in 0..config.replicates {
        let seed = config.seed.wrapping_add(u64::from(r));
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for _ in 0..config.plants {
            passes.push(PlannedPass {
                replicate: r as usize,
                seed,
                layout: PlantLayout::draw(&mut rng),
            });
        }
    }
    Ok(passes)
}

/// The harvest's outcome from the results of its `passes` (as [`plan_passes`] gave them,
/// wherever they were simulated).
pub fn assemble(
    config: &HarvestConfig,
    passes: &[PlannedPass],
    results: Vec<PassResult>,
) -> Result<HarvestOutcome, HarvestError> {
    let mut replicates: Vec<Replicate> = (0..config.replicates)
        .map(|r| Replicate {
            seed: config.seed.wrapping_add(u64::from(r)),
            tally: Tally::default(),
            loss_percent: 0.0,
            junction_breaks: 0,
            bond_breaks: 0,
            layouts: Vec::new(),
            digests: Vec::new(),
        })
        .collect();
    let mut steps = 0;
    let mut dt_s = 0.0;
    let mut pass_steps = 0;
    let mut frames = Vec::new();
    for (pass, res) in passes.iter().zip(results) {
        let rep = &mut replicates[pass.replicate];
        for &f in &res.fates {
            rep.tally.add(f);
        }
        rep.junction_breaks += res.junction_breaks;
        rep.bond_breaks += res.bond_breaks;
        rep.layouts.push(pass.layout);
        rep.digests.push(format!("{:016x}", res.digest));
        steps += res.steps;
        dt_s = res.dt_s;
        pass_steps = pass_steps.max(res.steps);
        frames.push(res.frames);
    }
    for rep in &mut replicates {
        rep.loss_percent = rep.tally.loss_percent().unwrap_or(0.0);
    }
    let sim: Vec<f64> = replicates.iter().map(|r| r.loss_percent).collect();
    let t_test = if sim.len() >= 2 && config.field_loss_percent.len() >= 2 {
        Some(
            pooled_t_test(&sim, &config.field_loss_percent)
                .map_err(|e| HarvestError::Stats(e.to_string()))?,
        )
    } else {
        None
    };
    Ok(HarvestOutcome {
        replicates,
        steps,
        dt_s,
        pass_time_s: pass_steps as f64 * dt_s,
        t_test,
        frames,
    })
}
