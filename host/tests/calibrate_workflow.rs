//! The calibration workflow through the real code paths (designs, ANOVA, desirability,
//! run cache, report) on seed 000's surrogate (`calibrate::surrogate`), which is built from
//! seed 000 Table 4, eq. (22) and Table 8 only, independently of the code under test.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use arachis::calibration::{
    calibrate, CalibrateError, Executor, Outcome, Progress, Responses, Rig, RigError, RunRequest,
    SpecHash,
};
use arachis::report::{write_calibration, CalibrationJson, Provenance};
use arachis::rigs::pod_bench::PodBenchRig;
use arachis::rigs::pod_world::ModeName;
use arachis::rigs::repose_cylinder::TEST as REPOSE;
use arachis::rigs::repose_surrogate::{standard_normal_from, Seed000Surrogate, SurrogateRig};
use arachis::study::Study;

const STUDY: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../testdata/peanut-pods-saline/study.toml"
);

fn study() -> Study {
    Study::load(Path::new(STUDY)).unwrap()
}

/// The surrogate as `study`'s repose rig.
fn surrogate(study: &Study, noise_sd_deg: f64) -> SurrogateRig<'_> {
    SurrogateRig {
        pod: PodBenchRig::new(study.pod_world().unwrap(), REPOSE, ModeName::Quick),
        surrogate: Seed000Surrogate { noise_sd_deg },
        delay: Duration::ZERO,
    }
}

/// A finished calibration: the engine's numbers and the written file's.
#[derive(Debug)]
struct Done {
    outcome: Outcome,
    json: CalibrationJson,
}

/// Calibrates `study` on `rig` into `out` with `jobs` threads, writing the report.
fn calibrate_into(
    study: &Study,
    rig: &dyn Rig,
    out: &Path,
    jobs: usize,
) -> Result<Done, CalibrateError> {
    let problem = study.problem(rig, rig).unwrap();
    let executor = Executor::new(Some(jobs), Some(&out.join("runs")), Progress::hidden())?;
    let outcome = calibrate(&problem, &executor)?;
    let provenance = Provenance {
        study: study.name().to_owned(),
        mode: "quick".into(),
        pile: None,
    };
    let json = write_calibration(&problem, &outcome.stages, &provenance, out)?;
    Ok(Done { outcome, json })
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

/// A rig failing every run after the first `k` (an interruption after k runs).
struct FailsAfter<R: Rig> {
    inner: R,
    k: usize,
    calls: AtomicUsize,
}

impl<R: Rig> Rig for FailsAfter<R> {
    fn id(&self) -> String {
        self.inner.id()
    }
    fn description(&self) -> String {
        self.inner.description()
    }
    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        self.inner.specification(request)
    }
    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        if self.calls.fetch_add(1, Ordering::SeqCst) >= self.k {
            return Err(RigError("interrupted".into()));
        }
        self.inner.run(request)
    }
}

/// The noise-free surrogate's angle transformed by `f(angle, spec hash)` (so the target is
/// out of reach, or pure noise).
struct Custom<'a, F: Fn(f64, u64) -> f64 + Sync> {
    name: &'static str,
    inner: SurrogateRig<'a>,
    f: F,
}

impl<F: Fn(f64, u64) -> f64 + Sync> Rig for Custom<'_, F> {
    fn id(&self) -> String {
        self.name.to_owned()
    }
    fn description(&self) -> String {
        format!("test rig {}", self.name)
    }
    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        self.inner.specification(request)
    }
    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        let mean = self.inner.run(request)?["repose_angle"];
        let hash = SpecHash::of(&self.specification(request)?).0;
        Ok(Responses::from([(
            "repose_angle".to_owned(),
            (self.f)(mean, hash),
        )]))
    }
}

fn custom<'a, F: Fn(f64, u64) -> f64 + Sync>(
    study: &'a Study,
    name: &'static str,
    f: F,
) -> Custom<'a, F> {
    Custom {
        name,
        inner: surrogate(study, 0.0),
        f,
    }
}

#[test]
fn screening_flags_pod_pod_static_friction_and_the_optimum_validates_within_2_percent() {
    let dir = tempfile::tempdir().unwrap();
    let study = study();
    let done = calibrate_into(&study, &surrogate(&study, 0.312), dir.path(), 2).unwrap();
    let (outcome, c) = (&done.outcome, &done.outcome.stages);
    // Seed 000 Table 5: x4 is the most significant factor (p = 0.0022).
    let strongest = c.screening.strongest().unwrap();
    assert_eq!(strongest.name, "pod-pod.static_friction");
    assert!(done.json.screening.significant.contains(&"x4".to_owned()));
    assert_eq!(c.screening.runs.len(), 12);
    // Seed 000 §3.6.2: the calibrated angle within 2 % of the bench's 31.06°.
    assert_eq!(done.json.target.value, 31.06);
    assert!(c.validation.passed, "{:?}", c.validation);
    assert!(c.validation.relative_error_pct < 2.0);
    // The polynomial the optimiser searches is the ANOVA's coded equation.
    use arachis::optimize::ResponseSurface;
    let surface = c.surface.surface();
    for r in &c.surface.runs {
        let d = surface.predict(&r.coded) - c.surface.anova.predict(&r.coded);
        assert!(d.abs() < 1e-9, "{d}");
    }
    // The optimum hits the target on the fitted surface.
    assert!((c.optimum.predicted - 31.06).abs() < 0.01);
    // The quadratic fit is adequate: lack of fit not significant against pure error.
    let lof = c.surface.anova.lack_of_fit.as_ref().unwrap();
    assert!(lof.p > 0.05, "{lof:?}");
    // Every run is stored once under its hash; nothing was replayed on a fresh folder.
    let total =
        c.screening.runs.len() + c.path.runs.len() + c.surface.runs.len() + c.validation.runs.len();
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
    let study = study();
    calibrate_into(&study, &surrogate(&study, 0.312), a.path(), 1).unwrap();
    calibrate_into(&study, &surrogate(&study, 0.312), b.path(), 2).unwrap();
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
    let study = study();
    let reference = tempfile::tempdir().unwrap();
    let full = calibrate_into(&study, &surrogate(&study, 0.312), reference.path(), 1).unwrap();
    let total = full.outcome.simulated;
    let expected = bytes(reference.path(), "calibration.json");
    // Interruptions in screening, on the path, in the Box–Behnken design, at validation.
    for k in [0, 7, 14, 40, total - 1] {
        let dir = tempfile::tempdir().unwrap();
        let failing = FailsAfter {
            inner: surrogate(&study, 0.312),
            k,
            calls: AtomicUsize::new(0),
        };
        let err = calibrate_into(&study, &failing, dir.path(), 1).unwrap_err();
        assert!(err.to_string().contains("interrupted"), "{err}");
        assert!(!dir.path().join("calibration.json").exists());
        assert_eq!(stored_runs(dir.path()), k, "k = {k}");
        let resumed = calibrate_into(&study, &surrogate(&study, 0.312), dir.path(), 1).unwrap();
        assert_eq!(resumed.outcome.replayed, k, "k = {k}");
        assert_eq!(resumed.outcome.simulated, total - k, "k = {k}");
        assert!(bytes(dir.path(), "calibration.json") == expected, "k = {k}");
    }
    // Two threads: whatever finished before the failure is kept, and the end is the same.
    let dir = tempfile::tempdir().unwrap();
    let failing = FailsAfter {
        inner: surrogate(&study, 0.312),
        k: 20,
        calls: AtomicUsize::new(0),
    };
    assert!(calibrate_into(&study, &failing, dir.path(), 2).is_err());
    let kept = stored_runs(dir.path());
    let resumed = calibrate_into(&study, &surrogate(&study, 0.312), dir.path(), 2).unwrap();
    assert_eq!(resumed.outcome.replayed, kept);
    assert!(bytes(dir.path(), "calibration.json") == expected);
}

#[test]
fn cached_runs_of_another_simulator_or_damaged_files_are_simulated_again() {
    let study = study();
    let dir = tempfile::tempdir().unwrap();
    let first = calibrate_into(&study, &surrogate(&study, 0.312), dir.path(), 2).unwrap();
    let other = calibrate_into(&study, &surrogate(&study, 0.0), dir.path(), 2).unwrap();
    assert_eq!(
        other.outcome.replayed, 0,
        "another simulator's results were replayed"
    );
    // Back to the first simulator: the screening runs (same specs) were overwritten by the
    // other simulator, so they run again, and the result is the first one's.
    let again = calibrate_into(&study, &surrogate(&study, 0.312), dir.path(), 2).unwrap();
    assert!(again.outcome.simulated >= first.outcome.stages.screening.runs.len());
    assert_eq!(again.json, first.json);
    // Damage one file: only that run is redone.
    let victim = &again.json.screening.stage.runs[3].spec_hash;
    std::fs::write(dir.path().join(format!("runs/{victim}.json")), "{\"trunc").unwrap();
    let repaired = calibrate_into(&study, &surrogate(&study, 0.312), dir.path(), 2).unwrap();
    assert_eq!(repaired.outcome.simulated, 1);
    assert_eq!(repaired.json, again.json);
}

#[test]
fn nothing_significant_proceeds_with_the_largest_effects_and_says_so() {
    // Pure scatter of SD 3° around 31°: no factor has an effect. At α = 0.001 the chance
    // that one of the 8 factors is flagged anyway is below 1 % (at the study's 0.05 it is
    // a third, so which draws a study's run hashes give would decide the test).
    let dir = tempfile::tempdir().unwrap();
    let study = study_with_line(dir.path(), "significance", "significance = 0.001");
    let noise = custom(&study, "noise-only", |_, hash| {
        31.0 + 3.0 * standard_normal_from(hash)
    });
    let c = calibrate_into(&study, &noise, &dir.path().join("out"), 2)
        .unwrap()
        .json;
    assert!(
        c.screening.significant.is_empty(),
        "{:?}",
        c.screening.stage.effects
    );
    assert_eq!(c.screening.selected.len(), 3);
    assert!(c.screening.notes[0].contains("no factor reached p < 0.001"));
    // The three carried are the three largest |effect|.
    let mut sizes: Vec<f64> = c
        .screening
        .stage
        .effects
        .iter()
        .map(|e| e.effect.abs())
        .collect();
    sizes.sort_by(|a, b| b.total_cmp(a));
    for e in c
        .screening
        .stage
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
fn fifteen_low(study: &Study) -> Custom<'_, impl Fn(f64, u64) -> f64 + Sync> {
    custom(study, "fifteen-low", |mean, hash| {
        mean - 15.0 + 0.3 * standard_normal_from(hash)
    })
}

#[test]
fn a_target_beyond_the_planned_path_is_reported_at_the_path_end() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_with_line(dir.path(), "max_points", "");
    let c = calibrate_into(&study, &fifteen_low(&study), &dir.path().join("out"), 2)
        .unwrap()
        .json;
    let sa = &c.steepest_ascent.stage;
    assert_eq!(sa.direction.name(), "ascent");
    assert_eq!(sa.runs.len(), 5);
    assert!(c.steepest_ascent.best_at_path_end);
    assert_eq!(sa.best, sa.runs.len());
    assert!(c.steepest_ascent.notes[0].contains("path's last"));
    // The box reaches one step past the path's end.
    assert_eq!(c.surface().path_points, [4, 6]);
    assert!(!c.validation.stage.passed);
    let report = String::from_utf8(bytes(&dir.path().join("out"), "report.md")).unwrap();
    assert!(report.contains("path's last") && report.contains("FAILED"));
}

#[test]
fn the_path_goes_on_with_doubling_gaps_until_it_crosses_the_target() {
    let dir = tempfile::tempdir().unwrap();
    let study = study();
    let c = calibrate_into(&study, &fifteen_low(&study), dir.path(), 2)
        .unwrap()
        .json;
    let sa = &c.steepest_ascent.stage;
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
    assert!(c
        .steepest_ascent
        .notes
        .iter()
        .any(|n| n.contains("went on with doubling gaps")));
    // Run numbers continue across the batches.
    let numbers: Vec<usize> = sa.runs.iter().map(|r| r.run).collect();
    assert_eq!(numbers, (1..=sa.runs.len()).collect::<Vec<_>>());
    // The Box–Behnken box brackets the target and the optimum validates (surrogate scatter
    // 0.3°, ψ limit 2 %).
    assert!(c.validation.stage.passed, "{:?}", c.validation);
}

#[test]
fn the_path_never_leaves_the_physical_limits() {
    // Every angle far above the target and nearly flat: a descent that never arrives, run
    // out to position 258, where the lead factor is 129 coded units from its origin.
    let dir = tempfile::tempdir().unwrap();
    let study = study_with_line(dir.path(), "max_points", "max_points = 12");
    let high = custom(&study, "always-high", |mean, hash| {
        60.0 + 0.05 * mean + 0.3 * standard_normal_from(hash)
    });
    let c = calibrate_into(&study, &high, &dir.path().join("out"), 2)
        .unwrap()
        .json;
    let sa = &c.steepest_ascent.stage;
    assert_eq!(sa.direction.name(), "descent");
    assert!(sa.runs.len() > 5);
    let mut at_a_bound = 0;
    for run in sa.runs.iter().chain(&c.surface().runs) {
        for (name, &value) in &run.values {
            let spec = arachis::study::parameters::lookup(name).unwrap();
            let range = c
                .screening
                .stage
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
