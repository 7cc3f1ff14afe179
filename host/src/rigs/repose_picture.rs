//! The picture of a simulated pile (`--picture FILE.svg|.png`): the side silhouette of
//! view 0 (every sphere as a disc, as the camera sees it), its upper contour, and the two
//! fitted flank lines with their angles, plus the mean over all views in the caption.
//! Drawn with plotters at equal scales (mm), written atomically.
//!
//! A PNG carries no text (no caption, no axis labels): plotters is built without its `ttf`
//! feature (which would pull in system font loading), and its bitmap backend panics when
//! asked to draw text without a font. The SVG carries the text as `<text>` elements.

use std::path::Path;

use anyhow::{anyhow, bail, Context};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::pod_world::observation::ReposeDetails;
use crate::io::write_atomic;

/// Picture width, pixels.
const WIDTH_PX: u32 = 1000;
/// Room for the caption, axes and margins, pixels.
const FRAME_PX: u32 = 110;
/// Empty room round the pile, fraction of its width.
const SIDE_ROOM: f64 = 0.05;

const DISC: RGBColor = RGBColor(205, 170, 120);
const CONTOUR: RGBColor = RGBColor(40, 40, 40);
const LEFT_LINE: RGBColor = RGBColor(200, 30, 30);
const RIGHT_LINE: RGBColor = RGBColor(30, 60, 200);

/// Writes the picture of `details` to `path`; the extension picks SVG or PNG.
pub fn write_pile_picture(path: &Path, details: &ReposeDetails, title: &str) -> anyhow::Result<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let view = details
        .measurement
        .views
        .first()
        .ok_or_else(|| anyhow!("the pile has no measured view"))?;
    let s = details.mm_per_px;
    // Silhouette coordinates: u across (mm, view 0: azimuth 0 → u = y), h above the floor.
    let us: Vec<f64> = details.pile.iter().map(|p| p.centre_mm[1]).collect();
    let u_lo = us
        .iter()
        .zip(&details.pile)
        .map(|(u, p)| u - p.radius_mm)
        .fold(f64::INFINITY, f64::min);
    let u_hi = us
        .iter()
        .zip(&details.pile)
        .map(|(u, p)| u + p.radius_mm)
        .fold(f64::NEG_INFINITY, f64::max);
    let h_hi = details
        .pile
        .iter()
        .map(|p| p.centre_mm[2] + p.radius_mm)
        .fold(0.0, f64::max);
    let pad = SIDE_ROOM * (u_hi - u_lo);
    let (x0, x1) = (u_lo - pad, u_hi + pad);
    let y1 = h_hi * 1.3;
    let height = ((f64::from(WIDTH_PX) * y1 / (x1 - x0)) as u32).max(100) + FRAME_PX;
    let size = (WIDTH_PX + FRAME_PX, height);
    let caption = format!(
        "{title}: repose angle {:.2}° (mean of {} views, SD {:.2}°); view 0: left {:.2}°, right {:.2}°",
        details.measurement.angle_deg,
        details.measurement.views.len(),
        details.view_sd_deg,
        view.angle.left.angle_deg,
        view.angle.right.angle_deg
    );
    // The profile's x is pixels from the image's left edge, whose centre is the pile's
    // u-centre (pile_raster centres the grid): x_mm = u_mid + (x − width/2)·s.
    let width_px = ((u_hi - u_lo) / s).ceil() + 2.0 * crate::repose::pile_raster::MARGIN_PX as f64;
    let u_mid = 0.5 * (u_lo + u_hi);
    let to_mm = move |x_px: f64| u_mid + (x_px - 0.5 * width_px) * s;
    let frame = (x0, x1, y1);
    match ext.as_deref() {
        Some("svg") => {
            let mut svg = String::new();
            let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
            draw_pile(root, details, view, Some(&caption), frame, &to_mm)?;
            write_atomic(path, |w| Ok(w.write_all(svg.as_bytes())?))
        }
        Some("png") => {
            let mut rgb = vec![0u8; (size.0 * size.1 * 3) as usize];
            let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
            // No text on the bitmap backend (module notes).
            draw_pile(root, details, view, None, frame, &to_mm)?;
            let img = image::RgbImage::from_raw(size.0, size.1, rgb)
                .ok_or_else(|| anyhow!("picture buffer has the wrong size"))?;
            write_atomic(path, |w| {
                let mut bytes = Vec::new();
                img.write_to(
                    &mut std::io::Cursor::new(&mut bytes),
                    image::ImageOutputFormat::Png,
                )
                .context("cannot encode the PNG")?;
                Ok(w.write_all(&bytes)?)
            })
        }
        _ => bail!(
            "picture {}: the file name must end in .svg or .png",
            path.display()
        ),
    }
}

fn draw_pile<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    details: &ReposeDetails,
    view: &crate::repose::SimulatedView,
    caption: Option<&str>,
    (x0, x1, y1): (f64, f64, f64),
    to_mm: &dyn Fn(f64) -> f64,
) -> anyhow::Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("cannot draw the pile picture: {e}");
    root.fill(&WHITE).map_err(err)?;
    let mut builder = ChartBuilder::on(&root);
    builder.margin(10);
    if let Some(caption) = caption {
        builder
            .caption(caption, ("sans-serif", 16))
            .x_label_area_size(30)
            .y_label_area_size(45);
    }
    let mut chart = builder.build_cartesian_2d(x0..x1, 0.0..y1).map_err(err)?;
    if caption.is_some() {
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("across the view (mm)")
            .y_desc("height (mm)")
            .draw()
            .map_err(err)?;
    }
    // Discs: the radius in pixels from the chart's x scale.
    let (px_w, _) = chart.plotting_area().dim_in_pixel();
    let px_per_mm = f64::from(px_w) / (x1 - x0);
    chart
        .draw_series(details.pile.iter().map(|p| {
            let r = (p.radius_mm * px_per_mm).round().max(1.0) as i32;
            Circle::new((p.centre_mm[1], p.centre_mm[2]), r, DISC.filled())
        }))
        .map_err(err)?;
    let s = details.mm_per_px;
    let contour: Vec<(f64, f64)> = view
        .profile
        .points()
        .iter()
        .map(|&(x, h)| (to_mm(x), h * s))
        .collect();
    chart
        .draw_series(LineSeries::new(contour, CONTOUR))
        .map_err(err)?;
    let height_px = view.profile.height_px();
    for (flank, colour) in [
        (&view.angle.left, LEFT_LINE),
        (&view.angle.right, RIGHT_LINE),
    ] {
        let (a, b) = (flank.line.intercept, flank.line.slope);
        if b == 0.0 {
            continue;
        }
        let ends = [0.0, height_px].map(|h| (to_mm((h - a) / b), h * s));
        chart
            .draw_series(LineSeries::new(ends, colour.stroke_width(3)))
            .map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::repose::{simulated_repose, FitBand, Sphere};

    /// A 35° cone of 2 mm spheres on a 40 mm base (rings every 2 mm), seen from 2 views.
    fn cone_details() -> ReposeDetails {
        const RADIUS_MM: f64 = 2.0;
        const BASE_MM: f64 = 40.0;
        let tan = 35f64.to_radians().tan();
        let mut pile = Vec::new();
        let mut ring = 0.0;
        while ring <= BASE_MM {
            let count = ((2.0 * std::f64::consts::PI * ring / RADIUS_MM) as usize).max(1);
            for k in 0..count {
                let a = 2.0 * std::f64::consts::PI * k as f64 / count as f64;
                let mut z = RADIUS_MM;
                while z <= (BASE_MM - ring) * tan {
                    pile.push(Sphere {
                        centre_mm: [ring * a.cos(), ring * a.sin(), z],
                        radius_mm: RADIUS_MM,
                    });
                    z += RADIUS_MM;
                }
            }
            ring += RADIUS_MM;
        }
        let measurement = simulated_repose(&pile, &[0.0, 90.0], 0.5, FitBand::default()).unwrap();
        ReposeDetails {
            pods: 0,
            spheres: pile.len() as u32,
            cylinder_diameter_mm: 0.0,
            dt_s: 0.0,
            lift_start_s: 0.0,
            lift_end_s: 0.0,
            end_s: 0.0,
            steps: 0,
            final_kinetic_energy_j: 0.0,
            view_sd_deg: 0.0,
            pile_height_mm: 0.0,
            pile_width_mm: 0.0,
            mm_per_px: 0.5,
            measurement,
            refused_views: Vec::new(),
            pile,
        }
    }

    #[test]
    fn png_and_svg_pictures_are_written_without_a_panic() {
        // The bitmap backend has no font: a PNG with a caption used to panic in plotters.
        let details = cone_details();
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("pile.png");
        write_pile_picture(&png, &details, "cone").unwrap();
        let img = image::open(&png).unwrap();
        assert_eq!(img.width(), WIDTH_PX + FRAME_PX);
        let svg = dir.path().join("pile.svg");
        write_pile_picture(&svg, &details, "cone").unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("cone: repose angle"), "caption missing");
        assert!(write_pile_picture(&dir.path().join("pile.gif"), &details, "cone").is_err());
    }
}
