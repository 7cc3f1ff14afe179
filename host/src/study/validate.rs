//! Semantic checks of a decoded study: everything serde cannot see, all of it before any
//! simulation starts, every failure collected.
//!
//! - names: materials referenced by pods and pairs exist; parameter names are in the
//!   registry (else the nearest name is suggested) and their material or pair exists;
//! - ranges: low < high, both within the physical limits of [`Limits`];
//! - values: every material and pair value within its limits; every pair property has a
//!   value or a range; shape-mix fractions sum to 1;
//! - measurements: quantity and unit known for the experiment, condition keys known,
//!   replicates or a summary (never both), no duplicate blocks;
//! - plan: mode exists, the screening design has room for the factors and an error
//!   estimate, the target and validation measurements exist and are unambiguous;
//! - files: every STL resolves (relative to the study file), is readable and looks like STL.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use super::error::StudyError;
use super::file_format::{StudyFile, PAIR_PROPERTIES};
use super::key_path::KeyPath;
use super::limits::Limits;
use super::measurements::{conditions_of, quantities_of, Experiment, Measurement};
use super::nearest_name::nearest_name;
use super::parameters::{self, lookup, Owner};
use super::source::Source;
use super::stl_check::check_stl;

/// The shape-mix fractions must sum to 1 within this (they are proportions of a count,
/// typed with a few decimals; a larger gap is a mistake, not rounding).
pub const SHAPE_MIX_TOLERANCE: f64 = 1e-6;

/// Smallest broad-phase cell, in sphere radii: a cell must hold a whole sphere diameter so
/// neighbour cells find every contact.
pub const MIN_GRID_CELL_RADII: f64 = 2.0;

/// Fewest replicated centre points that give a pure-error estimate (DESIGN §9).
pub const MIN_BOX_BEHNKEN_CENTRE_POINTS: u32 = 2;

/// Collects every semantic error of `file`; `dir` is the study file's directory.
pub(crate) fn validate(src: &Source<'_>, file: &StudyFile, dir: &Path) -> Vec<StudyError> {
    let mut v = Validator {
        src,
        errors: Vec::new(),
    };
    v.header(file);
    v.materials(file);
    v.pods(file, dir);
    v.pairs(file);
    v.measurements(file);
    v.parameters(file);
    v.plan(file);
    v.errors
}

struct Validator<'s, 'i> {
    src: &'s Source<'i>,
    errors: Vec<StudyError>,
}

impl Validator<'_, '_> {
    fn fail(&mut self, key: &KeyPath, reason: impl Into<String>) {
        self.errors.push(self.src.error(key, reason));
    }

    fn limit(&mut self, key: &KeyPath, value: f64, limits: Limits) {
        if let Err(reason) = limits.check(value) {
            self.fail(key, reason);
        }
    }

    fn header(&mut self, file: &StudyFile) {
        if file.study.name.trim().is_empty() {
            self.fail(
                &KeyPath::root().key("study").key("name"),
                "the study needs a name",
            );
        }
    }

    fn materials(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("materials");
        if file.materials.is_empty() {
            self.fail(&at, "no materials: add at least [materials.pod]");
        }
        for (name, m) in &file.materials {
            let k = at.key(name);
            if !is_material_name(name) {
                self.fail(&k, "a material name may hold only lower-case letters, digits and '_' ('-' joins pair names)");
            }
            self.limit(&k.key("density_kg_m3"), m.density_kg_m3, Limits::Positive);
            self.limit(&k.key("poisson"), m.poisson, Limits::Poisson);
            self.limit(
                &k.key("shear_modulus_pa"),
                m.shear_modulus_pa,
                Limits::Positive,
            );
        }
    }

    fn pods(&mut self, file: &StudyFile, dir: &Path) {
        let at = KeyPath::root().key("pods");
        let p = &file.pods;
        if !file.materials.contains_key(&p.material) {
            self.fail(
                &at.key("material"),
                format!("no [materials.{}] in this study", p.material),
            );
        }
        self.limit(&at.key("length_mm"), p.length_mm, Limits::Positive);
        self.limit(&at.key("width_mm"), p.width_mm, Limits::Positive);
        self.limit(&at.key("thickness_mm"), p.thickness_mm, Limits::Positive);
        let mix = at.key("shape_mix");
        let mut sum = 0.0;
        for (shape, fraction) in p.shape_mix.entries() {
            self.limit(&mix.key(shape), fraction, Limits::Fraction);
            sum += fraction;
        }
        if sum.is_finite() && (sum - 1.0).abs() > SHAPE_MIX_TOLERANCE {
            self.fail(
                &mix,
                format!(
                    "the fractions normal + cocoon + single_grain sum to {}, not 1",
                    round_for_message(sum)
                ),
            );
        }
        for (shape, written) in p.stl.entries() {
            let resolved = dir.join(written);
            if let Err(reason) = check_stl(&resolved) {
                self.fail(
                    &at.key("stl").key(shape),
                    format!("unreadable STL '{written}': {reason}"),
                );
            }
        }
    }

    fn pairs(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("pairs");
        let mut seen = BTreeSet::new();
        for (name, pair) in &file.pairs {
            let k = at.key(name);
            match name.split_once('-') {
                Some((a, b)) if is_material_name(a) && is_material_name(b) => {
                    for m in [a, b] {
                        if !file.materials.contains_key(m) {
                            self.fail(
                                &k,
                                format!("pair names material '{m}', which has no [materials.{m}]"),
                            );
                        }
                    }
                    let unordered = if a <= b { (a, b) } else { (b, a) };
                    if !seen.insert(unordered) {
                        self.fail(
                            &k,
                            format!("the pair {b}-{a} is given twice (as {a}-{b} and {b}-{a})"),
                        );
                    }
                }
                _ => self.fail(
                    &k,
                    "a pair is named '<material>-<material>', e.g. \"pod-steel\"",
                ),
            }
            for property in PAIR_PROPERTIES {
                let pk = k.key(property);
                let registered = parameters::for_property(name, property);
                let varied = registered.is_some_and(|p| file.parameters.contains_key(p.name));
                match (pair.property(property), registered) {
                    (Some(value), Some(spec)) => self.limit(&pk, value, spec.limits),
                    (Some(value), None) => self.limit(&pk, value, pair_limits(property)),
                    (None, _) if varied => {}
                    (None, Some(spec)) => self.fail(
                        &k,
                        format!(
                            "no {property}: give a value, or vary it under [parameters.\"{}\"]",
                            spec.name
                        ),
                    ),
                    (None, None) => self.fail(&k, format!("no {property}: give a value")),
                }
            }
        }
    }

    fn measurements(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("measurements");
        let mut seen: BTreeMap<String, usize> = BTreeMap::new();
        for (i, m) in file.measurements.iter().enumerate() {
            let k = at.index(i);
            self.quantity(&k, m.experiment, &m.quantity, Some(&m.unit));
            self.condition(&k.key("condition"), m.experiment, &m.condition);
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

    fn quantity(
        &mut self,
        k: &KeyPath,
        experiment: Experiment,
        quantity: &str,
        unit: Option<&str>,
    ) {
        let accepted = quantities_of(experiment);
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

    fn condition(
        &mut self,
        k: &KeyPath,
        experiment: Experiment,
        condition: &BTreeMap<String, f64>,
    ) {
        let accepted = conditions_of(experiment);
        let names: Vec<&str> = accepted.iter().map(|c| c.key).collect();
        for (key, value) in condition {
            match accepted.iter().find(|c| c.key == key) {
                Some(c) => self.limit(&k.key(key), *value, c.limits),
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

    fn replicates(&mut self, k: &KeyPath, m: &Measurement) {
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

    fn parameters(&mut self, file: &StudyFile) {
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
            let owner_present = match spec.owner {
                Owner::Material(m) => file.materials.contains_key(m),
                Owner::Pair(p) => file.pairs.contains_key(p),
            };
            if !owner_present {
                let table = match spec.owner {
                    Owner::Material(m) => format!("[materials.{m}]"),
                    Owner::Pair(p) => format!("[pairs.\"{p}\"]"),
                };
                self.fail(
                    &k,
                    format!(
                        "varies {} of {table}, which this study does not have",
                        spec.property
                    ),
                );
            }
            let limits = range.limits(spec);
            for (key, value) in [("low", range.low), ("high", range.high)] {
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

    fn plan(&mut self, file: &StudyFile) {
        let at = KeyPath::root().key("plan");
        let plan = &file.plan;
        if !plan.modes.contains_key(&plan.mode) {
            let names: Vec<&str> = plan.modes.keys().map(String::as_str).collect();
            self.fail(
                &at.key("mode"),
                format!(
                    "no [plan.modes.{}] (modes: {})",
                    plan.mode,
                    names.join(", ")
                ),
            );
        }
        for (name, mode) in &plan.modes {
            let k = at.key("modes").key(name);
            if mode.pods == 0 {
                self.fail(&k.key("pods"), "pods must be ≥ 1");
            }
            if mode.spheres_per_pod == 0 {
                self.fail(&k.key("spheres_per_pod"), "spheres_per_pod must be ≥ 1");
            }
        }

        let s = at.key("screening");
        let k = file.parameters.len() as u32;
        let columns = plan.screening.design.columns();
        if k == 0 {
            self.fail(
                &KeyPath::root().key("parameters"),
                "no parameters vary: nothing to calibrate",
            );
        } else if k > columns {
            self.fail(
                &s.key("design"),
                format!("{k} varied parameters do not fit the {columns} columns of this design"),
            );
        } else {
            let dummies = columns - k;
            if let Some(d) = plan.screening.dummies {
                if d != dummies {
                    self.fail(
                        &s.key("dummies"),
                        format!(
                            "{k} parameters in {columns} columns leave {dummies} dummies, not {d}"
                        ),
                    );
                }
            }
            if dummies + plan.screening.centre_points == 0 {
                self.fail(&s.key("design"), "no degrees of freedom left for error: use a larger design, fewer parameters or centre points");
            }
        }
        self.limit(
            &s.key("significance"),
            plan.screening.significance,
            Limits::Probability,
        );

        let sa = at.key("steepest_ascent");
        if plan.steepest_ascent.points < 2 {
            self.fail(&sa.key("points"), "a path needs at least 2 points");
        }
        self.limit(
            &sa.key("step_coded"),
            plan.steepest_ascent.step_coded,
            Limits::Positive,
        );
        let origin = plan.steepest_ascent.origin_coded;
        if !(-1.0..=1.0).contains(&origin) {
            self.fail(
                &sa.key("origin_coded"),
                format!("{origin} is outside the screened region [−1, 1]"),
            );
        }
        if plan.box_behnken.centre_points < MIN_BOX_BEHNKEN_CENTRE_POINTS {
            self.fail(
                &at.key("box_behnken").key("centre_points"),
                format!("at least {MIN_BOX_BEHNKEN_CENTRE_POINTS} centre points are needed for a pure-error estimate"),
            );
        }

        let t = &plan.target;
        self.referenced(
            file,
            &at.key("target"),
            t.experiment,
            &t.quantity,
            &t.condition,
            "target",
        );
        let v = &plan.validation;
        self.referenced(
            file,
            &at.key("validation"),
            v.experiment,
            &v.quantity,
            &v.condition,
            "validation",
        );
        self.limit(
            &at.key("validation").key("max_relative_error_pct"),
            v.max_relative_error_pct,
            Limits::Positive,
        );

        let sim = at.key("simulation");
        let p = &plan.simulation;
        let dt = p.dt_rayleigh_fraction;
        if !(dt > 0.0 && dt <= 1.0) {
            self.fail(
                &sim.key("dt_rayleigh_fraction"),
                format!("{dt} is outside (0, 1]"),
            );
        }
        if p.grid_cell_radii.is_nan() || p.grid_cell_radii < MIN_GRID_CELL_RADII {
            self.fail(
                &sim.key("grid_cell_radii"),
                format!(
                    "{} is below {MIN_GRID_CELL_RADII}: a cell must hold a sphere diameter",
                    p.grid_cell_radii
                ),
            );
        }
        self.limit(&sim.key("gravity_m_s2"), p.gravity_m_s2, Limits::Positive);
        let r = sim.key("repose");
        let rs = &p.repose;
        for (key, value) in [
            ("cylinder_diameter_mm", rs.cylinder_diameter_mm),
            ("cylinder_height_mm", rs.cylinder_height_mm),
            ("fill_time_s", rs.fill_time_s),
            ("fill_speed_m_s", rs.fill_speed_m_s),
            ("lift_speed_m_s", rs.lift_speed_m_s),
        ] {
            self.limit(&r.key(key), value, Limits::Positive);
        }
        self.limit(
            &r.key("settle_after_lift_s"),
            rs.settle_after_lift_s,
            Limits::NonNegative,
        );
        if rs.lift_start_s < rs.fill_time_s {
            self.fail(
                &r.key("lift_start_s"),
                format!(
                    "the cylinder rises at {} s, before filling ends at {} s",
                    rs.lift_start_s, rs.fill_time_s
                ),
            );
        }
    }

    /// Checks that exactly one measurement matches a plan reference.
    fn referenced(
        &mut self,
        file: &StudyFile,
        k: &KeyPath,
        experiment: Experiment,
        quantity: &str,
        condition: &BTreeMap<String, f64>,
        role: &str,
    ) {
        self.quantity(k, experiment, quantity, None);
        self.condition(&k.key("condition"), experiment, condition);
        let matching: Vec<usize> = file
            .measurements
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
                let m = &file.measurements[matching[0] - 1];
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

/// Material names: lower-case letters, digits and '_' (so '-' can join pair names).
fn is_material_name(name: &str) -> bool {
    !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

/// Limits of a pair property that has no registry entry.
fn pair_limits(property: &str) -> Limits {
    if property == "restitution" {
        Limits::Restitution
    } else {
        Limits::Friction
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

/// `x` without the binary-rounding tail (0.7 + 0.2 + 0.2 prints 1.1, not 1.0999999999999999).
fn round_for_message(x: f64) -> f64 {
    const DIGITS: f64 = 1e9;
    (x * DIGITS).round() / DIGITS
}
