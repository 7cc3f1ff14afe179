//! The fit file written by `arachis doe analyze --json`, read as a response surface.
//!
//! The agreed contract (only the parts optimisation needs): `response` is the response's
//! name; `factors` is an array of `{name, low, high}` where low/high are the actual levels of
//! coded −1/+1 (`null` when the design was analysed in coded units); `coefficients` is an
//! array of `{term, estimate, se}` with terms `Intercept`, `A`, `A*B` (factors in column
//! order) and `A^2`. Other keys are ignored.
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("fit.json");
//! std::fs::write(&path, r#"{"response": "y",
//!   "factors": [{"name": "A", "low": 10, "high": 20}],
//!   "coefficients": [{"term": "Intercept", "estimate": 1.5, "se": 0.1},
//!                    {"term": "A", "estimate": 2.0, "se": 0.1}]}"#).unwrap();
//! let fit = arachis::optimize::FitFile::read(&path).unwrap();
//! use arachis::optimize::ResponseSurface;
//! assert_eq!(fit.model.predict(&[1.0]), 3.5);
//! assert_eq!(fit.factors[0].to_actual(0.0), Some(15.0));
//! ```

use std::path::{Path, PathBuf};

use serde_json::Value;

use super::{OptimizeError, Polynomial};
use crate::optimize::polynomial::Term;

/// A factor of a fit: its name and, when the fit was in actual units, its ±1 levels.
#[derive(Debug, Clone, PartialEq)]
pub struct FitFactor {
    /// Column name.
    pub name: String,
    /// Actual levels (low, high) of coded −1 and +1, or `None` for coded-only columns.
    pub levels: Option<(f64, f64)>,
}

impl FitFactor {
    /// Actual level of coded `x`, or `None` for a coded-only factor.
    pub fn to_actual(&self, x: f64) -> Option<f64> {
        self.levels
            .map(|(low, high)| 0.5 * (low + high) + x * 0.5 * (high - low))
    }
}

/// A fitted model read from a fit file.
#[derive(Debug, Clone, PartialEq)]
pub struct FitFile {
    /// Where it was read from.
    pub path: PathBuf,
    /// The response's name.
    pub response: String,
    /// The factors, in column order.
    pub factors: Vec<FitFactor>,
    /// The fitted polynomial in coded units.
    pub model: Polynomial,
}

impl FitFile {
    /// Reads and checks `path`.
    pub fn read(path: &Path) -> Result<Self, OptimizeError> {
        let text = crate::io::text::read_text(path).map_err(|e| OptimizeError::FitFile {
            path: path.to_path_buf(),
            place: "file".into(),
            reason: format!("cannot read: {e}"),
        })?;
        Self::parse(path, &text)
    }

    /// Parses fit-file `text` as if read from `path` (the path is used in messages).
    pub fn parse(path: &Path, text: &str) -> Result<Self, OptimizeError> {
        let err = |place: &str, reason: String| OptimizeError::FitFile {
            path: path.to_path_buf(),
            place: place.to_owned(),
            reason,
        };
        crate::io::json_keys::check_unique_keys(text).map_err(|reason| err("file", reason))?;
        let root: Value = serde_json::from_str(text).map_err(|e| {
            err(
                &format!("line {} column {}", e.line(), e.column()),
                format!("not valid JSON: {e}"),
            )
        })?;
        let key = |name: &str| {
            root.get(name)
                .ok_or_else(|| err(name, "missing key (a fit file from `arachis doe analyze --json` has response, factors and coefficients)".into()))
        };
        let response = key("response")?
            .as_str()
            .ok_or_else(|| err("response", "must be a string".into()))?
            .to_owned();
        let factors_json = key("factors")?
            .as_array()
            .ok_or_else(|| err("factors", "must be an array".into()))?;
        if factors_json.is_empty() {
            return Err(err("factors", "is empty".into()));
        }
        let mut factors = Vec::with_capacity(factors_json.len());
        for (i, f) in factors_json.iter().enumerate() {
            let place = |field: &str| format!("factors[{i}].{field}");
            let name = f
                .get("name")
                .and_then(Value::as_str)
                .ok_or_else(|| err(&place("name"), "missing or not a string".into()))?
                .to_owned();
            if factors.iter().any(|g: &FitFactor| g.name == name) {
                return Err(err(
                    &place("name"),
                    format!("factor '{name}' appears twice"),
                ));
            }
            let level = |field: &str| -> Result<Option<f64>, OptimizeError> {
                match f.get(field) {
                    None | Some(Value::Null) => Ok(None),
                    Some(v) => v
                        .as_f64()
                        .filter(|x| x.is_finite())
                        .map(Some)
                        .ok_or_else(|| err(&place(field), "must be a number or null".into())),
                }
            };
            let levels = match (level("low")?, level("high")?) {
                (Some(low), Some(high)) if low < high => Some((low, high)),
                (Some(low), Some(high)) => {
                    return Err(err(
                        &place("low"),
                        format!("low level {low} must be below high level {high}"),
                    ))
                }
                (None, None) => None,
                _ => {
                    return Err(err(
                        &place("low"),
                        "low and high must both be numbers or both null".into(),
                    ))
                }
            };
            factors.push(FitFactor { name, levels });
        }
        let names: Vec<String> = factors.iter().map(|f| f.name.clone()).collect();
        let coefficients = key("coefficients")?
            .as_array()
            .ok_or_else(|| err("coefficients", "must be an array".into()))?;
        if coefficients.is_empty() {
            return Err(err("coefficients", "is empty".into()));
        }
        let mut terms = Vec::with_capacity(coefficients.len());
        for (i, c) in coefficients.iter().enumerate() {
            let place = |field: &str| format!("coefficients[{i}].{field}");
            let term_name = c
                .get("term")
                .and_then(Value::as_str)
                .ok_or_else(|| err(&place("term"), "missing or not a string".into()))?;
            let estimate = c
                .get("estimate")
                .and_then(Value::as_f64)
                .filter(|x| x.is_finite())
                .ok_or_else(|| err(&place("estimate"), "missing or not a finite number".into()))?;
            let term = Term::parse(term_name, &names).ok_or_else(|| {
                err(
                    &place("term"),
                    format!(
                        "unknown term '{term_name}': expected Intercept, a factor, A*B or A^2 over the factors {}",
                        names.join(", ")
                    ),
                )
            })?;
            if terms.iter().any(|(t, _)| *t == term) {
                return Err(err(
                    &place("term"),
                    format!("term '{term_name}' appears twice"),
                ));
            }
            terms.push((term, estimate));
        }
        Ok(Self {
            path: path.to_path_buf(),
            response,
            factors,
            model: Polynomial {
                factors: names,
                terms,
            },
        })
    }
}
