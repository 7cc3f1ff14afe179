//! Narrow phase: contact geometry and relative motion for sphere–sphere and sphere–wall
//! pairs, evaluation of the pair's contact terms, and accumulation of forces and torques.
//!
//! Geometry (seed 000 eqs. (1)–(2), DESIGN §2): α = Ri + Rj − |rj − ri|, n̂ = (rj − ri)/|rj − ri|
//! (n̂ = +z for exactly coincident centres, a deterministic choice; centres closer than 1 mm are
//! normalised after an exact power-of-two scaling, so n̂ stays unit, fuzz findings F1 and F4),
//! R* = RiRj/(Ri+Rj), m* =
//! mimj/(mi+mj) (wall: R* = Ri, m* = mi), a = √(R*α). The contact point is
//! c = ri + n̂(Ri − α/2); lever arms run from each body's centre of mass to c.
//!
//! Sphere pairs come from the neighbour list ([`super::neighbour_list`]), whose entries hold
//! the contact history, read and updated in place. One validity check per contact (force,
//! torques, history) turns any fixed-point overflow into [`StepError::Overflow`] naming both
//! parties.

use super::neighbour_list::{key_of, LIVE_FLAG};
use crate::body::{Body, Sphere};
use crate::contact::history::wall_key;
use crate::contact::{ContactKinematics, ContactSlot, ContactState, WALL_PARTNER_FLAG};
use crate::error::{Other, Stage, StepError};
use crate::material::MAX_MATERIALS;
use crate::num::{Scalar, Vec3};
use crate::pair::PairParams;
use crate::wall::Wall;
use crate::world::World;

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
    dt: S,
    /// Live bonds, sorted by sphere pair: bonded pairs get no contact force.
    bonded: &'w [crate::bond::Bond<S>],
}

/// A contact overflowed (the caller names the parties).
struct Overflowed;

impl<S: Scalar> Ctx<'_, S> {
    /// Evaluate one contact between a sphere of body `bi` (side i) and a partner, with its
    /// history `state` (updated in place), and accumulate the forces. Returns the force on j (N).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn contact(
        &mut self,
        pair: &PairParams<S>,
        state: &mut ContactState<S>,
        bi: usize,
        j: Partner<S>,
        p_i: Vec3<S>,
        r_i: S,
        n: Vec3<S>,
        overlap: S,
        r_star_alpha: S,
        r_star: S,
        m_star: S,
    ) -> Result<Vec3<S>, Overflowed> {
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
        let mut w_rel = Vec3::ZERO;
        let mut rolling_inertia = S::ZERO;
        if pair.rolling_epsd.on {
            w_rel = w_i;
            rolling_inertia = rolling_moment(bod_i, arm_i);
        }
        if let Some(bj) = j.body {
            let bod_j = &self.bodies[bj];
            arm_j = c - bod_j.position;
            if pair.rolling_epsd.on {
                w_rel -= bod_j.angular_velocity;
                if bod_j.inv_mass != S::ZERO {
                    let ij = rolling_moment(bod_j, arm_j);
                    rolling_inertia = rolling_inertia * ij / (rolling_inertia + ij);
                }
            }
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
        // A JKR neck (negative overlap) has no Hertz contact radius.
        let a = if r_star_alpha > S::ZERO {
            r_star_alpha.sqrt()
        } else {
            S::ZERO
        };
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
            r_star,
            w_rel,
            rolling_inertia,
        };
        if !pair.keeps_history() {
            *state = ContactState::default();
        }
        let out = pair.evaluate(&kin, state);
        let f = n.scale(out.normal) + out.tangential;
        let mut ti = arm_i.cross(f);
        let mut tj = arm_j.cross(f);
        if pair.rolling_epsd.on {
            // EPSD torque on j; i receives the opposite (i's torque is −ti).
            ti += out.rolling_torque;
            tj += out.rolling_torque;
        }
        if !(f.is_valid()
            & ti.is_valid()
            & tj.is_valid()
            & out.roll_i.is_valid()
            & out.roll_j.is_valid()
            & state.delta.is_valid())
        {
            return Err(Overflowed);
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
        Ok(f)
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

type PairTable<S> = [[PairParams<S>; MAX_MATERIALS]; MAX_MATERIALS];

/// Everything split out of the world for the contact loops.
struct Split<'w, S: Scalar> {
    ctx: Ctx<'w, S>,
    spheres: &'w [Sphere<S>],
    /// The live half of the neighbour list.
    slots: &'w mut [ContactSlot<S>],
    /// Entry counts of the live half.
    count: &'w mut [u32],
    k: usize,
    pairs: &'w PairTable<S>,
}

impl<S: Scalar> World<'_, S> {
    fn split(&mut self) -> Split<'_, S> {
        let cap = self.spheres.len();
        let k = self.slots_per_sphere as usize;
        let cur = self.current as usize;
        let slots = &mut self.slots[cur * cap * k..(cur + 1) * cap * k];
        let count = &mut self.index[(2 + cur) * cap..(3 + cur) * cap];
        Split {
            ctx: Ctx {
                bodies: &mut self.bodies[..],
                dt: self.dt,
                bonded: &self.bond_table.bonds[..self.bond_table.n as usize],
            },
            spheres: &self.spheres[..self.n_spheres as usize],
            slots,
            count,
            k,
            pairs: &self.pairs,
        }
    }

    /// All contacts, sphere by sphere in id order: first the sphere–sphere entries of its
    /// neighbour list (in list order; history updated in place, live flag set or cleared),
    /// then its wall contacts (walls in insertion order). One pass keeps each sphere's list
    /// in cache for both.
    pub(crate) fn contacts(&mut self) -> Result<(), StepError> {
        let n = self.n_spheres as usize;
        let mut walls = self.walls.clone();
        let Split {
            mut ctx,
            spheres,
            slots,
            count,
            k,
            pairs,
        } = self.split();
        for i in 0..n {
            let base = i * k;
            let list = &mut slots[base..base + k];
            let cnt = count[i] as usize;
            // Wall entries lose their live flag here; those not hit again are removed below.
            let mut had_wall = false;
            for e in list[..cnt].iter_mut() {
                if e.partner & WALL_PARTNER_FLAG != 0 {
                    e.partner &= !LIVE_FLAG;
                    had_wall = true;
                    continue;
                }
                let j = key_of(e.partner);
                let live = sphere_pair(&mut ctx, spheres, pairs, i, j as usize, &mut e.state)?;
                e.partner = if live { j | LIVE_FLAG } else { j };
            }
            if spheres[i].near_walls != 0 || had_wall {
                count[i] = sphere_walls(
                    &mut ctx,
                    &spheres[i],
                    i,
                    list,
                    cnt,
                    had_wall,
                    &mut walls,
                    pairs,
                )? as u32;
            }
        }
        self.walls = walls;
        Ok(())
    }
}

/// Wall contacts of sphere `si` with its near walls (`cnt` entries in `list`, wall entries
/// already un-flagged when `had_wall`). Wall entries are found by key (a sphere has a
/// handful of entries), appended when a contact starts and removed when it ends. Returns the
/// new entry count.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn sphere_walls<S: Scalar>(
    ctx: &mut Ctx<'_, S>,
    s: &Sphere<S>,
    si: usize,
    list: &mut [ContactSlot<S>],
    mut cnt: usize,
    had_wall: bool,
    walls: &mut [Wall<S>],
    pairs: &PairTable<S>,
) -> Result<usize, StepError> {
    let k = list.len();
    let bi = s.body as usize;
    for (wi, w) in walls.iter_mut().enumerate() {
        if s.near_walls & (1 << wi) == 0 {
            continue;
        }
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
            let mut scratch = ContactState::default();
            let state = if pair.keeps_history() {
                let at = match list[..cnt].iter().position(|e| key_of(e.partner) == key) {
                    Some(at) => at,
                    None => {
                        if cnt >= k {
                            return Err(StepError::ContactCapacity {
                                sphere: si as u32,
                                slots: k as u32,
                            });
                        }
                        list[cnt] = ContactSlot {
                            partner: key,
                            state: ContactState::default(),
                        };
                        cnt += 1;
                        cnt - 1
                    }
                };
                list[at].partner = key | LIVE_FLAG;
                &mut list[at].state
            } else {
                &mut scratch
            };
            match ctx.contact(
                pair,
                state,
                bi,
                partner,
                s.position,
                s.radius,
                nrm,
                a,
                s.radius * a,
                s.radius,
                m_star,
            ) {
                Ok(f) => w.force += f,
                Err(Overflowed) => {
                    return Err(StepError::Overflow {
                        stage: Stage::WallContact,
                        body: bi as u32,
                        other: Other::Wall(wi as u32),
                    })
                }
            }
        }
    }
    if had_wall {
        // Drop ended wall contacts, keeping the order of the rest.
        let mut kept = 0;
        for e in 0..cnt {
            let p = list[e].partner;
            if p & WALL_PARTNER_FLAG == 0 || p & LIVE_FLAG != 0 {
                list[kept] = list[e];
                kept += 1;
            }
        }
        cnt = kept;
    }
    Ok(cnt)
}

/// Evaluate one neighbour-list pair (a < b) if in contact, with its history `state`. Returns
/// whether the pair touches and keeps history; a pair that does not touch has its history
/// cleared.
#[inline(never)]
fn sphere_pair<S: Scalar>(
    ctx: &mut Ctx<'_, S>,
    spheres: &[Sphere<S>],
    pairs: &PairTable<S>,
    i: usize,
    j: usize,
    state: &mut ContactState<S>,
) -> Result<bool, StepError> {
    let si = &spheres[i];
    let sj = &spheres[j];
    let d = sj.position - si.position;
    let rs = si.radius + sj.radius;
    // An attached JKR contact holds across a neck, down to a negative overlap.
    let reach = if state.jkr_attached {
        rs + pairs[si.material as usize][sj.material as usize].jkr.reach
    } else {
        rs
    };
    // Cheap per-axis rejection before the squared distance.
    if d.x.abs() >= reach || d.y.abs() >= reach || d.z.abs() >= reach {
        *state = ContactState::default();
        return Ok(false);
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
    if d2 >= reach * reach {
        *state = ContactState::default();
        return Ok(false);
    }
    if crate::bond::arena::is_bonded(ctx.bonded, i as u32, j as u32) {
        // A bond carries the load; the pair meets the contact law, with fresh history, only
        // once the bond breaks.
        *state = ContactState::default();
        return Ok(false);
    }
    let pair = &pairs[si.material as usize][sj.material as usize];
    if !pair.defined {
        return Err(StepError::UndefinedPair {
            material_a: si.material,
            material_b: sj.material,
        });
    }
    // Beyond 1 mm the squared distance has ≥ 32 significant bits: dist is its correctly
    // rounded root (the overlap needs every bit) and the normal only needs 1/dist to within a
    // unit, which rsqrt gives without a division. Closer centres (huge overlaps) normalise d
    // after an exact power-of-two scaling, because a rounded |d|² of a few raw units would
    // leave the normal visibly non-unit (fuzz finding F4; F1 was the |d|² = 0 case); exactly
    // coincident centres take n = +z, a deterministic choice.
    let (n, dist) = if d2 >= S::ONE {
        let (root, inv_root) = d2.sqrt_rsqrt();
        (d.scale(inv_root), root)
    } else if let Some(u_len) = d.normalize_with_len() {
        u_len
    } else {
        (Vec3::new(S::ZERO, S::ZERO, S::ONE), S::ZERO)
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
    let r_star = if !pair.needs_r_star() {
        S::ZERO
    } else if si.radius == sj.radius {
        si.radius * S::HALF
    } else {
        si.radius * sj.radius / rs
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
        state,
        bi,
        partner,
        si.position,
        si.radius,
        n,
        overlap,
        r_star_alpha,
        r_star,
        m_star,
    ) {
        Ok(_) if pair.jkr.on && !state.jkr_attached => {
            // The JKR neck broke (beyond the separation): no force was applied.
            *state = ContactState::default();
            Ok(false)
        }
        Ok(_) => Ok(pair.keeps_history()),
        Err(Overflowed) => Err(overflow()),
    }
}
