//! Designs of experiments in coded and actual units (issue 3): Plackett–Burman screening
//! designs, two-level full and fractional factorials, the path of steepest ascent,
//! Box–Behnken and central composite designs.
//!
//! Every design is built in coded units (−1 … +1, axial points beyond) in a fixed standard
//! order; [`Factor`] maps coded values to actual levels (seed 001 §2.5:
//! `x = (X − X₀)/ΔX`). [`seed_run_orders`] holds the seeds' printed (randomised) run orders.
//!
//! ```
//! use arachis::doe::{box_behnken, seed_run_orders, Factor};
//! let factors = vec![
//!     Factor::new("x3", "-", 0.327, 0.340).unwrap(),
//!     Factor::new("x4", "-", 0.848, 0.858).unwrap(),
//!     Factor::new("x5", "-", 0.332, 0.350).unwrap(),
//! ];
//! let design = box_behnken(&factors, 5)
//!     .unwrap()
//!     .with_run_order(&seed_run_orders::SEED000_TABLE8_BOX_BEHNKEN)
//!     .unwrap();
//! // Seed 000 Table 8, run 1: 0.327, 0.848, 0.341.
//! let first = &design.actual_in_run_order()[0];
//! assert_eq!((first[0], first[1]), (0.327, 0.848));
//! assert!((first[2] - 0.341).abs() < 1e-12);
//! ```

pub mod box_behnken;
pub mod central_composite;
pub mod design;
pub mod design_csv;
pub mod error;
pub mod factor;
pub mod factorial;
pub mod plackett_burman;
pub mod seed_run_orders;
pub mod steepest_ascent;

pub use box_behnken::box_behnken;
pub use central_composite::{central_composite, Alpha};
pub use design::{Design, PointType};
pub use design_csv::design_to_csv;
pub use error::DesignError;
pub use factor::Factor;
pub use factorial::{fractional_factorial, full_factorial};
pub use plackett_burman::{plackett_burman, PlackettBurmanRuns};
pub use steepest_ascent::steepest_ascent;
