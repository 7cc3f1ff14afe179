//! VTK frames of a rig (`--vtk DIR`): the spheres' state sampled during the run, written as
//! a ParaView series by [`crate::vtk::write_series`] once the run is over (an unwritable
//! directory fails the run before any number is reported).

use std::path::{Path, PathBuf};

use arachis_core::prelude::*;

use super::error::ExperimentError;
use crate::vtk::{write_series, ParticleFrame};

/// Collects frames when a directory was asked for; does nothing otherwise.
#[derive(Debug, Default)]
pub struct FrameRecorder {
    dir: Option<PathBuf>,
    frames: Vec<ParticleFrame>,
}

impl FrameRecorder {
    /// A recorder writing into `dir` (none: recording is off).
    pub fn new(dir: Option<&Path>) -> Self {
        FrameRecorder {
            dir: dir.map(Path::to_path_buf),
            frames: Vec::new(),
        }
    }

    /// True when frames are being recorded.
    pub fn active(&self) -> bool {
        self.dir.is_some()
    }

    /// Records the world's current state.
    pub fn record(&mut self, w: &World<'_, Fx>) {
        if !self.active() {
            return;
        }
        self.frames.push(ParticleFrame::from_world(w));
    }

    /// Writes the series; returns the `.pvd` path when recording.
    pub fn finish(self) -> Result<Option<PathBuf>, ExperimentError> {
        match self.dir {
            None => Ok(None),
            Some(dir) => write_series(&dir, &self.frames)
                .map(Some)
                .map_err(|e| ExperimentError::Output(format!("{e:#}"))),
        }
    }
}
