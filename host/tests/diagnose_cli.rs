//! The diagnosis commands through the real binary: synth → compare → diagnose → fit on a
//! hidden drag effect (the cheapest to fit: no base parameter responds to it), plus clear
//! errors for bad input and the "not identifiable" message for a one-condition study.

use std::process::Output;

use crate::cli_support;
use cli_support::{arachis_at_root as arachis, file_stamps};

fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

const TEMPLATE: &str = "testdata/diagnosis-tutorial/template.toml";

#[test]
fn loop_finds_and_fits_hidden_drag() {
    let dir = tempfile::tempdir().unwrap();
    let m = dir.path().join("m.toml");
    let m = m.to_str().unwrap();
    ok(&arachis(&[
        "synth", TEMPLATE, "--hidden", "drag=0.3", "--seed", "3", "--out", m,
    ]));
    // Deterministic given the seed.
    let m2 = dir.path().join("m2.toml");
    ok(&arachis(&[
        "synth",
        TEMPLATE,
        "--hidden",
        "drag=0.3",
        "--seed",
        "3",
        "--out",
        m2.to_str().unwrap(),
    ]));
    assert_eq!(std::fs::read(m).unwrap(), std::fs::read(&m2).unwrap());
    let plots = dir.path().join("plots");
    let cmp = ok(&arachis(&[
        "compare",
        m,
        "--plots",
        plots.to_str().unwrap(),
    ]));
    assert!(cmp.contains("the model misses something here"), "{cmp}");
    assert!(std::fs::read_to_string(plots.join("compare-3-fall.svg"))
        .unwrap()
        .contains("<svg"));
    let diag = ok(&arachis(&["diagnose", m]));
    assert!(diag.contains("1    drag"), "{diag}");
    assert!(diag.contains("MISSING"), "{diag}");
    let fit = ok(&arachis(&["fit", m, "--with", "drag", "--no-loco"]));
    assert!(fit.contains("verdict: accept 'drag'"), "{fit}");
}

#[test]
fn a_restitution_of_one_is_diagnosed_and_reported_on_its_limit() {
    // A study calibrated at e = 1 (its closed upper limit): the sensitivities step below it,
    // and a fit whose estimate reaches it says so. Both stopped with "restitution = 1.01 must
    // be in (0, 1]" before.
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("t.toml");
    let text = std::fs::read_to_string(std::path::Path::new(cli_support::REPO_ROOT).join(TEMPLATE))
        .unwrap();
    std::fs::write(
        &template,
        text.replace("restitution = 0.5", "restitution = 1.0"),
    )
    .unwrap();
    let m = dir.path().join("m.toml");
    let m = m.to_str().unwrap();
    let t = template.to_str().unwrap();
    ok(&arachis(&[
        "synth",
        t,
        "--hidden",
        "viscoelastic=2e-5",
        "--seed",
        "2",
        "--out",
        m,
    ]));
    let diag = ok(&arachis(&["diagnose", m]));
    assert!(diag.contains("1    viscoelastic"), "{diag}");
    // Seed 2 puts the unconstrained estimate of e above 1.
    let fit = ok(&arachis(&["fit", m, "--with", "viscoelastic", "--no-loco"]));
    assert!(
        fit.contains("restitution      1.00000e0 - at its upper limit; one-sided 95 % interval ["),
        "{fit}"
    );
}

#[test]
fn liggghts_values_through_synth_truth_are_diagnosed() {
    // `synth --truth`: noise on LIGGGHTS' values (SJKR cohesion 5e3 J/m³ hidden); diagnose
    // finds cohesion, and says when no measurement would tell the runner-up apart (drag, whose
    // signature on these rigs is nil) instead of proposing a useless one.
    let dir = tempfile::tempdir().unwrap();
    let m = dir.path().join("m.toml");
    let m = m.to_str().unwrap();
    ok(&arachis(&[
        "synth",
        "testdata/diagnosis-liggghts/template.toml",
        "--truth",
        "testdata/diagnosis-liggghts/cohesion-5e3.csv",
        "--seed",
        "1",
        "--out",
        m,
    ]));
    let diag = ok(&arachis(&["diagnose", m]));
    assert!(diag.contains("1    cohesion"), "{diag}");
    assert!(diag.contains("MISSING"), "{diag}");
    assert!(
        diag.contains("to tell 'cohesion' from 'drag' apart: no measurement in the rigs' search ranges would separate them further"),
        "{diag}"
    );
}

#[test]
fn tutorial_measurements_regenerate_bit_for_bit() {
    // docs/diagnosis-tutorial.md step 1: the committed file is what synth writes.
    let dir = tempfile::tempdir().unwrap();
    let m = dir.path().join("m.toml");
    ok(&arachis(&[
        "synth",
        TEMPLATE,
        "--hidden",
        "viscoelastic=1.3e-5",
        "--seed",
        "7",
        "--out",
        m.to_str().unwrap(),
    ]));
    let committed = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../testdata/diagnosis-tutorial/measured.toml"
    );
    assert_eq!(
        std::fs::read(&m).unwrap(),
        std::fs::read(committed).unwrap()
    );
}

#[test]
fn one_condition_study_is_not_identifiable() {
    let dir = tempfile::tempdir().unwrap();
    let t = dir.path().join("t.toml");
    std::fs::write(
        &t,
        "[diagnosis]\n[diagnosis.calibration]\nrestitution = 0.5\nyoungs_modulus_pa = 8.43e6\n\
         [[diagnosis.experiment]]\nkind = \"rebound\"\n[[diagnosis.experiment.point]]\n\
         condition = 0.4\nvalues = [0.45, 0.46, 0.44, 0.455]\n",
    )
    .unwrap();
    let diag = ok(&arachis(&["diagnose", t.to_str().unwrap()]));
    assert!(diag.contains("NOT IDENTIFIABLE"), "{diag}");
    assert!(
        diag.contains("no candidate effect is identifiable"),
        "{diag}"
    );
}

/// Issue 23: the written study states the noise its replicates were drawn with: `--noise`
/// overrides the template's `noise_sd` (0.01, 0.1, 1.0), one SD for all or per kind.
#[test]
fn synth_writes_the_noise_it_drew_with() {
    let dir = tempfile::tempdir().unwrap();
    let noise_sds = |args: &[&str]| -> Vec<f64> {
        let m = dir.path().join("m.toml");
        let mut all = vec!["synth", TEMPLATE, "--out", m.to_str().unwrap()];
        all.extend_from_slice(args);
        ok(&arachis(&all));
        let text = std::fs::read_to_string(&m).unwrap();
        let doc: toml::Value = toml::from_str(&text).unwrap();
        doc["diagnosis"]["experiment"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e["noise_sd"].as_float().unwrap())
            .collect()
    };
    assert_eq!(noise_sds(&[]), [0.01, 0.1, 1.0]);
    assert_eq!(noise_sds(&["--noise", "0.02"]), [0.02, 0.02, 0.02]);
    assert_eq!(noise_sds(&["--noise", "press=0.3"]), [0.01, 0.3, 1.0]);
}

#[test]
fn bad_input_is_a_clear_error() {
    let out = arachis(&["fit", TEMPLATE, "--with", "magic"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown parameter or effect 'magic'"));
    // A template has no measurements.
    let out = arachis(&["diagnose", TEMPLATE]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no values"));
    let out = arachis(&[
        "synth",
        TEMPLATE,
        "--hidden",
        "drag=-1",
        "--out",
        "/nonexistent/x.toml",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("must be >= 0"));
    // Issue 23: noise that would bury the truth is refused, and nothing is written (--noise
    // 1e300 once wrote values of 1e300).
    let dir = tempfile::tempdir().unwrap();
    let never = dir.path().join("never.toml");
    let out = arachis(&[
        "synth",
        TEMPLATE,
        "--noise",
        "1e300",
        "--out",
        never.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("would be noise alone"));
    assert!(!never.exists());
    // Repeated options were read as their first or last value without a word.
    for (args, message) in [
        (
            vec!["--hidden", "drag=0.3", "--hidden", "drag=0.5"],
            "--hidden gives 'drag' twice",
        ),
        (
            vec!["--noise", "0.01", "--noise", "0.02"],
            "--noise gives the SD for every experiment twice",
        ),
    ] {
        let mut all = vec!["synth", TEMPLATE, "--out", never.to_str().unwrap()];
        all.extend(args);
        let out = arachis(&all);
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(message), "{err}");
        assert!(!never.exists());
    }
    // Issue 23: --plots naming a file is refused at once, with its path (it once ran the
    // whole fit, then said "File exists (os error 17)").
    let file = dir.path().join("plots.svg");
    std::fs::write(&file, "").unwrap();
    let measured = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../testdata/diagnosis-tutorial/measured.toml"
    );
    let out = arachis(&[
        "fit",
        measured,
        "--with",
        "drag",
        "--plots",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("plots.svg: is a file"), "{err}");
    assert!(out.stdout.is_empty(), "the fit ran first");
}

/// `--runs DIR` stores every simulation of `compare`, `diagnose` and `fit` in a run cache:
/// the first call fills it, a second replays it, and both print what the command prints
/// without a cache (the same numbers, wherever the runs came from).
#[test]
fn a_run_cache_gives_the_same_report_and_is_replayed() {
    const MEASURED: &str = "testdata/diagnosis-tutorial/measured.toml";
    let dir = tempfile::tempdir().unwrap();
    for command in [
        &["compare"][..],
        &["diagnose"],
        &["fit", "--with", "viscoelastic"],
    ] {
        let runs = dir.path().join(command[0]);
        let runs = runs.to_str().unwrap();
        let with = |extra: &[&str]| {
            let mut args = vec![command[0], MEASURED];
            args.extend_from_slice(&command[1..]);
            args.extend_from_slice(extra);
            ok(&arachis(&args))
        };
        let plain = with(&[]);
        let filled = with(&["--runs", runs]);
        let stored = std::fs::read_dir(runs).unwrap().count();
        assert!(stored > 1, "{command:?}: {stored} stored runs");
        // Replayed, not simulated again: no stored run is rewritten.
        let before = file_stamps(runs.as_ref());
        let replayed = with(&["--runs", runs]);
        assert_eq!(
            file_stamps(runs.as_ref()),
            before,
            "{command:?}: the cache was written again"
        );
        assert_eq!(filled, plain, "{command:?}");
        assert_eq!(replayed, plain, "{command:?}");
    }
}

/// LIGGGHTS' rolling data (EPSD μr 0.01 hidden, `testdata/diagnosis-liggghts`) at one launch
/// speed only, written into `dir`: the measured study's path.
fn roll_at_one_speed(dir: &std::path::Path) -> String {
    let template = dir.join("roll-one-speed.toml");
    let text = std::fs::read_to_string(
        std::path::Path::new(cli_support::REPO_ROOT)
            .join("testdata/diagnosis-liggghts/roll-template.toml"),
    )
    .unwrap();
    let head = &text[..text.find("[[diagnosis.experiment.point]]").unwrap()];
    std::fs::write(
        &template,
        format!("{head}[[diagnosis.experiment.point]]\ncondition = 0.4\nreplicates = 4\n"),
    )
    .unwrap();
    let m = dir.join("m.toml");
    let m = m.to_str().unwrap().to_owned();
    ok(&arachis(&[
        "synth",
        template.to_str().unwrap(),
        "--truth",
        "testdata/diagnosis-liggghts/roll-epsd-0.01.csv",
        "--seed",
        "1",
        "--out",
        &m,
    ]));
    m
}

/// The proposal line of a diagnosis: its rig, and the separation it reaches (SE).
fn proposal(diag: &str) -> (String, f64) {
    let line = diag
        .lines()
        .find(|l| l.starts_with("to tell"))
        .unwrap_or_else(|| panic!("no proposal: {diag}"));
    let rig = line
        .split(" apart: measure ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .unwrap_or_else(|| panic!("{line}"))
        .to_owned();
    let after = line
        .split(" -> ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("{line}"));
    (rig, after)
}

#[test]
fn one_rig_at_one_condition_cannot_tell_rolling_resistance_from_cohesion() {
    // Issue 22: EPSD rolling resistance, cohesion and drag each explain the one slower mean,
    // so the tool says it cannot tell them apart and names the rig and condition that would.
    let dir = tempfile::tempdir().unwrap();
    let m = roll_at_one_speed(dir.path());
    let m = m.as_str();
    let diag = ok(&arachis(&["diagnose", m]));
    assert!(
        diag.contains("NOT DISTINGUISHABLE: cohesion and epsd_rolling"),
        "{diag}"
    );
    assert!(
        diag.contains("but these data cannot tell"),
        "no single best candidate may be named: {diag}"
    );
    // The proposal is another launch speed of the roll rig, away from the measured 0.4 m/s.
    let line = diag
        .lines()
        .find(|l| l.starts_with("to tell"))
        .unwrap_or_else(|| panic!("no proposal: {diag}"));
    let speed: f64 = line
        .split("measure roll at launch speed, m/s = ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("{line}"));
    assert!((speed - 0.4).abs() > 0.2, "{line}");
    // One sphere rolls the same way every time: no placement scatter, no noise warning.
    assert!(!diag.contains("may rest on noise"), "{diag}");
}

#[test]
fn a_rig_not_yet_measured_is_proposed_when_it_separates_better_at_the_stated_sd() {
    // Issue 22: the same one-speed roll data. A free fall responds to air drag and not at
    // all to cohesion (no contact), so a fall-time measurement separates the top two,
    // cohesion and drag, if it is precise enough; how precise is the user's statement.
    let dir = tempfile::tempdir().unwrap();
    let m = roll_at_one_speed(dir.path());
    let m = m.as_str();
    let plain = ok(&arachis(&["diagnose", m]));
    let (rig, roll_best) = proposal(&plain);
    assert_eq!(rig, "roll", "{plain}");
    // The unmeasured rigs the study can simulate are named, with how to try one.
    let hint = plain
        .lines()
        .find(|l| l.starts_with("rigs not yet measured"))
        .unwrap_or_else(|| panic!("no hint: {plain}"));
    assert!(
        hint.contains("fall (fall time, ms)") && hint.contains("--consider"),
        "{hint}"
    );
    assert!(
        !hint.contains("roll "),
        "the measured rig is not offered: {hint}"
    );
    // Fall time to 0.05 ms: the fall rig wins, beyond the roll's best separation.
    let precise = ok(&arachis(&["diagnose", m, "--consider", "fall=0.05"]));
    let (rig, fall_best) = proposal(&precise);
    assert_eq!(rig, "fall", "{precise}");
    assert!(
        precise.contains("(not measured yet; replicate SD 0.05 assumed, from --consider)"),
        "{precise}"
    );
    assert!(fall_best > roll_best + 1.0, "{fall_best} vs {roll_best}");
    // A thousand times noisier, the fall no longer competes: the roll's proposal returns
    // with the same separation.
    let noisy = ok(&arachis(&["diagnose", m, "--consider", "fall=50"]));
    assert_eq!(proposal(&noisy), ("roll".to_owned(), roll_best), "{noisy}");
}

#[test]
fn considering_a_rig_that_cannot_be_proposed_is_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let m = roll_at_one_speed(dir.path());
    let nothing = dir.path().join("nothing-written");
    for (consider, named) in [
        ("rol=0.1", "did you mean 'roll'?"),
        ("roll=0.1", "measured already"),
        ("drum=0.7", "does not take 'restitution'"),
        ("fall=-1", "positive"),
        ("fall", "RIG=SD"),
    ] {
        cli_support::assert_refused(&["diagnose", &m, "--consider", consider], named, &nothing);
    }
}

#[test]
fn with_nothing_identifiable_a_considered_rig_is_proposed_for_the_effect_only_it_reveals() {
    // Issue 22: a press at one load, drag hidden. The calibrated E absorbs everything the
    // one overlap shows; a free fall has no contact, so neither e nor E moves it, and air
    // drag's signature there is wholly outside what the calibration can mimic (100 % left).
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("press-one-load.toml");
    std::fs::write(
        &template,
        "[diagnosis]\nname = \"one load\"\n\n[diagnosis.calibration]\nrestitution = 0.5\n\
         youngs_modulus_pa = 8.43e6\n\n[[diagnosis.experiment]]\nkind = \"press\"\n\
         noise_sd = 0.1\n\n[[diagnosis.experiment.point]]\ncondition = 0.01\nreplicates = 4\n",
    )
    .unwrap();
    let m = dir.path().join("m.toml");
    let m = m.to_str().unwrap();
    ok(&arachis(&[
        "synth",
        template.to_str().unwrap(),
        "--hidden",
        "drag=0.3",
        "--seed",
        "1",
        "--out",
        m,
    ]));
    let plain = ok(&arachis(&["diagnose", m]));
    assert!(
        plain.contains("verdict: no candidate effect is identifiable with these data"),
        "{plain}"
    );
    assert!(
        !plain.contains("to make"),
        "searched without --consider: {plain}"
    );
    assert!(plain.contains("fall (fall time, ms)"), "{plain}");
    let asked = ok(&arachis(&["diagnose", m, "--consider", "fall=0.05"]));
    let lines: Vec<&str> = asked.lines().filter(|l| l.starts_with("to make")).collect();
    // First the measurement that reveals the most: another load of the press itself.
    assert!(
        lines
            .first()
            .is_some_and(|l| l.contains("measure press at load")),
        "{asked}"
    );
    let drag = lines
        .iter()
        .find(|l| l.starts_with("to make drag ("))
        .unwrap_or_else(|| panic!("drag not proposed: {asked}"));
    assert!(
        drag.contains("identifiable: measure fall at fall height")
            && drag.contains("(not measured yet; replicate SD 0.05 assumed, from --consider)"),
        "{drag}"
    );
    let left: f64 = drag
        .split("to make drag (")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("{drag}"));
    assert!(left >= 99.5, "{drag}");
}
