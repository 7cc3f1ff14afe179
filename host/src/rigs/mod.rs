//! The rigs: every virtual bench test the host can calibrate and diagnose, one file each,
//! each behind the engine's [`crate::calibration::Rig`] interface.

pub mod pod_bench;
pub mod pull_off;
pub mod repose_surrogate;
