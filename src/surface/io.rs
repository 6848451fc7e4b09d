//! Import and export of height maps: a plain text matrix (CSV or whitespace separated; rows are
//! y, columns x; heights in metres) and Gwyddion's simple field format (`.gsf`).
//!
//! A text matrix carries no grid size, so the pixel size comes from the command line, unless the
//! file starts with the comment this module writes,
//! `# adhesion height map: nx=… ny=… lx=… ly=… [periodic=1] (SI units, rows are y)`; a `.gsf`
//! written here carries `Periodic = 1` for a periodic map. Imported maps are non-periodic
//! (finite patches, analysed with a window) unless the file says so. Written values use
//! Rust's shortest round-trip form, so CSV export and import are lossless. GSF stores 32-bit
//! floats: a GSF round trip is exact to f32 precision.

use std::path::Path;

use super::height_map::HeightMap;
use crate::error::Result;
use crate::render::write_atomic;

use super::formats::gsf::GSF_MAGIC;
/// Magic first line of a Gwyddion simple field file.
pub use super::formats::gsf::parse_gsf;
/// Start of the header comment written by [`to_csv`].
const CSV_HEADER: &str = super::formats::text::CSV_HEADER;

/// File formats of height maps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapFormat {
    /// Text matrix.
    Csv,
    /// Gwyddion simple field.
    Gsf,
}

impl MapFormat {
    /// The format of a path by its extension: `.gsf` is GSF, anything else text.
    pub fn of(path: &Path) -> MapFormat {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("gsf") => MapFormat::Gsf,
            _ => MapFormat::Csv,
        }
    }
}

/// The map as a text matrix with the header comment.
pub fn to_csv(map: &HeightMap) -> String {
    let mut s = format!(
        "{CSV_HEADER} nx={} ny={} lx={:e} ly={:e}{} (SI units, rows are y)\n",
        map.nx,
        map.ny,
        map.lx,
        map.ly,
        if map.periodic { " periodic=1" } else { "" }
    );
    for row in map.z.chunks(map.nx) {
        let line: Vec<String> = row.iter().map(|v| format!("{v:e}")).collect();
        s.push_str(&line.join(","));
        s.push('\n');
    }
    s
}

/// Parse a text height map ([`super::formats`]' text reader: a matrix, or xyz points on a
/// uniform grid). `pixel_size` [m] (square pixels) overrides the header's lengths; one of the two
/// must be present.
///
/// # Errors
/// [`Error::DataFile`] naming the line for a ragged row, a non-number; naming the file for an
/// empty file, a line scan, missing points, a missing or non-positive pixel size.
pub fn parse_csv(text: &str, path: &Path, pixel_size: Option<f64>) -> Result<HeightMap> {
    let (info, z) = super::formats::text_map(text, path)?;
    let m = super::formats::Measured {
        format: super::formats::Format::Text.name(),
        info,
        z,
    };
    m.into_height_map(path, pixel_size, true)
}

/// The map in Gwyddion simple field format (little-endian f32 heights after a text header
/// padded with NUL bytes to a multiple of 4).
pub fn to_gsf(map: &HeightMap) -> Vec<u8> {
    let mut h = format!(
        "{GSF_MAGIC}XRes = {}\nYRes = {}\nXReal = {:e}\nYReal = {:e}\nXYUnits = m\nZUnits = m\nTitle = adhesion height map\n{}",
        map.nx,
        map.ny,
        map.lx,
        map.ly,
        if map.periodic { "Periodic = 1\n" } else { "" }
    )
    .into_bytes();
    let pad = 4 - h.len() % 4;
    h.extend(std::iter::repeat_n(0u8, pad));
    h.reserve(4 * map.z.len());
    for v in &map.z {
        h.extend_from_slice(&(*v as f32).to_le_bytes());
    }
    h
}

/// Metres per unit of a length unit as written in a header ([`super::formats::metres_per_unit`]).
pub fn metres_per_unit(unit: &str) -> Option<f64> {
    super::formats::metres_per_unit(unit)
}

/// Read a height map, the format recognised by content ([`super::formats`]: text matrix or xyz,
/// `.gsf`, `.gwy`, `.x3p`, `.sdf`, `.sur`, `.ibw`, Nanoscope, `.mi`, `.al3d`, `.nid`, `.plu`,
/// MetroPro `.dat`, `.opd`, `.opdx`, Mountains `.mnt`). `pixel_size` [m] is needed for a
/// text matrix without lengths in its header and overrides them; ignored for the other formats.
/// `FILE#CHANNEL` (when no file of that whole name exists) reads the channel named CHANNEL; else
/// the first height channel.
///
/// # Errors
/// [`Error::DataFile`] naming the file and what is wrong with it, or when it cannot be read.
pub fn read_height_map(path: &Path, pixel_size: Option<f64>) -> Result<HeightMap> {
    let (file, channel) = super::formats::split_channel(path);
    read_height_map_channel(&file, pixel_size, channel.as_deref())
}

/// [`read_height_map`] of the channel named `channel` (the first height channel when `None`).
///
/// # Errors
/// As [`read_height_map`]; a channel the file lacks is an error listing those it holds.
pub fn read_height_map_channel(
    path: &Path,
    pixel_size: Option<f64>,
    channel: Option<&str>,
) -> Result<HeightMap> {
    let m = super::formats::read_measured(path, channel)?;
    let text = m.format == super::formats::Format::Text.name();
    m.into_height_map(path, pixel_size, text)
}

/// Write a height map atomically, the format by extension (`.gsf`, else text matrix).
///
/// # Errors
/// File-system errors.
pub fn write_height_map(map: &HeightMap, path: &Path) -> Result<()> {
    match MapFormat::of(path) {
        MapFormat::Gsf => write_atomic(path, &to_gsf(map)),
        MapFormat::Csv => write_atomic(path, to_csv(map).as_bytes()),
    }
}
