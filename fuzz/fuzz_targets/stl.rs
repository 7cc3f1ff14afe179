//! Fuzz the STL reader (`arachis::shapes::stl::parse_stl`: binary and ASCII) on any bytes
//! (issue 23).
//!
//! Checked properties:
//! 1. nothing panics, whatever the bytes (a binary header may announce any triangle count);
//! 2. an accepted mesh has only finite vertices, and every triangle indexes them.

#![no_main]

use arachis::shapes::stl::parse_stl;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(mesh) = parse_stl(Path::new("fuzz.stl"), data) else {
        return;
    };
    assert!(mesh
        .vertices_mm
        .iter()
        .all(|v| v.iter().all(|c| c.is_finite())));
    let n = mesh.vertices_mm.len();
    assert!(mesh.triangles.iter().all(|t| t.iter().all(|&i| i < n)));
});
