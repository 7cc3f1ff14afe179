//! A pre-flight check of scanned-pod STL files: present, readable, and plausibly STL.
//!
//! This is not the STL parser (that belongs to the `shapes` module, issue 4 §1, which was
//! not merged when this check was written). It rejects, before any simulation, what would
//! certainly fail later:
//! - a missing or unreadable file;
//! - a binary STL whose size is not 84 + 50·N bytes for the triangle count N in bytes
//!   80–83 (80-byte header, u32 count, 50 bytes per triangle);
//! - a file that is not binary by that rule and does not read as ASCII STL (`solid` …
//!   `facet` … `endsolid`).
//!
//! A binary STL may itself begin with the word `solid`, so the size rule is tried first.

use std::io::Read;
use std::path::Path;

/// Bytes of a binary STL header before the triangle count.
const BINARY_HEADER_BYTES: u64 = 80;
/// Header plus the little-endian u32 triangle count.
const BINARY_PREAMBLE_BYTES: u64 = BINARY_HEADER_BYTES + 4;
/// Normal (3 × f32), three vertices (9 × f32) and a u16 attribute.
const BINARY_TRIANGLE_BYTES: u64 = 50;

/// Which STL flavour a file passed the check as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StlKind {
    /// Binary, with this many triangles.
    Binary(u32),
    /// ASCII.
    Ascii,
}

/// Checks `path`; the error is the reason in words.
pub fn check_stl(path: &Path) -> Result<StlKind, String> {
    let metadata =
        std::fs::metadata(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    if !metadata.is_file() {
        return Err(format!("{} is not a file", path.display()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(metadata.len()).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let size = bytes.len() as u64;
    if size >= BINARY_PREAMBLE_BYTES {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
        let expected = BINARY_PREAMBLE_BYTES + BINARY_TRIANGLE_BYTES * u64::from(count);
        if expected == size {
            return if count == 0 {
                Err(format!("{}: binary STL with no triangles", path.display()))
            } else {
                Ok(StlKind::Binary(count))
            };
        }
    }
    let text = String::from_utf8_lossy(&bytes);
    let trimmed = text.trim_start();
    if trimmed.starts_with("solid") && text.contains("facet") && text.contains("endsolid") {
        return Ok(StlKind::Ascii);
    }
    let binary_note = if size >= BINARY_PREAMBLE_BYTES {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]);
        format!(
            "as binary it claims {count} triangles, which needs {} bytes",
            BINARY_PREAMBLE_BYTES + BINARY_TRIANGLE_BYTES * u64::from(count)
        )
    } else {
        format!("shorter than the {BINARY_PREAMBLE_BYTES}-byte binary header")
    };
    Err(format!(
        "{} is not an STL file: {size} bytes, {binary_note}, and it does not read as ASCII STL \
         (solid … facet … endsolid)",
        path.display()
    ))
}
