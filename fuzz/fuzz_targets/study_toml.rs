//! Fuzz the study loader (`arachis::study::Study::from_toml_reading`, what `study check` and
//! every study command run) on any text (issue 23). Files a study names are refused rather
//! than read, so the run touches no file system.
//!
//! Checked properties:
//! 1. nothing panics, whatever the text;
//! 2. an accepted study's counts are inside their limits (`arachis::count_limits`), so a
//!    study that loads cannot make `calibrate` allocate without bound;
//! 3. an accepted study re-checks to the same verdict (loading is a pure function).

#![no_main]

use arachis::count_limits::{MAX_CENTRE_POINTS, MAX_DESIGN_POINTS, MAX_PODS};
use arachis::study::Study;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let no_files = |p: &Path| -> std::io::Result<String> {
        Err(std::io::Error::other(format!(
            "{} not read while fuzzing",
            p.display()
        )))
    };
    let path = Path::new("fuzz/study.toml");
    let Ok(study) = Study::from_toml_reading(text, path, &no_files) else {
        return;
    };
    if let Some(plan) = &study.file().plan {
        assert!(u64::from(plan.steepest_ascent.points) <= MAX_DESIGN_POINTS);
        assert!(u64::from(plan.screening.centre_points) <= MAX_CENTRE_POINTS);
        for mode in plan.modes.values() {
            assert!(u64::from(mode.pods) <= MAX_PODS);
        }
    }
    assert!(Study::from_toml_reading(text, path, &no_files).is_ok());
});
