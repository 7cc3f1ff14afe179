//! The world's API for the bonded-particle model ([`crate::bond`]): storage, bond sets,
//! formation now or at a scheduled time, single bonds, and the bond table.

use super::World;
use crate::bond::{BondError, BondSetId, BondSetSpec, BondStorage, Bonds, FormationRule};
use crate::num::Scalar;

impl<'a, S: Scalar> World<'a, S> {
    /// Give the world bond storage (bond arena and break log). Allowed while the world has no
    /// bonds; bond sets already added are kept.
    pub fn attach_bond_storage(&mut self, storage: BondStorage<'a, S>) -> Result<(), BondError> {
        self.bond_table.attach(storage)
    }

    /// Add a bond set; returns its id.
    pub fn add_bond_set(&mut self, spec: &BondSetSpec) -> Result<BondSetId, BondError> {
        self.bond_table.add_set(spec)
    }

    /// The bond table: live bonds, sets, break log.
    pub fn bonds(&self) -> &Bonds<'a, S> {
        &self.bond_table
    }

    /// Bond every pair that `rule` selects, now. Returns the number of new bonds.
    /// On error nothing changes.
    pub fn form_bonds(&mut self, rule: &FormationRule) -> Result<u32, BondError> {
        let gap = self.bond_table.check_rule(rule, self.materials.len())?;
        let n = self.n_spheres as usize;
        self.bond_table
            .form(rule, gap, &self.spheres[..n], &self.bodies[..])
            .map_err(|capacity| BondError::Capacity { capacity })
    }

    /// Bond every pair that `rule` selects at simulated time `time_s` (at the start of the
    /// first step that begins at or after it). A capacity overflow then stops that step with
    /// [`crate::error::StepError::BondCapacity`].
    pub fn schedule_bond_formation(
        &mut self,
        time_s: f64,
        rule: &FormationRule,
    ) -> Result<(), BondError> {
        let gap = self.bond_table.check_rule(rule, self.materials.len())?;
        self.bond_table.schedule(time_s, rule, gap)
    }

    /// Bond spheres `i` and `j` (either order) with set `set`. Returns the bond id.
    pub fn add_bond(&mut self, i: u32, j: u32, set: BondSetId) -> Result<u32, BondError> {
        let n = self.n_spheres as usize;
        self.bond_table
            .add(i, j, set, &self.spheres[..n], &self.bodies[..])
    }

    /// Largest time step the bonds made so far allow, s (∞ with none; see
    /// [`crate::bond::formation`]).
    pub fn bond_max_timestep_s(&self) -> f64 {
        self.bond_table.max_timestep_s()
    }
}
