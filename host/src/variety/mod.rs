//! A variety file: how the plants of one cultivar are built, as distributions rather than as
//! one hand-listed plant. [`Variety::grow`] turns it and a seed into a [`Topology`] (and
//! the generated [`PlantModel`]): the main stem, pairs of lateral stems near its base, pods
//! on pod stalks (pegs) that dive from the lower nodes into the soil, and simplified
//! leaves. Two seeds give two different plants of the same variety; one seed always gives
//! the same plant.
//!
//! Every drawn quantity is a [`Spread`]: a mean and an SD, drawn from the normal
//! distribution truncated at [`TRUNCATION_SDS`] SDs (redrawn outside), so a plant never gets
//! a negative organ or an absurd one. Pod size follows pod mass: a plant's pods share one
//! drawn mass m, and their length, width and thickness are the variety's times
//! (m / mean mass)^(1/3).
//!
//! ```
//! use arachis::variety::Variety;
//! let text = include_str!("../../../testdata/peanut-plant/variety-huayu.toml");
//! let variety = Variety::from_toml(std::path::Path::new("variety-huayu.toml"), text).unwrap();
//! let (topology, model) = variety.grow(7).unwrap();
//! let pods = model.bodies.iter().filter(|b| b.kind == arachis::plant::topology::Kind::Pod);
//! assert_eq!(pods.count(), model.bond_count("pod_stalk"));
//! assert!(topology.dimensions.pod_mass_g.is_some());
//! ```
//!
//! A bad file is refused before anything is grown, with its path, line and key
//! ([`VarietyErrors`], positioned as a study file's errors are).

mod grow;

pub(crate) use grow::draw;

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;

use crate::plant::topology::{BondSet, MAX_POD_SPHERES};
use crate::plant::{PlantError, PlantModel, Topology};
use crate::plausible::PLANT_ORGAN_MM;
use crate::study::error::{file_errors, StudyError};
use crate::study::source::{decode_checked, read_checked, Source};

file_errors!(
    /// Every error found in one variety file, in file order (never empty when returned).
    VarietyErrors,
    "variety file",
    "any plant was grown"
);

/// Draws of a [`Spread`] are truncated at this many SDs from the mean.
pub const TRUNCATION_SDS: f64 = 3.0;

/// A quantity that varies between plants: its mean and SD, in the key's unit.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spread {
    /// Mean.
    pub mean: f64,
    /// Standard deviation (0 for a fixed value).
    pub sd: f64,
}

impl Spread {
    /// Smallest value a draw can take: mean − [`TRUNCATION_SDS`]·SD.
    pub fn low(&self) -> f64 {
        self.mean - TRUNCATION_SDS * self.sd
    }

    /// Largest value a draw can take: mean + [`TRUNCATION_SDS`]·SD.
    pub fn high(&self) -> f64 {
        self.mean + TRUNCATION_SDS * self.sd
    }
}

/// What the variety is and where its numbers come from.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct About {
    /// The cultivar's name.
    pub name: String,
    /// Where its numbers come from.
    #[serde(default)]
    pub source: String,
}

/// The main stem.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MainStem {
    /// Length, mm.
    pub length_mm: Spread,
    /// Diameter, mm (also the lateral stems').
    pub diameter_mm: f64,
}

/// The lateral stems: pairs growing from the lowest nodes of the main stem.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LateralStems {
    /// Pairs of opposite laterals; pair k+1 grows above pair k, turned by 90°.
    pub pairs: usize,
    /// Length of each lateral, mm.
    pub length_mm: Spread,
    /// Angle of each lateral above the horizontal, degrees.
    pub rise_deg: Spread,
}

/// The pod stalks (pegs).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PodStalks {
    /// Length of each stalk, mm.
    pub length_mm: Spread,
    /// Diameter, mm.
    pub diameter_mm: f64,
    /// Angle of each stalk below the horizontal, degrees (a peg grows down into the soil).
    pub dive_deg: Spread,
}

/// The pods.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pods {
    /// Pods per plant (drawn, then rounded; at least one).
    pub per_plant: Spread,
    /// Fraction of a plant's pods on the lateral stems; the rest hang from the main stem.
    pub on_laterals: f64,
    /// Depth of the pod–stalk junction below the soil surface (the root), mm: a stalk grows
    /// from the node at the height that puts its end at this depth.
    pub depth_mm: Spread,
    /// Mass of one pod, g (one draw per plant).
    pub mass_g: Spread,
    /// Pod length L at the mean mass, mm.
    pub length_mm: f64,
    /// Pod width W at the mean mass, mm.
    pub width_mm: f64,
    /// Pod thickness H at the mean mass, mm.
    pub thickness_mm: f64,
    /// Spheres filling each pod (1 to 64).
    pub spheres: usize,
}

/// The simplified leaves.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Leaves {
    /// Leaves on each stem (main and lateral), spread over its upper half.
    pub per_stem: usize,
    /// Length, mm.
    pub length_mm: f64,
    /// Sphere diameter, mm.
    pub diameter_mm: f64,
}

/// A whole variety file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Variety {
    /// Name and sources.
    pub variety: About,
    /// The main stem.
    pub main_stem: MainStem,
    /// The lateral stems.
    pub lateral_stems: LateralStems,
    /// The pod stalks.
    pub pod_stalks: PodStalks,
    /// The pods.
    pub pods: Pods,
    /// The leaves.
    pub leaves: Leaves,
    /// Bond sets by name, as in a topology file (`stem`, `stalk`, `stalk_stem`,
    /// `pod_stalk`, `stem_leaf`, `leaf`).
    pub bonds: BTreeMap<String, BondSet>,
}

impl Variety {
    /// Reads and checks a variety file; `path` names it in every error.
    pub fn from_toml(path: &Path, text: &str) -> Result<Self, VarietyErrors> {
        decode_checked(path, text, Self::problems).map_err(VarietyErrors)
    }

    /// Reads and checks the variety file at `path`.
    pub fn read(path: &Path) -> Result<Self, VarietyErrors> {
        read_checked(path, "variety", Self::problems).map_err(VarietyErrors)
    }

    /// Every value outside what a plant can be grown from, each at its key.
    fn problems(&self, source: &Source<'_>) -> Vec<StudyError> {
        let mut errors = Vec::new();
        let mut bad =
            |path: &[&str], reason: String| errors.push(source.error_at_keys(path, reason));
        let organ = |v: f64| v.is_finite() && PLANT_ORGAN_MM.check(v).is_ok() && v > 0.0;
        let organ_rule = format!(
            "must be a plant organ's size, {} to {} mm",
            PLANT_ORGAN_MM.low, PLANT_ORGAN_MM.high
        );
        let spreads: [(&[&str], Spread, f64, f64, &str); 7] = [
            (
                &["main_stem", "length_mm"],
                self.main_stem.length_mm,
                PLANT_ORGAN_MM.low,
                PLANT_ORGAN_MM.high,
                "mm",
            ),
            (
                &["lateral_stems", "length_mm"],
                self.lateral_stems.length_mm,
                PLANT_ORGAN_MM.low,
                PLANT_ORGAN_MM.high,
                "mm",
            ),
            (
                &["lateral_stems", "rise_deg"],
                self.lateral_stems.rise_deg,
                0.0,
                MAX_LATERAL_RISE_DEG,
                "degrees",
            ),
            (
                &["pod_stalks", "length_mm"],
                self.pod_stalks.length_mm,
                PLANT_ORGAN_MM.low,
                PLANT_ORGAN_MM.high,
                "mm",
            ),
            (
                &["pod_stalks", "dive_deg"],
                self.pod_stalks.dive_deg,
                10.0,
                90.0,
                "degrees",
            ),
            (
                &["pods", "depth_mm"],
                self.pods.depth_mm,
                0.0,
                PLANT_ORGAN_MM.high,
                "mm",
            ),
            (
                &["pods", "mass_g"],
                self.pods.mass_g,
                f64::MIN_POSITIVE,
                MAX_POD_MASS_G,
                "g",
            ),
        ];
        for (path, s, lo, hi, unit) in spreads {
            check_spread(&mut bad, path, s, lo, hi, unit);
        }
        check_spread(
            &mut bad,
            &["pods", "per_plant"],
            self.pods.per_plant,
            MIN_MEAN_PODS,
            MAX_PODS_PER_PLANT as f64,
            "pods",
        );
        for (path, v) in [
            (["main_stem", "diameter_mm"], self.main_stem.diameter_mm),
            (["pod_stalks", "diameter_mm"], self.pod_stalks.diameter_mm),
            (["pods", "length_mm"], self.pods.length_mm),
            (["pods", "width_mm"], self.pods.width_mm),
            (["pods", "thickness_mm"], self.pods.thickness_mm),
            (["leaves", "length_mm"], self.leaves.length_mm),
            (["leaves", "diameter_mm"], self.leaves.diameter_mm),
        ] {
            if !organ(v) {
                bad(&path, format!("{organ_rule}, got {v}"));
            }
        }
        if !(0.0..=1.0).contains(&self.pods.on_laterals) {
            bad(
                &["pods", "on_laterals"],
                format!(
                    "must be a fraction in [0, 1], got {}",
                    self.pods.on_laterals
                ),
            );
        }
        if self.pods.on_laterals > 0.0 && self.lateral_stems.pairs == 0 {
            bad(
                &["lateral_stems", "pairs"],
                "must be at least 1 when pods.on_laterals > 0 (pods need laterals to hang on)"
                    .into(),
            );
        }
        if self.lateral_stems.pairs > MAX_LATERAL_PAIRS {
            bad(
                &["lateral_stems", "pairs"],
                format!(
                    "must be at most {MAX_LATERAL_PAIRS}, got {}",
                    self.lateral_stems.pairs
                ),
            );
        }
        if !(1..=MAX_POD_SPHERES).contains(&self.pods.spheres) {
            bad(
                &["pods", "spheres"],
                format!("must be 1 to {MAX_POD_SPHERES}, got {}", self.pods.spheres),
            );
        }
        if self.leaves.per_stem > MAX_LEAVES_PER_STEM {
            bad(
                &["leaves", "per_stem"],
                format!(
                    "must be at most {MAX_LEAVES_PER_STEM}, got {}",
                    self.leaves.per_stem
                ),
            );
        }
        for (name, set) in &self.bonds {
            for (what, v) in [
                ("kn_n_m3", set.kn_n_m3),
                ("kt_n_m3", set.kt_n_m3),
                ("sigma_c_pa", set.sigma_c_pa),
                ("tau_c_pa", set.tau_c_pa),
                ("radius_m", set.radius_m),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    bad(&["bonds", name, what], format!("must be > 0, got {v}"));
                }
            }
        }
        errors
    }

    /// The plant of `seed`: its topology and the model generated from it
    /// ([`crate::plant::generate`]). Stalks whose pods would overlap another part are grown again
    /// in other directions (see [`grow`]).
    pub fn grow(&self, seed: u64) -> Result<(Topology, PlantModel), PlantError> {
        grow::grow(self, seed, &|_| Vec::new())
    }

    /// The plant of `seed`, grown around its surroundings: `outside` returns the indices of
    /// the spheres of a generated plant that touch something outside it (a neighbour in a
    /// field, [`crate::field`]). Touching stalks, pods and leaves are drawn again as clashing
    /// ones are; a touching stem refuses the plant ([`PlantError::Crowded`]).
    pub fn grow_around(
        &self,
        seed: u64,
        outside: &dyn Fn(&PlantModel) -> Vec<usize>,
    ) -> Result<(Topology, PlantModel), PlantError> {
        grow::grow(self, seed, outside)
    }
}

/// Heaviest pod mass accepted, g (a peanut pod weighs 1–4 g: seed 000 §2.2.1 gives
/// 227.7 g per 100 pods).
pub const MAX_POD_MASS_G: f64 = 50.0;
/// Steepest lateral, degrees above the horizontal: a lateral's first sphere touches the
/// stem sphere above its node at 30° (equal radii at one pitch), so a steeper one would
/// start inside the stem.
pub const MAX_LATERAL_RISE_DEG: f64 = 30.0;
/// Most pods a plant may have.
pub const MAX_PODS_PER_PLANT: usize = 500;
/// Smallest mean pod count whose truncated draws still round to at least one pod.
const MIN_MEAN_PODS: f64 = 0.5;
/// Most lateral pairs (the node heights of the laterals are spaced for this many).
pub const MAX_LATERAL_PAIRS: usize = 8;
/// Most leaves per stem.
pub const MAX_LEAVES_PER_STEM: usize = 50;

/// Refuses a spread whose draws could leave [`lo`, `hi`] or whose numbers are not finite.
pub(crate) fn check_spread(
    bad: &mut impl FnMut(&[&str], String),
    path: &[&str],
    s: Spread,
    lo: f64,
    hi: f64,
    unit: &str,
) {
    let mut sd_path = path.to_vec();
    sd_path.push("sd");
    let mut mean_path = path.to_vec();
    mean_path.push("mean");
    if !(s.sd.is_finite() && s.sd >= 0.0) {
        bad(&sd_path, format!("must be ≥ 0, got {}", s.sd));
    } else if !(s.mean.is_finite() && s.mean >= lo && s.mean <= hi) {
        bad(
            &mean_path,
            format!("must lie in [{lo}, {hi}] {unit}, got {}", s.mean),
        );
    } else if s.low() < lo || s.high() > hi {
        bad(
            &sd_path,
            format!(
                "draws reach mean ± {TRUNCATION_SDS}·sd = [{:.4}, {:.4}] {unit}, outside [{lo}, {hi}]: \
                 make sd at most {:.4}",
                s.low(),
                s.high(),
                ((s.mean - lo).min(hi - s.mean)) / TRUNCATION_SDS
            ),
        );
    }
}
