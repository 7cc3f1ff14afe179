//! Integration: symplectic Euler (kick then drift), the leapfrog form of velocity Verlet:
//! v ← v + (F_c/m + g)·dt, x ← x + v·dt (F_c the sum of contact, bond and drag forces;
//! gravity as g itself). It needs one force evaluation per step and is symplectic, so an
//! elastic system keeps its energy bounded (the energy test checks 0.1 % over 1e5 steps).
//!
//! Rotation:
//! - single spheres (isotropic): ω ← ω + (T/I)·dt; orientation is not integrated;
//! - clumps: Euler's equations in the principal frame, ω_b ← ω_b + I⁻¹(T_b − ω_b × Iω_b)·dt,
//!   then q ← normalise(q + ½dt ω⊗q) and the spheres are re-placed from their offsets.
//!
//! Rolling friction (seed 000 eq. (7)) arrives as a magnitude Tr = Σ μr Fn Ri per body, to be
//! applied along −ω̂ with ω̂ taken at the start of the step. Its angular impulse is capped so that
//! the ω component along ω̂ goes to zero at most, never negative: the torque never reverses ω
//! within a step (DESIGN §2).
//!
//! Single spheres move in unchecked arithmetic while their loads and velocities lie inside
//! bounds that exclude overflow ([`single_sphere`]); others, and clumps, in the checked
//! arithmetic.
//!
//! The stage runs in parts over disjoint body ranges ([`IntegratePart`]). Each body first
//! gathers its force sums from every accumulator arena of the contact stage (and clears them
//! for the next step), then moves. A kinematic body (inverse mass zero) keeps its velocity:
//! no contact force and no gravity.

mod rigid_body;
mod single_sphere;

use crate::body::{Body, BodyForce, Loads, Sphere};
use crate::error::{Other, Stage, StepError};
use crate::num::{Envelope, Scalar, Vec3};
use crate::step::multirate::{cycle_mean, Cycle};
use core::ops::Range;
use rigid_body::{clump_envelope, state_of, step_body, Motion, OFFSET_BITS};
use single_sphere::move_sphere;

/// One part of the integration stage: a range of bodies and their spheres, with room for
/// `SUMS` accumulator arenas (the world's and one per contact part that wrote beyond its
/// range; sized by the step, see `World::staged`).
pub(crate) struct IntegratePart<'w, S: Scalar, const SUMS: usize> {
    /// Id of the first body.
    pub first_body: usize,
    /// The bodies.
    pub bodies: &'w mut [Body<S>],
    /// Id of the first sphere of the first body.
    pub first_sphere: usize,
    /// The spheres of those bodies.
    pub spheres: &'w mut [Sphere<S>],
    /// The accumulators of these bodies: the world's and each contact part's private arena
    /// (those that touched the range), with the body-id range each covers.
    pub sums: heapless::Vec<(Range<usize>, &'w mut [BodyForce<S>]), SUMS>,
    /// Runs of consecutive slow bodies of the whole world, body ids in increasing order
    /// (`crate::step::multirate::SlowRuns`; empty in a single-rate world).
    pub slow_runs: &'w [Range<usize>],
    /// Largest sphere displacement of the step (L1 norm ≥ Euclidean), mm.
    pub max_disp: S,
    /// The first error, if any.
    pub result: Result<(), StepError>,
}

impl<S: Scalar, const SUMS: usize> IntegratePart<'_, S, SUMS> {
    /// Move every body of the part by one step `dt` (ms) under gravity `g` (mm/ms²); a slow
    /// body only at the end of its `cycle`, by the long step ([`crate::step::multirate`]).
    pub(crate) fn run(&mut self, dt: S, g: Vec3<S>, cycle: &Cycle<S>) {
        // One instance for single-rate worlds, whose time step is the same for every body.
        self.result = if cycle.multirate() {
            self.integrate::<true>(dt, g, cycle)
        } else {
            self.integrate::<false>(dt, g, cycle)
        };
    }

    /// Within a cycle, slow bodies keep their sums: the contact parts' arenas of bodies
    /// `ids` are added to their own accumulators and cleared (they must be zero between
    /// steps). [`Self::take_sums`] keeps its own loop: written as this and a take, it cost
    /// the DESIGN §8 pour 1.35 % more instructions.
    #[inline(always)]
    fn keep_sums(&mut self, ids: Range<usize>) {
        let Some(((_, own), beyond)) = self.sums.split_first_mut() else {
            return;
        };
        for (range, arena) in beyond.iter_mut() {
            for id in ids.start.max(range.start)..ids.end.min(range.end) {
                own[id - self.first_body].merge(&core::mem::take(&mut arena[id - range.start]));
            }
        }
    }

    /// Where the run of slow bodies that holds body `id` ends (clipped to the part), if one
    /// does; `next` is the first run not yet passed, and moves on with `id`.
    #[inline(always)]
    fn slow_run_end(&self, id: usize, next: &mut usize) -> Option<usize> {
        while self.slow_runs.get(*next).is_some_and(|r| r.end <= id) {
            *next += 1;
        }
        let run = self.slow_runs.get(*next)?;
        (run.start <= id).then(|| run.end.min(self.first_body + self.bodies.len()))
    }

    /// The summed loads of body `id`, with every accumulator of it cleared. The first arena
    /// is the part's own, which holds every body of the part: the contact parts' arenas are
    /// added into it, and it is read and cleared in place (returning the accumulator by
    /// value cost a copy of its 88 bytes a body).
    #[inline(always)]
    fn take_sums(&mut self, id: usize) -> Loads<S> {
        let Some(((_, own), beyond)) = self.sums.split_first_mut() else {
            return BodyForce::<S>::default().values();
        };
        let total = &mut own[id - self.first_body];
        for (range, arena) in beyond.iter_mut() {
            if range.contains(&id) {
                total.merge(&core::mem::take(&mut arena[id - range.start]));
            }
        }
        let loads = total.values();
        *total = BodyForce::default();
        loads
    }

    fn integrate<const MULTIRATE: bool>(
        &mut self,
        dt: S,
        g: Vec3<S>,
        cycle: &Cycle<S>,
    ) -> Result<(), StepError> {
        let mut max_disp = S::ZERO;
        let mut next_run = 0;
        let mut k = 0;
        while k < self.bodies.len() {
            let id = self.first_body + k;
            if MULTIRATE && !cycle.slow_moves {
                if let Some(end) = self.slow_run_end(id, &mut next_run) {
                    self.keep_sums(id..end);
                    k = end - self.first_body;
                    continue;
                }
            }
            let disp = self.move_one::<MULTIRATE>(k, dt, g, cycle)?;
            max_disp = max_disp.max(disp);
            k += 1;
        }
        self.max_disp = max_disp;
        Ok(())
    }

    /// Move the part's body `k` by one step (a slow body only at the end of its cycle, by the
    /// long step; before, it keeps its sums) and return its largest sphere displacement
    /// (L1, mm; zero for a body that did not move).
    #[inline(always)]
    fn move_one<const MULTIRATE: bool>(
        &mut self,
        k: usize,
        dt: S,
        g: Vec3<S>,
        cycle: &Cycle<S>,
    ) -> Result<S, StepError> {
        let id = self.first_body + k;
        let (sums, dt) = if MULTIRATE && self.bodies[k].slow {
            if !cycle.slow_moves {
                self.keep_sums(id..id + 1);
                return Ok(S::ZERO);
            }
            (cycle_mean(&self.take_sums(id), cycle.stride), cycle.long_dt)
        } else {
            (self.take_sums(id), dt)
        };
        let b = &mut self.bodies[k];
        let first = b.first_sphere as usize - self.first_sphere;
        let spheres = &mut self.spheres[first..first + b.sphere_count as usize];
        if !b.is_clump {
            if let Some(m) = move_sphere(b, &sums, dt, g) {
                b.velocity = m.velocity;
                b.position = m.position;
                b.angular_velocity = m.angular_velocity;
                b.force = m.force;
                b.torque = m.torque;
                b.roll_torque = m.roll;
                let s = &mut spheres[0];
                s.position = m.position;
                s.velocity = m.velocity;
                s.spin = m.angular_velocity;
                return Ok(m.l1_displacement);
            }
        }
        move_body(b, spheres, &sums, dt, g).ok_or(overflow(id))
    }
}

/// One step of body `b` and its spheres: in the fast arithmetic when it is a clump inside
/// [`clump_envelope`], else in the checked one ([`step_body`] either way, the same bits).
/// Returns the largest sphere displacement (L1, mm), or `None` after an overflow.
#[inline(always)]
fn move_body<S: Scalar>(
    b: &mut Body<S>,
    spheres: &mut [Sphere<S>],
    sums: &Loads<S>,
    dt: S,
    g: Vec3<S>,
) -> Option<S> {
    if b.is_clump {
        let (m, k) = state_of(b, sums, S::to_fast);
        let (dt_f, g_f) = (dt.to_fast(), g.map(S::to_fast));
        let offsets_in = spheres
            .iter()
            .all(|s| S::Fast::magnitude3(s.offset.map(S::to_fast)).within(OFFSET_BITS));
        if offsets_in && clump_envelope(&m, &k, dt_f, g_f) {
            let new = step_body(&m, &k, true, dt_f, g_f);
            return Some(store(b, spheres, &new, true, S::from_fast, S::to_fast));
        }
    }
    let (m, k) = state_of(b, sums, |x| x);
    let new = step_body(&m, &k, b.is_clump, dt, g);
    let disp = store(b, spheres, &new, b.is_clump, |x| x, |x| x);
    let valid = b.position.is_valid()
        & b.velocity.is_valid()
        & b.angular_velocity.is_valid()
        & b.orientation.is_valid()
        & spheres
            .iter()
            .all(|s| s.position.is_valid() & s.velocity.is_valid());
    valid.then_some(disp)
}

/// Write the new motion (arithmetic T, back to S through `back`) into the body and its
/// spheres: a clump's spheres at x + R·offset, each sphere's motion snapshot
/// ([`Sphere::sync_motion`]'s values, computed in T). Returns the largest sphere
/// displacement (L1, mm).
#[inline(always)]
fn store<S: Scalar, T: Scalar>(
    b: &mut Body<S>,
    spheres: &mut [Sphere<S>],
    new: &Motion<T>,
    clump: bool,
    back: impl Fn(T) -> S + Copy,
    to: impl Fn(S) -> T + Copy,
) -> S {
    let mut disp = T::ZERO;
    if clump {
        let rot = new.orientation.to_mat3();
        for s in spheres.iter_mut() {
            let arm = rot.mul_vec(s.offset.map(to));
            let p = new.position + arm;
            disp = disp.max((p - s.position.map(to)).l1_norm());
            s.position = p.map(back);
            s.arm = arm.map(back);
            s.velocity = (new.velocity + new.angular_velocity.cross(arm)).map(back);
            s.spin = new.angular_velocity.map(back);
        }
    } else {
        let s = &mut spheres[0];
        disp = (new.position - s.position.map(to)).l1_norm();
        s.position = new.position.map(back);
        s.velocity = new.velocity.map(back);
        s.spin = new.angular_velocity.map(back);
    }
    b.position = new.position.map(back);
    b.velocity = new.velocity.map(back);
    b.angular_velocity = new.angular_velocity.map(back);
    let q = new.orientation;
    b.orientation.w = back(q.w);
    b.orientation.x = back(q.x);
    b.orientation.y = back(q.y);
    b.orientation.z = back(q.z);
    b.force = new.force.map(back);
    b.torque = new.torque.map(back);
    b.roll_torque = back(new.roll);
    back(disp)
}

fn overflow(id: usize) -> StepError {
    StepError::Overflow {
        stage: Stage::Integration,
        body: id as u32,
        other: Other::None,
    }
}
