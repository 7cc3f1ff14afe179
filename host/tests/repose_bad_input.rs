//! Bad photographs are refused with a message naming the file and saying what is wrong;
//! never a panic.

use crate::repose_support;

use std::path::{Path, PathBuf};

use arachis::repose::{measure_photo, FitBand, PhotoOptions, Polarity};
use image::GrayImage;
use repose_support::{PileSpec, Style};

fn error_for(path: &Path, options: PhotoOptions, mm_per_px: Option<f64>) -> String {
    measure_photo(path, options, FitBand::default(), mm_per_px)
        .expect_err("must fail")
        .to_string()
}

fn saved(dir: &Path, name: &str, image: &GrayImage) -> PathBuf {
    let path = dir.join(name);
    image.save(&path).unwrap();
    path
}

fn assert_names(message: &str, path: &Path, needle: &str) {
    assert!(
        message.contains(&path.display().to_string()),
        "{message:?} does not name {}",
        path.display()
    );
    assert!(message.contains(needle), "{message:?} lacks {needle:?}");
}

#[test]
fn missing_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no-such-pile.png");
    let message = error_for(&path, PhotoOptions::default(), None);
    assert_names(&message, &path, "cannot read image");
}

#[test]
fn file_that_is_not_an_image() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pile.png");
    std::fs::write(&path, "x,y\n1,2\n").unwrap();
    let message = error_for(&path, PhotoOptions::default(), None);
    assert_names(&message, &path, "cannot read image");
    // A truncated PNG: a real header, then nothing.
    let mut png = Vec::new();
    let full = PileSpec::symmetric(100, 50, 30.0).render(Style::default());
    full.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let cut = dir.path().join("cut.png");
    std::fs::write(&cut, &png[..png.len() / 2]).unwrap();
    assert_names(
        &error_for(&cut, PhotoOptions::default(), None),
        &cut,
        "cannot read image",
    );
}

#[test]
fn uniform_image_has_no_pile() {
    let dir = tempfile::tempdir().unwrap();
    let path = saved(
        dir.path(),
        "blank.png",
        &GrayImage::from_pixel(200, 100, image::Luma([200])),
    );
    assert_names(
        &error_for(&path, PhotoOptions::default(), None),
        &path,
        "no pile found: the image is a single grey level",
    );
    // With a given threshold the pile side is empty instead.
    let options = PhotoOptions {
        threshold: Some(100),
        polarity: Polarity::DarkPile,
    };
    assert_names(
        &error_for(&path, options, None),
        &path,
        "no pixel is on the pile side of threshold 100",
    );
}

#[test]
fn pile_cut_off_by_the_frame() {
    let dir = tempfile::tempdir().unwrap();
    // The apex moved left until the left flank leaves the picture.
    let mut spec = PileSpec::symmetric(400, 200, 31.06);
    spec.apex_x = 100.0;
    let path = saved(dir.path(), "left.png", &spec.render(Style::default()));
    assert_names(
        &error_for(&path, PhotoOptions::default(), None),
        &path,
        "the pile touches the left border",
    );
    // Too tall for the picture: the apex is cut off at the top.
    let mut spec = PileSpec::symmetric(400, 200, 31.06);
    spec.apex_h = 250.0;
    spec.left_deg = 60.0;
    spec.right_deg = 60.0;
    let path = saved(dir.path(), "top.png", &spec.render(Style::default()));
    assert_names(
        &error_for(&path, PhotoOptions::default(), None),
        &path,
        "the pile touches the top border",
    );
}

#[test]
fn speck_too_small_for_a_line() {
    let dir = tempfile::tempdir().unwrap();
    let image = GrayImage::from_fn(100, 60, |x, y| {
        image::Luma([if (48..52).contains(&x) && (40..43).contains(&y) {
            30
        } else {
            220
        }])
    });
    let path = saved(dir.path(), "speck.png", &image);
    assert_names(
        &error_for(&path, PhotoOptions::default(), None),
        &path,
        "flank has 0 contour points inside the fit band",
    );
}

#[test]
fn bad_scale_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let image = PileSpec::symmetric(400, 200, 31.06).render(Style::default());
    let path = saved(dir.path(), "pile.png", &image);
    for bad in [0.0, -1.0, f64::NAN] {
        let message = error_for(&path, PhotoOptions::default(), Some(bad));
        assert!(
            message.contains("mm per pixel must be positive"),
            "{message}"
        );
    }
}
