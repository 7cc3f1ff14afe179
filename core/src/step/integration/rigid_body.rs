//! One kick–drift step of a rigid body, written once for any arithmetic: the checked scalar
//! of the world (every overflow poisons and is then reported), or its unchecked
//! [`Scalar::Fast`] twin inside an envelope of magnitudes that excludes overflow
//! ([`clump_envelope`]). Both give the same bits wherever the envelope holds, because the
//! fast arithmetic rounds exactly as the checked one.
//!
//! The formulas are those of the module docs of [`super`]: v ← v + (F/m + g)·dt,
//! x ← x + v·dt; a sphere's ω ← ω + (T/I)·dt, a clump's through Euler's equations in its
//! principal frame; rolling friction capped so that it never reverses ω; the orientation
//! advanced and renormalised; each clump sphere placed at x + R·offset.

use crate::body::{Body, Loads};
use crate::num::{Envelope, Quat, Scalar, Vec3};

/// The motion of a body, in arithmetic T.
#[derive(Clone, Copy, Debug)]
pub(super) struct Motion<T> {
    /// Centre of mass, mm.
    pub position: Vec3<T>,
    /// Velocity, mm/ms.
    pub velocity: Vec3<T>,
    /// Angular velocity, rad/ms.
    pub angular_velocity: Vec3<T>,
    /// Orientation (clumps).
    pub orientation: Quat<T>,
    /// Force of the step, gravity included, N (reported).
    pub force: Vec3<T>,
    /// Torque of the step, N·mm (reported).
    pub torque: Vec3<T>,
    /// Rolling-resistance torque magnitude of the step, N·mm (reported).
    pub roll: T,
}

/// A body's constants, in arithmetic T.
#[derive(Clone, Copy, Debug)]
pub(super) struct Inertia<T> {
    /// Mass, g.
    pub mass: T,
    /// 1/mass, 1/g (zero for a kinematic body).
    pub inv_mass: T,
    /// Principal moments, g·mm².
    pub moments: Vec3<T>,
    /// Their inverses, 1/(g·mm²).
    pub inv_moments: Vec3<T>,
}

/// Body `b` and its force sums in arithmetic T (through `f`, e.g. [`Scalar::to_fast`]).
#[inline(always)]
pub(super) fn state_of<S: Scalar, T: Scalar>(
    b: &Body<S>,
    sums: &Loads<S>,
    f: impl Fn(S) -> T + Copy,
) -> (Motion<T>, Inertia<T>) {
    let q = b.orientation;
    let Loads {
        force,
        torque,
        roll,
    } = *sums;
    (
        Motion {
            position: b.position.map(f),
            velocity: b.velocity.map(f),
            angular_velocity: b.angular_velocity.map(f),
            orientation: Quat {
                w: f(q.w),
                x: f(q.x),
                y: f(q.y),
                z: f(q.z),
            },
            force: force.map(f),
            torque: torque.map(f),
            roll: f(roll),
        },
        Inertia {
            mass: f(b.mass),
            inv_mass: f(b.inv_mass),
            moments: b.inertia.map(f),
            inv_moments: b.inv_inertia.map(f),
        },
    )
}

/// Unit vector along `v`, or `None` for the zero vector (accurate even for tiny ω, so rolling
/// friction acts down to the last raw unit): [`Envelope::unit3`] of the fast arithmetic,
/// whose scaled vector lies in [1, 2) per largest component, so it cannot overflow.
#[inline(always)]
pub(super) fn unit<T: Scalar>(v: Vec3<T>) -> Option<Vec3<T>> {
    T::Fast::unit3(v.map(T::to_fast)).map(|u| u.map(T::from_fast))
}

/// One step of a body whose loads `m.force`, `m.torque`, `m.roll` are its contact sums (the
/// reported force gains m·g). Sphere or clump by `clump`.
#[inline(always)]
pub(super) fn step_body<T: Scalar>(
    m: &Motion<T>,
    k: &Inertia<T>,
    clump: bool,
    dt: T,
    g: Vec3<T>,
) -> Motion<T> {
    // (F_c/m + g)·dt, not F·(dt/m): dt/m can be a few raw units in Q32.32 (tiny dt, light
    // body). Gravity enters as g itself, not as the rounded force m·g, which for a very light
    // body would shift its acceleration (fuzz finding F3); a kinematic body (inverse mass
    // zero) keeps its velocity: no contact force, no gravity.
    let velocity = if k.inv_mass != T::ZERO {
        m.velocity + (m.force.scale(k.inv_mass) + g).scale(dt)
    } else {
        m.velocity
    };
    let position = m.position + velocity.scale(dt);
    let w0 = m.angular_velocity;
    let (angular_velocity, orientation) = if !clump {
        let inv_i = k.inv_moments.x;
        let mut w = w0 + m.torque.scale(inv_i).scale(dt);
        if m.roll > T::ZERO {
            if let Some(hat) = unit(w0) {
                let along = w.dot(hat);
                if along > T::ZERO {
                    let dec = (m.roll * inv_i * dt).min(along);
                    w -= hat.scale(dec);
                }
            }
        }
        (w, m.orientation)
    } else {
        let rot = m.orientation.to_mat3();
        let wb0 = rot.mul_t_vec(w0);
        let tb = rot.mul_t_vec(m.torque);
        let gyro = wb0.cross(k.moments.mul_elem(wb0));
        let mut wb = wb0 + k.inv_moments.mul_elem(tb - gyro).scale(dt);
        if m.roll > T::ZERO {
            if let Some(hat) = unit(wb0) {
                let along = wb.dot(hat);
                // Δω = −s·I⁻¹ω̂ with angular impulse s ≤ Tr·dt; the ω̂ component then falls
                // by s·k, k = ω̂ᵀI⁻¹ω̂; cap s so it stops at zero.
                let dir = k.inv_moments.mul_elem(hat);
                let kk = dir.dot(hat);
                if along > T::ZERO && kk > T::ZERO {
                    let s = (m.roll * dt).min(along / kk);
                    wb -= dir.scale(s);
                }
            }
        }
        let w = rot.mul_vec(wb);
        (w, m.orientation.integrate(w, dt))
    };
    Motion {
        position,
        velocity,
        angular_velocity,
        orientation,
        force: m.force + g.scale(k.mass),
        torque: m.torque,
        roll: m.roll,
    }
}

/// Powers of two bounding a clump's step in the fast arithmetic (internal units): loads
/// < 2^28 N and N·mm, …
const LOAD_BITS: i32 = 28;
/// … velocity < 2^24 mm/ms and every kick (a·dt, I⁻¹τ·dt) < 2^24, …
const VELOCITY_BITS: i32 = 24;
/// … angular velocity < 2^5 rad/ms (32 000 rad/s), …
const SPIN_BITS: i32 = 5;
/// … position < 2^29 mm, …
const POSITION_BITS: i32 = 29;
/// … gravity < 2^16 mm/ms², …
const GRAVITY_BITS: i32 = 16;
/// … time step < 1 ms, …
const TIMESTEP_BITS: i32 = 0;
/// … mass < 2^12 g and principal moments < 2^16 g·mm², …
const MASS_BITS: i32 = 12;
const MOMENT_BITS: i32 = 16;
/// … inverse moments < 2^20 1/(g·mm²), within a factor 2^4 of each other, …
const INVERSE_MOMENT_BITS: i32 = 20;
const ANISOTROPY_BITS: i32 = 4;
/// … or all three zero (a kinematic clump: a machine part) with any principal moments that
/// keep ω×Iω below 2^28 N·mm, …
const KINEMATIC_GYRO_BITS: i32 = 28;
/// … and sphere offsets < 2^10 mm.
pub(super) const OFFSET_BITS: i32 = 10;

/// Whether a clump's step in the fast arithmetic cannot overflow. Inside these bounds (each
/// |x| < 2^b, and ⌊log₂⌋ bit lengths adding over products): Rᵀτ < 2^28.8; Iω < 2^21.8 and
/// ω×Iω < 2^28.6, so τ_b − ω×Iω < 2^29.8; the inverse products F/m and I⁻¹(τ_b − ω×Iω) are
/// bounded by their bit lengths below 2^24, so every kick (× dt < 1) is too and the new
/// velocities stay below 2^25; along ω̂ < 2^26.6, I⁻¹ω̂ < 2^20.6, its dot with ω̂ < 2^22.2,
/// and the capped impulse times I⁻¹ω̂ is at most `along` times the anisotropy 2^4: < 2^30.6;
/// Tr·dt < 2^28; m·g < 2^28; the quaternion terms stay below 2. Each sphere's R·offset
/// < 2^11 and ω × arm < 2^17 (offsets bounded by the caller).
///
/// A kinematic clump (every inverse moment zero, as `World::set_body_kinematic` leaves it)
/// keeps its body-frame spin: the kick I⁻¹(τ_b − ω×Iω)·dt is zero whatever its factor, and
/// the rolling cap does nothing (I⁻¹ω̂ = 0). Its moments can be far above 2^16 (a steel
/// machine part), so instead of their bound the gyroscopic terms are bounded through their
/// bit lengths, as the checked arithmetic would overflow there: with |x| < 2^(b(x)+1) and
/// |Rᵀω| < √3·2^(b(ω)+1), Iω < 2^(b(I)+b(ω)+2.8) and ω×Iω < 2^(2b(ω)+b(I)+5.6), so
/// 2b(ω) + b(I) + 6 ≤ [`KINEMATIC_GYRO_BITS`] keeps ω×Iω below 2^28, τ_b − ω×Iω below 2^30
/// and (with b(I) ≤ 30 in Q32.32) b(I) + b(ω) ≤ 26, so Iω below 2^29.
#[inline(always)]
pub(super) fn clump_envelope<T: Envelope>(
    m: &Motion<T>,
    k: &Inertia<T>,
    dt: T,
    g: Vec3<T>,
) -> bool {
    let mag = |v: Vec3<T>| T::magnitude3(v);
    // ⌊log₂|x|⌋, or far below any bound for 0.
    let bits = |x: T| {
        if x == T::ZERO {
            -64
        } else {
            x.log2_floor()
        }
    };
    let min3 = |v: Vec3<T>| v.x.min(v.y).min(v.z);
    let inputs_in = mag(m.force).within(LOAD_BITS)
        & mag(m.torque).within(LOAD_BITS)
        & m.roll.within(LOAD_BITS)
        & (m.roll >= T::ZERO)
        & mag(m.velocity).within(VELOCITY_BITS)
        & mag(m.angular_velocity).within(SPIN_BITS)
        & mag(m.position).within(POSITION_BITS)
        & mag(g).within(GRAVITY_BITS)
        & (dt > T::ZERO)
        & dt.within(TIMESTEP_BITS)
        & (k.mass >= T::ZERO)
        & k.mass.within(MASS_BITS)
        & (k.inv_mass >= T::ZERO)
        & mag(k.inv_moments).within(INVERSE_MOMENT_BITS);
    // Every inverse moment zero: a kinematic clump (see above).
    let spin_in = if mag(k.inv_moments) == T::ZERO {
        2 * bits(mag(m.angular_velocity)) + bits(mag(k.moments)) + 6 <= KINEMATIC_GYRO_BITS
    } else {
        mag(k.moments).within(MOMENT_BITS) & (min3(k.inv_moments) > T::ZERO)
    };
    if !(inputs_in && spin_in) {
        return false;
    }
    // Bit lengths of the torque-side sum: |τ_b| < 2^(b(τ)+2), |ω×Iω| < 2^(2b(ω)+b(I)+4).
    let spin_load =
        (bits(mag(m.torque)) + 2).max(2 * bits(mag(m.angular_velocity)) + bits(mag(k.moments)) + 4);
    bits(mag(m.force)) + bits(k.inv_mass) + 2 <= VELOCITY_BITS
        && spin_load + bits(mag(k.inv_moments)) + 2 <= VELOCITY_BITS
        && bits(mag(k.inv_moments)) - bits(min3(k.inv_moments)) <= ANISOTROPY_BITS
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Fx, FxFast};

    /// A deterministic stream of numbers in [−1, 1).
    struct Stream(u64);
    impl Stream {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
        /// A value between `lo` and `hi` (> 0), uniform in its logarithm.
        fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
            lo * (hi / lo).powf(0.5 * (self.next() + 1.0))
        }
        /// A random unit quaternion.
        fn unit_quat(&mut self) -> Quat<Fx> {
            let v = [self.next(), self.next(), self.next(), self.next()];
            let n = (v.iter().map(|x| x * x).sum::<f64>()).sqrt();
            Quat::from_f64(v.map(|x| x / n))
        }
        /// A motion at orientation `q`: position within ±`position_mm`, velocity, spin,
        /// force and torque within ± the four `scales`, rolling torque `roll`.
        fn motion(
            &mut self,
            q: Quat<Fx>,
            position_mm: f64,
            scales: [f64; 4],
            roll: f64,
        ) -> Motion<Fx> {
            Motion {
                position: self.vec(position_mm),
                velocity: self.vec(scales[0]),
                angular_velocity: self.vec(scales[1]),
                orientation: q,
                force: self.vec(scales[2]),
                torque: self.vec(scales[3]),
                roll: Fx::from_f64(roll),
            }
        }
        fn vec(&mut self, scale: f64) -> Vec3<Fx> {
            Vec3::new(
                Fx::from_f64(scale * self.next()),
                Fx::from_f64(scale * self.next()),
                Fx::from_f64(scale * self.next()),
            )
        }
    }

    /// The same motion and inertia in the fast arithmetic.
    fn fast_copy(m: &Motion<Fx>, k: &Inertia<Fx>) -> (Motion<FxFast>, Inertia<FxFast>) {
        let to = |x: Fx| FxFast::from(x);
        let q = m.orientation;
        (
            Motion {
                position: m.position.map(to),
                velocity: m.velocity.map(to),
                angular_velocity: m.angular_velocity.map(to),
                orientation: Quat {
                    w: to(q.w),
                    x: to(q.x),
                    y: to(q.y),
                    z: to(q.z),
                },
                force: m.force.map(to),
                torque: m.torque.map(to),
                roll: to(m.roll),
            },
            Inertia {
                mass: to(k.mass),
                inv_mass: to(k.inv_mass),
                moments: k.moments.map(to),
                inv_moments: k.inv_moments.map(to),
            },
        )
    }

    /// Every output of the checked step equals the fast step's, raw (case `k` in messages).
    fn assert_same_bits(checked: &Motion<Fx>, fast: &Motion<FxFast>, k: usize) {
        let bits = |v: Vec3<Fx>| [v.x.raw(), v.y.raw(), v.z.raw()];
        let bits_f = |v: Vec3<FxFast>| [v.x.raw(), v.y.raw(), v.z.raw()];
        assert_eq!(bits(checked.position), bits_f(fast.position), "case {k}");
        assert_eq!(bits(checked.velocity), bits_f(fast.velocity), "case {k}");
        assert_eq!(
            bits(checked.angular_velocity),
            bits_f(fast.angular_velocity),
            "case {k}"
        );
        let (o, of) = (checked.orientation, fast.orientation);
        assert_eq!(
            [o.w.raw(), o.x.raw(), o.y.raw(), o.z.raw()],
            [of.w.raw(), of.x.raw(), of.y.raw(), of.z.raw()],
            "case {k}"
        );
        assert_eq!(bits(checked.force), bits_f(fast.force), "case {k}");
    }

    /// Inside [`clump_envelope`] the fast arithmetic gives the checked one's bits: 100 000
    /// random clump steps (pod-like and far from it), every output compared raw.
    #[test]
    fn fast_clump_step_matches_the_checked_one_bit_for_bit() {
        let mut s = Stream(0x853C_49E6_748F_EA9B);
        let mut inside = 0;
        for k in 0..100_000 {
            let q = s.unit_quat();
            let moments = Vec3::new(
                s.log_uniform(10.0, 400.0),
                s.log_uniform(10.0, 400.0),
                s.log_uniform(10.0, 400.0),
            );
            let mass = s.log_uniform(0.1, 5.0);
            let (sv, sw, sf, st, sr) = (
                s.log_uniform(1e-6, 3.0),
                s.log_uniform(1e-6, 3.0),
                s.log_uniform(1e-6, 10.0),
                s.log_uniform(1e-6, 30.0),
                s.log_uniform(1e-6, 1.0),
            );
            let m = s.motion(q, 200.0, [sv, sw, sf, st], sr * (k % 2) as f64);
            let inertia = Inertia {
                mass: Fx::from_f64(mass),
                inv_mass: Fx::from_f64(1.0 / mass),
                moments: Vec3::new(
                    Fx::from_f64(moments.x),
                    Fx::from_f64(moments.y),
                    Fx::from_f64(moments.z),
                ),
                inv_moments: Vec3::new(
                    Fx::from_f64(1.0 / moments.x),
                    Fx::from_f64(1.0 / moments.y),
                    Fx::from_f64(1.0 / moments.z),
                ),
            };
            let dt = Fx::from_f64(s.log_uniform(5e-4, 5e-2));
            let g = Vec3::new(Fx::ZERO, Fx::ZERO, Fx::from_f64(-9.81e-3));
            let to = |x: Fx| FxFast::from(x);
            let (mf, kf) = fast_copy(&m, &inertia);
            if !clump_envelope(&mf, &kf, to(dt), g.map(to)) {
                continue;
            }
            inside += 1;
            let checked = step_body(&m, &inertia, true, dt, g);
            let fast = step_body(&mf, &kf, true, to(dt), g.map(to));
            assert_same_bits(&checked, &fast, k);
        }
        assert!(
            inside > 90_000,
            "only {inside} random steps inside the envelope"
        );
    }

    /// Kinematic clumps (inverse mass and moments zero; moments up to 2^30 g·mm², spins up
    /// to 8 rad/ms): inside [`clump_envelope`] the fast arithmetic gives the checked one's
    /// bits, and the checked step is free of overflow; the envelope takes every such clump of
    /// a machine's size (moments below 2^24, spins below 0.5 rad/ms) and refuses those whose
    /// gyroscopic terms overflow the checked arithmetic. Fails without the kinematic gyro
    /// bound (a wrapped ω×Iω would slip through).
    #[test]
    fn fast_kinematic_clump_step_matches_the_checked_one_bit_for_bit() {
        let mut s = Stream(0x2F0B_3C1D_9E8A_7765);
        let (mut inside, mut machine_sized, mut overflowing) = (0, 0, 0);
        for k in 0..100_000 {
            let q = s.unit_quat();
            let moments = [0; 3].map(|_| s.log_uniform(10.0, (1u64 << 30) as f64));
            let (spin, sv, sf, st) = (
                s.log_uniform(1e-6, 8.0),
                s.log_uniform(1e-6, 3.0),
                s.log_uniform(1e-6, 100.0),
                s.log_uniform(1e-6, 1e4),
            );
            let roll = s.log_uniform(1e-6, 1.0) * (k % 2) as f64;
            let m = s.motion(q, 500.0, [sv, spin, sf, st], roll);
            let inertia = Inertia {
                mass: Fx::from_f64(s.log_uniform(1.0, 4000.0)),
                inv_mass: Fx::ZERO,
                moments: Vec3::new(
                    Fx::from_f64(moments[0]),
                    Fx::from_f64(moments[1]),
                    Fx::from_f64(moments[2]),
                ),
                inv_moments: Vec3::ZERO,
            };
            let dt = Fx::from_f64(s.log_uniform(5e-4, 5e-2));
            let g = Vec3::new(Fx::ZERO, Fx::ZERO, Fx::from_f64(-9.81e-3));
            let checked = step_body(&m, &inertia, true, dt, g);
            let checked_ok = checked.angular_velocity.is_valid() && checked.orientation.is_valid();
            let to = |x: Fx| FxFast::from(x);
            let (mf, kf) = fast_copy(&m, &inertia);
            let machine = moments.iter().all(|&i| i < (1u64 << 24) as f64) && spin < 0.5;
            if !clump_envelope(&mf, &kf, to(dt), g.map(to)) {
                assert!(
                    !machine,
                    "case {k}: a machine-sized kinematic clump was refused"
                );
                overflowing += usize::from(!checked_ok);
                continue;
            }
            inside += 1;
            machine_sized += usize::from(machine);
            assert!(
                checked_ok,
                "case {k}: the checked step overflows inside the envelope"
            );
            let fast = step_body(&mf, &kf, true, to(dt), g.map(to));
            assert_same_bits(&checked, &fast, k);
        }
        assert!(
            inside > 30_000 && machine_sized > 5_000 && overflowing > 500,
            "inside {inside}, machine-sized {machine_sized}, refused and overflowing {overflowing}"
        );
    }
}
