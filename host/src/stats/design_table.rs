//! Reads a design table (CSV, one row per run) into a [`CodedDesign`]: picks the factor and
//! response columns, codes actual levels, and rejects what cannot be analysed with a message
//! naming the file, and where it applies the line and the column.
//!
//! Factor columns are those named (taken in the file's column order, which fixes term
//! names such as `A*B`), or by default every column left of the response except `run`. A factor without levels must already be coded: its values must be symmetric about
//! zero (coded designs always are), otherwise it is reported as needing `--levels`.

use anyhow::{bail, Context};

use super::curvature::LEVEL_TOLERANCE;
use super::{CodedDesign, FactorLevels};
use crate::io::{CsvTable, InputError};

/// The run-number column, never a factor.
const RUN_COLUMN: &str = "run";

/// A design read from a table, with the levels used to code each factor.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignTable {
    /// The coded design.
    pub design: CodedDesign,
    /// Per factor, the actual levels −1/+1 stand for; `None` when the column was coded.
    pub levels: Vec<Option<FactorLevels>>,
}

/// Builds the coded design of `response` from `table`.
pub fn read_design_table(
    table: &CsvTable,
    response: &str,
    factors: Option<&[String]>,
    levels: &[(String, FactorLevels)],
) -> anyhow::Result<DesignTable> {
    let path = table.path.display();
    let response_index = table.column_index(response)?;
    let factor_names: Vec<String> = match factors {
        Some(names) => {
            // Terms are named with factors in column order (the naming contract).
            let mut indexed = names
                .iter()
                .map(|n| Ok((table.column_index(n)?, n.clone())))
                .collect::<Result<Vec<_>, InputError>>()?;
            indexed.sort();
            indexed.dedup();
            indexed.into_iter().map(|(_, n)| n).collect()
        }
        None => table.headers[..response_index]
            .iter()
            .filter(|h| !h.eq_ignore_ascii_case(RUN_COLUMN))
            .cloned()
            .collect(),
    };
    if factor_names.is_empty() {
        bail!("{path}: no factor columns left of '{response}'; name them with --factors");
    }
    if factor_names.iter().any(|f| f == response) {
        bail!("{path}: '{response}' cannot be both the response and a factor");
    }
    for (name, _) in levels {
        if !factor_names.contains(name) {
            bail!(
                "{path}: levels given for '{name}', which is not a factor (factors: {})",
                factor_names.join(", ")
            );
        }
    }
    let y = table.f64_column(response)?;
    let mut columns = Vec::with_capacity(factor_names.len());
    let mut used_levels = Vec::with_capacity(factor_names.len());
    for name in &factor_names {
        let level = levels
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, l)| l.clone());
        let actual = table.f64_column(name)?;
        check_two_levels(table, name, &actual)?;
        let coded = match &level {
            Some(l) => code_column(table, name, &actual, l)?,
            None => {
                check_coded(table, name, &actual)?;
                actual
            }
        };
        columns.push(coded);
        used_levels.push(level);
    }
    let runs = (0..y.len())
        .map(|r| columns.iter().map(|c| c[r]).collect())
        .collect();
    let design = CodedDesign::new(factor_names, runs, y).with_context(|| format!("{path}"))?;
    Ok(DesignTable {
        design,
        levels: used_levels,
    })
}

fn check_two_levels(table: &CsvTable, name: &str, values: &[f64]) -> anyhow::Result<()> {
    let first = values[0];
    let scale = first.abs().max(1.0);
    if values
        .iter()
        .all(|v| (v - first).abs() <= LEVEL_TOLERANCE * scale)
    {
        bail!(
            "{}: column '{name}': factor has a single level ({first}) in all {} runs; \
             a factor needs at least two levels",
            table.path.display(),
            values.len()
        );
    }
    Ok(())
}

/// Coded columns of standard designs are symmetric about 0 (min = −max).
fn check_coded(table: &CsvTable, name: &str, values: &[f64]) -> anyhow::Result<()> {
    let (min, max) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(*v), hi.max(*v))
        });
    if (min + max).abs() > LEVEL_TOLERANCE * max.abs().max(min.abs()) {
        bail!(
            "{}: column '{name}' is not in coded units (its values run from {min} to {max}, \
             not symmetric about 0); give its actual levels with --levels {name}=LOW:HIGH",
            table.path.display()
        );
    }
    Ok(())
}

fn code_column(
    table: &CsvTable,
    name: &str,
    actual: &[f64],
    levels: &FactorLevels,
) -> Result<Vec<f64>, InputError> {
    actual
        .iter()
        .zip(&table.rows)
        .map(|(v, row)| {
            levels.code(*v).map_err(|reason| InputError::BadValue {
                path: table.path.clone(),
                line: row.line,
                column: name.to_owned(),
                reason,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn table(text: &str) -> CsvTable {
        CsvTable::parse(Path::new("d.csv"), text).unwrap()
    }

    #[test]
    fn default_factors_are_left_of_the_response() {
        let t = table("run,A,B,y,z\n1,-1,-1,1,9\n2,1,-1,2,9\n3,-1,1,3,9\n4,1,1,5,9\n");
        let d = read_design_table(&t, "y", None, &[]).unwrap();
        assert_eq!(d.design.factor_names, ["A", "B"]);
        assert_eq!(d.levels, [None, None]);
    }

    #[test]
    fn actual_units_without_levels_are_refused() {
        let t = table("A,y\n0.2,1\n0.6,2\n0.2,3\n");
        let err = read_design_table(&t, "y", None, &[]).unwrap_err();
        assert!(err.to_string().contains("--levels A=LOW:HIGH"), "{err}");
    }

    #[test]
    fn off_table_level_names_its_line() {
        let t = table("A,y\n0.327,1\n0.335,2\n0.340,3\n");
        let l = FactorLevels::with_printed_centre(0.327, 0.334, 0.340).unwrap();
        let err = read_design_table(&t, "y", None, &[("A".into(), l)]).unwrap_err();
        assert!(err.to_string().starts_with("d.csv:3: column 'A'"), "{err}");
    }

    #[test]
    fn named_factors_follow_column_order() {
        let t = table("B,A,y,z\n-1,-1,1,9\n1,-1,2,9\n-1,1,3,9\n1,1,5,9\n");
        let names = ["A".to_owned(), "B".to_owned()];
        let d = read_design_table(&t, "z", Some(&names), &[]).unwrap();
        assert_eq!(d.design.factor_names, ["B", "A"]);
    }
}
