//! The result of one bench-test analysis: the settings used, one replicate summary per
//! derived quantity, single derived values, and notes. It prints as a human-readable table
//! or serialises as one JSON object (SI units; the unit of every number is in its record).

use std::fmt::Write as _;

use serde::Serialize;

use super::error::LabError;
use super::summary::{summarize, Summary};
use crate::io::CsvTable;

/// One replicate value of a quantity and the CSV line it came from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Replicate {
    /// 1-based line number in the input file.
    pub line: u64,
    /// The value, in the quantity's SI unit.
    pub value: f64,
}

/// A quantity computed once per replicate, with its summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Quantity {
    /// Machine name, e.g. `apparent_modulus`.
    pub name: String,
    /// SI unit of every number in this record (`1` for dimensionless).
    pub unit: String,
    /// The replicate summary, in `unit`.
    #[serde(flatten)]
    pub summary: Summary,
    /// The replicates, in file order.
    pub replicates: Vec<Replicate>,
    /// Unit used in the human-readable table (not serialised).
    #[serde(skip)]
    pub display_unit: String,
    /// Factor from `unit` to `display_unit` (not serialised).
    #[serde(skip)]
    pub display_scale: f64,
}

impl Quantity {
    /// Summarises `values` (SI, `unit`) taken from the rows of `table` in order.
    pub fn new(table: &CsvTable, name: &str, unit: &str, values: &[f64]) -> Result<Self, LabError> {
        let summary = summarize(values).map_err(|cause| LabError::Summary {
            path: table.path.clone(),
            quantity: name.to_owned(),
            cause,
        })?;
        let replicates = table
            .rows
            .iter()
            .zip(values)
            .map(|(row, &value)| Replicate {
                line: row.line,
                value,
            })
            .collect();
        Ok(Self {
            name: name.to_owned(),
            unit: unit.to_owned(),
            summary,
            replicates,
            display_unit: unit.to_owned(),
            display_scale: 1.0,
        })
    }

    /// Shows this quantity in `unit` (value × `scale`) in the human-readable table.
    pub fn shown_in(mut self, unit: &str, scale: f64) -> Self {
        self.display_unit = unit.to_owned();
        self.display_scale = scale;
        self
    }
}

/// A named single value with its SI unit (a setting used, or a derived constant).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Value {
    /// Machine name.
    pub name: String,
    /// The value, in `unit`.
    pub value: f64,
    /// SI unit (`1` for dimensionless).
    pub unit: String,
}

impl Value {
    /// A value named `name` in `unit`.
    pub fn new(name: &str, value: f64, unit: &str) -> Self {
        Self {
            name: name.to_owned(),
            value,
            unit: unit.to_owned(),
        }
    }
}

/// Everything one analysis of one file produced.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LabReport {
    /// The test, as named on the command line (e.g. `hertz-modulus`).
    pub test: String,
    /// The input file.
    pub file: String,
    /// Settings the analysis used (from options or defaults).
    pub settings: Vec<Value>,
    /// Per-replicate quantities and their summaries.
    pub quantities: Vec<Quantity>,
    /// Single values derived from the summaries or settings.
    pub derived: Vec<Value>,
    /// Remarks on the method (formula variants, seed typos worked around).
    pub notes: Vec<String>,
}

/// Significant digits in the human-readable table.
const SIGNIFICANT_DIGITS: i32 = 5;

/// Formats `v` with [`SIGNIFICANT_DIGITS`] significant digits, switching to exponent form
/// for very small or large magnitudes.
fn sig(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let exponent = v.abs().log10().floor() as i32;
    if !(-4..=8).contains(&exponent) {
        return format!("{:.*e}", (SIGNIFICANT_DIGITS - 1) as usize, v);
    }
    let decimals = (SIGNIFICANT_DIGITS - 1 - exponent).max(0) as usize;
    format!("{v:.decimals$}")
}

impl LabReport {
    /// A new report for `test` on `table` with no results yet.
    pub fn new(test: &str, table: &CsvTable) -> Self {
        Self {
            test: test.to_owned(),
            file: table.path.display().to_string(),
            settings: Vec::new(),
            quantities: Vec::new(),
            derived: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// The quantity named `name`, if computed.
    pub fn quantity(&self, name: &str) -> Option<&Quantity> {
        self.quantities.iter().find(|q| q.name == name)
    }

    /// The derived value named `name`, if computed.
    pub fn derived_value(&self, name: &str) -> Option<f64> {
        self.derived
            .iter()
            .find(|v| v.name == name)
            .map(|v| v.value)
    }

    /// The human-readable table.
    pub fn to_table(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(out, "{}: {}", self.test, self.file);
        for s in &self.settings {
            let _ = writeln!(out, "  setting {} = {} {}", s.name, sig(s.value), s.unit);
        }
        let header = [
            "quantity",
            "unit",
            "n",
            "mean",
            "sd",
            "min",
            "max",
            "95% CI low",
            "95% CI high",
        ];
        let mut rows = vec![header.map(str::to_owned).to_vec()];
        for q in &self.quantities {
            let k = q.display_scale;
            let s = &q.summary;
            rows.push(vec![
                q.name.clone(),
                q.display_unit.clone(),
                s.n.to_string(),
                sig(s.mean * k),
                sig(s.sd * k),
                sig(s.min * k),
                sig(s.max * k),
                sig(s.ci95_low * k),
                sig(s.ci95_high * k),
            ]);
        }
        let widths: Vec<usize> = (0..header.len())
            .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
            .collect();
        for row in &rows {
            let cells: Vec<String> = row
                .iter()
                .zip(&widths)
                .enumerate()
                .map(|(c, (cell, w))| {
                    if c < 2 {
                        format!("{cell:<w$}")
                    } else {
                        format!("{cell:>w$}")
                    }
                })
                .collect();
            let _ = writeln!(out, "{}", cells.join("  ").trim_end());
        }
        for d in &self.derived {
            let _ = writeln!(out, "{} = {} {}", d.name, sig(d.value), d.unit);
        }
        for n in &self.notes {
            let _ = writeln!(out, "note: {n}");
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits() {
        assert_eq!(sig(582.3617), "582.36");
        assert_eq!(sig(0.38612), "0.38612");
        assert_eq!(sig(3.0411e6), "3041100");
        assert_eq!(sig(8.95e-6), "8.9500e-6");
    }
}
