//! One step of a single-sphere body in unchecked arithmetic, inside bounds that exclude
//! overflow (the module docs of [`super`] give the integrator itself).
//!
//! [`move_sphere`] takes the raw-integer path for Q32.32 fixed point ([`move_sphere_q32`]):
//! nineteen 128-bit products; each input vector's magnitude (|x| | |y| | |z|) is tested once
//! against a power of two, and the products with an inverse mass or inertia once per vector
//! by one bound product; the unit spin vector comes from [`Envelope::unit3`]. Floating point
//! takes the same arithmetic written on [`Scalar::Fast`] and tests only that its results are
//! finite ([`move_sphere_generic`]). Outside the bounds either returns `None`, and the
//! checked arithmetic moves the body and reports any overflow.

use crate::body::{Body, Loads};
use crate::num::{Envelope, FxFast, Scalar, Vec3};

/// One step of single-sphere body `b` under its force sums, or `None` outside the bounds.
#[inline(always)]
pub(super) fn move_sphere<S: Scalar>(
    b: &Body<S>,
    sums: &Loads<S>,
    dt: S,
    g: Vec3<S>,
) -> Option<SphereMove<S>> {
    if !S::Q32_32 {
        return move_sphere_generic(b, sums, dt, g);
    }
    let raw = |x: S| x.to_bits() as i64;
    let raw3 = |v: Vec3<S>| [raw(v.x), raw(v.y), raw(v.z)];
    let back = |x: i64| S::from_bits(x as u64);
    let back3 = |v: [i64; 3]| Vec3::new(back(v[0]), back(v[1]), back(v[2]));
    let Loads {
        force,
        torque,
        roll,
    } = *sums;
    let m = move_sphere_q32(&Q32Sphere {
        force: raw3(force),
        torque: raw3(torque),
        roll: raw(roll),
        velocity: raw3(b.velocity),
        position: raw3(b.position),
        spin: raw3(b.angular_velocity),
        inv_mass: raw(b.inv_mass),
        inv_inertia: raw(b.inv_inertia.x),
        mass: raw(b.mass),
        dt: raw(dt),
        gravity: raw3(g),
    })?;
    Some(SphereMove {
        velocity: back3(m.velocity),
        position: back3(m.position),
        angular_velocity: back3(m.spin),
        force: back3(m.force),
        torque: back3(m.torque),
        roll: back(m.roll),
        l1_displacement: back(m.l1),
    })
}

/// Raw Q32.32 bounds of the raw-integer path. They are tighter than the bounds below for
/// velocities and the time step, so that the new velocity needs no test of its own:
/// loads < 2^30 N and N·mm, …
const LOAD_RAW: u64 = 1 << (32 + LOAD_BITS);
/// … velocities and spins at the start of the step < 2^21 mm/ms and rad/ms, …
const START_VELOCITY_RAW: u64 = 1 << (32 + START_VELOCITY_BITS);
/// … accelerations F/m, T/I and Tr/I < 2^24 mm/ms² and rad/ms², …
const ACCELERATION_RAW: u128 = 1 << (32 + ACCELERATION_BITS);
/// … positions < 2^29 mm, …
const POSITION_RAW: u64 = 1 << (32 + POSITION_BITS);
/// … time step < 2^-2 ms, …
const SHORT_TIMESTEP_RAW: i64 = 1 << (32 + SHORT_TIMESTEP_BITS);
/// … gravity < 2^16 mm/ms², …
const GRAVITY_RAW: u64 = 1 << (32 + GRAVITY_BITS);
/// … mass < 2^12 g.
const MASS_RAW: i64 = 1 << (32 + MASS_BITS);
/// Velocities at the start of a step on the raw-integer path: below 2^21 mm/ms (2·10⁶ m/s).
const START_VELOCITY_BITS: i32 = 21;
/// Time steps on the raw-integer path: below 2^-2 ms (250 µs, far above any stable DEM step).
const SHORT_TIMESTEP_BITS: i32 = -2;
/// Half a unit of the last place of a Q.32 product, for rounding to nearest.
const HALF_ULP: i128 = 1 << 31;

/// A single-sphere body and its loads, raw Q32.32.
struct Q32Sphere {
    force: [i64; 3],
    torque: [i64; 3],
    roll: i64,
    velocity: [i64; 3],
    position: [i64; 3],
    spin: [i64; 3],
    inv_mass: i64,
    inv_inertia: i64,
    mass: i64,
    dt: i64,
    gravity: [i64; 3],
}

/// The moved body, raw Q32.32.
struct Q32Move {
    velocity: [i64; 3],
    position: [i64; 3],
    spin: [i64; 3],
    force: [i64; 3],
    torque: [i64; 3],
    roll: i64,
    l1: i64,
}

/// |x| | |y| | |z|: below 2^k iff every component is, and never below the largest |component|.
#[inline(always)]
fn magnitude(v: [i64; 3]) -> u64 {
    v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs()
}

/// a·b in Q.32, rounded to nearest (ties up), as an i128 (not yet range-checked).
#[inline(always)]
fn mul_q32(a: i64, b: i64) -> i128 {
    (a as i128 * b as i128 + HALF_ULP) >> 32
}

/// Whether every rounded product x·s of a component x with |x| ≤ `magnitude` and a factor
/// s ≥ 0 stays below `bound` (raw): it does when magnitude·s + 2^31 < bound·2^32, since
/// rounding adds at most half a unit. One product tests a whole vector, instead of one test
/// per component after the fact.
#[inline(always)]
fn products_within(magnitude: u64, s: i64, bound: u128) -> bool {
    (magnitude as u128 * s as u128 + HALF_ULP as u128) < bound << 32
}

/// The step of [`move_sphere`] on raw Q32.32 integers. Inside the bounds (all strict):
/// |a| < 2^24 and |g| < 2^16 give |a + g| < 2^25, and dt < 2^-2 keeps the velocity increment
/// within 2^23, so the new velocity stays below 2^21 + 2^23 + 1 < 2^24 without a test of
/// its own; |v·dt| ≤ 2^22, so the new position stays below 2^30 and the L1 displacement
/// below 2^24. The spin increment is within 2^23 likewise, the rolling cap never exceeds
/// ω·ω̂ ≤ |ω| < 2^24, and m·g < 2^28 before the sum with |F| < 2^30.
#[inline(always)]
fn move_sphere_q32(s: &Q32Sphere) -> Option<Q32Move> {
    let (load_force, load_turn) = (magnitude(s.force), magnitude(s.torque) | s.roll as u64);
    let inputs_in = ((load_force | load_turn) < LOAD_RAW)
        & ((magnitude(s.velocity) | magnitude(s.spin)) < START_VELOCITY_RAW)
        & (magnitude(s.position) < POSITION_RAW)
        & (magnitude(s.gravity) < GRAVITY_RAW)
        & (s.dt > 0)
        & (s.dt < SHORT_TIMESTEP_RAW)
        & (s.mass >= 0)
        & (s.mass < MASS_RAW)
        & (s.inv_mass >= 0)
        & (s.inv_inertia >= 0)
        & (s.roll >= 0);
    // `load_turn` bounds the torque components and the rolling torque at once.
    if !(inputs_in
        && products_within(load_force, s.inv_mass, ACCELERATION_RAW)
        && products_within(load_turn, s.inv_inertia, ACCELERATION_RAW))
    {
        return None;
    }
    let scale = |v: [i64; 3], f: i64| v.map(|x| mul_q32(x, f) as i64);
    let acc = scale(s.force, s.inv_mass);
    let spin_acc = scale(s.torque, s.inv_inertia);
    let roll_acc = mul_q32(s.roll, s.inv_inertia) as i64;
    let dt = s.dt;
    let step = |x: i64| mul_q32(x, dt) as i64;
    // A kinematic body (inverse mass zero) keeps its velocity: no contact force, no gravity.
    let velocity = if s.inv_mass != 0 {
        [
            s.velocity[0] + step(acc[0] + s.gravity[0]),
            s.velocity[1] + step(acc[1] + s.gravity[1]),
            s.velocity[2] + step(acc[2] + s.gravity[2]),
        ]
    } else {
        s.velocity
    };
    let dx = velocity.map(step);
    let mut spin = [
        s.spin[0] + step(spin_acc[0]),
        s.spin[1] + step(spin_acc[1]),
        s.spin[2] + step(spin_acc[2]),
    ];
    if s.roll > 0 {
        let w0 = Vec3::new(
            FxFast::from_raw(s.spin[0]),
            FxFast::from_raw(s.spin[1]),
            FxFast::from_raw(s.spin[2]),
        );
        if let Some(hat) = FxFast::unit3(w0) {
            let hat = [hat.x.raw(), hat.y.raw(), hat.z.raw()];
            let along = ((spin[0] as i128 * hat[0] as i128
                + spin[1] as i128 * hat[1] as i128
                + spin[2] as i128 * hat[2] as i128
                + HALF_ULP)
                >> 32) as i64;
            if along > 0 {
                let dec = step(roll_acc).min(along);
                spin = [
                    spin[0] - mul_q32(hat[0], dec) as i64,
                    spin[1] - mul_q32(hat[1], dec) as i64,
                    spin[2] - mul_q32(hat[2], dec) as i64,
                ];
            }
        }
    }
    Some(Q32Move {
        velocity,
        position: [
            s.position[0] + dx[0],
            s.position[1] + dx[1],
            s.position[2] + dx[2],
        ],
        spin,
        force: [
            s.force[0] + mul_q32(s.gravity[0], s.mass) as i64,
            s.force[1] + mul_q32(s.gravity[1], s.mass) as i64,
            s.force[2] + mul_q32(s.gravity[2], s.mass) as i64,
        ],
        torque: s.torque,
        roll: s.roll,
        l1: (dx[0].abs() + dx[1].abs() + dx[2].abs()),
    })
}

/// Magnitudes inside which the raw-integer step cannot overflow, as powers of two: of
/// accelerations (mm/ms², rad/ms²) …
const ACCELERATION_BITS: i32 = 24;
/// … of positions (mm) …
const POSITION_BITS: i32 = 29;
/// … of force and torque sums (N, N·mm) …
const LOAD_BITS: i32 = 30;
/// … of gravity (mm/ms²) …
const GRAVITY_BITS: i32 = 16;
/// … and of the mass (g), for the reported weight.
const MASS_BITS: i32 = 12;

/// The new state of a single-sphere body.
pub(super) struct SphereMove<S> {
    pub velocity: Vec3<S>,
    pub position: Vec3<S>,
    pub angular_velocity: Vec3<S>,
    pub force: Vec3<S>,
    pub torque: Vec3<S>,
    pub roll: S,
    pub l1_displacement: S,
}

/// One step of a single-sphere body (module docs) in floating point ([`Scalar::Fast`] is the
/// scalar itself), or `None` when a result is not finite (then the checked arithmetic moves
/// the body and reports the overflow). Floating point has no range to leave short of
/// infinity, so instead of bounds on every input one test on the results finds an infinite
/// or NaN value: their sum, which is not finite if any of them is not (or if the sum itself
/// overflows, and then the checked path gives the same finite values).
#[inline(always)]
fn move_sphere_generic<S: Scalar>(
    b: &Body<S>,
    sums: &Loads<S>,
    dt: S,
    g: Vec3<S>,
) -> Option<SphereMove<S>> {
    type F<S> = <S as Scalar>::Fast;
    let fast3 = |v: Vec3<S>| v.map(S::to_fast);
    let Loads {
        force,
        torque,
        roll,
    } = *sums;
    let (force, torque, roll) = (fast3(force), fast3(torque), roll.to_fast());
    let (vel, pos, w0) = (
        fast3(b.velocity),
        fast3(b.position),
        fast3(b.angular_velocity),
    );
    let (dt, g) = (dt.to_fast(), fast3(g));
    let (inv_m, inv_i, mass) = (
        b.inv_mass.to_fast(),
        b.inv_inertia.x.to_fast(),
        b.mass.to_fast(),
    );
    let acc = force.scale(inv_m);
    let spin_acc = torque.scale(inv_i);
    // A kinematic body (inverse mass zero) keeps its velocity: no contact force, no gravity.
    let velocity = if inv_m != F::<S>::ZERO {
        vel + (acc + g).scale(dt)
    } else {
        vel
    };
    let dx = velocity.scale(dt);
    let mut w = w0 + spin_acc.scale(dt);
    if roll > F::<S>::ZERO {
        if let Some(hat) = F::<S>::unit3(w0) {
            let along = w.dot(hat);
            if along > F::<S>::ZERO {
                w -= hat.scale((roll * inv_i * dt).min(along));
            }
        }
    }
    let (position, weight) = (pos + dx, g.scale(mass));
    let all = velocity + position + w + force + weight + torque;
    // The sum is infinite or NaN if any of its terms is (or if it overflows itself).
    if !S::from_fast(all.x + all.y + all.z + roll).is_valid() {
        return None;
    }
    let back = |v: Vec3<F<S>>| v.map(S::from_fast);
    Some(SphereMove {
        velocity: back(velocity),
        position: back(position),
        angular_velocity: back(w),
        force: back(force + weight),
        torque: back(torque),
        roll: S::from_fast(roll),
        l1_displacement: S::from_fast(dx.l1_norm()),
    })
}
