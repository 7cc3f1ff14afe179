//! The model-vs-measurement diagnosis loop (issue 5, DESIGN §10): compare the calibrated
//! model with measurements taken at several conditions, rank the optional physical effects
//! that could explain the misfit, fit the chosen one, and make synthetic data with a hidden
//! effect to test all of it.
//!
//! It takes any study and the same rigs a calibration runs: a study's measurements at
//! several conditions are the data, its rigs the model. One module per concept:
//! [`params`] (the base parameters and effects the rigs declare), [`model`] (the rigs of a
//! study's experiments), [`residuals`] (standardised residuals and lack of fit), [`sensitivity`] (finite-difference
//! sensitivities), [`scatter`] (which of them stand out of the placements' scatter), [`score`] (the ranking score test), [`fit`] (recalibration with an effect),
//! [`synth`] (synthetic measurements), [`plot`] (SVG plots), [`separate`] (which measurement
//! would tell two effects apart), [`prospect`] (rigs not yet measured, as candidates for it).

pub mod fit;
pub mod model;
pub mod params;
pub mod plot;
pub mod prospect;
pub mod residuals;
pub mod scatter;
pub mod score;
pub mod sensitivity;
pub mod separate;
pub mod synth;
