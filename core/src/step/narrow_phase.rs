//! Narrow phase: contact geometry and relative motion for sphere–sphere and sphere–wall
//! pairs, evaluation of the pair's contact terms, and accumulation of forces and torques.
//!
//! Geometry (seed 000 eqs. (1)–(2), DESIGN §2): α = Ri + Rj − |rj − ri|, n̂ = (rj − ri)/|rj − ri|
//! (n̂ = +z for exactly coincident centres, a deterministic choice; centres closer than 1 mm are
//! normalised after an exact power-of-two scaling, so n̂ stays unit, fuzz findings F1 and F4),
//! R* = RiRj/(Ri+Rj), m* = mimj/(mi+mj) (wall: R* = Ri, m* = mi), a = √(R*α). The contact
//! point is c = ri + n̂(Ri − α/2); lever arms run from each body's centre of mass to c.
//!
//! A touching contact whose pair uses only the base law, or the base law with JKR cohesion,
//! is evaluated by the fused law ([`crate::contact::fused`]) when it lies inside that law's
//! overflow envelope; any other (other optional effects, a base term switched off, an extreme
//! state, a JKR neck held beyond touching) by the pair's terms
//! ([`crate::pair::PairParams::evaluate`]), which check every operation.
//!
//! The stage runs in parts ([`ContactPart`]): each part owns a range of owner spheres (whole
//! bodies), the neighbour-list entries of those spheres (whose history it reads and updates in
//! place) and an accumulator arena. Loads on bodies of the part's own range go into the
//! world's accumulators (the part holds that range exclusively); loads on the partner body of
//! a contact that lies beyond the range go into the part's private arena, which the
//! integrator adds in. Every contact is a function of the state at the start of the step and
//! of its own history only, and in fixed point the sums are exact integers, so any number of
//! parts gives the same bits. One validity check per contact (force, torques, history) turns
//! any fixed-point overflow into [`StepError::Overflow`] naming both parties.

use super::multirate::{times, Cycle};
use super::neighbour_list::{is_wall, key_of, LIVE_FLAG, SLOW_PAIR_FLAG};
use super::parts::{widen, PairTable};
use super::prefetch::{prefetch_record, worth_hinting};
use crate::body::{Body, BodyForce, Sphere};
use crate::bond::arena::BondedPairs;
use crate::contact::fused::{evaluate_fast, evaluate_fast_jkr, FusedContact, FusedLoad, Geometry};
use crate::contact::{ContactKinematics, ContactState, EffectHistory, NeighbourEntry};
use crate::error::{Other, Stage, StepError};
use crate::num::{Envelope, Scalar, Vec3};
use crate::pair::PairParams;
use crate::wall::{Wall, MAX_WALLS};
use core::ops::Range;

/// What every part of the contact stage reads.
#[derive(Clone, Copy)]
pub(crate) struct Shared<'w, S: Scalar> {
    /// Bodies at the start of the step.
    pub bodies: &'w [Body<S>],
    /// Spheres at the start of the step.
    pub spheres: &'w [Sphere<S>],
    /// Pair parameters by material.
    pub pairs: &'w PairTable<S>,
    /// Walls.
    pub walls: &'w [Wall<S>],
    /// Live bonds: bonded pairs get no contact force.
    pub bonded: BondedPairs<'w, S>,
    /// Entry offsets of the live neighbour list, per owner sphere.
    pub offsets: &'w [u32],
    /// Time step, ms (the long step k·dt for the contacts between slow bodies).
    pub dt: S,
    /// Where the step lies in its multi-rate cycle ([`crate::step::multirate`]).
    pub cycle: Cycle<S>,
    /// Whether this is what the contacts between two slow bodies read
    /// ([`Shared::for_slow_pairs`]).
    pub slow_pairs: bool,
}

impl<S: Scalar> Shared<'_, S> {
    /// What the contacts between two slow bodies read: the long step for their springs.
    fn for_slow_pairs(&self) -> Self {
        Shared {
            dt: self.cycle.long_dt,
            slow_pairs: true,
            ..*self
        }
    }

    /// A contact's loads as they count: k times for a contact between slow bodies, which is
    /// evaluated once a cycle (its `dt` is the long step); `None` if that overflows.
    #[inline(always)]
    fn counted(&self, load: Load<S>) -> Option<Load<S>> {
        if !self.slow_pairs {
            return Some(load);
        }
        let k = self.cycle.stride;
        let counted = Load {
            force: times(load.force, k),
            torque_i: times(load.torque_i, k),
            torque_j: times(load.torque_j, k),
            roll_i: load.roll_i.mul_int(k as i32),
            roll_j: load.roll_j.mul_int(k as i32),
        };
        let valid = counted.force.is_valid()
            & counted.torque_i.is_valid()
            & counted.torque_j.is_valid()
            & counted.roll_i.is_valid()
            & counted.roll_j.is_valid();
        valid.then_some(counted)
    }
}

/// One part of the contact stage (see the module docs).
pub(crate) struct ContactPart<'w, S: Scalar> {
    /// Owner spheres of this part (whole bodies).
    pub spheres: Range<usize>,
    /// Bodies of those spheres.
    pub bodies: Range<usize>,
    /// The neighbour-list entries of the owner spheres.
    pub entries: &'w mut [NeighbourEntry<S>],
    /// Their effect history (empty when the world keeps none).
    pub effects: &'w mut [EffectHistory<S>],
    /// The world's accumulators of the bodies in `bodies`.
    pub own: &'w mut [BodyForce<S>],
    /// Accumulators (indexed by body id) for partner bodies beyond `bodies`; unused (may be
    /// empty) when the part is the last.
    pub beyond: &'w mut [BodyForce<S>],
    /// Bodies written in `beyond`, as a range (empty when none).
    pub beyond_touched: Range<usize>,
    /// Force on each wall, N (the force sums of an accumulator).
    pub wall_force: [BodyForce<S>; MAX_WALLS],
    /// The first error, if any.
    pub result: Result<(), StepError>,
}

impl<'w, S: Scalar> ContactPart<'w, S> {
    /// Evaluate every entry of the part.
    pub(crate) fn run(&mut self, sh: &Shared<'_, S>) {
        self.result = self.scan(sh);
    }

    /// Go through the part's entries: clear those whose pair does not touch, and evaluate the
    /// touching ones, by the fused law where the pair and the envelope allow, else by their
    /// terms.
    fn scan(&mut self, sh: &Shared<'_, S>) -> Result<(), StepError> {
        // One instance for single-rate worlds, in which the slow-pair test is not compiled
        // (with the test in the one loop, the DESIGN §8 pour took 1.7 % longer).
        if sh.cycle.multirate() {
            self.scan_with::<true>(sh)
        } else {
            self.scan_with::<false>(sh)
        }
    }

    /// [`ContactPart::scan`], with slow bodies (`MULTIRATE`) or without.
    #[inline(always)]
    fn scan_with<const MULTIRATE: bool>(&mut self, sh: &Shared<'_, S>) -> Result<(), StepError> {
        let base = sh.offsets[self.spheres.start] as usize;
        let with_effects = !self.effects.is_empty();
        let hint = worth_hinting(sh.spheres);
        let slow_sh = sh.for_slow_pairs();
        let single_rate = sh;
        let between_cycles = MULTIRATE && !sh.cycle.slow_contacts;
        for i in self.spheres.clone() {
            let range = sh.offsets[i] as usize - base..sh.offsets[i + 1] as usize - base;
            if hint {
                self.prefetch_partners(sh, i + PREFETCH_OWNERS_AHEAD, base);
            }
            let si = &sh.spheres[i];
            // The fast paths sum the owner's loads here and add them to its body once.
            let mut owner = BodyForce::<S>::default();
            let mut owner_touched = false;
            for e in range {
                let entry = self.entries[e];
                let key = key_of(entry.partner);
                // Two slow bodies meet once a cycle, with the long step; their entry keeps
                // its history in between (`crate::step::multirate`). The list flags their
                // entries and keeps them after the owner's others (`SLOW_PAIR_FLAG`), so
                // between a cycle's first step and the next the owner's first flagged entry
                // ends its scan; every write below keeps the flag.
                let slow = MULTIRATE && entry.partner & SLOW_PAIR_FLAG != 0;
                if slow && between_cycles {
                    break;
                }
                let sh = if slow { &slow_sh } else { single_rate };
                let fast = if is_wall(key) {
                    self.wall_fast(sh, si, key, e, &entry, &mut owner, with_effects)
                } else {
                    self.sphere_fast(sh, i, si, key as usize, e, &entry, &mut owner, with_effects)
                };
                match fast {
                    Fast::Done => {
                        owner_touched = true;
                        continue;
                    }
                    Fast::Apart => {
                        // A pair of the fused law keeps no effect history, so its slot
                        // holds the default and needs no test here.
                        if entry.partner != key || entry.delta != Vec3::ZERO {
                            self.write(e, key, &ContactState::default(), false);
                        }
                        continue;
                    }
                    Fast::General => {}
                }
                let state = ContactState::join(&entry, with_effects.then(|| &self.effects[e]));
                let found = if is_wall(key) {
                    wall_touch(sh, i, key, state)?
                } else {
                    sphere_touch(sh, i, key as usize, state)?
                };
                match found {
                    Some(mut touch) => {
                        let pair = touch.pair(sh);
                        if pair.fused.eligible {
                            let mut delta = state.delta.map(S::to_fast);
                            let mut root = state.jkr_root.to_fast();
                            let c = touch.fused_contact(sh);
                            let fused = pair.fused.fast();
                            if let Some(load) = evaluate_fast_jkr(&c, &fused, &mut delta, &mut root)
                            {
                                touch.state.delta = delta.map(S::from_fast);
                                touch.state.jkr_attached |= pair.fused.jkr;
                                touch.state.jkr_root = S::from_fast(root);
                                let load = sh.counted(load_of(&load)).ok_or(touch.overflow())?;
                                self.apply_touch(&touch, &load);
                                self.write(e, key, &touch.state, true);
                                continue;
                            }
                        }
                        self.by_terms(sh, e, key, touch)?;
                    }
                    // Only entries that held something need writing (a field's soil keeps
                    // effect history, and most of its entries stay apart step after step).
                    None if entry.partner != key
                        || entry.delta != Vec3::ZERO
                        || state.effects() != EffectHistory::default() =>
                    {
                        self.write(e, key, &ContactState::default(), false)
                    }
                    None => {}
                }
            }
            if owner_touched {
                self.acc(si.body as usize).merge(&owner);
            }
        }
        Ok(())
    }

    /// The fast path of a sphere–sphere entry (owner sphere `i`, record `si`, partner sphere
    /// `j`): the touching test and, for a pair that uses only the base law (with JKR
    /// cohesion or not), the fused law ([`crate::contact::fused::evaluate_fast_jkr`]) on the
    /// spheres' motion snapshots, in [`Scalar::Fast`] arithmetic.
    /// The centre difference cannot overflow: a listed pair was within reach plus the skin
    /// at the last rebuild and has moved less than the skin since. A bonded pair is apart, as
    /// on the general path. Anything else (optional effects, an undefined pair, a contact
    /// outside the fused law's envelope) goes to the general path, which takes the same
    /// touching decision (the same rounded |d|² and reach²).
    ///
    /// In a world that keeps effect history (`with_effects`) the pair is tested first: a
    /// pair with an effect may hold beyond touching (an attached JKR neck), which only the
    /// general path knows.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sphere_fast(
        &mut self,
        sh: &Shared<'_, S>,
        i: usize,
        si: &Sphere<S>,
        j: usize,
        e: usize,
        entry: &NeighbourEntry<S>,
        owner: &mut BodyForce<S>,
        with_effects: bool,
    ) -> Fast {
        let sj = &sh.spheres[j];
        let pair = &sh.pairs[si.material as usize][sj.material as usize];
        if with_effects && !pair.fused.eligible {
            return Fast::General;
        }
        if pair.fused.jkr {
            return self.sphere_pair_jkr(sh, i, si, sj, e, entry, owner, pair);
        }
        self.sphere_pair::<false>(sh, i, si, sj, e, entry, owner, pair)
    }

    /// [`ContactPart::sphere_pair`] for a JKR pair, out of line: the base law's path,
    /// inlined into the scan, then holds none of JKR's values (with one inlined path for
    /// both, the pour ran 2 % more instructions).
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn sphere_pair_jkr(
        &mut self,
        sh: &Shared<'_, S>,
        i: usize,
        si: &Sphere<S>,
        sj: &Sphere<S>,
        e: usize,
        entry: &NeighbourEntry<S>,
        owner: &mut BodyForce<S>,
        pair: &PairParams<S>,
    ) -> Fast {
        self.sphere_pair::<true>(sh, i, si, sj, e, entry, owner, pair)
    }

    /// The rest of [`ContactPart::sphere_fast`] for the pair `pair` of spheres `si`, `sj`,
    /// with JKR cohesion (`JKR`) or without.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sphere_pair<const JKR: bool>(
        &mut self,
        sh: &Shared<'_, S>,
        i: usize,
        si: &Sphere<S>,
        sj: &Sphere<S>,
        e: usize,
        entry: &NeighbourEntry<S>,
        owner: &mut BodyForce<S>,
        pair: &PairParams<S>,
    ) -> Fast {
        let j = key_of(entry.partner) as usize;
        let f = S::to_fast;
        let rs = f(si.radius) + f(sj.radius);
        // A JKR contact attached at its last step holds across its neck, out to the pair's
        // reach beyond touching (the general path's test, [`sphere_touch`]); the fused law
        // evaluates the neck in fixed point and leaves it to the general path in f64.
        let attached = JKR && self.jkr_attached(e);
        let reach = if attached { rs + f(pair.jkr.reach) } else { rs };
        if !reach.within(REACH_SQUARE_BITS) {
            // reach² could leave the range: the general path checks every operation.
            return Fast::General;
        }
        let d = sj.position.map(f) - si.position.map(f);
        if !(d.x.abs() < reach && d.y.abs() < reach && d.z.abs() < reach) {
            return Fast::Apart;
        }
        let d2 = d.norm2();
        if d2 >= reach * reach {
            return Fast::Apart;
        }
        if !pair.fused.eligible {
            return Fast::General;
        }
        if sh.bonded.joins(i as u32, j as u32) {
            return Fast::Apart;
        }
        // R* = RiRj/(Ri+Rj) and m* = mimj/(mi+mj), halved exactly when equal.
        let r_star = if si.radius == sj.radius {
            f(si.radius) * S::Fast::HALF
        } else {
            f(si.radius) * f(sj.radius) / rs
        };
        let m_star = effective_mass(f(si.mass), f(si.inv_mass), f(sj.mass), f(sj.inv_mass));
        let arm = |s: &Sphere<S>| s.in_clump().then(|| s.arm.map(f));
        let c = FusedContact {
            geometry: Geometry::Spheres {
                d,
                d2,
                r_j: f(sj.radius),
            },
            r_i: f(si.radius),
            r_star,
            m_star,
            v_centres: sj.velocity.map(f) - si.velocity.map(f),
            spin_i: si.spin.map(f),
            spin_j: sj.spin.map(f),
            offset_i: arm(si),
            offset_j: arm(sj),
            dt: f(sh.dt),
        };
        let mut delta = entry.delta.map(f);
        let mut root = S::Fast::ZERO;
        let load = if JKR {
            root = self.last_jkr_root(pair, e);
            evaluate_fast_jkr(&c, &pair.fused.fast(), &mut delta, &mut root)
        } else {
            evaluate_fast(&c, &pair.fused.fast(), &mut delta)
        };
        let Some(load) = load else {
            return Fast::General;
        };
        if JKR && attached && root == S::Fast::ZERO {
            // The neck broke: no loads, and the scan clears the entry.
            return Fast::Apart;
        }
        let Some(load) = sh.counted(load_of(&load)) else {
            // Counted k times it overflows: the general path reports it.
            return Fast::General;
        };
        owner.sub_force(load.force);
        owner.add_torque(-load.torque_i);
        owner.add_roll(load.roll_i);
        let a = self.acc(sj.body as usize);
        a.add_force(load.force);
        a.add_torque(load.torque_j);
        a.add_roll(load.roll_j);
        self.entries[e] = NeighbourEntry {
            partner: j as u32 | LIVE_FLAG | (entry.partner & SLOW_PAIR_FLAG),
            delta: delta.map(S::from_fast),
        };
        if JKR {
            self.note_jkr_attached(pair, e, root);
        }
        Fast::Done
    }

    /// Whether entry `e`'s JKR contact was attached at its last step (its neck may hold
    /// beyond touching).
    #[inline(always)]
    fn jkr_attached(&self, e: usize) -> bool {
        self.effects.get(e).is_some_and(|f| f.jkr_attached)
    }

    /// The JKR root x = √a of entry `e` at its last step, where the fused law's Newton loop
    /// starts ([`crate::contact::fused::jkr`]); zero for a pair without JKR.
    #[inline(always)]
    fn last_jkr_root(&self, pair: &PairParams<S>, e: usize) -> S::Fast {
        match self.effects.get(e) {
            Some(f) if pair.fused.jkr => f.jkr_root.to_fast(),
            _ => S::Fast::ZERO,
        }
    }

    /// After the fused law evaluated entry `e` of `pair`: a touching JKR contact is attached
    /// (its neck will hold beyond touching), as the checked term records it, and keeps its
    /// root for the next step's start.
    #[inline(always)]
    fn note_jkr_attached(&mut self, pair: &PairParams<S>, e: usize, root: S::Fast) {
        if pair.fused.jkr {
            if let Some(f) = self.effects.get_mut(e) {
                *f = EffectHistory {
                    jkr_attached: true,
                    jkr_root: S::from_fast(root),
                    ..EffectHistory::default()
                };
            }
        }
    }

    /// The fast path of a sphere–wall entry (see [`ContactPart::sphere_fast`]): the wall
    /// face's geometry (checked arithmetic, as in the general path), then the fused law.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn wall_fast(
        &mut self,
        sh: &Shared<'_, S>,
        si: &Sphere<S>,
        key: u32,
        e: usize,
        entry: &NeighbourEntry<S>,
        owner: &mut BodyForce<S>,
        with_effects: bool,
    ) -> Fast {
        let wi = ((key & !crate::contact::WALL_PARTNER_FLAG) >> 4) as usize;
        let w = &sh.walls[wi];
        let pair = &sh.pairs[si.material as usize][w.material as usize];
        if with_effects && !pair.fused.eligible {
            return Fast::General;
        }
        let Some((normal, overlap)) = w.shape.contact(key & 0xF, si.position, si.radius) else {
            return Fast::Apart;
        };
        let wall_velocity = wall_velocity_at(w, si, normal, overlap);
        if !pair.fused.eligible {
            return Fast::General;
        }
        let f = S::to_fast;
        let c = FusedContact {
            geometry: Geometry::Wall {
                normal: normal.map(f),
                overlap: f(overlap),
            },
            r_i: f(si.radius),
            r_star: f(si.radius),
            m_star: f(si.mass),
            v_centres: wall_velocity.map(f) - si.velocity.map(f),
            spin_i: si.spin.map(f),
            spin_j: Vec3::ZERO,
            offset_i: si.in_clump().then(|| si.arm.map(f)),
            offset_j: None,
            dt: f(sh.dt),
        };
        let mut delta = entry.delta.map(f);
        let mut root = self.last_jkr_root(pair, e);
        let Some(load) = evaluate_fast_jkr(&c, &pair.fused.fast(), &mut delta, &mut root) else {
            return Fast::General;
        };
        let load = load_of(&load);
        owner.sub_force(load.force);
        owner.add_torque(-load.torque_i);
        owner.add_roll(load.roll_i);
        self.wall_force[wi].add_force(load.force);
        self.entries[e] = NeighbourEntry {
            partner: key | LIVE_FLAG,
            delta: delta.map(S::from_fast),
        };
        self.note_jkr_attached(pair, e, root);
        Fast::Done
    }

    /// Start loading the partner spheres of owner `i`'s entries (if the part has the owner):
    /// their position and motion snapshot, the records' first two cache lines. One test of
    /// the hint per owner, not per entry, keeps the cost off worlds that do not use it.
    #[inline(always)]
    fn prefetch_partners(&self, sh: &Shared<'_, S>, i: usize, base: usize) {
        if i >= self.spheres.end {
            return;
        }
        let entries = sh.offsets[i] as usize - base..sh.offsets[i + 1] as usize - base;
        for entry in &self.entries[entries] {
            prefetch_record(
                sh.spheres,
                key_of(entry.partner) as usize,
                SPHERE_LINES_READ,
            );
        }
    }

    /// Store the history and live flag of entry `e`.
    #[inline(always)]
    fn write(&mut self, e: usize, key: u32, state: &ContactState<S>, live: bool) {
        let slow = self.entries[e].partner & SLOW_PAIR_FLAG;
        self.entries[e] = NeighbourEntry {
            partner: if live { key | LIVE_FLAG } else { key } | slow,
            delta: state.delta,
        };
        if let Some(f) = self.effects.get_mut(e) {
            *f = state.effects();
        }
    }

    /// Evaluate the touching contact of entry `e` by its pair's terms (checked arithmetic),
    /// apply its loads and store its history.
    fn by_terms(
        &mut self,
        sh: &Shared<'_, S>,
        e: usize,
        key: u32,
        touch: Touch<S>,
    ) -> Result<(), StepError> {
        let pair = touch.pair(sh);
        let mut lane = Lane::new(touch);
        lane.geometry(sh);
        lane.kinematics(sh);
        lane.roots(sh);
        lane.law(sh);
        let load = lane.load.and_then(|l| sh.counted(l));
        let load = load.ok_or(lane.t.overflow())?;
        self.apply_touch(&lane.t, &load);
        if pair.jkr.on && !lane.t.state.jkr_attached {
            // The JKR neck broke (beyond the separation): the law gave no force.
            self.write(e, key, &ContactState::default(), false);
        } else {
            self.write(e, key, &lane.t.state, pair.keeps_history());
        }
        Ok(())
    }

    /// Add a contact's loads to its bodies (and to its wall's force).
    #[inline(always)]
    fn apply_touch(&mut self, lane: &Touch<S>, load: &Load<S>) {
        let bi = lane.body_i as usize;
        if lane.is_wall() {
            self.apply(load, bi, None);
            self.wall_force[lane.wall as usize].add_force(load.force);
        } else {
            self.apply(load, bi, Some(lane.body_j as usize));
        }
    }

    /// The accumulator of body `b` (in the part's range, or beyond it).
    #[inline(always)]
    fn acc(&mut self, b: usize) -> &mut BodyForce<S> {
        if b < self.bodies.end {
            &mut self.own[b - self.bodies.start]
        } else {
            widen(&mut self.beyond_touched, b);
            &mut self.beyond[b]
        }
    }

    /// Add the loads of one contact (forces on i and j, lever torques) to the accumulators.
    #[inline(always)]
    fn apply(&mut self, load: &Load<S>, bi: usize, bj: Option<usize>) {
        {
            let a = self.acc(bi);
            a.sub_force(load.force);
            a.add_torque(-load.torque_i);
            a.add_roll(load.roll_i);
        }
        if let Some(bj) = bj {
            let a = self.acc(bj);
            a.add_force(load.force);
            a.add_torque(load.torque_j);
            a.add_roll(load.roll_j);
        }
    }
}

/// The fast path's sum of radii stays below 2^15 mm, so that |d|² and rs² (< 3·2^30 mm²)
/// cannot leave the Q32.32 range.
const REACH_SQUARE_BITS: i32 = 15;

/// How many owners ahead the scan asks for the partner spheres' records: far enough for the
/// loads to arrive while the owner in between is evaluated (an owner has about three
/// entries in a settled bed).
const PREFETCH_OWNERS_AHEAD: usize = 1;

/// Cache lines of a sphere record the contact scan reads (position and radius, then the
/// motion snapshot; [`Sphere`]'s layout).
const SPHERE_LINES_READ: usize = 2;

/// What the fast path did with an entry.
enum Fast {
    /// Evaluated, loads applied, history stored.
    Done,
    /// Not touching.
    Apart,
    /// Left to the general path.
    General,
}

/// Marks a lane whose partner is a wall (`Lane::body_j`).
const WALL_LANE: u32 = u32::MAX;

/// A touching contact as the scan found it.
#[derive(Clone, Copy)]
struct Touch<S: Scalar> {
    /// Sphere i and its body.
    sphere_i: u32,
    body_i: u32,
    /// Sphere j and its body, or [`WALL_LANE`] and the wall id.
    sphere_j: u32,
    body_j: u32,
    wall: u32,
    /// Materials of i and of j (or of the wall).
    material_i: u16,
    material_j: u16,
    /// j − i between sphere centres (sphere contacts), mm, and its square, mm².
    d: Vec3<S>,
    d2: S,
    /// Unit normal from i towards j, and the overlap α, mm (wall contacts; sphere contacts
    /// get them from `d` in the evaluation).
    normal: Vec3<S>,
    overlap: S,
    /// The wall's velocity, mm/ms (zero for a sphere partner).
    wall_velocity: Vec3<S>,
    /// History, updated by the evaluation.
    state: ContactState<S>,
}

/// A contact evaluated by the pair's terms: what the scan found, then each stage's results.
#[derive(Clone, Copy)]
struct Lane<S: Scalar> {
    /// The contact as found.
    t: Touch<S>,
    /// Unit normal from i towards j, and the overlap α, mm.
    normal: Vec3<S>,
    overlap: S,
    /// R*·α (mm²), R* (mm, zero unless a term needs it), m* (g, zero unless damping needs it).
    r_star_alpha: S,
    r_star: S,
    m_star: S,
    /// Distance from j's centre to the contact point when j is a single sphere (Rj − α/2).
    arm_len_j: S,
    /// Lever arms from each body's centre of mass to the contact point, mm.
    arm_i: Vec3<S>,
    arm_j: Vec3<S>,
    /// Contact velocity v_j − v_i at the contact point, mm/ms.
    v_rel: Vec3<S>,
    /// What the contact terms see.
    kin: ContactKinematics<S>,
    /// The loads; `None` when a value overflowed.
    load: Option<Load<S>>,
}

impl<S: Scalar> Lane<S> {
    fn new(t: Touch<S>) -> Self {
        Lane {
            t,
            normal: t.normal,
            overlap: t.overlap,
            r_star_alpha: S::ZERO,
            r_star: S::ZERO,
            m_star: S::ZERO,
            arm_len_j: S::ZERO,
            arm_i: Vec3::ZERO,
            arm_j: Vec3::ZERO,
            v_rel: t.wall_velocity,
            kin: ContactKinematics::default(),
            load: None,
        }
    }
}

/// The contact of sphere–wall entry `key` of sphere `si`, if that face touches.
#[inline(always)]
fn wall_touch<S: Scalar>(
    sh: &Shared<'_, S>,
    si: usize,
    key: u32,
    state: ContactState<S>,
) -> Result<Option<Touch<S>>, StepError> {
    let wi = ((key & !crate::contact::WALL_PARTNER_FLAG) >> 4) as usize;
    let face = key & 0xF;
    let s = &sh.spheres[si];
    let w = &sh.walls[wi];
    let Some((normal, overlap)) = w.shape.contact(face, s.position, s.radius) else {
        return Ok(None);
    };
    if !sh.pairs[s.material as usize][w.material as usize].defined {
        return Err(StepError::UndefinedPair {
            material_a: s.material,
            material_b: w.material,
        });
    }
    Ok(Some(Touch {
        sphere_i: si as u32,
        body_i: s.body,
        sphere_j: WALL_LANE,
        body_j: WALL_LANE,
        wall: wi as u32,
        material_i: s.material,
        material_j: w.material,
        d: Vec3::ZERO,
        d2: S::ZERO,
        normal,
        overlap,
        wall_velocity: wall_velocity_at(w, s, normal, overlap),
        state,
    }))
}

/// The velocity of wall `w`'s surface where sphere `s` touches it (unit `normal` from the
/// sphere towards the wall, `overlap` α, mm): at the contact point c = r + n̂(R − α/2), the
/// point the contact law takes the sphere's lever to. Checked arithmetic; the wall's own
/// velocity, the same bits, unless it spins.
#[inline(always)]
fn wall_velocity_at<S: Scalar>(w: &Wall<S>, s: &Sphere<S>, normal: Vec3<S>, overlap: S) -> Vec3<S> {
    if w.spin == S::ZERO {
        return w.velocity;
    }
    w.velocity_at(s.position + normal.scale(s.radius - overlap * S::HALF))
}

/// The contact of neighbour-list pair (i < j), if it touches (and is not bonded).
#[inline(always)]
fn sphere_touch<S: Scalar>(
    sh: &Shared<'_, S>,
    i: usize,
    j: usize,
    state: ContactState<S>,
) -> Result<Option<Touch<S>>, StepError> {
    let si = &sh.spheres[i];
    let sj = &sh.spheres[j];
    let d = sj.position - si.position;
    let rs = si.radius + sj.radius;
    // An attached JKR contact holds across a neck, down to a negative overlap.
    let reach = if state.jkr_attached {
        rs + sh.pairs[si.material as usize][sj.material as usize]
            .jkr
            .reach
    } else {
        rs
    };
    // Cheap per-axis rejection before the squared distance.
    if d.x.abs() >= reach || d.y.abs() >= reach || d.z.abs() >= reach {
        return Ok(None);
    }
    let d2 = d.norm2();
    if !d2.is_valid() {
        return Err(StepError::Overflow {
            stage: Stage::SphereContact,
            body: si.body,
            other: Other::Body(sj.body),
        });
    }
    if d2 >= reach * reach {
        return Ok(None);
    }
    if sh.bonded.joins(i as u32, j as u32) {
        // A bond carries the load; the pair meets the contact law, with fresh history, only
        // once the bond breaks.
        return Ok(None);
    }
    if !sh.pairs[si.material as usize][sj.material as usize].defined {
        return Err(StepError::UndefinedPair {
            material_a: si.material,
            material_b: sj.material,
        });
    }
    Ok(Some(Touch {
        sphere_i: i as u32,
        body_i: si.body,
        sphere_j: j as u32,
        body_j: sj.body,
        wall: 0,
        material_i: si.material,
        material_j: sj.material,
        d,
        d2,
        normal: Vec3::ZERO,
        overlap: S::ZERO,
        wall_velocity: Vec3::ZERO,
        state,
    }))
}

impl<S: Scalar> Touch<S> {
    #[inline(always)]
    fn is_wall(&self) -> bool {
        self.body_j == WALL_LANE
    }

    #[inline(always)]
    fn pair<'p>(&self, sh: &Shared<'p, S>) -> &'p PairParams<S> {
        &sh.pairs[self.material_i as usize][self.material_j as usize]
    }

    /// The error of an overflow in this contact, naming both parties.
    fn overflow(&self) -> StepError {
        if self.is_wall() {
            StepError::Overflow {
                stage: Stage::WallContact,
                body: self.body_i,
                other: Other::Wall(self.wall),
            }
        } else {
            StepError::Overflow {
                stage: Stage::SphereContact,
                body: self.body_i,
                other: Other::Body(self.body_j),
            }
        }
    }

    /// The contact as the fused law sees it, in [`Scalar::Fast`] arithmetic.
    #[inline(always)]
    fn fused_contact(&self, sh: &Shared<'_, S>) -> FusedContact<S::Fast> {
        let si = &sh.spheres[self.sphere_i as usize];
        let bi = &sh.bodies[self.body_i as usize];
        // Velocity of a sphere's centre, and its centre's offset from the body's centre of
        // mass (clumps only; checked arithmetic, as in the terms).
        let centre = |s: &Sphere<S>, b: &Body<S>| {
            if b.is_clump {
                let o = s.position - b.position;
                (
                    b.velocity + b.angular_velocity.cross(o),
                    Some(o.map(S::to_fast)),
                )
            } else {
                (b.velocity, None)
            }
        };
        let (v_i, offset_i) = centre(si, bi);
        let fast = |v: Vec3<S>| v.map(S::to_fast);
        if self.is_wall() {
            return FusedContact {
                geometry: Geometry::Wall {
                    normal: fast(self.normal),
                    overlap: self.overlap.to_fast(),
                },
                r_i: si.radius.to_fast(),
                r_star: si.radius.to_fast(),
                m_star: bi.mass.to_fast(),
                v_centres: fast(self.wall_velocity - v_i),
                spin_i: fast(bi.angular_velocity),
                spin_j: Vec3::ZERO,
                offset_i,
                offset_j: None,
                dt: sh.dt.to_fast(),
            };
        }
        let sj = &sh.spheres[self.sphere_j as usize];
        let bj = &sh.bodies[self.body_j as usize];
        let (v_j, offset_j) = centre(sj, bj);
        // R* = RiRj/(Ri+Rj) and m* = mimj/(mi+mj), halved exactly when equal.
        let r_star = if si.radius == sj.radius {
            si.radius * S::HALF
        } else {
            si.radius * sj.radius / (si.radius + sj.radius)
        };
        let m_star = effective_mass(bi.mass, bi.inv_mass, bj.mass, bj.inv_mass);
        FusedContact {
            geometry: Geometry::Spheres {
                d: fast(self.d),
                d2: self.d2.to_fast(),
                r_j: sj.radius.to_fast(),
            },
            r_i: si.radius.to_fast(),
            r_star: r_star.to_fast(),
            m_star: m_star.to_fast(),
            v_centres: fast(v_j - v_i),
            spin_i: fast(bi.angular_velocity),
            spin_j: fast(bj.angular_velocity),
            offset_i,
            offset_j,
            dt: sh.dt.to_fast(),
        }
    }
}

impl<S: Scalar> Lane<S> {
    /// Normal, overlap, R*·α, R* and m* (module docs; a wall lane has its normal and overlap
    /// from the wall, R* = Ri and m* = mi).
    #[inline(always)]
    fn geometry(&mut self, sh: &Shared<'_, S>) {
        let pair = self.t.pair(sh);
        let si = &sh.spheres[self.t.sphere_i as usize];
        if self.t.is_wall() {
            self.r_star_alpha = si.radius * self.overlap;
            self.r_star = si.radius;
            self.m_star = sh.bodies[self.t.body_i as usize].mass;
            return;
        }
        let sj = &sh.spheres[self.t.sphere_j as usize];
        let rs = si.radius + sj.radius;
        let (d, d2) = (self.t.d, self.t.d2);
        // Beyond 1 mm the squared distance has ≥ 32 significant bits: dist is its correctly
        // rounded root (the overlap needs every bit) and the normal only needs 1/dist to within
        // a unit, which rsqrt gives without a division. Closer centres (huge overlaps)
        // normalise d after an exact power-of-two scaling, because a rounded |d|² of a few raw
        // units would leave the normal visibly non-unit (fuzz finding F4; F1 was the |d|² = 0
        // case); exactly coincident centres take n = +z, a deterministic choice.
        let (n, dist) = if d2 >= S::ONE {
            let (root, inv_root) = d2.sqrt_rsqrt();
            (d.scale(inv_root), root)
        } else if let Some(u_len) = d.normalize_with_len() {
            u_len
        } else {
            (Vec3::new(S::ZERO, S::ZERO, S::ONE), S::ZERO)
        };
        let overlap = rs - dist;
        self.normal = n;
        self.overlap = overlap;
        // R* = RiRj/(Ri+Rj) and m* = mimj/(mi+mj); equal radii/masses (monodisperse beds) take
        // the exact halving shortcut and skip a division each.
        self.r_star_alpha = if si.radius == sj.radius {
            si.radius * S::HALF * overlap
        } else {
            si.radius * sj.radius * overlap / rs
        };
        self.r_star = if !pair.needs_r_star() {
            S::ZERO
        } else if si.radius == sj.radius {
            si.radius * S::HALF
        } else {
            si.radius * sj.radius / rs
        };
        self.m_star = if pair.needs_damping() {
            let (bi, bj) = (
                &sh.bodies[self.t.body_i as usize],
                &sh.bodies[self.t.body_j as usize],
            );
            effective_mass(bi.mass, bi.inv_mass, bj.mass, bj.inv_mass)
        } else {
            S::ZERO
        };
        self.arm_len_j = sj.radius - overlap * S::HALF;
    }

    /// Lever arms, contact velocity and its normal and tangential parts, levers of rolling
    /// friction, and the EPSD relative spin and rolling inertia.
    #[inline(always)]
    fn kinematics(&mut self, sh: &Shared<'_, S>) {
        let pair = self.t.pair(sh);
        let si = &sh.spheres[self.t.sphere_i as usize];
        let bod_i = &sh.bodies[self.t.body_i as usize];
        let n = self.normal;
        let arm_len_i = si.radius - self.overlap * S::HALF;
        let c = si.position + n.scale(arm_len_i);
        let arm_i = c - bod_i.position;
        // v_rel starts as the wall's velocity (zero for a sphere partner).
        let mut v_rel = self.v_rel - (bod_i.velocity + bod_i.angular_velocity.cross(arm_i));
        let mut arm_j = Vec3::ZERO;
        let mut lever_j = S::ZERO;
        let mut w_rel = Vec3::ZERO;
        let mut rolling_inertia = S::ZERO;
        if pair.needs_relative_spin() {
            w_rel = bod_i.angular_velocity;
        }
        if pair.rolling_epsd.on {
            rolling_inertia = rolling_moment(bod_i, arm_i);
        }
        if !self.t.is_wall() {
            let bod_j = &sh.bodies[self.t.body_j as usize];
            arm_j = c - bod_j.position;
            if pair.needs_relative_spin() {
                w_rel -= bod_j.angular_velocity;
            }
            if pair.rolling_epsd.on && bod_j.inv_mass != S::ZERO {
                let ij = rolling_moment(bod_j, arm_j);
                rolling_inertia = rolling_inertia * ij / (rolling_inertia + ij);
            }
            v_rel += bod_j.velocity + bod_j.angular_velocity.cross(arm_j);
            if pair.rolling.on {
                lever_j = if bod_j.is_clump {
                    arm_j.norm()
                } else {
                    self.arm_len_j
                };
            }
        }
        let vn = v_rel.dot(n);
        let lever_i = if pair.rolling.on && bod_i.is_clump {
            arm_i.norm()
        } else {
            arm_len_i
        };
        self.arm_i = arm_i;
        self.arm_j = arm_j;
        self.v_rel = v_rel;
        self.kin = ContactKinematics {
            normal: n,
            overlap: self.overlap,
            contact_radius: S::ZERO,
            sqrt_a_mstar: S::ZERO,
            vn,
            vt: v_rel - n.scale(vn),
            dt: sh.dt,
            lever_i,
            lever_j,
            r_star: self.r_star,
            w_rel,
            rolling_inertia,
        };
    }

    /// The contact radius a = √(R*α) and √(a·m*) for the damping terms.
    #[inline(always)]
    fn roots(&mut self, sh: &Shared<'_, S>) {
        // A JKR neck (negative overlap) has no Hertz contact radius.
        let a = if self.r_star_alpha > S::ZERO {
            self.r_star_alpha.sqrt()
        } else {
            S::ZERO
        };
        self.kin.contact_radius = a;
        self.kin.sqrt_a_mstar = if self.t.pair(sh).needs_damping() {
            (a * self.m_star).sqrt()
        } else {
            S::ZERO
        };
    }

    /// The contact terms, then the force on j and the lever torques.
    #[inline(always)]
    fn law(&mut self, sh: &Shared<'_, S>) {
        let pair = self.t.pair(sh);
        if !pair.keeps_history() {
            self.t.state = ContactState::default();
        }
        let out = pair.evaluate(&self.kin, &mut self.t.state);
        let f = self.normal.scale(out.normal) + out.tangential;
        let mut ti = self.arm_i.cross(f);
        let mut tj = self.arm_j.cross(f);
        if pair.needs_relative_spin() {
            // EPSD or LIGGGHTS rolling torque on j; i receives the opposite (i's torque is −ti).
            ti += out.rolling_torque;
            tj += out.rolling_torque;
        }
        let valid = f.is_valid()
            & ti.is_valid()
            & tj.is_valid()
            & out.roll_i.is_valid()
            & out.roll_j.is_valid()
            & self.t.state.delta.is_valid();
        self.load = valid.then_some(Load {
            force: f,
            torque_i: ti,
            torque_j: tj,
            roll_i: out.roll_i,
            roll_j: out.roll_j,
        });
    }
}

/// The loads of a fused evaluation in the world's scalar.
#[inline(always)]
fn load_of<S: Scalar>(l: &FusedLoad<S::Fast>) -> Load<S> {
    Load {
        force: l.force.map(S::from_fast),
        torque_i: l.torque_i.map(S::from_fast),
        torque_j: l.torque_j.map(S::from_fast),
        roll_i: S::from_fast(l.roll_i),
        roll_j: S::from_fast(l.roll_j),
    }
}

/// The loads of one contact.
#[derive(Clone, Copy, Debug, Default)]
struct Load<S> {
    /// Force on j (i receives the opposite), N.
    force: Vec3<S>,
    /// Torque of the contact on i is −`torque_i`, N·mm.
    torque_i: Vec3<S>,
    /// Torque of the contact on j, N·mm.
    torque_j: Vec3<S>,
    /// Rolling-resistance torque magnitude on i, N·mm.
    roll_i: S,
    /// Rolling-resistance torque magnitude on j, N·mm.
    roll_j: S,
}

/// m* = mᵢmⱼ/(mᵢ + mⱼ), g, from the masses (g) and inverse masses (1/g) of two bodies:
/// halved exactly when the bodies are alike (monodisperse beds skip a division); against a
/// kinematic partner (inverse mass 0, though it keeps its material's mass) the moving body's
/// mass, which is why the shortcut also compares inverse masses (a sphere once bounced off a
/// fixed equal sphere 17 % too fast, found by the LIGGGHTS cross-check); zero between two
/// kinematic bodies, which no force moves, instead of a division by zero.
#[inline(always)]
fn effective_mass<T: Scalar>(m_i: T, inv_i: T, m_j: T, inv_j: T) -> T {
    let inv = inv_i + inv_j;
    if inv == T::ZERO {
        T::ZERO
    } else if m_i == m_j && inv_i == inv_j {
        m_i * T::HALF
    } else {
        T::ONE / inv
    }
}

/// I + m·|arm|², g·mm², of one side of a rolling contact (Ai et al. 2011 eq. (14)): a
/// sphere's I, or for a clump the mean principal moment (an approximation: the exact rolling
/// inertia of a clump depends on the rolling axis).
#[inline]
fn rolling_moment<S: Scalar>(b: &Body<S>, arm: Vec3<S>) -> S {
    let i = if b.is_clump {
        (b.inertia.x + b.inertia.y + b.inertia.z) / S::ONE.mul_int(3)
    } else {
        b.inertia.x
    };
    i + b.mass * arm.norm2()
}
