//! Bond storage: the [`Bond`] records and break log live in caller-provided slices
//! ([`BondStorage`]), owned by the world's [`Bonds`] table together with the bond sets and the
//! formation schedule.
//!
//! Bonds are kept sorted by their sphere pair (lower id, higher id), so the narrow phase can
//! ask "is this pair bonded?" by binary search, and so the step visits bonds in a fixed order.
//! A broken bond is removed by compaction, which keeps the order. Every bond also has a
//! persistent id (creation order) that break records and dumps name.

use super::error::BondError;
use super::formation::FormationRule;
use super::log::BondBreak;
use super::params::{BondParams, BondSetId, BondSetSpec, MAX_BOND_SETS};
use crate::digest::Fnv1a;
use crate::num::{Scalar, Vec3};

/// Largest number of pending scheduled formations.
pub const MAX_SCHEDULED_FORMATIONS: usize = 8;

/// One bond: its ends, set, accumulated relative motion and current loads (internal units).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Bond<S> {
    /// Persistent id (creation order).
    pub id: u32,
    /// Lower sphere id (end a).
    pub sphere_a: u32,
    /// Higher sphere id (end b).
    pub sphere_b: u32,
    /// Index of the bond set.
    pub set: u16,
    /// Accumulated normal displacement δn = Σ vn·dt, mm (> 0: stretched).
    pub normal_disp: S,
    /// Accumulated tangential displacement δt = Σ vt·dt of b relative to a, mm.
    pub tangential_disp: Vec3<S>,
    /// Accumulated twist θn = Σ ωn·dt of b relative to a about n̂, rad.
    pub twist: S,
    /// Accumulated bending rotation θb = Σ ωt·dt of b relative to a, rad.
    pub bend: Vec3<S>,
    /// Normal force Fn = −Kn·A·δn, N (> 0: compression).
    pub normal_force: S,
    /// Tangential force on b, Ft = −Kt·A·δt, N.
    pub tangential_force: Vec3<S>,
    /// Twisting moment on b about n̂, Mt = −Kt·J·θn, N·mm.
    pub twisting_moment: S,
    /// Bending moment on b, Mb = −Kn·(J/2)·θb, N·mm.
    pub bending_moment: Vec3<S>,
    /// Bond axis n̂ (a → b) at the last update.
    pub normal: Vec3<S>,
}

impl<S: Scalar> Bond<S> {
    /// The same bond with every quantity through `f` (e.g. to [`Scalar::Fast`], same bits).
    #[inline(always)]
    pub(crate) fn map<T: Scalar>(&self, f: impl Fn(S) -> T + Copy) -> Bond<T> {
        Bond {
            id: self.id,
            sphere_a: self.sphere_a,
            sphere_b: self.sphere_b,
            set: self.set,
            normal_disp: f(self.normal_disp),
            tangential_disp: self.tangential_disp.map(f),
            twist: f(self.twist),
            bend: self.bend.map(f),
            normal_force: f(self.normal_force),
            tangential_force: self.tangential_force.map(f),
            twisting_moment: f(self.twisting_moment),
            bending_moment: self.bending_moment.map(f),
            normal: self.normal.map(f),
        }
    }

    /// Sort key: (lower sphere, higher sphere).
    #[inline(always)]
    pub fn key(&self) -> u64 {
        pair_key(self.sphere_a, self.sphere_b)
    }
}

/// Sort key of an ordered sphere pair (a < b).
#[inline(always)]
pub(crate) fn pair_key(a: u32, b: u32) -> u64 {
    ((a as u64) << 32) | b as u64
}

/// The live bonds, sorted by sphere pair, with a bound on their spheres: which pairs of
/// spheres a bond joins (bonded pairs get no contact force).
#[derive(Clone, Copy, Debug)]
pub(crate) struct BondedPairs<'b, S: Scalar> {
    bonds: &'b [Bond<S>],
    /// No bond's second sphere lies beyond this ([`Bonds::last_partner`]).
    last_partner: u32,
}

impl<S: Scalar> BondedPairs<'_, S> {
    /// `true` if spheres `i` < `j` are joined by a live bond. A pair outside the spheres that
    /// bonds join (below the first bond's first sphere, or beyond the last partner ever
    /// bonded) is answered without the search: in a field, every pair with a soil grain or a
    /// machine part, whose spheres come after the plants'. The answer is the search's.
    #[inline(always)]
    pub(crate) fn joins(&self, i: u32, j: u32) -> bool {
        match self.bonds.first() {
            Some(first) if i >= first.sphere_a && j <= self.last_partner => {
                is_bonded(self.bonds, i, j)
            }
            _ => false,
        }
    }
}

/// `true` if spheres `i` < `j` are joined by a bond in the sorted slice `bonds`.
#[inline]
pub(crate) fn is_bonded<S: Scalar>(bonds: &[Bond<S>], i: u32, j: u32) -> bool {
    !bonds.is_empty()
        && bonds
            .binary_search_by_key(&pair_key(i, j), |b| b.key())
            .is_ok()
}

/// Caller-provided bond storage.
pub struct BondStorage<'a, S> {
    /// Bond arena; its length is the bond capacity.
    pub bonds: &'a mut [Bond<S>],
    /// Break log; its length is the log capacity (breaks beyond it are counted, not stored).
    pub log: &'a mut [BondBreak<S>],
}

/// A formation waiting for its time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Scheduled<S> {
    /// Simulated time at which to form, ms.
    pub time: S,
    /// What to bond.
    pub rule: FormationRule,
    /// The rule's gap, quantised when scheduled, mm.
    pub gap: S,
}

/// The world's bond table: sets, bonds, break log, schedule.
pub struct Bonds<'a, S: Scalar> {
    pub(crate) sets: heapless::Vec<BondParams<S>, MAX_BOND_SETS>,
    pub(crate) bonds: &'a mut [Bond<S>],
    pub(crate) n: u32,
    pub(crate) next_id: u32,
    pub(crate) log: &'a mut [BondBreak<S>],
    pub(crate) n_log: u32,
    pub(crate) breaks_total: u64,
    pub(crate) schedule: heapless::Vec<Scheduled<S>, MAX_SCHEDULED_FORMATIONS>,
    /// Smallest stable time step over all bonds ever made, s (∞ with none).
    pub(crate) max_dt_s: f64,
    /// The largest second sphere (b) of any bond ever made (0 with none): no live bond joins
    /// a pair whose larger sphere lies beyond it ([`BondedPairs`]).
    pub(crate) last_partner: u32,
}

impl<'a, S: Scalar> Bonds<'a, S> {
    /// A table with no storage (capacity 0) and no sets: what a world starts with.
    pub fn empty() -> Self {
        Bonds {
            sets: heapless::Vec::new(),
            bonds: &mut [],
            n: 0,
            next_id: 0,
            log: &mut [],
            n_log: 0,
            breaks_total: 0,
            schedule: heapless::Vec::new(),
            max_dt_s: f64::INFINITY,
            last_partner: 0,
        }
    }

    /// The live bonds as the contact stage asks them ([`BondedPairs::joins`]).
    pub(crate) fn pairs(&self) -> BondedPairs<'_, S> {
        BondedPairs {
            bonds: self.bonds(),
            last_partner: self.last_partner,
        }
    }

    /// Live bonds, sorted by sphere pair.
    pub fn bonds(&self) -> &[Bond<S>] {
        &self.bonds[..self.n as usize]
    }

    /// The bond joining spheres `i` and `j` (either order), if any.
    pub fn find(&self, i: u32, j: u32) -> Option<&Bond<S>> {
        let (a, b) = if i < j { (i, j) } else { (j, i) };
        let live = self.bonds();
        live.binary_search_by_key(&pair_key(a, b), |x| x.key())
            .ok()
            .map(|k| &live[k])
    }

    /// Bond sets in insertion order.
    pub fn sets(&self) -> &[BondParams<S>] {
        &self.sets
    }

    /// Logged breaks, in break order.
    pub fn breaks(&self) -> &[BondBreak<S>] {
        &self.log[..self.n_log as usize]
    }

    /// Every break so far, logged or not.
    pub fn breaks_total(&self) -> u64 {
        self.breaks_total
    }

    /// Breaks that did not fit the log.
    pub fn breaks_not_logged(&self) -> u64 {
        self.breaks_total - self.n_log as u64
    }

    /// Bond capacity of the attached storage.
    pub fn capacity(&self) -> u32 {
        self.bonds.len() as u32
    }

    /// Record a break (counted always, stored while the log has room).
    pub(crate) fn record(&mut self, b: BondBreak<S>) {
        if (self.n_log as usize) < self.log.len() {
            self.log[self.n_log as usize] = b;
            self.n_log += 1;
        }
        self.breaks_total += 1;
    }

    /// `true` when the table would change nothing in the digest: no sets, no bonds, no
    /// schedule. Worlds without bonds then keep their pre-bond digests.
    pub(crate) fn is_unused(&self) -> bool {
        self.sets.is_empty() && self.n == 0 && self.schedule.is_empty() && self.breaks_total == 0
    }

    /// Hash the bond state (sets, bonds, counters, schedule, logged breaks) into `h`.
    pub(crate) fn hash_into(&self, h: &mut Fnv1a) {
        if self.is_unused() {
            return;
        }
        h.u64(self.sets.len() as u64);
        for p in self.sets.iter() {
            h.u64(p.tag as u64);
            for x in [
                p.radius,
                p.kn_area,
                p.kt_area,
                p.kt_polar,
                p.kn_inertia,
                p.inv_area,
                p.rb_over_inertia,
                p.rb_over_polar,
                p.normal_strength,
                p.tangential_strength,
            ] {
                h.s(x);
            }
        }
        h.u64(self.n as u64);
        h.u64(self.next_id as u64);
        for b in self.bonds() {
            h.u64(b.id as u64);
            h.u64(b.sphere_a as u64);
            h.u64(b.sphere_b as u64);
            h.u64(b.set as u64);
            h.s(b.normal_disp);
            h.v(b.tangential_disp);
            h.s(b.twist);
            h.v(b.bend);
            h.s(b.normal_force);
            h.v(b.tangential_force);
            h.s(b.twisting_moment);
            h.v(b.bending_moment);
            h.v(b.normal);
        }
        h.u64(self.breaks_total);
        for r in self.breaks() {
            h.u64(r.step);
            h.s(r.time_ms);
            h.u64(r.bond_id as u64);
            h.u64(r.criterion.code() as u64);
        }
        h.u64(self.schedule.len() as u64);
        for s in self.schedule.iter() {
            h.s(s.time);
            s.rule.hash_into(h);
        }
    }
}

impl<'a, S: Scalar> Bonds<'a, S> {
    /// Take bond storage (bond arena and break log). Allowed while there are no bonds; bond
    /// sets already added are kept.
    pub(crate) fn attach(&mut self, storage: BondStorage<'a, S>) -> Result<(), BondError> {
        if self.n > 0 {
            return Err(BondError::StorageInUse);
        }
        self.bonds = storage.bonds;
        self.log = storage.log;
        self.n_log = 0;
        Ok(())
    }

    /// Add a bond set; returns its id.
    pub(crate) fn add_set(&mut self, spec: &BondSetSpec) -> Result<BondSetId, BondError> {
        let p = spec.validate::<S>()?;
        let id = self.sets.len() as u16;
        self.sets.push(p).map_err(|_| BondError::TooMany {
            what: "bond sets",
            capacity: MAX_BOND_SETS as u32,
        })?;
        Ok(BondSetId(id))
    }
}
