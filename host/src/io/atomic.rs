//! Atomic output files.
//!
//! Every output file is first written to a temporary file in the same directory and then
//! renamed over the destination, so an error or an interruption half-way never leaves a
//! partial file behind: the destination either holds the complete new content or is
//! untouched.
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("design.csv");
//! arachis::io::write_string_atomic(&path, "A,B\n-1,1\n").unwrap();
//! assert_eq!(std::fs::read_to_string(&path).unwrap(), "A,B\n-1,1\n");
//! ```

use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::Context;

/// Writes `path` atomically: `fill` writes the content into a temporary file next to
/// `path`, which replaces `path` only when `fill` and the flush succeed.
pub fn write_atomic<F>(path: &Path, fill: F) -> anyhow::Result<()>
where
    F: FnOnce(&mut dyn Write) -> anyhow::Result<()>,
{
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let tmp = tempfile::NamedTempFile::new_in(dir)
        .with_context(|| format!("cannot create a temporary file in {}", dir.display()))?;
    {
        let mut out = BufWriter::new(tmp.as_file());
        fill(&mut out)?;
        out.flush()
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    tmp.persist(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// Writes `content` to `path` atomically (see [`write_atomic`]).
pub fn write_string_atomic(path: &Path, content: &str) -> anyhow::Result<()> {
    write_atomic(path, |w| {
        w.write_all(content.as_bytes())?;
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_fill_leaves_no_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.csv");
        let err = write_atomic(&path, |w| {
            w.write_all(b"partial")?;
            anyhow::bail!("simulated failure")
        });
        assert!(err.is_err());
        assert!(!path.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn failed_fill_keeps_previous_content() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.csv");
        write_string_atomic(&path, "old").unwrap();
        let _ = write_atomic(&path, |_| anyhow::bail!("simulated failure"));
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
    }
}
