//! The soil bed: grains on a jittered face-centred cubic lattice that fills the bed around
//! the plants.
//!
//! Neighbouring nodes lie the largest grain's diameter times (1 + [`GRAIN_GAP`]) apart; each
//! node holds one grain whose radius is drawn from the soil's spread and whose centre is
//! moved at random by at most half the room its neighbours leave (along each axis, scaled so
//! the move's length stays within it), so no two grains touch and no grain leaves the bed.
//! A grain that would overlap a plant sphere (pods, stalks, the root) is left out. The
//! grains are not yet settled: a harvest lets them fall into place under gravity, with their
//! cohesion, before the machine arrives.
//!
//! A face-centred cubic lattice of touching equal spheres fills π/√18 ≈ 74 % of the bed; with
//! the gap and the spread of radii the fill is lower ([`fill_fraction`] reports it).

use arachis_core::units::LENGTH_M_TO_MM;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use super::layout::PlacedPlant;
use super::Soil;
use crate::plant::overlap::SphereGrid;
use crate::variety::draw;

/// Clearance between lattice neighbours of the largest size, as a fraction of its diameter.
pub const GRAIN_GAP: f64 = 0.02;
/// Clearance kept between a grain and any plant sphere, m.
pub const PLANT_CLEARANCE_M: f64 = 1e-4;

/// One soil grain (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grain {
    /// Centre, m.
    pub centre_m: [f64; 3],
    /// Radius, m.
    pub radius_m: f64,
}

/// Grains filling the box from `min_m` to `max_m` around `plants`, drawn from `rng`.
pub fn fill_soil(
    soil: &Soil,
    min_m: [f64; 3],
    max_m: [f64; 3],
    plants: &[PlacedPlant],
    rng: &mut ChaCha8Rng,
) -> Vec<Grain> {
    let largest_m = soil.grain_radius_mm.high() / LENGTH_M_TO_MM;
    let spacing = 2.0 * largest_m * (1.0 + GRAIN_GAP);
    // The cubic cell of the lattice: four nodes at its corner and face centres.
    let cell = spacing * std::f64::consts::SQRT_2;
    let offsets = [
        [0.0, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        [0.5, 0.0, 0.5],
        [0.0, 0.5, 0.5],
    ];
    let plant_largest = plants
        .iter()
        .flat_map(|p| p.model.spheres.iter().map(|s| s.radius_m))
        .fold(0.0, f64::max);
    let mut plant_grid = SphereGrid::new(plant_largest.max(largest_m));
    for s in plants.iter().flat_map(|p| &p.model.spheres) {
        plant_grid.insert(s.centre_m, s.radius_m);
    }
    let cells = |k: usize| ((max_m[k] - min_m[k] - spacing) / cell).floor().max(0.0) as usize + 1;
    let (nx, ny, nz) = (cells(0), cells(1), cells(2));
    let mut grains = Vec::with_capacity(4 * nx * ny * nz);
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                for o in offsets {
                    let node = [
                        min_m[0] + spacing / 2.0 + (i as f64 + o[0]) * cell,
                        min_m[1] + spacing / 2.0 + (j as f64 + o[1]) * cell,
                        min_m[2] + spacing / 2.0 + (k as f64 + o[2]) * cell,
                    ];
                    if (0..3).any(|a| node[a] + spacing / 2.0 > max_m[a]) {
                        continue;
                    }
                    let radius_m = draw(&soil.grain_radius_mm, rng) / LENGTH_M_TO_MM;
                    // Neighbours are `spacing` apart: moving each by at most half the slack
                    // keeps them apart (the move's length is at most √3 × its per-axis bound).
                    let room = (spacing / 2.0 - radius_m) / 3f64.sqrt();
                    let centre_m: [f64; 3] =
                        std::array::from_fn(|a| node[a] + rng.gen_range(-room..=room));
                    let blocked = plant_grid
                        .overlapping(centre_m, radius_m + PLANT_CLEARANCE_M, 0.0)
                        .next()
                        .is_some();
                    if !blocked {
                        grains.push(Grain { centre_m, radius_m });
                    }
                }
            }
        }
    }
    grains
}

/// Fraction of the box from `min_m` to `max_m` that the grains fill.
pub fn fill_fraction(grains: &[Grain], min_m: [f64; 3], max_m: [f64; 3]) -> f64 {
    let volume: f64 = (0..3).map(|k| max_m[k] - min_m[k]).product();
    let solid: f64 = grains
        .iter()
        .map(|g| 4.0 / 3.0 * std::f64::consts::PI * g.radius_m.powi(3))
        .sum();
    solid / volume
}
