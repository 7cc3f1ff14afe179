//! The run cache: every finished run stored as one JSON file, `runs/<hash>.json`, named by
//! the [`SpecHash`] of its rig's specification and written atomically.
//!
//! A stored run is replayed only when its file parses, its specification is byte for byte
//! the requested one (canonical JSON, so a hash collision cannot mix two runs up) and it
//! was made by the same rig ([`Rig::id`](super::rig::Rig::id)); anything else is simulated
//! again and overwritten. Because a file appears only when complete (rename over a
//! temporary file), an interrupted calibration leaves either a whole run or none, and a
//! rerun picks up exactly the runs that finished.
//!
//! Format `arachis-run-2` stores every named response of the run. Files of format
//! `arachis-run-1` (written before rigs had named responses, by the repose calibration)
//! hold the one response the calibration asked for, and are read as that quantity.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::error::CalibrateError;
use super::rig::Responses;
use super::spec_hash::{canonical_json, SpecHash};
use crate::io::write_string_atomic;

/// Format tag of a stored run.
pub const RUN_FORMAT: &str = "arachis-run-2";
/// Format tag of a stored run with a single response (read only).
pub const SINGLE_RESPONSE_FORMAT: &str = "arachis-run-1";

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
    rig: &'a str,
    responses: &'a Responses,
    spec: &'a Value,
}

/// One stored run as read back, in either format.
#[derive(Deserialize)]
struct ReadRun {
    format: String,
    spec_hash: String,
    /// `arachis-run-2`.
    rig: Option<String>,
    responses: Option<Responses>,
    /// `arachis-run-1`.
    simulator: Option<String>,
    result: Option<SingleResponse>,
    spec: Value,
}

#[derive(Deserialize)]
struct SingleResponse {
    response: f64,
}

/// The folder of stored runs.
#[derive(Debug, Clone)]
pub struct RunCache {
    dir: PathBuf,
}

impl RunCache {
    /// Opens (creating) `dir`, removing temporary files a killed calibration may have left.
    pub fn open(dir: &Path) -> Result<Self, CalibrateError> {
        let io = |e: std::io::Error| CalibrateError::Io {
            path: dir.to_owned(),
            reason: e.to_string(),
        };
        std::fs::create_dir_all(dir).map_err(io)?;
        remove_stale_temporaries(dir).map_err(io)?;
        Ok(Self {
            dir: dir.to_owned(),
        })
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The file of `hash`.
    pub fn path(&self, hash: SpecHash) -> PathBuf {
        self.dir.join(format!("{hash}.json"))
    }

    /// The stored responses of `spec` made by rig `rig`, if a valid file exists; a
    /// single-response file answers for `quantity`.
    pub fn load(
        &self,
        spec: &Value,
        hash: SpecHash,
        rig: &str,
        quantity: &str,
    ) -> Option<Responses> {
        let text = std::fs::read_to_string(self.path(hash)).ok()?;
        let run: ReadRun = serde_json::from_str(&text).ok()?;
        let responses = match run.format.as_str() {
            RUN_FORMAT if run.rig.as_deref() == Some(rig) => run.responses?,
            SINGLE_RESPONSE_FORMAT if run.simulator.as_deref() == Some(rig) => {
                Responses::from([(quantity.to_owned(), run.result?.response)])
            }
            _ => return None,
        };
        let valid = run.spec_hash == hash.to_string()
            && canonical_json(&run.spec) == canonical_json(spec)
            && responses.values().all(|v| v.is_finite());
        valid.then_some(responses)
    }

    /// Stores the `responses` of `spec` made by rig `rig`, atomically.
    pub fn store(
        &self,
        spec: &Value,
        hash: SpecHash,
        rig: &str,
        responses: &Responses,
    ) -> Result<(), CalibrateError> {
        let stored = StoredRun {
            format: RUN_FORMAT,
            spec_hash: hash.to_string(),
            rig,
            responses,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stored_run_replays_only_for_its_rig_and_spec() {
        let dir = tempfile::tempdir().unwrap();
        let cache = RunCache::open(dir.path()).unwrap();
        let spec = serde_json::json!({"a": 1.5});
        let hash = SpecHash::of(&spec);
        let responses = Responses::from([("angle".to_owned(), 31.0)]);
        cache.store(&spec, hash, "rig-1", &responses).unwrap();
        assert_eq!(cache.load(&spec, hash, "rig-1", "angle"), Some(responses));
        assert_eq!(cache.load(&spec, hash, "rig-2", "angle"), None);
        let other = serde_json::json!({"a": 2.5});
        assert_eq!(cache.load(&other, hash, "rig-1", "angle"), None);
    }

    #[test]
    fn a_single_response_file_answers_for_the_quantity_asked() {
        let dir = tempfile::tempdir().unwrap();
        let cache = RunCache::open(dir.path()).unwrap();
        let spec = serde_json::json!({"b": [1, 2]});
        let hash = SpecHash::of(&spec);
        let old = serde_json::json!({
            "format": SINGLE_RESPONSE_FORMAT, "spec_hash": hash.to_string(),
            "simulator": "dem-1", "result": {"response": 30.5}, "spec": spec,
        });
        std::fs::write(cache.path(hash), old.to_string()).unwrap();
        assert_eq!(
            cache.load(&spec, hash, "dem-1", "repose_angle"),
            Some(Responses::from([("repose_angle".to_owned(), 30.5)]))
        );
    }

    /// What a reader on a network file system might see of a run being written: any prefix
    /// of the file. Only the whole file is replayed.
    #[test]
    fn no_prefix_of_a_stored_run_is_replayed() {
        let dir = tempfile::tempdir().unwrap();
        let cache = RunCache::open(dir.path()).unwrap();
        let spec = serde_json::json!({"c": [0.25, "x"]});
        let hash = SpecHash::of(&spec);
        let responses = Responses::from([("angle".to_owned(), 29.75)]);
        cache.store(&spec, hash, "rig-1", &responses).unwrap();
        let whole = std::fs::read(cache.path(hash)).unwrap();
        for len in 0..whole.len() {
            std::fs::write(cache.path(hash), &whole[..len]).unwrap();
            let replayed = cache.load(&spec, hash, "rig-1", "angle");
            // A prefix that still parses (cut in the trailing newline) is the whole run.
            let complete = whole[len..].iter().all(u8::is_ascii_whitespace);
            assert_eq!(replayed.is_some(), complete, "a {len}-byte prefix");
        }
    }
}
