//! The picture of a measurement: the pile's upper contour, the fit band, the two fitted
//! flank lines and their angles, as an SVG written atomically (in the manner of seed 000
//! Figure 9, which shows the extracted contour and the fitted edge).
//!
//! Both axes are in image pixels with equal scale, so the drawn slopes look as steep as
//! the pile.

use std::path::Path;

use anyhow::anyhow;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::profile::{FlankFit, Profile, ReposeAngle};
use crate::io::write_string_atomic;

/// Width of the plotting area (SVG pixels); the height follows from the pile's aspect.
const PLOT_WIDTH: u32 = 900;
/// Room for the caption (SVG pixels).
const CAPTION_ROOM: u32 = 40;
/// Blank margin round the chart (SVG pixels).
const MARGIN: u32 = 10;
/// Room for the x axis labels (SVG pixels).
const X_LABELS: u32 = 30;
/// Room for the y axis labels (SVG pixels).
const Y_LABELS: u32 = 50;
/// Head room above the apex (fraction of pile height), for the labels.
const HEAD_ROOM: f64 = 0.25;
/// Gap between a fitted line and its label (fraction of the picture's width).
const LABEL_OFFSET: f64 = 0.02;
/// Empty border left and right of the pile (fraction of pile width).
const SIDE_ROOM: f64 = 0.05;

const CONTOUR: RGBColor = RGBColor(40, 40, 40);
const BAND: RGBColor = RGBColor(190, 190, 190);
const LEFT_LINE: RGBColor = RGBColor(200, 30, 30);
const RIGHT_LINE: RGBColor = RGBColor(30, 60, 200);

/// Draws `profile` and `angle` as SVG; the caption starts with `title`.
pub fn overlay_svg(profile: &Profile, angle: &ReposeAngle, title: &str) -> anyhow::Result<String> {
    let x_first = profile.points().first().map_or(0.0, |p| p.0);
    let x_last = profile.points().last().map_or(1.0, |p| p.0);
    let pad = SIDE_ROOM * (x_last - x_first).max(1.0);
    let (x_lo, x_hi) = (x_first - pad, x_last + pad);
    let h_hi = profile.height_px().max(1.0) * (1.0 + HEAD_ROOM);
    let plot_height = (f64::from(PLOT_WIDTH) * h_hi / (x_hi - x_lo)).ceil() as u32;
    let size = (
        PLOT_WIDTH + Y_LABELS + 2 * MARGIN,
        plot_height.max(1) + CAPTION_ROOM + X_LABELS + 2 * MARGIN,
    );
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let caption = format!(
            "{title}: repose angle {:.2}° (left {:.2}°, right {:.2}°)",
            angle.angle_deg, angle.left.angle_deg, angle.right.angle_deg
        );
        let area = root
            .titled(&caption, ("sans-serif", 18))
            .map_err(plot_error)?;
        // Equal scales: the height range follows from the plotting area the title left.
        let (area_w, area_h) = area.dim_in_pixel();
        let plot_w = f64::from(area_w.saturating_sub(Y_LABELS + 2 * MARGIN).max(1));
        let plot_h = f64::from(area_h.saturating_sub(X_LABELS + 2 * MARGIN).max(1));
        let h_top = (x_hi - x_lo) * plot_h / plot_w;
        let mut chart = ChartBuilder::on(&area)
            .margin(MARGIN)
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS)
            .build_cartesian_2d(x_lo..x_hi, 0.0..h_top)
            .map_err(plot_error)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x (px)")
            .y_desc("height above base (px)")
            .draw()
            .map_err(plot_error)?;
        for fraction in [angle.band.low, angle.band.high] {
            let h = fraction * profile.height_px();
            chart
                .draw_series(LineSeries::new([(x_lo, h), (x_hi, h)], BAND))
                .map_err(plot_error)?;
        }
        chart
            .draw_series(LineSeries::new(profile.points().iter().copied(), CONTOUR))
            .map_err(plot_error)?;
        let offset = LABEL_OFFSET * (x_hi - x_lo);
        for (flank, colour, name, anchor, shift) in [
            (&angle.left, LEFT_LINE, "left", HPos::Right, -offset),
            (&angle.right, RIGHT_LINE, "right", HPos::Left, offset),
        ] {
            let ends = line_ends(flank, profile.height_px());
            chart
                .draw_series(LineSeries::new(ends, colour.stroke_width(2)))
                .map_err(plot_error)?;
            // The label sits outside its line, at mid-height.
            let middle = (
                0.5 * (ends[0].0 + ends[1].0) + shift,
                0.5 * profile.height_px(),
            );
            let style = ("sans-serif", 16)
                .into_font()
                .color(&colour)
                .pos(Pos::new(anchor, VPos::Center));
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{name} {:.2}°", flank.angle_deg),
                    middle,
                    style,
                )))
                .map_err(plot_error)?;
        }
        root.present().map_err(plot_error)?;
    }
    Ok(svg)
}

/// Writes [`overlay_svg`] to `path` atomically.
pub fn write_overlay_svg(
    path: &Path,
    profile: &Profile,
    angle: &ReposeAngle,
    title: &str,
) -> anyhow::Result<()> {
    write_string_atomic(path, &overlay_svg(profile, angle, title)?)
}

/// The fitted line from the base (h = 0) to the apex height (pixels).
fn line_ends(flank: &FlankFit, height_px: f64) -> [(f64, f64); 2] {
    let (a, b) = (flank.line.intercept, flank.line.slope);
    if b == 0.0 {
        return [(flank.x_range_px.0, a), (flank.x_range_px.1, a)];
    }
    [((0.0 - a) / b, 0.0), ((height_px - a) / b, height_px)]
}

fn plot_error<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("cannot draw the repose overlay: {e}")
}
