//! Fitting measured force-indentation curves (appendix A.4): the `--fit` command.

use std::path::PathBuf;

/// Options of the `--fit` command (flattened into [`crate::cli::Cli`]).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct FitArgs {
    /// Fit a measured force-indentation cycle (CSV) with --headless.
    #[arg(long, value_name = "FILE.csv")]
    pub fit: Option<PathBuf>,
}
