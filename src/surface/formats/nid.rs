//! Nanosurf easyScan files (`.nid`, `.ezd`): the line `[DataSet]`, an INI-style Latin-1 text
//! header (`[Section]` lines and `key=value` lines), then `#!` and the data blocks back to back.
//!
//! The `[DataSet]` section lists the groups (`GroupCount`, `Gr{i}-Count`) and, for each group
//! `i` and channel `j` the file holds, the section describing it (`Gr{i}-Ch{j}=DataSet-i:j`).
//! A channel section gives `Points` (x), `Lines` (y), `Frame` (e.g. `Scan forward`), the lengths
//! `Dim0Range`, `Dim1Range` in `Dim0Unit`, `Dim1Unit`, the heights' name `Dim2Name`, unit
//! `Dim2Unit` and range `Dim2Range`, and the stored integers (`SaveMode=Binary`, `SaveBits`,
//! `SaveSign`, `SaveOrder=Intel` for little-endian). The blocks follow in the order of the
//! groups and channels. A channel is named `FRAME (DIM2NAME)`; a height is the stored integer ×
//! `Dim2Range` / 2^`SaveBits` and the rows are reversed (the first stored row is the top of the
//! image), as SurfaceTopography reads them (without the `Dim2Min` offset, which does not change
//! a height map's statistics about its mean).

use std::collections::HashMap;
use std::path::Path;

use super::{Channel, ChannelInfo, Num, Unit};
use crate::error::{Error, Result};

/// The first line of the file.
pub(crate) const MAGIC: &[u8] = b"[DataSet]";

/// The channels of a `.nid` file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!(".nid: {m}"));
    let mut sections: HashMap<String, HashMap<String, String>> = HashMap::new();
    let mut current = String::new();
    let mut data_at = None;
    let mut at = 0usize;
    while at < bytes.len() {
        if bytes[at..].starts_with(b"#!") {
            data_at = Some(at + 2);
            break;
        }
        let end = bytes[at..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |p| at + p + 1);
        let line: String = bytes[at..end].iter().map(|&b| b as char).collect();
        at = end;
        let line = line.trim();
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            current = name.to_string();
        } else if let Some((k, v)) = line.split_once('=') {
            sections
                .entry(current.clone())
                .or_default()
                .insert(k.trim().to_string(), v.trim().to_string());
        }
    }
    let data_at = data_at.ok_or_else(|| err("truncated header: no `#!` before the data".into()))?;
    let empty = HashMap::new();
    let global = sections.get("DataSet").unwrap_or(&empty);
    let count = |s: &HashMap<String, String>, k: &str, limit: usize| -> Result<usize> {
        let v = s.get(k).ok_or_else(|| err(format!("the header lacks `{k}`")))?;
        v.parse()
            .ok()
            .filter(|&n| n <= limit)
            .ok_or_else(|| err(format!("`{k}={v}` is not a whole number up to {limit}")))
    };
    let groups = count(global, "GroupCount", 1000)?;
    let mut out = Vec::new();
    let mut offset = 0usize;
    for i in 0..groups {
        for j in 0..count(global, &format!("Gr{i}-Count"), 1000)? {
            let Some(s) = global.get(&format!("Gr{i}-Ch{j}")).and_then(|n| sections.get(n)) else {
                continue;
            };
            let get = |k: &str| {
                s.get(k)
                    .map(String::as_str)
                    .ok_or_else(|| err(format!("channel {i}:{j} lacks `{k}`")))
            };
            let nx = count(s, "Points", super::MAX_POINTS)?;
            let ny = count(s, "Lines", super::MAX_POINTS)?;
            let name = format!("{} ({})", get("Frame")?, get("Dim2Name")?);
            if get("SaveMode")? != "Binary" {
                return Err(err(format!(
                    "{name}: SaveMode `{}` is not read (Binary)",
                    get("SaveMode")?
                )));
            }
            let bits = count(s, "SaveBits", 64)?;
            let signed = get("SaveSign")? == "Signed";
            let num = match (bits, signed) {
                (16, true) => Num::I16,
                (16, false) => Num::U16,
                (32, true) => Num::I32,
                (32, false) => Num::U32,
                _ => {
                    return Err(err(format!(
                        "{name}: {bits}-bit data are not read (16 or 32 bits)"
                    )));
                }
            };
            let le = get("SaveOrder")? == "Intel";
            let float = |k: &str| -> Result<f64> {
                let v = get(k)?;
                v.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| err(format!("{name}: `{k}={v}` is not a finite number")))
            };
            let (lx, ly) = (float("Dim0Range")?, float("Dim1Range")?);
            let (ux, uy) = (Unit::named(get("Dim0Unit")?), Unit::named(get("Dim1Unit")?));
            if ux != uy {
                return Err(err(format!("{name}: lengths in `{}` and `{}`", ux.name, uy.name)));
            }
            let scale = float("Dim2Range")? / 2f64.powi(bits as i32);
            let info = ChannelInfo {
                name: name.clone(),
                nx,
                ny,
                size: Some([lx, ly]),
                xy_unit: ux,
                z_unit: Unit::named(get("Dim2Unit")?),
                periodic: false,
            };
            info.check_grid(path)?;
            let n = nx * ny;
            let start = data_at + offset;
            let size = n * num.size();
            offset += size;
            if start.saturating_add(size) > bytes.len() {
                return Err(super::truncated(
                    path,
                    &format!(".nid channel {name}"),
                    size,
                    bytes.len().saturating_sub(start),
                ));
            }
            let decode = move || -> Result<Vec<f64>> {
                let z = super::numbers(bytes, start, n, num, le, path, ".nid channel")?;
                let mut out = Vec::with_capacity(n);
                for row in z.chunks_exact(nx.max(1)).rev() {
                    out.extend(row.iter().map(|v| v * scale));
                }
                Ok(out)
            };
            out.push(Channel {
                info,
                decode: Box::new(decode),
            });
        }
    }
    Ok(out)
}
