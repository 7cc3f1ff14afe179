//! Laying a field out: holes in rows, plants in holes, each plant turned until it touches no
//! plant placed before it, then the soil around them.
//!
//! Geometry (m): x runs along the ridge from 0 to its length, y across it (rows at
//! y = (r − (rows − 1)/2)·row spacing), z up; the soil surface is z = 0, where every plant's
//! root lies (its pods hang below, at their drawn depths). The holes of a row sit at the
//! centres of equal hole-spacing slots along the section; the plants of one hole stand
//! [`super::Ridge::hole_plant_gap_m`] apart along the row.
//!
//! Plants of neighbouring holes reach into each other's space (a lateral is about 0.9 m
//! long, holes 0.2 m apart), as in the field. Contacts between plants are on, so two plants
//! must not start interpenetrating: each plant is tried at up to [`MAX_YAW_DRAWS`] yaw angles,
//! uniform on [0, 2π), and keeps the first that overlaps no plant placed before it. A plant
//! that finds none is grown again from its next seed, at most [`MAX_PLANT_REGROWTHS`] times;
//! then the field is refused as too crowded.

use arachis_core::units::LENGTH_M_TO_MM;
use rand::{Rng, RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::settle::lattice_above_surface_m;
use super::soil::{fill_soil, Grain};
use super::FieldSpec;
use crate::plant::overlap::SphereGrid;
use crate::plant::{PlantError, PlantModel};

/// Yaw angles tried per grown plant.
pub const MAX_YAW_DRAWS: usize = 64;
/// Plants grown again (from the next seed) when no yaw fits.
pub const MAX_PLANT_REGROWTHS: usize = 8;
/// Overlap tolerated between spheres of different plants, m (numerical noise only).
pub const PLANT_OVERLAP_TOLERANCE_M: f64 = 1e-7;

/// Why a field cannot be laid out.
#[derive(Debug, thiserror::Error)]
pub enum FieldError {
    /// The field file was read without its variety ([`FieldSpec::read`] sets it).
    #[error("the field has no variety: read it with FieldSpec::read")]
    NoVariety,
    /// A plant could not be grown.
    #[error("plant {plant} (seed {seed}): {source}")]
    Plant {
        /// Index of the plant in the field.
        plant: usize,
        /// Its seed.
        seed: u64,
        /// Why.
        source: PlantError,
    },
    /// A plant overlaps its neighbours at every yaw tried, with every regrowth.
    #[error(
        "plant {plant} at hole ({x_m:.3}, {y_m:.3}) m overlaps the plants placed before it at \
         every one of {tries} yaw angles: the field is too crowded (space the holes or rows \
         wider, or grow fewer plants per hole)"
    )]
    Crowded {
        /// Index of the plant in the field.
        plant: usize,
        /// Hole position along the ridge, m.
        x_m: f64,
        /// Hole position across the ridge, m.
        y_m: f64,
        /// Yaw angles tried over all regrowths.
        tries: usize,
    },
    /// The soil's settling failed (a step of its world, or the world's set-up).
    #[error("the soil's settling: {0}")]
    Settle(String),
}

/// One plant of the field, moved to its place.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedPlant {
    /// The seed it was grown from.
    pub seed: u64,
    /// Its root, m (z = 0, the soil surface).
    pub root_m: [f64; 3],
    /// Its rotation about the vertical through the root, rad.
    pub yaw_rad: f64,
    /// The plant, in field coordinates.
    pub model: PlantModel,
}

/// A laid-out field: plants and soil grains (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Plants, row by row, hole by hole.
    pub plants: Vec<PlacedPlant>,
    /// Soil grains.
    pub grains: Vec<Grain>,
    /// The bed: lowest corner, m.
    pub bed_min_m: [f64; 3],
    /// The bed: highest corner, m (z = 0, the surface).
    pub bed_max_m: [f64; 3],
}

impl Field {
    /// Pods in the field.
    pub fn pods(&self) -> usize {
        self.plants.iter().map(|p| p.model.pods()).sum()
    }

    /// Spheres in the field: every plant's and every grain.
    pub fn spheres(&self) -> usize {
        self.plants
            .iter()
            .map(|p| p.model.spheres.len())
            .sum::<usize>()
            + self.grains.len()
    }
}

/// `model` turned by `yaw` about the vertical and moved so its root is at `root`.
fn moved(model: &PlantModel, yaw: f64, root: [f64; 3]) -> PlantModel {
    let (s, c) = yaw.sin_cos();
    let mut m = model.clone();
    for sp in &mut m.spheres {
        let [x, y, z] = sp.centre_m;
        sp.centre_m = [
            root[0] + c * x - s * y,
            root[1] + s * x + c * y,
            root[2] + z,
        ];
    }
    m
}

/// The hole positions (x, y) of the field, m, row by row.
pub fn holes(spec: &FieldSpec) -> Vec<[f64; 2]> {
    let f = &spec.field;
    let per_row = ((f.ridge_length_m / f.hole_spacing_m).floor() as usize).max(1);
    let first_x =
        (f.ridge_length_m - per_row as f64 * f.hole_spacing_m) / 2.0 + f.hole_spacing_m / 2.0;
    let mid_row = (f.rows as f64 - 1.0) / 2.0;
    (0..f.rows)
        .flat_map(|r| {
            (0..per_row).map(move |h| {
                [
                    first_x + h as f64 * f.hole_spacing_m,
                    (r as f64 - mid_row) * f.row_spacing_m,
                ]
            })
        })
        .collect()
}

impl FieldSpec {
    /// The field of `seed`: plants in their holes, soil settled around them
    /// ([`FieldSpec::lay_out`], then [`Field::settle`] without progress reports).
    pub fn plant(&self, seed: u64) -> Result<Field, FieldError> {
        let mut field = self.lay_out(seed)?;
        field.settle(self, |_, _| {}).map_err(FieldError::Settle)?;
        Ok(field)
    }

    /// The field of `seed` before its soil settles: plants in their holes, and the loose
    /// lattice of grains around them, laid [`lattice_above_surface_m`] above the surface
    /// ([`super::settle`]).
    pub fn lay_out(&self, seed: u64) -> Result<Field, FieldError> {
        let variety = self.variety.as_ref().ok_or(FieldError::NoVariety)?;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let f = &self.field;
        let mid_plant = (f.plants_per_hole as f64 - 1.0) / 2.0;
        let roots: Vec<[f64; 3]> = holes(self)
            .into_iter()
            .flat_map(|[x, y]| {
                (0..f.plants_per_hole)
                    .map(move |k| [x + (k as f64 - mid_plant) * f.hole_plant_gap_m, y, 0.0])
            })
            .collect();
        let mut plants: Vec<PlacedPlant> = Vec::with_capacity(roots.len());
        let mut obstacles = Obstacles::reserving(
            &roots,
            variety.main_stem.diameter_mm / 2.0 / LENGTH_M_TO_MM,
            variety.main_stem.length_mm.high(),
        );
        for (i, &root) in roots.iter().enumerate() {
            let mut tries = 0;
            let mut placed = None;
            for _ in 0..=MAX_PLANT_REGROWTHS {
                let plant_seed = rng.next_u64();
                for _ in 0..MAX_YAW_DRAWS {
                    tries += 1;
                    let yaw = rng.gen_range(0.0..std::f64::consts::TAU);
                    let touching = |m: &PlantModel| obstacles.touching(&moved(m, yaw, root), i);
                    match variety.grow_around(plant_seed, &touching) {
                        Ok((_, model)) => {
                            placed = Some(PlacedPlant {
                                seed: plant_seed,
                                root_m: root,
                                yaw_rad: yaw,
                                model: moved(&model, yaw, root),
                            });
                            break;
                        }
                        // Its stems touch a neighbour at this yaw, or its stalks cannot be
                        // drawn clear of them: turn it.
                        Err(PlantError::Crowded { .. } | PlantError::TooCrowded { .. }) => {}
                        Err(source) => {
                            return Err(FieldError::Plant {
                                plant: i,
                                seed: plant_seed,
                                source,
                            })
                        }
                    }
                }
                if placed.is_some() {
                    break;
                }
            }
            let Some(p) = placed else {
                return Err(FieldError::Crowded {
                    plant: i,
                    x_m: root[0],
                    y_m: root[1],
                    tries,
                });
            };
            obstacles.add(&p.model, i);
            plants.push(p);
        }
        let half_width = self.bed_width_m() / 2.0;
        let margin = self.soil.margin_m;
        let bed_min_m = [-margin, -half_width, -self.soil.depth_m];
        let bed_max_m = [f.ridge_length_m + margin, half_width, 0.0];
        let mut lattice_max_m = bed_max_m;
        lattice_max_m[2] += lattice_above_surface_m(&self.soil);
        let grains = fill_soil(&self.soil, bed_min_m, lattice_max_m, &plants, &mut rng);
        Ok(Field {
            plants,
            grains,
            bed_min_m,
            bed_max_m,
        })
    }
}

/// What a new plant must not touch: the plants placed before it, and the main stems of the
/// plants still to come (a vertical column of stem spheres at each later root, as tall as
/// the variety's tallest stem), so an early plant's lateral does not grow through a hole
/// that a later plant needs.
struct Obstacles {
    grid: SphereGrid,
    /// The plant each stored sphere belongs to (or whose stem it reserves).
    owner: Vec<usize>,
    /// Number of reserved stem spheres, stored first.
    reserved: usize,
}

impl Obstacles {
    /// Reserved stems of `stem_radius` (m) at every root, up to `tallest_mm`.
    fn reserving(roots: &[[f64; 3]], stem_radius: f64, tallest_mm: f64) -> Self {
        let mut grid = SphereGrid::new(stem_radius);
        let mut owner = Vec::new();
        if stem_radius > 0.0 {
            let count = (tallest_mm / LENGTH_M_TO_MM / (2.0 * stem_radius)).ceil() as usize;
            for (i, root) in roots.iter().enumerate() {
                for k in 0..count {
                    let z = root[2] + stem_radius * (1 + 2 * k) as f64;
                    grid.insert([root[0], root[1], z], stem_radius);
                    owner.push(i);
                }
            }
        }
        let reserved = owner.len();
        Obstacles {
            grid,
            owner,
            reserved,
        }
    }

    /// The spheres of plant `plant` (in field coordinates) that touch a placed plant or
    /// another plant's reserved stem. Reserved stems of plants already placed no longer count
    /// (their real stems are stored).
    fn touching(&self, model: &PlantModel, plant: usize) -> Vec<usize> {
        (0..model.spheres.len())
            .filter(|&k| {
                let s = &model.spheres[k];
                self.grid
                    .overlapping(s.centre_m, s.radius_m, PLANT_OVERLAP_TOLERANCE_M)
                    .any(|j| {
                        let owner = self.owner[j];
                        owner != plant && (j >= self.reserved || owner > plant)
                    })
            })
            .collect()
    }

    /// Stores the spheres of placed plant `plant`.
    fn add(&mut self, model: &PlantModel, plant: usize) {
        for s in &model.spheres {
            self.grid.insert(s.centre_m, s.radius_m);
            self.owner.push(plant);
        }
    }
}
