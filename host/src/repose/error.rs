//! Why a repose angle could not be measured: the image could not be read, or it holds no
//! usable pile. Each error names its source (the photograph's path, or which simulated
//! view), so a batch of photographs points at the bad one.

use std::fmt;
use std::path::PathBuf;

use super::silhouette::Side;

/// Left or right flank of the pile as seen in the picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flank {
    /// The flank left of the apex.
    Left,
    /// The flank right of the apex.
    Right,
}

impl fmt::Display for Flank {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Flank::Left => "left",
            Flank::Right => "right",
        })
    }
}

/// What is wrong with a silhouette.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PileProblem {
    /// A single grey level: nothing to separate.
    #[error("no pile found: the image is a single grey level")]
    Uniform,
    /// No pixel on the pile side of the threshold.
    #[error("no pile found: no pixel is on the pile side of threshold {0}")]
    Empty(u8),
    /// A silhouette with no pile pixel.
    #[error("no pile found: the silhouette is empty")]
    EmptySilhouette,
    /// A simulated pile with no spheres.
    #[error("no pile found: no spheres")]
    NoSpheres,
    /// The pile is cut off by the frame.
    #[error(
        "the pile touches the {0} border of the image, so a flank is cut off \
         (photograph the whole pile with a margin above and beside it, crop the picture at the \
         plate, or check --dark-pile/--light-pile)"
    )]
    TouchesBorder(Side),
    /// Too few contour points inside the fit band.
    #[error(
        "the {flank} flank has {found} contour points inside the fit band, fewer than the \
         {needed} needed for a line (a wider pile, a finer image or a wider --fit-band helps)"
    )]
    TooFewPoints {
        /// Which flank.
        flank: Flank,
        /// Points found.
        found: usize,
        /// Points needed.
        needed: usize,
    },
    /// The rasterised picture would be unreasonably large.
    #[error("the picture would be {width} × {height} pixels; use a coarser scale (mm per pixel)")]
    TooLarge {
        /// Width (pixels).
        width: usize,
        /// Height (pixels).
        height: usize,
    },
}

/// Failure to measure a repose angle.
#[derive(Debug, thiserror::Error)]
pub enum ReposeError {
    /// The image file is missing or not a readable PNG/JPEG.
    #[error("cannot read image {}: {reason}", path.display())]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// The decoder's or the file system's message.
        reason: String,
    },
    /// The picture holds no usable pile.
    #[error("{source_name}: {problem}")]
    Pile {
        /// The file, or which simulated view.
        source_name: String,
        /// What is wrong.
        problem: PileProblem,
    },
    /// An option is out of range.
    #[error("{0}")]
    InvalidOption(String),
}
