//! ISO 25178-71 surface data files (`.sdf`), text (`aISO-1.0`) and binary (`bISO-1.0`).
//!
//! Header: `NumPoints` (x), `NumProfiles` (y), `Xscale`, `Yscale` (spacing [m]), `Zscale`
//! (metres per stored unit), `DataType` (5 int16, 6 int32, 7 double). The text variant's header
//! ends at a `*` line, its data section at the next; the binary header is 81 packed bytes
//! (little-endian). Missing points: `BAD` in text, the type's minimum for integers, NaN for
//! doubles.

use std::path::Path;

use super::{Bytes, Channel, ChannelInfo, Num, numbers};
use crate::error::{Error, Result};

/// Size of the binary header.
const BINARY_HEADER: usize = 81;

/// The channel of an `.sdf` file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, m);
    if bytes.starts_with(b"bISO-1.0") {
        let r = Bytes { b: bytes, le: true };
        if bytes.len() < BINARY_HEADER {
            return Err(super::truncated(
                path,
                "binary .sdf header",
                BINARY_HEADER,
                bytes.len(),
            ));
        }
        let nx = usize::from(r.u16(42).unwrap_or(0));
        let ny = usize::from(r.u16(44).unwrap_or(0));
        let sx = r.f64(46).unwrap_or(f64::NAN);
        let sy = r.f64(54).unwrap_or(f64::NAN);
        let sz = r.f64(62).unwrap_or(f64::NAN);
        let compression = bytes[78];
        let ty = bytes[79];
        if compression != 0 {
            return Err(err(format!(
                ".sdf compression {compression} is not read (only 0, none)"
            )));
        }
        let (num, invalid) = match ty {
            5 => (Num::I16, f64::from(i16::MIN)),
            6 => (Num::I32, f64::from(i32::MIN)),
            7 => (Num::F64, f64::NAN),
            other => return Err(err(format!(".sdf DataType {other} is not read (5, 6 or 7)"))),
        };
        let info = info(nx, ny, sx, sy, path)?;
        info.check_grid(path)?;
        let decode = move || -> Result<Vec<f64>> {
            let mut z = numbers(bytes, BINARY_HEADER, nx * ny, num, true, path, ".sdf data")?;
            for v in &mut z {
                *v = if *v == invalid { f64::NAN } else { *v * sz };
            }
            Ok(z)
        };
        return Ok(vec![Channel {
            info,
            decode: Box::new(decode),
        }]);
    }
    let text = std::str::from_utf8(bytes).map_err(|_| err("text .sdf is not ASCII".into()))?;
    let mut sections = text.splitn(3, '*');
    let header = sections.next().unwrap_or("");
    let data = sections
        .next()
        .ok_or_else(|| err("truncated .sdf: no `*` line after the header".into()))?;
    let get = |key: &str| -> Result<f64> {
        header
            .lines()
            .filter_map(|l| l.split_once('='))
            .find(|(k, _)| k.trim() == key)
            .ok_or_else(|| err(format!(".sdf header lacks {key}")))?
            .1
            .trim()
            .parse::<f64>()
            .map_err(|_| err(format!(".sdf header {key} is not a number")))
    };
    let whole = |v: f64, key: &str| -> Result<usize> {
        if v >= 0.0 && v.fract() == 0.0 && v <= 65535.0 {
            Ok(v as usize)
        } else {
            Err(err(format!(".sdf header {key} = {v} is not a count of points")))
        }
    };
    let nx = whole(get("NumPoints")?, "NumPoints")?;
    let ny = whole(get("NumProfiles")?, "NumProfiles")?;
    let (sx, sy, sz) = (get("Xscale")?, get("Yscale")?, get("Zscale")?);
    let ty = get("DataType")?;
    if ![5.0, 6.0, 7.0].contains(&ty) {
        return Err(err(format!(".sdf DataType {ty} is not read (5, 6 or 7)")));
    }
    let info = info(nx, ny, sx, sy, path)?;
    info.check_grid(path)?;
    let mut z = Vec::with_capacity(nx * ny);
    for tok in data.split_whitespace() {
        if z.len() == nx * ny {
            return Err(err(format!(
                ".sdf data has more than NumPoints x NumProfiles = {nx} x {ny} values"
            )));
        }
        let v = if tok.eq_ignore_ascii_case("BAD") {
            f64::NAN
        } else {
            tok.parse::<f64>()
                .map_err(|_| err(format!(".sdf data value `{tok}` is not a number")))?
                * sz
        };
        z.push(v);
    }
    if z.len() != nx * ny {
        return Err(err(format!(
            "truncated .sdf: {} values, NumPoints x NumProfiles = {nx} x {ny} needs {}",
            z.len(),
            nx * ny
        )));
    }
    Ok(vec![Channel::ready(info, z)])
}

fn info(nx: usize, ny: usize, sx: f64, sy: f64, path: &Path) -> Result<ChannelInfo> {
    if !(sx > 0.0 && sy > 0.0 && sx.is_finite() && sy.is_finite()) {
        return Err(Error::data_file(
            path,
            0,
            format!(".sdf Xscale = {sx}, Yscale = {sy}: spacings must be positive and finite"),
        ));
    }
    Ok(ChannelInfo::single_in_metres(nx, ny, sx, sy))
}
