//! Agilent / Molecular Imaging PicoView files (`.mi`): a text header of lines with a key in a
//! fixed column of 14 characters and the value after it, up to the line whose key is `data`;
//! then the buffers (channels) back to back, each `yPixels` rows of `xPixels` little-endian
//! integers (`data BINARY`: int16, `BINARY_32`: int32).
//!
//! Header keys used: `fileType` (`Image`; spectroscopy files are refused), `xPixels`, `yPixels`,
//! `xLength`, `yLength` (metres), `scanUp` (`TRUE`: the rows are stored from the bottom and are
//! reversed), and for each buffer, opened by a `bufferLabel` line, `bufferRange` and
//! `bufferUnit`. A height is the stored integer / 2^15 (int16) or / 2^31 (int32) × `bufferRange`
//! in `bufferUnit`, as SurfaceTopography reads it. Indented lines are continuation lines and are
//! skipped.

use std::path::Path;

use super::{Channel, ChannelInfo, Num, Unit};
use crate::error::{Error, Result};

/// Width of the key column.
const KEY_WIDTH: usize = 14;

/// The buffers of an `.mi` file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!(".mi: {m}"));
    let mut global: Vec<(String, String)> = Vec::new();
    let mut buffers: Vec<Vec<(String, String)>> = Vec::new();
    let mut data: Option<(String, usize)> = None;
    let mut at = 0usize;
    while at < bytes.len() {
        let end = bytes[at..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |p| at + p + 1);
        let raw = &bytes[at..end];
        at = end;
        let line: String = raw.iter().map(|&b| b as char).collect();
        let line = line.trim_end_matches(['\r', '\n']);
        if line.starts_with(' ') || line.trim().is_empty() {
            continue;
        }
        let split = line.char_indices().nth(KEY_WIDTH).map_or(line.len(), |(k, _)| k);
        let (key, value) = (line[..split].trim(), line[split..].trim());
        if key == "data" {
            data = Some((value.to_string(), at));
            break;
        }
        if key == "bufferLabel" {
            buffers.push(Vec::new());
        }
        match buffers.last_mut() {
            Some(b) => b.push((key.to_string(), value.to_string())),
            None => global.push((key.to_string(), value.to_string())),
        }
    }
    let get =
        |list: &[(String, String)], k: &str| list.iter().find(|(key, _)| key == k).map(|(_, v)| v.clone());
    match get(&global, "fileType").as_deref() {
        Some("Image") => {}
        Some("Spectroscopy") => {
            return Err(err("spectroscopy files are not height maps".into()));
        }
        other => {
            return Err(err(format!(
                "`fileType` is {}, not `Image`",
                other.map_or("missing".to_string(), |v| format!("`{v}`"))
            )));
        }
    }
    let Some((encoding, data_at)) = data else {
        return Err(err("truncated header: no `data` line".into()));
    };
    let (num, range) = match encoding.as_str() {
        "BINARY" => (Num::I16, 32768.0),
        "BINARY_32" => (Num::I32, 2_147_483_648.0),
        other => {
            return Err(err(format!(
                "data encoding `{other}` is not read (BINARY or BINARY_32)"
            )));
        }
    };
    let int = |k: &str| -> Result<usize> {
        let v = get(&global, k).ok_or_else(|| err(format!("the header lacks `{k}`")))?;
        v.parse::<usize>()
            .ok()
            .filter(|&n| n > 0)
            .ok_or_else(|| err(format!("`{k} {v}` is not a positive whole number")))
    };
    let float = |list: &[(String, String)], k: &str| -> Result<f64> {
        let v = get(list, k).ok_or_else(|| err(format!("the header lacks `{k}`")))?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| err(format!("`{k} {v}` is not a finite number")))
    };
    let nx = int("xPixels")?;
    let ny = int("yPixels")?;
    let lx = float(&global, "xLength")?;
    let ly = float(&global, "yLength")?;
    let flip = get(&global, "scanUp").as_deref() == Some("TRUE");
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n <= super::MAX_POINTS)
        .ok_or_else(|| {
            err(format!(
                "the header claims {nx} x {ny} points, above the limit of {}",
                super::MAX_POINTS
            ))
        })?;
    let stride = n * num.size();
    let mut out = Vec::new();
    for (k, b) in buffers.iter().enumerate() {
        let name = get(b, "bufferLabel").unwrap_or_default();
        let scale = float(b, "bufferRange")? / range;
        let unit = get(b, "bufferUnit").unwrap_or_default();
        let start = data_at.saturating_add(k.saturating_mul(stride));
        if start.saturating_add(stride) > bytes.len() {
            return Err(super::truncated(
                path,
                &format!(".mi buffer {} ({name})", k + 1),
                stride,
                bytes.len().saturating_sub(start),
            ));
        }
        let info = ChannelInfo {
            name: if name.is_empty() {
                format!("Buffer {}", k + 1)
            } else {
                name
            },
            nx,
            ny,
            size: Some([lx, ly]),
            xy_unit: Unit::metre(),
            z_unit: Unit::named(&unit),
            periodic: false,
        };
        let decode = move || -> Result<Vec<f64>> {
            let z = super::numbers(bytes, start, n, num, true, path, ".mi buffer")?;
            let mut out = Vec::with_capacity(n);
            for j in 0..ny {
                let row = if flip { ny - 1 - j } else { j };
                out.extend(z[row * nx..(row + 1) * nx].iter().map(|v| v * scale));
            }
            Ok(out)
        };
        out.push(Channel {
            info,
            decode: Box::new(decode),
        });
    }
    Ok(out)
}
