//! Checkpoint files of a field run (`arachis field --checkpoint FILE`): a pass of the
//! seed-scale field is hours of stepping, and a checkpoint lets it stop and go on, in another
//! session or on another machine, bit for bit.
//!
//! A file is one JSON line ([`Header`]: what run it belongs to, how far it got, the
//! harvester's own state) and then the world's state as little-endian 64-bit words
//! ([`arachis_core::world::checkpoint`]). `head -1 FILE` shows how far a run got. The header
//! holds a hash of the run's inputs (field and variety, harvester, layout seed) and an FNV-1a
//! checksum of the words: a file of other inputs, or a damaged file, is refused with its path
//! and the reason. Files are written whole or not at all ([`crate::io::write_atomic`]).
//!
//! ```
//! use arachis::checkpoint::{inputs_hash, read, write, Header};
//! use arachis::field::FieldSpec;
//! use arachis_core::prelude::*;
//! use arachis_core::scenario::BenchBed;
//!
//! let bed = BenchBed { particles: 20, seed: 1 };
//! let mut arena = arachis::arena::OwnedStorage::<Fx>::new(bed.storage_lengths());
//! let mut world = bed.build(arena.storage()).unwrap();
//! world.run(50).unwrap();
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("bed.ckpt");
//! let header = Header::new("inputs".into(), 1, 50, 0.5, None);
//! write(&path, header.clone(), &mut world).unwrap();
//! let (back, words) = read(&path).unwrap().unwrap();
//! assert_eq!(back.steps_done, 50);
//! assert!(back.matches(&header).is_ok());
//! assert!(!words.is_empty());
//! ```

use std::path::Path;

use anyhow::Context;
use arachis_core::digest::Fnv1a;
use arachis_core::prelude::*;
use arachis_core::world::checkpoint::{WordReader, WordWriter};
use serde::{Deserialize, Serialize};

use crate::field::FieldSpec;
use crate::harvester::rig::{Rig, RigState, CHUNK_STEPS};
use crate::harvester::HarvesterSpec;

/// The header's `format`: the layout of this file (the core's word layout has its own
/// version inside the words).
pub const FORMAT: &str = "arachis field checkpoint 1";
/// Bytes of one state word.
const WORD_BYTES: usize = 8;

/// A checkpoint's first line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// [`FORMAT`].
    pub format: String,
    /// [`inputs_hash`] of the run.
    pub inputs: String,
    /// The layout seed.
    pub seed: u64,
    /// Steps run so far.
    pub steps_done: u64,
    /// Wall time of those steps, summed over every session that ran them, s.
    pub wall_seconds: f64,
    /// CPU time of those steps, every thread, summed over every session, s: what a run
    /// paused or slowed by other programs still spent (0 in files written before
    /// 2026-12-02, and where the system gives no CPU clock).
    #[serde(default)]
    pub cpu_seconds: f64,
    /// The harvester's own state, if one is mounted.
    pub rig: Option<RigState>,
    /// State words that follow the line.
    pub words: u64,
    /// FNV-1a of the words (their little-endian bytes), hex.
    pub checksum: String,
}

impl Header {
    /// A header for a run of `inputs` and `seed`, `steps_done` steps in after `wall_seconds`
    /// (the words and their checksum are filled in when written).
    pub fn new(
        inputs: String,
        seed: u64,
        steps_done: u64,
        wall_seconds: f64,
        rig: Option<RigState>,
    ) -> Self {
        Header {
            format: FORMAT.into(),
            inputs,
            seed,
            steps_done,
            wall_seconds,
            cpu_seconds: 0.0,
            rig,
            words: 0,
            checksum: String::new(),
        }
    }

    /// Whether this checkpoint belongs to the run `want` describes (its inputs and seed).
    pub fn matches(&self, want: &Header) -> Result<(), String> {
        if self.seed != want.seed {
            return Err(format!(
                "it was written for layout seed {}, this run's is {}",
                self.seed, want.seed
            ));
        }
        if self.inputs != want.inputs {
            return Err(
                "it was written for other inputs (the field, variety or harvester file changed)"
                    .into(),
            );
        }
        Ok(())
    }
}

/// A hash of what a run's world is built from: the field (with its variety, but not the
/// variety's path), the harvester and the layout seed, hex.
pub fn inputs_hash(spec: &FieldSpec, machine: Option<&HarvesterSpec>, seed: u64) -> String {
    let mut spec = spec.clone();
    spec.field.variety = Default::default();
    let text = format!("{spec:?}\n{machine:?}\n{seed}");
    format!("{:016x}", fnv_bytes(text.as_bytes()))
}

fn fnv_bytes(bytes: &[u8]) -> u64 {
    let mut h = Fnv1a::default();
    for chunk in bytes.chunks(WORD_BYTES) {
        let mut w = [0u8; WORD_BYTES];
        w[..chunk.len()].copy_from_slice(chunk);
        h.u64(u64::from_le_bytes(w));
    }
    h.u64(bytes.len() as u64);
    h.finish()
}

/// Writes `world`'s state under `header` to `path`, whole or not at all.
pub fn write(path: &Path, mut header: Header, world: &mut World<'_, Fx>) -> anyhow::Result<()> {
    let mut bytes = Vec::new();
    world
        .write_checkpoint(&mut WordWriter::new(|w| {
            bytes.extend_from_slice(&w.to_le_bytes())
        }))
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    header.words = (bytes.len() / WORD_BYTES) as u64;
    header.checksum = format!("{:016x}", fnv_bytes(&bytes));
    let line = serde_json::to_string(&header)?;
    crate::io::write_atomic(path, |out| {
        out.write_all(line.as_bytes())?;
        out.write_all(b"\n")?;
        out.write_all(&bytes)?;
        Ok(())
    })
}

/// Reads the checkpoint at `path`: `None` when there is none; an error naming the file when
/// it is not a whole checkpoint of this format.
pub fn read(path: &Path) -> anyhow::Result<Option<(Header, Vec<u64>)>> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(e).with_context(|| format!("cannot read {}", path.display())),
    };
    let bad = |why: String| anyhow::anyhow!("{}: not a usable checkpoint: {why}", path.display());
    let end = bytes
        .iter()
        .position(|&b| b == b'\n')
        .ok_or_else(|| bad("no header line".into()))?;
    let header: Header =
        serde_json::from_slice(&bytes[..end]).map_err(|e| bad(format!("its header line: {e}")))?;
    if header.format != FORMAT {
        return Err(bad(format!(
            "its format is \"{}\", this arachis reads \"{FORMAT}\"",
            header.format
        )));
    }
    let body = &bytes[end + 1..];
    if body.len() as u64 != header.words.saturating_mul(WORD_BYTES as u64) {
        return Err(bad(format!(
            "it holds {} bytes of state where its header says {} words (cut short?)",
            body.len(),
            header.words
        )));
    }
    if format!("{:016x}", fnv_bytes(body)) != header.checksum {
        return Err(bad("its state does not match its checksum (damaged)".into()));
    }
    let words = body
        .chunks_exact(WORD_BYTES)
        .map(|c| u64::from_le_bytes(c.try_into().expect("chunks of WORD_BYTES")))
        .collect();
    Ok(Some((header, words)))
}

/// Puts `words` into `world` (built from the same inputs); the error names `path`.
pub fn restore(path: &Path, words: &[u64], world: &mut World<'_, Fx>) -> anyhow::Result<()> {
    world
        .read_checkpoint(&mut WordReader::new(words.iter().copied()))
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}

/// Goes on from the checkpoint at `path`, if there is one, of the run `wanted` describes:
/// puts its state into `world` and `rig`, and returns the steps it had done and their wall
/// and CPU time, s ((0, 0, 0) without one).
pub fn resume(
    path: &Path,
    wanted: &Header,
    steps: u64,
    world: &mut World<'_, Fx>,
    rig: Option<&mut Rig>,
) -> anyhow::Result<(u64, f64, f64)> {
    let Some((header, words)) = read(path)? else {
        return Ok((0, 0.0, 0.0));
    };
    let refuse = |why: String| {
        anyhow::anyhow!(
            "{}: cannot go on from this checkpoint: {why}; remove it or name another \
             --checkpoint",
            path.display()
        )
    };
    header.matches(wanted).map_err(refuse)?;
    if header.steps_done > steps {
        return Err(refuse(format!(
            "it is {} steps in, past the {steps} this run asks for",
            header.steps_done
        )));
    }
    restore(path, &words, world)?;
    match (rig, &header.rig) {
        (Some(r), Some(state)) => r.resume(state).map_err(refuse)?,
        (None, None) => {}
        _ => {
            return Err(refuse(
                "it was written with a harvester mounted or without".into(),
            ))
        }
    }
    if header.rig.is_some() && header.steps_done % CHUNK_STEPS != 0 && header.steps_done < steps {
        eprintln!(
            "field: note: {} is {} steps in, not a whole number of the machine's {CHUNK_STEPS}-step \
             chunks: from here the run differs in its last bits from one never stopped",
            path.display(),
            header.steps_done
        );
    }
    eprintln!(
        "field: going on from {} at step {} of {steps} ({:.0} s of wall time and {:.0} s of CPU so far)",
        path.display(),
        header.steps_done,
        header.wall_seconds,
        header.cpu_seconds
    );
    Ok((header.steps_done, header.wall_seconds, header.cpu_seconds))
}
