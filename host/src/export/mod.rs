//! Exports of a study for other engines: today a LIGGGHTS 3.8 input deck of the repose rig
//! ([`liggghts`]), written by `arachis export liggghts`.
//!
//! ```
//! use arachis::export::liggghts::cylinder_stl;
//! let stl = cylinder_stl(50.0, 120.0);
//! assert!(stl.starts_with("solid cylinder"));
//! assert_eq!(stl.matches("facet normal").count(), 2 * arachis::export::liggghts::CYLINDER_SEGMENTS);
//! ```

pub mod liggghts;
