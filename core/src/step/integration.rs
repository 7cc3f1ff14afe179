//! Integration: symplectic Euler (kick then drift), the leapfrog form of velocity Verlet:
//! v ← v + (F_c/m + g)·dt, x ← x + v·dt (F_c the contact force; gravity as g itself). It
//! needs one force evaluation per step and is symplectic, so an elastic system keeps its energy
//! bounded (the energy test checks 0.1 % over 1e5 steps).
//!
//! Rotation:
//! - single spheres (isotropic): ω ← ω + (T/I)·dt; orientation is not integrated;
//! - clumps: Euler's equations in the principal frame, ω_b ← ω_b + I⁻¹(T_b − ω_b × Iω_b)·dt,
//!   then q ← normalise(q + ½dt ω⊗q) and the spheres are re-placed from their offsets.
//!
//! Rolling friction (seed 000 eq. (7)) arrives as a magnitude Tr = Σ μr Fn Ri per body, to be
//! applied along −ω̂ with ω̂ taken at the start of the step. Its angular impulse is capped so that
//! the ω component along ω̂ goes to zero at most, never negative: the torque never reverses ω
//! within a step (DESIGN §2).

use crate::error::{Other, Stage, StepError};
use crate::num::{Scalar, Vec3};
use crate::world::World;

impl<S: Scalar> World<'_, S> {
    pub(crate) fn integrate(&mut self) -> Result<(), StepError> {
        let dt = self.dt;
        let nb = self.n_bodies as usize;
        // Largest sphere displacement of this step (L1 norm ≥ Euclidean), for the neighbour list.
        let mut max_disp = S::ZERO;
        let g = self.gravity;
        for (id, b) in self.bodies[..nb].iter_mut().enumerate() {
            // (F_c/m + g)·dt, not F·(dt/m): dt/m can be a few raw units in Q32.32 (tiny dt,
            // light body). Gravity enters as g itself, not as the rounded force m·g, which
            // for a very light body would shift its acceleration (fuzz finding F3): the
            // accumulator holds F_c + m·g, and subtracting the same rounded m·g that
            // body_forces added recovers the contact force F_c exactly.
            // A kinematic body (inverse mass zero, `body::kinematic`) keeps its velocity:
            // no contact force and no gravity.
            if b.inv_mass != S::ZERO {
                let contact = b.force - g.scale(b.mass);
                b.velocity += (contact.scale(b.inv_mass) + g).scale(dt);
            }
            let dx = b.velocity.scale(dt);
            b.position += dx;
            let w0 = b.angular_velocity;
            if !b.is_clump {
                let inv_i = b.inv_inertia.x;
                let mut w = w0 + b.torque.scale(inv_i).scale(dt);
                if b.roll_torque > S::ZERO {
                    if let Some(hat) = unit(w0) {
                        let along = w.dot(hat);
                        if along > S::ZERO {
                            let dec = (b.roll_torque * inv_i * dt).min(along);
                            w -= hat.scale(dec);
                        }
                    }
                }
                b.angular_velocity = w;
                let s = &mut self.spheres[b.first_sphere as usize];
                s.position = b.position;
                max_disp = max_disp.max(dx.l1_norm());
            } else {
                let rot = b.orientation.to_mat3();
                let wb0 = rot.mul_t_vec(w0);
                let tb = rot.mul_t_vec(b.torque);
                let lb = b.inertia.mul_elem(wb0);
                let gyro = wb0.cross(lb);
                let mut wb = wb0 + b.inv_inertia.mul_elem(tb - gyro).scale(dt);
                if b.roll_torque > S::ZERO {
                    if let Some(hat) = unit(wb0) {
                        let along = wb.dot(hat);
                        // Δω = −s·I⁻¹ω̂ with angular impulse s ≤ Tr·dt; the ω̂ component then
                        // falls by s·k, k = ω̂ᵀI⁻¹ω̂; cap s so it stops at zero.
                        let dir = b.inv_inertia.mul_elem(hat);
                        let k = dir.dot(hat);
                        if along > S::ZERO && k > S::ZERO {
                            let s = (b.roll_torque * dt).min(along / k);
                            wb -= dir.scale(s);
                        }
                    }
                }
                let w = rot.mul_vec(wb);
                b.angular_velocity = w;
                b.orientation = b.orientation.integrate(w, dt);
                let rot = b.orientation.to_mat3();
                let first = b.first_sphere as usize;
                for s in self.spheres[first..first + b.sphere_count as usize].iter_mut() {
                    let p = b.position + rot.mul_vec(s.offset);
                    max_disp = max_disp.max((p - s.position).l1_norm());
                    s.position = p;
                    if !s.position.is_valid() {
                        return Err(overflow(id));
                    }
                }
                if !b.orientation.is_valid() {
                    return Err(overflow(id));
                }
            }
            if !(b.position.is_valid() & b.velocity.is_valid() & b.angular_velocity.is_valid()) {
                return Err(overflow(id));
            }
        }
        self.note_drift(max_disp);
        Ok(())
    }
}

/// Unit vector along `v`, or `None` for the zero vector (accurate even for tiny ω, so rolling
/// friction acts down to the last raw unit; no division: see [`Vec3::normalize_with_len`]).
#[inline]
fn unit<S: Scalar>(v: Vec3<S>) -> Option<Vec3<S>> {
    v.normalize_with_len().map(|(u, _)| u)
}

fn overflow(id: usize) -> StepError {
    StepError::Overflow {
        stage: Stage::Integration,
        body: id as u32,
        other: Other::None,
    }
}
