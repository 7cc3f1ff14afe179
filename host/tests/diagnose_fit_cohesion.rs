//! Issue 5 must-show, second case (see `diagnose_fit.rs` for the criteria and the expected
//! sampling variation): hidden SJKR cohesion (3.2e3 J/m³, 3.2σ at the lightest load) in the
//! press experiment, 50 seeds. A separate file so each test binary stays near a minute in debug.

use crate::diagnose_support;
use diagnose_support::*;

#[test]
fn fit_recovers_cohesion() {
    fit_case("press", "cohesion", 3.2e3, SEEDS);
}
