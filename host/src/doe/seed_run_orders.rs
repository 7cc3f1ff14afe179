//! The run orders printed in the seeds, as permutations of this crate's standard order.
//!
//! The seeds print their designs in Design-Expert's randomised run order. A randomisation
//! cannot be regenerated, so each printed order is stored here as data: entry r is the
//! 1-based standard-order number (as [`super::box_behnken`], [`super::central_composite`]
//! and [`super::plackett_burman`] generate them) of the seed's run r + 1. They were read
//! off the printed tables by matching each printed row to its standard-order row; the
//! indistinguishable centre points are assigned in increasing order. Apply one with
//! [`super::Design::with_run_order`]; `tests/doe_seed_designs.rs` checks that the generated
//! design in this order reproduces every printed cell.

/// Seed 000 Table 4: Plackett–Burman, 12 runs, x1…x8 and dummies x9…x11, no centre points.
pub const SEED000_TABLE4_PLACKETT_BURMAN: [usize; 12] = [10, 9, 6, 12, 1, 4, 7, 2, 11, 5, 3, 8];

/// Seed 000 Table 8: Box–Behnken, 3 factors (x3, x4, x5), 5 centre points.
pub const SEED000_TABLE8_BOX_BEHNKEN: [usize; 17] =
    [1, 13, 14, 15, 9, 7, 10, 16, 3, 12, 2, 17, 4, 6, 8, 11, 5];

/// Seed 001 Table 6: Plackett–Burman, 12 runs, X1…X9 and 2 dummies, 3 centre points.
pub const SEED001_TABLE6_PLACKETT_BURMAN: [usize; 15] =
    [12, 1, 7, 3, 6, 13, 2, 9, 14, 11, 8, 10, 15, 4, 5];

/// Seed 001 Table 10: central composite, 2 factors (X7, X8), α = 1.414, 5 centre points.
pub const SEED001_TABLE10_CENTRAL_COMPOSITE: [usize; 13] =
    [1, 3, 8, 6, 9, 7, 10, 11, 12, 2, 5, 13, 4];
