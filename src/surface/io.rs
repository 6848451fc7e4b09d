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

use super::height_map::{HeightMap, size_problem};
use crate::error::{Error, Result};
use crate::params::fmt_sig;
use crate::render::write_atomic;

/// Magic first line of a Gwyddion simple field file.
const GSF_MAGIC: &str = "Gwyddion Simple Field 1.0\n";
/// Start of the header comment written by [`to_csv`].
const CSV_HEADER: &str = super::formats::CSV_HEADER;

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

/// Parse a Gwyddion simple field file. Lengths in XYUnits and heights in ZUnits (metres when
/// absent) are converted to metres; `Periodic = 1` marks a periodic map.
///
/// # Errors
/// [`Error::DataFile`] for a missing magic line, a missing or bad XRes/YRes/XReal/YReal, an
/// XYUnits or ZUnits that is not a length ([`metres_per_unit`]), a header without its NUL
/// padding, data shorter or longer than XRes x YRes, or non-finite heights.
pub fn parse_gsf(bytes: &[u8], path: &Path) -> Result<HeightMap> {
    if !bytes.starts_with(GSF_MAGIC.as_bytes()) {
        return Err(Error::data_file(
            path,
            1,
            "not a Gwyddion simple field file (bad magic line)",
        ));
    }
    let Some(nul) = bytes.iter().position(|&b| b == 0) else {
        return Err(Error::data_file(
            path,
            0,
            "truncated .gsf: header has no NUL padding",
        ));
    };
    let header = std::str::from_utf8(&bytes[..nul])
        .map_err(|_| Error::data_file(path, 0, "header of .gsf is not UTF-8"))?;
    let mut xres = None;
    let mut yres = None;
    let mut xreal = None;
    let mut yreal = None;
    let mut xy_unit = 1.0;
    let mut z_unit = 1.0;
    let mut periodic = false;
    for (ln, line) in header.lines().enumerate().skip(1) {
        let Some((k, v)) = line.split_once('=') else {
            continue;
        };
        let (k, v) = (k.trim(), v.trim());
        let bad = || Error::data_file(path, ln + 1, format!("{k} = `{v}` is not a valid value"));
        match k {
            "XRes" => xres = Some(v.parse::<usize>().map_err(|_| bad())?),
            "YRes" => yres = Some(v.parse::<usize>().map_err(|_| bad())?),
            "XReal" => xreal = Some(v.parse::<f64>().map_err(|_| bad())?),
            "YReal" => yreal = Some(v.parse::<f64>().map_err(|_| bad())?),
            "XYUnits" | "ZUnits" => {
                let f = metres_per_unit(v).ok_or_else(|| {
                    Error::data_file(
                        path,
                        ln + 1,
                        format!("{k} = `{v}` is not a length unit (m, mm, um, nm, pm or A)"),
                    )
                })?;
                if k == "ZUnits" {
                    z_unit = f;
                } else {
                    xy_unit = f;
                }
            }
            "Periodic" => periodic = v.parse::<u8>().map_err(|_| bad())? != 0,
            _ => {}
        }
    }
    let (Some(nx), Some(ny)) = (xres, yres) else {
        return Err(Error::data_file(path, 0, ".gsf header lacks XRes or YRes"));
    };
    // Gwyddion: XReal, YReal default to 1 (in XYUnits); we require them explicitly.
    let (Some(lx), Some(ly)) = (xreal, yreal) else {
        return Err(Error::data_file(path, 0, ".gsf header lacks XReal or YReal"));
    };
    let start = (nul / 4 + 1) * 4;
    let need = nx
        .checked_mul(ny)
        .and_then(|n| n.checked_mul(4))
        .ok_or_else(|| Error::data_file(path, 0, "XRes x YRes overflows"))?;
    if bytes.len() != start.saturating_add(need) {
        let have = bytes.len().saturating_sub(start);
        let what = if have < need {
            "truncated .gsf"
        } else {
            ".gsf data longer than its header says"
        };
        return Err(Error::data_file(
            path,
            0,
            format!("{what}: {have} bytes of data, XRes x YRes = {nx} x {ny} needs {need}"),
        ));
    }
    let z: Vec<f64> = bytes[start..start + need]
        .chunks_exact(4)
        .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])) * z_unit)
        .collect();
    let (lx_m, ly_m) = (lx * xy_unit, ly * xy_unit);
    let reason = if lx_m > 0.0 && ly_m > 0.0 && lx_m.is_finite() && ly_m.is_finite() {
        size_problem(nx, ny, lx_m, ly_m)
    } else {
        Some("the lengths must be positive and finite in metres".to_string())
    };
    if let Some(reason) = reason {
        return Err(Error::data_file(
            path,
            0,
            format!(
                "XReal = {}, YReal = {} (XYUnits): {reason}",
                fmt_sig(lx),
                fmt_sig(ly)
            ),
        ));
    }
    let mut map =
        HeightMap::new(nx, ny, lx_m, ly_m, z).map_err(|e| Error::data_file(path, 0, e.to_string()))?;
    map.periodic = periodic;
    Ok(map)
}

/// Read a height map, the format recognised by content ([`super::formats`]: text matrix or xyz,
/// `.gsf`, `.gwy`, `.x3p`, `.sdf`, `.sur`, `.ibw`, Nanoscope). `pixel_size` [m] is needed for a
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
