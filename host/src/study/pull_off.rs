//! The pull-off study's sections (seed 001's study, `testdata/peanut-plant/study.toml`):
//! `[rig]` ([`PullOffRigSection`]: the tensile test — the topology whose bond sets it uses,
//! and the pull's conditions), `[measurement]` ([`MeasuredForce`]: the detachment force to
//! calibrate to) and `[factors.x1]` … `[factors.x9]` ([`FactorLevels`]: seed 001 Table 5's
//! factors with their levels), their checks, and the rig's set-up they give.
//!
//! Checked before any pull: the nine Table 5 factors and only those, low < high within
//! physical limits, the measured force, the topology and its bond sets, the factors a
//! central composite plan names.

use std::collections::BTreeMap;
use std::path::Path;

use arachis_core::bond::BondSetSpec;
use arachis_core::scenario::pull_off::{PullOff, TAG_JUNCTION, TAG_STALK};
use serde::{Deserialize, Serialize};

use super::error::StudyError;
use super::key_path::KeyPath;
use super::source::Source;
use crate::nearest_name::nearest_name;
use crate::plant::topology::BondSet;
use crate::plant::Topology;
use crate::rigs::pull_off::{by_label, PARAMETERS};

/// The `[study] kind` of seed 001's study.
pub const KIND_PULL_OFF: &str = "pull_off";

/// The one quantity a pull-off study calibrates to.
pub const QUANTITY: &str = "detachment_force";
/// Largest pull angle from the stalk axis, degrees (the rig pulls in the x–y plane).
pub const MAX_PULL_ANGLE_DEG: f64 = 90.0;
/// Most stalk spheres (the arenas are sized for the rig; more only slows every pull).
pub const MAX_STALK_SPHERES: u32 = 64;

/// `[rig]`: the virtual tensile test (`arachis_core::scenario::PullOff`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PullOffRigSection {
    /// Plant topology file, relative to the study file; its `[bonds]` give the rig's sets.
    pub topology: String,
    /// The topology bond set of the pod–stalk junction.
    pub junction_bond_set: String,
    /// The topology bond set of the stalk's own bonds.
    pub stalk_bond_set: String,
    /// Spheres in the stalk (≥ 2; the first is clamped).
    pub stalk_spheres: u32,
    /// Gripper speed, m/s.
    pub pull_speed_m_s: f64,
    /// Pull direction from the stalk axis, degrees (0 = axial).
    pub pull_angle_deg: f64,
}

/// `[measurement]`: the measured detachment force.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasuredForce {
    /// What was measured (`"detachment_force"`).
    pub quantity: String,
    /// The force, N.
    pub value_n: f64,
    /// Where the number comes from.
    pub source: String,
}

/// `[factors.<label>]`: a Table 5 factor's levels, in SI units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FactorLevels {
    /// Level at coded −1.
    pub low: f64,
    /// Level at coded +1.
    pub high: f64,
    /// Where the numbers are printed.
    #[serde(default)]
    pub source: Option<String>,
}

/// Checks a decoded file; returns the junction and stalk bond sets of its topology when
/// they could be read, and every error found.
pub(crate) fn validate(
    src: &Source<'_>,
    rig: &PullOffRigSection,
    measurement: Option<&MeasuredForce>,
    factors: &BTreeMap<String, FactorLevels>,
    dir: &Path,
    read: ReadFile<'_>,
) -> (Option<(BondSet, BondSet)>, Vec<StudyError>) {
    let mut errors = Vec::new();
    let root = KeyPath::root();
    let mut err = |key: KeyPath, reason: String| errors.push(src.error(&key, reason));

    let at = root.key("rig");
    let max_speed = crate::rigs::pull_off::MAX_PULL_SPEED_M_S;
    if !(rig.pull_speed_m_s.is_finite()
        && rig.pull_speed_m_s > 0.0
        && rig.pull_speed_m_s <= max_speed)
    {
        err(
            at.key("pull_speed_m_s"),
            format!(
                "must be a positive number of m/s up to {max_speed} (a quasi-static pull), \
                 got {}",
                rig.pull_speed_m_s
            ),
        );
    }
    if !(rig.pull_angle_deg.is_finite() && rig.pull_angle_deg.abs() <= MAX_PULL_ANGLE_DEG) {
        err(
            at.key("pull_angle_deg"),
            format!(
                "must be between -{MAX_PULL_ANGLE_DEG} and {MAX_PULL_ANGLE_DEG} degrees, got {}",
                rig.pull_angle_deg
            ),
        );
    }
    if !(2..=MAX_STALK_SPHERES).contains(&rig.stalk_spheres) {
        err(
            at.key("stalk_spheres"),
            format!(
                "must be 2 to {MAX_STALK_SPHERES} (one clamped, one free at least), got {}",
                rig.stalk_spheres
            ),
        );
    }
    let sets = match read_topology(&dir.join(&rig.topology), read) {
        Err(reason) => {
            err(at.key("topology"), reason);
            None
        }
        Ok(t) => {
            let mut set = |key: &str, name: &str| match t.bonds.get(name) {
                None => {
                    let known: Vec<&str> = t.bonds.keys().map(String::as_str).collect();
                    err(
                        at.key(key),
                        format!(
                            "the topology {} has no bond set '{name}' (it has: {})",
                            rig.topology,
                            known.join(", ")
                        ),
                    );
                    None
                }
                Some(b) => {
                    let values = [b.kn_n_m3, b.kt_n_m3, b.sigma_c_pa, b.tau_c_pa, b.radius_m];
                    if values.iter().all(|v| v.is_finite() && *v > 0.0) {
                        Some(*b)
                    } else {
                        err(
                            at.key(key),
                            format!(
                                "bond set '{name}' of {} needs every stiffness, strength and \
                                 the radius > 0",
                                rig.topology
                            ),
                        );
                        None
                    }
                }
            };
            let junction = set("junction_bond_set", &rig.junction_bond_set);
            let stalk = set("stalk_bond_set", &rig.stalk_bond_set);
            junction.zip(stalk)
        }
    };

    // [measurement]
    let at = root.key("measurement");
    let missing = MeasuredForce {
        quantity: QUANTITY.to_owned(),
        value_n: f64::NAN,
        source: String::new(),
    };
    let m = measurement.unwrap_or(&missing);
    if m.quantity != QUANTITY {
        err(
            at.key("quantity"),
            format!(
                "a pull-off study calibrates to '{QUANTITY}', got '{}'",
                m.quantity
            ),
        );
    }
    if measurement.is_some() && !(m.value_n.is_finite() && m.value_n > 0.0) {
        err(
            at.key("value_n"),
            format!("the measured force must be > 0 N, got {}", m.value_n),
        );
    }

    // [factors]
    let at = root.key("factors");
    let labels: Vec<&str> = PARAMETERS.iter().map(|f| f.label).collect();
    for (label, levels) in factors {
        let Some(f) = by_label(label) else {
            let hint = nearest_name(label, &labels)
                .map_or(String::new(), |n| format!("; did you mean '{n}'?"));
            err(
                at.key(label),
                format!("unknown factor '{label}'{hint} (seed 001 Table 5 has x1…x9)"),
            );
            continue;
        };
        let here = at.key(label);
        let mut ok = true;
        for (key, v) in [("low", levels.low), ("high", levels.high)] {
            if let Err(reason) = f.limits.check(v) {
                err(
                    here.key(key),
                    format!("{} ({}): {reason}", f.label, f.description),
                );
                ok = false;
            }
        }
        if ok && levels.low >= levels.high {
            err(
                here.key("low"),
                format!(
                    "low {} must be below high {} ({} in {})",
                    levels.low, levels.high, f.description, f.unit
                ),
            );
        }
    }
    for f in &PARAMETERS {
        if !factors.contains_key(f.label) {
            err(
                at.key(f.label),
                format!(
                    "missing factor {} ({}): the screening needs all nine of seed 001 Table 5",
                    f.label, f.description
                ),
            );
        }
    }
    (sets, errors)
}

/// The pull-off rig's set-up of `rig` with the topology's `junction` and `stalk` bond sets:
/// the default rig's geometry (seed 001 Table 1) and the section's pull conditions.
pub fn rig_setup(rig: &PullOffRigSection, junction: &BondSet, stalk: &BondSet) -> PullOff {
    PullOff {
        stalk_spheres: rig.stalk_spheres,
        pull_speed_m_s: rig.pull_speed_m_s,
        pull_angle_deg: rig.pull_angle_deg,
        junction: spec(TAG_JUNCTION, junction),
        stalk: spec(TAG_STALK, stalk),
        ..PullOff::default()
    }
}

/// The core's bond set of a topology bond set.
fn spec(tag: u16, b: &BondSet) -> BondSetSpec {
    BondSetSpec {
        tag,
        normal_stiffness_n_m3: b.kn_n_m3,
        tangential_stiffness_n_m3: b.kt_n_m3,
        normal_strength_pa: b.sigma_c_pa,
        tangential_strength_pa: b.tau_c_pa,
        radius_m: b.radius_m,
    }
}

/// Reads a file a study names.
pub type ReadFile<'a> = &'a dyn Fn(&Path) -> std::io::Result<String>;

/// The topology at `path`, read with `read` and checked.
pub fn read_topology(path: &Path, read: ReadFile<'_>) -> Result<Topology, String> {
    let text =
        read(path).map_err(|e| format!("cannot read the topology {}: {e}", path.display()))?;
    let t = Topology::from_toml(&text).map_err(|e| e.to_string())?;
    t.check().map_err(|e| e.to_string())?;
    Ok(t)
}
