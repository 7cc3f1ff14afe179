//! Why a study file was rejected.
//!
//! Every [`StudyError`] names the file, the key path inside it (TOML dotted form, e.g.
//! `parameters."pod-pod.static_friction".low`), the 1-based line and column where the key or
//! value stands when it is known, and the reason. Loading collects every error it can find
//! before giving up, so one run of the loader lists all the fixes a file needs
//! ([`StudyErrors`]).

use std::fmt;
use std::path::PathBuf;

use super::key_path::KeyPath;

/// One thing wrong with a study file.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyError {
    /// The study file.
    pub file: PathBuf,
    /// Where in the file: the key path (empty for the file as a whole).
    pub key: KeyPath,
    /// 1-based line and column of the key or value, when known.
    pub position: Option<(usize, usize)>,
    /// What is wrong, and where apt what would be accepted.
    pub reason: String,
}

impl fmt::Display for StudyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some((line, column)) = self.position {
            write!(f, ":{line}:{column}")?;
        }
        if self.key.is_empty() {
            write!(f, ": {}", self.reason)
        } else {
            write!(f, ": {}: {}", self.key, self.reason)
        }
    }
}

impl std::error::Error for StudyError {}

/// Every error found in one study file, in file order where positions are known. Never
/// empty when returned by the loader.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyErrors(pub Vec<StudyError>);

impl StudyErrors {
    /// The individual errors.
    pub fn errors(&self) -> &[StudyError] {
        &self.0
    }

    /// Sorts by position (errors without a position keep their order, after the others), so
    /// the user reads them top to bottom.
    pub(crate) fn sorted(mut self) -> Self {
        self.0
            .sort_by_key(|e| e.position.unwrap_or((usize::MAX, usize::MAX)));
        self
    }
}

impl fmt::Display for StudyErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.0.len();
        let noun = if n == 1 { "error" } else { "errors" };
        write!(f, "study rejected before any simulation: {n} {noun}")?;
        for e in &self.0 {
            write!(f, "\n  {e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for StudyErrors {}

/// Writes "`what` rejected before `before`: n errors" and each error on its own line: the
/// message of every input file that is checked whole (variety and field files).
pub(crate) fn write_rejected(
    f: &mut fmt::Formatter<'_>,
    what: &str,
    before: &str,
    errors: &[StudyError],
) -> fmt::Result {
    let n = errors.len();
    let noun = if n == 1 { "error" } else { "errors" };
    write!(f, "{what} rejected before {before}: {n} {noun}")?;
    for e in errors {
        write!(f, "\n  {e}")?;
    }
    Ok(())
}

/// Declares the error type of an input file that is checked whole: a newtype over its
/// [`StudyError`]s in file order, shown by [`write_rejected`] as "`$what` rejected before
/// `$before`: …".
macro_rules! file_errors {
    ($(#[$doc:meta])* $name:ident, $what:literal, $before:literal) => {
        $(#[$doc])*
        #[derive(Debug, Clone, PartialEq)]
        pub struct $name(pub Vec<$crate::study::error::StudyError>);

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                $crate::study::error::write_rejected(f, $what, $before, &self.0)
            }
        }

        impl std::error::Error for $name {}
    };
}
pub(crate) use file_errors;
