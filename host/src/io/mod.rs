//! Input and output shared by every host module: CSV tables whose errors name the file,
//! line and column, and atomic file writes that never leave a half-written output behind.

pub mod atomic;
pub mod table;

pub use atomic::{write_atomic, write_string_atomic};
pub use table::{CsvTable, InputError};
