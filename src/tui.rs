//! The terminal UI (placeholder until the UI lands).

use std::process::ExitCode;

/// Start the terminal UI.
///
/// # Errors
/// Terminal errors.
pub fn run() -> anyhow::Result<ExitCode> {
    anyhow::bail!("the terminal UI is not built yet; use --headless")
}
