//! The host's scenario tests, one module per file of this folder, built as one test binary.
//!
//! Why one binary: each file of `tests/` used to be its own crate, compiled and linked
//! against the whole host library in release mode. With 80 files that was most of the
//! release build (measured in the commit that merged them), and the harness ran the files one
//! after another, so a long test held one core while the other waited. In one binary every
//! test goes through one queue on all cores (`cargo test -- --test-threads N`).
//!
//! Run one file's tests with a name filter: `cargo test --release -p arachis --test scenarios
//! repose_monotonic::`. A new file needs a `mod` line here (`autotests = false` in
//! `host/Cargo.toml`, so cargo does not build it on its own).

mod anova_support;
mod cli_support;
mod diagnose_support;
mod quick_pile_support;
mod repose_support;

mod anova_seed000_box_behnken;
mod anova_seed000_plackett_burman;
mod anova_seed001_ccd;
mod anova_seed001_plackett_burman;
mod bad_inputs_cli;
mod bench_bed;
mod bulk_density;
mod calibrate_any_rig;
mod calibrate_cli;
mod calibrate_committed_run;
mod calibrate_dem;
mod calibrate_workflow;
mod count_limits_cli;
mod diagnose_bounds;
mod diagnose_bulk;
mod diagnose_calibration_rigs;
mod diagnose_cli;
mod diagnose_fit;
mod diagnose_fit_cohesion;
mod diagnose_hysteretic;
mod diagnose_identify;
mod diagnose_liggghts;
mod diagnose_priors;
mod diagnose_random_rigs;
mod diagnose_rank;
mod diagnose_seed000;
mod doe_cli;
mod doe_properties;
mod doe_seed_designs;
mod drum;
mod experiments_rigs;
mod export_liggghts;
mod field;
mod field_calm;
mod field_checkpoint;
mod field_settle;
mod field_trial;
mod golden_c5d1f03;
mod harvest;
mod harvester;
mod hopper;
mod lab_analyses;
mod lab_bad_input;
mod lab_cli;
mod lab_properties;
mod lab_seed_values;
mod module_cycles;
mod optimize_cli;
mod optimize_desirability;
mod optimize_seed000_eq22;
mod plant_bond_sets;
mod plant_calibrate_cli;
mod plant_calibration;
mod plant_generator;
mod plant_study;
mod plant_variety;
mod pod_bulk_density;
mod pod_drum;
mod pod_effects;
mod pod_hopper;
mod pour_cli;
mod pulloff_cli;
mod repeatable_outputs;
mod repose_bad_input;
mod repose_cli;
mod repose_conditions;
mod repose_monotonic;
mod repose_sphere_pile;
mod repose_synthetic_image;
mod rig_conformance;
mod shapes_filling;
mod shapes_mass_properties;
mod shapes_principal_frame;
mod shapes_ray_parity;
mod shapes_stl;
mod slurm_cluster;
mod sphere_particles;
mod stats_cli;
mod stats_t_test;
mod stats_type_three;
mod study_bad_files;
mod study_checks;
mod study_cli;
mod study_conventions;
mod study_properties;
mod study_seed000;
