//! Property tests of the mesh inside test (ray parity along +z) on the shipped box, whose
//! interior is known exactly: random points, including points snapped onto the box's
//! faces, edges and diagonals (where the tie rule must count exactly one triangle), and the
//! column voxelizer against the point test on randomly placed grids.

use std::path::Path;

use arachis::shapes::*;
use proptest::prelude::*;

fn box_mesh() -> TriangleMesh {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/shapes/box_10x6x4_ascii.stl");
    read_stl(&path).unwrap()
}

/// Half-edges of the shipped box, mm.
const HALF: [f64; 3] = [5.0, 3.0, 2.0];

proptest! {
    #[test]
    fn points_off_the_surface_are_classified_exactly(
        x in -7.0..7.0f64, y in -5.0..5.0f64, z in -4.0..4.0f64
    ) {
        let p = [x, y, z];
        let inside = (0..3).all(|a| p[a].abs() < HALF[a]);
        let outside = (0..3).any(|a| p[a].abs() > HALF[a]);
        prop_assume!(inside || outside);
        prop_assert_eq!(box_mesh().contains_mm(p), inside);
    }

    #[test]
    fn rays_through_edges_and_diagonals_count_once(
        i in -20i32..=20, j in -12i32..=12, z in -1.9..1.9f64
    ) {
        // x, y on a 0.25 mm lattice: many rays hit the face diagonals (x/5 = y/3 lines are
        // hit at lattice points like (5, 3)) and the side faces' edges exactly.
        let (x, y) = (0.25 * f64::from(i), 0.25 * f64::from(j));
        let mesh = box_mesh();
        let got = mesh.contains_mm([x, y, z]);
        if x.abs() < HALF[0] && y.abs() < HALF[1] {
            prop_assert!(got, "interior point ({x}, {y}, {z}) missed");
        } else if x.abs() > HALF[0] || y.abs() > HALF[1] {
            prop_assert!(!got, "exterior point ({x}, {y}, {z}) counted");
        }
    }

    #[test]
    fn column_voxelizer_matches_the_point_test(
        ox in -0.5..0.5f64, oy in -0.5..0.5f64, oz in -0.5..0.5f64, h in 0.2..1.0f64
    ) {
        let mesh = box_mesh();
        let grid = VoxelGrid { min_mm: [-6.0 + ox, -4.0 + oy, -3.0 + oz], spacing_mm: h,
            dims: [(12.0 / h) as usize + 1, (8.0 / h) as usize + 1, (6.0 / h) as usize + 1] };
        let columns = mesh.voxelize(&grid);
        for k in 0..grid.dims[2] {
            for j in 0..grid.dims[1] {
                for i in 0..grid.dims[0] {
                    let p = grid.centre_mm(i, j, k);
                    prop_assert_eq!(columns[grid.index(i, j, k)], mesh.contains_mm(p));
                }
            }
        }
    }
}
