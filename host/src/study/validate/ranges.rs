//! Checks of `[parameters."<name>"]` ranges: registry names, owners, limits, order.

use std::collections::BTreeMap;

use super::Validator;
use crate::limits::Limits;
use crate::nearest_name::nearest_name;
use crate::rigs::catalogue;
use crate::rigs::parameter::RigParameter;
use crate::rigs::pod_world::parameters::{self, lookup, Owner};
use crate::study::file_format::StudyFile;
use crate::study::key_path::KeyPath;
use crate::study::measurements::study_measurements;

/// The parameters of the rigs `file` measures (without a pod world, `[parameters]` ranges
/// name these).
pub fn measured_rig_parameters(file: &StudyFile) -> Vec<&'static RigParameter> {
    let mut out: Vec<&'static RigParameter> = Vec::new();
    for m in study_measurements(file) {
        for p in catalogue::find(&m.experiment)
            .map(|k| k.parameters)
            .unwrap_or_default()
        {
            if out.iter().all(|q| q.key != p.key) {
                out.push(p);
            }
        }
    }
    out
}

impl Validator<'_, '_> {
    pub(super) fn parameters(&mut self, file: &StudyFile) {
        if !file.has_particles() {
            self.rig_parameters(file);
            return;
        }
        let at = KeyPath::root().key("parameters");
        let known = parameters::names();
        let mut labels: BTreeMap<String, String> = BTreeMap::new();
        for (name, range) in &file.parameters {
            let k = at.key(name);
            let Some(spec) = lookup(name) else {
                let hint = nearest_name(name, &known)
                    .map_or(String::new(), |n| format!("did you mean '{n}'? "));
                self.fail(
                    &k,
                    format!(
                        "unknown parameter '{name}'; {hint}(known: {})",
                        known.join(", ")
                    ),
                );
                continue;
            };
            let owner_present = match spec.sets.owner {
                Owner::Material(m) => file.materials.contains_key(m),
                Owner::Pair(p) => file.pairs.contains_key(p),
            };
            if !owner_present {
                let table = match spec.sets.owner {
                    Owner::Material(m) => format!("[materials.{m}]"),
                    Owner::Pair(p) => format!("[pairs.\"{p}\"]"),
                };
                self.fail(
                    &k,
                    format!(
                        "varies {} of {table}, which this study does not have",
                        spec.sets.property
                    ),
                );
            }
            let limits = range.limits(spec);
            let plausible = crate::plausible::for_property(spec.sets.property);
            for (key, value) in [("low", range.low), ("high", range.high)] {
                if let (Ok(()), Some(p)) = (limits.check(value), plausible) {
                    // Admitted by the model: is it believable (issue 23)?
                    if let Err(reason) = p.check(value) {
                        self.fail(&k.key(key), reason);
                    }
                }
                if let Err(mut reason) = limits.check(value) {
                    if limits == Limits::Poisson && (0.5..1.0).contains(&value) {
                        reason.push_str(
                            "; to screen beyond the isotropic limit knowingly (seed 000 Table 3 \
                             goes to 0.586), set poisson_above_half = true in this range",
                        );
                    }
                    self.fail(&k.key(key), reason);
                }
            }
            if range.poisson_above_half && spec.limits != Limits::Poisson {
                self.fail(
                    &k.key("poisson_above_half"),
                    "applies only to Poisson ratios",
                );
            }
            if range.low.is_finite() && range.high.is_finite() {
                if range.low > range.high {
                    self.fail(
                        &k.key("low"),
                        format!(
                            "low {} > high {}: the range is reversed",
                            range.low, range.high
                        ),
                    );
                } else if range.low == range.high {
                    self.fail(
                        &k.key("low"),
                        format!(
                            "low = high = {}: a parameter that does not vary cannot be screened; \
                             remove the range and give the value in its material or pair",
                            range.low
                        ),
                    );
                }
            }
            let label = range.label.clone().unwrap_or_else(|| spec.label.to_owned());
            if let Some(other) = labels.insert(label.clone(), name.clone()) {
                self.fail(
                    &k.key("label"),
                    format!("label '{label}' is also used by '{other}'"),
                );
            }
        }
    }

    /// `[parameters]` of a study without a pod world: each a parameter of a measured rig,
    /// its range ordered and within the parameter's limits.
    fn rig_parameters(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("parameters");
        let known = measured_rig_parameters(file);
        let names: Vec<&str> = known.iter().map(|p| p.key).collect();
        for (name, range) in &file.parameters {
            let k = at.key(name);
            let Some(p) = known.iter().find(|p| p.key == name) else {
                let hint = nearest_name(name, &names)
                    .map_or(String::new(), |n| format!("did you mean '{n}'? "));
                self.fail(
                    &k,
                    format!(
                        "unknown parameter '{name}': no measured rig has it; {hint}(known: {})",
                        names.join(", ")
                    ),
                );
                continue;
            };
            for (key, value) in [("low", range.low), ("high", range.high)] {
                self.limit(&k.key(key), value, p.limits);
            }
            if range.low.is_finite() && range.high.is_finite() && range.low >= range.high {
                self.fail(
                    &k.key("low"),
                    format!("low {} must be below high {}", range.low, range.high),
                );
            }
        }
    }
}
