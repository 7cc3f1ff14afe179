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
use arachis_core::units::{LENGTH_M_TO_MM as MM_PER_M, MASS_KG_TO_G as GRAMS_PER_KG};

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
    /// Organ sizes as built.
    pub organs: Organs,
}

/// Organ sizes of a generated plant, measured on its spheres: a chain part's length is the
/// distance between its end spheres' centres plus one diameter (its extent along its
/// axis), so it differs from the asked length by at most one sphere radius (n = round(L/D)
/// spheres) and the 1 µm gaps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Organs {
    /// Main stem length, mm.
    pub main_stem_length_mm: f64,
    /// Mean lateral stem length, mm (`null` without laterals).
    pub lateral_length_mm: Option<f64>,
    /// Mean pod stalk length, mm (`null` without pods).
    pub stalk_length_mm: Option<f64>,
    /// Mass of each pod, g, when the topology states it.
    pub pod_mass_g: Option<f64>,
    /// Shallowest and deepest pod–stalk junction (the stalk's end sphere) below the root
    /// (the soil surface), mm; negative for one above it (`null` without pods).
    pub junction_depth_mm: Option<[f64; 2]>,
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
            organs: self.organs(),
        }
    }

    /// Lengths of every part of `kind`, mm (module notes of [`Organs`]).
    pub fn part_lengths_mm(&self, kind: Kind) -> Vec<f64> {
        let mut ends: Vec<(&str, usize, usize)> = Vec::new();
        for b in self.bodies.iter().filter(|b| b.kind == kind) {
            let s = b.spheres[0];
            match ends.last_mut() {
                Some((part, _, last)) if *part == b.part => *last = s,
                _ => ends.push((&b.part, s, s)),
            }
        }
        ends.into_iter()
            .map(|(_, first, last)| {
                let (a, b) = (&self.spheres[first], &self.spheres[last]);
                let d2: f64 = (0..3)
                    .map(|k| (a.centre_m[k] - b.centre_m[k]).powi(2))
                    .sum();
                (d2.sqrt() + 2.0 * a.radius_m) * MM_PER_M
            })
            .collect()
    }

    /// Depth below the root of every pod–stalk junction (the centre of the stalk sphere
    /// of each `pod_stalk` bond), mm, in pod order.
    pub fn junction_depths_mm(&self) -> Vec<f64> {
        let root_z = self.spheres.first().map_or(0.0, |s| s.centre_m[2]);
        self.bonds
            .iter()
            .filter(|b| b.set == "pod_stalk")
            .map(|b| (root_z - self.spheres[b.a].centre_m[2]) * MM_PER_M)
            .collect()
    }

    /// The plant's organ sizes.
    pub fn organs(&self) -> Organs {
        let mean = |v: Vec<f64>| (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64);
        let depths = self.junction_depths_mm();
        Organs {
            main_stem_length_mm: mean(self.part_lengths_mm(Kind::MainStem)).unwrap_or(0.0),
            lateral_length_mm: mean(self.part_lengths_mm(Kind::LateralStem)),
            stalk_length_mm: mean(self.part_lengths_mm(Kind::PodStalk)),
            pod_mass_g: self.pod_mass_kg.map(|kg| kg * GRAMS_PER_KG),
            junction_depth_mm: (!depths.is_empty()).then(|| {
                [
                    depths.iter().copied().fold(f64::INFINITY, f64::min),
                    depths.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                ]
            }),
        }
    }
}
