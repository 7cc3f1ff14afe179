//! Plausible ranges: where each physical input of a study lies in any agricultural-material
//! DEM study, with the reason. [`crate::limits`] says what the contact model admits (e > 0,
//! μ ≥ 0); these say what is believable, so a typo such as a density of 1e300 or a
//! gravity of 1e300 is caught by `study check` instead of ruining a calibration (issue 23).
//! Research that needs a value outside passes `--allow-extreme`: the value is then accepted
//! and reported as a warning on standard error.
//!
//! ```
//! use arachis::plausible::DENSITY_KG_M3;
//! assert!(DENSITY_KG_M3.check(582.36).is_ok());
//! assert!(DENSITY_KG_M3.check(1e300).unwrap_err().contains("10 to 25000"));
//! ```

use std::sync::atomic::{AtomicBool, Ordering};

/// The believable range of one quantity, and why.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plausible {
    /// Smallest believable value, in the quantity's unit.
    pub low: f64,
    /// Largest believable value.
    pub high: f64,
    /// The quantity's unit, as written in messages.
    pub unit: &'static str,
    /// Why the range is where it is.
    pub reason: &'static str,
}

/// Density of a particle or wall material, kg/m³.
pub const DENSITY_KG_M3: Plausible = Plausible {
    low: 10.0,
    high: 25_000.0,
    unit: "kg/m³",
    reason: "from expanded foams to the densest metal (osmium, 22 590 kg/m³)",
};
/// Shear modulus of a material, Pa.
pub const SHEAR_MODULUS_PA: Plausible = Plausible {
    low: 1e3,
    high: 1e12,
    unit: "Pa",
    reason: "from soft gels to diamond (G ≈ 5e11 Pa)",
};
/// Static or rolling friction coefficient.
pub const FRICTION: Plausible = Plausible {
    low: 0.0,
    high: 10.0,
    unit: "",
    reason:
        "a coefficient of 10 is a slide angle of 84°; measured granular friction lies far below",
};
/// Gravity, m/s².
pub const GRAVITY_M_S2: Plausible = Plausible {
    low: 0.1,
    high: 100.0,
    unit: "m/s²",
    reason:
        "from a small moon to ten times Earth's (a laboratory centrifuge goes beyond on purpose)",
};
/// A measured angle (repose, slide), degrees.
pub const ANGLE_DEG: Plausible = Plausible {
    low: 0.0,
    high: 90.0,
    unit: "°",
    reason: "a repose or slide angle lies between flat and vertical",
};

/// A dimension of a plant organ (stem, stalk, pod, leaf length or diameter), mm.
pub const PLANT_ORGAN_MM: Plausible = Plausible {
    low: 0.01,
    high: 5_000.0,
    unit: "mm",
    reason: "a peanut main stem is 45–76 cm (seed 000 §2.2.1, seed 001 Table 1); 5 m leaves \
             room for any field crop",
};

/// The plausible range of a material or pair property by its study-file key, if it has one
/// beyond its model limits: the same range for a value in `[materials]` or `[pairs]` and for
/// a `[parameters]` range that varies it.
pub fn for_property(property: &str) -> Option<Plausible> {
    match property {
        "shear_modulus_pa" => Some(SHEAR_MODULUS_PA),
        "density_kg_m3" => Some(DENSITY_KG_M3),
        "static_friction" | "rolling_friction" => Some(FRICTION),
        _ => None,
    }
}

/// Set by `--allow-extreme` for the whole process.
static ALLOW_EXTREME: AtomicBool = AtomicBool::new(false);

/// Accept values outside their plausible range (with a warning) from now on.
pub fn allow_extreme(on: bool) {
    ALLOW_EXTREME.store(on, Ordering::Relaxed);
}

/// Whether `--allow-extreme` is on (a cluster task carries it to its worker).
pub fn extreme_allowed() -> bool {
    ALLOW_EXTREME.load(Ordering::Relaxed)
}

impl Plausible {
    /// `Ok` inside the range; else the reason, naming the range and why. With
    /// `--allow-extreme` a value outside is accepted and the reason printed as a warning.
    pub fn check(&self, value: f64) -> Result<(), String> {
        if (self.low..=self.high).contains(&value) {
            return Ok(());
        }
        let reason = format!(
            "{value:e} is outside the plausible {} to {}{} ({})",
            self.low,
            self.high,
            if self.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", self.unit)
            },
            self.reason
        );
        if ALLOW_EXTREME.load(Ordering::Relaxed) && value.is_finite() {
            eprintln!("warning: accepted with --allow-extreme: {reason}");
            return Ok(());
        }
        Err(format!(
            "{reason}; pass --allow-extreme if your research needs it"
        ))
    }
}
