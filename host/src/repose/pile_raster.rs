//! A simulated pile of spheres photographed from the side: the silhouette a distant camera
//! at a given azimuth would see, measured by exactly the same contour and line-fit path as
//! a photograph.
//!
//! A sphere of centre (x, y, z) and radius r seen along the horizontal direction
//! d = (cos φ, sin φ, 0) projects orthographically to the disc of radius r centred at
//! u = −x sin φ + y cos φ (across the picture) and z (up). The union of the discs is the
//! side silhouette — at every u it reaches the highest sphere top across the whole depth
//! of the pile, as a camera sees it. Views from opposite sides are mirror images under this
//! projection, so the default views are four azimuths within a half turn
//! ([`BENCH_AZIMUTHS_DEG`]); the bench photographs the pile from several sides and
//! averages, and so does [`simulated_repose`].
//!
//! ```
//! use arachis::repose::pile_raster::{side_silhouette, Sphere};
//! let spheres = [Sphere { centre_mm: [0.0, 0.0, 5.0], radius_mm: 5.0 }];
//! let s = side_silhouette(&spheres, 0.0, 0.5, "one sphere").unwrap();
//! // A 10 mm disc at 0.5 mm per pixel covers about π·10² pixels.
//! assert!((s.count() as f64 - std::f64::consts::PI * 100.0).abs() < 20.0);
//! ```

use serde::Serialize;

use super::error::{PileProblem, ReposeError};
use super::profile::{FitBand, Profile, ReposeAngle};
use super::silhouette::Silhouette;

/// Four viewing azimuths (degrees) giving four distinct side views.
pub const BENCH_AZIMUTHS_DEG: [f64; 4] = [0.0, 45.0, 90.0, 135.0];

/// Empty pixels around the rasterised pile on every side, so the pile never touches the
/// frame.
pub const MARGIN_PX: usize = 4;

/// Largest rasterised picture (pixels): a guard against a scale far too fine for the pile.
pub const MAX_PIXELS: usize = 50_000_000;

/// A sphere of a simulated pile; z points up, against gravity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// Centre (mm).
    pub centre_mm: [f64; 3],
    /// Radius (mm).
    pub radius_mm: f64,
}

/// One side view of a simulated pile.
#[derive(Debug, Clone, Serialize)]
pub struct SimulatedView {
    /// Viewing azimuth φ (degrees).
    pub azimuth_deg: f64,
    /// The measurement (pixels; mm through the scale).
    pub angle: ReposeAngle,
    /// The upper contour it was fitted to (for [`super::overlay`]).
    #[serde(skip)]
    pub profile: Profile,
}

/// The repose angle of a simulated pile, from several side views.
#[derive(Debug, Clone, Serialize)]
pub struct SimulatedRepose {
    /// Mean of the views' angles (degrees).
    pub angle_deg: f64,
    /// Each view.
    pub views: Vec<SimulatedView>,
}

/// The side silhouette of `spheres` seen from azimuth `azimuth_deg` (degrees, from +x
/// towards +y) at `mm_per_px` millimetres per pixel. `source_name` names the pile in
/// errors.
pub fn side_silhouette(
    spheres: &[Sphere],
    azimuth_deg: f64,
    mm_per_px: f64,
    source_name: &str,
) -> Result<Silhouette, ReposeError> {
    let problem = |problem| ReposeError::Pile {
        source_name: source_name.to_owned(),
        problem,
    };
    if !(mm_per_px.is_finite() && mm_per_px > 0.0) {
        return Err(ReposeError::InvalidOption(format!(
            "{source_name}: scale {mm_per_px} mm per pixel must be positive"
        )));
    }
    if let Some(bad) = spheres.iter().find(|s| {
        !(s.radius_mm > 0.0 && s.radius_mm.is_finite() && s.centre_mm.iter().all(|c| c.is_finite()))
    }) {
        return Err(ReposeError::InvalidOption(format!(
            "{source_name}: sphere {bad:?} needs a finite centre and a positive radius"
        )));
    }
    if spheres.is_empty() {
        return Err(problem(PileProblem::NoSpheres));
    }
    let (sin, cos) = azimuth_deg.to_radians().sin_cos();
    let discs: Vec<(f64, f64, f64)> = spheres
        .iter()
        .map(|s| {
            let [x, y, z] = s.centre_mm;
            (-x * sin + y * cos, z, s.radius_mm)
        })
        .collect();
    let u_min = discs
        .iter()
        .map(|d| d.0 - d.2)
        .fold(f64::INFINITY, f64::min);
    let u_max = discs
        .iter()
        .map(|d| d.0 + d.2)
        .fold(f64::NEG_INFINITY, f64::max);
    let z_min = discs
        .iter()
        .map(|d| d.1 - d.2)
        .fold(f64::INFINITY, f64::min);
    let z_max = discs
        .iter()
        .map(|d| d.1 + d.2)
        .fold(f64::NEG_INFINITY, f64::max);
    let width = ((u_max - u_min) / mm_per_px).ceil() as usize + 2 * MARGIN_PX;
    let height = ((z_max - z_min) / mm_per_px).ceil() as usize + 2 * MARGIN_PX;
    if width.saturating_mul(height) > MAX_PIXELS {
        return Err(problem(PileProblem::TooLarge { width, height }));
    }
    // Pixel (col, row) has its centre at u = u0 + (col + ½)·s, z = z0 − (row + ½)·s. The
    // grid is centred on the pile, so the views from opposite sides are exact mirror
    // images.
    let u0 = 0.5 * (u_min + u_max) - 0.5 * width as f64 * mm_per_px;
    let z0 = z_max + MARGIN_PX as f64 * mm_per_px;
    let mut inside = vec![false; width * height];
    for &(u, z, r) in &discs {
        let col_range = pixel_range((u - r - u0) / mm_per_px, (u + r - u0) / mm_per_px, width);
        let row_range = pixel_range((z0 - z - r) / mm_per_px, (z0 - z + r) / mm_per_px, height);
        for row in row_range {
            let dz = z0 - (row as f64 + 0.5) * mm_per_px - z;
            for col in col_range.clone() {
                let du = u0 + (col as f64 + 0.5) * mm_per_px - u;
                if du * du + dz * dz <= r * r {
                    inside[row * width + col] = true;
                }
            }
        }
    }
    Ok(Silhouette::from_fn(width, height, |x, y| {
        inside[y * width + x]
    }))
}

/// Pixel indices whose centres may fall in `[from, to]` (in pixel units), clamped to `n`.
fn pixel_range(from: f64, to: f64, n: usize) -> std::ops::Range<usize> {
    let first = from.floor().max(0.0) as usize;
    let last = (to.ceil().max(0.0) as usize).min(n);
    first..last
}

/// The repose angle of a simulated pile seen from each of `azimuths_deg` (degrees; e.g.
/// [`BENCH_AZIMUTHS_DEG`]) at `mm_per_px`, averaged over the views. Each view goes
/// through [`super::measure_silhouette`], exactly as a photograph does.
pub fn simulated_repose(
    spheres: &[Sphere],
    azimuths_deg: &[f64],
    mm_per_px: f64,
    band: FitBand,
) -> Result<SimulatedRepose, ReposeError> {
    if azimuths_deg.is_empty() {
        return Err(ReposeError::InvalidOption(
            "a simulated pile needs at least one viewing azimuth".into(),
        ));
    }
    let mut views = Vec::with_capacity(azimuths_deg.len());
    for &azimuth in azimuths_deg {
        let name = format!("simulated pile seen from azimuth {azimuth}°");
        let silhouette = side_silhouette(spheres, azimuth, mm_per_px, &name)?;
        let (profile, angle) =
            super::measure_silhouette(&silhouette, band, Some(mm_per_px), &name)?;
        views.push(SimulatedView {
            azimuth_deg: azimuth,
            angle,
            profile,
        });
    }
    let angle_deg = views.iter().map(|v| v.angle.angle_deg).sum::<f64>() / views.len() as f64;
    Ok(SimulatedRepose { angle_deg, views })
}
