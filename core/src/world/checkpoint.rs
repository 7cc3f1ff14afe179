//! Checkpoints: a world's whole changing state as a stream of 64-bit words, written by one
//! run and read back into a world set up the same way, which then steps on bit for bit as
//! the first would have (LIGGGHTS' `write_restart`, EDEM's saved time steps).
//!
//! **Why.** A seed-scale harvest pass is hours of stepping; a checkpoint lets it stop and go
//! on (another session, another machine of any kind: the words are the scalars' raw bits),
//! and lets many runs start from one settled bed.
//!
//! **What is in it.** Everything a step reads and set-up does not fix: the step count and
//! time; each body's and sphere's motion, mass properties (a kinematic body let go changes
//! them) and force sums; the walls' positions, velocities and last forces; the neighbour
//! list as it stands (its contact history, and when it will next be rebuilt, so that even
//! `f64` worlds resume exactly); and the bond table (live bonds, the break log and count,
//! the pending formations). What set-up fixes is not restored. Its shape is *checked* (the
//! counts of bodies, spheres, walls and materials, each sphere's body, material and radius,
//! each wall's kind, the time step, the bond sets' tags and the capacities): reading into a
//! world set up differently fails with [`CheckpointError::Mismatch`], naming what differs.
//! The pair and effect parameters and the bond sets' strengths are not in the words: the
//! caller answers for them (the host hashes its input files). A value no world could hold (a sphere id past the spheres, a list offset past
//! its half) fails with [`CheckpointError::Corrupt`], so a damaged stream cannot make the
//! step index out of bounds. On an error the world may be partly overwritten: set it up
//! again before using it.
//!
//! A world with slow bodies ([`crate::step::multirate`]) writes one only between cycles
//! ([`CheckpointError::MidCycle`]): within a cycle, the slow bodies' sums are not in the words.
//!
//! One field list serves both directions ([`StateWords`]: a writer records each word, a
//! reader replaces it), so writing and reading cannot disagree on the order.
//!
//! ```
//! use arachis_core::prelude::*;
//! use arachis_core::owned::OwnedStorage;
//! use arachis_core::scenario::BenchBed;
//! use arachis_core::world::checkpoint::{WordReader, WordWriter};
//!
//! let bed = BenchBed { particles: 60, seed: 1 };
//! let mut first = OwnedStorage::<Fx>::new(bed.storage_lengths());
//! let mut w = bed.build(first.storage()).unwrap();
//! w.run(300).unwrap();
//! let mut words = Vec::new();
//! w.write_checkpoint(&mut WordWriter::new(|x| words.push(x))).unwrap();
//! w.run(200).unwrap();
//!
//! // The same set-up, then the checkpoint: it goes on exactly as the first did.
//! let mut second = OwnedStorage::<Fx>::new(bed.storage_lengths());
//! let mut v = bed.build(second.storage()).unwrap();
//! v.read_checkpoint(&mut WordReader::new(words.iter().copied())).unwrap();
//! v.run(200).unwrap();
//! assert_eq!(v.digest(), w.digest());
//! ```

use super::World;
use crate::body::{Body, Sphere};
use crate::bond::{Bonds, BreakCriterion};
use crate::num::Scalar;
use crate::state_words::{index, quat, scalar, vec3};
pub use crate::state_words::{CheckpointError, StateWords, WordReader, WordWriter, MAGIC, VERSION};
use crate::wall::{Wall, WallShape};

impl<S: Scalar> World<'_, S> {
    /// Write the world's changing state (module docs). The world is not changed: `&mut`
    /// because writing and reading share one field list.
    pub fn write_checkpoint<F: FnMut(u64)>(
        &mut self,
        out: &mut WordWriter<F>,
    ) -> Result<(), CheckpointError> {
        let stride = self.slow_stride;
        let slow = self.bodies[..self.n_bodies as usize].iter().any(|b| b.slow);
        if slow && self.steps % u64::from(stride) != 0 {
            return Err(CheckpointError::MidCycle {
                steps: self.steps,
                stride,
            });
        }
        self.exchange(out)
    }

    /// Replace the world's changing state by a checkpoint's; the world must have been set up
    /// as the writer's was (module docs).
    pub fn read_checkpoint<I: Iterator<Item = u64>>(
        &mut self,
        input: &mut WordReader<I>,
    ) -> Result<(), CheckpointError> {
        self.exchange(input)
    }

    fn exchange(&mut self, v: &mut impl StateWords) -> Result<(), CheckpointError> {
        v.same(MAGIC, "the file kind")?;
        v.same(VERSION, "the checkpoint version")?;
        v.same(S::Q32_32 as u64, "the scalar (1 fixed point, 0 f64)")?;
        v.same(self.n_bodies as u64, "the body count")?;
        v.same(self.n_spheres as u64, "the sphere count")?;
        v.same(self.walls.len() as u64, "the wall count")?;
        v.same(self.materials.len() as u64, "the material count")?;
        v.same(self.dt.to_bits(), "the time step (raw bits)")?;
        v.word(&mut self.steps)?;
        scalar(v, &mut self.time)?;
        vec3(v, &mut self.gravity)?;
        for b in self.bodies[..self.n_bodies as usize].iter_mut() {
            body(v, b)?;
        }
        for s in self.spheres[..self.n_spheres as usize].iter_mut() {
            sphere(v, s)?;
        }
        for w in self.walls.iter_mut() {
            wall(v, w)?;
        }
        let walls = self.walls.len() as u32;
        self.list.exchange(v, self.n_spheres, walls)?;
        // The words do not hold the slow-pair flags of a multi-rate world's list, and the
        // exchange clears them: set them again, for the writer as for the reader.
        self.list
            .order_live_slow_pairs(&self.spheres[..self.n_spheres as usize]);
        bonds(v, &mut self.bond_table, self.n_spheres)
    }
}

fn body<S: Scalar>(v: &mut impl StateWords, b: &mut Body<S>) -> Result<(), CheckpointError> {
    v.same(b.first_sphere as u64, "a body's first sphere")?;
    v.same(b.sphere_count as u64, "a body's sphere count")?;
    v.same(b.is_clump as u64, "whether a body is a clump")?;
    for x in [&mut b.position, &mut b.velocity, &mut b.angular_velocity] {
        vec3(v, x)?;
    }
    quat(v, &mut b.orientation)?;
    scalar(v, &mut b.mass)?;
    scalar(v, &mut b.inv_mass)?;
    for x in [
        &mut b.inertia,
        &mut b.inv_inertia,
        &mut b.force,
        &mut b.torque,
    ] {
        vec3(v, x)?;
    }
    scalar(v, &mut b.roll_torque)
}

fn sphere<S: Scalar>(v: &mut impl StateWords, s: &mut Sphere<S>) -> Result<(), CheckpointError> {
    v.same(s.body as u64, "a sphere's body")?;
    v.same(s.material as u64, "a sphere's material")?;
    v.same(s.radius.to_bits(), "a sphere's radius (raw bits)")?;
    for x in [
        &mut s.position,
        &mut s.velocity,
        &mut s.spin,
        &mut s.arm,
        &mut s.offset,
    ] {
        vec3(v, x)?;
    }
    scalar(v, &mut s.mass)?;
    scalar(v, &mut s.inv_mass)
}

fn wall<S: Scalar>(v: &mut impl StateWords, w: &mut Wall<S>) -> Result<(), CheckpointError> {
    v.same(w.material as u64, "a wall's material")?;
    match &mut w.shape {
        WallShape::Plane(p) => {
            v.same(1, "a wall's kind (1 plane)")?;
            vec3(v, &mut p.point)?;
            vec3(v, &mut p.normal)?;
        }
        WallShape::Cylinder(c) => {
            v.same(2, "a wall's kind (2 cylinder)")?;
            v.same(c.finite as u64, "whether a cylinder is finite")?;
            vec3(v, &mut c.base)?;
            vec3(v, &mut c.axis)?;
            scalar(v, &mut c.radius)?;
            scalar(v, &mut c.length)?;
        }
        WallShape::AaBox(b) => {
            v.same(3, "a wall's kind (3 box)")?;
            vec3(v, &mut b.min)?;
            vec3(v, &mut b.max)?;
        }
        WallShape::OrificePlate(o) => {
            v.same(4, "a wall's kind (4 orifice plate)")?;
            vec3(v, &mut o.centre)?;
            vec3(v, &mut o.normal)?;
            scalar(v, &mut o.hole_radius)?;
        }
    }
    vec3(v, &mut w.velocity)?;
    scalar(v, &mut w.spin)?;
    vec3(v, &mut w.force)
}

/// Bound of an id that may take any `u32` value.
const ANY_U32: u64 = u32::MAX as u64 + 1;

/// The bond table: the sets are set-up (checked by tag), the rest changes as bonds break.
fn bonds<S: Scalar>(
    v: &mut impl StateWords,
    t: &mut Bonds<'_, S>,
    spheres: u32,
) -> Result<(), CheckpointError> {
    v.same(t.sets.len() as u64, "the bond-set count")?;
    for p in t.sets.iter() {
        v.same(p.tag as u64, "a bond set's tag")?;
    }
    v.same(t.bonds.len() as u64, "the bond capacity")?;
    v.same(t.log.len() as u64, "the break-log capacity")?;
    let sets = t.sets.len() as u64;
    index(v, &mut t.n, t.bonds.len() as u64 + 1, "the bond count")?;
    index(v, &mut t.next_id, ANY_U32, "the next bond id")?;
    for b in t.bonds[..t.n as usize].iter_mut() {
        index(v, &mut b.id, ANY_U32, "a bond's id")?;
        index(v, &mut b.sphere_a, spheres as u64, "a bond's first sphere")?;
        index(v, &mut b.sphere_b, spheres as u64, "a bond's second sphere")?;
        let mut set = b.set as u32;
        index(v, &mut set, sets, "a bond's set")?;
        b.set = set as u16;
        for x in [&mut b.normal_disp, &mut b.twist, &mut b.normal_force] {
            scalar(v, x)?;
        }
        scalar(v, &mut b.twisting_moment)?;
        for x in [
            &mut b.tangential_disp,
            &mut b.bend,
            &mut b.tangential_force,
            &mut b.bending_moment,
            &mut b.normal,
        ] {
            vec3(v, x)?;
        }
    }
    index(
        v,
        &mut t.n_log,
        t.log.len() as u64 + 1,
        "the logged break count",
    )?;
    for r in t.log[..t.n_log as usize].iter_mut() {
        v.word(&mut r.step)?;
        scalar(v, &mut r.time_ms)?;
        index(v, &mut r.bond_id, ANY_U32, "a break's bond id")?;
        index(v, &mut r.sphere_a, spheres as u64, "a break's first sphere")?;
        index(
            v,
            &mut r.sphere_b,
            spheres as u64,
            "a break's second sphere",
        )?;
        let mut tag = r.tag as u32;
        index(v, &mut tag, u16::MAX as u64 + 1, "a break's set tag")?;
        r.tag = tag as u16;
        let mut code = r.criterion.code() as u32;
        index(v, &mut code, 3, "a break's criterion")?;
        r.criterion = BreakCriterion::from_code(code as u8);
        scalar(v, &mut r.sigma_max_mpa)?;
        scalar(v, &mut r.tau_max_mpa)?;
    }
    v.word(&mut t.breaks_total)?;
    index(
        v,
        &mut t.last_partner,
        spheres as u64 + 1,
        "the bonds' last partner",
    )?;
    pending_formations(v, t)
}

/// Scheduled formations run and leave the schedule in order, so the pending ones are a
/// subsequence of set-up's: a reader keeps those whose times the checkpoint lists.
fn pending_formations<S: Scalar>(
    v: &mut impl StateWords,
    t: &mut Bonds<'_, S>,
) -> Result<(), CheckpointError> {
    let mut n = t.schedule.len() as u32;
    index(
        v,
        &mut n,
        t.schedule.len() as u64 + 1,
        "the pending formation count",
    )?;
    let mut kept = 0;
    for _ in 0..n {
        // The first set-up entry at or after `kept` with this time.
        let mut time = t.schedule.get(kept).map_or(0, |s| s.time.to_bits());
        v.word(&mut time)?;
        let Some(at) = (kept..t.schedule.len()).find(|&k| t.schedule[k].time.to_bits() == time)
        else {
            return Err(CheckpointError::Corrupt {
                what: "a pending formation's time (raw bits)",
                value: time,
            });
        };
        for _ in kept..at {
            t.schedule.remove(kept);
        }
        kept += 1;
    }
    t.schedule.truncate(kept);
    Ok(())
}
