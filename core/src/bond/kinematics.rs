//! Bond kinematics and loads: one update per bond per step.
//!
//! Geometry, as in the narrow phase: n̂ = (pb − pa)/|pb − pa|, bond centre
//! c = pa + n̂·(d + Ra − Rb)/2 (the mid-point of the gap or overlap between the surfaces), lever
//! arms from each body's centre of mass to c. Relative motion of b with respect to a:
//! v = (vB + ωB × rB) − (vA + ωA × rA), vn = v·n̂, vt = v − vn·n̂; ω = ωB − ωA, ωn = ω·n̂,
//! ωt = ω − ωn·n̂.
//!
//! Accumulation. The EDEM increments ΔFn = −vn·Kn·A·dt etc. (see [`super`]) with constant
//! stiffness sum to Fn = −Kn·A·Σvn·dt, so we accumulate the displacements δn = Σvn·dt,
//! δt = Σvt·dt, θn = Σωn·dt, θb = Σωt·dt and apply the stiffness once per step:
//!
//! ```text
//! Fn = −Kn·A·δn    Ft = −Kt·A·δt    Mt = −Kt·J·θn    Mb = −Kn·(J/2)·θb
//! ```
//!
//! The result is the same sum, but in Q32.32 the per-step rounding falls on vn·dt (typically
//! 1e4–1e5 raw units) instead of on the force increment (often only tens of raw units with
//! seed 001's soft bonds, Kn·A ≈ 2e-3 N/mm), which would bias the force by whole percents.
//! The tangential vectors δt and θb are first projected onto the current tangent plane each
//! step (x ← x − (x·n̂)n̂, as the contact history does), so they follow the bond as it turns.
//!
//! Loads on b: force F = Fn·n̂ + Ft at c, moment M = Mt·n̂ + Mb; a gets −F and −M.
//!
//! **Two arithmetics, one result.** In Q32.32 every checked operation tests its operands for
//! the overflow poison and its result for the range, and a field spends a quarter of its step
//! here. So after the axis (which stays checked: its root is the exact one) the update first
//! tries [`Scalar::Fast`], the same bits without the tests, inside bounds that leave no
//! operation a way out of the range ([`unchecked`], derivation below); a bond outside them
//! takes the checked arithmetic, which reports any overflow. Both run the same code
//! ([`advance`]), so they give the same bits wherever both are defined.
//!
//! ```
//! use arachis_core::bond::kinematics::update;
//! use arachis_core::bond::{Bond, BondSetSpec};
//! use arachis_core::body::{Body, Sphere};
//! use arachis_core::num::{Fx, Scalar, Vec3};
//! // Two spheres 2 mm apart along x, b moving away at 1 mm/ms: after one step of 0.001 ms the
//! // bond is stretched by 0.001 mm and pulls b back with Kn·A·0.001 mm.
//! let p = BondSetSpec { tag: 0, normal_stiffness_n_m3: 1e9, tangential_stiffness_n_m3: 1e9,
//!     normal_strength_pa: 1e6, tangential_strength_pa: 1e6, radius_m: 1e-3 }
//!     .validate::<Fx>().unwrap();
//! let fx = |x: f64| Fx::from_f64(x);
//! let sphere = |x: f64| Sphere::<Fx> { position: Vec3::new(fx(x), Fx::ZERO, Fx::ZERO),
//!     radius: Fx::ONE, ..Sphere::default() };
//! let (sa, sb) = (sphere(0.0), sphere(2.0));
//! let ba = Body::<Fx> { position: sa.position, ..Body::default() };
//! let bb = Body::<Fx> { position: sb.position, velocity: Vec3::new(Fx::ONE, Fx::ZERO, Fx::ZERO),
//!     ..Body::default() };
//! let mut bond = Bond::<Fx>::default();
//! let load = update(&mut bond, &p, &sa, &sb, &ba, &bb, fx(0.001)).unwrap();
//! let want = -p.kn_area.to_f64() * 0.001;
//! assert!((load.force.x.to_f64() - want).abs() < 1e-9);
//! ```

use super::arena::Bond;
use super::params::BondParams;
use crate::body::{Body, Sphere};
use crate::num::{Envelope, Scalar, Vec3};

/// What one bond exerts this step (on end b; end a gets the opposite).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BondLoad<S> {
    /// Force on b, N.
    pub force: Vec3<S>,
    /// Torque on b's body about its centre of mass (lever × force + bond moment), N·mm.
    pub torque_b: Vec3<S>,
    /// Torque on a's body about its centre of mass, N·mm.
    pub torque_a: Vec3<S>,
}

impl<S: Scalar> BondLoad<S> {
    /// The same loads through `f` (e.g. back from [`Scalar::Fast`], same bits).
    #[inline(always)]
    fn map<T: Scalar>(&self, f: impl Fn(S) -> T + Copy) -> BondLoad<T> {
        BondLoad {
            force: self.force.map(f),
            torque_b: self.torque_b.map(f),
            torque_a: self.torque_a.map(f),
        }
    }
}

/// Advance `bond` by one step of length `dt` (ms) from the current motion of its two ends,
/// update its stored loads, and return what it exerts. `None` on fixed-point overflow.
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn update<S: Scalar>(
    bond: &mut Bond<S>,
    p: &BondParams<S>,
    sa: &Sphere<S>,
    sb: &Sphere<S>,
    ba: &Body<S>,
    bb: &Body<S>,
    dt: S,
) -> Option<BondLoad<S>> {
    let d = sb.position - sa.position;
    // Unit axis; coincident centres (never produced by formation) keep the last axis.
    let (n, dist) = match d.normalize_with_len() {
        Some(x) => x,
        None => (bond.normal, S::ZERO),
    };
    let ends = Ends {
        centre_a: sa.position,
        radius_a: sa.radius,
        radius_b: sb.radius,
        body_a: ba.position,
        body_b: bb.position,
        velocity_a: ba.velocity,
        velocity_b: bb.velocity,
        spin_a: ba.angular_velocity,
        spin_b: bb.angular_velocity,
    };
    let k = Stiffness::of(p);
    if let Some(load) = unchecked(bond, &k, &ends, n, dist, dt) {
        return Some(load);
    }
    let load = advance(bond, &k, &ends, n, dist, dt, |_| true)?;
    valid(bond, &load).then_some(load)
}

/// Whether the checked arithmetic left no overflow poison in the loads or the state.
#[inline(always)]
fn valid<S: Scalar>(bond: &Bond<S>, load: &BondLoad<S>) -> bool {
    load.force.is_valid()
        & load.torque_a.is_valid()
        & load.torque_b.is_valid()
        & bond.tangential_disp.is_valid()
        & bond.bend.is_valid()
        & bond.normal_disp.is_valid()
        & bond.twist.is_valid()
}

/// The motion of a bond's two ends that one update reads (mm, mm/ms, rad/ms).
#[derive(Clone, Copy)]
struct Ends<S> {
    centre_a: Vec3<S>,
    radius_a: S,
    radius_b: S,
    body_a: Vec3<S>,
    body_b: Vec3<S>,
    velocity_a: Vec3<S>,
    velocity_b: Vec3<S>,
    spin_a: Vec3<S>,
    spin_b: Vec3<S>,
}

impl<S: Scalar> Ends<S> {
    /// The same motion through `f` (to [`Scalar::Fast`], same bits).
    #[inline(always)]
    fn map<T: Scalar>(&self, f: impl Fn(S) -> T + Copy) -> Ends<T> {
        Ends {
            centre_a: self.centre_a.map(f),
            radius_a: f(self.radius_a),
            radius_b: f(self.radius_b),
            body_a: self.body_a.map(f),
            body_b: self.body_b.map(f),
            velocity_a: self.velocity_a.map(f),
            velocity_b: self.velocity_b.map(f),
            spin_a: self.spin_a.map(f),
            spin_b: self.spin_b.map(f),
        }
    }
}

/// The four stiffnesses of a bond set: Kn·A, Kt·A (N/mm), Kt·J, Kn·J/2 (N·mm per rad).
#[derive(Clone, Copy)]
struct Stiffness<S> {
    kn_area: S,
    kt_area: S,
    kt_polar: S,
    kn_inertia: S,
}

impl<S: Scalar> Stiffness<S> {
    #[inline(always)]
    fn of(p: &BondParams<S>) -> Self {
        Stiffness {
            kn_area: p.kn_area,
            kt_area: p.kt_area,
            kt_polar: p.kt_polar,
            kn_inertia: p.kn_inertia,
        }
    }

    /// The same stiffnesses through `f` (to [`Scalar::Fast`], same bits).
    #[inline(always)]
    fn map<T: Scalar>(&self, f: impl Fn(S) -> T) -> Stiffness<T> {
        Stiffness {
            kn_area: f(self.kn_area),
            kt_area: f(self.kt_area),
            kt_polar: f(self.kt_polar),
            kn_inertia: f(self.kn_inertia),
        }
    }
}

/// Bounds of the unchecked update, powers of two: positions (mm) …
const POSITION_BITS: i32 = 29;
/// … the centre distance and the radii (mm), and sphere a's centre from either body's
/// centre of mass (mm), so that each lever to the bond centre is below 2^10 mm …
const SIZE_BITS: i32 = 8;
/// … body velocities (mm/ms) …
const VELOCITY_BITS: i32 = 20;
/// … body spins (rad/ms) …
const SPIN_BITS: i32 = 10;
/// … the time step (ms) …
const TIMESTEP_BITS: i32 = 0;
/// … the accumulated displacements and rotations before the step (mm, rad) …
const DISPLACEMENT_BITS: i32 = 20;
/// … and each stiffness times its displacement after the step (N, N·mm).
const LOAD_BITS: i32 = 18;

/// The update in [`Scalar::Fast`] arithmetic, or `None` (and `bond` untouched) outside the
/// bounds above. Inside them nothing leaves the range 2^31: each lever is below
/// 2^9 + 1.5·2^8 < 2^10, so ω × lever < 2^21, a side's velocity < 2^22, v < 2^23, vn < 2^24.6
/// and vt < 2^25.2; ω < 2^11, ωn < 2^12.6, ωt < 2^13.2; with dt < 1 each displacement stays
/// below 2^20 + 2^25.4. The four loads are tested below 2^18 before use, so F and M < 2^19,
/// each lever × F < 2^30 and each torque < 2^30 + 2^19.
#[inline(always)]
fn unchecked<S: Scalar>(
    bond: &mut Bond<S>,
    k: &Stiffness<S>,
    e: &Ends<S>,
    n: Vec3<S>,
    dist: S,
    dt: S,
) -> Option<BondLoad<S>> {
    type F<S> = <S as Scalar>::Fast;
    let f = S::to_fast;
    let within3 = |v: Vec3<F<S>>, bits| F::<S>::magnitude3(v).within(bits);
    let e = e.map(f);
    let mut fast = bond.map(f);
    let positions_in = within3(e.centre_a, POSITION_BITS)
        & within3(e.body_a, POSITION_BITS)
        & within3(e.body_b, POSITION_BITS);
    if !positions_in {
        return None;
    }
    let inputs_in = within3(e.centre_a - e.body_a, SIZE_BITS)
        & within3(e.centre_a - e.body_b, SIZE_BITS)
        & f(dist).within(SIZE_BITS)
        & e.radius_a.within(SIZE_BITS)
        & e.radius_b.within(SIZE_BITS)
        & within3(e.velocity_a, VELOCITY_BITS)
        & within3(e.velocity_b, VELOCITY_BITS)
        & within3(e.spin_a, SPIN_BITS)
        & within3(e.spin_b, SPIN_BITS)
        & f(dt).within(TIMESTEP_BITS)
        & fast.normal_disp.within(DISPLACEMENT_BITS)
        & within3(fast.tangential_disp, DISPLACEMENT_BITS)
        & fast.twist.within(DISPLACEMENT_BITS)
        & within3(fast.bend, DISPLACEMENT_BITS);
    if !inputs_in {
        return None;
    }
    let k = k.map(f);
    let loads_in = |b: &Bond<F<S>>| {
        let m3 = F::<S>::magnitude3;
        let (_, a) = k.kn_area.mul_within(b.normal_disp.abs(), LOAD_BITS);
        let (_, t) = k.kt_area.mul_within(m3(b.tangential_disp), LOAD_BITS);
        let (_, w) = k.kt_polar.mul_within(b.twist.abs(), LOAD_BITS);
        let (_, r) = k.kn_inertia.mul_within(m3(b.bend), LOAD_BITS);
        a & t & w & r
    };
    let load = advance(&mut fast, &k, &e, n.map(f), f(dist), f(dt), loads_in)?;
    *bond = fast.map(S::from_fast);
    Some(load.map(S::from_fast))
}

/// The update itself, in any arithmetic: accumulate the relative motion, then (if
/// `loads_in` accepts the accumulated state) the loads. `None` only when `loads_in` refuses,
/// and then `bond` is untouched.
#[inline(always)]
fn advance<T: Scalar>(
    bond: &mut Bond<T>,
    k: &Stiffness<T>,
    e: &Ends<T>,
    n: Vec3<T>,
    dist: T,
    dt: T,
    loads_in: impl Fn(&Bond<T>) -> bool,
) -> Option<BondLoad<T>> {
    let c = e.centre_a + n.scale((dist + e.radius_a - e.radius_b) * T::HALF);
    let arm_a = c - e.body_a;
    let arm_b = c - e.body_b;
    let v = (e.velocity_b + e.spin_b.cross(arm_b)) - (e.velocity_a + e.spin_a.cross(arm_a));
    let vn = v.dot(n);
    let vt = v - n.scale(vn);
    let w = e.spin_b - e.spin_a;
    let wn = w.dot(n);
    let wt = w - n.scale(wn);

    let mut b = *bond;
    let (dt_, th) = (b.tangential_disp, b.bend);
    b.normal_disp += vn * dt;
    b.tangential_disp = dt_ - n.scale(dt_.dot(n)) + vt.scale(dt);
    b.twist += wn * dt;
    b.bend = th - n.scale(th.dot(n)) + wt.scale(dt);
    b.normal = n;
    if !loads_in(&b) {
        return None;
    }

    b.normal_force = -(k.kn_area * b.normal_disp);
    b.tangential_force = -b.tangential_disp.scale(k.kt_area);
    b.twisting_moment = -(k.kt_polar * b.twist);
    b.bending_moment = -b.bend.scale(k.kn_inertia);
    *bond = b;

    let force = n.scale(b.normal_force) + b.tangential_force;
    let moment = n.scale(b.twisting_moment) + b.bending_moment;
    Some(BondLoad {
        force,
        torque_b: arm_b.cross(force) + moment,
        torque_a: -(arm_a.cross(force) + moment),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::fused::random_contacts::Stream;
    use crate::num::Fx;

    /// A random bond between two spheres and the motion of their bodies, with every magnitude
    /// log-uniform over a range that straddles the bounds of [`unchecked`] (so that some
    /// bonds take each path), in Q32.32.
    fn random_bond(s: &mut Stream) -> (Bond<Fx>, Stiffness<Fx>, Ends<Fx>, Vec3<Fx>, Fx, Fx) {
        let fx = Fx::from_f64;
        let v3 = |s: &mut Stream, lo, hi| s.vec_log(lo, hi).map(fx);
        let centre_a = v3(s, 1.0, 2e3);
        let d = v3(s, 0.1, 1e5);
        let (n, dist) = d.normalize_with_len().expect("nonzero axis");
        let bond = Bond {
            normal_disp: fx(s.range(-1.0, 1.0) * s.log_range(1e-9, 4e6)),
            tangential_disp: v3(s, 1e-9, 4e6),
            twist: fx(s.range(-1.0, 1.0) * s.log_range(1e-9, 4e6)),
            bend: v3(s, 1e-9, 4e6),
            ..Bond::default()
        };
        let k = Stiffness {
            kn_area: fx(s.log_range(1e-4, 1e5)),
            kt_area: fx(s.log_range(1e-4, 1e5)),
            kt_polar: fx(s.log_range(1e-4, 1e5)),
            kn_inertia: fx(s.log_range(1e-4, 1e5)),
        };
        let ends = Ends {
            centre_a,
            radius_a: fx(s.log_range(0.1, 400.0)),
            radius_b: fx(s.log_range(0.1, 400.0)),
            body_a: centre_a - v3(s, 1e-3, 1e5),
            body_b: centre_a + d - v3(s, 1e-3, 1e5),
            velocity_a: v3(s, 1e-6, 4e6),
            velocity_b: v3(s, 1e-6, 4e6),
            spin_a: v3(s, 1e-6, 4e3),
            spin_b: v3(s, 1e-6, 4e3),
        };
        (bond, k, ends, n, dist, fx(s.log_range(1e-5, 2.0)))
    }

    /// Wherever the unchecked update answers, it gives the checked update's bits (bond and
    /// loads); and it answers for enough bonds (about one in ten here, where the ranges reach
    /// far beyond its bounds) that the comparison means something.
    #[test]
    fn the_unchecked_update_gives_the_checked_bits() {
        let mut s = Stream(0x9E37_79B9_7F4A_7C15);
        let (mut fast_paths, mut both_valid) = (0, 0);
        for case in 0..200_000 {
            let (bond, k, ends, n, dist, dt) = random_bond(&mut s);
            let mut checked = bond;
            let want = advance(&mut checked, &k, &ends, n, dist, dt, |_| true).expect("no gate");
            let valid = valid(&checked, &want);
            both_valid += valid as u32;
            let mut fast = bond;
            match unchecked(&mut fast, &k, &ends, n, dist, dt) {
                Some(got) => {
                    fast_paths += 1;
                    assert!(valid, "case {case}: the fast path hid an overflow");
                    assert_eq!(got, want, "case {case}: loads differ");
                    assert_eq!(fast, checked, "case {case}: bond state differs");
                }
                None => assert_eq!(fast, bond, "case {case}: a refused bond was changed"),
            }
        }
        assert!(
            fast_paths > 10_000 && fast_paths < both_valid,
            "{fast_paths} fast of {both_valid} valid: both paths must be exercised"
        );
    }

    /// A bond whose load leaves the Q32.32 range is reported (`None`), not wrapped: the
    /// unchecked path refuses it and the checked path finds the overflow.
    #[test]
    fn an_overflowing_bond_is_reported() {
        let fx = Fx::from_f64;
        let spheres = |x: f64| Sphere::<Fx> {
            position: Vec3::new(fx(x), Fx::ZERO, Fx::ZERO),
            radius: Fx::ONE,
            ..Sphere::default()
        };
        let (sa, sb) = (spheres(0.0), spheres(2.0));
        let ba = Body::<Fx> {
            position: sa.position,
            ..Body::default()
        };
        let bb = Body::<Fx> {
            position: sb.position,
            ..Body::default()
        };
        let p = crate::bond::BondSetSpec {
            tag: 0,
            normal_stiffness_n_m3: 1e9,
            tangential_stiffness_n_m3: 1e9,
            normal_strength_pa: 1e6,
            tangential_strength_pa: 1e6,
            radius_m: 1e-3,
        }
        .validate::<Fx>()
        .unwrap();
        // Kn·A = π N/mm; a stretch of 1e9 mm would pull with 3e9 N, beyond 2^31.
        let mut bond = Bond::<Fx> {
            normal_disp: fx(1e9),
            ..Bond::default()
        };
        assert_eq!(update(&mut bond, &p, &sa, &sb, &ba, &bb, fx(0.001)), None);
        // A stretch of 1e6 mm (3e6 N) is beyond the unchecked bounds but inside the range:
        // the checked path answers, with Kn·A·δn.
        let mut bond = Bond::<Fx> {
            normal_disp: fx(1e6),
            ..Bond::default()
        };
        let load = update(&mut bond, &p, &sa, &sb, &ba, &bb, fx(0.001)).unwrap();
        let want = -p.kn_area.to_f64() * 1e6;
        assert!((load.force.x.to_f64() - want).abs() < 1e-6 * want.abs());
    }
}
