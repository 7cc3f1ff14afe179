//! The picture of a field (`arachis field --picture FILE.svg`): the plan view from above,
//! every plant sphere a disc coloured by its organ as in [`crate::plant::picture`], the
//! rows along x. The soil grains are not drawn (tens of thousands of them would hide the
//! pods); the caption gives their count and the bed's extent.

use std::path::Path;

use arachis_core::units::LENGTH_M_TO_MM;

use super::Field;
use crate::plant::picture::{organ_colour, write_disc_picture, Disc, View};

/// Writes the plan view of `field` to `path` (must end in `.svg`).
pub fn write_field_picture(path: &Path, field: &Field, title: &str) -> anyhow::Result<()> {
    // Lower spheres first, so the stems and leaves above the soil are drawn over the pods.
    let mut discs: Vec<(f64, Disc)> = field
        .plants
        .iter()
        .flat_map(|p| {
            p.model.spheres.iter().map(|s| {
                let [x, y, z] = s.centre_m.map(|c| c * LENGTH_M_TO_MM);
                (
                    z,
                    (
                        x,
                        y,
                        s.radius_m * LENGTH_M_TO_MM,
                        organ_colour(p.model.bodies[s.body].kind),
                    ),
                )
            })
        })
        .collect();
    discs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let discs: Vec<Disc> = discs.into_iter().map(|(_, d)| d).collect();
    let size_mm = |k: usize| (field.bed_max_m[k] - field.bed_min_m[k]) * LENGTH_M_TO_MM;
    let caption = format!(
        "{title}: {} plants, {} pods; {} soil grains (not drawn) in a bed {:.0} × {:.0} × {:.0} mm",
        field.plants.len(),
        field.pods(),
        field.grains.len(),
        size_mm(0),
        size_mm(1),
        size_mm(2)
    );
    let view = View {
        x_desc: "x, along the ridge (mm)",
        y_desc: "y, across the ridge (mm)",
        soil_surface: false,
    };
    write_disc_picture(path, &discs, &caption, &view)
}
