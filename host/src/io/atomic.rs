//! Atomic output files.
//!
//! Every output file is first written to a temporary file in the same directory and then
//! renamed over the destination, so an error or an interruption half-way never leaves a
//! partial file behind: the destination either holds the complete new content or is
//! untouched.
//!
//! The temporary file is named `.NAME.arachis.HOST.PID.XXXXXX` after its destination NAME, the
//! machine and the writing process. A process killed mid-write (`kill -9`) cannot remove it,
//! so the next run's first write of the same destination removes every such file left by a
//! process of this machine that is no longer running (each folder is listed once per run);
//! files of live processes, and of other machines sharing the folder, are left alone. Outputs are created with mode 0666 less the umask
//! (0644 under the usual umask 022), as a plain `File::create` would.
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("design.csv");
//! arachis::io::write_string_atomic(&path, "A,B\n-1,1\n").unwrap();
//! assert_eq!(std::fs::read_to_string(&path).unwrap(), "A,B\n-1,1\n");
//! ```

use std::collections::BTreeMap;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock, PoisonError};

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
    let stem = temporary_stem(path);
    remove_stale_temporaries(dir, &stem);
    let prefix = format!("{stem}{}.{}.", host_name(), std::process::id());
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // The umask applies to the mode at creation, as for File::create.
        builder.permissions(std::fs::Permissions::from_mode(OUTPUT_MODE));
    }
    let tmp = builder
        .tempfile_in(dir)
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

/// Mode of a new output file before the umask: read and write for everyone, as
/// `File::create` asks.
#[cfg(unix)]
const OUTPUT_MODE: u32 = 0o666;

/// The start of every temporary file name of destination `path`: `.NAME.arachis.`.
fn temporary_stem(path: &Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    format!(".{name}.arachis.")
}

/// This machine's name (Linux), or `localhost`; dots are dropped so the name parses back.
/// Read once per process.
fn host_name() -> &'static str {
    static HOST: OnceLock<String> = OnceLock::new();
    HOST.get_or_init(|| {
        std::fs::read_to_string("/proc/sys/kernel/hostname")
            .map(|h| h.trim().replace('.', "_"))
            .ok()
            .filter(|h| !h.is_empty())
            .unwrap_or_else(|| "localhost".into())
    })
}

/// `true` when process `pid` of this machine is running. Without `/proc` (not Linux) every
/// process counts as running, so nothing is removed.
fn process_running(pid: u32) -> bool {
    let proc = Path::new("/proc");
    !proc.is_dir() || proc.join(pid.to_string()).exists()
}

/// The temporary files in a folder that dead processes of this machine left, by folder: each
/// folder is listed once per process, not once per write (a run writing thousands of VTK
/// frames into one folder would otherwise list it for every frame).
static STALE: Mutex<BTreeMap<PathBuf, Vec<String>>> = Mutex::new(BTreeMap::new());

/// Removes the temporary files of the destination named by `stem` in `dir` that a process
/// of this machine left behind when it died. Errors are ignored: a file that cannot be
/// listed or removed costs disk space, not correctness.
fn remove_stale_temporaries(dir: &Path, stem: &str) {
    let mut stale = STALE.lock().unwrap_or_else(PoisonError::into_inner);
    let names = stale
        .entry(dir.to_path_buf())
        .or_insert_with(|| stale_in(dir));
    names.retain(|name| {
        let ours = name.starts_with(stem);
        if ours {
            let _ = std::fs::remove_file(dir.join(name));
        }
        !ours
    });
}

/// The names in `dir` of temporary files (`.NAME.arachis.HOST.PID.XXXXXX`) whose writer, a
/// process of this machine, is no longer running.
fn stale_in(dir: &Path) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    entries
        .flatten()
        .filter_map(|e| e.file_name().into_string().ok())
        .filter(|name| {
            // …arachis.HOST.PID.XXXXXX, the random part without dots.
            let mut parts = name.rsplitn(4, '.');
            let (_random, pid, owner, head) =
                (parts.next(), parts.next(), parts.next(), parts.next());
            let dead = pid
                .and_then(|p| p.parse::<u32>().ok())
                .is_some_and(|p| !process_running(p));
            name.starts_with('.')
                && head.is_some_and(|h| h.ends_with(".arachis"))
                && owner == Some(host_name())
                && dead
        })
        .collect()
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

    /// A temporary file left by a killed writer of this machine is removed by the next write of
    /// the same destination; one of a running process, one of another machine and one of
    /// another destination are kept.
    #[test]
    fn the_next_write_removes_a_killed_writers_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("design.csv");
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let dead = child.id();
        child.wait().unwrap();
        let host = host_name();
        let stem = temporary_stem(&path);
        let left = dir.path().join(format!("{stem}{host}.{dead}.Ab12Cd"));
        let live = dir
            .path()
            .join(format!("{stem}{host}.{}.Ef34Gh", std::process::id()));
        let elsewhere = dir.path().join(format!("{stem}other_host.{dead}.Ij56Kl"));
        let other = dir
            .path()
            .join(format!(".other.csv.arachis.{host}.{dead}.Mn78Op"));
        for f in [&left, &live, &elsewhere, &other] {
            std::fs::write(f, "partial").unwrap();
        }
        write_string_atomic(&path, "A\n").unwrap();
        assert!(!left.exists(), "the killed writer's file was kept");
        assert!(live.exists() && elsewhere.exists() && other.exists());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "A\n");
    }

    /// Outputs follow the umask like File::create, instead of the 0600 of a temporary file.
    #[cfg(unix)]
    #[test]
    fn outputs_follow_the_umask() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let reference = dir.path().join("reference");
        std::fs::File::create(&reference).unwrap();
        let path = dir.path().join("out.json");
        write_string_atomic(&path, "{}").unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&path), mode(&reference));
        assert_ne!(mode(&path), 0o600, "umask 077 would make this test vacuous");
    }
}
