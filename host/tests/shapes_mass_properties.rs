//! The grid integrator against exact formulas: the ellipsoid (V = 4/3·π·abc,
//! I_x = m(b² + c²)/5) and the two-lobe pod volume V = 2πabc(2/3 + s − s³/3).

use arachis::shapes::*;

/// Integration grid: voxels along the pod's length (h = 34.27/160 = 0.214 mm).
const RESOLUTION: usize = 160;
/// Stated tolerance of the grid integrator at this resolution, relative.
const VOLUME_TOL: f64 = 1e-3;
/// Stated tolerance for the principal moments, relative.
const INERTIA_TOL: f64 = 2e-3;

fn grid_props(solid: &dyn Solid, resolution: usize) -> MassProperties {
    let grid = VoxelGrid::covering(&solid.bounds_mm(), resolution, 0);
    voxel_mass_properties(&grid, &solid.voxelize(&grid), POD_DENSITY_KG_M3)
}

#[test]
fn ellipsoid_grid_integration_matches_the_exact_formulas() {
    let pod = PodShape::seed001_mean(PodKind::SingleGrain);
    let exact =
        ellipsoid_mass_properties([18.29 / 2.0, 15.76 / 2.0, 34.27 / 2.0], POD_DENSITY_KG_M3);
    let grid = grid_props(&pod, RESOLUTION);
    let rel = |a: f64, b: f64| (a - b) / b;
    let dv = rel(grid.volume_mm3, exact.volume_mm3);
    let di = [0, 1, 2].map(|a| {
        rel(
            grid.principal_inertia_kg_m2[a],
            exact.principal_inertia_kg_m2[a],
        )
    });
    println!(
        "ellipsoid 34.27 x 18.29 x 15.76 mm: exact V = {:.3} mm3, grid V = {:.3} mm3 (rel {dv:.2e}); \
         exact I = {:?} kg m2, grid I = {:?} (rel {:.2e} {:.2e} {:.2e}); grid COM = {:?} mm",
        exact.volume_mm3,
        grid.volume_mm3,
        exact.principal_inertia_kg_m2,
        grid.principal_inertia_kg_m2,
        di[0],
        di[1],
        di[2],
        grid.centre_of_mass_mm
    );
    assert!(dv.abs() < VOLUME_TOL, "volume error {dv}");
    for e in di {
        assert!(e.abs() < INERTIA_TOL, "inertia error {e}");
    }
    // The exact centre is 0; voxel centres computed as min + (k + ½)h are symmetric only to
    // rounding, so a boundary voxel may fall in on one side and out on the other: allow
    // 1e-3 mm (h/200).
    assert!(grid.centre_of_mass_mm.iter().all(|c| c.abs() < 1e-3));
    // Mass = ρV exactly: 582.36 kg/m³ × V.
    assert!((exact.mass_kg - 582.36e-9 * exact.volume_mm3).abs() < 1e-15);
}

#[test]
fn two_lobe_pod_volume_matches_its_closed_form() {
    for kind in PodKind::ALL {
        let pod = PodShape::seed001_mean(kind);
        let analytic = pod.analytic_volume_mm3();
        let grid = grid_props(&pod, RESOLUTION).volume_mm3;
        let rel = (grid - analytic) / analytic;
        println!(
            "{}: waist ratio {}, analytic V = {analytic:.3} mm3, grid V = {grid:.3} mm3, rel {rel:.2e}",
            kind.name(),
            pod.waist_ratio()
        );
        assert!(rel.abs() < VOLUME_TOL);
    }
}

#[test]
fn grid_integration_converges_as_the_grid_refines() {
    let pod = PodShape::seed001_mean(PodKind::SingleGrain);
    let exact = pod.analytic_volume_mm3();
    let errors: Vec<f64> = [20, 40, 80, 160]
        .iter()
        .map(|&r| ((grid_props(&pod, r).volume_mm3 - exact) / exact).abs())
        .collect();
    println!("ellipsoid |volume error| at 20, 40, 80, 160 voxels per length: {errors:.6?}");
    assert!(errors[3] < errors[0]);
}

#[test]
fn bad_dimensions_are_rejected() {
    assert!(PodShape::new(PodKind::Normal, 0.0, 18.29, 15.76).is_err());
    assert!(PodShape::new(PodKind::Normal, 34.27, f64::NAN, 15.76).is_err());
    assert!(PodShape::new(PodKind::Normal, 34.27, 18.29, -1.0).is_err());
    let pod = PodShape::new(PodKind::Cocoon, 34.27, 18.29, 15.76).unwrap();
    assert!(pod.with_waist_ratio(0.0).is_err());
    assert!(pod.with_waist_ratio(1.01).is_err());
    let err = PodShape::new(PodKind::Normal, 34.27, 0.0, 15.76).unwrap_err();
    assert!(err.to_string().contains("width W (mm)"), "{err}");
}
