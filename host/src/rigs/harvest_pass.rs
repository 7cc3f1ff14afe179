//! One plant's pass through the picking drum as a [`Rig`], so that `arachis harvest` can
//! hand its passes to an executor (a run cache, a Slurm cluster) like any campaign. It is
//! not a study experiment (not in the catalogue): the harvest command builds it from its
//! own flags, and a cluster worker from the task's recipe.
//!
//! The request's condition is the plant's layout (`yaw_rad`, `lateral_offset_m`,
//! `drum_phase_rad`, [`PlantLayout`]); its values must be empty. The specification names the
//! machine, the topology (by the FNV-1a 64 of its text), the scalar and the layout. The
//! responses are the pass's pod counts, bond breaks, steps, time step and the halves of its
//! state digest; [`pass_result`] turns them back into the [`PassResult`] a harvest report
//! is assembled from (the pods' fates as counts, which is all a report reads).
//!
//! ```no_run
//! use arachis::harvest::{Machine, PlantLayout};
//! use arachis::rigs::harvest_pass::{layout_condition, HarvestPassRig};
//! use arachis::calibration::{Rig, RunRequest};
//! let rig = HarvestPassRig::new(arachis::plant::SHIPPED_TOPOLOGY, Machine::default(), false)?;
//! let layout = PlantLayout { yaw_rad: 0.5, lateral_offset_m: 0.0, drum_phase_rad: 1.0 };
//! let condition = layout_condition(&layout);
//! let values = Default::default();
//! let responses = rig.run(&RunRequest { values: &values, condition: &condition, replicate: 0 })?;
//! # Ok::<(), anyhow::Error>(())
//! ```

use arachis_core::num::Fx;
use serde_json::json;

use crate::calibration::spec_hash::fnv1a_64;
use crate::calibration::{Condition, Responses, Rig, RigError, RunRequest};
use crate::harvest::{run_pass, Fate, Machine, PassResult, PlantLayout};
use crate::plant::{generate, PlantModel, Topology};

/// The rig's name in specifications and task files.
pub const NAME: &str = "harvest-pass";
/// The response the executor reads (every pass has it).
pub const QUANTITY: &str = "pods";

/// Condition keys of a layout.
const YAW: &str = "yaw_rad";
const OFFSET: &str = "lateral_offset_m";
const PHASE: &str = "drum_phase_rad";

/// One pass (module docs).
pub struct HarvestPassRig {
    model: PlantModel,
    topology_fnv: u64,
    machine: Machine,
    f64: bool,
}

impl HarvestPassRig {
    /// The rig of the plant of `topology` (TOML text) on `machine`, stepping in f64 when
    /// `f64`, else in fixed point.
    pub fn new(topology: &str, machine: Machine, f64: bool) -> anyhow::Result<Self> {
        machine.check()?;
        let model = generate(&Topology::from_toml(topology)?)?;
        Ok(Self {
            model,
            topology_fnv: fnv1a_64(topology.as_bytes()),
            machine,
            f64,
        })
    }
}

/// The condition of a pass with `layout`.
pub fn layout_condition(layout: &PlantLayout) -> Condition {
    Condition::from([
        (YAW.to_owned(), layout.yaw_rad),
        (OFFSET.to_owned(), layout.lateral_offset_m),
        (PHASE.to_owned(), layout.drum_phase_rad),
    ])
}

/// The layout a condition names.
fn layout_of(condition: &Condition) -> Result<PlantLayout, RigError> {
    let get = |k: &str| {
        condition
            .get(k)
            .copied()
            .filter(|v| v.is_finite())
            .ok_or_else(|| RigError(format!("a harvest pass needs a finite condition '{k}'")))
    };
    if let Some(k) = condition
        .keys()
        .find(|k| ![YAW, OFFSET, PHASE].contains(&k.as_str()))
    {
        return Err(RigError(format!("a harvest pass takes no condition '{k}'")));
    }
    Ok(PlantLayout {
        yaw_rad: get(YAW)?,
        lateral_offset_m: get(OFFSET)?,
        drum_phase_rad: get(PHASE)?,
    })
}

/// A response that holds a count or a 32-bit half, back as an integer.
fn whole(responses: &Responses, key: &str) -> Result<u64, RigError> {
    let v = responses.get(key).copied().unwrap_or(f64::NAN);
    if v.is_finite() && v >= 0.0 && v.fract() == 0.0 && v < 2f64.powi(53) {
        Ok(v as u64)
    } else {
        Err(RigError(format!(
            "the pass returned no whole '{key}' ({v})"
        )))
    }
}

/// The [`PassResult`] of a pass's responses (no frames; fates grouped by kind).
pub fn pass_result(responses: &Responses) -> Result<PassResult, RigError> {
    let mut fates = Vec::new();
    for (key, fate) in [
        ("collected", Fate::Collected),
        ("unpicked", Fate::Unpicked),
        ("dropped", Fate::Dropped),
    ] {
        fates.extend(std::iter::repeat_n(fate, whole(responses, key)? as usize));
    }
    Ok(PassResult {
        fates,
        junction_breaks: whole(responses, "junction_breaks")?,
        bond_breaks: whole(responses, "bond_breaks")?,
        steps: whole(responses, "steps")?,
        dt_s: responses.get("dt_s").copied().unwrap_or(f64::NAN),
        digest: (whole(responses, "digest_hi")? << 32) | whole(responses, "digest_lo")?,
        frames: Vec::new(),
    })
}

impl Rig for HarvestPassRig {
    fn id(&self) -> String {
        format!("arachis-{NAME}-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        "one plant through the toothed picking drum (seed 001 §3.3)".to_owned()
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        if let Some(name) = request.values.keys().next() {
            return Err(RigError(format!(
                "a harvest pass takes no parameter '{name}'"
            )));
        }
        let layout = layout_of(request.condition)?;
        Ok(json!({
            "rig": NAME,
            "machine": self.machine,
            "topology_fnv1a_64": format!("{:016x}", self.topology_fnv),
            "scalar": if self.f64 { "f64" } else { "fixed" },
            "layout": layout,
        }))
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        self.specification(request)?;
        let layout = layout_of(request.condition)?;
        let quiet = |_| {};
        let pass = if self.f64 {
            run_pass::<f64>(&self.machine, &self.model, &layout, None, &quiet)
        } else {
            run_pass::<Fx>(&self.machine, &self.model, &layout, None, &quiet)
        }
        .map_err(|e| RigError(e.to_string()))?;
        let count = |f: Fate| pass.fates.iter().filter(|&&x| x == f).count() as f64;
        Ok(Responses::from([
            (QUANTITY.to_owned(), pass.fates.len() as f64),
            ("collected".to_owned(), count(Fate::Collected)),
            ("unpicked".to_owned(), count(Fate::Unpicked)),
            ("dropped".to_owned(), count(Fate::Dropped)),
            ("junction_breaks".to_owned(), pass.junction_breaks as f64),
            ("bond_breaks".to_owned(), pass.bond_breaks as f64),
            ("steps".to_owned(), pass.steps as f64),
            ("dt_s".to_owned(), pass.dt_s),
            ("digest_hi".to_owned(), (pass.digest >> 32) as f64),
            ("digest_lo".to_owned(), (pass.digest & 0xffff_ffff) as f64),
        ]))
    }
}
