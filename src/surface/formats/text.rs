//! Text height maps: a matrix (rows are y, columns x; separated by commas, semicolons or white
//! space) or xyz points (three columns x, y, z on a uniform grid), heights and lengths in metres
//! unless the header says otherwise.
//!
//! Header lines (those before the data, and any line starting with `#`) may carry, as written by
//! this program, Gwyddion's and SPIP's text export and SurfaceTopography's conventions:
//! - `# adhesion height map: nx=… ny=… lx=… ly=… [periodic=1]` (SI units);
//! - `Channel: NAME`, `Width: 10 µm` / `x-length = …`, `Height: 5 µm` / `y-length = …`,
//!   `Value units: nm` / `z-unit = nm`;
//! - `pixel size = 3.7e-7 m`, `height conversion factor (-> m) = 2.9e-8`, `w=75`, `h=305`.
//!
//! `nan`, `bad`, `inf` (any case) are missing points. A single column or row, or two columns
//! whose first increases steadily, is a line scan.

use std::path::Path;

use super::{Channel, ChannelInfo, Unit, metres_per_unit};
use crate::error::{Error, Result};

/// Start of the header comment this program writes.
pub(crate) const CSV_HEADER: &str = "# adhesion height map:";

/// What the header lines say.
#[derive(Debug, Default, Clone)]
struct Meta {
    name: Option<String>,
    /// Grid and lengths [m] of this program's header, and its periodicity.
    own: Option<(usize, usize, f64, f64, bool)>,
    /// Physical sizes [m].
    width: Option<f64>,
    height: Option<f64>,
    /// Pixel size [m].
    pixel: Option<f64>,
    /// Height unit and factor.
    z_unit: Option<String>,
    z_factor: Option<f64>,
    /// Grid points declared (columns, rows).
    w: Option<usize>,
    h: Option<usize>,
}

/// The channel of a text height map.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => std::borrow::Cow::Borrowed(t),
        // Latin-1 headers (µ as 0xB5) of older exports.
        Err(_) => std::borrow::Cow::Owned(bytes.iter().map(|&b| b as char).collect::<String>()),
    };
    let (info, z) = parse(&text, path)?;
    Ok(vec![Channel::ready(info, z)])
}

/// A length with its unit, `10 µm`, in metres.
fn length(v: &str) -> Option<f64> {
    let v = v.trim();
    let split = v
        .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
        .unwrap_or(v.len());
    let x: f64 = v[..split].trim().parse().ok()?;
    let unit = v[split..].trim();
    let f = if unit.is_empty() {
        1.0
    } else {
        metres_per_unit(unit)?
    };
    Some(x * f)
}

fn header_line(line: &str, meta: &mut Meta, path: &Path, ln: usize) -> Result<()> {
    let t = line.trim().trim_start_matches('#').trim();
    if let Some(rest) = line.trim().strip_prefix(CSV_HEADER) {
        meta.own = Some(own_header(rest, path, ln)?);
        return Ok(());
    }
    let bad = |what: &str| Error::data_file(path, ln, format!("header `{t}`: {what}"));
    // `key: value` or `key = value`.
    let Some((k, v)) = t.split_once([':', '=']) else {
        return Ok(());
    };
    let (k, v) = (k.trim(), v.trim());
    match k.to_ascii_lowercase().as_str() {
        "channel" | "kanal" => meta.name = Some(v.to_string()),
        "width" | "breite" | "x-length" => {
            meta.width = Some(length(v).ok_or_else(|| bad("not a length with a unit"))?)
        }
        "height" | "höhe" | "y-length" => {
            meta.height = Some(length(v).ok_or_else(|| bad("not a length with a unit"))?)
        }
        "value units" | "z-unit" => meta.z_unit = Some(v.to_string()),
        "pixel size" => meta.pixel = Some(length(v).ok_or_else(|| bad("not a length with a unit"))?),
        "w" | "y-pixels" => meta.w = Some(v.parse().map_err(|_| bad("not a whole number"))?),
        "h" | "x-pixels" => {
            // `h=305 w=75` on one line.
            let mut it = t.split_whitespace();
            for tok in it.by_ref() {
                if let Some((a, b)) = tok.split_once('=') {
                    let n = b.parse().map_err(|_| bad("not a whole number"))?;
                    match a {
                        "h" | "x-pixels" => meta.h = Some(n),
                        "w" | "y-pixels" => meta.w = Some(n),
                        _ => {}
                    }
                }
            }
        }
        key if key.starts_with("height conversion factor") => {
            let unit = key
                .split_once("->")
                .map(|(_, u)| u.trim_end_matches(')').trim().to_string())
                .unwrap_or_default();
            meta.z_unit = Some(unit);
            meta.z_factor = Some(v.parse().map_err(|_| bad("not a number"))?);
        }
        _ => {}
    }
    Ok(())
}

/// A number, or NaN for a missing-data keyword; `None` for anything else.
fn value(field: &str) -> Option<f64> {
    match field.parse::<f64>() {
        Ok(v) if v.is_finite() => Some(v),
        _ => {
            let l = field.to_ascii_lowercase();
            ["nan", "bad", "inf", "-inf", "+inf", "infinite", "-nan"]
                .contains(&l.as_str())
                .then_some(f64::NAN)
        }
    }
}

/// Parse a text map into its header and heights.
pub(crate) fn parse(text: &str, path: &Path) -> Result<(ChannelInfo, Vec<f64>)> {
    let text = crate::params::normalise_line_ends(text);
    let text = text.trim_start_matches('\u{feff}');
    let mut meta = Meta::default();
    let mut z: Vec<f64> = Vec::new();
    let mut cols = 0usize;
    let mut rows = 0usize;
    let mut fields = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let ln = ln + 1;
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        if t.starts_with('#') {
            header_line(t, &mut meta, path, ln)?;
            continue;
        }
        fields.clear();
        fields.extend(
            t.split(|c: char| c == ',' || c == ';' || c.is_whitespace())
                .filter(|f| !f.is_empty()),
        );
        let parsed: Option<Vec<f64>> = fields.iter().map(|f| value(f)).collect();
        let Some(vals) = parsed else {
            if rows == 0 {
                header_line(t, &mut meta, path, ln)?;
                continue;
            }
            let field = fields.iter().find(|f| value(f).is_none()).unwrap_or(&"");
            return Err(Error::data_file(path, ln, format!("`{field}` is not a number")));
        };
        if rows == 0 {
            cols = vals.len();
        } else if vals.len() != cols {
            return Err(Error::data_file(
                path,
                ln,
                format!("ragged row: {} values, the first row has {cols}", vals.len()),
            ));
        }
        z.extend(vals);
        rows += 1;
        if z.len() > super::MAX_POINTS {
            return Err(Error::data_file(
                path,
                ln,
                format!("more than {} values", super::MAX_POINTS),
            ));
        }
    }
    if rows == 0 {
        return Err(Error::data_file(path, 0, "no height values"));
    }
    let name = meta.name.clone().unwrap_or_else(|| "Default".to_string());
    let metre = Unit::metre();
    // A line scan: one column, one row, or (x, z) pairs with x steadily increasing.
    let xz = cols == 2 && rows >= 3 && {
        let x: Vec<f64> = z.iter().step_by(2).copied().collect();
        x.windows(2).all(|w| w[1] > w[0])
    };
    if cols == 1 || rows == 1 || xz {
        let n = if xz { rows } else { z.len() };
        let info = ChannelInfo {
            name,
            nx: n,
            ny: 1,
            size: None,
            xy_unit: metre.clone(),
            z_unit: metre,
            periodic: false,
        };
        let z = if xz {
            z.iter().skip(1).step_by(2).copied().collect()
        } else {
            z
        };
        return Ok((info, z));
    }
    if cols == 3
        && rows >= 4
        && meta.own.is_none()
        && let Some(grid) = xyz(&z, rows, path, &name)?
    {
        return Ok(grid);
    }
    let (nx, ny) = (cols, rows);
    for (what, declared, found) in [("w", meta.w, nx), ("h", meta.h, ny)] {
        if let Some(d) = declared
            && d != found
        {
            return Err(Error::data_file(
                path,
                0,
                format!("header says {what}={d}, the data has {found}"),
            ));
        }
    }
    let mut periodic = false;
    let mut size = None;
    if let Some((hx, hy, lx, ly, p)) = meta.own {
        if (hx, hy) != (nx, ny) {
            return Err(Error::data_file(
                path,
                0,
                format!("header says {hx} x {hy} points, the data has {nx} x {ny}"),
            ));
        }
        periodic = p;
        size = Some([lx, ly]);
    }
    match (meta.width, meta.height, meta.pixel) {
        (Some(w), Some(h), _) => size = Some([w, h]),
        (Some(w), None, None) => size = Some([w, w * ny as f64 / nx as f64]),
        (_, _, Some(p)) => size = Some([p * nx as f64, p * ny as f64]),
        _ => {}
    }
    let mut z_unit = metre.clone();
    if let Some(u) = &meta.z_unit {
        z_unit = Unit::named(u);
    }
    if let Some(f) = meta.z_factor {
        z.iter_mut().for_each(|v| *v *= f);
    }
    let info = ChannelInfo {
        name,
        nx,
        ny,
        size,
        xy_unit: metre,
        z_unit,
        periodic,
    };
    Ok((info, z))
}

/// Three columns as points of a uniform grid: `None` when the x, y columns are not a grid of
/// distinct points (then the file is a 3-column matrix); an error for a non-uniform grid.
fn xyz(v: &[f64], rows: usize, path: &Path, name: &str) -> Result<Option<(ChannelInfo, Vec<f64>)>> {
    let axis = |k: usize| -> Vec<f64> {
        let mut a: Vec<f64> = v.iter().skip(k).step_by(3).copied().collect();
        a.sort_by(f64::total_cmp);
        a.dedup();
        a
    };
    let (xs, ys) = (axis(0), axis(1));
    if xs.iter().chain(&ys).any(|c| !c.is_finite()) || xs.len() < 2 || ys.len() < 2 {
        return Ok(None);
    }
    let (nx, ny) = (xs.len(), ys.len());
    // A grid: each point once, and at least half the grid present.
    if nx.saturating_mul(ny) > 2 * rows || nx * ny < rows {
        return Ok(None);
    }
    for (axis_name, a) in [("x", &xs), ("y", &ys)] {
        let d = (a[a.len() - 1] - a[0]) / (a.len() - 1) as f64;
        let off = a
            .iter()
            .enumerate()
            .map(|(k, c)| (c - (a[0] + k as f64 * d)).abs())
            .fold(0.0, f64::max);
        if d.is_nan() || d <= 0.0 || off > 1e-6 * d {
            return Err(Error::data_file(
                path,
                0,
                format!(
                    "xyz points on a non-uniform grid in {axis_name} ({} distinct values, spacing \
                     off by up to {} of {}): resample it onto a uniform grid first",
                    a.len(),
                    crate::params::fmt_sig(off),
                    crate::params::fmt_sig(d)
                ),
            ));
        }
    }
    let (dx, dy) = (
        (xs[nx - 1] - xs[0]) / (nx - 1) as f64,
        (ys[ny - 1] - ys[0]) / (ny - 1) as f64,
    );
    let mut z = vec![f64::NAN; nx * ny];
    let mut seen = vec![false; nx * ny];
    for (row, p) in v.chunks_exact(3).enumerate() {
        let i = ((p[0] - xs[0]) / dx).round() as usize;
        let j = ((p[1] - ys[0]) / dy).round() as usize;
        let k = j * nx + i;
        if seen[k] {
            return Err(Error::data_file(
                path,
                row + 1,
                format!("xyz point x = {}, y = {} given twice", p[0], p[1]),
            ));
        }
        seen[k] = true;
        z[k] = p[2];
    }
    let metre = Unit::metre();
    let info = ChannelInfo {
        name: name.to_string(),
        nx,
        ny,
        size: Some([dx * nx as f64, dy * ny as f64]),
        xy_unit: metre.clone(),
        z_unit: metre,
        periodic: false,
    };
    Ok(Some((info, z)))
}

/// This program's header: `nx=… ny=… lx=… ly=… [periodic=1]`.
fn own_header(rest: &str, path: &Path, ln: usize) -> Result<(usize, usize, f64, f64, bool)> {
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
            Ok((nx, ny, lx, ly, periodic))
        }
        _ => Err(Error::data_file(
            path,
            ln,
            "header needs nx, ny and positive lx, ly",
        )),
    }
}
