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
    // Pure scatter of SD 3° around 31°: no factor has an effect. At α = 0.001 the chance
    // that one of the 8 factors is flagged anyway is below 1 % (at the study's 0.05 it is
    // a third, so which draws a study's run hashes give would decide the test).
    let noise = Custom {
        name: "noise-only",
        f: |_, hash| 31.0 + 3.0 * arachis::calibrate::surrogate::standard_normal_from(hash),
    };
    let dir = tempfile::tempdir().unwrap();
    let study = study_with_line(dir.path(), "significance", "significance = 0.001");
    let c = calibrate(&study, &noise, &options(&dir.path().join("out"), 2))
        .unwrap()
        .calibration;
    assert!(
        c.screening.significant.is_empty(),
        "{:?}",
        c.screening.effects
    );
    assert_eq!(c.screening.selected.len(), 3);
    assert!(c.screening.notes[0].contains("no factor reached p < 0.001"));
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
    let report = String::from_utf8(bytes(&dir.path().join("out"), "report.md")).unwrap();
    assert!(report.contains("no factor reached p < 0.001"));
}

/// The shipped study with its line starting `key =` replaced by `line` (empty: removed),
/// written to `dir`.
fn study_with_line(dir: &Path, key: &str, line: &str) -> Study {
    let text = std::fs::read_to_string(STUDY).unwrap();
    let prefix = format!("{key} =");
    let edited: String = text
        .lines()
        .map(|l| if l.starts_with(&prefix) { line } else { l })
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(edited, text, "the shipped study has no '{key}' line");
    let path = dir.join("study.toml");
    std::fs::write(&path, edited).unwrap();
    Study::load(&path).unwrap()
}

/// Every angle 15° low: the planned path climbs all the way and still falls short.
fn fifteen_low() -> Custom<impl Fn(f64, u64) -> f64 + Sync> {
    Custom {
        name: "fifteen-low",
        f: |mean, hash| {
            mean - 15.0 + 0.3 * arachis::calibrate::surrogate::standard_normal_from(hash)
        },
    }
}

#[test]
fn a_target_beyond_the_planned_path_is_reported_at_the_path_end() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_with_line(dir.path(), "max_points", "");
    let c = calibrate(&study, &fifteen_low(), &options(&dir.path().join("out"), 2))
        .unwrap()
        .calibration;
    assert_eq!(c.steepest_ascent.direction, "ascent");
    assert_eq!(c.steepest_ascent.runs.len(), 5);
    assert!(c.steepest_ascent.best_at_path_end);
    assert_eq!(c.steepest_ascent.best, c.steepest_ascent.runs.len());
    assert!(c.steepest_ascent.notes[0].contains("path's last"));
    // The box reaches one step past the path's end.
    assert_eq!(c.box_behnken.path_points, [4, 6]);
    assert!(!c.validation.passed);
    let report = String::from_utf8(bytes(&dir.path().join("out"), "report.md")).unwrap();
    assert!(report.contains("path's last") && report.contains("FAILED"));
}

#[test]
fn the_path_goes_on_with_doubling_gaps_until_it_crosses_the_target() {
    let dir = tempfile::tempdir().unwrap();
    let c = run(&fifteen_low(), dir.path(), 2).unwrap().calibration;
    let sa = &c.steepest_ascent;
    let responses: Vec<f64> = sa.runs.iter().map(|r| r.response).collect();
    // The planned five stay below 31.06°; the extension runs in pairs, gaps 2, 4, 8, …
    assert!(responses[..5].iter().all(|&y| y < 31.06), "{responses:?}");
    assert!(sa.runs.len() > 5 && sa.runs.len() % 2 == 1, "{responses:?}");
    let gaps: Vec<f64> = sa.positions.windows(2).map(|w| w[1] - w[0]).collect();
    let mut expected = vec![1.0; 4];
    expected.extend((1..sa.runs.len() - 4).map(|k| f64::powi(2.0, k as i32)));
    assert_eq!(gaps, expected);
    // It stopped at the first pair that reached the target.
    let before_last_pair = &responses[..responses.len() - 2];
    assert!(before_last_pair.iter().all(|&y| y < 31.06));
    assert!(responses[responses.len() - 2..].iter().any(|&y| y >= 31.06));
    assert!(sa
        .notes
        .iter()
        .any(|n| n.contains("went on with doubling gaps")));
    // Run numbers continue across the batches.
    let numbers: Vec<usize> = sa.runs.iter().map(|r| r.run).collect();
    assert_eq!(numbers, (1..=sa.runs.len()).collect::<Vec<_>>());
    // The Box–Behnken box brackets the target and the optimum validates (surrogate scatter
    // 0.3°, ψ limit 2 %).
    assert!(c.validation.passed, "{:?}", c.validation);
}

#[test]
fn the_path_never_leaves_the_physical_limits() {
    // Every angle far above the target and nearly flat: a descent that never arrives, run
    // out to position 258, where the lead factor is 129 coded units from its origin.
    let high = Custom {
        name: "always-high",
        f: |mean, hash| {
            60.0 + 0.05 * mean + 0.3 * arachis::calibrate::surrogate::standard_normal_from(hash)
        },
    };
    let dir = tempfile::tempdir().unwrap();
    let study = study_with_line(dir.path(), "max_points", "max_points = 12");
    let c = calibrate(&study, &high, &options(&dir.path().join("out"), 2))
        .unwrap()
        .calibration;
    let sa = &c.steepest_ascent;
    assert_eq!(sa.direction, "descent");
    assert!(sa.runs.len() > 5);
    let mut at_a_bound = 0;
    for run in sa.runs.iter().chain(&c.box_behnken.runs) {
        for (name, &value) in &run.actual {
            let spec = arachis::study::parameters::lookup(name).unwrap();
            let range = c
                .screening
                .factors
                .iter()
                .find(|f| &f.name == name)
                .unwrap();
            let inside = (range.low..=range.high).contains(&value);
            assert!(
                inside || spec.limits.check(value).is_ok(),
                "{name} = {value} is outside its range and its physical limits"
            );
            at_a_bound +=
                usize::from(value == 0.0 || (inside && spec.limits.check(value).is_err()));
        }
    }
    // The far points did reach a limit (a friction coefficient at 0 or a Poisson ratio held
    // at its screened level beyond 0.5), so the check above was exercised.
    assert!(at_a_bound > 0, "{:?}", sa.runs);
}
