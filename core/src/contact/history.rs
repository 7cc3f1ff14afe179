//! Contact history: the accumulated tangential displacement δt of each live contact, and
//! the state of the optional terms that need one (α_max, the rolling angle θr, LIGGGHTS'
//! rolling spring torque, the JKR neck).
//!
//! History is stored beside the neighbour-list entries ([`crate::step::neighbour_list`]): a
//! [`NeighbourEntry`] holds the partner key and δt, which every Hertz–Mindlin contact needs;
//! the state of the optional effects lives in a parallel [`EffectHistory`] arena that only
//! worlds with such effects provide, so the common contact loop reads 32 bytes per entry.
//! The sphere with the lower id owns a sphere–sphere contact; a sphere owns its wall contacts.
//! An entry is keyed by the partner: the other sphere id, or [`WALL_PARTNER_FLAG`] | wall id
//! << 4 | face. Entries are visited in a fixed order, so the history (and its digest) is
//! reproducible bit for bit.
//!
//! The contact terms see both parts joined as one [`ContactState`].
//!
//! ```
//! use arachis_core::contact::{ContactState, EffectHistory, NeighbourEntry};
//! use arachis_core::num::Fx;
//! let entry = NeighbourEntry::<Fx>::default();
//! let state = ContactState::join(&entry, None::<&EffectHistory<Fx>>);
//! assert_eq!(state, ContactState::default());
//! ```

use crate::num::{Scalar, Vec3};

/// Partner-key flag marking a wall contact.
pub const WALL_PARTNER_FLAG: u32 = 0x8000_0000;

/// Per-contact state carried between steps, as the contact terms see it.
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
    /// Spring torque M of LIGGGHTS' `epsd2` rolling resistance, N·mm (only kept by
    /// [`super::RollingEpsd2Liggghts`]; zero otherwise).
    pub roll_torque: Vec3<S>,
    /// `true` while a JKR contact ([`super::CohesionJkr`]) is attached: it then holds down to
    /// the negative overlap of the JKR separation. `false` otherwise.
    pub jkr_attached: bool,
    /// √a of the JKR contact radius a that the fused law found at the contact's last step,
    /// √mm: where its Newton loop starts next ([`super::fused::jkr`]); 0 when none.
    pub jkr_root: S,
}

/// One neighbour-list entry: partner key and tangential history.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NeighbourEntry<S> {
    /// Partner key (sphere id, or wall key with [`WALL_PARTNER_FLAG`]), with the list's live
    /// flag while the pair touches.
    pub partner: u32,
    /// Accumulated tangential displacement δt, mm (zero while the pair does not touch).
    pub delta: Vec3<S>,
}

/// History of the optional effects of one neighbour-list entry (all zero while unused).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EffectHistory<S> {
    /// α_max, mm ([`ContactState::max_overlap`]).
    pub max_overlap: S,
    /// θr, rad ([`ContactState::roll_angle`]).
    pub roll_angle: Vec3<S>,
    /// M, N·mm ([`ContactState::roll_torque`]).
    pub roll_torque: Vec3<S>,
    /// The JKR neck flag ([`ContactState::jkr_attached`]).
    pub jkr_attached: bool,
    /// √a of the last JKR contact radius, √mm ([`ContactState::jkr_root`]).
    pub jkr_root: S,
}

impl<S: Scalar> ContactState<S> {
    /// The state of an entry and its effect history (`None`: no effects, all zero).
    #[inline(always)]
    pub fn join(entry: &NeighbourEntry<S>, effects: Option<&EffectHistory<S>>) -> Self {
        let e = effects.copied().unwrap_or_default();
        ContactState {
            delta: entry.delta,
            max_overlap: e.max_overlap,
            roll_angle: e.roll_angle,
            roll_torque: e.roll_torque,
            jkr_attached: e.jkr_attached,
            jkr_root: e.jkr_root,
        }
    }

    /// The optional-effect part of the state.
    #[inline(always)]
    pub fn effects(&self) -> EffectHistory<S> {
        EffectHistory {
            max_overlap: self.max_overlap,
            roll_angle: self.roll_angle,
            roll_torque: self.roll_torque,
            jkr_attached: self.jkr_attached,
            jkr_root: self.jkr_root,
        }
    }
}

/// A live contact as reported by [`crate::world::World::contact_slots`]: partner key and
/// state.
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
