//! The picture of a harvest frame (`arachis field --harvester … --section FILE.svg`): a
//! side view of a slice of the world along the ridge, every sphere whose centre lies within
//! [`SECTION_HALF_WIDTH_M`] of the section's plane a disc: soil grains brown, stems, stalks
//! and leaves green, pods tan, the machine's steel grey. A slice, because the whole bed seen
//! from the side is a wall of grains that hides the shovel and the pods.
//!
//! The map of where pods ended (`--pod-map FILE.svg`) is a plan view of every pod, drawn
//! where it is at the end of the run and coloured by its end ([`PodEnd`]): collected,
//! unpicked, or lost and where, with a legend and the bed's outline.

use std::path::Path;

use anyhow::anyhow;
use arachis_core::prelude::*;
use arachis_core::units::LENGTH_M_TO_MM;
use plotters::prelude::*;

use super::loss::{PodEnd, Where};
use crate::field::world::FieldMaterials;
use crate::io::write_atomic;
use crate::plant::picture::{write_disc_picture, Disc, View};

/// Half the thickness of the drawn slice, m (about four grain diameters).
pub const SECTION_HALF_WIDTH_M: f64 = 0.03;

/// Colour of each material of a harvest.
fn colour(material: u16, m: &FieldMaterials, steel: MaterialId) -> RGBColor {
    match material {
        x if x == m.soil.0 => RGBColor(150, 115, 80),
        x if x == m.pod.0 => RGBColor(215, 175, 110),
        x if x == m.plant.0 => RGBColor(60, 120, 50),
        x if x == steel.0 => RGBColor(90, 90, 100),
        _ => RGBColor(0, 0, 0),
    }
}

/// Writes the side view of the spheres of `world` within [`SECTION_HALF_WIDTH_M`] of the
/// plane y = `y_m` to `path` (must end in `.svg`).
pub fn write_section_picture<S: Scalar>(
    path: &Path,
    world: &World<'_, S>,
    materials: &FieldMaterials,
    steel: MaterialId,
    y_m: f64,
    title: &str,
) -> anyhow::Result<()> {
    let discs: Vec<Disc> = world
        .spheres()
        .iter()
        .filter_map(|s| {
            let [x, y, z] = s.position.to_f64();
            ((y / LENGTH_M_TO_MM - y_m).abs() <= SECTION_HALF_WIDTH_M).then(|| {
                (
                    x,
                    z,
                    s.radius.to_f64(),
                    colour(s.material, materials, steel),
                )
            })
        })
        .collect();
    let caption = format!(
        "{title}: t = {:.3} s, slice {:.0} ± {:.0} mm across the ridge",
        world.time_s(),
        y_m * LENGTH_M_TO_MM,
        SECTION_HALF_WIDTH_M * LENGTH_M_TO_MM
    );
    let view = View {
        x_desc: "x, along the ridge (mm)",
        y_desc: "height above the ground (mm)",
        soil_surface: true,
    };
    write_disc_picture(path, &discs, &caption, &view)
}

/// Width of the pod map's plot, pixels.
const MAP_WIDTH_PX: u32 = 1100;
/// Room round the bed on the pod map, mm.
const MAP_ROOM_MM: f64 = 60.0;
/// Room for the legend right of the pods, as a fraction of their extent along x.
const MAP_LEGEND_ROOM: f64 = 0.45;
/// Radius of a pod's dot on the map, pixels.
const MAP_DOT_PX: i32 = 5;

/// Every end a pod can have, in the legend's order, with its label and colour.
pub const POD_END_STYLES: [(PodEnd, &str, RGBColor); 8] = [
    (PodEnd::Collected, "collected", RGBColor(30, 140, 60)),
    (
        PodEnd::Unpicked,
        "unpicked (on the vine)",
        RGBColor(120, 160, 40),
    ),
    (
        PodEnd::Lost(Where::InSoil),
        "lost: in the soil",
        RGBColor(120, 80, 40),
    ),
    (
        PodEnd::Lost(Where::Shovel),
        "lost: off the shovel",
        RGBColor(200, 40, 40),
    ),
    (
        PodEnd::Lost(Where::Chain),
        "lost: through the chain",
        RGBColor(230, 120, 20),
    ),
    (
        PodEnd::Lost(Where::Behind),
        "lost: behind the collector",
        RGBColor(150, 40, 160),
    ),
    (
        PodEnd::Lost(Where::Beside),
        "lost: beside the machine",
        RGBColor(40, 90, 200),
    ),
    (
        PodEnd::Lost(Where::OnMachine),
        "still on the machine",
        RGBColor(90, 90, 100),
    ),
];

/// Writes the plan view of `pods` (body and end) in `world` to `path` (must end in `.svg`),
/// with the bed from `bed_min_m` to `bed_max_m` outlined.
pub fn write_pod_map<S: Scalar>(
    path: &Path,
    world: &World<'_, S>,
    pods: &[(BodyId, PodEnd)],
    bed_min_m: [f64; 3],
    bed_max_m: [f64; 3],
    title: &str,
) -> anyhow::Result<()> {
    if path.extension().and_then(|e| e.to_str()) != Some("svg") {
        anyhow::bail!("pod map {}: the file name must end in .svg", path.display());
    }
    let at = |id: BodyId| {
        let [x, y, _] = world.body(id).position.to_f64();
        (x, y)
    };
    let (bx0, by0) = (bed_min_m[0] * LENGTH_M_TO_MM, bed_min_m[1] * LENGTH_M_TO_MM);
    let (bx1, by1) = (bed_max_m[0] * LENGTH_M_TO_MM, bed_max_m[1] * LENGTH_M_TO_MM);
    let spread = |pick: fn((f64, f64)) -> f64, lo: f64, hi: f64| {
        pods.iter()
            .map(|&(id, _)| pick(at(id)))
            .fold((lo, hi), |(a, b), v| (a.min(v), b.max(v)))
    };
    let (x0, x1) = spread(|p| p.0, bx0, bx1);
    let (y0, y1) = spread(|p| p.1, by0, by1);
    let (x0, x1, y0, y1) = (
        x0 - MAP_ROOM_MM,
        x1 + MAP_ROOM_MM,
        y0 - MAP_ROOM_MM,
        y1 + MAP_ROOM_MM,
    );
    // Room on the right for the legend, so it covers no pod.
    let x1 = x1 + MAP_LEGEND_ROOM * (x1 - x0);
    let plot_h = (f64::from(MAP_WIDTH_PX) * (y1 - y0) / (x1 - x0)) as u32;
    let size = (MAP_WIDTH_PX + 60, plot_h.max(220) + 110);
    let caption = format!("{title}: where the pods ended, t = {:.3} s", world.time_s());
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        let err = |e: DrawingAreaErrorKind<_>| anyhow!("cannot draw the pod map: {e}");
        root.fill(&WHITE).map_err(err)?;
        let mut chart = ChartBuilder::on(&root)
            .margin(10)
            .caption(caption, ("sans-serif", 16))
            .x_label_area_size(30)
            .y_label_area_size(45)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x, along the ridge (mm)")
            .y_desc("y, across the ridge (mm)")
            .draw()
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(bx0, by0), (bx1, by1)],
                RGBColor(150, 115, 80).stroke_width(2),
            )))
            .map_err(err)?
            .label("soil bed")
            .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], RGBColor(150, 115, 80)));
        for (end, label, colour) in POD_END_STYLES {
            let here: Vec<(f64, f64)> = pods
                .iter()
                .filter(|(_, e)| *e == end)
                .map(|&(id, _)| at(id))
                .collect();
            if here.is_empty() {
                continue;
            }
            chart
                .draw_series(
                    here.iter()
                        .map(|&p| Circle::new(p, MAP_DOT_PX, colour.filled())),
                )
                .map_err(err)?
                .label(format!("{label}: {}", here.len()))
                .legend(move |(x, y)| Circle::new((x + 6, y), MAP_DOT_PX, colour.filled()));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
        root.present().map_err(err)?;
    }
    write_atomic(path, |w| Ok(w.write_all(svg.as_bytes())?))
}
