//! Decoding a parsed study file into [`StudyFile`], section by section and entry by entry,
//! collecting every structural error (unknown key, missing key, wrong type) instead of
//! stopping at the first.
//!
//! serde stops at the first error inside whatever it decodes, so the loader hands it small
//! pieces: each top-level section, each `[materials]`, `[pairs]` and `[parameters]` entry,
//! each `[[measurements]]` block, and each `[plan]` sub-table. A file with three bad blocks
//! gets three messages.

use std::collections::BTreeMap;

use serde::de::DeserializeOwned;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::error::StudyError;
use super::file_format::{StudyFile, SECTIONS};
use super::key_path::KeyPath;
use super::nearest_name::nearest_name;
use super::plan::Plan;
use super::source::Source;

/// The keys of `[plan]`, in the order they are decoded.
const PLAN_KEYS: [&str; 9] = [
    "mode",
    "screening",
    "steepest_ascent",
    "box_behnken",
    "model",
    "target",
    "validation",
    "modes",
    "simulation",
];

/// Decodes the whole file, or returns every structural error found.
pub(crate) fn decode_file(src: &Source<'_>) -> Result<StudyFile, Vec<StudyError>> {
    let (root, mut errors) = root_sections(src, &SECTIONS);

    let study = whole(src, root, "study", &mut errors);
    let materials = map(src, root, "materials", &mut errors);
    let pods = whole(src, root, "pods", &mut errors);
    let pairs = map(src, root, "pairs", &mut errors);
    let measurements = array(src, root, "measurements", &mut errors);
    let parameters = map(src, root, "parameters", &mut errors);
    let plan = plan(src, root, &mut errors);

    match (
        study,
        materials,
        pods,
        pairs,
        measurements,
        parameters,
        plan,
    ) {
        (
            Some(study),
            Some(materials),
            Some(pods),
            Some(pairs),
            Some(measurements),
            Some(parameters),
            Some(plan),
        ) if errors.is_empty() => Ok(StudyFile {
            study,
            materials,
            pods,
            pairs,
            measurements,
            parameters,
            plan,
        }),
        _ => Err(errors),
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

/// The value at `key` of `table`, or an error saying it is missing.
fn required<'a, 'i>(
    src: &Source<'i>,
    table: &'a DeTable<'i>,
    at: &KeyPath,
    key: &str,
    errors: &mut Vec<StudyError>,
) -> Option<&'a Spanned<DeValue<'i>>> {
    let value = table.get(key);
    if value.is_none() {
        let reason = if at.is_empty() {
            format!("missing section [{key}]")
        } else {
            format!("missing key '{key}' in [{at}]")
        };
        errors.push(src.error(&at.key(key), reason));
    }
    value
}

/// Decodes one top-level section as a whole.
pub(crate) fn whole<T: DeserializeOwned>(
    src: &Source<'_>,
    root: &DeTable<'_>,
    key: &str,
    errors: &mut Vec<StudyError>,
) -> Option<T> {
    let value = required(src, root, &KeyPath::root(), key, errors)?;
    src.decode(&KeyPath::root().key(key), value)
        .map_err(|e| errors.push(e))
        .ok()
}

/// Decodes a table of named entries, each separately.
pub(crate) fn map<T: DeserializeOwned>(
    src: &Source<'_>,
    root: &DeTable<'_>,
    key: &str,
    errors: &mut Vec<StudyError>,
) -> Option<BTreeMap<String, T>> {
    let at = KeyPath::root().key(key);
    let value = required(src, root, &KeyPath::root(), key, errors)?;
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
    errors: &mut Vec<StudyError>,
) -> Option<Vec<T>> {
    let at = KeyPath::root().key(key);
    let value = required(src, root, &KeyPath::root(), key, errors)?;
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

/// Decodes `[plan]` one sub-table at a time, then assembles it.
fn plan(src: &Source<'_>, root: &DeTable<'_>, errors: &mut Vec<StudyError>) -> Option<Plan> {
    let at = KeyPath::root().key("plan");
    let value = required(src, root, &KeyPath::root(), "plan", errors)?;
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
        if let Some(v) = required(src, table, &at, key, errors) {
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
        BoxBehnken, Mode, Model, Screening, Simulation, SteepestAscent, Target, Validation,
    };
    match key {
        "mode" => src.decode::<String>(at, value).map(drop),
        "screening" => src.decode::<Screening>(at, value).map(drop),
        "steepest_ascent" => src.decode::<SteepestAscent>(at, value).map(drop),
        "box_behnken" => src.decode::<BoxBehnken>(at, value).map(drop),
        "model" => src.decode::<Model>(at, value).map(drop),
        "target" => src.decode::<Target>(at, value).map(drop),
        "validation" => src.decode::<Validation>(at, value).map(drop),
        "modes" => src.decode::<BTreeMap<String, Mode>>(at, value).map(drop),
        "simulation" => src.decode::<Simulation>(at, value).map(drop),
        _ => Ok(()),
    }
}
