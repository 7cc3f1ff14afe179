//! What a pod bench run observed: the observable, the core's digest, and each rig's details
//! for reports ([`ObservationDetails`]), plus the options that change what a run writes,
//! never what it computes ([`RunOptions`]).

use std::path::PathBuf;
use std::sync::Arc;

use serde::Serialize;

use super::templates::TemplateCache;
use super::Experiment;
use crate::repose::{SimulatedRepose, Sphere as PileSphere};

/// Options that change what a run writes, never what it computes.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Write VTK frames of the run into this directory.
    pub vtk_dir: Option<PathBuf>,
    /// Filled pod templates shared across runs (a fresh cache per run when `None`).
    pub templates: Option<Arc<TemplateCache>>,
}

/// Per-rig details of an observation.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "rig", rename_all = "snake_case")]
pub enum ObservationDetails {
    /// Repose rig.
    Repose(ReposeDetails),
    /// Incline rig.
    InclineSlide(InclineDetails),
    /// Compression rig.
    Compression(CompressionDetails),
    /// Pod bulk-density rig.
    PodBulkDensity(BulkDensityDetails),
    /// Pod drum rig.
    PodDrum(DrumDetails),
    /// Pod hopper rig.
    PodHopper(HopperDetails),
}

/// The result of one virtual experiment.
#[derive(Debug, Clone, Serialize)]
pub struct Observation {
    /// The rig.
    pub experiment: Experiment,
    /// The observable's name (a study quantity, e.g. `repose_angle`).
    pub quantity: &'static str,
    /// Its value, in `unit`.
    pub value: f64,
    /// Its unit (`deg`, `-`, `mm`, `Pa`).
    pub unit: &'static str,
    /// The core's state digest at the end (16 hex digits): equal inputs give equal digests.
    pub digest: String,
    /// The ParaView series written, when VTK frames were asked for.
    pub vtk_series: Option<PathBuf>,
    /// Rig-specific numbers for reports.
    pub details: ObservationDetails,
}

/// The repose run's details, for reports.
#[derive(Debug, Clone, Serialize)]
pub struct ReposeDetails {
    /// Pods in the pile.
    pub pods: u32,
    /// Spheres in the pile.
    pub spheres: u32,
    /// Cylinder diameter used, mm (scaled for the mode, module notes).
    pub cylinder_diameter_mm: f64,
    /// Time step, s.
    pub dt_s: f64,
    /// When the fill had settled and the lift began, s.
    pub lift_start_s: f64,
    /// When the cylinder's lower edge cleared the pile, s.
    pub lift_end_s: f64,
    /// End of the run, s.
    pub end_s: f64,
    /// Steps run.
    pub steps: u64,
    /// Kinetic energy at the end, J.
    pub final_kinetic_energy_j: f64,
    /// Standard deviation of the per-view angles, degrees.
    pub view_sd_deg: f64,
    /// Pile height (mean over views), mm.
    pub pile_height_mm: f64,
    /// Pile base width (mean over views), mm.
    pub pile_width_mm: f64,
    /// Pixel size of the silhouettes, mm.
    pub mm_per_px: f64,
    /// Every usable view: azimuth and both flank angles.
    pub measurement: SimulatedRepose,
    /// Views whose flanks could not be fitted (azimuth, degrees, and why); they are left
    /// out of the mean (module notes, step 4).
    pub refused_views: Vec<(f64, String)>,
    /// Final sphere centres and radii, mm (for pictures).
    #[serde(skip)]
    pub pile: Vec<PileSphere>,
}

/// Details of the incline run.
#[derive(Debug, Clone, Serialize)]
pub struct InclineDetails {
    /// tan of the slide angle: the apparent static friction coefficient.
    pub static_friction: f64,
    /// Time step, s.
    pub dt_s: f64,
    /// Pod shape used (`sphere` for a sphere particle).
    pub pod_kind: &'static str,
}

/// Details of the compression run.
#[derive(Debug, Clone, Serialize)]
pub struct CompressionDetails {
    /// Force on the upper plate at the final travel, N.
    pub peak_force_n: f64,
    /// Compression δ (plate travel after first contact), mm.
    pub compression_mm: f64,
    /// Radius R of the Hertz law, mm.
    pub radius_mm: f64,
    /// Time step, s.
    pub dt_s: f64,
}

/// One pod of a settled bed: its mass and its spheres where they lie.
#[derive(Debug, Clone)]
pub struct BedPod {
    /// Mass, kg.
    pub mass_kg: f64,
    /// Its spheres: centres and radii, mm.
    pub spheres: Vec<PileSphere>,
}

/// Details of the pod bulk-density run (`crate::rigs::pod_bulk_density`).
#[derive(Debug, Clone, Serialize)]
pub struct BulkDensityDetails {
    /// Pods poured.
    pub pods: u32,
    /// Spheres over all pods.
    pub spheres: u32,
    /// Cylinder diameter used, mm (the repose rig's, scaled for the mode).
    pub cylinder_diameter_mm: f64,
    /// Drop height: floor to the lowest pods' centres of mass at release, mm.
    pub drop_height_mm: f64,
    /// Time step, s.
    pub dt_s: f64,
    /// End of the run, s.
    pub end_s: f64,
    /// Steps run.
    pub steps: u64,
    /// Kinetic energy at the end, J.
    pub final_kinetic_energy_j: f64,
    /// The bed's level (mean height of its top surface), mm.
    pub level_mm: f64,
    /// The measuring slab's bottom and top above the floor, mm.
    pub slab_mm: [f64; 2],
    /// Pod mass inside the slab, kg.
    pub slab_mass_kg: f64,
    /// The settled bed, pod by pod (for tests and pictures).
    #[serde(skip)]
    pub bed: Vec<BedPod>,
}

/// Details of the pod drum run (`crate::rigs::pod_drum`).
#[derive(Debug, Clone, Serialize)]
pub struct DrumDetails {
    /// Pods in the drum.
    pub pods: u32,
    /// Spheres over all pods.
    pub spheres: u32,
    /// Drum radius, mm.
    pub radius_mm: f64,
    /// Drum length between its end plates, mm.
    pub length_mm: f64,
    /// Drum speed, rpm.
    pub speed_rpm: f64,
    /// Froude number ω²R/g.
    pub froude: f64,
    /// Time step, s.
    pub dt_s: f64,
    /// The settled bed's angle before the drum turned, degrees.
    pub settled_angle_deg: f64,
    /// When the drum started to turn, s.
    pub spin_start_s: f64,
    /// End of the run, s.
    pub end_s: f64,
    /// Steps run.
    pub steps: u64,
    /// Each reading of the bed's angle, degrees.
    pub samples_deg: Vec<f64>,
    /// Their sample standard deviation, degrees.
    pub sample_sd_deg: f64,
}

/// Details of the pod hopper run (`crate::rigs::pod_hopper`).
#[derive(Debug, Clone, Serialize)]
pub struct HopperDetails {
    /// Pods in the silo.
    pub pods: u32,
    /// Spheres over all pods.
    pub spheres: u32,
    /// Silo diameter, mm.
    pub silo_diameter_mm: f64,
    /// Orifice diameter, mm.
    pub orifice_diameter_mm: f64,
    /// Depth of the catch floor below the orifice plate, mm.
    pub catch_depth_mm: f64,
    /// Mass of the fill, kg.
    pub fill_mass_kg: f64,
    /// Height of the highest pod's centre of mass in the settled fill, mm.
    pub fill_level_mm: f64,
    /// Time step, s.
    pub dt_s: f64,
    /// When the shutter opened, s.
    pub opened_s: f64,
    /// The flow window's start and end, s after the opening.
    pub window_s: [f64; 2],
    /// Whether the discharge stopped short of the window's upper fraction.
    pub jammed: bool,
    /// Fraction of the fill below the plate at the end.
    pub discharged_fraction: f64,
    /// End of the run, s.
    pub end_s: f64,
    /// Steps run.
    pub steps: u64,
}
