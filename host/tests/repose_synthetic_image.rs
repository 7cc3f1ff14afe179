//! Must-show (issue 4): "The photo extraction recovers the slope of a synthetic pile image
//! within 0.5°". Piles of known flank angles are drawn (anti-aliased or jagged, with grey
//! noise, rounded apex, flat top, light or dark), written as PNG or JPEG, and measured by
//! `measure_photo` exactly as a photograph is. Each test prints its achieved error
//! (`cargo test -p arachis --test scenarios repose_synthetic_image:: -- --nocapture`).

use crate::repose_support;

use std::path::PathBuf;

use arachis::repose::{measure_photo, FitBand, PhotoOptions, PhotoRepose, Polarity};
use image::GrayImage;
use repose_support::{PileSpec, Style};

/// The must-show tolerance (degrees).
const TOLERANCE_DEG: f64 = 0.5;

fn measure_png(image: &GrayImage, options: PhotoOptions) -> PhotoRepose {
    let dir = tempfile::tempdir().unwrap();
    let path: PathBuf = dir.path().join("pile.png");
    image.save(&path).unwrap();
    measure_photo(&path, options, FitBand::default(), None).unwrap()
}

fn assert_flanks(m: &PhotoRepose, left_deg: f64, right_deg: f64, what: &str) {
    let (el, er) = (
        m.angle.left.angle_deg - left_deg,
        m.angle.right.angle_deg - right_deg,
    );
    let mean_error = m.angle.angle_deg - 0.5 * (left_deg + right_deg);
    eprintln!(
        "{what}: left {:.3}° (error {el:+.3}°), right {:.3}° (error {er:+.3}°), mean error \
         {mean_error:+.3}°, R² {:.5}/{:.5}, threshold {}",
        m.angle.left.angle_deg,
        m.angle.right.angle_deg,
        m.angle.left.line.r_squared,
        m.angle.right.line.r_squared,
        m.threshold
    );
    assert!(el.abs() < TOLERANCE_DEG, "{what}: left error {el}°");
    assert!(er.abs() < TOLERANCE_DEG, "{what}: right error {er}°");
    assert!(
        mean_error.abs() < TOLERANCE_DEG,
        "{what}: mean error {mean_error}°"
    );
}

#[test]
fn anti_aliased_triangles_of_25_31_and_38_degrees() {
    for angle in [25.0, 31.06, 38.0] {
        let image = PileSpec::symmetric(800, 400, angle).render(Style::default());
        let m = measure_png(&image, PhotoOptions::default());
        assert_flanks(&m, angle, angle, &format!("anti-aliased {angle}°"));
        assert_eq!(m.polarity, Polarity::DarkPile);
        assert!(m.otsu);
    }
}

#[test]
fn noisy_pile_with_rounded_apex() {
    let mut spec = PileSpec::symmetric(800, 400, 31.06);
    spec.apex_radius_px = Some(120.0);
    // The fillet lowers the apex by ρ/cos θ − ρ = 20 px and meets the flanks ρ(1/cos θ −
    // cos θ) = 37 px below the sharp apex (217 px), above 80% of the rounded pile's height.
    let image = spec.render(Style {
        noise: 30.0,
        seed: 7,
        ..Style::default()
    });
    let m = measure_png(&image, PhotoOptions::default());
    assert!(m.angle.height_px < spec.apex_h - 15.0, "apex is rounded");
    assert_flanks(&m, 31.06, 31.06, "31.06°, rounded apex, ±30 grey noise");
}

#[test]
fn jagged_edges_without_anti_aliasing() {
    let image = PileSpec::symmetric(600, 300, 38.0).render(Style {
        samples: 1,
        ..Style::default()
    });
    let m = measure_png(&image, PhotoOptions::default());
    assert_flanks(&m, 38.0, 38.0, "jagged 38°");
}

#[test]
fn asymmetric_trapezoid_gives_each_flank_its_own_angle() {
    let mut spec = PileSpec::symmetric(800, 400, 28.0);
    spec.right_deg = 35.0;
    spec.flat_top_px = Some(0.85 * spec.apex_h);
    let m = measure_png(&spec.render(Style::default()), PhotoOptions::default());
    assert_flanks(&m, 28.0, 35.0, "trapezoid 28°/35°");
}

#[test]
fn light_pile_on_dark_background_found_by_the_border_rule_or_by_option() {
    let image = PileSpec::symmetric(700, 350, 31.06).render(Style {
        pile_grey: 200.0,
        background_grey: 30.0,
        noise: 10.0,
        ..Style::default()
    });
    let auto = measure_png(&image, PhotoOptions::default());
    assert_eq!(auto.polarity, Polarity::LightPile);
    assert_flanks(&auto, 31.06, 31.06, "light pile, auto");
    let given = measure_png(
        &image,
        PhotoOptions {
            threshold: Some(115),
            polarity: Polarity::LightPile,
        },
    );
    assert_eq!((given.threshold, given.otsu), (115, false));
    assert_flanks(&given, 31.06, 31.06, "light pile, threshold 115");
}

#[test]
fn specks_and_holes_are_cleaned_away() {
    let spec = PileSpec::symmetric(800, 400, 31.06);
    let mut image = spec.render(Style::default());
    // A dark speck in the sky and a light gap (shadow) inside the pile.
    for (x, y) in [(50u32, 30u32), (51, 30), (50, 31)] {
        image.put_pixel(x, y, image::Luma([60]));
    }
    for y in 300..320 {
        for x in 390..410 {
            image.put_pixel(x, y, image::Luma([225]));
        }
    }
    let m = measure_png(&image, PhotoOptions::default());
    assert_flanks(&m, 31.06, 31.06, "31.06° with a speck and a hole");
}

#[test]
fn jpeg_photograph_is_read_too() {
    let image = PileSpec::symmetric(800, 400, 31.06).render(Style {
        noise: 8.0,
        ..Style::default()
    });
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pile.jpg");
    image.save(&path).unwrap();
    let m = measure_photo(
        &path,
        PhotoOptions::default(),
        FitBand::default(),
        Some(0.25),
    )
    .unwrap();
    assert_flanks(&m, 31.06, 31.06, "JPEG 31.06°");
    // Height and width scale with 0.25 mm per pixel.
    assert_eq!(m.angle.height_mm, Some(0.25 * m.angle.height_px));
    assert_eq!(m.angle.width_mm, Some(0.25 * m.angle.width_px));
}

#[test]
fn sweep_from_20_to_45_degrees_stays_within_half_a_degree() {
    let mut worst: f64 = 0.0;
    for tenth in (200..=450).step_by(25) {
        let angle = f64::from(tenth) / 10.0;
        let image = PileSpec::symmetric(640, 320, angle).render(Style {
            noise: 15.0,
            seed: tenth as u64,
            ..Style::default()
        });
        let m = measure_png(&image, PhotoOptions::default());
        for e in [
            m.angle.left.angle_deg - angle,
            m.angle.right.angle_deg - angle,
        ] {
            worst = worst.max(e.abs());
        }
    }
    eprintln!("sweep 20°–45° step 2.5°, 640×320, ±15 grey noise: worst flank error {worst:.3}°");
    assert!(worst < TOLERANCE_DEG, "worst flank error {worst}°");
}
