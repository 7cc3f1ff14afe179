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
//! the pending formations). What set-up fixes (materials, pairs, effects, counts, the kind of
//! each wall, which sphere belongs to which body) is not restored but *checked*: reading
//! into a world set up differently fails with [`CheckpointError::Mismatch`], naming what
//! differs. A value no world could hold (a sphere id past the spheres, a list offset past
//! its half) fails with [`CheckpointError::Corrupt`], so a damaged stream cannot make the
//! step index out of bounds. On an error the world may be partly overwritten: set it up
//! again before using it.
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

use core::fmt;

use super::World;
use crate::body::{Body, Sphere};
use crate::bond::{Bonds, BreakCriterion};
use crate::num::{Quat, Scalar, Vec3};
use crate::wall::{Wall, WallShape};

/// First word of every checkpoint ("ARACHCKP" in ASCII).
pub const MAGIC: u64 = u64::from_be_bytes(*b"ARACHCKP");
/// Layout version; a reader refuses any other.
pub const VERSION: u64 = 1;

/// Why a checkpoint could not be read (or, for [`CheckpointError::Refused`], written).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CheckpointError {
    /// The world was set up differently from the one that wrote the checkpoint.
    Mismatch {
        /// What differs.
        what: &'static str,
        /// The world's value.
        world: u64,
        /// The checkpoint's value.
        checkpoint: u64,
    },
    /// A value no world could hold.
    Corrupt {
        /// Which value.
        what: &'static str,
        /// The value read.
        value: u64,
    },
    /// The stream ended early.
    Truncated,
    /// The sink refused a word (a full buffer or a failed write).
    Refused,
}

impl fmt::Display for CheckpointError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            CheckpointError::Mismatch {
                what,
                world,
                checkpoint,
            } => write!(
                f,
                "the checkpoint was written by a world set up differently: {what} is {checkpoint} \
                 there and {world} here"
            ),
            CheckpointError::Corrupt { what, value } => {
                write!(
                    f,
                    "the checkpoint is damaged: {what} = {value} is impossible"
                )
            }
            CheckpointError::Truncated => write!(f, "the checkpoint ends early"),
            CheckpointError::Refused => write!(f, "the checkpoint's words could not be written"),
        }
    }
}

/// A stream of state words, in either direction.
pub trait StateWords {
    /// A changing word: a writer records `*w`, a reader replaces it with the next word.
    fn word(&mut self, w: &mut u64) -> Result<(), CheckpointError>;
    /// A word set-up fixes (a count, a kind, a material): a writer records it, a reader
    /// checks that the next word equals it.
    fn same(&mut self, w: u64, what: &'static str) -> Result<(), CheckpointError>;
}

/// Writes every word to a sink (a `Vec::push`, a file's buffered writer).
pub struct WordWriter<F: FnMut(u64)> {
    sink: F,
}

impl<F: FnMut(u64)> WordWriter<F> {
    /// A writer into `sink`.
    pub fn new(sink: F) -> Self {
        WordWriter { sink }
    }
}

impl<F: FnMut(u64)> StateWords for WordWriter<F> {
    fn word(&mut self, w: &mut u64) -> Result<(), CheckpointError> {
        (self.sink)(*w);
        Ok(())
    }
    fn same(&mut self, w: u64, _: &'static str) -> Result<(), CheckpointError> {
        (self.sink)(w);
        Ok(())
    }
}

/// Reads words from an iterator.
pub struct WordReader<I: Iterator<Item = u64>> {
    words: I,
}

impl<I: Iterator<Item = u64>> WordReader<I> {
    /// A reader over `words`.
    pub fn new(words: I) -> Self {
        WordReader { words }
    }
}

impl<I: Iterator<Item = u64>> StateWords for WordReader<I> {
    fn word(&mut self, w: &mut u64) -> Result<(), CheckpointError> {
        *w = self.words.next().ok_or(CheckpointError::Truncated)?;
        Ok(())
    }
    fn same(&mut self, w: u64, what: &'static str) -> Result<(), CheckpointError> {
        let c = self.words.next().ok_or(CheckpointError::Truncated)?;
        if c != w {
            return Err(CheckpointError::Mismatch {
                what,
                world: w,
                checkpoint: c,
            });
        }
        Ok(())
    }
}

/// A scalar's raw bits.
pub(crate) fn scalar<S: Scalar>(v: &mut impl StateWords, x: &mut S) -> Result<(), CheckpointError> {
    let mut w = x.to_bits();
    v.word(&mut w)?;
    *x = S::from_bits(w);
    Ok(())
}

/// A vector's three raw words.
pub(crate) fn vec3<S: Scalar>(
    v: &mut impl StateWords,
    x: &mut Vec3<S>,
) -> Result<(), CheckpointError> {
    scalar(v, &mut x.x)?;
    scalar(v, &mut x.y)?;
    scalar(v, &mut x.z)
}

fn quat<S: Scalar>(v: &mut impl StateWords, q: &mut Quat<S>) -> Result<(), CheckpointError> {
    for x in [&mut q.w, &mut q.x, &mut q.y, &mut q.z] {
        scalar(v, x)?;
    }
    Ok(())
}

/// A changing count or id, read only up to `below` (exclusive).
pub(crate) fn index(
    v: &mut impl StateWords,
    x: &mut u32,
    below: u64,
    what: &'static str,
) -> Result<(), CheckpointError> {
    let mut w = *x as u64;
    v.word(&mut w)?;
    if w >= below {
        return Err(CheckpointError::Corrupt { what, value: w });
    }
    *x = w as u32;
    Ok(())
}

/// A changing flag (0 or 1).
pub(crate) fn flag(
    v: &mut impl StateWords,
    x: &mut bool,
    what: &'static str,
) -> Result<(), CheckpointError> {
    let mut w = *x as u64;
    v.word(&mut w)?;
    if w > 1 {
        return Err(CheckpointError::Corrupt { what, value: w });
    }
    *x = w == 1;
    Ok(())
}

impl<S: Scalar> World<'_, S> {
    /// Write the world's changing state (module docs). The world is not changed: `&mut`
    /// because writing and reading share one field list.
    pub fn write_checkpoint<F: FnMut(u64)>(
        &mut self,
        out: &mut WordWriter<F>,
    ) -> Result<(), CheckpointError> {
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
    index(v, &mut t.next_id, u32::MAX as u64 + 1, "the next bond id")?;
    for b in t.bonds[..t.n as usize].iter_mut() {
        index(v, &mut b.id, u32::MAX as u64 + 1, "a bond's id")?;
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
        index(v, &mut r.bond_id, u32::MAX as u64 + 1, "a break's bond id")?;
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
