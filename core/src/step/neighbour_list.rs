//! Verlet neighbour list with a skin, and the contact history stored beside its entries.
//!
//! The list holds, per owner sphere (the lower id of a pair), every sphere of another body
//! whose surface was within the skin s = R_max / [`SKIN_DIVISOR`] when the list was built:
//! |rj − ri| < Ri + Rj + s. A pair not in the list was farther apart than that, so it cannot
//! touch until one sphere of it has moved by s/2 or both by a total of s. The integrator adds
//! each step's largest sphere displacement (L1 norm, an upper bound on the Euclidean one) to
//! a drift bound; once 2·drift ≥ s the list is marked stale and rebuilt at the start of the
//! next step, from the cell grid of [`super::broad_phase`] with cell edge 2·R_max + s. Adding
//! a sphere or a wall also marks it stale. The rebuild is a pure function of the positions,
//! and since every touching pair is in the list, the contacts evaluated each step, and in
//! fixed point every force, do not depend on when rebuilds happen.
//!
//! Walls get the same treatment: a rebuild gives each sphere one entry per wall face it lies
//! within the skin of ([`crate::wall::WallShape::faces_near`]), after its sphere entries, and
//! the contact loop tests only those. Wall motion adds to the drift bound like sphere motion,
//! so a face left out cannot touch the sphere before the next rebuild.
//!
//! Storage: the list is packed (CSR): the entries of owner i are
//! `offsets[i]..offsets[i + 1]`, so a crowded sphere borrows room from a lonely one and the
//! contact loop streams through memory. Each entry carries its contact history
//! ([`NeighbourEntry`], and [`EffectHistory`] in a parallel arena where effects are used), so
//! the contact loop reads and updates δt in place with no search. The list is double-buffered:
//! a rebuild writes the idle half, copying each surviving entry's history (one short linear
//! search per entry, only on rebuild), then swaps halves. Entry keys carry [`LIVE_FLAG`] while
//! the pair touched in the last step with a term that keeps history: those are the "contacts
//! with history" that the world reports and the digest hashes; other entries have zero
//! history. More entries than one half holds is [`StepError::ContactCapacity`].
//!
//! ```
//! use arachis_core::step::neighbour_list::{key_of, LIVE_FLAG};
//! assert_eq!(key_of(7 | LIVE_FLAG), 7);
//! ```

use super::broad_phase::bin_spheres;
use super::parts::{Parallel, Serial, MAX_PARTS};
use super::prefetch::{prefetch_record, worth_hinting};
use crate::body::arena::index_len;
use crate::body::Sphere;
use crate::contact::history::wall_key;
use crate::contact::{EffectHistory, NeighbourEntry, WALL_PARTNER_FLAG};
use crate::error::{CapacityKind, Other, SetupError, Stage, StepError};
use crate::num::{Envelope, Scalar, Vec3};
use crate::state_words::{flag, index, scalar, vec3, CheckpointError, StateWords};
use crate::wall::Wall;

/// Partner-key flag of an entry whose pair touched in the last step and keeps history.
/// Sphere ids stay below 2^29 (the world refuses larger capacities) and wall keys use
/// [`WALL_PARTNER_FLAG`] with wall < 16, so the bit is free in every key.
pub const LIVE_FLAG: u32 = 0x4000_0000;

/// The skin is R_max / `SKIN_DIVISOR` (1 mm for the 4 mm spheres of the bench bed): larger
/// skins rebuild less often but hold more non-touching entries per sphere. R/4 was the
/// fastest of R/2 … R/16 on the DESIGN §8 bed and on the quick pod pile (core/API_NOTES.md,
/// 2026-11-27); in fixed point the results do not depend on it.
pub const SKIN_DIVISOR: i32 = 4;

/// How many candidates of a row ahead the rebuild asks for the sphere's record (its first
/// cache line: position, radius, body), so that the load overlaps the distance tests in
/// between ([`super::prefetch`]).
const PREFETCH_CANDIDATES_AHEAD: usize = 4;

/// Below a reach of 2^15 mm the rebuild squares distances in the unchecked arithmetic
/// (|d|² < 3·2^30 mm² stays in range).
const FAST_SQUARE_REACH_BITS: i32 = 15;

/// Partner-key flag of an entry between two slow bodies ([`crate::step::multirate`]). In a
/// multi-rate world the list sets it and keeps a slow owner's flagged entries after its
/// others (`order_slow_pairs`), so that at the steps between a cycle's first and the next
/// the contact scan stops at an owner's first flagged entry: it neither evaluates nor reads
/// the rest. Free in every key for the same reason as [`LIVE_FLAG`] (sphere ids below 2^29).
pub const SLOW_PAIR_FLAG: u32 = 0x2000_0000;

/// The partner key without [`LIVE_FLAG`] and [`SLOW_PAIR_FLAG`].
#[inline(always)]
pub fn key_of(partner: u32) -> u32 {
    partner & !(LIVE_FLAG | SLOW_PAIR_FLAG)
}

/// The live half of the list, read-only.
#[derive(Clone, Copy)]
pub struct Live<'l, S> {
    /// Entry offsets per owner sphere (one more than the spheres listed).
    pub offsets: &'l [u32],
    /// The entries.
    pub entries: &'l [NeighbourEntry<S>],
    /// The effect history beside the entries (empty when the world keeps none).
    pub effects: &'l [EffectHistory<S>],
}

impl<S: Scalar> Live<'_, S> {
    /// The entry index range of owner sphere `s` (empty if `s` is not listed).
    #[inline(always)]
    pub fn range(&self, s: usize) -> core::ops::Range<usize> {
        if s + 1 < self.offsets.len() {
            self.offsets[s] as usize..self.offsets[s + 1] as usize
        } else {
            0..0
        }
    }
}

/// The live half of the list, with entries and history writable (the contact stage).
pub struct LiveMut<'l, S> {
    /// Entry offsets per owner sphere (one more than the spheres listed).
    pub offsets: &'l [u32],
    /// The entries.
    pub entries: &'l mut [NeighbourEntry<S>],
    /// The effect history beside the entries (empty when the world keeps none).
    pub effects: &'l mut [EffectHistory<S>],
}

/// The neighbour list over caller-provided arenas (see the module docs).
pub struct NeighbourList<'a, S> {
    entries: &'a mut [NeighbourEntry<S>],
    effects: &'a mut [EffectHistory<S>],
    /// `[0, n)` cell of each sphere, `[n, 2n)` spheres sorted by cell, then the entry offsets
    /// of both halves (n + 1 each); n = sphere capacity.
    index: &'a mut [u32],
    cells: &'a mut [u32],
    sphere_capacity: usize,
    /// Entries per half.
    half: usize,
    /// Which half is live.
    current: usize,
    /// Spheres the live half lists.
    listed: usize,
    /// `false` until the list is (re)built.
    valid: bool,
    /// Upper bound on any sphere's (or wall's) displacement since the last build, mm.
    drift: S,
    /// Skin of the current list, mm.
    skin: S,
    /// Builds so far.
    builds: u64,
    /// The skin is R_max / `skin_divisor` ([`SKIN_DIVISOR`] unless a test changes it).
    pub(crate) skin_divisor: i32,
    /// Whether pairs of which neither side can respond are listed
    /// ([`crate::world::World::set_prescribed_contacts`]).
    pub(crate) prescribed_pairs: bool,
    /// Whether the world steps at more than one rate, so that a slow owner's slow pairs are
    /// flagged and kept last ([`SLOW_PAIR_FLAG`]).
    slow_pairs_last: bool,
}

impl<'a, S: Scalar> NeighbourList<'a, S> {
    /// An empty list over the arenas, for up to `spheres` spheres.
    pub(crate) fn new(
        entries: &'a mut [NeighbourEntry<S>],
        effects: &'a mut [EffectHistory<S>],
        index: &'a mut [u32],
        cells: &'a mut [u32],
        spheres: usize,
    ) -> Result<Self, SetupError> {
        let capacity = |kind, len: usize| SetupError::Capacity {
            kind,
            capacity: len.min(u32::MAX as usize) as u32,
        };
        if index.len() < index_len(spheres) {
            return Err(capacity(CapacityKind::SphereIndex, index.len()));
        }
        if cells.len() < 2 || cells.len() > u32::MAX as usize {
            return Err(capacity(CapacityKind::Cells, cells.len()));
        }
        let half = entries.len() / 2;
        if half > u32::MAX as usize / 2 {
            return Err(capacity(CapacityKind::ContactSlots, entries.len()));
        }
        if !effects.is_empty() && effects.len() < entries.len() {
            return Err(capacity(CapacityKind::EffectHistory, effects.len()));
        }
        index.fill(0);
        Ok(NeighbourList {
            entries,
            effects,
            index,
            cells,
            sphere_capacity: spheres,
            half,
            current: 0,
            listed: 0,
            valid: false,
            drift: S::ZERO,
            skin: S::ZERO,
            builds: 0,
            skin_divisor: SKIN_DIVISOR,
            prescribed_pairs: true,
            slow_pairs_last: false,
        })
    }

    /// Whether the world keeps the history of optional effects.
    pub fn has_effect_history(&self) -> bool {
        !self.effects.is_empty()
    }

    /// Entries per half: the most the list can hold.
    pub fn capacity(&self) -> usize {
        self.half
    }

    /// How many times the list has been built.
    pub fn builds(&self) -> u64 {
        self.builds
    }

    /// Mark the list stale (a sphere or wall was added).
    pub(crate) fn invalidate(&mut self) {
        self.valid = false;
    }

    /// Whether the world steps at more than one rate ([`SLOW_PAIR_FLAG`]); a change marks
    /// the list stale, so that the next build orders it so or not.
    pub(crate) fn set_multirate(&mut self, on: bool) {
        if self.slow_pairs_last != on {
            self.slow_pairs_last = on;
            self.valid = false;
        }
    }

    /// Flag and order the slow pairs of every slow owner of the live half
    /// ([`order_slow_pairs`]), in a multi-rate world: a checkpoint's words do not hold the
    /// flag and [`Self::exchange`] clears it, so a world that wrote or read one calls this.
    pub(crate) fn order_live_slow_pairs(&mut self, spheres: &[Sphere<S>]) {
        if !self.slow_pairs_last {
            return;
        }
        let offsets = self.offsets_at(self.current);
        let base = self.half_range(self.current).start;
        for i in 0..self.listed.min(spheres.len()) {
            if !spheres[i].slow {
                continue;
            }
            let range = self.index[offsets.start + i] as usize + base
                ..self.index[offsets.start + i + 1] as usize + base;
            let effects = self.effects.get_mut(range.clone()).unwrap_or_default();
            order_slow_pairs(&mut self.entries[range], effects, spheres);
        }
    }

    /// Add `disp` (mm, the largest sphere or wall displacement of a step) to the drift bound
    /// and mark the list stale once 2·drift ≥ skin (or the bound overflowed).
    pub(crate) fn note_drift(&mut self, disp: S) {
        let d = self.drift + disp;
        self.drift = d;
        if !d.is_valid() || d.mul_int(2) >= self.skin {
            self.valid = false;
        }
    }

    fn offsets_at(&self, half: usize) -> core::ops::Range<usize> {
        let n = self.sphere_capacity;
        let start = 2 * n + half * (n + 1);
        start..start + n + 1
    }

    fn half_range(&self, half: usize) -> core::ops::Range<usize> {
        half * self.half..(half + 1) * self.half
    }

    /// The live half.
    pub fn live(&self) -> Live<'_, S> {
        let r = self.half_range(self.current);
        Live {
            offsets: &self.index[self.offsets_at(self.current)][..self.listed + 1],
            entries: &self.entries[r.clone()],
            effects: if self.effects.is_empty() {
                &[]
            } else {
                &self.effects[r]
            },
        }
    }

    /// The live half, writable.
    pub(crate) fn live_mut(&mut self) -> LiveMut<'_, S> {
        let r = self.half_range(self.current);
        let offsets = self.offsets_at(self.current);
        LiveMut {
            offsets: &self.index[offsets][..self.listed + 1],
            entries: &mut self.entries[r.clone()],
            effects: if self.effects.is_empty() {
                &mut []
            } else {
                &mut self.effects[r]
            },
        }
    }

    /// Exchange the list as it stands with a checkpoint ([`crate::world::checkpoint`]): when
    /// it was built and how far it has drifted, and its live half (offsets, entries with
    /// their contact history, effect history), so that a resumed world rebuilds it when the
    /// first would have. Offsets and partners are checked against `spheres` and `walls`.
    pub(crate) fn exchange(
        &mut self,
        v: &mut impl StateWords,
        spheres: u32,
        walls: u32,
    ) -> Result<(), CheckpointError> {
        v.same(self.half as u64, "the contact slots")?;
        v.same(
            self.has_effect_history() as u64,
            "whether effect history is kept",
        )?;
        let mut current = self.current as u32;
        index(v, &mut current, 2, "the list's live half")?;
        self.current = current as usize;
        let mut listed = self.listed as u32;
        index(
            v,
            &mut listed,
            spheres as u64 + 1,
            "the listed sphere count",
        )?;
        self.listed = listed as usize;
        flag(v, &mut self.valid, "whether the list is valid")?;
        scalar(v, &mut self.drift)?;
        scalar(v, &mut self.skin)?;
        v.word(&mut self.builds)?;
        let offsets = self.offsets_at(self.current);
        let offsets = &mut self.index[offsets][..self.listed + 1];
        let mut last = 0;
        for o in offsets.iter_mut() {
            index(v, o, self.half as u64 + 1, "a list offset")?;
            if *o < last {
                return Err(CheckpointError::Corrupt {
                    what: "a list offset (smaller than the one before)",
                    value: *o as u64,
                });
            }
            last = *o;
        }
        let r = self.half_range(self.current);
        let live = r.start..r.start + last as usize;
        for e in self.entries[live.clone()].iter_mut() {
            // The slow-pair flag is a cache of the scan's: the words never hold it.
            let mut key = (e.partner & !SLOW_PAIR_FLAG) as u64;
            v.word(&mut key)?;
            let partner = key_of(key as u32);
            let bad = if is_wall(partner) {
                (partner & !WALL_PARTNER_FLAG) >> 4 >= walls
            } else {
                partner >= spheres
            };
            if key > u32::MAX as u64 || bad {
                return Err(CheckpointError::Corrupt {
                    what: "a contact's partner key",
                    value: key,
                });
            }
            e.partner = key as u32;
            vec3(v, &mut e.delta)?;
        }
        if self.has_effect_history() {
            for f in self.effects[live].iter_mut() {
                scalar(v, &mut f.max_overlap)?;
                vec3(v, &mut f.roll_angle)?;
                vec3(v, &mut f.roll_torque)?;
                flag(v, &mut f.jkr_attached, "a contact's JKR attachment")?;
                scalar(v, &mut f.jkr_root)?;
            }
        }
        Ok(())
    }

    /// Rebuild the list if it is stale, for `spheres` (max radius `max_radius`, mm) and
    /// `walls`.
    ///
    /// The owners are scanned in `par.parts()` parts at once (each writing its own stretch of
    /// the idle half, closed up afterwards), which gives the same list as one part.
    pub(crate) fn ensure<P: Parallel>(
        &mut self,
        spheres: &[Sphere<S>],
        walls: &[Wall<S>],
        max_radius: S,
        par: &P,
    ) -> Result<(), StepError> {
        if self.valid {
            return Ok(());
        }
        let skin = max_radius / S::ONE.mul_int(self.skin_divisor);
        let parts = par.parts().clamp(1, MAX_PARTS).min(spheres.len().max(1));
        if self
            .rebuild(spheres, walls, max_radius, skin, par, parts)
            .is_err()
        {
            // A part outgrew its share of the half (or an owner failed): once more in one
            // part, which reports the error, if any, as a serial rebuild would.
            self.rebuild(spheres, walls, max_radius, skin, &Serial, 1)?;
        }
        self.current ^= 1;
        self.listed = spheres.len();
        self.valid = true;
        self.drift = S::ZERO;
        self.builds += 1;
        self.skin = skin;
        Ok(())
    }

    /// Write the new list into the idle half, carrying history over, with the owners split
    /// into `parts` ranges that `par` scans at once.
    fn rebuild<P: Parallel>(
        &mut self,
        spheres: &[Sphere<S>],
        walls: &[Wall<S>],
        max_radius: S,
        skin: S,
        par: &P,
        parts: usize,
    ) -> Result<(), StepError> {
        let n = spheres.len();
        let cap = self.sphere_capacity;
        let old = self.current;
        let (grid_part, offsets_part) = self.index.split_at_mut(2 * cap);
        let (cell_of, sorted) = grid_part.split_at_mut(cap);
        let grid = bin_spheres(spheres, max_radius, skin, cell_of, sorted, self.cells);
        let (off0, off1) = offsets_part.split_at_mut(cap + 1);
        let (old_offsets, new_offsets) = if old == 0 {
            (&*off0, &mut off1[..cap + 1])
        } else {
            (&*off1, &mut off0[..cap + 1])
        };
        let (e0, e1) = self.entries.split_at_mut(self.half);
        let (old_entries, new_entries) = if old == 0 {
            (&*e0, &mut e1[..self.half])
        } else {
            (&*e1, &mut e0[..self.half])
        };
        let (old_effects, new_effects): (&[EffectHistory<S>], &mut [EffectHistory<S>]) =
            if self.effects.is_empty() {
                (&[], &mut [])
            } else {
                let (f0, f1) = self.effects.split_at_mut(self.half);
                if old == 0 {
                    (&*f0, &mut f1[..self.half])
                } else {
                    (&*f1, &mut f0[..self.half])
                }
            };
        let scan = Scan {
            spheres,
            walls,
            grid,
            cell_of,
            sorted,
            cells: self.cells,
            skin,
            fast_squares: (max_radius.mul_int(2) + skin)
                .to_fast()
                .within(FAST_SQUARE_REACH_BITS),
            prescribed_pairs: self.prescribed_pairs,
            slow_pairs_last: self.slow_pairs_last,
            old: Live {
                offsets: &old_offsets[..self.listed + 1],
                entries: old_entries,
                effects: old_effects,
            },
        };
        // Owners in `parts` ranges of equal size, each with an equal stretch of the half.
        new_offsets[0] = 0;
        let stretch = self.half / parts;
        let mut jobs: heapless::Vec<RebuildPart<'_, S>, MAX_PARTS> = heapless::Vec::new();
        {
            let mut entries = new_entries;
            let mut effects = new_effects;
            let mut offsets = &mut new_offsets[1..n + 1];
            for p in 0..parts {
                let owners = p * n / parts..(p + 1) * n / parts;
                let (o, rest) = core::mem::take(&mut offsets).split_at_mut(owners.len());
                offsets = rest;
                let len = if p + 1 == parts {
                    entries.len()
                } else {
                    stretch
                };
                let (e, rest) = core::mem::take(&mut entries).split_at_mut(len);
                entries = rest;
                let f = if effects.is_empty() {
                    &mut [][..]
                } else {
                    let (f, rest) = core::mem::take(&mut effects).split_at_mut(len);
                    effects = rest;
                    f
                };
                let _ = jobs.push(RebuildPart {
                    owners,
                    start: p * stretch,
                    ends: o,
                    out: Writer {
                        old: scan.old,
                        entries: e,
                        effects: f,
                        at: 0,
                    },
                    result: Ok(()),
                });
            }
        }
        par.for_each(&mut jobs, &|part: &mut RebuildPart<'_, S>| part.run(&scan));
        let mut counts: heapless::Vec<(usize, usize), MAX_PARTS> = heapless::Vec::new();
        for part in jobs.iter() {
            part.result?;
            let _ = counts.push((part.start, part.out.at));
        }
        drop(jobs);
        // Close the stretches up: each part's entries move down behind the previous part's,
        // and its owners' end offsets (written relative to its stretch) become absolute.
        let mut at = 0usize;
        for (p, &(start, count)) in counts.iter().enumerate() {
            let owners = p * n / parts..(p + 1) * n / parts;
            let half = &mut self.entries[self.half * (old ^ 1)..self.half * (old ^ 1) + self.half];
            half.copy_within(start..start + count, at);
            if !self.effects.is_empty() {
                let fx =
                    &mut self.effects[self.half * (old ^ 1)..self.half * (old ^ 1) + self.half];
                fx.copy_within(start..start + count, at);
            }
            let offsets_at = self.offsets_at(old ^ 1);
            for end in &mut self.index[offsets_at][owners.start + 1..owners.end + 1] {
                *end += at as u32;
            }
            at += count;
        }
        Ok(())
    }
}

/// Whether sphere `s` belongs to a body that no force moves (a kinematic body, inverse mass
/// zero). Where the world leaves out prescribed contacts
/// ([`crate::world::World::set_prescribed_contacts`]), a pair of which neither side can
/// respond, two such bodies or one and a wall (the parts of a machine touching each other or
/// the floor), gets no entry: its contact would move nothing.
#[inline(always)]
fn cannot_respond<S: Scalar>(s: &Sphere<S>) -> bool {
    s.inv_mass == S::ZERO
}

/// What every part of a rebuild reads.
struct Scan<'s, S> {
    spheres: &'s [Sphere<S>],
    walls: &'s [Wall<S>],
    grid: super::broad_phase::Grid,
    cell_of: &'s [u32],
    sorted: &'s [u32],
    cells: &'s [u32],
    skin: S,
    /// Whether distances may be squared in the unchecked arithmetic
    /// ([`FAST_SQUARE_REACH_BITS`]).
    fast_squares: bool,
    /// Whether pairs of which neither side can respond are listed ([`cannot_respond`]).
    prescribed_pairs: bool,
    /// Whether a slow owner's slow pairs are flagged and kept last ([`order_slow_pairs`]).
    slow_pairs_last: bool,
    old: Live<'s, S>,
}

/// One part of a rebuild: a range of owners, the stretch of the idle half it writes, and the
/// end offsets of its owners (relative to its stretch until the parts are closed up).
struct RebuildPart<'w, S> {
    owners: core::ops::Range<usize>,
    /// Where its stretch starts in the half.
    start: usize,
    ends: &'w mut [u32],
    out: Writer<'w, S>,
    result: Result<(), StepError>,
}

impl<S: Scalar> RebuildPart<'_, S> {
    fn run(&mut self, sc: &Scan<'_, S>) {
        self.result = self.scan(sc);
    }

    fn scan(&mut self, sc: &Scan<'_, S>) -> Result<(), StepError> {
        let (spheres, grid, cells) = (sc.spheres, &sc.grid, sc.cells);
        let hint = worth_hinting(spheres);
        for (k, i) in self.owners.clone().enumerate() {
            let si = &spheres[i];
            let first = self.out.at;
            let reach_i = si.radius + sc.skin;
            let fixed_i = !sc.prescribed_pairs && cannot_respond(si);
            let [cx, cy, cz] = grid.coords(sc.cell_of[i]);
            // The 3×3×3 neighbourhood as nine rows along x: the three cells of a row are
            // consecutive, so their spheres are one run of `sorted`.
            let x_lo = cx.saturating_sub(1);
            let x_hi = (cx + 1).min(grid.dims[0] - 1);
            for (dy, dz) in NEIGHBOUR_ROWS {
                let (Some(y), Some(z)) =
                    (step_in(cy, dy, grid.dims[1]), step_in(cz, dz, grid.dims[2]))
                else {
                    continue;
                };
                let row = (z * grid.dims[1] + y) * grid.dims[0];
                let run = cells[(row + x_lo) as usize] as usize
                    ..cells[(row + x_hi) as usize + 1] as usize;
                let candidates = &sc.sorted[run];
                for (c, &j) in candidates.iter().enumerate() {
                    if let Some(&ahead) = candidates
                        .get(c + PREFETCH_CANDIDATES_AHEAD)
                        .filter(|_| hint)
                    {
                        prefetch_record(spheres, ahead as usize, 1);
                    }
                    // The owner keeps only partners above it, and none of its own body (a
                    // clump's own spheres crowd its neighbourhood: skip them first).
                    let sj = &spheres[j as usize];
                    if j as usize <= i || sj.body == si.body || (fixed_i && cannot_respond(sj)) {
                        continue;
                    }
                    let rs = reach_i + sj.radius;
                    let d: Vec3<S> = sj.position - si.position;
                    if !(d.x.abs() < rs && d.y.abs() < rs && d.z.abs() < rs) {
                        continue;
                    }
                    // |d_k| < rs: with rs below 2^15 mm |d|² and rs² cannot overflow, and
                    // the unchecked products round as the checked ones.
                    let inside = if sc.fast_squares {
                        let (d, rs) = (d.map(S::to_fast), rs.to_fast());
                        d.norm2() < rs * rs
                    } else {
                        let d2 = d.norm2();
                        if !d2.is_valid() {
                            return Err(StepError::Overflow {
                                stage: Stage::SphereContact,
                                body: si.body,
                                other: Other::Body(sj.body),
                            });
                        }
                        d2 < rs * rs
                    };
                    if inside {
                        self.out.push(i, j)?;
                    }
                }
            }
            for (w, wall) in sc.walls.iter().enumerate().filter(|_| !fixed_i) {
                let mut faces = wall.shape.faces_near(si.position, si.radius, sc.skin);
                while faces != 0 {
                    let face = faces.trailing_zeros();
                    faces &= faces - 1;
                    self.out.push(i, wall_key(w as u32, face))?;
                }
            }
            if sc.slow_pairs_last && si.slow {
                let owned = first..self.out.at;
                let effects = self.out.effects.get_mut(owned.clone()).unwrap_or_default();
                order_slow_pairs(&mut self.out.entries[owned], effects, spheres);
            }
            self.ends[k] = self.out.at as u32;
        }
        Ok(())
    }
}

/// The idle half being written during a rebuild, with the live half to carry history from.
struct Writer<'w, S> {
    old: Live<'w, S>,
    entries: &'w mut [NeighbourEntry<S>],
    effects: &'w mut [EffectHistory<S>],
    at: usize,
}

impl<S: Scalar> Writer<'_, S> {
    /// Append the entry `key` of owner `owner`, with the history it had in the old list.
    #[inline]
    fn push(&mut self, owner: usize, key: u32) -> Result<(), StepError> {
        if self.at >= self.entries.len() {
            return Err(StepError::ContactCapacity {
                sphere: owner as u32,
                capacity: self.entries.len() as u32,
            });
        }
        let old = self.old.range(owner);
        let carried = self.old.entries[old.clone()]
            .iter()
            .position(|e| key_of(e.partner) == key)
            .map(|k| old.start + k);
        let (entry, effects) = match carried {
            Some(k) => (
                NeighbourEntry {
                    // The rebuild flags the slow pairs anew (a body marked slow or not
                    // since the last build invalidated the list).
                    partner: self.old.entries[k].partner & !SLOW_PAIR_FLAG,
                    delta: self.old.entries[k].delta,
                },
                self.old.effects.get(k).copied().unwrap_or_default(),
            ),
            None => (
                NeighbourEntry {
                    partner: key,
                    delta: Vec3::ZERO,
                },
                EffectHistory::default(),
            ),
        };
        self.entries[self.at] = entry;
        if let Some(e) = self.effects.get_mut(self.at) {
            *e = effects;
        }
        self.at += 1;
        Ok(())
    }
}

/// Flag the entries of one slow owner (and their effect history: as long, or empty when the
/// world keeps none)
/// whose partner is a slow sphere with [`SLOW_PAIR_FLAG`], and move them behind its other
/// entries, each part in its order. A wall is never a slow partner. The order of an owner's
/// entries changes no fixed-point bit: the loads are summed exactly and the digest hashes the
/// contacts in partner order.
fn order_slow_pairs<S: Scalar>(
    entries: &mut [NeighbourEntry<S>],
    effects: &mut [EffectHistory<S>],
    spheres: &[Sphere<S>],
) {
    // A stable partition in place: an owner has a few dozen entries at most, so moving each
    // other entry down past the slow pairs before it costs less than a scratch buffer.
    let mut others = 0;
    for k in 0..entries.len() {
        let key = key_of(entries[k].partner);
        if !is_wall(key) && spheres[key as usize].slow {
            entries[k].partner |= SLOW_PAIR_FLAG;
            continue;
        }
        entries[others..=k].rotate_right(1);
        if !effects.is_empty() {
            effects[others..=k].rotate_right(1);
        }
        others += 1;
    }
}

/// The (y, z) cell offsets of the nine rows of a 3×3×3 neighbourhood.
const NEIGHBOUR_ROWS: [(i32, i32); 9] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (0, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// Cell coordinate `c + d` if it lies in `0..dim`.
#[inline(always)]
fn step_in(c: u32, d: i32, dim: u32) -> Option<u32> {
    let v = c as i64 + d as i64;
    (0..dim as i64).contains(&v).then_some(v as u32)
}

/// `true` for a wall entry's key.
#[inline(always)]
pub fn is_wall(key: u32) -> bool {
    key & WALL_PARTNER_FLAG != 0
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    use crate::num::{Fx, Vec3};
    use crate::owned::OwnedStorage;
    use crate::scenario::BenchBed;
    use crate::wall::{WallId, WallShape};
    use crate::world::World;

    /// Steps of the test pour: falling, landing and the first settling.
    const STEPS: u64 = 2_500;
    /// The step from which every wall rises (the container lifts its bed), so that wall
    /// drift counts too.
    const LIFT_FROM: u64 = 1_500;
    /// The walls' rise, m/s.
    const LIFT_M_S: f64 = 0.05;
    /// Kept steps between two brute-force searches for touching pairs.
    const TOUCH_CHECK_EVERY: u32 = 3;

    #[test]
    fn a_slow_owners_slow_pairs_are_flagged_and_kept_last_in_order() {
        use super::{is_wall, key_of, order_slow_pairs, SLOW_PAIR_FLAG};
        use crate::body::Sphere;
        use crate::contact::{EffectHistory, NeighbourEntry};
        use crate::num::Scalar;
        // Spheres 0–5: 1, 2 and 4 slow; the owner's entries in list order, a wall among them.
        let spheres: Vec<Sphere<Fx>> = (0..6)
            .map(|i| Sphere {
                slow: matches!(i, 1 | 2 | 4),
                ..Sphere::default()
            })
            .collect();
        let wall = super::wall_key(0, 1);
        let keys = [1, 3, 2, wall, 4, 5];
        let mut entries: Vec<NeighbourEntry<Fx>> = keys
            .iter()
            .map(|&k| NeighbourEntry {
                partner: k | super::LIVE_FLAG,
                delta: Vec3::new(Fx::from_int(k as i32 & 0xff), Fx::ZERO, Fx::ZERO),
            })
            .collect();
        let mut effects: Vec<EffectHistory<Fx>> = keys
            .iter()
            .map(|&k| EffectHistory {
                max_overlap: Fx::from_int(k as i32 & 0xff),
                ..EffectHistory::default()
            })
            .collect();
        order_slow_pairs(&mut entries, &mut effects, &spheres);
        let order: Vec<u32> = entries.iter().map(|e| key_of(e.partner)).collect();
        assert_eq!(order, [3, wall, 5, 1, 2, 4]);
        for (e, f) in entries.iter().zip(&effects) {
            let k = key_of(e.partner);
            let slow = !is_wall(k) && spheres[k as usize].slow;
            assert_eq!(e.partner & SLOW_PAIR_FLAG != 0, slow, "entry {k}");
            assert_ne!(
                e.partner & super::LIVE_FLAG,
                0,
                "entry {k} keeps its live flag"
            );
            // The history moved with its entry.
            assert_eq!(e.delta.x, Fx::from_int(k as i32 & 0xff));
            assert_eq!(f.max_overlap, e.delta.x);
        }
        // Ordering an ordered owner again changes nothing.
        let again = entries.clone();
        order_slow_pairs(&mut entries, &mut effects, &spheres);
        assert_eq!(entries, again);
    }

    fn raw3(v: Vec3<Fx>) -> [i64; 3] {
        [v.x.raw(), v.y.raw(), v.z.raw()]
    }

    /// |a − b|₁ in raw Q32.32 units (exact).
    fn l1(a: [i64; 3], b: [i64; 3]) -> i128 {
        (0..3).map(|k| (a[k] as i128 - b[k] as i128).abs()).sum()
    }

    /// A point of each wall that moves with it.
    fn wall_points(w: &World<'_, Fx>) -> Vec<[i64; 3]> {
        w.walls()
            .iter()
            .map(|wall| {
                raw3(match &wall.shape {
                    WallShape::Plane(p) => p.point,
                    WallShape::Cylinder(c) => c.base,
                    WallShape::AaBox(b) => b.min,
                    WallShape::OrificePlate(o) => o.centre,
                })
            })
            .collect()
    }

    /// Every pair of spheres of different bodies that touches is in the live list, under
    /// its owner (the lower id).
    fn assert_touching_pairs_listed(w: &World<'_, Fx>, step: u64) {
        let spheres = w.spheres();
        let live = w.list.live();
        for (i, a) in spheres.iter().enumerate() {
            let listed: Vec<u32> = live.entries[live.range(i)]
                .iter()
                .map(|e| super::key_of(e.partner))
                .collect();
            let pa = raw3(a.position);
            for (j, b) in spheres.iter().enumerate().skip(i + 1) {
                if a.body == b.body {
                    continue;
                }
                let pb = raw3(b.position);
                let d2: i128 = (0..3)
                    .map(|k| {
                        let d = pb[k] as i128 - pa[k] as i128;
                        d * d
                    })
                    .sum();
                let reach = a.radius.raw() as i128 + b.radius.raw() as i128;
                if d2 < reach * reach {
                    assert!(
                        listed.contains(&(j as u32)),
                        "step {step}: spheres {i} and {j} touch but are not listed"
                    );
                }
            }
        }
    }

    /// The list goes stale exactly when twice its drift bound reaches the skin: the bound is
    /// the sum over the steps since the build of each step's largest sphere displacement plus
    /// its largest wall displacement (L1 norms), measured here from the positions the test
    /// saw, in exact integers. While the list is kept, every touching pair is in it. A pour
    /// of 200 spheres whose container rises at the end, so that wall motion counts too.
    /// Fails with a factor 1 for 2 (stale too late), or when the bound is not reset at a
    /// build (stale every step).
    #[test]
    fn the_list_goes_stale_exactly_when_twice_its_drift_bound_reaches_the_skin() {
        let bed = BenchBed {
            particles: 200,
            seed: 5,
        };
        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let mut w = bed.build(arenas.storage()).unwrap();
        let (mut drift, mut wall_moved): (i128, i128) = (0, 0);
        let (mut kept, mut stale) = (0u32, 0u32);
        for step in 0..STEPS {
            if step == LIFT_FROM {
                for k in 0..w.walls().len() {
                    w.set_wall_velocity_m_s(WallId(k as u32), [0.0, 0.0, LIFT_M_S])
                        .unwrap();
                }
            }
            let before: Vec<[i64; 3]> = w.spheres().iter().map(|s| raw3(s.position)).collect();
            let walls_before = wall_points(&w);
            let builds = w.list.builds();
            w.step().unwrap();
            // A build happens at the start of a step and clears the bound.
            if w.list.builds() != builds {
                drift = 0;
            }
            let sphere_step = w
                .spheres()
                .iter()
                .zip(&before)
                .map(|(s, &b)| l1(raw3(s.position), b))
                .max()
                .unwrap_or(0);
            let wall_step = walls_before
                .iter()
                .zip(wall_points(&w))
                .map(|(&a, b)| l1(a, b))
                .max()
                .unwrap_or(0);
            drift += sphere_step;
            drift += wall_step;
            wall_moved += wall_step;
            let due = 2 * drift >= w.list.skin.raw() as i128;
            assert_eq!(!w.list.valid, due, "step {step}");
            if w.list.valid {
                kept += 1;
                // The brute-force search every few steps keeps the debug build quick.
                if kept % TOUCH_CHECK_EVERY == 0 {
                    assert_touching_pairs_listed(&w, step);
                }
            } else {
                stale += 1;
            }
        }
        // Both outcomes occurred, and the walls did move.
        assert!(kept > 1_000 && stale > 20, "kept {kept}, stale {stale}");
        assert!(wall_moved > 0);
    }
}
