//! Integration: symplectic Euler (kick then drift), the leapfrog form of velocity Verlet:
//! v ← v + (F_c/m + g)·dt, x ← x + v·dt (F_c the sum of contact, bond and drag forces;
//! gravity as g itself). It needs one force evaluation per step and is symplectic, so an
//! elastic system keeps its energy bounded (the energy test checks 0.1 % over 1e5 steps).
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
//!
//! Single spheres move in unchecked arithmetic while their loads and velocities lie inside
//! bounds that exclude overflow ([`single_sphere`]); others, and clumps, in the checked
//! arithmetic.
//!
//! The stage runs in parts over disjoint body ranges ([`IntegratePart`]). Each body first
//! gathers its force sums from every accumulator arena of the contact stage (and clears them
//! for the next step), then moves. A kinematic body (inverse mass zero) keeps its velocity:
//! no contact force and no gravity.

mod single_sphere;

use super::parts::MAX_PARTS;
use crate::body::{Body, BodyForce, Sphere};
use crate::error::{Other, Stage, StepError};
use crate::num::{Envelope, Scalar, Vec3};
use core::ops::Range;
use single_sphere::move_sphere;

/// One part of the integration stage: a range of bodies and their spheres.
pub(crate) struct IntegratePart<'w, S: Scalar> {
    /// Id of the first body.
    pub first_body: usize,
    /// The bodies.
    pub bodies: &'w mut [Body<S>],
    /// Id of the first sphere of the first body.
    pub first_sphere: usize,
    /// The spheres of those bodies.
    pub spheres: &'w mut [Sphere<S>],
    /// The accumulators of these bodies: the world's and each contact part's private arena
    /// (those that touched the range), with the body-id range each covers.
    pub sums: heapless::Vec<(Range<usize>, &'w mut [BodyForce<S>]), { MAX_PARTS + 1 }>,
    /// Largest sphere displacement of the step (L1 norm ≥ Euclidean), mm.
    pub max_disp: S,
    /// The first error, if any.
    pub result: Result<(), StepError>,
}

impl<S: Scalar> IntegratePart<'_, S> {
    /// Move every body of the part by one step `dt` (ms) under gravity `g` (mm/ms²).
    pub(crate) fn run(&mut self, dt: S, g: Vec3<S>) {
        self.result = self.integrate(dt, g);
    }

    /// The summed loads of body `id`, with every accumulator of it cleared.
    #[inline(always)]
    fn take_sums(&mut self, id: usize) -> BodyForce<S> {
        let mut total = BodyForce::default();
        for (range, arena) in self.sums.iter_mut() {
            if range.contains(&id) {
                let a = &mut arena[id - range.start];
                total.merge(a);
                *a = BodyForce::default();
            }
        }
        total
    }

    fn integrate(&mut self, dt: S, g: Vec3<S>) -> Result<(), StepError> {
        let mut max_disp = S::ZERO;
        for k in 0..self.bodies.len() {
            let id = self.first_body + k;
            let sums = self.take_sums(id);
            let b = &mut self.bodies[k];
            if !b.is_clump {
                if let Some(m) = move_sphere(b, &sums, dt, g) {
                    b.velocity = m.velocity;
                    b.position = m.position;
                    b.angular_velocity = m.angular_velocity;
                    b.force = m.force;
                    b.torque = m.torque;
                    b.roll_torque = m.roll;
                    let s = &mut self.spheres[b.first_sphere as usize - self.first_sphere];
                    s.position = m.position;
                    s.velocity = m.velocity;
                    s.spin = m.angular_velocity;
                    max_disp = max_disp.max(m.l1_displacement);
                    continue;
                }
            }
            let force = sums.force();
            b.torque = sums.torque();
            b.roll_torque = sums.roll();
            // (F_c/m + g)·dt, not F·(dt/m): dt/m can be a few raw units in Q32.32 (tiny dt,
            // light body). Gravity enters as g itself, not as the rounded force m·g, which for
            // a very light body would shift its acceleration (fuzz finding F3); the body
            // reports F_c + m·g.
            if b.inv_mass != S::ZERO {
                b.velocity += (force.scale(b.inv_mass) + g).scale(dt);
            }
            b.force = force + g.scale(b.mass);
            let dx = b.velocity.scale(dt);
            b.position += dx;
            let w0 = b.angular_velocity;
            let first = b.first_sphere as usize - self.first_sphere;
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
                self.spheres[first].position = b.position;
                self.spheres[first].sync_motion(b);
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
                for s in self.spheres[first..first + b.sphere_count as usize].iter_mut() {
                    let p = b.position + rot.mul_vec(s.offset);
                    max_disp = max_disp.max((p - s.position).l1_norm());
                    s.position = p;
                    s.sync_motion(b);
                    if !(s.position.is_valid() & s.velocity.is_valid()) {
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
        self.max_disp = max_disp;
        Ok(())
    }
}

/// Unit vector along `v`, or `None` for the zero vector (accurate even for tiny ω, so rolling
/// friction acts down to the last raw unit; no division: see [`Vec3::normalize_with_len`]).
/// The scaled vector lies in [1, 2) per largest component, so the unchecked arithmetic of
/// [`Scalar::Fast`] cannot overflow; its reciprocal root is the fast one.
#[inline]
fn unit<S: Scalar>(v: Vec3<S>) -> Option<Vec3<S>> {
    S::Fast::unit3(v.map(S::to_fast)).map(|u| u.map(S::from_fast))
}

fn overflow(id: usize) -> StepError {
    StepError::Overflow {
        stage: Stage::Integration,
        body: id as u32,
        other: Other::None,
    }
}
