//! A design as CSV text: comment lines describing the design and its factors, then one row
//! per run with `run`, `std_order`, `point`, the coded columns (`<name>_coded`, dummy columns
//! included) and the actual columns (`<name>`, in the unit the comments give).
//!
//! The comment lines start with `#`, so [`crate::io::CsvTable`] reads the file back directly.

use std::fmt::Write;

use super::Design;

/// Significant digits kept when printing a level: enough for any measured quantity while
/// hiding binary noise such as 0.8574999999999999 for 0.8575.
const SIGNIFICANT_DIGITS: usize = 12;

/// Formats `v` with at most [`SIGNIFICANT_DIGITS`] significant digits and no trailing zeros.
pub fn format_level(v: f64) -> String {
    format_significant(v, SIGNIFICANT_DIGITS)
}

/// Formats `v` rounded to `digits` (≥ 1) significant digits, without trailing zeros.
pub fn format_significant(v: f64, digits: usize) -> String {
    let rounded: f64 = format!("{:.*e}", digits.max(1) - 1, v).parse().unwrap_or(v);
    // `-0` would look like a level of its own.
    let rounded = if rounded == 0.0 { 0.0 } else { rounded };
    format!("{rounded}")
}

/// The design as CSV text, rows in run order.
pub fn design_to_csv(design: &Design) -> String {
    let mut out = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(
        out,
        "# design: {}, {} runs, {} factors{}",
        design.kind,
        design.runs(),
        design.factors.len(),
        if design.dummy_columns.is_empty() {
            String::new()
        } else {
            format!(" + {} dummy columns", design.dummy_columns.len())
        }
    );
    for f in &design.factors {
        let _ = writeln!(
            out,
            "# factor {}: unit {}, coded -1 = {}, 0 = {}, +1 = {}",
            f.name,
            f.unit,
            format_level(f.low),
            format_level(f.centre()),
            format_level(f.high)
        );
    }
    for d in &design.dummy_columns {
        let _ = writeln!(out, "# dummy column {d}: coded only");
    }
    let mut header = vec!["run".to_owned(), "std_order".into(), "point".into()];
    header.extend(design.column_names().iter().map(|n| format!("{n}_coded")));
    header.extend(design.factors.iter().map(|f| f.name.clone()));
    let _ = writeln!(out, "{}", header.join(","));
    for (run, &std) in design.run_order.iter().enumerate() {
        let mut cells = vec![
            (run + 1).to_string(),
            (std + 1).to_string(),
            design.point_types[std].label().to_owned(),
        ];
        cells.extend(design.coded[std].iter().map(|&x| format_level(x)));
        cells.extend(design.actual_row(std).into_iter().map(format_level));
        let _ = writeln!(out, "{}", cells.join(","));
    }
    out
}
