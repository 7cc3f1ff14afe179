//! Designs of experiments in coded and actual units (issue 3).
