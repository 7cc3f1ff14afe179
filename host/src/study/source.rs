//! The study file as parsed text with positions: the bridge between serde's typed view and
//! messages that name a key and a line:column.
//!
//! The loader parses the whole file once into toml's spanned document tree
//! ([`toml::de::DeTable`]), then decodes each section (and each entry of a map or array)
//! separately, so one bad entry does not hide the errors in the others. When serde rejects
//! a piece, the error's byte span is mapped back to the innermost key that contains it;
//! semantic checks go the other way, from a key path to its position.

use std::ops::Range;
use std::path::Path;

use serde::de::DeserializeOwned;
use toml::de::{DeTable, DeValue, ValueDeserializer};
use toml::Spanned;

use super::error::{StudyError, StudyErrors};
use super::key_path::{KeyPath, Segment};
use crate::nearest_name::nearest_name;

/// A parsed study file: its name for messages, its text, and its spanned document tree.
pub(crate) struct Source<'i> {
    /// The file, as named in every message.
    pub path: &'i Path,
    text: &'i str,
    /// The document root.
    pub doc: Spanned<DeTable<'i>>,
}

impl<'i> Source<'i> {
    /// Parses `text`; on syntax errors returns every one the parser recovered from.
    pub fn parse(path: &'i Path, text: &'i str) -> Result<Self, Vec<StudyError>> {
        let (doc, errors) = DeTable::parse_recoverable(text);
        let source = Self { path, text, doc };
        if errors.is_empty() {
            return Ok(source);
        }
        Err(errors
            .iter()
            .map(|e| {
                let offset = e.span().map(|s| s.start);
                let key = offset
                    .map(|o| source.path_at(o))
                    .unwrap_or_else(KeyPath::root);
                StudyError {
                    file: path.to_owned(),
                    key,
                    position: offset.map(|o| source.line_col(o)),
                    reason: format!("not valid TOML: {}", e.message().trim()),
                }
            })
            .collect())
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let before = &self.text[..floor_char_boundary(self.text, offset)];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before[line_start..].chars().count() + 1;
        (line, column)
    }

    /// An error at `key`, positioned at the key (or array element) if the file has it,
    /// else at the nearest enclosing key that it has.
    pub fn error(&self, key: &KeyPath, reason: impl Into<String>) -> StudyError {
        StudyError {
            file: self.path.to_owned(),
            key: key.clone(),
            position: self.span_of(key).map(|s| self.line_col(s.start)),
            reason: reason.into(),
        }
    }

    /// [`Source::error`] at the table path `keys` (e.g. `["soil", "depth_m"]`).
    pub fn error_at_keys(&self, keys: &[&str], reason: impl Into<String>) -> StudyError {
        let key = keys
            .iter()
            .fold(KeyPath::root(), |k, segment| k.key(segment));
        self.error(&key, reason)
    }

    /// The span of `key`'s name (for a table key) or of the element (for an array index);
    /// for a path the file does not hold in full, the span of its longest held prefix.
    pub fn span_of(&self, key: &KeyPath) -> Option<Range<usize>> {
        let mut best: Option<Range<usize>> = None;
        // The value reached so far; the root is a table with no value of its own.
        let mut value: Option<&Spanned<DeValue<'i>>> = None;
        for segment in &key.0 {
            let next = match segment {
                Segment::Key(k) => {
                    let table = match value {
                        None => Some(self.doc.get_ref()),
                        Some(v) => v.get_ref().as_table(),
                    };
                    table
                        .and_then(|t| t.get_key_value(k.as_str()))
                        .map(|(name, v)| (name.span(), v))
                }
                Segment::Index(i) => value
                    .and_then(|v| v.get_ref().as_array())
                    .and_then(|a| a.get(*i))
                    .map(|element| (element.span(), element)),
            };
            let Some((span, v)) = next else { break };
            best = Some(span);
            value = Some(v);
        }
        best
    }

    /// The innermost key path whose key or value contains byte `offset`.
    pub fn path_at(&self, offset: usize) -> KeyPath {
        let mut path = KeyPath::root();
        descend_table(self.doc.get_ref(), offset, &mut path);
        path
    }

    /// Decodes `value` (found at `key`) into `T`; a rejection names the innermost key that
    /// serde's error span points into.
    pub fn decode<T: DeserializeOwned>(
        &self,
        key: &KeyPath,
        value: &Spanned<DeValue<'i>>,
    ) -> Result<T, StudyError> {
        T::deserialize(ValueDeserializer::from(value.clone())).map_err(|e| {
            let offset = e.span().map_or(value.span().start, |s| s.start);
            let mut inner = key.clone();
            if let Some(t) = value.get_ref().as_table() {
                descend_table(t, offset, &mut inner);
            } else if let Some(a) = value.get_ref().as_array() {
                descend_array(a, offset, &mut inner);
            }
            StudyError {
                file: self.path.to_owned(),
                key: inner,
                position: Some(self.line_col(offset)),
                reason: explain_serde(e.message()),
            }
        })
    }
}

fn descend_table(table: &DeTable<'_>, offset: usize, path: &mut KeyPath) {
    for (name, value) in table.iter() {
        if name.span().contains(&offset) {
            path.0.push(Segment::Key(name.get_ref().to_string()));
            return;
        }
        if value.span().contains(&offset) {
            path.0.push(Segment::Key(name.get_ref().to_string()));
            descend_value(value.get_ref(), offset, path);
            return;
        }
    }
    // Tables opened by `[a.b]` headers have no value span covering their body: find the
    // nested table whose entries contain the offset.
    for (name, value) in table.iter() {
        if let Some(t) = value.get_ref().as_table() {
            if t.iter().any(|(k, v)| contains_deep(k.span(), v, offset)) {
                path.0.push(Segment::Key(name.get_ref().to_string()));
                descend_table(t, offset, path);
                return;
            }
        } else if let Some(a) = value.get_ref().as_array() {
            if a.iter().any(|v| contains_deep(v.span(), v, offset)) {
                path.0.push(Segment::Key(name.get_ref().to_string()));
                descend_array(a, offset, path);
                return;
            }
        }
    }
}

fn descend_array(array: &[Spanned<DeValue<'_>>], offset: usize, path: &mut KeyPath) {
    for (i, element) in array.iter().enumerate() {
        if contains_deep(element.span(), element, offset) {
            path.0.push(Segment::Index(i));
            descend_value(element.get_ref(), offset, path);
            return;
        }
    }
}

fn descend_value(value: &DeValue<'_>, offset: usize, path: &mut KeyPath) {
    match value {
        DeValue::Table(t) => descend_table(t, offset, path),
        DeValue::Array(a) => descend_array(a, offset, path),
        _ => {}
    }
}

/// True when `offset` lies in `span` or anywhere inside `value`'s nested keys and values.
fn contains_deep(span: Range<usize>, value: &Spanned<DeValue<'_>>, offset: usize) -> bool {
    if span.contains(&offset) || value.span().contains(&offset) {
        return true;
    }
    match value.get_ref() {
        DeValue::Table(t) => t.iter().any(|(k, v)| contains_deep(k.span(), v, offset)),
        DeValue::Array(a) => a.iter().any(|v| contains_deep(v.span(), v, offset)),
        _ => false,
    }
}

/// The largest char boundary ≤ `offset` (spans are byte offsets; columns count chars).
fn floor_char_boundary(text: &str, mut offset: usize) -> usize {
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    offset
}

/// Rewords serde's messages for a reader who edits TOML, not Rust.
fn explain_serde(message: &str) -> String {
    let m = message.trim();
    if let Some(rest) = m.strip_prefix("unknown field ") {
        // serde writes: unknown field `x`, expected one of `a`, `b` (or: expected `a`).
        let quoted: Vec<&str> = rest.split('`').skip(1).step_by(2).collect();
        if let Some((name, expected)) = quoted.split_first() {
            let hint = nearest_name(name, expected)
                .map_or(String::new(), |n| format!("; did you mean '{n}'?"));
            return format!(
                "unknown key '{name}'{hint} (accepted: {})",
                expected.join(", ")
            );
        }
        return format!("unknown key {rest}");
    }
    if let Some(rest) = m.strip_prefix("unknown variant ") {
        return format!("unknown value {}", rest.replace('`', "'"));
    }
    if let Some(rest) = m.strip_prefix("missing field ") {
        return format!("missing key {}", rest.replace('`', "'"));
    }
    m.replace('`', "'")
        .replace("expected f64", "expected a number")
        .replace("expected u32", "expected a whole number ≥ 0")
        .replace("expected u64", "expected a whole number ≥ 0")
}

/// Decodes the whole of `text` (the file at `path`) as a `T`, then checks it with
/// `problems`: every error is positioned and they come sorted by position. For input files
/// that are read whole (variety and field files).
pub(crate) fn decode_checked<T: DeserializeOwned>(
    path: &Path,
    text: &str,
    problems: impl FnOnce(&T, &Source<'_>) -> Vec<StudyError>,
) -> Result<T, Vec<StudyError>> {
    let source = Source::parse(path, text)?;
    let root = Spanned::new(
        source.doc.span(),
        DeValue::Table(source.doc.get_ref().clone()),
    );
    let value: T = source
        .decode(&KeyPath::root(), &root)
        .map_err(|e| vec![e])?;
    let errors = problems(&value, &source);
    if errors.is_empty() {
        Ok(value)
    } else {
        Err(StudyErrors(errors).sorted().0)
    }
}

/// Reads the file at `path` and [`decode_checked`]s it; `what` names the kind of file when it
/// cannot be read.
pub(crate) fn read_checked<T: DeserializeOwned>(
    path: &Path,
    what: &str,
    problems: impl FnOnce(&T, &Source<'_>) -> Vec<StudyError>,
) -> Result<T, Vec<StudyError>> {
    let text = crate::io::text::read_text(path).map_err(|e| {
        vec![StudyError {
            file: path.to_owned(),
            key: KeyPath::root(),
            position: None,
            reason: format!("cannot read the {what} file: {e}"),
        }]
    })?;
    decode_checked(path, &text, problems)
}
