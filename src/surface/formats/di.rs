//! Bruker / Digital Instruments Nanoscope files (`.di`, `.spm`, `.001`…): a text header of
//! `\*Section` lines and `\key: value` lines (Latin-1, up to `\*File list end`), then the images.
//!
//! Each `\*Ciao image list` section is one channel: `@2:Image Data: S [NAME] "…"`,
//! `Samps/line` (x), `Number of lines` (y), `Scan Size: SX SY UNIT` (`~m` is µm), `Data offset`,
//! `Data length`, `Bytes/pixel` (2, or 4 rescaled by 1/65536), and `@2:Z scale: V [QUANTITY]
//! (… V/LSB) HARD V`. The height of a stored integer is integer × HARD/65536 × the scanner's
//! soft scale `@QUANTITY: V SOFT nm/V` (from `\*Scanner list` or `\*Ciao scan list`), as
//! SurfaceTopography reads it; a channel whose soft scale is not a length per volt has no length
//! unit. Rows are stored from the bottom of the image and are reversed.

use std::collections::HashMap;
use std::path::Path;

use super::{Channel, ChannelInfo, Num, Unit};
use crate::error::{Error, Result};

/// The images of a Nanoscope file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!("Nanoscope: {m}"));
    let mut sections: Vec<(String, HashMap<String, String>)> = Vec::new();
    let mut ended = false;
    for raw in bytes.split(|&b| b == b'\n') {
        if raw.contains(&0) {
            break;
        }
        let line: String = raw.iter().map(|&b| b as char).collect();
        let line = line.trim();
        if line.eq_ignore_ascii_case("\\*File list end") {
            ended = true;
            break;
        }
        if let Some(name) = line.strip_prefix("\\*") {
            sections.push((name.to_ascii_lowercase(), HashMap::new()));
        } else if let Some(kv) = line.strip_prefix('\\') {
            let (k, v) = kv.split_once(": ").unwrap_or((kv.trim_end_matches(':'), ""));
            if let Some((_, map)) = sections.last_mut() {
                map.insert(k.to_ascii_lowercase(), v.trim().to_string());
            }
        }
    }
    if !ended {
        return Err(err("truncated header: no `\\*File list end` line".into()));
    }
    let mut scanner: HashMap<String, String> = HashMap::new();
    for (name, map) in &sections {
        if name == "scanner list" || name == "ciao scan list" {
            scanner.extend(map.iter().map(|(k, v)| (k.clone(), v.clone())));
        }
    }
    let mut out = Vec::new();
    for (name, p) in &sections {
        if name != "ciao image list" {
            continue;
        }
        let get = |k: &str| p.get(k).ok_or_else(|| err(format!("an image lacks `{k}`")));
        let int = |k: &str| -> Result<usize> {
            let v = get(k)?;
            v.trim()
                .parse()
                .map_err(|_| err(format!("`{k}: {v}` is not a whole number")))
        };
        let image = get("@2:image data")?;
        let channel = image
            .split_once('[')
            .and_then(|(_, r)| r.split_once(']'))
            .map(|(n, _)| n.to_string())
            .ok_or_else(|| err(format!("`@2:Image Data: {image}` names no channel")))?;
        let nx = int("samps/line")?;
        let ny = int("number of lines")?;
        let offset = int("data offset")?;
        let length = int("data length")?;
        let elsize = int("bytes/pixel")?;
        let (num, binary) = match elsize {
            2 => (Num::I16, 1.0),
            4 => (Num::I32, 1.0 / 65536.0),
            e => {
                return Err(err(format!(
                    "{channel}: {e} bytes per pixel are not read (2 or 4)"
                )));
            }
        };
        let need = nx
            .checked_mul(ny)
            .and_then(|n| n.checked_mul(elsize))
            .unwrap_or(usize::MAX);
        if need > length {
            return Err(err(format!(
                "{channel}: {nx} x {ny} points of {elsize} bytes need {need}, the data length is {length}"
            )));
        }
        if offset.checked_add(need).is_none_or(|e| e > bytes.len()) {
            return Err(super::truncated(
                path,
                &format!("Nanoscope image {channel} at byte {offset}"),
                need,
                bytes.len().saturating_sub(offset),
            ));
        }
        let scan = get("scan size")?;
        let mut t = scan.split_whitespace();
        let (sx, sy, su) = (t.next(), t.next(), t.next().unwrap_or(""));
        let num_of = |s: Option<&str>| s.and_then(|s| s.parse::<f64>().ok());
        let (Some(sx), Some(sy)) = (num_of(sx), num_of(sy)) else {
            return Err(err(format!(
                "{channel}: `Scan Size: {scan}` is not two lengths and a unit"
            )));
        };
        let xy_unit = Unit::named(if su == "~m" { "µm" } else { su });
        let zs = get("@2:z scale")?;
        let (quantity, hard) =
            z_scale(zs).ok_or_else(|| err(format!("{channel}: `@2:Z scale: {zs}` is not read")))?;
        let (soft, z_unit) = match &quantity {
            None => (1.0, Unit::named("")),
            Some(q) => {
                let s = scanner
                    .get(&format!("@{}", q.to_ascii_lowercase()))
                    .ok_or_else(|| err(format!("{channel}: no scanner entry `@{q}` for its z scale")))?;
                let mut t = s.split_whitespace();
                let soft = (t.next() == Some("V"))
                    .then(|| t.next().and_then(|v| v.parse::<f64>().ok()))
                    .flatten()
                    .ok_or_else(|| err(format!("{channel}: scanner entry `@{q}: {s}` is not read")))?;
                match t.next().and_then(|u| u.split_once('/')) {
                    Some((hu, "V")) => (soft, Unit::named(if hu == "~m" { "µm" } else { hu })),
                    Some((hu, _)) => (
                        soft,
                        Unit {
                            name: hu.to_string(),
                            metres: None,
                        },
                    ),
                    None => (soft, Unit::named("")),
                }
            }
        };
        let scale = hard / 65536.0 * soft * binary;
        let info = ChannelInfo {
            name: channel,
            nx,
            ny,
            size: Some([sx, sy]),
            xy_unit,
            z_unit,
            periodic: false,
        };
        let decode = move || -> Result<Vec<f64>> {
            let raw = super::numbers(bytes, offset, nx * ny, num, true, path, "Nanoscope image data")?;
            let mut z = Vec::with_capacity(nx * ny);
            for j in (0..ny).rev() {
                z.extend(raw[j * nx..(j + 1) * nx].iter().map(|v| v * scale));
            }
            Ok(z)
        };
        out.push(Channel {
            info,
            decode: Box::new(decode),
        });
    }
    Ok(out)
}

/// `V [QUANTITY] (0.000375 V/LSB) 24.57563 V` → (QUANTITY, 24.57563).
fn z_scale(s: &str) -> Option<(Option<String>, f64)> {
    let s = s.trim().strip_prefix('V')?.trim();
    let (quantity, rest) = match s.strip_prefix('[') {
        Some(r) => {
            let (q, rest) = r.split_once(']')?;
            (Some(q.to_string()), rest)
        }
        None => (None, s),
    };
    let after = rest.split_once(')').map_or(rest, |(_, a)| a);
    let hard = after.split_whitespace().next()?.parse::<f64>().ok()?;
    Some((quantity, hard))
}
