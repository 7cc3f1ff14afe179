//! The full specification of one pod bench run ([`RunSpec`]): the experiment and its
//! condition, every material and pair value after the run's parameter values are applied,
//! the pod geometry, the mode (pod and sphere counts) and the simulation settings.
//! Free-text notes (`source`) are left out, so editing a citation does not invalidate the
//! run cache. Its canonical JSON names the run ([`crate::calibration::spec_hash`]);
//! [`SPEC_FORMAT_VERSION`] is part of it, so a change to what a spec means can retire old
//! cache entries.

use std::collections::BTreeMap;

use arachis_core::contact::{Conventions, FrictionConvention, RollingConvention};
use serde::Serialize;

use super::experiment::Experiment;
use super::parameters::{effect_for, for_property, lookup_any, Owner};
use super::sections::{Particles, ShapeMix, SizeClass};
use super::settings::{Mode, Simulation, CYLINDER_DIAMETER, LIFT_SPEED};
use super::PodWorld;
use crate::calibration::spec_hash::{canonical_json, fnv1a_64, SpecHash};

/// Version of the [`RunSpec`] layout; bump it when the meaning of a field changes.
pub const SPEC_FORMAT_VERSION: u32 = 1;

/// Material values of one run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunMaterial {
    /// Density, kg/m³.
    pub density_kg_m3: f64,
    /// Poisson ratio.
    pub poisson: f64,
    /// Shear modulus, Pa.
    pub shear_modulus_pa: f64,
}

/// Pair values of one run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunPair {
    /// Coefficient of restitution.
    pub restitution: f64,
    /// Coefficient of static friction.
    pub static_friction: f64,
    /// Coefficient of rolling friction.
    pub rolling_friction: f64,
    /// The pair's conventions. Written only when one is not EDEM's, so the spec of a run in
    /// EDEM's conventions, and so its hash and cache entry, is the same as before conventions
    /// existed.
    #[serde(flatten, serialize_with = "conventions_if_not_edem")]
    pub conventions: Conventions,
    /// Optional effects (`sections::PAIR_EFFECTS`), each written only when on, so the spec
    /// of a run without them, and so its hash and cache entry, is the same as before they
    /// existed: SJKR cohesion energy density, J/m³, …
    #[serde(skip_serializing_if = "is_off")]
    pub cohesion_j_m3: f64,
    /// … EPSD rolling resistance μr, …
    #[serde(skip_serializing_if = "is_off")]
    pub epsd_rolling_friction: f64,
    /// … viscoelastic relaxation time, s.
    #[serde(skip_serializing_if = "is_off")]
    pub viscoelastic_time_s: f64,
}

/// serde helper: an effect at 0 is off and not written.
fn is_off(x: &f64) -> bool {
    *x == 0.0
}

/// `rolling_convention` and `friction_convention` by name, each only when not EDEM's.
fn conventions_if_not_edem<S: serde::Serializer>(c: &Conventions, s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let mut map = s.serialize_map(None)?;
    if c.rolling != RollingConvention::Edem {
        map.serialize_entry("rolling_convention", c.rolling.name())?;
    }
    if c.friction != FrictionConvention::Edem {
        map.serialize_entry("friction_convention", c.friction.name())?;
    }
    map.end()
}

/// Pod geometry of one run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunPods {
    /// Material name.
    pub material: String,
    /// Length, mm.
    pub length_mm: f64,
    /// Width, mm.
    pub width_mm: f64,
    /// Thickness, mm.
    pub thickness_mm: f64,
    /// Shape fractions.
    pub shape_mix: ShapeMix,
    /// Scanned shapes by shape: the path as written in the study and the FNV-1a 64 of the
    /// file's bytes, so a re-scanned pod under the same name is a different run.
    pub stl: BTreeMap<String, RunStl>,
}

/// Sphere particles of one run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSpheres {
    /// Material name.
    pub material: String,
    /// Size classes (radius, mm; fraction by number).
    pub sizes: Vec<SizeClass>,
}

impl RunSpec {
    /// The particles' material name (`None` when the spec has no particles).
    pub fn particle_material(&self) -> Option<&str> {
        match (&self.pods, &self.spheres) {
            (Some(p), _) => Some(&p.material),
            (None, Some(s)) => Some(&s.material),
            (None, None) => None,
        }
    }
}

/// A scanned shape in a run spec.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunStl {
    /// The path as written in the study.
    pub path: String,
    /// FNV-1a 64 of the file's content, 16 hex digits.
    pub content_fnv1a: String,
}

/// Everything that determines one simulation run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSpec {
    /// [`SPEC_FORMAT_VERSION`].
    pub spec_format: u32,
    /// The experiment.
    pub experiment: Experiment,
    /// The measurement condition (keys unit-suffixed).
    pub condition: BTreeMap<String, f64>,
    /// Material values after the run's parameter values.
    pub materials: BTreeMap<String, RunMaterial>,
    /// Pair values after the run's parameter values.
    pub pairs: BTreeMap<String, RunPair>,
    /// Pod geometry (a pod study).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pods: Option<RunPods>,
    /// Sphere sizes (a sphere study).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spheres: Option<RunSpheres>,
    /// Mode name and sizes.
    pub mode: Mode,
    /// Simulation settings, with condition overrides applied.
    pub simulation: Simulation,
}

impl RunSpec {
    /// The canonical JSON text the hash is taken over.
    pub fn canonical_json(&self) -> String {
        canonical_json(&serde_json::to_value(self).expect("a run spec serialises"))
    }

    /// FNV-1a 64 of [`RunSpec::canonical_json`].
    pub fn spec_hash(&self) -> SpecHash {
        SpecHash(fnv1a_64(self.canonical_json().as_bytes()))
    }
}

impl PodWorld<'_> {
    /// The full specification of one run of `experiment` at `condition`, with the
    /// parameters in `values` (registry names → values) and every other parameter at its
    /// held value ([`Study::held_value`]), in mode `mode`.
    pub fn run_spec(
        &self,
        experiment: Experiment,
        condition: &BTreeMap<String, f64>,
        values: &BTreeMap<String, f64>,
        mode: &str,
    ) -> Result<RunSpec, String> {
        let mode_settings = self
            .modes
            .get(mode)
            .ok_or_else(|| format!("no mode '{mode}' in the study"))?
            .clone();
        for name in values.keys() {
            if lookup_any(name).is_none() {
                return Err(format!("unknown parameter '{name}'"));
            }
        }
        let mut materials: BTreeMap<String, RunMaterial> = self
            .materials
            .iter()
            .map(|(n, m)| {
                let run = RunMaterial {
                    density_kg_m3: m.density_kg_m3,
                    poisson: m.poisson,
                    shear_modulus_pa: m.shear_modulus_pa,
                };
                (n.clone(), run)
            })
            .collect();
        let mut pairs = BTreeMap::new();
        for name in self.pairs.keys() {
            let get = |property: &str| -> Result<f64, String> {
                let spec =
                    for_property(name, property).filter(|s| matches!(s.sets.owner, Owner::Pair(_)));
                match spec {
                    Some(s) => values
                        .get(s.name)
                        .copied()
                        .or_else(|| self.held_value(s))
                        .ok_or_else(|| format!("{}: no value", s.name)),
                    None => self.pairs[name]
                        .property(property)
                        .ok_or_else(|| format!("pair {name}: no {property}")),
                }
            };
            // An effect: the run's value, else the pair's, else off.
            let effect = |property: &str| -> f64 {
                effect_for(name, property)
                    .and_then(|s| values.get(s.name).copied())
                    .or_else(|| self.pairs[name].property(property))
                    .unwrap_or(0.0)
            };
            pairs.insert(
                name.clone(),
                RunPair {
                    restitution: get("restitution")?,
                    static_friction: get("static_friction")?,
                    rolling_friction: get("rolling_friction")?,
                    conventions: self.pairs[name].conventions(),
                    cohesion_j_m3: effect("cohesion_j_m3"),
                    epsd_rolling_friction: effect("epsd_rolling_friction"),
                    viscoelastic_time_s: effect("viscoelastic_time_s"),
                },
            );
        }
        for (name, value) in values {
            let spec = lookup_any(name).expect("checked above");
            if let Owner::Material(m) = spec.sets.owner {
                let mat = materials
                    .get_mut(m)
                    .ok_or_else(|| format!("{name}: the study has no material '{m}'"))?;
                match spec.sets.property {
                    "poisson" => mat.poisson = *value,
                    "shear_modulus_pa" => mat.shear_modulus_pa = *value,
                    other => return Err(format!("{name}: unsupported material property {other}")),
                }
            }
        }
        let mut simulation = self.simulation.clone();
        if let Some(speed) = condition.get(LIFT_SPEED) {
            simulation.repose.lift_speed_m_s = *speed;
        }
        if let Some(diameter) = condition.get(CYLINDER_DIAMETER) {
            simulation.repose.cylinder_diameter_mm = *diameter;
        }
        let (pods, spheres) = match self.particles {
            Particles::Pods(pods) => (
                Some(RunPods {
                    material: pods.material.clone(),
                    length_mm: pods.length_mm,
                    width_mm: pods.width_mm,
                    thickness_mm: pods.thickness_mm,
                    shape_mix: pods.shape_mix.clone(),
                    stl: self.run_stl()?,
                }),
                None,
            ),
            Particles::Spheres(spheres) => (
                None,
                Some(RunSpheres {
                    material: spheres.material.clone(),
                    sizes: spheres.classes(),
                }),
            ),
        };
        Ok(RunSpec {
            spec_format: SPEC_FORMAT_VERSION,
            experiment,
            condition: condition.clone(),
            materials,
            pairs,
            pods,
            spheres,
            mode: mode_settings,
            simulation,
        })
    }
}

impl PodWorld<'_> {
    /// Each scanned shape's path and content hash (the files were checked at load; one
    /// that has since vanished is an error here).
    fn run_stl(&self) -> Result<BTreeMap<String, RunStl>, String> {
        let written = match self.particles {
            Particles::Pods(pods) => pods.stl.entries(),
            Particles::Spheres(_) => Vec::new(),
        };
        self.stl_paths()
            .into_iter()
            .zip(written)
            .map(|((shape, resolved), (_, path))| {
                let bytes = std::fs::read(&resolved)
                    .map_err(|e| format!("cannot read {}: {e}", resolved.display()))?;
                let stl = RunStl {
                    path: path.to_owned(),
                    content_fnv1a: SpecHash(fnv1a_64(&bytes)).to_string(),
                };
                Ok((shape.to_owned(), stl))
            })
            .collect()
    }
}
