//! The poured bulk-density rig: pod spheres of the bench bed (radius 4 mm) fall from a column
//! a drop height above the floor of a steel measuring cylinder of radius 30 mm and settle
//! (`arachis_core::scenario::bulk_density`). The response is the bulk density of the settled
//! bed, kg/m³, in a slab two sphere diameters above the floor and well below the free
//! surface. The condition that moves it is the drop height, mm, from the floor to the
//! column's lowest sphere centres.
//!
//! What this rig adds to a diagnosis: the static packing, which friction, rolling resistance
//! and cohesion all loosen while the hopper's rate and the drum's angle answer to the same
//! effects in other proportions. The drop height moves the effects little and alike.
//! Measured on smooth spheres (μs 0.3, μr 0.02; 2026-11-27, two seeds each), the change of
//! the density at 150 / 600 mm: μs +0.04: −5 / −4 kg/m³; cohesion 5e4 J/m³: −9 / −10;
//! EPSD rolling 0.05: −4 / −3; viscoelastic 1e-5 s: 0 / −2. Seeds scatter by an SD of
//! 2.8 kg/m³ around about 320.
//!
//! Parameters: those of every rig of pod spheres in bulk ([`super::sphere_bulk`]). Replicate
//! r inserts from seed [`BASE_SEED`] + r. Fixed point: the same request gives the same bits.

use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::TIMESTEP_S;
use arachis_core::scenario::bulk_density::{
    slab_bulk_density_kg_m3, BulkDensity, MAX_DROP_HEIGHT_UM, MIN_DROP_HEIGHT_UM, SLAB_BOTTOM_MM,
    SLAB_TOP_MM,
};
use serde_json::json;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
pub use super::sphere_bulk::PARTICLES;
use super::sphere_bulk::{Declared, Values, PARAMETERS, UM_PER_MM};
use crate::arena::OwnedStorage;
use crate::calibration::{Responses, Rig, RigError, RunRequest};
use crate::limits::Limits;

/// The rig's name in study files.
pub const NAME: &str = "bulk_density";
/// The bulk density response, kg/m³.
pub const BULK_DENSITY: &str = "bulk_density";
/// The drop-height condition, mm.
pub const DROP_HEIGHT: &str = "drop_height_mm";
/// Spheres poured unless a measurement says otherwise: a bed about 115 mm deep, the slab's
/// top 50 mm below its surface.
pub const DEFAULT_PARTICLES: u32 = 700;
/// Seed of replicate 0's insertion.
pub const BASE_SEED: u64 = 0x5EED_B01C;
/// Drop heights a diagnosis may propose, mm: from just above the bed to a fall of 0.6 m.
pub const DROP_HEIGHT_SEARCH_MM: (f64, f64) = (150.0, 600.0);

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: NAME,
    about: "pod spheres poured from a drop height into a measuring cylinder (bulk density)",
    world: WorldKind::Fixed,
    random: true,
    quantities: &[Quantity {
        name: BULK_DENSITY,
        unit: "kg/m^3",
        label: "bulk density, kg/m³",
    }],
    conditions: &[
        ConditionKey::new(DROP_HEIGHT, "drop height, mm", Limits::Positive).within(
            (
                MIN_DROP_HEIGHT_UM as f64 / UM_PER_MM,
                MAX_DROP_HEIGHT_UM as f64 / UM_PER_MM,
            ),
            DROP_HEIGHT_SEARCH_MM,
        ),
        ConditionKey::new(PARTICLES, "spheres poured", Limits::Positive),
    ],
    parameters: &PARAMETERS,
    build: |_, _| Ok(Box::new(BulkDensityRig)),
};

/// What the rig declares of its requests.
const DECLARED: Declared = Declared {
    kind: &KIND,
    condition: DROP_HEIGHT,
    condition_about: "the height of the falling column's lowest spheres above the floor, mm",
    default_particles: DEFAULT_PARTICLES,
    min_particles: BulkDensity::min_particles,
    max_particles: BulkDensity::max_particles,
    base_seed: BASE_SEED,
};

/// One run's set-up.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Setup {
    pour: BulkDensity,
    values: Values,
}

/// The poured bulk-density rig (module notes).
#[derive(Debug, Clone, Copy, Default)]
pub struct BulkDensityRig;

impl BulkDensityRig {
    /// The set-up of `request`; an unknown parameter or condition, or a value outside its
    /// limits, is refused.
    fn setup(request: &RunRequest<'_>) -> Result<Setup, RigError> {
        let read = DECLARED.read(request)?;
        Ok(Setup {
            pour: BulkDensity {
                particles: read.particles,
                seed: read.seed,
                drop_height_um: (read.condition * UM_PER_MM).round() as i64,
            },
            values: read.values,
        })
    }
}

impl Rig for BulkDensityRig {
    fn id(&self) -> String {
        format!("arachis-bulk-density-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        "Arachis poured bulk density (fixed-point core; pod spheres of radius 4 mm falling into \
         a steel cylinder of radius 30 mm)"
            .to_owned()
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        let s = Self::setup(request)?;
        let mut spec = json!({
            "rig": NAME,
            "particles": s.pour.particles,
            "seed": s.pour.seed,
            "drop_height_um": s.pour.drop_height_um,
            "dt_s": TIMESTEP_S,
            "run_time_s": s.pour.run_time_s(),
            "slab_mm": [SLAB_BOTTOM_MM, SLAB_TOP_MM],
        });
        s.values.specification(&mut spec);
        Ok(spec)
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        let s = Self::setup(request)?;
        let mut arenas =
            OwnedStorage::<Fx>::new(s.values.storage_lengths(s.pour.storage_lengths()));
        let mut world = s
            .pour
            .build(arenas.storage())
            .map_err(|e| DECLARED.failed(e))?;
        s.values.apply(&mut world).map_err(|e| DECLARED.failed(e))?;
        DECLARED.run_for(&mut world, s.pour.run_time_s())?;
        Ok(Responses::from([(
            BULK_DENSITY.to_owned(),
            slab_bulk_density_kg_m3(&world),
        )]))
    }
}
