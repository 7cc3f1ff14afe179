//! The picture of a plant (`arachis plant --picture FILE.svg`): a side view along y, every
//! sphere a disc coloured by its organ (stems green, pod stalks brown, pods tan, leaves
//! light green), the soil surface (z = 0, the root) as a line. Drawn with plotters at equal
//! scales (mm) and written atomically. SVG only: it carries the caption and axes as text
//! (see `crate::rigs::repose_picture` for why a PNG of plotters carries none).
//!
//! ```no_run
//! use arachis::plant::{generate, picture::write_plant_picture, Topology, SHIPPED_TOPOLOGY};
//! let plant = generate(&Topology::from_toml(SHIPPED_TOPOLOGY).unwrap()).unwrap();
//! write_plant_picture(std::path::Path::new("plant.svg"), &plant, "the shipped plant").unwrap();
//! ```

use std::path::Path;

use anyhow::{anyhow, bail};
use arachis_core::units::LENGTH_M_TO_MM;
use plotters::prelude::*;

use super::topology::Kind;
use super::PlantModel;
use crate::io::write_atomic;

/// Picture width, pixels.
const WIDTH_PX: u32 = 1100;
/// Room for the caption, axes and margins, pixels.
const FRAME_PX: u32 = 110;
/// Empty room round the plant, mm.
const ROOM_MM: f64 = 20.0;

/// One sphere as drawn: the two coordinates of its centre, its radius (mm), its colour.
pub(crate) type Disc = (f64, f64, f64, RGBColor);

/// The colour of an organ.
pub(crate) fn organ_colour(kind: Kind) -> RGBColor {
    match kind {
        Kind::MainStem | Kind::LateralStem => RGBColor(60, 120, 50),
        Kind::PodStalk => RGBColor(140, 90, 40),
        Kind::Pod => RGBColor(215, 175, 110),
        Kind::Leaf => RGBColor(150, 200, 110),
    }
}

/// Writes the side view of `plant` to `path` (must end in `.svg`).
pub fn write_plant_picture(path: &Path, plant: &PlantModel, title: &str) -> anyhow::Result<()> {
    let discs: Vec<Disc> = plant
        .spheres
        .iter()
        .map(|s| {
            let [x, _, z] = s.centre_m.map(|c| c * LENGTH_M_TO_MM);
            (
                x,
                z,
                s.radius_m * LENGTH_M_TO_MM,
                organ_colour(plant.bodies[s.body].kind),
            )
        })
        .collect();
    let view = View {
        x_desc: "x (mm)",
        y_desc: "height above the soil surface (mm)",
        soil_surface: true,
    };
    write_disc_picture(path, &discs, title, &view)
}

/// How a picture of discs is labelled.
pub(crate) struct View {
    /// Label of the horizontal axis.
    pub x_desc: &'static str,
    /// Label of the vertical axis.
    pub y_desc: &'static str,
    /// Draw the soil surface (vertical coordinate 0) as a line.
    pub soil_surface: bool,
}

/// Writes `discs` (centre and radius in mm, organ) at equal scales to `path` (must end in
/// `.svg`), with `title` and the axes of `view`.
pub(crate) fn write_disc_picture(
    path: &Path,
    discs: &[Disc],
    title: &str,
    view: &View,
) -> anyhow::Result<()> {
    if path.extension().and_then(|e| e.to_str()) != Some("svg") {
        bail!("picture {}: the file name must end in .svg", path.display());
    }
    if discs.is_empty() {
        bail!("there is no sphere to draw");
    }
    let lowest = |pick: &dyn Fn(&Disc) -> f64| discs.iter().map(pick).fold(f64::INFINITY, f64::min);
    let x0 = lowest(&|d| d.0 - d.2) - ROOM_MM;
    let x1 = -lowest(&|d| -(d.0 + d.2)) + ROOM_MM;
    let z0 = if view.soil_surface {
        lowest(&|d| d.1 - d.2).min(0.0)
    } else {
        lowest(&|d| d.1 - d.2)
    } - ROOM_MM;
    let z1 = -lowest(&|d| -(d.1 + d.2)) + ROOM_MM;
    let plot_h = (f64::from(WIDTH_PX) * (z1 - z0) / (x1 - x0)) as u32;
    let size = (WIDTH_PX + FRAME_PX, plot_h.max(100) + FRAME_PX);
    let px_per_mm = f64::from(WIDTH_PX) / (x1 - x0);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        let err = |e: DrawingAreaErrorKind<_>| anyhow!("cannot draw the plant picture: {e}");
        root.fill(&WHITE).map_err(err)?;
        let mut chart = ChartBuilder::on(&root)
            .margin(10)
            .caption(title, ("sans-serif", 16))
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(x0..x1, z0..z1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(view.x_desc)
            .y_desc(view.y_desc)
            .draw()
            .map_err(err)?;
        if view.soil_surface {
            chart
                .draw_series(LineSeries::new(
                    [(x0, 0.0), (x1, 0.0)],
                    RGBColor(120, 80, 40),
                ))
                .map_err(err)?;
        }
        chart
            .draw_series(discs.iter().map(|&(x, z, r, colour)| {
                let radius_px = ((r * px_per_mm).round() as i32).max(1);
                Circle::new((x, z), radius_px, colour.filled())
            }))
            .map_err(err)?;
        root.present().map_err(err)?;
    }
    write_atomic(path, |w| Ok(w.write_all(svg.as_bytes())?))
}
