//! One plant through the picking machine: world set-up, stepping, and the fate of its pods.
//!
//! World (SI in, core units inside): the plant of [`crate::plant`] (stems, stalks and leaves
//! of the stalk material, pods of the pod material of `arachis_core::scenario::pull_off`),
//! yawed by [`PlantLayout::yaw_rad`] about its stem and shifted by
//! [`PlantLayout::lateral_offset_m`]; its top main-stem sphere is the clamp, a kinematic body
//! moving at the forward speed along +x; every other plant body starts with that velocity, so
//! the clamp does not jerk the plant. The drum is one kinematic clump of steel teeth spinning
//! about the x axis (ω = 2π·n/60); two steel planes at y = ±housing half-width are the
//! housing. Gravity −z. The time step is [`TIMESTEP_SAFETY`] × the smaller of the contact
//! bound (Rayleigh) and the bond bound.
//!
//! Every [`CHECK_EVERY_STEPS`] steps the pods are checked: a pod is *free* when no chain of
//! live bonds joins it to the clamp (union–find over the bond list). A free pod that has
//! fallen below the bottom of the tooth circle is classified there (over the collector or
//! not, [`super::accounting`]) and frozen (made kinematic at rest) so it costs nothing more.
//! When the plant has left the drum, free pods still in the air are classified by their
//! ballistic landing point, pods still bonded to the clamp are unpicked.

use arachis_core::prelude::*;
use arachis_core::scenario::materials::{GRAVITY_M_S2, STEEL};
use arachis_core::scenario::pull_off::{POD_CONTACT, POD_MATERIAL, STALK_CONTACT, STALK_MATERIAL};
use arachis_core::units::{LENGTH_M_TO_MM, VELOCITY_M_S_TO_MM_MS};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::accounting::{ballistic_landing_x, Fate};
use super::machine::Machine;
use super::HarvestError;
use crate::arena::{OwnedBonds, OwnedStorage};
use crate::plant::topology::Kind;
use crate::plant::PlantModel;
use crate::vtk::ParticleFrame;

/// Fraction of the stable time step used (margin under both bounds).
pub const TIMESTEP_SAFETY: f64 = 0.9;
/// Steps between pod checks (and the granularity of progress and frames).
pub const CHECK_EVERY_STEPS: u64 = 250;
/// Clearance between the plant and the first/last tooth ring at the start/end of a pass, m.
pub const CLEARANCE_M: f64 = 0.005;
/// Height of the housing's cover above the plant's highest sphere, m (the clamp chain runs
/// through a slot in it; pods thrown upwards bounce back into the chamber).
pub const COVER_CLEARANCE_M: f64 = 0.02;
/// Largest random lateral offset of a plant from the drum's vertical plane, m (the clamp
/// conveyor does not hold every plant at the same place).
pub const MAX_LATERAL_OFFSET_M: f64 = 0.01;
/// Pod–steel contact, seed 001 Table 2: e 0.29, μs 0.54, μr 0.42.
pub const POD_STEEL_CONTACT: PairSpec = PairSpec {
    restitution: 0.29,
    friction: 0.54,
    rolling_friction: 0.42,
    conventions: arachis_core::contact::Conventions::EDEM,
    terms: TermSwitches::ALL,
};
/// Stalk (and stem, leaf)–steel contact, seed 001 Table 2: e 0.21, μs 0.71, μr 0.58.
pub const STALK_STEEL_CONTACT: PairSpec = PairSpec {
    restitution: 0.21,
    friction: 0.71,
    rolling_friction: 0.58,
    conventions: arachis_core::contact::Conventions::EDEM,
    terms: TermSwitches::ALL,
};

/// Random placement of one plant in the machine.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PlantLayout {
    /// Rotation of the plant about its (vertical) main stem, rad.
    pub yaw_rad: f64,
    /// Offset of the clamp from the drum's vertical plane along y, m.
    pub lateral_offset_m: f64,
    /// Drum angle when the pass starts, rad.
    pub drum_phase_rad: f64,
}

impl PlantLayout {
    /// A layout drawn from `rng`: yaw and drum phase uniform on [0, 2π), offset uniform on
    /// ±[`MAX_LATERAL_OFFSET_M`].
    pub fn draw(rng: &mut ChaCha8Rng) -> Self {
        let tau = std::f64::consts::TAU;
        PlantLayout {
            yaw_rad: rng.gen_range(0.0..tau),
            lateral_offset_m: rng.gen_range(-MAX_LATERAL_OFFSET_M..MAX_LATERAL_OFFSET_M),
            drum_phase_rad: rng.gen_range(0.0..tau),
        }
    }
}

/// Progress reports of a pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progress {
    /// A pass starts and will run this many steps.
    Started(u64),
    /// This many more steps were run.
    Stepped(u64),
}

/// Outcome of one plant pass.
#[derive(Debug, Clone)]
pub struct PassResult {
    /// Fate of each pod, in the plant's pod order.
    pub fates: Vec<Fate>,
    /// Pod–stalk junction bonds broken.
    pub junction_breaks: u64,
    /// All bonds broken.
    pub bond_breaks: u64,
    /// Steps run.
    pub steps: u64,
    /// Time step, s.
    pub dt_s: f64,
    /// State digest at the end (FNV-1a of the whole world).
    pub digest: u64,
    /// VTK frames (empty unless asked for).
    pub frames: Vec<ParticleFrame>,
}

/// Plant placed for the pass: the model with moved spheres, the clamp body, the pod bodies.
struct Placed {
    model: PlantModel,
    clamp: usize,
    pods: Vec<usize>,
    /// Smallest x of any plant sphere's surface, m.
    min_x_m: f64,
}

fn place(
    model: &PlantModel,
    layout: &PlantLayout,
    tooth_radius_m: f64,
) -> Result<Placed, HarvestError> {
    let clamp = model
        .bodies
        .iter()
        .rposition(|b| b.kind == Kind::MainStem)
        .ok_or_else(|| HarvestError::Plant("the plant has no main stem".to_owned()))?;
    let pods: Vec<usize> = (0..model.bodies.len())
        .filter(|&i| model.bodies[i].kind == Kind::Pod)
        .collect();
    if pods.is_empty() {
        return Err(HarvestError::Plant("the plant has no pods".to_owned()));
    }
    let (s, c) = layout.yaw_rad.sin_cos();
    let mut m = model.clone();
    for sp in &mut m.spheres {
        let [x, y, z] = sp.centre_m;
        sp.centre_m = [c * x - s * y, s * x + c * y + layout.lateral_offset_m, z];
    }
    // Shift along x so the plant's front surface starts CLEARANCE_M before the first teeth.
    let max_x = m
        .spheres
        .iter()
        .map(|p| p.centre_m[0] + p.radius_m)
        .fold(f64::MIN, f64::max);
    let shift = -tooth_radius_m - CLEARANCE_M - max_x;
    for sp in &mut m.spheres {
        sp.centre_m[0] += shift;
    }
    let min_x_m = m
        .spheres
        .iter()
        .map(|p| p.centre_m[0] - p.radius_m)
        .fold(f64::MAX, f64::min);
    Ok(Placed {
        model: m,
        clamp,
        pods,
        min_x_m,
    })
}

/// The tooth sphere centres, m: ring j at x = j·pitch, tooth k at angle
/// φ + 2πk/n (+ π/n on odd rings), y = R cos θ, z = z_axis + R sin θ.
fn teeth(machine: &Machine, axis_z_m: f64, phase: f64) -> Vec<[f64; 3]> {
    let n = machine.teeth_per_ring as usize;
    let step = std::f64::consts::TAU / n as f64;
    let mut out = Vec::with_capacity(machine.teeth());
    for j in 0..machine.rings() {
        let stagger = if j % 2 == 1 { step / 2.0 } else { 0.0 };
        for k in 0..n {
            let th = phase + stagger + step * k as f64;
            out.push([
                j as f64 * machine.ring_pitch_m,
                machine.tip_radius_m * th.cos(),
                axis_z_m + machine.tip_radius_m * th.sin(),
            ]);
        }
    }
    out
}

/// Union–find root with path halving.
pub(crate) fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// For each body, whether live bonds join it to body `clamp`.
fn attached_to<S: Scalar>(world: &World<'_, S>, n_bodies: usize, clamp: usize) -> Vec<bool> {
    let mut parent: Vec<usize> = (0..n_bodies).collect();
    let spheres = world.spheres();
    for b in world.bonds().bonds() {
        let i = spheres[b.sphere_a as usize].body as usize;
        let j = spheres[b.sphere_b as usize].body as usize;
        if i < n_bodies && j < n_bodies {
            let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
            parent[ri] = rj;
        }
    }
    let rc = root(&mut parent, clamp);
    (0..n_bodies).map(|i| root(&mut parent, i) == rc).collect()
}

/// Run one plant through the machine. `frame_every`: steps between VTK frames (`None`: no
/// frames); `progress` hears the pass's step count, then the steps as they are run.
pub fn run_pass<S: Scalar>(
    machine: &Machine,
    model: &PlantModel,
    layout: &PlantLayout,
    frame_every: Option<u64>,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<PassResult, HarvestError> {
    machine.check()?;
    let core = |e: &dyn std::fmt::Display| HarvestError::Core(e.to_string());
    let placed = place(model, layout, machine.tooth_radius_m)?;
    let axis_z = machine.reach_above_root_m - machine.tip_radius_m;
    let floor_z = axis_z - machine.tip_radius_m - machine.tooth_radius_m;
    let teeth_at = teeth(machine, axis_z, layout.drum_phase_rad);
    let n_plant_bodies = placed.model.bodies.len();
    let n_bodies = n_plant_bodies + 1;
    let n_spheres = placed.model.spheres.len() + teeth_at.len();
    let len = StorageLengths::for_spheres(n_bodies, n_spheres);
    let mut arena = OwnedStorage::<S>::new(len);
    let mut bond_arena = OwnedBonds::<S>::new(placed.model.bonds.len());
    let mut w = World::new(arena.storage()).map_err(|e| core(&e))?;
    w.attach_bond_storage(bond_arena.storage())
        .map_err(|e| core(&e))?;
    let plant = w.add_material(STALK_MATERIAL).map_err(|e| core(&e))?;
    let pod = w.add_material(POD_MATERIAL).map_err(|e| core(&e))?;
    let steel = w.add_material(STEEL).map_err(|e| core(&e))?;
    for (x, y, spec) in [
        (plant, plant, STALK_CONTACT),
        (plant, pod, POD_CONTACT),
        (pod, pod, POD_CONTACT),
        (pod, steel, POD_STEEL_CONTACT),
        (plant, steel, STALK_STEEL_CONTACT),
    ] {
        w.set_pair(x, y, spec).map_err(|e| core(&e))?;
    }
    w.set_gravity_m_s2(GRAVITY_M_S2).map_err(|e| core(&e))?;
    placed
        .model
        .load_into(&mut w, plant, pod)
        .map_err(|e| HarvestError::Plant(e.to_string()))?;
    let v = [machine.forward_speed_m_s, 0.0, 0.0];
    for i in 0..n_plant_bodies {
        w.set_body_velocity(BodyId(i as u32), v, [0.0; 3])
            .map_err(|e| core(&e))?;
    }
    w.set_body_kinematic(BodyId(placed.clamp as u32))
        .map_err(|e| core(&e))?;
    // The drum: kinematic, so its mass properties only need to be valid (a ring of teeth).
    let tooth_mass =
        STEEL.density_kg_m3 * 4.0 / 3.0 * std::f64::consts::PI * machine.tooth_radius_m.powi(3);
    let mass = tooth_mass * teeth_at.len() as f64;
    let r2 = machine.tip_radius_m.powi(2);
    let l2 = machine.drum_length_m.powi(2);
    let spheres: Vec<ClumpSphere> = teeth_at
        .iter()
        .map(|&c| ClumpSphere {
            center_m: c,
            radius_m: machine.tooth_radius_m,
            material: steel,
        })
        .collect();
    let omega = [machine.drum_omega_rad_s(), 0.0, 0.0];
    let drum = w
        .add_clump_with_mass(
            &ClumpSpec {
                spheres: &spheres,
                velocity_m_s: [0.0; 3],
                angular_velocity_rad_s: omega,
            },
            &MassProperties {
                mass_kg: mass,
                center_of_mass_m: [machine.drum_length_m / 2.0, 0.0, axis_z],
                principal_inertia_kg_m2: [
                    mass * r2,
                    mass * (r2 / 2.0 + l2 / 12.0),
                    mass * (r2 / 2.0 + l2 / 12.0),
                ],
                principal_axes: [1.0, 0.0, 0.0, 0.0],
            },
        )
        .map_err(|e| core(&e))?;
    w.set_body_kinematic(drum).map_err(|e| core(&e))?;
    for sign in [-1.0, 1.0] {
        w.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0, sign * machine.housing_half_width_m, 0.0],
                normal: [0.0, -sign, 0.0],
            },
            steel,
        ))
        .map_err(|e| core(&e))?;
    }
    let top = placed
        .model
        .spheres
        .iter()
        .map(|p| p.centre_m[2] + p.radius_m)
        .fold(f64::MIN, f64::max);
    w.add_wall(WallSpec::fixed(
        WallGeometry::Plane {
            point_m: [0.0, 0.0, top + COVER_CLEARANCE_M],
            normal: [0.0, 0.0, -1.0],
        },
        steel,
    ))
    .map_err(|e| core(&e))?;
    let dt = TIMESTEP_SAFETY * w.max_timestep_s().min(w.bond_max_timestep_s());
    w.set_timestep_s(dt).map_err(|e| core(&e))?;

    let drum_end = machine.drum_length_m + machine.tooth_radius_m;
    let travel_m = drum_end + CLEARANCE_M - placed.min_x_m;
    let steps = (travel_m / machine.forward_speed_m_s / dt).ceil() as u64;
    let collector = (-machine.tooth_radius_m - machine.collector_margin_m)
        ..=(drum_end + machine.collector_margin_m);
    progress(Progress::Started(steps));
    let mut fates: Vec<Option<Fate>> = vec![None; placed.pods.len()];
    let mut frames = Vec::new();
    if frame_every.is_some() {
        frames.push(ParticleFrame::from_world(&w));
    }
    let g = -GRAVITY_M_S2[2];
    let m_of = |mm: f64| mm / LENGTH_M_TO_MM;
    while w.step_count() < steps {
        let chunk = CHECK_EVERY_STEPS.min(steps - w.step_count());
        crate::stepping::run(&mut w, chunk).map_err(|e| HarvestError::Step {
            time_s: w.time_s(),
            what: e.to_string(),
        })?;
        progress(Progress::Stepped(chunk));
        if let Some(every) = frame_every {
            let done = w.step_count();
            if done % every < chunk || done == steps {
                frames.push(ParticleFrame::from_world(&w));
            }
        }
        let on = attached_to(&w, n_plant_bodies, placed.clamp);
        for (k, &p) in placed.pods.iter().enumerate() {
            if fates[k].is_some() || on[p] {
                continue;
            }
            let pos = w.bodies()[p].position.to_f64().map(m_of);
            if pos[2] < floor_z {
                fates[k] = Some(if collector.contains(&pos[0]) {
                    Fate::Collected
                } else {
                    Fate::Dropped
                });
                let id = BodyId(p as u32);
                w.set_body_kinematic(id).map_err(|e| core(&e))?;
                w.set_body_velocity(id, [0.0; 3], [0.0; 3])
                    .map_err(|e| core(&e))?;
            }
        }
    }
    let on = attached_to(&w, n_plant_bodies, placed.clamp);
    let fates: Vec<Fate> = placed
        .pods
        .iter()
        .zip(fates)
        .map(|(&p, f)| {
            f.unwrap_or_else(|| {
                if on[p] {
                    return Fate::Unpicked;
                }
                let b = &w.bodies()[p];
                let pos = b.position.to_f64().map(m_of);
                let vel = b.velocity.to_f64().map(|x| x / VELOCITY_M_S_TO_MM_MS);
                let x = ballistic_landing_x(pos[0], pos[2], vel[0], vel[2], floor_z, g);
                if collector.contains(&x) {
                    Fate::Collected
                } else {
                    Fate::Dropped
                }
            })
        })
        .collect();
    let junction_tag = placed.model.sets.get("pod_stalk").map(|s| s.tag);
    let junction_breaks = w
        .bonds()
        .breaks()
        .iter()
        .filter(|b| Some(b.tag) == junction_tag)
        .count() as u64;
    Ok(PassResult {
        fates,
        junction_breaks,
        bond_breaks: w.bonds().breaks_total(),
        steps: w.step_count(),
        dt_s: dt,
        digest: w.digest(),
        frames,
    })
}
