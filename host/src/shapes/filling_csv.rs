//! A sphere filling as CSV rows `x_mm,y_mm,z_mm,r_mm` (body frame), written atomically and
//! read back with file/line/column errors.
//!
//! ```
//! use arachis::shapes::{filling_csv, read_filling_csv, Sphere, SphereFilling};
//! let filling = SphereFilling {
//!     spheres: vec![Sphere { centre_mm: [0.0, 0.0, 4.5], radius_mm: 7.25 }],
//!     covered_fraction: 1.0,
//!     fill_spacing_mm: 0.5,
//! };
//! assert_eq!(filling_csv(&filling), "x_mm,y_mm,z_mm,r_mm\n0,0,4.5,7.25\n");
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("pod.csv");
//! arachis::shapes::write_filling_csv(&path, &filling).unwrap();
//! assert_eq!(read_filling_csv(&path).unwrap(), filling.spheres);
//! ```

use std::path::Path;

use crate::io::{write_string_atomic, CsvTable, InputError};

use super::sphere_fill::{Sphere, SphereFilling};

/// Column headers, in order.
pub const FILLING_CSV_COLUMNS: [&str; 4] = ["x_mm", "y_mm", "z_mm", "r_mm"];

/// The filling as CSV text: a header row, then one row per sphere in placement order,
/// numbers in Rust's shortest round-trip form.
pub fn filling_csv(filling: &SphereFilling) -> String {
    let mut out = FILLING_CSV_COLUMNS.join(",") + "\n";
    for s in &filling.spheres {
        let [x, y, z] = s.centre_mm;
        out += &format!("{x},{y},{z},{}\n", s.radius_mm);
    }
    out
}

/// Writes [`filling_csv`] to `path` atomically.
pub fn write_filling_csv(path: &Path, filling: &SphereFilling) -> anyhow::Result<()> {
    write_string_atomic(path, &filling_csv(filling))
}

/// Reads spheres from a CSV with the columns of [`FILLING_CSV_COLUMNS`]; radii must be > 0.
pub fn read_filling_csv(path: &Path) -> Result<Vec<Sphere>, InputError> {
    let table = CsvTable::read(path)?;
    let [x, y, z] = ["x_mm", "y_mm", "z_mm"].map(|c| table.f64_column(c));
    let (x, y, z) = (x?, y?, z?);
    let r = table.f64_column_checked("r_mm", |r| {
        if r > 0.0 {
            Ok(())
        } else {
            Err(format!("radius {r} mm must be > 0"))
        }
    })?;
    Ok((0..r.len())
        .map(|n| Sphere {
            centre_mm: [x[n], y[n], z[n]],
            radius_mm: r[n],
        })
        .collect())
}
