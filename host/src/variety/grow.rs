//! Growing one plant of a [`Variety`] from a seed.
//!
//! The root (the main stem's first sphere) is at the origin, on the soil surface; z is up.
//! - The main stem grows straight up.
//! - Lateral pair k grows from the main-stem node at [`LATERAL_NODE_STEP`]·(k + 1) of its
//!   length: two opposite laterals at azimuths φ₀ + 90°·k and φ₀ + 90°·k + 180°, each rising
//!   at its drawn angle (peanut's first laterals are the cotyledonary pair at the base; the
//!   n+1 and n+2 cotyledonary branches bear 65–67 % and 24–26 % of the pods: "Temporal
//!   Analysis of Branches Pod Production in Peanut Genotypes with Different Growth Habits
//!   and Branching Patterns", Peanut Science, peanutscience.com/article/id/1150).
//! - A pod's stalk dives from a node at the drawn angle δ and length Ls. It grows from the
//!   node at the height h = Ls·sin δ − d that puts its end at the drawn depth d (pegs carry
//!   the pod 1–7 cm into the soil), clamped to the stem: a lateral's node is found along
//!   its rise. A main-stem stalk grows from the root (the stem's lowest node, where a peg
//!   can leave without crossing the stem), so it dives at δ = asin(d / Ls) instead of its
//!   drawn angle, shallow enough to end at the drawn depth. Lateral pods point within
//!   ±[`STALK_AZIMUTH_SPREAD_DEG`] of their lateral's azimuth; main-stem pods anywhere.
//! - Leaves sit on the upper half of every stem, at random azimuths, rising at
//!   [`LEAF_RISE`].
//!
//! Plants are generated with touching neighbours only: when a stalk or its pod overlaps any
//! sphere of another body (contacts within a plant are on in a harvest, so an overlap would
//! start as a violent push), that stalk is drawn again (and a clashing leaf's azimuth) and
//! the plant is regenerated, up to [`MAX_REGROWTHS`] rounds.

use std::f64::consts::TAU;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use super::{Spread, Variety, MAX_PODS_PER_PLANT};
use crate::plant::generate::{chain_spheres, generate, GAP_MM};
use crate::plant::topology::{Dimensions, Kind, Part, Topology, DEFAULT_POD_FILL_RESOLUTION};
use crate::plant::{PlantError, PlantModel};

/// Main-stem node spacing between lateral pairs, as a fraction of the stem's length: the
/// pod-bearing laterals are basal (about 7.6 mm apart on the seed 001 stem), so the lowest
/// lateral nodes lie low enough for every drawn stalk to reach its depth.
pub const LATERAL_NODE_STEP: f64 = 0.01;
/// Largest angle between a lateral pod's stalk and its lateral's azimuth, degrees.
pub const STALK_AZIMUTH_SPREAD_DEG: f64 = 60.0;
/// Lowest node of a lateral a stalk grows from, as a fraction of the lateral's length (0:
/// its first sphere, one pitch out from the main stem).
pub const MIN_STALK_NODE: f64 = 0.0;
/// Direction of a leaf: rise over horizontal reach (about 27° above the horizontal).
pub const LEAF_RISE: f64 = 0.5;
/// Rounds of regrowing clashing stalks before the plant is refused.
pub const MAX_REGROWTHS: usize = 50;
/// Overlap below which two spheres count as touching, not clashing, m.
const CLASH_TOLERANCE_M: f64 = 1.0e-7;

/// What stem a pod hangs on.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Host {
    /// The main stem (its root node).
    MainStem,
    /// Lateral number k.
    Lateral(usize),
}

/// One lateral as drawn.
#[derive(Debug, Clone, Copy)]
struct Lateral {
    at: f64,
    azimuth: f64,
    length_mm: f64,
    rise: f64,
}

/// One pod and its stalk as drawn.
#[derive(Debug, Clone, Copy)]
struct Stalk {
    host: Host,
    length_mm: f64,
    dive: f64,
    depth_mm: f64,
    azimuth: f64,
}

/// Where a stalk grows from: its stem's part index (0 the main stem, k + 1 lateral k), the
/// node as a fraction of that stem, and its dive below the horizontal, rad.
#[derive(Debug, Clone, Copy)]
struct Placement {
    stem: usize,
    at: f64,
    dive: f64,
}

/// Draws of a stalk before it is refused as unable to reach its depth from any node.
const MAX_STALK_DRAWS: usize = 1000;

/// Every draw of one plant.
struct Plan {
    stem_length_mm: f64,
    laterals: Vec<Lateral>,
    stalks: Vec<(Stalk, Placement)>,
    pod_mass_g: f64,
    leaf_azimuths: Vec<f64>,
}

/// A truncated-normal draw of `s` (redrawn outside mean ± 3 SD).
pub(crate) fn draw(s: &Spread, rng: &mut ChaCha8Rng) -> f64 {
    if s.sd == 0.0 {
        return s.mean;
    }
    let normal = Normal::new(s.mean, s.sd).expect("checked: sd is finite and > 0");
    loop {
        let x = normal.sample(rng);
        if (s.low()..=s.high()).contains(&x) {
            return x;
        }
    }
}

impl Plan {
    fn draw(v: &Variety, rng: &mut ChaCha8Rng) -> Result<Self, PlantError> {
        let stem_length_mm = draw(&v.main_stem.length_mm, rng);
        let phase = rng.gen_range(0.0..TAU);
        let laterals: Vec<Lateral> = (0..v.lateral_stems.pairs)
            .flat_map(|k| [(k, 0.0), (k, 0.5)])
            .map(|(k, half)| Lateral {
                at: LATERAL_NODE_STEP * (k + 1) as f64,
                azimuth: phase + TAU * (0.25 * k as f64 + half),
                length_mm: draw(&v.lateral_stems.length_mm, rng),
                rise: draw(&v.lateral_stems.rise_deg, rng).to_radians(),
            })
            .collect();
        let pods = (draw(&v.pods.per_plant, rng).round() as usize).clamp(1, MAX_PODS_PER_PLANT);
        let on_laterals = if laterals.is_empty() {
            0
        } else {
            (pods as f64 * v.pods.on_laterals).round() as usize
        };
        let first_lateral = if laterals.is_empty() {
            0
        } else {
            rng.gen_range(0..laterals.len())
        };
        let mut plan = Plan {
            stem_length_mm,
            laterals,
            stalks: Vec::with_capacity(pods),
            pod_mass_g: draw(&v.pods.mass_g, rng),
            leaf_azimuths: Vec::new(),
        };
        for i in 0..pods {
            let host = if i < on_laterals {
                Host::Lateral((first_lateral + i) % plan.laterals.len())
            } else {
                Host::MainStem
            };
            let stalk = plan.reachable_stalk(v, host, rng)?;
            plan.stalks.push(stalk);
        }
        plan.leaf_azimuths = (0..(1 + plan.laterals.len()) * v.leaves.per_stem)
            .map(|_| rng.gen_range(0.0..TAU))
            .collect();
        Ok(plan)
    }

    /// A stalk on `host` that can reach its drawn depth, and its placement: drawn again
    /// while it cannot (so the stalks are the variety's draws given that they reach).
    fn reachable_stalk(
        &self,
        v: &Variety,
        host: Host,
        rng: &mut ChaCha8Rng,
    ) -> Result<(Stalk, Placement), PlantError> {
        for _ in 0..MAX_STALK_DRAWS {
            let stalk = Stalk::draw(v, host, &self.laterals, rng);
            if let Some(placement) = self.placement(v, &stalk) {
                return Ok((stalk, placement));
            }
        }
        Err(PlantError::Unreachable {
            tries: MAX_STALK_DRAWS,
        })
    }

    /// The plan as a topology: names `stem`, `lat{k}`, `peg{i}`, `pod{i}`, `leaf{j}`.
    fn topology(&self, v: &Variety) -> Topology {
        let size = (self.pod_mass_g / v.pods.mass_g.mean).cbrt();
        let dimensions = Dimensions {
            stem_length_mm: self.stem_length_mm,
            stem_diameter_mm: v.main_stem.diameter_mm,
            lateral_length_mm: v.lateral_stems.length_mm.mean,
            stalk_length_mm: v.pod_stalks.length_mm.mean,
            stalk_diameter_mm: v.pod_stalks.diameter_mm,
            pod_length_mm: v.pods.length_mm * size,
            pod_width_mm: v.pods.width_mm * size,
            pod_thickness_mm: v.pods.thickness_mm * size,
            pod_spheres: v.pods.spheres,
            pod_fill_resolution: DEFAULT_POD_FILL_RESOLUTION,
            leaf_length_mm: v.leaves.length_mm,
            leaf_diameter_mm: v.leaves.diameter_mm,
            pod_mass_g: Some(self.pod_mass_g),
        };
        let mut parts = vec![part(
            "stem",
            Kind::MainStem,
            None,
            0.0,
            [0.0, 0.0, 1.0],
            None,
        )];
        for (k, l) in self.laterals.iter().enumerate() {
            parts.push(part(
                &format!("lat{k}"),
                Kind::LateralStem,
                Some("stem"),
                l.at,
                heading(l.azimuth, l.rise),
                Some(l.length_mm),
            ));
        }
        let stems: Vec<String> = std::iter::once("stem".to_owned())
            .chain((0..self.laterals.len()).map(|k| format!("lat{k}")))
            .collect();
        for (i, s) in self.stalks.iter().enumerate() {
            let (s, place) = (&s.0, &s.1);
            let parent = stems[place.stem].as_str();
            let peg = format!("peg{i}");
            let dir = heading(s.azimuth, -place.dive);
            parts.push(part(
                &peg,
                Kind::PodStalk,
                Some(parent),
                place.at,
                dir,
                Some(s.length_mm),
            ));
            parts.push(part(
                &format!("pod{i}"),
                Kind::Pod,
                Some(&peg),
                1.0,
                dir,
                None,
            ));
        }
        let per_stem = v.leaves.per_stem;
        for (j, azimuth) in self.leaf_azimuths.iter().enumerate() {
            let (stem, slot) = (j / per_stem, j % per_stem);
            let at = 0.5 + 0.5 * (slot + 1) as f64 / (per_stem + 1) as f64;
            let dir = [azimuth.cos(), azimuth.sin(), LEAF_RISE];
            parts.push(part(
                &format!("leaf{j}"),
                Kind::Leaf,
                Some(&stems[stem]),
                at,
                dir,
                None,
            ));
        }
        Topology {
            dimensions,
            bonds: v.bonds.clone(),
            parts,
        }
    }

    /// The stem, node fraction and dive of a stalk (module notes), placed so that its end
    /// sphere's centre lies exactly at the drawn depth: the node is the sphere nearest to the
    /// height the drawn dive needs, and the dive is then set to reach the depth from that
    /// node's actual height (as [`generate`] places the spheres). `None` when even a stalk
    /// straight down cannot reach the depth from the lowest node it may use.
    fn placement(&self, v: &Variety, s: &Stalk) -> Option<Placement> {
        let stem_d = v.main_stem.diameter_mm;
        let stalk_d = v.pod_stalks.diameter_mm;
        let pitch = |d: f64| d + GAP_MM;
        // From the node sphere's centre to the stalk's end sphere's centre, along the stalk.
        let reach_mm = stem_d / 2.0
            + GAP_MM
            + stalk_d / 2.0
            + (chain_spheres(s.length_mm, stalk_d) - 1) as f64 * pitch(stalk_d);
        let dive_from = |height_mm: f64| {
            let sin = (height_mm + s.depth_mm) / reach_mm;
            (sin <= 1.0).then(|| sin.asin())
        };
        match s.host {
            Host::MainStem => Some(Placement {
                stem: 0,
                at: 0.0,
                dive: dive_from(0.0)?,
            }),
            Host::Lateral(k) => {
                let l = &self.laterals[k];
                let stem_nodes = chain_spheres(self.stem_length_mm, stem_d) - 1;
                let lateral_nodes = chain_spheres(l.length_mm, stem_d) - 1;
                let node = (l.at * stem_nodes as f64).round();
                // Height of the lateral's sphere j: its stem node, then one pitch per sphere
                // along the rise (the first sphere is one pitch out from the stem node).
                let step_mm = pitch(stem_d) * l.rise.sin();
                let height = |j: f64| node * pitch(stem_d) + (j + 1.0) * step_mm;
                let wanted_mm = reach_mm * s.dive.sin() - s.depth_mm;
                let lowest = (MIN_STALK_NODE * lateral_nodes as f64).round();
                let j = if step_mm > 0.0 {
                    ((wanted_mm - height(0.0)) / step_mm).round()
                } else {
                    lowest
                }
                .clamp(lowest, lateral_nodes as f64);
                Some(Placement {
                    stem: k + 1,
                    at: j / lateral_nodes as f64,
                    dive: dive_from(height(j))?,
                })
            }
        }
    }
}

impl Stalk {
    /// A stalk on `host` drawn from the variety: its azimuth near its lateral's, or anywhere
    /// for the main stem.
    fn draw(v: &Variety, host: Host, laterals: &[Lateral], rng: &mut ChaCha8Rng) -> Self {
        let spread = STALK_AZIMUTH_SPREAD_DEG.to_radians();
        Stalk {
            host,
            length_mm: draw(&v.pod_stalks.length_mm, rng),
            dive: draw(&v.pod_stalks.dive_deg, rng).to_radians(),
            depth_mm: draw(&v.pods.depth_mm, rng),
            azimuth: match host {
                Host::MainStem => rng.gen_range(0.0..TAU),
                Host::Lateral(k) => laterals[k].azimuth + rng.gen_range(-spread..=spread),
            },
        }
    }
}

/// Unit direction at `azimuth` (from +x about +z) and `elevation` above the horizontal.
fn heading(azimuth: f64, elevation: f64) -> [f64; 3] {
    [
        elevation.cos() * azimuth.cos(),
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
    ]
}

fn part(
    name: &str,
    kind: Kind,
    parent: Option<&str>,
    at: f64,
    direction: [f64; 3],
    length_mm: Option<f64>,
) -> Part {
    Part {
        name: name.to_owned(),
        kind,
        parent: parent.map(str::to_owned),
        at,
        direction,
        length_mm,
    }
}

/// Grows the plant of `seed` (module notes) around its surroundings: `outside` names the
/// spheres of a generated plant that touch something outside it (a neighbouring plant in a
/// field); those are regrown like clashing parts, and a stem among them refuses the plant
/// ([`PlantError::Crowded`]).
pub(super) fn grow(
    v: &Variety,
    seed: u64,
    outside: &dyn Fn(&PlantModel) -> Vec<usize>,
) -> Result<(Topology, PlantModel), PlantError> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut plan = Plan::draw(v, &mut rng)?;
    for _ in 0..MAX_REGROWTHS {
        let topology = plan.topology(v);
        let model = generate(&topology)?;
        let clashes = model.overlapping_pairs(CLASH_TOLERANCE_M);
        let touching = outside(&model);
        if clashes.is_empty() && touching.is_empty() {
            return Ok((topology, model));
        }
        let mut regrow: Vec<Regrow> = Vec::new();
        for (a, b) in clashes {
            let of = |s: usize| Regrow::of(&model.bodies[model.spheres[s].body].part);
            // A stalk gives way before a leaf; two stems that clash cannot be regrown.
            let r = match (of(a), of(b)) {
                (Some(x @ Regrow::Stalk(_)), _) | (_, Some(x @ Regrow::Stalk(_))) => x,
                (Some(x), _) | (_, Some(x)) => x,
                (None, None) => {
                    return Err(PlantError::Crowded {
                        seed,
                        parts: [a, b].map(|s| model.bodies[model.spheres[s].body].part.clone()),
                    })
                }
            };
            regrow.push(r);
        }
        for s in touching {
            let part = &model.bodies[model.spheres[s].body].part;
            match Regrow::of(part) {
                Some(r) => regrow.push(r),
                None => {
                    return Err(PlantError::Crowded {
                        seed,
                        parts: [part.clone(), NEIGHBOUR.to_owned()],
                    })
                }
            }
        }
        regrow.sort_unstable();
        regrow.dedup();
        for r in regrow {
            match r {
                Regrow::Stalk(i) => {
                    let host = plan.stalks[i].0.host;
                    plan.stalks[i] = plan.reachable_stalk(v, host, &mut rng)?;
                }
                Regrow::Leaf(j) => plan.leaf_azimuths[j] = rng.gen_range(0.0..TAU),
            }
        }
    }
    Err(PlantError::TooCrowded {
        seed,
        rounds: MAX_REGROWTHS,
    })
}

/// What a part touching something outside its plant is said to clash with.
const NEIGHBOUR: &str = "a neighbouring plant";

/// A part that can be drawn again when it clashes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Regrow {
    /// Stalk `peg{i}` with its pod `pod{i}`.
    Stalk(usize),
    /// Leaf `leaf{j}`.
    Leaf(usize),
}

impl Regrow {
    /// The regrowable part named `part`, if it is one.
    fn of(part: &str) -> Option<Self> {
        let index = |prefix: &str| part.strip_prefix(prefix).and_then(|n| n.parse().ok());
        index("peg")
            .or_else(|| index("pod"))
            .map(Regrow::Stalk)
            .or_else(|| index("leaf").map(Regrow::Leaf))
    }
}
