//! The rotating-drum rig: pod spheres of the bench bed (radius 4 mm) fill a quarter of a steel
//! drum of radius 60 mm and length 40 mm, which spins about its horizontal axis with its end
//! plates (`arachis_core::scenario::drum`). The response is the dynamic angle of repose,
//! degrees: the mean of [`SAMPLES`] readings of the bed's angle ([`bed_angle_deg`]) while the
//! drum turns through [`MEASURE_TURN_RAD`], after it has turned through [`SPIN_UP_TURN_RAD`]
//! to reach its steady flow. The condition that moves it is the drum's speed, rpm.
//!
//! Why this rig diagnoses: the speed sets how fast the surface layer must flow. Rolling
//! resistance and friction hold the bed up at any speed, the more so the slower it turns
//! (the bed creeps as a block and avalanches); viscous damping and the drum's own shear grow
//! with speed; cohesion holds the surface up at slow speeds most. So the angle against speed
//! separates effects that one pile cannot.
//!
//! Parameters: those of every rig of pod spheres in bulk ([`super::sphere_bulk`]). Replicate r
//! inserts from seed [`BASE_SEED`] + r. Fixed point: the same request gives the same bits.

use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::TIMESTEP_S;
use arachis_core::scenario::drum::{bed_angle_deg, Drum};
use serde_json::json;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
pub use super::sphere_bulk::PARTICLES;
use super::sphere_bulk::{Declared, Values, PARAMETERS};
use crate::arena::OwnedStorage;
use crate::calibration::{Responses, Rig, RigError, RunRequest};
use crate::limits::Limits;

/// The rig's name in study files.
pub const NAME: &str = "drum";
/// The dynamic angle of repose response, degrees.
pub const DYNAMIC_ANGLE: &str = "dynamic_angle";
/// The drum-speed condition, rpm.
pub const ROTATION_SPEED: &str = "rotation_speed_rpm";
/// Spheres in the drum unless a measurement says otherwise: about a quarter of its volume.
pub const DEFAULT_PARTICLES: u32 = 250;
/// Seed of replicate 0's insertion.
pub const BASE_SEED: u64 = 0x5EED_D7A3;
/// Time from insertion to the start of rotation, s: the highest sphere falls 76 mm from rest
/// in 0.12 s, and the bed comes to rest in the rest.
pub const SETTLE_TIME_S: f64 = 0.30;
/// Turn of the drum before the first reading, rad (86°): the bed is lifted as a block until
/// its surface passes its largest angle of stability (the pods of DESIGN §8 still turn
/// rigidly at 57°), then flows.
pub const SPIN_UP_TURN_RAD: f64 = 1.5;
/// Turn of the drum over which the readings are taken, rad.
pub const MEASURE_TURN_RAD: f64 = 1.5;
/// Readings of the bed's angle, evenly spaced over [`MEASURE_TURN_RAD`].
pub const SAMPLES: u32 = 15;
/// Slowest and fastest drum speeds the rig simulates, rpm: below, a run takes minutes; above,
/// the bed approaches cataracting (Froude number ω²R/g reaches 0.1 at 38 rpm).
const SPEED_RANGE_RPM: (f64, f64) = (2.0, 60.0);
/// Speeds a diagnosis may propose, rpm.
const SPEED_SEARCH_RPM: (f64, f64) = (3.0, 40.0);
/// Radians per second in one rpm.
const RAD_S_PER_RPM: f64 = std::f64::consts::TAU / 60.0;

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: NAME,
    about: "pod spheres in a drum rotating about a horizontal axis (dynamic angle of repose)",
    world: WorldKind::Fixed,
    random: true,
    quantities: &[Quantity {
        name: DYNAMIC_ANGLE,
        unit: "deg",
        label: "dynamic angle of repose, deg",
    }],
    conditions: &[
        ConditionKey::new(ROTATION_SPEED, "drum speed, rpm", Limits::Positive)
            .within(SPEED_RANGE_RPM, SPEED_SEARCH_RPM),
        ConditionKey::new(PARTICLES, "spheres in the drum", Limits::Positive),
    ],
    parameters: &PARAMETERS,
    build: |_, _| Ok(Box::new(DrumRig)),
};

/// What the rig declares of its requests.
const DECLARED: Declared = Declared {
    kind: &KIND,
    condition: ROTATION_SPEED,
    condition_about: "the drum's speed, rpm",
    default_particles: DEFAULT_PARTICLES,
    min_particles: || 1,
    max_particles: Drum::max_particles,
    base_seed: BASE_SEED,
};

/// One run's set-up.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Setup {
    drum: Drum,
    speed_rpm: f64,
    values: Values,
}

/// The rotating-drum rig (module notes).
#[derive(Debug, Clone, Copy, Default)]
pub struct DrumRig;

impl DrumRig {
    /// The set-up of `request`; an unknown parameter or condition, or a value outside its
    /// limits, is refused.
    fn setup(request: &RunRequest<'_>) -> Result<Setup, RigError> {
        let read = DECLARED.read(request)?;
        Ok(Setup {
            drum: Drum {
                particles: read.particles,
                seed: read.seed,
            },
            speed_rpm: read.condition,
            values: read.values,
        })
    }
}

impl Rig for DrumRig {
    fn id(&self) -> String {
        format!("arachis-drum-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        "Arachis rotating drum (fixed-point core; pod spheres of radius 4 mm in a steel drum of \
         radius 60 mm and length 40 mm, end plates turning with it)"
            .to_owned()
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        let s = Self::setup(request)?;
        let mut spec = json!({
            "rig": NAME,
            "particles": s.drum.particles,
            "seed": s.drum.seed,
            "rotation_speed_rpm": s.speed_rpm,
            "dt_s": TIMESTEP_S,
            "settle_time_s": SETTLE_TIME_S,
            "turns_rad": [SPIN_UP_TURN_RAD, MEASURE_TURN_RAD],
            "samples": SAMPLES,
        });
        s.values.specification(&mut spec);
        Ok(spec)
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        let s = Self::setup(request)?;
        let mut arenas =
            OwnedStorage::<Fx>::new(s.values.storage_lengths(s.drum.storage_lengths()));
        let mut world = s
            .drum
            .build(arenas.storage())
            .map_err(|e| DECLARED.failed(e))?;
        s.values.apply(&mut world).map_err(|e| DECLARED.failed(e))?;
        let omega = s.speed_rpm * RAD_S_PER_RPM;
        DECLARED.run_for(&mut world, SETTLE_TIME_S)?;
        Drum::spin(&mut world, omega).map_err(|e| DECLARED.failed(e))?;
        DECLARED.run_for(&mut world, SPIN_UP_TURN_RAD / omega)?;
        let mut sum = 0.0;
        for _ in 0..SAMPLES {
            DECLARED.run_for(&mut world, MEASURE_TURN_RAD / omega / f64::from(SAMPLES))?;
            sum += bed_angle_deg(&world, omega);
        }
        Ok(Responses::from([(
            DYNAMIC_ANGLE.to_owned(),
            sum / f64::from(SAMPLES),
        )]))
    }
}
