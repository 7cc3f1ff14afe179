//! Why a bench-test analysis rejected its input. Every message names the file, and where it
//! applies the line and the column(s), so a user can go straight to the bad cell.

use std::path::PathBuf;

use thiserror::Error;

use super::summary::SummaryError;
use crate::io::InputError;

/// A rejected bench-test input.
#[derive(Debug, Error)]
pub enum LabError {
    /// The CSV itself, or one cell of it, is bad (ragged row, non-numeric cell, missing
    /// column, value out of range).
    #[error(transparent)]
    Input(#[from] InputError),
    /// A row whose cells are each valid but together describe an impossible measurement.
    #[error("{path}:{line}: columns {columns}: {reason}")]
    Row {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// The columns involved, quoted and comma-separated.
        columns: String,
        /// What is impossible about them.
        reason: String,
    },
    /// The replicates of a quantity cannot be summarised (too few of them).
    #[error("{path}: {quantity}: {cause}")]
    Summary {
        /// The file.
        path: PathBuf,
        /// The quantity being summarised.
        quantity: String,
        /// Why.
        cause: SummaryError,
    },
    /// The file lacks every accepted set of columns, or a needed setting is missing.
    #[error("{path}: {reason}")]
    Layout {
        /// The file.
        path: PathBuf,
        /// What is missing.
        reason: String,
    },
    /// A command-line setting is outside its physical range.
    #[error("option --{option}: {reason}")]
    Option {
        /// The option's long name.
        option: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// Quotes column names for [`LabError::Row`]: `'a', 'b'`.
pub fn quote_columns(columns: &[&str]) -> String {
    columns
        .iter()
        .map(|c| format!("'{c}'"))
        .collect::<Vec<_>>()
        .join(", ")
}
