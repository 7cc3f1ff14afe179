//! Typed errors: [`SetupError`] for invalid input at set-up, [`StepError`] for failures while
//! stepping (overflow, capacity, time step). Every variant has a `Display` message that says
//! what was wrong and, where useful, what to do.

use core::fmt;

/// What kind of fixed-capacity storage ran out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CapacityKind {
    /// The body arena.
    Bodies,
    /// The sphere arena.
    Spheres,
    /// The material table (at most [`crate::material::MAX_MATERIALS`]).
    Materials,
    /// The wall list (at most [`crate::wall::MAX_WALLS`]).
    Walls,
    /// Spheres in one clump (at most [`crate::body::clump::MAX_CLUMP_SPHERES`]).
    ClumpSpheres,
    /// The neighbour-list arena (contact history).
    ContactSlots,
    /// The history arena of the optional effects (empty, or as long as the neighbour list;
    /// see [`crate::body::StorageLengths::with_effects`]).
    EffectHistory,
    /// The index scratch array (must be ≥ 4 × sphere capacity + 2).
    SphereIndex,
    /// The grid cell array (must be ≥ 2).
    Cells,
}

/// Invalid input at set-up. Nothing is changed when one of these is returned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SetupError {
    /// A number was NaN or infinite.
    NonFinite {
        /// Which input.
        what: &'static str,
    },
    /// A value does not fit the fixed-point range (|x| < 2.1e9 in internal units) or loses all
    /// precision (non-zero but below the 2.3e-10 resolution).
    NotRepresentable {
        /// Which input.
        what: &'static str,
        /// The value in internal units.
        value: f64,
    },
    /// A sphere radius ≤ 0.
    NonPositiveRadius {
        /// The radius in m.
        radius_m: f64,
    },
    /// Restitution coefficient outside (0, 1].
    RestitutionOutOfRange {
        /// The value given.
        e: f64,
    },
    /// A friction coefficient < 0.
    NegativeFriction {
        /// Which coefficient ("sliding" or "rolling").
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// Poisson ratio outside (−1, 0.5).
    PoissonOutOfRange {
        /// The value given.
        nu: f64,
    },
    /// Young's modulus ≤ 0.
    NonPositiveYoungsModulus {
        /// The value in Pa.
        youngs_modulus_pa: f64,
    },
    /// Density ≤ 0.
    NonPositiveDensity {
        /// The value in kg/m³.
        density_kg_m3: f64,
    },
    /// A clump whose mass (or a principal moment of inertia) is zero or negative.
    ZeroMassClump,
    /// A clump with no spheres.
    EmptyClump,
    /// A fixed-capacity store is full (or too small to be usable).
    Capacity {
        /// Which store.
        kind: CapacityKind,
        /// Its capacity.
        capacity: u32,
    },
    /// A material id that was never added.
    UnknownMaterial {
        /// The id.
        id: u16,
    },
    /// A body or wall id out of range.
    UnknownId {
        /// The id.
        id: u32,
    },
    /// dt ≤ 0.
    NonPositiveTimeStep {
        /// The value in s.
        dt_s: f64,
    },
    /// dt above the stable bound ([`crate::timestep`]).
    TimeStepTooLarge {
        /// Requested dt, s.
        dt_s: f64,
        /// Largest accepted dt, s.
        max_s: f64,
    },
    /// A multi-rate stride outside 1..=max ([`crate::step::multirate`]).
    BadSlowStride {
        /// The stride asked for.
        stride: u32,
        /// The largest stride.
        max: u32,
    },
    /// A wall description that makes no sense (zero normal or axis, empty box, radius ≤ 0).
    BadWall {
        /// What is wrong.
        reason: &'static str,
    },
    /// An optional effect's parameter is negative (its off value is 0).
    NegativeEffectParameter {
        /// Which parameter.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// Two optional effects that cannot be on together for one pair.
    IncompatibleEffects {
        /// The first effect.
        a: &'static str,
        /// The second effect.
        b: &'static str,
    },
}

impl fmt::Display for SetupError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            SetupError::NonFinite { what } => write!(f, "{what} is not a finite number"),
            SetupError::NotRepresentable { what, value } => write!(
                f,
                "{what} = {value:e} (internal units) is outside the fixed-point range \
                 (|x| < 2.1e9, resolution 2.3e-10)"
            ),
            SetupError::NonPositiveRadius { radius_m } => {
                write!(f, "sphere radius must be > 0, got {radius_m} m")
            }
            SetupError::RestitutionOutOfRange { e } => {
                write!(f, "coefficient of restitution must be in (0, 1], got {e}")
            }
            SetupError::NegativeFriction { what, value } => {
                write!(f, "{what} friction coefficient must be >= 0, got {value}")
            }
            SetupError::PoissonOutOfRange { nu } => {
                write!(
                    f,
                    "Poisson ratio must be in (-1, 0.5) (or (-1, 1) with PoissonRange::ContactModel), got {nu}"
                )
            }
            SetupError::NonPositiveYoungsModulus { youngs_modulus_pa } => {
                write!(f, "Young's modulus must be > 0, got {youngs_modulus_pa} Pa")
            }
            SetupError::NonPositiveDensity { density_kg_m3 } => {
                write!(f, "density must be > 0, got {density_kg_m3} kg/m^3")
            }
            SetupError::ZeroMassClump => {
                write!(f, "clump has zero mass or a zero principal moment of inertia")
            }
            SetupError::EmptyClump => write!(f, "clump has no spheres"),
            SetupError::Capacity { kind, capacity } => write!(
                f,
                "capacity exceeded: {kind:?} holds at most {capacity}; give the world larger storage"
            ),
            SetupError::UnknownMaterial { id } => write!(f, "material {id} was never added"),
            SetupError::UnknownId { id } => write!(f, "no body or wall with id {id}"),
            SetupError::NonPositiveTimeStep { dt_s } => {
                write!(f, "time step must be > 0, got {dt_s} s")
            }
            SetupError::TimeStepTooLarge { dt_s, max_s } => write!(
                f,
                "time step {dt_s:e} s exceeds the stable bound {max_s:e} s \
                 (a fraction of the Rayleigh time of the smallest sphere)"
            ),
            SetupError::BadSlowStride { stride, max } => write!(
                f,
                "slow stride {stride} is outside 1..={max} (steps per cycle of multi-rate stepping)"
            ),
            SetupError::BadWall { reason } => write!(f, "invalid wall: {reason}"),
            SetupError::IncompatibleEffects { a, b } => {
                write!(f, "{a} and {b} cannot both be on for one material pair")
            }
            SetupError::NegativeEffectParameter { what, value } => {
                write!(f, "{what} must be >= 0 (0 switches the effect off), got {value}")
            }
        }
    }
}

/// Pipeline stage where a step failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Cell-grid binning.
    BroadPhase,
    /// Sphere–sphere contact geometry and forces.
    SphereContact,
    /// Sphere–wall contact geometry and forces.
    WallContact,
    /// Gravity and other body forces.
    BodyForces,
    /// Velocity and position update.
    Integration,
    /// Wall motion.
    WallMotion,
    /// Bond loads and breakage.
    Bonds,
}

/// The second party of a failed interaction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Other {
    /// No second party (a body-only stage).
    None,
    /// Another body (by body id).
    Body(u32),
    /// A wall (by wall id).
    Wall(u32),
}

/// A step that could not be completed. The world state is then unspecified (partly advanced);
/// rebuild it or restore a copy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepError {
    /// A fixed-point operation overflowed (or an `f64` became NaN/∞).
    Overflow {
        /// Where.
        stage: Stage,
        /// The body concerned (body id), or the wall id for [`Stage::WallMotion`].
        body: u32,
        /// The other party.
        other: Other,
    },
    /// The neighbour list (contacts plus near pairs and wall faces within the skin, see
    /// [`crate::step::neighbour_list`]) needs more entries than its arena holds.
    ContactCapacity {
        /// The sphere whose entries did not fit.
        sphere: u32,
        /// Entries the list holds.
        capacity: u32,
    },
    /// Two materials came into contact but no pair parameters were set for them.
    UndefinedPair {
        /// First material id.
        material_a: u16,
        /// Second material id.
        material_b: u16,
    },
    /// No time step was set.
    NoTimeStep,
    /// A scheduled bond formation did not fit the bond arena.
    BondCapacity {
        /// Bond capacity.
        capacity: u32,
    },
    /// dt exceeds the stable bound (e.g. a smaller sphere was added after `set_timestep`).
    TimeStepTooLarge {
        /// dt, s.
        dt_s: f64,
        /// Bound, s.
        max_s: f64,
    },
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            StepError::Overflow { stage, body, other } => {
                write!(f, "numeric overflow in {stage:?} at body {body}")?;
                match other {
                    Other::None => Ok(()),
                    Other::Body(b) => write!(f, " against body {b}"),
                    Other::Wall(w) => write!(f, " against wall {w}"),
                }
            }
            StepError::ContactCapacity { sphere, capacity } => write!(
                f,
                "the neighbour list is full at sphere {sphere}: more than {capacity} contacts and \
                 near neighbours (within the skin); give more neighbour entries per sphere"
            ),
            StepError::UndefinedPair {
                material_a,
                material_b,
            } => write!(
                f,
                "materials {material_a} and {material_b} touch but no pair parameters were set"
            ),
            StepError::NoTimeStep => write!(f, "no time step set; call set_timestep first"),
            StepError::BondCapacity { capacity } => write!(
                f,
                "scheduled bond formation needs more than {capacity} bonds; give larger bond storage"
            ),
            StepError::TimeStepTooLarge { dt_s, max_s } => write!(
                f,
                "time step {dt_s:e} s exceeds the stable bound {max_s:e} s"
            ),
        }
    }
}
