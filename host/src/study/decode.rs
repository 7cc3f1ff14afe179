//! Decoding a parsed study file into [`StudyFile`], section by section and entry by entry,
//! collecting every structural error (unknown key, missing key, wrong type) instead of
//! stopping at the first.
//!
//! serde stops at the first error inside whatever it decodes, so the loader hands it small
//! pieces: each top-level section, each `[materials]`, `[pairs]`, `[parameters]` and
//! `[factors]` entry, each `[[measurements]]` block, and each `[plan]` sub-table. A file
//! with three bad blocks gets three messages. Which sections and plan keys a file must have
//! depends on its kind ([`Layout`]): a pod study, a pull-off study, a diagnosis study.

use std::collections::BTreeMap;

use serde::de::DeserializeOwned;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::error::StudyError;
use super::file_format::{StudyFile, POD_SECTIONS, PULL_OFF_SECTIONS, SECTIONS};
use super::key_path::KeyPath;
use super::plan::{Plan, PLAN_KEYS};
use super::source::Source;
use crate::nearest_name::nearest_name;

/// Which sections `root` has, and so which kinds of study it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Layout {
    /// A pod world (`[materials]`, `[pods]` or `[pairs]`), also when nothing else marks the
    /// file (a study of other rigs says what it measures in `[[measurements]]`).
    pub pods: bool,
    /// Sphere particles (`[spheres]`), which stand in for `[pods]`.
    pub spheres: bool,
    /// The pull-off tensile test (`[rig]`, `[measurement]` or `[factors]`).
    pub pull_off: bool,
    /// `[[measurements]]` (then a pull-off study needs no `[measurement]`).
    pub measurements: bool,
    /// `[diagnosis]`.
    pub diagnosis: bool,
}

impl Layout {
    fn of(root: &DeTable<'_>) -> Self {
        let has = |keys: &[&str]| keys.iter().any(|k| root.get(*k).is_some());
        let pull_off = has(&["rig", "measurement", "factors"]);
        let diagnosis = has(&["diagnosis"]);
        let measurements = has(&["measurements"]);
        let spheres = has(&["spheres"]);
        let pods = has(&["materials", "pods", "spheres", "pairs"])
            || !(pull_off || diagnosis || measurements || has(&["parameters"]));
        Self {
            pods,
            spheres,
            pull_off,
            measurements,
            diagnosis,
        }
    }

    /// Whether the file must have section `key`.
    fn requires(&self, key: &str) -> bool {
        (self.pods && POD_SECTIONS.contains(&key) && !(key == "pods" && self.spheres))
            || (self.pull_off
                && PULL_OFF_SECTIONS.contains(&key)
                && !(key == "measurement" && self.measurements))
    }
}

/// Decodes the whole file, or returns every structural error found.
pub(crate) fn decode_file(src: &Source<'_>) -> Result<StudyFile, Vec<StudyError>> {
    let (root, mut errors) = root_sections(src, &SECTIONS);
    let layout = Layout::of(root);
    let need = |key: &str| layout.requires(key);
    let file = StudyFile {
        study: whole(src, root, "study", need("study"), &mut errors),
        materials: map(src, root, "materials", need("materials"), &mut errors).unwrap_or_default(),
        pods: whole(src, root, "pods", need("pods"), &mut errors),
        spheres: whole(src, root, "spheres", false, &mut errors),
        pairs: map(src, root, "pairs", need("pairs"), &mut errors).unwrap_or_default(),
        rig: whole(src, root, "rig", need("rig"), &mut errors),
        measurements: array(src, root, "measurements", need("measurements"), &mut errors)
            .unwrap_or_default(),
        measurement: whole(src, root, "measurement", need("measurement"), &mut errors),
        parameters: map(src, root, "parameters", need("parameters"), &mut errors)
            .unwrap_or_default(),
        factors: map(src, root, "factors", need("factors"), &mut errors).unwrap_or_default(),
        plan: plan(src, root, layout, &mut errors),
        diagnosis: whole(src, root, "diagnosis", false, &mut errors),
        priors: map(src, root, "priors", false, &mut errors).unwrap_or_default(),
    };
    if errors.is_empty() {
        Ok(file)
    } else {
        Err(errors)
    }
}

/// Reports every key of `table` not in `known`, suggesting the nearest known one.
pub(crate) fn reject_unknown_keys(
    src: &Source<'_>,
    table: &DeTable<'_>,
    at: &KeyPath,
    known: &[&str],
    what: &str,
    errors: &mut Vec<StudyError>,
) {
    for (name, _) in table.iter() {
        let name: &str = name.get_ref();
        if !known.contains(&name) {
            let hint = match nearest_name(name, known) {
                Some(n) => format!("; did you mean '{n}'?"),
                None => String::new(),
            };
            errors.push(src.error(
                &at.key(name),
                format!(
                    "unknown {what} '{name}'{hint} (accepted: {})",
                    known.join(", ")
                ),
            ));
        }
    }
}

/// The file's root table, and the errors of its unknown top-level sections (any name not in
/// `sections`): where every study decoder starts.
pub(crate) fn root_sections<'a, 'i>(
    src: &'a Source<'i>,
    sections: &[&str],
) -> (&'a DeTable<'i>, Vec<StudyError>) {
    let root = src.doc.get_ref();
    let mut errors = Vec::new();
    reject_unknown_keys(
        src,
        root,
        &KeyPath::root(),
        sections,
        "section",
        &mut errors,
    );
    (root, errors)
}

/// The value at `key` of `table`; when it is missing and `needed`, an error saying so.
fn required<'a, 'i>(
    src: &Source<'i>,
    table: &'a DeTable<'i>,
    at: &KeyPath,
    key: &str,
    needed: bool,
    errors: &mut Vec<StudyError>,
) -> Option<&'a Spanned<DeValue<'i>>> {
    let value = table.get(key);
    if value.is_none() && needed {
        let reason = if at.is_empty() {
            format!("missing section [{key}]")
        } else {
            format!("missing key '{key}' in [{at}]")
        };
        errors.push(src.error(&at.key(key), reason));
    }
    value
}

/// Decodes one top-level section as a whole (`None` when it is absent; an error too when
/// it is `needed`).
fn whole<T: DeserializeOwned>(
    src: &Source<'_>,
    root: &DeTable<'_>,
    key: &str,
    needed: bool,
    errors: &mut Vec<StudyError>,
) -> Option<T> {
    let value = required(src, root, &KeyPath::root(), key, needed, errors)?;
    src.decode(&KeyPath::root().key(key), value)
        .map_err(|e| errors.push(e))
        .ok()
}

/// Decodes a table of named entries, each separately.
fn map<T: DeserializeOwned>(
    src: &Source<'_>,
    root: &DeTable<'_>,
    key: &str,
    needed: bool,
    errors: &mut Vec<StudyError>,
) -> Option<BTreeMap<String, T>> {
    let at = KeyPath::root().key(key);
    let value = required(src, root, &KeyPath::root(), key, needed, errors)?;
    let Some(table) = value.get_ref().as_table() else {
        errors.push(src.error(
            &at,
            format!(
                "expected a table of named entries, found {}",
                value.get_ref().type_str()
            ),
        ));
        return None;
    };
    let mut out = BTreeMap::new();
    let mut ok = true;
    for (name, entry) in table.iter() {
        match src.decode(&at.key(name.get_ref()), entry) {
            Ok(v) => {
                out.insert(name.get_ref().to_string(), v);
            }
            Err(e) => {
                errors.push(e);
                ok = false;
            }
        }
    }
    ok.then_some(out)
}

/// Decodes an array of tables, each element separately.
fn array<T: DeserializeOwned>(
    src: &Source<'_>,
    root: &DeTable<'_>,
    key: &str,
    needed: bool,
    errors: &mut Vec<StudyError>,
) -> Option<Vec<T>> {
    let at = KeyPath::root().key(key);
    let value = required(src, root, &KeyPath::root(), key, needed, errors)?;
    let Some(array) = value.get_ref().as_array() else {
        errors.push(src.error(
            &at,
            format!(
                "expected [[{key}]] blocks, found {}",
                value.get_ref().type_str()
            ),
        ));
        return None;
    };
    let mut out = Vec::new();
    let mut ok = true;
    for (i, element) in array.iter().enumerate() {
        match src.decode(&at.index(i), element) {
            Ok(v) => out.push(v),
            Err(e) => {
                errors.push(e);
                ok = false;
            }
        }
    }
    ok.then_some(out)
}

/// The keys `[plan]` must have in a study of `layout` whose plan has `table`'s keys.
fn plan_requires(layout: Layout, table: &DeTable<'_>, key: &str) -> bool {
    let surface = table.get("box_behnken").is_some() || table.get("central_composite").is_some();
    match key {
        "screening" | "steepest_ascent" | "validation" => true,
        "mode" | "modes" | "simulation" | "target" => layout.pods,
        // The response surface: a Box–Behnken one (the seed 000 layout, with its model)
        // unless the plan has the other.
        "box_behnken" => !surface,
        "model" => table.get("box_behnken").is_some() || !surface,
        _ => false,
    }
}

/// Decodes `[plan]` one sub-table at a time, then assembles it.
fn plan(
    src: &Source<'_>,
    root: &DeTable<'_>,
    layout: Layout,
    errors: &mut Vec<StudyError>,
) -> Option<Plan> {
    let at = KeyPath::root().key("plan");
    let value = required(
        src,
        root,
        &KeyPath::root(),
        "plan",
        layout.requires("plan"),
        errors,
    )?;
    let Some(table) = value.get_ref().as_table() else {
        errors.push(src.error(
            &at,
            format!("expected a table, found {}", value.get_ref().type_str()),
        ));
        return None;
    };
    reject_unknown_keys(src, table, &at, &PLAN_KEYS, "key", errors);
    let before = errors.len();
    for key in PLAN_KEYS {
        let needed = plan_requires(layout, table, key);
        if let Some(v) = required(src, table, &at, key, needed, errors) {
            // Decode each part alone to collect its errors; the typed value is rebuilt below.
            let part = decode_plan_part(src, &at.key(key), key, v);
            if let Err(e) = part {
                errors.push(e);
            }
        }
    }
    if errors.len() > before {
        return None;
    }
    src.decode(&at, value).map_err(|e| errors.push(e)).ok()
}

/// Decodes one `[plan]` part into its own type, discarding the value.
fn decode_plan_part(
    src: &Source<'_>,
    at: &KeyPath,
    key: &str,
    value: &Spanned<DeValue<'_>>,
) -> Result<(), StudyError> {
    use super::plan::{
        BoxBehnken, CentralComposite, Mode, Model, Optimisation, Screening, Simulation,
        SteepestAscent, Target, Validation,
    };
    match key {
        "mode" => src.decode::<String>(at, value).map(drop),
        "screening" => src.decode::<Screening>(at, value).map(drop),
        "steepest_ascent" => src.decode::<SteepestAscent>(at, value).map(drop),
        "box_behnken" => src.decode::<BoxBehnken>(at, value).map(drop),
        "central_composite" => src.decode::<CentralComposite>(at, value).map(drop),
        "model" => src.decode::<Model>(at, value).map(drop),
        "optimisation" => src.decode::<Optimisation>(at, value).map(drop),
        "target" => src.decode::<Target>(at, value).map(drop),
        "validation" => src.decode::<Validation>(at, value).map(drop),
        "modes" => src.decode::<BTreeMap<String, Mode>>(at, value).map(drop),
        "simulation" => src.decode::<Simulation>(at, value).map(drop),
        _ => Ok(()),
    }
}
