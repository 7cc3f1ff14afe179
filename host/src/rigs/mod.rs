//! The rigs: every virtual bench test the host can calibrate and diagnose, one file each,
//! each behind the engine's [`crate::calibration::Rig`] interface.

pub mod catalogue;
pub mod compression;
pub mod fall;
pub mod incline;
pub mod kind;
pub mod pod_bench;
pub mod pod_world;
pub mod press;
pub mod pull_off;
pub mod rebound;
pub mod repose_cylinder;
pub mod repose_picture;
pub mod repose_surrogate;
pub mod single_sphere;
pub mod unload;
