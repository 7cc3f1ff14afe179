//! STL import (ASCII and binary), the ray-parity inside test, filling of imported meshes,
//! and clear errors naming the file for unreadable, malformed and open meshes.

use std::path::{Path, PathBuf};

use arachis::shapes::*;

/// Integration grid for the mesh volumes: voxels along the longest edge.
const REPORT_RESOLUTION: usize = 160;
/// Stated tolerance of the grid volume of a closed mesh against its divergence-theorem
/// volume, relative.
const GRID_VOLUME_TOL: f64 = 1e-3;
/// Icosphere radius, mm.
const ICOSPHERE_RADIUS_MM: f64 = 5.0;

fn testdata(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/shapes")
        .join(name)
}

/// An icosphere: the icosahedron with each face split into 4, `levels` times, vertices
/// pushed onto the sphere of radius `r`; faces wound outward.
fn icosphere(r: f64, levels: usize) -> Vec<[[f64; 3]; 3]> {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let v = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let f = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let onto = |p: [f64; 3]| {
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        p.map(|x| x * r / n)
    };
    let mut tris: Vec<[[f64; 3]; 3]> = f.iter().map(|t| t.map(|i| onto(v[i]))).collect();
    for _ in 0..levels {
        let mid = |a: [f64; 3], b: [f64; 3]| onto([0, 1, 2].map(|k| 0.5 * (a[k] + b[k])));
        tris = tris
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    tris
}

fn fill_report(mesh: &TriangleMesh, coverage: f64) -> (SphereFilling, FillingReport) {
    let filling = fill_with_spheres(
        mesh,
        &FillOptions {
            resolution: DEFAULT_FILL_RESOLUTION,
            target: FillTarget::Coverage {
                fraction: coverage,
                max_spheres: 400,
            },
        },
    )
    .unwrap();
    let report = filling_report(mesh, &filling, REPORT_RESOLUTION, POD_DENSITY_KG_M3).unwrap();
    (filling, report)
}

#[test]
fn icosphere_imports_from_ascii_and_binary_and_fills() {
    let dir = tempfile::tempdir().unwrap();
    let tris = icosphere(ICOSPHERE_RADIUS_MM, 3);
    let ascii = dir.path().join("icosphere_ascii.stl");
    let binary = dir.path().join("icosphere_binary.stl");
    std::fs::write(&ascii, ascii_stl_text("icosphere", &tris)).unwrap();
    std::fs::write(&binary, binary_stl_bytes(&tris)).unwrap();
    for path in [&ascii, &binary] {
        let mesh = read_stl(path).unwrap();
        assert_eq!(mesh.triangles.len(), 20 * 4usize.pow(3));
        assert_eq!(mesh.vertices_mm.len(), 642); // V = F/2 + 2 for a closed genus-0 mesh
        let exact = mesh.enclosed_volume_mm3();
        let (_, report) = fill_report(&mesh, 0.99);
        let grid_rel = report.exact.volume_mm3 / exact - 1.0;
        println!(
            "{}: polyhedron V = {exact:.3} mm3 (ball {:.3}), grid V = {:.3} (rel {grid_rel:.2e}); \
             {} spheres: volume {:+.4}, COM offset/L {:.4}, inertia {:+.4} {:+.4} {:+.4}",
            path.file_name().unwrap().to_string_lossy(),
            4.0 / 3.0 * std::f64::consts::PI * ICOSPHERE_RADIUS_MM.powi(3),
            report.exact.volume_mm3,
            report.sphere_count,
            report.volume_rel_error,
            report.centre_of_mass_rel_error,
            report.inertia_rel_error[0],
            report.inertia_rel_error[1],
            report.inertia_rel_error[2],
        );
        assert!(grid_rel.abs() < GRID_VOLUME_TOL);
        // Stated tolerance for a 99%-coverage filling at 64 voxels per diameter: 1%
        // (measured −0.41%, one sphere: the icosphere is nearly a ball).
        assert!(report.volume_rel_error.abs() < 0.01);
    }
}

#[test]
fn shipped_ascii_box_imports_with_its_exact_volume() {
    let path = testdata("box_10x6x4_ascii.stl");
    let mesh = read_stl(&path).unwrap();
    assert_eq!(mesh.triangles.len(), 12);
    assert_eq!(mesh.enclosed_volume_mm3(), 240.0);
    let (filling, report) = fill_report(&mesh, 0.9);
    println!(
        "box 10 x 6 x 4 mm: grid V = {:.3} mm3; {} spheres cover {:.4} of the fill grid; \
         fine-grid volume error {:+.4}",
        report.exact.volume_mm3,
        report.sphere_count,
        filling.covered_fraction,
        report.volume_rel_error
    );
    assert!((report.exact.volume_mm3 / 240.0 - 1.0).abs() < GRID_VOLUME_TOL);
    // The fine grid sees the coverage the fill grid aimed at, within 2 percentage points
    // (sphere radii are estimated to about a fill voxel, 10/64 mm).
    assert!((report.volume_rel_error + (1.0 - filling.covered_fraction)).abs() < 0.02);
    // Binary round trip: the same welded mesh.
    let tris: Vec<[[f64; 3]; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| mesh.vertices_mm[i]))
        .collect();
    let again = parse_stl(Path::new("box.stl"), &binary_stl_bytes(&tris)).unwrap();
    assert_eq!(again, mesh);
}

#[test]
fn ray_parity_agrees_with_the_column_voxelizer_and_on_edges() {
    let mesh = read_stl(&testdata("box_10x6x4_ascii.stl")).unwrap();
    // Grid lines pass exactly through the box's faces, edges and face diagonals.
    let grid = VoxelGrid {
        min_mm: [-6.5, -4.5, -3.5],
        spacing_mm: 0.5,
        dims: [26, 18, 14],
    };
    let columns = mesh.voxelize(&grid);
    let mut inside = 0;
    for k in 0..14 {
        for j in 0..18 {
            for i in 0..26 {
                let p = grid.centre_mm(i, j, k);
                assert_eq!(mesh.contains_mm(p), columns[grid.index(i, j, k)], "{p:?}");
                inside += usize::from(columns[grid.index(i, j, k)]);
            }
        }
    }
    // Centres at −4.75…4.75 step 0.5 along x: points on the faces x = ±5 count on one
    // side only. Inside: x ∈ [−4.75, 4.75] (20), y ∈ [−2.75, 2.75] (12), z (8) = 1920.
    assert_eq!(inside, 20 * 12 * 8);
}

fn err_of(path: &Path) -> String {
    read_stl(path).unwrap_err().to_string()
}

#[test]
fn bad_stl_files_are_rejected_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, bytes: &[u8]| {
        let p = dir.path().join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    };
    let missing = dir.path().join("missing.stl");
    let e = err_of(&missing);
    assert!(
        e.contains("missing.stl") && e.contains("cannot read"),
        "{e}"
    );

    let good = std::fs::read_to_string(testdata("box_10x6x4_ascii.stl")).unwrap();
    let bad_number = write(
        "bad_number.stl",
        good.replacen("vertex -5 -3 -2", "vertex -5 abc -2", 1)
            .as_bytes(),
    );
    let e = err_of(&bad_number);
    assert!(
        e.contains("bad_number.stl:4:17") && e.contains("'abc'"),
        "{e}"
    );

    // Cut after line 20 (inside the third facet), and in the middle of a word.
    let head: String = good.lines().take(20).map(|l| format!("{l}\n")).collect();
    let truncated = write("truncated.stl", head.as_bytes());
    let e = err_of(&truncated);
    assert!(
        e.contains("truncated.stl") && e.contains("file ends"),
        "{e}"
    );
    let cut = write("cut.stl", &good.as_bytes()[..good.len() / 2]);
    let e = err_of(&cut);
    assert!(
        e.contains("cut.stl:43:3") && e.contains("found 'endfac'"),
        "{e}"
    );

    let wrong_word = write(
        "wrong_word.stl",
        good.replacen("outer loop", "outer lop", 1).as_bytes(),
    );
    let e = err_of(&wrong_word);
    assert!(
        e.contains("wrong_word.stl:3:11") && e.contains("expected 'loop'"),
        "{e}"
    );

    let e = err_of(&testdata("open_box_ascii.stl"));
    assert!(
        e.contains("open_box_ascii.stl") && e.contains("not a closed surface"),
        "{e}"
    );
    assert!(e.contains("3 edges"), "{e}");

    let tris = icosphere(ICOSPHERE_RADIUS_MM, 1);
    let mut bytes = binary_stl_bytes(&tris);
    bytes.truncate(bytes.len() - 10);
    let short = write("short.stl", &bytes);
    let e = err_of(&short);
    assert!(
        e.contains("short.stl") && e.contains("declares 80 triangles"),
        "{e}"
    );

    let mut bytes = binary_stl_bytes(&tris);
    let at = 84 + 50 * 5 + 12 + 4; // triangle 6, vertex 1, y
    bytes[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    let nan = write("nan.stl", &bytes);
    let e = err_of(&nan);
    assert!(
        e.contains("nan.stl") && e.contains(&format!("byte {at}")),
        "{e}"
    );
    assert!(e.contains("triangle 6 vertex 1"), "{e}");

    // A binary file whose header starts with "solid" but whose size is wrong.
    let mut bytes = binary_stl_bytes(&tris);
    bytes[..5].copy_from_slice(b"solid");
    bytes[84 + 13] = 0xFF; // not UTF-8
    bytes.push(0);
    let solid_binary = write("solid_binary.stl", &bytes);
    let e = err_of(&solid_binary);
    assert!(
        e.contains("solid_binary.stl")
            && e.contains("header declares 4084 bytes but the file has 4085"),
        "{e}"
    );

    // Written atomically, read back.
    let out = dir.path().join("written.stl");
    write_binary_stl(&out, &tris).unwrap();
    assert_eq!(read_stl(&out).unwrap().triangles.len(), 80);

    let empty = write("empty.stl", b"");
    let e = err_of(&empty);
    assert!(
        e.contains("empty.stl") && e.contains("fewer than the 84-byte"),
        "{e}"
    );

    let no_facets = write("no_facets.stl", b"solid nothing\nendsolid nothing\n");
    let e = err_of(&no_facets);
    assert!(
        e.contains("no_facets.stl") && e.contains("no triangle"),
        "{e}"
    );
}

/// Signed volume Σ v0·(v1 × v2)/6: positive when the triangles face outward.
fn signed_volume(tris: &[[[f64; 3]; 3]]) -> f64 {
    tris.iter()
        .map(|[a, b, c]| {
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum::<f64>()
        / 6.0
}

#[test]
fn exported_pod_stl_fills_like_the_analytic_pod() {
    let dir = tempfile::tempdir().unwrap();
    for kind in PodKind::ALL {
        let pod = PodShape::seed001_mean(kind);
        let tris = pod_triangles(&pod, 48, 96);
        assert!(signed_volume(&tris) > 0.0, "outward winding");
        let path = dir.path().join(format!("{}.stl", kind.name()));
        std::fs::write(&path, binary_stl_bytes(&tris)).unwrap();
        let mesh = read_stl(&path).unwrap();
        let analytic = pod.analytic_volume_mm3();
        let poly = mesh.enclosed_volume_mm3();
        let options = FillOptions {
            resolution: DEFAULT_FILL_RESOLUTION,
            target: FillTarget::SphereCount(15),
        };
        let from_mesh = fill_with_spheres(&mesh, &options).unwrap();
        let from_shape = fill_with_spheres(&pod, &options).unwrap();
        let mesh_report =
            filling_report(&mesh, &from_mesh, REPORT_RESOLUTION, POD_DENSITY_KG_M3).unwrap();
        let shape_report =
            filling_report(&pod, &from_shape, REPORT_RESOLUTION, POD_DENSITY_KG_M3).unwrap();
        let grid_rel = mesh_report.exact.volume_mm3 / poly - 1.0;
        println!(
            "{:>12}: analytic V = {analytic:.2}, polyhedron {poly:.2} ({:+.2e}), mesh grid {:.2} \
             ({grid_rel:+.2e}); 15 spheres: volume error mesh {:+.4}, analytic {:+.4}; \
             max inertia error mesh {:.4}, analytic {:.4}",
            kind.name(),
            poly / analytic - 1.0,
            mesh_report.exact.volume_mm3,
            mesh_report.volume_rel_error,
            shape_report.volume_rel_error,
            mesh_report.max_inertia_rel_error(),
            shape_report.max_inertia_rel_error()
        );
        // Ray parity through a non-convex mesh with a crease at the waist.
        assert!(grid_rel.abs() < GRID_VOLUME_TOL);
        // 48 rings × 96 sectors: the inscribed polyhedron is within 0.2% of the shape.
        assert!((poly / analytic - 1.0).abs() < 2e-3);
        // Filled the same way: errors within 1 percentage point of the analytic pod's.
        assert!((mesh_report.volume_rel_error - shape_report.volume_rel_error).abs() < 0.01);
        assert!(
            (mesh_report.max_inertia_rel_error() - shape_report.max_inertia_rel_error()).abs()
                < 0.015
        );
    }
}
