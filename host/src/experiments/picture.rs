//! The picture of a simulated pile (`--picture FILE.svg|.png`): the side silhouette of
//! view 0 (every sphere as a disc, as the camera sees it), its upper contour, and the two
//! fitted flank lines with their angles, plus the mean over all views in the caption.
//! Drawn with plotters at equal scales (mm), written atomically.

use std::path::Path;

use anyhow::{anyhow, bail, Context};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::repose::ReposeDetails;
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
            draw_pile(root, details, view, &caption, frame, &to_mm)?;
            write_atomic(path, |w| Ok(w.write_all(svg.as_bytes())?))
        }
        Some("png") => {
            let mut rgb = vec![0u8; (size.0 * size.1 * 3) as usize];
            let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
            draw_pile(root, details, view, &caption, frame, &to_mm)?;
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
    caption: &str,
    (x0, x1, y1): (f64, f64, f64),
    to_mm: &dyn Fn(f64) -> f64,
) -> anyhow::Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("cannot draw the pile picture: {e}");
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(45)
        .build_cartesian_2d(x0..x1, 0.0..y1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("across the view (mm)")
        .y_desc("height (mm)")
        .draw()
        .map_err(err)?;
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
