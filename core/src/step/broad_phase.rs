//! Broad phase: a dense cell grid over the spheres' bounding box, cell edge ≥ 2·R_max + skin,
//! used only when the neighbour list is rebuilt ([`super::neighbour_list`]); filled by
//! counting sort into caller-provided arrays. O(N) per rebuild, no allocation, deterministic:
//! spheres are binned in id order, and each cell keeps its spheres in id order.
//!
//! When the bounding box needs more cells than the caller gave, neighbouring cells are merged
//! (edge × k) until it fits: always correct, slower only for very spread-out particles.
//!
//! ```
//! use arachis_core::num::{Fx, Scalar, Vec3};
//! use arachis_core::body::Sphere;
//! use arachis_core::step::broad_phase::bin_spheres;
//! let mut spheres = [Sphere::<Fx>::default(); 3];
//! for (k, s) in spheres.iter_mut().enumerate() {
//!     s.radius = Fx::from_int(1);
//!     s.position = Vec3::new(Fx::from_int(10 * k as i32), Fx::ZERO, Fx::ZERO);
//! }
//! let (mut cell_of, mut sorted, mut cells) = ([0u32; 3], [0u32; 3], [0u32; 64]);
//! let grid = bin_spheres(&spheres, Fx::from_int(1), Fx::ZERO, &mut cell_of, &mut sorted, &mut cells);
//! assert_eq!(grid.dims[0], 10); // 20 mm of centres over cells of 2 mm (+ margin)
//! assert_eq!(sorted, [0, 1, 2]);
//! ```

use crate::body::Sphere;
use crate::num::{Scalar, Vec3};

/// Grid geometry of one rebuild.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Grid {
    /// Cells along x, y, z.
    pub dims: [u32; 3],
}

impl Grid {
    /// The (x, y, z) cell coordinates of cell index `c`.
    #[inline(always)]
    pub fn coords(&self, c: u32) -> [u32; 3] {
        let [dx, dy, _] = self.dims;
        [c % dx, (c / dx) % dy, c / (dx * dy)]
    }
}

/// Relative margin added to the cell edge, so that rounding in the binning products can
/// never put two spheres within reach two cells apart.
const EDGE_MARGIN_DIVISOR: i32 = 65_536;

/// Bin `spheres` into cells of edge ≥ 2·`max_radius` + `reach` (mm): `cell_of[i]` gets the
/// cell of sphere i, `sorted` the sphere ids ordered by cell (ids ascending within a cell),
/// and `cells[c]..cells[c + 1]` the range of cell c in `sorted`. Returns the grid.
pub fn bin_spheres<S: Scalar>(
    spheres: &[Sphere<S>],
    max_radius: S,
    reach: S,
    cell_of: &mut [u32],
    sorted: &mut [u32],
    cells: &mut [u32],
) -> Grid {
    let n = spheres.len();
    if n == 0 {
        return Grid::default();
    }
    let mut lo = spheres[0].position;
    let mut hi = spheres[0].position;
    for s in spheres {
        let p = s.position;
        lo = Vec3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
        hi = Vec3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
    }
    let two_r = max_radius.mul_int(2) + reach;
    let edge = two_r + two_r / S::ONE.mul_int(EDGE_MARGIN_DIVISOR);
    let ext = hi - lo;
    // Integer cell counts at edge 2·R_max (floor(ext/edge) + 1, saturating).
    let dim = |e: S| -> i64 { (e / edge).floor_i64().clamp(0, 1 << 40) + 1 };
    let d0 = [dim(ext.x), dim(ext.y), dim(ext.z)];
    let budget = (cells.len() - 1) as i64;
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
    let cells = &mut cells[..ncell + 1];
    cells.fill(0);
    // One division per rebuild; binning multiplies by the reciprocal of the (merged) edge.
    let inv = S::ONE / edge.mul_int(k.min(i32::MAX as i64) as i32);
    for (i, s) in spheres.iter().enumerate() {
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
