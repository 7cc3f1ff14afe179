//! The bench experiments of a pod world (issue 4 §2): the names a study gives them and the
//! order they are listed in.

use std::fmt;

use serde::{Deserialize, Serialize};

/// The virtual (and bench) experiments a study can measure and simulate (issue 4 §2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Experiment {
    /// Stacking (repose) angle by cylinder lifting (seed 000 §2.7, §3.6.1).
    Repose,
    /// Drop onto the 45° plate (restitution rig, seed 000 §2.6.1).
    PlateDrop,
    /// Sliding on an inclined plane (static friction, seed 000 §2.6.2).
    InclineSlide,
    /// Rolling on an incline followed by a flat (rolling friction, seed 000 §2.6.3).
    Rolling,
    /// Compression between two plates (apparent modulus, seed 000 §2.5.3).
    Compression,
    /// Pods poured from a drop height into a cylinder (bulk density, issue 22).
    PodBulkDensity,
    /// Pods in a rotating drum (dynamic angle of repose, issue 22).
    PodDrum,
    /// Pods running out of a silo through an orifice (mass flow rate, issue 22).
    PodHopper,
}

impl Experiment {
    /// Every experiment, in declaration order.
    pub const ALL: [Experiment; 8] = [
        Self::Repose,
        Self::PlateDrop,
        Self::InclineSlide,
        Self::Rolling,
        Self::Compression,
        Self::PodBulkDensity,
        Self::PodDrum,
        Self::PodHopper,
    ];

    /// The name used in study files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Repose => "repose",
            Self::PlateDrop => "plate_drop",
            Self::InclineSlide => "incline_slide",
            Self::Rolling => "rolling",
            Self::Compression => "compression",
            Self::PodBulkDensity => "pod_bulk_density",
            Self::PodDrum => "pod_drum",
            Self::PodHopper => "pod_hopper",
        }
    }
}

impl fmt::Display for Experiment {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
