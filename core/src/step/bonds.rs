//! Bond stage (between the narrow phase and integration): run due bond formations, check the
//! bond time-step bound, then for every bond in sorted order update its kinematics and loads
//! ([`crate::bond::kinematics`]), test the breakage criterion ([`crate::bond::breakage`]), and
//! either apply its force and torques to the two bodies or remove it and log the break. A bond
//! that breaks exerts nothing in the step it breaks; from the next step its pair meets the
//! ordinary contact law. Worlds that never used bonds skip the stage entirely.
//!
//! The loads run in parts over consecutive runs of bonds ([`BondPart`]), each adding into its
//! own accumulator arena; forces are summed as exact integers, so in fixed point any split
//! gives the same bits. Removing the broken bonds and logging them stays serial and in bond
//! order ([`remove_broken`]), so the log and the compacted table do not depend on the split.

use super::parts::widen;
use super::prefetch::{prefetch_record, worth_hinting};
use crate::body::{Body, BodyForce, Sphere};
use crate::bond::breakage::Stresses;
use crate::bond::kinematics::update;
use crate::bond::{Bond, BondBreak, BondParams, Bonds};
use crate::error::{Other, Stage, StepError};
use crate::num::Scalar;
use core::ops::Range;

/// Fewest bonds worth a part of their own: below this a thread's wake-up costs more than the
/// bonds it would load (a bond update is about 0.1–0.3 µs).
pub const MIN_BONDS_PER_PART: usize = 512;

/// How many bonds ahead the stage asks for the two spheres' records (their positions), so
/// that the loads overlap the bonds in between ([`super::prefetch`]).
const PREFETCH_BONDS_AHEAD: usize = 4;

/// The clock of the step, for the bond stage.
pub(crate) struct Clock<S> {
    /// Step number.
    pub step: u64,
    /// Simulated time at the start of the step, ms.
    pub time: S,
    /// Time step, s.
    pub dt_s: f64,
}

/// What every part of the bond stage reads.
pub(crate) struct BondShared<'w, S: Scalar> {
    /// Bond sets, by index.
    pub sets: &'w [BondParams<S>],
    /// Every sphere.
    pub spheres: &'w [Sphere<S>],
    /// Every body.
    pub bodies: &'w [Body<S>],
    /// Time step, ms.
    pub dt: S,
}

/// One part of the bond stage: a run of consecutive bonds and the arena their loads go to.
pub(crate) struct BondPart<'w, S: Scalar> {
    /// The bonds of this part, updated in place.
    pub bonds: &'w mut [Bond<S>],
    /// Accumulators of every body, indexed by body id.
    pub forces: &'w mut [BodyForce<S>],
    /// The bodies this part wrote (a hull).
    pub touched: Range<usize>,
    /// Bonds of this part that met their breakage criterion (they exerted nothing).
    pub breaks: u32,
    /// The first error, if any.
    pub result: Result<(), StepError>,
}

impl<S: Scalar> BondPart<'_, S> {
    /// Update every bond of the part and add the loads of those that hold.
    pub(crate) fn run(&mut self, shared: &BondShared<'_, S>) {
        self.result = self.load(shared);
    }

    fn load(&mut self, shared: &BondShared<'_, S>) -> Result<(), StepError> {
        // Counted in locals and stored once: a field written per bond would share its cache
        // line with the next part's struct (false sharing, core/API_NOTES.md).
        let (mut touched, mut breaks) = (0..0, 0u32);
        let result = self.load_each(shared, &mut touched, &mut breaks);
        self.touched = touched;
        self.breaks = breaks;
        result
    }

    fn load_each(
        &mut self,
        shared: &BondShared<'_, S>,
        touched: &mut Range<usize>,
        breaks: &mut u32,
    ) -> Result<(), StepError> {
        let hint = worth_hinting(shared.spheres);
        for k in 0..self.bonds.len() {
            if let Some(ahead) = self.bonds.get(k + PREFETCH_BONDS_AHEAD).filter(|_| hint) {
                prefetch_record(shared.spheres, ahead.sphere_a as usize, 1);
                prefetch_record(shared.spheres, ahead.sphere_b as usize, 1);
            }
            let bond = &mut self.bonds[k];
            let p = shared.sets[bond.set as usize];
            let sa = shared.spheres[bond.sphere_a as usize];
            let sb = shared.spheres[bond.sphere_b as usize];
            let (ia, ib) = (sa.body as usize, sb.body as usize);
            let overflow = StepError::Overflow {
                stage: Stage::Bonds,
                body: sa.body,
                other: Other::Body(sb.body),
            };
            let (ba, bb) = (&shared.bodies[ia], &shared.bodies[ib]);
            let load = update(bond, &p, &sa, &sb, ba, bb, shared.dt).ok_or(overflow)?;
            // Most bonds are far from breaking: a bound decides them without two roots.
            if !Stresses::surely_holds(bond, &p) {
                let st = Stresses::of(bond, &p);
                if !(st.sigma_max.is_valid() & st.tau_max.is_valid()) {
                    return Err(overflow);
                }
                if st.criterion(&p).is_some() {
                    *breaks += 1;
                    continue;
                }
            }
            self.forces[ib].add_force(load.force);
            self.forces[ib].add_torque(load.torque_b);
            self.forces[ia].sub_force(load.force);
            self.forces[ia].add_torque(load.torque_a);
            widen(touched, ia);
            widen(touched, ib);
        }
        Ok(())
    }
}

/// The serial start of the stage: run due formations and check the bond time-step bound.
/// Returns `false` when the world never used bonds (the stage is skipped).
pub(crate) fn prepare<S: Scalar>(
    table: &mut Bonds<'_, S>,
    spheres: &[Sphere<S>],
    bodies: &[Body<S>],
    clock: &Clock<S>,
) -> Result<bool, StepError> {
    if table.is_unused() {
        return Ok(false);
    }
    table
        .run_scheduled(clock.time, spheres, bodies)
        .map_err(|capacity| StepError::BondCapacity { capacity })?;
    if clock.dt_s > table.max_dt_s {
        return Err(StepError::TimeStepTooLarge {
            dt_s: clock.dt_s,
            max_s: table.max_dt_s,
        });
    }
    Ok(true)
}

/// The serial end of the stage, after parts that found breaks: remove every bond that meets
/// its breakage criterion, in bond order, logging each. The parts left the updated loads in
/// the bonds, so the criterion is the one they tested.
pub(crate) fn remove_broken<S: Scalar>(table: &mut Bonds<'_, S>, clock: &Clock<S>) {
    let n = table.n as usize;
    let mut kept = 0usize;
    for r in 0..n {
        let bond = table.bonds[r];
        let p = table.sets[bond.set as usize];
        let st = Stresses::of(&bond, &p);
        if let Some(criterion) = st.criterion(&p) {
            table.record(BondBreak {
                step: clock.step,
                time_ms: clock.time,
                bond_id: bond.id,
                sphere_a: bond.sphere_a,
                sphere_b: bond.sphere_b,
                tag: p.tag,
                criterion,
                sigma_max_mpa: st.sigma_max,
                tau_max_mpa: st.tau_max,
            });
            continue;
        }
        table.bonds[kept] = bond;
        kept += 1;
    }
    table.n = kept as u32;
}
