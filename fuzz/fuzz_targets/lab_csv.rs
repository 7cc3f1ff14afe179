//! Fuzz the bench-test CSV reader and the analyses that need no settings (density,
//! Poisson's ratio, shear and tensile modulus, plate restitution, static friction) on any
//! text (issue 23).
//!
//! Checked properties:
//! 1. nothing panics, whatever the text;
//! 2. an analysis that succeeds reports only finite numbers: no inf or NaN is ever printed
//!    or written (its JSON holds every summary and replicate).

#![no_main]

use arachis::io::CsvTable;
use arachis::lab::{
    density, poisson, restitution_plate, shear_modulus, static_friction, tensile_modulus, LabReport,
};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

/// Every number of a report's JSON is finite (serde_json writes inf and NaN as null).
fn all_finite(report: &LabReport) {
    let json = serde_json::to_value(report).expect("a report serialises");
    fn walk(v: &serde_json::Value) {
        match v {
            serde_json::Value::Null => panic!("a non-finite number (null) in the report"),
            serde_json::Value::Array(a) => a.iter().for_each(walk),
            serde_json::Value::Object(o) => o.values().for_each(walk),
            _ => {}
        }
    }
    walk(&json);
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(table) = CsvTable::parse(Path::new("fuzz.csv"), text) else {
        return;
    };
    for analysis in [
        density::analyze,
        poisson::analyze,
        shear_modulus::analyze,
        tensile_modulus::analyze,
        restitution_plate::analyze,
        static_friction::analyze,
    ] {
        if let Ok(report) = analysis(&table) {
            all_finite(&report);
        }
    }
});
