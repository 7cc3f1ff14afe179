//! Exports of a study for other engines: today LIGGGHTS 3.8 input decks of the repose and
//! incline rigs ([`liggghts`]), written by `arachis export liggghts`.
//!
//! ```
//! use arachis::export::liggghts::repose::{cylinder_stl, CYLINDER_SEGMENTS};
//! // 50 mm radius, 120 mm long: faces 3.3 mm wide, in 2 rows of at most 20 widths.
//! let stl = cylinder_stl(50.0, 120.0);
//! assert!(stl.starts_with("solid cylinder"));
//! assert_eq!(stl.matches("facet normal").count(), 2 * 2 * CYLINDER_SEGMENTS);
//! ```

pub mod liggghts;
