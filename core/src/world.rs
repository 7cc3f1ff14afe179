//! [`World`]: the simulation state over caller-provided storage, and its set-up API.
//!
//! Set-up takes SI values and validates them (typed [`SetupError`]s); stepping lives in
//! [`crate::step`]. A world is generic over the [`Scalar`]: `World<Fx>` is the deterministic
//! fixed-point production path, `World<f64>` the reference.
//!
//! ```
//! use arachis_core::prelude::*;
//! let len = StorageLengths::for_spheres(1, 1);
//! let mut bodies = vec![Body::<Fx>::default(); len.bodies];
//! let mut spheres = vec![Sphere::<Fx>::default(); len.spheres];
//! let mut contacts = vec![ContactSlot::<Fx>::default(); len.contacts];
//! let mut index = vec![0u32; len.sphere_index];
//! let mut cells = vec![0u32; len.cells];
//! let mut w = World::new(Storage {
//!     bodies: &mut bodies, spheres: &mut spheres, contacts: &mut contacts,
//!     sphere_index: &mut index, cells: &mut cells,
//! }).unwrap();
//! let pod = w.add_material(MaterialSpec { youngs_modulus_pa: 8.43e6, poisson: 0.386, density_kg_m3: 582.0 }).unwrap();
//! let steel = w.add_material(MaterialSpec { youngs_modulus_pa: 2.05e11, poisson: 0.3, density_kg_m3: 7865.0 }).unwrap();
//! w.set_pair(pod, steel, PairSpec::hertz_mindlin(0.339, 0.589, 0.159)).unwrap();
//! w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
//! w.add_wall(WallSpec::fixed(WallGeometry::Plane { point_m: [0.0; 3], normal: [0.0, 0.0, 1.0] }, steel)).unwrap();
//! w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0, 0.0, 0.01])).unwrap();
//! w.set_timestep_s(2e-5).unwrap();
//! for _ in 0..100 { w.step().unwrap(); }
//! assert!(w.body(BodyId(0)).position.z.to_f64() < 10.0); // fell (mm)
//! let _digest: u64 = w.digest();
//! ```

use crate::body::{
    clump_mass_properties, Body, BodyId, ClumpSphere, MassProperties, MassSphere, Sphere,
    SphereSpec, Storage, DEFAULT_MASS_GRID,
};
use crate::contact::ContactSlot;
use crate::error::{CapacityKind, SetupError};
use crate::material::{finite, Material, MaterialId, MaterialSpec, PoissonRange, MAX_MATERIALS};
use crate::num::{Quat, Scalar, Vec3};
use crate::pair::{PairParams, PairSpec};
use crate::timestep::{max_stable_dt_s, rayleigh_time_s};
use crate::units::*;
use crate::wall::{q3, Wall, WallId, WallSpec, MAX_WALLS};
use core::f64::consts::PI;

/// Largest magnitude accepted at set-up in internal units: inside the Q32.32 range (±2.1e9)
/// with headroom for the sums the stepper forms.
pub const MAX_INTERNAL_MAGNITUDE: f64 = 1.0e9;

/// Largest number of spheres in one clump (set-up works in fixed-size stack buffers).
pub const MAX_CLUMP_SPHERES: usize = 64;

/// Quantise a set-up value (internal units) into `S`, refusing non-finite values, values
/// beyond [`MAX_INTERNAL_MAGNITUDE`], and non-zero values that would round to zero.
pub fn quantise<S: Scalar>(x: f64, what: &'static str) -> Result<S, SetupError> {
    let q = quantise_coordinate(x, what)?;
    if x != 0.0 && q == S::ZERO {
        return Err(SetupError::NotRepresentable { what, value: x });
    }
    Ok(q)
}

/// Quantise a coordinate-like value (position, velocity, offset): like [`quantise`] but
/// values below the resolution may round to zero.
pub fn quantise_coordinate<S: Scalar>(x: f64, what: &'static str) -> Result<S, SetupError> {
    let x = finite(x, what)?;
    if x.abs() > MAX_INTERNAL_MAGNITUDE {
        return Err(SetupError::NotRepresentable { what, value: x });
    }
    let q = S::from_f64(x);
    if !q.is_valid() {
        return Err(SetupError::NotRepresentable { what, value: x });
    }
    Ok(q)
}

/// Quantise a vector whose components must not round to zero (inertia and its inverse).
fn q3_nonzero<S: Scalar>(v: [f64; 3], what: &'static str) -> Result<Vec3<S>, SetupError> {
    Ok(Vec3::new(
        quantise(v[0], what)?,
        quantise(v[1], what)?,
        quantise(v[2], what)?,
    ))
}

/// A clump as given by the user: its spheres (world frame at set-up) and initial motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClumpSpec<'s> {
    /// The spheres (at least one).
    pub spheres: &'s [ClumpSphere],
    /// Velocity of the centre of mass, m/s.
    pub velocity_m_s: [f64; 3],
    /// Angular velocity, rad/s.
    pub angular_velocity_rad_s: [f64; 3],
}

/// The simulation state. See the module docs for an example.
pub struct World<'a, S: Scalar> {
    pub(crate) bodies: &'a mut [Body<S>],
    pub(crate) n_bodies: u32,
    pub(crate) spheres: &'a mut [Sphere<S>],
    pub(crate) n_spheres: u32,
    pub(crate) slots: &'a mut [ContactSlot<S>],
    pub(crate) slots_per_sphere: u32,
    /// Which half of `slots` (and of the count region of `index`) holds the live history.
    pub(crate) current: u32,
    pub(crate) index: &'a mut [u32],
    pub(crate) cells: &'a mut [u32],
    pub(crate) walls: heapless::Vec<Wall<S>, MAX_WALLS>,
    pub(crate) materials: heapless::Vec<Material, MAX_MATERIALS>,
    pub(crate) pairs: [[PairParams<S>; MAX_MATERIALS]; MAX_MATERIALS],
    pub(crate) gravity: Vec3<S>,
    pub(crate) dt: S,
    pub(crate) dt_s: f64,
    pub(crate) time: S,
    pub(crate) steps: u64,
    pub(crate) max_radius: S,
    pub(crate) min_rayleigh_s: f64,
    /// `false` until the neighbour list is (re)built ([`crate::step::neighbour_list`]).
    pub(crate) list_valid: bool,
    /// Upper bound on any sphere's displacement since the last list build, mm.
    pub(crate) list_drift: S,
    /// Skin of the current neighbour list, mm.
    pub(crate) list_skin: S,
    /// Bonded-particle model state ([`crate::bond`]).
    pub(crate) bond_table: crate::bond::Bonds<'a, S>,
    /// Optional air drag (off by default; [`crate::effects`]).
    pub(crate) air_drag: crate::step::air_drag::AirDrag<S>,
}

impl<'a, S: Scalar> World<'a, S> {
    /// Build an empty world over `storage`.
    pub fn new(storage: Storage<'a, S>) -> Result<Self, SetupError> {
        let ns = storage.spheres.len();
        if ns > u32::MAX as usize / 8 || storage.bodies.len() > u32::MAX as usize / 2 {
            return Err(SetupError::Capacity {
                kind: CapacityKind::Spheres,
                capacity: u32::MAX / 8,
            });
        }
        if storage.sphere_index.len() < 4 * ns {
            return Err(SetupError::Capacity {
                kind: CapacityKind::SphereIndex,
                capacity: storage.sphere_index.len() as u32,
            });
        }
        if storage.cells.len() < 2 || storage.cells.len() > u32::MAX as usize {
            return Err(SetupError::Capacity {
                kind: CapacityKind::Cells,
                capacity: storage.cells.len().min(u32::MAX as usize) as u32,
            });
        }
        let k = if ns == 0 {
            1
        } else {
            storage.contacts.len() / (2 * ns)
        };
        if ns > 0 && (k == 0 || k > u16::MAX as usize) {
            return Err(SetupError::Capacity {
                kind: CapacityKind::ContactSlots,
                capacity: storage.contacts.len() as u32,
            });
        }
        for c in storage.sphere_index.iter_mut() {
            *c = 0;
        }
        Ok(World {
            bodies: storage.bodies,
            n_bodies: 0,
            spheres: storage.spheres,
            n_spheres: 0,
            slots: storage.contacts,
            slots_per_sphere: k as u32,
            current: 0,
            index: storage.sphere_index,
            cells: storage.cells,
            walls: heapless::Vec::new(),
            materials: heapless::Vec::new(),
            pairs: [[PairParams::default(); MAX_MATERIALS]; MAX_MATERIALS],
            gravity: Vec3::ZERO,
            dt: S::ZERO,
            dt_s: 0.0,
            time: S::ZERO,
            steps: 0,
            max_radius: S::ZERO,
            min_rayleigh_s: f64::INFINITY,
            list_valid: false,
            list_drift: S::ZERO,
            list_skin: S::ZERO,
            bond_table: crate::bond::Bonds::empty(),
            air_drag: crate::step::air_drag::AirDrag::default(),
        })
    }

    /// Add a material; returns its id. ν must lie in (−1, 0.5).
    pub fn add_material(&mut self, spec: MaterialSpec) -> Result<MaterialId, SetupError> {
        self.add_material_with(spec, PoissonRange::Isotropic)
    }

    /// Add a material whose Poisson ratio is checked against `range`: pass
    /// [`PoissonRange::ContactModel`] to accept ν ∈ (−1, 1) knowingly (seed 000 Table 3
    /// screens ν = 0.586). Returns its id.
    pub fn add_material_with(
        &mut self,
        spec: MaterialSpec,
        range: PoissonRange,
    ) -> Result<MaterialId, SetupError> {
        let m = spec.validate_with(range)?;
        let id = self.materials.len() as u16;
        self.materials.push(m).map_err(|_| SetupError::Capacity {
            kind: CapacityKind::Materials,
            capacity: MAX_MATERIALS as u32,
        })?;
        Ok(MaterialId(id))
    }

    fn material(&self, id: MaterialId) -> Result<Material, SetupError> {
        self.materials
            .get(id.0 as usize)
            .copied()
            .ok_or(SetupError::UnknownMaterial { id: id.0 })
    }

    /// Set the interaction of materials `a` and `b` (symmetric; `a == b` allowed).
    pub fn set_pair(
        &mut self,
        a: MaterialId,
        b: MaterialId,
        spec: PairSpec,
    ) -> Result<(), SetupError> {
        spec.validate()?;
        let ma = self.material(a)?;
        let mb = self.material(b)?;
        let p = PairParams::new(&ma, &mb, &spec);
        let vals: [S; 6] = [
            p.hertz.four_thirds_e_star,
            p.normal_damping.coef,
            p.tangential.eight_g_star,
            p.tangential_damping.coef,
            p.coulomb.mu,
            p.rolling.mu_r,
        ];
        if vals.iter().any(|v| !v.is_valid()) {
            return Err(SetupError::NotRepresentable {
                what: "pair constant",
                value: p.g_star_mpa * 8.0,
            });
        }
        self.pairs[a.0 as usize][b.0 as usize] = p;
        self.pairs[b.0 as usize][a.0 as usize] = p;
        Ok(())
    }

    /// The precomputed parameters of a material pair.
    pub fn pair(&self, a: MaterialId, b: MaterialId) -> Option<&PairParams<S>> {
        self.pairs
            .get(a.0 as usize)
            .and_then(|r| r.get(b.0 as usize))
            .filter(|p| p.defined)
    }

    /// Set gravity, m/s² (e.g. `[0, 0, -9.81]`).
    pub fn set_gravity_m_s2(&mut self, g: [f64; 3]) -> Result<(), SetupError> {
        self.gravity = q3(g, ACCELERATION_M_S2_TO_MM_MS2, "gravity")?;
        Ok(())
    }

    fn check_capacity(&self, spheres: usize) -> Result<(), SetupError> {
        if self.n_bodies as usize >= self.bodies.len() {
            return Err(SetupError::Capacity {
                kind: CapacityKind::Bodies,
                capacity: self.bodies.len() as u32,
            });
        }
        if self.n_spheres as usize + spheres > self.spheres.len() {
            return Err(SetupError::Capacity {
                kind: CapacityKind::Spheres,
                capacity: self.spheres.len() as u32,
            });
        }
        Ok(())
    }

    fn check_radius(r: f64) -> Result<f64, SetupError> {
        let r = finite(r, "sphere radius")?;
        if r <= 0.0 {
            return Err(SetupError::NonPositiveRadius { radius_m: r });
        }
        Ok(r)
    }

    fn note_sphere(&mut self, radius_m: f64, mat: &Material) {
        // A new sphere is in no neighbour list yet.
        self.list_valid = false;
        let r = S::from_f64(radius_m * LENGTH_M_TO_MM);
        if r > self.max_radius {
            self.max_radius = r;
        }
        let t = rayleigh_time_s(
            radius_m,
            mat.density_g_mm3 / DENSITY_KG_M3_TO_G_MM3,
            mat.youngs_modulus_mpa / STRESS_PA_TO_MPA,
            mat.poisson,
        );
        if t < self.min_rayleigh_s {
            self.min_rayleigh_s = t;
        }
    }

    /// Add a free sphere (a one-sphere body); returns its body id.
    pub fn add_sphere(&mut self, spec: SphereSpec) -> Result<BodyId, SetupError> {
        self.check_capacity(1)?;
        let mat = self.material(spec.material)?;
        let r_m = Self::check_radius(spec.radius_m)?;
        let r_mm = r_m * LENGTH_M_TO_MM;
        let mass_g = mat.density_g_mm3 * 4.0 / 3.0 * PI * r_mm * r_mm * r_mm;
        let inertia = 0.4 * mass_g * r_mm * r_mm;
        let radius: S = quantise(r_mm, "sphere radius")?;
        let pos = q3(spec.position_m, LENGTH_M_TO_MM, "sphere position")?;
        let body = Body {
            position: pos,
            velocity: q3(spec.velocity_m_s, VELOCITY_M_S_TO_MM_MS, "sphere velocity")?,
            angular_velocity: q3(
                spec.angular_velocity_rad_s,
                ANGULAR_VELOCITY_RAD_S_TO_RAD_MS,
                "sphere angular velocity",
            )?,
            orientation: Quat::IDENTITY,
            mass: quantise(mass_g, "sphere mass")?,
            inv_mass: quantise(1.0 / mass_g, "sphere inverse mass")?,
            inertia: q3_nonzero([inertia; 3], "sphere inertia")?,
            inv_inertia: q3_nonzero([1.0 / inertia; 3], "sphere inverse inertia")?,
            first_sphere: self.n_spheres,
            sphere_count: 1,
            is_clump: false,
            ..Body::default()
        };
        let id = self.n_bodies;
        self.spheres[self.n_spheres as usize] = Sphere {
            position: pos,
            radius,
            offset: Vec3::ZERO,
            body: id,
            material: spec.material.0,
            near_walls: 0,
        };
        self.bodies[id as usize] = body;
        self.n_spheres += 1;
        self.n_bodies += 1;
        self.note_sphere(r_m, &mat);
        Ok(BodyId(id))
    }

    /// Add a clump, computing its mass properties by grid integration
    /// ([`clump_mass_properties`] with [`DEFAULT_MASS_GRID`]); returns its body id.
    pub fn add_clump(&mut self, spec: &ClumpSpec<'_>) -> Result<BodyId, SetupError> {
        if spec.spheres.is_empty() {
            return Err(SetupError::EmptyClump);
        }
        let mut ms: heapless::Vec<MassSphere, MAX_CLUMP_SPHERES> = heapless::Vec::new();
        for s in spec.spheres {
            let mat = self.material(s.material)?;
            ms.push(MassSphere {
                center_m: s.center_m,
                radius_m: s.radius_m,
                density_kg_m3: mat.density_g_mm3 / DENSITY_KG_M3_TO_G_MM3,
            })
            .map_err(|_| SetupError::Capacity {
                kind: CapacityKind::ClumpSpheres,
                capacity: MAX_CLUMP_SPHERES as u32,
            })?;
        }
        let props = clump_mass_properties(&ms, DEFAULT_MASS_GRID)?;
        self.add_clump_with_mass(spec, &props)
    }

    /// Add a clump with caller-given mass properties (e.g. from the host's shape tools).
    /// `props.center_of_mass_m` and `props.principal_axes` are in the same (world) frame as the
    /// sphere centres.
    pub fn add_clump_with_mass(
        &mut self,
        spec: &ClumpSpec<'_>,
        props: &MassProperties,
    ) -> Result<BodyId, SetupError> {
        if spec.spheres.is_empty() {
            return Err(SetupError::EmptyClump);
        }
        if spec.spheres.len() > MAX_CLUMP_SPHERES {
            return Err(SetupError::Capacity {
                kind: CapacityKind::ClumpSpheres,
                capacity: MAX_CLUMP_SPHERES as u32,
            });
        }
        self.check_capacity(spec.spheres.len())?;
        let m = finite(props.mass_kg, "clump mass")?;
        for &i in &props.principal_inertia_kg_m2 {
            finite(i, "clump inertia")?;
            if i <= 0.0 {
                return Err(SetupError::ZeroMassClump);
            }
        }
        if m <= 0.0 {
            return Err(SetupError::ZeroMassClump);
        }
        for x in props
            .principal_axes
            .iter()
            .chain(props.center_of_mass_m.iter())
        {
            finite(*x, "clump frame")?;
        }
        let qn = props.principal_axes;
        let nq = libm::sqrt(qn.iter().map(|x| x * x).sum::<f64>());
        if nq == 0.0 {
            return Err(SetupError::NonFinite {
                what: "clump orientation (zero quaternion)",
            });
        }
        let q = [qn[0] / nq, qn[1] / nq, qn[2] / nq, qn[3] / nq];
        let rot = quat_matrix_f64(q);
        let mut mats = heapless::Vec::<Material, MAX_CLUMP_SPHERES>::new();
        for s in spec.spheres {
            Self::check_radius(s.radius_m)?;
            for x in s.center_m {
                finite(x, "clump sphere centre")?;
            }
            let mat = self.material(s.material)?;
            let _ = mats.push(mat);
        }
        let mass_g = m * MASS_KG_TO_G;
        let inertia = props
            .principal_inertia_kg_m2
            .map(|i| i * INERTIA_KG_M2_TO_G_MM2);
        let id = self.n_bodies;
        let first = self.n_spheres;
        // Build the spheres first in a local buffer so a failure leaves the world unchanged.
        let mut new_spheres: heapless::Vec<Sphere<S>, MAX_CLUMP_SPHERES> = heapless::Vec::new();
        for s in spec.spheres {
            let d = [
                s.center_m[0] - props.center_of_mass_m[0],
                s.center_m[1] - props.center_of_mass_m[1],
                s.center_m[2] - props.center_of_mass_m[2],
            ];
            // Body-frame offset = Rᵀ d (R maps principal → world).
            let off = [
                rot[0][0] * d[0] + rot[1][0] * d[1] + rot[2][0] * d[2],
                rot[0][1] * d[0] + rot[1][1] * d[1] + rot[2][1] * d[2],
                rot[0][2] * d[0] + rot[1][2] * d[1] + rot[2][2] * d[2],
            ];
            new_spheres
                .push(Sphere {
                    position: q3(s.center_m, LENGTH_M_TO_MM, "clump sphere centre")?,
                    radius: quantise(s.radius_m * LENGTH_M_TO_MM, "clump sphere radius")?,
                    offset: q3(off, LENGTH_M_TO_MM, "clump sphere offset")?,
                    body: id,
                    material: s.material.0,
                    near_walls: 0,
                })
                .map_err(|_| SetupError::Capacity {
                    kind: CapacityKind::ClumpSpheres,
                    capacity: MAX_CLUMP_SPHERES as u32,
                })?;
        }
        let body = Body {
            position: q3(
                props.center_of_mass_m,
                LENGTH_M_TO_MM,
                "clump centre of mass",
            )?,
            velocity: q3(spec.velocity_m_s, VELOCITY_M_S_TO_MM_MS, "clump velocity")?,
            angular_velocity: q3(
                spec.angular_velocity_rad_s,
                ANGULAR_VELOCITY_RAD_S_TO_RAD_MS,
                "clump angular velocity",
            )?,
            orientation: Quat::from_f64(q),
            mass: quantise(mass_g, "clump mass")?,
            inv_mass: quantise(1.0 / mass_g, "clump inverse mass")?,
            inertia: q3_nonzero(inertia, "clump inertia")?,
            inv_inertia: q3_nonzero(inertia.map(|i| 1.0 / i), "clump inverse inertia")?,
            first_sphere: first,
            sphere_count: spec.spheres.len() as u32,
            is_clump: true,
            ..Body::default()
        };
        for (k, s) in new_spheres.iter().enumerate() {
            self.spheres[first as usize + k] = *s;
        }
        self.bodies[id as usize] = body;
        self.n_spheres += new_spheres.len() as u32;
        self.n_bodies += 1;
        for (s, mat) in spec.spheres.iter().zip(mats.iter()) {
            self.note_sphere(s.radius_m, mat);
        }
        Ok(BodyId(id))
    }

    /// Add a wall; returns its id.
    pub fn add_wall(&mut self, spec: WallSpec) -> Result<WallId, SetupError> {
        self.material(spec.material)?;
        let w = spec.build::<S>()?;
        let id = self.walls.len() as u32;
        self.walls.push(w).map_err(|_| SetupError::Capacity {
            kind: CapacityKind::Walls,
            capacity: MAX_WALLS as u32,
        })?;
        // The new wall is in no sphere's near-wall set yet.
        self.list_valid = false;
        Ok(WallId(id))
    }

    /// Change a wall's prescribed velocity, m/s (e.g. start lifting the repose cylinder).
    pub fn set_wall_velocity_m_s(&mut self, id: WallId, v: [f64; 3]) -> Result<(), SetupError> {
        let q = q3(v, VELOCITY_M_S_TO_MM_MS, "wall velocity")?;
        let w = self
            .walls
            .get_mut(id.0 as usize)
            .ok_or(SetupError::UnknownId { id: id.0 })?;
        w.velocity = q;
        Ok(())
    }

    /// Set the body's velocity (m/s) and angular velocity (rad/s), e.g. to launch a test.
    pub fn set_body_velocity(
        &mut self,
        id: BodyId,
        v_m_s: [f64; 3],
        w_rad_s: [f64; 3],
    ) -> Result<(), SetupError> {
        if id.0 >= self.n_bodies {
            return Err(SetupError::UnknownId { id: id.0 });
        }
        let v = q3(v_m_s, VELOCITY_M_S_TO_MM_MS, "body velocity")?;
        let w = q3(
            w_rad_s,
            ANGULAR_VELOCITY_RAD_S_TO_RAD_MS,
            "body angular velocity",
        )?;
        let b = &mut self.bodies[id.0 as usize];
        b.velocity = v;
        b.angular_velocity = w;
        Ok(())
    }

    /// Set the time step, s. Refused above [`max_stable_dt_s`] of the smallest sphere's
    /// Rayleigh time ([`crate::timestep`]).
    pub fn set_timestep_s(&mut self, dt_s: f64) -> Result<(), SetupError> {
        let dt_s = finite(dt_s, "time step")?;
        if dt_s <= 0.0 {
            return Err(SetupError::NonPositiveTimeStep { dt_s });
        }
        let max_s = self.max_timestep_s();
        if dt_s > max_s {
            return Err(SetupError::TimeStepTooLarge { dt_s, max_s });
        }
        self.dt = quantise(dt_s * TIME_S_TO_MS, "time step")?;
        self.dt_s = dt_s;
        Ok(())
    }

    /// Largest accepted time step, s (∞ while the world has no sphere).
    pub fn max_timestep_s(&self) -> f64 {
        max_stable_dt_s(self.min_rayleigh_s)
    }

    /// Smallest Rayleigh time over all spheres, s.
    pub fn min_rayleigh_time_s(&self) -> f64 {
        self.min_rayleigh_s
    }

    /// Time step, s.
    pub fn timestep_s(&self) -> f64 {
        self.dt_s
    }

    /// Simulated time, s.
    pub fn time_s(&self) -> f64 {
        self.time.to_f64() / TIME_S_TO_MS
    }

    /// Number of completed steps.
    pub fn step_count(&self) -> u64 {
        self.steps
    }

    /// Bodies in insertion order.
    pub fn bodies(&self) -> &[Body<S>] {
        &self.bodies[..self.n_bodies as usize]
    }

    /// One body (panics if `id` is out of range, like slice indexing).
    pub fn body(&self, id: BodyId) -> &Body<S> {
        &self.bodies()[id.0 as usize]
    }

    /// Spheres in insertion order.
    pub fn spheres(&self) -> &[Sphere<S>] {
        &self.spheres[..self.n_spheres as usize]
    }

    /// Walls in insertion order.
    pub fn walls(&self) -> &[Wall<S>] {
        &self.walls
    }

    /// Materials in insertion order.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// Gravity, mm/ms².
    pub fn gravity(&self) -> Vec3<S> {
        self.gravity
    }

    /// Contact-history slots per sphere.
    pub fn slots_per_sphere(&self) -> u32 {
        self.slots_per_sphere
    }

    /// All neighbour-list entries of sphere `s`, live or not (empty if out of range).
    fn list_entries(&self, s: u32) -> &[ContactSlot<S>] {
        if s >= self.n_spheres {
            return &[];
        }
        let n = self.spheres.len();
        let k = self.slots_per_sphere as usize;
        let cnt = self.index[(2 + self.current as usize) * n + s as usize] as usize;
        let base = self.current as usize * n * k + s as usize * k;
        &self.slots[base..base + cnt]
    }

    /// The live contact-history slots of sphere `s` (contacts of the last step that carry
    /// tangential history), in list order; empty if out of range. Neighbour-list entries of
    /// pairs that are not touching are skipped.
    pub fn contact_slots(&self, s: u32) -> impl Iterator<Item = ContactSlot<S>> + '_ {
        use crate::step::neighbour_list::LIVE_FLAG;
        self.list_entries(s)
            .iter()
            .filter(|c| c.partner & LIVE_FLAG != 0)
            .map(|c| ContactSlot {
                partner: c.partner & !LIVE_FLAG,
                state: c.state,
            })
    }

    /// Number of live contacts (sphere–sphere and sphere–wall) with stored history.
    pub fn contact_count(&self) -> u32 {
        (0..self.n_spheres)
            .map(|s| self.contact_slots(s).count() as u32)
            .sum()
    }

    /// Total kinetic energy (translational + rotational), mJ.
    pub fn kinetic_energy_mj(&self) -> f64 {
        self.bodies().iter().map(|b| b.kinetic_energy_mj()).sum()
    }
}

/// Rotation matrix of a unit quaternion `[w, x, y, z]` (f64, set-up only).
pub(crate) fn quat_matrix_f64(q: [f64; 4]) -> [[f64; 3]; 3] {
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
