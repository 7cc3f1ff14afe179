//! A pile photograph (PNG or JPEG) to a silhouette: greyed, binarised at Otsu's threshold
//! (or a given one), as seed 000 §3.6.1 does before extracting the contour.
//!
//! Which class is the pile: with [`Polarity::Auto`] it is the class that covers less of
//! the image border, since a photograph of the whole pile has background all round it.
//! `--dark-pile` / `--light-pile` override this for a pile photographed against a backdrop
//! that is not uniform.

use std::path::Path;

use image::GrayImage;
use serde::Serialize;

use super::error::{PileProblem, ReposeError};
use super::otsu::{grey_histogram, otsu_threshold};
use super::silhouette::Silhouette;

/// Whether the pile is darker or lighter than its background.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Polarity {
    /// Decide from the image border (the pile is the class less present on it).
    #[default]
    Auto,
    /// Dark pile on a light background: pile is grey ≤ threshold.
    DarkPile,
    /// Light pile on a dark background: pile is grey > threshold.
    LightPile,
}

/// How to binarise a photograph.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PhotoOptions {
    /// Grey-level threshold (0–255; pile ≤ t when dark, > t when light); Otsu's when `None`.
    pub threshold: Option<u8>,
    /// Which side of the threshold is the pile.
    pub polarity: Polarity,
}

/// The binarised photograph and how it was binarised.
#[derive(Debug, Clone)]
pub struct Binarised {
    /// Pile pixels (before cleaning).
    pub silhouette: Silhouette,
    /// Threshold used (grey level 0–255).
    pub threshold: u8,
    /// Whether it was Otsu's.
    pub otsu: bool,
    /// The resolved polarity: [`Polarity::DarkPile`] or [`Polarity::LightPile`].
    pub polarity: Polarity,
}

/// Reads `path` as a greyscale image (PNG or JPEG; colour is converted to luma).
pub fn read_grey(path: &Path) -> Result<GrayImage, ReposeError> {
    let unreadable = |reason: String| ReposeError::Unreadable {
        path: path.to_owned(),
        reason,
    };
    let reader = image::io::Reader::open(path)
        .map_err(|e| unreadable(e.to_string()))?
        .with_guessed_format()
        .map_err(|e| unreadable(e.to_string()))?;
    let decoded = reader.decode().map_err(|e| unreadable(e.to_string()))?;
    Ok(decoded.to_luma8())
}

/// Binarises a grey image; `source_name` names it in errors.
pub fn binarise(
    grey: &GrayImage,
    options: PhotoOptions,
    source_name: &str,
) -> Result<Binarised, ReposeError> {
    let problem = |problem| ReposeError::Pile {
        source_name: source_name.to_owned(),
        problem,
    };
    let (threshold, otsu) = match options.threshold {
        Some(t) => (t, false),
        None => (
            otsu_threshold(&grey_histogram(grey.as_raw())).ok_or(problem(PileProblem::Uniform))?,
            true,
        ),
    };
    let polarity = match options.polarity {
        Polarity::Auto => border_polarity(grey, threshold),
        chosen => chosen,
    };
    let dark = polarity == Polarity::DarkPile;
    let silhouette = Silhouette::from_fn(grey.width() as usize, grey.height() as usize, |x, y| {
        (grey.get_pixel(x as u32, y as u32)[0] <= threshold) == dark
    });
    if silhouette.count() == 0 {
        return Err(problem(PileProblem::Empty(threshold)));
    }
    Ok(Binarised {
        silhouette,
        threshold,
        otsu,
        polarity,
    })
}

/// The pile is the class in the minority on the image border; a tie means dark pile.
fn border_polarity(grey: &GrayImage, threshold: u8) -> Polarity {
    let (w, h) = (grey.width(), grey.height());
    let border = (0..w)
        .flat_map(|x| [(x, 0), (x, h.saturating_sub(1))])
        .chain((0..h).flat_map(|y| [(0, y), (w.saturating_sub(1), y)]));
    let (mut dark, mut light) = (0usize, 0usize);
    for (x, y) in border {
        if grey.get_pixel(x, y)[0] <= threshold {
            dark += 1;
        } else {
            light += 1;
        }
    }
    if dark > light {
        Polarity::LightPile
    } else {
        Polarity::DarkPile
    }
}
