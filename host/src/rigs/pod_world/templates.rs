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

use arachis_core::units::LENGTH_M_TO_MM;

use super::error::ExperimentError;
use crate::shapes::{
    fill_with_spheres, filling_report, read_stl, FillOptions, FillTarget, MassProperties, PodKind,
    PodShape, Solid, Sphere, IDENTITY_AXES,
};

/// Voxels along a pod's longest edge when filling it: 40 resolves 0.9 mm on a 34 mm pod,
/// finer than the smallest sphere of a 20-sphere filling.
pub const FILL_RESOLUTION: usize = 40;
/// Voxels along the longest edge when integrating the shape's mass properties.
pub const MASS_RESOLUTION: usize = 64;

/// One filled pod shape (or one sphere) in its principal frame (centre of mass at the
/// origin, principal axes along x, y, z).
#[derive(Debug, Clone, PartialEq)]
pub struct PodTemplate {
    /// The pod shape; `None` for a sphere particle.
    pub kind: Option<PodKind>,
    /// Spheres, principal frame, mm.
    pub spheres: Vec<Sphere>,
    /// The shape's mass properties (body frame of the shape).
    pub mass: MassProperties,
    /// Radius of the smallest sphere enclosing every sphere about the centre of mass, mm.
    pub bounding_radius_mm: f64,
    /// Radius of the smallest sphere of the filling, mm.
    pub min_sphere_radius_mm: f64,
}

impl PodTemplate {
    /// One sphere of radius `radius_mm` and density `density_kg_m3`: m = ρ·(4/3)πR³,
    /// I = (2/5)mR² about every axis.
    pub fn sphere(radius_mm: f64, density_kg_m3: f64) -> Self {
        let volume_mm3 = 4.0 / 3.0 * std::f64::consts::PI * radius_mm.powi(3);
        let mass_kg = density_kg_m3 * volume_mm3 / LENGTH_M_TO_MM.powi(3);
        let r_m = radius_mm / LENGTH_M_TO_MM;
        let inertia = SOLID_SPHERE_INERTIA_FACTOR * mass_kg * r_m * r_m;
        PodTemplate {
            kind: None,
            spheres: vec![Sphere {
                centre_mm: [0.0; 3],
                radius_mm,
            }],
            mass: MassProperties {
                volume_mm3,
                mass_kg,
                centre_of_mass_mm: [0.0; 3],
                principal_inertia_kg_m2: [inertia; 3],
                principal_axes: IDENTITY_AXES,
            },
            bounding_radius_mm: radius_mm,
            min_sphere_radius_mm: radius_mm,
        }
    }

    /// `true` for a sphere particle (one sphere at the centre of mass).
    pub fn is_sphere(&self) -> bool {
        self.kind.is_none()
    }
}

/// (2/5): a solid sphere's moment of inertia over m·R².
const SOLID_SPHERE_INERTIA_FACTOR: f64 = 0.4;

/// What a set of templates depends on.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub enum TemplateKey {
    /// Pods of a shape mix.
    Pods {
        /// L, W, H (mm) and density (kg/m³) as raw f64 bits.
        dims_bits: [u64; 4],
        /// Spheres per pod.
        spheres_per_pod: u32,
        /// Scanned STL path per shape (resolved), if any.
        stl: Vec<(PodKind, PathBuf)>,
    },
    /// Spheres: each class's radius (mm) and the density (kg/m³) as raw f64 bits.
    Spheres {
        /// Radii, mm, as raw f64 bits.
        radii_bits: Vec<u64>,
        /// Density, kg/m³, as raw f64 bits.
        density_bits: u64,
    },
}

/// The templates of a study's particle classes: the three pod shapes indexed by
/// `PodKind as usize`, or one sphere per size class in file order.
pub type TemplateSet = Arc<Vec<PodTemplate>>;

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

/// Fills the three shapes of `key`, or makes its spheres.
pub fn build_templates(key: &TemplateKey) -> Result<TemplateSet, ExperimentError> {
    let (dims_bits, spheres_per_pod, stl) = match key {
        TemplateKey::Pods {
            dims_bits,
            spheres_per_pod,
            stl,
        } => (dims_bits, *spheres_per_pod, stl),
        TemplateKey::Spheres {
            radii_bits,
            density_bits,
        } => {
            let rho = f64::from_bits(*density_bits);
            return Ok(Arc::new(
                radii_bits
                    .iter()
                    .map(|&r| PodTemplate::sphere(f64::from_bits(r), rho))
                    .collect(),
            ));
        }
    };
    let [l, w, h, rho] = dims_bits.map(f64::from_bits);
    let one = |kind: PodKind| -> Result<PodTemplate, ExperimentError> {
        let scan = stl.iter().find(|(k, _)| *k == kind);
        let solid: Box<dyn Solid> = match scan {
            Some((_, path)) => Box::new(read_stl(path)?),
            None => Box::new(PodShape::new(kind, l, w, h)?),
        };
        template(kind, solid.as_ref(), spheres_per_pod as usize, rho)
    };
    PodKind::ALL
        .into_iter()
        .map(one)
        .collect::<Result<Vec<_>, _>>()
        .map(Arc::new)
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
        kind: Some(kind),
        spheres: principal.spheres,
        mass: report.exact,
        bounding_radius_mm,
        min_sphere_radius_mm,
    })
}
