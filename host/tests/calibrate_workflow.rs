//! The calibration workflow through the real code paths (designs, ANOVA, desirability,
//! run cache, report) on seed 000's surrogate (`calibrate::surrogate`), which is built from
//! seed 000 Table 4, eq. (22) and Table 8 only, independently of the code under test.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use arachis::calibrate::{
    calibrate, CalibrateError, CalibrateOptions, Outcome, Progress, RunResult, Seed000Surrogate,
    SimulationError, Simulator,
};
use arachis::study::{RunSpec, Study};

const STUDY: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../testdata/peanut-pods-saline/study.toml"
);

fn study() -> Study {
    Study::load(Path::new(STUDY)).unwrap()
}

fn options(out: &Path, jobs: usize) -> CalibrateOptions {
    CalibrateOptions {
        mode: None,
        jobs: Some(jobs),
        out_dir: out.to_owned(),
        progress: Progress::hidden(),
    }
}

fn run(sim: &dyn Simulator, out: &Path, jobs: usize) -> Result<Outcome, CalibrateError> {
    calibrate(&study(), sim, &options(out, jobs))
}

fn bytes(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap()
}

fn stored_runs(dir: &Path) -> usize {
    std::fs::read_dir(dir.join("runs"))
        .map(|d| {
            d.filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .ends_with(".json")
            })
            .count()
        })
        .unwrap_or(0)
}

/// The surrogate, failing every call after the first `k` (an interruption after k runs).
struct FailsAfter {
    inner: Seed000Surrogate,
    k: usize,
    calls: AtomicUsize,
}

impl Simulator for FailsAfter {
    fn id(&self) -> String {
        self.inner.id()
    }
    fn description(&self) -> String {
        self.inner.description()
    }
    fn simulate(&self, spec: &RunSpec) -> Result<RunResult, SimulationError> {
        if self.calls.fetch_add(1, Ordering::SeqCst) >= self.k {
            return Err(SimulationError("interrupted".into()));
        }
        self.inner.simulate(spec)
    }
}

/// A simulator with a shifted response (so the target is out of reach, or pure noise).
struct Custom<F: Fn(f64, u64) -> f64 + Sync> {
    name: &'static str,
    f: F,
}

impl<F: Fn(f64, u64) -> f64 + Sync> Simulator for Custom<F> {
    fn id(&self) -> String {
        self.name.to_owned()
    }
    fn description(&self) -> String {
        format!("test simulator {}", self.name)
    }
    fn simulate(&self, spec: &RunSpec) -> Result<RunResult, SimulationError> {
        let mean = Seed000Surrogate { noise_sd_deg: 0.0 }
            .simulate(spec)?
            .response;
        Ok(RunResult {
            response: (self.f)(mean, spec.spec_hash().0),
        })
    }
}

#[test]
fn screening_flags_pod_pod_static_friction_and_the_optimum_validates_within_2_percent() {
    let dir = tempfile::tempdir().unwrap();
    let outcome = run(&Seed000Surrogate::default(), dir.path(), 2).unwrap();
    let c = &outcome.calibration;
    // Seed 000 Table 5: x4 is the most significant factor (p = 0.0022).
    let strongest = c.screening.strongest().unwrap();
    assert_eq!(strongest.name, "pod-pod.static_friction");
    assert!(c.screening.significant.contains(&"x4".to_owned()));
    assert_eq!(c.screening.runs.len(), 12);
    // Seed 000 §3.6.2: the calibrated angle within 2 % of the bench's 31.06°.
    assert_eq!(c.target.value, 31.06);
    assert!(c.validation.passed, "{:?}", c.validation);
    assert!(c.validation.relative_error_pct < 2.0);
    // The polynomial the optimiser searches is the ANOVA's coded equation.
    use arachis::optimize::ResponseSurface;
    let surface = c.box_behnken.surface();
    for r in &c.box_behnken.runs {
        let d = surface.predict(&r.coded) - c.box_behnken.anova.predict(&r.coded);
        assert!(d.abs() < 1e-9, "{d}");
    }
    // The optimum hits the target on the fitted surface.
    assert!((c.optimum.predicted - 31.06).abs() < 0.01);
    // The quadratic fit is adequate: lack of fit not significant against pure error.
    let lof = c.box_behnken.anova.lack_of_fit.as_ref().unwrap();
    assert!(lof.p > 0.05, "{lof:?}");
    // Every run is stored once under its hash; nothing was replayed on a fresh folder.
    let total = c.screening.runs.len()
        + c.steepest_ascent.runs.len()
        + c.box_behnken.runs.len()
        + c.validation.runs.len();
    assert_eq!(outcome.simulated + outcome.replayed, total);
    assert_eq!(outcome.replayed, 0);
    assert_eq!(stored_runs(dir.path()), total);
    for r in &c.screening.runs {
        assert!(dir
            .path()
            .join(format!("runs/{}.json", r.spec_hash))
            .is_file());
    }
    // The report folder.
    let json: serde_json::Value =
        serde_json::from_slice(&bytes(dir.path(), "calibration.json")).unwrap();
    assert_eq!(json["format"], "arachis-calibration-1");
    assert!(
        json["box_behnken"]["anova"]["terms"]
            .as_array()
            .unwrap()
            .len()
            > 3
    );
    let report = String::from_utf8(bytes(dir.path(), "report.md")).unwrap();
    assert!(report.contains("NOT a DEM simulation"));
    assert!(report.contains("figures/pareto.svg"));
    for f in ["pareto.svg", "pile.svg"] {
        let svg = String::from_utf8(bytes(&dir.path().join("figures"), f)).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
            "{f}"
        );
    }
    assert!(report.contains("figures/surface_"));
}

#[test]
fn one_and_two_jobs_write_identical_bytes() {
    let a = tempfile::tempdir().unwrap();
    let b = tempfile::tempdir().unwrap();
    run(&Seed000Surrogate::default(), a.path(), 1).unwrap();
    run(&Seed000Surrogate::default(), b.path(), 2).unwrap();
    for f in [
        "calibration.json",
        "report.md",
        "figures/pareto.svg",
        "figures/pile.svg",
    ] {
        assert!(bytes(a.path(), f) == bytes(b.path(), f), "{f} differs");
    }
}

#[test]
fn interrupted_calibrations_resume_without_redoing_work_and_end_byte_identical() {
    let reference = tempfile::tempdir().unwrap();
    let full = run(&Seed000Surrogate::default(), reference.path(), 1).unwrap();
    let total = full.simulated;
    let expected = bytes(reference.path(), "calibration.json");
    // Interruptions in screening, on the path, in the Box–Behnken design, at validation.
    for k in [0, 7, 14, 40, total - 1] {
        let dir = tempfile::tempdir().unwrap();
        let failing = FailsAfter {
            inner: Seed000Surrogate::default(),
            k,
            calls: AtomicUsize::new(0),
        };
        let err = run(&failing, dir.path(), 1).unwrap_err();
        assert!(err.to_string().contains("interrupted"), "{err}");
        assert!(!dir.path().join("calibration.json").exists());
        assert_eq!(stored_runs(dir.path()), k, "k = {k}");
        let resumed = run(&Seed000Surrogate::default(), dir.path(), 1).unwrap();
        assert_eq!(resumed.replayed, k, "k = {k}");
        assert_eq!(resumed.simulated, total - k, "k = {k}");
        assert!(bytes(dir.path(), "calibration.json") == expected, "k = {k}");
    }
    // Two threads: whatever finished before the failure is kept, and the end is the same.
    let dir = tempfile::tempdir().unwrap();
    let failing = FailsAfter {
        inner: Seed000Surrogate::default(),
        k: 20,
        calls: AtomicUsize::new(0),
    };
    assert!(run(&failing, dir.path(), 2).is_err());
    let kept = stored_runs(dir.path());
    let resumed = run(&Seed000Surrogate::default(), dir.path(), 2).unwrap();
    assert_eq!(resumed.replayed, kept);
    assert!(bytes(dir.path(), "calibration.json") == expected);
}

#[test]
fn cached_runs_of_another_simulator_or_damaged_files_are_simulated_again() {
    let dir = tempfile::tempdir().unwrap();
    let first = run(&Seed000Surrogate::default(), dir.path(), 2).unwrap();
    let quiet = Seed000Surrogate { noise_sd_deg: 0.0 };
    let other = run(&quiet, dir.path(), 2).unwrap();
    assert_eq!(
        other.replayed, 0,
        "another simulator's results were replayed"
    );
    // Back to the first simulator: the screening runs (same specs) were overwritten by the
    // other simulator, so they run again, and the result is the first one's.
    let again = run(&Seed000Surrogate::default(), dir.path(), 2).unwrap();
    assert!(again.simulated >= first.calibration.screening.runs.len());
    assert_eq!(again.calibration, first.calibration);
    // Damage one file: only that run is redone.
    let victim = &again.calibration.screening.runs[3].spec_hash;
    std::fs::write(dir.path().join(format!("runs/{victim}.json")), "{\"trunc").unwrap();
    let repaired = run(&Seed000Surrogate::default(), dir.path(), 2).unwrap();
    assert_eq!(repaired.simulated, 1);
    assert_eq!(repaired.calibration, again.calibration);
}

#[test]
fn nothing_significant_proceeds_with_the_largest_effects_and_says_so() {
    // Pure scatter of SD 3° around 31°: no factor has an effect.
    let noise = Custom {
        name: "noise-only",
        f: |_, hash| 31.0 + 3.0 * arachis::calibrate::surrogate::standard_normal_from(hash),
    };
    let dir = tempfile::tempdir().unwrap();
    let c = run(&noise, dir.path(), 2).unwrap().calibration;
    assert!(
        c.screening.significant.is_empty(),
        "{:?}",
        c.screening.effects
    );
    assert_eq!(c.screening.selected.len(), 3);
    assert!(c.screening.notes[0].contains("no factor reached p < 0.05"));
    // The three carried are the three largest |effect|.
    let mut sizes: Vec<f64> = c.screening.effects.iter().map(|e| e.effect.abs()).collect();
    sizes.sort_by(|a, b| b.total_cmp(a));
    for e in c
        .screening
        .effects
        .iter()
        .filter(|e| c.screening.selected.contains(&e.label))
    {
        assert!(e.effect.abs() >= sizes[2]);
    }
    let report = String::from_utf8(bytes(dir.path(), "report.md")).unwrap();
    assert!(report.contains("no factor reached p < 0.05"));
}

#[test]
fn a_target_beyond_the_path_is_reported_at_the_path_end() {
    // Every angle 15° low: the path climbs all the way and still falls short.
    let low = Custom {
        name: "fifteen-low",
        f: |mean, hash| {
            mean - 15.0 + 0.3 * arachis::calibrate::surrogate::standard_normal_from(hash)
        },
    };
    let dir = tempfile::tempdir().unwrap();
    let c = run(&low, dir.path(), 2).unwrap().calibration;
    assert_eq!(c.steepest_ascent.direction, "ascent");
    assert!(c.steepest_ascent.best_at_path_end);
    assert_eq!(c.steepest_ascent.best, c.steepest_ascent.runs.len());
    assert!(c.steepest_ascent.notes[0].contains("path's last"));
    // The box reaches one step past the path's end.
    assert_eq!(c.box_behnken.path_points, [4, 6]);
    assert!(!c.validation.passed);
    let report = String::from_utf8(bytes(dir.path(), "report.md")).unwrap();
    assert!(report.contains("path's last") && report.contains("FAILED"));
}
