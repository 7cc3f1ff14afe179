//! From a silhouette to the repose angle: the upper contour, the apex, and a straight line
//! fitted to each flank inside a band of heights.
//!
//! Seed 000 §3.6.1 extracts "contour edge coordinates" from the binarised photograph and
//! takes the slope of the line fitted to the contour edge as tan ζ. Here the contour is
//! the top of the pile in each image column, h(x) in pixels above the pile's lowest row.
//! The apex is the highest column (the middle of a flat top). The flat base, where pods
//! lie spread on the plate, and the rounded apex, where the pile is not yet at its angle,
//! are left out: only contour points with `low·H ≤ h ≤ high·H` are fitted, H the pile
//! height. Each flank's angle is
//!
//! ζ_left = atan(b_left),  ζ_right = atan(−b_right),  ζ = (ζ_left + ζ_right) / 2,
//!
//! with b the fitted slope dh/dx (pixels are square, so the slope needs no scale).
//!
//! ```
//! use arachis::repose::{FitBand, Profile, Silhouette};
//! // A symmetric triangle pile with slope 1/2 (26.57°).
//! let s = Silhouette::from_fn(220, 70, |x, y| {
//!     let h = 60.0 - (x as f64 + 0.5 - 110.0).abs() / 2.0;
//!     (69 - y) as f64 + 0.5 < h
//! });
//! let angle = Profile::from_silhouette(&s).unwrap().fit(FitBand::default(), None).unwrap();
//! assert!((angle.angle_deg - 0.5f64.atan().to_degrees()).abs() < 0.1);
//! ```

use std::str::FromStr;

use serde::Serialize;

use super::error::{Flank, PileProblem};
use super::line_fit::{fit_line, LineFit};
use super::silhouette::Silhouette;

/// Default lower edge of the fit band (fraction of pile height): below it lies the flat
/// base, pods spread on the plate.
pub const DEFAULT_BAND_LOW: f64 = 0.2;
/// Default upper edge of the fit band (fraction of pile height): above it the apex is
/// rounded by the last pods to settle.
pub const DEFAULT_BAND_HIGH: f64 = 0.8;
/// Fewest contour points a flank needs inside the band for a line with a meaningful R².
pub const MIN_FLANK_POINTS: usize = 5;

/// The band of heights, as fractions of the pile height, inside which the flanks are
/// fitted.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FitBand {
    /// Lower edge (fraction of pile height, 0 ≤ low < high).
    pub low: f64,
    /// Upper edge (fraction of pile height, high ≤ 1).
    pub high: f64,
}

impl FitBand {
    /// The band `low..high`; fails unless 0 ≤ low < high ≤ 1.
    pub fn new(low: f64, high: f64) -> Result<Self, String> {
        if !((0.0..1.0).contains(&low) && low < high && high <= 1.0) {
            return Err(format!(
                "fit band {low}:{high} must satisfy 0 ≤ low < high ≤ 1 (fractions of pile height)"
            ));
        }
        Ok(FitBand { low, high })
    }
}

impl Default for FitBand {
    fn default() -> Self {
        FitBand {
            low: DEFAULT_BAND_LOW,
            high: DEFAULT_BAND_HIGH,
        }
    }
}

impl FromStr for FitBand {
    type Err = String;

    /// Parses `LOW:HIGH`, e.g. `0.2:0.8`.
    fn from_str(s: &str) -> Result<Self, String> {
        let (low, high) = s
            .split_once(':')
            .ok_or_else(|| format!("fit band {s:?} must be LOW:HIGH, e.g. 0.2:0.8"))?;
        let parse = |t: &str| {
            t.trim()
                .parse::<f64>()
                .map_err(|_| format!("fit band {s:?}: {t:?} is not a number"))
        };
        FitBand::new(parse(low)?, parse(high)?)
    }
}

/// The upper contour of a silhouette (read-only: the apex is found once, on creation).
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    points: Vec<(f64, f64)>,
    base_row: usize,
    height_px: f64,
    apex_first: usize,
    apex_last: usize,
}

/// One flank's fitted line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FlankFit {
    /// Flank angle ζ (degrees) from the horizontal, positive for a flank rising towards
    /// the apex.
    pub angle_deg: f64,
    /// h = a + b·x in pixels; `rms_residual` in pixels.
    pub line: LineFit,
    /// x range of the fitted points (pixels).
    pub x_range_px: (f64, f64),
}

/// The measured repose angle of one silhouette.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReposeAngle {
    /// Mean of the two flank angles (degrees).
    pub angle_deg: f64,
    /// The left flank.
    pub left: FlankFit,
    /// The right flank.
    pub right: FlankFit,
    /// The band of heights fitted.
    pub band: FitBand,
    /// Pile height H (pixels).
    pub height_px: f64,
    /// Pile width at its base (pixels).
    pub width_px: f64,
    /// x of the apex (pixels).
    pub apex_x_px: f64,
    /// Scale (mm per pixel), when given.
    pub mm_per_px: Option<f64>,
    /// Pile height (mm), when the scale is given.
    pub height_mm: Option<f64>,
    /// Pile width at its base (mm), when the scale is given.
    pub width_mm: Option<f64>,
}

impl Profile {
    /// The upper contour of `silhouette`; `None` when it holds no pile pixel.
    pub fn from_silhouette(silhouette: &Silhouette) -> Option<Profile> {
        let (w, h) = (silhouette.width(), silhouette.height());
        let tops: Vec<(usize, usize)> = (0..w)
            .filter_map(|x| (0..h).find(|&y| silhouette.get(x, y)).map(|y| (x, y)))
            .collect();
        let base_row = (0..h)
            .rev()
            .find(|&y| (0..w).any(|x| silhouette.get(x, y)))?;
        let points: Vec<(f64, f64)> = tops
            .iter()
            .map(|&(x, top)| (x as f64 + 0.5, (base_row + 1 - top) as f64))
            .collect();
        let height_px = points.iter().map(|p| p.1).fold(0.0, f64::max);
        let apex_first = points.iter().position(|p| p.1 == height_px)?;
        let apex_last = points.iter().rposition(|p| p.1 == height_px)?;
        Some(Profile {
            points,
            base_row,
            height_px,
            apex_first,
            apex_last,
        })
    }

    /// One point per column holding pile, left to right: x (pixels from the image's left
    /// edge, at the column centre) and h (pixels from the bottom of the pile's lowest row
    /// to the top of the column's highest pile pixel).
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points
    }

    /// Image row of the pile's lowest pixel (row 0 at the top).
    pub fn base_row(&self) -> usize {
        self.base_row
    }

    /// Pile height H = max h (pixels).
    pub fn height_px(&self) -> f64 {
        self.height_px
    }

    /// x of the apex (pixels): the middle of the columns reaching H.
    pub fn apex_x_px(&self) -> f64 {
        0.5 * (self.points[self.apex_first].0 + self.points[self.apex_last].0)
    }

    /// Pile width at its base (pixels): the span of columns holding pile.
    pub fn width_px(&self) -> f64 {
        self.points.len() as f64
    }

    /// Contour points of one flank inside the band (pixels).
    pub fn flank_points(&self, flank: Flank, band: FitBand) -> Vec<(f64, f64)> {
        let side = match flank {
            Flank::Left => &self.points[..self.apex_first],
            Flank::Right => &self.points[self.apex_last + 1..],
        };
        let (low, high) = (band.low * self.height_px, band.high * self.height_px);
        side.iter()
            .copied()
            .filter(|&(_, h)| (low..=high).contains(&h))
            .collect()
    }

    /// Fits both flanks inside `band`; `mm_per_px` (mm per pixel) converts the pile's size.
    pub fn fit(&self, band: FitBand, mm_per_px: Option<f64>) -> Result<ReposeAngle, PileProblem> {
        let left = self.fit_flank(Flank::Left, band)?;
        let right = self.fit_flank(Flank::Right, band)?;
        let width_px = self.width_px();
        Ok(ReposeAngle {
            angle_deg: 0.5 * (left.angle_deg + right.angle_deg),
            left,
            right,
            band,
            height_px: self.height_px,
            width_px,
            apex_x_px: self.apex_x_px(),
            mm_per_px,
            height_mm: mm_per_px.map(|s| s * self.height_px),
            width_mm: mm_per_px.map(|s| s * width_px),
        })
    }

    fn fit_flank(&self, flank: Flank, band: FitBand) -> Result<FlankFit, PileProblem> {
        let points = self.flank_points(flank, band);
        let too_few = PileProblem::TooFewPoints {
            flank,
            found: points.len(),
            needed: MIN_FLANK_POINTS,
        };
        if points.len() < MIN_FLANK_POINTS {
            return Err(too_few);
        }
        let line = fit_line(&points).ok_or(too_few)?;
        let rise = match flank {
            Flank::Left => line.slope,
            Flank::Right => -line.slope,
        };
        let x_first = points.first().map_or(0.0, |p| p.0);
        let x_last = points.last().map_or(0.0, |p| p.0);
        Ok(FlankFit {
            angle_deg: rise.atan().to_degrees(),
            line,
            x_range_px: (x_first, x_last),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_parses_and_rejects() {
        let band: FitBand = "0.1:0.9".parse().unwrap();
        assert_eq!((band.low, band.high), (0.1, 0.9));
        assert!("0.8:0.2"
            .parse::<FitBand>()
            .unwrap_err()
            .contains("low < high"));
        assert!("0.2".parse::<FitBand>().unwrap_err().contains("LOW:HIGH"));
        assert!("a:0.5"
            .parse::<FitBand>()
            .unwrap_err()
            .contains("not a number"));
        assert!("0.2:1.5".parse::<FitBand>().is_err());
    }

    #[test]
    fn flat_top_apex_is_its_middle_and_thin_flank_is_refused() {
        // A rectangle: no flank points strictly left of the flat top.
        let s = Silhouette::from_fn(20, 10, |x, y| (4..16).contains(&x) && y >= 3);
        let p = Profile::from_silhouette(&s).unwrap();
        assert_eq!(p.apex_x_px(), 10.0);
        assert_eq!(p.height_px(), 7.0);
        assert_eq!(
            p.fit(FitBand::default(), None).unwrap_err(),
            PileProblem::TooFewPoints {
                flank: Flank::Left,
                found: 0,
                needed: MIN_FLANK_POINTS
            }
        );
    }
}
