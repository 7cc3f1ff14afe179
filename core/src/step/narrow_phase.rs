//! Narrow phase: contact geometry and relative motion for sphere–sphere and sphere–wall
//! pairs, evaluation of the pair's contact terms, and accumulation of forces and torques.
//!
//! Geometry (seed 000 eqs. (1)–(2), DESIGN §2): α = Ri + Rj − |rj − ri|, n̂ = (rj − ri)/|rj − ri|
//! (n̂ = +z for exactly coincident centres, a deterministic choice; near-coincident centres whose
//! |d|² underflows are normalised after scaling by the largest component), R* = RiRj/(Ri+Rj), m* =
//! mimj/(mi+mj) (wall: R* = Ri, m* = mi), a = √(R*α). The contact point is
//! c = ri + n̂(Ri − α/2); lever arms run from each body's centre of mass to c.
//!
//! One validity check per contact (force, torques, history) turns any fixed-point overflow
//! into [`StepError::Overflow`] naming both parties.

use super::broad_phase::{Grid, HALF_NEIGHBOURS};
use crate::body::{Body, Sphere};
use crate::contact::history::{lookup, wall_key};
use crate::contact::{ContactKinematics, ContactSlot, ContactState};
use crate::error::{Other, Stage, StepError};
use crate::material::MAX_MATERIALS;
use crate::num::{Scalar, Vec3};
use crate::pair::PairParams;
use crate::world::World;

/// Why a single contact failed.
enum Fail {
    Overflow,
    Capacity,
}

/// The j side of a contact.
struct Partner<S> {
    /// Body index, or `None` for a wall.
    body: Option<usize>,
    /// Wall velocity (mm/ms); zero for a body.
    wall_velocity: Vec3<S>,
    /// Distance from j's centre to the contact point when j is a single sphere (Rj − α/2).
    arm_len: S,
}

/// Views the contact loops need, split from the world.
struct Ctx<'w, S: Scalar> {
    bodies: &'w mut [Body<S>],
    old_slots: &'w [ContactSlot<S>],
    new_slots: &'w mut [ContactSlot<S>],
    old_count: &'w [u32],
    new_count: &'w mut [u32],
    k: usize,
    dt: S,
}

impl<S: Scalar> Ctx<'_, S> {
    /// Evaluate one contact between sphere `owner` (body `bi`, side i) and a partner,
    /// accumulate the forces and store the history in `owner`'s new slots. Returns the force
    /// on j (N).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn contact(
        &mut self,
        pair: &PairParams<S>,
        owner: u32,
        key: u32,
        bi: usize,
        j: Partner<S>,
        p_i: Vec3<S>,
        r_i: S,
        n: Vec3<S>,
        overlap: S,
        r_star_alpha: S,
        m_star: S,
    ) -> Result<Vec3<S>, Fail> {
        let bod_i = &self.bodies[bi];
        let (pos_i, vel_i, w_i, clump_i) = (
            bod_i.position,
            bod_i.velocity,
            bod_i.angular_velocity,
            bod_i.is_clump,
        );
        let arm_len_i = r_i - overlap * S::HALF;
        let c = p_i + n.scale(arm_len_i);
        let arm_i = c - pos_i;
        let mut v_rel = j.wall_velocity - (vel_i + w_i.cross(arm_i));
        let mut arm_j = Vec3::ZERO;
        let mut lever_j = S::ZERO;
        if let Some(bj) = j.body {
            let bod_j = &self.bodies[bj];
            arm_j = c - bod_j.position;
            v_rel += bod_j.velocity + bod_j.angular_velocity.cross(arm_j);
            if pair.rolling.on {
                lever_j = if bod_j.is_clump {
                    arm_j.norm()
                } else {
                    j.arm_len
                };
            }
        }
        let vn = v_rel.dot(n);
        let vt = v_rel - n.scale(vn);
        let a = r_star_alpha.sqrt();
        let sqrt_a_mstar = if pair.needs_damping() {
            (a * m_star).sqrt()
        } else {
            S::ZERO
        };
        let lever_i = if pair.rolling.on && clump_i {
            arm_i.norm()
        } else {
            arm_len_i
        };
        let kin = ContactKinematics {
            normal: n,
            overlap,
            contact_radius: a,
            sqrt_a_mstar,
            vn,
            vt,
            dt: self.dt,
            lever_i,
            lever_j,
        };
        let ow = owner as usize;
        let mut state = if pair.keeps_history() {
            let base = ow * self.k;
            lookup(
                &self.old_slots[base..base + self.old_count[ow] as usize],
                key,
            )
        } else {
            ContactState::default()
        };
        let out = pair.evaluate(&kin, &mut state);
        let f = n.scale(out.normal) + out.tangential;
        let ti = arm_i.cross(f);
        let tj = arm_j.cross(f);
        if !(f.is_valid()
            & ti.is_valid()
            & tj.is_valid()
            & out.roll_i.is_valid()
            & out.roll_j.is_valid()
            & state.delta.is_valid())
        {
            return Err(Fail::Overflow);
        }
        {
            let b = &mut self.bodies[bi];
            b.force -= f;
            b.torque -= ti;
            b.roll_torque += out.roll_i;
        }
        if let Some(bj) = j.body {
            let b = &mut self.bodies[bj];
            b.force += f;
            b.torque += tj;
            b.roll_torque += out.roll_j;
        }
        if pair.keeps_history() {
            let cnt = self.new_count[ow] as usize;
            if cnt >= self.k {
                return Err(Fail::Capacity);
            }
            self.new_slots[ow * self.k + cnt] = ContactSlot {
                partner: key,
                state,
            };
            self.new_count[ow] = cnt as u32 + 1;
        }
        Ok(f)
    }
}

type PairTable<S> = [[PairParams<S>; MAX_MATERIALS]; MAX_MATERIALS];

/// Everything split out of the world for the contact loops.
struct Split<'w, S: Scalar> {
    ctx: Ctx<'w, S>,
    spheres: &'w [Sphere<S>],
    cell_of: &'w [u32],
    sorted: &'w [u32],
    cells: &'w [u32],
    pairs: &'w PairTable<S>,
}

impl<S: Scalar> World<'_, S> {
    fn split(&mut self) -> Split<'_, S> {
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
        Split {
            ctx: Ctx {
                bodies: &mut self.bodies[..],
                old_slots,
                new_slots,
                old_count,
                new_count,
                k,
                dt: self.dt,
            },
            spheres: &self.spheres[..self.n_spheres as usize],
            cell_of,
            sorted,
            cells: &self.cells[..],
            pairs: &self.pairs,
        }
    }

    /// Sphere–sphere contacts over the half-neighbourhood cell sweep.
    pub(crate) fn sphere_contacts(&mut self, grid: Grid) -> Result<(), StepError> {
        let n = self.n_spheres as usize;
        let Split {
            mut ctx,
            spheres,
            cell_of,
            sorted,
            cells,
            pairs,
        } = self.split();
        for c in ctx.new_count[..n].iter_mut() {
            *c = 0;
        }
        if n == 0 {
            return Ok(());
        }
        let [dx, dy, dz] = grid.dims;
        for idx in 0..n {
            let i = sorted[idx] as usize;
            let c = cell_of[i];
            let cx = c % dx;
            let cy = (c / dx) % dy;
            let cz = c / (dx * dy);
            // Same cell: partners after i in the sorted order.
            let end = cells[c as usize + 1] as usize;
            let si = &spheres[i];
            let (pi, ri, body_i) = (si.position, si.radius, si.body);
            // Cheap per-axis rejection with sphere i's data hoisted; the full test and the
            // contact evaluation run only for the few candidates that pass.
            let near = |sj: &Sphere<S>| -> bool {
                let rs = ri + sj.radius;
                sj.body != body_i
                    && (sj.position.x - pi.x).abs() < rs
                    && (sj.position.y - pi.y).abs() < rs
                    && (sj.position.z - pi.z).abs() < rs
            };
            for &j in &sorted[idx + 1..end] {
                if near(&spheres[j as usize]) {
                    sphere_pair(&mut ctx, spheres, pairs, i, j as usize)?;
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
                        sphere_pair(&mut ctx, spheres, pairs, i, j as usize)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// Sphere–wall contacts, sphere by sphere in id order, walls in insertion order.
    pub(crate) fn wall_contacts(&mut self) -> Result<(), StepError> {
        if self.walls.is_empty() {
            return Ok(());
        }
        let mut walls = self.walls.clone();
        let Split {
            mut ctx,
            spheres,
            pairs,
            ..
        } = self.split();
        for (si, s) in spheres.iter().enumerate() {
            let bi = s.body as usize;
            for (wi, w) in walls.iter_mut().enumerate() {
                let mut hits: [(u32, Vec3<S>, S); 6] = [(0, Vec3::ZERO, S::ZERO); 6];
                let mut nh = 0usize;
                w.shape
                    .for_each_contact(s.position, s.radius, |face, nrm, a| {
                        if nh < hits.len() {
                            hits[nh] = (face, nrm, a);
                            nh += 1;
                        }
                    });
                if nh == 0 {
                    continue;
                }
                let pair = &pairs[s.material as usize][w.material as usize];
                if !pair.defined {
                    return Err(StepError::UndefinedPair {
                        material_a: s.material,
                        material_b: w.material,
                    });
                }
                let m_star = ctx.bodies[bi].mass;
                for &(face, nrm, a) in &hits[..nh] {
                    let partner = Partner {
                        body: None,
                        wall_velocity: w.velocity,
                        arm_len: S::ZERO,
                    };
                    let key = wall_key(wi as u32, face);
                    match ctx.contact(
                        pair,
                        si as u32,
                        key,
                        bi,
                        partner,
                        s.position,
                        s.radius,
                        nrm,
                        a,
                        s.radius * a,
                        m_star,
                    ) {
                        Ok(f) => w.force += f,
                        Err(Fail::Overflow) => {
                            return Err(StepError::Overflow {
                                stage: Stage::WallContact,
                                body: bi as u32,
                                other: Other::Wall(wi as u32),
                            })
                        }
                        Err(Fail::Capacity) => {
                            return Err(StepError::ContactCapacity {
                                sphere: si as u32,
                                slots: ctx.k as u32,
                            })
                        }
                    }
                }
            }
        }
        self.walls = walls;
        Ok(())
    }
}

/// Test one candidate sphere pair and evaluate it if in contact.
#[inline(never)]
fn sphere_pair<S: Scalar>(
    ctx: &mut Ctx<'_, S>,
    spheres: &[Sphere<S>],
    pairs: &PairTable<S>,
    a: usize,
    b: usize,
) -> Result<(), StepError> {
    // The lower id owns the contact and is side i.
    let (i, j) = if a < b { (a, b) } else { (b, a) };
    let si = &spheres[i];
    let sj = &spheres[j];
    if si.body == sj.body {
        return Ok(());
    }
    let d = sj.position - si.position;
    let rs = si.radius + sj.radius;
    // Cheap per-axis rejection before the squared distance.
    if d.x.abs() >= rs || d.y.abs() >= rs || d.z.abs() >= rs {
        return Ok(());
    }
    let d2 = d.norm2();
    let overflow = || StepError::Overflow {
        stage: Stage::SphereContact,
        body: si.body,
        other: Other::Body(sj.body),
    };
    if !d2.is_valid() {
        return Err(overflow());
    }
    if d2 >= rs * rs {
        return Ok(());
    }
    let pair = &pairs[si.material as usize][sj.material as usize];
    if !pair.defined {
        return Err(StepError::UndefinedPair {
            material_a: si.material,
            material_b: sj.material,
        });
    }
    let mut dist = d2.sqrt();
    let n = if dist > S::ZERO {
        d.scale(S::ONE / dist)
    } else if let Some((u, len)) = d.normalize_with_len() {
        // |d|² underflowed (centres within ~1.5e-5 mm) but d itself is resolvable.
        dist = len;
        u
    } else {
        Vec3::new(S::ZERO, S::ZERO, S::ONE)
    };
    let overlap = rs - dist;
    let bi = si.body as usize;
    let bj = sj.body as usize;
    // R* = RiRj/(Ri+Rj) and m* = mimj/(mi+mj); equal radii/masses (monodisperse beds) take
    // the exact halving shortcut and skip a division each.
    let r_star_alpha = if si.radius == sj.radius {
        si.radius * S::HALF * overlap
    } else {
        si.radius * sj.radius * overlap / rs
    };
    let m_star = if pair.needs_damping() {
        let (bi_, bj_) = (&ctx.bodies[bi], &ctx.bodies[bj]);
        if bi_.mass == bj_.mass {
            bi_.mass * S::HALF
        } else {
            S::ONE / (bi_.inv_mass + bj_.inv_mass)
        }
    } else {
        S::ZERO
    };
    let partner = Partner {
        body: Some(bj),
        wall_velocity: Vec3::ZERO,
        arm_len: sj.radius - overlap * S::HALF,
    };
    match ctx.contact(
        pair,
        i as u32,
        j as u32,
        bi,
        partner,
        si.position,
        si.radius,
        n,
        overlap,
        r_star_alpha,
        m_star,
    ) {
        Ok(_) => Ok(()),
        Err(Fail::Overflow) => Err(overflow()),
        Err(Fail::Capacity) => Err(StepError::ContactCapacity {
            sphere: i as u32,
            slots: ctx.k as u32,
        }),
    }
}
