//! Optimisation on fitted response surfaces (issue 3).
