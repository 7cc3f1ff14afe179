//! The run settings of a pod world: run modes (`[plan.modes.<name>]`: pods and spheres
//! per pod) and simulation settings (`[plan.simulation]`: time step, grid, gravity,
//! placement seed, wall material, the repose rig's cylinder and timeline).

use serde::{Deserialize, Serialize};

/// `[plan.modes.<name>]`: problem size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mode {
    /// Pods generated per repose run.
    pub pods: u32,
    /// Spheres filling each pod shape.
    pub spheres_per_pod: u32,
}

/// `[plan.simulation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Simulation {
    /// Time step as a fraction of the Rayleigh time T_R = πR√(ρ/G)/(0.1631ν + 0.8766)
    /// (DESIGN §2; seed 000 §2.7 uses 20 %).
    pub dt_rayleigh_fraction: f64,
    /// Broad-phase cell size in smallest sphere radii (seed 000 §2.7: 3R).
    pub grid_cell_radii: f64,
    /// Gravitational acceleration, m/s².
    pub gravity_m_s2: f64,
    /// Seed of the pseudo-random pod placement and orientation.
    pub random_seed: u64,
    /// Material of the cylinder, floor and plates (a `[materials]` key; seed 000 §2.4:
    /// 65Mn steel).
    pub wall_material: String,
    /// The repose (cylinder-lifting) experiment.
    pub repose: ReposeSettings,
}

/// The repose rig's lifting-speed condition, m/s: a measurement's value replaces
/// [`ReposeSettings::lift_speed_m_s`].
pub const LIFT_SPEED: &str = "lift_speed_m_s";
/// The repose rig's cylinder-diameter condition, mm: a measurement's value replaces
/// [`ReposeSettings::cylinder_diameter_mm`], so it is the full-scale diameter and a mode with
/// fewer pods scales it as it scales the study's own. With the pod count fixed, the
/// diameter sets the height of the column that collapses when the cylinder is lifted.
pub const CYLINDER_DIAMETER: &str = "cylinder_diameter_mm";

/// `[plan.simulation.repose]`: the cylinder-lifting test (seed 000 §2.7).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReposeSettings {
    /// Inner diameter of the cylinder, mm.
    pub cylinder_diameter_mm: f64,
    /// Height of the cylinder, mm.
    pub cylinder_height_mm: f64,
    /// Time over which the pods are generated, s.
    pub fill_time_s: f64,
    /// Speed of the generated pods, m/s.
    pub fill_speed_m_s: f64,
    /// Time at which the cylinder starts to rise, s.
    pub lift_start_s: f64,
    /// Cylinder lifting speed, m/s.
    pub lift_speed_m_s: f64,
    /// Time the pile is left to settle after the cylinder has cleared it, s.
    pub settle_after_lift_s: f64,
}
