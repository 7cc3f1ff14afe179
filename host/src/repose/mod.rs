//! The repose (stacking) angle of a pile from its side silhouette, for a photograph or a
//! simulated pile alike.
//!
//! Seed 000 §3.6.1 measures the stacking angle by cylinder lifting: the pile is
//! photographed from the side, "the captured images are grayed out and binarized, and
//! contour edge coordinates are extracted", and "the slope of the straight line at the edge
//! of the contour obtained after the fitting process is the tangent of the peanut pods'
//! stacking angle" (mean of 10 piles: 31.06°). The path here:
//!
//! 1. [`photo`]: grey the photograph and binarise it at Otsu's threshold ([`otsu`]), or a
//!    simulated pile is rasterised from the side ([`pile_raster`]);
//! 2. [`silhouette`]: keep the largest blob and fill its holes; refuse a pile cut off by
//!    the frame;
//! 3. [`profile`]: take the upper contour, find the apex, fit a line by least squares
//!    ([`line_fit`]) to each flank between 20% and 80% of the pile height;
//! 4. [`overlay`]: draw the contour, the lines and the angles as SVG.
//!
//! ```no_run
//! use arachis::repose::{measure_photo, FitBand, PhotoOptions};
//! let m = measure_photo("pile.png".as_ref(), PhotoOptions::default(), FitBand::default(), None)?;
//! println!("{:.2}°", m.angle.angle_deg);
//! # Ok::<(), arachis::repose::ReposeError>(())
//! ```

pub mod error;
pub mod line_fit;
pub mod otsu;
pub mod overlay;
pub mod photo;
pub mod pile_raster;
pub mod profile;
pub mod silhouette;

use std::path::Path;

pub use error::{Flank, PileProblem, ReposeError};
pub use photo::{PhotoOptions, Polarity};
pub use pile_raster::{
    simulated_repose, SimulatedRepose, SimulatedView, Sphere, BENCH_AZIMUTHS_DEG,
};
pub use profile::{FitBand, FlankFit, Profile, ReposeAngle};
pub use silhouette::Silhouette;

/// A photograph's measurement.
#[derive(Debug, Clone)]
pub struct PhotoRepose {
    /// The repose angle and the pile's size.
    pub angle: ReposeAngle,
    /// The upper contour it was fitted to (for the overlay).
    pub profile: Profile,
    /// Threshold used (grey level 0–255).
    pub threshold: u8,
    /// Whether the threshold was Otsu's.
    pub otsu: bool,
    /// Dark or light pile (resolved).
    pub polarity: Polarity,
}

/// Cleans `silhouette` (largest blob, holes filled), checks the pile is inside the frame,
/// and fits its flanks inside `band`. `mm_per_px` (mm per pixel) scales the pile's size;
/// `source_name` names the picture in errors.
pub fn measure_silhouette(
    silhouette: &Silhouette,
    band: FitBand,
    mm_per_px: Option<f64>,
    source_name: &str,
) -> Result<(Profile, ReposeAngle), ReposeError> {
    let problem = |problem| ReposeError::Pile {
        source_name: source_name.to_owned(),
        problem,
    };
    if let Some(s) = mm_per_px.filter(|s| !(s.is_finite() && *s > 0.0)) {
        return Err(ReposeError::InvalidOption(format!(
            "scale {s} mm per pixel must be positive"
        )));
    }
    let clean = silhouette.largest_blob().filled();
    let profile = Profile::from_silhouette(&clean).ok_or(problem(PileProblem::EmptySilhouette))?;
    if let Some(side) = clean.touched_side() {
        return Err(problem(PileProblem::TouchesBorder(side)));
    }
    let angle = profile.fit(band, mm_per_px).map_err(problem)?;
    Ok((profile, angle))
}

/// Measures the repose angle in the photograph at `path` (PNG or JPEG).
pub fn measure_photo(
    path: &Path,
    options: PhotoOptions,
    band: FitBand,
    mm_per_px: Option<f64>,
) -> Result<PhotoRepose, ReposeError> {
    let name = format!("image {}", path.display());
    let grey = photo::read_grey(path)?;
    let binarised = photo::binarise(&grey, options, &name)?;
    let (profile, angle) = measure_silhouette(&binarised.silhouette, band, mm_per_px, &name)?;
    Ok(PhotoRepose {
        angle,
        profile,
        threshold: binarised.threshold,
        otsu: binarised.otsu,
        polarity: binarised.polarity,
    })
}
