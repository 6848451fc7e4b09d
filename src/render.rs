//! Renderers of a [`crate::figure::Figure`]: PNG and SVG through plotters ([`plot`]), CSV and
//! JSON ([`data`]), and a ratatui chart for the terminal ([`terminal`]). All file output is
//! atomic ([`write_atomic`]): a temporary file in the target folder, renamed on success.

pub mod axes;
pub mod data;
pub mod plot;
pub mod terminal;

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::Result;

/// Export formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Format {
    /// Raster figure.
    Png,
    /// Vector figure.
    Svg,
    /// Long-form data `panel,series,style,x,y`.
    Csv,
    /// Parameters, results, fields, version, run time.
    Json,
}

impl Format {
    /// All formats.
    pub const ALL: [Format; 4] = [Format::Png, Format::Svg, Format::Csv, Format::Json];

    /// File extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Svg => "svg",
            Format::Csv => "csv",
            Format::Json => "json",
        }
    }

    /// Parse one name (`png`, `svg`, `csv`, `json`).
    pub fn parse(name: &str) -> Option<Format> {
        Format::ALL
            .into_iter()
            .find(|f| f.extension() == name.trim().to_ascii_lowercase())
    }
}

/// A temporary path next to `path` (same folder, so the rename is atomic), keeping the
/// extension (the PNG encoder chooses its format by it).
pub fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = format!(".{name}.tmp-{}.{ext}", std::process::id());
    path.with_file_name(tmp)
}

/// Write `bytes` to `path` atomically: a temporary file in the same folder, flushed, then
/// renamed. On failure the temporary file is removed and `path` is untouched.
///
/// # Errors
/// File-system errors.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = temporary_path(path);
    let result = (|| -> std::io::Result<()> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    Ok(result?)
}
