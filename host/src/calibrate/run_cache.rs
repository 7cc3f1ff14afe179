//! The run cache: every finished simulation stored as one JSON file, `runs/<hash>.json`,
//! named by the [`SpecHash`] of its full [`RunSpec`] and written atomically.
//!
//! A stored run is replayed only when its file parses, its spec is byte-for-byte the
//! requested spec (canonical JSON, so a hash collision cannot mix two runs up) and it was
//! made by the same simulator ([`Simulator::id`]); anything else is simulated again and
//! overwritten. Because a file appears only when complete (rename over a temporary file),
//! an interrupted calibration leaves either a whole run or none, and a rerun picks up
//! exactly the runs that finished.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::error::CalibrateError;
use super::simulator::{RunResult, Simulator};
use crate::io::write_string_atomic;
use crate::study::spec_hash::write_canonical;
use crate::study::{RunSpec, SpecHash};

/// Format tag of a stored run.
pub const RUN_FORMAT: &str = "arachis-run-1";

/// Prefix of the temporary files `write_atomic` creates (the `tempfile` crate's default);
/// leftovers of a killed run are removed when the cache opens.
const TEMP_PREFIX: &str = ".tmp";

/// Removes the temporary files an interrupted atomic write left in `dir` (best effort: a
/// leftover that cannot be removed is ignored, never read).
pub fn remove_stale_temporaries(dir: &Path) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        if entry.file_name().to_string_lossy().starts_with(TEMP_PREFIX) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    Ok(())
}

/// One stored run as written.
#[derive(Serialize)]
struct StoredRun<'a> {
    format: &'static str,
    spec_hash: String,
    simulator: String,
    result: RunResult,
    spec: &'a RunSpec,
}

/// One stored run as read back.
#[derive(Deserialize)]
struct ReadRun {
    format: String,
    spec_hash: String,
    simulator: String,
    result: RunResult,
    spec: Value,
}

/// The folder of stored runs.
#[derive(Debug, Clone)]
pub struct RunCache {
    dir: PathBuf,
    simulator: String,
}

impl RunCache {
    /// Opens (creating) `dir` for runs of `simulator`, removing temporary files a killed
    /// calibration may have left.
    pub fn open(dir: &Path, simulator: &dyn Simulator) -> Result<Self, CalibrateError> {
        let io = |e: std::io::Error| CalibrateError::Io {
            path: dir.to_owned(),
            reason: e.to_string(),
        };
        std::fs::create_dir_all(dir).map_err(io)?;
        remove_stale_temporaries(dir).map_err(io)?;
        Ok(Self {
            dir: dir.to_owned(),
            simulator: simulator.id(),
        })
    }

    /// The file of `hash`.
    pub fn path(&self, hash: SpecHash) -> PathBuf {
        self.dir.join(format!("{hash}.json"))
    }

    /// The stored result of `spec`, if a valid one exists.
    pub fn load(&self, spec: &RunSpec, hash: SpecHash) -> Option<RunResult> {
        let text = std::fs::read_to_string(self.path(hash)).ok()?;
        let run: ReadRun = serde_json::from_str(&text).ok()?;
        let mut stored_spec = String::new();
        write_canonical(&run.spec, &mut stored_spec);
        let valid = run.format == RUN_FORMAT
            && run.spec_hash == hash.to_string()
            && run.simulator == self.simulator
            && stored_spec == spec.canonical_json()
            && run.result.response.is_finite();
        valid.then_some(run.result)
    }

    /// Stores `result` of `spec` atomically.
    pub fn store(
        &self,
        spec: &RunSpec,
        hash: SpecHash,
        result: RunResult,
    ) -> Result<(), CalibrateError> {
        let stored = StoredRun {
            format: RUN_FORMAT,
            spec_hash: hash.to_string(),
            simulator: self.simulator.clone(),
            result,
            spec,
        };
        let text = serde_json::to_string_pretty(&stored).expect("a run serialises");
        let path = self.path(hash);
        write_string_atomic(&path, &(text + "\n")).map_err(|e| CalibrateError::Io {
            path,
            reason: format!("{e:#}"),
        })
    }
}
