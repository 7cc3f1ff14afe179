//! How well a sphere filling represents its solid: volume, mass, centre of mass and
//! principal inertia of the union of spheres against the solid's, as relative errors.
//!
//! Both are integrated on the same fine voxel grid (midpoint rule, see
//! [`super::mass_properties`]); the union of overlapping spheres is a voxel set, so overlaps
//! count once. The centre-of-mass error is the offset between the two centres divided by
//! the solid's longest bounding-box edge (the exact centre is often 0, so a plain relative
//! error would be undefined).

use serde::Serialize;

use super::error::ShapeError;
use super::mass_properties::{voxel_mass_properties, MassProperties};
use super::solid::Solid;
use super::sphere_fill::{SphereFilling, MAX_RESOLUTION, MIN_FILL_RESOLUTION};
use super::voxel_grid::VoxelGrid;

/// Default voxels along the solid's longest edge for the report's integration.
pub const DEFAULT_REPORT_RESOLUTION: usize = 160;

/// The filling's mass properties against the solid's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FillingReport {
    /// Spheres in the filling.
    pub sphere_count: usize,
    /// Voxel edge of the integration grid, mm.
    pub grid_spacing_mm: f64,
    /// The solid's mass properties.
    pub exact: MassProperties,
    /// The union of spheres' mass properties.
    pub filling: MassProperties,
    /// (V_fill − V_exact) / V_exact.
    pub volume_rel_error: f64,
    /// (m_fill − m_exact) / m_exact (equal to the volume error at uniform density).
    pub mass_rel_error: f64,
    /// |c_fill − c_exact| / (longest bounding-box edge of the solid).
    pub centre_of_mass_rel_error: f64,
    /// (I_fill − I_exact) / I_exact for each principal moment, ascending order.
    pub inertia_rel_error: [f64; 3],
}

impl FillingReport {
    /// The largest |relative error| of the three principal moments.
    pub fn max_inertia_rel_error(&self) -> f64 {
        self.inertia_rel_error
            .iter()
            .fold(0.0, |m, e| m.max(e.abs()))
    }
}

impl std::fmt::Display for FillingReport {
    /// A Markdown table: the solid, the filling and the relative error of each quantity.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (e, s) = (&self.exact, &self.filling);
        writeln!(
            f,
            "{} spheres, integration grid {:.4} mm",
            self.sphere_count, self.grid_spacing_mm
        )?;
        writeln!(f, "| quantity | solid | filling | relative error |")?;
        writeln!(f, "|---|---|---|---|")?;
        writeln!(
            f,
            "| volume (mm³) | {:.3} | {:.3} | {:+.4} |",
            e.volume_mm3, s.volume_mm3, self.volume_rel_error
        )?;
        writeln!(
            f,
            "| mass (g) | {:.4} | {:.4} | {:+.4} |",
            e.mass_kg * 1e3,
            s.mass_kg * 1e3,
            self.mass_rel_error
        )?;
        let c = |m: &MassProperties| {
            let [x, y, z] = m.centre_of_mass_mm;
            format!("({x:.3}, {y:.3}, {z:.3})")
        };
        writeln!(
            f,
            "| centre of mass (mm) | {} | {} | {:.4} of the length |",
            c(e),
            c(s),
            self.centre_of_mass_rel_error
        )?;
        for a in 0..3 {
            writeln!(
                f,
                "| principal inertia {} (kg·m²) | {:.4e} | {:.4e} | {:+.4} |",
                a + 1,
                e.principal_inertia_kg_m2[a],
                s.principal_inertia_kg_m2[a],
                self.inertia_rel_error[a]
            )?;
        }
        Ok(())
    }
}

/// Compares `filling` with `solid` on a grid of `resolution` voxels along the solid's
/// longest edge (4..=1000), at density `density_kg_m3` (kg/m³, finite, > 0).
pub fn filling_report(
    solid: &dyn Solid,
    filling: &SphereFilling,
    resolution: usize,
    density_kg_m3: f64,
) -> Result<FillingReport, ShapeError> {
    if !(MIN_FILL_RESOLUTION..=MAX_RESOLUTION).contains(&resolution) {
        return Err(ShapeError::InvalidParameter {
            name: "report resolution (voxels along the longest edge)",
            value: resolution as f64,
            reason: "must lie in 4..=1000",
        });
    }
    if !(density_kg_m3.is_finite() && density_kg_m3 > 0.0) {
        return Err(ShapeError::InvalidParameter {
            name: "density (kg/m³)",
            value: density_kg_m3,
            reason: "must be a finite number > 0",
        });
    }
    let bounds = solid.bounds_mm();
    let longest = bounds.extent_mm().iter().cloned().fold(0.0_f64, f64::max);
    let all = filling.bounds_mm().map_or(bounds, |b| b.union(&bounds));
    let grid = VoxelGrid::with_spacing(&all, longest / resolution.max(1) as f64, 0);
    let exact = voxel_mass_properties(&grid, &solid.voxelize(&grid), density_kg_m3);
    let union = voxelize_spheres(&grid, filling);
    let fill = voxel_mass_properties(&grid, &union, density_kg_m3);
    let rel = |f: f64, e: f64| (f - e) / e;
    let offset: f64 = (0..3)
        .map(|a| (fill.centre_of_mass_mm[a] - exact.centre_of_mass_mm[a]).powi(2))
        .sum::<f64>()
        .sqrt();
    Ok(FillingReport {
        sphere_count: filling.spheres.len(),
        grid_spacing_mm: grid.spacing_mm,
        exact,
        filling: fill,
        volume_rel_error: rel(fill.volume_mm3, exact.volume_mm3),
        mass_rel_error: rel(fill.mass_kg, exact.mass_kg),
        centre_of_mass_rel_error: offset / longest,
        inertia_rel_error: [0, 1, 2].map(|a| {
            rel(
                fill.principal_inertia_kg_m2[a],
                exact.principal_inertia_kg_m2[a],
            )
        }),
    })
}

/// Inside flags of the union of the filling's spheres on `grid`.
pub fn voxelize_spheres(grid: &VoxelGrid, filling: &SphereFilling) -> Vec<bool> {
    let mut inside = vec![false; grid.len()];
    for s in &filling.spheres {
        let (c, r) = (s.centre_mm, s.radius_mm);
        let r2 = r * r;
        for k in grid.index_range(2, c[2] - r, c[2] + r) {
            let dz2 = (grid.coord_mm(2, k) - c[2]).powi(2);
            for j in grid.index_range(1, c[1] - r, c[1] + r) {
                let dyz2 = dz2 + (grid.coord_mm(1, j) - c[1]).powi(2);
                for i in grid.index_range(0, c[0] - r, c[0] + r) {
                    if dyz2 + (grid.coord_mm(0, i) - c[0]).powi(2) <= r2 {
                        inside[grid.index(i, j, k)] = true;
                    }
                }
            }
        }
    }
    inside
}
