//! Why a pod shape, a shape mix or an STL file was rejected.
//!
//! Every file error names the file; ASCII STL errors also give the 1-based line and column,
//! binary STL errors the byte offset, so the user can open the file at the fault.

use std::path::PathBuf;

use thiserror::Error;

/// A rejected shape parameter, shape mix or STL file.
#[derive(Debug, Error)]
pub enum ShapeError {
    /// A dimension or parameter is not a finite number in its allowed range.
    #[error("pod shape: {name} = {value} is invalid: {reason}")]
    InvalidParameter {
        /// The parameter's name, with its unit.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range.
        reason: &'static str,
    },
    /// Shape-mix fractions are negative, not finite, or do not sum to 1.
    #[error("shape mix: {reason}")]
    InvalidMix {
        /// What is wrong.
        reason: String,
    },
    /// The STL file could not be opened or read.
    #[error("{path}: cannot read STL: {reason}")]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        reason: String,
    },
    /// An ASCII STL file breaks the grammar or holds a bad number.
    #[error("{path}:{line}:{column}: malformed ASCII STL: {reason}")]
    MalformedAscii {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column (in characters).
        column: usize,
        /// What was expected and what was found.
        reason: String,
    },
    /// A binary STL file is truncated, too long, or holds a non-finite coordinate.
    #[error("{path}: byte {offset}: malformed binary STL: {reason}")]
    MalformedBinary {
        /// The file.
        path: PathBuf,
        /// 0-based byte offset of the fault.
        offset: usize,
        /// What is wrong.
        reason: String,
    },
    /// The mesh has no triangles, or an edge is not shared by exactly two triangles.
    #[error("{path}: STL mesh is not a closed surface: {reason}")]
    NotClosed {
        /// The file.
        path: PathBuf,
        /// Which edge is open or over-shared, and how many such edges there are.
        reason: String,
    },
}
