//! Reading checked numeric columns from a bench-test CSV.
//!
//! Each helper rejects a value outside its physical range at its own line and column, with
//! the reason (for example "deformation must be positive, got -0.2"), so no analysis ever
//! sees a negative deformation, a zero mass or an angle past 90°.

use crate::io::{CsvTable, InputError};

use super::error::LabError;

/// The column `name`, every value > 0. `what` names the quantity in the message.
pub fn positive(table: &CsvTable, name: &str, what: &str) -> Result<Vec<f64>, InputError> {
    table.f64_column_checked(name, |v| {
        if v > 0.0 {
            Ok(())
        } else {
            Err(format!("{what} must be positive, got {v}"))
        }
    })
}

/// The column `name`, every value ≥ 0.
pub fn non_negative(table: &CsvTable, name: &str, what: &str) -> Result<Vec<f64>, InputError> {
    table.f64_column_checked(name, |v| {
        if v >= 0.0 {
            Ok(())
        } else {
            Err(format!("{what} must not be negative, got {v}"))
        }
    })
}

/// The column `name` in degrees, every value in `[low, high)`; `what` describes the angle.
pub fn angle_deg(
    table: &CsvTable,
    name: &str,
    low: f64,
    high: f64,
    what: &str,
) -> Result<Vec<f64>, InputError> {
    table.f64_column_checked(name, |v| {
        if (low..high).contains(&v) {
            Ok(())
        } else {
            Err(format!("{what} must be in [{low}°, {high}°), got {v}°"))
        }
    })
}

/// Whether the header has a column named `name`.
pub fn has(table: &CsvTable, name: &str) -> bool {
    table.headers.iter().any(|h| h == name)
}

/// 1-based line numbers of the data rows, in file order.
pub fn lines(table: &CsvTable) -> Vec<u64> {
    table.rows.iter().map(|r| r.line).collect()
}

/// A [`LabError::Row`] at data row `index` of `table`.
pub fn row_error(table: &CsvTable, index: usize, columns: &[&str], reason: String) -> LabError {
    LabError::Row {
        path: table.path.clone(),
        line: table.rows[index].line,
        columns: super::error::quote_columns(columns),
        reason,
    }
}
