//! The calm at the start of a field's run: for its first steps every body moves through a
//! still, dense medium (the core's quadratic air drag, [`arachis_core::step::air_drag`]),
//! then the medium is taken away and the field stands in still air, as before.
//!
//! **Why.** The soil settles around the plants while their stems, stalks and pegs are held
//! still ([`super::settle`]), so the settled grains press on the pegs they packed against:
//! at the start of the shipped field's run 377 plant spheres overlap grains, by up to 0.40 mm
//! (about 3 N on a 1 mm, 4 mg peg sphere). Let go with bonds that start unstressed, the pegs
//! spring out of the grains and ring for thousands of steps (668 plant spheres above 0.5 m/s
//! at step 250, 200 at step 10 000; `core/API_NOTES.md`, "What moves in the shipped field at
//! rest"). The field's bonds have no damping of their own. A drag F = −½ρC_dA|v|v takes that
//! energy out where it is: a 1 mm peg sphere at 1 m/s in the default medium (water's
//! density, C_d = 2.5) decelerates at about 1 000 m/s², while a grain or a pod at rest feels
//! nothing, and the drag goes with the square of the speed, so what crawls is left alone.
//! With the default calm no plant sphere of the shipped field moves faster than 0.5 m/s from
//! step 10 000 on.
//!
//! **What it does not do.** It does not hold the field still: what moves slowly, it leaves
//! alone. The shipped field still breaks the same pod–stalk bond, at step 45 779 instead of
//! 36 531; by step 150 000 six are broken with a calm of 10 250 steps as without one, three
//! under a calm over all of them. The soil that the settling packed onto the held pegs pushes
//! them down once they are free, and the plants' laterals and leaves come down under their
//! weight; a peg bent between its lateral and its pod breaks at the pod (`core/API_NOTES.md`,
//! "A calm start, built, and what it does not fix").
//!
//! **When.** From the run's first step for the field file's [`Calm::duration_s`], rounded down
//! to whole chunks of [`CHUNK_STEPS`] ([`CalmPhase::of`]), so that the drag is switched
//! only between chunks, where the harvester moves its parts, frames are taken and
//! checkpoints written, and the calm never lasts longer than the file says. With a harvester
//! the calm is the first part of the machine's wait (its `settle_s`, which may not be
//! shorter): the machine sets off into still air. Nothing about the calm is in a
//! checkpoint's words (the core keeps its drag among the set-up values): a run going on from
//! one sets the drag again from the steps it had done ([`CalmPhase::set`]), so it gives the
//! bits of a run never stopped, and the checkpoint's inputs hash covers the `[calm]` table.
//!
//! ```
//! use arachis::field::calm::CalmPhase;
//! use arachis::field::Calm;
//! // 7.5 ms at 7.46e-7 s a step: 10 053 steps, rounded down to whole 250-step chunks.
//! let calm = CalmPhase::of(&Calm::default(), 7.46e-7);
//! assert_eq!(calm.steps, 10_000);
//! assert!(calm.is_on(9_999) && !calm.is_on(10_000));
//! assert_eq!(calm.steps_to_switch(9_750), 250);
//! assert_eq!(calm.steps_to_switch(10_000), u64::MAX);
//! // Shorter than a chunk: no calm.
//! let none = CalmPhase::of(&Calm { duration_s: 1.0e-4, ..Calm::default() }, 7.46e-7);
//! assert_eq!(none.steps, 0);
//! ```

use arachis_core::prelude::*;
use serde::Serialize;

use super::{Calm, CHUNK_STEPS};

/// The calm of one run, in the run's steps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CalmPhase {
    /// Steps from the run's start during which the medium's drag acts (a whole number of
    /// [`CHUNK_STEPS`]; 0: no calm).
    pub steps: u64,
    /// Their simulated time, s.
    pub duration_s: f64,
    /// The medium's density, kg/m³.
    pub medium_density_kg_m3: f64,
    /// Its drag coefficient.
    pub drag_coefficient: f64,
}

impl CalmPhase {
    /// The calm of `calm` in a run of time step `dt_s`: [`Calm::duration_s`] rounded down to
    /// whole chunks of [`CHUNK_STEPS`] steps (none if it is shorter than one).
    pub fn of(calm: &Calm, dt_s: f64) -> Self {
        let wanted = if calm.duration_s > 0.0 && dt_s > 0.0 {
            (calm.duration_s / dt_s).floor() as u64
        } else {
            0
        };
        let steps = wanted / CHUNK_STEPS * CHUNK_STEPS;
        CalmPhase {
            steps,
            duration_s: steps as f64 * dt_s,
            medium_density_kg_m3: calm.medium_density_kg_m3,
            drag_coefficient: calm.drag_coefficient,
        }
    }

    /// Whether the step after `done` steps of the run is calmed.
    pub fn is_on(&self, done: u64) -> bool {
        done < self.steps
    }

    /// Steps from `done` until the drag is switched off (`u64::MAX` once it is off): a run
    /// steps no further than this before calling [`CalmPhase::set`] again.
    pub fn steps_to_switch(&self, done: u64) -> u64 {
        if self.is_on(done) {
            self.steps - done
        } else {
            u64::MAX
        }
    }

    /// Sets `world`'s drag for a run `done` steps in: the medium's while the calm lasts,
    /// none from its end on.
    pub fn set<S: Scalar>(&self, world: &mut World<'_, S>, done: u64) -> Result<(), String> {
        let (rho, cd) = if self.is_on(done) {
            (self.medium_density_kg_m3, self.drag_coefficient)
        } else {
            (0.0, 0.0)
        };
        world.set_air_drag(rho, cd).map_err(|e| e.to_string())
    }
}
