//! Shared set-up of every rig: the study, the parameter values and the mode resolved into
//! core materials and pairs ([`RunInputs`]), owned core storage ([`Arena`]), pod clumps in
//! the study's shape mix, and the stepping helpers the rigs share.
//!
//! Materials: the study gives G and ν (seed 000 §3.1); the core takes E = 2G(1 + ν)
//! (seed 000 eq. (12) solved for E). A pod ν ≥ 0.5 (seed 000 Table 3 screens 0.586) is
//! passed with the core's explicit [`PoissonRange::ContactModel`] opt-in, only when the
//! study's range says `poisson_above_half = true` (checked in [`super::values`]).

use std::collections::BTreeMap;

use arachis_core::body::MassProperties as CoreMass;
use arachis_core::effects::EffectSpec;
use arachis_core::prelude::*;
use arachis_core::scenario::SplitMix64;

use super::error::ExperimentError;
use super::run_spec::RunSpec;
use super::settings::{Mode, Simulation};
use super::templates::{PodTemplate, TemplateCache, TemplateKey, TemplateSet};
use super::values::{check_values, ModeName, ParameterValues};
use super::{Experiment, PodWorld};
use crate::arena::OwnedStorage;
use crate::shapes::{apportion, PodKind, ShapeMix};

/// m per mm.
pub const M_PER_MM: f64 = 1e-3;
/// Poisson ratio at and above which the isotropic-solid check is waived (with the opt-in).
pub const ISOTROPIC_POISSON_LIMIT: f64 = 0.5;

/// Everything a rig needs, resolved from the study, the values and the mode.
#[derive(Debug, Clone)]
pub struct RunInputs {
    /// The full run specification (its hash names the run, [`RunSpec::spec_hash`]).
    pub spec: RunSpec,
    /// Pod material.
    pub pod: MaterialSpec,
    /// Whether the pod material needs the ν ∈ (−1, 1) opt-in.
    pub pod_poisson: PoissonRange,
    /// Wall (rig) material.
    pub wall: MaterialSpec,
    /// Pod–pod contact (seed 000 x3–x5).
    pub pod_pod: PairSpec,
    /// Pod–wall contact (seed 000 x6–x8).
    pub pod_wall: PairSpec,
    /// Optional effects of the pod–pod contact (all off unless the study or the run's
    /// values switch one on).
    pub pod_pod_effects: EffectSpec,
    /// Optional effects of the pod–wall contact.
    pub pod_wall_effects: EffectSpec,
    /// The mode's pods and spheres per pod.
    pub mode: Mode,
    /// The mode's name.
    pub mode_name: ModeName,
    /// Pods in the full mode (for geometric scaling of the quick rig), if the study has it.
    pub full_pods: Option<u32>,
    /// Simulation settings (time-step fraction, gravity, repose rig).
    pub simulation: Simulation,
    /// Fraction by number of each particle class ([`RunInputs::template`]).
    pub fractions: Vec<f64>,
    /// Filled pod templates, or the spheres of each size class.
    pub templates: TemplateSet,
}

fn study_error(experiment: Experiment, reason: impl Into<String>) -> ExperimentError {
    ExperimentError::Study {
        experiment: experiment.name(),
        reason: reason.into(),
    }
}

fn material(
    spec: &RunSpec,
    name: &str,
    experiment: Experiment,
) -> Result<MaterialSpec, ExperimentError> {
    let m = spec
        .materials
        .get(name)
        .ok_or_else(|| study_error(experiment, format!("no material '{name}'")))?;
    Ok(MaterialSpec {
        // seed 000 eq. (12): G = E/(2(1 + ν)).
        youngs_modulus_pa: 2.0 * m.shear_modulus_pa * (1.0 + m.poisson),
        poisson: m.poisson,
        density_kg_m3: m.density_kg_m3,
    })
}

/// The pair `a`-`b` of `spec`: its contact law and its optional effects.
fn pair(
    spec: &RunSpec,
    a: &str,
    b: &str,
    experiment: Experiment,
) -> Result<(PairSpec, EffectSpec), ExperimentError> {
    let p = spec
        .pairs
        .get(&format!("{a}-{b}"))
        .or_else(|| spec.pairs.get(&format!("{b}-{a}")))
        .ok_or_else(|| study_error(experiment, format!("no pair '{a}-{b}'")))?;
    let effects = EffectSpec {
        cohesion_energy_density_j_m3: p.cohesion_j_m3,
        epsd_rolling_friction: p.epsd_rolling_friction,
        viscoelastic_time_s: p.viscoelastic_time_s,
        ..EffectSpec::default()
    };
    Ok((
        PairSpec::hertz_mindlin(p.restitution, p.static_friction, p.rolling_friction)
            .with_conventions(p.conventions),
        effects,
    ))
}

impl RunInputs {
    /// Resolves `values` (checked against the registry and limits) over `world` at
    /// `condition` in `mode`.
    pub fn resolve(
        world: &PodWorld<'_>,
        experiment: Experiment,
        condition: &BTreeMap<String, f64>,
        values: &ParameterValues,
        mode: ModeName,
        cache: &TemplateCache,
    ) -> Result<Self, ExperimentError> {
        check_values(world, values)?;
        if !world.modes.contains_key(mode.as_str()) {
            return Err(ExperimentError::MissingMode {
                mode: mode.as_str().to_owned(),
            });
        }
        let spec = world
            .run_spec(experiment, condition, values, mode.as_str())
            .map_err(|reason| study_error(experiment, reason))?;
        let no_particles = || study_error(experiment, "the study has no particles");
        let pod_name = spec
            .particle_material()
            .ok_or_else(no_particles)?
            .to_owned();
        let wall_name = spec.simulation.wall_material.clone();
        let pod = material(&spec, &pod_name, experiment)?;
        let pod_poisson = if pod.poisson >= ISOTROPIC_POISSON_LIMIT {
            PoissonRange::ContactModel
        } else {
            PoissonRange::Isotropic
        };
        let wall = material(&spec, &wall_name, experiment)?;
        let (pod_pod, pod_pod_effects) = pair(&spec, &pod_name, &pod_name, experiment)?;
        let (pod_wall, pod_wall_effects) = pair(&spec, &pod_name, &wall_name, experiment)?;
        let (key, fractions) = match (&spec.pods, &spec.spheres) {
            (Some(pods), _) => {
                let m = &pods.shape_mix;
                let mix = ShapeMix::new([m.normal, m.cocoon, m.single_grain])?;
                let key = TemplateKey::Pods {
                    dims_bits: [
                        pods.length_mm,
                        pods.width_mm,
                        pods.thickness_mm,
                        pod.density_kg_m3,
                    ]
                    .map(f64::to_bits),
                    spheres_per_pod: spec.mode.spheres_per_pod,
                    stl: world
                        .stl_paths()
                        .into_iter()
                        .filter_map(|(k, p)| PodKind::from_key(k).map(|k| (k, p)))
                        .collect(),
                };
                (key, PodKind::ALL.map(|k| mix.fraction(k)).to_vec())
            }
            (None, Some(spheres)) => {
                let key = TemplateKey::Spheres {
                    radii_bits: spheres
                        .sizes
                        .iter()
                        .map(|c| c.radius_mm.to_bits())
                        .collect(),
                    density_bits: pod.density_kg_m3.to_bits(),
                };
                (key, spheres.sizes.iter().map(|c| c.fraction).collect())
            }
            (None, None) => return Err(no_particles()),
        };
        let templates = cache.get(&key)?;
        Ok(RunInputs {
            mode: spec.mode.clone(),
            mode_name: mode,
            full_pods: world.modes.get("full").map(|m| m.pods),
            simulation: spec.simulation.clone(),
            spec,
            pod,
            pod_poisson,
            wall,
            pod_pod,
            pod_wall,
            pod_pod_effects,
            pod_wall_effects,
            fractions,
            templates,
        })
    }

    /// The template of particle class `class` (a pod shape, `PodKind as usize`, or a sphere
    /// size class).
    pub fn template(&self, class: usize) -> &PodTemplate {
        &self.templates[class]
    }

    /// Radius of the smallest sphere of any particle class, mm.
    pub fn min_sphere_radius_mm(&self) -> f64 {
        self.templates
            .iter()
            .map(|t| t.min_sphere_radius_mm)
            .fold(f64::INFINITY, f64::min)
    }

    /// Bounding radius of the largest particle class, mm: half the lattice cell of the bulk
    /// rigs' layouts.
    pub fn max_bounding_radius_mm(&self) -> f64 {
        self.templates
            .iter()
            .map(|t| t.bounding_radius_mm)
            .fold(0.0, f64::max)
    }

    /// The most common particle class (the single particle of the one-pod rigs); the first
    /// of equals.
    pub fn typical_class(&self) -> usize {
        (0..self.fractions.len()).fold(0, |best, k| {
            if self.fractions[k] > self.fractions[best] {
                k
            } else {
                best
            }
        })
    }

    /// `n` particle classes in the study's proportions (largest remainders), shuffled by
    /// `rng` (Fisher–Yates), so every placement seed mixes them differently.
    pub fn shuffled_classes(&self, n: usize, rng: &mut SplitMix64) -> Vec<usize> {
        let counts = apportion(&self.fractions, n);
        let mut classes: Vec<usize> = counts
            .into_iter()
            .enumerate()
            .flat_map(|(k, c)| std::iter::repeat_n(k, c))
            .collect();
        for i in (1..classes.len()).rev() {
            let j = rng.below(i as u64 + 1) as usize;
            classes.swap(i, j);
        }
        classes
    }
}

/// Owned storage for one core world.
pub struct Arena(OwnedStorage<Fx>);

impl Arena {
    /// Room for `bodies` bodies made of `spheres` spheres in all, and for the contact state of
    /// `inputs`' pairs (an effect-history arena when a pair keeps one, as LIGGGHTS' `epsd2`
    /// rolling convention and the EPSD effect do).
    pub fn new(inputs: &RunInputs, bodies: usize, spheres: usize) -> Self {
        let lengths = StorageLengths::for_spheres(bodies.max(1), spheres.max(1))
            .with_effects_for(&[inputs.pod_pod, inputs.pod_wall]);
        let effects_kept =
            inputs.pod_pod_effects.needs_history() || inputs.pod_wall_effects.needs_history();
        let lengths = if effects_kept {
            lengths.with_effects()
        } else {
            lengths
        };
        Arena(OwnedStorage::new(lengths))
    }

    /// A world over this storage.
    pub fn world(&mut self, experiment: Experiment) -> Result<World<'_, Fx>, ExperimentError> {
        World::new(self.0.storage()).map_err(|reason| setup_error(experiment, reason))
    }
}

/// Wraps a core set-up error.
pub fn setup_error(experiment: Experiment, source: SetupError) -> ExperimentError {
    ExperimentError::Setup {
        experiment: experiment.name(),
        reason: source,
    }
}

/// The materials and pairs of a rig, added to a fresh world.
#[derive(Debug, Clone, Copy)]
pub struct RigMaterials {
    /// Pod material id.
    pub pod: MaterialId,
    /// Wall material id.
    pub wall: MaterialId,
}

/// Adds the pod and wall materials, both pairs and gravity (−z) to `w`.
pub fn add_materials(
    w: &mut World<'_, Fx>,
    inputs: &RunInputs,
    experiment: Experiment,
) -> Result<RigMaterials, ExperimentError> {
    // Each refusal names the study key its values came from.
    let at = |key: String| {
        move |reason| ExperimentError::SetupAt {
            experiment: experiment.name(),
            key,
            reason,
        }
    };
    let pod_name = inputs.spec.particle_material().unwrap_or("pod");
    let wall_name = inputs.simulation.wall_material.as_str();
    let pod = w
        .add_material_with(inputs.pod, inputs.pod_poisson)
        .map_err(at(format!("materials.{pod_name}")))?;
    let wall = w
        .add_material(inputs.wall)
        .map_err(at(format!("materials.{wall_name}")))?;
    w.set_pair(pod, pod, inputs.pod_pod)
        .map_err(at(format!("pairs.\"{pod_name}-{pod_name}\"")))?;
    w.set_pair(pod, wall, inputs.pod_wall)
        .map_err(at(format!("pairs.\"{pod_name}-{wall_name}\"")))?;
    // Effects only where one is on, so a run without them sets up the world as before.
    for (a, b, effects, name) in [
        (
            pod,
            pod,
            inputs.pod_pod_effects,
            format!("{pod_name}-{pod_name}"),
        ),
        (
            pod,
            wall,
            inputs.pod_wall_effects,
            format!("{pod_name}-{wall_name}"),
        ),
    ] {
        if effects != EffectSpec::default() {
            w.set_pair_effects(a, b, effects)
                .map_err(at(format!("pairs.\"{name}\"")))?;
        }
    }
    w.set_gravity_m_s2([0.0, 0.0, -inputs.simulation.gravity_m_s2])
        .map_err(at("plan.simulation.gravity_m_s2".into()))?;
    Ok(RigMaterials { pod, wall })
}

/// Adds the steel floor of a pod rig: the plane z = 0, facing up, of the wall material.
pub fn add_floor(
    w: &mut World<'_, Fx>,
    mats: RigMaterials,
    experiment: Experiment,
) -> Result<WallId, ExperimentError> {
    w.add_wall(WallSpec::fixed(
        WallGeometry::Plane {
            point_m: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
        },
        mats.wall,
    ))
    .map_err(|s| setup_error(experiment, s))
}

/// Rotation matrix of unit quaternion `q = [w, x, y, z]` (rows).
pub fn quat_matrix(q: [f64; 4]) -> [[f64; 3]; 3] {
    let [w, x, y, z] = q;
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// A uniform number in [0, 1) from 53 random bits.
pub fn unit_uniform(rng: &mut SplitMix64) -> f64 {
    const MANTISSA_BITS: u32 = 53;
    (rng.next_u64() >> (64 - MANTISSA_BITS)) as f64 / (1u64 << MANTISSA_BITS) as f64
}

/// A uniformly random orientation (Shoemake 1992, "Uniform random rotations").
pub fn random_quaternion(rng: &mut SplitMix64) -> [f64; 4] {
    use std::f64::consts::TAU;
    let (u1, u2, u3) = (unit_uniform(rng), unit_uniform(rng), unit_uniform(rng));
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    [
        b * (TAU * u3).cos(),
        a * (TAU * u2).sin(),
        a * (TAU * u2).cos(),
        b * (TAU * u3).sin(),
    ]
}

/// Adds `template` as a clump with its centre of mass at `position_mm`, its principal frame
/// turned by `q`, moving at `velocity_m_s`.
pub fn add_pod(
    w: &mut World<'_, Fx>,
    template: &PodTemplate,
    material: MaterialId,
    position_mm: [f64; 3],
    q: [f64; 4],
    velocity_m_s: [f64; 3],
    experiment: Experiment,
) -> Result<BodyId, ExperimentError> {
    if template.is_sphere() {
        // A sphere particle is a body of its own, not a one-sphere clump: the same mass and
        // inertia (the core's sphere of the material's density), the cheaper integrator.
        let mut s = SphereSpec::at_rest(
            material,
            template.spheres[0].radius_mm * M_PER_MM,
            position_mm.map(|x| x * M_PER_MM),
        );
        s.velocity_m_s = velocity_m_s;
        return w.add_sphere(s).map_err(|e| setup_error(experiment, e));
    }
    let r = quat_matrix(q);
    let spheres: Vec<ClumpSphere> = template
        .spheres
        .iter()
        .map(|s| {
            let c = s.centre_mm;
            let world = [0, 1, 2]
                .map(|i| position_mm[i] + r[i][0] * c[0] + r[i][1] * c[1] + r[i][2] * c[2]);
            ClumpSphere {
                center_m: world.map(|x| x * M_PER_MM),
                radius_m: s.radius_mm * M_PER_MM,
                material,
            }
        })
        .collect();
    let mass = CoreMass {
        mass_kg: template.mass.mass_kg,
        center_of_mass_m: position_mm.map(|x| x * M_PER_MM),
        principal_inertia_kg_m2: template.mass.principal_inertia_kg_m2,
        principal_axes: q,
    };
    let spec = ClumpSpec {
        spheres: &spheres,
        velocity_m_s,
        angular_velocity_rad_s: [0.0; 3],
    };
    w.add_clump_with_mass(&spec, &mass)
        .map_err(|s| setup_error(experiment, s))
}

/// Sets dt to the study's fraction of the smallest Rayleigh time (seed 000 §2.7: 20 %).
pub fn set_rayleigh_timestep(
    w: &mut World<'_, Fx>,
    inputs: &RunInputs,
    experiment: Experiment,
) -> Result<f64, ExperimentError> {
    let dt = inputs.simulation.dt_rayleigh_fraction * w.min_rayleigh_time_s();
    w.set_timestep_s(dt)
        .map_err(|s| setup_error(experiment, s))?;
    Ok(dt)
}

/// Runs `steps` steps on the run's threads ([`crate::stepping::run`]), naming the time of a
/// failure.
pub fn run_steps(
    w: &mut World<'_, Fx>,
    steps: u64,
    experiment: Experiment,
) -> Result<(), ExperimentError> {
    crate::stepping::run(w, steps).map_err(|reason| ExperimentError::Step {
        experiment: experiment.name(),
        time_s: w.time_s(),
        reason,
    })
}

/// Steps `w` in chunks of `chunk` steps, recording a frame after each, until its kinetic
/// energy is below `at_rest_j` at a time of at least `not_before_s`, or until `until_s`
/// has passed (s). The fill-and-settle phase of the bulk pod rigs.
pub fn settle(
    w: &mut World<'_, Fx>,
    chunk: u64,
    not_before_s: f64,
    until_s: f64,
    at_rest_j: f64,
    frames: &mut super::frames::FrameRecorder,
    experiment: Experiment,
) -> Result<(), ExperimentError> {
    while w.time_s() < until_s {
        run_steps(w, chunk, experiment)?;
        frames.record(w);
        if w.time_s() >= not_before_s && kinetic_energy_j(w) < at_rest_j {
            break;
        }
    }
    Ok(())
}

/// Steps in `duration_s` at the world's dt (at least one).
pub fn steps_for(w: &World<'_, Fx>, duration_s: f64) -> u64 {
    steps_in(duration_s, w.timestep_s())
}

/// Steps in `duration_s` at time step `dt_s` (at least one).
pub fn steps_in(duration_s: f64, dt_s: f64) -> u64 {
    ((duration_s / dt_s).round() as u64).max(1)
}

/// Kinetic energy, J (the core reports mJ).
pub fn kinetic_energy_j(w: &World<'_, Fx>) -> f64 {
    const J_PER_MJ: f64 = 1e-3;
    w.kinetic_energy_mj() * J_PER_MJ
}
