//! Gwyddion Simple Field (.gsf): a text header of `Key = value` lines padded with NUL bytes to
//! a multiple of four, then XRes × YRes little-endian f32 heights.

use std::path::Path;

use crate::error::{Error, Result};
use crate::params::fmt_sig;
use crate::surface::formats::metres_per_unit;
use crate::surface::height_map::{HeightMap, size_problem};

/// The first line of a Gwyddion simple field file.
pub(crate) const GSF_MAGIC: &str = "Gwyddion Simple Field 1.0\n";

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
