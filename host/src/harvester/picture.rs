//! The picture of a harvest frame (`arachis field --harvester … --section FILE.svg`): a
//! side view of a slice of the world along the ridge, every sphere whose centre lies within
//! [`SECTION_HALF_WIDTH_M`] of the section's plane a disc: soil grains brown, stems, stalks
//! and leaves green, pods tan, the machine's steel grey. A slice, because the whole bed seen
//! from the side is a wall of grains that hides the shovel and the pods.

use std::path::Path;

use arachis_core::prelude::*;
use arachis_core::units::LENGTH_M_TO_MM;
use plotters::style::RGBColor;

use crate::field::world::FieldMaterials;
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
