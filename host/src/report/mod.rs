//! Reports of a finished calibration: the numbers (`calibration.json`,
//! [`calibration_json`]), the story with tables (`report.md`, [`markdown`]) and SVG
//! figures ([`figures`]); the stages' decisions phrased once ([`notes`]). Every file is
//! written atomically, the JSON last, so a folder with a `calibration.json` is complete.
//! Nothing here depends on time, paths or thread count: the same calibration writes the
//! same bytes.
//!
//! [`pull_off`] is seed 001's pull-off report (`plant-calibration.json`), which a pull-off
//! study writes for one release so existing outputs still compare byte for byte.

pub mod calibration_json;
pub mod figures;
pub mod markdown;
pub mod notes;
pub mod pull_off;

use std::path::Path;

use crate::calibration::plan::validation;
use crate::calibration::run_cache::remove_stale_temporaries;
use crate::calibration::{CalibrateError, Executor, Problem, RunRequest, Stages};
use crate::io::write_string_atomic;
pub use calibration_json::{CalibrationJson, Provenance};

/// Folder of the figures inside the output folder.
pub const FIGURES_DIR: &str = "figures";
/// The JSON file name.
pub const JSON_FILE: &str = "calibration.json";
/// The report file name.
pub const REPORT_FILE: &str = "report.md";
/// The measured and simulated pile as cone profiles, inside the figures folder.
pub const PILE_SCHEMATIC: &str = "pile.svg";
/// The quantity whose measured and simulated values are drawn as cone profiles.
const REPOSE_ANGLE: &str = "repose_angle";

/// Writes `text` to `path` atomically.
pub fn write(path: &Path, text: &str) -> Result<(), CalibrateError> {
    write_string_atomic(path, text).map_err(|e| CalibrateError::Io {
        path: path.to_owned(),
        reason: format!("{e:#}"),
    })
}

fn figure(path: &Path, svg: Result<String, String>) -> Result<(), CalibrateError> {
    let svg = svg.map_err(|reason| CalibrateError::Io {
        path: path.to_owned(),
        reason,
    })?;
    write(path, &svg)
}

/// Creates `dir` and removes temporary files a killed write left there.
pub fn prepare_dir(dir: &Path) -> Result<(), CalibrateError> {
    let io = |e: std::io::Error| CalibrateError::Io {
        path: dir.to_owned(),
        reason: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(io)?;
    remove_stale_temporaries(dir).map_err(io)
}

/// Writes the figures, `report.md` and `calibration.json` of `stages` into `out`.
pub fn write_calibration(
    problem: &Problem<'_>,
    stages: &Stages,
    provenance: &Provenance,
    out: &Path,
) -> Result<CalibrationJson, CalibrateError> {
    let figures_dir = out.join(FIGURES_DIR);
    prepare_dir(out)?;
    prepare_dir(&figures_dir)?;
    let unit = &problem.target.unit;
    let mut drawn = markdown::Figures::default();
    figure(
        &figures_dir.join("pareto.svg"),
        figures::pareto(&stages.screening, unit),
    )?;
    let fitted = &stages.surface;
    for (i, j) in figures::surface_pairs(fitted) {
        let name = format!(
            "surface_{}_{}.svg",
            fitted.factors[i].label, fitted.factors[j].label
        );
        figure(
            &figures_dir.join(&name),
            figures::surface_map(
                fitted,
                i,
                j,
                &stages.optimum.coded,
                problem.target.value,
                unit,
            ),
        )?;
        drawn.surfaces.push(name);
    }
    let v = &stages.validation;
    if problem.validation.quantity == REPOSE_ANGLE {
        figure(
            &figures_dir.join(PILE_SCHEMATIC),
            figures::pile_profiles(v.measured, v.simulated),
        )?;
        drawn.pile_schematic = true;
    }
    // The rig's own picture of the first validation run, when it can draw one.
    let first = &validation::planned(&stages.optimum, 1)[0];
    let values = Executor::full_values(&problem.factors, first);
    let request = RunRequest {
        values: &values,
        condition: &problem.validation.condition,
        replicate: first.replicate,
    };
    drawn.picture = problem
        .validation
        .rig
        .picture(&request, &figures_dir)
        .map_err(|e| CalibrateError::Io {
            path: figures_dir.clone(),
            reason: format!("the rig could not draw the optimum: {e}"),
        })?
        .and_then(|p| {
            p.strip_prefix(out)
                .ok()
                .map(|r| r.to_string_lossy().into_owned())
        });
    let json = CalibrationJson::new(problem, stages, provenance);
    let strongest = stages.screening.strongest();
    write(
        &out.join(REPORT_FILE),
        &markdown::markdown(
            &json,
            strongest.map(|e| (e.label.as_str(), e.name.as_str())),
            &drawn,
        ),
    )?;
    let text = serde_json::to_string_pretty(&json).expect("a calibration serialises");
    write(&out.join(JSON_FILE), &(text + "\n"))?;
    Ok(json)
}
