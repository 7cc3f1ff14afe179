//! Fuzz the fit-file reader (`arachis::optimize::FitFile::parse`, what `doe optimize`
//! reads) on any text (issue 23).
//!
//! Checked properties:
//! 1. nothing panics, whatever the text;
//! 2. an accepted fit predicts a finite response at the design's centre (every coefficient
//!    it accepted is a finite number).

#![no_main]

use arachis::optimize::{FitFile, ResponseSurface};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(fit) = FitFile::parse(Path::new("fuzz.json"), text) else {
        return;
    };
    let centre = vec![0.0; fit.factors.len()];
    assert!(fit.model.predict(&centre).is_finite());
});
