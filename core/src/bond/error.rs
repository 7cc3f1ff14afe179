//! [`BondError`]: typed errors of the bond set-up API (sets, storage, formation, single
//! bonds). Nothing is changed when one of these is returned.

use crate::error::SetupError;
use core::fmt;

/// Invalid bond input or full bond storage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BondError {
    /// A generic set-up error (non-finite or unrepresentable number, unknown material).
    Setup(SetupError),
    /// A bond radius ≤ 0.
    NonPositiveBondRadius {
        /// The radius, m.
        radius_m: f64,
    },
    /// A stiffness, critical stress or distance that must be > 0 (or ≥ 0) was not.
    NonPositive {
        /// Which input.
        what: &'static str,
        /// The value given (SI).
        value: f64,
    },
    /// The bond arena is full.
    Capacity {
        /// Its capacity (bonds).
        capacity: u32,
    },
    /// The bond-set table is full ([`super::MAX_BOND_SETS`]) or the formation schedule is full.
    TooMany {
        /// Which table.
        what: &'static str,
        /// Its capacity.
        capacity: u32,
    },
    /// A bond set id that was never added.
    UnknownSet {
        /// The id.
        id: u16,
    },
    /// A sphere id out of range.
    UnknownSphere {
        /// The id.
        id: u32,
    },
    /// Both spheres belong to the same rigid body: a bond there would carry no load.
    SameBody {
        /// The body id.
        body: u32,
    },
    /// The pair is already bonded.
    AlreadyBonded {
        /// Lower sphere id.
        sphere_a: u32,
        /// Higher sphere id.
        sphere_b: u32,
    },
    /// Bond storage was already attached and holds bonds.
    StorageInUse,
}

impl From<SetupError> for BondError {
    fn from(e: SetupError) -> Self {
        BondError::Setup(e)
    }
}

impl fmt::Display for BondError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            BondError::Setup(e) => write!(f, "{e}"),
            BondError::NonPositiveBondRadius { radius_m } => {
                write!(f, "bond radius must be > 0, got {radius_m} m")
            }
            BondError::NonPositive { what, value } => {
                write!(f, "{what} must be > 0, got {value}")
            }
            BondError::Capacity { capacity } => write!(
                f,
                "bond storage full: it holds at most {capacity} bonds; give larger bond storage"
            ),
            BondError::TooMany { what, capacity } => {
                write!(f, "too many {what}: at most {capacity}")
            }
            BondError::UnknownSet { id } => write!(f, "bond set {id} was never added"),
            BondError::UnknownSphere { id } => write!(f, "no sphere with id {id}"),
            BondError::SameBody { body } => write!(
                f,
                "both spheres belong to body {body}; a bond inside one rigid body carries no load"
            ),
            BondError::AlreadyBonded { sphere_a, sphere_b } => {
                write!(f, "spheres {sphere_a} and {sphere_b} are already bonded")
            }
            BondError::StorageInUse => {
                write!(f, "bond storage is already attached and holds bonds")
            }
        }
    }
}

impl core::error::Error for BondError {}
