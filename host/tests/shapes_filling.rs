//! Sphere fillings of the three pod shapes: errors fall as spheres are added, the seed 001
//! pod's mass against seed 000's 100-pod mass, determinism, CSV and SVG output.

use arachis::shapes::*;

/// Fill grid: voxels along the pod's length (h = 34.27/64 = 0.535 mm).
const FILL_RESOLUTION: usize = 64;
/// Report grid: voxels along the pod's length (h = 0.214 mm).
const REPORT_RESOLUTION: usize = 160;
/// Seed 000 §2.2.1: "The weight of one hundred pods is 227.7 g".
const HUNDRED_POD_MASS_G: f64 = 227.7;
/// Sphere counts of the convergence test.
const COUNTS: [usize; 4] = [1, 3, 7, 15];

fn fill(solid: &dyn Solid, target: FillTarget) -> SphereFilling {
    fill_with_spheres(
        solid,
        &FillOptions {
            resolution: FILL_RESOLUTION,
            target,
        },
    )
    .unwrap()
}

/// Measured (fill grid 64, report grid 160), relative errors of the filling:
///
/// | shape | spheres | volume | COM offset / L | inertia (ascending moments) |
/// |---|---|---|---|---|
/// | normal | 1 | −0.626 | 0.188 | −0.686 −0.886 −0.892 |
/// | normal | 3 | −0.222 | 0.022 | −0.348 −0.262 −0.300 |
/// | normal | 7 | −0.111 | 0.004 | −0.202 −0.135 −0.164 |
/// | normal | 15 | −0.033 | 0.001 | −0.047 −0.056 −0.057 |
/// | cocoon | 1, 3, 7, 15 | −0.626, −0.231, −0.116, −0.041 | 0.125, 0.026, 0.003, 0.004 | max 0.885, 0.366, 0.196, 0.072 |
/// | single-grain | 1, 3, 7, 15 | −0.582, −0.246, −0.142, −0.052 | 0, 0, 0.010, 0 | max 0.857, 0.392, 0.255, 0.096 |
///
/// Volume and inertia errors fall strictly (asserted). The centre-of-mass offset does not
/// always: an odd sphere count on a symmetric pod leaves one sphere unpaired (cocoon 7 → 15,
/// single-grain 3 → 7), so it is printed, not asserted.
#[test]
fn filling_errors_fall_as_the_sphere_count_rises() {
    for kind in PodKind::ALL {
        let pod = PodShape::seed001_mean(kind);
        let reports: Vec<FillingReport> = COUNTS
            .iter()
            .map(|&n| {
                let f = fill(&pod, FillTarget::SphereCount(n));
                assert_eq!(f.spheres.len(), n);
                filling_report(&pod, &f, REPORT_RESOLUTION, POD_DENSITY_KG_M3).unwrap()
            })
            .collect();
        for (n, r) in COUNTS.iter().zip(&reports) {
            println!(
                "{:>12} {n:>2} spheres: volume {:+.4}, COM offset/L {:.4}, inertia {:+.4} {:+.4} {:+.4}",
                kind.name(),
                r.volume_rel_error,
                r.centre_of_mass_rel_error,
                r.inertia_rel_error[0],
                r.inertia_rel_error[1],
                r.inertia_rel_error[2]
            );
        }
        for pair in reports.windows(2) {
            assert!(pair[1].volume_rel_error.abs() < pair[0].volume_rel_error.abs());
            assert!(pair[1].max_inertia_rel_error() < pair[0].max_inertia_rel_error());
        }
        // Stated targets for 15 spheres: volume within 6%, each principal moment within 10%.
        let last = &reports[COUNTS.len() - 1];
        assert!(last.volume_rel_error.abs() < 0.06 && last.max_inertia_rel_error() < 0.10);
    }
}

/// Measured at 95% coverage: normal 13 spheres, solid 3.374 g, filling 3.231 g (+48.2% and
/// +41.9% against 2.277 g); cocoon 15 spheres, 3.370 g, 3.231 g (+48.0%, +41.9%);
/// single-grain 17 spheres, 3.012 g, 2.876 g (+32.3%, +26.3%).
#[test]
fn seed001_pod_mass_against_the_hundred_pod_mass() {
    let measured_g = HUNDRED_POD_MASS_G / 100.0;
    for kind in PodKind::ALL {
        let pod = PodShape::seed001_mean(kind);
        let f = fill(
            &pod,
            FillTarget::Coverage {
                fraction: 0.95,
                max_spheres: 400,
            },
        );
        let r = filling_report(&pod, &f, REPORT_RESOLUTION, POD_DENSITY_KG_M3).unwrap();
        let analytic_g = POD_DENSITY_KG_M3 * pod.analytic_volume_mm3() * 1e-6;
        let exact_g = r.exact.mass_kg * 1e3;
        let fill_g = r.filling.mass_kg * 1e3;
        println!(
            "{:>12}: {} spheres, solid {exact_g:.3} g (closed form {analytic_g:.3} g), filling \
             {fill_g:.3} g; measured 2.277 g/pod: solid {:+.1}%, filling {:+.1}%",
            kind.name(),
            f.spheres.len(),
            100.0 * (exact_g / measured_g - 1.0),
            100.0 * (fill_g / measured_g - 1.0)
        );
        // The grid mass is ρV of the closed-form volume (grid tolerance 1e-3).
        assert!((exact_g / analytic_g - 1.0).abs() < 1e-3);
        // The solid pod of mean dimensions is heavier than the mean measured pod: measured
        // 2.277 g at 582.36 kg/m³ is 3910 mm³, 0.396 of the 34.27 × 18.29 × 15.76 mm box,
        // while an ellipsoid fills π/6 = 0.524 of it (+32%) and our two-lobe shapes more
        // (+48%). Reasons: the dimensions (seed 001, Huayu varieties, 2025) and the mass
        // (seed 000, Yuhua 18, 2024) come from different pods; the mean of L·W·H exceeds
        // the product of the means; real pods taper to a beak. Not a fault of the filling.
        assert!(exact_g > measured_g && fill_g > measured_g);
    }
}

#[test]
fn filling_is_deterministic_and_written_as_csv_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let mut panels_data = Vec::new();
    for kind in PodKind::ALL {
        let pod = PodShape::seed001_mean(kind);
        let a = fill(&pod, FillTarget::SphereCount(15));
        let b = fill(&pod, FillTarget::SphereCount(15));
        assert_eq!(filling_csv(&a), filling_csv(&b));
        let path = dir.path().join(format!("{}.csv", kind.name()));
        write_filling_csv(&path, &a).unwrap();
        assert_eq!(read_filling_csv(&path).unwrap(), a.spheres);
        panels_data.push((pod, a, format!("{}, 15 spheres", kind.name())));
    }
    let panels: Vec<PicturePanel> = panels_data
        .iter()
        .map(|(pod, f, label)| PicturePanel {
            label,
            filling: f,
            outline: Some(pod),
        })
        .collect();
    let svg_path = dir.path().join("fillings.svg");
    write_fillings_svg(&svg_path, &panels).unwrap();
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(svg.starts_with("<svg"));
    // Each sphere drawn twice (fill, edge) in two views: 3 shapes × 15 × 4 circles.
    assert_eq!(svg.matches("<circle").count(), 3 * 15 * 4);
    assert!(svg.contains("cocoon, 15 spheres"));
}

#[test]
fn higher_smoothness_takes_more_spheres_and_errs_less() {
    let pod = PodShape::seed001_mean(PodKind::Normal);
    let mut last: Option<(usize, f64)> = None;
    for fraction in [0.8, 0.9, 0.95, 0.98] {
        let f = fill(
            &pod,
            FillTarget::Coverage {
                fraction,
                max_spheres: 1000,
            },
        );
        assert!(f.covered_fraction >= fraction);
        let r = filling_report(&pod, &f, REPORT_RESOLUTION, POD_DENSITY_KG_M3).unwrap();
        println!("coverage {fraction}: {} spheres\n{r}", f.spheres.len());
        let json = serde_json::to_value(r).unwrap();
        assert_eq!(json["volume_rel_error"].as_f64(), Some(r.volume_rel_error));
        if let Some((n, err)) = last {
            assert!(f.spheres.len() > n && r.volume_rel_error.abs() < err);
        }
        last = Some((f.spheres.len(), r.volume_rel_error.abs()));
    }
}

#[test]
fn svg_into_a_missing_directory_fails_without_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let pod = PodShape::seed001_mean(PodKind::Cocoon);
    let f = fill(&pod, FillTarget::SphereCount(3));
    let path = dir.path().join("no_such_dir").join("fillings.svg");
    let panel = PicturePanel {
        label: "cocoon",
        filling: &f,
        outline: Some(&pod),
    };
    assert!(write_fillings_svg(&path, &[panel]).is_err());
    assert!(!path.exists());
}

#[test]
fn bad_fill_options_are_rejected() {
    let pod = PodShape::seed001_mean(PodKind::Normal);
    let bad = |resolution, target| fill_with_spheres(&pod, &FillOptions { resolution, target });
    assert!(bad(2, FillTarget::SphereCount(3)).is_err());
    assert!(bad(32, FillTarget::SphereCount(0)).is_err());
    let coverage = |fraction| FillTarget::Coverage {
        fraction,
        max_spheres: 10,
    };
    assert!(bad(32, coverage(0.0)).is_err());
    assert!(bad(32, coverage(1.5)).is_err());
    assert!(bad(32, coverage(f64::NAN)).is_err());
    assert!(bad(1001, FillTarget::SphereCount(3)).is_err());
    let f = bad(32, FillTarget::SphereCount(3)).unwrap();
    assert!(filling_report(&pod, &f, 3, POD_DENSITY_KG_M3).is_err());
    assert!(filling_report(&pod, &f, usize::MAX, POD_DENSITY_KG_M3).is_err());
    let e = filling_report(&pod, &f, 64, -1.0).unwrap_err().to_string();
    assert!(e.contains("density (kg/m³)"), "{e}");
}
