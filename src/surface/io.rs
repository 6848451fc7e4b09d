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
const CSV_HEADER: &str = "# adhesion height map:";

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

/// Parse a text matrix. `pixel_size` [m] (square pixels) overrides the header comment; one of
/// the two must be present.
///
/// # Errors
/// [`Error::DataFile`] naming the line for a ragged row, a non-number, a non-finite height, an
/// empty file, a missing or non-positive pixel size.
pub fn parse_csv(text: &str, path: &Path, pixel_size: Option<f64>) -> Result<HeightMap> {
    let mut header: Option<Header> = None;
    let mut z = Vec::new();
    let mut nx = 0usize;
    let mut ny = 0usize;
    let text = crate::params::normalise_line_ends(text);
    for (ln, line) in text.lines().enumerate() {
        let ln = ln + 1;
        let t = line.trim();
        if let Some(rest) = t.strip_prefix(CSV_HEADER) {
            header = Some(parse_header(rest, path, ln)?);
            continue;
        }
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let mut count = 0;
        for field in t.split(|c: char| c == ',' || c == ';' || c.is_whitespace()) {
            if field.is_empty() {
                continue;
            }
            let v: f64 = field
                .parse()
                .map_err(|_| Error::data_file(path, ln, format!("`{field}` is not a number")))?;
            if !v.is_finite() {
                return Err(Error::data_file(
                    path,
                    ln,
                    format!("height `{field}` is not finite"),
                ));
            }
            z.push(v);
            count += 1;
        }
        if ny == 0 {
            nx = count;
        } else if count != nx {
            return Err(Error::data_file(
                path,
                ln,
                format!("ragged row: {count} values, the first row has {nx}"),
            ));
        }
        ny += 1;
    }
    if ny == 0 {
        return Err(Error::data_file(path, 0, "no height values"));
    }
    if nx < 2 || ny < 2 {
        return Err(Error::data_file(
            path,
            0,
            format!("a height map needs at least 2 x 2 values, found {nx} x {ny}"),
        ));
    }
    // The header's periodicity holds only for the grid it describes.
    let periodic = header.is_some_and(|h| h.periodic && (h.nx, h.ny) == (nx, ny));
    let (lx, ly) = match (pixel_size, header) {
        (Some(p), _) => {
            if !(p > 0.0 && p.is_finite()) {
                return Err(Error::data_file(
                    path,
                    0,
                    format!("pixel size {} must be positive and finite", fmt_sig(p)),
                ));
            }
            (p * nx as f64, p * ny as f64)
        }
        (
            None,
            Some(Header {
                nx: hx,
                ny: hy,
                lx,
                ly,
                ..
            }),
        ) => {
            if (hx, hy) != (nx, ny) {
                return Err(Error::data_file(
                    path,
                    0,
                    format!("header says {hx} x {hy} points, the data has {nx} x {ny}"),
                ));
            }
            (lx, ly)
        }
        (None, None) => {
            return Err(Error::data_file(
                path,
                0,
                "no pixel size: give --pixel-size METRES for a plain text matrix",
            ));
        }
    };
    if let Some(reason) = size_problem(nx, ny, lx, ly) {
        let field = match pixel_size {
            Some(p) => format!("pixel size {}", fmt_sig(p)),
            None => format!("header lx = {}, ly = {}", fmt_sig(lx), fmt_sig(ly)),
        };
        return Err(Error::data_file(path, 0, format!("{field}: {reason}")));
    }
    let mut map = HeightMap::new(nx, ny, lx, ly, z).map_err(|e| Error::data_file(path, 0, e.to_string()))?;
    map.periodic = periodic;
    Ok(map)
}

/// The header comment of a text map.
#[derive(Debug, Clone, Copy)]
struct Header {
    nx: usize,
    ny: usize,
    lx: f64,
    ly: f64,
    periodic: bool,
}

fn parse_header(rest: &str, path: &Path, ln: usize) -> Result<Header> {
    let mut n = [None; 2];
    let mut l = [None; 2];
    let mut periodic = false;
    for tok in rest.split_whitespace() {
        if let Some((k, v)) = tok.split_once('=') {
            let int = || {
                v.parse::<usize>().map_err(|_| {
                    Error::data_file(path, ln, format!("header value `{tok}` is not a whole number"))
                })
            };
            let real = || {
                v.parse::<f64>()
                    .map_err(|_| Error::data_file(path, ln, format!("header value `{tok}` is not a number")))
            };
            match k {
                "nx" => n[0] = Some(int()?),
                "ny" => n[1] = Some(int()?),
                "lx" => l[0] = Some(real()?),
                "ly" => l[1] = Some(real()?),
                "periodic" => periodic = int()? != 0,
                _ => {}
            }
        }
    }
    match (n, l) {
        ([Some(nx), Some(ny)], [Some(lx), Some(ly)])
            if lx > 0.0 && ly > 0.0 && lx.is_finite() && ly.is_finite() =>
        {
            Ok(Header {
                nx,
                ny,
                lx,
                ly,
                periodic,
            })
        }
        _ => Err(Error::data_file(
            path,
            ln,
            "header needs nx, ny and positive lx, ly",
        )),
    }
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

/// Metres per unit of a length unit as written in a `.gsf` header (`m` with an SI prefix, or
/// ångström); `None` for anything else.
pub fn metres_per_unit(unit: &str) -> Option<f64> {
    Some(match unit {
        "m" => 1.0,
        "mm" => 1e-3,
        "um" | "µm" | "μm" => 1e-6,
        "nm" => 1e-9,
        "pm" => 1e-12,
        "A" | "Å" | "Å" => 1e-10,
        _ => return None,
    })
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

/// Read a height map, the format by extension (`.gsf`, else text). `pixel_size` [m] is needed
/// for a text matrix without the header comment and overrides it; ignored for `.gsf`.
///
/// # Errors
/// [`Error::DataFile`] as [`parse_csv`] and [`parse_gsf`], or when the file cannot be read.
pub fn read_height_map(path: &Path, pixel_size: Option<f64>) -> Result<HeightMap> {
    let bytes = crate::input::read_input(path, crate::input::limit())?;
    match MapFormat::of(path) {
        MapFormat::Gsf => parse_gsf(&bytes, path),
        MapFormat::Csv => {
            let text =
                std::str::from_utf8(&bytes).map_err(|_| Error::data_file(path, 0, "not a text file"))?;
            parse_csv(text, path, pixel_size)
        }
    }
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
