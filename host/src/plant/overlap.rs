//! Overlapping spheres of a generated plant: pairs of spheres of different bodies that
//! interpenetrate. Contacts within a plant are on in a harvest, so a plant must start with
//! none (bonded neighbours are placed with a 1 µm gap and never count).
//!
//! Spheres are binned in a uniform grid of cells one largest diameter wide, so only
//! spheres in neighbouring cells are compared: O(n) for a plant of n spheres.
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

impl PlantModel {
    /// Pairs (a < b) of spheres of different bodies whose overlap
    /// r_a + r_b − |c_a − c_b| exceeds `tolerance_m` (m), in increasing order.
    pub fn overlapping_pairs(&self, tolerance_m: f64) -> Vec<(usize, usize)> {
        let cell_m = 2.0 * self.spheres.iter().map(|s| s.radius_m).fold(0.0, f64::max);
        if cell_m <= 0.0 {
            return Vec::new();
        }
        let cell_of = |c: [f64; 3]| -> Cell { c.map(|x| (x / cell_m).floor() as i64) };
        let mut grid: HashMap<Cell, Vec<usize>> = HashMap::new();
        for (i, s) in self.spheres.iter().enumerate() {
            grid.entry(cell_of(s.centre_m)).or_default().push(i);
        }
        let mut pairs = Vec::new();
        for (a, sa) in self.spheres.iter().enumerate() {
            let [x, y, z] = cell_of(sa.centre_m);
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        let Some(near) = grid.get(&[x + dx, y + dy, z + dz]) else {
                            continue;
                        };
                        for &b in near.iter().filter(|&&b| b > a) {
                            let sb = &self.spheres[b];
                            if sa.body == sb.body {
                                continue;
                            }
                            let d2: f64 = (0..3)
                                .map(|k| (sa.centre_m[k] - sb.centre_m[k]).powi(2))
                                .sum();
                            if sa.radius_m + sb.radius_m - d2.sqrt() > tolerance_m {
                                pairs.push((a, b));
                            }
                        }
                    }
                }
            }
        }
        pairs.sort_unstable();
        pairs
    }
}
