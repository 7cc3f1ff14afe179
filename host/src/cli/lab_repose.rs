//! `arachis lab repose PHOTO.png`: the repose (stacking) angle of a pile photographed from
//! the side, measured as seed 000 §3.6.1 does (grey, binarise, extract the contour, fit a
//! line to each flank). Prints the angle, or with `--json` one JSON object; `--svg` draws
//! the contour and the fitted lines.

use std::io::Write;
use std::path::PathBuf;

use serde::Serialize;

use crate::repose::overlay::write_overlay_svg;
use crate::repose::{measure_photo, FitBand, PhotoOptions, Polarity, ReposeAngle};

/// Arguments of `arachis lab repose`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Photograph of the pile from the side (PNG or JPEG), the whole pile inside the frame.
    pub photo: PathBuf,
    /// Grey-level threshold 0–255 [default: Otsu's threshold].
    #[arg(long)]
    pub threshold: Option<u8>,
    /// The pile is darker than the background [default: decided from the image border].
    #[arg(long, conflicts_with = "light_pile")]
    pub dark_pile: bool,
    /// The pile is lighter than the background.
    #[arg(long)]
    pub light_pile: bool,
    /// Image scale (mm per pixel), to report the pile's height and width in mm.
    #[arg(long, value_name = "S")]
    pub mm_per_px: Option<f64>,
    /// Heights fitted, as fractions of the pile height LOW:HIGH (leaves out the flat base
    /// and the rounded apex).
    #[arg(long, default_value = "0.2:0.8", value_name = "LOW:HIGH")]
    pub fit_band: FitBand,
    /// Write the contour with the fitted lines to this SVG file.
    #[arg(long, value_name = "OUT.svg")]
    pub svg: Option<PathBuf>,
}

/// The JSON output.
#[derive(Debug, Serialize)]
struct Report<'a> {
    photo: String,
    threshold: u8,
    otsu_threshold: bool,
    polarity: Polarity,
    #[serde(flatten)]
    angle: &'a ReposeAngle,
}

/// Runs `arachis lab repose`, printing to standard output (one JSON object when `json`; the
/// flag is `arachis lab --json`, shared by every lab test).
pub fn run(args: Args, json: bool) -> anyhow::Result<()> {
    execute(args, json, &mut std::io::stdout().lock())
}

/// Runs `arachis lab repose`, printing to `out`.
pub fn execute(args: Args, json: bool, out: &mut dyn Write) -> anyhow::Result<()> {
    let polarity = match (args.dark_pile, args.light_pile) {
        (true, _) => Polarity::DarkPile,
        (_, true) => Polarity::LightPile,
        _ => Polarity::Auto,
    };
    let options = PhotoOptions {
        threshold: args.threshold,
        polarity,
    };
    let m = measure_photo(&args.photo, options, args.fit_band, args.mm_per_px)?;
    if let Some(svg) = &args.svg {
        let title = args
            .photo
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        write_overlay_svg(svg, &m.profile, &m.angle, &title)?;
    }
    let a = &m.angle;
    if json {
        let report = Report {
            photo: args.photo.display().to_string(),
            threshold: m.threshold,
            otsu_threshold: m.otsu,
            polarity: m.polarity,
            angle: a,
        };
        writeln!(out, "{}", serde_json::to_string_pretty(&report)?)?;
        return Ok(());
    }
    let pile = if m.polarity == Polarity::DarkPile {
        "dark pile on a light background"
    } else {
        "light pile on a dark background"
    };
    let how = if m.otsu { "Otsu's" } else { "given" };
    writeln!(
        out,
        "repose angle of {}: {:.2}°",
        args.photo.display(),
        a.angle_deg
    )?;
    writeln!(out, "  threshold {} ({how}), {pile}", m.threshold)?;
    writeln!(
        out,
        "  fitted between {:.0}% and {:.0}% of the pile height",
        100.0 * a.band.low,
        100.0 * a.band.high
    )?;
    for (name, f) in [("left ", &a.left), ("right", &a.right)] {
        writeln!(
            out,
            "  {name} flank {:6.2}°  R² {:.4}  rms residual {:.2} px  ({} points)",
            f.angle_deg, f.line.r_squared, f.line.rms_residual, f.line.points
        )?;
    }
    match (a.height_mm, a.width_mm) {
        (Some(h), Some(w)) => writeln!(out, "  pile height {h:.1} mm, base width {w:.1} mm")?,
        _ => writeln!(
            out,
            "  pile height {:.0} px, base width {:.0} px",
            a.height_px, a.width_px
        )?,
    }
    Ok(())
}
