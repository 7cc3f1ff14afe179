//! An SVG picture of sphere fillings: for each shape a side view (z across, y up: length ×
//! thickness) and a top view (z across, x up: length × width), circles drawn to scale
//! (8 px/mm, less for solids wider than 75 mm), with the exact outline of an analytic pod
//! where given. Written atomically.

use std::path::Path;

use anyhow::Context;
use plotters::prelude::*;

use crate::io::write_string_atomic;

use super::pod_shape::PodShape;
use super::sphere_fill::SphereFilling;

/// Picture scale for pod-sized solids, pixels per mm.
const PX_PER_MM: f64 = 8.0;
/// Widest panel, px: larger solids are drawn at a smaller scale.
const MAX_PANEL_PX: f64 = 600.0;
/// Space around and between panels, px.
const GAP_PX: i32 = 30;
/// Height of the label line above each panel, px.
const LABEL_PX: i32 = 22;
/// Points along an outline.
const OUTLINE_POINTS: usize = 200;

/// One row of the picture.
#[derive(Debug, Clone, Copy)]
pub struct PicturePanel<'a> {
    /// Label, e.g. "normal, 15 spheres".
    pub label: &'a str,
    /// The spheres.
    pub filling: &'a SphereFilling,
    /// The exact shape, drawn as an outline, if analytic.
    pub outline: Option<&'a PodShape>,
}

/// Draws `panels` (one row each, side and top views) as an SVG at `path`, atomically.
pub fn write_fillings_svg(path: &Path, panels: &[PicturePanel]) -> anyhow::Result<()> {
    let svg = fillings_svg(panels)?;
    write_string_atomic(path, &svg)
}

/// The SVG text of [`write_fillings_svg`].
pub fn fillings_svg(panels: &[PicturePanel]) -> anyhow::Result<String> {
    // Panel size from the largest half-extents over all panels (same scale everywhere).
    let mut half = [1.0f64; 3];
    for p in panels {
        if let Some(b) = p.filling.bounds_mm() {
            half = [0, 1, 2].map(|a| half[a].max(b.min_mm[a].abs()).max(b.max_mm[a].abs()));
        }
        if let Some(shape) = p.outline {
            let e = [shape.width_mm(), shape.thickness_mm(), shape.length_mm()];
            half = [0, 1, 2].map(|a| half[a].max(0.5 * e[a]));
        }
    }
    let largest = half.iter().cloned().fold(0.0, f64::max);
    let scale = PX_PER_MM.min(MAX_PANEL_PX / (2.0 * largest));
    let px = |mm: f64| (mm * scale).round() as i32;
    let panel_w = px(2.0 * half[2]);
    let panel_h = px(2.0 * half[0].max(half[1]));
    let width = 2 * panel_w + 3 * GAP_PX;
    let row_h = panel_h + LABEL_PX + GAP_PX;
    let height = panels.len().max(1) as i32 * row_h + GAP_PX;
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (width as u32, height as u32)).into_drawing_area();
        root.fill(&WHITE).context("SVG background")?;
        let fill_style = RGBAColor(30, 100, 200, 0.25).filled();
        let edge_style = RGBColor(30, 60, 140).stroke_width(1);
        for (row, p) in panels.iter().enumerate() {
            let top = GAP_PX + row as i32 * row_h;
            root.draw(&Text::new(
                p.label.to_owned(),
                (GAP_PX, top),
                ("sans-serif", 16).into_font(),
            ))
            .context("SVG label")?;
            // View 0: side (vertical axis y), view 1: top (vertical axis x).
            for (view, (vertical, name)) in [(1usize, "side (L × H)"), (0usize, "top (L × W)")]
                .into_iter()
                .enumerate()
            {
                let left = GAP_PX + view as i32 * (panel_w + GAP_PX);
                let cx = left + panel_w / 2;
                let cy = top + LABEL_PX + panel_h / 2;
                let to_px = |z: f64, v: f64| (cx + px(z), cy - px(v));
                root.draw(&Text::new(
                    name.to_owned(),
                    (left + panel_w - 90, top),
                    ("sans-serif", 12).into_font(),
                ))
                .context("SVG label")?;
                for s in &p.filling.spheres {
                    let centre = to_px(s.centre_mm[2], s.centre_mm[vertical]);
                    let r = px(s.radius_mm).max(1);
                    root.draw(&Circle::new(centre, r, fill_style))
                        .context("SVG circle")?;
                    root.draw(&Circle::new(centre, r, edge_style))
                        .context("SVG circle")?;
                }
                if let Some(shape) = p.outline {
                    let half_v = 0.5 * [shape.width_mm(), shape.thickness_mm()][vertical];
                    let half_l = 0.5 * shape.length_mm();
                    let zs: Vec<f64> = (0..=OUTLINE_POINTS)
                        .map(|n| -half_l + 2.0 * half_l * n as f64 / OUTLINE_POINTS as f64)
                        .collect();
                    let upper = zs
                        .iter()
                        .map(|&z| to_px(z, half_v * shape.section_scale(z)));
                    let lower = zs
                        .iter()
                        .rev()
                        .map(|&z| to_px(z, -half_v * shape.section_scale(z)));
                    let mut outline: Vec<(i32, i32)> = upper.chain(lower).collect();
                    outline.push(outline[0]);
                    root.draw(&PathElement::new(outline, BLACK.stroke_width(1)))
                        .context("SVG outline")?;
                }
            }
        }
        root.present().context("SVG present")?;
    }
    Ok(svg)
}
