//! Bond stage (between the narrow phase and integration): run due bond formations, check the
//! bond time-step bound, then for every bond in sorted order update its kinematics and loads
//! ([`crate::bond::kinematics`]), test the breakage criterion ([`crate::bond::breakage`]), and
//! either apply its force and torques to the two bodies or remove it and log the break. A bond
//! that breaks exerts nothing in the step it breaks; from the next step its pair meets the
//! ordinary contact law. Worlds that never used bonds skip the stage entirely.

use crate::bond::breakage::Stresses;
use crate::bond::kinematics::update;
use crate::bond::BondBreak;
use crate::error::{Other, Stage, StepError};
use crate::num::Scalar;
use crate::world::World;

impl<S: Scalar> World<'_, S> {
    /// The bond stage (see the module docs).
    pub(crate) fn bond_forces(&mut self) -> Result<(), StepError> {
        if self.bond_table.is_unused() {
            return Ok(());
        }
        self.run_scheduled_formations()
            .map_err(|capacity| StepError::BondCapacity { capacity })?;
        if self.dt_s > self.bond_table.max_dt_s {
            return Err(StepError::TimeStepTooLarge {
                dt_s: self.dt_s,
                max_s: self.bond_table.max_dt_s,
            });
        }
        let dt = self.dt;
        let n = self.bond_table.n as usize;
        let mut kept = 0usize;
        for r in 0..n {
            let mut bond = self.bond_table.bonds[r];
            let p = self.bond_table.sets[bond.set as usize];
            let sa = self.spheres[bond.sphere_a as usize];
            let sb = self.spheres[bond.sphere_b as usize];
            let (ia, ib) = (sa.body as usize, sb.body as usize);
            let overflow = StepError::Overflow {
                stage: Stage::Bonds,
                body: sa.body,
                other: Other::Body(sb.body),
            };
            let load = update(
                &mut bond,
                &p,
                &sa,
                &sb,
                &self.bodies[ia],
                &self.bodies[ib],
                dt,
            )
            .ok_or(overflow)?;
            let st = Stresses::of(&bond, &p);
            if !(st.sigma_max.is_valid() & st.tau_max.is_valid()) {
                return Err(overflow);
            }
            if let Some(criterion) = st.criterion(&p) {
                self.bond_table.record(BondBreak {
                    step: self.steps,
                    time_ms: self.time,
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
            {
                let b = &mut self.bodies[ib];
                b.force += load.force;
                b.torque += load.torque_b;
            }
            {
                let a = &mut self.bodies[ia];
                a.force -= load.force;
                a.torque += load.torque_a;
            }
            self.bond_table.bonds[kept] = bond;
            kept += 1;
        }
        self.bond_table.n = kept as u32;
        Ok(())
    }
}
