//! Derringer–Suich desirability functions and the overall desirability
//! D = (Π dᵢ^rᵢ)^(1/Σrᵢ) (DESIGN §9), checked against hand-computed values, and the
//! polynomial terms of fit files.

use arachis::optimize::{
    overall_desirability, FitFile, Goal, GoalKind, Polynomial, ResponseSurface, Term,
};

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-12
}

#[test]
fn maximise_and_minimise_ramps() {
    let max = Goal::new(GoalKind::Maximise, 10.0, 20.0).unwrap();
    assert_eq!(max.desirability(9.0), 0.0);
    assert!(close(max.desirability(12.5), 0.25));
    assert_eq!(max.desirability(25.0), 1.0);
    let min = Goal::new(GoalKind::Minimise, 10.0, 20.0).unwrap();
    assert_eq!(min.desirability(9.0), 1.0);
    assert!(close(min.desirability(12.5), 0.75));
    assert_eq!(min.desirability(25.0), 0.0);
    // Weight 2 squares the ramp: ((12.5 − 10)/10)² = 0.0625.
    let max2 = max.with_weights(2.0, 1.0).unwrap();
    assert!(close(max2.desirability(12.5), 0.0625));
}

#[test]
fn target_ramps_on_both_sides() {
    // Target 31.06 with limits 28.133 … 32.153 (eq. (22)'s range over the box).
    let g = Goal::new(GoalKind::Target(31.06), 28.133, 32.153)
        .unwrap()
        .with_weights(1.0, 0.5)
        .unwrap();
    assert_eq!(g.desirability(31.06), 1.0);
    // Lower side: (30.00 − 28.133)/(31.06 − 28.133) = 1.867/2.927.
    assert!(close(g.desirability(30.00), 1.867 / 2.927));
    // Upper side with t = 0.5: √((32.153 − 31.6)/(32.153 − 31.06)) = √(0.553/1.093).
    assert!(close(g.desirability(31.6), (0.553f64 / 1.093).sqrt()));
    assert_eq!(g.desirability(28.0), 0.0);
    assert_eq!(g.desirability(32.2), 0.0);
    assert!(close(g.shortfall(28.0), 0.133 / 4.02));
    assert_eq!(g.shortfall(30.0), 0.0);
}

#[test]
fn in_range_is_all_or_nothing() {
    let g = Goal::new(GoalKind::InRange, 1.0, 2.0).unwrap();
    assert_eq!(g.desirability(1.0), 1.0);
    assert_eq!(g.desirability(1.5), 1.0);
    assert_eq!(g.desirability(2.0 + 1e-9), 0.0);
}

#[test]
fn overall_desirability_weighs_by_importance() {
    // d₁ = 0.5 (importance 1), d₂ = 0.8 (importance 3):
    // D = (0.5 × 0.8³)^(1/4) = 0.256^(1/4) = 0.711312…
    let g1 = Goal::new(GoalKind::Maximise, 0.0, 1.0).unwrap();
    let g2 = Goal::new(GoalKind::Maximise, 0.0, 1.0)
        .unwrap()
        .with_importance(3.0)
        .unwrap();
    let d = overall_desirability(&[g1, g2], &[0.5, 0.8]);
    assert!(close(d, 0.256f64.powf(0.25)), "{d}");
    assert!((d - 0.711_312).abs() < 1e-6);
    // Equal importances give the geometric mean; one zero makes D zero.
    assert!(close(
        overall_desirability(&[g1, g1], &[0.5, 0.8]),
        0.4f64.sqrt()
    ));
    assert_eq!(overall_desirability(&[g1, g2], &[0.0, 0.8]), 0.0);
}

#[test]
fn inconsistent_goals_are_rejected() {
    assert!(Goal::new(GoalKind::Maximise, 2.0, 1.0).is_err());
    assert!(Goal::new(GoalKind::Target(3.0), 1.0, 2.0).is_err());
    assert!(Goal::new(GoalKind::Maximise, 1.0, 2.0)
        .unwrap()
        .with_importance(0.0)
        .is_err());
    assert!(Goal::new(GoalKind::InRange, f64::NAN, 2.0).is_err());
}

#[test]
fn term_names_follow_the_fit_file_contract() {
    let names = ["A", "B", "C"].map(String::from).to_vec();
    assert_eq!(Term::parse("Intercept", &names), Some(Term::Intercept));
    assert_eq!(Term::parse("B", &names), Some(Term::Linear(1)));
    assert_eq!(Term::parse("A*C", &names), Some(Term::Interaction(0, 2)));
    assert_eq!(Term::parse("C*A", &names), Some(Term::Interaction(0, 2)));
    assert_eq!(Term::parse("B^2", &names), Some(Term::Quadratic(1)));
    assert_eq!(Term::parse("D", &names), None);
    assert_eq!(Term::parse("A*B*C", &names), None);
    assert_eq!(Term::parse("A^3", &names), None);
    let p = Polynomial::new(names, &[("A*B*C", 1.0)]);
    assert_eq!(p.unwrap_err(), "A*B*C");
}

#[test]
fn coded_only_fit_files_have_no_actual_levels() {
    let text = r#"{"response": "force_n",
        "factors": [{"name": "X7", "low": null, "high": null},
                    {"name": "X8", "low": null, "high": null}],
        "coefficients": [{"term": "Intercept", "estimate": 6.96, "se": 0.07},
                         {"term": "X7", "estimate": 0.2796, "se": 0.05},
                         {"term": "X8", "estimate": 0.3739, "se": 0.05},
                         {"term": "X7*X8", "estimate": 0.13, "se": 0.08},
                         {"term": "X7^2", "estimate": -0.0159, "se": 0.06},
                         {"term": "X8^2", "estimate": 0.1516, "se": 0.06}]}"#;
    let fit = FitFile::parse(std::path::Path::new("ccd.json"), text).unwrap();
    assert_eq!(fit.response, "force_n");
    assert_eq!(fit.factors[0].to_actual(0.5), None);
    // Seed 001's CCD equation at (1, 1): 6.96 + 0.2796 + 0.3739 + 0.13 − 0.0159 + 0.1516.
    assert!(close(fit.model.predict(&[1.0, 1.0]), 7.8792));
    let half = r#"{"response": "y", "factors": [{"name": "A", "low": 1, "high": null}],
        "coefficients": [{"term": "A", "estimate": 1}]}"#;
    let err = FitFile::parse(std::path::Path::new("half.json"), half).unwrap_err();
    assert_eq!(
        err.to_string(),
        "half.json: factors[0].low: low and high must both be numbers or both null"
    );
}
