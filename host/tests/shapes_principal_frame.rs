//! Principal axes of a rotated (imported) box, and a filling moved into its principal
//! frame, where a DEM clump wants it.

use std::path::Path;

use arachis::shapes::*;

/// Box half-edges, mm (the shipped 10 × 6 × 4 mm box).
const HALF: [f64; 3] = [5.0, 3.0, 2.0];
/// Integration grid: voxels along the longest edge.
const RESOLUTION: usize = 200;
/// Stated tolerance for principal moments of a grid-integrated box tilted against the grid.
const MOMENT_TOL: f64 = 2e-3;
/// Stated tolerance for the principal axes' directions, |1 − |cos(angle)||.
const AXIS_TOL: f64 = 1e-4;

/// Rotation by 30° about z after 20° about x: columns are the rotated body axes.
fn rotation() -> [[f64; 3]; 3] {
    let (a, b) = (30f64.to_radians(), 20f64.to_radians());
    let rz = [
        [a.cos(), -a.sin(), 0.0],
        [a.sin(), a.cos(), 0.0],
        [0.0, 0.0, 1.0],
    ];
    let rx = [
        [1.0, 0.0, 0.0],
        [0.0, b.cos(), -b.sin()],
        [0.0, b.sin(), b.cos()],
    ];
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = (0..3).map(|k| rz[i][k] * rx[k][j]).sum();
        }
    }
    r
}

fn rotate(r: &[[f64; 3]; 3], p: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (0..3).map(|k| r[i][k] * p[k]).sum())
}

#[test]
fn a_tilted_box_has_the_box_moments_about_its_rotated_axes() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/shapes/box_10x6x4_ascii.stl");
    let flat = read_stl(&path).unwrap();
    let r = rotation();
    let tris: Vec<[[f64; 3]; 3]> = flat
        .triangles
        .iter()
        .map(|t| t.map(|i| rotate(&r, flat.vertices_mm[i])))
        .collect();
    let tilted = TriangleMesh::from_triangles(Path::new("tilted box"), &tris).unwrap();

    let grid = VoxelGrid::covering(&tilted.bounds_mm(), RESOLUTION, 0);
    let m = voxel_mass_properties(&grid, &tilted.voxelize(&grid), POD_DENSITY_KG_M3);
    // Box: I about body axis a = m (e_b² + e_c²)/12 with full edges e = 2·HALF.
    let mass = POD_DENSITY_KG_M3 * 240.0 * 1e-9;
    let e = HALF.map(|h| 2.0 * h * 1e-3);
    let exact = [
        mass * (e[1] * e[1] + e[2] * e[2]) / 12.0,
        mass * (e[0] * e[0] + e[2] * e[2]) / 12.0,
        mass * (e[0] * e[0] + e[1] * e[1]) / 12.0,
    ];
    for a in 0..3 {
        let rel = m.principal_inertia_kg_m2[a] / exact[a] - 1.0;
        let body_axis = [0, 1, 2].map(|i| r[i][a]);
        let cos: f64 = (0..3).map(|i| body_axis[i] * m.principal_axes[a][i]).sum();
        println!(
            "moment {a}: rel {rel:+.2e}, |cos| to the rotated body axis {:.8}",
            cos.abs()
        );
        assert!(rel.abs() < MOMENT_TOL);
        assert!(1.0 - cos.abs() < AXIS_TOL);
    }

    // A filling moved to the principal frame: centre of mass at 0, axes along x, y, z.
    let filling = fill_with_spheres(
        &tilted,
        &FillOptions {
            resolution: DEFAULT_FILL_RESOLUTION,
            target: FillTarget::SphereCount(30),
        },
    )
    .unwrap();
    let report = filling_report(&tilted, &filling, RESOLUTION, POD_DENSITY_KG_M3).unwrap();
    let local = filling.in_principal_frame(&report.filling);
    let bounds = local.bounds_mm().unwrap();
    let g = VoxelGrid::covering(&bounds, RESOLUTION, 0);
    let moved = voxel_mass_properties(&g, &voxelize_spheres(&g, &local), POD_DENSITY_KG_M3);
    println!(
        "filling in its principal frame: COM {:?} mm, axes {:?}",
        moved.centre_of_mass_mm, moved.principal_axes
    );
    for a in 0..3 {
        // Re-voxelizing moved spheres on a new grid: about one voxel (≈0.05 mm) of slack.
        assert!(moved.centre_of_mass_mm[a].abs() < 0.05);
        assert!(moved.principal_axes[a][a] > 0.999);
    }
}
