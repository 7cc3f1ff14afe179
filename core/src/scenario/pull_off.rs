//! Virtual tensile (pull-off) test of a pod on its stalk (issue 6; seed 001 §2.3: the
//! pod–stalk junction "clamped at both ends of the texture analyzer" and stretched).
//!
//! A pod stalk of [`PullOff::stalk_spheres`] spheres (R = 0.965 mm: D = 1.93 mm, seed 001
//! Table 1) lies along +x, its first sphere clamped (kinematic, at rest). A three-sphere pod
//! clump (R 7.88 mm = H/2, overall length 34.27 mm: seed 001 Table 1) sits at the free end. At
//! [`PullOff::bond_time_s`] every neighbouring pair is bonded ([`crate::bond::formation`]): stalk
//! spheres with the stalk set, the end sphere and the pod with the junction set. The pod is a
//! kinematic gripper moving at [`PullOff::pull_speed_m_s`] along a direction
//! [`PullOff::pull_angle_deg`] from the stalk axis (in the x–y plane; 0 = axial, the texture
//! analyser); gravity acts along −z. [`PullOff::run`] reports the pull force
//! F = −(F_on_pod − m·g)·û against the pod displacement, and the detachment force: the largest
//! pull force before the junction bond breaks.
//!
//! Bond parameters (defaults; they are what the calibration varies):
//! - junction: Rb = 1.1 mm (seed 001 Table 4), σc = τc = 9.35e5 Pa (seed 001 §3.2 calibrated
//!   τc; σc set equal, as in Table 4's start values);
//! - stalk: Rb = 0.965 mm (the stalk radius), σc = τc from the stalk's maximum tensile force
//!   10.21 N over its section (seed 001 Table 3): 3.49 MPa;
//! - stiffness per unit area from the junction's apparent modulus (E = 118 MPa, ν = 0.247, seed
//!   001 Table 3) over the bond length L (centre distance): Kn = E/L, Kt = G/L with
//!   G = E/(2(1+ν)), i.e. the bond is an elastic beam of the measured material. Seed 001's
//!   own Kn = 5e5 N/m³ would stretch a bond by σc/Kn ≈ 2 m before it breaks, which no
//!   tensile test shows; DESIGN §3 lists those values for the calibration to start from.
//!
//! With an axial pull the junction is in pure tension, so the criterion predicts detachment at
//! F = σc·πRb² = 3.554 N ([`PullOff::predicted_axial_detachment_n`]); the stalk's own bonds
//! hold to 10.21 N.

use super::ScenarioError;
use crate::body::{ClumpSphere, SphereSpec, Storage, StorageLengths};
use crate::bond::{BondSetSpec, BondStorage, FormationRule};
use crate::material::MaterialSpec;
use crate::num::Scalar;
use crate::pair::{PairSpec, TermSwitches};
use crate::units::LENGTH_M_TO_MM;
use crate::world::{ClumpSpec, World};
use core::f64::consts::PI;

/// Pod stalk diameter, mm (seed 001 Table 1).
pub const STALK_DIAMETER_MM: f64 = 1.93;
/// Pod length L and thickness H, mm (seed 001 Table 1).
pub const POD_LENGTH_MM: f64 = 34.27;
/// Pod thickness H, mm (seed 001 Table 1); the pod spheres have radius H/2.
pub const POD_THICKNESS_MM: f64 = 15.76;
/// Spheres in the pod clump.
pub const POD_SPHERES: usize = 3;
/// Surface gap between neighbours at set-up, mm (no contact before bonding).
pub const SETUP_GAP_MM: f64 = 0.001;
/// Largest gap bonded at formation, m (5 × the set-up gap).
pub const FORMATION_GAP_M: f64 = 5.0 * SETUP_GAP_MM / LENGTH_M_TO_MM;
/// Time step, s: seed 001 §2.4.2 uses 4.98e-7 s; the stalk bonds allow about 9e-7 s.
pub const TIMESTEP_S: f64 = 5.0e-7;
/// Junction apparent modulus, Pa, and Poisson ratio (seed 001 Table 3).
pub const JUNCTION_E_PA: f64 = 118.0e6;
/// Junction apparent Poisson ratio (seed 001 Table 3).
pub const JUNCTION_POISSON: f64 = 0.247;
/// Stalk maximum tensile force, N (seed 001 Table 3).
pub const STALK_MAX_TENSILE_N: f64 = 10.21;
/// Calibrated tangential critical stress of the junction, Pa (seed 001 §3.2).
pub const JUNCTION_STRENGTH_PA: f64 = 9.35e5;
/// Junction bond radius, m (seed 001 Table 4).
pub const JUNCTION_BOND_RADIUS_M: f64 = 1.1e-3;
/// Bond-set tags.
pub const TAG_JUNCTION: u16 = 1;
/// Tag of the stalk's own bonds.
pub const TAG_STALK: u16 = 2;

/// Stalk material: the junction's E and ν (seed 001 Table 3); density 1000 kg/m³ (assumed:
/// not given by the seeds; only the stalk's dynamics, not the static pull force, depend on it).
pub const STALK_MATERIAL: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: JUNCTION_E_PA,
    poisson: JUNCTION_POISSON,
    density_kg_m3: 1000.0,
};
/// Pod material: E 296 MPa, ν 0.37 (seed 001 Table 3), ρ 582.36 kg/m³ (seed 000 §3.1.1).
pub const POD_MATERIAL: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 296.0e6,
    poisson: 0.37,
    density_kg_m3: 582.36,
};
/// Pod–pod and pod–stalk contact: e 0.34, μs 0.62, μr 0.47 (seed 001 Table 2, pod–pod).
pub const POD_CONTACT: PairSpec = PairSpec {
    restitution: 0.34,
    friction: 0.62,
    rolling_friction: 0.47,
    conventions: crate::contact::Conventions::EDEM,
    terms: TermSwitches::ALL,
};
/// Stalk–stalk contact: e 0.21, μs 0.71, μr 0.58 (seed 001 Table 2, stalk–steel, the only
/// stalk pair measured).
pub const STALK_CONTACT: PairSpec = PairSpec {
    restitution: 0.21,
    friction: 0.71,
    rolling_friction: 0.58,
    conventions: crate::contact::Conventions::EDEM,
    terms: TermSwitches::ALL,
};

/// Bond set of a beam of modulus E, Poisson ratio ν and length L: Kn = E/L, Kt = G/L.
pub fn beam_bond_set(tag: u16, length_m: f64, radius_m: f64, strength_pa: f64) -> BondSetSpec {
    let g = JUNCTION_E_PA / (2.0 * (1.0 + JUNCTION_POISSON));
    BondSetSpec {
        tag,
        normal_stiffness_n_m3: JUNCTION_E_PA / length_m,
        tangential_stiffness_n_m3: g / length_m,
        normal_strength_pa: strength_pa,
        tangential_strength_pa: strength_pa,
        radius_m,
    }
}

/// The pull-off scenario.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PullOff {
    /// Spheres in the stalk (≥ 2; the first is clamped).
    pub stalk_spheres: u32,
    /// Gripper speed, m/s.
    pub pull_speed_m_s: f64,
    /// Pull direction from the stalk axis, degrees, in the x–y plane.
    pub pull_angle_deg: f64,
    /// Simulated time of bond formation, s.
    pub bond_time_s: f64,
    /// Junction (pod–stalk) bond set.
    pub junction: BondSetSpec,
    /// Stalk (stalk–stalk) bond set.
    pub stalk: BondSetSpec,
    /// Unbonded stalk–stalk contact (default [`STALK_CONTACT`]).
    pub stalk_contact: PairSpec,
    /// Unbonded stalk–pod and pod–pod contact (default [`POD_CONTACT`]).
    pub pod_contact: PairSpec,
}

impl Default for PullOff {
    fn default() -> Self {
        let r_stalk_m = STALK_DIAMETER_MM / 2.0 / LENGTH_M_TO_MM;
        let r_pod_m = POD_THICKNESS_MM / 2.0 / LENGTH_M_TO_MM;
        let stalk_area_m2 = PI * r_stalk_m * r_stalk_m;
        PullOff {
            stalk_spheres: 8,
            pull_speed_m_s: 0.1,
            pull_angle_deg: 0.0,
            bond_time_s: 0.0,
            junction: beam_bond_set(
                TAG_JUNCTION,
                r_stalk_m + r_pod_m,
                JUNCTION_BOND_RADIUS_M,
                JUNCTION_STRENGTH_PA,
            ),
            stalk: beam_bond_set(
                TAG_STALK,
                2.0 * r_stalk_m,
                r_stalk_m,
                STALK_MAX_TENSILE_N / stalk_area_m2,
            ),
            stalk_contact: STALK_CONTACT,
            pod_contact: POD_CONTACT,
        }
    }
}

/// What a pull-off run measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PullOffResult {
    /// Largest pull force before the junction broke, N (the detachment force).
    pub detachment_force_n: f64,
    /// Gripper displacement at that force, mm.
    pub detachment_displacement_mm: f64,
    /// Step in which the junction broke (`None`: it held for the whole run).
    pub break_step: Option<u64>,
    /// `true` if a stalk bond broke before the junction did.
    pub stalk_broke_first: bool,
}

impl PullOff {
    /// Arena lengths this scenario needs.
    pub fn storage_lengths(&self) -> StorageLengths {
        StorageLengths::for_spheres(
            self.stalk_spheres as usize + 1,
            self.stalk_spheres as usize + POD_SPHERES,
        )
    }

    /// Bond capacity this scenario needs (stalk chain plus junction).
    pub fn bond_capacity(&self) -> usize {
        self.stalk_spheres as usize
    }

    /// Body id of the pod (the last body).
    pub fn pod_body(&self) -> crate::body::BodyId {
        crate::body::BodyId(self.stalk_spheres)
    }

    /// Detachment force the criterion predicts for an axial pull: σc·πRb², N.
    pub fn predicted_axial_detachment_n(&self) -> f64 {
        let r = self.junction.radius_m;
        self.junction.normal_strength_pa * PI * r * r
    }

    /// Unit pull direction.
    fn direction(&self) -> [f64; 3] {
        let a = self.pull_angle_deg.to_radians();
        [libm::cos(a), libm::sin(a), 0.0]
    }

    /// Build the scenario over `storage` and `bonds`.
    pub fn build<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
        bonds: BondStorage<'a, S>,
    ) -> Result<World<'a, S>, ScenarioError> {
        if self.stalk_spheres < 2 {
            return Err(ScenarioError::NoParticles);
        }
        let mut w = World::new(storage)?;
        w.attach_bond_storage(bonds)?;
        let stalk = w.add_material(STALK_MATERIAL)?;
        let pod = w.add_material(POD_MATERIAL)?;
        w.set_pair(stalk, stalk, self.stalk_contact)?;
        w.set_pair(stalk, pod, self.pod_contact)?;
        w.set_pair(pod, pod, self.pod_contact)?;
        w.set_gravity_m_s2(super::materials::GRAVITY_M_S2)?;
        let rs = STALK_DIAMETER_MM / 2.0;
        let pitch = 2.0 * rs + SETUP_GAP_MM;
        for k in 0..self.stalk_spheres {
            let x = k as f64 * pitch / LENGTH_M_TO_MM;
            let id = w.add_sphere(SphereSpec::at_rest(
                stalk,
                rs / LENGTH_M_TO_MM,
                [x, 0.0, 0.0],
            ))?;
            if k == 0 {
                w.set_body_kinematic(id)?;
            }
        }
        let rp = POD_THICKNESS_MM / 2.0;
        let spacing = (POD_LENGTH_MM - 2.0 * rp) / (POD_SPHERES as f64 - 1.0);
        let first = (self.stalk_spheres - 1) as f64 * pitch + rs + SETUP_GAP_MM + rp;
        let spheres: [ClumpSphere; POD_SPHERES] = core::array::from_fn(|k| ClumpSphere {
            center_m: [(first + k as f64 * spacing) / LENGTH_M_TO_MM, 0.0, 0.0],
            radius_m: rp / LENGTH_M_TO_MM,
            material: pod,
        });
        let u = self.direction();
        let v = u.map(|x| x * self.pull_speed_m_s);
        let pod_id = w.add_clump(&ClumpSpec {
            spheres: &spheres,
            velocity_m_s: v,
            angular_velocity_rad_s: [0.0; 3],
        })?;
        w.set_body_kinematic(pod_id)?;
        let stalk_set = w.add_bond_set(&self.stalk)?;
        let junction_set = w.add_bond_set(&self.junction)?;
        w.schedule_bond_formation(
            self.bond_time_s,
            &FormationRule {
                set: stalk_set,
                materials: Some((stalk, stalk)),
                max_gap_m: FORMATION_GAP_M,
            },
        )?;
        w.schedule_bond_formation(
            self.bond_time_s,
            &FormationRule {
                set: junction_set,
                materials: Some((stalk, pod)),
                max_gap_m: FORMATION_GAP_M,
            },
        )?;
        w.set_timestep_s(TIMESTEP_S)?;
        Ok(w)
    }

    /// Pull force on the gripper along the pull direction, N: −(F_on_pod − m·g)·û.
    pub fn pull_force_n<S: Scalar>(&self, w: &World<'_, S>) -> f64 {
        let b = w.body(self.pod_body());
        let f = b.force.to_f64();
        let m = b.mass.to_f64();
        let g = w.gravity().to_f64();
        let u = self.direction();
        -(0..3).map(|k| (f[k] - m * g[k]) * u[k]).sum::<f64>()
    }

    /// Run up to `max_steps` steps or until the junction breaks, calling `record(displacement
    /// mm, pull force N)` after every step. The displacement is the gripper's travel,
    /// speed × simulated time (the pod is kinematic), so consecutive calls continue one run.
    pub fn run<S: Scalar>(
        &self,
        w: &mut World<'_, S>,
        max_steps: u64,
        mut record: impl FnMut(f64, f64),
    ) -> Result<PullOffResult, ScenarioError> {
        let speed_mm_ms = self.pull_speed_m_s * crate::units::VELOCITY_M_S_TO_MM_MS;
        let mut out = PullOffResult {
            detachment_force_n: 0.0,
            detachment_displacement_mm: 0.0,
            break_step: None,
            stalk_broke_first: false,
        };
        let is_junction = |b: &crate::bond::Bond<S>| b.sphere_b >= self.stalk_spheres;
        // Start from the world's state, so that consecutive calls continue one run.
        let mut junction_formed = w.bonds().bonds().iter().any(is_junction);
        let mut stalk_bonds = w.bonds().bonds().iter().filter(|b| !is_junction(b)).count();
        for _ in 0..max_steps {
            let step = w.step_count();
            w.step()?;
            let disp = speed_mm_ms * w.time_s() * crate::units::TIME_S_TO_MS;
            let f = self.pull_force_n(w);
            record(disp, f);
            let live = w.bonds().bonds();
            let junction = live.iter().any(is_junction);
            let stalk_now = live.iter().filter(|b| !is_junction(b)).count();
            if stalk_now < stalk_bonds {
                out.stalk_broke_first = true;
            }
            stalk_bonds = stalk_now;
            if junction_formed && !junction {
                out.break_step = Some(step);
                return Ok(out);
            }
            junction_formed |= junction;
            if f > out.detachment_force_n {
                out.detachment_force_n = f;
                out.detachment_displacement_mm = disp;
            }
        }
        Ok(out)
    }
}
