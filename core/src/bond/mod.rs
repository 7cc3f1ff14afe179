//! Bonded-particle model (BPM): elastic, breakable bonds between spheres, as in EDEM's
//! "Hertz–Mindlin with bonding" (seed 001 §2.4.1, DESIGN §2), which follows the parallel bond
//! of Potyondy & Cundall (2004, Int. J. Rock Mech. Min. Sci. 41:1329, eqs. (8)–(12)).
//!
//! A bond of radius Rb joins two spheres of different bodies (free spheres or clump spheres;
//! across clumps is the main use: a plant is many bodies bonded together). Its cross-section
//! has area A = πRb² and polar moment J = πRb⁴/2 (area moment I = J/2). Each bond carries a
//! normal force Fn, a tangential force Ft, a twisting moment Mt (about the bond axis n̂) and a
//! bending moment Mb (about an axis in the tangent plane), built up incrementally from the
//! relative motion at the bond centre (EDEM manual; Potyondy & Cundall eq. (10)):
//!
//! ```text
//! ΔFn = −vn·Kn·A·dt        ΔFt = −vt·Kt·A·dt
//! ΔMt = −ωn·Kt·J·dt        ΔMb = −ωt·Kn·(J/2)·dt
//! ```
//!
//! with Kn, Kt the normal and tangential stiffness per unit area (N/m³), vn, vt the normal and
//! tangential relative velocity of the bond centre, and ωn, ωt the normal and tangential parts
//! of the relative angular velocity. Fn > 0 is compression. See [`kinematics`] for how the
//! increments are accumulated (as displacements, with the stiffness applied once, which is the
//! same sum with far less rounding).
//!
//! A bond breaks ([`breakage`]) when
//!
//! ```text
//! σmax = −Fn/A + 2|Mb|·Rb/J ≥ σc     or     τmax = |Ft|/A + |Mt|·Rb/J ≥ τc
//! ```
//!
//! **Reading of the seed.** Seed 001 §2.4.1 writes σmax = Fn/A + 2MtRb/J and
//! τmax = Ft/A + 2MnRb/J, with "Mn and Mt the normal and tangential moments". In EDEM's naming
//! the *tangential* moment is the bending moment (about an axis in the tangent plane) and the
//! *normal* moment is the twisting moment (about n̂). Beam theory for a circular section gives
//! the bending stress M·Rb/I = 2M·Rb/J and the torsional shear stress T·Rb/J, so the σ line
//! agrees with beam theory (and with DESIGN §2), while the factor 2 in the seed's τ line does
//! not: we follow beam theory, EDEM and Potyondy & Cundall eq. (12) (τ = |Ft|/A + |Mt|Rb/J) and
//! flag the seed's factor as a likely typesetting slip. The normal force enters with its sign
//! (tension raises σmax, compression lowers it), as in Potyondy & Cundall.
//!
//! A broken bond is removed and logged ([`log`]); from the next step the pair interacts by
//! ordinary contact. While bonded, a pair gets **no** ordinary contact force (the narrow phase
//! skips it). Bonds are formed ([`formation`]) at a chosen time between every sphere pair of
//! chosen materials whose surface gap is below a chosen distance (seed 001 §2.4.3: "bond
//! generation time 0.008 s"), or one by one. Storage is caller-provided ([`arena`]).
//!
//! Everything in the step is integer arithmetic in [`crate::num::Fx`]; set-up converts SI
//! inputs once (Kn N/m³ → N/mm³, σc Pa → MPa, Rb m → mm).

pub mod arena;
pub mod breakage;
pub mod error;
pub mod formation;
pub mod kinematics;
pub mod log;
pub mod params;

pub use arena::{Bond, BondStorage, Bonds};
pub use breakage::{BreakCriterion, Stresses};
pub use error::BondError;
pub use formation::FormationRule;
pub use log::BondBreak;
pub use params::{BondParams, BondSetId, BondSetSpec, MAX_BOND_SETS};
