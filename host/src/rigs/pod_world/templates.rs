//! Pod templates: each harvest-time shape of the study (seed 000 §2.2) filled with the
//! mode's sphere count, in its principal frame, with the shape's own mass properties.
//!
//! The clump gets the mass and inertia of the pod shape itself (density × shape volume,
//! seed 000 §3.1.1), not of the union of its inscribed spheres: a coarse filling falls short
//! of the pod's volume, and the pile's weight should not depend on the smoothness chosen.
//!
//! Filling is deterministic but not free (a voxel grid per shape), so a [`TemplateCache`]
//! keeps the filled templates per (dimensions, sphere count, scan); share one across runs
//! (and rayon threads: it is `Sync`) through [`super::RunOptions::templates`].

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use super::error::ExperimentError;
use crate::shapes::{
    fill_with_spheres, filling_report, read_stl, FillOptions, FillTarget, MassProperties, PodKind,
    PodShape, Solid, Sphere,
};

/// Voxels along a pod's longest edge when filling it: 40 resolves 0.9 mm on a 34 mm pod,
/// finer than the smallest sphere of a 20-sphere filling.
pub const FILL_RESOLUTION: usize = 40;
/// Voxels along the longest edge when integrating the shape's mass properties.
pub const MASS_RESOLUTION: usize = 64;

/// One filled pod shape in its principal frame (centre of mass at the origin, principal
/// axes along x, y, z).
#[derive(Debug, Clone, PartialEq)]
pub struct PodTemplate {
    /// The shape.
    pub kind: PodKind,
    /// Spheres, principal frame, mm.
    pub spheres: Vec<Sphere>,
    /// The shape's mass properties (body frame of the shape).
    pub mass: MassProperties,
    /// Radius of the smallest sphere enclosing every sphere about the centre of mass, mm.
    pub bounding_radius_mm: f64,
    /// Radius of the smallest sphere of the filling, mm.
    pub min_sphere_radius_mm: f64,
}

/// What a set of templates depends on.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct TemplateKey {
    /// L, W, H (mm) and density (kg/m³) as raw f64 bits.
    pub dims_bits: [u64; 4],
    /// Spheres per pod.
    pub spheres_per_pod: u32,
    /// Scanned STL path per shape (resolved), if any.
    pub stl: Vec<(PodKind, PathBuf)>,
}

/// The three templates (normal, cocoon, single grain), indexed by `PodKind as usize`.
pub type TemplateSet = Arc<[PodTemplate; 3]>;

/// Filled templates by key; `Sync`, so rayon threads can share one.
#[derive(Debug, Default)]
pub struct TemplateCache {
    sets: Mutex<BTreeMap<TemplateKey, TemplateSet>>,
}

impl TemplateCache {
    /// An empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// The templates for `key`, filled on first use. Two threads asking at once may both
    /// fill; both results are identical (filling is deterministic), one is kept.
    pub fn get(&self, key: &TemplateKey) -> Result<TemplateSet, ExperimentError> {
        if let Some(set) = self.lock().get(key) {
            return Ok(set.clone());
        }
        let set = build_templates(key)?;
        Ok(self.lock().entry(key.clone()).or_insert(set).clone())
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, BTreeMap<TemplateKey, TemplateSet>> {
        // A panic elsewhere cannot leave the map half-written (insert is atomic for us).
        self.sets.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// Fills the three shapes of `key`.
pub fn build_templates(key: &TemplateKey) -> Result<TemplateSet, ExperimentError> {
    let [l, w, h, rho] = key.dims_bits.map(f64::from_bits);
    let one = |kind: PodKind| -> Result<PodTemplate, ExperimentError> {
        let scan = key.stl.iter().find(|(k, _)| *k == kind);
        let solid: Box<dyn Solid> = match scan {
            Some((_, path)) => Box::new(read_stl(path)?),
            None => Box::new(PodShape::new(kind, l, w, h)?),
        };
        template(kind, solid.as_ref(), key.spheres_per_pod as usize, rho)
    };
    Ok(Arc::new([
        one(PodKind::Normal)?,
        one(PodKind::Cocoon)?,
        one(PodKind::SingleGrain)?,
    ]))
}

fn template(
    kind: PodKind,
    solid: &dyn Solid,
    spheres: usize,
    density_kg_m3: f64,
) -> Result<PodTemplate, ExperimentError> {
    let options = FillOptions {
        resolution: FILL_RESOLUTION,
        target: FillTarget::SphereCount(spheres),
    };
    let filling = fill_with_spheres(solid, &options)?;
    let report = filling_report(solid, &filling, MASS_RESOLUTION, density_kg_m3)?;
    let principal = filling.in_principal_frame(&report.exact);
    let bounding_radius_mm = principal
        .spheres
        .iter()
        .map(|s| s.centre_mm.iter().map(|c| c * c).sum::<f64>().sqrt() + s.radius_mm)
        .fold(0.0, f64::max);
    let min_sphere_radius_mm = principal
        .spheres
        .iter()
        .map(|s| s.radius_mm)
        .fold(f64::INFINITY, f64::min);
    Ok(PodTemplate {
        kind,
        spheres: principal.spheres,
        mass: report.exact,
        bounding_radius_mm,
        min_sphere_radius_mm,
    })
}
