//! Issue 22 on a second engine's data: true values that LIGGGHTS 3.8 made
//! (`testdata/diagnosis-liggghts/*.csv`, written by `scripts/liggghts-diagnosis-truth.py`;
//! LIGGGHTS is not needed to replay them), with noise drawn by `synth`'s own function over
//! ten seeds.
//!
//! - Must-show 1: rebound ratios with no damping (e = 1) and no cohesion (`rebound-e1.csv`).
//!   Both the restitution (1) and the cohesion (0) lie on an end of their intervals: the fit
//!   and the diagnosis run without error, and the restitution is on its end or within 2 SE.
//! - Must-show 2 and 3 for SJKR cohesion on the rebound and press rigs (`cohesion-5e3.csv`,
//!   `null.csv`): the hidden cohesion ranked first and claimed, the fit within 2 SE of
//!   LIGGGHTS' value; no claim without it.
//!
//! - Must-show 2 and 3 for EPSD rolling resistance on the roll rig (`roll-epsd-0.01.csv`,
//!   `roll-null.csv`; LIGGGHTS' `rolling_friction epsd2`): found, claimed and fitted; no claim
//!   without it.
//!
//! The cohesion is not determined by these data: without damping, SJKR's attraction depends
//! on the overlap only, so it returns on the way out what it took on the way in. LIGGGHTS'
//! rebound ratios at e = 1 stay 1 to 1e-8 up to k = 5e4 J/m³ (scripts/liggghts-diagnosis-truth.py
//! --cohesion-j-m3, 2026-11-27). The fit reports that as a standard error far above any
//! plausible k, and the test asserts only that its estimate stays in its interval.

use crate::diagnose_support;
use std::path::{Path, PathBuf};

use arachis::diagnose::residuals::lack_of_fit;
use arachis::diagnose::synth::truths_from_csv;
use arachis::study::diagnosis::DiagnosisSection;
use arachis::study::Study;
use diagnose_support::*;

/// Noise seeds.
const SEEDS: u64 = 10;

fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../testdata/diagnosis-liggghts")
}

/// The `[diagnosis]` of the template `file` in the data folder.
fn section(file: &str) -> DiagnosisSection {
    Study::load(&data_dir().join(file))
        .unwrap()
        .file()
        .diagnosis
        .clone()
        .unwrap()
}

/// The rebound template's `[diagnosis]`, calibrated at `restitution`.
fn template_at(restitution: f64) -> DiagnosisSection {
    let mut section = section("rebound-template.toml");
    section.calibration.restitution = restitution;
    section
}

/// The rebound template calibrated at `restitution`, with LIGGGHTS' truths.
fn case_at(restitution: f64) -> Case {
    let study = study_of(&template_at(restitution));
    let truth = truths_from_csv(&data_dir().join("rebound-e1.csv"), &study.series()).unwrap();
    case_from_truth(study, truth)
}

/// `value` is on `end`, or within 2 SE of it.
fn near(name: &str, value: f64, se: f64, on: Option<f64>, end: f64) -> bool {
    println!("  {name} {value:.5e} ± {se:.2e}, on an end: {on:?}");
    on == Some(end) || (value - end).abs() <= 2.0 * se
}

#[test]
fn liggghts_data_on_the_limits_are_fitted_without_error() {
    // From a first guess e = 0.5, as a user would start.
    let c = case_at(0.5);
    let cohesion = effect("cohesion");
    let mut e_ok = 0;
    for seed in 0..SEEDS {
        let cmp = c.compare(seed, cohesion, false);
        let f = &cmp.with;
        let at = |name: &str| {
            let k = f.free.iter().position(|p| p.name == name).unwrap();
            (
                arachis::diagnose::params::value(f.free[k], &f.params),
                f.std_errors[k],
                f.on_end[k],
            )
        };
        println!("seed {seed}:");
        let (e, se, on) = at("restitution");
        e_ok += near("restitution", e, se, on, 1.0) as usize;
        let (k, se, _) = at("cohesion");
        println!("  cohesion {k:.3e} ± {se:.2e} J/m^3");
        assert!(k >= 0.0 && se > 1e5, "seed {seed}: cohesion {k} ± {se}");
    }
    println!("restitution at 1: {e_ok}/{SEEDS}");
    assert!(e_ok >= 8);
}

#[test]
fn liggghts_data_are_diagnosed_at_a_calibration_on_the_limit() {
    // Calibrated at e = 1 (the truth): the sensitivities step below it, and no effect is
    // claimed where none is hidden.
    let c = case_at(1.0);
    let claims = (0..SEEDS).filter(|&s| c.ranking(s).any_claimed()).count();
    println!("claims with no hidden effect: {claims}/{SEEDS}");
    assert!(claims <= 1);
}

#[test]
fn a_truth_file_must_cover_every_point() {
    let study = study_of(&template_at(0.5));
    let dir = tempfile::tempdir().unwrap();
    let short = dir.path().join("short.csv");
    let text = std::fs::read_to_string(data_dir().join("rebound-e1.csv")).unwrap();
    let kept: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with("rebound,0.7,"))
        .collect();
    std::fs::write(&short, kept.join("\n")).unwrap();
    let err = truths_from_csv(Path::new(&short), &study.series())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("no truth for rebound at condition 0.7"),
        "{err}"
    );
}

/// The template `template` with LIGGGHTS' truths from `file`, both in the data folder.
fn liggghts_case(template: &str, file: &str) -> Case {
    let study = study_of(&section(template));
    let truth = truths_from_csv(&data_dir().join(file), &study.series()).unwrap();
    case_from_truth(study, truth)
}

/// The rebound-and-press template with LIGGGHTS' truths from `file`.
fn rebound_and_press(file: &str) -> Case {
    liggghts_case("template.toml", file)
}

/// The largest |a − b| over matching entries.
fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The SJKR cohesion LIGGGHTS hid in cohesion-5e3.csv, J/m³.
const HIDDEN_COHESION_J_M3: f64 = 5.0e3;

/// Over the ten noise seeds of case `c`, with `name` hidden at `hidden` by LIGGGHTS: the
/// effect ranked first and claimed, the fit within 2 SE of `hidden`, and the replicate RMS of
/// every experiment within [0.8, 1.3] × its pure-error SD after the fit, each in ≥ 8 of 10.
fn found_and_fitted(c: &Case, name: &str, hidden: f64) {
    let effect = effect(name);
    let (mut first, mut covered, mut in_band) = (0, 0, 0);
    for seed in 0..SEEDS {
        let r = c.ranking(seed);
        if r.top().map(|t| t.effect.name) == Some(name) && r.any_claimed() {
            first += 1;
        }
        let f = c.compare(seed, effect, false).with;
        // Residual RMS over the replicates against the pure-error SD, per experiment.
        let ratios: Vec<f64> = lack_of_fit(&c.data(seed), &f.predictions)
            .unwrap()
            .iter()
            .map(|l| l.rms / l.sd)
            .collect();
        if ratios.iter().all(|r| (0.8..=1.3).contains(r)) {
            in_band += 1;
        }
        let k = f.free.iter().position(|p| p.name == name).unwrap();
        let (v, se) = (
            arachis::diagnose::params::value(effect, &f.params),
            f.std_errors[k],
        );
        println!("seed {seed}: {name} {v:.5e} ± {se:.2e}; RMS/SD after the fit {ratios:.3?}");
        if (v - hidden).abs() <= 2.0 * se {
            covered += 1;
        }
    }
    println!(
        "{name} first and claimed {first}/{SEEDS}; within 2 SE {covered}/{SEEDS}; \
         RMS/SD in [0.8, 1.3] for every rig {in_band}/{SEEDS}"
    );
    assert!(first >= 8);
    assert!(covered >= 8);
    assert!(in_band >= 8);
}

/// Claims over the ten noise seeds of case `c`, which hides nothing: at most 1 of 10.
fn rarely_claimed(c: &Case) {
    let claims = (0..SEEDS).filter(|&s| c.ranking(s).any_claimed()).count();
    println!("no hidden effect: a claim in {claims}/{SEEDS}");
    assert!(claims <= 1);
}

#[test]
fn cohesion_hidden_by_liggghts_is_found_and_fitted() {
    // Rebound and press at six conditions each, made by LIGGGHTS with SJKR cohesion 5e3 J/m³
    // (the press at 0.1 N moves by 0.50 µm, 10 SE of its mean); the study is calibrated at
    // LIGGGHTS' e and E, without cohesion.
    found_and_fitted(
        &rebound_and_press("cohesion-5e3.csv"),
        "cohesion",
        HIDDEN_COHESION_J_M3,
    );
}

#[test]
fn liggghts_data_without_a_hidden_effect_rarely_claim_one() {
    rarely_claimed(&rebound_and_press("null.csv"));
}

#[test]
fn the_rigs_agree_with_liggghts() {
    // LIGGGHTS at e = 0.5 with SJKR cohesion 5e3 J/m³ (cohesion-5e3.csv) against these rigs
    // with the same values: rebound ratios within 5e-4 and resting overlaps within 0.01 µm,
    // a twentieth and a tenth of the template's noise SDs (0.01 and 0.1 µm). Measured on
    // 2026-11-27: rebound 2.7e-4 apart at most (3.3e-4 without cohesion, null.csv), a
    // systematic offset: the rig takes 100 steps per contact and symplectic Euler, LIGGGHTS'
    // deck about 1 000 and velocity Verlet (LIGGGHTS alone moves by 5e-5 from dt 1e-7 to
    // 1e-6). Issue 18's single-contact cross-check holds 0.5 %.
    let c = rebound_and_press("cohesion-5e3.csv");
    let ours = case_for(
        section("template.toml"),
        Some(("cohesion", HIDDEN_COHESION_J_M3)),
    )
    .truth;
    for (ei, tolerance) in [(0, 5e-4), (1, 0.01)] {
        let worst = largest_difference(&c.truth[ei], &ours[ei]);
        println!("experiment {ei}: largest difference {worst:.3e}");
        assert!(worst <= tolerance, "experiment {ei}: {worst} > {tolerance}");
    }
}

/// The roll template with LIGGGHTS' truths from `file`.
fn roll(file: &str) -> Case {
    liggghts_case("roll-template.toml", file)
}

/// The rolling friction LIGGGHTS' `epsd2` used in roll-epsd-0.01.csv.
const HIDDEN_ROLLING_FRICTION: f64 = 0.01;

#[test]
fn the_roll_rig_agrees_with_liggghts() {
    // LIGGGHTS' epsd2 at μr 0.01 against the rig with the core's EPSD at 0.01: speed ratios
    // within 1e-3, a tenth of the template's noise SD (0.01). Without rolling resistance both
    // keep the launch speed (roll-null.csv holds 1 at every speed).
    let c = roll("roll-epsd-0.01.csv");
    let ours = case_for(
        section("roll-template.toml"),
        Some(("epsd_rolling", HIDDEN_ROLLING_FRICTION)),
    )
    .truth;
    let worst = largest_difference(&c.truth[0], &ours[0]);
    println!("LIGGGHTS {:?}\nArachis  {:?}", c.truth[0], ours[0]);
    println!("largest difference {worst:.3e}");
    assert!(worst <= 1e-3, "{worst}");
    // The smallest launch speed, 0.1 m/s, loses 14 % of its speed: the effect is 28 SE of
    // that point's mean (noise SD 0.01, 4 replicates).
    assert!(c.truth[0][0] < 0.9);
}

#[test]
fn rolling_resistance_hidden_by_liggghts_is_found_and_fitted() {
    found_and_fitted(
        &roll("roll-epsd-0.01.csv"),
        "epsd_rolling",
        HIDDEN_ROLLING_FRICTION,
    );
}

#[test]
fn rolling_data_without_a_hidden_effect_rarely_claim_one() {
    rarely_claimed(&roll("roll-null.csv"));
}
