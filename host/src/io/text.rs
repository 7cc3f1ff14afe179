//! Reading a text input file: like `std::fs::read_to_string`, but a file that is not UTF-8
//! is refused with the line and offset of its first bad byte, so the user can find it (the
//! standard message names neither).
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("study.toml");
//! std::fs::write(&path, b"[study]\nname = \"caf\xe9\"\n").unwrap();
//! let e = arachis::io::text::read_text(&path).unwrap_err();
//! assert!(e.to_string().contains("line 2"), "{e}");
//! ```

use std::io;
use std::path::Path;

/// The text of `path`; an I/O error as `std::fs::read_to_string` gives it, or
/// [`io::ErrorKind::InvalidData`] naming the line (1-based) and byte offset of the first byte
/// that is not UTF-8.
pub fn read_text(path: &Path) -> io::Result<String> {
    let bytes = std::fs::read(path)?;
    String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let line = 1 + e.as_bytes()[..offset]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("not UTF-8 text: the first bad byte is on line {line} (byte offset {offset})"),
        )
    })
}
