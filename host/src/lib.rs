//! Arachis host library: lab analysis, designs of experiments, regression and ANOVA,
//! optimisation, and (later) calibration, diagnosis and reports.
//!
//! The `arachis` command-line program in `src/main.rs` is a thin face over these modules.
#![deny(missing_docs)]

pub mod arena;
pub mod calibration;
pub mod checkpoint;
pub mod cli;
pub mod cluster;
pub mod count_limits;
pub mod diagnose;
pub mod doe;
pub mod export;
pub mod field;
pub mod harvest;
pub mod harvester;
pub mod io;
pub mod lab;
pub mod limits;
pub mod nearest_name;
pub mod optimize;
pub mod plant;
pub mod plausible;
pub mod report;
pub mod repose;
pub mod rigs;
pub mod shapes;
pub mod stats;
pub mod stepping;
pub mod study;
pub mod variety;
pub mod vtk;
