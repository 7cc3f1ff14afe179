//! The fused base law ([`crate::contact::fused`]: Hertz with damping and the no-attraction
//! clip, Mindlin with damping and the Coulomb limit, CDT rolling magnitudes; seed 000 eqs.
//! (1)–(7)) on [`LANES`] contacts at a time in **narrow lanes** (issue 16): every product
//! is 32 × 32 → 64 bits, so a vector unit does four (AVX2) or eight (AVX-512) of them in one
//! instruction, where the Q32.32 kernel takes a 64 × 64 → 128-bit multiply, a carry and a
//! double shift per product per contact.
//!
//! ## Formats and error budget
//! State stays wide (Q32.32 positions, velocities, history); the kernel narrows what it
//! multiplies. "Q.f" is a raw integer x·2^f below 2^31. The bounds are the kernel's envelope:
//! a contact outside them is not evaluated here (its lane reports `ok = false`) and goes to
//! the checked terms, as today.
//!
//! | quantity | bound | format | resolution |
//! |---|---|---|---|
//! | radii Rᵢ, Rⱼ, R*, clump offsets | < 2^5 mm ([`LENGTH_BITS`]) | Q.25 (levers) | 3e-8 mm |
//! | overlap α (spheres) | < R/2 | block value from the exact-ish (Rᵢ+Rⱼ)² − \|d\|² (Q.43) | 2^-31 α |
//! | unit normal n̂ | 1 | Q.30 | 1e-9 |
//! | centre velocity difference | < 2^5 mm/ms ([`SPEED_BITS`]) | Q.23 | 1.2e-7 m/s |
//! | angular velocities | < 2^6 rad/ms ([`SPIN_BITS`]) | Q.24 | 6e-8 rad/ms |
//! | contact velocity, vn, vt | < 2^8 mm/ms (follows) | Q.23 | 1.2e-7 m/s |
//! | history δt | < 2^3 mm ([`DELTA_BITS`]) | kept Q.32; Q.27 in products | 7e-9 mm per product |
//! | time step | < 2^-3 ms | Q.34 | 6e-11 ms |
//! | a = √(R*α), √(a·m*), E*, G*, damping factors, Fn, St, μ | any | block values (31 bits) | 2^-31 relative |
//! | forces, torques, rolling torques (out) | < 2^13 N ([`FORCE_BITS`]) | Q.32 | 2.3e-10 N |
//!
//! Why the overlap is not simply Rᵢ + Rⱼ − |d|: with |d| good to 31 bits that difference
//! would carry an absolute error of |d|·2^-31 (4e-9 mm on 4 mm spheres, 2e-4 of a steel
//! sphere's overlap under its weight). Instead α = ((Rᵢ+Rⱼ)² − |d|²)/(Rᵢ + Rⱼ + |d|), whose
//! numerator is computed exactly to 2^-43 mm² from the Q32.32 centres by splitting each
//! coordinate in 17 + 21 bits (every partial product fits 64 bits): α is good to about
//! 2^-29 of itself at any size.
//!
//! What the formats cost against the Q32.32 kernel: velocities resolve 1.2e-7 m/s instead of
//! 2.3e-10, so a damping force is off by at most its damping coefficient times 6e-8 mm/ms
//! (1.4e-8 N on a settled pod, whose weight is 1.5e-3 N); every other quantity is good to
//! 2^-29 of itself or better. The test below states the budget contact by contact against
//! the f64 law.
//!
//! ```
//! use arachis_core::contact::lanes::{evaluate, LaneBatch, LANES};
//! // Pod on a steel plate, 0.02 mm overlap, at rest: the Hertz force (4/3)E*·√(Rα)·α.
//! let q = |x: f64| (x * 4294967296.0).round() as i64;
//! let mut b = LaneBatch::default();
//! b.wall = [true; LANES];
//! b.d[2] = [q(1.0); LANES];
//! b.overlap = [q(0.02); LANES];
//! b.r_i = [q(4.0); LANES];
//! b.r_star = [q(4.0); LANES];
//! b.m_star = [q(0.156); LANES];
//! b.kn = [q(13.2); LANES];
//! b.kt = [q(48.0); LANES];
//! b.mu = [q(0.589); LANES];
//! let out = evaluate(&b, q(0.02));
//! let hertz = 13.2 * (4.0f64 * 0.02).sqrt() * 0.02;
//! assert!(out.ok[0]);
//! assert!((out.force[2][0] as f64 / 4294967296.0 - hertz).abs() < 1e-8 * hertz);
//! ```

// Lane code indexes structure-of-arrays fields by the lane number on purpose: one loop per
// operation over every lane is what the compiler turns into one vector instruction.
#![allow(clippy::needless_range_loop)]

mod dispatch;
mod geometry;
mod law;

use crate::contact::fused::FusedPair;
pub use crate::num::lanes::{Lanes, Mask, LANES};
use crate::num::FxFast;
pub use dispatch::{evaluate, evaluate_portable, evaluate_with, Isa};

/// Radii, R*, lever lengths and clump offsets below 2^LENGTH_BITS mm.
pub const LENGTH_BITS: i64 = 5;
/// Centre velocity differences and the spin part of the contact velocity below
/// 2^SPEED_BITS mm/ms.
pub const SPEED_BITS: i64 = 5;
/// Angular velocities below 2^SPIN_BITS rad/ms.
pub const SPIN_BITS: i64 = 6;
/// Tangential history below 2^DELTA_BITS mm, before and after the step's increment.
pub const DELTA_BITS: i64 = 3;
/// Effective mass below 2^MASS_BITS g.
pub const MASS_BITS: i64 = 10;
/// Time step below 2^TIMESTEP_BITS ms.
pub const TIMESTEP_BITS: i64 = -3;
/// Normal and tangential force components below 2^FORCE_BITS N.
pub const FORCE_BITS: i64 = 13;

/// Fraction bits of the wide state (Q32.32): the kernel's inputs and outputs.
const STATE: i64 = 32;

/// [`LANES`] contacts as the kernel reads them, structure of arrays, every quantity in raw
/// Q32.32 (internal units: mm, g, ms, N). Unused lanes may hold anything; their results are
/// ignored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LaneBatch {
    /// Whether the partner is a wall.
    pub wall: Mask,
    /// Sphere partner: centre of j minus centre of i, mm. Wall: unit normal from the sphere
    /// towards the wall.
    pub d: [Lanes; 3],
    /// Wall: overlap α, mm (unused for spheres).
    pub overlap: Lanes,
    /// Rᵢ, mm.
    pub r_i: Lanes,
    /// Rⱼ, mm (unused for walls).
    pub r_j: Lanes,
    /// Effective radius R*, mm (wall: Rᵢ).
    pub r_star: Lanes,
    /// Effective mass m*, g (wall: mᵢ).
    pub m_star: Lanes,
    /// Velocity of j's centre minus i's (wall: the wall's velocity minus i's), mm/ms.
    pub v: [Lanes; 3],
    /// ωᵢ, rad/ms.
    pub spin_i: [Lanes; 3],
    /// ωⱼ, rad/ms (zero for a wall).
    pub spin_j: [Lanes; 3],
    /// Clump sphere i: its centre minus its body's centre of mass, mm (zero for a single
    /// sphere).
    pub offset_i: [Lanes; 3],
    /// The same for j.
    pub offset_j: [Lanes; 3],
    /// Whether sphere i belongs to a clump (its rolling lever runs from the clump's centre
    /// of mass).
    pub clump_i: Mask,
    /// The same for j.
    pub clump_j: Mask,
    /// Tangential history δt, mm.
    pub delta: [Lanes; 3],
    /// (4/3)E*, MPa.
    pub kn: Lanes,
    /// Normal damping factor 2√(5/6)(−β)√(2E*), √MPa.
    pub cn: Lanes,
    /// 8G*, MPa.
    pub kt: Lanes,
    /// Tangential damping factor 2√(5/6)(−β)√(8G*), √MPa.
    pub ct: Lanes,
    /// Sliding friction μs.
    pub mu: Lanes,
    /// CDT rolling friction μr.
    pub mu_r: Lanes,
}

impl LaneBatch {
    /// Put the fused-law constants of pair `p` into lane `lane`.
    pub fn set_pair(&mut self, lane: usize, p: &FusedPair<FxFast>) {
        self.kn[lane] = p.four_thirds_e_star.raw();
        self.cn[lane] = p.normal_damping.raw();
        self.kt[lane] = p.eight_g_star.raw();
        self.ct[lane] = p.tangential_damping.raw();
        self.mu[lane] = p.friction.raw();
        self.mu_r[lane] = p.rolling_friction.raw();
    }
}

/// The loads of [`LANES`] contacts (raw Q32.32, as [`crate::contact::fused::FusedLoad`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LaneLoads {
    /// Whether the contact lay inside the envelope; the other fields hold garbage where not.
    pub ok: Mask,
    /// Force on j (i receives the opposite), N.
    pub force: [Lanes; 3],
    /// Torque on i about its centre of mass is −`torque_i`, N·mm.
    pub torque_i: [Lanes; 3],
    /// Torque on j about its centre of mass, N·mm.
    pub torque_j: [Lanes; 3],
    /// Rolling-resistance torque magnitude on i, N·mm.
    pub roll_i: Lanes,
    /// Rolling-resistance torque magnitude on j, N·mm.
    pub roll_j: Lanes,
    /// The new tangential history, mm.
    pub delta: [Lanes; 3],
}

#[cfg(test)]
mod tests;
