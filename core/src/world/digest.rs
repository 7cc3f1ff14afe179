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
            // In increasing partner order: the list keeps its entries in the order of the
            // last rebuild's cell scan, which depends on when rebuilds happened, while the
            // contacts themselves do not (each partner appears once).
            let mut last = None;
            while let Some(c) = self
                .contact_slots(i as u32)
                .filter(|c| last.is_none_or(|p| c.partner > p))
                .min_by_key(|c| c.partner)
            {
                last = Some(c.partner);
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
                if c.state.roll_torque != Vec3::ZERO {
                    h.v(c.state.roll_torque);
                }
                if c.state.jkr_attached {
                    h.u64(1);
                }
                if c.state.jkr_root != S::ZERO {
                    h.s(c.state.jkr_root);
                }
            }
        }
        h.u64(self.walls.len() as u64);
        for w in self.walls.iter() {
            w.shape.for_each_bits(|x| h.u64(x));
            h.v(w.velocity);
            h.u64(w.material as u64);
            // Hashed only when set, so the digests of worlds without spinning walls stay.
            if w.spin != S::ZERO {
                h.u64(w.spin.to_bits());
            }
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

#[cfg(test)]
mod tests {
    use crate::num::Fx;
    use crate::owned::OwnedStorage;
    use crate::scenario::BenchBed;

    /// A list with another skin is rebuilt at other times and scans its cells in another
    /// order, so each sphere's entries come in another order, but no contact changes: the
    /// digest, which hashes the contacts in partner order, stays the same. Skins R/8 (the
    /// default), R/4 and R/2 over 15 000 steps of a 300-sphere pour, into contact.
    #[test]
    fn digest_does_not_depend_on_the_list_skin() {
        let bed = BenchBed {
            particles: 300,
            seed: 3,
        };
        let run = |skin_divisor: i32| {
            let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
            let mut w = bed.build(arenas.storage()).unwrap();
            w.list.skin_divisor = skin_divisor;
            w.run(15_000).unwrap();
            assert!(w.contact_count() > 50, "the bed should be in contact");
            w.digest()
        };
        let default = run(crate::step::neighbour_list::SKIN_DIVISOR);
        assert_eq!(run(4), default);
        assert_eq!(run(2), default);
    }
}
