//! Broad phase: a dense cell grid over the spheres' bounding box, cell edge ≥ 2·R_max + skin,
//! used only when the neighbour list is rebuilt ([`super::neighbour_list`]); filled
//! by counting sort into the caller's `cells` and `sphere_index` arrays. O(N) per rebuild, no
//! allocation, deterministic: spheres are binned in id order and pairs are visited cell by
//! cell over a half neighbourhood (the cell itself and 13 of its 26 neighbours), so each pair
//! is seen once.
//!
//! When the bounding box needs more cells than the caller gave, neighbouring cells are merged
//! (edge × k) until it fits: always correct, slower only for very spread-out particles.
//!
//! Layout of `sphere_index` (n = sphere capacity): `[0, n)` cell of each sphere, `[n, 2n)`
//! spheres sorted by cell, `[2n, 4n)` contact counts of the two history halves.

use crate::num::{Scalar, Vec3};
use crate::world::World;

/// Grid geometry of the current step.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Grid {
    pub dims: [u32; 3],
}

/// Forward half of the 26 neighbour offsets: (dx, dy, dz) lexicographically after (0,0,0).
pub(crate) const HALF_NEIGHBOURS: [[i32; 3]; 13] = [
    [1, 0, 0],
    [-1, 1, 0],
    [0, 1, 0],
    [1, 1, 0],
    [-1, -1, 1],
    [0, -1, 1],
    [1, -1, 1],
    [-1, 0, 1],
    [0, 0, 1],
    [1, 0, 1],
    [-1, 1, 1],
    [0, 1, 1],
    [1, 1, 1],
];

impl<S: Scalar> World<'_, S> {
    /// Bin spheres into cells of edge ≥ 2·R_max + `reach` (mm); returns the grid dimensions.
    pub(crate) fn bin_spheres(&mut self, reach: S) -> Grid {
        let n = self.n_spheres as usize;
        let cap = self.spheres.len();
        if n == 0 {
            return Grid::default();
        }
        let sp = &self.spheres[..n];
        let mut lo = sp[0].position;
        let mut hi = sp[0].position;
        for s in sp {
            let p = s.position;
            lo = Vec3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
            hi = Vec3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
        }
        // Cell edge 2·R_max + reach plus a 2^-16 relative margin, so that rounding in the
        // binning products below can never put two spheres within reach two cells apart.
        let two_r = self.max_radius.mul_int(2) + reach;
        let edge = two_r + two_r / S::ONE.mul_int(65_536);
        let ext = hi - lo;
        // Integer cell counts at edge 2·R_max (floor(ext/edge) + 1, saturating).
        let dim = |e: S| -> i64 { (e / edge).floor_i64().clamp(0, 1 << 40) + 1 };
        let d0 = [dim(ext.x), dim(ext.y), dim(ext.z)];
        let budget = (self.cells.len() - 1) as i64;
        let total = |k: i64| -> i64 {
            let c = |d: i64| (d + k - 1) / k;
            c(d0[0]).saturating_mul(c(d0[1])).saturating_mul(c(d0[2]))
        };
        // Smallest merge factor k with total(k) ≤ budget: double until it fits, then bisect
        // (total is non-increasing in k). O(log k) evaluations for any spread.
        let mut k: i64 = 1;
        if total(1) > budget {
            let mut hi: i64 = 2;
            while total(hi) > budget {
                hi *= 2;
            }
            let mut lo = hi / 2; // total(lo) > budget
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if total(mid) > budget {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            k = hi;
        }
        let dims = [
            ((d0[0] + k - 1) / k) as u32,
            ((d0[1] + k - 1) / k) as u32,
            ((d0[2] + k - 1) / k) as u32,
        ];
        let ncell = dims[0] as usize * dims[1] as usize * dims[2] as usize;
        let (cell_of, rest) = self.index.split_at_mut(cap);
        let sorted = &mut rest[..cap];
        let cells = &mut self.cells[..ncell + 1];
        for c in cells.iter_mut() {
            *c = 0;
        }
        // One division per step; binning multiplies by the reciprocal of the (merged) edge.
        let inv = S::ONE / edge.mul_int(k.min(i32::MAX as i64) as i32);
        for (i, s) in sp.iter().enumerate() {
            let r = (s.position - lo).scale(inv);
            let cx = (r.x.floor_i64().clamp(0, dims[0] as i64 - 1)) as u32;
            let cy = (r.y.floor_i64().clamp(0, dims[1] as i64 - 1)) as u32;
            let cz = (r.z.floor_i64().clamp(0, dims[2] as i64 - 1)) as u32;
            let c = (cz * dims[1] + cy) * dims[0] + cx;
            cell_of[i] = c;
            cells[c as usize + 1] += 1;
        }
        for c in 0..ncell {
            cells[c + 1] += cells[c];
        }
        // Scatter in id order: cells[c] becomes the running insertion point, after which
        // cells[c] = end of cell c = start of cell c + 1; restore starts by shifting.
        for (i, &c) in cell_of[..n].iter().enumerate() {
            let at = &mut cells[c as usize];
            sorted[*at as usize] = i as u32;
            *at += 1;
        }
        for c in (1..=ncell).rev() {
            cells[c] = cells[c - 1];
        }
        cells[0] = 0;
        Grid { dims }
    }
}
