//! The world's set-up API: materials and pairs, gravity, bodies (spheres and clumps), walls,
//! velocities and the time step. Every input is SI, validated and quantised here; a refused
//! input changes nothing.

use super::World;
use crate::body::clump::{ClumpSpec, MAX_CLUMP_SPHERES};
use crate::body::{
    clump_mass_properties, Body, BodyId, MassProperties, MassSphere, Sphere, SphereSpec,
    DEFAULT_MASS_GRID,
};
use crate::error::{CapacityKind, SetupError};
use crate::material::{finite, Material, MaterialId, MaterialSpec, PoissonRange, MAX_MATERIALS};
use crate::num::quantise::quantise;
use crate::num::{Quat, Scalar, Vec3};
use crate::pair::{PairParams, PairSpec};
use crate::step::multirate::MAX_SLOW_STRIDE;
use crate::timestep::rayleigh_time_s;
use crate::units::*;
use crate::wall::{q3, WallId, WallSpec, MAX_WALLS};
use core::f64::consts::PI;

/// Quantise a vector whose components must not round to zero (inertia and its inverse).
fn q3_nonzero<S: Scalar>(v: [f64; 3], what: &'static str) -> Result<Vec3<S>, SetupError> {
    Ok(Vec3::new(
        quantise(v[0], what)?,
        quantise(v[1], what)?,
        quantise(v[2], what)?,
    ))
}

impl<S: Scalar> World<'_, S> {
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
    /// Errors: an invalid spec, an unknown material, a constant outside the fixed-point range,
    /// or LIGGGHTS' `epsd2` rolling convention (which keeps a torque per contact) in a world
    /// without an effect-history arena ([`crate::body::StorageLengths::with_effects`]).
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
        // Each constant with the name and value (internal units) a message should give: the
        // user's own μs and μr, else the modulus-derived constant (it once named 8G* whatever
        // failed, so μs = 1e300 read "pair constant = 15.07").
        let e_star = p.e_star_mpa;
        let named: [(&'static str, S, f64); 6] = [
            (
                "(4/3)E* of the pair, MPa",
                p.hertz.four_thirds_e_star,
                4.0 / 3.0 * e_star,
            ),
            (
                "normal damping of the pair's E*, MPa",
                p.normal_damping.coef,
                e_star,
            ),
            (
                "8G* of the pair, MPa",
                p.tangential.eight_g_star,
                8.0 * p.g_star_mpa,
            ),
            (
                "tangential damping of the pair's G*, MPa",
                p.tangential_damping.coef,
                p.g_star_mpa,
            ),
            ("sliding friction μs", p.coulomb.mu, spec.friction),
            ("rolling friction μr", p.rolling.mu_r, spec.rolling_friction),
        ];
        if let Some(&(what, _, value)) = named.iter().find(|(_, v, _)| !v.is_valid()) {
            return Err(SetupError::NotRepresentable { what, value });
        }
        if p.needs_effect_history() && !self.list.has_effect_history() {
            return Err(SetupError::Capacity {
                kind: CapacityKind::EffectHistory,
                capacity: 0,
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
        self.list.invalidate();
        let r = S::from_f64(radius_m * LENGTH_M_TO_MM);
        if r > self.max_radius {
            self.max_radius = r;
        }
        let t = sphere_rayleigh_s(radius_m, mat);
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
        let mut sphere = Sphere {
            position: pos,
            radius,
            body: id,
            material: spec.material.0,
            ..Sphere::default()
        };
        sphere.sync_motion(&body);
        self.spheres[self.n_spheres as usize] = sphere;
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
                    ..Sphere::default()
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
            let mut s = *s;
            s.sync_motion(&body);
            self.spheres[first as usize + k] = s;
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
        // The new wall has no entries in the neighbour list yet.
        self.list.invalidate();
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

    /// Spin a wall about its own axis of symmetry at `omega_rad_s` (rad/s, right-handed
    /// about the axis of [`crate::wall::WallShape::spin_axis`]: a cylinder's axis, a plane's
    /// normal through its point), e.g. a rotating drum and its end plates. The shape stays
    /// where it is; its surface moves, and contacts see that motion. 0 stops it. A box cannot
    /// spin (its shape would change): [`SetupError::BadWall`].
    pub fn set_wall_spin_rad_s(&mut self, id: WallId, omega_rad_s: f64) -> Result<(), SetupError> {
        let omega = finite(omega_rad_s, "wall spin")?;
        let w = self
            .walls
            .get_mut(id.0 as usize)
            .ok_or(SetupError::UnknownId { id: id.0 })?;
        if w.shape.spin_axis().is_none() && omega != 0.0 {
            return Err(SetupError::BadWall {
                reason: "a box cannot spin about an axis of symmetry",
            });
        }
        w.spin = quantise(omega * ANGULAR_VELOCITY_RAD_S_TO_RAD_MS, "wall spin")?;
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
        self.sync_spheres_of(id.0 as usize);
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

    /// Make body `id` kinematic: it then moves only with its prescribed velocity and angular
    /// velocity, whatever forces act on it (a clamp, a gripper pulling at constant speed).
    /// Its inverse mass and inverse inertia become zero, so the integrator's kick vanishes
    /// exactly, and gravity, which the integrator adds as an acceleration, is skipped too.
    /// Its force and torque still show what the rest of the world exerts on it (gravity
    /// included), which is how a test reads the reaction of a clamp or the pull of a gripper
    /// (other kinematic bodies and walls only while [`World::set_prescribed_contacts`] is on).
    /// Keep its velocities with [`World::set_body_velocity`]. Irreversible.
    pub fn set_body_kinematic(&mut self, id: BodyId) -> Result<(), SetupError> {
        if id.0 >= self.n_bodies {
            return Err(SetupError::UnknownId { id: id.0 });
        }
        let b = &mut self.bodies[id.0 as usize];
        b.inv_mass = S::ZERO;
        b.inv_inertia = Vec3::ZERO;
        self.sync_spheres_of(id.0 as usize);
        // Its pairs with other kinematic bodies and walls may leave the list.
        self.list.invalidate();
        Ok(())
    }

    /// Let kinematic body `id` go: forces and gravity move it again, from its present
    /// velocities (a taproot cut by a digging shovel). Its inverse mass and inverse inertia
    /// are the reciprocals of its stored mass (g) and principal moments (g·mm²), so a body
    /// made kinematic and let go has the inverses it had to within their quantisation.
    /// A body that was never kinematic is left as it is.
    pub fn set_body_dynamic(&mut self, id: BodyId) -> Result<(), SetupError> {
        if id.0 >= self.n_bodies {
            return Err(SetupError::UnknownId { id: id.0 });
        }
        let b = &self.bodies[id.0 as usize];
        if b.inv_mass != S::ZERO {
            return Ok(());
        }
        let inv_mass = quantise(1.0 / b.mass.to_f64(), "inverse mass")?;
        let inertia = [b.inertia.x, b.inertia.y, b.inertia.z].map(|i| 1.0 / i.to_f64());
        let inv_inertia = q3_nonzero(inertia, "inverse inertia")?;
        let b = &mut self.bodies[id.0 as usize];
        b.inv_mass = inv_mass;
        b.inv_inertia = inv_inertia;
        self.sync_spheres_of(id.0 as usize);
        // Its pairs with kinematic bodies and walls may enter the list.
        self.list.invalidate();
        Ok(())
    }

    /// Whether contacts whose sides all move as prescribed are evaluated: between two
    /// kinematic bodies, and between a kinematic body and a wall. On by default, so that a
    /// clamp pressed on a fixed part reports the reaction. A machine of kinematic parts
    /// running over a floor (a harvester) turns it off: those contacts move nothing, and
    /// parts with long levers take the checked terms, which cost a 0.3 m field about an
    /// eighth of its step (`core/API_NOTES.md`). Such pairs then get no neighbour-list entry,
    /// and a kinematic body's force shows only what the bodies that move exert on it. A
    /// set-up value that a checkpoint does not record: read one into a world set up the same
    /// way.
    pub fn set_prescribed_contacts(&mut self, on: bool) {
        if self.list.prescribed_pairs != on {
            self.list.prescribed_pairs = on;
            self.list.invalidate();
        }
    }

    /// Multi-rate stepping ([`crate::step::multirate`]): slow bodies move once every
    /// `stride` steps by the long step stride·dt. 1 (the default) is single-rate stepping.
    /// Refused outside 1..=[`MAX_SLOW_STRIDE`], and when the long step would exceed the slow
    /// spheres' stable bound ([`crate::timestep`]; checked again at every step, since the
    /// time step may change). A set-up value that a checkpoint does not record.
    pub fn set_slow_stride(&mut self, stride: u32) -> Result<(), SetupError> {
        if !(1..=MAX_SLOW_STRIDE).contains(&stride) {
            return Err(SetupError::BadSlowStride {
                stride,
                max: MAX_SLOW_STRIDE,
            });
        }
        let old = self.slow_stride;
        self.slow_stride = stride;
        if let Err(e) = self.check_long_step() {
            self.slow_stride = old;
            return Err(e);
        }
        self.list.set_multirate(stride > 1);
        Ok(())
    }

    /// Mark body `id` slow (`true`) or not: a slow body moves once a cycle by the long step,
    /// and its contacts with other slow bodies are evaluated once a cycle
    /// ([`crate::step::multirate`]). Without a stride above 1 the mark changes nothing. A
    /// set-up value that a checkpoint does not record.
    pub fn set_body_slow(&mut self, id: BodyId, slow: bool) -> Result<(), SetupError> {
        if id.0 >= self.n_bodies {
            return Err(SetupError::UnknownId { id: id.0 });
        }
        let b = &self.bodies[id.0 as usize];
        let spheres = b.first_sphere as usize..(b.first_sphere + b.sphere_count) as usize;
        let mut rayleigh = self.min_rayleigh_slow_s;
        if slow {
            for s in &self.spheres[spheres.clone()] {
                let mat = &self.materials[s.material as usize];
                rayleigh = rayleigh.min(sphere_rayleigh_s(s.radius_m(), mat));
            }
        }
        let old = core::mem::replace(&mut self.min_rayleigh_slow_s, rayleigh);
        if let Err(e) = self.check_long_step() {
            self.min_rayleigh_slow_s = old;
            return Err(e);
        }
        if self.bodies[id.0 as usize].slow != slow {
            // The list flags and orders slow pairs (`SLOW_PAIR_FLAG`): rebuild it.
            self.list.invalidate();
            self.slow_runs.invalidate();
        }
        self.bodies[id.0 as usize].slow = slow;
        for s in &mut self.spheres[spheres] {
            s.slow = slow;
        }
        Ok(())
    }

    /// The long step stride·dt against the slow spheres' stable bound.
    fn check_long_step(&self) -> Result<(), SetupError> {
        match self.long_step_excess() {
            Some((dt_s, max_s)) => Err(SetupError::TimeStepTooLarge { dt_s, max_s }),
            None => Ok(()),
        }
    }

    /// The long step stride·dt and the slow spheres' bound, s, when it exceeds the bound.
    pub(crate) fn long_step_excess(&self) -> Option<(f64, f64)> {
        let long_s = self.dt_s * f64::from(self.slow_stride);
        let max_s = self.max_slow_timestep_s();
        (self.slow_stride > 1 && long_s > max_s).then_some((long_s, max_s))
    }

    /// Refresh the motion snapshot of body `b`'s spheres ([`Sphere::sync_motion`]).
    fn sync_spheres_of(&mut self, b: usize) {
        let body = &self.bodies[b];
        let first = body.first_sphere as usize;
        for s in &mut self.spheres[first..first + body.sphere_count as usize] {
            s.sync_motion(body);
        }
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

/// The Rayleigh time of a sphere of radius `radius_m` (m) and material `mat`, s.
fn sphere_rayleigh_s(radius_m: f64, mat: &Material) -> f64 {
    rayleigh_time_s(
        radius_m,
        mat.density_g_mm3 / DENSITY_KG_M3_TO_G_MM3,
        mat.youngs_modulus_mpa / STRESS_PA_TO_MPA,
        mat.poisson,
    )
}
