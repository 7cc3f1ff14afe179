//! Bond stage (between the narrow phase and integration): run due bond formations, check the
//! bond time-step bound, then for every bond in sorted order update its kinematics and loads
//! ([`crate::bond::kinematics`]), test the breakage criterion ([`crate::bond::breakage`]), and
//! either apply its force and torques to the two bodies or remove it and log the break. A bond
//! that breaks exerts nothing in the step it breaks; from the next step its pair meets the
//! ordinary contact law. Worlds that never used bonds skip the stage entirely.

use crate::body::{Body, BodyForce, Sphere};
use crate::bond::breakage::Stresses;
use crate::bond::kinematics::update;
use crate::bond::BondBreak;
use crate::bond::Bonds;
use crate::error::{Other, Stage, StepError};
use crate::num::Scalar;

/// The clock of the step, for the bond stage.
pub(crate) struct Clock<S> {
    /// Step number.
    pub step: u64,
    /// Simulated time at the start of the step, ms.
    pub time: S,
    /// Time step, ms.
    pub dt: S,
    /// Time step, s.
    pub dt_s: f64,
}

/// The bond stage (see the module docs): loads go into `forces`.
pub(crate) fn bond_forces<S: Scalar>(
    table: &mut Bonds<'_, S>,
    spheres: &[Sphere<S>],
    bodies: &[Body<S>],
    forces: &mut [BodyForce<S>],
    clock: &Clock<S>,
) -> Result<(), StepError> {
    if table.is_unused() {
        return Ok(());
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
    let n = table.n as usize;
    let mut kept = 0usize;
    for r in 0..n {
        let mut bond = table.bonds[r];
        let p = table.sets[bond.set as usize];
        let sa = spheres[bond.sphere_a as usize];
        let sb = spheres[bond.sphere_b as usize];
        let (ia, ib) = (sa.body as usize, sb.body as usize);
        let overflow = StepError::Overflow {
            stage: Stage::Bonds,
            body: sa.body,
            other: Other::Body(sb.body),
        };
        let load =
            update(&mut bond, &p, &sa, &sb, &bodies[ia], &bodies[ib], clock.dt).ok_or(overflow)?;
        let st = Stresses::of(&bond, &p);
        if !(st.sigma_max.is_valid() & st.tau_max.is_valid()) {
            return Err(overflow);
        }
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
        forces[ib].add_force(load.force);
        forces[ib].add_torque(load.torque_b);
        forces[ia].sub_force(load.force);
        forces[ia].add_torque(load.torque_a);
        table.bonds[kept] = bond;
        kept += 1;
    }
    table.n = kept as u32;
    Ok(())
}
