//! Input and output shared by every host module: CSV tables whose errors name the file,
//! line and column, atomic file writes that never leave a half-written output behind, and
//! names from input that become file names, and text files refused at their first non-UTF-8
//! byte.

pub mod atomic;
pub mod file_name;
pub mod json_keys;
pub mod table;
pub mod text;

pub use atomic::{write_atomic, write_string_atomic};
pub use table::{CsvTable, InputError};
