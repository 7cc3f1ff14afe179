//! Volume, mass, centre of mass and principal moments of inertia of a solid of uniform
//! density, by midpoint-rule integration over a voxel grid, and exactly for an ellipsoid.
//!
//! Each voxel whose centre is inside counts as a small cube of volume h³ at its centre,
//! carrying its own moment m h²/6 about every axis through its centre (a cube of edge h).
//! The inertia tensor about the centre of mass is I = ρ (tr(S) 1 − S) with
//! S = ∫ (p − c)(p − c)ᵀ dV; its eigenvalues (nalgebra's symmetric eigen-solver) are the
//! principal moments, reported in ascending order.
//!
//! ```
//! use arachis::shapes::{ellipsoid_mass_properties, POD_DENSITY_KG_M3};
//! let m = ellipsoid_mass_properties([5.0, 5.0, 5.0], POD_DENSITY_KG_M3);
//! // A 10 mm ball: V = 4/3·π·125 mm³.
//! assert!((m.volume_mm3 - 523.598_775_598).abs() < 1e-6);
//! ```

use std::f64::consts::PI;

use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use serde::Serialize;

use super::voxel_grid::VoxelGrid;

/// Density of pods at harvest (water content 36.72%), kg/m³ (seed 000 §3.1.1).
pub const POD_DENSITY_KG_M3: f64 = 582.36;

/// mm³ → m³.
const M3_PER_MM3: f64 = 1e-9;
/// mm⁵ (an integral of r² dV) → m⁵.
const M5_PER_MM5: f64 = 1e-15;

/// Mass properties of a uniform solid in its body frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MassProperties {
    /// Volume, mm³.
    pub volume_mm3: f64,
    /// Mass m = ρV, kg.
    pub mass_kg: f64,
    /// Centre of mass, mm.
    pub centre_of_mass_mm: [f64; 3],
    /// Principal moments of inertia about the centre of mass, kg·m², ascending.
    pub principal_inertia_kg_m2: [f64; 3],
    /// Unit principal axes in the body frame, one per moment (same order), forming a
    /// right-handed frame; for a symmetric pod, the body axes ordered by moment.
    pub principal_axes: [[f64; 3]; 3],
}

/// The frame's own axes (a sphere's principal axes, or a symmetric shape's).
pub const IDENTITY_AXES: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// Mass properties of the voxels flagged `inside` in `grid`, at density `density_kg_m3`.
pub fn voxel_mass_properties(
    grid: &VoxelGrid,
    inside: &[bool],
    density_kg_m3: f64,
) -> MassProperties {
    let [nx, ny, nz] = grid.dims;
    // Sums relative to the grid's centre keep the second moments free of cancellation.
    let origin = [0, 1, 2].map(|a| grid.min_mm[a] + 0.5 * grid.dims[a] as f64 * grid.spacing_mm);
    // Plain sums (not nalgebra products per voxel): this loop runs millions of times.
    let mut count = 0.0;
    let mut first = [0.0f64; 3];
    // xx, yy, zz, xy, xz, yz
    let mut second = [0.0f64; 6];
    for k in 0..nz {
        let z = grid.coord_mm(2, k) - origin[2];
        for j in 0..ny {
            let y = grid.coord_mm(1, j) - origin[1];
            let row = grid.index(0, j, k);
            for i in 0..nx {
                if inside[row + i] {
                    let x = grid.coord_mm(0, i) - origin[0];
                    count += 1.0;
                    first[0] += x;
                    first[1] += y;
                    first[2] += z;
                    second[0] += x * x;
                    second[1] += y * y;
                    second[2] += z * z;
                    second[3] += x * y;
                    second[4] += x * z;
                    second[5] += y * z;
                }
            }
        }
    }
    let first = Vector3::from(first);
    let [xx, yy, zz, xy, xz, yz] = second;
    let second = Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz);
    let h = grid.spacing_mm;
    let dv = grid.voxel_volume_mm3();
    let volume_mm3 = count * dv;
    if count == 0.0 {
        return MassProperties {
            volume_mm3: 0.0,
            mass_kg: 0.0,
            centre_of_mass_mm: origin,
            principal_inertia_kg_m2: [0.0; 3],
            principal_axes: IDENTITY_AXES,
        };
    }
    let mean = first / count;
    // S about the centre of mass, plus each cube's own h²/12 per axis.
    let s = (second / count - mean * mean.transpose()) * volume_mm3
        + Matrix3::identity() * (volume_mm3 * h * h / 12.0);
    let com = [0, 1, 2].map(|a| mean[a] + origin[a]);
    from_second_moment(volume_mm3, com, s, density_kg_m3)
}

/// Mass properties from volume (mm³), centre (mm) and S = ∫(p−c)(p−c)ᵀ dV (mm⁵).
fn from_second_moment(
    volume_mm3: f64,
    centre_of_mass_mm: [f64; 3],
    s_mm5: Matrix3<f64>,
    density_kg_m3: f64,
) -> MassProperties {
    let inertia = (Matrix3::identity() * s_mm5.trace() - s_mm5) * (density_kg_m3 * M5_PER_MM5);
    let eigen = SymmetricEigen::new(inertia);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    // Axis signs fixed so results are reproducible: the largest component of each of the
    // first two axes is positive, and the third completes a right-handed frame.
    let axis = |n: usize| {
        let v: Vector3<f64> = eigen.eigenvectors.column(order[n]).into_owned();
        let big = v.iamax();
        if v[big] < 0.0 {
            -v
        } else {
            v
        }
    };
    let (e1, e2) = (axis(0), axis(1));
    let e3 = e1.cross(&e2);
    MassProperties {
        volume_mm3,
        mass_kg: density_kg_m3 * volume_mm3 * M3_PER_MM3,
        centre_of_mass_mm,
        principal_inertia_kg_m2: order.map(|i| eigen.eigenvalues[i]),
        principal_axes: [e1, e2, e3].map(|e| [e[0], e[1], e[2]]),
    }
}

/// Exact mass properties of the ellipsoid with semi-axes `semi_axes_mm` (a, b, c) centred
/// at the origin: V = 4/3·π·abc, S = diag(a², b², c²)·V/5, so I_x = m(b² + c²)/5 etc.
pub fn ellipsoid_mass_properties(semi_axes_mm: [f64; 3], density_kg_m3: f64) -> MassProperties {
    let [a, b, c] = semi_axes_mm;
    let volume_mm3 = 4.0 / 3.0 * PI * a * b * c;
    let s = Matrix3::from_diagonal(&Vector3::new(a * a, b * b, c * c)) * (volume_mm3 / 5.0);
    from_second_moment(volume_mm3, [0.0; 3], s, density_kg_m3)
}
