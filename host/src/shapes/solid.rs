//! The implicit-solid interface shared by the analytic pod shapes and imported STL meshes:
//! a bounding box and an inside test, in the body frame, mm.

use super::voxel_grid::{Aabb, VoxelGrid};

/// A closed solid known by its inside test. Coordinates are in the body frame, mm.
pub trait Solid {
    /// A box holding the whole solid, mm.
    fn bounds_mm(&self) -> Aabb;

    /// True when the point `p_mm` lies inside the solid.
    fn contains_mm(&self, p_mm: [f64; 3]) -> bool;

    /// Inside flags of every voxel centre of `grid`, indexed by [`VoxelGrid::index`].
    /// The default asks [`Solid::contains_mm`] at each centre; meshes override it with a
    /// faster column-by-column ray test.
    fn voxelize(&self, grid: &VoxelGrid) -> Vec<bool> {
        let [nx, ny, nz] = grid.dims;
        let mut inside = Vec::with_capacity(grid.len());
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    inside.push(self.contains_mm(grid.centre_mm(i, j, k)));
                }
            }
        }
        inside
    }
}
