//! The harvest rig: plants through a toothed picking drum (seed 001 §3.3, `crate::harvest`),
//! one replicate per run — [`PLANTS_PER_RUN`] plants of the shipped small topology, their
//! layouts drawn from the replicate's seed — and its loss rate, the percentage of pods lost.
//!
//! Parameters: the machine's drum speed, conveyor speed and drum length, and the pod–stalk
//! junction's critical stress σc = τc (the bond a calibration to field losses would tune;
//! seed 001 Table 12). The rest of the machine is `harvest::Machine`'s default, the plant
//! the shipped `testdata/peanut-plant/topology-small.toml`. Fixed point: the same values
//! and replicate give the same bits on any thread count.

use arachis_core::prelude::Fx;
use serde_json::json;

use super::kind::{Quantity, RigKind, WorldKind};
use super::parameter::RigParameter;
use crate::calibration::{ParameterValues, Responses, Rig, RigError, RunRequest};
use crate::harvest::{run_harvest, HarvestConfig, Machine};
use crate::limits::Limits;
use crate::plant::{generate, Topology, SHIPPED_TOPOLOGY};

/// The rig's name in study files.
pub const NAME: &str = "harvest";
/// The response: pods lost over pods harvested, %.
pub const LOSS_RATE: &str = "loss_rate";
/// The pod–stalk junction bonds broken in the run.
pub const JUNCTION_BREAKS: &str = "junction_breaks";
/// Plants per run (one replicate): as many as `arachis harvest` puts in a replicate.
pub const PLANTS_PER_RUN: u32 = 4;
/// Seed of replicate 0's plant layouts (replicate r uses this + r).
pub const BASE_SEED: u64 = 1;
/// The topology bond set of the pod–stalk junction.
const JUNCTION_SET: &str = "pod_stalk";

/// The drum speed, rpm.
pub const DRUM_SPEED: RigParameter = RigParameter::base(
    "machine.drum_speed_rpm",
    "rpm",
    Limits::Positive,
    "picking-drum speed",
    10.0,
    500.0,
);
/// The conveyor speed, m/s.
pub const FORWARD_SPEED: RigParameter = RigParameter::base(
    "machine.forward_speed_m_s",
    "m/s",
    Limits::Positive,
    "clamp-conveyor speed of the plants",
    0.02,
    1.0,
);
/// The drum length, m.
pub const DRUM_LENGTH: RigParameter = RigParameter::base(
    "machine.drum_length_m",
    "m",
    Limits::Positive,
    "length of the picking drum",
    0.002,
    0.12,
);
/// The junction's critical stresses σc = τc, Pa.
pub const JUNCTION_STRENGTH: RigParameter = RigParameter::base(
    "junction.strength_pa",
    "Pa",
    Limits::Positive,
    "critical stress σc = τc of the pod–stalk junction",
    1.0e4,
    1.0e6,
);

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: NAME,
    about: "plants through a toothed picking drum (loss rate, seed 001 §3.3)",
    world: WorldKind::Fixed,
    random: true,
    quantities: &[
        Quantity {
            name: LOSS_RATE,
            unit: "%",
            label: "loss rate, %",
        },
        Quantity {
            name: JUNCTION_BREAKS,
            unit: "-",
            label: "pod–stalk junctions broken",
        },
    ],
    conditions: &[],
    parameters: &[DRUM_SPEED, FORWARD_SPEED, DRUM_LENGTH, JUNCTION_STRENGTH],
    build: |_, _| Ok(Box::new(HarvestRig)),
};

/// The harvest rig (module notes).
#[derive(Debug, Clone, Copy, Default)]
pub struct HarvestRig;

impl HarvestRig {
    /// The machine and the plant topology with `values` applied; an unknown parameter or a
    /// value outside its limits is refused.
    fn setup(&self, values: &ParameterValues) -> Result<(Machine, Topology), RigError> {
        let mut machine = Machine::default();
        let mut topology =
            Topology::from_toml(SHIPPED_TOPOLOGY).map_err(|e| RigError(e.to_string()))?;
        for (name, &v) in values {
            if !(v.is_finite() && v > 0.0) {
                return Err(RigError(format!("{name} = {v} must be a positive number")));
            }
            match name.as_str() {
                n if n == DRUM_SPEED.key => machine.drum_speed_rpm = v,
                n if n == FORWARD_SPEED.key => machine.forward_speed_m_s = v,
                n if n == DRUM_LENGTH.key => machine.drum_length_m = v,
                n if n == JUNCTION_STRENGTH.key => {
                    let set = topology.bonds.get_mut(JUNCTION_SET).ok_or_else(|| {
                        RigError(format!("the plant has no bond set '{JUNCTION_SET}'"))
                    })?;
                    set.sigma_c_pa = v;
                    set.tau_c_pa = v;
                }
                other => {
                    let known: Vec<&str> = KIND.parameters.iter().map(|p| p.key).collect();
                    return Err(RigError(format!(
                        "the harvest rig has no parameter '{other}' (it has {})",
                        known.join(", ")
                    )));
                }
            }
        }
        machine.check().map_err(|e| RigError(e.to_string()))?;
        Ok((machine, topology))
    }
}

impl Rig for HarvestRig {
    fn id(&self) -> String {
        format!("arachis-harvest-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        format!(
            "Arachis virtual harvest (fixed-point core; {PLANTS_PER_RUN} small plants through a \
             toothed picking drum, seed 001 §3.3)"
        )
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        if let Some(key) = request.condition.keys().next() {
            return Err(RigError(format!(
                "the harvest rig takes no condition '{key}'"
            )));
        }
        let (machine, topology) = self.setup(request.values)?;
        let junction = &topology.bonds[JUNCTION_SET];
        Ok(json!({
            "rig": NAME,
            "machine": machine,
            "junction_strength_pa": [junction.sigma_c_pa, junction.tau_c_pa],
            "plants": PLANTS_PER_RUN,
            "seed": BASE_SEED.wrapping_add(u64::from(request.replicate)),
        }))
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        self.specification(request)?;
        let (machine, topology) = self.setup(request.values)?;
        let model = generate(&topology).map_err(|e| RigError(e.to_string()))?;
        let config = HarvestConfig {
            machine,
            plants: PLANTS_PER_RUN,
            replicates: 1,
            seed: BASE_SEED.wrapping_add(u64::from(request.replicate)),
            ..HarvestConfig::default()
        };
        let outcome =
            run_harvest::<Fx>(&config, &model, &|_| {}).map_err(|e| RigError(e.to_string()))?;
        let replicate = &outcome.replicates[0];
        Ok(Responses::from([
            (LOSS_RATE.to_owned(), replicate.loss_percent),
            (JUNCTION_BREAKS.to_owned(), replicate.junction_breaks as f64),
        ]))
    }
}
