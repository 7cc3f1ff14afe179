//! Multi-rate stepping: bodies marked *slow* move once every `k` steps, by one long step of
//! k·dt, while every other body moves every step.
//!
//! **Why.** A field couples two time scales. The plant's thin stalks, held by stiff bonds,
//! need dt ≈ 8e-7 s (the bond bound of [`crate::bond`]); the soil's grains (8 mm, 10 MPa) are
//! stable at 40 % of their Rayleigh time, about 3e-4 s, and their collisions with the
//! machine last about a millisecond. Stepping every grain at the plant's dt spends most of a
//! field's step on soil that changes by nothing from one step to the next
//! (`core/API_NOTES.md`, "Multi-rate stepping").
//!
//! **How** (a cycle is k steps, k = [`crate::world::World::set_slow_stride`]):
//! - a contact between two slow bodies is evaluated once, at the cycle's first step, with
//!   the long step k·dt for its tangential spring; its loads count k times (they act over
//!   the whole cycle);
//! - every other contact (slow with fast, kinematic or wall), every bond and the air drag
//!   act every step, as without slow bodies; a slow body sums them over the cycle;
//! - at the cycle's last step a slow body moves by symplectic Euler with the long step:
//!   v ← v + (F̄/m + g)·k·dt, x ← x + v·k·dt, F̄ = ΣF/k the mean force of the cycle (the
//!   same for the torque and the rolling torque). The momentum a slow body receives is the
//!   impulse of the cycle, to the rounding of F̄ (2^-33 N per component);
//! - between, a slow body stands where it was, with its velocity: its partners see it as a
//!   body moving at that velocity through a fixed point, and its tangential springs grow by
//!   the relative velocity, so the cycle's displacement is counted once, when it moves.
//!
//! With k = 1 (the default) nothing of this runs and the step is the single-rate step, bit
//! for bit. In fixed point the sums are exact integers, so the bits do not depend on the
//! number of threads. A world with slow bodies can be checkpointed only between cycles
//! ([`crate::world::checkpoint`]): within one, the sums of the cycle are not in the words.
//!
//! ```
//! use arachis_core::prelude::*;
//! use arachis_core::scenario::materials::POD;
//! let lengths = StorageLengths::for_spheres(1, 1);
//! let mut storage = arachis_core::owned::OwnedStorage::<Fx>::new(lengths);
//! let mut w = World::new(storage.storage()).unwrap();
//! let m = w.add_material(POD).unwrap();
//! let b = w.add_sphere(SphereSpec::at_rest(m, 0.004, [0.0, 0.0, 1.0])).unwrap();
//! w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
//! w.set_timestep_s(1e-5).unwrap();
//! w.set_slow_stride(4).unwrap();
//! w.set_body_slow(b, true).unwrap();
//! w.run(3).unwrap(); // within the cycle: the slow sphere has not moved yet
//! assert_eq!(w.body(b).velocity.z, Fx::ZERO);
//! w.run(1).unwrap(); // the cycle's last step: one long step of 4·dt
//! let v = w.body(b).velocity.z.to_f64(); // mm/ms = m/s
//! assert!((v + 9.81 * 4e-5).abs() < 1e-9);
//! ```

use crate::body::{Body, Loads};
use crate::num::{Scalar, Vec3};
use core::ops::Range;

/// The largest slow stride k: the long step's loads count k times, so k bounds how far a
/// contact's load is multiplied before its overflow test.
pub const MAX_SLOW_STRIDE: u32 = 256;

/// The most runs of consecutive slow bodies [`SlowRuns`] keeps.
const MAX_SLOW_RUNS: usize = 16;

/// The fewest consecutive slow bodies [`SlowRuns`] keeps as a run: a shorter run costs the
/// integration little when its bodies are tested one by one.
const MIN_SLOW_RUN: usize = 64;

/// The longest runs of consecutive slow bodies (body ids), in increasing order: between a
/// cycle's moves the integration passes over each run without reading its bodies' records
/// (about 240 bytes each, read only to find the slow mark: a third of a field's integration
/// time went to that load), and only gathers the contact parts' sums of its bodies. Bodies
/// outside the runs are tested one by one, so the runs kept are an optimisation only: up to
/// [`MAX_SLOW_RUNS`] runs of at least [`MIN_SLOW_RUN`] bodies, recomputed when a mark changes.
#[derive(Clone, Debug, Default)]
pub(crate) struct SlowRuns {
    runs: heapless::Vec<Range<usize>, MAX_SLOW_RUNS>,
    /// Whether a body's mark changed since the runs were found.
    stale: bool,
}

impl SlowRuns {
    /// Note that a body's slow mark changed.
    pub fn invalidate(&mut self) {
        self.stale = true;
    }

    /// The runs of `bodies`, found again if a mark changed.
    pub fn of<S>(&mut self, bodies: &[Body<S>]) -> &[Range<usize>] {
        if self.stale {
            self.runs.clear();
            let mut start = 0;
            while start < bodies.len() && !self.runs.is_full() {
                let len = bodies[start..].iter().take_while(|b| b.slow).count();
                if len >= MIN_SLOW_RUN {
                    let _ = self.runs.push(start..start + len);
                }
                start += len.max(1);
            }
            self.stale = false;
        }
        &self.runs
    }
}

/// Where a step lies in its cycle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cycle<S> {
    /// k, steps per cycle (1: single-rate).
    pub stride: u32,
    /// Contacts between slow bodies are evaluated at this step (the cycle's first).
    pub slow_contacts: bool,
    /// Slow bodies move at the end of this step (the cycle's last).
    pub slow_moves: bool,
    /// The long step k·dt, ms.
    pub long_dt: S,
}

impl<S: Scalar> Cycle<S> {
    /// The cycle position of the step that follows `steps` completed steps, with stride `k`
    /// and time step `dt` (ms).
    pub fn at(steps: u64, stride: u32, dt: S) -> Self {
        let k = u64::from(stride.max(1));
        Cycle {
            stride: stride.max(1),
            slow_contacts: steps % k == 0,
            slow_moves: (steps + 1) % k == 0,
            long_dt: dt.mul_int(stride.max(1) as i32),
        }
    }
}

impl<S> Cycle<S> {
    /// Whether any body may be slow (k > 1).
    #[inline(always)]
    pub fn multirate(&self) -> bool {
        self.stride > 1
    }

    /// A multi-rate step at which the slow bodies' contacts are evaluated: the contact
    /// stage's cost lies elsewhere among the bodies than at the steps between, so a
    /// threaded step balances it apart ([`crate::step::balance`]).
    pub fn is_slow_contact_step(&self) -> bool {
        self.multirate() && self.slow_contacts
    }

    /// A multi-rate step at whose end the slow bodies move (balanced apart, as above).
    pub fn is_slow_move_step(&self) -> bool {
        self.multirate() && self.slow_moves
    }
}

/// A slow pair's loads count `stride` times (`x.mul_int`, which reports an overflow as an
/// invalid value).
#[inline(always)]
pub(crate) fn times<S: Scalar>(v: Vec3<S>, stride: u32) -> Vec3<S> {
    v.map(|x| x.mul_int(stride as i32))
}

/// The mean of a cycle's sums, ΣF/k (rounded to nearest in fixed point).
pub(crate) fn cycle_mean<S: Scalar>(sums: &Loads<S>, stride: u32) -> Loads<S> {
    let k = S::ONE.mul_int(stride as i32);
    Loads {
        force: sums.force.map(|x| x / k),
        torque: sums.torque.map(|x| x / k),
        roll: sums.roll / k,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::BodyForce;
    use crate::num::Fx;

    #[test]
    fn slow_runs_are_the_long_runs_of_slow_bodies_found_again_when_a_mark_changes() {
        let mut bodies = alloc::vec![Body::<Fx>::default(); 400];
        let mark = |bodies: &mut [Body<Fx>], r: Range<usize>| {
            bodies[r].iter_mut().for_each(|b| b.slow = true);
        };
        // Runs of 100, 63 (too short) and 64 bodies.
        mark(&mut bodies, 10..110);
        mark(&mut bodies, 150..213);
        mark(&mut bodies, 300..364);
        let mut runs = SlowRuns::default();
        assert!(runs.of(&bodies).is_empty(), "no mark noted yet");
        runs.invalidate();
        assert_eq!(runs.of(&bodies), [10..110, 300..364]);
        mark(&mut bodies, 213..214);
        assert_eq!(
            runs.of(&bodies),
            [10..110, 300..364],
            "kept until a change is noted"
        );
        runs.invalidate();
        assert_eq!(runs.of(&bodies), [10..110, 150..214, 300..364]);
        // At most MAX_SLOW_RUNS are kept; the bodies of the others are tested one by one.
        let mut many = alloc::vec![Body::<Fx>::default(); (MIN_SLOW_RUN + 1) * 20];
        for r in 0..20 {
            let start = r * (MIN_SLOW_RUN + 1);
            mark(&mut many, start..start + MIN_SLOW_RUN);
        }
        runs.invalidate();
        assert_eq!(runs.of(&many).len(), MAX_SLOW_RUNS);
    }

    #[test]
    fn a_cycle_evaluates_slow_contacts_first_and_moves_slow_bodies_last() {
        let dt = Fx::from_f64(0.001);
        let at = |s| Cycle::at(s, 4, dt);
        let phases: [(bool, bool); 8] =
            core::array::from_fn(|s| (at(s as u64).slow_contacts, at(s as u64).slow_moves));
        assert_eq!(
            phases,
            [
                (true, false),
                (false, false),
                (false, false),
                (false, true),
                (true, false),
                (false, false),
                (false, false),
                (false, true)
            ]
        );
        assert_eq!(at(0).long_dt, dt.mul_int(4));
        // Single-rate: every step does both, with dt itself.
        let one = Cycle::at(7, 1, dt);
        assert!(one.slow_contacts && one.slow_moves && !one.multirate());
        assert_eq!(one.long_dt, dt);
    }

    #[test]
    fn the_cycle_mean_is_the_sum_over_k_rounded_to_nearest() {
        let mut sums = BodyForce::<Fx>::default();
        let f = Vec3::new(Fx::from_f64(3.0), Fx::from_f64(-1.0), Fx::from_f64(0.5));
        for _ in 0..3 {
            sums.add_force(f);
            sums.add_torque(f.map(|x| -x));
            sums.add_roll(Fx::ONE);
        }
        let mean = cycle_mean(&sums.values(), 3);
        assert_eq!(mean.force, f);
        assert_eq!(mean.torque, f.map(|x| -x));
        assert_eq!(mean.roll, Fx::ONE);
        // 1 N over 3 steps: 1/3 N to half a unit of 2^-32 N.
        let mut one = BodyForce::<Fx>::default();
        one.add_force(Vec3::new(Fx::ONE, Fx::ZERO, Fx::ZERO));
        let third = cycle_mean(&one.values(), 3).force.x.to_f64();
        assert!((third - 1.0 / 3.0).abs() <= 0.5 / 4_294_967_296.0);
    }

    #[test]
    fn a_load_counted_k_times_that_leaves_the_range_is_invalid() {
        let big = Vec3::new(Fx::from_f64(1.0e8), Fx::ZERO, Fx::ZERO);
        assert!(times(big, 16).is_valid());
        assert!(!times(big, 256).is_valid());
    }
}
