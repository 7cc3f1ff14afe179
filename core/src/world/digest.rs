//! The world's state digest and per-body dump ([`crate::digest`]).

use super::World;
use crate::digest::{BodyRecord, Fnv1a};
use crate::num::{Scalar, Vec3};

impl<S: Scalar> World<'_, S> {
    /// 64-bit FNV-1a digest of the whole state (see the module docs).
    pub fn digest(&self) -> u64 {
        let mut h = Fnv1a::default();
        h.u64(self.steps);
        h.s(self.time);
        h.s(self.dt);
        h.v(self.gravity);
        h.u64(self.n_bodies as u64);
        for b in self.bodies() {
            h.body(b);
        }
        h.u64(self.n_spheres as u64);
        for (i, s) in self.spheres().iter().enumerate() {
            h.v(s.position);
            h.s(s.radius);
            h.v(s.offset);
            h.u64(s.body as u64);
            h.u64(s.material as u64);
            h.u64(self.contact_slots(i as u32).count() as u64);
            for c in self.contact_slots(i as u32) {
                h.u64(c.partner as u64);
                h.v(c.state.delta);
                // Optional-effect state is hashed only when set, so digests of runs without those
                // effects are unchanged.
                if c.state.max_overlap != S::ZERO {
                    h.s(c.state.max_overlap);
                }
                if c.state.roll_angle != Vec3::ZERO {
                    h.v(c.state.roll_angle);
                }
                if c.state.jkr_attached {
                    h.u64(1);
                }
            }
        }
        h.u64(self.walls.len() as u64);
        for w in self.walls.iter() {
            w.shape.for_each_bits(|x| h.u64(x));
            h.v(w.velocity);
            h.u64(w.material as u64);
        }
        // Bond state; hashes nothing in worlds that never used bonds.
        self.bond_table.hash_into(&mut h);
        h.finish()
    }

    /// Per-body records (insertion order) for a diffable dump.
    pub fn body_records(&self) -> impl Iterator<Item = BodyRecord> + '_ {
        self.bodies().iter().enumerate().map(|(i, b)| {
            let mut h = Fnv1a::default();
            h.body(b);
            BodyRecord {
                id: i as u32,
                position_mm: b.position.to_f64(),
                velocity_mm_ms: b.velocity.to_f64(),
                angular_velocity_rad_ms: b.angular_velocity.to_f64(),
                orientation: b.orientation.to_f64(),
                hash: h.finish(),
            }
        })
    }
}
