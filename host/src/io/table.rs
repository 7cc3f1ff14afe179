//! CSV tables read with errors that name the file, the line and the column.
//!
//! A [`CsvTable`] keeps every cell as text with its line number; numeric columns are parsed
//! on request, so a non-numeric cell is reported where it stands. Lines starting with `#`
//! are comments; cells are trimmed.
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("friction.csv");
//! std::fs::write(&path, "# static friction, degrees\nsample,angle_deg\n1,40.5\n2,41.0\n").unwrap();
//! let table = arachis::io::CsvTable::read(&path).unwrap();
//! assert_eq!(table.f64_column("angle_deg").unwrap(), vec![40.5, 41.0]);
//! ```

use std::path::{Path, PathBuf};

use thiserror::Error;

/// Why an input file was rejected. Every variant names the file, and where it applies the
/// 1-based line and the column.
#[derive(Debug, Error)]
pub enum InputError {
    /// The file could not be opened or read.
    #[error("{path}: cannot read: {reason}")]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// The operating system's or parser's reason.
        reason: String,
    },
    /// The file has no header row or no data rows.
    #[error("{path}: no data rows")]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// A row has a different number of cells from the header.
    #[error("{path}:{line}: row has {found} cells but the header has {expected}")]
    Ragged {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// Cells in the header.
        expected: usize,
        /// Cells in this row.
        found: usize,
    },
    /// A cell that must be a finite number is not.
    #[error("{path}:{line}: column '{column}': '{value}' is not a finite number")]
    NotNumeric {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// Column header.
        column: String,
        /// The offending cell text.
        value: String,
    },
    /// A required column is missing from the header.
    #[error("{path}: no column named '{column}' (columns: {available})")]
    MissingColumn {
        /// The file.
        path: PathBuf,
        /// The column asked for.
        column: String,
        /// The header, comma-separated.
        available: String,
    },
    /// Two header cells name the same column: which one an analysis should read is not
    /// known, so neither is taken.
    #[error("{path}: column '{column}' appears twice, as columns {first} and {second}")]
    DuplicateColumn {
        /// The file.
        path: PathBuf,
        /// The repeated header.
        column: String,
        /// 1-based positions of its first and second appearance.
        first: usize,
        /// See `first`.
        second: usize,
    },
    /// A value is numeric but outside what the analysis accepts.
    #[error("{path}:{line}: column '{column}': {reason}")]
    BadValue {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// Column header.
        column: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// One data row: its 1-based line number in the file and its cells as trimmed text.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// 1-based line number in the file.
    pub line: u64,
    /// Cells, trimmed.
    pub cells: Vec<String>,
}

/// A CSV file with a header row, every cell kept as text with its position.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvTable {
    /// Where the table was read from (used in error messages).
    pub path: PathBuf,
    /// Header cells, trimmed.
    pub headers: Vec<String>,
    /// Data rows in file order.
    pub rows: Vec<Row>,
}

/// Longest cell text echoed in a message, in characters; a longer one is cut there (a
/// 20-million-digit cell was once echoed in full, 20 MB on stderr).
pub const ECHO_CHARS: usize = 40;

/// `text` as a message shows it: whole up to [`ECHO_CHARS`] characters, else its start and
/// its length.
pub fn shorten(text: &str) -> String {
    let n = text.chars().count();
    if n <= ECHO_CHARS {
        return text.to_string();
    }
    let head: String = text.chars().take(ECHO_CHARS).collect();
    format!("{head}… ({n} characters)")
}

impl CsvTable {
    /// Reads `path`. Rejects unreadable files, text that is not UTF-8 (at its line), files
    /// without data rows, repeated column names and ragged rows.
    pub fn read(path: &Path) -> Result<Self, InputError> {
        let text = super::text::read_text(path).map_err(|e| InputError::Unreadable {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })?;
        Self::parse(path, &text)
    }

    /// Parses CSV `text` as if read from `path` (the path is only used in messages).
    pub fn parse(path: &Path, text: &str) -> Result<Self, InputError> {
        let unreadable = |e: csv::Error| InputError::Unreadable {
            path: path.to_path_buf(),
            reason: e.to_string(),
        };
        let mut reader = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .flexible(true)
            .from_reader(text.as_bytes());
        let headers: Vec<String> = reader
            .headers()
            .map_err(unreadable)?
            .iter()
            .map(str::to_owned)
            .collect();
        for (second, column) in headers.iter().enumerate() {
            if let Some(first) = headers[..second].iter().position(|h| h == column) {
                return Err(InputError::DuplicateColumn {
                    path: path.to_path_buf(),
                    column: shorten(column),
                    first: first + 1,
                    second: second + 1,
                });
            }
        }
        let mut rows = Vec::new();
        for record in reader.records() {
            let record = record.map_err(unreadable)?;
            let line = record.position().map_or(0, |p| p.line());
            if record.len() == 1 && record.get(0) == Some("") {
                continue; // a blank line
            }
            if record.len() != headers.len() {
                return Err(InputError::Ragged {
                    path: path.to_path_buf(),
                    line,
                    expected: headers.len(),
                    found: record.len(),
                });
            }
            rows.push(Row {
                line,
                cells: record.iter().map(str::to_owned).collect(),
            });
        }
        if headers.is_empty() || rows.is_empty() {
            return Err(InputError::Empty {
                path: path.to_path_buf(),
            });
        }
        Ok(Self {
            path: path.to_path_buf(),
            headers,
            rows,
        })
    }

    /// Index of the column named `name` (exact match after trimming).
    pub fn column_index(&self, name: &str) -> Result<usize, InputError> {
        self.headers
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| InputError::MissingColumn {
                path: self.path.clone(),
                column: name.to_owned(),
                available: self.headers.join(", "),
            })
    }

    /// Parses the cell at `row`, column index `col` as a finite `f64`.
    pub fn f64_cell(&self, row: &Row, col: usize) -> Result<f64, InputError> {
        let text = &row.cells[col];
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(InputError::NotNumeric {
                path: self.path.clone(),
                line: row.line,
                column: shorten(&self.headers[col]),
                value: shorten(text),
            }),
        }
    }

    /// The column named `name`, parsed as finite numbers.
    pub fn f64_column(&self, name: &str) -> Result<Vec<f64>, InputError> {
        let col = self.column_index(name)?;
        self.rows.iter().map(|r| self.f64_cell(r, col)).collect()
    }

    /// The column named `name`, parsed as finite numbers that `accept` approves; a rejected
    /// value is reported at its line with `accept`'s reason.
    pub fn f64_column_checked(
        &self,
        name: &str,
        accept: impl Fn(f64) -> Result<(), String>,
    ) -> Result<Vec<f64>, InputError> {
        let col = self.column_index(name)?;
        self.rows
            .iter()
            .map(|r| {
                let v = self.f64_cell(r, col)?;
                accept(v).map_err(|reason| InputError::BadValue {
                    path: self.path.clone(),
                    line: r.line,
                    column: name.to_owned(),
                    reason,
                })?;
                Ok(v)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<CsvTable, InputError> {
        CsvTable::parse(Path::new("runs.csv"), text)
    }

    #[test]
    fn ragged_row_names_file_and_line() {
        let err = parse("a,b\n1,2\n3\n").unwrap_err();
        assert_eq!(
            err.to_string(),
            "runs.csv:3: row has 1 cells but the header has 2"
        );
    }

    #[test]
    fn non_numeric_cell_names_line_and_column() {
        let t = parse("# comment\na,b\n1,2\n3,x4\n").unwrap();
        let err = t.f64_column("b").unwrap_err();
        assert_eq!(
            err.to_string(),
            "runs.csv:4: column 'b': 'x4' is not a finite number"
        );
    }

    #[test]
    fn nan_is_not_a_number_here() {
        let t = parse("a\nNaN\n").unwrap();
        assert!(matches!(
            t.f64_column("a"),
            Err(InputError::NotNumeric { line: 2, .. })
        ));
    }

    #[test]
    fn missing_column_lists_the_header() {
        let t = parse("a,b\n1,2\n").unwrap();
        assert_eq!(
            t.f64_column("c").unwrap_err().to_string(),
            "runs.csv: no column named 'c' (columns: a, b)"
        );
    }

    #[test]
    fn checked_column_reports_reason() {
        let t = parse("d\n0.5\n-0.1\n").unwrap();
        let err = t
            .f64_column_checked("d", |v| {
                if v > 0.0 {
                    Ok(())
                } else {
                    Err(format!("deformation must be positive, got {v}"))
                }
            })
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "runs.csv:3: column 'd': deformation must be positive, got -0.1"
        );
    }

    #[test]
    fn header_only_is_empty() {
        assert!(matches!(parse("a,b\n"), Err(InputError::Empty { .. })));
        // A repeated column is refused, naming both places.
        let e = parse("mass_g,volume_ml,mass_g\n1,2,3\n").unwrap_err();
        assert!(matches!(
            e,
            InputError::DuplicateColumn {
                first: 1,
                second: 3,
                ..
            }
        ));
        assert!(e.to_string().contains("'mass_g' appears twice"));
        // A huge cell is echoed as its start and length.
        let t = CsvTable::parse(
            Path::new("x.csv"),
            &format!("a\n{}x\n", "9".repeat(100_000)),
        )
        .unwrap();
        let msg = t.f64_column("a").unwrap_err().to_string();
        assert!(msg.len() < 200, "{msg}");
        assert!(msg.contains("(100001 characters)"), "{msg}");
        // Bytes that are not UTF-8 are refused at their line.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("latin1.csv");
        std::fs::write(&path, b"name,mass_g\npod,1.5\nnoix \xe9,2\n").unwrap();
        let e = CsvTable::read(&path).unwrap_err().to_string();
        assert!(e.contains("latin1.csv") && e.contains("line 3"), "{e}");
    }
}
