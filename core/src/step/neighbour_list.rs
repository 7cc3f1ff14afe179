//! Verlet neighbour list with a skin, and the contact history stored beside its entries.
//!
//! The list holds, per owner sphere (the lower id of a pair), every sphere whose surface was
//! within the skin s = R_max / [`SKIN_DIVISOR`] when the list was built:
//! |rj − ri| < Ri + Rj + s. A pair not in the list was farther apart than that, so it cannot
//! touch until one sphere of it has moved by s/2 or both by a total of s. The integrator adds
//! each step's largest sphere displacement (L1 norm, an upper bound on the Euclidean one) to
//! a drift bound in the world; once 2·drift ≥ s the list is marked stale and rebuilt at the start of
//! the next step, from the cell grid of [`super::broad_phase`] with cell edge 2·R_max + s. Adding
//! a sphere also marks it stale. The rebuild is a pure function of the positions, so stepping
//! stays deterministic; and since every touching pair is in the list, the set of contacts
//! evaluated each step — and in fixed point every force — does not depend on when rebuilds
//! happen.
//!
//! Storage: the double-buffered `contacts` arena of [`crate::body::Storage`], `k` slots per
//! sphere per half. The live half holds the list; each entry carries its contact history
//! ([`ContactSlot`]), so the contact loop reads and updates δt in place with no search. A
//! rebuild writes the other half, copying each surviving entry's history (one short linear
//! search per entry, only on rebuild), then swaps halves. Entry keys carry [`LIVE_FLAG`] when
//! the pair touched in the last step with its tangential term on: those are the "contacts with
//! history" that [`World::contact_slots`] and the digest report; other entries have zero δt.
//!
//! Walls get the same treatment: a rebuild records in [`Sphere::near_walls`] the walls each
//! sphere lies within the skin of ([`crate::wall::WallShape::may_touch`]), and the contact
//! loop tests only those. Wall motion adds to the drift bound like sphere motion, so a wall
//! left out cannot touch the sphere before the next rebuild (sphere and wall together move
//! less than s/2). Wall contacts keep their history as entries keyed by wall and face in the
//! same per-sphere list: appended when a contact starts, removed when it ends, carried over on
//! rebuild.
//!
//! More entries than `k` for one owner is [`StepError::ContactCapacity`].

use super::broad_phase::{Grid, HALF_NEIGHBOURS};
use crate::body::Sphere;
use crate::contact::{ContactSlot, ContactState, WALL_PARTNER_FLAG};
use crate::error::{Other, Stage, StepError};
use crate::num::{Scalar, Vec3};
use crate::world::World;

/// Partner-key flag of an entry whose pair touched in the last step and keeps history.
/// Sphere ids stay below 2^29 ([`World::new`] refuses larger capacities) and wall keys use
/// [`WALL_PARTNER_FLAG`] with wall < 16, so the bit is free in every key.
pub const LIVE_FLAG: u32 = 0x4000_0000;

/// The skin is R_max / `SKIN_DIVISOR` (0.5 mm for the 4 mm pods of the bench bed): larger
/// skins rebuild less often but hold more non-touching entries per sphere.
pub const SKIN_DIVISOR: i32 = 8;

/// The partner key without [`LIVE_FLAG`].
#[inline(always)]
pub(crate) fn key_of(partner: u32) -> u32 {
    partner & !LIVE_FLAG
}

// One bit per wall in `Sphere::near_walls`.
const _: () = assert!(crate::wall::MAX_WALLS <= u16::BITS as usize);

/// History of `key` in an old entry list, or zero (rebuild only).
#[inline]
fn carried(old: &[ContactSlot<impl Scalar>], key: u32) -> Option<usize> {
    old.iter().position(|e| key_of(e.partner) == key)
}

impl<S: Scalar> World<'_, S> {
    /// Rebuild the neighbour list if it is stale.
    pub(crate) fn ensure_neighbour_list(&mut self) -> Result<(), StepError> {
        if self.list_valid {
            return Ok(());
        }
        let skin = self.max_radius / S::ONE.mul_int(SKIN_DIVISOR);
        let grid = self.bin_spheres(skin);
        self.build_list(grid, skin)?;
        self.mark_near_walls(skin);
        self.current ^= 1;
        self.list_valid = true;
        self.list_drift = S::ZERO;
        self.list_skin = skin;
        Ok(())
    }

    /// Record in each sphere the walls it lies within `skin` (mm) of.
    fn mark_near_walls(&mut self, skin: S) {
        let walls = &self.walls;
        for s in self.spheres[..self.n_spheres as usize].iter_mut() {
            s.near_walls = walls
                .iter()
                .enumerate()
                .filter(|(_, w)| w.shape.may_touch(s.position, s.radius, skin))
                .fold(0, |mask, (id, _)| mask | 1 << id);
        }
    }

    /// Add `disp` (mm, the largest sphere or wall displacement of this step) to the drift
    /// bound and mark the list stale once 2·drift ≥ skin (or the bound overflowed).
    pub(crate) fn note_drift(&mut self, disp: S) {
        let d = self.list_drift + disp;
        self.list_drift = d;
        if !d.is_valid() || d.mul_int(2) >= self.list_skin {
            self.list_valid = false;
        }
    }

    /// Write the new list into the idle half from the grid sweep, carrying history over.
    fn build_list(&mut self, grid: Grid, skin: S) -> Result<(), StepError> {
        let n = self.n_spheres as usize;
        let cap = self.spheres.len();
        let k = self.slots_per_sphere as usize;
        let cur = self.current as usize;
        let (h0, h1) = self.slots.split_at_mut(cap * k);
        let h1 = &mut h1[..cap * k];
        let (old_slots, new_slots) = if cur == 0 { (&*h0, h1) } else { (&*h1, h0) };
        let (head, counts) = self.index.split_at_mut(2 * cap);
        let (c0, c1) = counts.split_at_mut(cap);
        let c1 = &mut c1[..cap];
        let (old_count, new_count) = if cur == 0 { (&*c0, c1) } else { (&*c1, c0) };
        let (cell_of, sorted) = head.split_at(cap);
        let spheres = &self.spheres[..n];
        let cells = &self.cells[..];
        for c in new_count[..n].iter_mut() {
            *c = 0;
        }
        if n == 0 {
            return Ok(());
        }
        let mut list = Lists {
            old_slots,
            old_count,
            new_slots,
            new_count,
            k,
        };
        let [dx, dy, dz] = grid.dims;
        for idx in 0..n {
            let i = sorted[idx] as usize;
            let c = cell_of[i];
            let cx = c % dx;
            let cy = (c / dx) % dy;
            let cz = c / (dx * dy);
            let end = cells[c as usize + 1] as usize;
            let si = &spheres[i];
            let (pi, ri, body_i) = (si.position, si.radius + skin, si.body);
            // Per-axis rejection with sphere i hoisted; the full test runs for the rest.
            let near = |sj: &Sphere<S>| -> bool {
                let rs = ri + sj.radius;
                sj.body != body_i
                    && (sj.position.x - pi.x).abs() < rs
                    && (sj.position.y - pi.y).abs() < rs
                    && (sj.position.z - pi.z).abs() < rs
            };
            for &j in &sorted[idx + 1..end] {
                if near(&spheres[j as usize]) {
                    list.consider(spheres, i, j as usize, skin)?;
                }
            }
            for off in HALF_NEIGHBOURS.iter() {
                let nx = cx as i64 + off[0] as i64;
                let ny = cy as i64 + off[1] as i64;
                let nz = cz as i64 + off[2] as i64;
                if nx < 0
                    || ny < 0
                    || nz < 0
                    || nx >= dx as i64
                    || ny >= dy as i64
                    || nz >= dz as i64
                {
                    continue;
                }
                let nc = ((nz as u32 * dy + ny as u32) * dx + nx as u32) as usize;
                let (s, e) = (cells[nc] as usize, cells[nc + 1] as usize);
                for &j in &sorted[s..e] {
                    if near(&spheres[j as usize]) {
                        list.consider(spheres, i, j as usize, skin)?;
                    }
                }
            }
        }
        // Live wall contacts keep their entries (and history).
        for (s, &cnt) in old_count[..n].iter().enumerate() {
            let base = s * k;
            for e in 0..cnt as usize {
                let slot = list.old_slots[base + e];
                if slot.partner & WALL_PARTNER_FLAG != 0 {
                    list.push(s, slot)?;
                }
            }
        }
        Ok(())
    }
}

/// Old and new halves of the list during a rebuild.
struct Lists<'a, S> {
    old_slots: &'a [ContactSlot<S>],
    old_count: &'a [u32],
    new_slots: &'a mut [ContactSlot<S>],
    new_count: &'a mut [u32],
    k: usize,
}

impl<S: Scalar> Lists<'_, S> {
    /// Append `slot` to sphere `owner`'s new list.
    #[inline]
    fn push(&mut self, owner: usize, slot: ContactSlot<S>) -> Result<(), StepError> {
        let cnt = self.new_count[owner] as usize;
        if cnt >= self.k {
            return Err(StepError::ContactCapacity {
                sphere: owner as u32,
                slots: self.k as u32,
            });
        }
        self.new_slots[owner * self.k + cnt] = slot;
        self.new_count[owner] = cnt as u32 + 1;
        Ok(())
    }

    /// Enter the pair (a, b) if their surfaces are within `skin`; the lower id owns it.
    #[inline(never)]
    fn consider(
        &mut self,
        spheres: &[Sphere<S>],
        a: usize,
        b: usize,
        skin: S,
    ) -> Result<(), StepError> {
        let (i, j) = if a < b { (a, b) } else { (b, a) };
        let (si, sj) = (&spheres[i], &spheres[j]);
        let d: Vec3<S> = sj.position - si.position;
        let reach = si.radius + sj.radius + skin;
        let d2 = d.norm2();
        if !d2.is_valid() {
            return Err(StepError::Overflow {
                stage: Stage::SphereContact,
                body: si.body,
                other: Other::Body(sj.body),
            });
        }
        if d2 >= reach * reach {
            return Ok(());
        }
        let key = j as u32;
        let base = i * self.k;
        let old = &self.old_slots[base..base + self.old_count[i] as usize];
        let slot = match carried(old, key) {
            Some(e) => old[e],
            None => ContactSlot {
                partner: key,
                state: ContactState::default(),
            },
        };
        self.push(i, slot)
    }
}
