//! Overlapping spheres: pairs of spheres of different bodies that interpenetrate. Contacts
//! within a plant are on in a harvest, so a plant must start with none (bonded neighbours are
//! placed with a 1 µm gap and never count); a field's plants and soil grains likewise.
//!
//! [`SphereGrid`] bins spheres in a uniform grid of cells at least one largest diameter
//! wide, so a query compares only spheres in the 27 neighbouring cells: O(n) for n spheres.
//!
//! ```
//! use arachis::plant::{generate, Topology, SHIPPED_TOPOLOGY};
//! let plant = generate(&Topology::from_toml(SHIPPED_TOPOLOGY).unwrap()).unwrap();
//! assert!(plant.overlapping_pairs(1e-7).is_empty());
//! ```

use std::collections::HashMap;

use super::PlantModel;

/// A grid cell index.
type Cell = [i64; 3];

/// Spheres binned for overlap queries (SI: centres and radii in m).
#[derive(Debug, Clone)]
pub struct SphereGrid {
    cell_m: f64,
    cells: HashMap<Cell, Vec<usize>>,
    spheres: Vec<([f64; 3], f64)>,
    /// Largest radius stored, m: a query reaches as many cells as it and the query's radius
    /// need, so a larger sphere than the grid was sized for is still found.
    largest_m: f64,
}

impl SphereGrid {
    /// An empty grid sized for spheres of radius about `typical_max_radius_m` (queries look
    /// in one ring of cells around their own when every radius is at most that).
    pub fn new(typical_max_radius_m: f64) -> Self {
        SphereGrid {
            cell_m: (2.0 * typical_max_radius_m).max(f64::MIN_POSITIVE),
            cells: HashMap::new(),
            spheres: Vec::new(),
            largest_m: 0.0,
        }
    }

    fn cell_of(&self, c: [f64; 3]) -> Cell {
        c.map(|x| (x / self.cell_m).floor() as i64)
    }

    /// Adds a sphere; returns its index (insertion order).
    pub fn insert(&mut self, centre_m: [f64; 3], radius_m: f64) -> usize {
        let i = self.spheres.len();
        self.spheres.push((centre_m, radius_m));
        self.largest_m = self.largest_m.max(radius_m);
        self.cells
            .entry(self.cell_of(centre_m))
            .or_default()
            .push(i);
        i
    }

    /// Indices of the stored spheres that a sphere at `centre_m` of `radius_m` overlaps by
    /// more than `tolerance_m` (overlap r_a + r_b − |c_a − c_b|), in no particular order.
    pub fn overlapping(
        &self,
        centre_m: [f64; 3],
        radius_m: f64,
        tolerance_m: f64,
    ) -> impl Iterator<Item = usize> + '_ {
        let [x, y, z] = self.cell_of(centre_m);
        let reach = ((radius_m + self.largest_m) / self.cell_m).ceil().max(1.0) as i64;
        let near = (-reach..=reach).flat_map(move |dx| {
            (-reach..=reach)
                .flat_map(move |dy| (-reach..=reach).map(move |dz| [x + dx, y + dy, z + dz]))
        });
        near.filter_map(|cell| self.cells.get(&cell))
            .flatten()
            .copied()
            .filter(move |&b| {
                let (c, r) = self.spheres[b];
                let d2: f64 = (0..3).map(|k| (c[k] - centre_m[k]).powi(2)).sum();
                radius_m + r - d2.sqrt() > tolerance_m
            })
    }
}

impl PlantModel {
    /// Pairs (a < b) of spheres of different bodies whose overlap
    /// r_a + r_b − |c_a − c_b| exceeds `tolerance_m` (m), in increasing order.
    pub fn overlapping_pairs(&self, tolerance_m: f64) -> Vec<(usize, usize)> {
        let largest = self.spheres.iter().map(|s| s.radius_m).fold(0.0, f64::max);
        let mut grid = SphereGrid::new(largest);
        for s in &self.spheres {
            grid.insert(s.centre_m, s.radius_m);
        }
        let mut pairs: Vec<(usize, usize)> = self
            .spheres
            .iter()
            .enumerate()
            .flat_map(|(a, sa)| {
                grid.overlapping(sa.centre_m, sa.radius_m, tolerance_m)
                    .filter(move |&b| b > a)
                    .filter(move |&b| self.spheres[b].body != sa.body)
                    .map(move |b| (a, b))
            })
            .collect();
        pairs.sort_unstable();
        pairs
    }
}
