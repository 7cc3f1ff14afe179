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

use super::arena::Bond;
use super::params::BondParams;
use crate::body::{Body, Sphere};
use crate::num::{Scalar, Vec3};

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
    let c = sa.position + n.scale((dist + sa.radius - sb.radius) * S::HALF);
    let arm_a = c - ba.position;
    let arm_b = c - bb.position;
    let v = (bb.velocity + bb.angular_velocity.cross(arm_b))
        - (ba.velocity + ba.angular_velocity.cross(arm_a));
    let vn = v.dot(n);
    let vt = v - n.scale(vn);
    let w = bb.angular_velocity - ba.angular_velocity;
    let wn = w.dot(n);
    let wt = w - n.scale(wn);

    let dt_ = bond.tangential_disp;
    let th = bond.bend;
    bond.normal_disp += vn * dt;
    bond.tangential_disp = dt_ - n.scale(dt_.dot(n)) + vt.scale(dt);
    bond.twist += wn * dt;
    bond.bend = th - n.scale(th.dot(n)) + wt.scale(dt);
    bond.normal = n;

    bond.normal_force = -(p.kn_area * bond.normal_disp);
    bond.tangential_force = -bond.tangential_disp.scale(p.kt_area);
    bond.twisting_moment = -(p.kt_polar * bond.twist);
    bond.bending_moment = -bond.bend.scale(p.kn_inertia);

    let force = n.scale(bond.normal_force) + bond.tangential_force;
    let moment = n.scale(bond.twisting_moment) + bond.bending_moment;
    let torque_b = arm_b.cross(force) + moment;
    let torque_a = -(arm_a.cross(force) + moment);
    let ok = force.is_valid()
        & torque_a.is_valid()
        & torque_b.is_valid()
        & bond.tangential_disp.is_valid()
        & bond.bend.is_valid()
        & bond.normal_disp.is_valid()
        & bond.twist.is_valid();
    ok.then_some(BondLoad {
        force,
        torque_b,
        torque_a,
    })
}
