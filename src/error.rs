//! The library's error type.
//!
//! One `thiserror` enum for the whole library. Variants carry numbers and names, not
//! pre-formatted strings; messages are lowercase, one line, with no final period, so that the
//! command line can print them as they are and the terminal UI can show them in its status bar.

use std::path::PathBuf;

/// Everything that can go wrong in the library.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter value outside its valid range (after parsing succeeded).
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name as the user writes it.
        name: String,
        /// The offending value, as text.
        value: String,
        /// Why it is invalid, e.g. "must be positive".
        reason: String,
    },
    /// A parameter name the scene does not have.
    #[error("unknown parameter `{name}` for scene {scene}{hint}")]
    UnknownParameter {
        /// The name given.
        name: String,
        /// The scene id.
        scene: String,
        /// A suggestion (" (did you mean `x`?)") or empty.
        hint: String,
    },
    /// A value that could not be parsed as the parameter's type.
    #[error("parameter `{name}` expects {expected}, got `{text}`")]
    ParseParameter {
        /// Parameter name.
        name: String,
        /// What was expected ("a number", "true or false", "one of exact, empirical").
        expected: String,
        /// The text given.
        text: String,
    },
    /// A scene id that is not in the registry.
    #[error("unknown scene `{id}`{hint}; `adhesion --list` shows the scenes")]
    UnknownScene {
        /// The id given.
        id: String,
        /// A suggestion or empty.
        hint: String,
    },
    /// A preset file that is not valid TOML or does not fit the scene.
    #[error("preset {}: {message}", path.display())]
    Preset {
        /// The preset file.
        path: PathBuf,
        /// What is wrong, one line.
        message: String,
    },
    /// An input data file (force curve, height map, profile) that cannot be read.
    #[error("{}:{line}: {message}", path.display())]
    DataFile {
        /// The file.
        path: PathBuf,
        /// 1-based line number (0 when the problem is not tied to a line).
        line: usize,
        /// What is wrong, one line.
        message: String,
    },
    /// A bracketing root finder was given an interval without a sign change.
    #[error("no sign change on [{}, {}]", crate::text::fmt_sig(*lo), crate::text::fmt_sig(*hi))]
    NoBracket {
        /// Lower end.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
    /// An iteration did not converge.
    #[error("{method} did not converge in {iterations} iterations (residual {residual:.3e})")]
    NoConvergence {
        /// Which method.
        method: &'static str,
        /// Iterations done.
        iterations: usize,
        /// Last residual.
        residual: f64,
    },
    /// A regime the model cannot resolve in floating point.
    #[error("{model}: {reason}")]
    Unresolvable {
        /// The model.
        model: &'static str,
        /// Why, with the numbers involved.
        reason: String,
    },
    /// A scene's run failed inside its model, or gave non-finite results, at the parameters
    /// the user changed: the message names them (with their defaults) before the model's reason.
    #[error("{scene} with {at}: {cause}")]
    AtParameters {
        /// The scene id.
        scene: &'static str,
        /// The changed parameters as `` `name` = value (default d) ``, most changed first.
        at: String,
        /// The model's reason, with its numbers shortened to 6 significant digits.
        cause: String,
    },
    /// The run was cancelled through its [`crate::job::Job`].
    #[error("cancelled")]
    Cancelled,
    /// A rendering backend failed.
    #[error("rendering {format}: {message}")]
    Render {
        /// "png", "svg", ...
        format: &'static str,
        /// Backend message.
        message: String,
    },
    /// Command-line options that do not belong together or that the command does not use.
    #[error("{0}")]
    Usage(String),
    /// A file operation that failed, with the file and what was being done.
    #[error("{operation} {}: {cause}", path.display())]
    File {
        /// What was being done: "writing", "reading", "creating the folder", ...
        operation: &'static str,
        /// The file or folder.
        path: PathBuf,
        /// The system's error (not a `source`: its text is already in the message).
        cause: std::io::Error,
    },
    /// File-system error.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(name: impl Into<String>, value: impl ToString, reason: impl Into<String>) -> Self {
        Error::InvalidParameter {
            name: crate::text::escape_for_message(&name.into(), 80),
            value: crate::text::echo_value(&value.to_string()),
            reason: reason.into(),
        }
    }

    /// `Ok` when `v` is finite and positive, otherwise [`Error::InvalidParameter`] naming
    /// `name` with "must be positive".
    pub fn require_positive(name: &str, v: f64) -> Result<()> {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(Error::invalid(name, v, "must be positive"))
        }
    }

    /// A closure turning an I/O error into [`Error::File`] for `operation` on `path`.
    pub fn file(operation: &'static str, path: &std::path::Path) -> impl FnOnce(std::io::Error) -> Self {
        let path = path.to_path_buf();
        move |cause| Error::File {
            operation,
            path,
            cause,
        }
    }

    /// Shorthand for [`Error::DataFile`].
    pub fn data_file(path: impl Into<PathBuf>, line: usize, message: impl Into<String>) -> Self {
        Error::DataFile {
            path: path.into(),
            line,
            message: message.into(),
        }
    }
}

/// Result alias used throughout the library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A suggestion " (did you mean `x`?)" for a misspelled name, or an empty string.
///
/// Uses the Levenshtein distance; a candidate is suggested when it is within a third of the
/// name's length (at least 2 edits).
pub fn did_you_mean<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> String {
    let limit = (name.chars().count() / 3).max(2);
    candidates
        .into_iter()
        .map(|c| (levenshtein(name, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| format!(" (did you mean `{c}`?)"))
        .unwrap_or_default()
}

fn levenshtein(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for (i, ca) in a.chars().enumerate() {
        cur[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cost = usize::from(ca != *cb);
            cur[j + 1] = (prev[j + 1] + 1).min(cur[j] + 1).min(prev[j] + cost);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestion_for_a_close_misspelling_only() {
        assert_eq!(
            did_you_mean("radus", ["radius", "modulus"]),
            " (did you mean `radius`?)"
        );
        assert_eq!(did_you_mean("zzzzzz", ["radius", "modulus"]), "");
    }
}
