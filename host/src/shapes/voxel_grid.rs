//! Regular grids of cubic voxels covering a solid, used both to integrate mass properties
//! (midpoint rule: each voxel is counted when its centre is inside) and to place spheres.
//!
//! Voxel (i, j, k) has its centre at `min_mm + (index + 0.5)·spacing_mm`; its linear index
//! is `i + nx·(j + ny·k)`. Grids are centred on the box they cover, so a solid symmetric
//! about the box centre gets a symmetric set of voxel centres.

/// An axis-aligned box, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Lower corner, mm.
    pub min_mm: [f64; 3],
    /// Upper corner, mm.
    pub max_mm: [f64; 3],
}

impl Aabb {
    /// Edge lengths, mm.
    pub fn extent_mm(&self) -> [f64; 3] {
        [0, 1, 2].map(|a| self.max_mm[a] - self.min_mm[a])
    }

    /// Centre, mm.
    pub fn centre_mm(&self) -> [f64; 3] {
        [0, 1, 2].map(|a| 0.5 * (self.max_mm[a] + self.min_mm[a]))
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min_mm: [0, 1, 2].map(|a| self.min_mm[a].min(other.min_mm[a])),
            max_mm: [0, 1, 2].map(|a| self.max_mm[a].max(other.max_mm[a])),
        }
    }
}

/// A regular grid of cubic voxels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VoxelGrid {
    /// Lower corner of voxel (0, 0, 0), mm.
    pub min_mm: [f64; 3],
    /// Voxel edge length, mm.
    pub spacing_mm: f64,
    /// Voxels along x, y, z.
    pub dims: [usize; 3],
}

impl VoxelGrid {
    /// A grid of `resolution` voxels along the longest edge of `bounds`, centred on it and
    /// widened by `margin` voxels on every side (a margin of 1 guarantees that the outer
    /// layer lies outside the solid, which the distance transform needs).
    pub fn covering(bounds: &Aabb, resolution: usize, margin: usize) -> Self {
        let longest = bounds.extent_mm().iter().cloned().fold(0.0_f64, f64::max);
        Self::with_spacing(bounds, longest / resolution.max(1) as f64, margin)
    }

    /// A grid of voxels of edge `spacing_mm` centred on `bounds`, covering it, widened by
    /// `margin` voxels on every side. The voxel count along each axis is odd, so a voxel
    /// centre sits at the box centre (a symmetric pod then gets a centred sphere).
    pub fn with_spacing(bounds: &Aabb, spacing_mm: f64, margin: usize) -> Self {
        let centre = bounds.centre_mm();
        let dims = bounds.extent_mm().map(|e| {
            let n = (e / spacing_mm).ceil().max(1.0) as usize;
            (n | 1) + 2 * margin
        });
        let min_mm = [0, 1, 2].map(|a| centre[a] - 0.5 * dims[a] as f64 * spacing_mm);
        VoxelGrid {
            min_mm,
            spacing_mm,
            dims,
        }
    }

    /// Number of voxels.
    pub fn len(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    /// True when the grid has no voxel.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Linear index of voxel (i, j, k).
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.dims[0] * (j + self.dims[1] * k)
    }

    /// Centre coordinate of voxel number `index` along axis `axis`, mm.
    pub fn coord_mm(&self, axis: usize, index: usize) -> f64 {
        self.min_mm[axis] + (index as f64 + 0.5) * self.spacing_mm
    }

    /// Centre of voxel (i, j, k), mm.
    pub fn centre_mm(&self, i: usize, j: usize, k: usize) -> [f64; 3] {
        [
            self.coord_mm(0, i),
            self.coord_mm(1, j),
            self.coord_mm(2, k),
        ]
    }

    /// Volume of one voxel, mm³.
    pub fn voxel_volume_mm3(&self) -> f64 {
        self.spacing_mm.powi(3)
    }

    /// The range of voxel indices along `axis` whose centres may lie within
    /// `[lo_mm, hi_mm]` (clamped to the grid; empty when outside it).
    pub fn index_range(&self, axis: usize, lo_mm: f64, hi_mm: f64) -> std::ops::Range<usize> {
        let to_index = |x: f64| (x - self.min_mm[axis]) / self.spacing_mm - 0.5;
        let lo = to_index(lo_mm).ceil().max(0.0);
        let hi = (to_index(hi_mm).floor() + 1.0).min(self.dims[axis] as f64);
        if hi <= lo {
            0..0
        } else {
            lo as usize..hi as usize
        }
    }
}
