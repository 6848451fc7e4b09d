//! Alicona Imaging files (`.al3d`, focus variation): the magic `AliconaImaging\0\r\n`, then
//! tags of 52 bytes (a 20-byte key, a 30-byte value, both NUL-padded, and `\r\n`): `Version`,
//! `TagCount`, then `TagCount` more.
//!
//! Tags used: `Cols` (x), `Rows` (y), `PixelSizeXMeter`, `PixelSizeYMeter`, `DepthImageOffset`
//! (absolute offset of the depth image) and `InvalidPixelValue`. The depth image is `Rows` rows of
//! little-endian f32 heights in metres, each row padded to a multiple of 8 bytes. A point is
//! missing where it is NaN or within 1.5e-7 relative of the invalid-pixel marker, as
//! SurfaceTopography reads it.

use std::collections::HashMap;
use std::path::Path;

use super::{Bytes, Channel, ChannelInfo, cstr};
use crate::error::{Error, Result};

/// The magic bytes at the start.
pub(crate) const MAGIC: &[u8] = b"AliconaImaging\x00\r\n";

const TAG: usize = 52;

/// The depth image of an `.al3d` file.
pub(crate) fn channels<'a>(bytes: &'a [u8], path: &'a Path) -> Result<Vec<Channel<'a>>> {
    let err = |m: String| Error::data_file(path, 0, format!(".al3d: {m}"));
    let tag = |k: usize| -> Result<(String, String)> {
        let at = MAGIC.len() + k * TAG;
        let t = bytes.get(at..at + TAG).ok_or_else(|| {
            super::truncated(
                path,
                &format!(".al3d tag {}", k + 1),
                TAG,
                bytes.len().saturating_sub(at),
            )
        })?;
        if &t[50..52] != b"\r\n" {
            return Err(err(format!("tag {} does not end in CR LF", k + 1)));
        }
        Ok((cstr(&t[..20]), cstr(&t[20..50])))
    };
    let (k0, _) = tag(0)?;
    let (k1, count) = tag(1)?;
    if k0 != "Version" || k1 != "TagCount" {
        return Err(err(format!(
            "the first tags are `{k0}`, `{k1}`, not `Version`, `TagCount`"
        )));
    }
    let count: usize = count
        .parse()
        .ok()
        .filter(|&c| c <= 10_000)
        .ok_or_else(|| err(format!("tag count `{count}` is not a whole number up to 10000")))?;
    let mut tags = HashMap::new();
    for k in 0..count {
        let (key, value) = tag(k + 2)?;
        tags.entry(key).or_insert(value);
    }
    let get = |k: &str| {
        tags.get(k)
            .map(String::as_str)
            .ok_or_else(|| err(format!("no `{k}` tag")))
    };
    let int = |k: &str| -> Result<usize> {
        let v = get(k)?;
        v.parse()
            .map_err(|_| err(format!("`{k}` = `{v}` is not a whole number")))
    };
    let float = |k: &str| -> Result<f64> {
        let v = get(k)?;
        v.parse()
            .map_err(|_| err(format!("`{k}` = `{v}` is not a number")))
    };
    let nx = int("Cols")?;
    let ny = int("Rows")?;
    let (dx, dy) = (float("PixelSizeXMeter")?, float("PixelSizeYMeter")?);
    let offset = int("DepthImageOffset")?;
    let invalid = float("InvalidPixelValue")?;
    let info = ChannelInfo::single_in_metres(nx, ny, dx, dy);
    info.check_grid(path)?;
    // Rows padded to multiples of 8 bytes.
    let row = (nx * 4).div_ceil(8) * 8;
    let need = row.saturating_mul(ny);
    if offset.saturating_add(need) > bytes.len() {
        return Err(super::truncated(
            path,
            ".al3d depth image",
            need,
            bytes.len().saturating_sub(offset),
        ));
    }
    let decode = move || -> Result<Vec<f64>> {
        let r = Bytes { b: bytes, le: true };
        let mut z = Vec::with_capacity(nx * ny);
        let marker = invalid as f32;
        for j in 0..ny {
            for i in 0..nx {
                let v = r
                    .f32(offset + j * row + i * 4)
                    .ok_or_else(|| super::truncated(path, ".al3d depth image", need, 0))?;
                let bad =
                    v.is_nan() || (!invalid.is_nan() && (v - marker).abs() < (1.5e-7 * invalid.abs()) as f32);
                z.push(if bad { f64::NAN } else { f64::from(v) });
            }
        }
        Ok(z)
    };
    Ok(vec![Channel {
        info,
        decode: Box::new(decode),
    }])
}
