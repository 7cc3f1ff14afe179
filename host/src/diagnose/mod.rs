//! The model-vs-measurement diagnosis loop (issue 5, DESIGN §10): compare the calibrated
//! model with measurements taken at several conditions, rank the optional physical effects
//! that could explain the misfit, fit the chosen one, and make synthetic data with a hidden
//! effect to test all of it.
//!
//! One module per concept: [`params`] (base parameters and the effect catalogue),
//! [`experiment`] (the cheap core simulations), [`study`] (the study file),
//! [`residuals`] (standardised residuals and lack of fit), [`sensitivity`] (finite-difference
//! sensitivities), [`score`] (the ranking score test), [`fit`] (recalibration with an effect),
//! [`synth`] (synthetic measurements), [`plot`] (SVG plots), [`separate`] (which measurement
//! would tell two effects apart).

pub mod experiment;
pub mod fit;
pub mod params;
pub mod plot;
pub mod residuals;
pub mod score;
pub mod sensitivity;
pub mod separate;
pub mod study;
pub mod synth;
