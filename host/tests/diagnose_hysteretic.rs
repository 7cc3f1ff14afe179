//! Hysteretic normal contact as a diagnosis candidate: with the tutorial study plus an
//! `unload` experiment (the press conditions, same noise), a hidden plastic fraction (≥ 3σ at
//! the most sensitive condition) is ranked first in ≥ 90 % of 50 seeds, and with nothing
//! hidden a missing effect is claimed in ≤ 10 % of seeds. The tutorial study itself has no
//! unload experiment; there hysteresis only shows as a restitution change, which the
//! calibrated e absorbs.
//! `cargo test -p arachis --test scenarios diagnose_hysteretic:: -- --nocapture` prints the rates.

use crate::diagnose_support;
use arachis::study::diagnosis::DiagnosisSection;
use diagnose_support::*;

/// Hidden plastic fraction λ.
const LAMBDA: f64 = 0.04;

/// The tutorial template plus an unload experiment at the press conditions.
fn with_unload() -> DiagnosisSection {
    let mut study = template();
    let press = study
        .experiment
        .iter()
        .find(|e| e.kind == "press")
        .unwrap()
        .clone();
    let mut unload = press;
    unload.kind = "unload".to_owned();
    study.experiment.push(unload);
    study
}

#[test]
fn hidden_hysteresis_is_ranked_first_with_an_unload_experiment() {
    let c = case_for(with_unload(), Some(("hysteretic", LAMBDA)));
    assert!(
        c.effect_size_sigma >= 3.0,
        "only {:.2} sigma",
        c.effect_size_sigma
    );
    let mut first = 0;
    for seed in 0..SEEDS {
        if c.ranking(seed).top().map(|t| t.effect.name) == Some("hysteretic") {
            first += 1;
        }
    }
    println!(
        "hidden hysteretic={LAMBDA} ({:.1} sigma max): ranked first {first}/{SEEDS}",
        c.effect_size_sigma
    );
    assert!(first as f64 >= 0.9 * SEEDS as f64);
}

#[test]
fn no_hidden_effect_rarely_claims_one_with_an_unload_experiment() {
    let c = case_for(with_unload(), None);
    let claims = (0..SEEDS).filter(|&s| c.ranking(s).any_claimed()).count();
    println!("unload study, no hidden effect: a missing effect claimed in {claims}/{SEEDS} seeds");
    assert!(claims as f64 <= 0.1 * SEEDS as f64);
}
