//! [`PlantError`]: why a topology cannot become a plant.

use thiserror::Error;

/// A bad plant topology.
#[derive(Debug, Error, PartialEq)]
pub enum PlantError {
    /// The TOML text does not parse or has unknown keys.
    #[error("cannot read the plant topology: {0}")]
    Parse(String),
    /// A part names a parent that does not exist.
    #[error("part `{part}` is attached to unknown part `{parent}`")]
    UnknownPart {
        /// The part.
        part: String,
        /// The missing parent.
        parent: String,
    },
    /// Two parts share a name.
    #[error("part name `{0}` is used twice")]
    DuplicateName(String),
    /// No main stem, or more than one.
    #[error("a plant needs exactly one main_stem part, found {0}")]
    MainStemCount(usize),
    /// A part of this kind cannot hang on that parent kind.
    #[error("part `{part}` ({kind}) cannot be attached to `{parent}` ({parent_kind})")]
    BadParent {
        /// The part.
        part: String,
        /// Its kind.
        kind: &'static str,
        /// The parent.
        parent: String,
        /// The parent's kind.
        parent_kind: &'static str,
    },
    /// A part whose chain of parents never reaches the main stem (a cycle).
    #[error("part `{0}` is not connected to the main stem")]
    Unconnected(String),
    /// A pod stalk carries no pod.
    #[error("pod stalk `{0}` is dangling: no pod is attached to it")]
    DanglingStalk(String),
    /// A bond set the plant needs is not defined.
    #[error("bond set `{0}` is needed but not defined in [bonds]")]
    MissingBondSet(&'static str),
    /// A bond set is defined but no bond of the plant uses it (a misspelt set).
    #[error("bond set `{set}` is defined in [bonds] but no bond of this plant uses it (sets used: {used})")]
    UnusedBondSet {
        /// The set.
        set: String,
        /// The sets the plant uses, comma-separated.
        used: String,
    },
    /// A bond radius ≤ 0.
    #[error("bond set `{set}`: bond radius must be > 0, got {radius_m} m")]
    NonPositiveBondRadius {
        /// The set.
        set: String,
        /// The radius, m.
        radius_m: f64,
    },
    /// A number out of range.
    #[error("{what} must be {rule}, got {value}")]
    BadValue {
        /// What.
        what: String,
        /// The rule ("> 0", "in [0, 1]").
        rule: &'static str,
        /// The value.
        value: f64,
    },
    /// A dimension outside its plausible range ([`crate::plausible::PLANT_ORGAN_MM`]).
    #[error("{what}: {reason}")]
    Implausible {
        /// What.
        what: String,
        /// The range and why.
        reason: String,
    },
    /// The pod shape could not be built or filled with spheres (`crate::shapes`).
    #[error("cannot build the pod from its shape: {0}")]
    PodShape(String),
    /// Two parts that cannot be grown again (stems) overlap in a grown plant.
    #[error("the plant of seed {seed} cannot be grown: parts `{}` and `{}` overlap", parts[0], parts[1])]
    Crowded {
        /// The plant's seed.
        seed: u64,
        /// The two parts.
        parts: [String; 2],
    },
    /// Stalks or leaves still overlap after every regrowth round.
    #[error("the plant of seed {seed} still has overlapping stalks or leaves after {rounds} regrowths: the variety has more pods than its stems can hold apart")]
    TooCrowded {
        /// The plant's seed.
        seed: u64,
        /// Rounds tried.
        rounds: usize,
    },
    /// No draw of a stalk reached its depth from any node it may grow from.
    #[error("no pod stalk of {tries} draws could reach its drawn depth from a node of its stem: make the stalks longer or the pods shallower")]
    Unreachable {
        /// Draws tried.
        tries: usize,
    },
    /// The core refused the plant (capacity, ranges).
    #[error("the simulation core refused the plant: {0}")]
    Core(String),
}
