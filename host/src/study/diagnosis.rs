//! `[diagnosis]`: a study of the single-sphere rigs (rebound, press, fall, unload, roll) written
//! for the diagnosis loop — the current calibration of their parameters and, per
//! experiment, measurements at several conditions with replicates (or, in a template for
//! `arachis synth`, how many replicates to make).
//!
//! ```toml
//! [diagnosis]
//! name = "pods, lab 2026-11"
//! [diagnosis.calibration]          # base parameters; effects default to 0 (off)
//! restitution = 0.5
//! youngs_modulus_pa = 8.43e6
//! [diagnosis.prior]                # optional: base parameters measured on the bench
//! restitution = { mean = 0.48, sd = 0.02 }
//! [[diagnosis.experiment]]
//! kind = "rebound"                 # a single-sphere rig: rebound | press | fall | unload | roll
//! noise_sd = 0.01                  # optional: used only by `arachis synth`
//! [[diagnosis.experiment.point]]
//! condition = 0.05                 # the rig's one condition (drop height, m)
//! values = [0.551, 0.562, 0.548]   # replicates; or `replicates = 5` in a template
//! ```

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::error::StudyError;
use super::key_path::KeyPath;
use super::source::Source;
use crate::rigs::catalogue;
use crate::rigs::kind::WorldKind;
use crate::rigs::parameter::{RigParameter, Role};
use crate::rigs::single_sphere::{ModelParams, PARAMETERS};

/// `[diagnosis]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiagnosisSection {
    /// Free-text name.
    #[serde(default)]
    pub name: String,
    /// The current calibration (base parameters and any effects already on).
    pub calibration: ModelParams,
    /// The experiments.
    #[serde(default)]
    pub experiment: Vec<DiagnosisExperiment>,
    /// Base parameters measured on the bench (`arachis lab`), by parameter name: a fit weighs
    /// the distance from each in SDs and reports it.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub prior: BTreeMap<String, Prior>,
}

/// A bench measurement of a base parameter: mean ± SD, in the parameter's unit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Prior {
    /// The measured mean.
    pub mean: f64,
    /// Its standard deviation (of the value, not of a replicate), > 0.
    pub sd: f64,
}

/// One experiment: a single-sphere rig and its measured points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiagnosisExperiment {
    /// The rig.
    pub kind: String,
    /// Measurement noise SD in the observable's unit; only `arachis synth` uses it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise_sd: Option<f64>,
    /// Measurements at each condition.
    pub point: Vec<Point>,
}

/// Replicate measurements at one condition.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// The rig's condition (its unit).
    pub condition: f64,
    /// Replicate measurements (the rig's quantity's unit).
    #[serde(default)]
    pub values: Vec<f64>,
    /// Number of replicates to synthesise (templates only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replicates: Option<usize>,
}

/// The file of a diagnosis study, as `arachis synth` writes it.
#[derive(Serialize)]
struct DiagnosisFile<'a> {
    diagnosis: &'a DiagnosisSection,
}

/// Largest replicate count a template may ask for.
pub const MAX_REPLICATES: usize = 1000;

impl DiagnosisSection {
    /// The section as a whole study file (TOML).
    pub fn to_toml(&self) -> Result<String, toml::ser::Error> {
        toml::to_string(&DiagnosisFile { diagnosis: self })
    }
}

/// A replicate this many times larger than the median magnitude of its experiment's
/// replicates is refused as a typo (one value of 1e300 among rebound ratios near 0.5 made the
/// diagnosis report "no missing effect"). Six decades leave room for any real spread of one
/// measured quantity over its conditions.
pub const OUTLIER_RATIO: f64 = 1e6;

/// The median of |v| over the finite values (0 when there are none).
fn median_magnitude<'a>(values: impl Iterator<Item = &'a f64>) -> f64 {
    let mut m: Vec<f64> = values.filter(|v| v.is_finite()).map(|v| v.abs()).collect();
    if m.is_empty() {
        return 0.0;
    }
    m.sort_by(f64::total_cmp);
    m[m.len() / 2]
}

/// [`check_prior_among`] the single-sphere rigs' parameters.
fn check_prior(name: &str, prior: &Prior) -> Result<(), String> {
    check_prior_among(name, prior, &PARAMETERS.iter().collect::<Vec<_>>())
}

/// `Ok` when `prior` is a bench value of a base parameter named `name` among `parameters`: a
/// known name, a mean inside the parameter's limits and a finite SD > 0.
pub(crate) fn check_prior_among(
    name: &str,
    prior: &Prior,
    parameters: &[&RigParameter],
) -> Result<(), String> {
    let base: Vec<&str> = parameters
        .iter()
        .filter(|p| p.role == Role::Base)
        .map(|p| p.name)
        .collect();
    let Some(info) = parameters
        .iter()
        .find(|p| p.name == name && p.role == Role::Base)
    else {
        return Err(format!(
            "unknown base parameter '{name}' (priors are for: {})",
            base.join(", ")
        ));
    };
    info.limits
        .check(prior.mean)
        .map_err(|reason| format!("mean {reason}"))?;
    if !(prior.sd.is_finite() && prior.sd > 0.0) {
        return Err(format!("sd = {} must be a finite number > 0", prior.sd));
    }
    Ok(())
}

/// Every error of a decoded `[diagnosis]`: the calibration's ranges, each experiment's rig
/// (a single-sphere one), its noise SD, and each point's condition (inside the rig's range,
/// no condition twice), values (finite) and replicate count.
pub(crate) fn validate(src: &Source<'_>, d: &DiagnosisSection) -> Vec<StudyError> {
    let mut errors = Vec::new();
    let at = KeyPath::root().key("diagnosis");
    let mut err = |key: KeyPath, reason: String| errors.push(src.error(&key, reason));
    if !d.name.is_empty() {
        if let Err(reason) = crate::io::file_name::check_name_component(&d.name) {
            err(at.key("name"), reason);
        }
    }
    if let Err(reason) = d.calibration.validate() {
        err(at.key("calibration"), reason);
    }
    for (name, prior) in &d.prior {
        let here = at.key("prior").key(name);
        if let Err(reason) = check_prior(name, prior) {
            err(here, reason);
        }
    }
    if d.experiment.is_empty() {
        err(
            at.clone(),
            "the study has no [[diagnosis.experiment]]".into(),
        );
    }
    let rigs: Vec<&str> = catalogue::RIGS
        .iter()
        .filter(|k| k.world == WorldKind::Fixed)
        .map(|k| k.name)
        .collect();
    for (ei, e) in d.experiment.iter().enumerate() {
        let here = at.key("experiment").index(ei);
        let Some(kind) = catalogue::find(&e.kind).filter(|k| rigs.contains(&k.name)) else {
            err(
                here.key("kind"),
                format!("unknown value '{}' (accepted: {})", e.kind, rigs.join(", ")),
            );
            continue;
        };
        let what = format!("experiment {} ({})", ei + 1, e.kind);
        if e.point.is_empty() {
            err(here.clone(), format!("{what} has no points"));
        }
        if let Some(s) = e.noise_sd {
            if !(s.is_finite() && s >= 0.0) {
                err(
                    here.key("noise_sd"),
                    format!("{what}: noise_sd {s} must be >= 0"),
                );
            }
        }
        let condition = kind.conditions[0];
        let typical = median_magnitude(e.point.iter().flat_map(|p| &p.values));
        for (pi, p) in e.point.iter().enumerate() {
            let at_point = here.key("point").index(pi);
            if let Err(reason) = condition.check(p.condition) {
                err(
                    at_point.key("condition"),
                    format!("{what} point {}: condition {reason}", pi + 1),
                );
            }
            if e.point[..pi].iter().any(|q| q.condition == p.condition) {
                err(
                    at_point.key("condition"),
                    format!(
                        "{what}: condition {} appears twice; put all replicates in one point",
                        p.condition
                    ),
                );
            }
            if let Some(v) = p.values.iter().find(|v| !v.is_finite()) {
                err(
                    at_point.key("values"),
                    format!("{what} point {}: value {v} is not a finite number", pi + 1),
                );
            }
            let outlier = |v: &&f64| typical > 0.0 && v.abs() > OUTLIER_RATIO * typical;
            if let Some(v) = p.values.iter().find(outlier) {
                err(
                    at_point.key("values"),
                    format!(
                        "{what} point {}: value {v:e} is more than {OUTLIER_RATIO:e} times the \
                         typical size of this experiment's values ({typical}): a typo?",
                        pi + 1
                    ),
                );
            }
            if let Some(r) = p.replicates {
                if !(1..=MAX_REPLICATES).contains(&r) {
                    err(
                        at_point.key("replicates"),
                        format!(
                            "{what} point {}: replicates {r} must be in 1..={MAX_REPLICATES}",
                            pi + 1
                        ),
                    );
                }
            }
        }
    }
    errors
}

impl super::Study {
    /// The study as TOML with `values[s][p]` as the replicates of point `p` of series `s`
    /// (the order of [`super::Study::series`]), for `arachis synth`: a `[diagnosis]` study
    /// is written as its section alone (so a template becomes a measured study, byte for
    /// byte what earlier versions wrote); a study with `[[measurements]]` gets their
    /// `values`, replacing a printed mean. `noise_sd[s]`, when given, is the SD the replicates
    /// of diagnosis experiment `s` were drawn with and replaces its `noise_sd`. Comments are
    /// not kept.
    pub fn toml_with_replicates(
        &self,
        values: &[Vec<Vec<f64>>],
        noise_sd: Option<&[f64]>,
    ) -> Result<String, String> {
        let mut out = self.file().clone();
        if out.measurement.is_some() {
            return Err(
                "a pull-off study's [measurement] holds one printed force, not replicates".into(),
            );
        }
        let mut series = values.iter();
        if let Some(d) = &mut out.diagnosis {
            for (ei, e) in d.experiment.iter_mut().enumerate() {
                let v = series
                    .next()
                    .ok_or("fewer replicate sets than experiments")?;
                if let Some(sd) = noise_sd.and_then(|sds| sds.get(ei)) {
                    e.noise_sd = Some(*sd);
                }
                for (p, v) in e.point.iter_mut().zip(v) {
                    p.values = v.clone();
                    p.replicates = None;
                }
            }
        }
        let rest: Vec<&Vec<Vec<f64>>> = series.collect();
        // [[measurements]] blocks are grouped into series by experiment and quantity in
        // order of first appearance (as `study_series` groups them).
        let mut groups: Vec<(String, String, usize)> = Vec::new();
        for m in &mut out.measurements {
            let g = match groups
                .iter()
                .position(|(e, q, _)| *e == m.experiment && *q == m.quantity)
            {
                Some(g) => g,
                None => {
                    groups.push((m.experiment.clone(), m.quantity.clone(), 0));
                    groups.len() - 1
                }
            };
            let point = groups[g].2;
            groups[g].2 += 1;
            let v = rest
                .get(g)
                .and_then(|s| s.get(point))
                .ok_or("fewer replicate sets than measurements")?;
            m.values = Some(v.clone());
            m.mean = None;
            m.sd = None;
            m.n = None;
        }
        match (
            &out.diagnosis,
            out.study.is_none() && out.measurements.is_empty(),
        ) {
            (Some(d), true) => d.to_toml().map_err(|e| e.to_string()),
            _ => toml::to_string_pretty(&out).map_err(|e| e.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_prior_names_a_base_parameter_with_an_admissible_mean_and_a_positive_sd() {
        let ok = Prior {
            mean: 0.5,
            sd: 0.01,
        };
        assert!(check_prior("restitution", &ok).is_ok());
        let e = check_prior("viscoelastic", &ok).unwrap_err();
        assert!(e.contains("unknown base parameter 'viscoelastic'") && e.contains("restitution"));
        let e = check_prior("restitution", &Prior { mean: 1.2, ..ok }).unwrap_err();
        assert!(e.starts_with("mean ") && e.contains("(0, 1]"), "{e}");
        for sd in [0.0, -1.0, f64::NAN] {
            let e = check_prior("restitution", &Prior { sd, ..ok }).unwrap_err();
            assert!(e.contains("must be a finite number > 0"), "{e}");
        }
    }
}
