//! The core's scenario tests, one module per file of this folder, built as one test binary.
//!
//! Why one binary: the core's tests are built twice by `scripts/test-all.sh` (release and
//! debug), and each file of `tests/` used to be its own crate with its own link; in one binary
//! every test also goes through one queue on all cores. Run one file's tests with a name
//! filter, e.g. `cargo test -p arachis-core --test scenarios digest_scenarios::`. A new file
//! needs a `mod` line here (`autotests = false` in `core/Cargo.toml`).

mod common;

mod bad_input;
mod bond_beam;
mod bonds;
mod broad_phase;
mod checkpoint;
mod clumps;
mod cross_check_liggghts;
mod digest_scenarios;
mod effects;
mod effects_rolling_jkr;
mod energy;
mod fixed_vs_f64;
mod hertz_impact;
mod incline;
mod kinematic_partner;
mod light_body_gravity;
mod multirate;
mod near_centres;
mod near_walls;
mod oblique_impact;
mod poisson_extended;
mod restitution;
mod rolling;
mod rolling_conventions;
mod sphere_drop;
mod spinning_walls;
mod walls;
