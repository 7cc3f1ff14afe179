//! The rigs: every virtual bench test the host can calibrate and diagnose, one file each,
//! each behind the engine's [`crate::calibration::Rig`] interface and listed in the
//! [`catalogue`] with its [`kind::RigKind`].
//!
//! | rig | file | measures |
//! |---|---|---|
//! | `repose` | [`repose_cylinder`] | repose angle by cylinder lifting (seed 000 §2.7) |
//! | `incline_slide` | [`incline`] | slide angle on a tilting plate (seed 000 §2.6.2) |
//! | `compression` | [`compression`] | apparent modulus between two plates (seed 000 §2.5.3) |
//! | `plate_drop`, `rolling` | [`pod_bench`] | measurable, not simulated yet |
//! | `pull_off` | [`pull_off`] | detachment force of a pod off its stalk (seed 001 §2.3) |
//! | `harvest` | [`harvest`] | loss rate through a picking drum (seed 001 §3.3) |
//! | `bench_bed` | [`bench_bed`] | bed height of pod spheres poured into a cylinder (DESIGN §8) |
//! | `hopper` | [`hopper`] | mass flow rate of pod spheres out of a silo through an orifice |
//! | `bulk_density` | [`bulk_density`] | bulk density of pod spheres poured from a drop height |
//! | `pod_bulk_density` | [`pod_bulk_density`] | bulk density of the study's pods poured from a drop height |
//! | `pod_drum` | [`pod_drum`] | dynamic angle of repose of the study's pods in a rotating drum |
//! | `pod_hopper` | [`pod_hopper`] | mass flow rate of the study's pods out of a silo through an orifice |
//! | `drum` | [`drum`] | dynamic angle of repose of pod spheres in a rotating drum |
//! | `rebound`, `press`, `fall`, `unload`, `roll` | [`rebound`], [`press`], [`fall`], [`unload`], [`roll`] | one pod sphere: restitution, overlap, fall time, rolling speed |
//!
//! What rigs share lives beside them: the pod world ([`pod_world`], [`pod_bench`]), the
//! single sphere ([`single_sphere`]), pod spheres in bulk ([`sphere_bulk`]);
//! [`repose_surrogate`] is a test stand-in for the repose rig. [`kind`] says what the catalogue knows of a rig, [`parameter`] what a rig's
//! parameters are; [`conformance`] is the test every rig must pass.

pub mod bench_bed;
pub mod bulk_density;
pub mod catalogue;
pub mod compression;
pub mod conformance;
pub mod drum;
pub mod fall;
pub mod harvest;
pub mod harvest_pass;
pub mod hopper;
pub mod incline;
pub mod kind;
pub mod parameter;
pub mod pod_bench;
pub mod pod_bulk_density;
pub mod pod_drum;
pub mod pod_hopper;
pub mod pod_world;
pub mod press;
pub mod pull_off;
pub mod rebound;
pub mod repose_cylinder;
pub mod repose_picture;
pub mod repose_surrogate;
pub mod roll;
pub mod single_sphere;
pub mod sphere_bulk;
pub mod unload;
