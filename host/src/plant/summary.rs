//! What a generated plant holds, for reports: parts by kind, spheres, bodies, and the bond
//! count of every named set, with seed 001's counts for its plant beside the three named
//! sets issue 6 asks for (pod–stalk, stalk–stem, stem–leaf).
//!
//! Seed 001 §2.4.3 prints, for its whole plant: 191 pod–stalk bonds, 201 "pod-to-pod"
//! bonds and 150 stem–leaf bonds. Its plant and its bonding differ from a topology file
//! here (several bonds per junction in EDEM's bonding of overlapping particles, versus
//! one bond per junction here), so the numbers are put side by side, not compared by a
//! test.

use std::collections::BTreeMap;

use serde::Serialize;

use super::generate::PlantModel;
use super::topology::Kind;

/// Seed 001 §2.4.3: pod–stalk bonds of its plant.
pub const SEED001_POD_STALK_BONDS: usize = 191;
/// Seed 001 §2.4.3: "pod-to-pod" bonds of its plant (issue 6 lists them beside the
/// stalk–stem set).
pub const SEED001_POD_POD_BONDS: usize = 201;
/// Seed 001 §2.4.3: stem–leaf bonds of its plant.
pub const SEED001_STEM_LEAF_BONDS: usize = 150;

/// The three named junction sets of issue 6.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct NamedBondSets {
    /// Pod–stalk junction bonds.
    pub pod_stalk: usize,
    /// Stalk–stem attachment bonds.
    pub stalk_stem: usize,
    /// Stem–leaf attachment bonds.
    pub stem_leaf: usize,
}

/// Seed 001's counts for its plant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Seed001Counts {
    /// Pod–stalk bonds (191).
    pub pod_stalk: usize,
    /// "Pod-to-pod" bonds (201).
    pub pod_pod: usize,
    /// Stem–leaf bonds (150).
    pub stem_leaf: usize,
}

/// A plant's summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlantSummary {
    /// Parts by kind name (`main_stem`, `lateral_stem`, `pod_stalk`, `pod`, `leaf`).
    pub parts: BTreeMap<&'static str, usize>,
    /// Spheres.
    pub spheres: usize,
    /// Rigid bodies (a pod clump is one).
    pub bodies: usize,
    /// Bonds in all.
    pub bonds: usize,
    /// Bonds of every set, by set name.
    pub bond_sets: BTreeMap<&'static str, usize>,
    /// The three named sets of issue 6.
    pub named: NamedBondSets,
    /// Seed 001's counts for its plant, for comparison.
    pub seed001: Seed001Counts,
}

impl PlantModel {
    /// Bonds of every set used, by set name.
    pub fn bond_counts(&self) -> BTreeMap<&'static str, usize> {
        let mut counts = BTreeMap::new();
        for b in &self.bonds {
            *counts.entry(b.set).or_insert(0) += 1;
        }
        counts
    }

    /// The plant's summary.
    pub fn summary(&self) -> PlantSummary {
        let mut parts: BTreeMap<&'static str, usize> = BTreeMap::new();
        let mut last: Option<&str> = None;
        for b in &self.bodies {
            // Chain parts are one body per sphere, in order: count each part once.
            if last != Some(b.part.as_str()) {
                *parts.entry(b.kind.name()).or_insert(0) += 1;
            }
            last = Some(&b.part);
        }
        for k in [
            Kind::MainStem,
            Kind::LateralStem,
            Kind::PodStalk,
            Kind::Pod,
            Kind::Leaf,
        ] {
            parts.entry(k.name()).or_insert(0);
        }
        PlantSummary {
            parts,
            spheres: self.spheres.len(),
            bodies: self.bodies.len(),
            bonds: self.bonds.len(),
            bond_sets: self.bond_counts(),
            named: NamedBondSets {
                pod_stalk: self.bond_count("pod_stalk"),
                stalk_stem: self.bond_count("stalk_stem"),
                stem_leaf: self.bond_count("stem_leaf"),
            },
            seed001: Seed001Counts {
                pod_stalk: SEED001_POD_STALK_BONDS,
                pod_pod: SEED001_POD_POD_BONDS,
                stem_leaf: SEED001_STEM_LEAF_BONDS,
            },
        }
    }
}
