//! The hopper rig: pod spheres of the bench bed (radius 4 mm) settle in a flat-bottomed steel
//! silo of radius 40 mm and run out through a circular orifice in its floor
//! (`arachis_core::scenario::hopper`). The response is the mass flow rate, g/s: the mass that
//! crosses the orifice plate between [`WINDOW_START_S`] and [`WINDOW_END_S`] after the
//! shutter opens, over that time. The condition that moves it is the orifice diameter, mm.
//!
//! Why this rig diagnoses: by Beverloo's law, W = C·ρ_b·√g·(D − k·d)^(5/2), the orifice
//! diameter D enters through the empty annulus k·d that particles cannot use. Friction and
//! rolling resistance change C and k a little; cohesion makes the particles hold on to each
//! other and to the rim, which chokes small orifices far more than large ones. So the shape of
//! W against D tells cohesion from friction where one diameter cannot.
//!
//! Parameters: those of every rig of pod spheres in bulk ([`super::sphere_bulk`]): the bench
//! bed's six pair coefficients and three optional pod–pod effects. Replicate r inserts from
//! seed [`BASE_SEED`] + r. Fixed point: the same request gives the same bits.

use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::TIMESTEP_S;
use arachis_core::scenario::hopper::{
    discharged_mass_g, Hopper, MAX_ORIFICE_DIAMETER_UM, MIN_ORIFICE_DIAMETER_UM, SHUTTER_TRAVEL_S,
};
use serde_json::json;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
pub use super::sphere_bulk::PARTICLES;
use super::sphere_bulk::{Declared, Values, PARAMETERS, UM_PER_MM};
use crate::arena::OwnedStorage;
use crate::calibration::{Responses, Rig, RigError, RunRequest};
use crate::limits::Limits;

/// The rig's name in study files.
pub const NAME: &str = "hopper";
/// The mass flow rate response, g/s.
pub const MASS_FLOW_RATE: &str = "mass_flow_rate";
/// The orifice-diameter condition, mm.
pub const ORIFICE_DIAMETER: &str = "orifice_diameter_mm";
/// Spheres in the silo unless a measurement says otherwise: a fill about 2.5 orifice
/// diameters high at the largest orifice searched, so the flow is steady over the window.
pub const DEFAULT_PARTICLES: u32 = 1200;
/// Seed of replicate 0's insertion.
pub const BASE_SEED: u64 = 0x5EED_4099;
/// Time from insertion to opening, s: the highest sphere, launched down at 0.2 m/s, falls
/// the 0.24 m of the insertion region in 0.2 s, and the fill comes to rest in the rest.
pub const SETTLE_TIME_S: f64 = 0.30;
/// Start of the measuring window after opening, s: the shutter has reached the catch floor
/// ([`SHUTTER_TRAVEL_S`]) and the flow has started.
pub const WINDOW_START_S: f64 = 0.10;
/// End of the measuring window after opening, s.
pub const WINDOW_END_S: f64 = 0.30;

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: NAME,
    about: "pod spheres running out of a flat-bottomed silo through an orifice (mass flow rate)",
    world: WorldKind::Fixed,
    random: true,
    quantities: &[Quantity {
        name: MASS_FLOW_RATE,
        unit: "g/s",
        label: "mass flow rate, g/s",
    }],
    conditions: &[
        ConditionKey::new(ORIFICE_DIAMETER, "orifice diameter, mm", Limits::Positive).within(
            (
                MIN_ORIFICE_DIAMETER_UM as f64 / UM_PER_MM,
                MAX_ORIFICE_DIAMETER_UM as f64 / UM_PER_MM,
            ),
            (28.0, 60.0),
        ),
        ConditionKey::new(PARTICLES, "spheres in the silo", Limits::Positive),
    ],
    parameters: &PARAMETERS,
    build: |_, _| Ok(Box::new(HopperRig)),
};

/// What the rig declares of its requests.
const DECLARED: Declared = Declared {
    kind: &KIND,
    condition: ORIFICE_DIAMETER,
    condition_about: "the orifice's diameter, mm",
    default_particles: DEFAULT_PARTICLES,
    min_particles: || 1,
    max_particles: Hopper::max_particles,
    base_seed: BASE_SEED,
};

/// One run's set-up.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Setup {
    hopper: Hopper,
    values: Values,
}

/// The hopper rig (module notes).
#[derive(Debug, Clone, Copy, Default)]
pub struct HopperRig;

impl HopperRig {
    /// The set-up of `request`; an unknown parameter or condition, or a value outside its
    /// limits, is refused.
    fn setup(request: &RunRequest<'_>) -> Result<Setup, RigError> {
        let read = DECLARED.read(request)?;
        Ok(Setup {
            hopper: Hopper {
                particles: read.particles,
                seed: read.seed,
                orifice_diameter_um: (read.condition * UM_PER_MM).round() as i64,
            },
            values: read.values,
        })
    }
}

impl Rig for HopperRig {
    fn id(&self) -> String {
        format!("arachis-hopper-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        "Arachis hopper (fixed-point core; pod spheres of radius 4 mm running out of a steel \
         silo of radius 40 mm through an orifice plate)"
            .to_owned()
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        let s = Self::setup(request)?;
        let mut spec = json!({
            "rig": NAME,
            "particles": s.hopper.particles,
            "seed": s.hopper.seed,
            "orifice_diameter_um": s.hopper.orifice_diameter_um,
            "dt_s": TIMESTEP_S,
            "settle_time_s": SETTLE_TIME_S,
            "window_s": [WINDOW_START_S, WINDOW_END_S],
        });
        s.values.specification(&mut spec);
        Ok(spec)
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        let s = Self::setup(request)?;
        let mut arenas =
            OwnedStorage::<Fx>::new(s.values.storage_lengths(s.hopper.storage_lengths()));
        let mut world = s
            .hopper
            .build(arenas.storage())
            .map_err(|e| DECLARED.failed(e))?;
        s.values.apply(&mut world).map_err(|e| DECLARED.failed(e))?;
        DECLARED.run_for(&mut world, SETTLE_TIME_S)?;
        Hopper::open(&mut world).map_err(|e| DECLARED.failed(e))?;
        DECLARED.run_for(&mut world, SHUTTER_TRAVEL_S)?;
        Hopper::catch(&mut world).map_err(|e| DECLARED.failed(e))?;
        DECLARED.run_for(&mut world, WINDOW_START_S - SHUTTER_TRAVEL_S)?;
        let before = discharged_mass_g(&world);
        DECLARED.run_for(&mut world, WINDOW_END_S - WINDOW_START_S)?;
        let after = discharged_mass_g(&world);
        Ok(Responses::from([(
            MASS_FLOW_RATE.to_owned(),
            (after - before) / (WINDOW_END_S - WINDOW_START_S),
        )]))
    }
}
