//! Checks of `[[measurements]]` blocks against the rig catalogue, and of the plan's
//! references to the study's measurements.

use std::collections::BTreeMap;

use super::Validator;
use crate::limits::Limits;
use crate::nearest_name::nearest_name;
use crate::plausible::ANGLE_DEG;
use crate::rigs::catalogue;
use crate::rigs::kind::{RigKind, WorldKind};
use crate::study::file_format::StudyFile;
use crate::study::key_path::KeyPath;
use crate::study::measurements::Measurement;

/// The unit of measured angles (repose, slide), whose values must lie in
/// [`ANGLE_DEG`].
const ANGLE_UNIT: &str = "deg";

impl Validator<'_, '_> {
    pub(super) fn measurements(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("measurements");
        let mut seen: BTreeMap<String, usize> = BTreeMap::new();
        for (i, m) in file.measurements.iter().enumerate() {
            let k = at.index(i);
            if let Some(rig) = self.rig(file, &k, &m.experiment) {
                self.quantity(&k, rig, &m.quantity, Some(&m.unit));
                self.condition(&k.key("condition"), rig, &m.condition);
            }
            self.replicates(&k, m);
            let identity = format!("{} {} {:?}", m.experiment, m.quantity, m.condition);
            if let Some(first) = seen.insert(identity, i) {
                self.fail(
                    &k,
                    format!(
                        "same experiment, quantity and condition as measurements[{}]: merge the replicates into one block",
                        first + 1
                    ),
                );
            }
        }
    }

    /// The catalogue's rig named `experiment`, when it exists and the study describes what
    /// it simulates; else the error at `k.experiment`.
    pub(super) fn rig(
        &mut self,
        file: &StudyFile,
        k: &KeyPath,
        experiment: &str,
    ) -> Option<&'static RigKind> {
        let Some(rig) = catalogue::find(experiment) else {
            let names = catalogue::names();
            let hint = nearest_name(experiment, &names)
                .map_or(String::new(), |n| format!("; did you mean '{n}'?"));
            self.fail(
                &k.key("experiment"),
                format!(
                    "unknown value '{experiment}': no rig of that name{hint} (accepted: {})",
                    names.join(", ")
                ),
            );
            return None;
        };
        let missing = match rig.world {
            WorldKind::Pods if !file.has_particles() => {
                Some("[materials], [pods] (or [spheres]) and [pairs]")
            }
            WorldKind::PullOff if file.rig.is_none() => Some("[rig]"),
            _ => None,
        };
        if let Some(sections) = missing {
            self.fail(
                &k.key("experiment"),
                format!("the {experiment} rig needs the study's {sections}"),
            );
            return None;
        }
        Some(rig)
    }

    pub(super) fn quantity(
        &mut self,
        k: &KeyPath,
        rig: &RigKind,
        quantity: &str,
        unit: Option<&str>,
    ) {
        let experiment = rig.name;
        let accepted = rig.quantities;
        match accepted.iter().find(|q| q.name == quantity) {
            Some(q) => {
                if let Some(unit) = unit {
                    if unit != q.unit {
                        self.fail(
                            &k.key("unit"),
                            format!("{experiment} {quantity} is in '{}', not '{unit}'", q.unit),
                        );
                    }
                }
            }
            None => {
                let names: Vec<&str> = accepted.iter().map(|q| q.name).collect();
                self.fail(
                    &k.key("quantity"),
                    format!(
                        "{experiment} does not measure '{quantity}' (accepted: {})",
                        names.join(", ")
                    ),
                );
            }
        }
    }

    pub(super) fn condition(
        &mut self,
        k: &KeyPath,
        rig: &RigKind,
        condition: &BTreeMap<String, f64>,
    ) {
        let experiment = rig.name;
        let accepted = rig.conditions;
        let names: Vec<&str> = accepted.iter().map(|c| c.key).collect();
        for (key, value) in condition {
            match accepted.iter().find(|c| c.key == key) {
                Some(c) => {
                    if let Err(reason) = c.check(*value) {
                        self.fail(&k.key(key), reason);
                    }
                }
                None => {
                    let hint = nearest_name(key, &names)
                        .map_or(String::new(), |n| format!("; did you mean '{n}'?"));
                    self.fail(
                        &k.key(key),
                        format!(
                            "unknown condition for {experiment}{hint} (accepted: {})",
                            names.join(", ")
                        ),
                    );
                }
            }
        }
    }

    pub(super) fn replicates(&mut self, k: &KeyPath, m: &Measurement) {
        match (&m.values, m.mean) {
            (Some(_), Some(_)) => {
                self.fail(&k.key("mean"), "give either the replicates 'values' or the summary 'mean'/'n', not both")
            }
            (None, None) => self.fail(
                k,
                "missing measurement values: give 'values = [...]' (replicates) or 'mean' and 'n' (printed summary)",
            ),
            (Some(values), None) => {
                if values.is_empty() {
                    self.fail(&k.key("values"), "no replicates");
                }
                for (j, v) in values.iter().enumerate() {
                    if !v.is_finite() {
                        self.fail(&k.key("values").index(j), format!("{v} is not a finite number"));
                    } else if m.unit == ANGLE_UNIT {
                        if let Err(reason) = ANGLE_DEG.check(*v) {
                            self.fail(&k.key("values").index(j), reason);
                        }
                    }
                }
                for key in ["sd", "n"] {
                    let given = if key == "sd" { m.sd.is_some() } else { m.n.is_some() };
                    if given {
                        self.fail(&k.key(key), format!("'{key}' goes with 'mean'; with 'values' it is computed"));
                    }
                }
            }
            (None, Some(mean)) => {
                if !mean.is_finite() {
                    self.fail(&k.key("mean"), format!("{mean} is not a finite number"));
                } else if m.unit == ANGLE_UNIT {
                    if let Err(reason) = ANGLE_DEG.check(mean) {
                        self.fail(&k.key("mean"), reason);
                    }
                }
                match m.n {
                    None => self.fail(&k.key("mean"), "a printed mean needs 'n', the number of replicates behind it"),
                    Some(0) => self.fail(&k.key("n"), "n must be ≥ 1"),
                    Some(1) if m.sd.is_some() => self.fail(&k.key("sd"), "an SD needs n ≥ 2"),
                    Some(_) => {}
                }
                if let Some(sd) = m.sd {
                    self.limit(&k.key("sd"), sd, Limits::NonNegative);
                }
            }
        }
    }

    /// Checks that exactly one of the study's `measurements` matches a plan reference.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn referenced(
        &mut self,
        file: &StudyFile,
        measurements: &[Measurement],
        k: &KeyPath,
        experiment: &str,
        quantity: &str,
        condition: &BTreeMap<String, f64>,
        role: &str,
    ) {
        let Some(rig) = self.rig(file, k, experiment) else {
            return;
        };
        self.quantity(k, rig, quantity, None);
        self.condition(&k.key("condition"), rig, condition);
        let matching: Vec<usize> = measurements
            .iter()
            .enumerate()
            .filter(|(_, m)| m.matches(experiment, quantity, condition))
            .map(|(i, _)| i + 1)
            .collect();
        match matching.len() {
            0 => self.fail(
                &k.key("experiment"),
                format!(
                    "missing measurement: the plan's {role} is {experiment} {quantity}{}, but no [[measurements]] block measures it",
                    describe(condition)
                ),
            ),
            1 => {
                let m = &measurements[matching[0] - 1];
                if m.mean().is_some_and(|x| x == 0.0) {
                    self.fail(k, format!("the {role} measurement's mean is 0, so a relative error is undefined"));
                }
            }
            _ => {
                let list: Vec<String> = matching.iter().map(|i| format!("measurements[{i}]")).collect();
                self.fail(
                    &k.key("condition"),
                    format!("ambiguous: {} match the {role} ({}); narrow it with a condition", list.len(), list.join(", ")),
                );
            }
        }
    }
}

fn describe(condition: &BTreeMap<String, f64>) -> String {
    if condition.is_empty() {
        return String::new();
    }
    let parts: Vec<String> = condition
        .iter()
        .map(|(k, v)| format!("{k} = {v}"))
        .collect();
    format!(" at {}", parts.join(", "))
}
