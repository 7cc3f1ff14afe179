//! Issue 6 must-show: "The calibrated detachment force is within 5 % of the target", now
//! through the one calibration engine (issue 17).
//!
//! Runs seed 001's plan (Plackett–Burman + 3 centre points → steepest ascent → central
//! composite, α = 1.414, 5 centre points → optimum → validation pull) of the shipped study
//! on the fixed-point pull-off rig; about 40 pulls of a few hundredths of a second each.

use arachis::calibration::{calibrate, Executor, Progress};
use arachis::report::pull_off::{markdown, PlantCalibration};
use arachis::rigs::pull_off::PullOffRig;
use arachis::rigs::pull_off::SEED_SIGNIFICANT;
use arachis::study::Study;

/// The shipped study calibrated with `named` factors for the path and the design (`None`:
/// the screening's choice).
fn calibrated(named: Option<Vec<String>>) -> PlantCalibration {
    let mut study = Study::shipped_pull_off();
    study.set_named_factors(named, "this test").unwrap();
    let rig = PullOffRig {
        base: study.pull_off_setup().unwrap(),
    };
    let problem = study.problem(&rig, &rig).unwrap();
    let executor = Executor::new(None, None, Progress::hidden()).unwrap();
    let outcome = calibrate(&problem, &executor).unwrap();
    PlantCalibration::new(&problem, &outcome.stages, "test", &rig)
}

#[test]
fn seed001_plan_calibrates_the_junction_to_the_target() {
    let cal = calibrated(None);
    let o = &cal.optimum;

    // The must-show: the validation pull at the optimum within 5 % of 7.18 N.
    assert!(
        o.relative_error_pct <= 5.0 && o.passed,
        "validated {} N vs target {} N: {} %",
        o.validated_n,
        cal.target_n,
        o.relative_error_pct
    );

    // Independent check of every run: in an axial pull the junction is in pure tension, so
    // the criterion σmax = Fn/A ≥ σc breaks it at F = σc·πRb² (DESIGN §2). Tolerance 1 %:
    // the pull force also carries the stalk's inertia at 0.1 m/s.
    assert!(
        cal.axial_check_max_deviation_pct < 1.0,
        "largest deviation from σc·πRb²: {} %",
        cal.axial_check_max_deviation_pct
    );
    assert!((o.validated_n - o.predicted_axial_n).abs() / o.predicted_axial_n < 0.01);

    // Screening: of the seed's significant factors (x8, x7, x2, x4) the strength x8 is found,
    // with the largest effect; the bond radius x9 (seed p = 0.061) is found too.
    let s = &cal.screening;
    assert_eq!(SEED_SIGNIFICANT[0], "x8");
    assert!(
        s.significant.contains(&"x8".to_owned()),
        "{:?}",
        s.significant
    );
    assert!(
        s.significant.contains(&"x9".to_owned()),
        "{:?}",
        s.significant
    );
    let effect = |label: &str| s.effects.iter().find(|e| e.label == label).unwrap();
    assert!(effect("x8").effect > 0.0);
    // Why x7, x2 and x4 differ from the seed, with numbers: an axial pull does not load the
    // junction's shear stiffness, and no unbonded pair touches before the break, so x1–x7
    // show only what the x8·x9 interaction of F = σc·πRb² aliases onto every column of a
    // 12-run Plackett–Burman design: ±2b₈₉/3, computed independently from σc·πRb² at the
    // corners (0.184 N). Tolerance 2 %: the simulated forces deviate from σc·πRb² by < 1 %.
    let alias = s.x8_x9_alias_effect_n;
    assert!((alias - 0.1843).abs() < 1e-3, "{alias}");
    for label in ["x1", "x2", "x3", "x4", "x5", "x6", "x7"] {
        let e = effect(label);
        assert!(
            (e.effect.abs() - alias).abs() < 0.02 * alias && e.p >= 0.05,
            "{label}: effect {} N (alias {alias} N), p {}",
            e.effect,
            e.p
        );
    }
    // The carried factors are the two strong ones; the surface fits the rig closely.
    assert_eq!(s.carried, ["x8", "x9"]);
    assert_eq!(cal.central_composite.runs.len(), 13);
    assert!(cal.central_composite.anova.fit.r2 > 0.99);

    // The report renders every stage.
    let md = markdown(&cal);
    for heading in ["## 1.", "## 2.", "## 3.", "## 4."] {
        assert!(md.contains(heading), "{md}");
    }
}

/// Seed 001 carried x7 and x8 (Table 7's **), as the shipped study does; on the same path
/// the plan still reaches the target, through x8 alone: x7 moves but does not act in an
/// axial pull.
#[test]
fn seed001_carried_factors_also_reach_the_target() {
    let carry = vec!["x7".to_owned(), "x8".to_owned()];
    let cal = calibrated(Some(carry.clone()));
    assert_eq!(cal.screening.carried, carry);
    assert!(cal.optimum.passed, "{} %", cal.optimum.relative_error_pct);
    let ccd = &cal.central_composite.anova;
    let p = |name: &str| ccd.terms.iter().find(|t| t.name == name).unwrap().p;
    assert!(p("x8") < 0.01, "x8 p {}", p("x8"));
    // x7's coded coefficient is below 0.1 % of x8's over the design.
    let b = |name: &str| {
        ccd.coefficients
            .iter()
            .find(|c| c.term == name)
            .unwrap()
            .estimate
    };
    assert!(
        b("x7").abs() < 1e-3 * b("x8").abs(),
        "x7 {} x8 {}",
        b("x7"),
        b("x8")
    );
}
