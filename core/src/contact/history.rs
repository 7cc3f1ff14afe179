//! Contact history: the accumulated tangential displacement δt of each live contact, and
//! the state of the optional terms that need one (α_max, the rolling angle θr, the JKR neck).
//!
//! Storage is a fixed arena of [`ContactSlot`]s, a fixed number per sphere, double-buffered
//! (last step's slots are read, this step's are written). The sphere with the lower id owns a
//! sphere–sphere contact; a sphere owns its wall contacts. A slot is keyed by the partner: the
//! other sphere id, or [`WALL_PARTNER_FLAG`] | wall id << 4 | face. Slots are written in the
//! deterministic order the pipeline visits contacts, so the history (and its digest) is
//! reproducible bit for bit.

use crate::num::{Scalar, Vec3};

/// Partner-key flag marking a wall contact.
pub const WALL_PARTNER_FLAG: u32 = 0x8000_0000;

/// Per-contact state carried between steps.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactState<S> {
    /// Accumulated tangential displacement δt of j relative to i, mm (seed 000 eq. (5)).
    pub delta: Vec3<S>,
    /// Largest overlap α_max of this contact so far, mm (only kept by the hysteretic normal
    /// term; 0 otherwise).
    pub max_overlap: S,
    /// Accumulated relative rolling rotation θr of i relative to j, rad, in the tangent plane
    /// (only kept by the EPSD rolling term, [`super::RollingEpsd`]; zero otherwise).
    pub roll_angle: Vec3<S>,
    /// `true` while a JKR contact ([`super::CohesionJkr`]) is attached: it then holds down to
    /// the negative overlap of the JKR separation. `false` otherwise.
    pub jkr_attached: bool,
}

/// One history slot: partner key and state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactSlot<S> {
    /// Partner key (sphere id, or wall key with [`WALL_PARTNER_FLAG`]).
    pub partner: u32,
    /// The contact state.
    pub state: ContactState<S>,
}

/// Key for a wall contact.
#[inline(always)]
pub fn wall_key(wall: u32, face: u32) -> u32 {
    WALL_PARTNER_FLAG | (wall << 4) | face
}

/// Find the state for `partner` in a slot list (linear scan; lists are short), or zero.
#[inline(always)]
pub fn lookup<S: Scalar>(slots: &[ContactSlot<S>], partner: u32) -> ContactState<S> {
    for s in slots {
        if s.partner == partner {
            return s.state;
        }
    }
    ContactState::default()
}
